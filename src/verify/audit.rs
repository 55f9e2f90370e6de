//! Auditing a change: two output directories compared, so that a reviewer (or CI)
//! sees what moved and by how much, and the audit can fail.
//!
//! Two run directories (`summary.json`, `history.csv`, `energy.csv`) or two `verify`
//! output directories (`verify.json`, every case's checks) are compared:
//!
//! - JSON values leaf by leaf under dotted keys (array entries that name a case and a
//!   check are keyed by them, not by position): numbers within tolerance, strings,
//!   booleans and nulls equal, and every key present on both sides;
//! - CSV files column by column (by name): the same rows, and in each column
//!   |candidate − baseline| ≤ atol + rtol·(the baseline column's peak |value|), with
//!   the largest difference and the first row that differs.
//!
//! A summary number passes when |candidate − baseline| ≤ atol + rtol·|baseline|.
//! Wall-clock times and the program's version are listed but never gate.

use super::gold;
use serde::Serialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

/// Two directories that cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum AuditError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Read {
        /// The file.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
    /// A JSON file could not be parsed.
    #[error("{path}: {source}")]
    Json {
        /// The file.
        path: String,
        /// What failed.
        #[source]
        source: serde_json::Error,
    },
    /// A CSV could not be read.
    #[error("{0}")]
    Csv(#[from] gold::CsvError),
    #[error(
        "{base} and {cand}: neither holds the outputs of a run (summary.json) in both, nor those of \
         `impactlab verify` (verify.json) in both"
    )]
    /// The directories hold neither two runs nor two verify outputs.
    NotComparable {
        /// The baseline directory.
        base: String,
        /// The candidate directory.
        cand: String,
    },
    /// A tolerance is negative or not finite.
    #[error("--{name} must be a finite number ≥ 0, not {value}")]
    Tolerance {
        /// The option.
        name: &'static str,
        /// The value given.
        value: f64,
    },
}

/// What counts as moved.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AuditTol {
    /// Relative tolerance: of |baseline| for JSON numbers, of the column's peak for CSV columns.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
}

impl Default for AuditTol {
    /// Any change at all.
    fn default() -> Self {
        AuditTol { rtol: 0.0, atol: 0.0 }
    }
}

/// One difference between the two sides.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Change {
    /// A number of a JSON file, or the largest difference of a CSV column.
    Number {
        /// Dotted JSON key, or file and column.
        what: String,
        /// The baseline's value.
        baseline: f64,
        /// The candidate's value.
        candidate: f64,
        /// |candidate − baseline|.
        difference: f64,
        /// What the tolerance is relative to (|baseline|, or the column's peak).
        scale: f64,
        /// For a column: the row (1 = first data row) and time of the largest
        /// difference, and the first row beyond tolerance.
        #[serde(skip_serializing_if = "Option::is_none")]
        at: Option<RowAt>,
        /// The first row beyond tolerance (1 = first data row).
        #[serde(skip_serializing_if = "Option::is_none")]
        first_row_beyond: Option<usize>,
    },
    /// A string, boolean or null that differs (or a value whose type changed).
    Text {
        /// Dotted JSON key.
        what: String,
        /// The baseline's value, as JSON.
        baseline: String,
        /// The candidate's value, as JSON.
        candidate: String,
    },
    /// A key or column present on one side only.
    OneSide {
        /// The key or column.
        what: String,
        /// The side that has it.
        side: Side,
    },
    /// Files whose row counts differ.
    Rows {
        /// The file.
        what: String,
        /// Rows on the baseline's side.
        baseline: usize,
        /// Rows on the candidate's side.
        candidate: usize,
    },
}

/// A row of a CSV and its time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RowAt {
    /// Row, 1 = first data row.
    pub row: usize,
    /// Its time.
    pub time: f64,
}

/// One of the two directories audited.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// The baseline (the first directory).
    Baseline,
    /// The candidate (the second).
    Candidate,
}

impl Change {
    /// The key or column the change is about.
    pub fn what(&self) -> &str {
        match self {
            Change::Number { what, .. }
            | Change::Text { what, .. }
            | Change::OneSide { what, .. }
            | Change::Rows { what, .. } => what,
        }
    }
}

/// The audit of two directories.
#[derive(Debug, Clone, Serialize)]
pub struct Audit {
    /// The baseline directory.
    pub baseline: String,
    /// The candidate directory.
    pub candidate: String,
    /// The tolerance applied.
    pub tolerance: AuditTol,
    /// True when nothing moved beyond tolerance.
    pub passed: bool,
    /// Quantities compared (JSON leaves and CSV columns).
    pub compared: usize,
    /// Everything that moved beyond tolerance, largest relative move first among numbers.
    pub moved: Vec<Change>,
    /// Numbers that moved within tolerance (not zero), for the record.
    pub within_tolerance: Vec<Change>,
    /// Wall-clock times and versions: listed when they differ, never gating.
    pub not_gated: Vec<Change>,
}

/// A JSON leaf under its dotted key.
fn leaves(prefix: &str, v: &Value, out: &mut BTreeMap<String, Value>) {
    let key = |k: &str| {
        if prefix.is_empty() {
            k.to_string()
        } else {
            format!("{prefix}.{k}")
        }
    };
    match v {
        Value::Object(m) => m.iter().for_each(|(k, v)| leaves(&key(k), v, out)),
        Value::Array(a) => a.iter().enumerate().for_each(|(i, v)| {
            // verify.json's results: keyed by case and check, so that a check added
            // or removed does not shift every later one.
            let named = match (
                v.get("case").and_then(Value::as_str),
                v.get("check").and_then(Value::as_str),
            ) {
                (Some(c), Some(k)) => format!("{prefix}[{c}/{k}]"),
                (Some(c), None) => format!("{prefix}[{c}]"),
                _ => format!("{prefix}[{i}]"),
            };
            leaves(&named, v, out)
        }),
        other => {
            out.insert(prefix.to_string(), other.clone());
        }
    }
}

/// The prefixes of a dotted key that end at a `.` or `[` outside brackets, shortest
/// first, then the key itself.
fn ancestors(key: &str) -> impl Iterator<Item = &str> {
    let mut depth = 0;
    let mut cuts = Vec::new();
    for (i, ch) in key.char_indices() {
        match ch {
            '[' if depth == 0 => {
                cuts.push(i);
                depth += 1;
            }
            '[' => depth += 1,
            ']' => depth -= 1,
            '.' if depth == 0 => cuts.push(i),
            _ => {}
        }
    }
    cuts.into_iter()
        .filter(|&i| i > 0)
        .map(move |i| &key[..i])
        .chain(std::iter::once(key))
}

/// Keys that say how long something took or which build wrote it.
fn not_gated(key: &str) -> bool {
    let last = key.rsplit('.').next().unwrap_or(key);
    last == "impactlab_version"
        || last == "wall_s"
        || (key.starts_with("run.") && last.ends_with("_s"))
        || last == "time_s"
}

fn read_json(path: &Path) -> Result<Value, AuditError> {
    let p = || path.display().to_string();
    let t = std::fs::read_to_string(path).map_err(|source| AuditError::Read { path: p(), source })?;
    serde_json::from_str(&t).map_err(|source| AuditError::Json { path: p(), source })
}

/// A directory that must exist: an I/O error naming it otherwise.
fn existing(dir: &Path) -> Result<(), AuditError> {
    std::fs::read_dir(dir).map(|_| ()).map_err(|source| AuditError::Read {
        path: dir.display().to_string(),
        source,
    })
}

struct Collector {
    tol: AuditTol,
    audit: Audit,
}

impl Collector {
    fn number(&mut self, c: Change, scale: f64, difference: f64, gated: bool) {
        let beyond = difference > self.tol.atol + self.tol.rtol * scale || difference.is_nan();
        if !gated {
            if difference != 0.0 {
                self.audit.not_gated.push(c);
            }
        } else if beyond {
            self.audit.moved.push(c);
        } else if difference != 0.0 {
            self.audit.within_tolerance.push(c);
        }
    }

    fn json(&mut self, file: &str, a: &Value, b: &Value) {
        let (mut la, mut lb) = (BTreeMap::new(), BTreeMap::new());
        leaves("", a, &mut la);
        leaves("", b, &mut lb);
        self.one_side(file, &la, &lb, Side::Baseline);
        self.one_side(file, &lb, &la, Side::Candidate);
        for (k, va) in &la {
            let what = format!("{file} {k}");
            self.audit.compared += 1;
            let Some(vb) = lb.get(k) else {
                continue;
            };
            match (va.as_f64(), vb.as_f64()) {
                (Some(x), Some(y)) => {
                    let d = (y - x).abs();
                    let c = Change::Number {
                        what,
                        baseline: x,
                        candidate: y,
                        difference: d,
                        scale: x.abs(),
                        at: None,
                        first_row_beyond: None,
                    };
                    self.number(c, x.abs(), d, !not_gated(k));
                }
                _ if va != vb => {
                    let c = Change::Text {
                        what,
                        baseline: va.to_string(),
                        candidate: vb.to_string(),
                    };
                    if not_gated(k) {
                        self.audit.not_gated.push(c);
                    } else {
                        self.audit.moved.push(c);
                    }
                }
                _ => {}
            }
        }
    }

    /// The keys of `here` that `there` lacks, each named by its shortest ancestor that
    /// `there` lacks altogether (a check missing from a verify run is one entry, not
    /// one per field).
    fn one_side(&mut self, file: &str, here: &BTreeMap<String, Value>, there: &BTreeMap<String, Value>, side: Side) {
        let mut named = std::collections::BTreeSet::new();
        for k in here.keys().filter(|k| !there.contains_key(*k)) {
            let lacks = |p: &str| {
                !there
                    .keys()
                    .any(|t| t == p || t.starts_with(&format!("{p}.")) || t.starts_with(&format!("{p}[")))
            };
            let ancestor = ancestors(k).find(|p| lacks(p)).unwrap_or(k);
            if named.insert(ancestor.to_string()) {
                if side == Side::Candidate {
                    self.audit.compared += 1;
                }
                self.audit.moved.push(Change::OneSide {
                    what: format!("{file} {ancestor}"),
                    side,
                });
            }
        }
    }

    fn csv(&mut self, file: &str, base: &Path, cand: &Path) -> Result<(), AuditError> {
        let (ha, ra) = gold::read(base)?;
        let (hb, rb) = gold::read(cand)?;
        if ra.len() != rb.len() {
            self.audit.moved.push(Change::Rows {
                what: format!("{file} rows"),
                baseline: ra.len(),
                candidate: rb.len(),
            });
        }
        for (j, name) in ha.iter().enumerate() {
            let what = format!("{file} {name}");
            self.audit.compared += 1;
            let Some(jb) = hb.iter().position(|n| n == name) else {
                self.audit.moved.push(Change::OneSide {
                    what,
                    side: Side::Baseline,
                });
                continue;
            };
            let peak = ra.iter().map(|r| r[j].abs()).fold(0.0, f64::max);
            let allowed = self.tol.atol + self.tol.rtol * peak;
            let (mut worst, mut at, mut first) = (0.0f64, 0usize, None);
            for (i, (x, y)) in ra.iter().zip(&rb).enumerate() {
                let d = (y[jb] - x[j]).abs();
                let d = if d.is_nan() && !(x[j].is_nan() && y[jb].is_nan()) {
                    f64::INFINITY
                } else if d.is_nan() {
                    0.0
                } else {
                    d
                };
                if d > worst {
                    (worst, at) = (d, i);
                }
                if d > allowed && first.is_none() {
                    first = Some(i + 1);
                }
            }
            if ra.is_empty() || rb.is_empty() {
                continue;
            }
            let c = Change::Number {
                what,
                baseline: ra[at][j],
                candidate: rb[at][jb],
                difference: worst,
                scale: peak,
                at: Some(RowAt {
                    row: at + 1,
                    time: ra[at][0],
                }),
                first_row_beyond: first,
            };
            self.number(c, peak, worst, true);
        }
        for name in hb.iter().filter(|n| !ha.contains(n)) {
            self.audit.compared += 1;
            self.audit.moved.push(Change::OneSide {
                what: format!("{file} {name}"),
                side: Side::Candidate,
            });
        }
        Ok(())
    }
}

/// Compares two run directories or two `verify` output directories.
///
/// ```
/// use impactlab::verify::audit::{audit, AuditTol};
/// let model = impactlab::paper::rod_model()?;
/// let run = impactlab::run::run_model(&model, &Default::default())?;
/// let tmp = tempfile::tempdir()?;
/// let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
/// for dir in [&a, &b] {
///     impactlab::output::write_dir_atomically(dir, &impactlab::output::run_files(&model, &run))?;
/// }
/// let same = audit(&a, &b, AuditTol::default())?;
/// assert!(same.passed && same.moved.is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn audit(base: &Path, cand: &Path, tol: AuditTol) -> Result<Audit, AuditError> {
    for (name, value) in [("rtol", tol.rtol), ("atol", tol.atol)] {
        if !(value >= 0.0 && value.is_finite()) {
            return Err(AuditError::Tolerance { name, value });
        }
    }
    existing(base)?;
    existing(cand)?;
    let both = |f: &str| base.join(f).is_file() && cand.join(f).is_file();
    let mut c = Collector {
        tol,
        audit: Audit {
            baseline: base.display().to_string(),
            candidate: cand.display().to_string(),
            tolerance: tol,
            passed: false,
            compared: 0,
            moved: Vec::new(),
            within_tolerance: Vec::new(),
            not_gated: Vec::new(),
        },
    };
    if both("summary.json") {
        c.json(
            "summary",
            &read_json(&base.join("summary.json"))?,
            &read_json(&cand.join("summary.json"))?,
        );
        for file in ["history.csv", "energy.csv"] {
            match (base.join(file).is_file(), cand.join(file).is_file()) {
                (true, true) => c.csv(file, &base.join(file), &cand.join(file))?,
                (false, false) => {}
                (a, _) => c.audit.moved.push(Change::OneSide {
                    what: file.to_string(),
                    side: if a { Side::Baseline } else { Side::Candidate },
                }),
            }
        }
    } else if both("verify.json") {
        c.json(
            "verify",
            &read_json(&base.join("verify.json"))?,
            &read_json(&cand.join("verify.json"))?,
        );
    } else {
        return Err(AuditError::NotComparable {
            base: base.display().to_string(),
            cand: cand.display().to_string(),
        });
    }
    let mut a = c.audit;
    let relative = |ch: &Change| match ch {
        Change::Number { difference, scale, .. } => difference / scale.max(f64::MIN_POSITIVE),
        _ => f64::INFINITY,
    };
    a.moved.sort_by(|x, y| relative(y).total_cmp(&relative(x)));
    a.within_tolerance.sort_by(|x, y| relative(y).total_cmp(&relative(x)));
    a.passed = a.moved.is_empty();
    Ok(a)
}

/// How an audit is printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Format {
    /// Plain text for a terminal.
    #[default]
    Text,
    /// JSON, for programs.
    Json,
    /// A table to paste into a pull request.
    Markdown,
}

fn describe(c: &Change) -> [String; 4] {
    match c {
        Change::Number {
            baseline,
            candidate,
            difference,
            scale,
            at,
            first_row_beyond,
            ..
        } => {
            let rel = difference / scale.max(f64::MIN_POSITIVE);
            let mut w = String::new();
            if let Some(at) = at {
                w = format!("largest at row {} (t = {:.6e})", at.row, at.time);
                if let Some(f) = first_row_beyond {
                    w += &format!(", first beyond tolerance row {f}");
                }
            }
            [
                format!("{baseline:.9e}"),
                format!("{candidate:.9e}"),
                format!("{rel:.2e}"),
                w,
            ]
        }
        Change::Text {
            baseline, candidate, ..
        } => [baseline.clone(), candidate.clone(), "changed".into(), String::new()],
        Change::OneSide { side, .. } => match side {
            Side::Baseline => [
                "present".into(),
                "missing".into(),
                "only in baseline".into(),
                String::new(),
            ],
            Side::Candidate => [
                "missing".into(),
                "present".into(),
                "only in candidate".into(),
                String::new(),
            ],
        },
        Change::Rows {
            baseline, candidate, ..
        } => [
            baseline.to_string(),
            candidate.to_string(),
            "row count".into(),
            String::new(),
        ],
    }
}

/// The audit printed as text, JSON or markdown.
pub fn render(a: &Audit, format: Format) -> String {
    if format == Format::Json {
        return serde_json::to_string_pretty(a).expect("plain data") + "\n";
    }
    let verdict = format!(
        "{}: {} of {} quantities moved beyond rtol {:e}, atol {:e} ({} within tolerance; timings and versions not gated)",
        if a.passed { "unchanged" } else { "MOVED" },
        a.moved.len(),
        a.compared,
        a.tolerance.rtol,
        a.tolerance.atol,
        a.within_tolerance.len()
    );
    let mut s = String::new();
    let md = format == Format::Markdown;
    if md {
        s += &format!(
            "### impactlab audit: `{}` → `{}`\n\n**{verdict}**\n\n",
            a.baseline, a.candidate
        );
    }
    for (title, list) in [("moved", &a.moved), ("within tolerance", &a.within_tolerance)] {
        if list.is_empty() {
            continue;
        }
        if md {
            s += &format!("#### {title}\n\n| quantity | baseline | candidate | moved (relative) | where |\n|---|---|---|---|---|\n");
        } else {
            s += &format!(
                "{title}:\n{:<48} {:>16} {:>16} {:>16}  where\n",
                "quantity", "baseline", "candidate", "moved"
            );
        }
        for c in list {
            let [b, cand, m, w] = describe(c);
            if md {
                s += &format!("| `{}` | {b} | {cand} | {m} | {w} |\n", c.what());
            } else {
                s += &format!("{:<48} {b:>16} {cand:>16} {m:>16}  {w}\n", c.what());
            }
        }
        s += "\n";
    }
    if !md {
        s += &verdict;
        s += "\n";
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_dir(dir: &Path, summary: &str, history: &str) {
        std::fs::create_dir_all(dir).unwrap();
        std::fs::write(dir.join("summary.json"), summary).unwrap();
        std::fs::write(dir.join("history.csv"), history).unwrap();
    }

    /// Goal: keys and columns present on one side only are reported (a missing
    /// subtree once), a changed boolean is reported, timings never gate, and a column's
    /// largest difference names its row, time and the first row beyond tolerance.
    #[test]
    fn one_sided_keys_columns_and_changed_booleans_are_reported() {
        let t = tempfile::tempdir().unwrap();
        let (a, b) = (t.path().join("a"), t.path().join("b"));
        run_dir(
            &a,
            r#"{"contact": {"open_at_end": false, "peak_force": 2.0}, "run": {"wall_s": 1.0}, "rod": {"length": 36.0, "wave_speed": 2e5}}"#,
            "time [s],f [lbf],g [in]\n0,0,1\n1,1,1\n2,4,1\n",
        );
        run_dir(
            &b,
            r#"{"contact": {"open_at_end": true, "peak_force": 2.0}, "run": {"wall_s": 9.0}, "extra": 1}"#,
            "time [s],f [lbf],h [in]\n0,0,1\n1,1.5,1\n2,4.1,1\n",
        );
        let r = audit(&a, &b, AuditTol::default()).unwrap();
        assert!(!r.passed);
        let whats: Vec<&str> = r.moved.iter().map(Change::what).collect();
        for w in [
            "summary contact.open_at_end",
            "summary rod",
            "summary extra",
            "history.csv g",
            "history.csv h",
            "history.csv f",
        ] {
            assert!(whats.contains(&w), "{w} in {whats:?}");
        }
        assert!(!whats.iter().any(|w| w.contains("wall_s")), "{whats:?}");
        assert_eq!(r.not_gated.len(), 1);
        let f = r.moved.iter().find(|c| c.what() == "history.csv f").unwrap();
        match f {
            Change::Number {
                difference,
                scale,
                at,
                first_row_beyond,
                ..
            } => {
                assert_eq!(*difference, 0.5);
                assert_eq!(*scale, 4.0);
                assert_eq!(*at, Some(RowAt { row: 2, time: 1.0 }));
                assert_eq!(*first_row_beyond, Some(2));
            }
            other => panic!("{other:?}"),
        }
        // Relative to the column's peak (4): 0.5/4 = 0.125 passes rtol 0.2.
        let loose = audit(&a, &b, AuditTol { rtol: 0.2, atol: 0.0 }).unwrap();
        assert!(!loose.moved.iter().any(|c| c.what() == "history.csv f"));
        assert!(loose.within_tolerance.iter().any(|c| c.what() == "history.csv f"));
    }

    /// Goal: directories that hold neither kind of output, or a tolerance that is not
    /// a number ≥ 0, are input errors.
    #[test]
    fn directories_of_nothing_comparable_are_an_input_error() {
        let t = tempfile::tempdir().unwrap();
        let e = audit(t.path(), t.path(), AuditTol::default()).unwrap_err();
        assert!(matches!(e, AuditError::NotComparable { .. }), "{e}");
        let e = audit(t.path(), t.path(), AuditTol { rtol: -1.0, atol: 0.0 }).unwrap_err();
        assert_eq!(e.to_string(), "--rtol must be a finite number ≥ 0, not -1");
    }
}
