//! NASTRAN's printed output (the `.f06` of MSC, the `.out` of NASTRAN-95) read for
//! its displacements, its real eigenvalues and its transient displacement histories
//! (SORT1 or SORT2), and an impactlab run compared with it.
//!
//! The page format: every page starts with a line whose first column is `1`, then
//! the title, the subtitle and a line (first column `0`) that ends with `SUBCASE n`;
//! a table of real displacements is headed `D I S P L A C E M E N T   V E C T O R`
//! (the complex and eigenvector tables are other titles and are not read), then
//! `POINT ID.   TYPE   T1 T2 T3 R1 R2 R3`, then one row a grid (`id G` and its six
//! components, in its displacement frame) or a row of up to six scalar points from
//! `id` on (`id S` and their values). A table runs on over page breaks until a row
//! that is neither. SORT2 output (`DISPLACEMENTS (SORT2)`) prints a table a point,
//! `POINT-ID = n` above its title and a row a SUBCASE (`SUBCASE TYPE T1 …`).

use std::collections::BTreeMap;
use std::path::Path;

/// The displacements a printed output holds: per SUBCASE, each point's components
/// (grids: T1..R3 as 1..6; scalar points: 0).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Printed {
    /// SUBCASE → (point, component) → value.
    pub subcases: BTreeMap<i64, BTreeMap<(i64, u8), f64>>,
}

/// Why a printed output or a run directory cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum PrintedError {
    /// A file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// A file is not what it should be.
    #[error("{path}:{line}: {message}")]
    Format {
        /// The file.
        path: String,
        /// Its line (1-based; 0 for the file as a whole).
        line: usize,
        /// What is wrong.
        message: String,
    },
}

const TITLE: &str = "D I S P L A C E M E N T   V E C T O R";

/// Reads the real displacement tables of a printed output's text.
pub fn read_printed(text: &str) -> Printed {
    let mut out = Printed::default();
    // NASTRAN prints SUBCASE 1 for a deck of none.
    let mut subcase = 1;
    let mut in_table = false;
    // SORT2: the point of the table, and whether rows are SUBCASEs.
    let mut point = None;
    let mut sort2 = false;
    for line in text.lines() {
        let trimmed = line.trim_end();
        if let Some((_, n)) = trimmed.split_once("POINT-ID =") {
            point = n.trim().parse::<i64>().ok();
        }
        if let Some(n) = page_subcase(trimmed) {
            subcase = n;
        }
        if trimmed.contains(TITLE) {
            // "C O M P L E X   D I S P L A C E M E N T   V E C T O R" and the like are
            // other tables.
            in_table = trimmed.trim_start().starts_with(TITLE);
            continue;
        }
        if !in_table || trimmed.trim().is_empty() {
            continue;
        }
        if trimmed.contains("POINT ID.") || trimmed.contains("SUBCASE") && trimmed.contains("TYPE") {
            sort2 = !trimmed.contains("POINT ID.");
            continue;
        }
        if line.starts_with('1') {
            // A page break: the table goes on after the next page's title.
            in_table = false;
            continue;
        }
        let words: Vec<&str> = trimmed.split_whitespace().collect();
        let (Some(id), Some(kind)) = (words.first().and_then(|w| w.parse::<i64>().ok()), words.get(1)) else {
            in_table = false;
            continue;
        };
        let values: Option<Vec<f64>> = words[2..].iter().map(|w| w.parse::<f64>().ok()).collect();
        let Some(values) = values else {
            in_table = false;
            continue;
        };
        let (id, table) = match (sort2, point) {
            (true, Some(p)) => (p, out.subcases.entry(id).or_default()),
            (true, None) => {
                in_table = false;
                continue;
            }
            (false, _) => (id, out.subcases.entry(subcase).or_default()),
        };
        match *kind {
            "G" if values.len() == 6 => {
                for (c, v) in values.iter().enumerate() {
                    table.insert((id, c as u8 + 1), *v);
                }
            }
            "S" => {
                for (k, v) in values.iter().enumerate() {
                    table.insert((id + k as i64, 0), *v);
                }
            }
            _ => in_table = false,
        }
    }
    out.subcases.retain(|_, t| !t.is_empty());
    out
}

/// A printed output's text (bytes that are not UTF-8 replaced: NASTRAN-95's pages are
/// ASCII).
pub(super) fn read_text(path: &Path) -> Result<String, PrintedError> {
    let bytes = std::fs::read(path).map_err(|source| PrintedError::Io {
        path: path.display().to_string(),
        source,
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Reads a printed output file.
pub fn read_printed_file(path: &Path) -> Result<Printed, PrintedError> {
    let printed = read_printed(&read_text(path)?);
    if printed.subcases.is_empty() {
        return Err(PrintedError::Format {
            path: path.display().to_string(),
            line: 0,
            message: format!("holds no real displacement table ({TITLE})"),
        });
    }
    Ok(printed)
}

const EIGENVALUES: &str = "R E A L   E I G E N V A L U E S";

/// One row of a printed REAL EIGENVALUES table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrintedRoot {
    /// MODE NO.
    pub mode: usize,
    /// EXTRACTION ORDER.
    pub order: usize,
    /// EIGENVALUE (λ = ω²).
    pub eigenvalue: f64,
    /// RADIAN FREQUENCY.
    pub radians: f64,
    /// CYCLIC FREQUENCY.
    pub cycles: f64,
    /// GENERALIZED MASS.
    pub generalized_mass: f64,
    /// GENERALIZED STIFFNESS.
    pub generalized_stiffness: f64,
}

/// Reads the REAL EIGENVALUES tables of a printed output's text, their rows in the
/// order printed: a table headed `R E A L   E I G E N V A L U E S`, then `MODE
/// EXTRACTION EIGENVALUE …` over two lines, then a row a root (`MODE NO.`, `EXTRACTION
/// ORDER` and five reals) until a page break (a line whose first column is `1`).
/// Boxed messages between the heading and the rows are passed over.
pub fn read_eigenvalues(text: &str) -> Vec<PrintedRoot> {
    let mut out = Vec::new();
    let mut in_table = false;
    for line in text.lines() {
        if line.contains(EIGENVALUES) {
            in_table = line.trim_start().starts_with(EIGENVALUES);
            continue;
        }
        if !in_table {
            continue;
        }
        if line.starts_with('1') {
            in_table = false;
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        if let [mode, order, rest @ ..] = words.as_slice() {
            let values: Option<Vec<f64>> = rest.iter().map(|w| w.parse::<f64>().ok()).collect();
            if let (Ok(mode), Ok(order), Some([l, w, f, m, k])) = (mode.parse(), order.parse(), values.as_deref()) {
                out.push(PrintedRoot {
                    mode,
                    order,
                    eigenvalue: *l,
                    radians: *w,
                    cycles: *f,
                    generalized_mass: *m,
                    generalized_stiffness: *k,
                });
            }
        }
    }
    out
}

/// Reads a printed output file's REAL EIGENVALUES tables.
pub fn read_eigenvalues_file(path: &Path) -> Result<Vec<PrintedRoot>, PrintedError> {
    let roots = read_eigenvalues(&read_text(path)?);
    if roots.is_empty() {
        return Err(PrintedError::Format {
            path: path.display().to_string(),
            line: 0,
            message: format!("holds no real eigenvalue table ({EIGENVALUES})"),
        });
    }
    Ok(roots)
}

/// One root of an impactlab normal modes run (`modes.csv`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunRoot {
    /// Its number.
    pub mode: usize,
    /// λ = ω².
    pub eigenvalue: f64,
    /// Cycles per unit time.
    pub cycles: f64,
}

/// A run's CSV file opened for reading, with its headers and its name for messages.
pub(super) fn open_csv(path: &Path) -> Result<(csv::Reader<std::fs::File>, csv::StringRecord, String), PrintedError> {
    let name = path.display().to_string();
    let mut r = csv::Reader::from_path(path).map_err(|e| PrintedError::Io {
        path: name.clone(),
        source: std::io::Error::other(e.to_string()),
    })?;
    let headers = r.headers().map_err(|e| format_error(&name, 1, e.to_string()))?.clone();
    Ok((r, headers, name))
}

/// What is wrong at a line of a file.
pub(super) fn format_error(path: &str, line: usize, message: String) -> PrintedError {
    PrintedError::Format {
        path: path.to_string(),
        line,
        message,
    }
}

/// The roots of an impactlab normal modes run (`modes.csv` of its directory).
pub fn read_run_roots(dir: &Path) -> Result<Vec<RunRoot>, PrintedError> {
    let path = dir.join("modes.csv");
    let (mut r, _, name) = open_csv(&path)?;
    let mut out = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let bad = |message: String| format_error(&name, i + 2, message);
        let rec = rec.map_err(|e| bad(e.to_string()))?;
        let field = |k: usize| rec.get(k).and_then(|t| t.parse::<f64>().ok());
        match (rec.get(0).and_then(|t| t.parse().ok()), field(1), field(3)) {
            (Some(mode), Some(eigenvalue), Some(cycles)) => out.push(RunRoot {
                mode,
                eigenvalue,
                cycles,
            }),
            _ => return Err(bad("not a row of mode, eigenvalue, radians, cycles, …".into())),
        }
    }
    Ok(out)
}

/// A root of the run beside the printed one of the same rank.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RootComparison {
    /// The rank (1: the lowest).
    pub rank: usize,
    /// The run's.
    pub ours: RunRoot,
    /// The printed one.
    pub theirs: PrintedRoot,
    /// |λ − λ_printed| / |λ_printed| (relative to 1e-6 of the largest printed
    /// eigenvalue where that is larger: a rigid-body root is zero to round-off).
    pub relative: f64,
}

/// The run's roots and the printed ones paired by rank (both in ascending order; as
/// many pairs as the shorter list has).
pub fn compare_roots(ours: &[RunRoot], theirs: &[PrintedRoot]) -> Vec<RootComparison> {
    let mut ours = ours.to_vec();
    ours.sort_by(|a, b| a.eigenvalue.total_cmp(&b.eigenvalue));
    let mut theirs = theirs.to_vec();
    theirs.sort_by(|a, b| a.eigenvalue.total_cmp(&b.eigenvalue));
    let top = theirs.iter().fold(0.0_f64, |a, r| a.max(r.eigenvalue.abs()));
    ours.iter()
        .zip(&theirs)
        .enumerate()
        .map(|(k, (o, t))| RootComparison {
            rank: k + 1,
            ours: *o,
            theirs: *t,
            relative: (o.eigenvalue - t.eigenvalue).abs() / t.eigenvalue.abs().max(1e-6 * top).max(f64::MIN_POSITIVE),
        })
        .collect()
}

/// The root comparison as a table.
pub fn render_roots(c: &[RootComparison], ours: usize, theirs: usize) -> String {
    let mut out = format!(
        "roots: {ours} in the run, {theirs} printed; {} compared by rank\n  rank    cycles (run)  cycles (printed)  eigenvalue difference\n",
        c.len()
    );
    for r in c {
        out.push_str(&format!(
            "  {:>4}  {:>14.6e}  {:>15.6e}  {:>21.2e}\n",
            r.rank, r.ours.cycles, r.theirs.cycles, r.relative
        ));
    }
    out
}

/// An impactlab static run's displacements (`displacements.csv` of its directory),
/// in the same form: per SUBCASE (1 for a deck of one), each grid's T1..R3.
pub fn read_run(dir: &Path) -> Result<Printed, PrintedError> {
    let path = dir.join("displacements.csv");
    let (mut r, headers, name) = open_csv(&path)?;
    let bad = |line: usize, message: String| format_error(&name, line, message);
    let col = |h: &str| headers.iter().position(|x| x == h);
    let (Some(grid), Some(t1)) = (col("grid"), col("T1")) else {
        return Err(bad(
            1,
            "is not a static run's displacements.csv (no grid and T1 columns)".into(),
        ));
    };
    let subcase_col = col("subcase");
    let mut out = Printed::default();
    for (k, row) in r.records().enumerate() {
        let line = k + 2;
        let row = row.map_err(|e| bad(line, e.to_string()))?;
        let int = |i: usize| row.get(i).and_then(|t| t.parse::<i64>().ok());
        let g = int(grid).ok_or_else(|| bad(line, "grid is not an integer".into()))?;
        let sc = match subcase_col {
            Some(i) => int(i).ok_or_else(|| bad(line, "subcase is not an integer".into()))?,
            None => 1,
        };
        let table = out.subcases.entry(sc).or_default();
        for c in 0..6 {
            let v = row
                .get(t1 + c)
                .and_then(|t| t.parse::<f64>().ok())
                .ok_or_else(|| bad(line, format!("T{} is not a number", c + 1)))?;
            table.insert((g, c as u8 + 1), v);
        }
    }
    Ok(out)
}

/// A transient solution's displacement histories as NASTRAN prints them, in SORT2
/// or SORT1: per (point, component: 1..6 for a grid, 0 for a scalar point), its
/// (time, value) rows in the order printed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Histories {
    /// (point, component) → (time, value).
    pub series: BTreeMap<(i64, u8), Vec<(f64, f64)>>,
}

/// Reads the real displacement histories of a transient solution's printed output,
/// in either sort. SORT2: `POINT-ID = n` above the table's title, then `TIME TYPE T1
/// …` and a row a printed time, `time G` and six components or `time S` and one
/// value. SORT1: `TIME = t` above the table's title, then `POINT ID. TYPE T1 …` and a
/// row a point, `id G` and six components or `id S` and the values of up to six
/// scalar points from `id` on, as a static table's. SUBCASEs are not told apart: a
/// transient deck has one.
pub fn read_transient(text: &str) -> Histories {
    let mut out = Histories::default();
    let mut point = None;
    let mut time = None;
    let mut in_table = false;
    // The table's rows are points at one time (SORT1) rather than times of one point.
    let mut by_point = false;
    for line in text.lines() {
        let trimmed = line.trim_end();
        if let Some((_, n)) = trimmed.split_once("POINT-ID =") {
            point = n.trim().parse::<i64>().ok();
            continue;
        }
        if let Some((_, t)) = trimmed.split_once("TIME =") {
            time = t.split_whitespace().next().and_then(|w| w.parse::<f64>().ok());
            continue;
        }
        if trimmed.contains(TITLE) {
            in_table = trimmed.trim_start().starts_with(TITLE);
            continue;
        }
        if !in_table || trimmed.trim().is_empty() {
            continue;
        }
        let words: Vec<&str> = trimmed.split_whitespace().collect();
        if words.starts_with(&["TIME", "TYPE"]) || words.starts_with(&["POINT", "ID.", "TYPE"]) {
            by_point = words[0] == "POINT";
            continue;
        }
        let row = (|| {
            let key = words.first()?.parse::<f64>().ok()?;
            let values: Vec<f64> = words[2..]
                .iter()
                .map(|w| w.parse::<f64>().ok())
                .collect::<Option<_>>()?;
            Some((key, *words.get(1)?, values))
        })();
        let (p, t, kind, values) = match (by_point, row, point, time) {
            (false, Some((t, kind, values)), Some(p), _) => (p, t, kind, values),
            (true, Some((p, kind, values)), _, Some(t)) if p.fract() == 0.0 => (p as i64, t, kind, values),
            _ => {
                in_table = false;
                continue;
            }
        };
        match (kind, values.len()) {
            ("G", 6) => {
                for (c, v) in values.iter().enumerate() {
                    out.series.entry((p, c as u8 + 1)).or_default().push((t, *v));
                }
            }
            ("S", 1) => out.series.entry((p, 0)).or_default().push((t, values[0])),
            ("S", 2..=6) if by_point => {
                for (k, v) in values.iter().enumerate() {
                    out.series.entry((p + k as i64, 0)).or_default().push((t, *v));
                }
            }
            _ => in_table = false,
        }
    }
    out
}

/// Reads a transient printed output file's displacement histories.
pub fn read_transient_file(path: &Path) -> Result<Histories, PrintedError> {
    let h = read_transient(&read_text(path)?);
    if h.series.is_empty() {
        return Err(PrintedError::Format {
            path: path.display().to_string(),
            line: 0,
            message: "has no displacement history (SORT2: POINT-ID = n, D I S P L A C E M E N T   V E C T O R, \
                      TIME TYPE T1 ...; SORT1: TIME = t, D I S P L A C E M E N T   V E C T O R, POINT ID. TYPE T1 \
                      ...)"
                .into(),
        });
    }
    Ok(h)
}

/// A transient run's displacement histories (the `disp_…` columns of its
/// `history.csv`, those in the basic system or a scalar point's), in the same form.
pub fn read_run_histories(dir: &Path) -> Result<Histories, PrintedError> {
    let path = dir.join("history.csv");
    let (mut r, headers, name) = open_csv(&path)?;
    let bad = |line: usize, message: String| format_error(&name, line, message);
    const C: [&str; 6] = ["T1", "T2", "T3", "R1", "R2", "R3"];
    // `disp_12_T3 [unit]` → (12, 3); `disp_7 [unit]` → (7, 0).
    let dof = |h: &str| -> Option<(i64, u8)> {
        let name = h.split(' ').next()?.strip_prefix("disp_")?;
        match name.split_once('_') {
            None => Some((name.parse().ok()?, 0)),
            Some((p, c)) => Some((p.parse().ok()?, C.iter().position(|x| *x == c)? as u8 + 1)),
        }
    };
    let columns: Vec<(usize, (i64, u8))> = headers
        .iter()
        .enumerate()
        .filter_map(|(i, h)| Some((i, dof(h)?)))
        .collect();
    if headers.get(0).is_none_or(|h| !h.starts_with("time")) || columns.is_empty() {
        return Err(bad(
            1,
            "is not a transient run's history.csv with displacements (time, disp_…)".into(),
        ));
    }
    let mut out = Histories::default();
    for (k, row) in r.records().enumerate() {
        let line = k + 2;
        let row = row.map_err(|e| bad(line, e.to_string()))?;
        let num = |i: usize| row.get(i).and_then(|t| t.parse::<f64>().ok());
        let time = num(0).ok_or_else(|| bad(line, "time is not a number".into()))?;
        for &(i, key) in &columns {
            let v = num(i).ok_or_else(|| bad(line, format!("{} is not a number", &headers[i])))?;
            out.series.entry(key).or_default().push((time, v));
        }
    }
    Ok(out)
}

/// A transient run compared with NASTRAN's printed histories: at every printed time,
/// the run's row at the same time (within a hundredth of the run's output interval:
/// NASTRAN prints its times in single precision).
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryComparison {
    /// The largest |value| NASTRAN printed of a translation (or scalar point).
    pub scale: f64,
    /// The largest |value| NASTRAN printed of a rotation.
    pub rotation_scale: f64,
    /// Every (time, component) both give, with the time: the largest relative
    /// difference first.
    pub differences: Vec<(f64, Difference)>,
    /// Printed (point, component) histories the run does not write.
    pub missing: Vec<(i64, u8)>,
    /// Printed times the run has no row at.
    pub unmatched_times: usize,
}

impl HistoryComparison {
    /// A difference relative to the scale of its kind (translations, rotations; see
    /// [`SubcaseComparison::relative`]).
    pub fn relative(&self, d: &Difference) -> f64 {
        relative(self.scale, self.rotation_scale, d)
    }

    /// The largest relative difference.
    pub fn worst(&self) -> f64 {
        self.differences.first().map_or(0.0, |(_, d)| self.relative(d))
    }
}

/// Compares a run's histories with the printed ones.
pub fn compare_histories(ours: &Histories, theirs: &Histories) -> HistoryComparison {
    let scale = |rot: bool| {
        theirs
            .series
            .iter()
            .filter(|((_, c), _)| (4..=6).contains(c) == rot)
            .flat_map(|(_, s)| s.iter().map(|p| p.1.abs()))
            .fold(0.0f64, f64::max)
    };
    let mut cmp = HistoryComparison {
        scale: scale(false),
        rotation_scale: scale(true),
        differences: Vec::new(),
        missing: Vec::new(),
        unmatched_times: 0,
    };
    for (&(point, component), printed) in &theirs.series {
        let Some(run) = ours.series.get(&(point, component)) else {
            cmp.missing.push((point, component));
            continue;
        };
        let interval = match run.as_slice() {
            [a, b, ..] => b.0 - a.0,
            _ => f64::INFINITY,
        };
        for &(t, v) in printed {
            let k = run.partition_point(|r| r.0 < t - 0.01 * interval);
            match run.get(k).filter(|r| (r.0 - t).abs() <= 0.01 * interval) {
                Some(&(_, ours)) => cmp.differences.push((
                    t,
                    Difference {
                        point,
                        component,
                        ours,
                        theirs: v,
                    },
                )),
                None => cmp.unmatched_times += 1,
            }
        }
    }
    let mut diffs = std::mem::take(&mut cmp.differences);
    diffs.sort_by(|a, b| cmp.relative(&b.1).total_cmp(&cmp.relative(&a.1)));
    cmp.differences = diffs;
    cmp
}

/// The history comparison as a table: the scales, the largest relative difference
/// and the `top` largest differences by point, component and time.
pub fn render_histories(c: &HistoryComparison, top: usize) -> String {
    let mut s = format!(
        "{} values compared; largest printed translation {:.6e}, rotation {:.6e}; largest difference {:.2e} of its \
         scale\n",
        c.differences.len(),
        c.scale,
        c.rotation_scale,
        c.worst()
    );
    if !c.missing.is_empty() {
        s += &format!(
            "  not in the run: {} printed history(ies), first point {}\n",
            c.missing.len(),
            c.missing[0].0
        );
    }
    if c.unmatched_times > 0 {
        s += &format!("  printed times without a run row: {}\n", c.unmatched_times);
    }
    s += &format!(
        "  {:>9} {:>4} {:>13} {:>14} {:>14} {:>12} {:>10}\n",
        "point", "comp", "time", "impactlab", "NASTRAN", "difference", "relative"
    );
    for (t, d) in c.differences.iter().take(top) {
        s += &format!(
            "  {:>9} {:>4} {:>13.6e} {:>14.6e} {:>14.6e} {:>12.3e} {:>10.2e}\n",
            d.point,
            component_name(d.component),
            t,
            d.ours,
            d.theirs,
            d.delta(),
            c.relative(d)
        );
    }
    s
}

/// A component's name in the printed tables: S (scalar point), T1..T3, R1..R3.
fn component_name(c: u8) -> String {
    match c {
        0 => "S".to_string(),
        1..=3 => format!("T{c}"),
        _ => format!("R{}", c - 3),
    }
}

/// One component's difference.
#[derive(Debug, Clone, PartialEq)]
pub struct Difference {
    /// The point.
    pub point: i64,
    /// Its component (1..6; 0 for a scalar point).
    pub component: u8,
    /// impactlab's value.
    pub ours: f64,
    /// NASTRAN's printed value.
    pub theirs: f64,
}

impl Difference {
    /// ours − theirs.
    pub fn delta(&self) -> f64 {
        self.ours - self.theirs
    }
}

/// A difference relative to the scale of its component's kind: the largest printed
/// translation, or for R1-R3 the largest printed rotation (at least 1e-9 of the
/// translation's: rotations printed as round-off are no scale); 0 where the
/// difference is 0, infinite where only the scale is.
fn relative(translation_scale: f64, rotation_scale: f64, d: &Difference) -> f64 {
    let scale = if (4..=6).contains(&d.component) {
        rotation_scale.max(1e-9 * translation_scale)
    } else {
        translation_scale
    };
    relative_to(d.delta(), scale)
}

/// |delta| / scale: 0 where the difference is 0, infinite where only the scale is.
pub(super) fn relative_to(delta: f64, scale: f64) -> f64 {
    if delta == 0.0 {
        0.0
    } else if scale == 0.0 {
        f64::INFINITY
    } else {
        delta.abs() / scale
    }
}

/// The SUBCASE a page heading names (its line starting with `0` ends `SUBCASE n`).
pub(super) fn page_subcase(line: &str) -> Option<i64> {
    if !line.starts_with('0') {
        return None;
    }
    let words: Vec<&str> = line.split_whitespace().collect();
    match words.as_slice() {
        [.., "SUBCASE", n] => n.parse().ok(),
        _ => None,
    }
}

/// One SUBCASE compared: the largest printed translation and rotation (the scales
/// differences are read against, [`SubcaseComparison::relative`]) and every component's difference, largest first
/// relative to its scale.
#[derive(Debug, Clone, PartialEq)]
pub struct SubcaseComparison {
    /// The SUBCASE.
    pub subcase: i64,
    /// The largest |T1..T3| (and scalar point value) NASTRAN printed.
    pub translation_scale: f64,
    /// The largest |R1..R3| NASTRAN printed.
    pub rotation_scale: f64,
    /// Every component both give, the largest relative difference first.
    pub differences: Vec<Difference>,
    /// Grids NASTRAN printed that the run does not have.
    pub missing: Vec<i64>,
}

impl SubcaseComparison {
    /// A difference relative to its component's scale (0 where the scale is 0 and
    /// the difference too). Rotations that NASTRAN prints as round-off (a membrane
    /// model's, ~1e-18) are no scale: the rotations' scale is at least 1e-9 of the
    /// largest translation's value.
    pub fn relative(&self, d: &Difference) -> f64 {
        relative(self.translation_scale, self.rotation_scale, d)
    }

    /// The largest relative difference.
    pub fn worst(&self) -> f64 {
        self.differences.first().map_or(0.0, |d| self.relative(d))
    }

    /// The largest relative difference among the rotations (R1-R3, `rotations`) or
    /// the other components, with the component it is of.
    pub fn worst_of(&self, rotations: bool) -> Option<(f64, &Difference)> {
        self.differences
            .iter()
            .find(|d| (4..=6).contains(&d.component) == rotations)
            .map(|d| (self.relative(d), d))
    }
}

/// Compares a run with a printed output, SUBCASE by SUBCASE (those of the printed
/// output the run has).
pub fn compare(ours: &Printed, theirs: &Printed) -> Vec<SubcaseComparison> {
    let mut out = Vec::new();
    for (sc, printed) in &theirs.subcases {
        let Some(run) = ours.subcases.get(sc) else { continue };
        let scale = |rot: bool| {
            printed
                .iter()
                .filter(|((_, c), _)| (4..=6).contains(c) == rot)
                .fold(0.0f64, |m, (_, v)| m.max(v.abs()))
        };
        let mut cmp = SubcaseComparison {
            subcase: *sc,
            translation_scale: scale(false),
            rotation_scale: scale(true),
            differences: Vec::new(),
            missing: Vec::new(),
        };
        for (&(p, c), &v) in printed {
            match run.get(&(p, c)) {
                Some(&ours) => cmp.differences.push(Difference {
                    point: p,
                    component: c,
                    ours,
                    theirs: v,
                }),
                None if !cmp.missing.contains(&p) => cmp.missing.push(p),
                None => {}
            }
        }
        let mut diffs = std::mem::take(&mut cmp.differences);
        diffs.sort_by(|a, b| cmp.relative(b).total_cmp(&cmp.relative(a)));
        cmp.differences = diffs;
        out.push(cmp);
    }
    out
}

/// The comparison as a table: per SUBCASE the scales, the largest relative
/// difference and the `top` largest differences by grid and component.
pub fn render(comparisons: &[SubcaseComparison], top: usize) -> String {
    let name = component_name;
    let mut s = String::new();
    for c in comparisons {
        s += &format!(
            "SUBCASE {}: {} components; largest printed translation {:.6e}, rotation {:.6e}; largest difference {:.2e} \
             of its scale\n",
            c.subcase,
            c.differences.len(),
            c.translation_scale,
            c.rotation_scale,
            c.worst()
        );
        if !c.missing.is_empty() {
            s += &format!(
                "  not in the run: {} grid(s), first {}\n",
                c.missing.len(),
                c.missing[0]
            );
        }
        s += &format!(
            "  {:>9} {:>4} {:>14} {:>14} {:>12} {:>10}\n",
            "point", "comp", "impactlab", "NASTRAN", "difference", "relative"
        );
        for d in c.differences.iter().take(top) {
            s += &format!(
                "  {:>9} {:>4} {:>14.6e} {:>14.6e} {:>12.3e} {:>10.2e}\n",
                d.point,
                name(d.component),
                d.ours,
                d.theirs,
                d.delta(),
                c.relative(d)
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: the eigenvalue table is read past its boxed information message, its rows
    /// in the order printed, and a table of another title (complex) is not read.
    #[test]
    fn real_eigenvalue_table_of_nastran_95() {
        let text = "1     VIBRATIONS OF A 10 BY 20 PLATE     PAGE    25
0
                                              R E A L   E I G E N V A L U E S

   MODE    EXTRACTION       EIGENVALUE            RADIAN              CYCLIC           GENERALIZED         GENERALIZED
    NO.       ORDER                              FREQUENCY           FREQUENCY            MASS              STIFFNESS

                                     ****************************************************************
                                     *         4 EIGENVALUE(S) AT LOW FREQ. END NOT FOUND           *
                                     ****************************************************************

        1         2        3.237408E+01        5.689823E+00        9.055634E-01        1.030220E+04        3.335242E+05
        2         1        2.022407E+02        1.422113E+01        2.263364E+00        1.030220E+04        2.083523E+06
1     VIBRATIONS OF A 10 BY 20 PLATE     PAGE    26
                                     C O M P L E X   E I G E N V A L U E S
        1         1        1.0E+00        1.0E+00        1.0E+00        1.0E+00        1.0E+00
";
        let r = read_eigenvalues(text);
        assert_eq!(r.len(), 2);
        assert_eq!((r[0].mode, r[0].order, r[0].cycles), (1, 2, 9.055634e-1));
        assert_eq!((r[1].eigenvalue, r[1].generalized_stiffness), (2.022407e2, 2.083523e6));
    }

    const PAGE: &str = "\
1     STATIC ANALYSIS OF A BEAM                                   /    95 SUN SOLARIS NASTRAN    / MAY 17, 95 / PAGE     8
      NASTRAN DEMONSTRATION PROBLEM NO. D01-14-1A
0     BENDING LOAD                                                                               SUBCASE 2
 
                                             D I S P L A C E M E N T   V E C T O R
 
      POINT ID.   TYPE          T1             T2             T3             R1             R2             R3
             1      G      0.0            0.0            0.0            0.0            0.0            0.0
             2      G      0.0            5.666667E+00   0.0            0.0            0.0            1.100000E+01
1     STATIC ANALYSIS OF A BEAM                                   /    95 SUN SOLARIS NASTRAN    / MAY 17, 95 / PAGE     9
      NASTRAN DEMONSTRATION PROBLEM NO. D01-14-1A
0     BENDING LOAD                                                                               SUBCASE 2
 
                                             D I S P L A C E M E N T   V E C T O R
 
      POINT ID.   TYPE          T1             T2             T3             R1             R2             R3
             7      G      0.0            1.440000E+02   0.0            0.0            0.0            3.600000E+01
            10      S      1.0           -2.0            3.5E-01
1     STATIC ANALYSIS OF A BEAM                                   /    95 SUN SOLARIS NASTRAN    / MAY 17, 95 / PAGE    10
0                                                                                                SUBCASE 2
                               C O M P L E X   D I S P L A C E M E N T   V E C T O R
      POINT ID.   TYPE          T1             T2             T3             R1             R2             R3
             7      G      9.0            9.0            9.0            9.0            9.0            9.0
";

    /// Goal: the page format as NASTRAN-95 prints it: a table over a page break, its
    /// SUBCASE from the page header, grid rows and a row of scalar points; a complex
    /// table is not read.
    #[test]
    fn a_displacement_table_is_read_over_page_breaks() {
        let p = read_printed(PAGE);
        assert_eq!(p.subcases.keys().copied().collect::<Vec<_>>(), [2]);
        let t = &p.subcases[&2];
        assert_eq!(t[&(2, 2)], 5.666667);
        assert_eq!(t[&(2, 6)], 11.0);
        assert_eq!(t[&(7, 2)], 144.0);
        assert_eq!(t[&(7, 1)], 0.0);
        assert_eq!((t[&(10, 0)], t[&(11, 0)], t[&(12, 0)]), (1.0, -2.0, 0.35));
        assert_eq!(t.len(), 3 * 6 + 3);
    }

    /// Goal: SORT2's tables (a point a table, a SUBCASE a row) read as SORT1's.
    #[test]
    fn a_sort2_table_is_read_by_point() {
        let page = "\
1     STATIC ANALYSIS OF A DELTA WING                       /    95 SUN SOLARIS NASTRAN    / MAY 17, 95 / PAGE
0
      POINT-ID =      12
                                             D I S P L A C E M E N T   V E C T O R
 
      SUBCASE     TYPE          T1             T2             T3             R1             R2             R3
         1          G      6.614148E-04   6.103728E-04   3.598766E-02   0.0            0.0            0.0
         2          G      7.075042E-04   5.407654E-04   3.301679E-02   0.0            0.0            0.0
";
        let p = read_printed(page);
        assert_eq!(p.subcases[&1][&(12, 3)], 3.598766E-02);
        assert_eq!(p.subcases[&2][&(12, 1)], 7.075042E-04);
        assert_eq!(p.subcases[&2].len(), 6);
    }

    /// Goal: a transient SORT2 table (NASTRAN-95's t09071a.out) is read a point at a
    /// time over a page break, its rows by time; a run's rows are matched by time.
    #[test]
    fn a_transient_sort2_history_is_read_and_matched_by_time() {
        let page = "\
0     A DYNAMIC TRANSIENT RESPONSE ANALYSIS - IMPACT LOADING                                                 SUBCASE 1
      POINT-ID =       1
                                             D I S P L A C E M E N T   V E C T O R
 
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   0.0              G      0.0            0.0            0.0            0.0            0.0            0.0
   5.000000E-05     G      0.0            7.791522E-05   0.0            0.0            0.0            0.0
1     DYNAMIC DELAMINATION BUCKLING IN COMPOSITE LAMINATES UDER             /    95 SUN SOLARIS NASTRAN    / M
0     A DYNAMIC TRANSIENT RESPONSE ANALYSIS - IMPACT LOADING                                                 SUBCASE 1
      POINT-ID =       1
                                             D I S P L A C E M E N T   V E C T O R
 
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   2.499999E-04     G      0.0            7.243613E-04   0.0            0.0            0.0            0.0
      POINT-ID =       2
                                             D I S P L A C E M E N T   V E C T O R
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   0.0              G      0.0            0.0            0.0            0.0            0.0            0.0
";
        let h = read_transient(page);
        assert_eq!(
            h.series[&(1, 2)],
            [(0.0, 0.0), (5e-5, 7.791522e-5), (2.499999e-4, 7.243613e-4)]
        );
        assert_eq!(h.series[&(2, 6)], [(0.0, 0.0)]);
        assert_eq!(h.series.len(), 12);
        let mut ours = Histories::default();
        ours.series.insert(
            (1, 2),
            vec![(0.0, 0.0), (5e-5, 7.8e-5), (1e-4, 1.0), (2.5e-4, 7.243613e-4)],
        );
        let c = compare_histories(&ours, &h);
        assert_eq!(c.differences.len(), 3);
        assert_eq!(c.missing.len(), 11);
        assert_eq!(c.differences[0].0, 5e-5);
        assert!((c.worst() - (7.8e-5 - 7.791522e-5) / 7.243613e-4).abs() < 1e-15);
    }

    /// Goal: a transient SORT1 output (a table a time, `TIME = t` above it, as MSC
    /// prints one; a page break inside a time's table; scalar points several a row)
    /// is read into the same histories as the SORT2 print of the same values.
    #[test]
    fn a_transient_sort1_output_reads_as_its_sort2_print() {
        let sort1 = "\
0                                                                                                            SUBCASE 1
      TIME =   0.000000E+00
                                             D I S P L A C E M E N T   V E C T O R
 
      POINT ID.   TYPE          T1             T2             T3             R1             R2             R3
             1      G      0.0            0.0            0.0            0.0            0.0            0.0
           101      S      1.0            2.0
1     PAGE 7
      TIME =   0.000000E+00
                                             D I S P L A C E M E N T   V E C T O R
      POINT ID.   TYPE          T1             T2             T3             R1             R2             R3
             2      G      0.0            0.0            0.0            0.0            0.0            0.0
0                                                                                                            SUBCASE 1
      TIME =   5.000000E-05
                                             D I S P L A C E M E N T   V E C T O R
      POINT ID.   TYPE          T1             T2             T3             R1             R2             R3
             1      G      0.0            7.791522E-05   0.0            0.0            0.0            0.0
             2      G      1.0            0.0            0.0            0.0            0.0           -2.5E-01
           101      S      3.0            4.0
";
        let sort2 = "\
      POINT-ID =       1
                                             D I S P L A C E M E N T   V E C T O R
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   0.0              G      0.0            0.0            0.0            0.0            0.0            0.0
   5.000000E-05     G      0.0            7.791522E-05   0.0            0.0            0.0            0.0
      POINT-ID =       2
                                             D I S P L A C E M E N T   V E C T O R
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   0.0              G      0.0            0.0            0.0            0.0            0.0            0.0
   5.000000E-05     G      1.0            0.0            0.0            0.0            0.0           -2.5E-01
      POINT-ID =     101
                                             D I S P L A C E M E N T   V E C T O R
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   0.0              S      1.0
   5.000000E-05     S      3.0
      POINT-ID =     102
                                             D I S P L A C E M E N T   V E C T O R
       TIME       TYPE          T1             T2             T3             R1             R2             R3
   0.0              S      2.0
   5.000000E-05     S      4.0
";
        let (a, b) = (read_transient(sort1), read_transient(sort2));
        assert_eq!(a, b);
        assert_eq!(a.series.len(), 14);
        assert_eq!(a.series[&(2, 6)], [(0.0, 0.0), (5e-5, -0.25)]);
        // A static output (no TIME =) holds no history.
        assert!(read_transient(PAGE).series.is_empty());
    }

    /// Goal: differences are read against the largest printed translation (rotation),
    /// largest first.
    #[test]
    fn differences_are_relative_to_the_largest_printed_value() {
        let theirs = read_printed(PAGE);
        let mut ours = theirs.clone();
        ours.subcases.get_mut(&2).unwrap().insert((2, 2), 5.666667 + 1.44e-3);
        ours.subcases.get_mut(&2).unwrap().insert((7, 6), 36.0 - 3.6e-6);
        let c = &compare(&ours, &theirs)[0];
        assert_eq!((c.translation_scale, c.rotation_scale), (144.0, 36.0));
        assert_eq!((c.differences[0].point, c.differences[0].component), (2, 2));
        assert!((c.worst() - 1e-5).abs() < 1e-12);
        assert!((c.relative(&c.differences[1]) - 1e-7).abs() < 1e-12);
    }
}
