//! The stability map: for each scheme, the paper's rod over a grid of time step ×
//! impact velocity (both log-spaced), each cell coloured by the maximum relative
//! energy error and labelled with it, and marked where the run failed: refused (the
//! explicit scheme above its critical step), or stopped by the energy guard
//! ([`crate::run::DEFAULT_ENERGY_GUARD`]), which every run has.
//!
//! The map's data is `stability-map.csv`; its page and figure are made from that
//! file alone ([`read_csv`], [`readme`], [`figure`]), so that a test can remake them
//! from the committed CSV and find them current without running the study again.

use super::StudyError;
use crate::integrate::Scheme;
use crate::model::{Model, Modify};
use crate::run::{run_model, RunError, RunOptions};
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The map's Δt axis, in units of [`DT0`].
pub const DT_FACTORS: [f64; 9] = [0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0];
/// The map's impact-velocity axis, as multiples of the deck's.
pub const VELOCITY_SCALES: [f64; 7] = [1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0];
/// The paper's Δt for the rod, the map's unit of Δt (the rod deck's time unit is the second).
pub const DT0: f64 = 2e-7;

/// One run of the map, as a row of `stability-map.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    /// The scheme.
    pub scheme: Scheme,
    /// Time step, s.
    pub dt_s: f64,
    /// Impact velocity as a multiple of the deck's.
    pub velocity_scale: f64,
    /// Max |relative energy error| of a completed run; for a run the energy guard
    /// stopped, the error at the step that tripped it. None for a refused run.
    pub max_energy_error: Option<f64>,
    /// Why the run failed (refused, or stopped by the energy guard).
    pub failure: Option<String>,
}

impl Cell {
    /// True when the run was refused or stopped.
    pub fn failed(&self) -> bool {
        self.failure.is_some()
    }
    fn stopped_by_guard(&self) -> bool {
        self.failure.as_deref().is_some_and(|f| f.starts_with("energy guard"))
    }
}

/// The largest difference of the energy error between the engines the map accepts
/// where both ran a cell: 1e-9, absolute (the errors span round-off to 1e2; the
/// engines agree to round-off of the initial energy, measured at most 2e-13).
pub const ENGINE_CHECK_MAX: f64 = 1e-9;

/// What a run of the map gives: its energy error, and why it failed if it did.
type Outcome = (Option<f64>, Option<String>);

fn outcome(run: Result<crate::run::RunResult, RunError>) -> Outcome {
    match run {
        Ok(r) => (r.summary.energy.max_relative_error, None),
        Err(RunError::EnergyGuard { trip, .. }) => (Some(trip.error.abs()), Some(trip.to_string())),
        Err(e) => (None, Some(e.to_string())),
    }
}

/// Runs the grid on `model` (the rod) over `t_end` seconds, every run with the
/// default energy guard. The Δt axis is direct, step by step (it is what the map
/// measures); along the velocity axis the trapezoidal schemes (`newmark`, `energy`) run
/// on the convolution engine, one kernel pass per Δt, the deck's own velocity also
/// directly as the column's check: the two must agree (the same failure, the same
/// step, energy errors within [`ENGINE_CHECK_MAX`]) or the study fails. Returns the
/// cells and the largest difference of the checks.
pub fn run_map(model: &Model, dt0: f64, t_end: f64, progress: &dyn Fn(&str)) -> Result<(Vec<Cell>, f64), StudyError> {
    use crate::run::convolution::Kernels;
    use crate::run::Engine;
    let at_velocity = |m: &Model, v: f64| {
        Modify {
            velocity_scale: Some(v),
            ..Default::default()
        }
        .apply(m)
    };
    let prepared = crate::run::prepare(model, &RunOptions::default())?;
    let (solved, sys) = (prepared.model.as_ref(), &prepared.system);
    let mut outcomes: BTreeMap<(usize, usize, usize), Outcome> = BTreeMap::new();
    let mut worst_check = 0.0f64;
    for (s, scheme) in Scheme::ALL.into_iter().enumerate() {
        progress(scheme.name());
        for (d, f) in DT_FACTORS.into_iter().enumerate() {
            let dt = dt0 * f;
            let opts = RunOptions {
                scheme,
                dt: Some(dt),
                steps: Some((t_end / dt).ceil() as usize),
                ..Default::default()
            };
            if scheme.newmark_params().is_none() {
                for (v, scale) in VELOCITY_SCALES.into_iter().enumerate() {
                    outcomes.insert((s, v, d), outcome(run_model(&at_velocity(model, scale)?, &opts)));
                }
                continue;
            }
            let conv = RunOptions {
                engine: Engine::Convolution,
                ..opts.clone()
            };
            let steps = conv.steps.expect("set above");
            let hidden = indicatif::ProgressBar::hidden();
            let (kernels, _) = Kernels::for_run(solved, sys, dt, steps, None, &hidden)?;
            for (v, scale) in VELOCITY_SCALES.into_iter().enumerate() {
                let c = outcome(kernels.run(&at_velocity(solved, scale)?, &conv, &hidden));
                if scale == 1.0 {
                    let direct = outcome(run_model(&at_velocity(model, scale)?, &opts));
                    // Failed or not, and at which step the guard stopped the run.
                    let step = |o: &Outcome| {
                        o.1.as_ref().map(|f| {
                            f.split(" at step ")
                                .nth(1)
                                .and_then(|r| r.split(' ').next())
                                .map(String::from)
                        })
                    };
                    let diff = match (c.0, direct.0) {
                        (Some(a), Some(b)) => (a - b).abs(),
                        (None, None) => 0.0,
                        _ => f64::INFINITY,
                    };
                    if step(&c) != step(&direct) || diff.is_nan() || diff > ENGINE_CHECK_MAX {
                        return Err(StudyError::Input(format!(
                            "stability map, {} at Δt {dt:e} s: the convolution engine gives {c:?}, the direct one \
                             {direct:?}",
                            scheme.name()
                        )));
                    }
                    worst_check = worst_check.max(diff);
                }
                outcomes.insert((s, v, d), c);
            }
        }
    }
    let mut cells = Vec::new();
    for ((s, v, d), (max_energy_error, failure)) in outcomes {
        cells.push(Cell {
            scheme: Scheme::ALL[s],
            dt_s: dt0 * DT_FACTORS[d],
            velocity_scale: VELOCITY_SCALES[v],
            max_energy_error,
            failure,
        });
    }
    Ok((cells, worst_check))
}

/// `stability-map.csv`: one row per run, numbers in their shortest round-trip form.
pub fn csv(cells: &[Cell]) -> Vec<u8> {
    super::write_rows(cells)
}

/// The cells of a `stability-map.csv`.
pub fn read_csv(bytes: &[u8]) -> Result<Vec<Cell>, csv::Error> {
    super::read_rows(bytes)
}

/// Colour of a max energy error: log10 from −16 (round-off) to +2 (a hundred times
/// the initial energy created): green → yellow → red.
fn color(err: f64) -> RGBColor {
    let t = ((err.max(1e-16).log10() + 16.0) / 18.0).clamp(0.0, 1.0);
    let (r, g) = if t < 0.5 {
        (2.0 * t, 1.0)
    } else {
        (1.0, 2.0 * (1.0 - t))
    };
    RGBColor((40.0 + 215.0 * r) as u8, (40.0 + 180.0 * g) as u8, 60)
}

/// The map: one panel per scheme, and a colour bar.
struct Map<'a> {
    cells: &'a [Cell],
}

impl crate::plot::Figure for Map<'_> {
    fn size(&self) -> (u32, u32) {
        (1900, 640)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, plotters::coord::Shift>) -> crate::plot::Res
    where
        DB::ErrorType: 'static,
    {
        draw(self.cells, root)
    }
}

/// Draws the map (one panel per scheme) as PNG and SVG.
pub fn figure(cells: &[Cell], stem: &Path) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
    crate::plot::write_figure(&Map { cells }, stem)
}

/// A cell's label: its error to one digit (`3e-5`).
fn label(err: f64) -> String {
    format!("{err:.0e}")
}

fn draw<DB: DrawingBackend>(cells: &[Cell], root: &DrawingArea<DB, plotters::coord::Shift>) -> crate::plot::Res
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| crate::plot::err(x);
    root.fill(&WHITE).map_err(e)?;
    let root = root
        .margin(10, 0, 0, 0)
        .titled(
            "Stability map, paper's rod: max relative energy error over Δt × impact velocity",
            ("sans-serif", 22),
        )
        .map_err(e)?;
    let (body, foot) = root.split_vertically(540);
    foot.draw_text(
        &format!(
            "number: max |relative energy error| of the run · grey with X: refused (explicit scheme over its critical \
             step) or stopped by the energy guard ({:.0e}; the number is the error that stopped it) · impactlab study stability",
            crate::run::DEFAULT_ENERGY_GUARD
        ),
        &("sans-serif", 14).into_font().color(&RGBColor(90, 90, 90)),
        (12, 10),
    )
    .map_err(e)?;
    let (panels, bar) = body.split_horizontally(1780);
    // x: log2(Δt/Δt0), one unit per cell; y: log10(v0 scale), one unit per cell.
    let (lx, hx) = (
        DT_FACTORS[0].log2() - 0.5,
        DT_FACTORS[DT_FACTORS.len() - 1].log2() + 0.5,
    );
    let (ly, hy) = (
        VELOCITY_SCALES[0].log10() - 0.5,
        VELOCITY_SCALES[VELOCITY_SCALES.len() - 1].log10() + 0.5,
    );
    let dx = 0.5;
    let small = ("sans-serif", 12).into_font();
    for (area, scheme) in panels.split_evenly((1, Scheme::ALL.len())).iter().zip(Scheme::ALL) {
        let mut ch = ChartBuilder::on(area)
            .caption(scheme.name(), ("sans-serif", 18))
            .margin(8)
            .x_label_area_size(42)
            .y_label_area_size(56)
            .build_cartesian_2d(lx..hx, ly..hy)
            .map_err(e)?;
        ch.configure_mesh()
            .disable_mesh()
            .x_desc(format!("Δt / {DT0:.0e} s"))
            .y_desc("v0 / paper's v0")
            .label_style(("sans-serif", 13))
            .x_labels(DT_FACTORS.len())
            .y_labels(VELOCITY_SCALES.len())
            .x_label_formatter(&|v| crate::plot::fmt_tick(2f64.powf(*v)))
            .y_label_formatter(&|v| format!("{:.0e}", 10f64.powf(*v)))
            .draw()
            .map_err(e)?;
        for c in cells.iter().filter(|c| c.scheme == scheme) {
            let x = (c.dt_s / DT0).log2();
            let y = c.velocity_scale.log10();
            let rect = [(x - dx, y - 0.5), (x + dx, y + 0.5)];
            let fill = match (c.failed(), c.max_energy_error) {
                (false, Some(err)) if err.is_finite() => color(err),
                _ => RGBColor(215, 215, 215),
            };
            ch.draw_series([
                Rectangle::new(rect, fill.filled()),
                Rectangle::new(rect, WHITE.stroke_width(1)),
            ])
            .map_err(e)?;
            let text = match (c.failed(), c.max_energy_error) {
                (true, Some(err)) => format!("X {}", label(err)),
                (true, None) => "X".into(),
                (false, Some(err)) => label(err),
                (false, None) => "-".into(),
            };
            ch.draw_series(std::iter::once(Text::new(
                text,
                (x - 0.42, y + 0.12),
                small.color(&BLACK),
            )))
            .map_err(e)?;
        }
    }
    // Colour bar: log10 of the error, −16 … +2.
    let (bx, by, h) = (14, 60, 400);
    for k in 0..h {
        let l = 2.0 - 18.0 * k as f64 / (h - 1) as f64;
        bar.draw(&Rectangle::new(
            [(bx, by + k), (bx + 22, by + k + 1)],
            color(10f64.powf(l)).filled(),
        ))
        .map_err(e)?;
    }
    for l in [2, 0, -4, -8, -12, -16] {
        let yk = by + ((2 - l) as f64 / 18.0 * (h - 1) as f64) as i32;
        bar.draw_text(
            &format!("1e{l}"),
            &("sans-serif", 13).into_font().color(&BLACK),
            (bx + 26, yk - 6),
        )
        .map_err(e)?;
    }
    bar.draw_text("error", &("sans-serif", 13).into_font().color(&BLACK), (bx, by - 24))
        .map_err(e)?;
    Ok(())
}

/// `README.md` of the map, every number from the cells (read from the CSV): what was
/// run, the figure, per scheme the runs, failures and largest error, and every failure.
pub fn readme(cells: &[Cell]) -> String {
    let guard = crate::run::DEFAULT_ENERGY_GUARD;
    let check = ENGINE_CHECK_MAX;
    let mut s = format!(
        "# Stability map\n\nGenerated by `impactlab study stability` (this page and the figure are made from \
         `stability-map.csv` alone; a test remakes them from it): the paper's rod (144 CRODs), 500 µs, every \
         scheme over Δt = ¼…64 × {DT0:e} s and impact velocity 1e-4…100 × 62.1 in/s, every run with the default \
         energy guard ({guard:.0e}: a run whose relative energy error exceeds it is stopped and counts as \
         failed). Each Δt is run step by step; along the velocity axis `newmark` and `energy` run on the \
         convolution engine (one kernel pass per Δt), the deck's velocity also on the direct engine as the \
         column's check (the same outcome, energy errors within {check:.0e}). That engine's ledger takes the \
         target's energy from the discrete work identity, so the `energy` scheme's errors there are the \
         round-off of that identity (about 1e-14), not of ½vᵀMv + ½uᵀKu summed over the rod (about 1e-12).\n\n![stability map](stability-map.png)\n\n| scheme | runs | completed | refused | stopped by \
         the energy guard | largest error of a completed run | at Δt, velocity scale |\n|---|---|---|---|---|---|---|\n",
    );
    for scheme in Scheme::ALL {
        let mine: Vec<&Cell> = cells.iter().filter(|c| c.scheme == scheme).collect();
        let guarded = mine.iter().filter(|c| c.stopped_by_guard()).count();
        let failed = mine.iter().filter(|c| c.failed()).count();
        let worst = mine
            .iter()
            .filter(|c| !c.failed())
            .filter_map(|c| c.max_energy_error.map(|e| (e, c)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {guarded} | {} | {} |",
            scheme.name(),
            mine.len(),
            mine.len() - failed,
            failed - guarded,
            worst.map_or("—".into(), |w| format!("{:.2e}", w.0)),
            worst.map_or("—".into(), |w| format!(
                "{:.1e} s, ×{:e}",
                w.1.dt_s, w.1.velocity_scale
            )),
        );
    }
    // Failures grouped by scheme, Δt and message, with the velocities they hit.
    let mut groups: BTreeMap<(usize, u64, String), Vec<f64>> = BTreeMap::new();
    for c in cells {
        if let Some(f) = &c.failure {
            let k = Scheme::ALL.iter().position(|x| *x == c.scheme).unwrap_or(0);
            groups
                .entry((k, c.dt_s.to_bits(), f.clone()))
                .or_default()
                .push(c.velocity_scale);
        }
    }
    if !groups.is_empty() {
        s += "\nFailures (scheme, Δt, the impact velocities as multiples of the paper's, and why):\n\n";
        for ((k, dt, why), vs) in &groups {
            let vs: Vec<String> = vs.iter().map(|v| format!("{v:e}")).collect();
            let _ = writeln!(
                s,
                "- {} Δt {:.2e} s, ×{}: {why}",
                Scheme::ALL[*k].name(),
                f64::from_bits(*dt),
                vs.join(", ×")
            );
        }
    }
    s
}

/// One run of the plate's hard cases ([`hard_cases`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HardCase {
    /// What the case stresses.
    pub case: &'static str,
    /// The scheme.
    pub scheme: Scheme,
    /// Time step (the deck's time unit).
    pub dt: f64,
    /// Steps run.
    pub steps: usize,
    /// Max |relative energy error| (None when the run failed).
    pub max_energy_error: Option<f64>,
    /// The scheme's bound: round-off (1e-10) for `energy`, the energy guard
    /// ([`crate::run::DEFAULT_ENERGY_GUARD`]) for the others.
    pub bound: f64,
    /// Every contact force, indentation and ledger entry finite.
    pub finite: bool,
    /// Why the run failed, if it did.
    pub failure: Option<String>,
}

impl HardCase {
    /// Finite, completed, and within the scheme's bound.
    pub fn passed(&self) -> bool {
        self.finite && self.failure.is_none() && self.max_energy_error.is_some_and(|e| e <= self.bound)
    }
}

/// The stability suite's hard cases on the paper's plate with an N×N mesh, for the
/// implicit schemes (`newmark`, `energy`, `nastran`) over 200 µs: the impact moved
/// next to the clamped edge (the element in the second row, same column), the
/// impact velocity ×100, the time step ×64, and a stiff chattering contact (K ×1000).
pub fn hard_cases(n: usize, progress: &dyn Fn(&str)) -> Result<Vec<HardCase>, StudyError> {
    let centre = crate::model_from_text("plate", &crate::mesh::plate_deck(n)?)?;
    let edge = crate::model_from_text("plate-edge", &plate_deck_next_to_the_edge(n)?)?;
    let dt0 = centre.time.dt;
    let scaled = |m: Modify| m.apply(&centre);
    let cases: Vec<(&'static str, Model, f64)> = vec![
        ("impact next to the clamped edge", edge, dt0),
        (
            "impact velocity x100",
            scaled(Modify {
                velocity_scale: Some(100.0),
                ..Default::default()
            })?,
            dt0,
        ),
        ("time step x64", centre.clone(), 64.0 * dt0),
        (
            "stiff chattering contact (K x1000)",
            scaled(Modify {
                contact_stiffness_scale: Some(1000.0),
                ..Default::default()
            })?,
            dt0,
        ),
    ];
    let t_end = 2000.0 * dt0;
    let mut rows = Vec::new();
    for (case, model, dt) in &cases {
        for scheme in [Scheme::Newmark, Scheme::Energy, Scheme::Nastran] {
            progress(&format!("{case}, {scheme}"));
            let steps = (t_end / dt).round() as usize;
            let opts = RunOptions {
                scheme,
                dt: Some(*dt),
                steps: Some(steps),
                ..Default::default()
            };
            let bound = if scheme == Scheme::Energy {
                1e-10
            } else {
                crate::run::DEFAULT_ENERGY_GUARD
            };
            let (max_energy_error, finite, failure) = match run_model(model, &opts) {
                Ok(r) => {
                    let s = &r.series;
                    let finite = s.force.iter().chain(&s.alpha).all(|v| v.is_finite())
                        && r.energy
                            .iter()
                            .all(|e| e.values(crate::ledger::Dissipations::ALL).iter().all(|v| v.is_finite()));
                    (r.summary.energy.max_relative_error, finite, None)
                }
                Err(RunError::EnergyGuard { trip, .. }) => (Some(trip.error.abs()), true, Some(trip.to_string())),
                Err(e) => (None, false, Some(e.to_string())),
            };
            rows.push(HardCase {
                case,
                scheme,
                dt: *dt,
                steps,
                max_energy_error,
                bound,
                finite,
                failure,
            });
        }
    }
    Ok(rows)
}

/// The N×N plate deck ([`crate::mesh::plate_deck`]) with its contact (the NOLIN3
/// and TF grids, output SET 15) moved from the centre element to the one in the
/// second row of the same column, next to the clamped edge.
pub fn plate_deck_next_to_the_edge(n: usize) -> Result<String, StudyError> {
    let deck = crate::mesh::plate_deck(n)?;
    let m = crate::mesh::PlateMesh::new(n)?;
    let centre = m.contact_grids();
    let col = n.div_ceil(2);
    let edge = [m.grid(2, col), m.grid(2, col + 1), m.grid(3, col), m.grid(3, col + 1)];
    let moved: BTreeMap<String, String> = centre
        .iter()
        .zip(edge)
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    let mut out = String::new();
    for l in deck.lines() {
        if ["NOLIN3", "+TF", "  SET 15"].iter().any(|p| l.starts_with(p)) {
            let fields: Vec<&str> = l.split(',').map(|f| moved.get(f).map_or(f, String::as_str)).collect();
            out.push_str(&fields.join(","));
        } else {
            out.push_str(l);
        }
        out.push('\n');
    }
    Ok(out)
}

/// The hard cases as a table (Markdown), each row passed or FAILED.
pub fn hard_cases_table(n: usize, rows: &[HardCase]) -> String {
    let mut out = format!(
        "Hard cases on the {n}x{n} plate, 200 µs each\n\n| case | scheme | Δt | steps | max energy error | bound | finite | verdict |\n|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let _ = writeln!(
            out,
            "| {} | {} | {:e} | {} | {} | {:e} | {} | {} |",
            r.case,
            r.scheme,
            r.dt,
            r.steps,
            r.max_energy_error.map_or("-".into(), |e| format!("{e:.2e}")),
            r.bound,
            if r.finite { "yes" } else { "no" },
            match (&r.failure, r.passed()) {
                (Some(f), _) => format!("FAILED: {f}"),
                (None, true) => "passed".into(),
                (None, false) => "FAILED: over the bound".into(),
            }
        );
    }
    out
}
