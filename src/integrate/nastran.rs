//! COSMIC NASTRAN's direct transient scheme (three-point Newmark, β = 1/3), as
//! documented in the NASTRAN Theoretical Manual, with no damping (B = 0):
//!
//!   [M/Δt² + K/3] u(n+1) = (P(n+1) + P(n) + P(n−1))/3 + N(n)
//!                          + [2M/Δt² − K/3] u(n) + [−M/Δt² − K/3] u(n−1)
//!
//! The nonlinear load N(n) = g φ(α(n)) is explicit: evaluated from u(n) and acting
//! over the step from n to n+1, so the contact force first appears at t = Δt.
//! Start-up u(−1) = u(0) − Δt v(0); velocity v(n) = (u(n+1) − u(n−1))/(2Δt), so
//! state n is reported once u(n+1) is known. Order 2; the linear part is
//! unconditionally stable (β = 1/3 ≥ 1/4); the lagged contact load is only
//! conditionally stable, which matters for very stiff contacts.

use super::linear::Factor;
use super::{check_finite, contact_vectors, Observer, RunStats, SolveError, StepState};
use crate::assembly::System;
use crate::model::{apply, Model};

pub fn run(model: &Model, sys: &System, dt: f64, steps: usize, obs: &mut dyn Observer) -> Result<RunStats, SolveError> {
    let n = model.n();
    let mut stats = RunStats::default();
    let a = sys.combine(1.0 / (dt * dt), 1.0 / 3.0);
    let mut factor = Factor::new(&a, &model.dofs)?;
    stats.factorizations = 1;
    let (g, c) = contact_vectors(model);
    let ct = model.contact.as_ref();
    let phi = |x: f64| ct.map(|c| c.law(x)).unwrap_or(0.0);

    let mut u_prev: Vec<f64> = (0..n).map(|i| model.u0[i] - dt * model.v0[i]).collect();
    let mut u = model.u0.clone();
    let mut u_next = vec![0.0; n];
    let mut v = vec![0.0; n];
    let mut t1 = vec![0.0; n];
    let mut t2 = vec![0.0; n];
    let mut t3 = vec![0.0; n];
    let mut phi_prev = phi(apply(&c, &u));
    check_finite(model, 0, 0.0, &u)?;
    check_finite(model, 0, 0.0, &model.v0)?;
    for step in 0..=steps {
        let time = step as f64 * dt;
        let alpha = apply(&c, &u);
        let phi_n = phi(alpha);
        // rhs = N(n) + M(2u(n) − u(n−1))/Δt² − K(u(n) + u(n−1))/3
        for i in 0..n {
            t1[i] = (2.0 * u[i] - u_prev[i]) / (dt * dt);
            t2[i] = (u[i] + u_prev[i]) / 3.0;
        }
        sys.m_mul(&t1, &mut t3);
        sys.k_mul(&t2, &mut t1);
        for i in 0..n {
            u_next[i] = t3[i] - t1[i] + g[i] * phi_n;
        }
        factor.solve_in_place(&mut u_next);
        check_finite(model, step + 1, time + dt, &u_next)?;
        for i in 0..n {
            v[i] = if step == 0 {
                model.v0[i]
            } else {
                (u_next[i] - u_prev[i]) / (2.0 * dt)
            };
        }
        let go = obs.observe(&StepState {
            step,
            time,
            u: &u,
            v: &v,
            alpha,
            load_factor: phi_n,
            work_factor: 0.5 * (phi_prev + phi_n),
        })?;
        stats.steps = step;
        if !go {
            break;
        }
        phi_prev = phi_n;
        std::mem::swap(&mut u_prev, &mut u);
        std::mem::swap(&mut u, &mut u_next);
    }
    stats.solves = factor.solves;
    stats.factor_time = factor.factor_time;
    stats.solve_time = factor.solve_time;
    Ok(stats)
}
