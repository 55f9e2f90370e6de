//! Another solver's results as a reference: a CSV with a time column and named
//! columns (`reference-data/nastran95/`), compared with a run's history column by
//! column at every time both have. A value passes when
//!
//!   |ours − theirs| ≤ max · peak,   peak = max |column| in the external file,
//!
//! so each column is judged against its own size, not against values near its zero
//! crossings. Times are matched by step: the external time divided by the run's Δt
//! must be a whole number (to 1e-6 of a step) that the run recorded.

use super::gold::{self, CsvError};
use std::collections::BTreeMap;
use std::path::Path;

/// A column of another solver's results, on the run's time axis.
#[derive(Debug, Clone)]
pub struct ExternalSeries {
    /// Who computed it (the case file's `solver`).
    pub solver: String,
    /// The run's history column it stands beside.
    pub ours: String,
    /// Its name in the external file.
    pub theirs: String,
    /// Times.
    pub time: Vec<f64>,
    /// Values at those times.
    pub values: Vec<f64>,
    /// max |value| over the file.
    pub peak: f64,
}

/// Reads the columns a case maps (`ours → theirs`) from an external CSV.
pub fn load(
    path: &Path,
    solver: &str,
    time: &str,
    columns: &BTreeMap<String, String>,
) -> Result<Vec<ExternalSeries>, CsvError> {
    let (header, rows) = gold::read(path)?;
    let missing = |name: &str| CsvError::Number {
        path: path.display().to_string(),
        row: 1,
        message: format!("no column {name} (columns: {})", header.join(", ")),
    };
    let index = |name: &str| header.iter().position(|h| h == name).ok_or_else(|| missing(name));
    let jt = index(time)?;
    let t: Vec<f64> = rows.iter().map(|r| r[jt]).collect();
    columns
        .iter()
        .map(|(ours, theirs)| {
            let j = index(theirs)?;
            let values: Vec<f64> = rows.iter().map(|r| r[j]).collect();
            Ok(ExternalSeries {
                solver: solver.to_string(),
                ours: ours.clone(),
                theirs: theirs.clone(),
                time: t.clone(),
                peak: values.iter().fold(0.0, |a: f64, v| a.max(v.abs())),
                values,
            })
        })
        .collect()
}

/// The largest difference of one column, relative to the external peak.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnDiff {
    /// The history column.
    pub ours: String,
    /// max |ours − theirs| / peak over the common times.
    pub worst: f64,
    /// The time of the largest difference.
    pub at: f64,
    /// Times compared.
    pub compared: usize,
}

/// A column the run does not have, or no time in common: the comparison cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Mismatch {
    /// The run has no such history column.
    #[error("the run has no history column {0}")]
    NoColumn(String),
    /// No time of the external column is a step the run recorded.
    #[error("no time of the external column {0} is a step the run recorded")]
    NoCommonTime(String),
}

/// Compares each external column with the run's history (`names` without units; the
/// first column is time) at the times both have.
pub fn compare(
    series: &[ExternalSeries],
    names: &[String],
    history: &[Vec<f64>],
    dt: f64,
) -> Result<Vec<ColumnDiff>, Mismatch> {
    let step = |t: f64| {
        let k = t / dt;
        ((k - k.round()).abs() < 1e-6).then_some(k.round() as i64)
    };
    let rows: BTreeMap<i64, usize> = history
        .iter()
        .enumerate()
        .filter_map(|(i, r)| step(r[0]).map(|k| (k, i)))
        .collect();
    series
        .iter()
        .map(|s| {
            let j = names
                .iter()
                .position(|n| *n == s.ours)
                .ok_or_else(|| Mismatch::NoColumn(s.ours.clone()))?;
            let mut d = ColumnDiff {
                ours: s.ours.clone(),
                worst: 0.0,
                at: f64::NAN,
                compared: 0,
            };
            for (t, v) in s.time.iter().zip(&s.values) {
                let Some(&i) = step(*t).and_then(|k| rows.get(&k)) else {
                    continue;
                };
                let r = (history[i][j] - v).abs() / s.peak.max(f64::MIN_POSITIVE);
                d.compared += 1;
                if r > d.worst || r.is_nan() {
                    d.worst = if r.is_nan() { f64::INFINITY } else { r };
                    d.at = *t;
                }
            }
            if d.compared == 0 {
                return Err(Mismatch::NoCommonTime(s.theirs.clone()));
            }
            Ok(d)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(ours: &str, time: Vec<f64>, values: Vec<f64>) -> ExternalSeries {
        ExternalSeries {
            solver: "other".into(),
            ours: ours.into(),
            theirs: format!("{ours}_theirs"),
            peak: values.iter().fold(0.0, |a: f64, v| a.max(v.abs())),
            time,
            values,
        }
    }

    /// Goal: the difference is measured at the common steps only, relative to the
    /// external peak, and its time is reported.
    #[test]
    fn compares_at_common_steps_relative_to_the_peak() {
        let dt = 1e-7;
        let names = vec!["time".to_string(), "f".to_string()];
        // Ours every 2 steps, theirs every step: steps 0, 2, 4 are common.
        let history: Vec<Vec<f64>> = (0..3).map(|k| vec![(2 * k) as f64 * dt, k as f64]).collect();
        let theirs = series(
            "f",
            (0..5).map(|k| k as f64 * dt).collect(),
            vec![0.0, 9.0, 1.0, 9.0, 4.0],
        );
        let d = compare(&[theirs], &names, &history, dt).unwrap();
        assert_eq!(d[0].compared, 3);
        // At step 4: |2 − 4| / 9.
        assert!((d[0].worst - 2.0 / 9.0).abs() < 1e-15);
        assert!((d[0].at - 4.0 * dt).abs() < 1e-20);
    }

    /// Goal: a missing column or no common time is an error, never a pass.
    #[test]
    fn a_comparison_that_cannot_be_made_is_an_error() {
        let names = vec!["time".to_string(), "f".to_string()];
        let history = vec![vec![0.0, 1.0]];
        let other = series("g", vec![0.0], vec![1.0]);
        assert_eq!(
            compare(&[other], &names, &history, 1.0),
            Err(Mismatch::NoColumn("g".into()))
        );
        let late = series("f", vec![0.5], vec![1.0]);
        assert_eq!(
            compare(&[late], &names, &history, 1.0),
            Err(Mismatch::NoCommonTime("f_theirs".into()))
        );
    }
}
