//! The curved panel against the flat plate: the paper's plate and the same plate
//! wrapped onto a cylinder of radius [`RADIUS`] (its 6 in × 6 in as arc and width,
//! clamped, struck at the centre along the normal: [`crate::mesh::panel_deck`]), each on
//! the mesh study's meshes ([`super::mesh::MESHES`]), run alike by the study's settings
//! ([`options`]: 600 µs, long enough for the panel's first contact to end). Per run:
//! the contacts, the energy ledger at the end of the run (each part's share of the
//! initial energy) and its largest error, and the back-face gage strains at the
//! paper's gages A and B (the panel's in its elements' own axes, x along the arc).
//!
//! The study's data are `panel-study.csv` (one row per mesh and surface) and
//! `panel-histories.csv` (the contact force and gage strains at every output time);
//! the page and figures are made from those files alone, so a test remakes them.

use super::mesh::gage_columns;
use super::{history_extreme, StudyError};
use crate::mesh::{panel_model, plate_model};
use crate::plot::{self, Chart, Line};
use crate::run::{run_model, Column, RunOptions};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The panel's radius (in): 10 in, the plate's 6 in span a 34° arc, its crown 0.45 in
/// above its edges.
pub const RADIUS: f64 = 10.0;

/// The study's run settings: newmark at the paper's Δt for 6000 steps (600 µs: the
/// panel's first contact lasts about 340 µs, past the paper's 300).
pub fn options(progress: Option<indicatif::ProgressBar>) -> RunOptions {
    RunOptions {
        steps: Some(6000),
        ..super::mesh::options(progress)
    }
}

/// One run, as a row of `panel-study.csv` (the generated decks' units: in, lbf, s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PanelRow {
    /// Elements a side.
    pub n: usize,
    /// The cylinder's radius (in); `None` for the flat plate.
    pub radius_in: Option<f64>,
    /// Solved DOFs.
    pub solved_dofs: u64,
    /// Length of the first contact.
    pub contact_duration_s: Option<f64>,
    /// Contacts (intervals with α > 0) in the run.
    pub contacts: usize,
    /// The last contact is still open at the end of the run.
    pub open_at_end: bool,
    /// 1 − (v_rebound/v0)², once the impactor has left: the energy left in the target.
    pub transferred: Option<f64>,
    /// Largest contact force.
    pub peak_force_lbf: f64,
    /// Its time.
    pub peak_force_time_s: Option<f64>,
    /// The ledger's largest |relative energy error|.
    pub energy_error_max: Option<f64>,
    /// At the end of the run, the impactor's kinetic energy over the initial energy.
    pub impactor_ke_end: f64,
    /// The target's kinetic energy over the initial energy.
    pub target_ke_end: f64,
    /// The target's strain energy over the initial energy.
    pub target_se_end: f64,
    /// Back-face (z2 = +T/2) strain extremes at the gages, signed.
    pub gage_a_exx: Option<f64>,
    /// Gage A, εyy.
    pub gage_a_eyy: Option<f64>,
    /// Gage B, εxx.
    pub gage_b_exx: Option<f64>,
    /// Gage B, εyy.
    pub gage_b_eyy: Option<f64>,
    /// Wall-clock seconds of the run.
    pub wall_s: f64,
}

/// One output time of one run, as a row of `panel-histories.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PanelSample {
    /// Elements a side.
    pub n: usize,
    /// The cylinder's radius (in); `None` for the flat plate.
    pub radius_in: Option<f64>,
    /// Time.
    pub time_s: f64,
    /// Contact force.
    pub contact_force_lbf: f64,
    /// Gage A, back-face εyy.
    pub gage_a_eyy: f64,
    /// Gage B, back-face εyy.
    pub gage_b_eyy: f64,
}

/// Runs the flat plate and the panel on each mesh.
pub fn run(ns: &[usize], opts: &RunOptions) -> Result<(Vec<PanelRow>, Vec<PanelSample>), StudyError> {
    let (mut rows, mut samples) = (Vec::new(), Vec::new());
    for &n in ns {
        let (_, cols) = gage_columns(n)?;
        for radius in [None, Some(RADIUS)] {
            let model = match radius {
                None => plate_model(n)?,
                Some(r) => panel_model(n, r)?,
            };
            let run = run_model(&model, opts)?;
            let [axx, ayy, bxx, byy] = cols.map(|c| history_extreme(&run, &c).map(|e| e.value));
            let [ja, jb] = [&cols[1], &cols[3]].map(|c| run.column(c));
            let fc = run.column(&Column::ContactForce);
            samples.extend(run.history.iter().map(|h| PanelSample {
                n,
                radius_in: radius,
                time_s: h[0],
                contact_force_lbf: fc.map_or(f64::NAN, |j| h[j]),
                gage_a_eyy: ja.map_or(f64::NAN, |j| h[j]),
                gage_b_eyy: jb.map_or(f64::NAN, |j| h[j]),
            }));
            let (first, last) = (&run.energy[0], &run.energy[run.energy.len() - 1]);
            let s = &run.summary;
            rows.push(PanelRow {
                n,
                radius_in: radius,
                solved_dofs: s.model.solved_dofs as u64,
                contact_duration_s: s.contact.duration,
                contacts: s.contact.intervals.len(),
                open_at_end: s.contact.open_at_end,
                transferred: s.energy.transferred_fraction,
                peak_force_lbf: s.contact.peak_force,
                peak_force_time_s: s.contact.peak_force_time,
                energy_error_max: s.energy.max_relative_error,
                impactor_ke_end: last.ke_impactor / first.total,
                target_ke_end: last.ke_target / first.total,
                target_se_end: last.se_target / first.total,
                gage_a_exx: axx,
                gage_a_eyy: ayy,
                gage_b_exx: bxx,
                gage_b_eyy: byy,
                wall_s: run.stats.total_time.as_secs_f64(),
            });
        }
    }
    Ok((rows, samples))
}

pub use super::{read_rows as read_csv, write_rows as csv};

/// The signals drawn: slug, label, value.
type Signal = (&'static str, &'static str, fn(&PanelSample) -> f64);
const SIGNALS: [Signal; 3] = [
    ("force", "contact force [lbf]", |s| s.contact_force_lbf),
    ("gage-a-eyy", "gage A εyy, back face [-]", |s| s.gage_a_eyy),
    ("gage-b-eyy", "gage B εyy, back face [-]", |s| s.gage_b_eyy),
];

/// The name of a surface.
fn surface(radius: Option<f64>) -> String {
    radius.map_or("flat".into(), |r| format!("panel R = {r} in"))
}

/// The figures: each signal of the flat plate (solid) and the panel (dashed) on the
/// finest and the paper's 49×49 mesh, with each line's difference from the flat plate
/// on the finest mesh under it.
pub fn figures(samples: &[PanelSample], dir: &Path) -> Result<Vec<PathBuf>, plot::PlotError> {
    let mut ns: Vec<usize> = samples.iter().map(|s| s.n).collect();
    ns.sort_unstable_by(|a, b| b.cmp(a));
    ns.dedup();
    let shown: Vec<usize> = ns.iter().copied().filter(|&n| n == ns[0] || n == 49).collect();
    let mut out = Vec::new();
    for (slug, label, get) in SIGNALS {
        let mut lines = Vec::new();
        for (k, &n) in shown.iter().enumerate() {
            for (radius, colour) in [(None, [5, 1][k % 2]), (Some(RADIUS), [0, 2][k % 2])] {
                let (t, v): (Vec<f64>, Vec<f64>) = samples
                    .iter()
                    .filter(|s| s.n == n && s.radius_in == radius)
                    .map(|s| (s.time_s * 1e6, get(s)))
                    .unzip();
                let line = Line::new(format!("{n}×{n} {}", surface(radius)), t, v, colour);
                lines.push(if radius.is_some() { line.dashed() } else { line });
            }
        }
        let finest = shown.first().copied().unwrap_or(0);
        out.extend(plot::line_chart(
            &Chart {
                title: format!(
                    "Curved panel against the flat plate: {}",
                    label.split(" [").next().unwrap_or(label)
                ),
                x_label: "time [µs]".into(),
                y_label: label.into(),
                footer: format!(
                    "impactlab study panel · the paper's plate flat and on a cylinder of radius {RADIUS} in, newmark, \
                     Δt 1e-7 s"
                ),
                lines,
                difference: Some(format!(
                    "− flat {finest}×{finest} [{}",
                    label.split(" [").nth(1).unwrap_or("-]")
                )),
                ..Default::default()
            },
            &dir.join(format!("panel-{slug}")),
        )?);
    }
    Ok(out)
}

/// `README.md` of the study, every number from the rows.
pub fn readme(rows: &[PanelRow]) -> String {
    let e = |x: Option<f64>, scale: f64, d: usize| x.map_or("—".into(), |v| format!("{:.*}", d, v * scale));
    let mut s = format!(
        "# The curved panel against the flat plate\n\nGenerated by `impactlab study panel` (this page and the \
         figures are made from `panel-study.csv` and `panel-histories.csv` alone; a test remakes them from those \
         files). The paper's clamped glass/epoxy plate (its MAT2 section, impactor and contact) flat, and wrapped \
         onto a cylinder of radius {RADIUS} in (`impactlab mesh panel --radius {RADIUS}`: its 6 in span a 34° arc, \
         the crown 0.45 in above the clamped edges, struck at the crown along the normal), on generated n×n \
         meshes, each run by newmark, Δt 1e-7 s, 6000 steps (600 µs). On the panel membrane and bending are \
         coupled, so it solves every grid's six DOFs (the flat plate drops its inert membrane).\n\n\
         ## Contact\n\n\
         The first contact's length; the contacts in the run (the flat plate meets the impactor again as it \
         rings); the energy left in the target once the impactor has gone, 1 − (v_rebound/v0)²:\n\n\
         | mesh | surface | solved DOF | first contact [µs] | contacts | peak force [lbf] | at [µs] | left in the \
         target | wall time [s] |\n|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2} | {3} | {4}{5} | {6:.1} | {7} | {8} | {9:.2} |",
            r.n,
            surface(r.radius_in),
            r.solved_dofs,
            e(r.contact_duration_s, 1e6, 2),
            r.contacts,
            if r.open_at_end { " (open at the end)" } else { "" },
            r.peak_force_lbf,
            e(r.peak_force_time_s, 1e6, 1),
            r.transferred.map_or("—".into(), |v| format!("{:.1} %", 100.0 * v)),
            r.wall_s
        );
    }
    s += "\nThe panel against the flat plate on each mesh (panel / flat − 1; for the gages, of the largest \
          |strain|, whichever its sign):\n\n\
          | mesh | contact | peak force | gage A εyy | gage A εxx | gage B εyy | gage B εxx |\n\
          |---|---|---|---|---|---|---|\n";
    let ratio = |p: Option<f64>, f: Option<f64>| match (p, f) {
        (Some(p), Some(f)) if f != 0.0 => format!("{:+.1} %", 100.0 * (p / f - 1.0)),
        _ => "—".into(),
    };
    for pair in rows.chunks(2) {
        let [flat, panel] = pair else { continue };
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2} | {3} | {4} | {5} | {6} |",
            flat.n,
            ratio(panel.contact_duration_s, flat.contact_duration_s),
            ratio(Some(panel.peak_force_lbf), Some(flat.peak_force_lbf)),
            ratio(panel.gage_a_eyy.map(f64::abs), flat.gage_a_eyy.map(f64::abs)),
            ratio(panel.gage_a_exx.map(f64::abs), flat.gage_a_exx.map(f64::abs)),
            ratio(panel.gage_b_eyy.map(f64::abs), flat.gage_b_eyy.map(f64::abs)),
            ratio(panel.gage_b_exx.map(f64::abs), flat.gage_b_exx.map(f64::abs)),
        );
    }
    s += "\n## The energy ledger\n\nAt the end of the run (600 µs), each part's share of the initial energy (the \
          impactor's ½mv²), and the run's largest relative energy error:\n\n\
          | mesh | surface | impactor KE | target KE | target SE | largest error |\n|---|---|---|---|---|---|\n";
    for r in rows {
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2:.4} | {3:.4} | {4:.4} | {5} |",
            r.n,
            surface(r.radius_in),
            r.impactor_ke_end,
            r.target_ke_end,
            r.target_se_end,
            r.energy_error_max.map_or("—".into(), |v| format!("{v:.1e}")),
        );
    }
    s += "\n## Gage strains\n\nBack-face (z = +T/2) extremes over the run (the largest |strain|, with its \
          sign) at the paper's gages A and B (on the panel \
          in each element's own axes: x along the arc, y along the cylinder's axis):\n\n\
          | mesh | surface | gage A εyy | gage A εxx | gage B εyy | gage B εxx |\n|---|---|---|---|---|---|\n";
    for r in rows {
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2} | {3} | {4} | {5} |",
            r.n,
            surface(r.radius_in),
            e(r.gage_a_eyy, 1.0, 6),
            e(r.gage_a_exx, 1.0, 6),
            e(r.gage_b_eyy, 1.0, 6),
            e(r.gage_b_exx, 1.0, 6),
        );
    }
    s += "\n## Figures\n\n";
    for (slug, _, _) in SIGNALS {
        let _ = writeln!(s, "![panel-{slug}](panel-{slug}.png)\n");
    }
    s
}

/// Writes the study's CSVs, then its page and figures made from them as written.
pub fn write(dir: &Path, rows: &[PanelRow], samples: &[PanelSample]) -> Result<(), StudyError> {
    super::write_data(
        dir,
        &[("panel-study.csv", csv(rows)), ("panel-histories.csv", csv(samples))],
    )?;
    redraw(dir)
}

/// Remakes the page and figures in `dir` from the CSVs there.
pub fn redraw(dir: &Path) -> Result<(), StudyError> {
    let rows: Vec<PanelRow> = super::read_rows_file(&dir.join("panel-study.csv"))?;
    let samples: Vec<PanelSample> = super::read_rows_file(&dir.join("panel-histories.csv"))?;
    super::write_page(&dir.join("README.md"), &readme(&rows))?;
    figures(&samples, dir)?;
    Ok(())
}
