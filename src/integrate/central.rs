//! Explicit central differences in velocity-Verlet form (leapfrog; Newmark β = 0,
//! γ = 1/2), with a diagonal (lumped) mass matrix:
//!
//!   a(n)   = M⁻¹ (g φ(α(n)) + P(t(n)) − K u(n))
//!   u(n+1) = u(n) + Δt v(n) + Δt²/2 a(n)
//!   v(n+1) = v(n) + Δt/2 (a(n) + a(n+1))
//!
//! P is the deck's dynamic load (DLOAD), its work booked as Δu·(P(n) + P(n+1))/2.
//! Order 2, symplectic (energy error bounded and oscillating, no drift, while stable),
//! no linear solve. Stable for Δt ≤ Δt_crit = 2/ω_max; ω_max² is bounded above by the
//! Gershgorin bound of M^(-1/2) K M^(-1/2), max_i Σ_j |K_ij| / √(m_i m_j), so the
//! Δt_crit used here is safe. It is conservative by the mass steps: on a uniform
//! lumped-mass rod with half masses at its ends the row next to an end gives
//! (2 + 1 + √2)k/m, so Δt_crit = 2/√(3 + √2)·L_e/C = 0.952·L_e/C against the exact
//! L_e/C (checked in `verification/rod-central.toml`). A step above it is refused
//! before the run starts, naming the critical step. Every solved DOF
//! needs mass: a plate without rotary inertia is an error (use an implicit scheme).
//!
//! Viscous damping C makes a(n+1) depend on v(n+1), which the step cannot solve for
//! without a factorisation. It is taken at a predicted velocity instead, one
//! correction of the half-step one:
//!
//!   f = g φ(α(n+1)) + P(t(n+1)) − K u(n+1),  v* = v(n+½) + Δt/2 M⁻¹(f − C v(n+½)),
//!   a(n+1) = M⁻¹(f − C v*)
//!
//! v* differs from the v(n+1) of the implicit equation by O(Δt³) (the fixed-point
//! iteration's contraction Δt/2·M⁻¹C applied twice to an O(Δt) difference), so the
//! scheme stays second order, at two products with C a step. The damping's work is
//! booked as the dynamic load's is, Δu·(C v*(n) + C v*(n+1))/2. The critical step
//! becomes the root of ω²Δt²/4 + cΔt/2 = 1 (the damped oscillator's limit
//! Δt ≤ 2/ω·(√(1 + ζ²) − ζ), c = 2ζω) with ω the Gershgorin bound above and c the
//! Gershgorin bound of M⁻¹ᐟ² C M⁻¹ᐟ², so that damping shortens it.

use super::law::History;
use super::{contact_vectors, AppliedLoad, Current, SolveError, StepCosts, Stepper};
use crate::assembly::System;
use crate::model::{apply, Functional, Model};

/// The critical step 2/ω_max from the Gershgorin bound, or the DOF without mass.
pub fn critical_step(model: &Model, sys: &System) -> Result<f64, SolveError> {
    let m = sys.m_lumped.as_ref().ok_or_else(|| SolveError::Explicit {
        reason: "the mass matrix is not diagonal (rotary inertia coupling, or coupled mass)".into(),
    })?;
    if let Some(i) = m.iter().position(|&x| x <= 0.0) {
        return Err(SolveError::Explicit {
            reason: format!(
                "{} has no mass (no rotary inertia); use an implicit scheme",
                model.dofs[i]
            ),
        });
    }
    let lmax = gershgorin(sys.k_csc.as_ref(), m);
    if !sys.damped() {
        return Ok(if lmax > 0.0 { 2.0 / lmax.sqrt() } else { f64::INFINITY });
    }
    let c = faer::sparse::SparseColMat::try_new_from_triplets(sys.n, sys.n, &sys.c).expect("indices are in range");
    let cmax = gershgorin(c.as_ref(), m);
    // The positive root of (ω²/4)Δt² + (c/2)Δt − 1 = 0.
    Ok(match (lmax > 0.0, cmax > 0.0) {
        (true, _) => (-cmax / 2.0 + (cmax * cmax / 4.0 + lmax).sqrt()) * 2.0 / lmax,
        (false, true) => 2.0 / cmax,
        (false, false) => f64::INFINITY,
    })
}

/// The Gershgorin bound of M^(-1/2) A M^(-1/2), `m` the diagonal of M: the largest
/// row sum of |A_ij|/√(m_i m_j).
fn gershgorin(a: faer::sparse::SparseColMatRef<'_, usize, f64>, m: &[f64]) -> f64 {
    let (cp, ri, val) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
    let mut row = vec![0.0f64; m.len()];
    for j in 0..m.len() {
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            row[i] += val[p].abs() / (m[i] * m[j]).sqrt();
        }
    }
    row.iter().cloned().fold(0.0, f64::max)
}

/// Velocity Verlet's state: u, v and the acceleration at the current step.
pub struct Central<'a> {
    sys: &'a System,
    /// The contact's law and its history.
    history: Option<History<'a>>,
    dt: f64,
    m: &'a [f64],
    g: Vec<f64>,
    c: Functional,
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    ku: Vec<f64>,
    /// C v* at the current state and a workspace, when damped.
    cv: Option<[Vec<f64>; 2]>,
    /// The energy dissipated by damping so far.
    dissipated: f64,
    alpha: f64,
    phi_n: f64,
    phi_prev: f64,
    applied: Option<AppliedLoad<'a>>,
}

impl<'a> Central<'a> {
    /// Refuses a step above the critical one (naming it); sets up the initial state.
    pub fn new(model: &'a Model, sys: &'a System, dt: f64) -> Result<Self, SolveError> {
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
        let (g, c) = contact_vectors(model);
        let alpha = apply(&c, &model.u0);
        let history = model.contact.as_ref().map(|ct| History::new(ct, alpha));
        let phi_n = history.as_ref().map_or(0.0, History::load_factor);
        let mut s = Central {
            sys,
            history,
            dt,
            m: sys.m_lumped.as_deref().expect("checked by critical_step"),
            g,
            c,
            u: model.u0.clone(),
            v: model.v0.clone(),
            a: vec![0.0; n],
            ku: vec![0.0; n],
            cv: sys.damped().then(|| [vec![0.0; n], vec![0.0; n]]),
            dissipated: 0.0,
            alpha,
            phi_n,
            phi_prev: phi_n,
            applied: AppliedLoad::new(model),
        };
        s.accelerate(false);
        Ok(s)
    }

    /// a = M⁻¹ (g φ + P − K u) at the current state, P the dynamic load there; with
    /// damping, less M⁻¹ C v* (see the module doc): v* predicted from the half-step
    /// velocity in `v` after a step (`predict`), v(0) itself at the start.
    fn accelerate(&mut self, predict: bool) {
        self.sys.k_mul(&self.u, &mut self.ku);
        match self.applied.as_ref().map(|p| &p.now) {
            None => {
                for i in 0..self.u.len() {
                    self.a[i] = (self.g[i] * self.phi_n - self.ku[i]) / self.m[i];
                }
            }
            Some(p) => {
                for (i, load) in p.iter().enumerate() {
                    self.a[i] = (self.g[i] * self.phi_n + load - self.ku[i]) / self.m[i];
                }
            }
        }
        if let Some([cv, work]) = &mut self.cv {
            // v* = v + Δt/2 M⁻¹(f − C v), then a = M⁻¹(f − C v*).
            self.sys.c_mul(&self.v, cv);
            if predict {
                for i in 0..self.u.len() {
                    work[i] = self.v[i] + 0.5 * self.dt * (self.a[i] - cv[i] / self.m[i]);
                }
                self.sys.c_mul(work, cv);
            }
            for ((a, c), m) in self.a.iter_mut().zip(cv.iter()).zip(self.m) {
                *a -= c / m;
            }
        }
    }
}

impl Stepper for Central<'_> {
    fn advance(&mut self, _step: usize, time: f64) -> Result<(), SolveError> {
        let (n, dt) = (self.u.len(), self.dt);
        for i in 0..n {
            self.v[i] += 0.5 * dt * self.a[i];
            self.u[i] += dt * self.v[i];
        }
        self.phi_prev = self.phi_n;
        self.alpha = apply(&self.c, &self.u);
        self.phi_n = self.history.as_mut().map_or(0.0, |h| h.commit(self.alpha));
        if let Some(p) = &mut self.applied {
            p.load_end(time);
            // Δu = Δt v(n+½), the half-step velocity in v now.
            let v = &self.v;
            p.book(|i| dt * v[i]);
        }
        // The damping's work: Δu·(C v*(n) + C v*(n+1))/2, Δu = Δt v(n+½).
        let before = self.cv.as_ref().map(|[cv, _]| dt * crate::numerics::dot(&self.v, cv));
        self.accelerate(true);
        if let (Some(before), Some([cv, _])) = (before, &self.cv) {
            self.dissipated += 0.5 * (before + dt * crate::numerics::dot(&self.v, cv));
        }
        for i in 0..n {
            self.v[i] += 0.5 * dt * self.a[i];
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
            applied_work: self.applied.as_ref().map_or(0.0, |p| p.work),
            dissipated: self.dissipated,
            contact: self.history.as_ref().map(History::energy).unwrap_or_default(),
        }
    }

    fn costs(&self) -> StepCosts {
        StepCosts::default()
    }
}
