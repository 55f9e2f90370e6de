//! Auditing a change: two runs' output directories compared column by column and
//! summary value by summary value, so a reviewer sees what moved and by how much.

use super::gold;
use serde_json::Value;
use std::path::Path;

/// Two run directories that cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum AuditError {
    #[error("{path}: {source}")]
    Read {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {source}")]
    Json {
        path: String,
        #[source]
        source: serde_json::Error,
    },
    #[error("{0}")]
    Csv(#[from] gold::CsvError),
}

/// One compared quantity.
#[derive(Debug, Clone)]
pub struct Moved {
    pub what: String,
    pub baseline: f64,
    pub candidate: f64,
    /// |candidate − baseline| relative to the baseline's scale (column max or value).
    pub relative: f64,
    pub at: String,
}

fn leaves(prefix: &str, v: &Value, out: &mut Vec<(String, f64)>) {
    match v {
        Value::Number(n) => out.push((prefix.to_string(), n.as_f64().unwrap_or(f64::NAN))),
        Value::Object(m) => m.iter().for_each(|(k, v)| {
            leaves(
                &if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                },
                v,
                out,
            )
        }),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, v)| leaves(&format!("{prefix}[{i}]"), v, out)),
        _ => {}
    }
}

/// Compares `history.csv`, `energy.csv` and `summary.json` of two run directories.
/// Timing entries (`run.*_s`) are listed but never count as a numerical change.
pub fn audit(base: &Path, cand: &Path) -> Result<Vec<Moved>, AuditError> {
    let mut out = Vec::new();
    let read_json = |d: &Path| -> Result<Value, AuditError> {
        let p = d.join("summary.json");
        let path = || p.display().to_string();
        let t = std::fs::read_to_string(&p).map_err(|source| AuditError::Read { path: path(), source })?;
        serde_json::from_str(&t).map_err(|source| AuditError::Json { path: path(), source })
    };
    let (mut a, mut b) = (Vec::new(), Vec::new());
    leaves("", &read_json(base)?, &mut a);
    leaves("", &read_json(cand)?, &mut b);
    for (k, va) in &a {
        if let Some((_, vb)) = b.iter().find(|(kb, _)| kb == k) {
            let scale = va.abs().max(f64::MIN_POSITIVE);
            out.push(Moved {
                what: format!("summary {k}"),
                baseline: *va,
                candidate: *vb,
                relative: (vb - va).abs() / scale,
                at: String::new(),
            });
        }
    }
    for file in ["history.csv", "energy.csv"] {
        let (ha, ra) = gold::read(&base.join(file))?;
        let (hb, rb) = gold::read(&cand.join(file))?;
        for (j, name) in ha.iter().enumerate().skip(1) {
            let Some(jb) = hb.iter().position(|n| n == name) else {
                continue;
            };
            let scale = ra.iter().map(|r| r[j].abs()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
            let mut worst = (0.0, 0.0, 0.0, 0.0);
            for (x, y) in ra.iter().zip(&rb) {
                let d = (y[jb] - x[j]).abs() / scale;
                if d > worst.0 || d.is_nan() {
                    worst = (d, x[j], y[jb], x[0]);
                }
            }
            out.push(Moved {
                what: format!("{file} {name}"),
                baseline: worst.1,
                candidate: worst.2,
                relative: worst.0,
                at: format!("t = {:.6e}", worst.3),
            });
        }
        if ra.len() != rb.len() {
            out.push(Moved {
                what: format!("{file} rows"),
                baseline: ra.len() as f64,
                candidate: rb.len() as f64,
                relative: 1.0,
                at: String::new(),
            });
        }
    }
    Ok(out)
}

/// The audit as text: what moved, largest first; unchanged quantities counted.
pub fn audit_text(moved: &[Moved]) -> String {
    let is_timing = |m: &Moved| m.what.starts_with("summary run.") && m.what.ends_with("_s");
    let mut v: Vec<&Moved> = moved.iter().filter(|m| m.relative > 0.0 && !is_timing(m)).collect();
    v.sort_by(|a, b| b.relative.total_cmp(&a.relative));
    let mut s = format!(
        "{:<48} {:>16} {:>16} {:>10}  where\n",
        "quantity", "baseline", "candidate", "moved"
    );
    for m in &v {
        s += &format!(
            "{:<48} {:>16.9e} {:>16.9e} {:>10.2e}  {}\n",
            m.what, m.baseline, m.candidate, m.relative, m.at
        );
    }
    s += &format!(
        "{} quantities moved, {} unchanged (timings not compared)\n",
        v.len(),
        moved.iter().filter(|m| m.relative == 0.0 && !is_timing(m)).count()
    );
    s
}
