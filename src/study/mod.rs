//! Studies over families of runs: the paper's plate mesh study ([`mesh`]), the
//! stability map ([`stability`]), the work-precision study ([`accuracy`]), and the
//! verification cases run in parallel ([`cases`]), sweeps and thresholds ([`sweep`],
//! [`threshold`]), the benchmarks ([`mod@bench`]) and the mutation campaign ([`mutants`]).

pub mod cases;
pub mod mesh;
pub mod panel;
pub mod stiffened;

use crate::run::{Column, RunResult};
use serde::{de::DeserializeOwned, Serialize};
use std::path::Path;

/// A study that could not be run or written: the error of the stage that failed, or
/// the study's own (an option it cannot take, a result it cannot confirm).
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// A model could not be loaded.
    #[error("{0}")]
    Load(#[from] crate::model::LoadError),
    /// A generated mesh could not be made.
    #[error("{0}")]
    Mesh(#[from] crate::mesh::MeshError),
    /// A model modification could not be made.
    #[error("{0}")]
    Modify(#[from] crate::model::ModifyError),
    /// A run failed.
    #[error("{0}")]
    Run(#[from] crate::run::RunError),
    /// A solve failed.
    #[error("numerical failure: {0}")]
    Solve(#[from] crate::integrate::SolveError),
    /// A static solution could not be had.
    #[error("{0}")]
    Static(#[from] crate::run::statics::StaticError),
    /// A verification case could not be used.
    #[error("{0}")]
    Case(#[from] crate::verify::CaseError),
    /// A check could not be evaluated.
    #[error("{0}")]
    Check(#[from] crate::verify::CheckError),
    /// A reference could not be computed.
    #[error("{0}")]
    Reference(#[from] crate::physics::references::ReferenceError),
    /// A figure could not be drawn.
    #[error("{0}")]
    Plot(#[from] crate::plot::PlotError),
    /// A scene could not be made into a model.
    #[error("{0}")]
    Scene(#[from] crate::scene::SceneError),
    /// The mutation campaign's page could not be made.
    #[error("{0}")]
    Mutants(#[from] mutants::MutantsError),
    /// The study cannot take what it was given.
    #[error("invalid option: {0}")]
    Input(String),
    /// A result the study could not confirm (a threshold the direct engine does not
    /// bracket).
    #[error("numerical failure: {0}")]
    Unconfirmed(String),
    /// A file could not be read or written.
    #[error("cannot write outputs to {path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
}

/// Rows of a study as CSV (serde rows: shortest round-trip floats, `None` empty).
pub fn write_rows<T: Serialize>(rows: &[T]) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in rows {
        w.serialize(r).expect("plain rows serialise");
    }
    w.into_inner().expect("writing to memory")
}

/// Rows of a study read back from CSV.
pub fn read_rows<T: DeserializeOwned>(bytes: &[u8]) -> Result<Vec<T>, csv::Error> {
    csv::Reader::from_reader(bytes).deserialize().collect()
}

/// Rows of a study read from a CSV file; an error names the file.
pub fn read_rows_file<T: DeserializeOwned>(path: &Path) -> Result<Vec<T>, StudyError> {
    let io = |source| StudyError::Io {
        path: path.display().to_string(),
        source,
    };
    let bytes = std::fs::read(path).map_err(io)?;
    read_rows(&bytes).map_err(|e| io(std::io::Error::new(std::io::ErrorKind::InvalidData, e)))
}

/// Writes a study's data files as its output directory `dir`, atomically (the
/// directory replaced whole); an error names the directory.
pub fn write_data(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<(), StudyError> {
    crate::output::write_dir_atomically(dir, files).map_err(|source| StudyError::Io {
        path: dir.display().to_string(),
        source,
    })
}

/// Writes a generated page atomically; an error names the file.
pub fn write_page(path: &Path, text: &str) -> Result<(), StudyError> {
    crate::output::write_file_atomically(path, text.as_bytes()).map_err(|source| StudyError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// Extreme (largest magnitude, signed) of a history column and its time.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct Extreme {
    /// The value of largest magnitude, signed.
    pub value: f64,
    /// Its time.
    pub time_s: f64,
}

/// Signed extreme of a history column, if the run wrote it.
pub fn history_extreme(run: &RunResult, c: &Column) -> Option<Extreme> {
    let j = run.column(c)?;
    run.history
        .iter()
        .map(|r| Extreme {
            value: r[j],
            time_s: r[0],
        })
        .fold(None, |acc: Option<Extreme>, e| match acc {
            Some(a) if a.value.abs() >= e.value.abs() => Some(a),
            _ => Some(e),
        })
}

/// Largest local maximum of the contact force in the latter half of the first contact
/// interval: the "secondary impact" the paper reads off Figure 6 (t ≈ 175 µs).
pub fn secondary_peak(run: &RunResult) -> Option<Extreme> {
    let (t, f) = (&run.series.time, &run.series.force);
    let (intervals, _) = crate::run::contact_intervals(t, &run.series.alpha);
    let [t0, t1] = *intervals.first()?;
    let half = 0.5 * (t0 + t1);
    (1..f.len().saturating_sub(1))
        .filter(|&k| t[k] > half && t[k] < t1 && f[k] > 0.0 && f[k] > f[k - 1] && f[k] >= f[k + 1])
        .map(|k| Extreme {
            value: f[k],
            time_s: t[k],
        })
        .max_by(|a, b| a.value.total_cmp(&b.value))
}

/// Runs `count` tasks, numbered from 0 and taken in order, on `jobs` threads; their
/// results in task order.
pub(crate) fn in_parallel<T: Send>(jobs: usize, count: usize, task: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(Vec::with_capacity(count));
    std::thread::scope(|scope| {
        for _ in 0..jobs.max(1).min(count.max(1)) {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                if k >= count {
                    break;
                }
                let result = task(k);
                done.lock().expect("no worker panics").push((k, result));
            });
        }
    });
    let mut done = done.into_inner().expect("no worker panics");
    done.sort_by_key(|(k, _)| *k);
    done.into_iter().map(|(_, r)| r).collect()
}

pub mod accuracy;
pub mod bench;
pub mod mutants;
pub mod stability;
pub mod sweep;
pub mod threshold;
