//! The user guide's Slurm array script (`docs/src/how-to/slurm.md`), run as written on a real single-node Slurm
//! (Debian's slurm-wlm and munge; `tests/slurm/cluster.sh` starts and stops it). Under
//! CI (`CI` set; `.ci/run` installs the packages) a missing Slurm fails the test;
//! elsewhere the test says it skipped.

use crate::common;

use common::{deck, root};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The guide's Slurm array script: the `sh` block after "On Slurm" in
/// `docs/src/how-to/slurm.md`.
fn guide_script() -> String {
    let page = std::fs::read_to_string(root().join("docs/src/how-to/slurm.md")).unwrap();
    let after = &page[page.find("On Slurm").expect("the guide's Slurm page")..];
    let start = after.find("```sh\n").expect("its script block") + "```sh\n".len();
    let script = &after[start..];
    script[..script.find("```").unwrap()].to_string()
}

/// Why this machine cannot run the cluster, if it cannot.
fn missing() -> Option<String> {
    let have = |tool: &str| {
        ["/usr/bin", "/usr/sbin", "/usr/local/bin", "/usr/local/sbin"]
            .iter()
            .any(|d| Path::new(d).join(tool).exists())
    };
    if let Some(t) = ["sbatch", "slurmctld", "slurmd", "munged"]
        .into_iter()
        .find(|t| !have(t))
    {
        return Some(format!("{t} not found (apt-get install slurm-wlm munge)"));
    }
    let uid = Command::new("id").arg("-u").output().ok()?;
    (String::from_utf8_lossy(&uid.stdout).trim() != "0").then(|| "the daemons need root".into())
}

/// The cluster of `tests/slurm/cluster.sh`, stopped when dropped.
struct Cluster(std::path::PathBuf);

impl Cluster {
    fn start(dir: &Path) -> Cluster {
        let o = Command::new(root().join("tests/slurm/cluster.sh"))
            .args(["start", dir.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "cluster.sh start: {}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        Cluster(dir.to_path_buf())
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = Command::new(root().join("tests/slurm/cluster.sh"))
            .args(["stop", self.0.to_str().unwrap()])
            .status();
    }
}

/// Goal: the guide's array script, unchanged, runs a 40-point rod sweep as 4 array
/// tasks (`sbatch --wait --array=1-4`) sharing one kernel cache, and `impactlab
/// collect` merges the shards into the very bytes of the unsharded `sweep.csv`; the
/// shard count comes from the array, so no point is missing.
#[test]
fn the_guides_array_script_runs_on_a_real_slurm() {
    if let Some(why) = missing() {
        assert!(std::env::var_os("CI").is_none(), "Slurm is required under CI: {why}");
        eprintln!("skipped: no Slurm here: {why}");
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let work = tmp.path().join("work");
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(work.join("sweep-array.sh"), guide_script()).unwrap();
    std::fs::copy(deck("rod.bdf"), work.join("rod.bdf")).unwrap();
    let _cluster = Cluster::start(&tmp.path().join("cluster"));
    let conf = tmp.path().join("cluster/slurm.conf");
    let bin = Path::new(env!("CARGO_BIN_EXE_impactlab")).parent().unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let vary = ["--vary", "velocity=10:400:40"];

    let mut job = Command::new("sbatch")
        .args(["--wait", "--array=1-4", "sweep-array.sh", "rod.bdf", "sw"])
        .args(vary)
        .current_dir(&work)
        .env("SLURM_CONF", &conf)
        .env("PATH", &path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(300);
    let status = loop {
        if let Some(s) = job.try_wait().unwrap() {
            break s;
        }
        if Instant::now() > deadline {
            let _ = job.kill();
            panic!("sbatch --wait did not return within 300 s");
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    let logs: String = std::fs::read_dir(&work)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with("slurm-"))
        .map(|e| std::fs::read_to_string(e.path()).unwrap_or_default())
        .collect();
    assert!(status.success(), "the array failed: {logs}");

    let shards: Vec<String> = (1..=4).map(|i| format!("sw/shard-{i}")).collect();
    let kernels: Vec<_> = std::fs::read_dir(work.join("sw/kernels")).unwrap().collect();
    assert_eq!(kernels.len(), 1, "one shared kernel file: {kernels:?}");
    let impactlab = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_impactlab"))
            .args(args)
            .current_dir(&work)
            .output()
            .unwrap();
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    };
    let mut collect = vec!["collect"];
    collect.extend(shards.iter().map(String::as_str));
    collect.extend(["--out", "sw/all"]);
    impactlab(&collect);
    let mut whole = vec!["sweep", "rod.bdf", "--no-cache", "--out", "whole"];
    whole.extend(vary);
    impactlab(&whole);
    let merged = std::fs::read(work.join("sw/all/sweep.csv")).unwrap();
    assert_eq!(merged, std::fs::read(work.join("whole/sweep.csv")).unwrap());
    assert_eq!(
        merged.iter().filter(|&&b| b == b'\n').count(),
        41,
        "40 points and the header"
    );
}
