//! The report regenerates without error, its figures are real PNG/SVG files, its
//! summary numbers are the run's, and its text is snapshot-tested (numbers rounded to
//! the significant digits the report prints; the wall-time line and the momentum
//! check, a round-off-level number, removed: they differ between machines).

mod common;

use common::root;
use impactlab::report::{report_case, sig};
use impactlab::verify::read_case;

#[test]
fn rod_report_regenerates_and_matches_its_run() {
    let case = read_case(&root().join("verification/rod.toml")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let r = report_case(&case, dir.path()).unwrap();
    assert_eq!(r.failed, 0);
    for stem in ["force", "strain", "energy"] {
        let png = std::fs::read(dir.path().join(format!("{stem}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{stem}.png");
        assert!(png.len() > 20_000, "{stem}.png has content");
        let svg = std::fs::read_to_string(dir.path().join(format!("{stem}.svg"))).unwrap();
        assert!(
            svg.contains("<svg") && svg.contains("tC/L") || svg.contains("time"),
            "{stem}.svg"
        );
    }
    let md = std::fs::read_to_string(dir.path().join("index.md")).unwrap();
    let s = &r.summary;
    for (label, v) in [
        ("peak force", s["contact"]["peak_force"].as_f64().unwrap()),
        ("contact ends (tC/L)", s["rod"]["contact_end_tcl"].as_f64().unwrap()),
        (
            "impactor at rest (tC/L)",
            s["rod"]["velocity_zero_time_tcl"].as_f64().unwrap(),
        ),
    ] {
        assert!(
            md.contains(&format!("| {label} | {}", sig(v, 6))),
            "{label} = {v} not in report"
        );
    }
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(html.contains("<table>") && html.contains("<img src=\"energy.png\""));
    let text: String = md
        .lines()
        .filter(|l| !l.starts_with("| wall time") && !l.starts_with("| momentum |"))
        .map(|l| format!("{l}\n"))
        .collect();
    insta::assert_snapshot!("rod_report", text);
}
