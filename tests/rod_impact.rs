//! The paper's first problem: a 5/8 in steel ball (m = 9.587e-5 lbf·s²/in) at
//! 62.1 in/s on a free-free 36 in aluminium rod (144 CRODs, E = 10e6 psi,
//! ρ = 2.5e-4 lbf·s²/in⁴, A = 0.196 in²), Hertz K = 6.24e6 lbf/in^1.5, run from the
//! restored deck `reference-data/decks/rod.bdf` (Δt = 2e-7 s, 2500 steps).
//! C = √(E/ρ) = 2e5 in/s, L/C = 180 µs.

use crate::common;
use common::*;
use impactlab::integrate::Scheme;
use impactlab::numerics::interp;
use impactlab::run::Column;

/// Goal: the deck builds the model the paper describes.
/// Model: rod.bdf. Reference: the paper's text, "a total of 147 degrees of freedom"
/// (145 axial grid DOFs, the impactor, the indentation EPOINT). Exact.
#[test]
fn rod_deck_has_147_active_dofs() {
    let m = rod_model();
    assert_eq!(m.active_dofs(), 147);
    assert_eq!(m.n(), 146, "the EPOINT is algebraic (TF), not solved for");
    let c = m.contact.as_ref().unwrap();
    assert_eq!(c.impactor.grid, 999);
    assert_eq!(c.stiffness, 6.24e6);
    assert!(
        c.nonconservative.is_empty(),
        "the rod deck's NOLIN3 pair is exactly conservative"
    );
    let rod = m.rod.unwrap();
    assert_eq!((rod.length, rod.wave_speed), (36.0, 2.0e5));
}

/// Goal: the invariants the paper reads off its Figure 4, with the exact values.
/// Model: rod.bdf, newmark. Reference: the semi-infinite-rod Hertz model (ball and a
/// dashpot of impedance ρCA, exact until the reflection returns at 2L/C), integrated
/// to rtol 1e-12: contact ends at tC/L = 0.41340, the impactor is at rest at 0.22352,
/// 79.11 % of the energy goes to the rod (reference-data/rod-published.toml).
/// Tolerances: 2e-3 in tC/L and 0.5 % in energy fraction cover the FE mesh and Δt
/// (measured: 4e-5 and 2e-4); the paper's own readings (0.4, 0.25, 80 %) are checked
/// against these with the width of a figure reading.
#[test]
fn rod_contact_ends_at_041_and_impactor_stops_at_0224() {
    let r = run(&rod_model(), Scheme::Newmark, None, None);
    let s = &r.summary;
    let rod = s.rod.as_ref().unwrap();
    let end = rod.contact_end_tcl.unwrap();
    let stop = rod.velocity_zero_time_tcl.unwrap();
    let frac = s.energy.transferred_fraction.unwrap();
    assert_eq!(s.contact.intervals.len(), 1);
    assert!((end - 0.41340).abs() < 2e-3, "contact end {end}");
    assert!((stop - 0.22352).abs() < 2e-3, "impactor at rest {stop}");
    assert!((frac - 0.7911).abs() < 5e-3, "transferred {frac}");
    // The paper's readings: 0.4 and 80 % hold; 0.25 does not (it is 0.2235).
    assert!((end - 0.4).abs() < 0.02);
    assert!((frac - 0.80).abs() < 0.015);
    assert!(
        (stop - 0.25).abs() > 0.02,
        "the paper's 0.25 is a figure reading; the exact value is 0.2235"
    );
}

/// Goal: after contact the pulse travels as a d'Alembert wave, for which kinetic and
/// strain energy are equal. Model: rod.bdf, newmark. Reference: KE_t = SE_t (½vᵀMv
/// form) for 0.45 < tC/L < 0.95, before the front reaches the free end. Tolerance
/// 1e-6 relative: measured 3.4e-8; the residual is the mesh dispersion of the tail.
#[test]
fn rod_kinetic_equals_strain_energy_of_the_travelling_pulse() {
    let m = rod_model();
    let r = run(&m, Scheme::Newmark, None, None);
    let tau = 180e-6;
    let mut worst: f64 = 0.0;
    for e in r.energy.iter().filter(|e| e.time / tau > 0.45 && e.time / tau < 0.95) {
        worst = worst.max((e.ke_target - e.se_target).abs() / (e.ke_target + e.se_target));
    }
    assert!(worst < 1e-6, "KE_t vs SE_t: {worst}");
}

/// Goal: mid-rod strain is the contact force carried by a non-dispersive wave.
/// Model: rod.bdf with output every step, elements 72 and 73 (centres at
/// x = 17.875 and 18.125 in). Reference: ε(x, t) = −F(t − x/C)/(EA) until the
/// reflection from the far end returns (tC/L < 1.5). Tolerance 2.5 % of the peak
/// strain: measured 1.7 %, the dispersion of lumped-mass linear rods with 0.25 in
/// elements on a 74 µs pulse (≈ 60 elements per pulse length).
#[test]
fn rod_midpoint_strain_is_the_shifted_contact_force() {
    let mut m = rod_model();
    m.time.every = 1;
    let r = run(&m, Scheme::Newmark, None, None);
    let (c, ea) = (2.0e5, 10.0e6 * 0.196);
    let peak = r.series.force.iter().cloned().fold(0.0, f64::max) / ea;
    for (eid, xc) in [(72, 17.875), (73, 18.125)] {
        let col = r.column(&Column::rod_strain(eid)).unwrap();
        let mut worst: f64 = 0.0;
        for h in r.history.iter().filter(|h| h[0] * c / 36.0 < 1.45) {
            let reference = -interp(&r.series.time, &r.series.force, h[0] - xc / c) / ea;
            worst = worst.max((h[col] - reference).abs());
        }
        assert!(
            worst < 0.025 * peak,
            "element {eid}: {:.3} % of peak",
            100.0 * worst / peak
        );
    }
}

/// Goal: Newmark's energy error is second order in Δt.
/// Model: rod.bdf over 500 µs at Δt = 4e-7, 2e-7, 1e-7, 5e-8. Reference: the
/// trapezoidal rule's energy error is O(Δt²). Assertion: each halving divides the
/// max energy error by 4 ± 0.3, and the least-squares slope of log error against
/// log Δt is 2 ± 0.05 (measured 3.95, 3.97, 3.98; slope 1.99).
#[test]
fn rod_newmark_energy_error_is_second_order() {
    let m = rod_model();
    let dts = [4e-7, 2e-7, 1e-7, 5e-8];
    let errs: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let r = run(&m, Scheme::Newmark, Some(dt), Some((5e-4 / dt).round() as usize));
            r.summary.energy.max_relative_error.unwrap()
        })
        .collect();
    for w in errs.windows(2) {
        let ratio = w[0] / w[1];
        assert!((ratio - 4.0).abs() < 0.3, "halving ratio {ratio} ({errs:?})");
    }
    let (x, y): (Vec<f64>, Vec<f64>) = dts.iter().zip(&errs).map(|(d, e)| (d.ln(), e.ln())).unzip();
    let slope = impactlab::numerics::slope(&x, &y);
    assert!((slope - 2.0).abs() < 0.05, "order {slope}");
    assert!(errs[1] < 2e-5, "at the paper's Δt: {}", errs[1]);
}

/// Goal: the free-free rod conserves momentum. Model: rod.bdf, newmark and energy.
/// Reference: total momentum m v0 = 5.9535e-3 lbf·s (contact forces are equal and
/// opposite; K has the rigid mode in its null space). Tolerance 1e-10 relative:
/// round-off of 2500 solves (measured 1.5e-12).
#[test]
fn rod_momentum_is_conserved_to_round_off() {
    let m = rod_model();
    for scheme in [Scheme::Newmark, Scheme::Energy] {
        let r = run(&m, scheme, None, None);
        let p0 = r.summary.momentum.initial.unwrap();
        assert!((p0 - 9.587e-5 * 62.1).abs() < 1e-15);
        let dp = r.summary.momentum.max_abs_change.unwrap();
        assert!(dp < 1e-10 * p0, "{scheme:?}: momentum change {dp}");
    }
}

/// Goal: the NASTRAN three-point scheme and Newmark agree, so either can audit the
/// other. Model: rod.bdf at the paper's Δt. Reference: Newmark's contact duration.
/// Tolerance 1e-4 relative (the bound; measured 1.3e-6).
#[test]
fn rod_nastran_and_newmark_agree_on_contact_duration() {
    let m = rod_model();
    let d = |s: Scheme| run(&m, s, None, None).summary.contact.duration.unwrap();
    let (a, b) = (d(Scheme::Newmark), d(Scheme::Nastran));
    assert!((a - b).abs() / a < 1e-4, "newmark {a} nastran {b}");
}

/// Goal: the energy-conserving scheme conserves energy to round-off at any step.
/// Model: rod.bdf at Δt = 2e-7 and 1.6e-6 (8×). Reference: U_t = U_0 exactly (the
/// discrete gradient makes the contact's work equal its potential change). Tolerance
/// 1e-10 (measured 9.5e-13 and 1.9e-13).
#[test]
fn rod_energy_scheme_conserves_energy_to_round_off() {
    let m = rod_model();
    for dt in [2e-7, 1.6e-6] {
        let r = run(&m, Scheme::Energy, Some(dt), Some((5e-4 / dt).round() as usize));
        let e = r.summary.energy.max_relative_error.unwrap();
        assert!(e < 1e-10, "dt {dt}: {e}");
    }
}

/// Goal: the contact law is respected at every step: F ≥ 0, F = 0 exactly when
/// α ≤ 0, SE_i > 0 only in contact. Model: rod.bdf, all three schemes. Exact.
#[test]
fn rod_contact_force_is_nonnegative_and_zero_out_of_contact() {
    let m = rod_model();
    for scheme in [Scheme::Newmark, Scheme::Energy, Scheme::Nastran] {
        let r = run(&m, scheme, None, None);
        for (k, (&a, &fc)) in r.series.alpha.iter().zip(&r.series.force).enumerate() {
            assert!(fc >= 0.0);
            assert_eq!(fc == 0.0, a <= 0.0, "{scheme:?} step {k}: α {a} F {fc}");
            assert_eq!(r.energy[k].se_impactor > 0.0, a > 0.0);
        }
    }
}

/// Goal: the contact equation converges quadratically: a contact step takes 2-4
/// Newton iterations (it took about 22 when a converged estimate was rejected by the
/// bracket test). Model: rod.bdf, newmark and energy schemes. Reference: at most 4
/// iterations per step in contact, on average (measured 3.0 for both).
#[test]
fn contact_solve_takes_few_newton_iterations() {
    for scheme in [Scheme::Newmark, Scheme::Energy] {
        let r = run(&rod_model(), scheme, None, None);
        let in_contact = r.series.alpha.iter().filter(|&&a| a > 0.0).count() + 1;
        let per_step = r.stats.contact_iterations as f64 / in_contact as f64;
        assert!(per_step <= 4.0, "{scheme}: {per_step} iterations per contact step");
        assert!(per_step >= 1.0, "{scheme}: {per_step}");
    }
}
