//! Parameter sweeps on the convolution engine: the target's kernels computed once,
//! then one contact history per point, over the impactor's velocity and mass and the
//! Hertz law's K and exponent (everything outside the target's linear system).
//!
//! Points are the Cartesian product of the `--vary` lists, the first varying slowest,
//! numbered from 0. The first, the last and every tenth point are also run on the
//! direct engine; their largest difference ([`engine_difference`]) is the row's
//! `direct_check`, and one over [`DIRECT_CHECK_MAX`] fails the sweep. A shard `I/N`
//! runs the points whose number is I−1 modulo N; [`collect`] merges shards into the
//! `sweep.csv` an unsharded run writes.

use super::in_parallel;
use crate::integrate::Scheme;
use crate::model::{Model, Modify};
use crate::run::convolution::{engine_difference, CacheUse, Kernels};
use crate::run::{run_model, solved_system, Column, Engine, RunError, RunOptions, RunResult};
use crate::Error;
use indicatif::ProgressBar;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Mutex;

/// The largest `direct_check` a sweep accepts, relative to each quantity's peak: the
/// engines agree to round-off (measured 2.5e-13 to 6.7e-13 on the rod and the plate), so
/// 1e-9 leaves room for longer runs' round-off and still fails any difference in the
/// schemes' arithmetic (the `superposition` check's bound is 1e-10 for the fixed cases).
pub const DIRECT_CHECK_MAX: f64 = 1e-9;

/// What a sweep can vary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    /// The impactor's impact speed (the deck's direction kept).
    Velocity,
    /// The impactor's mass (its inertia scaled with it).
    Mass,
    /// The Hertz stiffness K (every NOLIN3 scale with it).
    K,
    /// The contact law's exponent.
    Exponent,
}

impl Param {
    /// Every parameter, by name.
    pub const ALL: [Param; 4] = [Param::Velocity, Param::Mass, Param::K, Param::Exponent];

    /// The name on the command line and in `sweep.csv`.
    pub fn name(self) -> &'static str {
        match self {
            Param::Velocity => "velocity",
            Param::Mass => "mass",
            Param::K => "k",
            Param::Exponent => "exponent",
        }
    }
}

/// One `--vary`: a parameter and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    /// The parameter.
    pub param: Param,
    /// Its values, in order.
    pub values: Vec<f64>,
}

impl Vary {
    /// Reads `NAME=START:STOP:COUNT` (evenly spaced, or geometrically when `log`) or
    /// `NAME=v1,v2,...`.
    pub fn parse(text: &str, log: &[String]) -> Result<Vary, String> {
        let (name, spec) = text
            .split_once('=')
            .ok_or_else(|| format!("--vary {text}: expected NAME=START:STOP:COUNT or NAME=v1,v2,..."))?;
        let param = Param::ALL
            .into_iter()
            .find(|p| p.name() == name)
            .ok_or_else(|| format!("--vary {text}: unknown parameter {name} (velocity, mass, k, exponent)"))?;
        let number = |s: &str| -> Result<f64, String> {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(|| format!("--vary {text}: '{s}' is not a positive number"))
        };
        let values = match spec.split(':').collect::<Vec<_>>()[..] {
            [a, b, n] => {
                let (a, b) = (number(a)?, number(b)?);
                let n: usize = n
                    .trim()
                    .parse()
                    .ok()
                    .filter(|n| (1..=100_000).contains(n))
                    .ok_or_else(|| format!("--vary {text}: COUNT must be 1 to 100000"))?;
                let geometric = log.iter().any(|l| l == name);
                (0..n)
                    .map(|i| {
                        let f = if n == 1 { 0.0 } else { i as f64 / (n - 1) as f64 };
                        if geometric {
                            a * (b / a).powf(f)
                        } else {
                            a + (b - a) * f
                        }
                    })
                    .collect()
            }
            [_] => spec.split(',').map(number).collect::<Result<Vec<f64>, String>>()?,
            _ => return Err(format!("--vary {text}: expected START:STOP:COUNT or a list")),
        };
        Ok(Vary { param, values })
    }
}

/// The points of a sweep: the Cartesian product of the values, the first `Vary`
/// slowest.
pub fn points(varies: &[Vary]) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::new()];
    for v in varies {
        out = out
            .into_iter()
            .flat_map(|p| {
                v.values.iter().map(move |x| {
                    let mut q = p.clone();
                    q.push(*x);
                    q
                })
            })
            .collect();
    }
    out
}

/// The model of one point: the base model with its impactor and contact law changed.
pub fn point_model(base: &Model, varies: &[Vary], values: &[f64]) -> Result<Model, Error> {
    let ct = base
        .contact
        .as_ref()
        .ok_or_else(|| Error::Usage("a sweep needs a model with a contact".into()))?;
    let v0 = base.v0[ct.impactor.dof];
    let mut m = Modify::default();
    let mut exponent = None;
    for (v, x) in varies.iter().zip(values) {
        match v.param {
            Param::Velocity => m.velocity_scale = Some(x / v0.abs()),
            Param::Mass => m.impactor_mass_scale = Some(x / ct.impactor.mass),
            Param::K => m.contact_stiffness_scale = Some(x / ct.stiffness),
            Param::Exponent => exponent = Some(*x),
        }
    }
    let mut model = m.apply(base)?;
    if let (Some(a), Some(c)) = (exponent, model.contact.as_mut()) {
        c.exponent = a;
    }
    Ok(model)
}

/// How to sweep.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// The parameters varied.
    pub varies: Vec<Vary>,
    /// `newmark` or `energy`.
    pub scheme: Scheme,
    /// Points run at once.
    pub jobs: usize,
    /// Run only the points numbered I−1 modulo N (`Some((I, N))`, I from 1).
    pub shard: Option<(usize, usize)>,
    /// A progress bar, set up by the caller.
    pub progress: Option<ProgressBar>,
}

/// The fixed columns of `sweep.csv` after the point number and the varied values.
pub const RESULT_COLUMNS: [&str; 7] = [
    "peak_force",
    "peak_force_time",
    "contact_end",
    "n_contacts",
    "rebound_velocity",
    "transferred_fraction",
    "energy_error",
];

/// A sweep's outputs: `sweep.csv` and whether every direct check passed.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// The CSV's header.
    pub header: Vec<String>,
    /// Its rows (point number first), in point order.
    pub rows: Vec<Vec<f64>>,
    /// Points checked against the direct engine.
    pub direct_checks: usize,
    /// The largest direct check (0 when none ran).
    pub worst_direct_check: f64,
    /// Seconds of the kernel pass within the first phase (0 when read from the cache).
    pub kernel_pass_s: f64,
    /// Where the kernels came from.
    pub kernel_cache: CacheUse,
    /// Wall seconds of the first phase: the kernel pass side by side with the direct
    /// runs of the checked points.
    pub checks_s: f64,
    /// Wall seconds of the second phase: every point on the convolution engine.
    pub points_s: f64,
}

impl SweepOutcome {
    /// True when every direct check is within [`DIRECT_CHECK_MAX`].
    pub fn passed(&self) -> bool {
        self.worst_direct_check <= DIRECT_CHECK_MAX
    }
}

/// The columns of `sweep.csv` for a model and its varied parameters.
pub fn header(model: &Model, varies: &[Vary]) -> Vec<String> {
    let mut h = vec!["point".to_string()];
    h.extend(varies.iter().map(|v| v.param.name().to_string()));
    h.extend(RESULT_COLUMNS.iter().map(|c| c.to_string()));
    h.extend(output_columns(model).iter().map(|c| format!("peak_{}", c.name())));
    h.push("direct_check".into());
    h
}

/// The history columns whose peaks a sweep reports: the requested outputs.
fn output_columns(model: &Model) -> Vec<Column> {
    crate::run::history_columns(model).into_iter().skip(5).collect()
}

/// The row of one point.
fn row(index: usize, values: &[f64], run: &RunResult, direct_check: Option<f64>) -> Vec<f64> {
    let s = &run.summary;
    let nan = f64::NAN;
    let mut r = vec![index as f64];
    r.extend_from_slice(values);
    r.extend([
        s.contact.peak_force,
        s.contact.peak_force_time.unwrap_or(nan),
        s.contact.intervals.first().map_or(nan, |i| i[1]),
        s.contact.intervals.len() as f64,
        s.impactor.rebound_velocity.unwrap_or(nan),
        s.energy.transferred_fraction.unwrap_or(nan),
        s.energy.max_relative_error.unwrap_or(nan),
    ]);
    for j in 5..run.history_columns.len() {
        r.push(
            run.history
                .iter()
                .map(|h| h[j])
                .fold(0.0, |a: f64, x| if x.abs() > a.abs() { x } else { a }),
        );
    }
    r.push(direct_check.unwrap_or(nan));
    r
}

/// A run that the energy guard stopped still gives its outputs up to the stop.
fn outputs(run: Result<RunResult, RunError>) -> Result<RunResult, Error> {
    match run {
        Ok(r) => Ok(r),
        Err(RunError::EnergyGuard { partial, .. }) => Ok(*partial),
        Err(e) => Err(e.into()),
    }
}

/// Runs a sweep of `base` (its Δt and steps from `run`) in two phases on `jobs`
/// threads: first the kernel pass side by side with the direct runs of the checked
/// points (the longest tasks, and independent of the kernels), then every point on
/// the convolution engine.
pub fn sweep(base: &Model, run: &RunOptions, opts: &SweepOptions) -> Result<SweepOutcome, Error> {
    let all = points(&opts.varies);
    let last = all.len() - 1;
    let mine: Vec<usize> = (0..all.len())
        .filter(|i| opts.shard.is_none_or(|(k, n)| i % n == k - 1))
        .collect();
    let checked: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|&i| i == 0 || i == last || i % 10 == 0)
        .collect();
    let bar = opts.progress.clone().unwrap_or_else(ProgressBar::hidden);
    let (model, sys) = solved_system(base, run.skip_inert)?;
    let model = model.as_ref();
    let dt = run.dt.unwrap_or(model.time.dt);
    let steps = run.steps.unwrap_or(model.time.steps);
    let on = |engine| RunOptions {
        scheme: opts.scheme,
        engine,
        progress: None,
        ..run.clone()
    };
    let (opts_conv, opts_direct) = (on(Engine::Convolution), on(Engine::Direct));
    bar.set_length((mine.len() + checked.len()) as u64);

    let t0 = std::time::Instant::now();
    let kernels = Mutex::new(None);
    let direct = in_parallel(opts.jobs, checked.len() + 1, |k| {
        if k == 0 {
            let pass = Kernels::for_run(
                model,
                &sys,
                dt,
                steps,
                run.kernel_cache.as_deref(),
                &ProgressBar::hidden(),
            );
            *kernels.lock().expect("no worker panics") = Some(pass);
            return None;
        }
        let i = checked[k - 1];
        let result = point_model(model, &opts.varies, &all[i]).and_then(|m| outputs(run_model(&m, &opts_direct)));
        bar.inc(1);
        Some(result.map(|r| (i, r)))
    });
    let (kernels, cache) = kernels
        .into_inner()
        .expect("no worker panics")
        .expect("task 0 is the kernel pass")?;
    let direct: HashMap<usize, RunResult> = direct.into_iter().flatten().collect::<Result<_, _>>()?;
    let checks_s = t0.elapsed().as_secs_f64();

    let t1 = std::time::Instant::now();
    let rows = in_parallel(opts.jobs, mine.len(), |k| {
        let i = mine[k];
        let result = point_model(model, &opts.varies, &all[i]).and_then(|m| {
            let conv = outputs(kernels.run(&m, &opts_conv, &ProgressBar::hidden()))?;
            let check = direct
                .get(&i)
                .map(|d| engine_difference(d, &conv).map_or(f64::INFINITY, |w| w.0));
            Ok(row(i, &all[i], &conv, check))
        });
        bar.inc(1);
        result
    });
    bar.finish_and_clear();
    let rows: Vec<Vec<f64>> = rows.into_iter().collect::<Result<_, _>>()?;
    let (direct_checks, worst_direct_check) = direct_checks(&rows);
    Ok(SweepOutcome {
        header: header(model, &opts.varies),
        direct_checks,
        worst_direct_check,
        rows,
        kernel_pass_s: kernels.pass_s,
        kernel_cache: cache,
        checks_s,
        points_s: t1.elapsed().as_secs_f64(),
    })
}

/// The points of `sweep.csv` rows also run on the direct engine: how many, and the
/// largest difference (0 when none; `direct_check` is the last column, empty where a
/// point was not checked).
pub fn direct_checks(rows: &[Vec<f64>]) -> (usize, f64) {
    let checks = rows.iter().filter_map(|r| r.last().copied()).filter(|v| !v.is_nan());
    checks.fold((0, 0.0), |(n, worst), v| (n + 1, worst.max(v)))
}

/// `sweep.csv`: the header, then the rows; numbers in the shortest form that reads
/// back to the same f64, NaN as an empty field, the point number as an integer.
pub fn csv_bytes(header: &[String], rows: &[Vec<f64>]) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header).expect("in memory");
    for r in rows {
        w.write_record(r.iter().enumerate().map(|(j, v)| {
            if v.is_nan() {
                String::new()
            } else if j == 0 {
                format!("{}", *v as u64)
            } else {
                format!("{v:e}")
            }
        }))
        .expect("in memory");
    }
    w.into_inner().expect("in memory")
}

/// Reads a `sweep.csv` back: header and rows (empty fields as NaN).
pub fn read_csv(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), Error> {
    let bad = |what: String| Error::Usage(format!("{}: {what}", path.display()));
    let mut r = csv::Reader::from_path(path).map_err(|e| bad(e.to_string()))?;
    let header: Vec<String> = r
        .headers()
        .map_err(|e| bad(e.to_string()))?
        .iter()
        .map(String::from)
        .collect();
    let mut rows = Vec::new();
    for (k, rec) in r.records().enumerate() {
        let rec = rec.map_err(|e| bad(e.to_string()))?;
        let row = rec
            .iter()
            .map(|f| if f.is_empty() { Ok(f64::NAN) } else { f.parse::<f64>() })
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|e| bad(format!("row {}: {e}", k + 2)))?;
        rows.push(row);
    }
    Ok((header, rows))
}

/// Merges shards' `sweep.csv` files: the same header in each, every point once, in
/// point order; `total` points in all when given.
pub fn collect(
    parts: &[(Vec<String>, Vec<Vec<f64>>)],
    total: Option<usize>,
) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    let Some((header, _)) = parts.first() else {
        return Err("no shards to collect".into());
    };
    if let Some(k) = parts.iter().position(|(h, _)| h != header) {
        return Err(format!("shard {} has other columns than the first", k + 1));
    }
    let mut rows: Vec<Vec<f64>> = parts.iter().flat_map(|(_, r)| r.iter().cloned()).collect();
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    for w in rows.windows(2) {
        if w[0][0] == w[1][0] {
            return Err(format!("point {} is in two shards", w[0][0]));
        }
    }
    if let Some(n) = total {
        let missing: Vec<usize> = (0..n).filter(|i| !rows.iter().any(|r| r[0] == *i as f64)).collect();
        if !missing.is_empty() {
            return Err(format!(
                "{} of {n} points missing (first: {})",
                missing.len(),
                missing[0]
            ));
        }
    }
    Ok((header.clone(), rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: `--vary` reads ranges (even or geometric) and lists, and refuses the rest.
    #[test]
    fn vary_reads_ranges_and_lists() {
        let v = Vary::parse("velocity=100:300:3", &[]).unwrap();
        assert_eq!((v.param, v.values), (Param::Velocity, vec![100.0, 200.0, 300.0]));
        let v = Vary::parse("k=1e5:1e7:3", &["k".into()]).unwrap();
        assert!((v.values[1] - 1e6).abs() < 1e-6, "{:?}", v.values);
        let v = Vary::parse("exponent=1.5,1.4", &[]).unwrap();
        assert_eq!(v.values, vec![1.5, 1.4]);
        for bad in [
            "speed=1:2:3",
            "velocity",
            "velocity=1:2",
            "velocity=-1,2",
            "mass=1:2:0",
            "k=NaN",
        ] {
            assert!(Vary::parse(bad, &[]).is_err(), "{bad}");
        }
    }

    /// Goal: points are the Cartesian product, the first parameter slowest.
    #[test]
    fn points_vary_the_first_parameter_slowest() {
        let a = Vary {
            param: Param::Velocity,
            values: vec![1.0, 2.0],
        };
        let b = Vary {
            param: Param::K,
            values: vec![10.0, 20.0, 30.0],
        };
        let p = points(&[a, b]);
        assert_eq!(p.len(), 6);
        assert_eq!(p[0], vec![1.0, 10.0]);
        assert_eq!(p[1], vec![1.0, 20.0]);
        assert_eq!(p[3], vec![2.0, 10.0]);
    }
}

/// What the figures of a sweep need beyond `sweep.csv`: the deck's units and the
/// impactor's mass where it is not varied.
#[derive(Debug, Clone)]
pub struct FigureContext {
    /// The deck's name.
    pub deck: String,
    /// The impactor's mass, for the impact energy of points that do not vary it.
    pub mass: f64,
    /// Units of the deck: length, force, time.
    pub units: crate::run::UnitSystem,
}

/// The figures of a sweep, from its `sweep.csv` alone: peak force, contact duration,
/// transferred fraction and the largest |strain| of the strain outputs against the impact
/// energy ½mv², one line per combination of the other varied parameters, the points
/// also run on the direct engine ringed. Written as `DIR/<name>.png` and `.svg`.
pub fn figures(
    header: &[String],
    rows: &[Vec<f64>],
    cx: &FigureContext,
    dir: &Path,
) -> Result<Vec<std::path::PathBuf>, crate::plot::PlotError> {
    use crate::plot::{line_chart, Chart, Line};
    let col = |name: &str| header.iter().position(|h| h == name);
    let (Some(vcol), Some(check)) = (col("velocity"), col("direct_check")) else {
        return Ok(Vec::new()); // no impact energy axis without a velocity sweep
    };
    let mcol = col("mass");
    let energy = |r: &[f64]| 0.5 * mcol.map_or(cx.mass, |j| r[j]) * r[vcol] * r[vcol];
    // Lines: one per combination of the varied parameters other than velocity and mass.
    let others: Vec<usize> = (1..header.len())
        .take_while(|&j| header[j] != RESULT_COLUMNS[0])
        .filter(|&j| j != vcol && Some(j) != mcol)
        .collect();
    let key = |r: &[f64]| others.iter().map(|&j| r[j]).collect::<Vec<f64>>();
    let mut groups: Vec<(Vec<f64>, Vec<&Vec<f64>>)> = Vec::new();
    for r in rows {
        match groups.iter_mut().find(|(k, _)| *k == key(r)) {
            Some((_, g)) => g.push(r),
            None => groups.push((key(r), vec![r])),
        }
    }
    let u = &cx.units;
    let label = |k: &[f64]| {
        if k.is_empty() {
            "sweep".to_string()
        } else {
            others
                .iter()
                .zip(k)
                .map(|(&j, v)| format!("{} = {v:e}", header[j]))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    // Lines of column j (its magnitude when `abs`), colours from `colour0` on.
    let lines_of = |j: usize, name: &str, colour0: usize, abs: bool| -> Vec<Line> {
        groups
            .iter()
            .enumerate()
            .map(|(g, (k, rs))| {
                let mut rs: Vec<&&Vec<f64>> = rs.iter().filter(|r| r[j].is_finite()).collect();
                rs.sort_by(|a, b| energy(a).total_cmp(&energy(b)));
                let rings = rs
                    .iter()
                    .enumerate()
                    .filter(|(_, r)| !r[check].is_nan())
                    .map(|(i, _)| i)
                    .collect();
                let title = if name.is_empty() {
                    label(k)
                } else {
                    format!("{name}, {}", label(k))
                };
                let y = rs.iter().map(|r| if abs { r[j].abs() } else { r[j] }).collect();
                Line::new(title, rs.iter().map(|r| energy(r)).collect(), y, colour0 + g)
                    .markers()
                    .emphasis(rings)
            })
            .collect()
    };
    let x_label = format!("impact energy ½mv² [{}]", u.energy);
    let footer = format!(
        "impactlab sweep · {} · convolution engine; ringed: also run on the direct engine",
        cx.deck
    );
    let chart = |title: &str, y: String, lines: Vec<Line>| Chart {
        title: title.into(),
        x_label: x_label.clone(),
        y_label: y,
        footer: footer.clone(),
        lines,
        ..Default::default()
    };
    let mut out = Vec::new();
    for (name, title, y) in [
        ("peak_force", "Peak contact force", format!("peak force [{}]", u.force)),
        (
            "contact_end",
            "End of the first contact",
            format!("contact end [{}]", u.time),
        ),
        (
            "transferred_fraction",
            "Energy left in the target",
            "1 − (v_rebound/v0)² [-]".to_string(),
        ),
    ] {
        if let Some(j) = col(name) {
            let lines = lines_of(j, "", 0, false);
            out.extend(line_chart(&chart(title, y, lines), &dir.join(name.replace('_', "-")))?);
        }
    }
    // At most as many lines as the palette has colours.
    let strains: Vec<usize> = (0..header.len())
        .filter(|&j| header[j].starts_with("peak_strain_"))
        .take((crate::plot::PALETTE.len() / groups.len().max(1)).max(1))
        .collect();
    if !strains.is_empty() {
        let lines = strains
            .iter()
            .enumerate()
            .flat_map(|(s, &j)| lines_of(j, header[j].trim_start_matches("peak_"), s * groups.len(), true))
            .collect();
        out.extend(line_chart(
            &chart("Largest strain at each gage", "largest |strain| [-]".into(), lines),
            &dir.join("strain-peaks"),
        )?);
    }
    Ok(out)
}
