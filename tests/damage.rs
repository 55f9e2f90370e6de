//! Damage onset and the threshold impact: the delamination threshold in the run's
//! summary, and `sweep --find velocity --until …`.

mod common;

use common::{deck, rod_model, root};
use impactlab::run::{run_model, RunOptions};
use impactlab::study::threshold::{find_velocity, Until, BRACKET_WIDTH};
use indicatif::ProgressBar;
use std::process::Command;

fn impactlab(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_impactlab"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("impactlab runs")
}

/// Goal: the search inverts the run. Asked for the very peak force the deck's own
/// impact gives (direct engine), the threshold speed is the deck's speed to the
/// bracket's width (1e-6), the energy is ½mv² of it, and the direct engine puts that
/// force between the bracket's ends. The deck's peak ×1.5 needs a higher speed, the
/// peak ×0.5 a lower one. Model: the paper's rod (62.1 in/s).
#[test]
fn threshold_of_the_decks_own_peak_force_is_the_decks_speed() {
    let model = rod_model();
    let opts = RunOptions::default();
    let peak = run_model(&model, &opts).unwrap().summary.contact.peak_force;
    let t = find_velocity(&model, &opts, Until::PeakForce(peak), &ProgressBar::hidden()).unwrap();
    assert!((t.velocity / 62.1 - 1.0).abs() <= BRACKET_WIDTH, "{}", t.velocity);
    assert!(t.bracket[1] - t.bracket[0] <= BRACKET_WIDTH * t.bracket[1]);
    assert!(
        t.direct_peaks[0] < peak && peak <= t.direct_peaks[1],
        "{:?}",
        t.direct_peaks
    );
    assert!(t.direct_check <= impactlab::study::sweep::DIRECT_CHECK_MAX);
    assert_eq!(t.energy, 0.5 * 9.587e-5 * t.velocity * t.velocity);
    for (scale, above) in [(1.5, true), (0.5, false)] {
        let s = find_velocity(&model, &opts, Until::PeakForce(scale * peak), &ProgressBar::hidden()).unwrap();
        assert_eq!(s.velocity > 62.1, above, "{scale}: {}", s.velocity);
    }
}

/// Goal: with G_IIc the run's summary gives the plate's delamination threshold
/// (Davies-Zhang, D* of the paper's MAT2 bending matrix) against the peak force, the
/// threshold search stops where the direct engine's peak reaches that F_crit and prints
/// the impact energy in joules for an in-lbf-s deck (1 lbf·in = 0.1129848 J), and the
/// requests that cannot be answered are input errors (exit 2) that say why. Model: the
/// paper's plate (2100 steps), G_IIc 5.71 lbf/in (1.0 kJ/m²).
#[test]
fn delamination_threshold_in_the_summary_and_as_a_threshold_speed() {
    let dir = tempfile::tempdir().unwrap();
    let plate = deck("plate.bdf");
    let p = plate.to_str().unwrap();
    let run_dir = dir.path().join("run");
    let o = impactlab(&[
        "run",
        p,
        "--steps",
        "2100",
        "--giic",
        "5.71",
        "--out",
        run_dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(run_dir.join("summary.json")).unwrap()).unwrap();
    let d = &s["delamination"];
    let t3 = 0.15f64.powi(3) / 12.0;
    let (d11, d22, d12, d66) = (5.7e6 * t3, 1.4e6 * t3, 2.9e5 * t3, 5.7e5 * t3);
    let a = (d12 + 2.0 * d66) / (d11 * d22).sqrt();
    let d_star = (d11 * d22 * (a + 1.0) / 2.0).sqrt();
    let f_crit = std::f64::consts::PI * (32.0 * d_star * 5.71 / 9.0).sqrt();
    assert!(
        (d["critical_force"].as_f64().unwrap() / f_crit - 1.0).abs() < 1e-12,
        "{d}"
    );
    let peak = s["contact"]["peak_force"].as_f64().unwrap();
    assert_eq!(
        d["peak_over_critical"].as_f64().unwrap(),
        peak / d["critical_force"].as_f64().unwrap()
    );

    let out = dir.path().join("threshold");
    let o = impactlab(&[
        "sweep",
        p,
        "--steps",
        "2100",
        "--find",
        "velocity",
        "--until",
        "delamination",
        "--giic",
        "5.71",
        "--no-cache",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    let t: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("threshold.json")).unwrap()).unwrap();
    assert!((t["target_force"].as_f64().unwrap() / f_crit - 1.0).abs() < 1e-12);
    let peaks = t["direct_peaks"].as_array().unwrap();
    assert!(
        peaks[0].as_f64().unwrap() < f_crit && f_crit <= peaks[1].as_f64().unwrap(),
        "{t}"
    );
    let (energy, joules) = (t["energy"].as_f64().unwrap(), t["energy_joules"].as_f64().unwrap());
    assert!((joules / (energy * 0.0254 * 4.4482216152605) - 1.0).abs() < 1e-15);
    assert!(stdout.contains(&format!("{joules:.6e} J")), "{stdout}");

    let refused = |args: &[&str], why: &str| {
        let o = impactlab(args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(why), "{args:?}: {stderr}");
    };
    let rod = deck("rod.bdf");
    let r = rod.to_str().unwrap();
    refused(&["run", r, "--giic", "5.71"], "has no plate with bending stiffness");
    refused(
        &["sweep", p, "--find", "velocity", "--until", "delamination"],
        "needs the interface's toughness: --giic",
    );
    refused(
        &["sweep", p, "--find", "velocity", "--until", "failure_index=1"],
        "expected peak_force=F or delamination",
    );
    refused(
        &["sweep", p, "--find", "velocity", "--until", "peak_force=-3"],
        "must be a positive number",
    );
    refused(&["run", p, "--giic", "0"], "--giic must be a positive number");
}
