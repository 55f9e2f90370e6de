//! COSMIC NASTRAN's direct transient scheme (three-point Newmark, β = 1/3), as
//! documented in the NASTRAN Theoretical Manual, with viscous damping B:
//!
//!   [M/Δt² + B/(2Δt) + βK] u(n+1) = βP(n+1) + (1 − 2β)P(n) + βP(n−1) + N(n)
//!                         + [2M/Δt² − (1 − 2β)K] u(n) + [−M/Δt² + B/(2Δt) − βK] u(n−1)
//!
//! The nonlinear load N(n) = g φ(α(n)) is explicit: evaluated from u(n) and acting
//! over the step from n to n+1, so the contact force first appears at t = Δt.
//! Start-up as NASTRAN-95 does it: the initial state is held in equilibrium by the
//! loads K u(−1) + B v(0) at t = −Δt and K u(0) + B v(0) at t = 0, so that a
//! structure released from a displaced shape (TIC) starts with no acceleration. Found
//! by NASTRAN-95's own output: its demonstration problem D09-02-1A (a string released
//! from a triangular shape) equals NASTRAN-95's printed displacements to their 7
//! digits (2.9e-7 of the peak) with these start loads and differs by 7.6e-2 without
//! them. The paper's decks are untouched: their structures start at rest and the
//! impactor has no stiffness, so both loads are zero.
//! P is the deck's dynamic load (DLOAD) at the step times, P(−1) taken as P(0) (the
//! load held before the start; NASTRAN-95's outputs cannot tell this apart, t09071a
//! starting from P(0) = 0). The work of P and of the start loads is booked as the
//! scheme's own energy identity books it: multiplied by d(n) = (u(n+1) − u(n−1))/2, step n's equation is
//! exactly E(n+½) − E(n−½) = P̄(n)·d(n), with P̄(n) = βP(n+1) + (1 − 2β)P(n) + βP(n−1)
//! and E(n+½) the energy of the half step (kinetic from (u(n+1) − u(n))/Δt). The
//! ledger's energies at state n are the mean of those at n ± ½ to O(Δt²), so the work
//! booked at state n is W(n) = Σ_(k<n) P̄(k)·d(k) + ½P̄(n)·d(n) − ½P̄(0)·d(0) (zero at
//! the start). Booking (u(n) − u(n−1))·(P(n−1) + P(n))/2 instead left 96 % of the
//! tiny energy of the first step unbalanced in a bar loaded from rest (NASTRAN-95's
//! t09071a).
//! The damping's term, multiplied by d(n), is Δt v(n)ᵀB v(n) = D(n): the energy it
//! dissipated is booked as the work is, Σ_(k<n) D(k) + ½D(n) − ½D(0) at state n, so
//! that the balance closes as tightly as without damping.
//! u(−1) = u(0) − Δt v(0); velocity v(n) = (u(n+1) − u(n−1))/(2Δt), so
//! state n is reported once u(n+1) is known. Order 2; the linear part is
//! unconditionally stable (β = 1/3 ≥ 1/4); the lagged contact load is only
//! conditionally stable, which matters for very stiff contacts.

use super::law::History;
use super::linear::Factor;
use super::{check_finite, contact_vectors, AppliedLoad, Current, SolveError, StepCosts, Stepper};
use crate::assembly::{Combination, System};
use crate::model::{apply, Functional, Model};

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
    /// The contact's law and its history.
    history: Option<History<'a>>,
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
    /// The dynamic load and its work.
    applied: Option<ThreePointLoad<'a>>,
    /// The damping's dissipation, when damped.
    damping: Option<ThreePointDamping>,
}

/// The damping's terms of the three-point scheme: a workspace, and the sums of the
/// dissipation booked at state n (see the module doc).
struct ThreePointDamping {
    work: [Vec<f64>; 2],
    /// Σ_(k<n) D(k).
    full: f64,
    /// D(n).
    last: f64,
    /// D(0).
    first: f64,
}

/// The loads of the three-point scheme: the dynamic load's P(n), P(n+1) (in
/// `dynamic`) and P(n−1), the start loads, the step's P̄(n), and the sums of the work
/// booked at state n (see the module doc).
struct ThreePointLoad<'a> {
    dynamic: Option<AppliedLoad<'a>>,
    before: Vec<f64>,
    /// K u(−1) and K u(0), while they act (steps 0 and 1).
    start: Option<[Vec<f64>; 2]>,
    pbar: Vec<f64>,
    /// Σ_(k<n) P̄(k)·d(k).
    full: f64,
    /// P̄(n)·d(n).
    last: f64,
    /// P̄(0)·d(0).
    first: f64,
}

impl<'a> ThreePoint<'a> {
    /// Factorises M/Δt² + βK, starts from u(−1) = u(0) − Δt v(0) and solves for u(1).
    pub fn new(model: &'a Model, sys: &'a System, dt: f64, params: ThreePointParams) -> Result<Self, SolveError> {
        let n = model.n();
        // The first solve (for u(1)) comes before the driver sees state 0: a bad initial
        // state is reported at step 0 here, not as a NaN at step 1.
        check_finite(model, 0, 0.0, &model.u0)?;
        check_finite(model, 0, 0.0, &model.v0)?;
        let factor = Factor::effective(
            sys,
            Combination {
                mass: 1.0 / (dt * dt),
                damping: 0.5 / dt,
                stiffness: params.beta,
            },
            &model.dofs,
        )?;
        let (g, c) = contact_vectors(model);
        let u_prev: Vec<f64> = (0..n).map(|i| model.u0[i] - dt * model.v0[i]).collect();
        let history = model.contact.as_ref().map(|ct| History::new(ct, apply(&c, &model.u0)));
        let phi_prev = history.as_ref().map_or(0.0, History::load_factor);
        let mut s = ThreePoint {
            model,
            sys,
            history,
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
            applied: None,
            damping: sys.damped().then(|| ThreePointDamping {
                work: [vec![0.0; n], vec![0.0; n]],
                full: 0.0,
                last: 0.0,
                first: 0.0,
            }),
        };
        // K u + B v(0), B v(0) only when damped.
        let bv = sys.damped().then(|| {
            let mut bv = vec![0.0; n];
            sys.c_mul(&model.v0, &mut bv);
            bv
        });
        let start = [&s.u_prev, &model.u0].map(|u| {
            let mut ku = vec![0.0; n];
            sys.k_mul(u, &mut ku);
            for (k, b) in ku.iter_mut().zip(bv.iter().flatten()) {
                *k += b;
            }
            ku
        });
        let dynamic = AppliedLoad::new(model);
        let start = start.iter().flatten().any(|&x| x != 0.0).then_some(start);
        if dynamic.is_some() || start.is_some() {
            s.applied = Some(ThreePointLoad {
                before: dynamic.as_ref().map_or_else(|| vec![0.0; n], |p| p.now.clone()),
                dynamic,
                start,
                pbar: vec![0.0; n],
                full: 0.0,
                last: 0.0,
                first: 0.0,
            });
        }
        s.solve_next(0)?;
        s.v.copy_from_slice(&model.v0);
        Ok(s)
    }

    /// With u(n−1) and u(n) in place: α(n), φ(n) and u(n+1).
    fn solve_next(&mut self, step: usize) -> Result<(), SolveError> {
        let (n, dt, beta) = (self.u.len(), self.dt, self.beta);
        self.alpha = apply(&self.c, &self.u);
        self.phi_n = self.history.as_mut().map_or(0.0, |h| h.commit(self.alpha));
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
        if let Some(d) = &mut self.damping {
            // + B u(n−1)/(2Δt)
            self.sys.c_mul(&self.u_prev, &mut d.work[0]);
            for i in 0..n {
                self.u_next[i] += d.work[0][i] / (2.0 * dt);
            }
        }
        if let Some(a) = &mut self.applied {
            // P̄(n) = βP(n+1) + (1 − 2β)P(n) + βP(n−1), with the start loads at n = 0, 1.
            a.pbar.fill(0.0);
            if let Some(p) = &mut a.dynamic {
                p.load_end((step + 1) as f64 * dt);
                for i in 0..n {
                    a.pbar[i] = beta * p.next[i] + (1.0 - 2.0 * beta) * p.now[i] + beta * a.before[i];
                }
            }
            match (&a.start, step) {
                (Some([before, at_start]), 0) => {
                    for i in 0..n {
                        a.pbar[i] += beta * before[i] + (1.0 - 2.0 * beta) * at_start[i];
                    }
                }
                (Some([_, at_start]), 1) => {
                    for (p, s) in a.pbar.iter_mut().zip(at_start) {
                        *p += beta * s;
                    }
                }
                _ => a.start = None,
            }
            for i in 0..n {
                self.u_next[i] += a.pbar[i];
            }
        }
        self.factor.solve_in_place(&mut self.u_next);
        if let Some(a) = &mut self.applied {
            a.full += a.last;
            a.last = (0..n)
                .map(|i| a.pbar[i] * (self.u_next[i] - self.u_prev[i]))
                .sum::<f64>()
                / 2.0;
            if step == 0 {
                a.first = a.last;
            }
        }
        if let Some(d) = &mut self.damping {
            // D(n) = Δt v(n)ᵀB v(n), v(n) = (u(n+1) − u(n−1))/(2Δt).
            let [v, work] = &mut d.work;
            for ((v, next), prev) in v.iter_mut().zip(&self.u_next).zip(&self.u_prev) {
                *v = (next - prev) / (2.0 * dt);
            }
            d.full += d.last;
            d.last = dt * self.sys.c_norm(v, work);
            if step == 0 {
                d.first = d.last;
            }
        }
        check_finite(self.model, step + 1, (step + 1) as f64 * dt, &self.u_next)
    }
}

impl Stepper for ThreePoint<'_> {
    fn advance(&mut self, step: usize, _time: f64) -> Result<(), SolveError> {
        self.phi_prev = self.phi_n;
        std::mem::swap(&mut self.u_prev, &mut self.u);
        std::mem::swap(&mut self.u, &mut self.u_next);
        if let Some(ThreePointLoad {
            dynamic: Some(p),
            before,
            ..
        }) = &mut self.applied
        {
            // P(n−1) ← P(n) ← P(n+1).
            before.copy_from_slice(&p.now);
            std::mem::swap(&mut p.now, &mut p.next);
        }
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
            applied_work: self
                .applied
                .as_ref()
                .map_or(0.0, |a| a.full + 0.5 * a.last - 0.5 * a.first),
            dissipated: self
                .damping
                .as_ref()
                .map_or(0.0, |d| d.full + 0.5 * d.last - 0.5 * d.first),
            contact: self.history.as_ref().map(History::energy).unwrap_or_default(),
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
