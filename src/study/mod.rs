//! Studies over families of runs: the paper's plate mesh study ([`mesh`]), the
//! stability map ([`stability`]), the work-precision study ([`accuracy`]), and the
//! verification cases run in parallel ([`cases`]).

pub mod cases;
pub mod mesh;

use crate::error::Error;
use crate::numerics::median;
use crate::run::{run_model, Column, RunOptions, RunResult};
use serde::{de::DeserializeOwned, Serialize};
use std::fmt::Write as _;
use std::path::Path;

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
pub fn read_rows_file<T: DeserializeOwned>(path: &Path) -> Result<Vec<T>, Error> {
    let io = |source| Error::Io {
        path: path.display().to_string(),
        source,
    };
    let bytes = std::fs::read(path).map_err(io)?;
    read_rows(&bytes).map_err(|e| io(std::io::Error::new(std::io::ErrorKind::InvalidData, e)))
}

/// Writes a generated page atomically; an error names the file.
pub fn write_page(path: &Path, text: &str) -> Result<(), Error> {
    crate::output::write_file_atomically(path, text.as_bytes()).map_err(|source| Error::Io {
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

/// Times the paper's 49×49 plate deck: one warm-up, then `repeats` timed runs; reports
/// the median of each stage.
pub fn bench_plate(repeats: usize, steps: usize) -> Result<String, Error> {
    use std::time::Instant;
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "));
    let mut stages: Vec<[f64; 7]> = Vec::new();
    // Per repeat: the direct run's loop and its solves, the convolution run's loop.
    let mut ratios: Vec<[f64; 3]> = Vec::new();
    let mut solved = 0;
    for rep in 0..=repeats {
        let t0 = Instant::now();
        let model = crate::paper::plate_model()?;
        let read = t0.elapsed().as_secs_f64();
        let opts = RunOptions {
            steps: Some(steps),
            ..Default::default()
        };
        let run = run_model(&model, &opts)?;
        let t1 = Instant::now();
        let dir = tempfile::tempdir().map_err(|source| Error::Io {
            path: "temporary directory".into(),
            source,
        })?;
        let out = dir.path().join("plate");
        crate::output::write_dir_atomically(&out, &crate::output::run_files(&model, &run)).map_err(|source| {
            Error::Io {
                path: out.display().to_string(),
                source,
            }
        })?;
        let write = t1.elapsed().as_secs_f64();
        let s = &run.stats;
        let assembly = run.summary.run.assembly_s;
        let total = s.total_time.as_secs_f64();
        let (factor, solve) = (s.factor_time.as_secs_f64(), s.solve_time.as_secs_f64());
        solved = run.summary.model.solved_dofs as u64;
        let wall = t0.elapsed().as_secs_f64();
        let conv = run_model(
            &model,
            &RunOptions {
                engine: crate::run::Engine::Convolution,
                ..opts
            },
        )?;
        if rep > 0 {
            ratios.push([total, solve, conv.stats.total_time.as_secs_f64()]);
            stages.push([read, assembly, factor, solve, total - factor - solve, write, wall]);
        }
    }
    let col = |j: usize| median(stages.iter().map(|r| r[j]).collect());
    let mut out = format!(
        "plate 49x49 ({solved} solved DOF), newmark, dt 1e-7 s, {steps} steps; median of {repeats} runs after a warm-up\n"
    );
    if let Some(load) = &load {
        out += &format!("load average at the start (1, 5, 15 min): {load}\n");
    }
    for (j, name) in [
        "read deck + build model",
        "assembly (incl. inert-DOF detection)",
        "factorisation",
        "stepping: linear solves",
        "stepping: everything else (matvecs, contact, ledger, recording)",
        "output (CSV + JSON, atomic)",
        "total wall",
    ]
    .iter()
    .enumerate()
    {
        out += &format!("  {name:<66} {:>9.4} s\n", col(j));
    }
    // Ratios within each repeat (the machine's load cancels), then their median.
    let ratio = |f: &dyn Fn(&[f64; 3]) -> f64| median(ratios.iter().map(f).collect());
    out += "ratios, each measured within one repeat (median):\n";
    out += &format!(
        "  {:<66} {:>9.3}\n",
        "direct run's stepping / its triangular solve pairs (goal 1.2)",
        ratio(&|r| r[0] / r[1])
    );
    out += &format!(
        "  {:<66} {:>9.3}\n",
        "convolution engine run (kernel pass included) / direct run",
        ratio(&|r| r[2] / r[0])
    );
    // The cache and a sweep, once each, against the median direct run.
    let direct = median(ratios.iter().map(|r| r[0]).collect());
    let model = crate::paper::plate_model()?;
    let cache = tempfile::tempdir().map_err(|source| Error::Io {
        path: "temporary directory".into(),
        source,
    })?;
    let cached = RunOptions {
        steps: Some(steps),
        engine: crate::run::Engine::Convolution,
        kernel_cache: Some(cache.path().join("kernels")),
        ..Default::default()
    };
    let cold = run_model(&model, &cached)?.stats.total_time.as_secs_f64();
    let warm = run_model(&model, &cached)?.stats.total_time.as_secs_f64();
    out += &format!(
        "  {:<66} {:>9.3}\n",
        "kernel pass (cold cache) / direct run",
        cold / direct
    );
    out += &format!(
        "  {:<66} {:>9.4}\n",
        "cached convolution run / direct run (goal 0.05)",
        warm / direct
    );
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let cache_dir = cache.path();
    let sweep_of = |varies: &[&str], cache: &str| -> Result<sweep::SweepOutcome, Error> {
        sweep::sweep(
            &model,
            &RunOptions {
                steps: Some(steps),
                kernel_cache: Some(cache_dir.join(cache)),
                ..Default::default()
            },
            &sweep::SweepOptions {
                varies: varies
                    .iter()
                    .map(|v| sweep::Vary::parse(v, &[]))
                    .collect::<Result<_, _>>()
                    .map_err(|e| Error::Usage(e.to_string()))?,
                scheme: crate::integrate::Scheme::Newmark,
                jobs,
                shard: None,
                progress: None,
                checks: Default::default(),
            },
        )
    };
    let line = sweep_of(&["velocity=100:2000:100"], "line")?;
    let mass = model.contact.as_ref().map_or(1.0, |c| c.impactor.mass);
    let grid = sweep_of(
        &[
            "velocity=100:2000:100",
            &format!("mass={}:{}:100", mass / 4.0, mass * 4.0),
        ],
        "grid",
    )?;
    for (name, value) in [
        (
            format!(
                "100-velocity sweep, cold cache, {} direct checks, {jobs} jobs / direct (goal 2.0)",
                line.direct_checks
            ),
            line.wall_s,
        ),
        (
            "  its 100 points on the convolution engine, one core / direct (goal 0.2)".into(),
            line.points_s,
        ),
        ("  its kernel pass / direct".into(), line.kernel_pass_s),
        (
            format!("  its {} direct checks, summed / direct", line.direct_checks),
            line.checks_s,
        ),
        (
            format!(
                "100 x 100 grid (velocity x mass), cold cache, {} direct checks, {jobs} jobs / direct (goal 25)",
                grid.direct_checks
            ),
            grid.wall_s,
        ),
        (
            "  its 10 000 points on the convolution engine, one core / direct".into(),
            grid.points_s,
        ),
    ] {
        out += &format!("  {name:<66} {:>9.3}\n", value / direct);
    }
    Ok(out)
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
pub mod mutants;
pub mod stability;
pub mod sweep;
pub mod threshold;

/// What each optional effect costs: wall time (median of 3 runs) of the scene as
/// configured, with the membrane DOFs solved, and without the ledger.
pub fn scene_costs(model: &crate::model::Model, opts: &RunOptions) -> Result<String, Error> {
    let time = |o: &RunOptions| -> Result<(f64, crate::run::Summary), Error> {
        let mut w = Vec::new();
        let mut last = crate::run::Summary::default();
        for _ in 0..3 {
            let t0 = std::time::Instant::now();
            let r = run_model(model, o)?;
            w.push(t0.elapsed().as_secs_f64());
            last = r.summary;
        }
        Ok((median(w), last))
    };
    let variants = [
        (
            "membrane DOFs skipped, ledger on",
            RunOptions {
                skip_inert: true,
                ledger: true,
                ..opts.clone()
            },
        ),
        (
            "membrane DOFs solved, ledger on",
            RunOptions {
                skip_inert: false,
                ledger: true,
                ..opts.clone()
            },
        ),
        (
            "membrane DOFs skipped, ledger off",
            RunOptions {
                skip_inert: true,
                ledger: false,
                ..opts.clone()
            },
        ),
    ];
    let mut out = String::from("| variant | solved DOF | wall [s] | peak force |\n|---|---|---|---|\n");
    for (name, o) in variants {
        let (t, s) = time(&o)?;
        let _ = writeln!(
            out,
            "| {name} | {} | {t:.3} | {} |",
            s.model.solved_dofs, s.contact.peak_force
        );
    }
    Ok(out)
}

/// The peak resident memory of this process since the last [`reset_peak_memory`]
/// (`VmHWM` of `/proc/self/status`, Linux), in bytes; `None` elsewhere.
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb = status.lines().find_map(|l| l.strip_prefix("VmHWM:"))?;
    Some(kb.trim().trim_end_matches("kB").trim().parse::<u64>().ok()? * 1024)
}

/// Resets the peak that [`peak_memory`] reads (`5` into `/proc/self/clear_refs`).
fn reset_peak_memory() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// How the reader, the model build, the factorisation and the stepping scale with
/// the plate mesh: for each N of `sizes`, the N×N plate deck (`mesh plate --n N`)
/// read and built, assembled, factorised and run `steps` steps, each stage timed,
/// with the peak resident memory of the whole (Linux) beside the run's
/// [`crate::run::memory_estimate`] of the model as read (every DOF) and as solved (the
/// inert ones dropped). Then the reader and model build alone on the
/// plates of `read_sizes` (N = 705 is about a million lines), per line.
pub fn bench_size(sizes: &[usize], read_sizes: &[usize], steps: usize) -> Result<String, Error> {
    use std::time::Instant;
    let gib = |b: u64| b as f64 / (1u64 << 30) as f64;
    let mut out = format!(
        "plate N×N, newmark, dt 1e-7 s, {steps} steps, one run each\n\
         {:>5} {:>8} {:>8} {:>9} {:>10} {:>10} {:>12} {:>10} {:>10} {:>10}\n",
        "N",
        "lines",
        "solved",
        "read [s]",
        "assemb [s]",
        "factor [s]",
        "step [ms]",
        "peak [GiB]",
        "est. read",
        "est. solved"
    );
    for &n in sizes {
        let deck = crate::mesh::plate_deck(n)?;
        reset_peak_memory();
        let t0 = Instant::now();
        let model = crate::model_from_text("plate", &deck)?;
        let read = t0.elapsed().as_secs_f64();
        let opts = RunOptions {
            steps: Some(steps),
            ..Default::default()
        };
        let run = run_model(&model, &opts)?;
        let peak = peak_memory().map_or("-".into(), |b| format!("{:.3}", gib(b)));
        let s = &run.stats;
        let per_step = (s.total_time - s.factor_time).as_secs_f64() / steps as f64;
        let solved = crate::run::solved_system(&model, opts.skip_inert)?.0;
        let as_read = crate::run::memory_estimate(&model, steps, opts.engine);
        let estimate = crate::run::memory_estimate(&solved, steps, opts.engine);
        let _ = writeln!(
            out,
            "{n:>5} {:>8} {:>8} {read:>9.3} {:>10.3} {:>10.3} {:>12.3} {peak:>10} {:>10.3} {:>10.3}",
            deck.lines().count(),
            run.summary.model.solved_dofs,
            run.summary.run.assembly_s,
            s.factor_time.as_secs_f64(),
            1e3 * per_step,
            gib(as_read),
            gib(estimate)
        );
    }
    let _ = writeln!(
        out,
        "\nreader and model build alone, by deck length\n{:>5} {:>9} {:>9} {:>12}",
        "N", "lines", "read [s]", "µs per line"
    );
    for &n in read_sizes {
        let deck = crate::mesh::plate_deck(n)?;
        let lines = deck.lines().count();
        let t0 = Instant::now();
        let model = crate::model_from_text("plate", &deck)?;
        let read = t0.elapsed().as_secs_f64();
        drop(model);
        let _ = writeln!(out, "{n:>5} {lines:>9} {read:>9.3} {:>12.3}", 1e6 * read / lines as f64);
    }
    Ok(out)
}
