//! Time integration of M ü + K u = Σ S_i φ(α) e_i, with the contact law φ(α) =
//! max(α, 0)^A (Hertz's, elastic) or a law that unloads along another curve
//! ([`law`]: Yang and Sun's, whose history each stepper keeps), and α a linear
//! functional of u.
//!
//! One driver loop ([`integrate`]) owns what every scheme shares: the initial state,
//! the finite checks, the observer (which may stop the run), and the costs. A scheme
//! is a [`Stepper`]: its parameters and its step. [`Scheme::ALL`] lists them.
//!
//! Every implicit scheme factorises its constant effective matrix once and solves the
//! contact by condensation: u(n+1) = u* + z ψ, with z = A⁻¹ g precomputed, so each
//! step is one sparse solve plus a scalar equation in α; the matrix is never refactored.
//!
//! Schemes (one file each):
//! - [`Scheme::Newmark`]: average-acceleration Newmark (trapezoidal rule), contact
//!   implicit. Second order, unconditionally stable for the linear part.
//! - [`Scheme::Energy`]: the same with the contact force taken as the discrete
//!   gradient of the Hertz potential: conserves energy to round-off at any Δt.
//! - [`Scheme::Nastran`]: COSMIC NASTRAN's three-point direct transient scheme
//!   (β = 1/3) with the nonlinear load lagged (explicit), for auditing against NASTRAN.
//! - [`Scheme::Central`]: explicit central differences (velocity Verlet), lumped mass,
//!   conditionally stable.
//!
//! [`convolution`] runs the two trapezoidal schemes another way: the target's linear
//! response computed once, the contact by an exact history sum.

pub mod central;
mod contact;
pub mod law;
pub mod convolution;
pub mod linear;
mod subtrees;
pub mod nastran;
pub mod newmark;
#[cfg(test)]
mod scheme_tests;
#[cfg(test)]
mod test_models;

use crate::assembly::System;
use crate::model::Model;
use std::time::Duration;

/// The time schemes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Scheme {
    /// Trapezoidal Newmark, end-point contact force ([`NewmarkParams::TRAPEZOIDAL`]).
    #[default]
    Newmark,
    /// Trapezoidal Newmark, discrete-gradient contact force
    /// ([`NewmarkParams::ENERGY_CONSERVING`]).
    Energy,
    /// COSMIC NASTRAN's three-point scheme ([`ThreePointParams::NASTRAN`]).
    Nastran,
    /// Explicit central differences (velocity Verlet), conditionally stable.
    Central,
}

impl Scheme {
    /// Every scheme, in the order studies list them.
    pub const ALL: [Scheme; 4] = [Scheme::Newmark, Scheme::Energy, Scheme::Nastran, Scheme::Central];

    /// The name on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Newmark => "newmark",
            Scheme::Energy => "energy",
            Scheme::Nastran => "nastran",
            Scheme::Central => "central",
        }
    }

    /// The scheme with this name.
    pub fn from_name(name: &str) -> Option<Scheme> {
        Scheme::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The trapezoidal rule's parameters for the two schemes that are one (`newmark`,
    /// `energy`; the convolution engine runs those), `None` for the others.
    pub fn newmark_params(self) -> Option<NewmarkParams> {
        match self {
            Scheme::Newmark => Some(NewmarkParams::TRAPEZOIDAL),
            Scheme::Energy => Some(NewmarkParams::ENERGY_CONSERVING),
            Scheme::Nastran | Scheme::Central => None,
        }
    }

    /// The scheme's stepper for a model, step size and system.
    fn stepper<'a>(self, model: &'a Model, sys: &'a System, dt: f64) -> Result<Box<dyn Stepper + 'a>, SolveError> {
        Ok(match self {
            Scheme::Newmark | Scheme::Energy => {
                let params = self.newmark_params().expect("a trapezoidal scheme");
                Box::new(Newmark::new(model, sys, dt, params)?)
            }
            Scheme::Nastran => Box::new(ThreePoint::new(model, sys, dt, ThreePointParams::NASTRAN)?),
            Scheme::Central => Box::new(Central::new(model, sys, dt)?),
        })
    }
}

impl std::fmt::Display for Scheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

pub use central::Central;
pub use nastran::{ThreePoint, ThreePointParams};
pub use newmark::{ContactForm, Newmark, NewmarkParams};

/// Numerical failures. Each says where it happened.
#[derive(Debug, Clone, thiserror::Error)]
pub enum SolveError {
    #[error(
        "the effective matrix is singular at {dof}: a mechanism (nothing restrains this DOF: \
         constrain it with SPC1/PS or attach stiffness or mass to it)"
    )]
    /// A DOF nothing restrains.
    Mechanism {
        /// The DOF, as the deck names it.
        dof: String,
    },
    /// A NaN or infinity appeared in the state.
    #[error("non-finite value (NaN or infinity) in the state at step {step} (t = {time:e}), {dof}")]
    NonFinite {
        /// The step.
        step: usize,
        /// Its time.
        time: f64,
        /// The first DOF with a non-finite value.
        dof: String,
    },
    /// The scalar contact equation had no solution in its bracket.
    #[error("the contact equation did not converge at step {step} (t = {time:e})")]
    ContactSolve {
        /// The step.
        step: usize,
        /// Its time.
        time: f64,
    },
    /// The explicit scheme cannot run this model.
    #[error("explicit scheme refused: {reason}")]
    Explicit {
        /// Why.
        reason: String,
    },
    /// The sparse factorisation failed.
    #[error("linear solver failure: {0}")]
    Linear(String),
    /// A stage would exceed the run's memory limit.
    #[error(
        "over the memory limit: {what} ({:.2} GiB); raise --max-memory, or ask for less",
        *bytes as f64 / (1u64 << 30) as f64
    )]
    Memory {
        /// What would not fit.
        what: String,
        /// The bytes it holds when stopped.
        bytes: u64,
    },
    /// A Lanczos extraction lost roots it had converged: round-off has overtaken the
    /// recurrence, whose later Ritz values are not the structure's.
    #[error(
        "the Lanczos extraction broke down after {vectors} Lanczos vectors: it had converged {seen} roots in the range asked \
         for and ends with {found}; ask for fewer roots (a lower cutoff, --modes-up-to, or a smaller ND)"
    )]
    Lanczos {
        /// Lanczos vectors formed.
        vectors: usize,
        /// Roots in the range accepted at the end.
        found: usize,
        /// The most roots in the range accepted at an earlier test.
        seen: usize,
    },
    /// A Lanczos extraction's vectors are no longer M-orthogonal: a fault in its
    /// re-orthogonalisation, not a hard model.
    #[error(
        "the Lanczos vectors have lost their orthogonality: after {vectors} Lanczos vectors the newest is {loss:.1e} \
         off M-orthogonal to the first (full re-orthogonalisation keeps it at round-off), so copies of the converged \
         roots would follow"
    )]
    Orthogonality {
        /// Lanczos vectors formed.
        vectors: usize,
        /// The largest |q_iᵀ M q_j| of the newest vectors against the first.
        loss: f64,
    },
}

/// The state after a step, as observers see it.
#[derive(Debug, Clone, Copy)]
pub struct StepState<'a> {
    /// Steps done.
    pub step: usize,
    /// Time of the state.
    pub time: f64,
    /// Displacements of the solved DOFs.
    pub u: &'a [f64],
    /// Velocities of the solved DOFs.
    pub v: &'a [f64],
    /// K u, where the scheme keeps it: the ledger's SE_t = ½ u·Ku without a product.
    pub internal_force: Option<&'a [f64]>,
    /// The contact driver (indentation α).
    pub alpha: f64,
    /// Load factor acting at this state: every NOLIN3 load is S·factor.
    pub load_factor: f64,
    /// Mean load factor the scheme applied over the step that ended here; the work of
    /// the contact loads over the step is (Δu · g)·work_factor.
    pub work_factor: f64,
    /// The work the deck's dynamic load ([`crate::model::excitation`]) has done from
    /// the start to this state, as the scheme applies it (0 without one).
    pub applied_work: f64,
    /// The energy the viscous damping has dissipated from the start to this state,
    /// as the scheme's energy identity books it (0 without damping).
    pub dissipated: f64,
    /// The contact's energies at this state (zero without a contact).
    pub contact: ContactEnergy,
}

/// The energies of a contact ([`law::History`]): what it holds and what it has
/// dissipated.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactEnergy {
    /// K·E: what the contact would return unloading from this state (for an elastic
    /// law its potential, Eq. 15).
    pub stored: f64,
    /// K·D: the work done on the contact beyond what it holds, so far.
    pub dissipated: f64,
}

/// Receives each state; may stop the run (returns false) or fail it.
pub trait Observer {
    /// Sees the state after a step; `Ok(false)` stops the run.
    fn observe(&mut self, s: &StepState) -> Result<bool, SolveError>;
}

/// What a run cost.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct RunStats {
    /// Steps done.
    pub steps: usize,
    /// Factorisations of the effective matrix.
    pub factorizations: usize,
    /// Triangular solve pairs.
    pub solves: usize,
    /// Iterations of the scalar contact solve, over all steps.
    pub contact_iterations: usize,
    /// Time spent factorising.
    #[serde(serialize_with = "secs")]
    pub factor_time: Duration,
    /// Time spent in solves.
    #[serde(serialize_with = "secs")]
    pub solve_time: Duration,
    /// The whole time loop (factorisation and solves included).
    #[serde(serialize_with = "secs")]
    pub total_time: Duration,
    /// Assembly of K and M and the inert-DOF reduction, before the loop (set by the
    /// run stage).
    #[serde(serialize_with = "secs")]
    pub assembly_time: Duration,
}

fn secs<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

/// The state a stepper holds after a step (or at the start).
#[derive(Debug, Clone, Copy)]
pub struct Current<'a> {
    /// Displacements.
    pub u: &'a [f64],
    /// Velocities.
    pub v: &'a [f64],
    /// K u, where the scheme keeps it.
    pub internal_force: Option<&'a [f64]>,
    /// The indentation α.
    pub alpha: f64,
    /// Load factor acting at this state.
    pub load_factor: f64,
    /// Mean load factor the scheme applied over the step that ended here.
    pub work_factor: f64,
    /// Work of the dynamic load from the start to this state.
    pub applied_work: f64,
    /// Energy dissipated by damping from the start to this state.
    pub dissipated: f64,
    /// The contact's energies.
    pub contact: ContactEnergy,
}

/// What a scheme's step costs: linear algebra and the contact solve.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepCosts {
    /// Factorisations.
    pub factorizations: usize,
    /// Triangular solve pairs.
    pub solves: usize,
    /// Contact solve iterations.
    pub contact_iterations: usize,
    /// Time spent factorising.
    pub factor_time: Duration,
    /// Time spent in solves.
    pub solve_time: Duration,
}

/// A time scheme reduced to its step; [`integrate`] drives it.
pub trait Stepper {
    /// Advances from step `step − 1` to `step` (at `time`); the state is checked for
    /// finite values by the driver.
    fn advance(&mut self, step: usize, time: f64) -> Result<(), SolveError>;
    /// The state after the last step (after construction: the initial state).
    fn current(&self) -> Current<'_>;
    /// What the run has cost so far.
    fn costs(&self) -> StepCosts;
}

/// Integrates `steps` steps of size `dt` from the model's initial state, calling the
/// observer with the initial state (step 0) and after every step; the observer may
/// stop the run early. Every state is checked for NaN and infinity first.
pub fn integrate(
    model: &Model,
    sys: &System,
    scheme: Scheme,
    dt: f64,
    steps: usize,
    obs: &mut dyn Observer,
) -> Result<RunStats, SolveError> {
    let t0 = std::time::Instant::now();
    let mut stepper = scheme.stepper(model, sys, dt)?;
    let mut stats = RunStats::default();
    let mut go = observe(model, 0, 0.0, stepper.current(), obs)?;
    let mut step = 0;
    while go && step < steps {
        step += 1;
        let time = step as f64 * dt;
        stepper.advance(step, time)?;
        stats.steps = step;
        go = observe(model, step, time, stepper.current(), obs)?;
    }
    let c = stepper.costs();
    stats.factorizations = c.factorizations;
    stats.solves = c.solves;
    stats.contact_iterations = c.contact_iterations;
    stats.factor_time = c.factor_time;
    stats.solve_time = c.solve_time;
    stats.total_time = t0.elapsed();
    Ok(stats)
}

/// Checks a state and shows it to the observer.
fn observe(model: &Model, step: usize, time: f64, c: Current, obs: &mut dyn Observer) -> Result<bool, SolveError> {
    check_finite(model, step, time, c.u)?;
    check_finite(model, step, time, c.v)?;
    obs.observe(&StepState {
        step,
        time,
        u: c.u,
        v: c.v,
        internal_force: c.internal_force,
        alpha: c.alpha,
        load_factor: c.load_factor,
        work_factor: c.work_factor,
        applied_work: c.applied_work,
        dissipated: c.dissipated,
        contact: c.contact,
    })
}

/// Checks a state vector for NaN/inf and names the first bad DOF.
fn check_finite(model: &Model, step: usize, time: f64, x: &[f64]) -> Result<(), SolveError> {
    // A pass without an early exit, which the compiler vectorises, then the search.
    if !x.iter().fold(false, |bad, v| bad | !v.is_finite()) {
        return Ok(());
    }
    match x.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(SolveError::NonFinite {
            step,
            time,
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

/// The deck's dynamic load as a scheme applies it: P(t) at the two ends of the step
/// being taken, and the work it has done, booked step by step as
/// Δu·(P(n) + P(n+1))/2 — for the trapezoidal rule exactly the work its energy
/// identity books, so that the ledger balances to round-off.
pub(crate) struct AppliedLoad<'a> {
    excitation: &'a crate::model::excitation::Excitation,
    /// P at the current state.
    pub now: Vec<f64>,
    /// P at the end of the step being taken (after [`AppliedLoad::load_end`]).
    pub next: Vec<f64>,
    /// The work done from the start to the current state.
    pub work: f64,
}

impl<'a> AppliedLoad<'a> {
    /// P(0) in place, when the model has a dynamic load.
    pub fn new(model: &'a Model) -> Option<Self> {
        let excitation = model.excitation.as_ref()?;
        let mut now = vec![0.0; model.n()];
        excitation.load_at(0.0, &mut now);
        Some(AppliedLoad {
            excitation,
            now,
            next: vec![0.0; model.n()],
            work: 0.0,
        })
    }

    /// P at the end of the step, t.
    pub fn load_end(&mut self, t: f64) {
        self.excitation.load_at(t, &mut self.next);
    }

    /// Books the work of the step over the increment `du` and makes its end current.
    pub fn book(&mut self, du: impl Fn(usize) -> f64) {
        self.work += 0.5
            * (0..self.now.len())
                .map(|i| du(i) * (self.now[i] + self.next[i]))
                .sum::<f64>();
        std::mem::swap(&mut self.now, &mut self.next);
    }
}

#[cfg(test)]
mod tests {
    /// Goal: a NaN or an infinity in a state is an error naming the step, the time and
    /// the DOF; a finite state passes. Model: the one-DOF oscillator.
    #[test]
    fn check_finite_names_a_nan_or_an_infinity() {
        let o = super::test_models::oscillator();
        assert!(super::check_finite(&o.model, 3, 0.5, &[1.0]).is_ok());
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = super::check_finite(&o.model, 3, 0.5, &[bad]).unwrap_err();
            let dof = o.model.dofs[0].to_string();
            assert!(
                matches!(&e, super::SolveError::NonFinite { step: 3, dof: d, .. } if *d == dof),
                "{e}"
            );
        }
    }
}
