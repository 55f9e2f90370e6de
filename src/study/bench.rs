//! Benchmarks: what accuracy and each effect cost in time, measured as ratios within
//! one run (`impactlab bench`), and what the model's size costs in time and memory.

use super::{sweep, StudyError};
use crate::model::Model;
use crate::numerics::median;
use crate::run::{run_model, Engine, RunOptions};
use std::fmt::Write as _;
use std::path::Path;

/// Times the paper's 49×49 plate deck: one warm-up, then `repeats` timed runs; reports
/// the median of each stage, then ratios measured within one run (the machine's load
/// cancels): the direct run against its solves, the convolution engine, the kernel
/// cache and sweeps against the direct run, the shear-deformable plate (the cross-ply
/// with G1Z, G2Z: MITC4) against the thin one per step, and the curved panel (the
/// plate wrapped onto a cylinder of radius 10 in, `mesh::panel_deck`: its membrane
/// coupled to its bending, six DOFs a grid solved) against the flat plate per step.
pub fn bench_plate(repeats: usize, steps: usize) -> Result<String, StudyError> {
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "));
    let timed = plate_repeats(repeats, steps)?;
    let mut out = format!(
        "plate 49x49 ({} solved DOF), newmark, dt 1e-7 s, {steps} steps; median of {repeats} runs after a warm-up\n",
        timed.solved
    );
    if let Some(load) = &load {
        out += &format!("load average at the start (1, 5, 15 min): {load}\n");
    }
    out += &stage_table(&timed.stages);
    out += &engine_ratios(&timed.ratios);
    if let Some((duration, peak, t)) = &timed.modal {
        out += &format!(
            "  {:<66} {:>9.3}\n",
            "modal engine run (reduction included) / direct run (goal 0.3)",
            median(timed.ratios.iter().map(|r| r[7] / r[6]).collect())
        );
        out += &format!(
            "    its reduction: {} modes, {} residual vectors, {} Lanczos vectors, {:.3} s of which modes {:.3} s;\n    \
             against the direct run: contact duration {duration:.1e}, peak force {peak:.1e} (goal 1e-3)\n",
            t.modes, t.residual_vectors, t.lanczos_steps, t.reduction_s, t.modes_s
        );
    }
    out += &format!(
        "  {:<66} {:>9.3}\n",
        format!(
            "curved panel R = 10 in ({} solved DOF) / flat plate, per step (goal 2.5)",
            timed.panel_solved
        ),
        median(timed.ratios.iter().map(|r| r[5] / r[4]).collect())
    );
    // The cache and a sweep, once each, against the median direct run.
    let direct = median(timed.ratios.iter().map(|r| r[0]).collect());
    let model = crate::paper::plate_model()?;
    let cache = tempfile::tempdir().map_err(|source| StudyError::Io {
        path: "temporary directory".into(),
        source,
    })?;
    out += &cache_ratios(&model, steps, cache.path(), direct)?;
    out += &sweep_ratios(&model, steps, cache.path(), direct)?;
    Ok(out)
}

/// The timed repeats of the plate: per repeat, the stages of [`STAGES`] and the
/// direct run's loop, its solves, the convolution run's loop, the shear plate's
/// direct stepping (its loop less its factorisation) with the thin plate's, and the
/// curved panel's stepping.
struct PlateRepeats {
    stages: Vec<[f64; 7]>,
    ratios: Vec<[f64; 8]>,
    solved: u64,
    /// The modal run's relative differences from the direct run (contact duration,
    /// peak force) and its truncation.
    modal: Option<(f64, f64, crate::run::modal::Truncation)>,
    /// The curved panel's solved DOFs.
    panel_solved: u64,
}

/// The stages [`plate_repeats`] times, in its order.
const STAGES: [&str; 7] = [
    "read deck + build model",
    "assembly (incl. inert-DOF detection)",
    "factorisation",
    "stepping: linear solves",
    "stepping: everything else (matvecs, contact, ledger, recording)",
    "output (CSV + JSON, atomic)",
    "total wall",
];

fn plate_repeats(repeats: usize, steps: usize) -> Result<PlateRepeats, StudyError> {
    use std::time::Instant;
    let mut stages: Vec<[f64; 7]> = Vec::new();
    // Per repeat: the direct run's loop and its solves, the convolution run's loop,
    // the shear plate's stepping and the thin plate's.
    let mut ratios: Vec<[f64; 8]> = Vec::new();
    let mut modal_error = None;
    let shear_model = crate::paper::plate_shear_model()?;
    let panel_model = crate::mesh::panel_model(49, 10.0)?;
    let (mut solved, mut panel_solved) = (0, 0);
    for rep in 0..=repeats {
        let t0 = Instant::now();
        let model = crate::paper::plate_model()?;
        let read = t0.elapsed().as_secs_f64();
        let opts = RunOptions {
            steps: Some(steps),
            ..Default::default()
        };
        let direct_start = Instant::now();
        let run = run_model(&model, &opts)?;
        let direct_wall = direct_start.elapsed().as_secs_f64();
        let t1 = Instant::now();
        let dir = tempfile::tempdir().map_err(|source| StudyError::Io {
            path: "temporary directory".into(),
            source,
        })?;
        let out = dir.path().join("plate");
        crate::output::write_dir_atomically(&out, &crate::output::run_files(&model, &run)).map_err(|source| {
            StudyError::Io {
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
        let shear = run_model(&shear_model, &opts)?.stats;
        let panel = run_model(&panel_model, &opts)?;
        panel_solved = panel.summary.model.solved_dofs as u64;
        let panel = panel.stats;
        let conv = run_model(
            &model,
            &RunOptions {
                engine: Engine::Convolution,
                ..opts.clone()
            },
        )?;
        let modal_start = Instant::now();
        let modal = run_model(
            &model,
            &RunOptions {
                engine: Engine::Modal,
                ..opts
            },
        )?;
        let modal_wall = modal_start.elapsed().as_secs_f64();
        if modal_error.is_none() {
            let (duration, peak) = modal.summary.contact.relative_difference(&run.summary.contact);
            modal_error = Some((
                duration.unwrap_or(f64::NAN),
                peak,
                modal
                    .summary
                    .run
                    .modal
                    .clone()
                    .expect("a modal run reports its truncation"),
            ));
        }
        if rep > 0 {
            let stepping = (shear.total_time - shear.factor_time).as_secs_f64();
            ratios.push([
                total,
                solve,
                conv.stats.total_time.as_secs_f64(),
                stepping,
                total - factor,
                (panel.total_time - panel.factor_time).as_secs_f64(),
                direct_wall,
                modal_wall,
            ]);
            stages.push([read, assembly, factor, solve, total - factor - solve, write, wall]);
        }
    }
    Ok(PlateRepeats {
        stages,
        ratios,
        solved,
        modal: modal_error,
        panel_solved,
    })
}

/// The median of each stage over the repeats.
fn stage_table(stages: &[[f64; 7]]) -> String {
    let col = |j: usize| median(stages.iter().map(|r| r[j]).collect());
    let mut out = String::new();
    for (j, name) in STAGES.iter().enumerate() {
        out += &format!("  {name:<66} {:>9.4} s\n", col(j));
    }
    out
}

/// Ratios within each repeat (the machine's load cancels), then their median.
fn engine_ratios(ratios: &[[f64; 8]]) -> String {
    let ratio = |f: &dyn Fn(&[f64; 8]) -> f64| median(ratios.iter().map(f).collect());
    let mut out = String::from("ratios, each measured within one repeat (median):\n");
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
    out += &format!(
        "  {:<66} {:>9.3}\n",
        "shear plate (MITC4 cross-ply) / thin plate, per step (goal 1.5)",
        ratio(&|r| r[3] / r[4])
    );
    out
}

/// The convolution run with a cold then a warm kernel cache, against the direct run.
fn cache_ratios(model: &Model, steps: usize, cache: &Path, direct: f64) -> Result<String, StudyError> {
    let cached = RunOptions {
        steps: Some(steps),
        engine: Engine::Convolution,
        kernel_cache: Some(cache.join("kernels")),
        ..Default::default()
    };
    let cold = run_model(model, &cached)?.stats.total_time.as_secs_f64();
    let warm = run_model(model, &cached)?.stats.total_time.as_secs_f64();
    let mut out = format!(
        "  {:<66} {:>9.3}\n",
        "kernel pass (cold cache) / direct run",
        cold / direct
    );
    out += &format!(
        "  {:<66} {:>9.4}\n",
        "cached convolution run / direct run (goal 0.05)",
        warm / direct
    );
    Ok(out)
}

/// A 100-velocity sweep and a 100 × 100 velocity-mass grid, cold caches, on every
/// core, against the direct run.
fn sweep_ratios(model: &Model, steps: usize, cache_dir: &Path, direct: f64) -> Result<String, StudyError> {
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let sweep_of = |varies: &[&str], cache: &str, engine: Engine| -> Result<sweep::SweepOutcome, StudyError> {
        sweep::sweep(
            model,
            &RunOptions {
                steps: Some(steps),
                kernel_cache: Some(cache_dir.join(cache)),
                engine,
                ..Default::default()
            },
            &sweep::SweepOptions {
                varies: varies
                    .iter()
                    .map(|v| sweep::Vary::parse(v, &[]))
                    .collect::<Result<_, _>>()
                    .map_err(|e| StudyError::Input(e.to_string()))?,
                scheme: crate::integrate::Scheme::Newmark,
                jobs,
                shard: None,
                progress: None,
                checks: Default::default(),
            },
        )
    };
    let line = sweep_of(&["velocity=100:2000:100"], "line", Engine::Convolution)?;
    let modal = sweep_of(&["velocity=100:2000:100"], "modal", Engine::Modal)?;
    let mass = model.contact.as_ref().map_or(1.0, |c| c.impactor.mass);
    let grid = sweep_of(
        &[
            "velocity=100:2000:100",
            &format!("mass={}:{}:100", mass / 4.0, mass * 4.0),
        ],
        "grid",
        Engine::Convolution,
    )?;
    let mut out = String::new();
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
                "the same sweep's kernels from the modal engine, {} modal checks, {jobs} jobs / direct (goal 0.5)",
                modal.direct_checks
            ),
            modal.wall_s,
        ),
        (
            format!(
                "  its reduction ({} modes + {} residual vectors) and kernel pass / direct",
                modal.modal.as_ref().map_or(0, |t| t.modes),
                modal.modal.as_ref().map_or(0, |t| t.residual_vectors)
            ),
            modal.kernel_pass_s,
        ),
        (
            format!(
                "  its {} modal checks (on its reduction), summed / direct",
                modal.direct_checks
            ),
            modal.checks_s,
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

/// What each optional effect costs: wall time (median of 3 runs) of the scene as
/// configured, with the membrane DOFs solved, and without the ledger.
pub fn scene_costs(model: &crate::model::Model, opts: &RunOptions) -> Result<String, StudyError> {
    let time = |o: &RunOptions| -> Result<(f64, crate::run::Summary), StudyError> {
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
pub fn bench_size(sizes: &[usize], read_sizes: &[usize], steps: usize) -> Result<String, StudyError> {
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
        let solved = crate::run::prepare(&model, &opts)?.model;
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

/// What `impactlab check` costs on a production-sized deck: the plate wrapped onto a
/// cylinder (`mesh panel --n 499 --radius 100`: 250 000 grids and 249 001 CQUAD4, about
/// 500 000 lines) written to a temporary file, then read and checked `repeats` times
/// after a warm-up. Reports the median of each stage (the reader; the survey of the
/// structure and the rest of the check) and the largest peak resident memory of a
/// repeat (Linux `VmHWM`, reset before each), as a multiple of the deck's size.
pub fn bench_check(repeats: usize) -> Result<String, StudyError> {
    use std::time::Instant;
    let text = crate::mesh::panel_deck(499, 100.0, crate::mesh::Cells::Quad4)?;
    let io = |source| StudyError::Io {
        path: "a temporary deck".into(),
        source,
    };
    let dir = tempfile::tempdir().map_err(io)?;
    let path = dir.path().join("panel499.bdf");
    std::fs::write(&path, &text).map_err(io)?;
    let (bytes, lines) = (text.len(), text.lines().count());
    drop(text);
    let read = crate::deck::ReadOptions {
        structure: true,
        ..Default::default()
    };
    let (mut reads, mut checks, mut totals, mut peak) = (Vec::new(), Vec::new(), Vec::new(), 0u64);
    let mut elements = 0;
    for k in 0..=repeats {
        reset_peak_memory();
        let t0 = Instant::now();
        let deck = crate::deck::read_deck(&path, read).map_err(crate::model::LoadError::from)?;
        let t1 = Instant::now();
        let report = crate::model::check::check(&deck);
        drop(deck);
        let t2 = Instant::now();
        if !report.takes {
            return Err(StudyError::Input(format!(
                "check refuses the panel deck: {:?}",
                report.errors
            )));
        }
        elements = report.elements.values().sum::<usize>();
        if k > 0 {
            reads.push((t1 - t0).as_secs_f64());
            checks.push((t2 - t1).as_secs_f64());
            totals.push((t2 - t0).as_secs_f64());
            peak = peak.max(peak_memory().unwrap_or(0));
        }
    }
    let mib = |b: u64| b as f64 / (1u64 << 20) as f64;
    let mut out = format!(
        "check of the panel deck (mesh panel --n 499 --radius 100): {lines} lines, {:.1} MiB, {elements} elements; \
         median of {repeats} after a warm-up\n",
        mib(bytes as u64)
    );
    let _ = writeln!(out, "{:>24} {:>9}", "stage", "wall [s]");
    for (name, v) in [
        ("read", &reads),
        ("survey, check, deck freed", &checks),
        ("total (goal 2 s)", &totals),
    ] {
        let _ = writeln!(out, "{name:>24} {:>9.3}", median(v.clone()));
    }
    match peak {
        0 => out += "peak resident memory: not available on this system\n",
        p => {
            let _ = writeln!(
                out,
                "peak resident memory {:.0} MiB, {:.1}× the deck's size (goal 10×)",
                mib(p),
                p as f64 / bytes as f64
            );
        }
    }
    Ok(out)
}

/// `impactlab bench --modes`: the cost of the Lanczos extraction
/// ([`crate::eigen::lanczos`]) as the model grows: the paper's plate, its structure
/// alone (`mesh::plate_structure_deck`), on the 49×49, 99×99 and 199×199 meshes, its
/// `roots` lowest roots (`check --modes`' extraction), once each. Reports the DOFs,
/// the structure's build and assembly, the factorisation, the solves, the rest of the
/// extraction (re-orthogonalisation, tridiagonal eigenproblems, Ritz vectors), the
/// Lanczos vectors, and the extraction's time per root.
pub fn bench_modes(sizes: &[usize], roots: usize) -> Result<String, StudyError> {
    let mut out = format!(
        "normal modes of the paper's plate (its structure alone), the {roots} lowest roots by Lanczos; one run each\n"
    );
    let _ = writeln!(
        out,
        "{:>8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>7} {:>12}",
        "mesh", "DOFs", "build [s]", "factor [s]", "solves [s]", "rest [s]", "vectors", "per root [s]"
    );
    for &n in sizes {
        let text = crate::mesh::plate_structure_deck(n)?;
        let deck = crate::deck::parse_deck_str(&format!("plate{n}"), &text, Default::default())
            .map_err(crate::model::LoadError::from)?;
        let (s, _) = crate::run::modes::lowest(&deck, roots).map_err(|e| StudyError::Input(e.to_string()))?;
        let t = s.timing;
        let secs = |d: std::time::Duration| d.as_secs_f64();
        let rest = secs(t.lanczos) - secs(t.factor) - secs(t.solves);
        let _ = writeln!(
            out,
            "{:>8} {:>8} {:>10.3} {:>10.3} {:>10.3} {:>10.3} {:>7} {:>12.4}",
            format!("{n}×{n}"),
            s.dofs,
            secs(t.build),
            secs(t.factor),
            secs(t.solves),
            rest,
            s.lanczos_steps,
            secs(t.lanczos) / s.modes.len().max(1) as f64
        );
    }
    Ok(out)
}
