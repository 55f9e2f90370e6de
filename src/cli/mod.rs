//! One function per subcommand: read the arguments, call the library, print, write
//! files, and return the exit code (0 success, 1 verification failed); errors map to
//! theirs in `main`. Progress bars are made here.

pub mod error;

use crate::{
    AuditArgs, AuditFormat, BenchArgs, CheckArgs, CollectArgs, CompareArgs, MeshKind, ReportArgs, RunArgs, SceneArgs,
    StudyKind, SweepArgs, VerifyArgs,
};
use error::Error;
use impactlab::run::{Engine, RunOptions};
use impactlab::{deck, output, verify};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

// Printing never panics: a closed pipe (`impactlab ... | head`) just ends the output.
fn say(s: &str) {
    let _ = write!(std::io::stdout(), "{s}");
}
fn sayln(s: &str) {
    let _ = writeln!(std::io::stdout(), "{s}");
}
/// A line on standard error.
pub fn say_err(s: &str) {
    let _ = writeln!(std::io::stderr(), "{s}");
}

/// The output directory the running command is about to write, named by the
/// interrupt message.
static DESTINATION: Mutex<Option<PathBuf>> = Mutex::new(None);

fn set_destination(dir: Option<&Path>) {
    *DESTINATION.lock().unwrap_or_else(|e| e.into_inner()) = dir.map(Path::to_path_buf);
}

/// SIGINT, SIGTERM and SIGHUP end the command, with exit code 128 + the signal's
/// number, only between output writes ([`output::stop_writes`]): a file being written
/// is finished first, none is started after, so every output path holds its previous
/// contents or complete new ones. SIGXFSZ (a file-size limit reached) is caught so
/// that the write fails with an error naming its path instead of killing the process.
pub fn handle_signals() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGXFSZ};
    let _ = signal_hook::flag::register(SIGXFSZ, std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)));
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(sig) = signals.forever().next() {
            let _stopped = output::stop_writes();
            let name = signal_hook::low_level::signal_name(sig).unwrap_or("a signal");
            let dest = DESTINATION.lock().unwrap_or_else(|e| e.into_inner()).clone();
            say_err(&match dest {
                Some(d) => format!(
                    "interrupted by {name}: {} was not written and holds what it held before",
                    d.display()
                ),
                None => format!("interrupted by {name}; no output was left half-written"),
            });
            std::process::exit(128 + sig);
        }
    });
}

/// A progress bar on standard error when it is a terminal.
fn progress(message: String) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let b = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    b.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {pos}/{len} steps ({eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    b.set_message(message);
    Some(b)
}

/// How long a run must look to take before its estimate is printed.
const ANNOUNCE_AFTER: std::time::Duration = std::time::Duration::from_secs(10);

/// Watches a run's progress bar from its own thread: once a second of stepping has
/// passed, prints the estimate of the whole run (time and memory) if it exceeds
/// [`ANNOUNCE_AFTER`]; with `log_every`, also a line at that interval (for standard
/// error that is not a terminal, where no bar is drawn), before the first step the
/// bar's message (the modal engine's reduction says itself there). Ends when the bar
/// finishes.
/// The bar counts the run's `steps`, or twice as many for the convolution engine
/// (its kernel pass, then the run): time is projected from the fraction done.
fn watch_run(
    bar: ProgressBar,
    steps: usize,
    memory: u64,
    log_every: Option<std::time::Duration>,
) -> std::thread::JoinHandle<()> {
    use std::time::{Duration, Instant};
    std::thread::spawn(move || {
        let (mut announced, mut logged) = (false, Instant::now());
        while !bar.is_finished() {
            std::thread::sleep(Duration::from_millis(100));
            let (done, len) = (bar.position(), bar.length().unwrap_or(0));
            if done == 0 || len == 0 {
                // Before the first step (a modal reduction): what the bar says.
                if log_every.is_some_and(|every| logged.elapsed() >= every) {
                    logged = Instant::now();
                    say_err(&format!(
                        "progress: {}, {:.0} s elapsed",
                        bar.message(),
                        bar.elapsed().as_secs_f64()
                    ));
                }
                continue;
            }
            let elapsed = bar.elapsed();
            let left = elapsed.mul_f64((len - done.min(len)) as f64 / done as f64);
            if !announced && elapsed >= Duration::from_secs(1) {
                announced = true;
                if elapsed + left > ANNOUNCE_AFTER {
                    bar.suspend(|| {
                        say_err(&format!(
                            "estimate: about {:.0} s for {steps} steps ({:.0} % done in {:.1} s), memory about {:.2} GiB",
                            (elapsed + left).as_secs_f64(),
                            100.0 * done as f64 / len as f64,
                            elapsed.as_secs_f64(),
                            memory as f64 / (1u64 << 30) as f64
                        ))
                    });
                }
            }
            if log_every.is_some_and(|every| logged.elapsed() >= every) {
                logged = Instant::now();
                say_err(&format!(
                    "progress: {:.0} % of {steps} steps, {:.0} s elapsed, about {:.0} s left",
                    100.0 * done as f64 / len as f64,
                    elapsed.as_secs_f64(),
                    left.as_secs_f64()
                ));
            }
        }
    })
}

/// The kernel cache directory of `--cache`/`--no-cache`: the given one, else
/// `$XDG_CACHE_HOME/impactlab`, else `~/.cache/impactlab`.
fn kernel_cache(dir: Option<PathBuf>, off: bool) -> Option<PathBuf> {
    if off {
        return None;
    }
    dir.or_else(|| {
        let env = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty()).map(PathBuf::from);
        env("XDG_CACHE_HOME")
            .or_else(|| env("HOME").map(|h| h.join(".cache")))
            .map(|c| c.join("impactlab"))
    })
}

/// Says where the kernels came from when the cache could not be used.
fn report_cache(c: &Option<impactlab::run::convolution::CacheUse>) {
    use impactlab::run::convolution::CacheUse;
    match c {
        Some(CacheUse::Recomputed(why)) => {
            say_err(&format!("warning: kernel cache: {why}; recomputed and stored again"))
        }
        Some(CacheUse::NotStored(why)) => say_err(&format!("warning: kernel cache: {why}; computed, not stored")),
        _ => {}
    }
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |source| Error::Io {
        path: path.display().to_string(),
        source,
    }
}

/// `impactlab run`: a deck or a scene, its outputs, its printed summary.
pub fn run(a: RunArgs) -> Result<u8, Error> {
    if let Some(dt) = a.dt {
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(Error::Usage(format!("--dt must be a positive number, not {dt}")));
        }
    }
    if a.steps == Some(0) {
        return Err(Error::Usage("--steps must be positive".into()));
    }
    modes_up_to(a.modes_up_to, a.engine)?;
    let is_scene = a.deck.extension().is_some_and(|e| e == "toml");
    let (model, opts, scene) = if is_scene {
        if a.all_dofs || a.allow_unknown {
            return Err(Error::Usage(format!(
                "{}: --all-dofs and --allow-unknown apply to decks; a scene generates a deck with \
                 no unknown cards and says itself which DOFs to solve (effects.membrane = true)",
                a.deck.display()
            )));
        }
        let (s, model, _) = impactlab::scene::load(&a.deck)?;
        let mut o = RunOptions::for_scene(&s);
        o.scheme = a.scheme.unwrap_or(s.run.scheme);
        (model, o, Some(s))
    } else {
        let read = deck::ReadOptions {
            allow_unknown: a.allow_unknown,
            ..Default::default()
        };
        let d = deck::read_deck(&a.deck, read).map_err(impactlab::model::LoadError::from)?;
        if d.executive.sol == Some(deck::STATICS) {
            return run_static(&a, &d);
        }
        if d.executive.sol == Some(deck::MODES) {
            return run_modes(&a, &d);
        }
        let (model, mut warnings) = impactlab::model::build_model(&d).map_err(impactlab::model::LoadError::from)?;
        let mut all = d.warnings;
        all.append(&mut warnings);
        for w in &all {
            say_err(&w.to_string());
        }
        let o = RunOptions {
            scheme: a.scheme.unwrap_or_default(),
            skip_inert: !a.all_dofs,
            ..Default::default()
        };
        (model, o, None)
    };
    let mut opts = RunOptions {
        dt: a.dt.or(opts.dt),
        steps: a.steps.or(opts.steps),
        max_energy_error: a.max_energy_error.0,
        max_memory: Some((a.max_memory.max(0.0) * (1u64 << 30) as f64) as u64),
        progress: Some({
            // Not drawn off a terminal, but its message is what `--progress` logs there.
            let label = format!("{} {}", model.name, opts.scheme);
            progress(label.clone()).unwrap_or_else(|| ProgressBar::hidden().with_message(label))
        }),
        engine: a.engine,
        modal: impactlab::run::modal::ModalParams {
            cutoff: a.modes_up_to,
            ..Default::default()
        },
        kernel_cache: kernel_cache(a.cache, a.no_cache),
        interlaminar_toughness: interlaminar_toughness(a.giic, &model)?,
        ..opts
    };
    if a.fields.is_some() {
        opts.snapshot_times = impactlab::report::fields::field_times(
            opts.dt.unwrap_or(model.time.dt),
            opts.steps.unwrap_or(model.time.steps),
            a.field_count,
        );
    }
    let dir = a.out.unwrap_or_else(|| PathBuf::from("out").join(&model.name));
    set_destination(Some(&dir));
    let steps = opts.steps.unwrap_or(model.time.steps);
    let watcher = opts.progress.clone().map(|bar| {
        let log = (a.progress && !std::io::stderr().is_terminal()).then(|| std::time::Duration::from_secs(10));
        watch_run(
            bar,
            steps,
            impactlab::run::memory_estimate(&model, steps, opts.engine),
            log,
        )
    });
    let result = impactlab::run::run_model(&model, &opts);
    if let Some(bar) = &opts.progress {
        bar.finish_and_clear();
    }
    if let Some(w) = watcher {
        let _ = w.join();
    }
    let (mut r, failure) = match result {
        Ok(r) => (r, None),
        Err(impactlab::run::RunError::EnergyGuard { trip, partial }) => (*partial, Some(trip)),
        Err(e) => return Err(e.into()),
    };
    if let Some(s) = &scene {
        let m = &r.summary;
        r.summary.effects = Some(impactlab::scene::effects(
            s,
            m.model.inert_dofs_skipped,
            m.run.steps_done,
        ));
        r.summary.contact_stiffness_source = impactlab::scene::contact_stiffness(s).map(|k| k.1).ok();
    }
    report_cache(&r.summary.run.kernel_cache);
    output::write_dir_atomically(&dir, &output::run_files(&model, &r)).map_err(io_error(&dir))?;
    set_destination(a.fields.as_deref());
    say(&output::human_summary(&model, &r));
    sayln(&format!("  outputs:  {}", dir.display()));
    if let Some(trip) = failure {
        return Err(Error::Stopped(format!(
            "{trip}; the outputs up to there are in {} (summary.json: run.complete = false)",
            dir.display()
        )));
    }
    if let Some(fdir) = a.fields {
        let files = impactlab::report::fields::write_fields(&model, &r, &fdir)?;
        sayln(&format!(
            "  fields:   {} VTU files and fields.pvd in {}",
            files.len() - 1,
            fdir.display()
        ));
    }
    Ok(0)
}

/// `impactlab run` on a linear static deck (SOL 101): K u = f, its displacements and
/// summary written to the output directory.
fn run_static(a: &RunArgs, d: &deck::Deck) -> Result<u8, Error> {
    run_solution(a, d, "a linear static one (SOL 101)", |d| {
        let (solutions, warnings) = impactlab::run::statics::solve_subcases(d)?;
        let text: String = solutions.iter().map(output::static_summary).collect();
        Ok((output::static_files(&solutions), text, warnings))
    })
}

/// `impactlab run` on a normal modes deck (SOL 3, 103).
fn run_modes(a: &RunArgs, d: &deck::Deck) -> Result<u8, Error> {
    run_solution(a, d, "a normal modes one (SOL 103)", |d| {
        let (solution, warnings) = impactlab::run::modes::solve(d)?;
        Ok((
            output::modal_files(&solution),
            output::modal_summary(&solution),
            warnings,
        ))
    })
}

/// The files a solution writes, what it says, and its warnings.
type Solved = (Vec<(&'static str, Vec<u8>)>, String, Vec<deck::Diagnostic>);

/// A deck of `kind` solved rather than integrated: the transient flags refused, the
/// warnings said, the files written to the output directory in one step.
fn run_solution(
    a: &RunArgs,
    d: &deck::Deck,
    kind: &str,
    solve: impl FnOnce(&deck::Deck) -> Result<Solved, Error>,
) -> Result<u8, Error> {
    refuse_transient_flags(a, kind)?;
    for w in &d.warnings {
        say_err(&w.to_string());
    }
    let (files, text, warnings) = solve(d)?;
    for w in &warnings {
        say_err(&w.to_string());
    }
    let dir = a.out.clone().unwrap_or_else(|| PathBuf::from("out").join(&d.name));
    output::write_dir_atomically(&dir, &files).map_err(io_error(&dir))?;
    say(&text);
    sayln(&format!("  outputs:  {}", dir.display()));
    Ok(0)
}

/// A run's flags that apply only to a transient deck, refused on a deck of `kind`.
fn refuse_transient_flags(a: &RunArgs, kind: &str) -> Result<(), Error> {
    let transient = [
        (a.scheme.is_some(), "--scheme"),
        (a.dt.is_some(), "--dt"),
        (a.steps.is_some(), "--steps"),
        (a.giic.is_some(), "--giic"),
        (a.fields.is_some(), "--fields"),
        (a.all_dofs, "--all-dofs"),
        (!a.engine.is_direct(), "--engine"),
        (a.modes_up_to.is_some(), "--modes-up-to"),
    ];
    match transient.iter().find(|t| t.0) {
        Some((_, flag)) => Err(Error::Usage(format!(
            "{}: {flag} applies to a transient run; this deck is {kind}",
            a.deck.display()
        ))),
        None => Ok(()),
    }
}

/// The model a sweep or a threshold search varies: a deck's (its warnings printed),
/// or a scene's, whose contact law a deck may not be able to express.
fn sweep_model(path: &Path) -> Result<impactlab::model::Model, Error> {
    if path.extension().is_some_and(|e| e == "toml") {
        return Ok(impactlab::scene::load(path)?.1);
    }
    let (model, warnings) = impactlab::load_deck(path, Default::default())?;
    for w in &warnings {
        say_err(&w.to_string());
    }
    Ok(model)
}

/// A sweep's (or a threshold search's) `--modes-up-to` and `--cache` against its
/// engine.
fn engine_arguments(a: &SweepArgs) -> Result<(), Error> {
    modes_up_to(a.modes_up_to, a.engine)?;
    if a.engine == Engine::Modal && a.cache.is_some() {
        return Err(Error::Usage(
            "--cache: a modal sweep's kernels come with its reduction, computed afresh and not cached".into(),
        ));
    }
    Ok(())
}

/// `impactlab sweep --find velocity --until …`: the threshold impact speed and energy,
/// printed and written to OUT/threshold.json.
fn threshold(a: SweepArgs) -> Result<u8, Error> {
    use impactlab::study::threshold::{find_velocity, Until, BRACKET_WIDTH};
    engine_arguments(&a)?;
    let until = Until::parse(a.until.as_deref().unwrap_or_default())?;
    let model = sweep_model(&a.deck)?;
    let run = RunOptions {
        scheme: a.scheme,
        dt: a.dt,
        steps: a.steps,
        kernel_cache: kernel_cache(a.cache, a.no_cache),
        interlaminar_toughness: interlaminar_toughness(a.giic, &model)?,
        engine: a.engine,
        modal: impactlab::run::modal::ModalParams {
            cutoff: a.modes_up_to,
            ..Default::default()
        },
        ..Default::default()
    };
    let bar = progress(format!("{} threshold", model.name)).unwrap_or_else(ProgressBar::hidden);
    let t = find_velocity(&model, &run, until, &bar)?;
    bar.finish_and_clear();
    let units = impactlab::run::UnitSystem::of(&model.units);
    let joules = model.units.joules_per_energy_unit();
    let dir = a
        .out
        .unwrap_or_else(|| PathBuf::from("out").join(format!("{}-threshold", model.name)));
    let summary = serde_json::json!({
        "deck": model.name,
        "deck_sha256": model.deck_sha256,
        "units": units,
        "scheme": a.scheme,
        "dt": a.dt.unwrap_or(model.time.dt),
        "steps": a.steps.unwrap_or(model.time.steps),
        "until": t.target,
        "target_value": t.target_value,
        "g_iic": run.interlaminar_toughness,
        "impactor_mass": t.mass,
        "velocity": t.velocity,
        "velocity_bracket": t.bracket,
        "bracket_width": BRACKET_WIDTH,
        "energy": t.energy,
        "energy_joules": joules.map(|j| j * t.energy),
        "checked_on": t.checked_on.name(),
        "direct_values": t.direct_values,
        "direct_check": t.direct_check,
        "direct_check_max": impactlab::study::sweep::DIRECT_CHECK_MAX,
        "evaluations": t.evaluations,
        "search_engine": if t.direct_reason.is_some() { "direct" } else { "convolution" },
        "modes_up_to": a.modes_up_to,
        "direct_reason": t.direct_reason,
        "kernel_pass_s": t.times_s[0],
        "search_s": t.times_s[1],
        "direct_checks_s": t.times_s[2],
    });
    let json = (serde_json::to_string_pretty(&summary).expect("plain JSON") + "\n").into_bytes();
    output::write_dir_atomically(&dir, &[("threshold.json", json)]).map_err(io_error(&dir))?;
    let u = &model.units;
    sayln(&format!("{}: {}", model.name, t.target));
    sayln(&format!(
        "  threshold speed {:.7e} {}/{} (bracket {:.7e}..{:.7e}, {} runs on the {} engine{})",
        t.velocity,
        u.length,
        u.time,
        t.bracket[0],
        t.bracket[1],
        t.evaluations,
        if t.direct_reason.is_some() {
            "direct"
        } else {
            "convolution"
        },
        t.direct_reason.as_ref().map_or(String::new(), |why| format!(": {why}"))
    ));
    sayln(&format!(
        "  impact energy ½mv² = {:.6e} {}{}",
        t.energy,
        units.energy,
        joules.map_or(String::new(), |j| format!(" = {:.6e} J", j * t.energy))
    ));
    sayln(&format!(
        "  {} engine: {:.6e} below and {:.6e} at the threshold; engines agree to {:.1e} (max {:.0e})",
        t.checked_on.name(),
        t.direct_values[0],
        t.direct_values[1],
        t.direct_check,
        impactlab::study::sweep::DIRECT_CHECK_MAX
    ));
    sayln(&format!(
        "  {:.2} s: kernel pass {:.2} s, search {:.2} s, direct checks {:.2} s",
        t.times_s.iter().sum::<f64>(),
        t.times_s[0],
        t.times_s[1],
        t.times_s[2]
    ));
    sayln(&format!("  outputs:  {}", dir.join("threshold.json").display()));
    Ok(0)
}

/// `--giic`: a positive number, for a target that is a plate with bending stiffness.
fn interlaminar_toughness(giic: Option<f64>, model: &impactlab::model::Model) -> Result<Option<f64>, Error> {
    let Some(g) = giic else { return Ok(None) };
    if !(g > 0.0 && g.is_finite()) {
        return Err(Error::Usage(format!("--giic must be a positive number, not {g}")));
    }
    impactlab::physics::references::plate_bending_stiffness(model).map_err(|_| {
        Error::Usage(format!(
            "--giic: {} has no plate with bending stiffness (PSHELL MID2 or PCOMP) to delaminate",
            model.name
        ))
    })?;
    Ok(Some(g))
}

/// Checks `--modes-up-to`: the modal engine's cutoff, a positive frequency.
fn modes_up_to(cutoff: Option<f64>, engine: Engine) -> Result<(), Error> {
    let Some(f) = cutoff else { return Ok(()) };
    if engine != Engine::Modal {
        return Err(Error::Usage(
            "--modes-up-to is the modal engine's cutoff: add --engine modal".into(),
        ));
    }
    if !(f > 0.0 && f.is_finite()) {
        return Err(Error::Usage(format!(
            "--modes-up-to must be a positive frequency, not {f}"
        )));
    }
    Ok(())
}

/// `impactlab scene`: its K, its deck, what its effects cost.
pub fn scene(a: SceneArgs) -> Result<u8, Error> {
    let (s, model, deck) = impactlab::scene::load(&a.scene)?;
    let (k, how) = impactlab::scene::contact_stiffness(&s).map_err(|e| impactlab::scene::invalid(&a.scene, e))?;
    sayln(&format!("Hertz K = {k:.6e} ({how})"));
    if let Some(p) = a.to_deck {
        impactlab::scene::deck_twin(&s).map_err(|e| impactlab::scene::invalid(&a.scene, e))?;
        output::write_file_atomically(&p, deck.as_bytes()).map_err(io_error(&p))?;
        sayln(&format!("deck: {}", p.display()));
    }
    if a.costs {
        say(&impactlab::study::bench::scene_costs(
            &model,
            &RunOptions::for_scene(&s),
        )?);
    }
    Ok(0)
}

/// `impactlab check DECK`: the deck's structure, counted and weighed, and every card
/// impactlab does not take; exit 0 when it takes the deck, 2 when not.
pub fn check(a: CheckArgs) -> Result<u8, Error> {
    let read = deck::ReadOptions {
        structure: true,
        ..Default::default()
    };
    let d = deck::read_deck(&a.deck, read)?;
    let mut r = impactlab::model::check::check(&d);
    if let (Some(n), true) = (a.modes, r.takes) {
        match impactlab::run::modes::lowest(&d, n) {
            Ok((s, _)) => {
                r.warnings.extend(impactlab::run::modes::inaccurate_roots(&s.modes));
                r.lowest_frequencies = Some(s.modes.iter().map(|m| m.cycles).collect());
            }
            Err(e) => r.warnings.push(format!("the lowest frequencies were not found: {e}")),
        }
    }
    if a.json {
        say(&serde_json::to_string_pretty(&r).expect("the report serialises"));
    } else {
        say(&check_text(&r));
    }
    Ok(if r.takes { 0 } else { 2 })
}

/// The check report as text.
fn check_text(r: &impactlab::model::check::CheckReport) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let sol = r.solution.as_deref().map(|v| format!(" (SOL {v})")).unwrap_or_default();
    let _ = writeln!(s, "{}{sol}", r.deck);
    let _ = writeln!(s, "  grids           {}", r.grids);
    let kinds: Vec<String> = r.elements.iter().map(|(k, n)| format!("{k} {n}")).collect();
    let _ = writeln!(
        s,
        "  elements        {}",
        if kinds.is_empty() {
            "none".into()
        } else {
            kinds.join(", ")
        }
    );
    if !r.rigid.is_empty() {
        let kinds: Vec<String> = r.rigid.iter().map(|(k, n)| format!("{k} {n}")).collect();
        let _ = writeln!(s, "  rigid elements  {}", kinds.join(", "));
    }
    let _ = writeln!(
        s,
        "  DOFs            {} free, {} constrained{}; {} scalar points",
        r.free_dofs,
        r.constrained_dofs,
        if r.dependent_dofs > 0 {
            format!(", {} dependent", r.dependent_dofs)
        } else {
            String::new()
        },
        r.scalar_points
    );
    if let Some(w) = &r.weight {
        let _ = writeln!(
            s,
            "  mass            {:.6e} (x), {:.6e} (y), {:.6e} (z)",
            w.mass[0], w.mass[1], w.mass[2]
        );
        if let Some(c) = w.centre {
            let _ = writeln!(s, "  centre of mass  ({:.6e}, {:.6e}, {:.6e}) basic", c[0], c[1], c[2]);
        }
        for (i, row) in w.inertia.iter().enumerate() {
            let head = if i == 0 {
                "  inertia at cg  "
            } else {
                "                 "
            };
            let _ = writeln!(s, "{head} [{:.6e}, {:.6e}, {:.6e}]", row[0], row[1], row[2]);
        }
        let p = w.principal;
        let _ = writeln!(s, "  principal       {:.6e}, {:.6e}, {:.6e}", p[0], p[1], p[2]);
    }
    if let (Some(w), Some(m)) = (r.wtmass, r.scaled_mass) {
        let _ = writeln!(
            s,
            "  WTMASS {w:e}   the mass above is in the deck's input units; solutions use {:.6e} (x), {:.6e} (y), {:.6e} (z)",
            m[0], m[1], m[2]
        );
    }
    if let Some(f) = &r.lowest_frequencies {
        let f: Vec<String> = f.iter().map(|f| format!("{f:.6e}")).collect();
        let _ = writeln!(
            s,
            "  frequencies     {} (cycles per unit time, lowest first)",
            f.join(", ")
        );
    }
    for (what, n) in &r.readings {
        let _ = writeln!(s, "  read as         {what} ({n} card(s))");
    }
    if !r.not_written.is_empty() {
        let _ = writeln!(
            s,
            "  not written     {} (requested in case control)",
            r.not_written.join(", ")
        );
    }
    for c in &r.systems {
        let _ = writeln!(
            s,
            "  system {}        {} ({}): {} grids located in it, {} displaced in it",
            c.cid, c.card, c.kind, c.located, c.displaced
        );
    }
    for (what, list) in [("not supported", &r.unsupported), ("ignored", &r.ignored)] {
        for c in list {
            let _ = writeln!(
                s,
                "  {what:<15} {} ×{} (first at {}: {})",
                c.card,
                c.count,
                c.first_at,
                c.first_line.trim()
            );
        }
    }
    for w in &r.warnings {
        let _ = writeln!(s, "{w}");
    }
    for e in &r.errors {
        let _ = writeln!(s, "{e}");
    }
    let verdict = match (r.errors.is_empty(), r.unsupported.is_empty()) {
        (true, true) => "impactlab takes this deck".to_string(),
        (true, false) => format!(
            "impactlab does not take this deck: {} kind(s) of card that would change its structure are not supported",
            r.unsupported.len()
        ),
        (false, _) => format!("the structure does not build: {} error(s)", r.errors.len()),
    };
    let _ = writeln!(s, "{verdict}");
    s
}

/// `impactlab mesh plate|panel`: a generated deck.
pub fn mesh(what: MeshKind) -> Result<u8, Error> {
    let (text, out) = match what {
        MeshKind::Plate {
            n,
            cells,
            stiffeners: 0,
            out,
        } => (
            impactlab::mesh::plate_deck_with(n, impactlab::mesh::Edges::Clamped, cells)?,
            out,
        ),
        MeshKind::Plate {
            n,
            cells,
            stiffeners,
            out,
        } => (
            impactlab::mesh::stiffened_plate_deck(n, cells, &impactlab::mesh::Stiffeners::blade(stiffeners))?,
            out,
        ),
        MeshKind::Panel { n, radius, cells, out } => (impactlab::mesh::panel_deck(n, radius, cells)?, out),
    };
    match out {
        Some(p) => output::write_file_atomically(&p, text.as_bytes()).map_err(io_error(&p))?,
        None => say(&text),
    }
    Ok(0)
}

/// `impactlab study mesh|stability|accuracy`.
pub fn study(what: StudyKind) -> Result<u8, Error> {
    match what {
        StudyKind::HardCases { n } => {
            use impactlab::study::stability;
            let bar = progress(format!("hard cases, {n}x{n} plate"));
            let rows = stability::hard_cases(n, &|what| {
                if let Some(b) = &bar {
                    b.set_message(what.to_string());
                } else {
                    say_err(what);
                }
            })?;
            if let Some(b) = bar {
                b.finish_and_clear();
            }
            say(&stability::hard_cases_table(n, &rows));
            return Ok(if rows.iter().all(|r| r.passed()) { 0 } else { 1 });
        }
        StudyKind::Mesh { out, redraw: true, .. } => {
            impactlab::study::mesh::redraw(&out)?;
            sayln(&format!("redrawn from its CSVs: {}", out.display()));
        }
        StudyKind::Mesh { n, out, .. } => {
            use impactlab::study::mesh;
            let (rows, samples) = mesh::run(&n, &mesh::options(progress("plate mesh study".into())))?;
            mesh::write(&out, &rows, &samples)?;
            say(&String::from_utf8_lossy(&mesh::csv(&rows)));
            sayln(&format!("outputs: {}", out.display()));
        }
        StudyKind::Panel { out, redraw: true, .. } => {
            impactlab::study::panel::redraw(&out)?;
            sayln(&format!("redrawn from its CSVs: {}", out.display()));
        }
        StudyKind::Panel { n, out, .. } => {
            use impactlab::study::panel;
            let (rows, samples) = panel::run(&n, &panel::options(progress("panel study".into())))?;
            panel::write(&out, &rows, &samples)?;
            say(&String::from_utf8_lossy(&panel::csv(&rows)));
            sayln(&format!("outputs: {}", out.display()));
        }
        StudyKind::Stiffened { out, redraw: true, .. } => {
            impactlab::study::stiffened::redraw(&out)?;
            sayln(&format!("redrawn from its CSVs: {}", out.display()));
        }
        StudyKind::Stiffened { n, out, .. } => {
            use impactlab::study::stiffened;
            let (rows, samples, thresholds) =
                stiffened::run(&n, &stiffened::options(progress("stiffened plate study".into())))?;
            stiffened::write(&out, &rows, &samples, &thresholds)?;
            say(&String::from_utf8_lossy(&stiffened::csv(&rows)));
            say(&String::from_utf8_lossy(&stiffened::csv(&thresholds)));
            sayln(&format!("outputs: {}", out.display()));
        }
        StudyKind::Mutants { from, run, out } => {
            let from = from.as_deref().zip(run.as_deref());
            impactlab::study::mutants::write(&out, from)?;
            sayln(&format!("page: {}", out.join("README.md").display()));
        }
        StudyKind::Stability { out } => {
            use impactlab::study::stability;
            let model = impactlab::paper::rod_model()?;
            let (cells, check) = stability::run_map(&model, stability::DT0, 500e-6, &|s| say_err(&format!("  {s}")))?;
            sayln(&format!(
                "newmark and energy along the velocity axis on the convolution engine; each Δt's direct check \
                 within {check:.2e} of the energy error (max {:.0e})",
                stability::ENGINE_CHECK_MAX
            ));
            // The page and figure are made from the CSV as written, as the test remakes them.
            let csv = stability::csv(&cells);
            let cells = stability::read_csv(&csv).expect("the CSV just written reads back");
            let readme = stability::readme(&cells);
            output::write_dir_atomically(&out, &[("stability-map.csv", csv), ("README.md", readme.into_bytes())])
                .map_err(io_error(&out))?;
            stability::figure(&cells, &out.join("stability-map"))?;
            let failed = cells.iter().filter(|c| c.failed()).count();
            sayln(&format!(
                "{} runs, {} refused or failed; outputs: {}",
                cells.len(),
                failed,
                out.display()
            ));
        }
        StudyKind::Accuracy { out, redraw: true, .. } => {
            impactlab::study::accuracy::redraw(&out)?;
            sayln(&format!("redrawn from work-precision.csv: {}", out.display()));
        }
        StudyKind::Accuracy {
            out,
            repeats,
            plate_meshes,
            ..
        } => {
            let rows = impactlab::study::accuracy::run_study(&out, repeats.max(1), &plate_meshes, &|s| {
                say_err(&format!("  {s}"))
            })?;
            sayln(&format!("{} runs; outputs: {}", rows.len(), out.display()));
        }
    }
    Ok(0)
}

/// `impactlab verify`: every case run once and judged; table, verify.json, junit.xml;
/// exit 1 when a check fails or a case does not run.
pub fn verify(a: VerifyArgs) -> Result<u8, Error> {
    let cases = verify::load_cases(&a.cases)?;
    let mut outcomes = impactlab::study::cases::evaluate_all(&cases, a.jobs);
    if a.bless {
        for (_, o) in outcomes.iter_mut() {
            if let Ok(o) = o {
                for p in verify::bless(o)? {
                    sayln(&format!("wrote {}", p.display()));
                }
            }
        }
    }
    let v = verify::Verdicts::of(&outcomes);
    say(&verify::table(&v));
    let files = [("verify.json", verify::json(&v)), ("junit.xml", verify::junit(&v))];
    output::write_dir_atomically(&a.out, &files).map_err(io_error(&a.out))?;
    sayln(&format!("outputs: {}", a.out.display()));
    Ok(if v.passed() { 0 } else { 1 })
}

/// `impactlab report`: every case that runs a deck or a scene, run once, reported; an index.
pub fn report(a: ReportArgs) -> Result<u8, Error> {
    use impactlab::report;
    let cases: Vec<verify::Case> = verify::load_cases(&a.cases)?
        .into_iter()
        .filter(|c| c.reported())
        .collect();
    for (_, outcome) in impactlab::study::cases::evaluate_all(&cases, 2) {
        let outcome = outcome?;
        let r = report::report_case(&outcome, &a.out.join(&outcome.case.name))?;
        say(&r.human);
        sayln(&format!(
            "{}: {} checks passed, {} failed, {} figures",
            r.name,
            r.passed,
            r.failed,
            r.figures.len()
        ));
    }
    let index = a.out.join("README.md");
    let index_md = report::index(&a.out);
    output::write_file_atomically(&index, index_md.as_bytes()).map_err(io_error(&index))?;
    for (rel, html) in report::html_pages(&a.out, &index_md) {
        let p = a.out.join(rel);
        output::write_file_atomically(&p, html.as_bytes()).map_err(io_error(&p))?;
    }
    sayln(&format!("index: {} and index.html", index.display()));
    Ok(0)
}

/// `impactlab compare`: a static run against NASTRAN's printed displacements.
pub fn compare(a: CompareArgs) -> Result<u8, Error> {
    use impactlab::verify::printed::{compare, read_printed_file, read_run, render};
    if a.run.join("modes.csv").exists() {
        return compare_roots(&a);
    }
    if a.run.join("history.csv").exists() {
        return compare_histories(&a);
    }
    use impactlab::verify::element_tables::{
        compare_elements, read_element_tables_file, read_run_elements, render_elements,
    };
    let theirs = read_printed_file(&a.nastran)?;
    let ours = read_run(&a.run)?;
    let comparisons = compare(&ours, &theirs);
    if comparisons.is_empty() {
        return Err(Error::Usage(format!(
            "{} prints SUBCASE {:?} and {} holds {:?}: no SUBCASE in common",
            a.nastran.display(),
            theirs.subcases.keys().collect::<Vec<_>>(),
            a.run.display(),
            ours.subcases.keys().collect::<Vec<_>>()
        )));
    }
    say(&render(&comparisons, a.top));
    let mut worst = comparisons.iter().map(|c| c.worst()).fold(0.0, f64::max);
    let printed_elements = read_element_tables_file(&a.nastran)?;
    if !printed_elements.subcases.is_empty() {
        let run_elements = read_run_elements(&a.run)?;
        if run_elements.subcases.is_empty() {
            sayln(&format!(
                "element results: {} prints some and {} holds none (elements.csv: ask for them with STRESS or FORCE)",
                a.nastran.display(),
                a.run.display()
            ));
        } else {
            let c = compare_elements(&run_elements, &printed_elements);
            say(&render_elements(&c, a.top));
            worst = worst.max(c.worst());
        }
    }
    Ok(verdict(worst, a.tolerance))
}

/// Exit status 1 (said) when the largest difference exceeds the tolerance, 0 otherwise.
fn verdict(worst: f64, tolerance: Option<f64>) -> u8 {
    match tolerance {
        Some(t) if worst > t => {
            sayln(&format!("largest difference {worst:.2e} exceeds --tolerance {t:e}"));
            1
        }
        _ => 0,
    }
}

/// `impactlab compare` of a transient run: its displacement histories against the
/// printed SORT2 ones, time by time.
fn compare_histories(a: &CompareArgs) -> Result<u8, Error> {
    use impactlab::verify::printed::{compare_histories, read_run_histories, read_transient_file, render_histories};
    let theirs = read_transient_file(&a.nastran)?;
    let ours = read_run_histories(&a.run)?;
    let c = compare_histories(&ours, &theirs);
    if c.differences.is_empty() {
        return Err(Error::Usage(format!(
            "{} and {} have no displacement at a common time and DOF",
            a.nastran.display(),
            a.run.display()
        )));
    }
    say(&render_histories(&c, a.top));
    Ok(verdict(c.worst(), a.tolerance))
}

/// `impactlab compare` of a normal modes run: its roots against the printed REAL
/// EIGENVALUES table, rank by rank.
fn compare_roots(a: &CompareArgs) -> Result<u8, Error> {
    use impactlab::verify::printed::{compare_roots, read_eigenvalues_file, read_run_roots, render_roots};
    let theirs = read_eigenvalues_file(&a.nastran)?;
    let ours = read_run_roots(&a.run)?;
    let c = compare_roots(&ours, &theirs);
    say(&render_roots(&c, ours.len(), theirs.len()));
    let worst = c.iter().map(|r| r.relative).fold(0.0, f64::max);
    Ok(verdict(worst, a.tolerance))
}

/// `impactlab audit`: what moved between two runs; exit 1 when anything moved
/// beyond tolerance.
pub fn audit(a: AuditArgs) -> Result<u8, Error> {
    use impactlab::verify::audit::{audit, render, AuditTol, Format};
    let tol = AuditTol {
        rtol: a.rtol,
        atol: a.atol,
    };
    let report = audit(&a.baseline, &a.candidate, tol)?;
    let format = match a.format {
        AuditFormat::Text => Format::Text,
        AuditFormat::Json => Format::Json,
        AuditFormat::Markdown => Format::Markdown,
    };
    say(&render(&report, format));
    Ok(if report.passed { 0 } else { 1 })
}

/// `impactlab bench`: where the plate's time goes.
pub fn bench(a: BenchArgs) -> Result<u8, Error> {
    if a.size {
        say(&impactlab::study::bench::bench_size(
            &[49, 99, 199],
            &[177, 353, 705],
            a.steps,
        )?);
        return Ok(0);
    }
    if a.check {
        say(&impactlab::study::bench::bench_check(a.repeats.max(1))?);
        return Ok(0);
    }
    if a.modes {
        say(&impactlab::study::bench::bench_modes(&[49, 99, 199], 20)?);
        return Ok(0);
    }
    say(&impactlab::study::bench::bench_plate(a.repeats.max(1), a.steps)?);
    Ok(0)
}

/// `impactlab sweep`.
pub fn sweep(a: SweepArgs) -> Result<u8, Error> {
    use impactlab::study::sweep::{self, SweepOptions};
    if a.find.is_some() {
        return threshold(a);
    }
    let (varies, shard, checks) = sweep_arguments(&a)?;
    if checks.is_off() {
        say_err("warning: --checks 0: no point of this sweep is checked against the direct engine");
    }
    let model = sweep_model(&a.deck)?;
    let jobs = a
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let bar = progress(format!("{} sweep", model.name)).inspect(|b| {
        b.set_style(
            ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {pos}/{len} points ({eta})")
                .expect("valid template")
                .progress_chars("=> "),
        )
    });
    let run = RunOptions {
        dt: a.dt,
        steps: a.steps,
        kernel_cache: kernel_cache(a.cache.clone(), a.no_cache),
        engine: a.engine,
        modal: impactlab::run::modal::ModalParams {
            cutoff: a.modes_up_to,
            ..Default::default()
        },
        ..Default::default()
    };
    let opts = SweepOptions {
        varies,
        scheme: a.scheme,
        jobs,
        shard,
        progress: bar,
        checks,
    };
    let out = sweep::sweep(&model, &run, &opts)?;
    report_cache(&Some(out.kernel_cache.clone()));
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(format!("{}-sweep", model.name)));
    write_sweep(&a, &model, &opts, &out, &dir)?;
    Ok(if out.passed() { 0 } else { 1 })
}

/// A sweep's --vary (with --log), --shard (I of N) and self-check arguments.
type SweepArguments = (
    Vec<impactlab::study::sweep::Vary>,
    Option<(usize, usize)>,
    impactlab::study::sweep::SelfCheck,
);

/// Reads and checks a sweep's [`SweepArguments`].
fn sweep_arguments(a: &SweepArgs) -> Result<SweepArguments, Error> {
    use impactlab::study::sweep::{SelfCheck, Vary};
    let varies = a
        .vary
        .iter()
        .map(|v| Vary::parse(v, &a.log))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| Error::Usage(e.to_string()))?;
    if let Some(l) = a
        .log
        .iter()
        .find(|l| !varies.iter().any(|v| v.param.name() == l.as_str()))
    {
        return Err(Error::Usage(format!("--log {l}: not a varied parameter")));
    }
    let shard = a
        .shard
        .as_deref()
        .map(|s| {
            s.split_once('/')
                .and_then(|(i, n)| Some((i.parse::<usize>().ok()?, n.parse::<usize>().ok()?)))
                .filter(|&(i, n)| n >= 1 && (1..=n).contains(&i))
                .ok_or_else(|| Error::Usage(format!("--shard {s}: expected I/N with 1 ≤ I ≤ N")))
        })
        .transpose()?;
    let checks = SelfCheck {
        spread: a.checks,
        every: a.check_every.map(|n| n as usize),
    };
    engine_arguments(a)?;
    if a.checks == 0 && a.check_every.is_some() {
        return Err(Error::Usage(
            "--checks 0 turns the self-check off; --check-every needs it on".into(),
        ));
    }
    Ok((varies, shard, checks))
}

/// Writes a sweep's sweep.csv, summary.json and figures into `dir`, and prints what
/// it cost.
fn write_sweep(
    a: &SweepArgs,
    model: &impactlab::model::Model,
    opts: &impactlab::study::sweep::SweepOptions,
    out: &impactlab::study::sweep::SweepOutcome,
    dir: &Path,
) -> Result<(), Error> {
    use impactlab::study::sweep;
    let (varies, shard, checks, jobs) = (&opts.varies, opts.shard, opts.checks, opts.jobs);
    let points = sweep::points(varies).len();
    let units = impactlab::run::UnitSystem::of(&model.units);
    let mass = model.contact.as_ref().map_or(f64::NAN, |c| c.impactor.mass);
    let mut summary = serde_json::json!({
        "deck": model.name,
        "units": units,
        "impactor_mass": mass,
        "deck_sha256": model.deck_sha256,
        "scheme": a.scheme,
        "engine": "convolution",
        "dt": a.dt.unwrap_or(model.time.dt),
        "steps": a.steps.unwrap_or(model.time.steps),
        "varied": varies.iter().map(|v| serde_json::json!({"name": v.param.name(), "values": v.values})).collect::<Vec<_>>(),
        "points_total": points,
        "points": out.rows.len(),
        "shard": shard.map(|(i, n)| format!("{i}/{n}")),
        "self_check": {
            "off": checks.is_off(),
            "spread": checks.spread,
            "every": checks.every,
            "deck_point": sweep::deck_point(model, varies),
            "points": out.checked,
        },
        "direct_checks": out.direct_checks,
        "worst_direct_check": out.worst_direct_check,
        "direct_check_max": sweep::DIRECT_CHECK_MAX,
        "passed": out.passed(),
        "kernel_pass_s": out.kernel_pass_s,
        "kernel_cache": out.kernel_cache,
        "checks_s": out.checks_s,
        "points_s": out.points_s,
        "wall_s": out.wall_s,
    });
    // A modal sweep: its kernels' reduction, and the engine its checks ran on.
    if let Some(t) = &out.modal {
        summary["kernels"] = "modal".into();
        summary["check_engine"] = "modal".into();
        summary["modal"] = serde_json::to_value(t).expect("plain data");
    }
    let files = [
        ("sweep.csv", sweep::csv_bytes(&out.header, &out.rows)),
        (
            "summary.json",
            (serde_json::to_string_pretty(&summary).expect("plain JSON") + "\n").into_bytes(),
        ),
    ];
    output::write_dir_atomically(dir, &files).map_err(io_error(dir))?;
    let cx = sweep::FigureContext {
        deck: model.name.clone(),
        mass,
        units,
        modal: out.modal.is_some(),
    };
    let figures = sweep::figures(&out.header, &out.rows, &cx, dir)?;
    let checks = if out.modal.is_some() { "modal" } else { "direct" };
    sayln(&format!(
        "{}: {} of {points} points ({} jobs) in {:.2} s: kernel pass {:.2} s, {checks} checks {:.2} s, points {:.2} s (each summed over its tasks); {} {checks} checks, worst {:.2e} (max {:.0e})",
        model.name,
        out.rows.len(),
        jobs,
        out.wall_s,
        out.kernel_pass_s,
        out.checks_s,
        out.points_s,
        out.direct_checks,
        out.worst_direct_check,
        sweep::DIRECT_CHECK_MAX
    ));
    if let Some(t) = &out.modal {
        sayln(&format!(
            "  kernels:  the modal reduction, {} modes up to {:.4e} ({}) and {} residual vectors, in {:.2} s; \
             contact flexibility captured {:.6}",
            t.modes, t.cutoff_frequency, t.cutoff_from, t.residual_vectors, t.reduction_s, t.flexibility_reduced
        ));
    }
    sayln(&format!(
        "  outputs:  {} (sweep.csv, summary.json, {} figures)",
        dir.display(),
        figures.len() / 2
    ));
    Ok(())
}

/// `impactlab collect`.
pub fn collect(a: CollectArgs) -> Result<u8, Error> {
    use impactlab::study::sweep;
    let mut parts = Vec::new();
    let mut total = None;
    let mut summaries = Vec::new();
    for d in &a.dirs {
        parts.push(sweep::read_csv(&d.join("sweep.csv"))?);
        let path = d.join("summary.json");
        let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
            path: path.display().to_string(),
            source,
        })?;
        let s: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| Error::Usage(format!("{}: {e}", path.display())))?;
        let n = s["points_total"].as_u64().map(|n| n as usize);
        if total.is_some() && n != total {
            return Err(Error::Usage(format!(
                "{}: another sweep (points_total differs)",
                d.display()
            )));
        }
        if summaries
            .first()
            .is_some_and(|f: &serde_json::Value| f["kernels"] != s["kernels"])
        {
            return Err(Error::Usage(format!(
                "{}: another sweep (its kernels come from another engine)",
                d.display()
            )));
        }
        total = n;
        summaries.push(s);
    }
    let (header, rows) = sweep::collect(&parts, total).map_err(Error::Usage)?;
    let (checked, worst) = sweep::direct_checks(&rows);
    let mut summary = summaries[0].clone();
    summary["shard"] = serde_json::Value::Null;
    summary["points"] = rows.len().into();
    summary["direct_checks"] = checked.into();
    summary["worst_direct_check"] = worst.into();
    summary["passed"] = (worst <= sweep::DIRECT_CHECK_MAX).into();
    summary["collected_from"] = a
        .dirs
        .iter()
        .map(|d| d.display().to_string())
        .collect::<Vec<_>>()
        .into();
    summary["self_check"]["points"] = rows
        .iter()
        .filter(|r| r.last().is_some_and(|c| !c.is_nan()))
        .map(|r| r[0] as u64)
        .collect::<Vec<_>>()
        .into();
    for key in ["kernel_pass_s", "checks_s", "points_s", "wall_s"] {
        summary[key] = summaries.iter().filter_map(|s| s[key].as_f64()).sum::<f64>().into();
    }
    let files = [
        ("sweep.csv", sweep::csv_bytes(&header, &rows)),
        (
            "summary.json",
            (serde_json::to_string_pretty(&summary).expect("plain JSON") + "\n").into_bytes(),
        ),
    ];
    output::write_dir_atomically(&a.out, &files).map_err(io_error(&a.out))?;
    let cx = sweep::FigureContext {
        deck: summary["deck"].as_str().unwrap_or("").to_string(),
        mass: summary["impactor_mass"].as_f64().unwrap_or(f64::NAN),
        units: serde_json::from_value(summary["units"].clone()).unwrap_or_default(),
        modal: summary["kernels"] == "modal",
    };
    sweep::figures(&header, &rows, &cx, &a.out)?;
    sayln(&format!(
        "{} points from {} shards: {}",
        rows.len(),
        a.dirs.len(),
        a.out.display()
    ));
    Ok(if worst <= sweep::DIRECT_CHECK_MAX { 0 } else { 1 })
}
