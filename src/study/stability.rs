//! The stability map: for each scheme, the paper's rod over a grid of time step ×
//! impact velocity (both log-spaced), each cell coloured by the maximum relative
//! energy error, and marked where the run failed or was refused (the explicit scheme
//! above its critical step).

use crate::error::Error;
use crate::integrate::Scheme;
use crate::model::{Model, Modify};
use crate::run::{run_model, RunOptions};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub const DT_FACTORS: [f64; 9] = [0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0];
pub const VELOCITY_SCALES: [f64; 7] = [1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0];

#[derive(Debug, Clone)]
pub struct Cell {
    pub scheme: Scheme,
    pub dt_s: f64,
    pub velocity_scale: f64,
    /// Max relative energy error, or the failure.
    pub outcome: Result<f64, crate::run::RunError>,
}

/// Runs the grid on `model` (the rod) over `t_end` seconds.
pub fn run_map(model: &Model, dt0: f64, t_end: f64, progress: &dyn Fn(&str)) -> Result<Vec<Cell>, Error> {
    let mut cells = Vec::new();
    for scheme in Scheme::ALL {
        progress(scheme.name());
        for v in VELOCITY_SCALES {
            let m = Modify {
                velocity_scale: Some(v),
                ..Default::default()
            }
            .apply(model)?;
            for f in DT_FACTORS {
                let dt = dt0 * f;
                let opts = RunOptions {
                    scheme,
                    dt: Some(dt),
                    steps: Some((t_end / dt).ceil() as usize),
                    ..Default::default()
                };
                let outcome = run_model(&m, &opts).map(|r| r.summary.energy.max_relative_error.unwrap_or(f64::NAN));
                cells.push(Cell {
                    scheme,
                    dt_s: dt,
                    velocity_scale: v,
                    outcome,
                });
            }
        }
    }
    Ok(cells)
}

pub fn csv(cells: &[Cell]) -> String {
    let mut s = String::from("scheme,dt_s,velocity_scale,max_energy_error,failure\n");
    for c in cells {
        let (e, f) = match &c.outcome {
            Ok(e) => (format!("{e:.6e}"), String::new()),
            Err(f) => (String::new(), f.to_string().replace('"', "'")),
        };
        let _ = writeln!(
            s,
            "{},{:e},{:e},{},\"{}\"",
            c.scheme.name(),
            c.dt_s,
            c.velocity_scale,
            e,
            f
        );
    }
    s
}

fn color(err: f64) -> RGBColor {
    // log10 error from −16 (round-off) to 0 (everything lost): green → yellow → red.
    let t = ((err.max(1e-16).log10() + 16.0) / 16.0).clamp(0.0, 1.0);
    let (r, g) = if t < 0.5 {
        (2.0 * t, 1.0)
    } else {
        (1.0, 2.0 * (1.0 - t))
    };
    RGBColor((40.0 + 215.0 * r) as u8, (40.0 + 180.0 * g) as u8, 60)
}

/// The map: one panel per scheme.
struct Map<'a> {
    cells: &'a [Cell],
    dt0: f64,
}

impl crate::plot::Figure for Map<'_> {
    fn size(&self) -> (u32, u32) {
        (1400, 560)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, plotters::coord::Shift>) -> crate::plot::Res
    where
        DB::ErrorType: 'static,
    {
        draw(self.cells, self.dt0, root)
    }
}

/// Draws the map (one panel per scheme) as PNG and SVG.
pub fn figure(cells: &[Cell], dt0: f64, stem: &Path) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
    crate::plot::write_figure(&Map { cells, dt0 }, stem)
}

fn draw<DB: DrawingBackend>(
    cells: &[Cell],
    dt0: f64,
    root: &DrawingArea<DB, plotters::coord::Shift>,
) -> crate::plot::Res
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| crate::plot::err(x);
    root.fill(&WHITE).map_err(e)?;
    let root = root
        .margin(10, 0, 0, 0)
        .titled(
            "Stability map, paper's rod: max relative energy error over Δt × impact velocity (X: run refused or failed)",
            ("sans-serif", 20),
        )
        .map_err(e)?;
    let (body, foot) = root.split_vertically(480);
    foot.draw_text(
        "colour: log10 of the max energy error, green 1e-16 (round-off) → yellow 1e-8 → red 1 · impactlab study stability",
        &("sans-serif", 14).into_font().color(&RGBColor(90, 90, 90)),
        (12, 10),
    )
    .map_err(e)?;
    let (lx, hx) = (
        DT_FACTORS[0].log10() - 0.5,
        DT_FACTORS[DT_FACTORS.len() - 1].log10() + 0.5,
    );
    let (ly, hy) = (
        VELOCITY_SCALES[0].log10() - 0.5,
        VELOCITY_SCALES[VELOCITY_SCALES.len() - 1].log10() + 0.5,
    );
    for (area, scheme) in body.split_evenly((1, Scheme::ALL.len())).iter().zip(Scheme::ALL) {
        let mut ch = ChartBuilder::on(area)
            .caption(scheme.name(), ("sans-serif", 18))
            .margin(8)
            .x_label_area_size(42)
            .y_label_area_size(56)
            .build_cartesian_2d(lx..hx, ly..hy)
            .map_err(e)?;
        ch.configure_mesh()
            .disable_mesh()
            .x_desc(format!("log10(Δt / {dt0:.0e} s)"))
            .y_desc("log10(v0 / paper v0)")
            .label_style(("sans-serif", 13))
            .x_label_formatter(&|v| format!("{v:.1}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .draw()
            .map_err(e)?;
        let dx = 0.5 * (DT_FACTORS[1] / DT_FACTORS[0]).log10();
        for c in cells.iter().filter(|c| c.scheme == scheme) {
            let x = (c.dt_s / dt0).log10();
            let y = c.velocity_scale.log10();
            let rect = [(x - dx, y - 0.5), (x + dx, y + 0.5)];
            match &c.outcome {
                Ok(err) if err.is_finite() => {
                    ch.draw_series(std::iter::once(Rectangle::new(rect, color(*err).filled())))
                        .map_err(e)?;
                }
                _ => {
                    ch.draw_series(std::iter::once(Rectangle::new(rect, RGBColor(230, 230, 230).filled())))
                        .map_err(e)?;
                    ch.draw_series(std::iter::once(Text::new(
                        "X",
                        (x - 0.07, y + 0.2),
                        ("sans-serif", 16).into_font().color(&BLACK),
                    )))
                    .map_err(e)?;
                }
            }
        }
    }
    Ok(())
}

/// `README.md` of the map: what was run, the figure, the worst cell per scheme and the
/// refusals.
pub fn readme(cells: &[Cell]) -> String {
    let mut s = String::from(
        "# Stability map\n\nGenerated by `impactlab study stability`: the paper's rod (144 CRODs), 500 µs, every \
         scheme over Δt = ¼…64 × 2e-7 s and impact velocity 1e-4…100 × 62.1 in/s. Data: \
         `stability-map.csv`.\n\n![stability map](stability-map.png)\n\n| scheme | runs | refused or failed | \
         largest energy error | at Δt, velocity scale |\n|---|---|---|---|---|\n",
    );
    for scheme in Scheme::ALL {
        let mine: Vec<&Cell> = cells.iter().filter(|c| c.scheme == scheme).collect();
        let failed = mine.iter().filter(|c| c.outcome.is_err()).count();
        let worst = mine
            .iter()
            .filter_map(|c| c.outcome.as_ref().ok().map(|e| (*e, c)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        let _ = writeln!(
            s,
            "| {} | {} | {failed} | {} | {} |",
            scheme.name(),
            mine.len(),
            worst.map_or("—".into(), |w| format!("{:.2e}", w.0)),
            worst.map_or("—".into(), |w| format!(
                "{:.1e} s, ×{:e}",
                w.1.dt_s, w.1.velocity_scale
            )),
        );
    }
    let refusals: Vec<String> = cells
        .iter()
        .filter_map(|c| {
            c.outcome
                .as_ref()
                .err()
                .map(|e| format!("- {} Δt {:.1e} s: {e}", c.scheme.name(), c.dt_s))
        })
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    if !refusals.is_empty() {
        s += "\nRefusals and failures (one line per distinct message):\n\n";
        s += &refusals.join("\n");
        s += "\n";
    }
    s
}
