//! The stiffened plate struck on a stiffener and between stiffeners, beside the
//! unstiffened plate: the paper's plate with [`STIFFENERS`] blade stiffeners under it
//! ([`crate::mesh::stiffened_plate_deck`]: CBARs offset to its back face), struck by
//! the paper's impactor through scenes on the deck ([`crate::scene`]'s deck target):
//! on the middle stiffener's line (x = 0) and midway between it and the next; the
//! unstiffened plate at its centre. On each mesh the three run alike ([`options`]).
//! Per run: the contacts, the peak force, the ledger's error and, at the end of the
//! run, where the impact's energy is (the impactor, the skin's and the stiffeners'
//! kinetic and strain energy, each a share of the initial energy); and, on the
//! paper's 49×49 mesh, each strike's impact speed at which the peak force reaches
//! [`THRESHOLD_FORCE`] ([`super::threshold`]).
//!
//! The study's data are `stiffened-study.csv`, `stiffened-histories.csv` and
//! `stiffened-thresholds.csv`; the page and figures are made from those files alone,
//! so a test remakes them.

use super::threshold::{find_velocity, Until};
use super::StudyError;
use crate::elements::Family;
use crate::mesh::{PlateMesh, Stiffeners, PLATE_SIDE};
use crate::plot::{self, Chart, Line};
use crate::run::{run_model, Column, RunOptions};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Stiffeners under the plate: three blades 1.5 in apart, the middle one under the
/// centre ([`Stiffeners::blade`]).
pub const STIFFENERS: usize = 3;

/// The meshes: the paper's, and about twice as fine.
pub const MESHES: [usize; 2] = [49, 99];

/// The threshold searches' force (lbf): the Davies-Zhang delamination threshold of the
/// paper's plate as its cross-ply laminate with G_IIc = 1 kJ/m² (README, "From a
/// layup to a threshold energy").
pub const THRESHOLD_FORCE: f64 = 374.4;

/// The study's run settings: newmark at the paper's Δt for 4000 steps (400 µs).
pub fn options(progress: Option<indicatif::ProgressBar>) -> RunOptions {
    RunOptions {
        steps: Some(4000),
        ..super::mesh::options(progress)
    }
}

/// Where a run strikes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Struck {
    /// The unstiffened plate, at its centre.
    Unstiffened,
    /// The stiffened plate on its middle stiffener's line.
    OnStiffener,
    /// The stiffened plate midway between the middle stiffener and the next.
    BetweenStiffeners,
}

impl Struck {
    /// The three, in the study's order.
    pub const ALL: [Struck; 3] = [Struck::Unstiffened, Struck::OnStiffener, Struck::BetweenStiffeners];

    /// Its label.
    pub fn label(self) -> &'static str {
        match self {
            Struck::Unstiffened => "unstiffened, centre",
            Struck::OnStiffener => "on a stiffener",
            Struck::BetweenStiffeners => "between stiffeners",
        }
    }

    /// The struck point (x, y) on an n×n mesh.
    pub fn point(self, n: usize) -> Result<[f64; 2], StudyError> {
        let m = PlateMesh::new(n)?;
        let rows = Stiffeners::blade(STIFFENERS).rows(&m);
        let y = |r: usize| (r as f64 - (n as f64 + 2.0) / 2.0) * PLATE_SIDE / n as f64;
        Ok(match self {
            Struck::Unstiffened => [0.0, 0.0],
            Struck::OnStiffener => [0.0, y(rows[1])],
            Struck::BetweenStiffeners => [0.0, 0.5 * (y(rows[1]) + y(rows[2]))],
        })
    }
}

/// One run, as a row of `stiffened-study.csv` (the generated decks' units: in, lbf, s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StiffenedRow {
    /// Elements a side.
    pub n: usize,
    /// Where it was struck.
    pub struck: Struck,
    /// The struck point's y (in; x = 0).
    pub y_in: f64,
    /// Solved DOFs.
    pub solved_dofs: u64,
    /// Length of the first contact.
    pub contact_duration_s: Option<f64>,
    /// Contacts (intervals with α > 0) in the run.
    pub contacts: usize,
    /// Largest contact force.
    pub peak_force_lbf: f64,
    /// Its time.
    pub peak_force_time_s: Option<f64>,
    /// The ledger's largest |relative energy error|.
    pub energy_error_max: Option<f64>,
    /// At the end of the run, the impactor's kinetic energy over the initial energy.
    pub impactor_ke_end: f64,
    /// The contact's (Hertz) potential energy over the initial energy.
    pub contact_se_end: f64,
    /// The skin's (shells') kinetic energy over the initial energy.
    pub skin_ke_end: f64,
    /// The skin's strain energy over the initial energy.
    pub skin_se_end: f64,
    /// The stiffeners' (beams') kinetic energy over the initial energy.
    pub stiffener_ke_end: f64,
    /// The stiffeners' strain energy over the initial energy.
    pub stiffener_se_end: f64,
    /// Wall-clock seconds of the run.
    pub wall_s: f64,
}

/// One output time of one run, as a row of `stiffened-histories.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StiffenedSample {
    /// Elements a side.
    pub n: usize,
    /// Where it was struck.
    pub struck: Struck,
    /// Time.
    pub time_s: f64,
    /// Contact force.
    pub contact_force_lbf: f64,
}

/// One threshold search, as a row of `stiffened-thresholds.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThresholdRow {
    /// Elements a side.
    pub n: usize,
    /// Where it was struck.
    pub struck: Struck,
    /// The force the peak had to reach (lbf).
    pub force_lbf: f64,
    /// The threshold impact speed (in/s).
    pub velocity_in_s: f64,
    /// The impactor's ½mv² there (lbf·in).
    pub energy_lbf_in: f64,
    /// The engine the search ran on: `convolution`, or `direct` where the
    /// convolution engine cannot run the model.
    pub engine: String,
    /// The engines' largest difference at the bracket's ends (convolution searches).
    pub direct_check: Option<f64>,
}

/// The scene (TOML) striking `deck` (a file beside it) at (x, y) along +z with the
/// paper's impactor, contact and run.
fn scene(deck: &str, [x, y]: [f64; 2], steps: usize) -> String {
    format!(
        "title = \"stiffened plate study\"\nunits = {{ length = \"in\", force = \"lbf\", time = \"s\" }}\n\
         [target]\nkind = \"deck\"\ndeck = \"{deck}\"\n\
         [impactor]\nat = [{x:?}, {y:?}, 0.0]\ndirection = [0.0, 0.0, 1.0]\nmass = 8.096e-5\nradius = 0.1875\n\
         material = {{ e = 30.0e6, nu = 0.3 }}\nvelocity = 1470.0\n[contact]\nk = 7.779e5\n\
         [output]\nevery = 10\n[run]\ndt = 1e-7\nend = {:?}\n",
        steps as f64 * 1e-7
    )
}

/// The model of a run: the (un)stiffened plate's deck, struck where `struck` says.
fn model(n: usize, struck: Struck, steps: usize) -> Result<crate::model::Model, StudyError> {
    let dir = tempfile::tempdir().map_err(|source| StudyError::Io {
        path: "a temporary directory".into(),
        source,
    })?;
    let deck = match struck {
        Struck::Unstiffened => crate::mesh::plate_deck(n)?,
        _ => crate::mesh::stiffened_plate_deck(n, crate::mesh::Cells::Quad4, &Stiffeners::blade(STIFFENERS))?,
    };
    let io = |path: &Path, source| StudyError::Io {
        path: path.display().to_string(),
        source,
    };
    let deck_path = dir.path().join("plate.bdf");
    std::fs::write(&deck_path, deck).map_err(|e| io(&deck_path, e))?;
    let scene_path = dir.path().join("strike.toml");
    std::fs::write(&scene_path, scene("plate.bdf", struck.point(n)?, steps)).map_err(|e| io(&scene_path, e))?;
    let (_, model, _) = crate::scene::load(&scene_path)?;
    Ok(model)
}

/// Kinetic and strain energy of the shells, then of the beams, at a run's state
/// (`u`, `v` over the model's solved DOFs).
fn parts(model: &crate::model::Model, u: &[f64], v: &[f64]) -> [f64; 4] {
    let mut out = [0.0; 4];
    for e in model.elements.iter() {
        let k = match e.kernel.family() {
            Family::Shell(_) => 0,
            Family::Beam { .. } => 2,
            _ => continue,
        };
        out[k] += e.kinetic_energy(v);
        out[k + 1] += e.strain_energy(u);
    }
    out
}

/// What the study computes: its runs, their histories, the threshold searches.
pub type StudyData = (Vec<StiffenedRow>, Vec<StiffenedSample>, Vec<ThresholdRow>);

/// Runs the three strikes on each mesh, and the threshold searches on the paper's
/// mesh.
pub fn run(ns: &[usize], opts: &RunOptions) -> Result<StudyData, StudyError> {
    let (mut rows, mut samples, mut thresholds) = (Vec::new(), Vec::new(), Vec::new());
    let steps = opts.steps.unwrap_or(4000);
    for &n in ns {
        for struck in Struck::ALL {
            let model = model(n, struck, steps)?;
            let end = steps as f64 * opts.dt.unwrap_or(model.time.dt);
            let run = run_model(
                &model,
                &RunOptions {
                    snapshot_times: vec![end],
                    ..opts.clone()
                },
            )?;
            let fc = run.column(&Column::ContactForce);
            samples.extend(run.history.iter().map(|h| StiffenedSample {
                n,
                struck,
                time_s: h[0],
                contact_force_lbf: fc.map_or(f64::NAN, |j| h[j]),
            }));
            // The last state over the model's DOFs (the run's inert DOFs are zero).
            let snap = run
                .snapshots
                .last()
                .ok_or_else(|| StudyError::Input("the run kept no state".into()))?;
            let index: std::collections::HashMap<_, _> = run.dofs.iter().enumerate().map(|(i, d)| (*d, i)).collect();
            let full =
                |x: &[f64]| -> Vec<f64> { model.dofs.iter().map(|d| index.get(d).map_or(0.0, |&i| x[i])).collect() };
            let [ske, sse, bke, bse] = parts(&model, &full(&snap.u), &full(&snap.v));
            let (first, last) = (&run.energy[0], &run.energy[run.energy.len() - 1]);
            let e0 = first.total;
            let s = &run.summary;
            rows.push(StiffenedRow {
                n,
                struck,
                y_in: struck.point(n)?[1],
                solved_dofs: s.model.solved_dofs as u64,
                contact_duration_s: s.contact.duration,
                contacts: s.contact.intervals.len(),
                peak_force_lbf: s.contact.peak_force,
                peak_force_time_s: s.contact.peak_force_time,
                energy_error_max: s.energy.max_relative_error,
                impactor_ke_end: last.ke_impactor / e0,
                contact_se_end: last.se_impactor / e0,
                skin_ke_end: ske / e0,
                skin_se_end: sse / e0,
                stiffener_ke_end: bke / e0,
                stiffener_se_end: bse / e0,
                wall_s: run.stats.total_time.as_secs_f64(),
            });
            if n == 49 {
                let bar = opts.progress.clone().unwrap_or_else(indicatif::ProgressBar::hidden);
                let t = find_velocity(
                    &model,
                    &RunOptions {
                        progress: None,
                        ..opts.clone()
                    },
                    Until::PeakForce(THRESHOLD_FORCE),
                    &bar,
                )?;
                thresholds.push(ThresholdRow {
                    n,
                    struck,
                    force_lbf: THRESHOLD_FORCE,
                    velocity_in_s: t.velocity,
                    energy_lbf_in: t.energy,
                    engine: if t.direct_reason.is_some() {
                        "direct"
                    } else {
                        "convolution"
                    }
                    .into(),
                    direct_check: t.direct_reason.is_none().then_some(t.direct_check),
                });
            }
        }
    }
    Ok((rows, samples, thresholds))
}

pub use super::{read_rows as read_csv, write_rows as csv};

/// The contact force figure: each strike on the finest mesh (solid) and the paper's
/// (dashed).
pub fn figures(samples: &[StiffenedSample], dir: &Path) -> Result<Vec<PathBuf>, plot::PlotError> {
    let mut ns: Vec<usize> = samples.iter().map(|s| s.n).collect();
    ns.sort_unstable_by(|a, b| b.cmp(a));
    ns.dedup();
    let mut lines = Vec::new();
    for (k, &n) in ns.iter().enumerate() {
        for (c, struck) in Struck::ALL.into_iter().enumerate() {
            let (t, f): (Vec<f64>, Vec<f64>) = samples
                .iter()
                .filter(|s| s.n == n && s.struck == struck)
                .map(|s| (s.time_s * 1e6, s.contact_force_lbf))
                .unzip();
            let line = Line::new(format!("{n}×{n} {}", struck.label()), t, f, [5, 0, 2][c]);
            lines.push(if k == 0 { line } else { line.dashed() });
        }
    }
    plot::line_chart(
        &Chart {
            title: "Stiffened plate: contact force, on and between stiffeners".into(),
            x_label: "time [µs]".into(),
            y_label: "contact force [lbf]".into(),
            footer: format!(
                "impactlab study stiffened · the paper's plate, {STIFFENERS} blade stiffeners 0.15 × 0.5 in, newmark, Δt 1e-7 s"
            ),
            lines,
            ..Default::default()
        },
        &dir.join("stiffened-force"),
    )
}

/// `README.md` of the study, every number from the rows.
pub fn readme(rows: &[StiffenedRow], thresholds: &[ThresholdRow]) -> String {
    let e = |x: Option<f64>, scale: f64, d: usize| x.map_or("—".into(), |v| format!("{:.*}", d, v * scale));
    let mut s = format!(
        "# The stiffened plate, struck on a stiffener and between stiffeners\n\nGenerated by `impactlab study \
         stiffened` (this page and the figure are made from `stiffened-study.csv`, `stiffened-histories.csv` and \
         `stiffened-thresholds.csv` alone; a test remakes them from those files). The paper's clamped glass/epoxy \
         plate (6 × 6 × 0.15 in, its MAT2 section) with {STIFFENERS} blade stiffeners along x under it \
         (`impactlab mesh plate --stiffeners {STIFFENERS}`: PBARL BAR 0.15 × 0.5 in, E = 4.3e6 psi, ρ = 1.8e-4, \
         CBARs under grid rows 1.5 in apart, the middle one under the centre, offset 0.325 in to the back face, \
         edge to edge), struck by the paper's impactor (8.096e-5 lbf·s²/in at 1470 in/s, K = 7.779e5) along +z \
         through a scene on the deck: on the middle stiffener's line, and midway between it and the next; the \
         unstiffened plate at its centre. Each runs by newmark, Δt 1e-7 s, 4000 steps (400 µs). The \
         stiffeners' offsets couple the skin's membrane to its bending, so the stiffened plate solves five DOFs a \
         grid (R3 is held, GRDSET PS 6, as in the paper's deck).\n\n\
         ## Contact\n\n\
         | mesh | struck | y [in] | solved DOF | first contact [µs] | contacts | peak force [lbf] | at [µs] | \
         wall time [s] |\n|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2:.4} | {3} | {4} | {5} | {6:.1} | {7} | {8:.2} |",
            r.n,
            r.struck.label(),
            r.y_in,
            r.solved_dofs,
            e(r.contact_duration_s, 1e6, 2),
            r.contacts,
            r.peak_force_lbf,
            e(r.peak_force_time_s, 1e6, 1),
            r.wall_s
        );
    }
    s += "\n## Where the energy goes\n\nAt the end of the run (400 µs), each part's share of the initial energy \
          (the impactor's ½mv²): the impactor's kinetic energy and the contact's Hertz potential (from the \
          ledger), the kinetic (KE) and strain (SE) energy of the skin (the CQUAD4s) and of the stiffeners (the \
          CBARs), summed element by element from the run's last state, their sum, and the ledger's largest \
          relative error over the run:\n\n\
          | mesh | struck | impactor KE | contact | skin KE | skin SE | stiffeners KE | stiffeners SE | sum | \
          largest error |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for r in rows {
        let sum = r.impactor_ke_end
            + r.contact_se_end
            + r.skin_ke_end
            + r.skin_se_end
            + r.stiffener_ke_end
            + r.stiffener_se_end;
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2:.4} | {3:.4} | {4:.4} | {5:.4} | {6:.4} | {7:.4} | {8:.6} | {9} |",
            r.n,
            r.struck.label(),
            r.impactor_ke_end,
            r.contact_se_end,
            r.skin_ke_end,
            r.skin_se_end,
            r.stiffener_ke_end,
            r.stiffener_se_end,
            sum,
            r.energy_error_max.map_or("—".into(), |v| format!("{v:.1e}")),
        );
    }
    let _ = write!(
        s,
        "\n## Threshold speed\n\nThe impact speed at which the peak contact force reaches {THRESHOLD_FORCE} lbf \
         (the Davies-Zhang delamination threshold of the paper's plate as its cross-ply laminate with \
         G_IIc = 1 kJ/m², README): `impactlab sweep --find velocity --until peak_force={THRESHOLD_FORCE}` on each \
         strike's deck, bisected to 1e-6 of the speed. The unstiffened plate is searched on the convolution \
         engine, both ends of the final bracket checked on the direct engine; the stiffened plate on the direct \
         engine, run by run (its offset stiffeners' masses couple translations and rotations, and the \
         convolution engine takes a lumped mass matrix only):\n\n\
         | mesh | struck | speed [in/s] | ½mv² [lbf·in] | engine | engines' difference |\n\
         |---|---|---|---|---|---|\n"
    );
    for t in thresholds {
        let _ = writeln!(
            s,
            "| {0}×{0} | {1} | {2:.2} | {3:.4} | {4} | {5} |",
            t.n,
            t.struck.label(),
            t.velocity_in_s,
            t.energy_lbf_in,
            t.engine,
            t.direct_check.map_or("—".into(), |d| format!("{d:.1e}"))
        );
    }
    s += "\n## Figure\n\n![stiffened-force](stiffened-force.png)\n";
    s
}

/// Writes the study's CSVs, then its page and figure made from them as written.
pub fn write(
    dir: &Path,
    rows: &[StiffenedRow],
    samples: &[StiffenedSample],
    thresholds: &[ThresholdRow],
) -> Result<(), StudyError> {
    super::write_data(
        dir,
        &[
            ("stiffened-study.csv", csv(rows)),
            ("stiffened-histories.csv", csv(samples)),
            ("stiffened-thresholds.csv", csv(thresholds)),
        ],
    )?;
    redraw(dir)
}

/// Remakes the page and figure in `dir` from the CSVs there.
pub fn redraw(dir: &Path) -> Result<(), StudyError> {
    let rows: Vec<StiffenedRow> = super::read_rows_file(&dir.join("stiffened-study.csv"))?;
    let thresholds: Vec<ThresholdRow> = super::read_rows_file(&dir.join("stiffened-thresholds.csv"))?;
    let samples: Vec<StiffenedSample> = super::read_rows_file(&dir.join("stiffened-histories.csv"))?;
    super::write_page(&dir.join("README.md"), &readme(&rows, &thresholds))?;
    figures(&samples, dir)?;
    Ok(())
}
