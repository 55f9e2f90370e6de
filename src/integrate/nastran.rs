//! COSMIC NASTRAN's direct transient scheme (three-point Newmark, β = 1/3), as
//! documented in the NASTRAN Theoretical Manual, with no damping (B = 0):
//!
//!   [M/Δt² + βK] u(n+1) = βP(n+1) + (1 − 2β)P(n) + βP(n−1) + N(n)
//!                         + [2M/Δt² − (1 − 2β)K] u(n) + [−M/Δt² − βK] u(n−1)
//!
//! The nonlinear load N(n) = g φ(α(n)) is explicit: evaluated from u(n) and acting
//! over the step from n to n+1, so the contact force first appears at t = Δt.
//! Start-up u(−1) = u(0) − Δt v(0); velocity v(n) = (u(n+1) − u(n−1))/(2Δt), so
//! state n is reported once u(n+1) is known. Order 2; the linear part is
//! unconditionally stable (β = 1/3 ≥ 1/4); the lagged contact load is only
//! conditionally stable, which matters for very stiff contacts.

use super::linear::Factor;
use super::{check_finite, contact_vectors, Current, SolveError, StepCosts, Stepper};
use crate::assembly::System;
use crate::model::{apply, Contact, Functional, Model};

/// Parameters of the three-point scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThreePointParams {
    /// Newmark's β; unconditionally stable for the linear part when β ≥ 1/4.
    pub beta: f64,
}

impl ThreePointParams {
    /// COSMIC NASTRAN's choice (scheme `nastran`).
    pub const NASTRAN: ThreePointParams = ThreePointParams { beta: 1.0 / 3.0 };
}

/// The three-point scheme's state: u(n−1), u(n), u(n+1); state n is the current one.
pub struct ThreePoint<'a> {
    model: &'a Model,
    sys: &'a System,
    contact: Option<&'a Contact>,
    dt: f64,
    beta: f64,
    factor: Factor,
    g: Vec<f64>,
    c: Functional,
    u_prev: Vec<f64>,
    u: Vec<f64>,
    u_next: Vec<f64>,
    v: Vec<f64>,
    t1: Vec<f64>,
    t2: Vec<f64>,
    t3: Vec<f64>,
    alpha: f64,
    phi_n: f64,
    phi_prev: f64,
}

impl<'a> ThreePoint<'a> {
    /// Factorises M/Δt² + βK, starts from u(−1) = u(0) − Δt v(0) and solves for u(1).
    pub fn new(model: &'a Model, sys: &'a System, dt: f64, params: ThreePointParams) -> Result<Self, SolveError> {
        let n = model.n();
        // The first solve (for u(1)) comes before the driver sees state 0: a bad initial
        // state is reported at step 0 here, not as a NaN at step 1.
        check_finite(model, 0, 0.0, &model.u0)?;
        check_finite(model, 0, 0.0, &model.v0)?;
        let factor = Factor::effective(sys, 1.0 / (dt * dt), params.beta, &model.dofs)?;
        let (g, c) = contact_vectors(model);
        let contact = model.contact.as_ref();
        let u_prev: Vec<f64> = (0..n).map(|i| model.u0[i] - dt * model.v0[i]).collect();
        let phi_prev = contact.map_or(0.0, |ct| ct.law(apply(&c, &model.u0)));
        let mut s = ThreePoint {
            model,
            sys,
            contact,
            dt,
            beta: params.beta,
            factor,
            g,
            c,
            u_prev,
            u: model.u0.clone(),
            u_next: vec![0.0; n],
            v: model.v0.clone(),
            t1: vec![0.0; n],
            t2: vec![0.0; n],
            t3: vec![0.0; n],
            alpha: 0.0,
            phi_n: 0.0,
            phi_prev,
        };
        s.solve_next(0)?;
        s.v.copy_from_slice(&model.v0);
        Ok(s)
    }

    /// With u(n−1) and u(n) in place: α(n), φ(n) and u(n+1).
    fn solve_next(&mut self, step: usize) -> Result<(), SolveError> {
        let (n, dt, beta) = (self.u.len(), self.dt, self.beta);
        self.alpha = apply(&self.c, &self.u);
        self.phi_n = self.contact.map_or(0.0, |ct| ct.law(self.alpha));
        // rhs = N(n) + M(2u(n) − u(n−1))/Δt² − K((1 − 2β)u(n) + βu(n−1))
        for i in 0..n {
            self.t1[i] = (2.0 * self.u[i] - self.u_prev[i]) / (dt * dt);
            self.t2[i] = (1.0 - 2.0 * beta) * self.u[i] + beta * self.u_prev[i];
        }
        self.sys.m_mul(&self.t1, &mut self.t3);
        self.sys.k_mul(&self.t2, &mut self.t1);
        for i in 0..n {
            self.u_next[i] = self.t3[i] - self.t1[i] + self.g[i] * self.phi_n;
        }
        self.factor.solve_in_place(&mut self.u_next);
        check_finite(self.model, step + 1, (step + 1) as f64 * dt, &self.u_next)
    }
}

impl Stepper for ThreePoint<'_> {
    fn advance(&mut self, step: usize, _time: f64) -> Result<(), SolveError> {
        self.phi_prev = self.phi_n;
        std::mem::swap(&mut self.u_prev, &mut self.u);
        std::mem::swap(&mut self.u, &mut self.u_next);
        self.solve_next(step)?;
        for i in 0..self.u.len() {
            self.v[i] = (self.u_next[i] - self.u_prev[i]) / (2.0 * self.dt);
        }
        Ok(())
    }

    fn current(&self) -> Current<'_> {
        Current {
            u: &self.u,
            v: &self.v,
            internal_force: None,
            alpha: self.alpha,
            load_factor: self.phi_n,
            work_factor: 0.5 * (self.phi_prev + self.phi_n),
        }
    }

    fn costs(&self) -> StepCosts {
        StepCosts {
            factorizations: 1,
            solves: self.factor.solves,
            contact_iterations: 0,
            factor_time: self.factor.factor_time,
            solve_time: self.factor.solve_time,
        }
    }
}
