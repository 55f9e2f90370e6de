//! The study's figures, from its rows alone.

use super::{factor_label, fitted_order, sweep, Row, MEASURES, PLATE_DT, SWEEPS};
use crate::integrate::Scheme;
use crate::plot::{self, Chart, Line};
use std::path::{Path, PathBuf};

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

/// Every figure of the study, made from the rows alone: each time-step sweep's
/// work-precision and error-against-Δt figures, then the plate's mesh figure.
pub fn figures(rows: &[Row], dir: &Path) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
    let mut out = Vec::new();
    for (problem, against, dt0) in SWEEPS {
        for measure in MEASURES {
            out.extend(sweep_figures(rows, (problem, against, dt0), measure, dir)?);
        }
    }
    out.extend(mesh_figure(rows, dir)?);
    Ok(out)
}

/// One scheme per line over a sweep's Δt: error against wall time (work-precision)
/// and against Δt, each point labelled by its Δt factor, the paper's Δt ringed; and
/// the points of each (above round-off), for placing guides.
struct SweepLines {
    work_precision: Vec<Line>,
    error_vs_dt: Vec<Line>,
    wp_pts: Vec<(f64, f64)>,
    ed_pts: Vec<(f64, f64)>,
}

fn sweep_lines(rows: &[Row], problem: &str, dt0: f64, get: fn(&Row) -> f64) -> SweepLines {
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
    SweepLines {
        work_precision: wp,
        error_vs_dt: ed,
        wp_pts,
        ed_pts,
    }
}

/// The smallest and largest of one coordinate of the points.
fn span(pts: &[(f64, f64)], f: fn(&(f64, f64)) -> f64) -> (f64, f64) {
    pts.iter()
        .map(f)
        .fold((f64::INFINITY, 0.0f64), |a, v| (a.0.min(v), a.1.max(v)))
}

/// A sweep's figures for one measure: work-precision (with its order-2 guide; not for
/// the rod against the continuum, whose error levels off at the mesh's) and error
/// against Δt (with the order-2 guide, or the rod's mesh-error floor).
fn sweep_figures(
    rows: &[Row],
    (problem, against, dt0): (&str, &str, f64),
    (slug, name, get): super::Measure,
    dir: &Path,
) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
    let mut out = Vec::new();
    let SweepLines {
        work_precision: mut wp,
        error_vs_dt: mut ed,
        wp_pts,
        ed_pts,
    } = sweep_lines(rows, problem, dt0, get);
    if wp.is_empty() {
        return Ok(out);
    }
    let footer = format!("impactlab study accuracy · {problem}: errors against {against} · ring: the paper's Δt");
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
    Ok(out)
}

/// The plate's mesh sweep: each measure's error against the element size, the finest
/// mesh the reference.
fn mesh_figure(rows: &[Row], dir: &Path) -> Result<Vec<PathBuf>, crate::plot::PlotError> {
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
    plot::line_chart(
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
    )
}
