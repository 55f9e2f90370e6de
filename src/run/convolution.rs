//! A run on the convolution engine ([`crate::integrate::convolution`]): the kernel
//! pass, the contact history, then the requested outputs rebuilt as history sums.
//!
//! What it computes, and how:
//! - contact force, indentation, impactor displacement and velocity: every step,
//!   exactly as the direct scheme defines them;
//! - every `history.csv` column: its own kernel, recorded in the one linear pass,
//!   convolved with the loads at the rows written (plus the impactor's part);
//! - the ledger: the impactor's KE_i and SE_i exactly, the target's total from the
//!   discrete work identity, the external work of a non-conservative contact and the
//!   momentum from their kernels; KE_t, its Eq. 16 form and SE_t are not computed
//!   (NaN): they need the whole field.
//!
//! Field snapshots need the whole field too: this engine refuses them.

use super::modal::Reduction;
use super::{
    history_columns, history_row, linear_outputs, summarize, Engine, GuardTrip, RowHead, RunError, RunOptions,
    RunResult, Series,
};
use crate::assembly::System;
use crate::integrate::convolution::{
    contact_history, unit_response, ConvStep, Convolver, NotConvolvable, RunFailure, Spectrum, UnitResponse,
};
use crate::integrate::ContactForm;
use crate::integrate::RunStats;
use crate::ledger::EnergyRow;
use crate::model::{apply, Contact, Model};
use indicatif::ProgressBar;

impl From<RunFailure> for RunError {
    fn from(e: RunFailure) -> Self {
        match e {
            RunFailure::Model(m) => RunError::Engine(m.to_string()),
            RunFailure::Solve(s) => RunError::Solve(s),
        }
    }
}

/// Runs a prepared model ([`super::prepare`]) on the convolution engine.
pub fn run(model: &Model, sys: &System, opts: &RunOptions) -> Result<RunResult, RunError> {
    let t0 = std::time::Instant::now();
    let dt = opts.dt.unwrap_or(model.time.dt);
    let steps = opts.steps.unwrap_or(model.time.steps);
    let bar = opts.progress.clone().unwrap_or_else(ProgressBar::hidden);
    bar.set_length(2 * steps as u64);
    bar.set_position(0);
    // The bar's clock (its rate and estimate) starts with the stepping.
    bar.reset_elapsed();
    let (kernels, cache) = Kernels::for_run(model, sys, dt, steps, opts.kernel_cache.as_deref(), &bar)?;
    let mut run = kernels.run(model, opts, &bar)?;
    run.summary.run.kernel_cache = (cache != CacheUse::Off).then_some(cache);
    bar.finish_and_clear();
    run.stats.total_time = t0.elapsed();
    run.summary.run.wall_s = run.stats.total_time.as_secs_f64();
    Ok(run)
}

/// The history's linear outputs of a state (u, v) of the system a kernel pass runs on.
type Outputs<'a> = dyn Fn(&[f64], &[f64]) -> Vec<f64> + 'a;

/// The kernels of a model's convolution runs: computed once ([`Kernels::compute`]),
/// reused by every run of the same target, Δt and steps whose impactor (mass,
/// velocity) or contact law (K, exponent) differs ([`Kernels::run`]): those are
/// outside the target's linear system (a K scaled by s scales every kernel by s, the
/// work's by s²).
pub struct Kernels {
    response: UnitResponse,
    /// Kernels by column: `columns[c][k − 1]` is output c at step k; the history's
    /// linear outputs, then the target's momentum, then its non-conservative work
    /// functional.
    columns: Vec<Vec<f64>>,
    /// The Hertz K the kernels were computed with.
    stiffness: f64,
    dt: f64,
    steps: usize,
    /// Wall-clock seconds of the kernel pass.
    pub pass_s: f64,
    /// The kernels' spectra, made by the first run.
    spectra: std::sync::OnceLock<Spectra>,
}

/// Where a run's kernels came from.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CacheUse {
    /// Computed; no cache asked for.
    Off,
    /// Read from the cache.
    Hit,
    /// Computed and stored: the cache had none.
    Miss,
    /// Computed and stored again: the cached file could not be used (why).
    Recomputed(String),
    /// Computed, but the cache could not store them (why: a full disk, a directory
    /// that cannot be written); the run goes on without.
    NotStored(String),
}

/// The version of the kernel file format; a file of another version is recomputed.
const CACHE_FORMAT: u32 = 1;
const CACHE_MAGIC: &[u8; 18] = b"impactlab-kernels\n";

impl Kernels {
    /// The kernels of a model: through the cache in `cache` when given
    /// ([`Kernels::cached`]), computed otherwise.
    pub fn for_run(
        model: &Model,
        sys: &System,
        dt: f64,
        steps: usize,
        cache: Option<&std::path::Path>,
        bar: &ProgressBar,
    ) -> Result<(Kernels, CacheUse), RunError> {
        match cache {
            Some(dir) => Kernels::cached(model, sys, dt, steps, dir, bar),
            None => Ok((Kernels::compute(model, sys, dt, steps, bar)?, CacheUse::Off)),
        }
    }

    /// The kernels of a model from the cache directory `dir` when a file there holds
    /// them for exactly this input, else computed and stored (atomically). The file is
    /// named by a SHA-256 of everything the kernels depend on: the format version, Δt,
    /// steps, the deck's SHA-256, the solved DOFs, K, M (the impactor's excluded),
    /// the contact operator and the non-conservative part, and the output columns.
    /// A file that is truncated, corrupt (its own SHA-256 fails) or of another
    /// format is recomputed, and the reason returned, never read as data; kernels
    /// the cache cannot store are used all the same ([`CacheUse::NotStored`]).
    pub fn cached(
        model: &Model,
        sys: &System,
        dt: f64,
        steps: usize,
        dir: &std::path::Path,
        bar: &ProgressBar,
    ) -> Result<(Kernels, CacheUse), RunError> {
        let key = cache_key(model, sys, dt, steps);
        let path = dir.join(format!("{key}.kernels"));
        let why = match std::fs::read(&path) {
            Ok(bytes) => match decode(&bytes, &key, dt, steps) {
                Ok(k) => return Ok((k, CacheUse::Hit)),
                Err(why) => Some(format!("{}: {why}", path.display())),
            },
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => Some(format!("{}: {e}", path.display())),
        };
        let k = Kernels::compute(model, sys, dt, steps, bar)?;
        // Written whole beside its final name, then renamed: a reader sees the old
        // file or the new one, never a part.
        let store = || -> std::io::Result<()> {
            use std::io::Write;
            std::fs::create_dir_all(dir)?;
            let mut tmp = tempfile::NamedTempFile::new_in(dir)?;
            tmp.write_all(&encode(&k, &key))?;
            tmp.as_file().sync_all()?;
            tmp.persist(&path).map_err(|e| e.error)?;
            Ok(())
        };
        if let Err(e) = store() {
            return Ok((k, CacheUse::NotStored(format!("{}: {e}", path.display()))));
        }
        Ok((k, why.map_or(CacheUse::Miss, CacheUse::Recomputed)))
    }

    /// The kernel pass of a model (the base of a family of runs).
    pub fn compute(model: &Model, sys: &System, dt: f64, steps: usize, bar: &ProgressBar) -> Result<Kernels, RunError> {
        let t0 = std::time::Instant::now();
        if model.contact.is_some() && sys.m_lumped.is_none() {
            // The pass itself takes a coupled mass (the modal kernels' is dense); a
            // deck's coupled mass (offset beams and masses) stays on the direct
            // engine (the threshold search falls back to it).
            return Err(RunFailure::Model(NotConvolvable("its mass matrix is not lumped".into())).into());
        }
        Kernels::pass(
            model,
            sys,
            &model.momentum_weights(),
            &|u, v| linear_outputs(model, u, v),
            (dt, steps, t0),
            bar,
        )
    }

    /// The kernel pass of a model's modal reduction ([`super::modal::reduce`]): the same
    /// kernels of the reduced model, the outputs read from its coordinates. With them
    /// every run is the modal engine's run of the same point to round-off, at the cost
    /// of one reduction and a pass on the reduced system.
    pub fn compute_modal(r: &Reduction, dt: f64, steps: usize, bar: &ProgressBar) -> Result<Kernels, RunError> {
        Kernels::pass(
            &r.model,
            &r.system,
            &r.momentum,
            &|q, qd| r.outputs(q, qd),
            (dt, steps, std::time::Instant::now()),
            bar,
        )
    }

    /// The kernel pass on a linear system (a model's own or its reduction's), the
    /// target's momentum along `direction` (weights on M v) and the history's
    /// outputs from `outputs`; `t0` the start of the clock of `pass_s`.
    fn pass(
        model: &Model,
        sys: &System,
        direction: &[f64],
        outputs: &Outputs,
        (dt, steps, t0): (f64, usize, std::time::Instant),
        bar: &ProgressBar,
    ) -> Result<Kernels, RunError> {
        let ct = model
            .contact
            .as_ref()
            .ok_or_else(|| RunError::Engine("the convolution engine needs a model with a contact".into()))?;
        // Functionals the ledger needs beyond the outputs, over the target's DOFs.
        let imp = ct.impactor.dof;
        let mut mw = vec![0.0; model.n()];
        sys.m_mul(direction, &mut mw);
        let target = model.target_mask();
        let momentum_t: Vec<(usize, f64)> = (0..model.n())
            .filter(|&i| target[i] && mw[i] != 0.0)
            .map(|i| (i, mw[i]))
            .collect();
        let nc_t: Vec<(usize, f64)> = ct.nonconservative.iter().copied().filter(|&(j, _)| j != imp).collect();
        let mut rows: Vec<Vec<f64>> = Vec::with_capacity(steps);
        let response = unit_response(model, sys, dt, steps, &mut |u, v| {
            let mut k = outputs(u, v);
            k.push(apply(&momentum_t, v));
            k.push(apply(&nc_t, u));
            rows.push(k);
            if rows.len() % 64 == 0 {
                bar.set_position(rows.len() as u64);
            }
        })?;
        let width = rows.first().map_or(2, Vec::len);
        let columns = (0..width).map(|c| rows.iter().map(|k| k[c]).collect()).collect();
        Ok(Kernels {
            response,
            columns,
            stiffness: ct.stiffness,
            dt,
            steps,
            pass_s: t0.elapsed().as_secs_f64(),
            spectra: Default::default(),
        })
    }

    /// The spectra of the columns' kernels and of the work's, computed by the first
    /// run that needs them and kept for the others.
    fn spectra(&self) -> &Spectra {
        self.spectra.get_or_init(|| {
            let fft = Convolver::new(self.steps);
            let columns = self.columns.iter().map(|c| fft.spectrum(c)).collect();
            let work = fft.spectrum(&self.response.work);
            Spectra { fft, columns, work }
        })
    }

    /// A run of `model` (the kernels' target, with any impactor and Hertz law) on
    /// these kernels; `opts` as for any run, its Δt and steps those of the kernels.
    ///
    /// Three stages: the contact history, step by step (the only causal part); then,
    /// from its finished loads, every output column and the ledger's w, work and
    /// momentum as full convolutions by FFT; then the ledger, whose energy guard, when
    /// it trips at step n, ends the run's outputs at step n as a direct run's would be.
    pub fn run(&self, model: &Model, opts: &RunOptions, bar: &ProgressBar) -> Result<RunResult, RunError> {
        let t0 = std::time::Instant::now();
        let (form, ct) = runnable(model, opts)?;
        // A K scaled by s scales every load, so every kernel (the work's by s²).
        let s = ct.stiffness / self.stiffness;
        let scaled;
        let kernel = if s == 1.0 {
            &self.response
        } else {
            scaled = self.response.scaled(s);
            &scaled
        };
        let mut rec = ContactRecord::run(model, ct, form, kernel, self.steps, opts, bar)?;
        // Everything linear in the loads, as convolutions: y(n) = conv[n − 1], y(0) = 0.
        let spectra = self.spectra();
        let loads = spectra.fft.spectrum(&rec.p);
        let width = self.columns.len();
        let conv = |c: usize| {
            spectra
                .fft
                .convolve(&spectra.columns[c], &loads, if c == width - 1 { s * s } else { s })
        };
        let (energy, tripped) = if opts.ledger {
            let w = spectra.fft.convolve(&spectra.work, &loads, s * s);
            ledger(
                ct,
                model.damped(),
                &rec.steps_done,
                &w,
                &conv(width - 2),
                &conv(width - 1),
                opts.max_energy_error,
            )
        } else {
            (Vec::new(), None)
        };
        if let Some(trip) = &tripped {
            rec.truncate(trip.step);
        }
        let columns: Vec<Vec<f64>> = (0..width - 2).map(conv).collect();
        let history = history_rows(model, ct, &rec.heads, &columns);
        let stats = RunStats {
            steps: rec.p.len(),
            factorizations: kernel.costs.factorizations,
            solves: kernel.costs.solves,
            contact_iterations: rec.steps_done.iter().map(|c| c.iterations).sum(),
            factor_time: kernel.costs.factor_time,
            solve_time: kernel.costs.solve_time,
            total_time: t0.elapsed(),
            assembly_time: Default::default(),
        };
        let mut run = RunResult {
            scheme: opts.scheme,
            dt: self.dt,
            steps: self.steps,
            stats,
            series: rec.series,
            energy,
            history_columns: history_columns(model),
            history,
            summary: Default::default(),
            dofs: model.dofs.clone(),
            snapshots: Vec::new(),
        };
        run.summary = summarize(model, &run, tripped, opts, Engine::Convolution)?;
        match tripped {
            None => Ok(run),
            Some(trip) => Err(RunError::EnergyGuard {
                trip,
                partial: Box::new(run),
            }),
        }
    }
}

/// y(n) of a convolution's output `y` (y(0) = 0, y(n) = y[n − 1]).
fn at(y: &[f64], n: usize) -> f64 {
    if n == 0 {
        0.0
    } else {
        y[n - 1]
    }
}

/// What the convolution engine can run: a trapezoidal scheme's contact form, no field
/// snapshots, a model with a contact and no dynamic load.
fn runnable<'m>(model: &'m Model, opts: &RunOptions) -> Result<(ContactForm, &'m Contact), RunError> {
    if let Some(ex) = &model.excitation {
        return Err(RunError::Engine(format!(
            "the convolution engine sums the response to the contact alone; this model also has a dynamic load \
             ({}): run it on the direct engine",
            ex.source
        )));
    }
    let form = opts.scheme.newmark_params().map(|p| p.contact).ok_or_else(|| {
        RunError::Engine(format!(
            "the convolution engine runs the trapezoidal schemes (newmark, energy), not {}",
            opts.scheme
        ))
    })?;
    if !opts.snapshot_times.is_empty() {
        return Err(RunError::Engine(
            "field snapshots need the whole field: run them on the direct engine".into(),
        ));
    }
    let ct = model
        .contact
        .as_ref()
        .ok_or_else(|| RunError::Engine("the convolution engine needs a model with a contact".into()))?;
    Ok((form, ct))
}

/// The contact history of a convolution run: the series every step, the heads of the
/// history rows, every step's state, and the loads.
struct ContactRecord {
    series: Series,
    heads: Vec<(usize, RowHead)>,
    steps_done: Vec<ConvStep>,
    p: Vec<f64>,
}

impl ContactRecord {
    /// The contact history, with its planned stop (after separation, when asked).
    fn run(
        model: &Model,
        ct: &Contact,
        form: ContactForm,
        kernel: &UnitResponse,
        steps: usize,
        opts: &RunOptions,
        bar: &ProgressBar,
    ) -> Result<ContactRecord, RunError> {
        let mut series = Series::default();
        let mut heads: Vec<(usize, RowHead)> = Vec::new();
        let mut steps_done: Vec<ConvStep> = Vec::with_capacity(steps + 1);
        let every = model.time.every.max(1);
        let (mut in_contact, mut separated_at) = (false, None::<f64>);
        let mut observe = |c: &ConvStep| {
            let force = ct.stiffness * c.load_factor;
            series.time.push(c.time);
            series.alpha.push(c.alpha);
            series.force.push(force);
            series.impactor_u.push(c.x);
            series.impactor_v.push(c.xv);
            steps_done.push(*c);
            if c.step % every == 0 {
                heads.push((
                    c.step,
                    RowHead {
                        time: c.time,
                        force,
                        alpha: c.alpha,
                        impactor_u: c.x,
                        impactor_v: c.xv,
                        load_factor: c.load_factor,
                    },
                ));
            }
            if ct.closed(c.alpha, c.load_factor) {
                in_contact = true;
            } else if in_contact && separated_at.is_none() {
                separated_at = Some(c.time);
            }
            if c.step % 64 == 0 {
                bar.set_position((steps + c.step) as u64);
            }
            let done = matches!((separated_at, opts.stop_after_separation), (Some(t), Some(w)) if c.time >= t + w);
            Ok(!done)
        };
        let (p, _) = contact_history(model, form, kernel, steps, &mut observe)?;
        Ok(ContactRecord {
            series,
            heads,
            steps_done,
            p,
        })
    }

    /// Ends the record at step `last` (where the energy guard tripped), as a direct
    /// run's would end.
    fn truncate(&mut self, last: usize) {
        let kept = last + 1;
        let s = &mut self.series;
        for v in [
            &mut s.time,
            &mut s.alpha,
            &mut s.force,
            &mut s.impactor_u,
            &mut s.impactor_v,
        ] {
            v.truncate(kept);
        }
        self.steps_done.truncate(kept);
        self.heads.retain(|(n, _)| *n <= last);
        self.p.truncate(last);
    }
}

/// The ledger of a convolution run from the target's work `w`, momentum and
/// non-conservative work convolutions, and where its energy guard (`limit`) stops
/// the run. The target's energy is the contact's work on it: for a `damped` target,
/// its energy together with what its damping dissipated, which this identity cannot
/// split, so its rows give D as NaN (not known apart) and their total holds it, with
/// what the impactor's own damping took.
fn ledger(
    ct: &Contact,
    damped: bool,
    steps_done: &[ConvStep],
    w: &[f64],
    momentum_t: &[f64],
    nc_t: &[f64],
    limit: Option<f64>,
) -> (Vec<EnergyRow>, Option<GuardTrip>) {
    let mut energy: Vec<EnergyRow> = Vec::with_capacity(steps_done.len());
    let imp = ct.impactor.dof;
    let nc_imp: f64 = ct
        .nonconservative
        .iter()
        .filter(|&&(j, _)| j == imp)
        .map(|&(_, r)| r)
        .sum();
    let mass = ct.impactor.mass;
    let (mut target_energy, mut external, mut initial) = (0.0, 0.0, None);
    for c in steps_done {
        let n = c.step;
        if n > 0 {
            let prev = &steps_done[n - 1];
            target_energy += (at(w, n) - at(w, n - 1)) * c.work_factor;
            external += (nc_imp * (c.x - prev.x) + (at(nc_t, n) - at(nc_t, n - 1))) * c.work_factor;
        }
        let ke_i = 0.5 * mass * c.xv * c.xv;
        let u0 = *initial.get_or_insert(ke_i + c.contact.stored + target_energy);
        let momentum = mass * c.xv + at(momentum_t, n);
        // The target's energy with what its damping took, and the impactor's damping's.
        let held = target_energy + c.impactor_dissipated;
        let mut row = EnergyRow::with_target_total(c.time, ke_i, c.contact, held, external, u0, momentum);
        if damped {
            row.dissipated_damping = f64::NAN;
        }
        let trip = limit
            .filter(|&limit| row.error.abs() > limit || row.error.is_nan())
            .map(|limit| GuardTrip {
                step: n,
                time: c.time,
                error: row.error,
                limit,
            });
        energy.push(row);
        if trip.is_some() {
            return (energy, trip);
        }
    }
    (energy, None)
}

/// The history rows: the impactor's part of each linear output plus the target's
/// convolution `columns`.
fn history_rows(model: &Model, ct: &Contact, heads: &[(usize, RowHead)], columns: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let (mut u_imp, mut v_imp) = (model.u0.clone(), model.v0.clone());
    let imp = ct.impactor.dof;
    heads
        .iter()
        .map(|(n, h)| {
            u_imp[imp] = h.impactor_u;
            v_imp[imp] = h.impactor_v;
            let mut linear = linear_outputs(model, &u_imp, &v_imp);
            for (y, c) in linear.iter_mut().zip(columns) {
                *y += at(c, *n);
            }
            history_row(model, h, &linear)
        })
        .collect()
}

/// The kernels' spectra for [`Convolver`]: the output columns' (momentum and the
/// non-conservative work last) and the work's.
struct Spectra {
    fft: Convolver,
    columns: Vec<Spectrum>,
    work: Spectrum,
}

/// How far a run on the convolution engine is from the same run on the direct one:
/// the largest difference of the contact force (every step) and of each history
/// column, relative to its peak, with what and when; `None` when the runs did not
/// make the same number of steps. A column below 1e-8 of the peak of the columns in
/// its unit vanishes in exact arithmetic (the shear on the plate's centre lines, by
/// symmetry): its own peak is round-off, and it is compared with that larger peak.
///
/// With [`Scale::Family`] every column is compared with its family's peak: the scale of
/// a reduced model's round-off, whose outputs are sums over its coordinates of terms
/// the size of the field ([`super::modal`]). A column its truncation leaves small
/// but not zero (the paper's plate's in-plane shear at the centre: zero by symmetry
/// on the mesh, 1.7e-4 of the normal strains in the reduced model) agrees to 7.9e-10
/// of its own peak, every column to 8.1e-13 of its family's (tests/modal.rs).
pub fn engine_difference(direct: &RunResult, conv: &RunResult, by: Scale) -> Option<(f64, String, f64)> {
    let units = &direct.summary.units;
    if conv.history.len() != direct.history.len() || conv.series.force.len() != direct.series.force.len() {
        return None;
    }
    let peak = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0, |a: f64, x| a.max(x.abs()));
    // (relative difference, what, time) of the force and of each history column.
    let mut worst = (0.0, String::new(), 0.0);
    let mut judge = |what: String, scale: f64, a: &[f64], b: &[f64], t: &[f64]| {
        for k in 0..a.len() {
            let d = (a[k] - b[k]).abs() / scale.max(f64::MIN_POSITIVE);
            if d > worst.0 || d.is_nan() {
                worst = (d, what.clone(), t[k]);
            }
        }
    };
    let f_peak = peak(&mut direct.series.force.iter().copied());
    judge(
        "contact force (every step)".into(),
        f_peak,
        &direct.series.force,
        &conv.series.force,
        &direct.series.time,
    );
    let times: Vec<f64> = direct.history.iter().map(|r| r[0]).collect();
    let cols = &direct.history_columns;
    let column = |h: &[Vec<f64>], j: usize| h.iter().map(|r| r[j]).collect::<Vec<f64>>();
    let peaks: Vec<f64> = (0..cols.len())
        .map(|j| peak(&mut direct.history.iter().map(|r| r[j])))
        .collect();
    let unit: Vec<String> = cols.iter().map(|c| c.unit(units)).collect();
    for (j, c) in cols.iter().enumerate().skip(1) {
        let family = (0..cols.len())
            .filter(|&i| unit[i] == unit[j])
            .map(|i| peaks[i])
            .fold(0.0, f64::max);
        // A column below 1e-8 of its family's peak is zero in exact arithmetic (by
        // symmetry): its own peak is round-off, so the family's is the scale.
        let scale = if peaks[j] < 1e-8 * family || by == Scale::Family {
            family
        } else {
            peaks[j]
        };
        let (a, b) = (column(&direct.history, j), column(&conv.history, j));
        judge(c.header(units), scale, &a, &b, &times);
    }
    Some(worst)
}

/// What [`engine_difference`] measures a history column's difference against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Its own peak (its family's when it vanishes by symmetry).
    Column,
    /// The peak of its family: the columns in its unit.
    Family,
}

/// The SHA-256 (hex) of everything a model's kernels depend on.
fn cache_key(model: &Model, sys: &System, dt: f64, steps: usize) -> String {
    use sha2::{Digest, Sha256};
    let mut h = Sha256::new();
    let mut f = |x: f64| h.update(x.to_bits().to_le_bytes());
    f(CACHE_FORMAT as f64);
    f(dt);
    f(steps as f64);
    let imp: Vec<usize> = model.contact.as_ref().map_or(Vec::new(), |c| c.impactor.dofs.clone());
    let m = sys.m_diag();
    for (i, d) in model.dofs.iter().enumerate() {
        f(d.point as f64);
        f(d.comp as f64);
        f(if imp.contains(&i) { 0.0 } else { m[i] });
    }
    let k = &sys.k_csc;
    for &p in k.symbolic().col_ptr() {
        f(p as f64);
    }
    for &r in k.symbolic().row_idx() {
        f(r as f64);
    }
    for &v in k.val() {
        f(v);
    }
    // The damping, for a damped structure only (an undamped one's key is unchanged).
    for t in &sys.c {
        f(t.row as f64);
        f(t.col as f64);
        f(t.val);
    }
    if let Some(c) = &model.contact {
        for l in &c.loads {
            f(l.dof as f64);
            f(l.scale);
        }
        for &(j, w) in c.driver.iter().chain(&c.nonconservative) {
            f(j as f64);
            f(w);
        }
        f(c.stiffness);
    }
    let mut h2 = h;
    h2.update(model.deck_sha256.as_bytes());
    for c in history_columns(model) {
        h2.update(c.name().as_bytes());
        h2.update(b"\n");
    }
    h2.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// A kernel file: magic, format, key, Δt, steps, K, the kernels, then the SHA-256 of
/// all that.
fn encode(k: &Kernels, key: &str) -> Vec<u8> {
    use sha2::{Digest, Sha256};
    let mut b = Vec::new();
    b.extend_from_slice(CACHE_MAGIC);
    b.extend_from_slice(&CACHE_FORMAT.to_le_bytes());
    b.extend_from_slice(key.as_bytes());
    let mut put = |x: f64| b.extend_from_slice(&x.to_le_bytes());
    put(k.dt);
    put(k.steps as f64);
    put(k.stiffness);
    put(k.columns.len() as f64);
    for v in [&k.response.alpha, &k.response.work].into_iter().chain(&k.columns) {
        for x in v {
            put(*x);
        }
    }
    let sum = Sha256::digest(&b);
    b.extend_from_slice(&sum);
    b
}

/// Reads a kernel file written by [`encode`] for this key, Δt and steps, or says why not.
fn decode(b: &[u8], key: &str, dt: f64, steps: usize) -> Result<Kernels, String> {
    use sha2::{Digest, Sha256};
    if b.len() < CACHE_MAGIC.len() + 4 + 64 + 32 || &b[..CACHE_MAGIC.len()] != CACHE_MAGIC {
        return Err("not a kernel file".into());
    }
    let (body, sum) = b.split_at(b.len() - 32);
    if Sha256::digest(body).as_slice() != sum {
        return Err("corrupt or truncated (its checksum fails)".into());
    }
    let mut at = CACHE_MAGIC.len();
    let format = u32::from_le_bytes(body[at..at + 4].try_into().expect("4 bytes"));
    if format != CACHE_FORMAT {
        return Err(format!("format {format}, not {CACHE_FORMAT}"));
    }
    at += 4;
    if &body[at..at + 64] != key.as_bytes() {
        return Err("written for another input".into());
    }
    at += 64;
    let words: Vec<f64> = body[at..]
        .chunks(8)
        .map(|c| c.try_into().map(f64::from_le_bytes))
        .collect::<Result<_, _>>()
        .map_err(|_| "truncated".to_string())?;
    let [fdt, fsteps, stiffness, width, data @ ..] = &words[..] else {
        return Err("truncated".into());
    };
    let (n, w) = (*fsteps as usize, *width as usize);
    if *fdt != dt || n != steps || data.len() != (w + 2) * n {
        return Err("its sizes do not match".into());
    }
    let mut parts = data.chunks(n.max(1)).map(<[f64]>::to_vec);
    let mut next = || parts.next().unwrap_or_default();
    let (alpha, work) = (next(), next());
    Ok(Kernels {
        response: UnitResponse {
            dt,
            alpha,
            work,
            costs: Default::default(),
        },
        columns: (0..w).map(|_| next()).collect(),
        stiffness: *stiffness,
        dt,
        steps,
        pass_s: 0.0,
        spectra: Default::default(),
    })
}
