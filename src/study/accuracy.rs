//! What accuracy costs in time: the work-precision study.
//!
//! Rod (the paper's deck, and generated meshes of 36-288 elements): every scheme over
//! Δt = 8×…1/8× the paper's 2e-7 s, errors against the ball on a semi-infinite rod
//! (analytic, exact for the continuum until 2L/C) and d'Alembert's mid-rod strain.
//! Plate (25×25 mesh, so the sweep stays affordable): the implicit schemes over
//! Δt = 8×…1/8× the paper's 1e-7 s against a converged run of the energy scheme at
//! Δt/16 on the same mesh; and the mesh sweep 13…97 at the paper's Δt against the
//! 97×97 mesh. The explicit scheme cannot run the plate (no rotary inertia: the
//! rotations have no mass), and says so. Wall time is the median of repeats after one
//! warm-up run.

use super::history_extreme;
use crate::error::Error;
use crate::integrate::Scheme;
use crate::mesh::plate_model;
use crate::model::Model;
use crate::numerics::{interp, median};
use crate::physics::analytic;
use crate::plot::{self, Chart, Line};
use crate::run::{run_model, RunError, RunOptions, RunResult};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One run of the study, as a row of `work-precision.csv` (a value that was not
/// measured is NaN here and an empty field in the file).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// `rod` (against the continuum), `rod-dt` (the same runs against a converged run
    /// of the same mesh), `rod-mesh`, `plate` (against a converged run of the same
    /// mesh), `plate-mesh` (against the finest mesh).
    pub problem: String,
    /// The scheme.
    pub scheme: Scheme,
    /// Time step, s.
    pub dt_s: f64,
    /// Elements (rod) or elements a side (plate).
    pub mesh: usize,
    /// Relative contact duration error |duration / reference − 1|.
    #[serde(with = "nan_empty")]
    pub error_contact_duration: f64,
    /// Relative peak force error |peak / reference − 1|.
    #[serde(with = "nan_empty")]
    pub error_peak_force: f64,
    /// L2 norm of the force difference over the reference's, on the reference's contact.
    #[serde(with = "nan_empty")]
    pub error_force_l2: f64,
    /// Rod: max |mid-rod strain − d'Alembert| / peak. Plate: gage A εyy extreme, relative.
    #[serde(with = "nan_empty")]
    pub error_strain: f64,
    /// Max |relative energy error| of the run.
    #[serde(with = "nan_empty")]
    pub energy_error: f64,
    /// Wall-clock seconds of the run.
    #[serde(with = "nan_empty")]
    pub wall_s: f64,
    /// Triangular solve pairs.
    pub solves: usize,
    /// Factorisations.
    pub factorizations: usize,
    /// Peak resident memory of the process so far, MB.
    #[serde(with = "nan_empty")]
    pub peak_rss_mb: f64,
    /// Why a run was skipped (empty for a run made).
    pub note: String,
}

/// NaN written as an empty CSV field and read back from one.
mod nan_empty {
    use serde::{Deserialize, Deserializer, Serializer};
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        if x.is_nan() {
            s.serialize_none()
        } else {
            s.serialize_some(x)
        }
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

/// Δt factors relative to the paper's step.
pub const DT_FACTORS: [f64; 7] = [8.0, 4.0, 2.0, 1.0, 0.5, 0.25, 0.125];

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
fn converged(model: &Model, dt0: f64, t_end: f64) -> Result<(RunResult, Reference), Error> {
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

fn rod_model(n: usize) -> Result<Model, Error> {
    let text = crate::mesh::rod_deck(n)?;
    let mut m = crate::model_from_text(&format!("rod-{n}"), &text)?;
    m.time.every = 1;
    Ok(m)
}

/// The rod sweeps: schemes × Δt on the paper's 144 elements, and schemes × mesh at the
/// paper's Δt.
/// The rod's time step and mesh at the paper's settings: the semi-infinite rod (the
/// continuum) and a converged run of the same mesh (the step error alone) as references.
fn rod_rows(repeats: usize, progress: &dyn Fn(&str)) -> Result<Vec<Row>, Error> {
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

/// The paper's step for the rod.
pub const ROD_DT: f64 = 2e-7;
/// Past the contact, before the reflection returns (360 µs).
pub const ROD_T_END: f64 = 150e-6;
/// The paper's step for the plate.
pub const PLATE_DT: f64 = 1e-7;
/// Past the contact (about 204 µs).
pub const PLATE_T_END: f64 = 230e-6;

impl RodStudy {
    fn new() -> Result<Self, Error> {
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
    fn dt_sweep(&self, repeats: usize, progress: &dyn Fn(&str)) -> Result<Vec<Row>, Error> {
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
    fn mesh_sweep(&self, repeats: usize, progress: &dyn Fn(&str)) -> Result<Vec<Row>, Error> {
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
fn plate_rows(repeats: usize, meshes: &[usize], progress: &dyn Fn(&str)) -> Result<Vec<Row>, Error> {
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

/// The rows as `work-precision.csv` (shortest round-trip floats; NaN empty).
pub fn csv(rows: &[Row]) -> Vec<u8> {
    super::write_rows(rows)
}

/// The rows read back from `work-precision.csv`.
pub fn read_csv(bytes: &[u8]) -> Result<Vec<Row>, csv::Error> {
    super::read_rows(bytes)
}

/// Least-squares slope of log y on log x over finite pairs above round-off (1e-13).
fn fitted_order(x: &[f64], y: &[f64]) -> f64 {
    crate::numerics::order(x, y, 1e-13, 3)
}

type Measure = (&'static str, &'static str, fn(&Row) -> f64);
const MEASURES: [Measure; 3] = [
    ("contact-duration", "contact duration", |r| r.error_contact_duration),
    ("peak-force", "peak force", |r| r.error_peak_force),
    ("force-l2", "force history (L2)", |r| r.error_force_l2),
];

/// The time-step sweeps: problem, what its errors are measured against, the paper's Δt.
const SWEEPS: [(&str, &str, f64); 3] = [
    (
        "rod-dt",
        "a converged run of the same 144-element rod, energy scheme at Δt/16",
        ROD_DT,
    ),
    (
        "plate",
        "a converged run of the same 25×25 plate, energy scheme at Δt/16",
        PLATE_DT,
    ),
    (
        "rod",
        "the continuum, a ball on a semi-infinite rod; levels off at the mesh error",
        ROD_DT,
    ),
];

/// The completed runs of one scheme's time-step sweep, smallest Δt last.
fn sweep<'a>(rows: &'a [Row], problem: &str, scheme: Scheme) -> Vec<&'a Row> {
    let mut rs: Vec<&Row> = rows
        .iter()
        .filter(|r| r.problem == problem && r.scheme == scheme && r.note.is_empty() && !r.wall_s.is_nan())
        .collect();
    rs.sort_by(|a, b| b.dt_s.total_cmp(&a.dt_s));
    rs
}

/// Δt as a multiple of the paper's, as a short label ("8×", "½×").
fn factor_label(dt: f64, dt0: f64) -> String {
    let f = dt / dt0;
    match f {
        _ if (f - 0.5).abs() < 1e-9 => "½×".into(),
        _ if (f - 0.25).abs() < 1e-9 => "¼×".into(),
        _ if (f - 0.125).abs() < 1e-9 => "⅛×".into(),
        _ => format!("{f}×"),
    }
}

/// A guide line of the given log-log slope through (x0, y0), across `xs`.
fn guide(name: String, slope: f64, (x0, y0): (f64, f64), xs: (f64, f64)) -> Line {
    let y = |x: f64| y0 * (x / x0).powf(slope);
    Line::new(name, vec![xs.0, xs.1], vec![y(xs.0), y(xs.1)], 6).dashed()
}

/// The geometric middle of a set of points (for anchoring a guide line).
fn log_centre(pts: &[(f64, f64)]) -> (f64, f64) {
    let n = pts.len().max(1) as f64;
    let (lx, ly) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0.ln(), a.1 + p.1.ln()));
    ((lx / n).exp(), (ly / n).exp())
}

/// Every figure of the study, made from the rows alone.
pub fn figures(rows: &[Row], dir: &Path) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
    let mut out = Vec::new();
    for (problem, against, dt0) in SWEEPS {
        for (slug, name, get) in MEASURES {
            let (mut wp, mut ed) = (Vec::new(), Vec::new());
            let (mut wp_pts, mut ed_pts) = (Vec::new(), Vec::new());
            for (k, scheme) in Scheme::ALL.iter().enumerate() {
                let rs = sweep(rows, problem, *scheme);
                if rs.is_empty() {
                    continue;
                }
                let err: Vec<f64> = rs.iter().map(|r| get(r)).collect();
                let wall: Vec<f64> = rs.iter().map(|r| r.wall_s).collect();
                let dt: Vec<f64> = rs.iter().map(|r| r.dt_s).collect();
                let labels: Vec<String> = dt.iter().map(|d| factor_label(*d, dt0)).collect();
                let paper: Vec<usize> = dt
                    .iter()
                    .position(|d| (d / dt0 - 1.0).abs() < 1e-9)
                    .into_iter()
                    .collect();
                let ok = |x: f64, y: f64| x > 0.0 && y > 1e-13 && x.is_finite() && y.is_finite();
                wp_pts.extend(err.iter().zip(&wall).map(|(e, w)| (*e, *w)).filter(|p| ok(p.0, p.1)));
                ed_pts.extend(dt.iter().zip(&err).map(|(d, e)| (*d, *e)).filter(|p| ok(p.0, p.1)));
                wp.push(
                    Line::new(scheme.name(), err.clone(), wall, k)
                        .markers()
                        .point_labels(labels.clone())
                        .emphasis(paper.clone()),
                );
                // Against the continuum the error levels off at the mesh's: no order to fit.
                let name = if problem == "rod" {
                    scheme.name().to_string()
                } else {
                    format!("{} (fitted order {:.2})", scheme.name(), fitted_order(&dt, &err))
                };
                ed.push(
                    Line::new(name, dt, err, k)
                        .markers()
                        .point_labels(labels)
                        .emphasis(paper),
                );
            }
            if wp.is_empty() {
                continue;
            }
            let footer =
                format!("impactlab study accuracy · {problem}: errors against {against} · ring: the paper's Δt");
            let span = |pts: &[(f64, f64)], f: fn(&(f64, f64)) -> f64| {
                pts.iter()
                    .map(f)
                    .fold((f64::INFINITY, 0.0f64), |a, v| (a.0.min(v), a.1.max(v)))
            };
            if problem != "rod" {
                // Work ∝ 1/Δt and error ∝ Δt² give wall ∝ error^(−1/2).
                wp.push(guide(
                    "order 2: wall ∝ error^(−1/2)".into(),
                    -0.5,
                    log_centre(&wp_pts),
                    span(&wp_pts, |p| p.0),
                ));
                out.extend(plot::line_chart(
                    &Chart {
                        title: format!("Work-precision, {problem}: {name}"),
                        x_label: format!("relative error in {name}"),
                        y_label: "wall time [s] (median)".into(),
                        footer: footer.clone(),
                        lines: wp,
                        log_x: true,
                        log_y: true,
                        ..Default::default()
                    },
                    &dir.join(format!("work-precision-{problem}-{slug}")),
                )?);
            }
            let xs = span(&ed_pts, |p| p.0);
            if problem == "rod" {
                let floor = rows
                    .iter()
                    .find(|r| r.problem == "rod-mesh" && r.mesh == 144 && r.scheme == Scheme::Newmark)
                    .map(get);
                if let Some(e) = floor {
                    ed.push(
                        Line::new(
                            "144-element mesh error (newmark, paper's Δt)",
                            vec![xs.0, xs.1],
                            vec![e, e],
                            6,
                        )
                        .dashed(),
                    );
                }
            } else {
                ed.push(guide("order 2 (slope 2)".into(), 2.0, log_centre(&ed_pts), xs));
            }
            out.extend(plot::line_chart(
                &Chart {
                    title: format!("Error against time step, {problem}: {name}"),
                    x_label: "Δt [s]".into(),
                    y_label: format!("relative error in {name}"),
                    footer,
                    lines: ed,
                    vlines: vec![(dt0, format!("paper's Δt {dt0:e} s"))],
                    log_x: true,
                    log_y: true,
                    ..Default::default()
                },
                &dir.join(format!("error-vs-dt-{problem}-{slug}")),
            )?);
        }
    }
    let mesh: Vec<&Row> = rows.iter().filter(|r| r.problem == "plate-mesh").collect();
    let finest = mesh.iter().map(|r| r.mesh).max().unwrap_or(0);
    let mesh: Vec<&Row> = mesh.into_iter().filter(|r| r.mesh != finest).collect();
    let h: Vec<f64> = mesh.iter().map(|r| 6.0 / r.mesh as f64).collect();
    let mut lines = Vec::new();
    for (k, (label, get)) in [
        (
            "contact duration",
            (|r: &Row| r.error_contact_duration) as fn(&Row) -> f64,
        ),
        ("peak force", |r: &Row| r.error_peak_force),
        ("gage A strain", |r: &Row| r.error_strain),
    ]
    .into_iter()
    .enumerate()
    {
        let e: Vec<f64> = mesh.iter().map(|r| get(r)).collect();
        let labels = mesh.iter().map(|r| format!("{0}×{0}", r.mesh)).collect();
        lines.push(
            Line::new(
                format!("{label} (fitted order {:.2})", fitted_order(&h, &e)),
                h.clone(),
                e,
                k,
            )
            .markers()
            .point_labels(if k == 0 { labels } else { Vec::new() }),
        );
    }
    out.extend(plot::line_chart(
        &Chart {
            title: format!("Plate: error against element size (reference: {finest}×{finest} mesh)"),
            x_label: "element size h [in]".into(),
            y_label: "relative error".into(),
            footer: format!("impactlab study accuracy · newmark, Δt {PLATE_DT:e} s"),
            lines,
            log_x: true,
            log_y: true,
            ..Default::default()
        },
        &dir.join("error-vs-mesh-plate"),
    )?);
    Ok(out)
}

/// The largest Δt at which this run and every run of the sweep with a smaller Δt are
/// within `tol` in both contact duration and peak force (an error that dips below the
/// tolerance at one Δt by cancellation, and rises again, does not count).
fn reliable<'a>(rs: &[&'a Row], tol: f64) -> Option<&'a Row> {
    let within = |r: &Row| r.error_contact_duration <= tol && r.error_peak_force <= tol;
    (0..rs.len())
        .find(|&k| rs[k..].iter().all(|r| within(r)))
        .map(|k| rs[k])
}

/// Text of a fraction: "3.2e-5".
fn e2(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else {
        format!("{x:.1e}")
    }
}

/// The fitted order of each measure ([`MEASURES`]) per time-step sweep against a
/// converged run (rod-dt, plate) and scheme.
fn sweep_orders(rows: &[Row]) -> Vec<(&'static str, Scheme, [f64; 3])> {
    let mut out = Vec::new();
    for (problem, _, _) in SWEEPS.iter().take(2) {
        for scheme in Scheme::ALL {
            let rs = sweep(rows, problem, scheme);
            if rs.is_empty() {
                continue;
            }
            let dt: Vec<f64> = rs.iter().map(|r| r.dt_s).collect();
            let p = MEASURES.map(|(_, _, get)| fitted_order(&dt, &rs.iter().map(|r| get(r)).collect::<Vec<_>>()));
            out.push((*problem, scheme, p));
        }
    }
    out
}

/// `README.md` of the study: the method, the conclusions and the tables, every number
/// computed from the rows (read from `work-precision.csv`).
pub fn readme(rows: &[Row]) -> String {
    let mut s = String::from(
        "# What accuracy costs in time\n\nGenerated by `impactlab study accuracy` (`cargo run --release -- study \
         accuracy`). This page and its figures are made from `work-precision.csv` alone (one row per run; errors \
         relative; wall time the median of the repeats after one warm-up run; `peak_rss_mb` the process's peak \
         resident memory so far, so it only grows down the file); a test remakes them from it.\n\n## Method\n\n",
    );
    let factors: Vec<String> = {
        let mut f: Vec<f64> = rows
            .iter()
            .filter(|r| r.problem == "rod-dt")
            .map(|r| r.dt_s / ROD_DT)
            .collect();
        f.sort_by(|a, b| b.total_cmp(a));
        f.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        f.iter().map(|x| factor_label(*x, 1.0)).collect()
    };
    let meshes = |problem: &str| -> Vec<usize> {
        let mut m: Vec<usize> = rows.iter().filter(|r| r.problem == problem).map(|r| r.mesh).collect();
        m.sort_unstable();
        m.dedup();
        m
    };
    let finest = meshes("plate-mesh").last().copied().unwrap_or(0);
    let _ = writeln!(
        s,
        "- **Rod** (the paper's deck, 144 CRODs; generated decks of {:?} elements for the `rod-mesh` rows): every \
         scheme at Δt = {} the paper's {ROD_DT:e} s, {:.0} µs simulated. Rows `rod-dt` measure each run against a \
         converged run of the same 144-element rod (energy scheme at Δt/16): the time-step error alone. Rows `rod` \
         measure the same runs against the continuum: the ball on a semi-infinite rod (analytic model, exact until \
         2L/C), the strain against d'Alembert's −F(t − x/C)/EA at mid-rod; these errors level off at the mesh \
         error as Δt shrinks. `central` above its critical step is skipped (the row says so).\n\
         - **Plate** (a 25×25 mesh, to keep the sweep affordable): the implicit schemes over the same Δt factors of \
         the paper's {PLATE_DT:e} s, {:.0} µs simulated, against a converged run of the same mesh (energy scheme at \
         Δt/16). `central` cannot run the plate (the row says why). Rows `plate-mesh`: meshes {:?} at the paper's \
         Δt against the {finest}×{finest} mesh.\n",
        meshes("rod-mesh"),
        factors.join(", "),
        ROD_T_END * 1e6,
        PLATE_T_END * 1e6,
        meshes("plate-mesh"),
    );
    s += &conclusions(rows);
    s += "\n## Largest Δt within a tolerance\n\nThe largest Δt at which contact duration and peak force are both within \
          the tolerance, at that Δt and at every smaller one of the sweep (so an error that crosses the tolerance \
          by cancellation does not count), with the run's median wall time.\n";
    for (problem, against, dt0) in SWEEPS {
        let _ = writeln!(
            s,
            "\n### {problem} (against {against})\n\n| scheme | ≤ 1 % | ≤ 0.1 % | ≤ 0.01 % |\n|---|---|---|---|"
        );
        for scheme in Scheme::ALL {
            let rs = sweep(rows, problem, scheme);
            if rs.is_empty() {
                continue;
            }
            let cells: Vec<String> = [1e-2, 1e-3, 1e-4]
                .iter()
                .map(|&tol| {
                    reliable(&rs, tol).map_or("not reached".into(), |r| {
                        format!("Δt {:.2e} s ({}), {:.4} s", r.dt_s, factor_label(r.dt_s, dt0), r.wall_s)
                    })
                })
                .collect();
            let _ = writeln!(s, "| {} | {} |", scheme.name(), cells.join(" | "));
        }
    }
    s += "\n## Fitted orders\n\nLeast-squares slope of log(error) on log(Δt) over the sweep (errors under 1e-13 \
          left out as round-off).\n\n| problem | scheme | contact duration | peak force | force history (L2) |\n\
          |---|---|---|---|---|\n";
    for (problem, scheme, p) in sweep_orders(rows) {
        let p: Vec<String> = p.iter().map(|p| format!("{p:.2}")).collect();
        let _ = writeln!(s, "| {problem} | {} | {} |", scheme.name(), p.join(" | "));
    }
    s += "\n## Figures\n\nThe primary figures come first: the rod against its own converged run, then the plate; \
          the rod against the continuum and the plate's mesh error last.\n\n";
    for (problem, _, _) in SWEEPS {
        for (slug, _, _) in MEASURES {
            for kind in ["work-precision", "error-vs-dt"] {
                if kind == "work-precision" && problem == "rod" {
                    continue;
                }
                let name = format!("{kind}-{problem}-{slug}");
                let _ = writeln!(s, "![{name}]({name}.png)\n");
            }
        }
    }
    s += "![error-vs-mesh-plate](error-vs-mesh-plate.png)\n";
    s
}

/// The conclusions, each sentence chosen and filled in from the rows.
fn conclusions(rows: &[Row]) -> String {
    let mut s = String::from("\n## Conclusions (from the rows of the CSV)\n\n");
    let at = |problem: &str, scheme: Scheme, dt: f64| {
        rows.iter().find(|r| {
            r.problem == problem && r.scheme == scheme && (r.dt_s / dt - 1.0).abs() < 1e-9 && r.note.is_empty()
        })
    };
    let implicit = [Scheme::Newmark, Scheme::Energy, Scheme::Nastran];
    // 1. The mesh against the step at the paper's settings.
    let step_err = implicit
        .iter()
        .filter_map(|sc| at("plate", *sc, PLATE_DT))
        .map(|r| r.error_contact_duration.max(r.error_peak_force))
        .fold(0.0f64, f64::max);
    let mesh49 = rows.iter().find(|r| r.problem == "plate-mesh" && r.mesh == 49);
    let finest = rows
        .iter()
        .filter(|r| r.problem == "plate-mesh")
        .map(|r| r.mesh)
        .max()
        .unwrap_or(0);
    if let Some(m) = mesh49 {
        let mesh_err = m.error_contact_duration.min(m.error_peak_force);
        let verdict = if mesh_err > 10.0 * step_err {
            "**The mesh, not the step, limits accuracy at the paper's settings.**"
        } else {
            "**At the paper's settings the step matters as much as the mesh.**"
        };
        let _ = writeln!(
            s,
            "- {verdict} Plate: at the paper's Δt the time-step error of the implicit schemes (25×25) is at most {} \
             in contact duration and peak force; the 49×49 mesh differs from the {finest}×{finest} by {} in \
             contact duration and {} in peak force.",
            e2(step_err),
            e2(m.error_contact_duration),
            e2(m.error_peak_force)
        );
    }
    let rod_mesh = |n: usize| {
        rows.iter()
            .filter(|r| r.problem == "rod-mesh" && r.mesh == n && r.scheme != Scheme::Central)
            .map(|r| (r.error_contact_duration, r.error_peak_force))
            .fold((0.0f64, 0.0f64), |a, e| (a.0.max(e.0), a.1.max(e.1)))
    };
    let floor: Vec<f64> = implicit
        .iter()
        .filter_map(|sc| sweep(rows, "rod", *sc).last().map(|r| r.error_contact_duration))
        .collect();
    if !floor.is_empty() {
        let (m144, m288) = (rod_mesh(144), rod_mesh(288));
        let _ = writeln!(
            s,
            "- Rod against the continuum: at the smallest Δt the implicit schemes' contact-duration error is {}; \
             the 144-element mesh's error at the paper's Δt is {} in duration and {} in peak force, 288 \
             elements give {} and {}.",
            {
                let (lo, hi) = floor
                    .iter()
                    .fold((f64::INFINITY, 0.0f64), |a, v| (a.0.min(*v), a.1.max(*v)));
                if e2(lo) == e2(hi) {
                    e2(lo)
                } else {
                    format!("{} to {}", e2(lo), e2(hi))
                }
            },
            e2(m144.0),
            e2(m144.1),
            e2(m288.0),
            e2(m288.1)
        );
    }
    // 2. How large a step each tolerance allows.
    for (problem, _, dt0) in SWEEPS.iter().take(2) {
        for tol in [1e-3, 1e-4] {
            let parts: Vec<String> = Scheme::ALL
                .iter()
                .filter_map(|sc| {
                    let rs = sweep(rows, problem, *sc);
                    (!rs.is_empty()).then(|| {
                        reliable(&rs, tol).map_or(format!("{} never", sc.name()), |r| {
                            format!("{} at {}", sc.name(), factor_label(r.dt_s, *dt0))
                        })
                    })
                })
                .collect();
            let _ = writeln!(
                s,
                "- {problem}: contact duration and peak force within {} % from Δt = (× the paper's) {}.",
                tol * 100.0,
                parts.join(", ")
            );
        }
    }
    // 3. Orders.
    let mut second = Vec::new();
    let mut other = Vec::new();
    for (problem, sc, p) in sweep_orders(rows) {
        let text = format!("{} on {problem} ({:.2}, {:.2})", sc.name(), p[0], p[1]);
        if p[..2].iter().all(|p| (p - 2.0).abs() <= 0.2) {
            second.push(text);
        } else {
            other.push(text);
        }
    }
    let _ = writeln!(
        s,
        "- Orders (contact duration, peak force): within 0.2 of 2: {}; otherwise: {}.",
        if second.is_empty() {
            "none".into()
        } else {
            second.join(", ")
        },
        if other.is_empty() {
            "none".into()
        } else {
            other.join(", ")
        }
    );
    // 4. Cost per step and energy balance, per scheme.
    let per_step = |sc: Scheme, problem: &str| {
        let v: Vec<f64> = sweep(rows, problem, sc)
            .iter()
            .filter(|r| r.solves > 0)
            .map(|r| r.wall_s / r.solves as f64)
            .collect();
        (!v.is_empty()).then(|| median(v))
    };
    let mut cost = Vec::new();
    for problem in ["rod-dt", "plate"] {
        let Some(base) = per_step(Scheme::Newmark, problem) else {
            continue;
        };
        let r: Vec<String> = Scheme::ALL
            .iter()
            .filter_map(|sc| per_step(*sc, problem).map(|c| format!("{} {:.2}", sc.name(), c / base)))
            .collect();
        cost.push(format!("{problem}: {}", r.join(", ")));
    }
    let worst_energy = |sc: Scheme| {
        rows.iter()
            .filter(|r| r.scheme == sc && r.note.is_empty() && matches!(r.problem.as_str(), "rod-dt" | "plate"))
            .map(|r| r.energy_error)
            .filter(|e| e.is_finite())
            .fold(0.0f64, f64::max)
    };
    let energies: Vec<String> = Scheme::ALL
        .iter()
        .map(|sc| format!("{} {}", sc.name(), e2(worst_energy(*sc))))
        .collect();
    let _ = writeln!(
        s,
        "- Cost per solve relative to newmark (median over the sweep): {}. Largest relative energy error of any \
         run: {}.",
        cost.join("; "),
        energies.join(", ")
    );
    let skipped: Vec<String> = rows
        .iter()
        .filter(|r| !r.note.is_empty() && r.wall_s.is_nan())
        .map(|r| format!("{} {}", r.scheme.name(), r.note))
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    if !skipped.is_empty() {
        let _ = writeln!(s, "- Not run: {}.", skipped.join("; "));
    }
    s
}

/// Runs the study and writes `work-precision.csv` into `dir`, then the page and the
/// figures made from it ([`redraw`]). `plate_meshes` is the mesh sweep (the finest is
/// its reference).
pub fn run_study(
    dir: &Path,
    repeats: usize,
    plate_meshes: &[usize],
    progress: &dyn Fn(&str),
) -> Result<Vec<Row>, Error> {
    let mut rows = rod_rows(repeats, progress)?;
    rows.extend(plate_rows(repeats, plate_meshes, progress)?);
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.display().to_string(),
        source,
    })?;
    let path = dir.join("work-precision.csv");
    crate::output::write_file_atomically(&path, &csv(&rows)).map_err(|source| Error::Io {
        path: path.display().to_string(),
        source,
    })?;
    redraw(dir)?;
    Ok(rows)
}

/// Remakes `README.md` and the figures in `dir` from its `work-precision.csv`.
pub fn redraw(dir: &Path) -> Result<(), Error> {
    let rows: Vec<Row> = super::read_rows_file(&dir.join("work-precision.csv"))?;
    figures(&rows, dir)?;
    super::write_page(&dir.join("README.md"), &readme(&rows))
}
