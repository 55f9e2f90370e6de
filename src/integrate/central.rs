//! Explicit central differences in velocity-Verlet form (leapfrog; Newmark β = 0,
//! γ = 1/2), with a diagonal (lumped) mass matrix:
//!
//!   a(n)   = M⁻¹ (g φ(α(n)) − K u(n))
//!   u(n+1) = u(n) + Δt v(n) + Δt²/2 a(n)
//!   v(n+1) = v(n) + Δt/2 (a(n) + a(n+1))
//!
//! Order 2, symplectic (energy error bounded and oscillating, no drift, while stable),
//! no linear solve. Stable for Δt ≤ Δt_crit = 2/ω_max; ω_max² is bounded above by the
//! Gershgorin bound of M^(-1/2) K M^(-1/2), max_i Σ_j |K_ij| / √(m_i m_j), which is
//! tight for lumped-mass rods (2C/L_e) — so the Δt_crit used here is safe. A step above
//! it is refused before the run starts, naming the critical step. Every solved DOF
//! needs mass: a plate without rotary inertia is an error (use an implicit scheme).

use super::{check_finite, contact_vectors, Observer, RunStats, SolveError, StepState};
use crate::assembly::System;
use crate::model::{apply, Model};

/// The critical step 2/ω_max from the Gershgorin bound, or the DOF without mass.
pub fn critical_step(model: &Model, sys: &System) -> Result<f64, SolveError> {
    let m = sys.m_lumped.as_ref().ok_or_else(|| SolveError::Explicit {
        reason: "the mass matrix is not diagonal (rotary inertia coupling)".into(),
    })?;
    if let Some(i) = m.iter().position(|&x| x <= 0.0) {
        return Err(SolveError::Explicit {
            reason: format!(
                "{} has no mass (no rotary inertia); use an implicit scheme",
                model.dofs[i]
            ),
        });
    }
    let k = sys.k_csc.as_ref();
    let (cp, ri, val) = (k.symbolic().col_ptr(), k.symbolic().row_idx(), k.val());
    let mut row = vec![0.0f64; sys.n];
    for j in 0..sys.n {
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            row[i] += val[p].abs() / (m[i] * m[j]).sqrt();
        }
    }
    let lmax = row.iter().cloned().fold(0.0, f64::max);
    Ok(if lmax > 0.0 { 2.0 / lmax.sqrt() } else { f64::INFINITY })
}

pub fn run(model: &Model, sys: &System, dt: f64, steps: usize, obs: &mut dyn Observer) -> Result<RunStats, SolveError> {
    let crit = critical_step(model, sys)?;
    if dt > crit {
        return Err(SolveError::Explicit {
            reason: format!(
                "dt = {dt:.4e} exceeds the critical step 2/omega_max = {crit:.4e} of central differences; \
                 use dt <= {crit:.4e} or an implicit scheme"
            ),
        });
    }
    let n = model.n();
    let m = sys.m_lumped.as_ref().expect("checked by critical_step");
    let (g, c) = contact_vectors(model);
    let ct = model.contact.as_ref();
    let phi = |x: f64| ct.map(|c| c.law(x)).unwrap_or(0.0);
    let mut stats = RunStats::default();
    let mut u = model.u0.clone();
    let mut v = model.v0.clone();
    let mut a = vec![0.0; n];
    let mut ku = vec![0.0; n];
    let accel = |u: &[f64], phi_n: f64, ku: &mut Vec<f64>, a: &mut Vec<f64>| {
        sys.k_mul(u, ku);
        for i in 0..n {
            a[i] = (g[i] * phi_n - ku[i]) / m[i];
        }
    };
    let mut alpha = apply(&c, &u);
    let mut phi_n = phi(alpha);
    accel(&u, phi_n, &mut ku, &mut a);
    check_finite(model, 0, 0.0, &u)?;
    check_finite(model, 0, 0.0, &v)?;
    let mut go = obs.observe(&StepState {
        step: 0,
        time: 0.0,
        u: &u,
        v: &v,
        alpha,
        load_factor: phi_n,
        work_factor: phi_n,
    })?;
    let mut step = 0;
    while go && step < steps {
        step += 1;
        let time = step as f64 * dt;
        for i in 0..n {
            v[i] += 0.5 * dt * a[i];
            u[i] += dt * v[i];
        }
        let phi_prev = phi_n;
        alpha = apply(&c, &u);
        phi_n = phi(alpha);
        accel(&u, phi_n, &mut ku, &mut a);
        for i in 0..n {
            v[i] += 0.5 * dt * a[i];
        }
        check_finite(model, step, time, &u)?;
        check_finite(model, step, time, &v)?;
        go = obs.observe(&StepState {
            step,
            time,
            u: &u,
            v: &v,
            alpha,
            load_factor: phi_n,
            work_factor: 0.5 * (phi_prev + phi_n),
        })?;
    }
    stats.steps = step;
    Ok(stats)
}
