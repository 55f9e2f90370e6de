//! The NASTRAN deck reader, feature by feature. Each test feeds a small deck and
//! checks the typed result or the exact diagnostic.

use crate::common;

use common::{bulk_deck as deck, bulk_errors, deck_errors as errors, BULK_HEAD as HEAD};
use impactlab::deck::{parse_deck_str, ReadOptions};

#[test]
fn free_small_and_large_field_read_the_same_grid() {
    let free = deck("GRID,7,,1.5,-2.0,3.25");
    let small = deck("GRID           7            1.5    -2.0    3.25");
    let large =
        deck("GRID*                  7                             1.5            -2.0*G7\n*G7                 3.25");
    for d in [free, small, large] {
        let g = &d.bulk.grids[0];
        assert_eq!((g.id, g.x), (7, [1.5, -2.0, 3.25]));
    }
}

#[test]
fn continuation_by_marker_and_implicit() {
    let explicit = deck("CONM2,1,5,0,2.0,,,,,+C1\nGRID,5\n+C1,1.0,,2.0,,,3.0");
    assert_eq!(explicit.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
    let implicit = deck("GRID,5\nCONM2,1,5,0,2.0\n,1.0,,2.0,,,3.0");
    assert_eq!(implicit.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
    let blank = deck(
        "GRID,5\nCONM2          1       5       0     2.0\n             1.0             2.0                     3.0",
    );
    assert_eq!(blank.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
}

#[test]
fn free_field_line_with_more_than_ten_fields_continues() {
    // Field 11 is the continuation's marker slot (blank), values go on from field 12.
    let d = deck("GRID,5\nCONM2,1,5,0,2.0,,,,,,,1.0,,2.0,,,3.0");
    assert_eq!(d.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
    let e = bulk_errors("GRID,5\nCONM2,1,5,0,2.0,,,,,,1.0,,2.0");
    assert!(e[0].contains("must be blank or a continuation marker"), "{e:?}");
    assert_eq!(d.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
}

#[test]
fn replication_generates_the_rod_decks_grids_and_elements() {
    let d = deck("GRID,1,,0.0,0.0,0.0\n=(144),*(1),=,*(0.25),=\nCROD, 1, 1, 1, 2\n=(143),*(1),=,*(1),*(1)");
    assert_eq!(d.bulk.grids.len(), 145);
    let last = d.bulk.grids.last().unwrap();
    assert_eq!((last.id, last.x), (145, [36.0, 0.0, 0.0]));
    assert_eq!(d.bulk.elements.len(), 144);
    assert_eq!(
        (d.bulk.elements[143].kind.card, &d.bulk.elements[143].g[..]),
        ("CROD", &[144, 145][..])
    );
    // MSC-style forms without parentheses, `==` and a bare =(n) repeating the pattern.
    let d = deck("GRID,10,,1.0,2.0,3.0\n=,*1,==\n=2\nSPC1,1,123,10\n=,=,=,*100\n=(2)");
    let ids: Vec<i64> = d.bulk.grids.iter().map(|g| g.id).collect();
    assert_eq!(ids, [10, 11, 12, 13]);
    assert!(d.bulk.grids.iter().all(|g| g.x == [1.0, 2.0, 3.0]));
    let spc: Vec<i64> = d.bulk.spc1s.iter().map(|s| s.grids[0]).collect();
    assert_eq!(spc, [10, 110, 210, 310]);
}

#[test]
fn nastran_reals_integers_and_blank_defaults() {
    let d = deck("MAT1,11,10.0+6,,0.33,2.5-4\nTIC,1,5,1,1D-3,1.E3\nGRID,5");
    let m = &d.bulk.mat1s[0];
    assert_eq!((m.e, m.nu, m.rho), (10.0e6, 0.33, 2.5e-4));
    assert!((m.g - 10.0e6 / 2.66).abs() < 1e-6, "blank G from E and NU");
    assert_eq!((d.bulk.tics[0].u0, d.bulk.tics[0].v0), (1e-3, 1e3));
}

#[test]
fn thru_lists_in_spc1_epoint_and_case_sets() {
    let d = deck("SPC1,4,23456,1,THRU,145\nEPOINT,1001,THRU,1003");
    assert_eq!(d.bulk.spc1s[0].grids.len(), 145);
    assert_eq!(
        d.bulk.epoints.iter().map(|e| e.0).collect::<Vec<_>>(),
        [1001, 1002, 1003]
    );
    let d = parse_deck_str(
        "t.bdf",
        "SOL 9\nCEND\nSET 3 = 1 THRU 4, 9,\n 12\nDISP(PRINT,SORT2) = 3\nBEGIN BULK\nENDDATA\n",
        ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(d.case.sets[&3].members, [1, 2, 3, 4, 9, 12]);
    assert!(d.case.outputs.contains_key("DISP"));
}

#[test]
fn executive_control_accepts_every_direct_transient_sol_statics_and_modes() {
    for (sol, read) in [
        ("9", 9),
        ("27", 27),
        ("109", 109),
        ("129", 129),
        ("SEDTRAN", 109),
        ("101", 101),
        ("1", 101),
        ("SESTATIC", 101),
        ("STATICS", 101),
        ("3", 103),
        ("103", 103),
        ("SEMODES", 103),
    ] {
        let d = parse_deck_str(
            "t.bdf",
            &format!("ID A,B\nSOL {sol}\nCEND\nBEGIN BULK\nENDDATA\n"),
            ReadOptions::default(),
        );
        assert_eq!(d.map(|d| d.executive.sol).ok(), Some(Some(read)), "SOL {sol}");
    }
    let e = errors("SOL 111\nCEND\nBEGIN BULK\nENDDATA\n");
    assert!(e[0].contains("SOL 111 is not supported"), "{e:?}");
}

#[test]
fn include_is_relative_to_the_including_file_and_cycles_are_caught() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(
        dir.path().join("main.bdf"),
        format!("{HEAD}INCLUDE 'sub/mesh.bdf'\nENDDATA\n"),
    )
    .unwrap();
    std::fs::write(dir.path().join("sub/mesh.bdf"), "GRID,1\nINCLUDE 'more.bdf'\n").unwrap();
    std::fs::write(dir.path().join("sub/more.bdf"), "GRID,2\n").unwrap();
    let d = impactlab::deck::read_deck(&dir.path().join("main.bdf"), ReadOptions::default()).unwrap();
    assert_eq!(d.bulk.grids.len(), 2);
    std::fs::write(dir.path().join("sub/more.bdf"), "INCLUDE 'mesh.bdf'\n").unwrap();
    let e = impactlab::deck::read_deck(&dir.path().join("main.bdf"), ReadOptions::default()).unwrap_err();
    assert!(e.to_string().contains("INCLUDE cycle"), "{e}");
}

#[test]
fn errors_name_file_line_column_card_field_and_token() {
    let e = bulk_errors("CROD,1,x1,1,2");
    assert_eq!(
        e[0],
        "t.bdf:6:8: error: CROD field 3 (PID): 'x1' is not an integer\n    | CROD,1,x1,1,2"
    );
    let e = bulk_errors("MAT1,11,10.0+6,,0.33,2.5-4.1");
    assert!(
        e[0].starts_with("t.bdf:6:22: error: MAT1 field 6 (RHO): '2.5-4.1' is not a real number"),
        "{e:?}"
    );
}

#[test]
fn all_errors_of_a_deck_are_reported_together() {
    let e = bulk_errors("CROD,1,x1,1,2\nGRID,y\nPROD,1,11,-0.2\nFOO,1\nBAR,2");
    assert!(e.iter().any(|m| m.contains("CROD field 3 (PID)")));
    assert!(e.iter().any(|m| m.contains("GRID field 2 (ID)")));
    assert!(e
        .iter()
        .any(|m| m.contains("PROD field 4 (A)") && m.contains("must be positive")));
    let unknown: Vec<_> = e.iter().filter(|m| m.contains("unknown card")).collect();
    assert_eq!(unknown.len(), 2);
    assert!(unknown[0].contains("BAR, FOO"), "lists them: {}", unknown[0]);
}

#[test]
fn unknown_cards_are_warnings_with_allow_unknown() {
    let text = format!("{HEAD}FOO,1\nENDDATA\n");
    let d = parse_deck_str(
        "t.bdf",
        &text,
        ReadOptions {
            allow_unknown: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(d.warnings.iter().any(|w| w.to_string().contains("FOO")));
}

#[test]
fn conm2_inertia_in_i32_without_i33_is_a_warning() {
    let d = deck("GRID,999\nCONM2,200,999,0,9.587-5,0.0,0.0,0.0,, +CON2-2\n+CON2-2,3.745-6,,3.745-6,,3.745-6");
    let w: Vec<String> = d.warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        w.iter()
            .any(|w| w.contains("CONM2 field 6 (I32)") && w.contains("no I33")),
        "{w:?}"
    );
}

#[test]
fn structural_mistakes_are_errors() {
    assert!(bulk_errors("+X,1,2")[0].contains("continuation marker matches no parent"));
    assert!(errors("SOL 9\nCEND\nBEGIN BULK\n=(3),*1\nENDDATA\n")[0].contains("nothing to replicate"));
    assert!(bulk_errors("GRID,1\nGRID,1")[0].contains("duplicate point id 1"));
    assert!(bulk_errors("SPC1,1,1,9,THRU,3")[0].contains("reversed"));
    assert!(errors("SOL 9\nCEND\nBEGIN BULK\nGRID,1\n")[0].contains("missing ENDDATA"));
    assert!(errors("SOL 9\nCEND\nDISP = 4\n")[0].contains("missing BEGIN BULK"));
    let e = errors("SOL 9\nCEND\nDISP = 4\nBEGIN BULK\nENDDATA\n");
    assert!(
        e[0].contains("names SET 4, which case control does not define"),
        "{e:?}"
    );
}

#[test]
fn the_papers_restored_decks_parse_as_is() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reference-data/decks");
    let rod = impactlab::deck::read_deck(&root.join("rod.bdf"), ReadOptions::default()).unwrap();
    assert_eq!((rod.bulk.grids.len(), rod.bulk.elements.len()), (146, 144));
    assert_eq!(rod.units.length, "in");
    let plate = impactlab::deck::read_deck(&root.join("plate.bdf"), ReadOptions::default()).unwrap();
    assert_eq!((plate.bulk.grids.len(), plate.bulk.elements.len()), (2501, 2401));
    // Edge SPC1s: two THRU rows of 50, and two columns of 1 + 1 + 48 replicated cards.
    let spc: usize = plate
        .bulk
        .spc1s
        .iter()
        .filter(|s| s.c.0 == 63)
        .map(|s| s.grids.len())
        .sum();
    assert_eq!(spc, 50 + 50 + 2 * 50);
    let last_column: Vec<i64> = plate
        .bulk
        .spc1s
        .iter()
        .rev()
        .skip(1)
        .take(50)
        .map(|s| s.grids[0])
        .collect();
    assert_eq!((last_column[0], last_column[49]), (5050, 150));
}

/// Goal: the embedded paper decks (what an installed binary runs) are the files in
/// reference-data: same SHA-256 (the plate's INCLUDE included) and the same model size.
#[test]
fn embedded_paper_decks_are_the_reference_files() {
    for (embedded, file) in [
        (impactlab::paper::rod_model().unwrap(), "rod.bdf"),
        (impactlab::paper::plate_model().unwrap(), "plate.bdf"),
    ] {
        let (from_file, _) = impactlab::load_deck(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("reference-data/decks")
                .join(file),
            Default::default(),
        )
        .unwrap();
        assert_eq!(embedded.deck_sha256, from_file.deck_sha256, "{file}");
        assert_eq!(embedded.n(), from_file.n(), "{file}");
        assert_eq!(embedded.elements.len(), from_file.elements.len(), "{file}");
    }
}

#[test]
fn limits_stop_a_deck_that_asks_for_too_much() {
    use impactlab::deck::Limits;
    let read = |text: &str, limits: Limits| {
        let e = parse_deck_str(
            "t.bdf",
            text,
            ReadOptions {
                limits,
                ..Default::default()
            },
        )
        .unwrap_err();
        e.diagnostics.iter().map(|d| d.to_string()).collect::<Vec<_>>()
    };
    let small = Limits {
        max_cards: 10,
        max_replication: 5,
        max_include_depth: 0,
        max_listed_ids: 20,
    };
    // Cards, written one by one or replicated (HEAD holds one: its TSTEP).
    let grids: String = (1..=10).map(|g| format!("GRID,{g}\n")).collect();
    let e = read(&format!("{HEAD}{grids}ENDDATA\n"), small);
    assert!(
        e[0].starts_with("t.bdf:15:1: error: the deck has more than 10 bulk data cards"),
        "{e:?}"
    );
    assert!(e[0].ends_with("| GRID,10"), "{e:?}");
    let e = read(&format!("{HEAD}GRID,1\n=(5),*(1)\n=(5),*(1)\nENDDATA\n"), small);
    assert!(
        e[0].contains("t.bdf:8:1: error: the deck has more than 10 bulk data cards"),
        "{e:?}"
    );
    let e = read(&format!("{HEAD}GRID,1\n=(6),*(1)\nENDDATA\n"), small);
    assert!(e[0].contains("replicates 6 cards, more than the limit of 5"), "{e:?}");
    // Listed ids, THRU ranges expanded, in the bulk data and in case control.
    let e = read(&format!("{HEAD}SPC1,1,123,1,THRU,100000000000\nENDDATA\n"), small);
    assert!(
        e[0].contains("SPC1 field 6 (G): '100000000000' lists more ids than the reader's limit allows (19 left"),
        "{e:?}"
    );
    let e = read(
        "SOL 9\nCEND\nSET 3 = 1 THRU 15, 20 THRU 30\nBEGIN BULK\nENDDATA\n",
        small,
    );
    assert!(
        e[0].contains("SET: lists more ids than the reader's limit allows (4 left"),
        "{e:?}"
    );
    // INCLUDE: refused outright by the untrusted limits, and past the depth otherwise.
    let e = read(
        &format!("{HEAD}INCLUDE '/etc/hostname'\nENDDATA\n"),
        Limits::untrusted(),
    );
    assert!(e[0].contains("INCLUDE is not allowed for this input"), "{e:?}");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("main.bdf"), format!("{HEAD}INCLUDE 'a.bdf'\nENDDATA\n")).unwrap();
    std::fs::write(dir.path().join("a.bdf"), "INCLUDE 'b.bdf'\n").unwrap();
    std::fs::write(dir.path().join("b.bdf"), "GRID,1\n").unwrap();
    let opts = |depth| ReadOptions {
        limits: Limits {
            max_include_depth: depth,
            ..Limits::default()
        },
        ..Default::default()
    };
    let main = dir.path().join("main.bdf");
    assert_eq!(impactlab::deck::read_deck(&main, opts(2)).unwrap().bulk.grids.len(), 1);
    let e = impactlab::deck::read_deck(&main, opts(1)).unwrap_err().to_string();
    assert!(
        e.contains("a.bdf:1:1: error: INCLUDE: INCLUDE nested more than 1 deep"),
        "{e}"
    );
}

/// Goal: the dynamic load cards are read by NASTRAN-95's field rules (BULK.TXT):
/// DAREA and DELAY with "One or two" triples on a card, TLOAD1's DELAY set and MSC's
/// real delay, TLOAD2's continuation (C, B), TABLED2's X1 with a SKIP entry left out,
/// a descending TABLED1 turned ascending, and DLOAD's combination; and DLOAD's rule
/// "The Li must be unique" refused naming the field.
#[test]
fn dynamic_load_cards_read_by_the_manuals_rules() {
    use impactlab::deck::cards::{DelayRef, TableFunction, TloadShape};
    let d = deck(
        "DAREA,8,1,2,1.5,2,3,-2.0\nDELAY,5,1,2,1.0-4\nTLOAD1,4,8,5,,6\nTLOAD1,7,8,2.5-4,LOAD,6\n\
         TLOAD2,9,8,,,0.0,1.0-3,100.,90.\n,-2.0,1.0\nTABLED2,6,1.0-4,,,,,,,+T\n+T,0.0,0.0,SKIP,SKIP,1.0,2.0,ENDT\n\
         TABLED1,3\n,2.0,1.0,1.0,5.0,ENDT\nDLOAD,10,2.0,1.0,4,-1.0,9\n\
         GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.",
    );
    let b = &d.bulk;
    assert_eq!(b.dareas.len(), 2);
    assert_eq!((b.dareas[1].p, b.dareas[1].c, b.dareas[1].a), (2, 3, -2.0));
    assert_eq!((b.delays[0].p, b.delays[0].t), (1, 1e-4));
    assert_eq!(b.tloads[0].delay, DelayRef::Set(5));
    assert_eq!(b.tloads[0].shape, TloadShape::Table(6));
    assert_eq!(b.tloads[1].delay, DelayRef::Value(2.5e-4));
    let TloadShape::Formula(f) = b.tloads[2].shape else {
        panic!("TLOAD2")
    };
    assert_eq!((f.t2, f.f, f.p, f.c, f.b), (1e-3, 100.0, 90.0, -2.0, 1.0));
    let TableFunction::Points { x1, points, .. } = &b.tableds[0].function else {
        panic!("TABLED2")
    };
    assert_eq!((*x1, points.as_slice()), (1e-4, &[(0.0, 0.0), (1.0, 2.0)][..]));
    let TableFunction::Points { points, .. } = &b.tableds[1].function else {
        panic!("TABLED1")
    };
    assert_eq!(points.as_slice(), &[(1.0, 5.0), (2.0, 1.0)]);
    assert_eq!(
        (b.dloads[0].scale, b.dloads[0].terms.as_slice()),
        (2.0, &[(1.0, 4), (-1.0, 9)][..])
    );
    let errors = bulk_errors("DLOAD,10,1.0,1.0,4,2.0,4");
    assert!(
        errors
            .iter()
            .any(|e| e.contains("DLOAD field 7 (Li)") && e.contains("The Li must be unique")),
        "{errors:?}"
    );
}
