//! Average-acceleration Newmark (β = 1/4, γ = 1/2), written as the trapezoidal rule:
//!
//!   u(n+1) = u(n) + Δt/2 (v(n) + v(n+1))
//!   M (v(n+1) − v(n)) = Δt/2 (F(n) + F(n+1)),   F = −K u + g ψ
//!
//! so that, in increments Δu = u(n+1) − u(n),
//!
//!   (4M/Δt² + K) Δu = 4M v(n)/Δt − 2 f(n) + g (ψ(n) + ψ(n+1)),   f = K u,
//!
//! with f updated as f(n+1) = f(n) + K Δu. Solving for the increment keeps the
//! round-off proportional to |Δu| rather than to |u|, which matters for a free-free
//! target drifting away as a rigid body. A = 4M/Δt² + K is SPD and constant:
//! factorised once.
//!
//! Contact forms (the load factor over a step, g times it being the contact load):
//! - `Endpoint` (scheme `newmark`): the average of the end-of-step laws,
//!   (φ(α(n)) + φ(α(n+1)))/2, implicit in α(n+1). Order 2 in Δt for displacement,
//!   force and energy; unconditionally stable for the linear part; the energy error
//!   is O(Δt²) and not signed.
//! - `DiscreteGradient` (scheme `energy`): (W(α(n+1)) − W(α(n)))/(α(n+1) − α(n)),
//!   W' = φ. The work of a conservative contact over a step then equals minus the change
//!   of its potential exactly, so U_t is conserved to round-off at every Δt. Order 2.
//!
//! Both solve the condensed scalar equation of [`super::contact`] each step.

use super::contact::{discrete_gradient, solve};
use super::linear::Factor;
use super::{check_finite, contact_vectors, Observer, RunStats, SolveError, StepState};
use crate::assembly::System;
use crate::model::{apply, Model};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactForm {
    Endpoint,
    DiscreteGradient,
}

pub fn run(
    model: &Model,
    sys: &System,
    form: ContactForm,
    dt: f64,
    steps: usize,
    obs: &mut dyn Observer,
) -> Result<RunStats, SolveError> {
    let n = model.n();
    let mut stats = RunStats::default();
    let a = sys.combine(4.0 / (dt * dt), 1.0);
    let mut factor = Factor::new(&a, &model.dofs)?;
    stats.factorizations = 1;
    let (g, c) = contact_vectors(model);
    let has_contact = model.contact.is_some();
    let mut z = g.clone();
    let mut s = 0.0;
    if has_contact {
        factor.solve_in_place(&mut z);
        s = apply(&c, &z);
    }
    let ct = model.contact.as_ref();
    let phi = |x: f64| ct.map(|c| c.law(x)).unwrap_or(0.0);
    let dphi = |x: f64| ct.map(|c| c.law_slope(x)).unwrap_or(0.0);
    let w = |x: f64| ct.map(|c| c.law_integral(x)).unwrap_or(0.0);

    let mut u = model.u0.clone();
    let mut v = model.v0.clone();
    let mut du = vec![0.0; n];
    let mut f = vec![0.0; n];
    let mut kdu = vec![0.0; n];
    let mut mv = vec![0.0; n];
    sys.k_mul(&u, &mut f);
    let mut alpha = apply(&c, &u);
    let mut phi_n = phi(alpha);
    check_finite(model, 0, 0.0, &u)?;
    check_finite(model, 0, 0.0, &v)?;
    let go = obs.observe(&StepState {
        step: 0,
        time: 0.0,
        u: &u,
        v: &v,
        alpha,
        load_factor: phi_n,
        work_factor: phi_n,
    })?;
    if !go {
        return Ok(stats);
    }
    for step in 1..=steps {
        let time = step as f64 * dt;
        // rhs = 4M v/Δt − 2f (+ g φ(n) for the endpoint form)
        sys.m_mul(&v, &mut mv);
        for i in 0..n {
            du[i] = 4.0 / dt * mv[i] - 2.0 * f[i];
        }
        if form == ContactForm::Endpoint && phi_n != 0.0 {
            for i in 0..n {
                du[i] += g[i] * phi_n;
            }
        }
        factor.solve_in_place(&mut du);
        // Contact: α = α* + s ψ(α), α* the indentation of the contact-free predictor.
        let mut psi = 0.0;
        let mut alpha_new = alpha + apply(&c, &du);
        if has_contact {
            let a_prev = alpha;
            let (root, its) = match form {
                ContactForm::Endpoint => solve(alpha_new, s, |x| (phi(x), dphi(x))),
                ContactForm::DiscreteGradient => solve(alpha_new, s, |x| {
                    let dg = 2.0 * discrete_gradient(a_prev, x, w, phi);
                    // Derivative of the secant slope, for Newton only (the bracket
                    // keeps the iteration convergent with any nonnegative slope).
                    let d = x - a_prev;
                    let slope = if d.abs() > 1e-12 * x.abs().max(a_prev.abs()) {
                        2.0 * (phi(x) - dg / 2.0) / d
                    } else {
                        dphi(x)
                    };
                    (dg, slope.max(0.0))
                }),
            }
            .ok_or(SolveError::ContactSolve { step, time_s: time })?;
            stats.contact_iterations += its;
            psi = match form {
                ContactForm::Endpoint => phi(root),
                ContactForm::DiscreteGradient => 2.0 * discrete_gradient(a_prev, root, w, phi),
            };
            if psi != 0.0 {
                for i in 0..n {
                    du[i] += z[i] * psi;
                }
            }
        }
        sys.k_mul(&du, &mut kdu);
        for i in 0..n {
            u[i] += du[i];
            f[i] += kdu[i];
            v[i] = 2.0 * du[i] / dt - v[i];
        }
        check_finite(model, step, time, &u)?;
        check_finite(model, step, time, &v)?;
        alpha_new = apply(&c, &u);
        let phi_new = phi(alpha_new);
        let work_factor = match form {
            ContactForm::Endpoint => 0.5 * (phi_n + phi_new),
            ContactForm::DiscreteGradient => 0.5 * psi,
        };
        alpha = alpha_new;
        phi_n = phi_new;
        stats.steps = step;
        let go = obs.observe(&StepState {
            step,
            time,
            u: &u,
            v: &v,
            alpha,
            load_factor: phi_n,
            work_factor,
        })?;
        if !go {
            break;
        }
    }
    stats.solves = factor.solves;
    stats.factor_time = factor.factor_time;
    stats.solve_time = factor.solve_time;
    Ok(stats)
}
