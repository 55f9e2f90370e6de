//! The report regenerates without error, its figures are real PNG/SVG files, its
//! summary numbers are the run's, and its text is snapshot-tested (numbers rounded to
//! the significant digits the report prints; the wall-time line and the momentum
//! check, a round-off-level number, removed, and the gold check's value, its worst
//! difference at round-off, masked: they differ between machines).

mod common;

use common::root;
use impactlab::report::{report_case, sig};
use impactlab::verify::read_case;

#[test]
fn rod_report_regenerates_and_matches_its_run() {
    let case = read_case(&root().join("verification/rod.toml")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let outcome = impactlab::study::cases::evaluate(&case).unwrap();
    let r = report_case(&outcome, dir.path()).unwrap();
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
        ("peak force", s.contact.peak_force),
        ("contact ends (tC/L)", s.rod.as_ref().unwrap().contact_end_tcl.unwrap()),
        (
            "impactor at rest (tC/L)",
            s.rod.as_ref().unwrap().velocity_zero_time_tcl.unwrap(),
        ),
    ] {
        assert!(
            md.contains(&format!("| {label} | {}", sig(v, 6))),
            "{label} = {v} not in report"
        );
    }
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(html.contains("<table>") && html.contains("<img src=\"energy.png\""));
    // The gold check's value is its worst difference in units of its tolerance: round-off
    // (1e-6 … 1e-4 of the tolerance as expressions are reordered); its verdict stays.
    let redact_gold = |l: &str| -> String {
        let mut cells: Vec<&str> = l.split('|').collect();
        cells[2] = " (round-off) ";
        cells.join("|")
    };
    let text: String = md
        .lines()
        .filter(|l| !l.starts_with("| wall time") && !l.starts_with("| momentum |"))
        .map(|l| {
            if l.starts_with("| gold ") {
                redact_gold(l)
            } else {
                l.to_string()
            }
        })
        .map(|l| format!("{l}\n"))
        .collect();
    insta::assert_snapshot!("rod_report", text);
}

/// Goal: `--fields` writes VTU files that parse back (vtkio) with the mesh's points
/// and cells, and a .pvd collection listing each with its time. Model: the 13×13
/// plate (196 grids, 169 CQUAD4) and the rod (145 grids, 144 CRODs).
#[test]
fn field_files_parse_back() {
    use impactlab::report::fields::{field_times, read_back, write_fields};
    let dir = tempfile::tempdir().unwrap();
    let m = impactlab::mesh::plate_model(13).unwrap();
    let opts = impactlab::run::RunOptions {
        steps: Some(400),
        snapshot_times: field_times(1e-7, 400, 4),
        ..Default::default()
    };
    let r = impactlab::run::run_model(&m, &opts).unwrap();
    let files = write_fields(&m, &r, &dir.path().join("plate")).unwrap();
    assert_eq!(files.len(), 6);
    for f in files.iter().filter(|f| f.extension().is_some_and(|e| e == "vtu")) {
        assert_eq!(read_back(f).unwrap(), (196, 169));
    }
    let pvd = std::fs::read_to_string(dir.path().join("plate/fields.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet timestep=").count(), 5);
    let rod = common::rod_model();
    let opts = impactlab::run::RunOptions {
        steps: Some(100),
        snapshot_times: vec![1e-5],
        ..Default::default()
    };
    let r = impactlab::run::run_model(&rod, &opts).unwrap();
    let files = write_fields(&rod, &r, &dir.path().join("rod")).unwrap();
    assert_eq!(read_back(&files[0]).unwrap(), (145, 144));
}

/// Goal: `report` draws every case: the rod with a contact that outlasts 2L/C
/// (rod-rigid, where the semi-infinite rod does not apply) gets the two-rigid-body
/// reference instead of the paper's figures, and no strain figure.
#[test]
fn rod_rigid_report_uses_the_two_rigid_body_reference() {
    let case = read_case(&root().join("verification/rod-rigid.toml")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let outcome = impactlab::study::cases::evaluate(&case).unwrap();
    let r = report_case(&outcome, dir.path()).unwrap();
    assert_eq!(r.failed, 0);
    let names: Vec<String> = r
        .figures
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["force.png", "force.svg", "energy.png", "energy.svg"]);
    let svg = std::fs::read_to_string(dir.path().join("force.svg")).unwrap();
    assert!(
        svg.contains("two rigid bodies") && !svg.contains("paper Fig"),
        "force.svg"
    );
}

/// Goal: a figure is never drawn from samples too coarse for its pulse. Model: the
/// rod at 8× the paper's Δt written at the deck's interval (every 25 steps, 40 µs,
/// against a 74 µs contact pulse): the report refuses, naming the figure and the fix.
#[test]
fn a_pulse_sampled_too_coarsely_is_not_drawn() {
    let mut case = impactlab::verify::read_case(&root().join("verification/rod-energy-8dt.toml")).unwrap();
    case.every_step = false;
    let outcome = impactlab::study::cases::evaluate(&case).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let e = impactlab::report::report_case(&outcome, dir.path())
        .unwrap_err()
        .to_string();
    assert!(e.contains("strain.png") && e.contains("every_step = true"), "{e}");
    case.every_step = true;
    let outcome = impactlab::study::cases::evaluate(&case).unwrap();
    assert!(impactlab::report::report_case(&outcome, dir.path()).is_ok());
}
