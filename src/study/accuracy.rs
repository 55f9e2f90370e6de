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
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One run of the study.
#[derive(Debug, Clone)]
pub struct Row {
    pub problem: String,
    pub scheme: Scheme,
    pub dt_s: f64,
    pub mesh: usize,
    pub error_contact_duration: f64,
    pub error_peak_force: f64,
    pub error_force_l2: f64,
    /// Rod: max |mid-rod strain − d'Alembert| / peak. Plate: gage A εyy extreme, relative.
    pub error_strain: f64,
    pub energy_error: f64,
    pub wall_s: f64,
    pub solves: usize,
    pub factorizations: usize,
    pub peak_rss_mb: f64,
    pub note: String,
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

/// The paper's step.
const ROD_DT: f64 = 2e-7;
/// Past the contact, before the reflection returns (360 µs).
const ROD_T_END: f64 = 150e-6;

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
            .filter(|e| e.kind::<crate::elements::rod::Rod>().is_some())
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
    let dt0 = 1e-7;
    let t_end = 230e-6;
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

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "problem,scheme,dt_s,mesh,error_contact_duration,error_peak_force,error_force_l2,error_strain,energy_error,wall_s,solves,factorizations,peak_rss_mb,note\n",
    );
    let e = |x: f64| if x.is_nan() { String::new() } else { format!("{x:.6e}") };
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{:e},{},{},{},{},{},{},{},{},{},{},\"{}\"",
            r.problem,
            r.scheme.name(),
            r.dt_s,
            r.mesh,
            e(r.error_contact_duration),
            e(r.error_peak_force),
            e(r.error_force_l2),
            e(r.error_strain),
            e(r.energy_error),
            e(r.wall_s),
            r.solves,
            r.factorizations,
            if r.peak_rss_mb.is_nan() {
                String::new()
            } else {
                format!("{:.1}", r.peak_rss_mb)
            },
            r.note
        );
    }
    s
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

fn figures(rows: &[Row], dir: &Path) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
    let mut out = Vec::new();
    for problem in ["rod", "rod-dt", "plate"] {
        for (slug, name, get) in MEASURES {
            let mut wp = Vec::new();
            let mut ed = Vec::new();
            for (k, scheme) in Scheme::ALL.iter().enumerate() {
                let rs: Vec<&Row> = rows
                    .iter()
                    .filter(|r| r.problem == problem && r.scheme == *scheme && r.note.is_empty() && !r.wall_s.is_nan())
                    .collect();
                if rs.is_empty() {
                    continue;
                }
                let err: Vec<f64> = rs.iter().map(|r| get(r)).collect();
                let wall: Vec<f64> = rs.iter().map(|r| r.wall_s).collect();
                let dt: Vec<f64> = rs.iter().map(|r| r.dt_s).collect();
                wp.push(Line::new(scheme.name(), err.clone(), wall, k).markers());
                let p = fitted_order(&dt, &err);
                ed.push(Line::new(format!("{} (fitted order {p:.2})", scheme.name()), dt, err, k).markers());
            }
            let footer =
                format!("impactlab study accuracy · {problem} · errors relative to the reference (see README)");
            if problem != "rod-dt" {
                out.extend(plot::line_chart(
                    &Chart {
                        title: format!("Work-precision, {problem}: {name}"),
                        x_label: format!("relative error in {name}"),
                        y_label: "wall time [s] (median)".into(),
                        footer: footer.clone(),
                        lines: wp,
                        log_x: true,
                        log_y: true,
                        headroom: 0.5,
                        ..Default::default()
                    },
                    &dir.join(format!("work-precision-{problem}-{slug}")),
                )?);
            }
            if problem == "rod" {
                continue; // its error against Δt is the mesh's; rod-dt shows the Δt error
            }
            out.extend(plot::line_chart(
                &Chart {
                    title: format!("Error against time step, {problem}: {name}"),
                    x_label: "Δt [s]".into(),
                    y_label: format!("relative error in {name}"),
                    footer,
                    lines: ed,
                    log_x: true,
                    log_y: true,
                    headroom: 0.8,
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
        lines.push(
            Line::new(
                format!("{label} (fitted order {:.2})", fitted_order(&h, &e)),
                h.clone(),
                e,
                k,
            )
            .markers(),
        );
    }
    out.extend(plot::line_chart(
        &Chart {
            title: format!("Plate: error against element size (reference: {finest}x{finest} mesh)"),
            x_label: "element size h [in]".into(),
            y_label: "relative error".into(),
            footer: "impactlab study accuracy · newmark, dt 1e-7 s".into(),
            lines,
            log_x: true,
            log_y: true,
            headroom: 0.6,
            ..Default::default()
        },
        &dir.join("error-vs-mesh-plate"),
    )?);
    Ok(out)
}

/// The cheapest setting (least wall time) per scheme reaching each tolerance.
fn cheapest_table(rows: &[Row]) -> String {
    let mut s = String::new();
    for problem in ["rod", "rod-dt", "plate"] {
        let _ = writeln!(s, "\n### {problem}\n");
        let _ = writeln!(
            s,
            "| scheme | measure | ≤ 1 % | ≤ 0.1 % | ≤ 0.01 % |\n|---|---|---|---|---|"
        );
        for scheme in Scheme::ALL {
            for (_, name, get) in MEASURES.iter().take(2) {
                let cells: Vec<String> = [1e-2, 1e-3, 1e-4]
                    .iter()
                    .map(|&tol| {
                        rows.iter()
                            .filter(|r| {
                                r.problem == problem && r.scheme == scheme && r.note.is_empty() && get(r) <= tol
                            })
                            .min_by(|a, b| a.wall_s.total_cmp(&b.wall_s))
                            .map_or("not reached".into(), |r| {
                                format!("Δt {:.2e} s, {:.3} s", r.dt_s, r.wall_s)
                            })
                    })
                    .collect();
                let _ = writeln!(s, "| {} | {name} | {} |", scheme.name(), cells.join(" | "));
            }
        }
    }
    s
}

/// Runs the study and writes `work-precision.csv`, the figures and `README.md` into
/// `dir`. `plate_meshes` is the mesh sweep (the finest is its reference).
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
    crate::output::write_file_atomically(&dir.join("work-precision.csv"), csv(&rows).as_bytes()).map_err(|source| {
        Error::Io {
            path: dir.display().to_string(),
            source,
        }
    })?;
    let figs = figures(&rows, dir)?;
    let mut md = String::from(include_str!("accuracy-intro.md"));
    let _ = writeln!(
        md,
        "\n## Cheapest setting per tolerance (wall time, median)\n{}",
        cheapest_table(&rows)
    );
    let _ = writeln!(md, "\n## Figures\n");
    for f in figs.iter().filter(|f| f.extension().is_some_and(|e| e == "png")) {
        let name = f
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let _ = writeln!(md, "![{name}]({name})\n");
    }
    crate::output::write_file_atomically(&dir.join("README.md"), md.as_bytes()).map_err(|source| Error::Io {
        path: dir.display().to_string(),
        source,
    })?;
    Ok(rows)
}
