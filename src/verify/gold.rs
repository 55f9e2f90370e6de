//! Gold-file comparison in the style of MOOSE's CSVDiff: a stored CSV of a reference
//! run against the current history, column by column, each value accepted when
//! |a − b| ≤ abs or |a − b| ≤ rel·|gold|. A missing gold file, a missing column or a
//! different number of rows fails. The report names the first column and time that
//! differ and the worst relative difference.

use super::Tol;
use std::collections::BTreeMap;
use std::path::Path;

pub struct GoldOutcome {
    pub passed: bool,
    /// Largest |a − b| / (abs + rel·|gold|): ≤ 1 passes.
    pub worst: f64,
    pub detail: String,
}

fn fail(detail: String) -> GoldOutcome {
    GoldOutcome {
        passed: false,
        worst: f64::INFINITY,
        detail,
    }
}

/// Reads a CSV written by [`crate::output`] (header with units, numbers).
pub fn read(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    let mut r = csv::Reader::from_path(path).map_err(|e| format!("gold file {}: {e}", path.display()))?;
    let header: Vec<String> = r
        .headers()
        .map_err(|e| e.to_string())?
        .iter()
        .map(|h| h.split(' ').next().unwrap_or("").to_string())
        .collect();
    let mut rows = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let rec = rec.map_err(|e| format!("{}: row {}: {e}", path.display(), i + 2))?;
        let row: Result<Vec<f64>, _> = rec.iter().map(|x| x.trim().parse::<f64>()).collect();
        rows.push(row.map_err(|e| format!("{}: row {}: {e}", path.display(), i + 2))?);
    }
    Ok((header, rows))
}

/// Compares a history with its gold file.
pub fn compare(
    path: &Path,
    columns: &[String],
    history: &[Vec<f64>],
    default: &Tol,
    per_column: &BTreeMap<String, Tol>,
) -> GoldOutcome {
    let (gh, grows) = match read(path) {
        Ok(g) => g,
        Err(e) => return fail(format!("missing or unreadable gold file: {e}")),
    };
    if grows.len() != history.len() {
        return fail(format!("{} rows, gold has {}", history.len(), grows.len()));
    }
    let names: Vec<&str> = columns.iter().map(|c| c.split(' ').next().unwrap_or("")).collect();
    let mut worst = 0.0f64;
    let mut first: Option<String> = None;
    let mut worst_at = String::new();
    for (gj, name) in gh.iter().enumerate() {
        let Some(j) = names.iter().position(|n| n == name) else {
            return fail(format!("column {name} of the gold file is not in the run's history"));
        };
        let tol = per_column.get(name).unwrap_or(default);
        for (row, grow) in history.iter().zip(&grows) {
            let (a, b) = (row[j], grow[gj]);
            let allowed = tol.abs.max(tol.rel * b.abs());
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
