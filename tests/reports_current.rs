//! The committed `reports/` are what the code now makes from their data: a page or a
//! figure that the code would draw differently fails here, so a stale report cannot
//! land. Studies are too slow to re-run in a test: their pages and figures are made
//! from their committed CSV alone, and remade here from it. The case reports are
//! judged in `tests/verify_gate.rs`, from the one evaluation of every case there.

use crate::common;

use common::root;

/// Goal: `reports/stability/README.md` and `stability-map.svg` are what
/// `impactlab study stability` makes from the committed `stability-map.csv`.
#[test]
fn stability_page_and_figure_are_current() {
    use impactlab::study::stability;
    let dir = root().join("reports/stability");
    let csv = std::fs::read(dir.join("stability-map.csv")).unwrap();
    let cells = stability::read_csv(&csv).unwrap();
    assert_eq!(cells.len(), 4 * 9 * 7, "every scheme over the whole grid");
    assert_eq!(stability::csv(&cells), csv, "the CSV reads back to itself");
    let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
    assert_eq!(
        stability::readme(&cells),
        readme,
        "reports/stability/README.md is stale: regenerate with `impactlab study stability`"
    );
    let tmp = tempfile::tempdir().unwrap();
    stability::figure(&cells, &tmp.path().join("stability-map")).unwrap();
    assert_eq!(
        std::fs::read_to_string(tmp.path().join("stability-map.svg")).unwrap(),
        std::fs::read_to_string(dir.join("stability-map.svg")).unwrap(),
        "reports/stability/stability-map.svg is stale"
    );
}

/// Goal: `reports/mesh/README.md` and every figure of it are what `impactlab study
/// mesh` makes from the committed `mesh-study.csv` and `mesh-histories.csv`.
#[test]
fn mesh_study_page_and_figures_are_current() {
    use impactlab::study::mesh;
    let dir = root().join("reports/mesh");
    let rows_csv = std::fs::read(dir.join("mesh-study.csv")).unwrap();
    let hist_csv = std::fs::read(dir.join("mesh-histories.csv")).unwrap();
    let rows: Vec<mesh::MeshRow> = mesh::read_csv(&rows_csv).unwrap();
    let samples: Vec<mesh::Sample> = mesh::read_csv(&hist_csv).unwrap();
    assert_eq!(
        rows.iter().map(|r| r.n).collect::<Vec<_>>(),
        mesh::MESHES,
        "the study's meshes"
    );
    assert_eq!(mesh::csv(&rows), rows_csv, "mesh-study.csv reads back to itself");
    assert_eq!(mesh::csv(&samples), hist_csv, "mesh-histories.csv reads back to itself");
    assert_eq!(
        mesh::readme(&rows, &samples),
        std::fs::read_to_string(dir.join("README.md")).unwrap(),
        "reports/mesh/README.md is stale: `impactlab study mesh --redraw`"
    );
    let tmp = tempfile::tempdir().unwrap();
    let figs = mesh::figures(&samples, tmp.path()).unwrap();
    assert_eq!(figs.len(), 10, "five figures, PNG and SVG");
    assert_svgs_current(&figs, &dir);
}

/// Goal: `reports/panel/README.md` and every figure of it are what `impactlab study
/// panel` makes from the committed `panel-study.csv` and `panel-histories.csv`, which
/// hold the flat plate and the panel on each of the mesh study's meshes.
#[test]
fn panel_study_page_and_figures_are_current() {
    use impactlab::study::{mesh, panel};
    let dir = root().join("reports/panel");
    let rows_csv = std::fs::read(dir.join("panel-study.csv")).unwrap();
    let hist_csv = std::fs::read(dir.join("panel-histories.csv")).unwrap();
    let rows: Vec<panel::PanelRow> = panel::read_csv(&rows_csv).unwrap();
    let samples: Vec<panel::PanelSample> = panel::read_csv(&hist_csv).unwrap();
    let expected: Vec<(usize, Option<f64>)> = mesh::MESHES
        .iter()
        .flat_map(|&n| [(n, None), (n, Some(panel::RADIUS))])
        .collect();
    assert_eq!(
        rows.iter().map(|r| (r.n, r.radius_in)).collect::<Vec<_>>(),
        expected,
        "the study's runs"
    );
    assert_eq!(panel::csv(&rows), rows_csv, "panel-study.csv reads back to itself");
    assert_eq!(
        panel::csv(&samples),
        hist_csv,
        "panel-histories.csv reads back to itself"
    );
    assert_eq!(
        panel::readme(&rows),
        std::fs::read_to_string(dir.join("README.md")).unwrap(),
        "reports/panel/README.md is stale: `impactlab study panel --redraw`"
    );
    let tmp = tempfile::tempdir().unwrap();
    let figs = panel::figures(&samples, tmp.path()).unwrap();
    assert_eq!(figs.len(), 6, "three figures, PNG and SVG");
    assert_svgs_current(&figs, &dir);
}

/// Goal: `reports/stiffened/README.md` and its figure are what `impactlab study
/// stiffened` makes from the committed CSVs, which hold the three strikes on each of
/// the study's meshes and a threshold search for each strike on the paper's mesh.
#[test]
fn stiffened_study_page_and_figure_are_current() {
    use impactlab::study::stiffened::{self, Struck};
    let dir = root().join("reports/stiffened");
    let read = |f: &str| std::fs::read(dir.join(f)).unwrap();
    let (rows_csv, hist_csv, thr_csv) = (
        read("stiffened-study.csv"),
        read("stiffened-histories.csv"),
        read("stiffened-thresholds.csv"),
    );
    let rows: Vec<stiffened::StiffenedRow> = stiffened::read_csv(&rows_csv).unwrap();
    let samples: Vec<stiffened::StiffenedSample> = stiffened::read_csv(&hist_csv).unwrap();
    let thresholds: Vec<stiffened::ThresholdRow> = stiffened::read_csv(&thr_csv).unwrap();
    let expected: Vec<(usize, Struck)> = stiffened::MESHES
        .iter()
        .flat_map(|&n| Struck::ALL.map(|s| (n, s)))
        .collect();
    assert_eq!(
        rows.iter().map(|r| (r.n, r.struck)).collect::<Vec<_>>(),
        expected,
        "the study's runs"
    );
    assert_eq!(
        thresholds.iter().map(|t| (t.n, t.struck)).collect::<Vec<_>>(),
        Struck::ALL.map(|s| (49, s)).to_vec(),
        "the threshold searches"
    );
    assert_eq!(
        stiffened::csv(&rows),
        rows_csv,
        "stiffened-study.csv reads back to itself"
    );
    assert_eq!(
        stiffened::csv(&samples),
        hist_csv,
        "stiffened-histories.csv reads back to itself"
    );
    assert_eq!(
        stiffened::csv(&thresholds),
        thr_csv,
        "stiffened-thresholds.csv reads back to itself"
    );
    assert_eq!(
        stiffened::readme(&rows, &thresholds),
        std::fs::read_to_string(dir.join("README.md")).unwrap(),
        "reports/stiffened/README.md is stale: `impactlab study stiffened --redraw`"
    );
    let tmp = tempfile::tempdir().unwrap();
    let figs = stiffened::figures(&samples, tmp.path()).unwrap();
    assert_eq!(figs.len(), 2, "one figure, PNG and SVG");
    assert_svgs_current(&figs, &dir);
}

/// Goal: `reports/mutants/README.md` is what `impactlab study mutants` makes from the
/// committed `campaign.toml` and runs' CSVs (which refuses a survivor without a verdict
/// that holds), and every run the campaign names has its CSV.
#[test]
fn mutants_page_is_current() {
    let dir = root().join("reports/mutants");
    let page = impactlab::study::mutants::page(&dir).unwrap();
    assert_eq!(
        page,
        std::fs::read_to_string(dir.join("README.md")).unwrap(),
        "reports/mutants/README.md is stale: `impactlab study mutants`"
    );
}

/// Goal: `reports/accuracy/` holds exactly what `impactlab study accuracy` makes from
/// its committed `work-precision.csv`: the README (method, conclusions, tables) and
/// every figure, nothing else.
#[test]
fn accuracy_page_and_figures_are_current() {
    use impactlab::study::accuracy;
    let dir = root().join("reports/accuracy");
    let csv = std::fs::read(dir.join("work-precision.csv")).unwrap();
    let rows = accuracy::read_csv(&csv).unwrap();
    assert_eq!(accuracy::csv(&rows), csv, "work-precision.csv reads back to itself");
    assert_eq!(
        accuracy::readme(&rows),
        std::fs::read_to_string(dir.join("README.md")).unwrap(),
        "reports/accuracy/README.md is stale: `impactlab study accuracy --redraw`"
    );
    let tmp = tempfile::tempdir().unwrap();
    let figs = accuracy::figures(&rows, tmp.path()).unwrap();
    let mut made: Vec<String> = figs
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .chain(["README.md", "README.html", "work-precision.csv"].map(String::from))
        .collect();
    made.sort();
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    assert_eq!(on_disk, made, "reports/accuracy holds exactly the study's files");
    assert_svgs_current(&figs, &dir);
}

/// Every SVG among freshly drawn `figs` equals its committed twin in `dir`.
fn assert_svgs_current(figs: &[std::path::PathBuf], dir: &std::path::Path) {
    for svg in figs.iter().filter(|f| f.extension().is_some_and(|e| e == "svg")) {
        let committed = dir.join(svg.file_name().unwrap());
        assert_eq!(
            std::fs::read_to_string(svg).unwrap(),
            std::fs::read_to_string(&committed).unwrap_or_default(),
            "{} is stale",
            committed.display()
        );
    }
}

/// Goal: every page under `reports/` links only to what is there: each relative
/// `href` and `src` of every HTML page names an existing file, every image is a PNG
/// or SVG that exists, and the top-level `index.html` reaches every case and study page.
#[test]
fn every_link_and_image_of_the_report_pages_exists() {
    fn html_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                html_files(&p, out);
            } else if p.extension().is_some_and(|x| x == "html") {
                out.push(p);
            }
        }
    }
    let reports = root().join("reports");
    let mut pages = Vec::new();
    html_files(&reports, &mut pages);
    assert!(pages.len() >= 10, "{pages:?}");
    let mut broken = Vec::new();
    for page in &pages {
        let text = std::fs::read_to_string(page).unwrap();
        assert!(
            text.starts_with("<!DOCTYPE html>") && text.trim_end().ends_with("</html>"),
            "{page:?}"
        );
        for attr in ["href=\"", "src=\""] {
            for part in text.split(attr).skip(1) {
                let target = part.split('"').next().unwrap();
                if target.starts_with("http") || target.starts_with('#') || target.is_empty() {
                    continue;
                }
                let path = page.parent().unwrap().join(target.split('#').next().unwrap());
                if !path.is_file() {
                    broken.push(format!("{}: {target}", page.strip_prefix(&reports).unwrap().display()));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links: {broken:?}");
    let index = std::fs::read_to_string(reports.join("index.html")).unwrap();
    for e in std::fs::read_dir(&reports)
        .unwrap()
        .flatten()
        .filter(|e| e.path().is_dir())
    {
        let name = e.file_name().to_string_lossy().into_owned();
        let page = if e.path().join("index.html").exists() {
            "index.html"
        } else {
            "README.html"
        };
        assert!(
            index.contains(&format!("href=\"{name}/{page}\"")),
            "index.html does not link {name}/{page}"
        );
    }
}

/// Goal: every page under `reports/` renders in a real browser (headless Chromium,
/// Debian's `chromium`): each loads from its file and is drawn to a screenshot of the
/// window's size. Missing images and broken links are the test above. Skipped, and
/// says so, where no Chromium is installed, except under CI (`.ci/run` installs it),
/// where a missing browser fails.
#[test]
fn every_report_page_renders_in_headless_chromium() {
    let Some(browser) = ["chromium", "chromium-browser"].into_iter().find(|b| {
        std::process::Command::new(b)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    }) else {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must install chromium (.ci/run does)"
        );
        eprintln!("skipped: no chromium on this machine (apt-get install chromium)");
        return;
    };
    let reports = root().join("reports");
    let tmp = tempfile::tempdir().unwrap();
    let mut pages: Vec<std::path::PathBuf> = vec![reports.join("index.html")];
    for e in std::fs::read_dir(&reports).unwrap().flatten() {
        for page in ["index.html", "README.html"] {
            if e.path().join(page).is_file() {
                pages.push(e.path().join(page));
            }
        }
    }
    for (i, page) in pages.iter().enumerate() {
        let shot = tmp.path().join(format!("{i}.png"));
        let o = std::process::Command::new("timeout")
            .args([
                "60",
                browser,
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--hide-scrollbars",
            ])
            .arg("--window-size=1200,1600")
            .arg(format!("--screenshot={}", shot.display()))
            .arg(format!("file://{}", page.display()))
            .output()
            .unwrap();
        assert!(o.status.success(), "{page:?}: {}", String::from_utf8_lossy(&o.stderr));
        let png = std::fs::read(&shot).unwrap_or_else(|e| panic!("{page:?}: no screenshot: {e}"));
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{page:?}");
        let (w, h) = (
            u32::from_be_bytes(png[16..20].try_into().unwrap()),
            u32::from_be_bytes(png[20..24].try_into().unwrap()),
        );
        assert_eq!((w, h), (1200, 1600), "{page:?}");
        // A blank white page compresses to a few kB; a drawn one does not.
        assert!(
            png.len() > 20_000,
            "{page:?}: the screenshot is blank ({} bytes)",
            png.len()
        );
    }
}

/// Goal: the README's first command (`cargo run --release -- report verification/rod.toml`,
/// read from the README itself) leaves a fresh clone clean: the pages and figures it
/// rewrites are the committed ones byte for byte, and nothing else it writes is
/// tracked. Run with this build's binary in a `git clone` of the committed tree;
/// skipped (with a message) where the project is not a git checkout.
#[test]
fn the_readmes_first_command_leaves_a_fresh_clone_clean() {
    use std::process::Command;
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let prefix = "cargo run --release -- ";
    let line = readme
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with(prefix))
        .expect("the README's first screen gives a `cargo run --release -- ...` command");
    let args: Vec<&str> = line[prefix.len()..].split_whitespace().collect();
    let git = |dir: &std::path::Path, args: &[&str]| Command::new("git").current_dir(dir).args(args).output();
    match git(&root(), &["rev-parse", "--is-inside-work-tree"]) {
        Ok(o) if o.status.success() => {}
        _ => {
            eprintln!("skipped: {} is not a git checkout", root().display());
            return;
        }
    }
    let tmp = tempfile::tempdir().unwrap();
    let clone = tmp.path().join("clone");
    let o = git(tmp.path(), &["clone", "-q", root().to_str().unwrap(), "clone"]).unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = Command::new(env!("CARGO_BIN_EXE_impactlab"))
        .current_dir(&clone)
        .args(&args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{line}: {}", String::from_utf8_lossy(&o.stderr));
    let status = git(&clone, &["status", "--porcelain"]).unwrap();
    let dirty = String::from_utf8_lossy(&status.stdout);
    assert!(dirty.is_empty(), "{line} left the clone dirty:\n{dirty}");
}
