//! Time integration of M ü + K u = Σ S_i φ(α) e_i, with the contact law φ(α) =
//! max(α, 0)^A and α a linear functional of u.
//!
//! Every scheme factorises its constant effective matrix once. Implicit schemes solve
//! the contact by condensation: u(n+1) = u* + z ψ, with z = A⁻¹ g precomputed, so each
//! step is one sparse solve plus a scalar equation in α; the matrix is never refactored.
//!
//! Schemes (one file each):
//! - [`Scheme::Newmark`]: average-acceleration Newmark (trapezoidal rule), contact
//!   implicit. Second order, unconditionally stable for the linear part.
//! - [`Scheme::Energy`]: the same with the contact force taken as the discrete
//!   gradient of the Hertz potential: conserves energy to round-off at any Δt.
//! - [`Scheme::Nastran`]: COSMIC NASTRAN's three-point direct transient scheme
//!   (β = 1/3) with the nonlinear load lagged (explicit), for auditing against NASTRAN.

pub mod central;
mod contact;
pub mod linear;
mod nastran;
mod newmark;

use crate::assembly::System;
use crate::model::Model;
use std::time::Duration;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Scheme {
    #[default]
    Newmark,
    Energy,
    Nastran,
    /// Explicit central differences (velocity Verlet), conditionally stable.
    Central,
}

impl Scheme {
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Newmark => "newmark",
            Scheme::Energy => "energy",
            Scheme::Nastran => "nastran",
            Scheme::Central => "central",
        }
    }
}

/// Numerical failures. Each says where it happened.
#[derive(Debug, Clone, thiserror::Error)]
pub enum SolveError {
    #[error(
        "the effective matrix is singular at {dof}: a mechanism (nothing restrains this DOF: \
         constrain it with SPC1/PS or attach stiffness or mass to it)"
    )]
    Mechanism { dof: String },
    #[error("non-finite value (NaN or infinity) in the state at step {step} (t = {time_s:e} s), {dof}")]
    NonFinite { step: usize, time_s: f64, dof: String },
    #[error("relative energy error {error:.3e} at step {step} (t = {time_s:e} s) exceeds the limit {limit:.3e}")]
    EnergyLimit {
        step: usize,
        time_s: f64,
        error: f64,
        limit: f64,
    },
    #[error("the contact equation did not converge at step {step} (t = {time_s:e} s)")]
    ContactSolve { step: usize, time_s: f64 },
    #[error("explicit scheme refused: {reason}")]
    Explicit { reason: String },
    #[error("linear solver failure: {0}")]
    Linear(String),
}

/// The state after a step, as observers see it.
#[derive(Debug, Clone, Copy)]
pub struct StepState<'a> {
    pub step: usize,
    pub time: f64,
    pub u: &'a [f64],
    pub v: &'a [f64],
    /// The contact driver (indentation α).
    pub alpha: f64,
    /// Load factor acting at this state: every NOLIN3 load is S·factor.
    pub load_factor: f64,
    /// Mean load factor the scheme applied over the step that ended here; the work of
    /// the contact loads over the step is (Δu · g)·work_factor.
    pub work_factor: f64,
}

/// Receives each state; may stop the run (returns false) or fail it.
pub trait Observer {
    fn observe(&mut self, s: &StepState) -> Result<bool, SolveError>;
}

/// What a run cost.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct RunStats {
    pub steps: usize,
    pub factorizations: usize,
    pub solves: usize,
    pub contact_iterations: usize,
    #[serde(serialize_with = "secs")]
    pub factor_time: Duration,
    #[serde(serialize_with = "secs")]
    pub solve_time: Duration,
    #[serde(serialize_with = "secs")]
    pub total_time: Duration,
}

fn secs<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

/// Integrates `steps` steps of size `dt` from the model's initial state, calling the
/// observer with the initial state (step 0) and after every step.
pub fn integrate(
    model: &Model,
    sys: &System,
    scheme: Scheme,
    dt: f64,
    steps: usize,
    obs: &mut dyn Observer,
) -> Result<RunStats, SolveError> {
    let t0 = std::time::Instant::now();
    let mut stats = match scheme {
        Scheme::Newmark => newmark::run(model, sys, newmark::ContactForm::Endpoint, dt, steps, obs),
        Scheme::Energy => newmark::run(model, sys, newmark::ContactForm::DiscreteGradient, dt, steps, obs),
        Scheme::Nastran => nastran::run(model, sys, dt, steps, obs),
        Scheme::Central => central::run(model, sys, dt, steps, obs),
    }?;
    stats.total_time = t0.elapsed();
    Ok(stats)
}

/// Checks a state vector for NaN/inf and names the first bad DOF.
fn check_finite(model: &Model, step: usize, time: f64, x: &[f64]) -> Result<(), SolveError> {
    match x.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(SolveError::NonFinite {
            step,
            time_s: time,
            dof: model.dofs[i].to_string(),
        }),
    }
}

/// Load vector g (the NOLIN3 scales on their DOFs) and driver functional c.
fn contact_vectors(model: &Model) -> (Vec<f64>, Vec<(usize, f64)>) {
    let mut g = vec![0.0; model.n()];
    let mut c = Vec::new();
    if let Some(ct) = &model.contact {
        for l in &ct.loads {
            g[l.dof] += l.scale;
        }
        c = ct.driver.clone();
    }
    (g, c)
}
