//! The paper's second problem: a steel rod striking a clamped 6 in × 6 in × 0.15 in
//! glass/epoxy plate at 1470 in/s (49×49 CQUAD4, measured contact time 204 µs).
//!
//! One Newmark run of the restored deck at the paper's Δt = 1e-7 s, 3000 steps (the
//! deck's 2000 steps end before separation), shared by the tests below.

use crate::common;

use common::deck;
use impactlab::integrate::Scheme;
use impactlab::model::Model;
use impactlab::run::{run_model, RunOptions, RunResult};
use std::sync::OnceLock;

fn plate() -> &'static (Model, RunResult) {
    static CELL: OnceLock<(Model, RunResult)> = OnceLock::new();
    CELL.get_or_init(|| {
        let (m, _) = impactlab::load_deck(&deck("plate.bdf"), Default::default()).expect("plate deck loads");
        let r = common::run(&m, Scheme::Newmark, None, Some(3000));
        (m, r)
    })
}

fn column<'a>(r: &'a RunResult, name: &str) -> impl Iterator<Item = f64> + 'a {
    let j = r
        .history_names()
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    r.history.iter().map(move |row| row[j])
}

/// Goal: the deck reads to the paper's model size. 50×50 grids, the 196 edge grids
/// clamped, 5 DOF per free grid (PS = 6), plus the impactor's T3 and the EPOINT:
/// 48² · 5 + 1 + 1 = 11522 active DOF (the paper quotes 11510). Of the solved DOFs, the
/// in-plane T1/T2 of the 2304 free grids carry no load and no coupling to bending
/// (B = 0): 4608 of them are dropped as inert.
#[test]
fn plate_deck_model_size_and_inert_membrane() {
    let (m, r) = plate();
    assert_eq!(m.active_dofs(), 11522);
    assert_eq!(r.summary.model.inert_dofs_skipped, 4608);
    assert_eq!(r.summary.model.solved_dofs, 11522 - 1 - 4608);
}

/// Goal: contact time against the measured 204 µs [8]. Our converged answer (mesh study
/// in reference-data/plate-mesh-study.csv) is 204.4 µs on this mesh; the measurement
/// is quoted to 1 µs, the tolerance 1 % covers the reading and the mesh error.
#[test]
fn plate_contact_time_matches_measured_204_us() {
    let (_, r) = plate();
    let iv = &r.summary.contact.intervals;
    assert_eq!(iv.len(), 1, "one contact interval: {iv:?}");
    let d = r.summary.contact.duration.unwrap();
    assert!((d / 204e-6 - 1.0).abs() < 0.01, "contact {d:e} s");
}

/// Goal: the paper's Figure 6 shows a secondary impact near t = 175 µs in the latter
/// half of the contact. We find a local force maximum there (±10 µs).
#[test]
fn plate_secondary_impact_near_175_us() {
    let (_, r) = plate();
    let sec = impactlab::study::secondary_peak(r).expect("a secondary peak");
    assert!(
        (sec.time_s - 175e-6).abs() < 10e-6,
        "secondary peak at {:e}",
        sec.time_s
    );
    assert!(sec.value > 0.1 * r.summary.contact.peak_force);
}

/// Goal: the contact force is the impactor's NOLIN3 load, and the four plate loads sum
/// to it up to the deck's own mismatch: 4 × 1.945e5 / 7.779e5 = 1 + 1.29e-4.
#[test]
fn plate_force_is_sum_of_the_four_plate_loads() {
    let (_, r) = plate();
    let ids = ["2525", "2526", "2625", "2626"];
    let sums: Vec<f64> = (0..r.history.len())
        .map(|k| {
            ids.iter()
                .map(|g| column(r, &format!("nlload_{g}_T3")).nth(k).unwrap())
                .sum()
        })
        .collect();
    let mut checked = 0;
    for ((s, fc), fi) in sums
        .iter()
        .zip(column(r, "contact_force"))
        .zip(column(r, "nlload_999_T3"))
    {
        assert!((fi + fc).abs() <= 1e-12 * fc.abs(), "impactor load −F");
        if fc > 1.0 {
            assert!((s / fc - 4.0 * 1.945e5 / 7.779e5).abs() < 1e-12, "{s} vs {fc}");
            checked += 1;
        } else {
            assert!(s.abs() <= 1e-9 * 7.8e5);
        }
    }
    assert!(checked > 100);
}

/// Goal: the ledger balances (Newmark, O(Δt²) error plus the booked work of the deck's
/// non-conservative load mismatch), the impactor rebounds, and the strains at the top
/// and bottom fibres are equal and opposite (pure bending, no membrane response).
#[test]
fn plate_ledger_rebound_and_fibre_strains() {
    let (_, r) = plate();
    let e = r.summary.energy.max_relative_error.unwrap();
    assert!(e < 1e-5, "energy error {e:e}");
    assert!(r.summary.impactor.rebound_velocity.unwrap() < 0.0);
    for g in ["2525", "3325", "4125"] {
        for c in ["xx", "yy"] {
            let peak = column(r, &format!("strain_{g}_z1_{c}")).fold(0.0f64, |a, x| a.max(x.abs()));
            assert!(peak > 1e-4, "{g} {c} strained");
            for (lo, hi) in column(r, &format!("strain_{g}_z1_{c}")).zip(column(r, &format!("strain_{g}_z2_{c}"))) {
                assert!((lo + hi).abs() <= 1e-12 * peak, "{g} {c}: {lo} vs {hi}");
            }
        }
    }
}

/// Goal: the flexural wave reaches gage A (8 elements from the centre) before gage B
/// (16 elements): the first time |εyy| passes 10 % of its peak is earlier at A.
#[test]
fn plate_gage_a_strains_before_gage_b() {
    let (_, r) = plate();
    let first = |g: &str| {
        let col: Vec<f64> = column(r, &format!("strain_{g}_z2_yy")).collect();
        let peak = col.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let k = col.iter().position(|x| x.abs() > 0.1 * peak).unwrap();
        r.history[k][0]
    };
    assert!(first("3325") < first("4125"));
}

/// Goal: dropping the inert membrane DOFs is exact: the contact force of a run that
/// solves all 11521 DOFs equals ours to 1e-10 relative (first 600 steps).
#[test]
fn plate_inert_dofs_dropping_is_exact() {
    let (m, _) = plate();
    let go = |skip_inert| {
        run_model(
            m,
            &RunOptions {
                steps: Some(600),
                skip_inert,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let (a, b) = (go(true), go(false));
    assert_eq!(b.summary.model.solved_dofs, 11521);
    let peak = a.series.force.iter().fold(0.0f64, |x, y| x.max(*y));
    for (x, y) in a.series.force.iter().zip(&b.series.force) {
        assert!((x - y).abs() <= 1e-10 * peak, "{x} vs {y}");
    }
}

/// Goal: every implicit scheme's ledger closes on the shear-deformable plate as on the
/// thin one (the target's strain energy includes the transverse shear part). Model:
/// the cross-ply with G1Z/G2Z (MITC4) and without (DKQ), Δt 1e-7 s, 2400 steps (past
/// the end of contact, 221 µs). Bounds: the energy-conserving scheme to round-off
/// (1e-10); Newmark and NASTRAN's three-point scheme at the thin case's 5e-6 (their
/// residual here is the deck's NOLIN3 mismatch booked as external work and the
/// schemes' own; measured 1.9e-6 and 2.9e-6 with shear, 2.1e-6 and 3.3e-6 thin), the
/// shear plate's within a factor 2 of the thin plate's.
#[test]
fn every_implicit_schemes_ledger_closes_on_the_shear_plate() {
    let thin = impactlab::load_deck(&deck("plate-pcomp.bdf"), Default::default())
        .unwrap()
        .0;
    let shear = impactlab::load_deck(&deck("plate-pcomp-shear.bdf"), Default::default())
        .unwrap()
        .0;
    let shells = shear.elements.iter().filter_map(|e| e.kernel.family().shell());
    assert!(shells.clone().count() == 2401 && shells.clone().all(|s| s.shear.is_some()));
    for (scheme, bound) in [
        (Scheme::Newmark, 5e-6),
        (Scheme::Energy, 1e-10),
        (Scheme::Nastran, 5e-6),
    ] {
        let error = |m: &Model| {
            let opts = RunOptions {
                scheme,
                steps: Some(2400),
                ..Default::default()
            };
            run_model(m, &opts).unwrap().summary.energy.max_relative_error.unwrap()
        };
        let (t, s) = (error(&thin), error(&shear));
        eprintln!("{scheme:?}: max energy error thin {t:e}, shear {s:e}");
        assert!(
            s <= bound && t <= bound,
            "{scheme:?}: thin {t:e}, shear {s:e}, bound {bound:e}"
        );
        assert!(s <= 2.0 * t.max(1e-13), "{scheme:?}: thin {t:e}, shear {s:e}");
    }
}
