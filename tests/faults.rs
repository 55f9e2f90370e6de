//! System faults lose nothing: an output directory that cannot be written, a full
//! disk, a file-size limit, SIGINT/SIGTERM at any moment and two runs into the same
//! `--out` each end with the previous outputs intact or one run's complete new ones,
//! never a mix, and with a message naming the path. Linux only (prlimit, setpriv,
//! unshare and mount from util-linux).
#![cfg(target_os = "linux")]

use crate::common;

use common::deck;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

const BIN: &str = env!("CARGO_BIN_EXE_impactlab");

/// Every file of a directory with its bytes; `summary.json` without its wall-clock
/// times (which differ run to run): two runs of one deck compare equal.
fn contents(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut m = BTreeMap::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = e.file_name().to_string_lossy().into_owned();
        let mut bytes = std::fs::read(e.path()).unwrap();
        if name == "summary.json" {
            let mut s: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
            for k in ["factor_s", "solve_s", "assembly_s", "wall_s"] {
                s["run"][k] = serde_json::Value::Null;
            }
            bytes = serde_json::to_vec(&s).unwrap();
        }
        m.insert(name, bytes);
    }
    m
}

/// Anything left beside `dir` by a write (staging directories, temporary files).
fn leftovers(dir: &Path) -> Vec<String> {
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    std::fs::read_dir(dir.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(&format!(".{name}.")) || n.starts_with(".tmp"))
        .collect()
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn rod() -> String {
    deck("rod.bdf").display().to_string()
}

/// The rod's outputs over `steps` steps, written to `dir`.
fn rod_outputs(dir: &Path, steps: usize) -> BTreeMap<String, Vec<u8>> {
    let o = run(&[
        "run",
        &rod(),
        "--steps",
        &steps.to_string(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    contents(dir)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts the command ended with `code` and said `text` on standard error.
fn fails_saying(o: &Output, code: i32, text: &str) {
    assert_eq!(o.status.code(), Some(code), "{}", stderr(o));
    assert!(stderr(o).contains(text), "expected {text:?} in:\n{}", stderr(o));
}

/// Asserts `dir` holds exactly `before` and nothing was left beside it.
fn intact(dir: &Path, before: &BTreeMap<String, Vec<u8>>) {
    assert_eq!(&contents(dir), before);
    assert!(leftovers(dir).is_empty(), "{:?}", leftovers(dir));
}

fn is_root() -> bool {
    let o = Command::new("id").arg("-u").output().unwrap();
    String::from_utf8_lossy(&o.stdout).trim() == "0"
}

/// Goal: an output directory that cannot be written is an error (exit 2) naming
/// it, and an earlier output directory there keeps its files.
#[test]
fn an_unwritable_output_directory_is_an_error_naming_it() {
    let tmp = tempfile::tempdir().unwrap();
    // Below a regular file.
    let file = tmp.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let out = file.join("out");
    let o = run(&["run", &rod(), "--out", out.to_str().unwrap()]);
    fails_saying(&o, 2, &format!("cannot write outputs to {}: ", out.display()));
    // In a directory without write permission (as another user when run as root,
    // whom permissions do not stop).
    let ro = tmp.path().join("ro");
    std::fs::create_dir(&ro).unwrap();
    let out = ro.join("out");
    let before = rod_outputs(&out, 100);
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(tmp.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let deck_copy = tmp.path().join("rod.bdf");
    std::fs::copy(deck("rod.bdf"), &deck_copy).unwrap();
    std::fs::set_permissions(&deck_copy, std::fs::Permissions::from_mode(0o644)).unwrap();
    let args = ["run", deck_copy.to_str().unwrap(), "--out", out.to_str().unwrap()];
    let o = if is_root() {
        Command::new("setpriv")
            .args(["--reuid=65534", "--regid=65534", "--clear-groups", BIN])
            .args(args)
            .output()
            .unwrap()
    } else {
        run(&args)
    };
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
    fails_saying(
        &o,
        2,
        &format!("cannot write outputs to {}: Permission denied", out.display()),
    );
    intact(&out, &before);
}

/// Goal: `--out` naming a directory that is not an earlier output (it holds a
/// subdirectory) is refused, and nothing in it is touched.
#[test]
fn a_directory_that_is_not_an_output_is_never_replaced() {
    let tmp = tempfile::tempdir().unwrap();
    let project = tmp.path().join("project");
    std::fs::create_dir_all(project.join("src")).unwrap();
    std::fs::write(project.join("notes.txt"), "mine").unwrap();
    let o = run(&["run", &rod(), "--out", project.to_str().unwrap()]);
    fails_saying(
        &o,
        2,
        &format!(
            "cannot write outputs to {}: it holds 'src', which is not a regular file",
            project.display()
        ),
    );
    assert_eq!(std::fs::read_to_string(project.join("notes.txt")).unwrap(), "mine");
    assert!(project.join("src").is_dir());
}

/// Goal: a write that fails part way (a file-size limit, as a nearly full disk
/// does) is an error naming the directory, and the previous outputs stay whole.
#[test]
fn a_file_size_limit_leaves_the_previous_outputs() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let before = rod_outputs(&out, 100);
    // The full run's energy.csv is about 480 kB; 100 kB lets the stage begin.
    let o = Command::new("prlimit")
        .args(["--fsize=100000", BIN, "run", &rod(), "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    fails_saying(
        &o,
        2,
        &format!("cannot write outputs to {}: File too large", out.display()),
    );
    intact(&out, &before);
}

/// Goal: a full disk (a 256 kB tmpfs, mounted in a private mount namespace) is an
/// error naming the directory; the previous outputs stay whole and the partial
/// stage is removed. Needs `unshare -m` (root, or user namespaces): under CI it must
/// run, elsewhere it says it was skipped.
#[test]
fn a_full_disk_leaves_the_previous_outputs() {
    let probe = Command::new("unshare").args(["-m", "true"]).output();
    if !probe.is_ok_and(|o| o.status.success()) {
        assert!(std::env::var_os("CI").is_none(), "CI must be able to mount a tmpfs");
        eprintln!("skipped: cannot mount a tmpfs here (unshare -m failed)");
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let mnt = tmp.path().join("mnt");
    std::fs::create_dir(&mnt).unwrap();
    // Inside the namespace: earlier outputs (100 steps, about 20 kB), then the full
    // run (about 520 kB), then what the directory holds, as hashes.
    let script = format!(
        "mount -t tmpfs -o size=256k tmpfs {m} && \
         {bin} run {rod} --steps 100 --out {m}/out >/dev/null && \
         sha256sum {m}/out/history.csv {m}/out/energy.csv > {m}/before && \
         {bin} run {rod} --out {m}/out; echo \"exit $?\"; \
         sha256sum -c --quiet {m}/before && echo intact; ls -a {m}",
        m = mnt.display(),
        bin = BIN,
        rod = rod()
    );
    let o = Command::new("unshare")
        .args(["-m", "sh", "-c", &script])
        .output()
        .unwrap();
    let (stdout, err) = (String::from_utf8_lossy(&o.stdout), stderr(&o));
    assert!(stdout.contains("exit 2"), "{stdout}\n{err}");
    assert!(
        err.contains(&format!(
            "cannot write outputs to {}/out: No space left on device",
            mnt.display()
        )),
        "{err}"
    );
    assert!(stdout.contains("intact"), "{stdout}");
    let listing: Vec<&str> = stdout.lines().skip_while(|l| *l != "intact").skip(1).collect();
    assert_eq!(listing, [".", "..", "before", "out"], "{stdout}");
}

/// Starts a run and sends it `signal` after `delay`; its output.
fn interrupted(args: &[&str], signal: &str, delay: Duration) -> Output {
    let child = Command::new(BIN)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(delay);
    Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    child.wait_with_output().unwrap()
}

/// Goal: SIGINT or SIGTERM in the middle of a long run ends it with 128 + the
/// signal's number and a message naming the output directory, which keeps the
/// previous outputs.
#[test]
fn an_interrupted_run_keeps_the_previous_outputs() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let before = rod_outputs(&out, 100);
    let plate = deck("plate.bdf").display().to_string();
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let args = ["run", &plate, "--steps", "100000", "--out", out.to_str().unwrap()];
        let o = interrupted(&args, signal, Duration::from_millis(500));
        fails_saying(
            &o,
            code,
            &format!(
                "interrupted by SIG{signal}: {} was not written and holds what it held before",
                out.display()
            ),
        );
        intact(&out, &before);
    }
}

/// Goal: a signal at any moment, writing included, leaves the previous outputs or
/// the complete new ones: SIGTERM at 24 moments across short rod runs.
#[test]
fn a_signal_at_any_moment_leaves_old_or_new_outputs_whole() {
    let tmp = tempfile::tempdir().unwrap();
    let new = rod_outputs(&tmp.path().join("new"), 2500);
    let out = tmp.path().join("out");
    let old = rod_outputs(&out, 100);
    let mut seen = (0, 0);
    for k in 0..24 {
        let args = ["run", &rod(), "--out", out.to_str().unwrap()];
        let o = interrupted(&args, "TERM", Duration::from_millis(5 * k));
        let now = contents(&out);
        if now == old {
            seen.0 += 1;
        } else {
            assert!(now == new, "a mix after SIGTERM at {} ms: {}", 5 * k, stderr(&o));
            seen.1 += 1;
        }
        assert!(leftovers(&out).is_empty(), "{:?}", leftovers(&out));
        // Back to the old outputs for the next round.
        rod_outputs(&out, 100);
    }
    eprintln!("old kept {} times, new written {} times", seen.0, seen.1);
}

/// Goal: two runs into the same `--out` at once both succeed and leave one run's
/// complete outputs, never a mix (five rounds).
#[test]
fn concurrent_runs_into_one_directory_leave_one_complete_set() {
    let tmp = tempfile::tempdir().unwrap();
    let a = rod_outputs(&tmp.path().join("a"), 2500);
    let b = rod_outputs(&tmp.path().join("b"), 1500);
    let out: PathBuf = tmp.path().join("out");
    for round in 0..5 {
        let spawn = |steps: &str| {
            Command::new(BIN)
                .args(["run", &rod(), "--steps", steps, "--out", out.to_str().unwrap()])
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        };
        let (x, y) = (spawn("2500"), spawn("1500"));
        for c in [x, y] {
            let o = c.wait_with_output().unwrap();
            assert!(o.status.success(), "round {round}: {}", stderr(&o));
        }
        let now = contents(&out);
        assert!(now == a || now == b, "round {round}: a mix of two runs");
        assert!(leftovers(&out).is_empty(), "{:?}", leftovers(&out));
    }
}

/// Goal: a run that will take long says so after its first second of stepping
/// (time and memory), before its bulk; here the plate asked for 10^6 steps (hours),
/// stopped by SIGTERM once the estimate is out.
#[test]
fn a_long_run_prints_its_estimate_first() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let plate = deck("plate.bdf").display().to_string();
    let args = ["run", &plate, "--steps", "1000000", "--out", out.to_str().unwrap()];
    let o = interrupted(&args, "TERM", Duration::from_secs(4));
    let err = stderr(&o);
    let line = err
        .lines()
        .find(|l| l.starts_with("estimate: about "))
        .unwrap_or_else(|| panic!("{err}"));
    let secs: f64 = line["estimate: about ".len()..]
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        secs > 100.0 && line.contains("for 1000000 steps") && line.contains("memory about"),
        "{line}"
    );
    assert_eq!(o.status.code(), Some(143), "{err}");
    assert!(!out.exists());
}

/// Goal: a kernel cache that cannot be written (below a regular file here; a full
/// disk alike) costs the convolution run its cache, not its result: the run
/// completes, writes its outputs and warns, naming the cache file.
#[test]
fn a_kernel_cache_that_cannot_be_written_is_a_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let cache = file.join("cache");
    let out = tmp.path().join("out");
    let o = run(&[
        "run",
        &rod(),
        "--engine",
        "convolution",
        "--cache",
        cache.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(&format!("warning: kernel cache: {}/", cache.display()))
            && stderr(&o).contains("computed, not stored"),
        "{}",
        stderr(&o)
    );
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert!(s["run"]["kernel_cache"]["not_stored"].is_string(), "{s}");
}
