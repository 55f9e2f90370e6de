//! The committed `reports/` are what the code now makes from their data: a page or a
//! figure that the code would draw differently fails here, so a stale report cannot
//! land. Studies are too slow to re-run in a test: their pages and figures are made
//! from their committed CSV alone, and remade here from it.

mod common;

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
