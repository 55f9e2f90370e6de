//! Transient decks loaded through time (DLOAD, TLOAD1/2, DAREA, DELAY, TABLEDi, LSEQ),
//! run by `impactlab run` as a user runs them.

use crate::common;

use impactlab::verify::printed::{read_run_histories, Histories};

/// Runs a deck (written into a temporary directory) with `scheme`, returning its
/// displacement histories and its summary.
fn run(deck: &str, scheme: &str) -> (Histories, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("deck.bdf");
    std::fs::write(&path, deck).unwrap();
    let out = dir.path().join("out");
    let o = common::impactlab(&[
        "run",
        path.to_str().unwrap(),
        "--scheme",
        scheme,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    (read_run_histories(&out).unwrap(), summary)
}

/// Goal: DLOAD's combination, DELAY and TLOAD2's formula act as the manual writes
/// them (P = S·S1·A·f(t − τ)). Model: a scalar spring-mass (CELAS2 k = 100, CMASS2
/// m = 1 on SPOINT 1, ω = 10) at rest, loaded by DLOAD 10 = 2.0 × (1.5 × TLOAD2 4), the
/// TLOAD2 a unit step (F = 0, B = 0) on DAREA A = 1, delayed by τ = 0.1; newmark,
/// Δt = 1e-3. Reference: u = (3/k)(1 − cos ω(t − τ)) for t ≥ τ, 0 before.
/// Tolerance: 0 before the delay (exactly); after it 3e-3 of the amplitude 6/k: the
/// trapezoidal rule meets the step at a step time and averages its two end loads,
/// which starts the step Δt/2 early, an error of (3/k)·ωΔt/2 = 2.5e-3 of the
/// amplitude (measured 2.49e-3); against the closed form started Δt/2 early, 1e-4
/// (measured 3.4e-5, the scheme's second-order remainder). The ledger closes to
/// round-off (1e-12).
#[test]
fn a_delayed_step_combined_by_a_dload_rings_a_spring_mass_as_the_closed_form() {
    let deck = "SOL 109\nCEND\nDISP = ALL\nDLOAD = 10\nTSTEP = 1\nBEGIN BULK\nSPOINT,1\nCELAS2,1,100.,1\n\
                CMASS2,2,1.0,1\nDAREA,8,1,,1.0\nDELAY,6,1,,0.1\nTLOAD2,4,8,6,,0.0,100.0\nDLOAD,10,2.0,1.5,4\n\
                TSTEP,1,1000,1.0-3,1\nENDDATA\n";
    let (h, summary) = run(deck, "newmark");
    let u = &h.series[&(1, 0)];
    assert_eq!(u.len(), 1001);
    let amplitude = 6.0 / 100.0;
    let (mut worst, mut shifted): (f64, f64) = (0.0, 0.0);
    let response = |t: f64| 3.0 / 100.0 * (1.0 - (10.0 * t).cos());
    for &(t, v) in u {
        if t < 0.1 - 1e-9 {
            assert_eq!(v, 0.0, "t = {t}");
        } else {
            worst = worst.max((v - response(t - 0.1)).abs() / amplitude);
            shifted = shifted.max((v - response(t - 0.1 + 0.5e-3)).abs() / amplitude);
        }
    }
    assert!(worst < 3e-3, "{worst:e}");
    assert!(shifted < 1e-4, "{shifted:e}");
    let error = summary["energy"]["max_relative_error"].as_f64().unwrap();
    assert!(error.abs() < 1e-12, "ledger {error:e}");
}

/// A cantilever strip of four CQUAD4 (10 × 1, clamped at x = 0, the drilling
/// rotations held by GRDSET) in a transient deck
/// loaded through TLOAD1 7 (a triangular pulse, TABLED1 9) on `load`.
fn strip(case: &str, load: &str) -> String {
    let mut d = format!(
        "SOL 109\nCEND\nSPC = 1\nDISP = ALL\nDLOAD = 7\nTSTEP = 1\n{case}BEGIN BULK\nMAT1,1,1.0+7,,0.3,2.5-4\n\
         PSHELL,1,1,0.1,1\nGRDSET,,,,,,,6\nTLOAD1,7,20,,,9\nTABLED1,9\n,0.0,0.0,1.0-3,1.0,2.0-3,0.0,1.0,0.0\n,ENDT\n\
         TSTEP,1,400,1.0-5,4\nSPC1,1,123456,1,101\n"
    );
    for i in 0..=4 {
        let x = 2.5 * i as f64;
        d += &format!("GRID,{},,{x:?},0.0,0.0\nGRID,{},,{x:?},1.0,0.0\n", i + 1, i + 101);
    }
    for i in 0..4 {
        d += &format!("CQUAD4,{},1,{},{},{},{}\n", i + 1, i + 1, i + 2, i + 102, i + 101);
    }
    d + load + "ENDDATA\n"
}

/// Goal: an LSEQ gives a static load set as a dynamic load's distribution, as MSC
/// reads it: a pressure pulse on a panel. Model: the cantilever strip under a
/// uniform pressure of 2.0 (PLOAD4 on its four elements, THRU) through LSEQ 1
/// (EXCITEID 20, LOADSET = 1), against its twin loaded by DAREA 20 with the pressure's
/// nodal forces (p·A/4 a corner: 2.5 at the inner grids, 1.25 at the tip), the same
/// TLOAD1 pulse. Reference: the twin's histories. Tolerance: 1e-12 of the largest
/// displacement (the consistent nodal forces are quadrature sums, equal to round-off);
/// both ledgers close to round-off.
#[test]
fn a_pressure_pulse_through_an_lseq_equals_its_nodal_forces_as_darea() {
    let lseq = strip("LOADSET = 1\n", "LSEQ,1,20,30\nPLOAD4,30,1,2.0,,,,THRU,4\n");
    let mut darea = String::new();
    for g in [2, 3, 4, 102, 103, 104] {
        darea += &format!("DAREA,20,{g},3,2.5\n");
    }
    darea += "DAREA,20,5,3,1.25,105,3,1.25\n";
    let twin = strip("", &darea);
    let (a, sa) = run(&lseq, "newmark");
    let (b, sb) = run(&twin, "newmark");
    let scale = b.series.values().flatten().fold(0.0f64, |m, p| m.max(p.1.abs()));
    assert!(scale > 1e-3, "the pulse moves the strip: {scale:e}");
    assert_eq!(a.series.keys().collect::<Vec<_>>(), b.series.keys().collect::<Vec<_>>());
    for (key, s) in &a.series {
        for (x, y) in s.iter().zip(&b.series[key]) {
            assert_eq!(x.0, y.0);
            assert!(
                (x.1 - y.1).abs() <= 1e-12 * scale,
                "{key:?} at {}: {} against {}",
                x.0,
                x.1,
                y.1
            );
        }
    }
    for s in [sa, sb] {
        let error = s["energy"]["max_relative_error"].as_f64().unwrap();
        assert!(error.abs() < 1e-12, "ledger {error:e}");
    }
}
