//! Damage onset and the threshold impact: the delamination threshold and the plies'
//! failure indices in the run's summary, and `sweep --find velocity --until …`.

use crate::common;

use common::{deck, hill, impactlab, pcomp_with_ft, rod_model, ALLOWABLES};
use impactlab::run::{run_model, RunOptions};
use impactlab::study::threshold::{find_velocity, Until, BRACKET_WIDTH};
use indicatif::ProgressBar;

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
        t.direct_values[0] < peak && peak <= t.direct_values[1],
        "{:?}",
        t.direct_values
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
    assert!((t["target_value"].as_f64().unwrap() / f_crit - 1.0).abs() < 1e-12);
    let peaks = t["direct_values"].as_array().unwrap();
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
        "--until failure_index needs failure indices: a PCOMP with FT",
    );
    refused(
        &["sweep", p, "--find", "velocity", "--until", "bond_index=1"],
        "--until bond_index needs bond indices: a PCOMP with SB and FT",
    );
    refused(
        &["sweep", p, "--find", "velocity", "--until", "strain=1"],
        "expected peak_force=F, delamination, failure_index=L or bond_index=L",
    );
    refused(
        &["sweep", p, "--find", "velocity", "--until", "peak_force=-3"],
        "must be a positive number",
    );
    refused(&["run", p, "--giic", "0"], "--giic must be a positive number");
}

/// Goal: the summary's failure indices are the theory applied to the ply stresses the
/// run writes. From `history.csv` alone, by its header names, this test computes
/// Tsai-Hill (X by the sign of σ1, Y by that of σ2) and the maximum-stress ratio at
/// every ply's bottom and top of the written elements at every row: the summary's
/// largest index, its element, ply, face and time, and the first time any reaches 1
/// are those, to round-off. Model: the paper's plate as its cross-ply, FT = HILL,
/// 600 steps.
#[test]
fn failure_indices_are_the_theory_on_the_written_ply_stresses() {
    let dir = tempfile::tempdir().unwrap();
    let path = pcomp_with_ft(dir.path(), "HILL", ALLOWABLES);
    let out = dir.path().join("run");
    let o = impactlab(&[
        "run",
        path.to_str().unwrap(),
        "--steps",
        "600",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let mut r = csv::Reader::from_path(out.join("history.csv")).unwrap();
    let headers: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Vec<f64>> = r
        .records()
        .map(|x| x.unwrap().iter().map(|v| v.parse().unwrap()).collect())
        .collect();
    let (xt, xc, yt, yc, sh) = (1.54e5, 8.85e4, 4.5e3, 1.71e4, 1.04e4);
    // (index, time, element, ply, face) of the largest, and the first time ≥ 1.
    let mut best_hill = (f64::MIN, 0.0, String::new(), String::new(), String::new());
    let mut most = best_hill.clone();
    let (mut first_hill, mut first_most) = (f64::INFINITY, f64::INFINITY);
    let mut points = 0;
    for (k, h) in headers.iter().enumerate() {
        let Some(rest) = h
            .strip_prefix("ply_stress_")
            .and_then(|r| r.strip_suffix("_11 [lbf/in^2]"))
        else {
            continue;
        };
        points += 1;
        let parts: Vec<&str> = rest.split('_').collect();
        let (eid, ply, face) = (parts[0], parts[1].trim_start_matches('p'), parts[2]);
        assert_eq!(headers[k + 1], format!("ply_stress_{rest}_22 [lbf/in^2]"));
        assert_eq!(headers[k + 2], format!("ply_stress_{rest}_12 [lbf/in^2]"));
        for row in &rows {
            let (s1, s2, t) = (row[k], row[k + 1], row[k + 2]);
            let h_index = hill(s1, s2, t);
            let ratio = |v: f64, tension: f64, compression: f64| if v >= 0.0 { v / tension } else { -v / compression };
            let m_index = ratio(s1, xt, xc).max(ratio(s2, yt, yc)).max(t.abs() / sh);
            for (index, best, first) in [
                (h_index, &mut best_hill, &mut first_hill),
                (m_index, &mut most, &mut first_most),
            ] {
                if index > best.0 {
                    *best = (index, row[0], eid.into(), ply.into(), face.into());
                }
                if index >= 1.0 {
                    *first = first.min(row[0]);
                }
            }
        }
    }
    // 3 written elements × 15 plies × bottom and top.
    assert_eq!(points, 90);
    let f = &s["failure"];
    for (key, (index, time, eid, ply, face), first) in [
        ("theory", best_hill.clone(), first_hill),
        ("max_stress", most, first_most),
    ] {
        let got = &f[key];
        assert!(
            (got["largest"].as_f64().unwrap() / index - 1.0).abs() < 1e-12,
            "{key}: {got} vs {index}"
        );
        assert_eq!(got["time"].as_f64().unwrap(), time, "{key}");
        assert_eq!(got["element"].to_string(), eid, "{key}");
        assert_eq!(got["ply"].to_string(), ply, "{key}");
        assert_eq!(
            got["face"].as_str().unwrap(),
            if face == "bot" { "bottom" } else { "top" },
            "{key}"
        );
        assert_eq!(
            got["first_reaches_one"].as_f64().unwrap_or(f64::INFINITY),
            first,
            "{key}"
        );
    }
    assert_eq!(f["theory"]["name"], "HILL");
    assert_eq!(f["max_stress"]["name"], "MAXSTRESS");
    // The struck plate fails its first ply at the paper's impact: a point load's plate
    // stresses under the impactor (see docs/src/reference/laminates.md on what they
    // are worth).
    assert!(best_hill.0 > 1.0, "{best_hill:?}");
}

/// Goal: a failure theory whose allowables are missing is an input error (exit 2) that
/// names the PCOMP, the ply, its material and the missing field: HILL without S,
/// HOFF over strain allowables (STRN = 1.0); nothing is written. TSAI without F12 runs,
/// with NASTRAN's F12 = 0 and a warning that says so.
#[test]
fn a_theory_without_its_allowables_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (ft, cont, why) in [
        (
            "HILL",
            ",,,1.54+5,8.85+4,4.5+3,1.71+4",
            "FT = HILL needs the allowable S, which is blank",
        ),
        (
            "HOFF",
            ",,,0.02,0.015,0.004,0.012,0.018,+M2\n+M2,,,1.0",
            "FT = HOFF reads stresses, but the allowables are strains (STRN = 1.0)",
        ),
    ] {
        let path = pcomp_with_ft(dir.path(), ft, cont);
        let out = dir.path().join(format!("out-{ft}"));
        let o = impactlab(&[
            "run",
            path.to_str().unwrap(),
            "--steps",
            "5",
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{ft}: {stderr}");
        let want = format!("PCOMP 1: ply 1 (material 8): {why}");
        assert!(stderr.contains(&want), "{ft}: want {want:?} in {stderr}");
        assert!(
            stderr.contains(&format!("plate-{}.bdf:", ft.to_lowercase())),
            "{stderr}"
        );
        assert!(!out.exists(), "{ft}");
    }
}

/// The cross-ply with FT = `ft` run 40 steps twice, its MAT8 continuation `blank`
/// (fields left blank) and `written` (NASTRAN's defaults for them written out): both
/// exit 0, the blank one's stderr holds every one of `warnings` and the written one's
/// none; their `history.csv` texts.
fn blank_and_written(ft: &str, blank: &str, written: &str, warnings: &[&str]) -> [String; 2] {
    let dir = tempfile::tempdir().unwrap();
    [("blank", blank), ("written", written)].map(|(name, cont)| {
        let sub = dir.path().join(name);
        std::fs::create_dir_all(&sub).unwrap();
        let path = pcomp_with_ft(&sub, ft, cont);
        let out = sub.join("out");
        let o = impactlab(&[
            "run",
            path.to_str().unwrap(),
            "--steps",
            "40",
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{name}: {stderr}");
        for w in warnings {
            assert_eq!(stderr.contains(w), name == "blank", "{name}: {w:?} in {stderr}");
        }
        std::fs::read_to_string(out.join("history.csv")).unwrap()
    })
}

/// Goal: a TSAI laminate whose MAT8 leaves F12 blank runs with NASTRAN's F12 = 0 and
/// says so: exit 0, a warning naming the PCOMP, and the same history, ply indices
/// included, as the deck with F12 = 0.0 written out.
#[test]
fn tsai_with_a_blank_f12_runs_as_with_f12_zero() {
    let [blank, written] = blank_and_written(
        "TSAI",
        ALLOWABLES,
        &format!("{ALLOWABLES},+M2\n+M2,,0.0"),
        &["FT = TSAI with a ply whose MAT8 leaves F12 blank: F12 = 0 there"],
    );
    assert!(blank.contains("ply_"), "ply columns written");
    assert_eq!(blank, written);
}

/// Goal: a MAT8 whose Xc and Yc are blank takes Xt and Yt for them, as NASTRAN does,
/// and says so: the cross-ply with FT = HILL runs (exit 0) with a warning on each
/// field, and its history, ply indices included, is the one with Xc = Xt and Yc = Yt
/// written out.
#[test]
fn blank_compressive_allowables_are_the_tensile_ones() {
    let [blank, written] = blank_and_written(
        "HILL",
        ",,,1.54+5,,4.5+3,,1.04+4",
        ",,,1.54+5,1.54+5,4.5+3,4.5+3,1.04+4",
        &[
            "(Xc): is blank: Xc = Xt = 1.54e5, as NASTRAN takes it",
            "(Yc): is blank: Yc = Yt = 4.5e3, as NASTRAN takes it",
        ],
    );
    assert_eq!(blank, written);
}

/// Goal: allowables so small that the struck plate's stresses cannot be divided by
/// them in double precision (1e-300 psi: HILL's σ²/X² overflows) end the run with exit
/// 3 and a message naming the theory, element, ply and stresses, and nothing is
/// written; the summary never carries a null where it promises a number (what it did
/// before: `"largest": null`). A run the energy guard stops first keeps the guard's
/// error and its partial outputs, without a failure summary. With the glass/epoxy
/// allowables the same run succeeds.
#[test]
fn allowables_too_small_for_double_precision_end_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let run = |allowables: &str| {
        let path = pcomp_with_ft(dir.path(), "HILL", allowables);
        let out = dir.path().join("out");
        let o = impactlab(&[
            "run",
            path.to_str().unwrap(),
            "--steps",
            "20",
            "--out",
            out.to_str().unwrap(),
        ]);
        (o, out)
    };
    let tiny = ",,,1.0-300,1.0-300,1.0-300,1.0-300,1.0-300";
    let (o, out) = run(tiny);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{stderr}");
    assert!(
        stderr.contains("the HILL failure index of element ") && stderr.contains(" is inf at t = "),
        "{stderr}"
    );
    assert!(stderr.contains("its MAT8 allowables are too small"), "{stderr}");
    assert!(!out.exists());
    // Stopped by the energy guard (1e-9) at step 1, a history row every step: the
    // guard's error and its partial outputs stand, the row's index overflowing as well.
    let path = pcomp_with_ft(dir.path(), "HILL", tiny);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("TSTEP, 1,2000, 1.0-7, 10\n"));
    std::fs::write(
        &path,
        text.replace("TSTEP, 1,2000, 1.0-7, 10\n", "TSTEP, 1,2000, 1.0-7, 1\n"),
    )
    .unwrap();
    let guarded = dir.path().join("guarded");
    let o = impactlab(&[
        "run",
        path.to_str().unwrap(),
        "--steps",
        "20",
        "--max-energy-error",
        "1e-9",
        "--out",
        guarded.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{stderr}");
    assert!(stderr.contains("energy guard: relative energy error"), "{stderr}");
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(guarded.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["run"]["complete"], false);
    assert!(s["failure"].is_null(), "{}", s["failure"]);
    let (o, out) = run(ALLOWABLES);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert!(s["failure"]["theory"]["largest"].as_f64().unwrap().is_finite());
}

/// Goal: `--until failure_index=1` finds the impact speed of first-ply failure: the
/// direct engine puts the largest HILL index below 1 at the bracket's low end and at or
/// above it at its high end, and the paper's speed (index far above 1) is above it.
/// Model: the plate as its cross-ply, FT = HILL, 1000 steps.
#[test]
fn first_ply_failure_threshold_is_bracketed_by_the_direct_engine() {
    let dir = tempfile::tempdir().unwrap();
    let path = pcomp_with_ft(dir.path(), "HILL", ALLOWABLES);
    let out = dir.path().join("threshold");
    let o = impactlab(&[
        "sweep",
        path.to_str().unwrap(),
        "--steps",
        "1000",
        "--find",
        "velocity",
        "--until",
        "failure_index=1",
        "--no-cache",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("threshold.json")).unwrap()).unwrap();
    let v = t["direct_values"].as_array().unwrap();
    let (lo, hi) = (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
    assert!(lo < 1.0 && 1.0 <= hi, "{t}");
    assert_eq!(t["target_value"].as_f64(), Some(1.0));
    let speed = t["velocity"].as_f64().unwrap();
    assert!(speed > 0.0 && speed < 1470.0, "{t}");
}

/// Goal: the interlaminar shear stresses and PCOMP's bond index on a plate flexible in
/// transverse shear. Reference: at gage A (element 3325) the 0°/90° interface of the
/// cross-ply [0₅/90₅/0₅] (the top of ply 5, z = −t/6) carries the equilibrium
/// stresses worked by hand from the MAT8 (Q11 = E1/(1 − ν12ν21), Q22 = E2/(…)):
/// τ1z = Qx·Q11(t²/4 − t²/36)/(2 D11), τ2z = Qy·Q22(…)/(2 D22), D from the three
/// layers, against the element's own shear force columns; the summary's bond index is
/// the largest max(|τ1z|, |τ2z|)/SB over every written interface and row, read back
/// from the history by its headers. The same laminate without G1Z/G2Z (thin) has no
/// interlaminar columns and no bond index. Model: the cross-ply with transverse shear
/// (its deck's FT = HILL, SB = 8000 psi), 600 steps. Tolerance: 1e-10 of the peak (round-off of
/// one product).
#[test]
fn bond_index_reads_the_equilibrium_interlaminar_shear() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(deck("plate-pcomp-shear.bdf")).unwrap();
    let mat8 = "MAT8,8,5.735+6,1.2855+6,0.2231,5.7+5,5.7+5,4.59+5,1.8-4,+M1";
    assert!(text.contains(mat8) && text.contains("PCOMP,1,,,8.0+3,HILL,,,,+P0"));
    let path = dir.path().join("plate-bond.bdf");
    std::fs::write(&path, &text).unwrap();
    std::fs::copy(deck("plate-mesh-49x49.bdf"), dir.path().join("plate-mesh-49x49.bdf")).unwrap();
    let opts = RunOptions {
        steps: Some(600),
        ..Default::default()
    };
    let model = impactlab::load_deck(&path, Default::default()).unwrap().0;
    let run = run_model(&model, &opts).unwrap();
    let named = |name: &str| {
        let j = run
            .history_columns
            .iter()
            .position(|c| c.name() == name)
            .unwrap_or_else(|| panic!("no column {name}"));
        run.history.iter().map(|r| r[j]).collect::<Vec<f64>>()
    };
    let (e1, e2, nu12) = (5.735e6, 1.2855e6, 0.2231);
    let d = 1.0 - nu12 * nu12 * e2 / e1;
    let (q11, q22, h) = (e1 / d, e2 / d, 0.15f64);
    let bending =
        |face: f64, core: f64| (2.0 * face * (h.powi(3) / 8.0 - h.powi(3) / 216.0) + core * h.powi(3) / 108.0) / 3.0;
    let lift = h * h / 4.0 - h * h / 36.0;
    let per = [
        q11 * lift / (2.0 * bending(q11, q22)),
        q22 * lift / (2.0 * bending(q22, q11)),
    ];
    let forces = [named("shear_force_3325_qx"), named("shear_force_3325_qy")];
    let stresses = [named("ply_stress_3325_p5_top_1z"), named("ply_stress_3325_p5_top_2z")];
    let peak = stresses[1].iter().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(peak > 100.0, "gage A's interface is loaded: {peak}");
    for c in 0..2 {
        for (tau, q) in stresses[c].iter().zip(&forces[c]) {
            assert!((tau - per[c] * q).abs() <= 1e-10 * peak, "{c}: {tau} vs {}", per[c] * q);
        }
    }
    let mut largest = 0.0f64;
    for c in run.history_columns.iter().map(|c| c.name()) {
        if c.ends_with("_1z") || c.ends_with("_2z") {
            largest = named(&c).iter().fold(largest, |a, x| a.max(x.abs() / 8.0e3));
        }
    }
    let bond = run
        .summary
        .failure
        .as_ref()
        .and_then(|f| f.bond.clone())
        .expect("a bond index");
    assert_eq!(bond.name, "BOND");
    assert!(
        (bond.largest - largest).abs() <= 1e-12 * largest,
        "{} vs {largest}",
        bond.largest
    );
    assert_eq!(bond.face, "top");

    let thin = text.replace(mat8, "MAT8,8,5.735+6,1.2855+6,0.2231,5.7+5,,,1.8-4,+M1");
    std::fs::write(&path, thin).unwrap();
    let model = impactlab::load_deck(&path, Default::default()).unwrap().0;
    let run = run_model(&model, &opts).unwrap();
    assert!(run.history_columns.iter().all(|c| !c.name().ends_with("z")));
    let failure = run.summary.failure.expect("HILL's indices");
    assert!(failure.bond.is_none());
}
