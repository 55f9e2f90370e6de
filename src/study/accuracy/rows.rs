//! The study's runs: the rod against the continuum and against a converged run, the
//! plate's time-step and mesh sweeps; each run timed and measured as a [`Row`].

use super::{Row, DT_FACTORS, PLATE_DT, PLATE_T_END, ROD_DT, ROD_T_END};
use crate::integrate::Scheme;
use crate::mesh::plate_model;
use crate::model::Model;
use crate::numerics::{interp, median};
use crate::physics::analytic;
use crate::run::{run_model, RunError, RunOptions, RunResult};
use crate::study::history_extreme;
use crate::study::StudyError;
use std::time::Instant;

/// Process peak resident memory so far (VmHWM), MB; NaN where /proc is unavailable.
fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse::<f64>().ok()))
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// A reference force history and its scalar measures.
struct Reference {
    t: Vec<f64>,
    f: Vec<f64>,
    duration: f64,
    peak: f64,
}

/// Relative L2 norm of F − F_ref over the reference's contact interval.
fn force_l2(run: &RunResult, r: &Reference) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (&t, &f) in r.t.iter().zip(&r.f).filter(|(t, _)| **t <= r.duration) {
        let d = interp(&run.series.time, &run.series.force, t) - f;
        num += d * d;
        den += f * f;
    }
    (num / den).sqrt()
}

/// A converged run of `model` (energy scheme at Δt/16 over `t_end`) and its force
/// history as a reference: what a scheme's step alone costs in accuracy is measured
/// against it.
fn converged(model: &Model, dt0: f64, t_end: f64) -> Result<(RunResult, Reference), StudyError> {
    let dt = dt0 / 16.0;
    let opts = RunOptions {
        scheme: Scheme::Energy,
        dt: Some(dt),
        steps: Some((t_end / dt).ceil() as usize),
        ..Default::default()
    };
    let run = run_model(model, &opts)?;
    let reference = Reference {
        t: run.series.time.clone(),
        f: run.series.force.clone(),
        duration: duration(&run),
        peak: peak(&run),
    };
    Ok((run, reference))
}

fn duration(run: &RunResult) -> f64 {
    run.summary.contact.duration.unwrap_or(f64::NAN)
}

fn peak(run: &RunResult) -> f64 {
    run.summary.contact.peak_force
}

/// Runs once to warm up, then `repeats` times; the last run and the median wall time.
fn timed(model: &Model, opts: &RunOptions, repeats: usize) -> Result<(RunResult, f64), RunError> {
    let mut walls = Vec::new();
    let mut last = None;
    for k in 0..=repeats {
        let t0 = Instant::now();
        let r = run_model(model, opts)?;
        if k > 0 {
            walls.push(t0.elapsed().as_secs_f64());
        }
        last = Some(r);
    }
    Ok((last.expect("at least one run"), median(walls)))
}

fn row(problem: &str, mesh: usize, run: &RunResult, wall: f64, r: &Reference, strain: f64) -> Row {
    Row {
        problem: problem.into(),
        scheme: run.scheme,
        dt_s: run.dt,
        mesh,
        error_contact_duration: (duration(run) / r.duration - 1.0).abs(),
        error_peak_force: (peak(run) / r.peak - 1.0).abs(),
        error_force_l2: force_l2(run, r),
        error_strain: strain,
        energy_error: run.summary.energy.max_relative_error.unwrap_or(f64::NAN),
        wall_s: wall,
        solves: run.stats.solves,
        factorizations: run.stats.factorizations,
        peak_rss_mb: peak_rss_mb(),
        note: String::new(),
    }
}

fn skipped(problem: &str, scheme: Scheme, dt: f64, mesh: usize, why: String) -> Row {
    Row {
        problem: problem.into(),
        scheme,
        dt_s: dt,
        mesh,
        error_contact_duration: f64::NAN,
        error_peak_force: f64::NAN,
        error_force_l2: f64::NAN,
        error_strain: f64::NAN,
        energy_error: f64::NAN,
        wall_s: f64::NAN,
        solves: 0,
        factorizations: 0,
        peak_rss_mb: f64::NAN,
        note: why,
    }
}

fn rod_model(n: usize) -> Result<Model, StudyError> {
    let text = crate::mesh::rod_deck(n)?;
    let mut m = crate::model_from_text(&format!("rod-{n}"), &text)?;
    m.time.every = 1;
    Ok(m)
}

/// The rod sweeps: schemes × Δt on the paper's 144 elements, and schemes × mesh at the
/// paper's Δt.
/// The rod's time step and mesh at the paper's settings: the semi-infinite rod (the
/// continuum) and a converged run of the same mesh (the step error alone) as references.
pub(super) fn rod_rows(repeats: usize, progress: &dyn Fn(&str)) -> Result<Vec<Row>, StudyError> {
    let r = RodStudy::new()?;
    let mut rows = r.dt_sweep(repeats, progress)?;
    rows.extend(r.mesh_sweep(repeats, progress)?);
    Ok(rows)
}

/// The rod study's model and references.
struct RodStudy {
    base: Model,
    rod: crate::model::RodInfo,
    trace: analytic::Trace,
    events: analytic::Events,
    lc: f64,
    reference: Reference,
    discrete: Reference,
}

impl RodStudy {
    fn new() -> Result<Self, StudyError> {
        let base = rod_model(144)?;
        let rod = base.rod.expect("a rod");
        let (tr, ev, lc) = crate::physics::references::semi_infinite(&base)?;
        let reference = Reference {
            t: tr.time.clone(),
            f: tr.force.clone(),
            duration: ev.contact_end,
            peak: ev.peak_force,
        };
        // The discrete reference for the time-step error alone: the same 144-element rod.
        let (_, discrete) = converged(&base, ROD_DT, ROD_T_END)?;
        Ok(RodStudy {
            base,
            rod,
            trace: tr,
            events: ev,
            lc,
            reference,
            discrete,
        })
    }

    /// Strain error of the mid-rod element against d'Alembert, relative to the peak.
    fn strain_error(&self, m: &Model, run: &RunResult) -> f64 {
        let (rod, ev, lc, tr) = (&self.rod, &self.events, self.lc, &self.trace);
        let ea = rod.e * rod.area;
        let n = m
            .elements
            .iter()
            .filter(|e| matches!(e.kernel.family(), crate::elements::Family::Rod { .. }))
            .count();
        let eid = n / 2;
        let Some(j) = run.column(&crate::run::Column::rod_strain(eid as i64)) else {
            return f64::NAN;
        };
        let xc = (eid as f64 - 0.5) * rod.length / n as f64;
        let peak = ev.peak_force / ea;
        run.history
            .iter()
            .filter(|h| h[0] / lc < 1.45)
            .map(|h| (h[j] - analytic::dalembert_strain(tr, xc, rod.wave_speed, ea, h[0])).abs() / peak)
            .fold(0.0, f64::max)
    }

    /// Every scheme over the Δt factors on the 144-element rod.
    fn dt_sweep(&self, repeats: usize, progress: &dyn Fn(&str)) -> Result<Vec<Row>, StudyError> {
        let (base, dt0, t_end) = (&self.base, ROD_DT, ROD_T_END);
        let (reference, discrete) = (&self.reference, &self.discrete);
        let strain_error = |m: &Model, run: &RunResult| self.strain_error(m, run);
        let mut rows = Vec::new();
        let sys = crate::assembly::assemble(base);
        let crit = crate::integrate::central::critical_step(base, &sys).ok();
        for scheme in Scheme::ALL {
            for f in DT_FACTORS {
                let dt = dt0 * f;
                progress(&format!("rod {} dt {dt:.3e}", scheme.name()));
                if scheme == Scheme::Central && crit.is_some_and(|c| dt > c) {
                    rows.push(skipped(
                        "rod",
                        scheme,
                        dt,
                        144,
                        format!("unstable: dt > critical {:.4e}", crit.unwrap_or(0.0)),
                    ));
                    continue;
                }
                let opts = RunOptions {
                    scheme,
                    dt: Some(dt),
                    steps: Some((t_end / dt).ceil() as usize),
                    ..Default::default()
                };
                let mut m = base.clone();
                m.time.every = 1;
                let (run, wall) = timed(&m, &opts, repeats)?;
                rows.push(row("rod", 144, &run, wall, reference, strain_error(&m, &run)));
                rows.push(row("rod-dt", 144, &run, wall, discrete, f64::NAN));
            }
        }
        Ok(rows)
    }

    /// Every scheme on 36 … 288 elements at the paper's step (central: its largest
    /// stable step not above it).
    fn mesh_sweep(&self, repeats: usize, progress: &dyn Fn(&str)) -> Result<Vec<Row>, StudyError> {
        let (dt0, t_end, reference) = (ROD_DT, ROD_T_END, &self.reference);
        let mut rows = Vec::new();
        for n in [36, 72, 144, 288] {
            let m = rod_model(n)?;
            for scheme in Scheme::ALL {
                progress(&format!("rod mesh {n} {}", scheme.name()));
                let sys = crate::assembly::assemble(&m);
                let crit = crate::integrate::central::critical_step(&m, &sys).ok();
                // Explicit: the largest stable step not above the paper's.
                let dt = if scheme == Scheme::Central {
                    crit.map_or(dt0, |c| c.min(dt0))
                } else {
                    dt0
                };
                let opts = RunOptions {
                    scheme,
                    dt: Some(dt),
                    steps: Some((t_end / dt).ceil() as usize),
                    ..Default::default()
                };
                let (run, wall) = timed(&m, &opts, repeats)?;
                let mut r = row("rod-mesh", n, &run, wall, reference, self.strain_error(&m, &run));
                r.note = "mesh sweep".into();
                rows.push(r);
            }
        }
        Ok(rows)
    }
}

/// The plate sweeps (see the module doc).
pub(super) fn plate_rows(repeats: usize, meshes: &[usize], progress: &dyn Fn(&str)) -> Result<Vec<Row>, StudyError> {
    let mut rows = Vec::new();
    let (dt0, t_end) = (PLATE_DT, PLATE_T_END);
    let gage_a = |n: usize, run: &RunResult| -> f64 {
        let mesh = crate::mesh::PlateMesh::new(n).expect("odd n");
        let [a, _] = mesh.gage_elements();
        let c = crate::run::Column::shell_strain(a as i64, crate::elements::Fibre::Z2, crate::elements::Plane::Yy);
        history_extreme(run, &c).map_or(f64::NAN, |e| e.value)
    };
    let m25 = plate_model(25)?;
    progress("plate reference: energy scheme, dt/16");
    let (rrun, reference) = converged(&m25, dt0, t_end)?;
    let ref_gage = gage_a(25, &rrun);
    for scheme in Scheme::ALL {
        for f in DT_FACTORS {
            let dt = dt0 * f;
            if scheme == Scheme::Central {
                rows.push(skipped(
                    "plate",
                    scheme,
                    dt,
                    25,
                    "explicit: the plate's rotations have no mass (no rotary inertia)".into(),
                ));
                continue;
            }
            progress(&format!("plate {} dt {dt:.3e}", scheme.name()));
            let opts = RunOptions {
                scheme,
                dt: Some(dt),
                steps: Some((t_end / dt).ceil() as usize),
                ..Default::default()
            };
            let (run, wall) = timed(&m25, &opts, repeats)?;
            let g = (gage_a(25, &run) / ref_gage - 1.0).abs();
            rows.push(row("plate", 25, &run, wall, &reference, g));
        }
    }
    // Mesh sweep at the paper's Δt against the finest mesh.
    let finest = *meshes.iter().max().unwrap_or(&97);
    let mut runs = Vec::new();
    for &n in meshes {
        progress(&format!("plate mesh {n}"));
        let m = plate_model(n)?;
        let opts = RunOptions {
            dt: Some(dt0),
            steps: Some((t_end / dt0).ceil() as usize),
            ..Default::default()
        };
        let reps = if n > 49 { 2 } else { repeats };
        let (run, wall) = timed(&m, &opts, reps)?;
        runs.push((n, run, wall, reps));
    }
    let fine = &runs.iter().find(|r| r.0 == finest).expect("finest mesh run").1;
    let reference = Reference {
        t: fine.series.time.clone(),
        f: fine.series.force.clone(),
        duration: duration(fine),
        peak: peak(fine),
    };
    let ref_gage = gage_a(finest, fine);
    for (n, run, wall, reps) in &runs {
        let g = (gage_a(*n, run) / ref_gage - 1.0).abs();
        let mut r = row("plate-mesh", *n, run, *wall, &reference, g);
        r.note = format!("reference: the {finest}x{finest} mesh; median of {reps} runs");
        rows.push(r);
    }
    Ok(rows)
}
