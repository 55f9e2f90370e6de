//! NASTRAN-95's own demonstration and test decks (`reference-data/nastran95-demos/inp/`,
//! 132 decks in COSMIC's dialect) through `impactlab check`, against the committed
//! table `reference-data/nastran95-demos.md`: for each deck, taken, or refused naming
//! the cards impactlab does not implement or why its structure does not build.
//!
//! Goal: no deck is refused for a reading error (NASTRAN-95 read every one of them),
//! and no deck's verdict changes unnoticed. A deck that moves in the table fails the
//! test until the table is written again on purpose:
//! `IMPACTLAB_WRITE_DEMO_TABLE=1 cargo test --test integration nastran95_demos::`.
//!
//! The static (SOL 1) decks it takes are then solved and their displacements compared
//! with NASTRAN-95's printed output (`reference-data/nastran95-demos/demoout/`), in the
//! committed table `reference-data/nastran95-demos-statics.md`, written the same way.

use crate::common;

use common::root;
use impactlab::deck::{read_deck, ReadOptions};
use std::fmt::Write as _;

/// The table's line of one deck.
fn verdict(path: &std::path::Path) -> Result<(String, bool), String> {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let read = ReadOptions {
        structure: true,
        ..Default::default()
    };
    let deck = read_deck(path, read).map_err(|e| format!("{name}: a reading error:\n{e}"))?;
    let r = impactlab::model::check::check(&deck);
    let sol = r.solution.clone().unwrap_or_else(|| "-".into());
    // Messages name the deck by its path: keep the file's own name.
    let local = |s: &str| {
        let first = s.lines().next().unwrap_or("");
        match first.find(&name) {
            Some(i) => first[i..].to_string(),
            None => first.to_string(),
        }
    };
    let (what, why) = if r.takes {
        let kinds: Vec<String> = r.elements.iter().map(|(k, n)| format!("{k} {n}")).collect();
        ("taken", kinds.join(", "))
    } else if !r.unsupported.is_empty() {
        let cards: Vec<&str> = r.unsupported.iter().map(|c| c.card.as_str()).collect();
        ("not supported", cards.join(", "))
    } else {
        ("does not build", local(&r.errors[0]))
    };
    let row = format!(
        "| {} | {sol} | {what} | {} |",
        name.trim_end_matches(".inp"),
        why.replace('|', "\\|")
    );
    Ok((row, r.takes))
}

#[test]
fn every_demonstration_deck_is_read_and_its_verdict_is_the_tables() {
    let dir = root().join("reference-data/nastran95-demos/inp");
    let mut decks: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "inp"))
        .collect();
    decks.sort();
    assert_eq!(decks.len(), 132);
    let mut rows = Vec::new();
    let mut misread = Vec::new();
    let mut taken = 0;
    for d in &decks {
        match verdict(d) {
            Ok((row, takes)) => {
                taken += usize::from(takes);
                rows.push(row);
            }
            Err(e) => misread.push(e),
        }
    }
    assert!(misread.is_empty(), "{}", misread.join("\n\n"));
    let mut table = String::new();
    let _ = writeln!(
        table,
        "# NASTRAN-95's demonstration decks through `impactlab check`\n\n\
         Written by `tests/nastran95_demos.rs` (`IMPACTLAB_WRITE_DEMO_TABLE=1 cargo test --test \
         integration nastran95_demos::`), which fails when a deck's verdict differs from this table. The decks are \
         NASTRAN-95's own (`nastran95-demos/inp/`, see its README). Taken: {taken} of {}.\n\n\
         | deck | SOL | verdict | elements, cards not supported, or the first error |\n|---|---|---|---|",
        decks.len()
    );
    for r in &rows {
        let _ = writeln!(table, "{r}");
    }
    let path = root().join("reference-data/nastran95-demos.md");
    if std::env::var_os("IMPACTLAB_WRITE_DEMO_TABLE").is_some() {
        std::fs::write(&path, &table).unwrap();
    }
    let committed = std::fs::read_to_string(&path).expect("the committed table");
    if committed != table {
        let old: Vec<&str> = committed.lines().collect();
        let changed: Vec<String> = table
            .lines()
            .filter(|l| !old.contains(l))
            .map(|l| format!("  now: {l}"))
            .collect();
        panic!(
            "the demonstration decks' verdicts differ from reference-data/nastran95-demos.md:\n{}",
            changed.join("\n")
        );
    }
}

/// A deck's elements, as the check table lists them ("CBAR 14, GENEL 5").
fn kinds(elements: &str) -> Vec<String> {
    elements
        .split(", ")
        .filter_map(|k| k.rsplit_once(' ').map(|(name, _)| name.to_string()))
        .collect()
}

/// Elements whose NASTRAN-95 formulation is impactlab's own (exact line elements,
/// springs, masses, the general element): a deck of only these agrees with NASTRAN-95
/// to its printed precision.
const SAME_FORMULATION: [&str; 12] = [
    "CROD", "CONROD", "CTUBE", "CBAR", "CBEAM", "GENEL", "CELAS1", "CELAS2", "CELAS3", "CELAS4", "CMASS1", "CMASS2",
];

/// Goal: every static (SOL 1) demonstration deck `check` takes is solved (every
/// SUBCASE, one factorisation) and compared with NASTRAN-95's printed displacements
/// (`impactlab compare`'s reading: each component's difference relative to the largest
/// printed translation, or rotation for R1-R3). Decks of rods, bars, springs and
/// general elements agree to NASTRAN-95's printed precision: within 1e-4 (its seven
/// digits, and its single-precision solution, leave up to ~1e-6). Decks with plates
/// differ by what NASTRAN-95's QUAD4, QDMEM, TRIA and SHEAR formulations differ from
/// impactlab's MITC4, DKMT and shear panel on the deck's mesh, stated per deck; a
/// deck that cannot be solved says why. The table is
/// `reference-data/nastran95-demos-statics.md`; a deck whose difference or verdict
/// moves fails until it is written again (`IMPACTLAB_WRITE_DEMO_TABLE=1`).
#[test]
fn taken_static_decks_are_solved_and_compared_with_nastran95() {
    use impactlab::verify::printed::{compare, read_printed_file, Printed};
    let checked = std::fs::read_to_string(root().join("reference-data/nastran95-demos.md")).unwrap();
    let mut rows = Vec::new();
    let mut element_rows = Vec::new();
    let mut disagree = Vec::new();
    let (mut solved, mut agree) = (0, 0);
    for line in checked.lines().filter(|l| l.contains("| taken |")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let (name, sol, elements) = (cells[1], cells[2], cells[4]);
        if sol != "1" {
            continue;
        }
        let inp = root().join(format!("reference-data/nastran95-demos/inp/{name}.inp"));
        let printed = read_printed_file(&root().join(format!("reference-data/nastran95-demos/demoout/{name}.out")));
        let same = kinds(elements).iter().all(|k| SAME_FORMULATION.contains(&k.as_str()));
        let solution = read_deck(&inp, Default::default())
            .map_err(|e| e.to_string())
            .and_then(|d| impactlab::run::statics::solve_subcases(&d).map_err(|e| e.to_string()));
        let (result, verdict) = match (solution, printed) {
            (_, Err(e)) if e.to_string().contains("holds no real displacement table") => (
                "-".to_string(),
                "nothing to compare: NASTRAN-95 printed no displacement table for it".to_string(),
            ),
            (_, Err(e)) => panic!("{e}"),
            (Err(e), _) => {
                let first = e.lines().next().unwrap_or("").to_string();
                let first = first.find(name).map_or(first.clone(), |i| first[i..].to_string());
                // The reader's list of the cards it supports is not the point here.
                let first = first.split("; supported:").next().unwrap_or("").to_string();
                ("-".to_string(), format!("not solved: {first}"))
            }
            (Ok((solutions, _)), Ok(printed)) => {
                solved += 1;
                let mut ours = Printed::default();
                for s in &solutions {
                    let table = ours.subcases.entry(s.subcase.unwrap_or(1)).or_default();
                    for g in &s.grids {
                        for (c, v) in g.u.iter().enumerate() {
                            table.insert((g.grid, c as u8 + 1), *v);
                        }
                    }
                }
                let cmp = compare(&ours, &printed);
                let worst = cmp.iter().map(|c| c.worst()).fold(0.0, f64::max);
                // The largest difference of the translations, then of the rotations, and
                // where each is.
                let largest = |rotations: bool| {
                    cmp.iter()
                        .filter_map(|c| c.worst_of(rotations).map(|(r, d)| (r, c.subcase, d.point, d.component)))
                        .max_by(|a, b| a.0.total_cmp(&b.0))
                        .map_or("-".to_string(), |(r, sc, p, c)| {
                            let comp = if c <= 3 { format!("T{c}") } else { format!("R{}", c - 3) };
                            format!("{r:.1e} (SUBCASE {sc}, grid {p} {comp})")
                        })
                };
                let result = format!(
                    "{} SUBCASE(s); translations {}; rotations {}",
                    cmp.len(),
                    largest(false),
                    largest(true)
                );
                let (elements, worst_element) = element_results(name, &solutions);
                element_rows.push(format!("| {name} | {elements} |"));
                let worst = worst.max(worst_element);
                let verdict = if same && worst <= 1e-4 {
                    agree += 1;
                    "agrees to NASTRAN-95's printed precision".to_string()
                } else if same {
                    disagree.push(format!("{name}: {result}"));
                    "DISAGREES".to_string()
                } else {
                    "differs: NASTRAN-95's plate or shear panel formulations are not impactlab's, on this mesh"
                        .to_string()
                };
                (result, verdict)
            }
        };
        rows.push(format!(
            "| {name} | {elements} | {result} | {} |",
            verdict.replace('|', "\\|")
        ));
    }
    assert!(
        disagree.is_empty(),
        "decks of NASTRAN-95's own formulations disagree:\n{}",
        disagree.join("\n")
    );
    let mut table = String::new();
    let _ = writeln!(
        table,
        "# NASTRAN-95's static demonstration decks solved by impactlab\n\n\
         Written by `tests/nastran95_demos.rs` (`IMPACTLAB_WRITE_DEMO_TABLE=1 cargo test --test \
         integration nastran95_demos::`): every SOL 1 deck `impactlab check` takes (`nastran95-demos.md`), solved for \
         every SUBCASE and compared with NASTRAN-95's printed displacements \
         (`nastran95-demos/demoout/`). A difference is relative to the largest translation (rotation, \
         for R1-R3) NASTRAN-95 printed in that SUBCASE. Solved: {solved} of {}; agreeing to NASTRAN-95's \
         printed precision (within 1e-4; decks of rods, bars, springs and general elements, whose \
         formulations are the same): {agree}.\n\n\
         | deck | elements | compared | verdict |\n|---|---|---|---|",
        rows.len()
    );
    for r in &rows {
        let _ = writeln!(table, "{r}");
    }
    let _ = writeln!(
        table,
        "\n## Element results\n\nThe element force and stress tables NASTRAN-95 printed for the decks solved \
         above (`impactlab compare`'s reading: `src/verify/element_tables.rs`), against the element results \
         impactlab writes for the same output requests, each difference relative to the largest printed value \
         of its kind (stress, moment or force) in its SUBCASE. A deck of NASTRAN's own formulations must agree \
         within 1e-4 here too.\n\n| deck | element results |\n|---|---|"
    );
    for r in &element_rows {
        let _ = writeln!(table, "{r}");
    }
    table_is_current("nastran95-demos-statics.md", &table);
}

/// A solved demonstration deck's element results against the tables NASTRAN-95
/// printed for it: the cell of the statics table and the largest relative difference
/// (0 when there is nothing to compare).
fn element_results(name: &str, solutions: &[impactlab::run::statics::StaticSolution]) -> (String, f64) {
    use impactlab::verify::element_tables::{compare_elements, read_element_tables_file, ElementTables};
    let printed = read_element_tables_file(&root().join(format!("reference-data/nastran95-demos/demoout/{name}.out")))
        .unwrap_or_else(|e| panic!("{e}"));
    if printed.subcases.is_empty() {
        return ("NASTRAN-95 printed no element table impactlab reads".into(), 0.0);
    }
    let mut ours = ElementTables::default();
    for s in solutions {
        let t = ours.subcases.entry(s.subcase.unwrap_or(1)).or_default();
        for e in &s.elements {
            for (n, v) in e.names.iter().zip(&e.values) {
                t.insert((e.eid, n.clone()), *v);
            }
        }
    }
    if ours.subcases.values().all(|t| t.is_empty()) {
        return ("printed, not written by impactlab (see the run's warnings)".into(), 0.0);
    }
    let c = compare_elements(&ours, &printed);
    let d = &c.differences[0];
    let cell = format!(
        "{} values, {} printed not written; largest {:.1e} (SUBCASE {}, element {} {})",
        c.differences.len(),
        c.missing.len(),
        d.relative,
        d.subcase,
        d.element,
        d.name
    );
    (cell, c.worst())
}

/// The theoretical frequencies a deck's own comments give, as NASTRAN-95's plate
/// decks write them (`$       MODE    M       N       FREQ` and a row a root:
/// `$       1       1       1       9.068997E-1`): mode number → frequency.
fn theory_in_comments(deck: &str) -> std::collections::BTreeMap<usize, f64> {
    let mut out = std::collections::BTreeMap::new();
    let mut in_table = false;
    for line in deck.lines().filter_map(|l| l.strip_prefix('$')) {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words == ["MODE", "M", "N", "FREQ"] {
            in_table = true;
            continue;
        }
        match (in_table, words.as_slice()) {
            (true, [mode, _, _, f]) => match (mode.parse(), f.parse()) {
                (Ok(mode), Ok(f)) => {
                    out.insert(mode, f);
                }
                _ => in_table = false,
            },
            _ => in_table = false,
        }
    }
    out
}

/// Goal: every normal modes (SOL 3) demonstration deck `check` takes is solved for
/// the roots its METHOD's EIGR asks for and compared, root by root in ascending
/// order, with NASTRAN-95's printed REAL EIGENVALUES table (and with the theoretical
/// frequencies the deck's comments give). The taken decks are NASTRAN-95's hinged
/// plate on two meshes (QUAD1, which impactlab reads as its QUAD4): the frequencies
/// differ from NASTRAN-95's by what the formulations differ on the mesh, and both
/// approach the theory as the mesh is refined. The table is
/// `reference-data/nastran95-demos-modes.md`; a root that moves fails until it is
/// written again (`IMPACTLAB_WRITE_DEMO_TABLE=1`).
#[test]
fn taken_modal_decks_are_solved_and_compared_with_nastran95() {
    use impactlab::verify::printed::read_eigenvalues;
    let checked = std::fs::read_to_string(root().join("reference-data/nastran95-demos.md")).unwrap();
    let mut rows = Vec::new();
    let mut decks = 0;
    for line in checked.lines().filter(|l| l.contains("| taken |")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let (name, sol, elements) = (cells[1], cells[2], cells[4]);
        if sol != "3" {
            continue;
        }
        decks += 1;
        let inp = root().join(format!("reference-data/nastran95-demos/inp/{name}.inp"));
        let out = root().join(format!("reference-data/nastran95-demos/demoout/{name}.out"));
        let printed = read_eigenvalues(&String::from_utf8_lossy(&std::fs::read(out).unwrap()));
        let theory = theory_in_comments(&std::fs::read_to_string(&inp).unwrap());
        let deck = read_deck(&inp, Default::default()).unwrap_or_else(|e| panic!("{e}"));
        let (s, _) = impactlab::run::modes::solve(&deck).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!s.modes.is_empty(), "{name}: no root found");
        let mut theirs: Vec<_> = printed.clone();
        theirs.sort_by_key(|r| r.mode);
        for (k, m) in s.modes.iter().enumerate() {
            assert!(m.residual < 1e-8, "{name} mode {}: residual {:e}", m.mode, m.residual);
            let nastran = theirs.get(k).map(|r| r.cycles);
            let th = theory.values().nth(k).copied();
            let cell = |f: Option<f64>| f.map_or("-".to_string(), |f| format!("{f:.6e}"));
            let rel = |f: Option<f64>| f.map_or("-".to_string(), |f| format!("{:+.1e}", m.cycles / f - 1.0));
            rows.push(format!(
                "| {name} | {elements} | {} | {:.6e} | {} | {} | {} | {} |",
                m.mode,
                m.cycles,
                cell(nastran),
                rel(nastran),
                cell(th),
                rel(th)
            ));
        }
    }
    let mut table = String::new();
    let _ = writeln!(
        table,
        "# NASTRAN-95's normal modes demonstration decks solved by impactlab\n\n\
         Written by `tests/nastran95_demos.rs` (`IMPACTLAB_WRITE_DEMO_TABLE=1 cargo test --test \
         integration nastran95_demos::`): every SOL 3 deck `impactlab check` takes (`nastran95-demos.md`), solved for \
         the roots its METHOD's EIGR asks for (`impactlab run`), each root against the one of the same \
         rank in NASTRAN-95's printed REAL EIGENVALUES table (`nastran95-demos/demoout/`) and against \
         the theoretical frequency the deck's own comments give (the hinged plate's, \
         `nastran95-demos/inp/d0301*a.inp`). Frequencies in cycles per unit time; a difference is \
         impactlab's relative to the other. Decks: {decks}. NASTRAN-95's QUAD1 is not impactlab's \
         QUAD4 (which it reads the card as): on the 10×20 mesh the two differ by a few 1e-4 to 3e-3, \
         and on the 20×40 mesh impactlab's first root is 4× nearer the theory than on the 10×20 \
         (the element's second order).\n\n\
         | deck | elements | mode | impactlab | NASTRAN-95 | difference | theory | difference |\n\
         |---|---|---|---|---|---|---|---|"
    );
    for r in &rows {
        let _ = writeln!(table, "{r}");
    }
    table_is_current("nastran95-demos-modes.md", &table);
}

/// The committed `reference-data/NAME` is `table` (written first when
/// `IMPACTLAB_WRITE_DEMO_TABLE` is set).
fn table_is_current(name: &str, table: &str) {
    let path = root().join("reference-data").join(name);
    if std::env::var_os("IMPACTLAB_WRITE_DEMO_TABLE").is_some() {
        std::fs::write(&path, table).unwrap();
    }
    let committed = std::fs::read_to_string(&path).expect("the committed table");
    assert_eq!(committed, table, "reference-data/{name} is not what the code makes now");
}

/// One transient deck run by `impactlab run` with a scheme, then held against
/// NASTRAN-95's printed SORT2 displacements by `impactlab compare` within `tolerance`
/// (of the largest printed value), its ledger error within `ledger`; the values
/// compared must be `values`.
fn transient_against_printed(deck: &str, printed: &str, values: usize, scheme: &str, tolerance: &str, ledger: f64) {
    let (deck, printed) = (root().join(deck), root().join(printed));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join(scheme);
    let o = common::impactlab(&[
        "run",
        deck.to_str().unwrap(),
        "--scheme",
        scheme,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = common::impactlab(&[
        "compare",
        out.to_str().unwrap(),
        printed.to_str().unwrap(),
        "--tolerance",
        tolerance,
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{scheme}: {text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(text.starts_with(&format!("{values} values compared")), "{text}");
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let error = summary["energy"]["max_relative_error"].as_f64().unwrap();
    assert!(error.abs() < ledger, "{scheme}: ledger error {error:e}");
}

/// Goal: a transient deck loaded by a dynamic load (DAREA, TLOAD1, TABLED1) runs as
/// NASTRAN-95 runs it. Model: test problem T09-07-1A's SUBCASE 1
/// (`reference-data/decks/t09071a-subcase1.bdf`, derived from `inp/t09071a.inp` as
/// its header says): ten CBARs clamped at one end, struck axially at the other by a
/// load that ramps to 120.9 in 25e-6 and holds. Reference: NASTRAN-95's printed SORT2
/// displacements (`demoout/t09071a.out`, 3060 values of grids 1-10). Tolerance: with
/// NASTRAN's own scheme (`nastran`, β = 1/3) 5e-7 of the largest printed
/// displacement, the rounding of its 7 printed digits (measured 2.1e-7); with the
/// trapezoidal rule (another scheme, second order both) 1e-2 (measured 7.6e-3, at
/// the tip after the second reflection). The trapezoidal rule's ledger closes on the
/// load's work to round-off (measured 4.9e-15 of the largest work); NASTRAN's scheme's
/// to its order (measured 1.06e-3).
#[test]
fn a_bar_struck_by_a_tload1_matches_nastran95_to_its_printed_digits() {
    let deck = "reference-data/decks/t09071a-subcase1.bdf";
    let printed = "reference-data/nastran95-demos/demoout/t09071a.out";
    transient_against_printed(deck, printed, 3060, "nastran", "5e-7", 2e-3);
    transient_against_printed(deck, printed, 3060, "newmark", "1e-2", 1e-13);
}

/// Goal: NASTRAN-95's start of a transient run from initial conditions (TIC) is
/// reproduced: the initial state held by the loads K u(−1) and K u(0) for the first
/// step. Model: demonstration problem D09-02-1A as distributed (`inp/d09021a.inp`):
/// a string of 1000 CELAS3 springs and CMASS3 masses released from a triangular
/// shape. Reference: NASTRAN-95's printed SORT2 displacements of its 20 points
/// (`demoout/d09021a.out`, 1020 values). Tolerance: 5e-7 of the largest printed
/// displacement, the rounding of its 7 digits (measured 2.9e-7; 7.6e-2 without the
/// start loads); the ledger, with the start loads' work booked, 2e-2 of the initial
/// energy (measured 1.06e-2: the three-point scheme's error at the shape's kinks).
#[test]
fn a_string_released_from_a_tic_shape_matches_nastran95_to_its_printed_digits() {
    transient_against_printed(
        "reference-data/nastran95-demos/inp/d09021a.inp",
        "reference-data/nastran95-demos/demoout/d09021a.out",
        1020,
        "nastran",
        "5e-7",
        2e-2,
    );
}
