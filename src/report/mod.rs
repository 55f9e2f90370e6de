//! Reports from a case outcome (nothing is run here): its figures (the paper's Figures 2-4 for the rod,
//! 6-9 for the plate), its ledger at key instants and its verdicts, as `index.md` and
//! an `index.html` with the images inline. Physics comes from the run and the
//! analytic references; this module only draws and writes.

pub mod fields;

use crate::elements::{Family, Fibre, Measure, Plane};
use crate::ledger::EnergyRow;
use crate::model::Model;
use crate::physics::analytic;
use crate::plot::{self, Chart, Contour, Line};
use crate::run::{Column, RunResult};
use crate::verify::external::{self, ExternalSeries};
use crate::verify::{Case, CaseOutcome, CheckResult, CheckSpec};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What a report says, for the index and for tests.
#[derive(Debug, Clone)]
pub struct CaseReport {
    /// The case's name.
    pub name: String,
    /// The page's Markdown.
    pub markdown: String,
    /// The figures written.
    pub figures: Vec<PathBuf>,
    /// Checks passed.
    pub passed: usize,
    /// Checks failed.
    pub failed: usize,
    /// The run's summary.
    pub summary: crate::run::Summary,
    /// The run's short human summary.
    pub human: String,
}

/// Significant-digit formatting used in every report table.
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if (-3..5).contains(&e) {
        let dec = (digits as i32 - 1 - e).max(0) as usize;
        format!("{x:.dec$}")
    } else {
        format!("{x:.prec$e}", prec = digits - 1)
    }
}

/// A report that could not be made: a figure, a reference it draws, an external
/// solver's file it overlays, or a file it writes.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The case is static: its verdicts are `verify`'s, with no run to draw.
    #[error("{0}: a static case has no run to report")]
    Static(String),
    /// A figure could not be drawn.
    #[error("{0}")]
    Plot(#[from] crate::plot::PlotError),
    /// A reference could not be computed.
    #[error("{0}")]
    Reference(#[from] crate::physics::references::ReferenceError),
    /// An external solver's results could not be read.
    #[error("{0}")]
    Check(#[from] crate::verify::CheckError),
    /// Field files could not be written.
    #[error("{0}")]
    Fields(#[from] fields::FieldsError),
    /// A file could not be written.
    #[error("cannot write outputs to {path}: {source}")]
    Io {
        /// The path being written.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl Fn(std::io::Error) -> ReportError + '_ {
    move |source| ReportError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Writes the report of a case's outcome into `dir` (created; files replaced). Nothing
/// is run: the figures and tables come from the outcome.
pub fn report_case(outcome: &CaseOutcome, dir: &Path) -> Result<CaseReport, ReportError> {
    let CaseOutcome { case, checks, .. } = outcome;
    let Some((model, run)) = outcome.transient() else {
        return Err(ReportError::Static(case.name.clone()));
    };
    // A plate in bending; a target of membranes alone (an in-plane strip) is not one.
    let plate = model
        .elements
        .iter()
        .any(|e| e.kernel.family().shell().is_some_and(|s| s.g_bending.is_some()));
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let footer = format!(
        "case {} · deck {} · scheme {} · dt {:e} {} · {} steps",
        case.name,
        model.name,
        run.scheme.name(),
        run.dt,
        model.units.time,
        run.steps
    );
    let external = external_series(case)?;
    let fig = Fig::new(model, run, dir, &footer, &external);
    let figures = if model.contact.is_none() {
        free_response_figures(&fig)
    } else if model.rod.is_some() {
        rod_figures(&fig)
    } else if plate {
        plate_figures(&fig)
    } else {
        contact_force_figure(&fig)
    }?;
    let markdown = markdown(case, model, run, checks, &figures);
    std::fs::write(dir.join("index.md"), &markdown).map_err(io(dir))?;
    std::fs::write(dir.join("index.html"), html(&case.name, &markdown)).map_err(io(dir))?;
    let failed = checks.iter().filter(|c| !c.passed).count();
    Ok(CaseReport {
        name: case.name.clone(),
        markdown,
        figures,
        passed: checks.len() - failed,
        failed,
        summary: run.summary.clone(),
        human: crate::output::human_summary(model, run),
    })
}

/// The time axis of a figure or table: the deck's time unit, in µs when it is the
/// second ([`crate::deck::Units::short_time`]).
struct TimeAxis {
    scale: f64,
    unit: String,
    /// The deck's times are seconds, as the paper's published times are.
    seconds: bool,
}

impl TimeAxis {
    fn of(model: &Model) -> Self {
        let (scale, unit) = model.units.short_time();
        TimeAxis {
            scale,
            unit,
            seconds: model.units.in_seconds(),
        }
    }
    fn map(&self, t: &[f64]) -> Vec<f64> {
        t.iter().map(|x| x * self.scale).collect()
    }
    fn label(&self) -> String {
        format!("time [{}]", self.unit)
    }
}

fn energy_lines(e: &[EnergyRow], x: impl Fn(f64) -> f64) -> Vec<Line> {
    let t: Vec<f64> = e.iter().map(|r| x(r.time)).collect();
    let get = |f: fn(&EnergyRow) -> f64| e.iter().map(f).collect::<Vec<f64>>();
    vec![
        Line::new("KE impactor (Eq. 14)", t.clone(), get(|r| r.ke_impactor), 0),
        Line::new("SE impactor (Eq. 15)", t.clone(), get(|r| r.se_impactor), 1),
        // Dashed: KE_t and SE_t are equal while a pulse travels, and one would hide
        // the other.
        Line::new("KE target (½vᵀMv)", t.clone(), get(|r| r.ke_target), 2).dashed(),
        Line::new("SE target (Eq. 17)", t.clone(), get(|r| r.se_target), 3),
        Line::new(
            "target total KE_t + SE_t",
            t.clone(),
            get(|r| r.ke_target + r.se_target),
            4,
        ),
        Line::new("total (Eq. 13)", t, get(|r| r.total), 5),
    ]
}

/// Refuses a history signal sampled coarser than a tenth of the contact pulse: drawn
/// from so few points a pulse loses its peak (and a reference sampled at the same
/// points seems to agree). The case should record every step (`every_step = true`).
fn resolves_the_pulse(f: &Fig, stem: &Path) -> Result<(), ReportError> {
    let h = &f.run.history;
    let (Some(pulse), true) = (f.run.summary.contact.duration, h.len() > 1) else {
        return Ok(());
    };
    let sample = h[1][0] - h[0][0];
    if sample > pulse / 10.0 {
        return Err(crate::plot::PlotError {
            path: stem.with_extension("png").display().to_string(),
            source: crate::plot::err(format!(
                "the history is written every {sample:.4e}, coarser than a tenth of the contact pulse ({pulse:.4e}): \
                 record every step (every_step = true in the case file)"
            )),
        }
        .into());
    }
    Ok(())
}

/// The samples (t, y) with t ≤ `t_end`, every `every`-th one.
fn samples_until(t: &[f64], y: &[f64], t_end: f64, every: usize) -> (Vec<f64>, Vec<f64>) {
    t.iter()
        .zip(y)
        .filter(|(t, _)| **t <= t_end)
        .step_by(every)
        .map(|(a, b)| (*a, *b))
        .unzip()
}

/// What every figure of a case reads.
struct Fig<'a> {
    model: &'a Model,
    run: &'a RunResult,
    dir: &'a Path,
    footer: &'a str,
    ax: TimeAxis,
    /// Other solvers' results the case is checked against (its `external` checks).
    external: &'a [ExternalSeries],
}

impl<'a> Fig<'a> {
    fn new(
        model: &'a Model,
        run: &'a RunResult,
        dir: &'a Path,
        footer: &'a str,
        external: &'a [ExternalSeries],
    ) -> Self {
        Fig {
            model,
            run,
            dir,
            footer,
            ax: TimeAxis::of(model),
            external,
        }
    }

    /// The external solvers' curve of a history column up to `t_end`, its time mapped
    /// by `x`, dotted, in `color`.
    fn external_line(&self, ours: &str, t_end: f64, x: impl Fn(f64) -> f64, color: usize) -> Option<Line> {
        let e = self.external.iter().find(|e| e.ours == ours)?;
        let (t, v) = samples_until(&e.time, &e.values, t_end, 1);
        Some(
            Line::new(
                format!("{} ({})", e.solver, e.theirs),
                t.into_iter().map(x).collect(),
                v,
                color,
            )
            .dashed(),
        )
    }
}

/// The external series of a case's `external` checks.
fn external_series(case: &Case) -> Result<Vec<ExternalSeries>, ReportError> {
    let mut out: Vec<ExternalSeries> = Vec::new();
    for spec in &case.checks {
        if let CheckSpec::External {
            file,
            solver,
            time,
            columns,
            ..
        } = spec
        {
            let series =
                external::load(&crate::verify::case::rel(case, file), solver, time, columns).map_err(|source| {
                    crate::verify::CheckError::External {
                        case: case.name.clone(),
                        source,
                    }
                })?;
            for s in series {
                if !out.iter().any(|o| o.ours == s.ours) {
                    out.push(s);
                }
            }
        }
    }
    Ok(out)
}

fn rod_figures(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    use crate::physics::references::{semi_infinite, ReferenceError};
    let (model, run) = (f.model, f.run);
    let (tr, _, lc) = match semi_infinite(model) {
        Ok(r) => r,
        // A contact that outlasts 2L/C: the rod moves as a rigid body during it, and
        // the paper's figures and readings do not apply.
        Err(ReferenceError::ContactDoesNotEnd) => return rigid_rod_figures(f),
        Err(e) => return Err(e.into()),
    };
    let end = run
        .summary
        .rod
        .as_ref()
        .and_then(|r| r.contact_end_tcl)
        .unwrap_or(f64::NAN);
    let mut out = rod_force(f, &tr, lc, end)?;
    out.extend(rod_strain(f, &tr, lc)?);
    out.extend(rod_energy(f, lc, end)?);
    Ok(out)
}

/// A rod struck by a contact much softer than the rod (it outlasts 2L/C): the force
/// against two rigid bodies in Hertz contact (reduced mass), and the energies in time.
fn rigid_rod_figures(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let u = &model.units;
    let (d, mu) = crate::physics::references::two_rigid_bodies(model)?;
    let (_, f_max, duration) = analytic::rigid_target(mu, d.v0, d.stiffness);
    let t_end = 1.2 * duration;
    let tr = d.integrate(t_end, duration / 2.0e4);
    let (ta, fa) = samples_until(&tr.time, &tr.force, f64::INFINITY, 20);
    let s = &run.series;
    let (tf, ff) = samples_until(&s.time, &s.force, t_end, 1);
    let mut out = plot::line_chart(
        &Chart {
            title: "Impact force: a contact much softer than the rod".into(),
            x_label: ax.label(),
            y_label: format!("contact force [{}]", u.force),
            footer: footer.into(),
            lines: vec![
                Line::new("impactlab (FE rod)", ax.map(&tf), ff, 0),
                Line::new(
                    format!("two rigid bodies, reduced mass {mu:.4e} (peak {f_max:.4e})"),
                    ax.map(&ta),
                    fa,
                    1,
                )
                .dashed(),
            ],
            headroom: 0.25,
            difference: Some(format!("reference − impactlab [{}]", u.force)),
            ..Default::default()
        },
        &dir.join("force"),
    )?;
    out.extend(plot::line_chart(
        &Chart {
            title: "Energy distribution, impactor and rod".into(),
            x_label: ax.label(),
            y_label: format!("energy [{}·{}]", u.force, u.length),
            footer: footer.into(),
            lines: energy_lines(&run.energy, |t| t * ax.scale),
            headroom: 0.45,
            ..Default::default()
        },
        &dir.join("energy"),
    )?);
    Ok(out)
}

/// The contact force against the ball on a semi-infinite rod (paper Fig. 2).
fn rod_force(f: &Fig, tr: &analytic::Trace, lc: f64, end: f64) -> Result<Vec<PathBuf>, ReportError> {
    let (u, s, ax, footer, dir) = (&f.model.units, &f.run.series, &f.ax, f.footer, f.dir);
    let mut out = Vec::new();
    let t_end = 1.2 * end * lc;
    let (tf, ff) = samples_until(&s.time, &s.force, t_end, 1);
    let (ta, fa) = samples_until(&tr.time, &tr.force, t_end, 50);
    out.extend(plot::line_chart(
        &Chart {
            title: "Impact force history (paper Fig. 2)".into(),
            x_label: ax.label(),
            y_label: format!("contact force [{}]", u.force),
            footer: footer.into(),
            lines: [
                Line::new("impactlab (FE rod)", ax.map(&tf), ff, 0),
                Line::new("ball on a semi-infinite rod (analytic)", ax.map(&ta), fa, 1).dashed(),
            ]
            .into_iter()
            .chain(f.external_line("contact_force", t_end, |t| t * ax.scale, 5))
            .collect(),
            vlines: vec![(end * lc * ax.scale, format!("contact ends, tC/L = {end:.4}"))],
            headroom: 0.25,
            difference: Some(format!("reference − impactlab [{}]", u.force)),
            ..Default::default()
        },
        &dir.join("force"),
    )?);
    Ok(out)
}

/// The strain of the requested element nearest mid-rod against d'Alembert (Fig. 3).
fn rod_strain(f: &Fig, tr: &analytic::Trace, lc: f64) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, footer, dir) = (f.model, f.run, f.footer, f.dir);
    let rod = model.rod.expect("a rod");
    let mut out = Vec::new();
    // Mid-rod strain: the requested element nearest L/2.
    let mid = model
        .elements
        .iter()
        .filter_map(|e| {
            let Family::Rod { .. } = e.kernel.family() else {
                return None;
            };
            let x = e.points();
            let xc = 0.5 * (x[0][0] + x[1][0]);
            run.column_values(&Column::rod_strain(e.eid)).map(|v| (e.eid, xc, v))
        })
        .min_by(|a, b| {
            (a.1 - rod.length / 2.0)
                .abs()
                .total_cmp(&(b.1 - rod.length / 2.0).abs())
        });
    if let Some((eid, xc, strain)) = mid {
        resolves_the_pulse(f, &dir.join("strain"))?;
        let t: Vec<f64> = run.history.iter().map(|r| r[0]).collect();
        let x0 = model
            .elements
            .iter()
            .find_map(|e| match e.kernel.family() {
                Family::Rod { .. } => {
                    let x = e.points();
                    Some(x[0][0].min(x[1][0]))
                }
                _ => None,
            })
            .unwrap_or(0.0);
        let ea = rod.e * rod.area;
        let dal: Vec<f64> = t
            .iter()
            .map(|&ti| {
                if ti / lc < 1.45 {
                    analytic::dalembert_strain(tr, xc - x0, rod.wave_speed, ea, ti)
                } else {
                    f64::NAN
                }
            })
            .collect();
        let tcl = |v: &[f64]| v.iter().map(|x| x / lc).collect::<Vec<f64>>();
        out.extend(plot::line_chart(
            &Chart {
                title: format!("Strain at mid-rod, element {eid} (paper Fig. 3)"),
                x_label: "tC/L [-]".into(),
                y_label: "axial strain [-]".into(),
                footer: footer.into(),
                lines: [
                    Line::new("impactlab", tcl(&t), strain, 0),
                    Line::new(
                        "d'Alembert −F(t − x/C)/EA, until the far-end reflection",
                        tcl(&t),
                        dal,
                        1,
                    )
                    .dashed(),
                ]
                .into_iter()
                .chain(f.external_line(&Column::rod_strain(eid).name(), f64::INFINITY, |t| t / lc, 5))
                .collect(),
                difference: Some("reference − impactlab [-]".into()),
                ..Default::default()
            },
            &dir.join("strain"),
        )?);
    }
    Ok(out)
}

/// The energy partition against tC/L with the paper's readings (Fig. 4).
fn rod_energy(f: &Fig, lc: f64, end: f64) -> Result<Vec<PathBuf>, ReportError> {
    let (u, run, footer, dir) = (&f.model.units, f.run, f.footer, f.dir);
    let mut out = Vec::new();
    let mut lines = energy_lines(&run.energy, |t| t / lc);
    let te: Vec<f64> = run.energy.iter().map(|r| r.time / lc).collect();
    lines.extend(dissipation_lines(f.model, run, &te));
    let u0 = run.energy[0].total;
    let tmax = run.energy.last().map_or(1.0, |r| r.time / lc);
    lines.push(
        Line::new(
            "paper: 80 % of U0 left in the rod",
            vec![0.0, tmax],
            vec![0.8 * u0, 0.8 * u0],
            6,
        )
        .dashed(),
    );
    let vz = run
        .summary
        .rod
        .as_ref()
        .and_then(|r| r.velocity_zero_time_tcl)
        .unwrap_or(f64::NAN);
    out.extend(plot::line_chart(
        &Chart {
            title: "Energy distribution (paper Fig. 4)".into(),
            x_label: "tC/L [-]".into(),
            y_label: format!("energy [{}·{}]", u.force, u.length),
            footer: footer.into(),
            lines,
            vlines: vec![
                (0.25, "paper: impactor at rest, 0.25".into()),
                (vz, format!("impactlab: at rest, {vz:.4}")),
                (0.4, "paper: contact over, 0.4".into()),
                (end, format!("impactlab: contact over, {end:.4}")),
            ],
            headroom: 0.75,
            ..Default::default()
        },
        &dir.join("energy"),
    )?);
    Ok(out)
}

/// The contact force of a target with no figures of its own (neither a rod of CRODs
/// nor a plate in bending), with the curves of the solvers it is checked against.
fn contact_force_figure(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let s = &run.series;
    let end = run.summary.contact.intervals.first().map_or(f64::INFINITY, |i| i[1]);
    let t_end = 1.15 * end.min(s.time.last().copied().unwrap_or(0.0));
    let (tf, ff) = samples_until(&s.time, &s.force, t_end, 1);
    Ok(plot::line_chart(
        &Chart {
            title: format!("Contact force, {}", model.name),
            x_label: ax.label(),
            y_label: format!("contact force [{}]", model.units.force),
            footer: footer.into(),
            lines: std::iter::once(Line::new("impactlab", ax.map(&tf), ff, 0))
                .chain(f.external_line("contact_force", t_end, |t| t * ax.scale, 5))
                .collect(),
            ..Default::default()
        },
        &dir.join("force"),
    )?)
}

/// A structure moving without an impactor (released from a displacement or a
/// velocity): its recorded displacements, and its energies with what damping took.
fn free_response_figures(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    use crate::run::history::Column;
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let u = &model.units;
    let t = ax.map(&run.history.iter().map(|r| r[0]).collect::<Vec<_>>());
    let lines: Vec<Line> = run
        .history_columns
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c, Column::Disp(..)))
        .enumerate()
        .map(|(k, (j, c))| Line::new(c.name(), t.clone(), run.history.iter().map(|r| r[j]).collect(), k))
        .collect();
    let mut out = plot::line_chart(
        &Chart {
            title: format!("Displacements, {}", model.name),
            x_label: ax.label(),
            y_label: format!("displacement [{}]", u.length),
            footer: footer.into(),
            lines,
            ..Default::default()
        },
        &dir.join("displacement"),
    )?;
    let te = ax.map(&run.energy.iter().map(|r| r.time).collect::<Vec<_>>());
    let get = |f: fn(&EnergyRow) -> f64| run.energy.iter().map(f).collect::<Vec<f64>>();
    let mut lines = vec![
        Line::new("KE target (½vᵀMv)", te.clone(), get(|r| r.ke_target), 2).dashed(),
        Line::new("SE target (Eq. 17)", te.clone(), get(|r| r.se_target), 3),
        Line::new("total (Eq. 13)", te.clone(), get(|r| r.total), 5),
    ];
    lines.extend(dissipation_lines(model, run, &te));
    out.extend(plot::line_chart(
        &Chart {
            title: format!("Energy, {}", model.name),
            x_label: ax.label(),
            y_label: format!("energy [{}·{}]", u.force, u.length),
            footer: footer.into(),
            lines,
            headroom: 0.3,
            ..Default::default()
        },
        &dir.join("energy"),
    )?);
    Ok(out)
}

/// What the structure's damping and the contact's hysteresis dissipated, each a band
/// stacked on the total (damping, then the contact): the top of the stack is the ledger's
/// balance, flat at U0 when it closes. Nothing for a run that dissipates nothing.
fn dissipation_lines(model: &Model, run: &RunResult, t: &[f64]) -> Vec<Line> {
    let e = &run.energy;
    let mut base: Vec<f64> = e.iter().map(|r| r.total).collect();
    let mut lines = Vec::new();
    for d in crate::ledger::Dissipations::of(model).booked() {
        // The contact's in the colour of the energy it holds (SE impactor).
        let color = if d.symbol == "D_c" { 1 } else { 6 };
        let top: Vec<f64> = base.iter().zip(e).map(|(b, r)| b + (d.value)(r)).collect();
        lines.push(
            Line::new(
                format!("{} (stacked on the total)", d.what),
                t.to_vec(),
                top.clone(),
                color,
            )
            .band(base),
        );
        base = top;
    }
    lines
}

fn plate_figures(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let mut out = plate_force(f)?;
    out.extend(plate_displacement(f)?);
    out.extend(plate_gages(f)?);
    out.extend(plate_energy(f)?);
    Ok(out)
}

/// The contact force against the infinite plate (paper Fig. 6).
fn plate_force(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let (u, s) = (&model.units, &run.series);
    let mut out = Vec::new();
    let end = run.summary.contact.intervals.first().map_or(250e-6, |i| i[1]);
    let (tf, ff) = samples_until(&s.time, &s.force, 1.15 * end, 1);
    // A stiffened plate or a curved shell is not the paper's: no infinite-plate
    // reference, no paper times. A shell is curved when two of its elements' normals
    // are more than 1e-2 rad apart (the panel of radius 10⁴ spans: 1e-4, the paper's
    // plate in the limit; of radius 10 in: 0.6).
    let stiffened = model
        .elements
        .iter()
        .any(|e| matches!(e.kernel.family(), crate::elements::Family::Beam { .. }));
    let curved = shell_normal_spread(model) > 1e-2;
    let paper_plate = !stiffened && !curved;
    let label = if curved {
        "impactlab (FE shell)"
    } else {
        "impactlab (FE plate)"
    };
    let mut lines = vec![Line::new(label, ax.map(&tf), ff, 0)];
    if paper_plate {
        let (p, _) = crate::physics::references::infinite_plate(model)?;
        let tr = p.integrate(80e-6, 1e-9);
        // Through Hertz's law: for a contact that unloads along another curve, valid
        // up to its peak only.
        let (until, label) = if model.hysteretic() {
            let k = tr
                .force
                .iter()
                .enumerate()
                .fold(0, |m, (k, f)| if *f > tr.force[m] { k } else { m });
            (
                tr.time[k],
                "infinite plate, Zener/Olsson (Hertz's law: valid up to its peak)",
            )
        } else {
            (
                f64::INFINITY,
                "infinite plate, Zener/Olsson (valid before edge reflections)",
            )
        };
        let (ta, fa) = samples_until(&tr.time, &tr.force, until, 100);
        lines.push(Line::new(label, ax.map(&ta), fa, 1).dashed());
    }
    out.extend(plot::line_chart(
        &Chart {
            title: if stiffened {
                "Impact force history, stiffened plate".into()
            } else if curved {
                "Impact force history, curved shell".into()
            } else {
                "Impact force history (paper Fig. 6)".into()
            },
            x_label: ax.label(),
            y_label: format!("contact force [{}]", u.force),
            footer: footer.into(),
            lines: lines
                .into_iter()
                .chain(f.external_line("contact_force", 1.15 * end, |t| t * ax.scale, 5))
                .collect(),
            // The paper's times are seconds: marked only on a deck in seconds.
            vlines: if ax.seconds && paper_plate {
                vec![
                    (204.0, "measured contact time, 204 µs".into()),
                    (175.0, "paper: secondary impact, 175 µs".into()),
                ]
            } else {
                Vec::new()
            },
            hlines: run
                .summary
                .delamination
                .iter()
                .map(|d| {
                    (
                        d.onset.critical_force,
                        format!(
                            "delamination threshold F_crit (Davies-Zhang, G_IIc {} {}/{})",
                            d.onset.g_iic, u.force, u.length
                        ),
                    )
                })
                .collect(),
            headroom: 0.3,
            difference: paper_plate.then(|| format!("reference − impactlab [{}]", u.force)),
            ..Default::default()
        },
        &dir.join("force"),
    )?);
    Ok(out)
}

/// The largest angle (radians) between the normals of two of the model's shells
/// ([`crate::geometry::shell_frame`] of each one's corners): 0 for a flat plate,
/// however it is turned.
fn shell_normal_spread(model: &Model) -> f64 {
    let normals: Vec<nalgebra::Vector3<f64>> = model
        .elements
        .iter()
        .filter(|e| e.kernel.family().shell().is_some())
        .filter_map(|e| crate::geometry::shell_frame(&e.points()).ok())
        .map(|f| f.axes.column(2).into_owned())
        .collect();
    let Some(first) = normals.first() else {
        return 0.0;
    };
    normals
        .iter()
        .map(|n| n.dot(first).abs().min(1.0).acos())
        .fold(0.0, f64::max)
}

/// The transverse displacement at the case's snapshot times (paper Fig. 7).
fn plate_displacement(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let u = &model.units;
    let mut out = Vec::new();
    // Displacement field w at the snapshot times.
    let w_index: std::collections::HashMap<i64, usize> = run
        .dofs
        .iter()
        .enumerate()
        .filter(|(_, l)| l.comp == 3)
        .map(|(i, l)| (l.point, i))
        .collect();
    // The recorded elements: the one under the impactor, then gages A and B (as the
    // gage figures take them), marked at their centres.
    let marks: Vec<((f64, f64), String)> = recorded_strain_elements(run)
        .iter()
        .take(3)
        .zip(["impact", "A", "B"])
        .filter_map(|(eid, label)| {
            let e = model.elements.iter().find(|e| e.eid == *eid)?;
            e.kernel.family().shell()?;
            let c = e
                .kernel
                .points()
                .iter()
                .fold((0.0, 0.0), |a, p| (a.0 + p[0] / 4.0, a.1 + p[1] / 4.0));
            Some((c, label.to_string()))
        })
        .collect();
    // Each grid point of the plate's elements once, with its coordinates.
    let grid_xy: std::collections::BTreeMap<i64, (f64, f64)> = model
        .elements
        .iter()
        .filter_map(|e| {
            e.kernel.family().shell()?;
            Some(
                e.grids
                    .iter()
                    .copied()
                    .zip(e.points().into_iter().map(|p| (p[0], p[1]))),
            )
        })
        .flatten()
        .collect();
    let panels: Vec<Contour> = run
        .snapshots
        .iter()
        .map(|snap| Contour {
            title: format!("t = {:.0} {}", snap.time * ax.scale, ax.unit),
            unit: u.length.clone(),
            cells: model
                .elements
                .iter()
                .filter_map(|e| {
                    e.kernel.family().shell()?;
                    let points = e.points();
                    let xy: [(f64, f64); 4] = std::array::from_fn(|k| (points[k][0], points[k][1]));
                    let v: f64 = e
                        .grids
                        .iter()
                        .map(|g| w_index.get(g).map_or(0.0, |&i| snap.u[i]))
                        .sum::<f64>()
                        / 4.0;
                    Some((xy, v))
                })
                .collect(),
            lattice: {
                let nodes: Vec<(f64, f64, f64)> = grid_xy
                    .iter()
                    .map(|(g, (x, y))| (*x, *y, w_index.get(g).map_or(0.0, |&i| snap.u[i])))
                    .collect();
                plot::Lattice::from_nodes(&nodes)
            },
            marks: marks.clone(),
        })
        .collect();
    if !panels.is_empty() {
        out.extend(plot::contours(
            &panels,
            &dir.join("displacement"),
            &format!(
                "Transverse displacement w [{}] (paper Fig. 7); contours at ±1/5…4/5 of each panel's |max|, negative dashed",
                u.length
            ),
            footer,
        )?);
    }
    Ok(out)
}

/// The elements whose strains the run recorded, by id: on the paper's plate the one
/// under the impactor, then gages A and B.
fn recorded_strain_elements(run: &RunResult) -> Vec<i64> {
    run.history_columns
        .iter()
        .filter_map(|c| match c {
            Column::Element { eid, value } if value.measure == Measure::Strain => Some(*eid),
            _ => None,
        })
        .collect::<std::collections::BTreeSet<i64>>()
        .into_iter()
        .collect()
}

/// The strains at gages A and B, both fibres (paper Figs. 8 and 9).
fn plate_gages(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let mut out = Vec::new();
    let mesh_gages = recorded_strain_elements(run);
    let t: Vec<f64> = run.history.iter().map(|r| r[0] * ax.scale).collect();
    if !mesh_gages.is_empty() {
        resolves_the_pulse(f, &dir.join("gage-a"))?;
    }
    // The gages are the recorded elements other than the struck one (every corner of
    // which the contact loads), A then B: the paper's deck records the struck element
    // too, a scene only the gages it names.
    let loaded: std::collections::BTreeSet<i64> = model
        .contact
        .iter()
        .flat_map(|c| c.loads.iter().map(|l| l.label.point))
        .collect();
    let struck = |eid: i64| {
        model
            .elements
            .iter()
            .find(|e| e.eid == eid)
            .is_some_and(|e| e.grids.iter().all(|g| loaded.contains(g)))
    };
    for (k, eid) in mesh_gages.iter().filter(|&&e| !struck(e)).take(2).enumerate() {
        let (fig, gage) = if k == 0 { ("Fig. 8", "A") } else { ("Fig. 9", "B") };
        let mut lines = Vec::new();
        for (i, (fibre, comp)) in [
            (Fibre::Z2, Plane::Xx),
            (Fibre::Z2, Plane::Yy),
            (Fibre::Z1, Plane::Xx),
            (Fibre::Z1, Plane::Yy),
        ]
        .into_iter()
        .enumerate()
        {
            if let Some(v) = run.column_values(&Column::shell_strain(*eid, fibre, comp)) {
                let side = if fibre == Fibre::Z2 {
                    "back face +T/2"
                } else {
                    "struck face −T/2"
                };
                let c = if comp == Plane::Xx { "xx" } else { "yy" };
                let l = Line::new(format!("ε{c}, {side}"), t.clone(), v, i);
                lines.push(if fibre == Fibre::Z1 { l.dashed() } else { l });
            }
        }
        for (comp, color) in [(Plane::Xx, 5), (Plane::Yy, 6)] {
            let name = Column::shell_strain(*eid, Fibre::Z2, comp).name();
            lines.extend(f.external_line(&name, f64::INFINITY, |t| t * ax.scale, color));
        }
        out.extend(plot::line_chart(
            &Chart {
                title: format!("Strain at gage {gage}, element {eid} (paper {fig})"),
                x_label: ax.label(),
                y_label: "strain [-]".into(),
                footer: footer.into(),
                lines,
                ..Default::default()
            },
            &dir.join(format!("gage-{}", gage.to_lowercase())),
        )?);
    }
    Ok(out)
}

/// The energy partition of impactor and plate with the deck's external work.
fn plate_energy(f: &Fig) -> Result<Vec<PathBuf>, ReportError> {
    let (model, run, ax, footer, dir) = (f.model, f.run, &f.ax, f.footer, f.dir);
    let u = &model.units;
    let mut out = Vec::new();
    let mut lines = energy_lines(&run.energy, |t| t * ax.scale);
    let te = ax.map(&run.energy.iter().map(|r| r.time).collect::<Vec<_>>());
    lines.push(Line::new(
        "external work (deck's non-conservative NOLIN3)",
        te.clone(),
        run.energy.iter().map(|r| r.external_work).collect(),
        6,
    ));
    lines.extend(dissipation_lines(model, run, &te));
    out.extend(plot::line_chart(
        &Chart {
            title: "Energy distribution, impactor and plate".into(),
            x_label: ax.label(),
            y_label: format!("energy [{}·{}]", u.force, u.length),
            footer: footer.into(),
            lines,
            headroom: 0.45,
            ..Default::default()
        },
        &dir.join("energy"),
    )?);
    Ok(out)
}

/// Ledger rows at the key instants: start, peak force, impactor at rest, separation, end.
fn key_instants(run: &RunResult) -> Vec<(&'static str, usize)> {
    let s = &run.series;
    let nearest = |t: f64| s.time.iter().position(|&x| x >= t).unwrap_or(s.time.len() - 1);
    let sm = &run.summary;
    let mut v = vec![("start", 0)];
    if let Some(t) = sm.contact.peak_force_time.filter(|_| sm.contact.peak_force > 0.0) {
        v.push(("peak force", nearest(t)));
    }
    if let Some(t) = sm.impactor.velocity_zero_time {
        v.push(("impactor at rest", nearest(t)));
    }
    if let Some(i) = sm.contact.intervals.first() {
        v.push(("separation", nearest(i[1])));
    }
    v.push(("end", s.time.len() - 1));
    v
}

fn markdown(case: &Case, model: &Model, run: &RunResult, checks: &[CheckResult], figures: &[PathBuf]) -> String {
    let mut m = String::new();
    let _ = writeln!(m, "# {} — {}\n", case.name, case.description);
    what_was_run(&mut m, model, run);
    summary_table(&mut m, model, run);
    ledger_table(&mut m, model, run);
    checks_table(&mut m, case, checks);
    figure_list(&mut m, figures);
    m
}

/// What was run. No wall time, date or path: a committed page is made byte for byte
/// again on any machine (the run's wall time is in its `summary.json`).
fn what_was_run(m: &mut String, model: &Model, run: &RunResult) {
    let (s, u) = (&run.summary, &model.units);
    let _ = writeln!(m, "## What was run\n");
    let _ = writeln!(m, "| | |\n|---|---|");
    let _ = writeln!(m, "| deck | `{}` ({}) |", model.name, model.title.trim());
    let _ = writeln!(m, "| scheme | `{}` |", run.scheme.name());
    let _ = writeln!(m, "| Δt, steps | {:e} {}, {} |", run.dt, u.time, run.steps);
    let _ = writeln!(
        m,
        "| DOF | {} active, {} solved, {} inert skipped |",
        s.model.active_dofs, s.model.solved_dofs, s.model.inert_dofs_skipped
    );
    let _ = writeln!(m, "| units | {}, {}, {} |\n", u.length, u.force, u.time);
}

fn summary_table(m: &mut String, model: &Model, run: &RunResult) {
    let (s, u, ax) = (&run.summary, &model.units, TimeAxis::of(model));
    let _ = writeln!(m, "## Summary\n");
    let _ = writeln!(m, "| quantity | value |\n|---|---|");
    let row = |m: &mut String, name: &str, v: Option<f64>, unit: &str| {
        let _ = writeln!(m, "| {name} | {} {unit} |", v.map_or("—".into(), |x| sig(x, 6)));
    };
    let energy = format!("{}·{}", u.force, u.length);
    if model.contact.is_some() {
        let iv: Vec<String> = s
            .contact
            .intervals
            .iter()
            .map(|i| format!("{}–{} {}", sig(i[0] * ax.scale, 5), sig(i[1] * ax.scale, 5), ax.unit))
            .collect();
        let _ = writeln!(m, "| contact intervals | {} |", iv.join(", "));
        row(m, "peak force", Some(s.contact.peak_force), &u.force);
        row(
            m,
            "peak force time",
            s.contact.peak_force_time.map(|t| t * ax.scale),
            &ax.unit,
        );
        row(
            m,
            "impactor at rest",
            s.impactor.velocity_zero_time.map(|t| t * ax.scale),
            &ax.unit,
        );
        row(
            m,
            "rebound velocity",
            s.impactor.rebound_velocity,
            &format!("{}/{}", u.length, u.time),
        );
        row(
            m,
            "energy transferred to the target",
            s.energy.transferred_fraction.map(|x| 100.0 * x),
            "%",
        );
    } else {
        // A structure moving without an impactor: its energy at both ends.
        row(m, "energy at the start", s.energy.initial, &energy);
        row(m, "energy at the end", s.energy.final_total, &energy);
    }
    if let Some(d) = &s.energy.damping {
        row(m, "energy dissipated by damping", Some(d.dissipated), &energy);
    }
    if let Some(c) = &s.energy.contact {
        row(m, "energy dissipated by the contact", Some(c.dissipated), &energy);
        row(m, "largest indentation", Some(c.max_indentation), &u.length);
        row(
            m,
            "permanent indentation (Yang and Sun's α0)",
            Some(c.permanent_indentation),
            &u.length,
        );
    }
    row(m, "max relative energy error", s.energy.max_relative_error, "");
    if let Some(r) = s.rod.as_ref().filter(|_| model.contact.is_some()) {
        row(m, "contact ends (tC/L)", r.contact_end_tcl, "");
        row(m, "impactor at rest (tC/L)", r.velocity_zero_time_tcl, "");
    }
}

fn ledger_table(m: &mut String, model: &Model, run: &RunResult) {
    let ax = TimeAxis::of(model);
    // The energy damping dissipated, D, and the contact's, D_c, only where there is one.
    let extra = crate::ledger::Dissipations::of(model).booked();
    let _ = writeln!(m, "\n## Energy ledger at key instants\n");
    let _ = writeln!(
        m,
        "| instant | t [{}] | KE_i | SE_i | KE_t | KE_t (Eq. 16) | SE_t | total | W_ext |{} error |\n|---|---|---|---|---|---|---|---|---|{}---|",
        ax.unit,
        extra.iter().map(|d| format!(" {} |", d.symbol)).collect::<String>(),
        "---|".repeat(extra.len())
    );
    for (name, k) in key_instants(run) {
        let r = &run.energy[k];
        let _ = writeln!(
            m,
            "| {name} | {} | {} | {} | {} | {} | {} | {} | {} |{} {:.2e} |",
            sig(r.time * ax.scale, 5),
            sig(r.ke_impactor, 5),
            sig(r.se_impactor, 5),
            sig(r.ke_target, 5),
            sig(r.ke_target_eq16, 5),
            sig(r.se_target, 5),
            sig(r.total, 6),
            sig(r.external_work, 4),
            extra
                .iter()
                .map(|d| format!(" {} |", sig((d.value)(r), 6)))
                .collect::<String>(),
            r.error
        );
    }
}

fn checks_table(m: &mut String, case: &Case, checks: &[CheckResult]) {
    let file = case
        .path
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default();
    let _ = writeln!(m, "\n## Verification checks (`verification/{file}`)\n");
    let _ = writeln!(
        m,
        "| check | value | reference | tolerance | verdict |\n|---|---|---|---|---|"
    );
    for c in checks {
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {} |",
            c.check.replace('|', "/"),
            sig(c.value, 6),
            c.reference.map_or("-".into(), |r| sig(r, 6)),
            c.bound.text,
            if c.passed { "pass" } else { "**FAIL**" }
        );
    }
}

fn figure_list(m: &mut String, figures: &[PathBuf]) {
    let _ = writeln!(m, "\n## Figures\n");
    for f in figures.iter().filter(|f| f.extension().is_some_and(|e| e == "png")) {
        let name = f
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let stem = name.trim_end_matches(".png");
        let _ = writeln!(m, "![{stem}]({name}) ([SVG]({stem}.svg))\n");
    }
}

fn html(title: &str, markdown: &str) -> String {
    let mut body = String::new();
    let parser = pulldown_cmark::Parser::new_ext(markdown, pulldown_cmark::Options::ENABLE_TABLES);
    pulldown_cmark::html::push_html(&mut body, parser);
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{title}</title>\n<style>body{{font-family:sans-serif;max-width:1100px;margin:2em auto}}table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:3px 8px;text-align:right}}img{{max-width:100%}}</style></head>\n<body>\n{body}</body></html>\n"
    )
}

/// A markdown page as HTML, its links to `.md` pages pointing at their `.html` twins.
pub fn page_html(title: &str, markdown: &str) -> String {
    html(title, &markdown.replace(".md)", ".html)"))
}

/// The HTML pages of a reports directory besides the case pages: `index.html` from
/// the index, and `README.html` beside each study's `README.md` (a subdirectory with a
/// README.md and no case report), each with its path relative to `dir`.
pub fn html_pages(dir: &Path, index_md: &str) -> Vec<(PathBuf, String)> {
    let mut out = vec![(PathBuf::from("index.html"), page_html("impactlab reports", index_md))];
    let mut studies: Vec<(String, String)> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| !e.path().join("index.md").exists())
        .filter_map(|e| {
            let md = std::fs::read_to_string(e.path().join("README.md")).ok()?;
            Some((e.file_name().to_string_lossy().into_owned(), md))
        })
        .collect();
    studies.sort();
    for (name, md) in studies {
        out.push((PathBuf::from(&name).join("README.html"), page_html(&name, &md)));
    }
    out
}

/// `reports/README.md`: one line per case report found in `dir` (a subdirectory with
/// an `index.md`), with its verdict counts read from that report, so regenerating one
/// case keeps the others listed.
pub fn index(dir: &Path) -> String {
    let mut m = String::from(
        "# Reports\n\nRegenerate with `cargo run --release -- report` (all cases in `verification/` that run a \
         deck); the studies with `impactlab study accuracy`, `impactlab study mesh`, `impactlab study \
         panel`, `impactlab study stiffened`, `impactlab study stability` and `impactlab study mutants`.\n\n\
         | case | checks passed | failed | report |\n|---|---|---|---|\n",
    );
    let mut cases: Vec<(String, String)> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let md = std::fs::read_to_string(e.path().join("index.md")).ok()?;
            Some((e.file_name().to_string_lossy().into_owned(), md))
        })
        .collect();
    cases.sort();
    for (name, md) in &cases {
        let passed = md.matches("| pass |").count();
        let failed = md.matches("| **FAIL** |").count();
        let _ = writeln!(m, "| {name} | {passed} | {failed} | [report]({name}/index.md) |");
    }
    let _ = writeln!(
        m,
        "\nStudies: [accuracy](accuracy/README.md) (what accuracy costs in time), [mesh](mesh/README.md) (the \
         paper's plate mesh study, 25/49/61), [panel](panel/README.md) (the curved panel, R = 10 in, against \
         the flat plate), [stiffened](stiffened/README.md) (the plate with blade stiffeners, struck on one \
         and between them), \
         [stability](stability/README.md) (the stability map), [scenes](scenes/README.md) (what each effect costs), \
         [mutants](mutants/README.md) (whether the gate catches injected faults)."
    );
    m
}
