//! The threshold impact velocity: the lowest impact speed at which the run's peak
//! contact force reaches a given force or the plate's delamination threshold, or the
//! plies' largest failure index reaches a level ([`crate::damage`]), found by
//! bisection on the convolution engine and checked on the direct engine.
//!
//! The peak force of a Hertz impact on a linear target grows with the impact speed
//! (the target's response is linear in the contact force and the contact law is
//! monotone), so a bracket [v_lo, v_hi] with the peak below the target force at v_lo
//! and at or above it at v_hi contains exactly one crossing. A failure index is read
//! from ply stresses that grow with the force; the search assumes its largest value
//! over the run grows with the speed too (true of HILL, a positive quadratic form of
//! stresses that scale together, and of the maximum ratios; HOFF's and TSAI's linear
//! terms could in principle break it) and the direct check confirms the bracket it
//! finds. From the deck's speed the
//! bracket is found by halving or doubling, then bisected until its width is below
//! 1e-6 of v_hi: each evaluation is one run on the convolution engine (the kernels are
//! computed once), so the whole search costs about one direct run. A model the
//! convolution engine cannot run (its mass matrix not lumped: offset beams or
//! masses) is searched on the direct engine instead, a full run per evaluation. Both ends of the
//! final bracket are then run on the direct engine, which must agree with the
//! convolution engine to [`super::sweep::DIRECT_CHECK_MAX`] and put the target (force or index)
//! between them.

use super::sweep::{point_model, Param, Vary, DIRECT_CHECK_MAX};
use super::StudyError;
use crate::model::Model;
use crate::run::convolution::{engine_difference, Kernels, Scale};
use crate::run::{prepare, run_model, Engine, RunError, RunOptions, RunResult};
use indicatif::ProgressBar;

/// Relative width of the final bracket.
pub const BRACKET_WIDTH: f64 = 1e-6;
/// Halvings or doublings of the deck's speed tried before giving up on a bracket.
const MAX_BRACKET_STEPS: usize = 60;

/// What the search stops on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Until {
    /// The peak contact force reaches this force.
    PeakForce(f64),
    /// The peak contact force reaches the plate's delamination threshold F_crit
    /// (needs the run's G_IIc).
    Delamination,
    /// The largest failure index of the theory the plies' PCOMP names (FT), over the
    /// written laminate elements, reaches this level.
    FailureIndex(f64),
    /// The largest bond index max(|τ1z|, |τ2z|)/SB at the written laminate elements'
    /// ply interfaces reaches this level.
    BondIndex(f64),
}

impl Until {
    /// Reads `peak_force=F`, `delamination`, `failure_index=L` or `bond_index=L`.
    pub fn parse(text: &str) -> Result<Until, StudyError> {
        let positive = |what: &str, x: &str| match x.trim().parse::<f64>() {
            Ok(x) if x > 0.0 && x.is_finite() => Ok(x),
            _ => Err(StudyError::Input(format!(
                "--until {text}: the {what} must be a positive number"
            ))),
        };
        match text.split_once('=') {
            None if text == "delamination" => Ok(Until::Delamination),
            Some(("peak_force", f)) => positive("force", f).map(Until::PeakForce),
            Some(("failure_index", f)) => positive("index", f).map(Until::FailureIndex),
            Some(("bond_index", f)) => positive("index", f).map(Until::BondIndex),
            _ => Err(StudyError::Input(format!(
                "--until {text}: expected peak_force=F, delamination, failure_index=L or bond_index=L"
            ))),
        }
    }

    /// The quantity of a run the search compares with the target.
    fn measure(&self, run: &RunResult) -> Result<f64, StudyError> {
        match self {
            Until::PeakForce(_) | Until::Delamination => Ok(run.summary.contact.peak_force),
            Until::FailureIndex(_) => run.summary.failure.as_ref().map(|f| f.theory.largest).ok_or_else(|| {
                StudyError::Input(
                    "--until failure_index needs failure indices: a PCOMP with FT and allowables, and its \
                     elements in the deck's STRESS or STRAIN set"
                        .into(),
                )
            }),
            Until::BondIndex(_) => run
                .summary
                .failure
                .as_ref()
                .and_then(|f| f.bond.as_ref())
                .map(|b| b.largest)
                .ok_or_else(|| {
                    StudyError::Input(
                        "--until bond_index needs bond indices: a PCOMP with SB and FT whose plies give G1Z and G2Z \
                         (transverse shear), and its elements in the deck's STRESS or STRAIN set"
                            .into(),
                    )
                }),
        }
    }
}

/// The threshold found.
#[derive(Debug, Clone)]
pub struct Threshold {
    /// The value the measure had to reach: a force, or a failure index.
    pub target_value: f64,
    /// What the measure is and what its target is (the given force, F_crit with its
    /// formula, or the index level).
    pub target: String,
    /// The final bracket [v_lo, v_hi] of the impact speed: below at v_lo, reached at v_hi.
    pub bracket: [f64; 2],
    /// The threshold speed, the bracket's midpoint.
    pub velocity: f64,
    /// The impactor's kinetic energy ½ m v² at it, in the deck's energy unit.
    pub energy: f64,
    /// The impactor's mass.
    pub mass: f64,
    /// The engine the bracket's ends are checked on: the direct engine, or the modal
    /// engine on the search's own reduction when the search's kernels came from it.
    pub checked_on: Engine,
    /// The measure (peak force, or largest failure index) at v_lo and v_hi on
    /// `checked_on`.
    pub direct_values: [f64; 2],
    /// The engines' largest difference at the two ends, relative to each quantity's peak.
    pub direct_check: f64,
    /// Runs of the search (on the convolution engine, or on the direct engine when
    /// `direct_reason` says why the convolution engine cannot run the model).
    pub evaluations: usize,
    /// Why the search ran on the direct engine; `None`: it ran on the convolution
    /// engine, and `direct_check` compares the two at the bracket's ends (0 when the
    /// search itself was direct).
    pub direct_reason: Option<String>,
    /// Seconds: kernel pass, search, direct checks.
    pub times_s: [f64; 3],
}

/// Finds the impact speed at which the run's measure reaches `until`'s target.
pub fn find_velocity(base: &Model, run: &RunOptions, until: Until, bar: &ProgressBar) -> Result<Threshold, StudyError> {
    let ct = base
        .contact
        .as_ref()
        .ok_or_else(|| StudyError::Input("a threshold search needs a model with a contact".into()))?;
    let (target_value, target) = match until {
        Until::PeakForce(f) => (f, format!("peak force {f:.6e}")),
        Until::FailureIndex(level) => (level, format!("largest failure index (PCOMP FT) {level}")),
        Until::BondIndex(level) => (level, format!("largest bond index (PCOMP SB) {level}")),
        Until::Delamination => {
            let g = run.interlaminar_toughness.ok_or_else(|| {
                StudyError::Input("--until delamination needs the interface's toughness: --giic G_IIc".into())
            })?;
            let d = crate::physics::references::plate_bending_stiffness(base)?;
            let onset = crate::damage::delamination_onset(&d, g);
            (
                onset.critical_force,
                format!(
                    "delamination threshold F_crit {:.6e}: {}",
                    onset.critical_force, onset.formula
                ),
            )
        }
    };
    let v_deck = base.v0[ct.impactor.dof].abs();
    let t0 = std::time::Instant::now();
    let on = |engine| RunOptions {
        engine,
        progress: None,
        ..run.clone()
    };
    let checked_on = if run.engine == Engine::Modal {
        Engine::Modal
    } else {
        Engine::Direct
    };
    let (conv_opts, direct_opts) = (on(Engine::Convolution), on(checked_on));
    let prepared = prepare(base, &conv_opts)?;
    let (model, sys) = (prepared.model.as_ref(), &prepared.system);
    let dt = run.dt.unwrap_or(model.time.dt);
    let steps = run.steps.unwrap_or(model.time.steps);
    // On the modal engine: one reduction at the cutoff asked for, its kernels for the
    // search and its coordinates for the checks. The default cutoff comes from the
    // contact time at a speed, the very speed the search looks for: it is not taken.
    let reduction = match checked_on {
        Engine::Modal => {
            if run.modal.cutoff.is_none() {
                return Err(StudyError::Input(
                    "a threshold search on the modal engine needs its cutoff (--modes-up-to): the default comes \
                     from the contact time at a speed, and the speed is what the search looks for"
                        .into(),
                ));
            }
            let cut = crate::run::modal::cutoff(model, &run.modal)?;
            Some(crate::run::modal::reduce_at(
                model,
                sys,
                &run.modal,
                cut,
                None,
                &|_| {},
            )?)
        }
        _ => None,
    };
    // A model the convolution engine cannot run (a mass matrix that is not lumped:
    // offset beams or masses) is searched on the direct engine, run by run.
    let (kernels, direct_reason) = match &reduction {
        Some(r) => (
            Some(Kernels::compute_modal(r, dt, steps, &ProgressBar::hidden())?),
            None,
        ),
        None => match Kernels::for_run(
            model,
            sys,
            dt,
            steps,
            run.kernel_cache.as_deref(),
            &ProgressBar::hidden(),
        ) {
            Ok((k, _)) => (Some(k), None),
            Err(RunError::Engine(why)) => (None, Some(why)),
            Err(e) => return Err(e.into()),
        },
    };
    // A point's run on the checking engine.
    let check = |m: &Model| -> Result<RunResult, StudyError> {
        guarded(match &reduction {
            Some(r) => r.run_point(m, &direct_opts),
            None => run_model(m, &direct_opts),
        })
    };
    let pass_s = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let point = |v: f64| {
        point_model(
            model,
            &[Vary {
                param: Param::Velocity,
                values: vec![v],
            }],
            &[v],
        )
    };
    let mut evaluations = 0;
    let mut peak = |v: f64| -> Result<f64, StudyError> {
        evaluations += 1;
        bar.inc(1);
        let m = point(v)?;
        until.measure(&match &kernels {
            Some(k) => guarded(k.run(&m, &conv_opts, &ProgressBar::hidden()))?,
            None => check(&m)?,
        })
    };
    let reached = |f: f64| f >= target_value;
    let (mut lo, mut hi) = (v_deck, v_deck);
    if reached(peak(v_deck)?) {
        lo /= 2.0;
        let mut k = 0;
        while reached(peak(lo)?) {
            hi = lo;
            lo /= 2.0;
            k += 1;
            if k == MAX_BRACKET_STEPS {
                return Err(StudyError::Input(format!(
                    "the measure reaches {target_value:e} even at {lo:e}: no threshold above zero speed"
                )));
            }
        }
    } else {
        hi *= 2.0;
        let mut k = 0;
        while !reached(peak(hi)?) {
            lo = hi;
            hi *= 2.0;
            k += 1;
            if k == MAX_BRACKET_STEPS {
                return Err(StudyError::Input(format!(
                    "the measure stays below {target_value:e} up to {hi:e}"
                )));
            }
        }
    }
    while hi - lo > BRACKET_WIDTH * hi {
        let mid = 0.5 * (lo + hi);
        if reached(peak(mid)?) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let search_s = t1.elapsed().as_secs_f64();
    let t2 = std::time::Instant::now();
    let mut direct_values = [0.0; 2];
    let mut direct_check = 0.0f64;
    for (k, v) in [lo, hi].into_iter().enumerate() {
        let m = point(v)?;
        let direct = check(&m)?;
        if let Some(kernels) = &kernels {
            let conv = guarded(kernels.run(&m, &conv_opts, &ProgressBar::hidden()))?;
            direct_check =
                direct_check.max(engine_difference(&direct, &conv, Scale::Column).map_or(f64::INFINITY, |w| w.0));
        }
        direct_values[k] = until.measure(&direct)?;
    }
    if direct_check > DIRECT_CHECK_MAX || reached(direct_values[0]) || !reached(direct_values[1]) {
        return Err(StudyError::Unconfirmed(format!(
            "the {} engine does not confirm the threshold bracket [{lo:e}, {hi:e}]: engines differ by \
             {direct_check:e} (at most {DIRECT_CHECK_MAX:e}), its values {:e} and {:e} against {target_value:e}",
            checked_on.name(),
            direct_values[0],
            direct_values[1]
        )));
    }
    let velocity = 0.5 * (lo + hi);
    Ok(Threshold {
        target_value,
        target,
        bracket: [lo, hi],
        velocity,
        energy: 0.5 * ct.impactor.mass * velocity * velocity,
        mass: ct.impactor.mass,
        checked_on,
        direct_values,
        direct_check,
        evaluations,
        direct_reason,
        times_s: [pass_s, search_s, t2.elapsed().as_secs_f64()],
    })
}

/// A run stopped by the energy guard still has its peak force.
fn guarded(run: Result<RunResult, RunError>) -> Result<RunResult, StudyError> {
    match run {
        Ok(r) => Ok(r),
        Err(RunError::EnergyGuard { partial, .. }) => Ok(*partial),
        Err(e) => Err(e.into()),
    }
}
