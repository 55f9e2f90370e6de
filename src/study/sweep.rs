//! Parameter sweeps on the convolution engine: the target's kernels computed once,
//! then one contact history per point, over the impactor's velocity and mass and the
//! Hertz law's K and exponent (everything outside the target's linear system).
//!
//! Points are the Cartesian product of the `--vary` lists, the first varying slowest,
//! numbered from 0. The self-check ([`SelfCheck`]) runs a few points on the direct
//! engine as well: by default the first and the last (the gentlest and the hardest
//! impact: the range of the contact's nonlinearity; the kernels depend on neither the
//! impactor nor the Hertz law, so a disagreement of the engines shows at any point),
//! and the point nearest the deck's own values when the sweep contains them. Their
//! largest difference ([`engine_difference`]) is the row's `direct_check`, and one over
//! [`DIRECT_CHECK_MAX`] fails the sweep. A shard `I/N` runs the points whose number is
//! I−1 modulo N; [`collect`] merges shards into the `sweep.csv` an unsharded run writes.
//!
//! On the modal engine (`--engine modal`) the kernels are the modal reduction's
//! ([`Kernels::compute_modal`]), at one cutoff for every point ([`modal_cutoff`]: by
//! default the hardest point's), and the checked points are stepped on the modal
//! engine on the same reduction ([`crate::run::modal::Reduction::for_point`]: the
//! point's own modal run at that cutoff, bit for bit); the check then compares two
//! evaluations of the same reduced model, every column against its family's peak
//! ([`Scale::Family`]). What the truncation costs against the direct engine is the
//! `modal_engine` verification check's to show.

use super::in_parallel;
use super::StudyError;
use crate::integrate::Scheme;
use crate::model::{Model, Modify};
use crate::run::convolution::{engine_difference, CacheUse, Kernels, Scale};
use crate::run::modal::{self, ModalParams, Truncation};
use crate::run::{prepare, run_model, Column, Engine, RunError, RunOptions, RunResult};
use indicatif::ProgressBar;
use std::collections::HashMap;
use std::path::Path;

/// The largest `direct_check` a sweep accepts, relative to each quantity's peak: the
/// engines agree to round-off (measured 2.5e-13 to 6.7e-13 on the rod and the plate), so
/// 1e-9 leaves room for longer runs' round-off and still fails any difference in the
/// schemes' arithmetic (the `superposition` check's bound is 1e-10 for the fixed cases).
pub const DIRECT_CHECK_MAX: f64 = 1e-9;

/// What a sweep can vary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    /// The impactor's impact speed (the deck's direction kept).
    Velocity,
    /// The impactor's mass (its inertia scaled with it).
    Mass,
    /// The Hertz stiffness K (every NOLIN3 scale with it).
    K,
    /// The contact law's exponent.
    Exponent,
}

impl Param {
    /// Every parameter, by name.
    pub const ALL: [Param; 4] = [Param::Velocity, Param::Mass, Param::K, Param::Exponent];

    /// Whether the parameter leaves the target (its K, M, constraints and outputs)
    /// unchanged: the impactor and the contact law are outside it. A sweep runs on
    /// the convolution engine, whose kernels are the target's computed once, and
    /// refuses a parameter that changes it.
    pub fn leaves_target(self) -> bool {
        match self {
            Param::Velocity | Param::Mass | Param::K | Param::Exponent => true,
        }
    }

    /// The name on the command line and in `sweep.csv`.
    pub fn name(self) -> &'static str {
        match self {
            Param::Velocity => "velocity",
            Param::Mass => "mass",
            Param::K => "k",
            Param::Exponent => "exponent",
        }
    }
}

/// One `--vary`: a parameter and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    /// The parameter.
    pub param: Param,
    /// Its values, in order.
    pub values: Vec<f64>,
}

/// Why a `--vary` cannot be read; each names the whole `--vary` text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VaryError {
    /// Neither a range nor a list.
    #[error("--vary {0}: expected NAME=START:STOP:COUNT or NAME=v1,v2,...")]
    Form(String),
    /// Not a parameter a sweep varies.
    #[error("--vary {text}: unknown parameter {name} (velocity, mass, k, exponent)")]
    Parameter {
        /// The `--vary` text.
        text: String,
        /// The name given.
        name: String,
    },
    /// A value that is not a positive finite number.
    #[error("--vary {text}: '{value}' is not a positive number")]
    Value {
        /// The `--vary` text.
        text: String,
        /// The value as given.
        value: String,
    },
    /// A range's COUNT out of bounds.
    #[error("--vary {0}: COUNT must be 1 to 100000")]
    Count(String),
}

impl Vary {
    /// Reads `NAME=START:STOP:COUNT` (evenly spaced, or geometrically when `log`) or
    /// `NAME=v1,v2,...`.
    pub fn parse(text: &str, log: &[String]) -> Result<Vary, VaryError> {
        let (name, spec) = text.split_once('=').ok_or_else(|| VaryError::Form(text.into()))?;
        let param = Param::ALL
            .into_iter()
            .find(|p| p.name() == name)
            .ok_or_else(|| VaryError::Parameter {
                text: text.into(),
                name: name.into(),
            })?;
        let number = |s: &str| -> Result<f64, VaryError> {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(|| VaryError::Value {
                    text: text.into(),
                    value: s.into(),
                })
        };
        let values = match spec.split(':').collect::<Vec<_>>()[..] {
            [a, b, n] => {
                let (a, b) = (number(a)?, number(b)?);
                let n: usize = n
                    .trim()
                    .parse()
                    .ok()
                    .filter(|n| (1..=100_000).contains(n))
                    .ok_or_else(|| VaryError::Count(text.into()))?;
                let geometric = log.iter().any(|l| l == name);
                (0..n)
                    .map(|i| {
                        let f = if n == 1 { 0.0 } else { i as f64 / (n - 1) as f64 };
                        if geometric {
                            a * (b / a).powf(f)
                        } else {
                            a + (b - a) * f
                        }
                    })
                    .collect()
            }
            [_] => spec.split(',').map(number).collect::<Result<Vec<f64>, VaryError>>()?,
            _ => return Err(VaryError::Form(text.into())),
        };
        Ok(Vary { param, values })
    }
}

/// The points of a sweep: the Cartesian product of the values, the first `Vary`
/// slowest.
pub fn points(varies: &[Vary]) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::new()];
    for v in varies {
        out = out
            .into_iter()
            .flat_map(|p| {
                v.values.iter().map(move |x| {
                    let mut q = p.clone();
                    q.push(*x);
                    q
                })
            })
            .collect();
    }
    out
}

/// The model of one point: the base model with its impactor and contact law changed.
pub fn point_model(base: &Model, varies: &[Vary], values: &[f64]) -> Result<Model, StudyError> {
    let ct = base
        .contact
        .as_ref()
        .ok_or_else(|| StudyError::Input("a sweep needs a model with a contact".into()))?;
    let v0 = base.v0[ct.impactor.dof];
    let mut m = Modify::default();
    let mut exponent = None;
    for (v, x) in varies.iter().zip(values) {
        match v.param {
            Param::Velocity => m.velocity_scale = Some(x / v0.abs()),
            Param::Mass => m.impactor_mass_scale = Some(x / ct.impactor.mass),
            Param::K => m.contact_stiffness_scale = Some(x / ct.stiffness),
            Param::Exponent => exponent = Some(*x),
        }
    }
    let mut model = m.apply(base)?;
    if let (Some(a), Some(c)) = (exponent, model.contact.as_mut()) {
        c.exponent = a;
    }
    Ok(model)
}

/// Which points of a sweep are also run on the direct engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SelfCheck {
    /// Points spread evenly from the first to the last: 2 (the default) is the first
    /// and the last, 1 the last alone, 0 none (no self-check at all: nor the deck's
    /// point nor `every`).
    pub spread: usize,
    /// Every N-th point besides (points 0, N, 2N, …).
    pub every: Option<usize>,
}

impl Default for SelfCheck {
    fn default() -> Self {
        SelfCheck { spread: 2, every: None }
    }
}

impl SelfCheck {
    /// No self-check.
    pub const OFF: SelfCheck = SelfCheck { spread: 0, every: None };

    /// True when no point is checked.
    pub fn is_off(&self) -> bool {
        self.spread == 0 && self.every.is_none()
    }

    /// The checked points of a sweep of `total` points, in order, each once: the
    /// spread, every N-th, and `deck_point` (the point nearest the deck's own values).
    pub fn points(&self, total: usize, deck_point: Option<usize>) -> Vec<usize> {
        if self.is_off() || total == 0 {
            return Vec::new();
        }
        let last = total - 1;
        let mut p: Vec<usize> = match self.spread {
            0 => Vec::new(),
            1 => vec![last],
            k => (0..k).map(|i| (i * last + (k - 1) / 2) / (k - 1)).collect(),
        };
        if let Some(n) = self.every {
            p.extend((0..total).step_by(n.max(1)));
        }
        p.extend(deck_point);
        p.sort_unstable();
        p.dedup();
        p
    }
}

/// The point nearest the deck's own values, when every varied parameter's values
/// span the deck's (nearest: the least sum of squared differences, each relative to
/// its parameter's span; the lowest number of equals).
pub fn deck_point(base: &Model, varies: &[Vary]) -> Option<usize> {
    let ct = base.contact.as_ref()?;
    let own = |p: Param| match p {
        Param::Velocity => base.v0[ct.impactor.dof].abs(),
        Param::Mass => ct.impactor.mass,
        Param::K => ct.stiffness,
        Param::Exponent => ct.exponent,
    };
    let mut spans = Vec::new();
    for v in varies {
        let lo = v.values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let x = own(v.param);
        if !(lo..=hi).contains(&x) {
            return None;
        }
        spans.push((x, if hi > lo { hi - lo } else { 1.0 }));
    }
    let distance = |values: &[f64]| -> f64 {
        values
            .iter()
            .zip(&spans)
            .map(|(v, (x, span))| ((v - x) / span).powi(2))
            .sum()
    };
    points(varies)
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| distance(a).total_cmp(&distance(b)))
        .map(|(i, _)| i)
}

/// How to sweep.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// The parameters varied.
    pub varies: Vec<Vary>,
    /// `newmark` or `energy`.
    pub scheme: Scheme,
    /// Points run at once.
    pub jobs: usize,
    /// Run only the points numbered I−1 modulo N (`Some((I, N))`, I from 1).
    pub shard: Option<(usize, usize)>,
    /// A progress bar, set up by the caller.
    pub progress: Option<ProgressBar>,
    /// Which points are also run on the direct engine.
    pub checks: SelfCheck,
}

/// The cutoff of a sweep's modal reduction: as asked, or the largest of its points'
/// defaults ([`modal::cutoff`]): the modes over its shortest contact, so that the
/// hardest impact is reduced as finely as a modal run of that point alone would be.
pub fn modal_cutoff(base: &Model, varies: &[Vary], params: &ModalParams) -> Result<(f64, String), StudyError> {
    if params.cutoff.is_some() {
        return Ok(modal::cutoff(base, params)?);
    }
    let all = points(varies);
    let mut worst: Option<(f64, String, usize)> = None;
    for (i, values) in all.iter().enumerate() {
        let (f, from) = modal::cutoff(&point_model(base, varies, values)?, params)?;
        if worst.as_ref().is_none_or(|w| f > w.0) {
            worst = Some((f, from, i));
        }
    }
    let (f, from, i) = worst.ok_or_else(|| StudyError::Input("a sweep of no points".into()))?;
    Ok((
        f,
        format!("{from}, at point {i}: the shortest of the sweep's {} points", all.len()),
    ))
}

/// The fixed columns of `sweep.csv` after the point number and the varied values.
pub const RESULT_COLUMNS: [&str; 7] = [
    "peak_force",
    "peak_force_time",
    "contact_end",
    "n_contacts",
    "rebound_velocity",
    "transferred_fraction",
    "energy_error",
];

/// A sweep's outputs: `sweep.csv` and whether every direct check passed.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// The CSV's header.
    pub header: Vec<String>,
    /// Its rows (point number first), in point order.
    pub rows: Vec<Vec<f64>>,
    /// Points checked against the direct engine.
    pub direct_checks: usize,
    /// The largest direct check (0 when none ran).
    pub worst_direct_check: f64,
    /// The checked points (numbers), this shard's.
    pub checked: Vec<usize>,
    /// Seconds of the kernel pass (0 when read from the cache).
    pub kernel_pass_s: f64,
    /// Where the kernels came from.
    pub kernel_cache: CacheUse,
    /// Seconds of the direct runs of the checked points, summed over them.
    pub checks_s: f64,
    /// Seconds of the points on the convolution engine, summed over them (one
    /// core's time for them all).
    pub points_s: f64,
    /// Wall seconds of the whole sweep.
    pub wall_s: f64,
    /// With `--engine modal`: the reduction the kernels and the checks ran on.
    pub modal: Option<Truncation>,
}

impl SweepOutcome {
    /// True when every direct check is within [`DIRECT_CHECK_MAX`].
    pub fn passed(&self) -> bool {
        self.worst_direct_check <= DIRECT_CHECK_MAX
    }
}

/// The columns of `sweep.csv` for a model and its varied parameters: the point,
/// the varied values, [`RESULT_COLUMNS`], `dissipated_contact` for a hysteretic
/// contact, the peaks of the requested outputs, and the direct check.
pub fn header(model: &Model, varies: &[Vary]) -> Vec<String> {
    let mut h = vec!["point".to_string()];
    h.extend(varies.iter().map(|v| v.param.name().to_string()));
    h.extend(RESULT_COLUMNS.iter().map(|c| c.to_string()));
    if model.hysteretic() {
        h.push("dissipated_contact".into());
    }
    h.extend(output_columns(model).iter().map(|c| format!("peak_{}", c.name())));
    h.push("direct_check".into());
    h
}

/// The history columns whose peaks a sweep reports: the requested outputs.
fn output_columns(model: &Model) -> Vec<Column> {
    crate::run::history_columns(model)
        .into_iter()
        .skip(crate::run::FIXED_COLUMNS.len())
        .collect()
}

/// The row of one point, its `direct_check` empty (NaN) until compared.
fn row(index: usize, values: &[f64], run: &RunResult) -> Vec<f64> {
    let s = &run.summary;
    let nan = f64::NAN;
    let mut r = vec![index as f64];
    r.extend_from_slice(values);
    r.extend([
        s.contact.peak_force,
        s.contact.peak_force_time.unwrap_or(nan),
        // A contact still open when the run ends has no end: empty, not the run's end.
        match s.contact.intervals[..] {
            [_] if s.contact.open_at_end => nan,
            _ => s.contact.intervals.first().map_or(nan, |i| i[1]),
        },
        s.contact.intervals.len() as f64,
        s.impactor.rebound_velocity.unwrap_or(nan),
        s.energy.transferred_fraction.unwrap_or(nan),
        s.energy.max_relative_error.unwrap_or(nan),
    ]);
    // A hysteretic contact's dissipation (its column only for such a contact).
    if let Some(c) = &s.energy.contact {
        r.push(c.dissipated);
    }
    for j in crate::run::FIXED_COLUMNS.len()..run.history_columns.len() {
        r.push(
            run.history
                .iter()
                .map(|h| h[j])
                .fold(0.0, |a: f64, x| if x.abs() > a.abs() { x } else { a }),
        );
    }
    r.push(nan);
    r
}

/// A run that the energy guard stopped still gives its outputs up to the stop.
fn outputs(run: Result<RunResult, RunError>) -> Result<RunResult, StudyError> {
    match run {
        Ok(r) => Ok(r),
        Err(RunError::EnergyGuard { partial, .. }) => Ok(*partial),
        Err(e) => Err(e.into()),
    }
}

/// Runs a sweep of `base` (its Δt and steps from `run`) on `jobs` threads as one
/// queue of tasks taken in order: the kernel pass, the direct runs of the checked
/// points (the longest tasks, independent of the kernels), then every point on the
/// convolution engine, each waiting for the kernels if the pass is not done. The
/// direct checks are compared with their points once all are done.
///
/// The direct runs go side by side with the kernel pass, each with its own
/// factorisation, rather than in lockstep with it as extra right-hand sides of one
/// solve: on the plate a supernodal solve of k right-hand sides costs about k/2.3
/// single solves at k = 11, so the pass and two checks in lockstep would take about as
/// long on one core as the three tasks take on two.
pub fn sweep(base: &Model, run: &RunOptions, opts: &SweepOptions) -> Result<SweepOutcome, StudyError> {
    let t0 = std::time::Instant::now();
    let all = points(&opts.varies);
    let mine: Vec<usize> = (0..all.len())
        .filter(|i| opts.shard.is_none_or(|(k, n)| i % n == k - 1))
        .collect();
    let checked: Vec<usize> = opts
        .checks
        .points(all.len(), deck_point(base, &opts.varies))
        .into_iter()
        .filter(|i| mine.contains(i))
        .collect();
    let bar = opts.progress.clone().unwrap_or_else(ProgressBar::hidden);
    if let Some(v) = opts.varies.iter().find(|v| !v.param.leaves_target()) {
        return Err(StudyError::Input(format!(
            "--vary {}: the parameter changes the target, whose kernels the convolution engine computes once",
            v.param.name()
        )));
    }
    let on = |engine| RunOptions {
        scheme: opts.scheme,
        engine,
        progress: None,
        ..run.clone()
    };
    let opts_conv = on(Engine::Convolution);
    let prepared = prepare(base, &opts_conv)?;
    let (model, sys) = (prepared.model.as_ref(), &prepared.system);
    let dt = run.dt.unwrap_or(model.time.dt);
    let steps = run.steps.unwrap_or(model.time.steps);
    // The modal engine's sweep: one reduction at the sweep's cutoff for the kernels,
    // the checked points stepped on the modal engine on that reduction.
    let modal = match run.engine {
        Engine::Modal => Some(modal_cutoff(model, &opts.varies, &run.modal)?),
        _ => None,
    };
    let opts_check = on(if modal.is_some() { Engine::Modal } else { Engine::Direct });
    bar.set_length((mine.len() + checked.len()) as u64);

    enum Done {
        Kernels,
        Direct(usize, RunResult, f64),
        Point(Vec<f64>, Option<RunResult>, f64),
    }
    // A modal sweep's reduction: made by the kernel pass, waited for by the checks.
    let reduction = std::sync::OnceLock::new();
    let reduced = |cut: &(f64, String)| {
        reduction
            .get_or_init(|| modal::reduce_at(model, sys, &run.modal, cut.clone(), None, &|_| {}))
            .as_ref()
            .map_err(RunError::clone)
    };
    let kernels = std::sync::OnceLock::new();
    let pass = || {
        kernels.get_or_init(|| match &modal {
            Some(cut) => {
                let r = reduced(cut)?;
                let mut k = Kernels::compute_modal(r, dt, steps, &ProgressBar::hidden())?;
                k.pass_s += r.truncation.reduction_s;
                Ok((k, CacheUse::Off, Some(r.truncation.clone())))
            }
            None => Kernels::for_run(
                model,
                sys,
                dt,
                steps,
                run.kernel_cache.as_deref(),
                &ProgressBar::hidden(),
            )
            .map(|(k, c)| (k, c, None)),
        })
    };
    let c = checked.len();
    let done = in_parallel(opts.jobs, 1 + c + mine.len(), |k| -> Result<Done, StudyError> {
        if k == 0 {
            pass();
            return Ok(Done::Kernels);
        }
        if k <= c {
            // A modal check waits for the reduction, untimed (the kernel pass's).
            if let Some(cut) = &modal {
                let _ = reduced(cut);
            }
            let t = std::time::Instant::now();
            let i = checked[k - 1];
            let r = point_model(model, &opts.varies, &all[i]).and_then(|m| match &modal {
                // Stepped on the modal engine with the sweep's reduction.
                Some(cut) => outputs(reduced(cut)?.run_point(&m, &opts_check)),
                None => outputs(run_model(&m, &opts_check)),
            });
            bar.inc(1);
            return r.map(|r| Done::Direct(i, r, t.elapsed().as_secs_f64()));
        }
        let i = mine[k - 1 - c];
        let Ok((kernels, _, _)) = pass() else {
            return Ok(Done::Kernels); // the pass's own error is reported below
        };
        let t = std::time::Instant::now();
        let r = point_model(model, &opts.varies, &all[i])
            .and_then(|m| outputs(kernels.run(&m, &opts_conv, &ProgressBar::hidden())));
        bar.inc(1);
        r.map(|conv| {
            let row = row(i, &all[i], &conv);
            let keep = checked.contains(&i).then_some(conv);
            Done::Point(row, keep, t.elapsed().as_secs_f64())
        })
    });
    bar.finish_and_clear();
    let (kernels, cache, truncation) = kernels.into_inner().expect("task 0 is the kernel pass")?;
    let (mut direct, mut checks_s, mut points_s) = (HashMap::new(), 0.0, 0.0);
    let mut rows = Vec::with_capacity(mine.len());
    let mut conv_checked = HashMap::new();
    for d in done {
        match d? {
            Done::Kernels => {}
            Done::Direct(i, r, s) => {
                checks_s += s;
                direct.insert(i, r);
            }
            Done::Point(row, keep, s) => {
                points_s += s;
                if let Some(conv) = keep {
                    conv_checked.insert(row[0] as usize, conv);
                }
                rows.push(row);
            }
        }
    }
    // The modal kernels' round-off is the field's ([`Scale::Family`]).
    let scale = if truncation.is_some() {
        Scale::Family
    } else {
        Scale::Column
    };
    for r in &mut rows {
        let i = r[0] as usize;
        if let (Some(d), Some(c)) = (direct.get(&i), conv_checked.get(&i)) {
            *r.last_mut().expect("a row ends with direct_check") =
                engine_difference(d, c, scale).map_or(f64::INFINITY, |w| w.0);
        }
    }
    let (direct_checks, worst_direct_check) = direct_checks(&rows);
    Ok(SweepOutcome {
        header: header(model, &opts.varies),
        direct_checks,
        worst_direct_check,
        rows,
        checked,
        kernel_pass_s: kernels.pass_s,
        kernel_cache: cache,
        checks_s,
        points_s,
        wall_s: t0.elapsed().as_secs_f64(),
        modal: truncation,
    })
}

/// The points of `sweep.csv` rows also run on the direct engine: how many, and the
/// largest difference (0 when none; `direct_check` is the last column, empty where a
/// point was not checked).
pub fn direct_checks(rows: &[Vec<f64>]) -> (usize, f64) {
    let checks = rows.iter().filter_map(|r| r.last().copied()).filter(|v| !v.is_nan());
    checks.fold((0, 0.0), |(n, worst), v| (n + 1, worst.max(v)))
}

/// `sweep.csv`: the header, then the rows; numbers in the shortest form that reads
/// back to the same f64, NaN as an empty field, the point number as an integer.
pub fn csv_bytes(header: &[String], rows: &[Vec<f64>]) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header).expect("in memory");
    for r in rows {
        w.write_record(r.iter().enumerate().map(|(j, v)| {
            if v.is_nan() {
                String::new()
            } else if j == 0 {
                format!("{}", *v as u64)
            } else {
                format!("{v:e}")
            }
        }))
        .expect("in memory");
    }
    w.into_inner().expect("in memory")
}

/// Reads a `sweep.csv` back: header and rows (empty fields as NaN).
pub fn read_csv(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), StudyError> {
    let bad = |what: String| StudyError::Input(format!("{}: {what}", path.display()));
    let mut r = csv::Reader::from_path(path).map_err(|e| bad(e.to_string()))?;
    let header: Vec<String> = r
        .headers()
        .map_err(|e| bad(e.to_string()))?
        .iter()
        .map(String::from)
        .collect();
    let mut rows = Vec::new();
    for (k, rec) in r.records().enumerate() {
        let rec = rec.map_err(|e| bad(e.to_string()))?;
        let row = rec
            .iter()
            .map(|f| if f.is_empty() { Ok(f64::NAN) } else { f.parse::<f64>() })
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|e| bad(format!("row {}: {e}", k + 2)))?;
        rows.push(row);
    }
    Ok((header, rows))
}

/// Merges shards' `sweep.csv` files: the same header in each, every point once, in
/// point order; `total` points in all when given.
pub fn collect(
    parts: &[(Vec<String>, Vec<Vec<f64>>)],
    total: Option<usize>,
) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    let Some((header, _)) = parts.first() else {
        return Err("no shards to collect".into());
    };
    if let Some(k) = parts.iter().position(|(h, _)| h != header) {
        return Err(format!("shard {} has other columns than the first", k + 1));
    }
    let mut rows: Vec<Vec<f64>> = parts.iter().flat_map(|(_, r)| r.iter().cloned()).collect();
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    for w in rows.windows(2) {
        if w[0][0] == w[1][0] {
            return Err(format!("point {} is in two shards", w[0][0]));
        }
    }
    if let Some(n) = total {
        let missing: Vec<usize> = (0..n).filter(|i| !rows.iter().any(|r| r[0] == *i as f64)).collect();
        if !missing.is_empty() {
            return Err(format!(
                "{} of {n} points missing (first: {})",
                missing.len(),
                missing[0]
            ));
        }
    }
    Ok((header.clone(), rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: `--vary` reads ranges (even or geometric) and lists, and refuses the rest.
    #[test]
    fn vary_reads_ranges_and_lists() {
        let v = Vary::parse("velocity=100:300:3", &[]).unwrap();
        assert_eq!((v.param, v.values), (Param::Velocity, vec![100.0, 200.0, 300.0]));
        let v = Vary::parse("k=1e5:1e7:3", &["k".into()]).unwrap();
        assert!((v.values[1] - 1e6).abs() < 1e-6, "{:?}", v.values);
        let v = Vary::parse("exponent=1.5,1.4", &[]).unwrap();
        assert_eq!(v.values, vec![1.5, 1.4]);
        let err = |t: &str| Vary::parse(t, &[]).unwrap_err();
        assert!(matches!(err("speed=1:2:3"), VaryError::Parameter { name, .. } if name == "speed"));
        assert_eq!(err("velocity"), VaryError::Form("velocity".into()));
        assert_eq!(err("velocity=1:2"), VaryError::Form("velocity=1:2".into()));
        assert!(matches!(err("velocity=-1,2"), VaryError::Value { value, .. } if value == "-1"));
        assert_eq!(err("mass=1:2:0"), VaryError::Count("mass=1:2:0".into()));
        assert!(matches!(err("k=NaN"), VaryError::Value { .. }));
        assert_eq!(
            err("mass=1:2:0").to_string(),
            "--vary mass=1:2:0: COUNT must be 1 to 100000"
        );
    }

    /// Goal: the default self-check is the first and the last point, plus the deck's
    /// point; `every` adds every N-th; a spread of k points includes both ends; off
    /// is off, whatever the deck's point.
    #[test]
    fn self_check_points() {
        let d = SelfCheck::default();
        assert_eq!(d.points(100, None), vec![0, 99]);
        assert_eq!(d.points(100, Some(37)), vec![0, 37, 99]);
        assert_eq!(d.points(100, Some(99)), vec![0, 99]);
        assert_eq!(d.points(1, None), vec![0]);
        let every = SelfCheck {
            every: Some(30),
            ..Default::default()
        };
        assert_eq!(every.points(100, None), vec![0, 30, 60, 90, 99]);
        let spread = SelfCheck { spread: 4, every: None };
        assert_eq!(spread.points(10, None), vec![0, 3, 6, 9]);
        assert_eq!(SelfCheck { spread: 1, every: None }.points(10, None), vec![9]);
        assert!(SelfCheck::OFF.points(100, Some(37)).is_empty());
    }

    /// Goal: the deck's point is the point nearest the deck's own values, and there is
    /// none when a varied parameter's values do not span the deck's value. Model: the
    /// paper's rod (impactor at 62.1 in/s).
    #[test]
    fn the_deck_point_is_the_nearest_when_the_sweep_spans_the_deck() {
        let rod = crate::paper::rod_model().unwrap();
        let v = |spec: &str| Vary::parse(spec, &[]).unwrap();
        assert_eq!(deck_point(&rod, &[v("velocity=10:100:10")]), Some(5)); // 60 is nearest 62.1
        assert_eq!(deck_point(&rod, &[v("velocity=70:100:4")]), None);
        let mass = rod.contact.as_ref().unwrap().impactor.mass;
        let grid = [
            v("velocity=10:100:10"),
            v(&format!("mass={},{}", mass / 2.0, mass * 1.5)),
        ];
        let i = deck_point(&rod, &grid).unwrap();
        assert_eq!(points(&grid)[i][0], 60.0);
    }

    /// Goal: points are the Cartesian product, the first parameter slowest.
    #[test]
    fn points_vary_the_first_parameter_slowest() {
        let a = Vary {
            param: Param::Velocity,
            values: vec![1.0, 2.0],
        };
        let b = Vary {
            param: Param::K,
            values: vec![10.0, 20.0, 30.0],
        };
        let p = points(&[a, b]);
        assert_eq!(p.len(), 6);
        assert_eq!(p[0], vec![1.0, 10.0]);
        assert_eq!(p[1], vec![1.0, 20.0]);
        assert_eq!(p[3], vec![2.0, 10.0]);
    }
}

/// What the figures of a sweep need beyond `sweep.csv`: the deck's units and the
/// impactor's mass where it is not varied.
#[derive(Debug, Clone)]
pub struct FigureContext {
    /// The deck's name.
    pub deck: String,
    /// The impactor's mass, for the impact energy of points that do not vary it.
    pub mass: f64,
    /// Units of the deck: length, force, time.
    pub units: crate::run::UnitSystem,
    /// The kernels came from the modal reduction, and the ringed points ran on the
    /// modal engine (`--engine modal`).
    pub modal: bool,
}

impl FigureContext {
    /// The figures' footer: the deck, the engines, and `more`.
    fn footer(&self, more: &str) -> String {
        let engines = if self.modal {
            "convolution engine, modal kernels; ringed: also run on the modal engine"
        } else {
            "convolution engine; ringed: also run on the direct engine"
        };
        format!("impactlab sweep · {} · {engines}{more}", self.deck)
    }
}

/// The figures of a sweep, from its `sweep.csv` alone: peak force, contact duration,
/// transferred fraction, the energy a hysteretic contact dissipated (when it has that
/// column) and the largest |strain| of the strain outputs against the impact
/// energy ½mv², one line per combination of the other varied parameters, the points
/// also run on the direct (or modal) engine ringed. Written as `DIR/<name>.png` and `.svg`.
pub fn figures(
    header: &[String],
    rows: &[Vec<f64>],
    cx: &FigureContext,
    dir: &Path,
) -> Result<Vec<std::path::PathBuf>, crate::plot::PlotError> {
    use crate::plot::{line_chart, Chart, Line};
    let col = |name: &str| header.iter().position(|h| h == name);
    if let Some(maps) = grid_maps(header, rows, cx, dir)? {
        return Ok(maps);
    }
    let (Some(vcol), Some(check)) = (col("velocity"), col("direct_check")) else {
        return Ok(Vec::new()); // no impact energy axis without a velocity sweep
    };
    let mcol = col("mass");
    let energy = |r: &[f64]| 0.5 * mcol.map_or(cx.mass, |j| r[j]) * r[vcol] * r[vcol];
    // Lines: one per combination of the varied parameters other than velocity and mass.
    let others: Vec<usize> = (1..header.len())
        .take_while(|&j| header[j] != RESULT_COLUMNS[0])
        .filter(|&j| j != vcol && Some(j) != mcol)
        .collect();
    let key = |r: &[f64]| others.iter().map(|&j| r[j]).collect::<Vec<f64>>();
    let mut groups: Vec<(Vec<f64>, Vec<&Vec<f64>>)> = Vec::new();
    for r in rows {
        match groups.iter_mut().find(|(k, _)| *k == key(r)) {
            Some((_, g)) => g.push(r),
            None => groups.push((key(r), vec![r])),
        }
    }
    let u = &cx.units;
    let label = |k: &[f64]| {
        if k.is_empty() {
            "sweep".to_string()
        } else {
            others
                .iter()
                .zip(k)
                .map(|(&j, v)| format!("{} = {v:e}", header[j]))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    // Lines of column j (its magnitude when `abs`), colours from `colour0` on.
    let lines_of = |j: usize, name: &str, colour0: usize, abs: bool| -> Vec<Line> {
        groups
            .iter()
            .enumerate()
            .map(|(g, (k, rs))| {
                let mut rs: Vec<&&Vec<f64>> = rs.iter().filter(|r| r[j].is_finite()).collect();
                rs.sort_by(|a, b| energy(a).total_cmp(&energy(b)));
                let rings = rs
                    .iter()
                    .enumerate()
                    .filter(|(_, r)| !r[check].is_nan())
                    .map(|(i, _)| i)
                    .collect();
                let title = if name.is_empty() {
                    label(k)
                } else {
                    format!("{name}, {}", label(k))
                };
                let y = rs.iter().map(|r| if abs { r[j].abs() } else { r[j] }).collect();
                Line::new(title, rs.iter().map(|r| energy(r)).collect(), y, colour0 + g)
                    .markers()
                    .emphasis(rings)
            })
            .collect()
    };
    let x_label = format!("impact energy ½mv² [{}]", u.energy);
    let footer = cx.footer("");
    let chart = |title: &str, y: String, lines: Vec<Line>| Chart {
        title: title.into(),
        x_label: x_label.clone(),
        y_label: y,
        footer: footer.clone(),
        lines,
        ..Default::default()
    };
    let mut out = Vec::new();
    for (name, title, y) in result_figures(u) {
        if let Some(j) = col(name) {
            let lines = lines_of(j, "", 0, false);
            out.extend(line_chart(&chart(title, y, lines), &dir.join(name.replace('_', "-")))?);
        }
    }
    // At most as many lines as the palette has colours.
    let strains: Vec<usize> = (0..header.len())
        .filter(|&j| header[j].starts_with("peak_strain_"))
        .take((crate::plot::PALETTE.len() / groups.len().max(1)).max(1))
        .collect();
    if !strains.is_empty() {
        let lines = strains
            .iter()
            .enumerate()
            .flat_map(|(s, &j)| lines_of(j, header[j].trim_start_matches("peak_"), s * groups.len(), true))
            .collect();
        out.extend(line_chart(
            &chart("Largest strain at each gage", "largest |strain| [-]".into(), lines),
            &dir.join("strain-peaks"),
        )?);
    }
    Ok(out)
}

/// The results a sweep draws, each when `sweep.csv` has its column: column, title,
/// and the quantity with its unit.
fn result_figures(u: &crate::run::UnitSystem) -> [(&'static str, &'static str, String); 4] {
    [
        ("peak_force", "Peak contact force", format!("peak force [{}]", u.force)),
        (
            "contact_end",
            "End of the first contact",
            format!("contact end [{}]", u.time),
        ),
        (
            "transferred_fraction",
            "Energy left in the target",
            "1 − (v_rebound/v0)² [-]".to_string(),
        ),
        (
            "dissipated_contact",
            "Energy the contact dissipated",
            format!("D_c [{}]", u.energy),
        ),
    ]
}

/// A parameter's axis label, with its unit in the deck's units.
fn param_label(name: &str, u: &crate::run::UnitSystem) -> String {
    match name {
        "velocity" => format!("impact velocity [{}/{}]", u.length, u.time),
        "mass" => format!("impactor mass [{}]", u.mass),
        "k" => format!("Hertz K [{}/{}^exponent]", u.force, u.length),
        _ => format!("{name} [-]"),
    }
}

/// The maps of a grid sweep (exactly two varied parameters, each over at least three
/// values): peak force, end of the first contact and the energy left in the target
/// over the two parameters, the points also run on the direct engine ringed. `None`
/// for any other sweep (its figures are line charts).
fn grid_maps(
    header: &[String],
    rows: &[Vec<f64>],
    cx: &FigureContext,
    dir: &Path,
) -> Result<Option<Vec<std::path::PathBuf>>, crate::plot::PlotError> {
    use crate::plot::{heat_map, HeatMap};
    let varied: Vec<usize> = (1..header.len())
        .take_while(|&j| header[j] != RESULT_COLUMNS[0])
        .collect();
    let axis = |j: usize| {
        let mut v: Vec<f64> = rows.iter().map(|r| r[j]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    let [a, b] = varied[..] else {
        return Ok(None);
    };
    let (x, y) = (axis(a), axis(b));
    if x.len() < 3 || y.len() < 3 {
        return Ok(None);
    }
    let check = header.len() - 1;
    let at = |v: &[f64], t: f64| v.binary_search_by(|p| p.total_cmp(&t)).expect("a grid value");
    let rings: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| !r[check].is_nan())
        .map(|r| (r[a], r[b]))
        .collect();
    let u = &cx.units;
    let mut out = Vec::new();
    for (name, title, unit) in result_figures(u) {
        let Some(j) = header.iter().position(|h| h == name) else {
            continue;
        };
        let mut values = vec![f64::NAN; x.len() * y.len()];
        for r in rows {
            values[at(&y, r[b]) * x.len() + at(&x, r[a])] = r[j];
        }
        let map = HeatMap {
            title: format!("{title} over {} × {} points", x.len(), y.len()),
            x_label: param_label(&header[a], u),
            x: x.clone(),
            y_label: param_label(&header[b], u),
            y: y.clone(),
            unit,
            values,
            rings: rings.clone(),
            footer: cx.footer("; grey: no value; white lines at 1/5 … 4/5 of the range"),
        };
        out.extend(heat_map(&map, &dir.join(format!("{}-map", name.replace('_', "-"))))?);
    }
    Ok(Some(out))
}
