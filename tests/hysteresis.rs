//! A contact that unloads along another curve than it loads on (Yang and Sun's law,
//! `[contact] law = "yang-sun"` in a scene): it reduces to Hertz's run bit for bit
//! when it cannot dissipate, books its dissipation in the ledger and the summary, has
//! no deck twin, and runs in sweeps and threshold searches.

use crate::common;

use common::{impactlab, root};
use impactlab::run::{run_model, RunOptions};

/// The paper's plate scene on a 17×17 mesh (for speed), its contact law `contact`.
fn plate17(dir: &std::path::Path, name: &str, contact: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(root().join("verification/scenes/plate.toml"))
        .unwrap()
        .replace("mesh = 49", "mesh = 17")
        .replace("gages = [3325, 4125]", "gages = []")
        .replace("law = \"hertz\"", contact);
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn run_scene(p: &std::path::Path) -> impactlab::run::RunResult {
    let (s, model, _) = impactlab::scene::load(p).unwrap();
    run_model(&model, &RunOptions::for_scene(&s)).unwrap()
}

/// Goal: Yang and Sun's law with α_cr = ∞ and q = 1.5 (the loading exponent) unloads
/// along its loading curve: the plate's run is the Hertz run bit for bit, in every
/// implicit scheme (the history, and every ledger column both write), and dissipates
/// nothing. (Central differences cannot run a plate, whose rotations have no mass;
/// the one-DOF wall shows it bit for bit there too.)
#[test]
fn yang_sun_that_cannot_dissipate_is_hertz_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let hertz = plate17(dir.path(), "h.toml", "law = \"hertz\"");
    let elastic = plate17(dir.path(), "e.toml", "law = \"yang-sun\"\nalpha_cr = inf\nq = 1.5");
    for scheme in impactlab::integrate::Scheme::ALL
        .into_iter()
        .filter(|s| *s != impactlab::integrate::Scheme::Central)
    {
        let at = |p: &std::path::Path| {
            let (s, model, _) = impactlab::scene::load(p).unwrap();
            let mut o = RunOptions::for_scene(&s);
            o.scheme = scheme;
            run_model(&model, &o).unwrap()
        };
        let (a, b) = (at(&hertz), at(&elastic));
        assert_eq!(a.history, b.history, "{scheme}");
        assert_eq!(a.series.force, b.series.force, "{scheme}");
        let drop_contact = |r: &impactlab::run::RunResult| -> Vec<_> {
            r.energy
                .iter()
                .map(|e| impactlab::ledger::EnergyRow {
                    dissipated_contact: 0.0,
                    ..*e
                })
                .collect()
        };
        assert_eq!(drop_contact(&a), drop_contact(&b), "{scheme}");
        assert!(b.energy.iter().all(|e| e.dissipated_contact == 0.0), "{scheme}");
        assert_eq!(b.summary.energy.contact.as_ref().unwrap().permanent_indentation, 0.0);
    }
}

/// Goal: with q = 2.5 and α_cr below the largest indentation the plate's contact
/// dissipates: the ledger's `dissipated_contact` never decreases and is positive, the
/// summary splits the impactor's loss into the target's gain and the contact's
/// dissipation with a residual that is the ledger's own balance (−error·U0), the
/// permanent indentation is Yang and Sun's α0 of the largest, and the impactor
/// rebounds slower than through Hertz's law (the energy the contact kept is gone).
#[test]
fn yang_sun_books_the_contacts_dissipation_and_splits_the_loss() {
    let dir = tempfile::tempdir().unwrap();
    let hertz = run_scene(&plate17(dir.path(), "h.toml", "law = \"hertz\""));
    let ys = run_scene(&plate17(
        dir.path(),
        "y.toml",
        "law = \"yang-sun\"\nalpha_cr = 0.005\nq = 2.5",
    ));
    let d: Vec<f64> = ys.energy.iter().map(|e| e.dissipated_contact).collect();
    assert!(d.windows(2).all(|w| w[1] >= w[0]));
    let last = ys.energy.last().unwrap();
    assert!(
        last.dissipated_contact > 0.01 * ys.energy[0].total,
        "{}",
        last.dissipated_contact
    );
    let e = &ys.summary.energy;
    let loss = e.impactor_loss.as_ref().unwrap();
    assert_eq!(loss.contact, last.dissipated_contact);
    let u0 = ys.energy[0].total;
    assert!(
        (loss.residual + last.error * u0).abs() <= 1e-9 * u0,
        "{loss:?} {}",
        last.error
    );
    let c = e.contact.as_ref().unwrap();
    let max = ys.series.alpha.iter().copied().fold(0.0, f64::max);
    assert_eq!(c.max_indentation, max);
    let a0 = max * (1.0 - (0.005f64 / max).powf(0.4));
    assert!((c.permanent_indentation - a0).abs() <= 1e-15 * max);
    let (vh, vy) = (
        hertz.summary.impactor.rebound_velocity.unwrap(),
        ys.summary.impactor.rebound_velocity.unwrap(),
    );
    assert!(vy.abs() < vh.abs(), "rebound {vy} through Yang-Sun, {vh} through Hertz");
    // The Hertz run books no contact dissipation and writes no such column.
    assert!(hertz.summary.energy.contact.is_none() && hertz.summary.energy.impactor_loss.is_none());
}

/// Goal: a scene whose contact a deck cannot express is refused by `--to-deck` (exit
/// 2, saying why), and Yang and Sun's parameters are checked: α_cr is required and
/// positive, q at least 1.5, and neither is taken with Hertz's law.
#[test]
fn yang_sun_scenes_have_no_deck_twin_and_their_parameters_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let p = plate17(dir.path(), "y.toml", "law = \"yang-sun\"\nalpha_cr = 0.005");
    let o = impactlab(&[
        "scene",
        p.to_str().unwrap(),
        "--to-deck",
        dir.path().join("y.bdf").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("no NASTRAN deck twin"), "{err}");
    assert!(!dir.path().join("y.bdf").exists());
    for (contact, says) in [
        ("law = \"yang-sun\"", "needs contact.alpha_cr"),
        ("law = \"yang-sun\"\nalpha_cr = -1.0", "must be positive"),
        (
            "law = \"yang-sun\"\nalpha_cr = 0.005\nq = 1.2",
            "at least the loading exponent",
        ),
        ("law = \"hertz\"\nalpha_cr = 0.005", "give them with law = \"yang-sun\""),
        ("law = \"plastic\"", "not supported"),
    ] {
        let p = plate17(dir.path(), "bad.toml", contact);
        let o = impactlab(&[
            "run",
            p.to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{contact}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{contact}: {err}");
    }
}

/// Goal: a sweep and a threshold search take a Yang-Sun scene: the sweep's points on
/// the convolution engine agree with the direct engine (its self-check passes) and
/// `sweep.csv` gains `dissipated_contact`, larger at a higher speed, and its figure;
/// the threshold search finds a speed.
#[test]
fn yang_sun_scenes_sweep_and_find_thresholds() {
    let dir = tempfile::tempdir().unwrap();
    let p = plate17(dir.path(), "y.toml", "law = \"yang-sun\"\nalpha_cr = 0.005");
    let out = dir.path().join("sweep");
    let o = impactlab(&[
        "sweep",
        p.to_str().unwrap(),
        "--vary",
        "velocity=800:1600:3",
        "--no-cache",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut r = csv::Reader::from_path(out.join("sweep.csv")).unwrap();
    let j = r
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == "dissipated_contact")
        .unwrap();
    let d: Vec<f64> = r.records().map(|x| x.unwrap()[j].parse().unwrap()).collect();
    assert!(d.len() == 3 && d[0] > 0.0 && d[2] > d[0], "{d:?}");
    assert!(out.join("dissipated-contact.png").exists(), "no figure of D_c");
    let o = impactlab(&[
        "sweep",
        p.to_str().unwrap(),
        "--find",
        "velocity",
        "--until",
        "peak_force=1000",
        "--no-cache",
        "--out",
        dir.path().join("find").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.path().join("find/threshold.json").exists());
}
