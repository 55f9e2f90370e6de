//! NASTRAN's own rules for writing a deck, one test each, quoting the User's Manual
//! (NASTRAN-95, `manual/BULK.TXT` section 2.4 and the card pages; `manual/CASE.TXT`),
//! and MSC's where the two dialects differ. Each test reads a small deck written by
//! the rule and checks the typed result; a reader that breaks the rule fails it.

use crate::common;

use common::{bulk_deck as deck, BULK_HEAD as HEAD};
use impactlab::deck::cards::BarOrientation;
use impactlab::deck::{parse_deck_str, Deck, OutputSet, ReadOptions};

fn structure(text: &str) -> Deck {
    parse_deck_str(
        "t.bdf",
        text,
        ReadOptions {
            structure: true,
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// 2.4.1.1: "field 10 (except column 73, which is not referenced) is used in
/// conjunction with field 1 of the continuation card as an identifier".
#[test]
fn column_73_of_a_continued_card_is_not_referenced() {
    // NASTRAN-95's D01-03-1A writes `CSPC-A` on the parent and `+SPC-A` on its continuation.
    let d = deck(
        "GRID,1\nGRID,2\nGRID,3\n\
         SPC1    4       123     1                                               CSPC-A\n\
         +SPC-A  2       3",
    );
    assert_eq!(d.bulk.spc1s[0].grids, [1, 2, 3]);
    // Blanks inside an identifier are its own (T01-22-1A: `CIH    1` ... `+IH    1`).
    let d = deck(
        "GRID,5\nCONM2          1       5       0     2.0                                CIH    1\n\
         +IH    1     1.0             2.0                     3.0",
    );
    assert_eq!(d.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
}

/// 2.4.1.1: a data item "must lie completely within the designated field"; NASTRAN-95
/// reads a real written with blanks inside its field (T01-25-1A: `2.0  E+7`).
#[test]
fn a_real_with_blanks_inside_its_field_reads_as_written_without_them() {
    let d = deck("MAT1    11      2.0  E+7        .3      1.5  -4");
    let m = &d.bulk.mat1s[0];
    assert_eq!((m.e, m.rho), (2.0e7, 1.5e-4));
    // An integer split by a blank is not joined into another number.
    let e = common::bulk_errors("GRID    1 2");
    assert!(e[0].contains("GRID field 2 (ID): '1 2' is not an integer"), "{e:?}");
}

/// 2.4.1.2 rule 3: "Data items must be separated with a comma, one or more blanks, or
/// the combination of a comma and blanks"; Example 1: `GRID, 2, 3, 1.0 2.0,, 4,316`.
#[test]
fn free_field_items_separated_by_blanks() {
    let d = deck("CORD2R,3,,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\nGRID, 2, 3, 1.0 2.0,, 4,316");
    let g = &d.bulk.grids[0];
    assert_eq!((g.id, g.cp, g.x, g.cd), (2, Some(3), [1.0, 2.0, 0.0], Some(4)));
    assert_eq!(g.ps.map(|c| c.0), Some(0b100101));
}

/// Rules 5-9 and Example 2: `=(4),*(1),=,%(1.8),==` generates four cards, "using ...
/// the computed incremental value" to reach 1.8 on the last; rule 25: `/` "indicates
/// that the current field is the same as the previous field".
#[test]
fn duplication_increments_reaches_and_repeats_fields() {
    let d = deck("grid,2,3,1.0,2.0,,4,316\n=(4),*(1),=,%(1.8),==\nCORD2R,3,,0.,0.,0.,0.,0.,1.\n,1.,0.,0.");
    let x: Vec<f64> = d.bulk.grids.iter().map(|g| g.x[0]).collect();
    assert_eq!(d.bulk.grids.iter().map(|g| g.id).collect::<Vec<_>>(), [2, 3, 4, 5, 6]);
    for (got, want) in x.iter().zip([1.0, 1.2, 1.4, 1.6, 1.8]) {
        assert!((got - want).abs() < 1e-12, "{x:?}");
    }
    // `///` after *(1) *(2): three more fields incremented by 2 (D01-06-2A).
    let d = deck("SPC1,1,1,10,20,30,40,50\n=(2), *(1),=,*(1) *(2),///");
    assert_eq!(d.bulk.spc1s[2].grids, [12, 24, 34, 44, 54]);
}

/// Rules 10-12: `n)X` puts X in field n, `)+X` in field 10, and "a right parenthesis )
/// in column 1 indicates the duplication of the tenth field of the preceding card into
/// the first field"; rule 13: "The continuation ID ... is automatically increased (by
/// 1) in the repeated-duplication operation. The ID must be in the form of +A-X".
#[test]
fn field_index_tenth_field_and_continuation_ids_that_count() {
    let d = deck("GRID,1\nGRID,2\nGRDSET, 8)456\nGRID,3\nCONM2, 9  1,, 5.0 0. 0. 0. )+C-21\n),1.0,,2.0,,,3.0");
    assert_eq!(d.bulk.grdset.ps.0, 0b111000);
    assert_eq!(d.bulk.conm2s[0].inertia, [1.0, 0.0, 2.0, 0.0, 0.0, 3.0]);
    // T13-02-1A: parents and continuations duplicated apart, joined by their counted IDs.
    let d = deck(
        "GRID,1\n=(2),*(1)\nCONM2,   9  1,,   5.0  0.  0.  0.  )+C-21\n=(2), *(1),*(1),,==\n\
         +C-21,  7.0  0.0  7.0,  0.  0.  7.0\n=(2),==",
    );
    assert_eq!(d.bulk.conm2s.len(), 3);
    for c in &d.bulk.conm2s {
        assert_eq!(c.inertia, [7.0, 0.0, 7.0, 0.0, 0.0, 7.0], "CONM2 {}", c.eid);
    }
    // A continuation duplicating the card image before it (T01-23-1A: `+P2,==`).
    let d = deck("SPC1,1,1,1,2,3,4,5,6,+S1\n+S1,7,8,9,10,11,12,13,14,+S2\n+S2,==");
    let want: Vec<i64> = (1..=14).chain(7..=14).collect();
    assert_eq!(d.bulk.spc1s[0].grids, want);
}

/// CBAR (BULK.TXT): field 9 is COSMIC's "F Flag to specify the nature of fields 6-8":
/// "F = 1: X1 X2 X3; F = 2: GO"; MSC's OFFT where it holds letters. BAROR: "The
/// contents of fields on this card will be assumed for any CBAR card whose
/// corresponding fields are blank".
#[test]
fn cbar_field_9_by_its_content_and_baror_defaults() {
    let grids = "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\n";
    let d = structure(&format!(
        "SOL 1\nCEND\nBEGIN BULK\n{grids}\
         CBAR,1,9,1,2,0.,1.,0.,1\nCBAR,2,9,1,2,3,,,2\nCBAR,3,9,1,2,0.,0.,1.,GGG\n\
         BAROR,,9,,,0.,0.,1.,1\nCBAR,4,,1,2\nENDDATA\n"
    ));
    let o: Vec<_> = d
        .bulk
        .elements
        .iter()
        .map(|e| e.bar.as_ref().unwrap().orientation)
        .collect();
    assert_eq!(o[0], BarOrientation::Vector([0.0, 1.0, 0.0]));
    assert_eq!(o[1], BarOrientation::Grid(3));
    assert_eq!(o[2], BarOrientation::Vector([0.0, 0.0, 1.0]));
    assert_eq!(
        (o[3], d.bulk.elements[3].pid),
        (BarOrientation::Vector([0.0, 0.0, 1.0]), 9)
    );
    assert_eq!(d.bulk.readings.values().sum::<usize>(), 3, "{:?}", d.bulk.readings);
}

/// BAROR's fields reach the CBARs written before it, and the cards are still typed
/// in the order they are written (a CBAR waiting for it holds the cards after it);
/// BAROR: "Only one BAROR card may appear in your Bulk Data Deck".
#[test]
fn cbars_before_baror_wait_for_it_in_order() {
    let grids = "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n";
    let d = structure(&format!(
        "SOL 1\nCEND\nBEGIN BULK\n{grids}\
         CBAR,1,,1,2\nCROD,2,5,1,2\nCBAR,3,9,1,2,0.,1.,0.,1\nBAROR,,9,,,0.,0.,1.,1\nCBAR,4,,1,2\nENDDATA\n"
    ));
    let e: Vec<(i64, i64)> = d.bulk.elements.iter().map(|e| (e.eid, e.pid)).collect();
    assert_eq!(e, [(1, 9), (2, 5), (3, 9), (4, 9)]);
    assert_eq!(
        d.bulk.elements[0].bar.as_ref().unwrap().orientation,
        BarOrientation::Vector([0.0, 0.0, 1.0])
    );
    let e = parse_deck_str(
        "t.bdf",
        &format!("SOL 1\nCEND\nBEGIN BULK\n{grids}CBAR,1,,1,2\nBAROR,,9,,,0.,0.,1.,1\nBAROR,,8\nENDDATA\n"),
        ReadOptions {
            structure: true,
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("t.bdf:8:1") && e.contains("only one BAROR card") && e.contains("is at t.bdf:7:1"),
        "{e}"
    );
}

/// CROD: "One or two ROD elements may be defined on a single card".
#[test]
fn two_rods_on_one_card() {
    let d = deck("GRID,1\nGRID,2\nGRID,3\nCROD,7,1,1,2,8,1,2,3");
    let e: Vec<(i64, Vec<i64>)> = d.bulk.elements.iter().map(|e| (e.eid, e.g.clone())).collect();
    assert_eq!(e, [(7, vec![1, 2]), (8, vec![2, 3])]);
}

/// CASE.TXT: a `$` ends a line's data; output requests take describers in parentheses
/// and any name of four letters or more that begins the request's name; `SET n = ALL`;
/// `EXCEPT` leaves members out of the range before it; the plotting packages are skipped.
#[test]
fn case_control_as_pre_processors_and_nastran_95_write_it() {
    let d = parse_deck_str(
        "t.bdf",
        "SOL 1\nCEND\nTITLE = A $ TITLE KEEPS ITS DOLLAR\nSPC = 14   $  SYM , NO PITCH\n\
         SET 1 = ALL\nSET 2 = 1 THRU 10 EXCEPT 4 7, 12 THRU 20 BY 4\n\
         DISPLACEMENT(SORT1,REAL)=1\nSTRESS(PLOT,PRINT,SORT1,REAL,VONMISES,BILIN)=2\n\
         SPCF = ALL\nOLOAD(PRINT) = ALL $ loads\nOUTPUT(PLOT)\nSET 1 = ELEMENTS TRIA2\nPLOT\n\
         BEGIN BULK\nENDDATA\n",
        ReadOptions {
            structure: true,
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let c = &d.case;
    assert_eq!(c.title, "A $ TITLE KEEPS ITS DOLLAR");
    assert_eq!(c.spc.as_ref().map(|s| s.id), Some(14));
    assert_eq!(c.outputs["DISP"].set, OutputSet::All);
    assert_eq!(c.outputs["STRESS"].set, OutputSet::Set(2));
    assert_eq!(c.sets[&2].members, [1, 2, 3, 5, 6, 8, 9, 10, 12, 16, 20]);
    let not: Vec<&str> = c.not_written.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(not, ["SPCFORCES", "OLOAD"]);
    assert!(d.warnings.iter().any(|w| w.message.contains("plotting section")));
}

/// Goal: what a transient deck asks for and impactlab does not write is named in the
/// run's summary (`model.not_written` in summary.json and a printed line), never
/// dropped in silence: the paper's rod with SPCFORCES, OLOAD (twice) and ACCEL asked
/// for; without such requests the key is absent.
#[test]
fn requests_impactlab_does_not_write_are_named_in_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(common::deck("rod.bdf")).unwrap();
    let asked = text.replacen(
        "CEND\n",
        "CEND\nSPCFORCES = ALL\nOLOAD(PRINT) = ALL\nACCEL = ALL\nOLOAD = ALL\n",
        1,
    );
    assert_ne!(asked, text, "the rod deck has a CEND line");
    let deck = dir.path().join("rod.bdf");
    std::fs::write(&deck, asked).unwrap();
    let summary = |deck: &std::path::Path, out: &str| {
        let out = dir.path().join(out);
        let o = common::impactlab(&[
            "run",
            deck.to_str().unwrap(),
            "--steps",
            "10",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        (s, String::from_utf8_lossy(&o.stdout).into_owned())
    };
    let (s, printed) = summary(&deck, "asked");
    assert_eq!(
        s["model"]["not_written"],
        serde_json::json!(["SPCFORCES", "OLOAD", "ACCEL"])
    );
    assert!(
        printed.contains("  not written: SPCFORCES, OLOAD, ACCEL (asked for in case control)"),
        "{printed}"
    );
    let (s, printed) = summary(&common::deck("rod.bdf"), "plain");
    assert!(s["model"].get("not_written").is_none(), "{}", s["model"]);
    assert!(!printed.contains("not written"), "{printed}");
}

/// PARAM WTMASS: "the terms of the structural mass matrix are multiplied by the value
/// of this parameter": a deck in weight units with WTMASS builds the mass of the same
/// deck with its densities and masses multiplied out.
#[test]
fn wtmass_scales_every_mass_of_the_deck() {
    let body = |rho: &str, m: &str, nsm: &str| {
        format!(
            "GRID,1,,0.,0.,0.\nGRID,2,,10.,0.,0.\nCROD,1,1,1,2\nPROD,1,1,0.5,,,{nsm}\n\
             MAT1,1,1.0+7,,0.3,{rho}\nCONM2,9,2,,{m}\n"
        )
    };
    let weighed = structure(&format!(
        "SOL 1\nCEND\nBEGIN BULK\n{}PARAM,WTMASS,0.00259\nENDDATA\n",
        body("0.1", "2.0", "0.01")
    ));
    let scaled = structure(&format!(
        "SOL 1\nCEND\nBEGIN BULK\n{}ENDDATA\n",
        body("2.59-4", "5.18-3", "2.59-5")
    ));
    let mass = |d: &Deck| {
        let (s, _) = impactlab::model::build_structure(d).unwrap();
        s.mass_properties().mass[0]
    };
    let (a, b) = (mass(&weighed), mass(&scaled));
    // One product more per term: a few units of round-off.
    assert!((a - b).abs() <= 1e-14 * b, "{a} {b}");
    // `check` weighs in the deck's input units, as the grid point weight generator does.
    let r = impactlab::model::check::check(&weighed);
    let input = 0.1 * 0.5 * 10.0 + 0.01 * 10.0 + 2.0;
    assert!((r.weight.unwrap().mass[0] - input).abs() < 1e-12 * input);
    assert!((r.scaled_mass.unwrap()[0] - b).abs() <= 1e-14 * b);
}

/// MAT1: "RHO Mass density (Real)": zero is a massless material, as blank is.
#[test]
fn zero_density_is_a_massless_material() {
    let d = deck("MAT1,1,1.0+7,,0.3,0.0");
    assert_eq!(d.bulk.mat1s[0].rho, 0.0);
}

/// CONROD: "EID G1 G2 MID A J C NSM"; PTUBE: "OD Outside diameter of tube", "T
/// Thickness of tube", "If T is zero, a solid circular rod is assumed".
#[test]
fn conrod_and_tube_sections() {
    let d = structure(&format!(
        "{}GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nCONROD,5,1,2,1,0.25,0.01\nCTUBE,6,3,1,2\n\
         PTUBE,3,1,2.0,0.5\nPTUBE,4,1,2.0\nMAT1,1,1.0+7,,0.3\nENDDATA\n",
        HEAD.replace("SOL 9", "SOL 1")
    ));
    let pi = std::f64::consts::PI;
    let tube = d.bulk.prods.iter().find(|p| p.pid == 3).unwrap();
    assert!((tube.a - pi / 4.0 * (4.0 - 1.0)).abs() < 1e-15);
    assert!((tube.j - pi / 32.0 * (16.0 - 1.0)).abs() < 1e-15);
    let solid = d.bulk.prods.iter().find(|p| p.pid == 4).unwrap();
    assert!((solid.a - pi).abs() < 1e-15);
    let r = impactlab::model::check::check(&d);
    assert!(r.takes, "{r:?}");
    assert_eq!(r.elements.get("CONROD"), Some(&1));
    assert_eq!(r.elements.get("CTUBE"), Some(&1));
}

/// PCOMP1: "all plies are composed of the same material and are of equal thickness"
/// (PID ZOC NSM SBOND FT MID TPLY LOPT / TH1 TH2 ...); PCOMP2: "all plies are composed
/// of the same material" (... / T1 TH1 T2 TH2 ...). Read as the PCOMP they describe.
#[test]
fn cosmic_uniform_laminates_are_the_pcomp_they_describe() {
    let d = deck(
        "PCOMP1  3                       1.2 E+04HILL    3       .0666666        +PCOMP1\n\
         +PCOMP1 0.0     90.0    0.0\n\
         PCOMP2,4,,,,STRAIN,3,,SYM,+PC1\n+PC1,0.025,45.,0.05,-45.",
    );
    let plies = |pid: i64| -> Vec<(i64, f64, f64)> {
        let p = d.bulk.pcomps.iter().find(|p| p.pid == pid).unwrap();
        p.plies.iter().map(|p| (p.mid, p.t, p.theta)).collect()
    };
    assert_eq!(
        plies(3),
        [(3, 0.0666666, 0.0), (3, 0.0666666, 90.0), (3, 0.0666666, 0.0)]
    );
    assert_eq!(plies(4), [(3, 0.025, 45.0), (3, 0.05, -45.0)]);
    let p4 = d.bulk.pcomps.iter().find(|p| p.pid == 4).unwrap();
    assert_eq!(
        (p4.lam, p4.ft.as_deref()),
        (impactlab::deck::cards::Lam::Sym, Some("STRN"))
    );
    assert_eq!(d.bulk.pcomps[0].sb, Some(1.2e4));
}
