//! The `impactlab` binary end to end: outputs, summary keys, exit codes.

use crate::common;
use common::*;
use std::process::Command;

/// Goal: times are printed in the deck's own time unit and every printed value
/// carries its unit. Model: the rod deck relabelled `$ Units: mm, kN, ms` (the same
/// numbers: impactlab never converts, so the contact lasts 7.442e-5 ms).
#[test]
fn printed_summary_keeps_the_decks_units() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(deck("rod.bdf")).unwrap();
    assert!(text.contains("$ Units: in, lbf, s."));
    let p = dir.path().join("rod-ms.bdf");
    std::fs::write(&p, text.replace("$ Units: in, lbf, s.", "$ Units: mm, kN, ms")).unwrap();
    let out = dir.path().join("o");
    let o = impactlab(&["run", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("contact:  0.0000e0 ms..7.4420e-5 ms"), "{stdout}");
    assert!(!stdout.contains(" us") && !stdout.contains("µs"), "{stdout}");
    assert!(stdout.contains("v0 6.2100e1 mm/ms"), "{stdout}");
    assert!(stdout.contains("peak force 2.1990e2 kN"), "{stdout}");
    assert!(stdout.contains("initial 1.8486e-1 kN*mm"), "{stdout}");
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    assert!(history.starts_with("time [ms],contact_force [kN]"), "{history:.80}");
}

#[test]
fn run_writes_history_energy_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rod");
    let o = impactlab(&["run", deck("rod.bdf").to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("contact ends 0.413"), "{stdout}");
    let bytes = std::fs::read(out.join("summary.json")).unwrap();
    let s: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
    for key in [
        "/contact/intervals",
        "/contact/peak_force",
        "/contact/peak_force_time",
        "/impactor/initial_velocity",
        "/impactor/velocity_zero_time",
        "/impactor/rebound_velocity",
        "/energy/initial",
        "/energy/transferred_fraction",
        "/energy/max_relative_error",
        "/run/scheme",
        "/run/dt",
        "/run/steps",
        "/run/wall_s",
        "/rod/contact_end_tcl",
        "/rod/velocity_zero_time_tcl",
    ] {
        assert!(s.pointer(key).is_some_and(|v| !v.is_null()), "summary lacks {key}");
    }
    // The file reads back as the typed summary, with its provenance and units.
    let typed: impactlab::run::Summary = serde_json::from_slice(&bytes).unwrap();
    assert_eq!(typed.schema_version, 3);
    assert!(typed.run.complete && typed.run.stopped_by.is_none());
    assert_eq!(typed.impactlab_version, env!("CARGO_PKG_VERSION"));
    use sha2::Digest;
    let digest = sha2::Sha256::digest(std::fs::read(deck("rod.bdf")).unwrap());
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    assert_eq!(typed.deck_sha256, hex, "sha256sum of the deck");
    let u = &typed.units;
    assert_eq!(
        [&u.length, &u.force, &u.time, &u.mass, &u.energy],
        ["in", "lbf", "s", "lbf*s^2/in", "lbf*in"]
    );
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let header = history.lines().next().unwrap();
    for col in [
        "time [s]",
        "contact_force [lbf]",
        "disp_73_T1 [in]",
        "disp_1001 [in]",
        "nlload_999_T1 [lbf]",
        "stress_72 [lbf/in^2]",
    ] {
        assert!(header.contains(col), "history header lacks {col}: {header}");
    }
    assert_eq!(
        history.lines().count(),
        1 + 2500 / 25 + 1,
        "TSTEP NO = 25: every 25th step"
    );
    let energy = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    assert_eq!(energy.lines().count(), 1 + 2501, "one ledger row per step");
    // The ledger's columns are the ledger's numbers: the initial total is the
    // impactor's ½mv0², the balance column stays within the summary's max error.
    let header: Vec<&str> = energy.lines().next().unwrap().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h.starts_with(name))
            .unwrap_or_else(|| panic!("{name}"))
    };
    let rows: Vec<Vec<f64>> = energy
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let u0 = 0.5 * 9.587e-5 * 62.1 * 62.1;
    assert!((rows[0][col("total")] / u0 - 1.0).abs() < 1e-12);
    assert!((rows[0][col("ke_impactor")] / u0 - 1.0).abs() < 1e-12);
    let max_err = s["energy"]["max_relative_error"].as_f64().unwrap();
    let worst = rows.iter().map(|r| r[col("error")].abs()).fold(0.0, f64::max);
    assert!((worst - max_err).abs() <= 1e-15, "{worst} vs {max_err}");
}

fn temp_deck(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("d.bdf");
    std::fs::write(&p, text).unwrap();
    (dir, p)
}

#[test]
fn bad_input_exits_2_with_the_position() {
    let rod = std::fs::read_to_string(deck("rod.bdf")).unwrap();
    let (_d, p) = temp_deck(&rod.replace("PROD,1,11,0.196", "PROD,1,11,0.1q6"));
    let o = impactlab(&[
        "run",
        p.to_str().unwrap(),
        "--out",
        _d.path().join("o").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("d.bdf:43:11:") && err.contains("PROD field 4 (A): '0.1q6' is not a real number"),
        "{err}"
    );
    assert!(!_d.path().join("o").exists(), "nothing written on failure");
}

#[test]
fn mechanism_exits_3_naming_the_dof() {
    let rod = std::fs::read_to_string(deck("rod.bdf")).unwrap();
    // Leave the rotations of the rod grids free: no stiffness and no mass on R2.
    let (_d, p) = temp_deck(&rod.replace("SPC1,4,23456,1,THRU,145", "SPC1,4,23,1,THRU,145"));
    let o = impactlab(&[
        "run",
        p.to_str().unwrap(),
        "--out",
        _d.path().join("o").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(3));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("singular at grid 1 R2") && err.contains("mechanism"),
        "{err}"
    );
}

/// Goal: a run that fails (a mechanism) leaves the previous outputs in its output
/// directory whole, and no staging directory behind.
#[test]
fn a_failed_run_leaves_the_previous_outputs_whole() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rod");
    let rod = deck("rod.bdf");
    assert!(
        impactlab(&["run", rod.to_str().unwrap(), "--out", out.to_str().unwrap()])
            .status
            .success()
    );
    let before = std::fs::read(out.join("summary.json")).unwrap();
    let text = std::fs::read_to_string(&rod).unwrap();
    let free = dir.path().join("free.bdf");
    std::fs::write(&free, text.replace("SPC1,4,23456,1,THRU,145", "SPC1,4,23,1,THRU,145")).unwrap();
    let o = impactlab(&["run", free.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&o.stderr).contains("mechanism"));
    assert_eq!(std::fs::read(out.join("summary.json")).unwrap(), before);
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert_eq!(names, ["free.bdf", "rod"], "no staging directories left behind");
}

/// Goal: a run whose energy is not a finite number from the start (the rod struck at
/// 1e200 in/s: ½mv² overflows) is stopped by the guard at step 0 with exit 3, and the
/// message says why the error is NaN rather than leaving "NaN exceeds 5e-2" to be
/// decoded. The guard's message for a finite error does not carry that sentence.
#[test]
fn a_run_whose_energy_overflows_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(deck("rod.bdf")).unwrap();
    assert!(text.contains("TIC,1,999,1,0.0,62.1\n"));
    let bdf = dir.path().join("fast.bdf");
    std::fs::write(
        &bdf,
        text.replace("TIC,1,999,1,0.0,62.1\n", "TIC,1,999,1,0.0,1.0+200\n"),
    )
    .unwrap();
    let out = dir.path().join("fast");
    let o = impactlab(&[
        "run",
        bdf.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--steps",
        "5",
    ]);
    assert_eq!(o.status.code(), Some(3));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("relative energy error NaN at step 0 "), "{err}");
    assert!(err.contains("the energy itself is not a finite number"), "{err}");
}

/// Goal: the energy guard (LS-DYNA ENDENG, Radioss /STOP Emax) stops a run whose
/// energy error exceeds it with exit 3 naming the step, time and error, and writes
/// the outputs up to there, marked incomplete; `off` lets the same run finish. Model:
/// the rod with a guard of 1e-6 (Newmark's error passes it within the first steps of
/// contact; 1.58e-5 at the end).
#[test]
fn the_energy_guard_stops_a_run_and_keeps_its_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rod");
    let rod = deck("rod.bdf");
    let run = |guard: &str| {
        impactlab(&[
            "run",
            rod.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--max-energy-error",
            guard,
        ])
    };
    let o = run("1e-6");
    assert_eq!(o.status.code(), Some(3));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("energy guard: relative energy error "), "{err}");
    assert!(err.contains(" exceeds 1.000e-6"), "{err}");
    assert!(!err.contains("not a finite number"), "{err}");
    assert!(err.contains(&out.display().to_string()), "{err}");
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["run"]["complete"], false);
    let done = s["run"]["steps_done"].as_u64().unwrap();
    assert!(done > 0 && done < 2500, "{done}");
    assert!(err.contains(&format!("at step {done} ")), "{err}");
    let energy = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    assert_eq!(
        energy.lines().count() as u64,
        1 + done + 1,
        "one ledger row per step done"
    );
    let last: f64 = energy
        .lines()
        .last()
        .unwrap()
        .split(',')
        .nth(8)
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        last.abs() > 1e-6,
        "the last row is the one that tripped the guard: {last}"
    );
    let o = run("off");
    assert_eq!(o.status.code(), Some(0));
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["run"]["complete"], true);
    assert!(s["run"]["stopped_by"].is_null());
    assert_eq!(run("0").status.code(), Some(2), "a guard must be positive or off");
}

/// Goal: the binary needs nothing from its source tree at run time (as after `cargo
/// install --path .`): `bench` runs the paper's plate deck from a directory that has
/// no `reference-data/`.
#[test]
fn bench_runs_from_any_directory() {
    let dir = tempfile::tempdir().unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_impactlab"))
        .args(["bench", "--repeats", "1", "--steps", "20"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("plate 49x49 (6913 solved DOF)"), "{out}");
}

/// Goal: the size benchmark reports every stage, the peak memory of each plate and
/// the run's estimates as read and as solved (the full one, `bench --size`, runs the 49, 99 and 199 plates and a million-line
/// deck: minutes, so here two small plates).
#[test]
fn size_benchmark_reports_each_plate() {
    let out = impactlab::study::bench::bench_size(&[3, 5], &[3, 7], 2).unwrap();
    let rows: Vec<Vec<&str>> = out.lines().map(|l| l.split_whitespace().collect()).collect();
    let plate = |n: &str| {
        rows.iter()
            .find(|r| r.len() == 10 && r[0] == n)
            .unwrap_or_else(|| panic!("{out}"))
    };
    // The 5×5 plate: 6×6 grids with the edges clamped leave 4×4 free grids of 3 DOF
    // (w, two rotations) and the impactor's one.
    assert_eq!(plate("5")[2], "49", "{out}");
    assert!(
        plate("5")[7].parse::<f64>().is_ok_and(|g| g > 0.0),
        "a peak memory on Linux: {out}"
    );
    // The estimate as solved (inert DOFs dropped) is at most the estimate as read.
    let est = |k: usize| plate("5")[k].parse::<f64>().unwrap();
    assert!(est(9) <= est(8), "{out}");
    let read = |n: &str| {
        rows.iter()
            .find(|r| r.len() == 4 && r[0] == n)
            .unwrap_or_else(|| panic!("{out}"))
    };
    assert!(read("7")[1].parse::<usize>().unwrap() > read("3")[1].parse::<usize>().unwrap());
}

/// Goal: the CSV files hold every digit: each value reads back to the same f64
/// (shortest round-trip form), so `audit` sees any change. Also the GLSTAT-style
/// `energy_ratio` = total/(initial + external work) is there and equals
/// 1 + error·U0/(U0 + W_ext), to 1e-14 (round-off of the two divisions; the values
/// are of order 1).
#[test]
fn csv_numbers_round_trip_and_energy_ratio_is_written() {
    let model = rod_model();
    let run = common::run(&model, impactlab::integrate::Scheme::Newmark, None, Some(400));
    let dir = tempfile::tempdir().unwrap();
    impactlab::output::write_dir_atomically(dir.path(), &impactlab::output::run_files(&model, &run)).unwrap();
    let (_, rows) = impactlab::verify::gold::read(&dir.path().join("history.csv")).unwrap();
    assert_eq!(rows.len(), run.history.len());
    for (a, b) in rows.iter().zip(&run.history) {
        for (x, y) in a.iter().zip(b) {
            assert_eq!(x.to_bits(), y.to_bits(), "{x:e} vs {y:e}");
        }
    }
    let (header, rows) = impactlab::verify::gold::read(&dir.path().join("energy.csv")).unwrap();
    let col = |n: &str| {
        header
            .iter()
            .position(|h| h == n)
            .unwrap_or_else(|| panic!("{n} in {header:?}"))
    };
    let (ratio, error, work) = (col("energy_ratio"), col("error"), col("external_work"));
    let u0 = run.energy[0].total;
    for (r, e) in rows.iter().zip(&run.energy) {
        assert_eq!(r[ratio].to_bits(), e.energy_ratio.to_bits());
        let expected = 1.0 + r[error] * u0 / (u0 + r[work]);
        assert!((r[ratio] - expected).abs() < 1e-14, "{} vs {expected}", r[ratio]);
    }
}

/// Goal: a deck that cannot be read is one error naming its path (exit 2), not a
/// cascade of "no CEND card" and "missing BEGIN BULK" on top of it.
#[test]
fn an_unreadable_deck_is_one_error_naming_its_path() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("not-a-file.bdf");
    std::fs::create_dir(&deck).unwrap();
    let o = impactlab(&[
        "run",
        deck.to_str().unwrap(),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("cannot read deck '{}'", deck.display())), "{err}");
    assert!(err.contains("1 error(s) in deck") && !err.contains("CEND"), "{err}");
}

/// A Python with pandas, or `None` (and why) where there is none; under CI
/// (`.ci/run` installs pandas) a missing one fails.
fn python_with(module: &str) -> Option<&'static str> {
    let ok = Command::new("python3")
        .args(["-c", &format!("import {module}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must install {module} for python3 (.ci/run does)"
        );
        eprintln!("skipped: python3 with {module} not found (pip install {module})");
    }
    ok.then_some("python3")
}

/// Goal: `examples/pandas_outputs.py` reads a run's history.csv, energy.csv and
/// summary.json into pandas, units parsed out of the headers, and gets the very
/// numbers the run wrote: the peak contact force and its time equal the summary's,
/// the last ledger row's total its final total, the largest |error| its largest
/// relative error (exactly: CSV and JSON numbers read back to the same f64). Model:
/// the paper's rod.
#[test]
fn pandas_example_reads_the_outputs_with_their_units() {
    let Some(python) = python_with("pandas") else { return };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rod");
    let o = impactlab(&["run", deck("rod.bdf").to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = Command::new(python)
        .arg(root().join("examples/pandas_outputs.py"))
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let value = |name: &str| -> (f64, String) {
        let line = stdout
            .lines()
            .find_map(|l| l.strip_prefix(&format!("{name} = ")))
            .unwrap_or_else(|| panic!("{name} in {stdout}"));
        let (v, unit) = line.split_once(' ').unwrap();
        (v.parse().unwrap(), unit.to_string())
    };
    let s: impactlab::run::Summary =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(value("peak_force"), (s.contact.peak_force, "lbf".into()));
    let some = |(v, unit): (f64, String)| (Some(v), unit);
    assert_eq!(some(value("peak_force_time")), (s.contact.peak_force_time, "s".into()));
    assert_eq!(some(value("final_total")), (s.energy.final_total, "lbf*in".into()));
    assert_eq!(some(value("max_abs_error")), (s.energy.max_relative_error, "-".into()));
}

/// Goal: a sweep over impact velocity and Hertz K on the convolution engine writes one
/// row per point (first `--vary` slowest), checks the first and the last point and the
/// point nearest the deck's own values (62.1 in/s and K = 6.24e6: point 3, at 48 in/s)
/// against the direct engine (within 1e-9), and the peak force grows with velocity;
/// three shards merged by `collect` give the very bytes of the unsharded `sweep.csv`,
/// and a missing shard is an error naming the missing points. `--checks 0` turns the
/// self-check off with a warning and says so in summary.json; `--check-every` with it
/// is refused. Model: the paper's rod, 6 velocities × 2 K (12 points).
#[test]
fn sweep_shards_collect_to_the_unsharded_csv() {
    let dir = tempfile::tempdir().unwrap();
    let rod = deck("rod.bdf");
    let sweep = |out: &std::path::Path, shard: Option<&str>| {
        let mut args = vec![
            "sweep",
            rod.to_str().unwrap(),
            "--vary",
            "velocity=10:200:6",
            "--vary",
            "k=3e6,6.24e6",
            "--out",
            out.to_str().unwrap(),
        ];
        if let Some(s) = shard {
            args.extend(["--shard", s]);
        }
        let o = impactlab(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    let whole = dir.path().join("whole");
    sweep(&whole, None);
    let (header, rows) = impactlab::study::sweep::read_csv(&whole.join("sweep.csv")).unwrap();
    for figure in ["peak-force", "contact-end", "transferred-fraction", "strain-peaks"] {
        let png = std::fs::read(whole.join(format!("{figure}.png"))).unwrap();
        assert_eq!(&png[..4], b"\x89PNG", "{figure}");
    }
    assert_eq!(&header[..3], ["point", "velocity", "k"]);
    assert_eq!(rows.len(), 12);
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (check, peak) = (col("direct_check"), col("peak_force"));
    for r in &rows {
        let i = r[0] as usize;
        let checked = [0, 3, 11].contains(&i);
        assert_eq!(!r[check].is_nan(), checked, "point {i}");
        assert!(r[check].is_nan() || r[check] <= 1e-9, "point {i}: {}", r[check]);
    }
    // Same K (every other row), velocity rising: the peak force rises.
    for w in rows.iter().step_by(2).collect::<Vec<_>>().windows(2) {
        assert!(w[1][1] > w[0][1] && w[1][peak] > w[0][peak]);
    }
    let shards: Vec<_> = (1..=3).map(|i| dir.path().join(format!("s{i}"))).collect();
    for (i, s) in shards.iter().enumerate() {
        sweep(s, Some(&format!("{}/3", i + 1)));
    }
    let merged = dir.path().join("merged");
    let mut args = vec!["collect"];
    args.extend(shards.iter().map(|s| s.to_str().unwrap()));
    args.extend(["--out", merged.to_str().unwrap()]);
    let o = impactlab(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read(merged.join("sweep.csv")).unwrap(),
        std::fs::read(whole.join("sweep.csv")).unwrap()
    );
    let o = impactlab(&[
        "collect",
        shards[0].to_str().unwrap(),
        shards[2].to_str().unwrap(),
        "--out",
        dir.path().join("partial").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("4 of 12 points missing (first: 1)"));
    let summary = |d: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(d.join("summary.json")).unwrap()).unwrap()
    };
    assert_eq!(summary(&whole)["self_check"]["points"], serde_json::json!([0, 3, 11]));
    assert_eq!(summary(&merged)["self_check"]["points"], serde_json::json!([0, 3, 11]));

    let off = dir.path().join("off");
    let args = |extra: &[&str]| {
        let mut a = vec!["sweep", rod.to_str().unwrap(), "--vary", "velocity=10:200:6", "--out"];
        a.push(off.to_str().unwrap());
        a.extend_from_slice(extra);
        impactlab(&a)
    };
    let o = args(&["--checks", "0"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("warning: --checks 0"));
    let s = summary(&off);
    assert_eq!(
        (s["self_check"]["off"].as_bool(), s["direct_checks"].as_u64()),
        (Some(true), Some(0))
    );
    let o = args(&["--checks", "0", "--check-every", "2"]);
    assert_eq!(o.status.code(), Some(2));
    let o = args(&["--check-every", "2"]);
    assert!(o.status.success());
    assert_eq!(
        summary(&off)["self_check"]["points"],
        serde_json::json!([0, 1, 2, 4, 5])
    );
}

/// Goal: a static deck's SUBCASEs are solved in one run and written together, and
/// `impactlab compare` reads NASTRAN's printed output against them and gates on its
/// tolerance, element results included. Model: NASTRAN-95's demonstration deck
/// d01141a (two SUBCASEs, ELFORCE = ALL on its CBAR) and its printed output.
/// Reference: its displacements agree to 2.3e-7 of the largest (NASTRAN-95 prints
/// seven digits) and its bar forces to 3.1e-5 (M1 at end A printed 9.999695E-01 where
/// the exact value is 1: NASTRAN-95's single-precision round-off): --tolerance 1e-4
/// passes (exit 0), 1e-5 fails on the bar forces alone (exit 1); a file with no
/// displacement table is an input error (exit 2).
#[test]
fn static_subcases_are_written_and_compared_with_nastrans_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("d");
    let o = impactlab(&[
        "run",
        "reference-data/nastran95-demos/inp/d01141a.inp",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("displacements.csv")).unwrap();
    assert!(csv.starts_with("subcase,grid,cd,T1"), "{csv}");
    assert_eq!(csv.lines().filter(|l| l.starts_with("2,")).count(), 7);
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["subcases"][1]["subcase"], 2);
    assert_eq!(summary["subcases"][1]["load_set"], 2);
    let printed = "reference-data/nastran95-demos/demoout/d01141a.out";
    let run = out.to_str().unwrap();
    let elements = std::fs::read_to_string(out.join("elements.csv")).unwrap();
    assert!(
        elements.starts_with("subcase,element,card,quantity,value\n"),
        "{elements}"
    );
    assert!(elements.contains("\n2,6,CBAR,force_a_v1,"), "{elements}");
    let pass = impactlab(&["compare", run, printed, "--tolerance", "1e-4"]);
    let text = String::from_utf8_lossy(&pass.stdout);
    assert_eq!(pass.status.code(), Some(0), "{text}");
    assert!(
        text.contains("SUBCASE 2: 42 components; largest printed translation 1.440000e2"),
        "{text}"
    );
    assert!(
        text.contains("element results: 24 values; largest difference 3.05e-5"),
        "{text}"
    );
    let fail = impactlab(&["compare", run, printed, "--tolerance", "1e-5"]);
    let text = String::from_utf8_lossy(&fail.stdout);
    assert_eq!(fail.status.code(), Some(1), "{text}");
    assert!(
        text.contains("largest difference 3.05e-5 exceeds --tolerance 1e-5"),
        "{text}"
    );
    let none = impactlab(&["compare", run, "reference-data/nastran95-demos/inp/d01141a.inp"]);
    assert_eq!(none.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&none.stderr).contains("holds no real displacement table"));
}
