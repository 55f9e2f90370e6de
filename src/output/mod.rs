//! Writing a run's files: `history.csv`, `energy.csv`, `summary.json`.
//!
//! A run's outputs are staged in a fresh directory beside the target and exchanged
//! with it in one rename (`renameat2(RENAME_EXCHANGE)`), so that an interrupted,
//! failed or concurrent run leaves either the previous complete outputs or one run's
//! complete new outputs, never a mix, a half-written file or a missing directory.
//! Every write holds a shared lock: [`stop_writes`] waits for the writes in
//! progress and lets no new one start, which is how an interrupted command ends.

use crate::ledger;
use crate::model::Model;
use crate::run::RunResult;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::{RwLock, RwLockWriteGuard};

/// Held shared by every write of this module, taken exclusively by [`stop_writes`].
static WRITES: RwLock<()> = RwLock::new(());

/// Waits until no output is being written and keeps it so: no write starts while
/// the guard lives. An interrupted command takes it, then exits.
pub fn stop_writes() -> RwLockWriteGuard<'static, ()> {
    WRITES.write().unwrap_or_else(|e| e.into_inner())
}

/// The directory `path` sits in (`.` for a bare name), created if missing.
fn parent_of(path: &Path) -> io::Result<PathBuf> {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    fs::create_dir_all(&parent)?;
    Ok(parent)
}

/// Writes named files into `dir` all at once (stage beside it, then exchange).
///
/// An existing `dir` is replaced only when it holds nothing but regular files (an
/// earlier output directory), so that `--out .` or `--out ~` is an error instead of
/// a deleted directory tree.
pub fn write_dir_atomically(dir: &Path, files: &[(&str, Vec<u8>)]) -> io::Result<()> {
    let _writing = WRITES.read().unwrap_or_else(|e| e.into_inner());
    check_replaceable(dir)?;
    let parent = parent_of(dir)?;
    let name = dir
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let stage = tempfile::Builder::new()
        .prefix(&format!(".{name}.staging-"))
        .tempdir_in(&parent)?;
    for (file, bytes) in files {
        let mut f = fs::File::create(stage.path().join(file))?;
        f.write_all(bytes)?;
        f.sync_all()?;
    }
    set_mode(stage.path(), 0o755)?;
    if swap_in(stage.path(), dir)? {
        // The stage now holds the previous outputs; dropping it removes them.
        drop(stage);
    } else {
        let _ = stage.keep();
    }
    sync_dir(&parent)
}

/// Refuses to replace anything but a directory of regular files.
fn check_replaceable(dir: &Path) -> io::Result<()> {
    let Ok(meta) = fs::symlink_metadata(dir) else {
        return Ok(());
    };
    let refuse = |why: String| {
        Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            format!("{why}; refusing to replace it (choose another output directory or remove it)"),
        ))
    };
    if !meta.is_dir() {
        return refuse("it exists and is not a directory".into());
    }
    for entry in fs::read_dir(dir)? {
        let entry = entry?;
        if !entry.file_type()?.is_file() {
            return refuse(format!(
                "it holds '{}', which is not a regular file, so it is not an output directory",
                entry.file_name().to_string_lossy()
            ));
        }
    }
    Ok(())
}

/// Puts the staged directory at `dir`: renamed there if `dir` does not exist, else
/// exchanged with it in one step. True when `staged` now holds the previous `dir`.
fn swap_in(staged: &Path, dir: &Path) -> io::Result<bool> {
    use rustix::fs::{renameat_with, RenameFlags, CWD};
    use rustix::io::Errno;
    loop {
        match renameat_with(CWD, staged, CWD, dir, RenameFlags::NOREPLACE) {
            Ok(()) => return Ok(false),
            Err(Errno::EXIST) => {}
            Err(e) => return Err(e.into()),
        }
        match renameat_with(CWD, staged, CWD, dir, RenameFlags::EXCHANGE) {
            Ok(()) => return Ok(true),
            // Removed by someone else between the two calls: try again.
            Err(Errno::NOENT) => {}
            Err(e) => return Err(e.into()),
        }
    }
}

/// Makes a rename in `dir` durable.
fn sync_dir(dir: &Path) -> io::Result<()> {
    fs::File::open(dir)?.sync_all()
}

/// Writes one file atomically (temporary file in the same directory, then rename).
pub fn write_file_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let _writing = WRITES.read().unwrap_or_else(|e| e.into_inner());
    let parent = parent_of(path)?;
    let mut tmp = tempfile::NamedTempFile::new_in(&parent)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    set_mode(tmp.path(), 0o644)?;
    tmp.persist(path).map_err(|e| e.error)?;
    sync_dir(&parent)
}

/// Temporary files and directories are private (0600/0700); outputs are not.
fn set_mode(path: &Path, mode: u32) -> io::Result<()> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        fs::set_permissions(path, fs::Permissions::from_mode(mode))?;
    }
    #[cfg(not(unix))]
    let _ = (path, mode);
    Ok(())
}

/// A CSV of numbers: the header, then each row, every float in the shortest form that reads back to the same f64.
pub fn csv_bytes(header: &[String], rows: impl Iterator<Item = Vec<f64>>) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header).expect("writing to memory");
    for r in rows {
        // `{:e}` is the shortest form that reads back to the same f64.
        w.write_record(r.iter().map(|v| format!("{v:e}")))
            .expect("writing to memory");
    }
    w.into_inner().expect("writing to memory")
}

/// Column names of `energy.csv` with units.
pub fn energy_columns(m: &Model) -> Vec<String> {
    let u = &m.units;
    let e = format!("{}*{}", u.force, u.length);
    ledger::columns(ledger::Dissipations::of(m))
        .iter()
        .map(|c| match *c {
            "time" => format!("time [{}]", u.time),
            "error" | "energy_ratio" => format!("{c} [-]"),
            "momentum" => format!("momentum [{}*{}]", u.force, u.time),
            other => format!("{other} [{e}]"),
        })
        .collect()
}

/// The three output files of a run.
pub fn run_files(model: &Model, run: &RunResult) -> Vec<(&'static str, Vec<u8>)> {
    let history = csv_bytes(&run.history_header(), run.history.iter().cloned());
    let booked = ledger::Dissipations::of(model);
    let energy = csv_bytes(&energy_columns(model), run.energy.iter().map(|r| r.values(booked)));
    let mut summary = serde_json::to_vec_pretty(&run.summary).expect("json of plain values");
    summary.push(b'\n');
    vec![
        ("history.csv", history),
        ("energy.csv", energy),
        ("summary.json", summary),
    ]
}

/// A short human summary of a run. Every value carries the deck's unit; times of the
/// order of a contact are printed in µs when the deck's time unit is the second.
pub fn human_summary(model: &Model, run: &RunResult) -> String {
    let s = &run.summary;
    let u = &model.units;
    let (scale, tu) = u.short_time();
    let num = |v: Option<f64>| v.map(|x| format!("{x:.4e}")).unwrap_or_else(|| "-".into());
    let time = |v: Option<f64>| {
        v.map(|x| match u.in_seconds() {
            true => format!("{:.2} {tu}", x * scale),
            false => format!("{x:.4e} {tu}"),
        })
        .unwrap_or_else(|| "-".into())
    };
    let tcl = |v: Option<f64>| v.map(|x| format!("{x:.4}")).unwrap_or_else(|| "-".into());
    let velocity = format!("{}/{}", u.length, u.time);
    let mut out = String::new();
    out += &format!(
        "{}: {} DOF ({} solved), scheme {}, dt {:e} {}, {} steps, {:.3} s wall\n",
        model.name,
        s.model.active_dofs,
        s.model.solved_dofs,
        run.scheme.name(),
        run.dt,
        u.time,
        run.stats.steps,
        run.stats.total_time.as_secs_f64()
    );
    let intervals: Vec<String> = s
        .contact
        .intervals
        .iter()
        .map(|i| format!("{}..{}", time(Some(i[0])), time(Some(i[1]))))
        .collect();
    if let Some(ex) = &model.excitation {
        out += &format!(
            "  load:     {}, work {} {}\n",
            ex.source,
            num(run.energy.last().map(|r| r.external_work)),
            s.units.energy
        );
    }
    // Without a contact there is no impactor to summarise.
    if model.contact.is_none() {
        out += "  contact:  none (no NOLIN3)\n";
    } else {
        out += &format!(
            "  contact:  {}\n",
            if intervals.is_empty() {
                "none".into()
            } else {
                intervals.join(", ")
            }
        );
        out += &format!(
            "  peak force {} {} at {}\n",
            num(Some(s.contact.peak_force)),
            u.force,
            time(s.contact.peak_force_time)
        );
        if let Some(d) = &s.delamination {
            out += &format!(
                "  delamination threshold F_crit {} {} (G_IIc {} {}/{}): peak / F_crit {:.4}{}\n",
                num(Some(d.onset.critical_force)),
                u.force,
                num(Some(d.onset.g_iic)),
                u.force,
                u.length,
                d.peak_over_critical,
                if d.peak_over_critical >= 1.0 { ", reached" } else { "" }
            );
        }
        if let Some(f) = &s.failure {
            for i in std::iter::once(&f.theory).chain(&f.max_stress).chain(&f.bond) {
                out += &format!(
                    "  failure index {} {:.4} at {} (element {}, ply {} {}), first reaches 1 at {}\n",
                    i.name,
                    i.largest,
                    time(Some(i.time)),
                    i.element,
                    i.ply,
                    i.face,
                    i.first_reaches_one.map_or("never".into(), |t| time(Some(t)))
                );
            }
        }
        out += &format!(
            "  impactor: v0 {} {velocity}, at rest at {}, rebound {} {velocity}\n",
            num(Some(s.impactor.initial_velocity)),
            time(s.impactor.velocity_zero_time),
            num(s.impactor.rebound_velocity),
        );
    }
    out += &format!(
        "  energy:   initial {} {}, transferred {}, max |error| {}\n",
        num(s.energy.initial),
        s.units.energy,
        s.energy
            .transferred_fraction
            .map(|x| format!("{:.2} %", 100.0 * x))
            .unwrap_or("-".into()),
        num(s.energy.max_relative_error)
    );
    if let Some(l) = &s.energy.impactor_loss {
        out += &format!(
            "  loss:     the impactor lost {}: target {}, damping {}, contact {}\n",
            num(Some(l.lost)),
            num(Some(l.target)),
            num(Some(l.damping)),
            num(Some(l.contact)),
        );
    }
    if let Some(c) = &s.energy.contact {
        out += &format!(
            "  contact:  {} (q {}, alpha_cr {} {}): largest indentation {}, permanent {} {}\n",
            c.law,
            c.unloading_exponent,
            num(Some(c.critical_indentation)),
            s.units.length,
            num(Some(c.max_indentation)),
            num(Some(c.permanent_indentation)),
            s.units.length,
        );
    }
    if let Some(t) = &s.run.modal {
        out += &format!(
            "  modal:    {} modes to {} cycles/{} ({} rigid), {} residual vectors; effective mass {:.4}, contact \
             flexibility by the modes {:.4}, reduced {:.6}\n",
            t.modes,
            num(Some(t.cutoff_frequency)),
            s.units.time,
            t.rigid_modes,
            t.residual_vectors,
            t.effective_mass_fraction,
            t.flexibility_by_modes,
            t.flexibility_reduced
        );
    }
    if !s.model.not_written.is_empty() {
        out += &format!(
            "  not written: {} (asked for in case control)\n",
            s.model.not_written.join(", ")
        );
    }
    if let Some(why) = &s.run.stopped_by {
        out += &format!(
            "  INCOMPLETE: stopped after {} of {} steps: {why}\n",
            s.run.steps_done, s.run.steps
        );
    }
    if let Some(r) = &s.rod {
        out += &format!(
            "  rod (tC/L): contact ends {}, impactor at rest {}, peak force {}\n",
            tcl(r.contact_end_tcl),
            tcl(r.velocity_zero_time_tcl),
            tcl(r.peak_force_time_tcl),
        );
    }
    out
}

/// A grid's row: `first` (a SUBCASE or mode) if any, the grid, its CD and T1..R3.
fn grid_row(first: Option<String>, d: &crate::run::statics::GridDisplacement) -> Vec<String> {
    first
        .into_iter()
        .chain([d.grid.to_string(), d.cd.to_string()])
        .chain(d.u.iter().map(|v| format!("{v:e}")))
        .collect()
}

/// A static solution's files: `displacements.csv` (every grid's T1..R3 in its
/// displacement frame, the frame's system in `cd`), `summary.json`, and
/// `elements.csv` when case control asks for element results. A deck of
/// several SUBCASEs writes every one's: `displacements.csv` with its `subcase` first,
/// and `summary.json` with each one's summary under `subcases`.
pub fn static_files(solutions: &[crate::run::statics::StaticSolution]) -> Vec<(&'static str, Vec<u8>)> {
    let several = solutions.len() > 1;
    let mut w = subcase_table(several, &["grid", "cd", "T1", "T2", "T3", "R1", "R2", "R3"]);
    for s in solutions {
        for d in &s.grids {
            let subcase = s.subcase.filter(|_| several).map(|n| n.to_string());
            w.write_record(grid_row(subcase, d)).expect("writing to memory");
        }
    }
    #[derive(serde::Serialize)]
    struct Summary<'a> {
        solution: &'static str,
        #[serde(flatten)]
        solved: &'a crate::run::statics::StaticSolution,
    }
    let without_grids = |s| {
        let mut json = serde_json::to_value(Summary {
            solution: "linear static (SOL 101)",
            solved: s,
        })
        .expect("plain data");
        if let Some(o) = json.as_object_mut() {
            o.remove("grids");
        }
        json
    };
    let json = match solutions {
        [one] => without_grids(one),
        _ => serde_json::json!({
            "solution": "linear static (SOL 101)",
            "subcases": solutions.iter().map(|s| {
                let mut v = without_grids(s);
                if let Some(o) = v.as_object_mut() {
                    o.remove("solution");
                }
                v
            }).collect::<Vec<_>>(),
        }),
    };
    let mut summary = serde_json::to_vec_pretty(&json).expect("plain data");
    summary.push(b'\n');
    let mut files = vec![
        ("displacements.csv", w.into_inner().expect("writing to memory")),
        ("summary.json", summary),
    ];
    if solutions.iter().any(|s| !s.elements.is_empty()) {
        files.push(("elements.csv", element_rows(solutions)));
    }
    files
}

/// A CSV table in memory headed by `header`, with a `subcase` column first when the
/// deck has `several` SUBCASEs.
fn subcase_table(several: bool, header: &[&str]) -> csv::Writer<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let subcase = several.then_some("subcase");
    w.write_record(subcase.iter().chain(header)).expect("writing to memory");
    w
}

/// `elements.csv` of a static solution: a row a recovered value (its element, card,
/// the value's name without the element's id, as the transient histories name it,
/// and the value), `subcase` first when the deck has several.
fn element_rows(solutions: &[crate::run::statics::StaticSolution]) -> Vec<u8> {
    let several = solutions.len() > 1;
    let mut w = subcase_table(several, &["element", "card", "quantity", "value"]);
    for s in solutions {
        let subcase = s.subcase.filter(|_| several).map(|n| n.to_string());
        for e in &s.elements {
            for (name, v) in e.names.iter().zip(&e.values) {
                let row = [e.eid.to_string(), e.card.to_string(), name.clone(), format!("{v:e}")];
                w.write_record(subcase.iter().cloned().chain(row))
                    .expect("writing to memory");
            }
        }
    }
    w.into_inner().expect("writing to memory")
}

/// A normal modes solution's files: `modes.csv` (each root: eigenvalue, radians and
/// cycles per unit time, generalised mass and stiffness, residual, effective masses
/// and their running sums as fractions), `shapes.csv`
/// (each mode's T1..R3 at every grid, in its displacement frame) and `summary.json`.
pub fn modal_files(s: &crate::run::modes::ModalSolution) -> Vec<(&'static str, Vec<u8>)> {
    let mut m = csv::Writer::from_writer(Vec::new());
    let dirs = ["T1", "T2", "T3", "R1", "R2", "R3"];
    let header: Vec<String> = [
        "mode",
        "eigenvalue",
        "radians",
        "cycles",
        "generalized_mass",
        "generalized_stiffness",
        "residual",
    ]
    .iter()
    .map(|h| h.to_string())
    .chain(dirs.iter().map(|d| format!("effective_mass_{d}")))
    .chain(dirs.iter().map(|d| format!("effective_mass_sum_{d}")))
    .collect();
    m.write_record(&header).expect("writing to memory");
    for r in &s.modes {
        let row: Vec<String> = std::iter::once(r.mode.to_string())
            .chain(
                [
                    r.eigenvalue,
                    r.radians,
                    r.cycles,
                    r.generalized_mass,
                    r.generalized_stiffness,
                    r.residual,
                ]
                .iter()
                .chain(&r.effective_mass)
                .chain(&r.effective_mass_sum)
                .map(|v| format!("{v:e}")),
            )
            .collect();
        m.write_record(&row).expect("writing to memory");
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(["mode", "grid", "cd", "T1", "T2", "T3", "R1", "R2", "R3"])
        .expect("writing to memory");
    for (mode, shape) in s.modes.iter().zip(&s.shapes) {
        for d in shape {
            w.write_record(grid_row(Some(mode.mode.to_string()), d))
                .expect("writing to memory");
        }
    }
    #[derive(serde::Serialize)]
    struct Summary<'a> {
        solution: &'static str,
        #[serde(flatten)]
        solved: &'a crate::run::modes::ModalSolution,
    }
    let mut summary = serde_json::to_vec_pretty(&Summary {
        solution: "normal modes (SOL 103)",
        solved: s,
    })
    .expect("plain data");
    summary.push(b'\n');
    vec![
        ("modes.csv", m.into_inner().expect("writing to memory")),
        ("shapes.csv", w.into_inner().expect("writing to memory")),
        ("summary.json", summary),
    ]
}

/// A normal modes solution in a few lines: the roots, in the deck's time unit.
pub fn modal_summary(s: &crate::run::modes::ModalSolution) -> String {
    let per = if s.units.time == crate::deck::Units::UNSPECIFIED {
        "unit time".to_string()
    } else {
        s.units.time.clone()
    };
    let mut out = format!(
        "{}: normal modes by {}, {}; {} DOF solved ({} held), {} Lanczos vectors\n  mode   eigenvalue     cycles per {per}\n",
        s.deck,
        s.method,
        s.roots_asked,
        s.dofs,
        s.autospc,
        s.lanczos_steps
    );
    for m in &s.modes {
        out.push_str(&format!("  {:>4}   {:.6e}   {:.6e}\n", m.mode, m.eigenvalue, m.cycles));
    }
    out
}

/// A static solution in a few lines, each value with the deck's unit.
pub fn static_summary(s: &crate::run::statics::StaticSolution) -> String {
    let (a, u) = (&s.applied, &s.units);
    let (t, g) = s.largest_translation;
    let subcase = s.subcase.map(|n| format!("SUBCASE {n}, ")).unwrap_or_default();
    format!(
        "{}: linear static, {subcase}LOAD = {}, {} DOF solved ({} unstiffened held)\n  applied force ({:.6e}, {:.6e}, {:.6e}) {}, \
         moment about the origin ({:.6e}, {:.6e}, {:.6e}) {}*{} (basic axes)\n  largest translation: {t:.6e} {} at grid \
         {g}\n  strain energy: {:.6e} {}\n  residual ‖Ku − f‖/‖f‖: {:.1e}\n",
        s.deck,
        s.load_set,
        s.dofs,
        s.autospc,
        a[0],
        a[1],
        a[2],
        u.force,
        a[3],
        a[4],
        a[5],
        u.force,
        u.length,
        u.length,
        s.strain_energy,
        u.energy,
        s.residual
    )
}
