//! The threshold impact velocity: the lowest impact speed at which the run's peak
//! contact force reaches a given force, or the plate's delamination threshold
//! ([`crate::damage`]), found by bisection on the convolution engine and checked on the
//! direct engine.
//!
//! The peak force of a Hertz impact on a linear target grows with the impact speed
//! (the target's response is linear in the contact force and the contact law is
//! monotone), so a bracket [v_lo, v_hi] with the peak below the target force at v_lo
//! and at or above it at v_hi contains exactly one crossing. From the deck's speed the
//! bracket is found by halving or doubling, then bisected until its width is below
//! 1e-6 of v_hi: each evaluation is one run on the convolution engine (the kernels are
//! computed once), so the whole search costs about one direct run. Both ends of the
//! final bracket are then run on the direct engine, which must agree with the
//! convolution engine to [`super::sweep::DIRECT_CHECK_MAX`] and put the target force
//! between them.

use super::sweep::{point_model, Param, Vary, DIRECT_CHECK_MAX};
use crate::model::Model;
use crate::run::convolution::{engine_difference, Kernels};
use crate::run::{run_model, solved_system, Engine, RunError, RunOptions, RunResult};
use crate::Error;
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
}

impl Until {
    /// Reads `peak_force=F` or `delamination`.
    pub fn parse(text: &str) -> Result<Until, Error> {
        match text.split_once('=') {
            None if text == "delamination" => Ok(Until::Delamination),
            Some(("peak_force", f)) => match f.trim().parse::<f64>() {
                Ok(f) if f > 0.0 && f.is_finite() => Ok(Until::PeakForce(f)),
                _ => Err(Error::Usage(format!(
                    "--until {text}: the force must be a positive number"
                ))),
            },
            _ => Err(Error::Usage(format!(
                "--until {text}: expected peak_force=F or delamination (failure indices need ply results, not yet computed)"
            ))),
        }
    }
}

/// The threshold found.
#[derive(Debug, Clone)]
pub struct Threshold {
    /// The force the peak had to reach.
    pub target_force: f64,
    /// What that force is (the given force, or F_crit with its formula).
    pub target: String,
    /// The final bracket [v_lo, v_hi] of the impact speed: below at v_lo, reached at v_hi.
    pub bracket: [f64; 2],
    /// The threshold speed, the bracket's midpoint.
    pub velocity: f64,
    /// The impactor's kinetic energy ½ m v² at it, in the deck's energy unit.
    pub energy: f64,
    /// The impactor's mass.
    pub mass: f64,
    /// Peak forces at v_lo and v_hi on the direct engine.
    pub direct_peaks: [f64; 2],
    /// The engines' largest difference at the two ends, relative to each quantity's peak.
    pub direct_check: f64,
    /// Runs on the convolution engine.
    pub evaluations: usize,
    /// Seconds: kernel pass, search, direct checks.
    pub times_s: [f64; 3],
}

/// Finds the impact speed at which the peak contact force reaches `until`'s force.
pub fn find_velocity(base: &Model, run: &RunOptions, until: Until, bar: &ProgressBar) -> Result<Threshold, Error> {
    let ct = base
        .contact
        .as_ref()
        .ok_or_else(|| Error::Usage("a threshold search needs a model with a contact".into()))?;
    let (target_force, target) = match until {
        Until::PeakForce(f) => (f, format!("peak force {f:.6e}")),
        Until::Delamination => {
            let g = run.interlaminar_toughness.ok_or_else(|| {
                Error::Usage("--until delamination needs the interface's toughness: --giic G_IIc".into())
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
    let (model, sys) = solved_system(base, run.skip_inert)?;
    let model = model.as_ref();
    let dt = run.dt.unwrap_or(model.time.dt);
    let steps = run.steps.unwrap_or(model.time.steps);
    let on = |engine| RunOptions {
        engine,
        progress: None,
        ..run.clone()
    };
    let (conv_opts, direct_opts) = (on(Engine::Convolution), on(Engine::Direct));
    crate::run::preflight_solved(model, &conv_opts)?;
    let (kernels, _) = Kernels::for_run(
        model,
        &sys,
        dt,
        steps,
        run.kernel_cache.as_deref(),
        &ProgressBar::hidden(),
    )?;
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
    let mut peak = |v: f64| -> Result<f64, Error> {
        evaluations += 1;
        bar.inc(1);
        Ok(guarded(kernels.run(&point(v)?, &conv_opts, &ProgressBar::hidden()))?
            .summary
            .contact
            .peak_force)
    };
    let reached = |f: f64| f >= target_force;
    let (mut lo, mut hi) = (v_deck, v_deck);
    if reached(peak(v_deck)?) {
        lo /= 2.0;
        let mut k = 0;
        while reached(peak(lo)?) {
            hi = lo;
            lo /= 2.0;
            k += 1;
            if k == MAX_BRACKET_STEPS {
                return Err(Error::Usage(format!(
                    "the peak force reaches {target_force:e} even at {lo:e}: no threshold above zero speed"
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
                return Err(Error::Usage(format!(
                    "the peak force stays below {target_force:e} up to {hi:e}"
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
    let mut direct_peaks = [0.0; 2];
    let mut direct_check = 0.0f64;
    for (k, v) in [lo, hi].into_iter().enumerate() {
        let m = point(v)?;
        let direct = guarded(run_model(&m, &direct_opts))?;
        let conv = guarded(kernels.run(&m, &conv_opts, &ProgressBar::hidden()))?;
        direct_check = direct_check.max(engine_difference(&direct, &conv).map_or(f64::INFINITY, |w| w.0));
        direct_peaks[k] = direct.summary.contact.peak_force;
    }
    if direct_check > DIRECT_CHECK_MAX || reached(direct_peaks[0]) || !reached(direct_peaks[1]) {
        return Err(Error::Stopped(format!(
            "the direct engine does not confirm the threshold bracket [{lo:e}, {hi:e}]: engines differ by \
             {direct_check:e} (at most {DIRECT_CHECK_MAX:e}), direct peaks {:e} and {:e} against {target_force:e}",
            direct_peaks[0], direct_peaks[1]
        )));
    }
    let velocity = 0.5 * (lo + hi);
    Ok(Threshold {
        target_force,
        target,
        bracket: [lo, hi],
        velocity,
        energy: 0.5 * ct.impactor.mass * velocity * velocity,
        mass: ct.impactor.mass,
        direct_peaks,
        direct_check,
        evaluations,
        times_s: [pass_s, search_s, t2.elapsed().as_secs_f64()],
    })
}

/// A run stopped by the energy guard still has its peak force.
fn guarded(run: Result<RunResult, RunError>) -> Result<RunResult, Error> {
    match run {
        Ok(r) => Ok(r),
        Err(RunError::EnergyGuard { partial, .. }) => Ok(*partial),
        Err(e) => Err(e.into()),
    }
}
