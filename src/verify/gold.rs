//! Gold-file comparison in the style of MOOSE's CSVDiff: a stored CSV of a reference
//! run against the current history, column by column. A value passes when
//!
//!   |a − b| ≤ max(rel·|b|, floor·peak),   peak = max |column| in the gold file,
//!
//! so each column's absolute floor scales with its own size: round-off of a
//! reordered expression (relative to the column's peak, not to a value near one of
//! its zero crossings) passes, while a relative change of the column fails. The
//! components of one stress or strain tensor (`…_xx`, `…_yy`, `…_xy` of one element
//! and fibre) share one peak, the largest of the three: their round-off scales with
//! the tensor, so a component that is zero up to round-off (the shear at the centre
//! of a symmetric plate, 1e-9 of the normal strains) is compared at the tensor's
//! round-off, not at its own noise. A missing
//! gold file, a missing column or a different number of rows fails. The report names
//! the first column and time that differ and the worst difference.

use serde::{Deserialize, Serialize};
use std::path::Path;

/// Tolerance of a gold comparison, the same for every column.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GoldTol {
    /// Relative to the gold value.
    pub rel: f64,
    /// Absolute floor, as a fraction of the column's peak |value| in the gold file.
    pub floor: f64,
}

impl GoldTol {
    /// The tolerance as numbers (`atol` is the floor, relative to each column's peak)
    /// and in words.
    pub fn bound(&self) -> super::Bound {
        super::Bound {
            rtol: Some(self.rel),
            atol: Some(self.floor),
            text: format!("rel {:.1e}, floor {:.1e}·peak", self.rel, self.floor),
        }
    }
}

/// A gold comparison's verdict.
pub struct GoldOutcome {
    /// True when every value is within tolerance.
    pub passed: bool,
    /// Largest |a − b| / (abs + rel·|gold|): ≤ 1 passes.
    pub worst: f64,
    /// Where the worst value is, in words.
    pub detail: String,
}

fn fail(detail: String) -> GoldOutcome {
    GoldOutcome {
        passed: false,
        worst: f64::INFINITY,
        detail,
    }
}

/// A CSV of numbers that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum CsvError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Read {
        /// The file.
        path: String,
        /// What failed.
        #[source]
        source: csv::Error,
    },
    /// A value is not a number.
    #[error("{path}: row {row}: {message}")]
    Number {
        /// The file.
        path: String,
        /// Row, 1 = header.
        row: usize,
        /// What is wrong.
        message: String,
    },
}

/// Reads a CSV written by [`crate::output`] (header with units, numbers): the column
/// names without units, and the rows.
pub fn read(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), CsvError> {
    let file = std::fs::File::open(path).map_err(|e| CsvError::Read {
        path: path.display().to_string(),
        source: e.into(),
    })?;
    let (header, rows) = read_from(file, &path.display().to_string())?;
    let names = header
        .iter()
        .map(|h| h.split(' ').next().unwrap_or("").to_string())
        .collect();
    Ok((names, rows))
}

/// Reads a CSV of numbers from any reader: the header as written (with its units) and
/// the rows; `name` names the source in errors.
pub fn read_from(source: impl std::io::Read, name: &str) -> Result<(Vec<String>, Vec<Vec<f64>>), CsvError> {
    let read = |source| CsvError::Read {
        path: name.to_string(),
        source,
    };
    let mut r = csv::Reader::from_reader(source);
    let header: Vec<String> = r.headers().map_err(read)?.iter().map(String::from).collect();
    let mut rows = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let rec = rec.map_err(read)?;
        let row: Result<Vec<f64>, _> = rec.iter().map(|x| x.trim().parse::<f64>()).collect();
        rows.push(row.map_err(|e| CsvError::Number {
            path: name.to_string(),
            row: i + 2,
            message: e.to_string(),
        })?);
    }
    Ok((header, rows))
}

/// Compares a history with its gold file.
pub fn compare(path: &Path, columns: &[String], history: &[Vec<f64>], tol: &GoldTol) -> GoldOutcome {
    let (gh, grows) = match read(path) {
        Ok(g) => g,
        Err(e) => return fail(format!("missing or unreadable gold file: {e}")),
    };
    if grows.len() != history.len() {
        return fail(format!("{} rows, gold has {}", history.len(), grows.len()));
    }
    let names: Vec<&str> = columns.iter().map(|c| c.split(' ').next().unwrap_or("")).collect();
    let peaks = tensor_peaks(&gh, &grows);
    let mut worst = 0.0f64;
    let mut first: Option<String> = None;
    let mut worst_at = String::new();
    for (gj, name) in gh.iter().enumerate() {
        let Some(j) = names.iter().position(|n| n == name) else {
            return fail(format!("column {name} of the gold file is not in the run's history"));
        };
        let peak = peaks[gj];
        for (row, grow) in history.iter().zip(&grows) {
            let (a, b) = (row[j], grow[gj]);
            let allowed = (tol.floor * peak).max(tol.rel * b.abs());
            let ratio = if allowed > 0.0 {
                (a - b).abs() / allowed
            } else if a == b {
                0.0
            } else {
                f64::INFINITY
            };
            if ratio > 1.0 && first.is_none() {
                first = Some(format!(
                    "first difference: column {name} at t = {:.6e}: {a:.9e} vs gold {b:.9e}",
                    row[0]
                ));
            }
            if ratio > worst || ratio.is_nan() {
                worst = if ratio.is_nan() { f64::INFINITY } else { ratio };
                worst_at = format!("worst: column {name} at t = {:.6e} ({a:.9e} vs {b:.9e})", row[0]);
            }
        }
    }
    GoldOutcome {
        passed: first.is_none(),
        worst,
        detail: match first {
            Some(f) => format!("{f}; {worst_at}"),
            None => format!(
                "{} columns × {} rows within tolerance; {worst_at}",
                gh.len(),
                grows.len()
            ),
        },
    }
}

/// The tensor a column belongs to: its name without a trailing in-plane component.
fn tensor_of(name: &str) -> &str {
    ["_xx", "_yy", "_xy"]
        .iter()
        .find_map(|c| name.strip_suffix(c))
        .unwrap_or(name)
}

/// The peak |value| of each column, taken over its whole tensor (see the module doc).
pub fn tensor_peaks(header: &[String], rows: &[Vec<f64>]) -> Vec<f64> {
    let own: Vec<f64> = (0..header.len())
        .map(|j| rows.iter().map(|r| r[j].abs()).fold(0.0, f64::max))
        .collect();
    header
        .iter()
        .map(|h| {
            let t = tensor_of(h);
            header
                .iter()
                .zip(&own)
                .filter(|(o, _)| tensor_of(o) == t)
                .map(|(_, p)| *p)
                .fold(0.0, f64::max)
        })
        .collect()
}
