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
//!
//! Three parts: `rows` runs the study (one row per run), `figures` and `page` make
//! the figures ([`figures()`]) and `README.md` ([`readme`]) from the rows alone.

mod figures;
mod page;
mod rows;

pub use figures::figures;
pub use page::readme;

use super::StudyError;
use crate::integrate::Scheme;
use serde::{Deserialize, Serialize};
use std::path::Path;

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

/// The paper's step for the rod.
pub const ROD_DT: f64 = 2e-7;

/// Past the contact, before the reflection returns (360 µs).
pub const ROD_T_END: f64 = 150e-6;

/// The paper's step for the plate.
pub const PLATE_DT: f64 = 1e-7;

/// Past the contact (about 204 µs).
pub const PLATE_T_END: f64 = 230e-6;

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

/// Runs the study and writes `work-precision.csv` into `dir`, then the page and the
/// figures made from it ([`redraw`]). `plate_meshes` is the mesh sweep (the finest is
/// its reference).
pub fn run_study(
    dir: &Path,
    repeats: usize,
    plate_meshes: &[usize],
    progress: &dyn Fn(&str),
) -> Result<Vec<Row>, StudyError> {
    let mut rows = rows::rod_rows(repeats, progress)?;
    rows.extend(rows::plate_rows(repeats, plate_meshes, progress)?);
    std::fs::create_dir_all(dir).map_err(|source| StudyError::Io {
        path: dir.display().to_string(),
        source,
    })?;
    let path = dir.join("work-precision.csv");
    crate::output::write_file_atomically(&path, &csv(&rows)).map_err(|source| StudyError::Io {
        path: path.display().to_string(),
        source,
    })?;
    redraw(dir)?;
    Ok(rows)
}

/// Remakes `README.md` and the figures in `dir` from its `work-precision.csv`.
pub fn redraw(dir: &Path) -> Result<(), StudyError> {
    let rows: Vec<Row> = super::read_rows_file(&dir.join("work-precision.csv"))?;
    figures(&rows, dir)?;
    super::write_page(&dir.join("README.md"), &readme(&rows))
}
