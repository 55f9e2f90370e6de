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
//! factorised once. The ledger reads SE_t = ½ u·f from the f kept here.
//!
//! The momentum equation would give f without the product with K,
//! f(n+1) = −f(n) + g p_n + (2/Δt) M (v(n) − v(n+1)), but K Δu is then the difference
//! of two inertial-scale terms: measured on the paper's rod, the free rod's momentum
//! drifted by 2.5e-9 of m·v0 (1e-16 with the product), the `energy` scheme's energy
//! error rose from 9.5e-13 to 1.3e-11, and outputs moved by 8e-10 of their peaks. The
//! product stays.
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
//! Both solve the condensed scalar equation of the contact module each step.
//!
//! A dynamic load P(t) (DLOAD) enters the trapezoidal rule as the contact does, at
//! both ends: F = −K u + g ψ + P, so the increment's right-hand side gains
//! P(n) + P(n+1), and its work over the step is Δu·(P(n) + P(n+1))/2 exactly.
//!
//! Viscous damping C (damping elements, proportional damping) enters F as −C v at
//! both ends. With v(n) + v(n+1) = 2Δu/Δt it adds 2C/Δt to the effective matrix and
//! nothing to the right-hand side: A = 4M/Δt² + 2C/Δt + K, still SPD and constant.
//! Its work over the step is −Δu·C(v(n) + v(n+1))/2 = −ΔuᵀCΔu/Δt exactly, which the
//! ledger books as the energy dissipated (one product with C a step): the balance
//! closes as tightly as without damping, and the dissipation never decreases. The
//! scheme stays second order (the trapezoidal rule of a linear first-order system)
//! and unconditionally stable (the damping only removes energy).

use super::contact::solve;
use super::law::{History, StepLaw};
use super::linear::Factor;
use super::{contact_vectors, AppliedLoad, Current, SolveError, StepCosts, Stepper};
use crate::assembly::{Combination, System};
use crate::model::{apply, Functional, Model};

/// How the contact load acts over a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactForm {
    /// The mean of the end-of-step laws, (φ(α(n)) + φ(α(n+1)))/2.
    Endpoint,
    /// The discrete gradient of the contact potential between α(n) and α(n+1).
    DiscreteGradient,
}

/// Parameters of the Newmark scheme. β = 1/4, γ = 1/2 (average acceleration, the
/// trapezoidal rule) is the only pair: the increment form below needs no
/// acceleration, which a singular lumped M (the plate's massless rotations) does not
/// define.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NewmarkParams {
    /// How the contact load enters the step.
    pub contact: ContactForm,
}

impl NewmarkParams {
    /// Scheme `newmark`: end-point contact force.
    pub const TRAPEZOIDAL: NewmarkParams = NewmarkParams {
        contact: ContactForm::Endpoint,
    };
    /// Scheme `energy`: discrete-gradient contact force, energy conserved to round-off.
    pub const ENERGY_CONSERVING: NewmarkParams = NewmarkParams {
        contact: ContactForm::DiscreteGradient,
    };
}

/// The trapezoidal rule's state and workspace.
pub struct Newmark<'a> {
    sys: &'a System,
    /// The contact's law and its history.
    history: Option<History<'a>>,
    form: ContactForm,
    dt: f64,
    factor: Factor,
    g: Vec<f64>,
    c: Functional,
    /// z = A⁻¹ g and s = c·z (the contact's condensed compliance).
    z: Vec<f64>,
    s: f64,
    u: Vec<f64>,
    v: Vec<f64>,
    du: Vec<f64>,
    /// f = K u, kept by increments (the ledger reads SE_t = ½ u·f from it).
    f: Vec<f64>,
    kdu: Vec<f64>,
    mv: Vec<f64>,
    alpha: f64,
    phi_n: f64,
    work_factor: f64,
    applied: Option<AppliedLoad<'a>>,
    /// The energy dissipated by damping so far.
    dissipated: f64,
    contact_iterations: usize,
}

impl<'a> Newmark<'a> {
    /// Factorises A = 4M/Δt² + K and sets up the initial state.
    pub fn new(model: &'a Model, sys: &'a System, dt: f64, params: NewmarkParams) -> Result<Self, SolveError> {
        let n = model.n();
        let mut factor = Factor::effective(sys, effective_matrix(dt), &model.dofs)?;
        let (g, c) = contact_vectors(model);
        let mut z = g.clone();
        let mut s = 0.0;
        if model.contact.is_some() {
            factor.solve_in_place(&mut z);
            s = apply(&c, &z);
        }
        let u = model.u0.clone();
        let mut f = vec![0.0; n];
        sys.k_mul(&u, &mut f);
        let alpha = apply(&c, &u);
        let history = model.contact.as_ref().map(|ct| History::new(ct, alpha));
        let phi_n = history.as_ref().map_or(0.0, History::load_factor);
        Ok(Newmark {
            sys,
            history,
            form: params.contact,
            dt,
            factor,
            g,
            c,
            z,
            s,
            v: model.v0.clone(),
            u,
            du: vec![0.0; n],
            f,
            kdu: vec![0.0; n],
            mv: vec![0.0; n],
            alpha,
            phi_n,
            work_factor: phi_n,
            applied: AppliedLoad::new(model),
            dissipated: 0.0,
            contact_iterations: 0,
        })
    }

    /// The load factor ψ of the step under the step's contact law, from the
    /// indentation α* of the contact-free predictor.
    fn contact_step(&mut self, law: &StepLaw, alpha_star: f64, step: usize, time: f64) -> Result<f64, SolveError> {
        let (psi, its) = contact_load(self.form, law, alpha_star, self.s, self.alpha)
            .ok_or(SolveError::ContactSolve { step, time })?;
        self.contact_iterations += its;
        Ok(psi)
    }
}

/// The trapezoidal rule's effective matrix A = 4M/Δt² + 2C/Δt + K.
pub(crate) fn effective_matrix(dt: f64) -> Combination {
    Combination {
        mass: 4.0 / (dt * dt),
        damping: 2.0 / dt,
        stiffness: 1.0,
    }
}

/// The trapezoidal rule's contact-free predictor: du = A⁻¹(4M v/Δt − 2f), plus g·φ
/// when `load` = (g, φ) is given and P(n) + P(n+1) when `applied` is.
/// `vectors` = (v, f, workspace for M v, du).
pub(crate) fn predictor(
    sys: &System,
    factor: &mut Factor,
    dt: f64,
    vectors: (&[f64], &[f64], &mut [f64], &mut [f64]),
    load: Option<(&[f64], f64)>,
    applied: Option<&AppliedLoad>,
) {
    let (v, f, mv, du) = vectors;
    sys.m_mul(v, mv);
    match load {
        None => {
            for i in 0..du.len() {
                du[i] = 4.0 / dt * mv[i] - 2.0 * f[i];
            }
        }
        Some((g, phi)) => {
            for i in 0..du.len() {
                du[i] = 4.0 / dt * mv[i] - 2.0 * f[i] + g[i] * phi;
            }
        }
    }
    if let Some(p) = applied {
        for ((d, now), next) in du.iter_mut().zip(&p.now).zip(&p.next) {
            *d += now + next;
        }
    }
    factor.solve_in_place(du);
}

/// Completes a trapezoidal step from its increment du: u += du, f += K du (`kdu` its
/// workspace), v = 2 du/Δt − v. `state` = (u, f, v).
pub(crate) fn complete(
    sys: &System,
    dt: f64,
    du: &[f64],
    kdu: &mut [f64],
    state: (&mut [f64], &mut [f64], &mut [f64]),
) {
    let (u, f, v) = state;
    sys.k_mul(du, kdu);
    for i in 0..du.len() {
        u[i] += du[i];
        f[i] += kdu[i];
        v[i] = 2.0 * du[i] / dt - v[i];
    }
}

/// The contact's load factor ψ over a step of the trapezoidal rule, solving
/// α = α* + s·ψ(α) (α* the indentation of the contact-free predictor, s the condensed
/// compliance, `a_prev` the indentation at the start of the step, `law` the step's
/// contact law); with the iterations it took, or `None` if the scalar solve failed.
/// Shared by the direct stepper and the convolution engine, which differ only in how
/// they get α* and s.
pub(crate) fn contact_load(
    form: ContactForm,
    law: &StepLaw,
    alpha_star: f64,
    s: f64,
    a_prev: f64,
) -> Option<(f64, usize)> {
    let (root, its) = match form {
        ContactForm::Endpoint => solve(alpha_star, s, |x| (law.phi(x), law.slope(x))),
        ContactForm::DiscreteGradient => solve(alpha_star, s, |x| {
            let dg = 2.0 * law.mean(a_prev, x);
            // Derivative of the secant slope, for Newton only (the bracket
            // keeps the iteration convergent with any nonnegative slope).
            let d = x - a_prev;
            let slope = if d.abs() > 1e-12 * x.abs().max(a_prev.abs()) {
                2.0 * (law.phi(x) - dg / 2.0) / d
            } else {
                law.slope(x)
            };
            (dg, slope.max(0.0))
        }),
    }?;
    Some((
        match form {
            ContactForm::Endpoint => law.phi(root),
            ContactForm::DiscreteGradient => 2.0 * law.mean(a_prev, root),
        },
        its,
    ))
}

impl Stepper for Newmark<'_> {
    fn advance(&mut self, step: usize, time: f64) -> Result<(), SolveError> {
        let n = self.u.len();
        let load = (self.form == ContactForm::Endpoint && self.phi_n != 0.0).then_some((&self.g[..], self.phi_n));
        if let Some(p) = &mut self.applied {
            p.load_end(time);
        }
        let step_vectors = (&self.v[..], &self.f[..], &mut self.mv[..], &mut self.du[..]);
        predictor(
            self.sys,
            &mut self.factor,
            self.dt,
            step_vectors,
            load,
            self.applied.as_ref(),
        );
        // Contact: α = α* + s ψ(α), α* the indentation of the contact-free predictor.
        let mut psi = 0.0;
        if let Some(law) = self.history.as_ref().map(History::step_law) {
            let alpha_star = self.alpha + apply(&self.c, &self.du);
            psi = self.contact_step(&law, alpha_star, step, time)?;
            if psi != 0.0 {
                for i in 0..n {
                    self.du[i] += self.z[i] * psi;
                }
            }
        }
        complete(
            self.sys,
            self.dt,
            &self.du,
            &mut self.kdu,
            (&mut self.u, &mut self.f, &mut self.v),
        );
        if let Some(p) = &mut self.applied {
            p.book(|i| self.du[i]);
        }
        // ΔuᵀCΔu/Δt, C Δu in the workspace `mv` (free until the next predictor).
        self.dissipated += self.sys.c_norm(&self.du, &mut self.mv) / self.dt;
        let alpha = apply(&self.c, &self.u);
        let phi_new = self.history.as_mut().map_or(0.0, |h| h.commit(alpha));
        self.work_factor = match self.form {
            ContactForm::Endpoint => 0.5 * (self.phi_n + phi_new),
            ContactForm::DiscreteGradient => 0.5 * psi,
        };
        self.alpha = alpha;
        self.phi_n = phi_new;
        Ok(())
    }

    fn current(&self) -> Current<'_> {
        Current {
            u: &self.u,
            v: &self.v,
            internal_force: Some(&self.f),
            alpha: self.alpha,
            load_factor: self.phi_n,
            work_factor: self.work_factor,
            applied_work: self.applied.as_ref().map_or(0.0, |p| p.work),
            dissipated: self.dissipated,
            contact: self.history.as_ref().map(History::energy).unwrap_or_default(),
        }
    }

    fn costs(&self) -> StepCosts {
        StepCosts {
            factorizations: 1,
            solves: self.factor.solves,
            contact_iterations: self.contact_iterations,
            factor_time: self.factor.factor_time,
            solve_time: self.factor.solve_time,
        }
    }
}
