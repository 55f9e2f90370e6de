//! Scenes: the two examples in `verification/scenes/` reproduce the paper's problems,
//! a scene and the deck it writes give the same answer, and only the effects the
//! scene calls for are simulated (the rest are listed as skipped, with why).

use crate::common;

use common::{impactlab, plate_structure, root};
use impactlab::run::run_model;

fn scene_text(name: &str) -> String {
    std::fs::read_to_string(root().join("verification/scenes").join(name)).unwrap()
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Goal: Eq. 5 with the paper's ball and rod gives the deck's K = 6.24e6 (to 0.1 %),
/// and the rod scene reproduces the deck's run (same contact end, same peak force).
#[test]
fn rod_scene_is_the_papers_rod() {
    let (s, model, _) = impactlab::scene::load(&root().join("verification/scenes/rod.toml")).unwrap();
    let (k, _) = impactlab::scene::contact_stiffness(&s).unwrap();
    assert!((k / 6.24e6 - 1.0).abs() < 1e-3, "K = {k}");
    let opts = impactlab::run::RunOptions::for_scene(&s);
    let r = run_model(&model, &opts).unwrap();
    let deck = common::run(&common::rod_model(), impactlab::integrate::Scheme::Newmark, None, None);
    let (a, b) = (
        r.summary.rod.as_ref().unwrap().contact_end_tcl.unwrap(),
        deck.summary.rod.as_ref().unwrap().contact_end_tcl.unwrap(),
    );
    assert!((a / b - 1.0).abs() < 2e-3, "{a} vs {b}");
    assert!((r.summary.contact.peak_force / deck.summary.contact.peak_force - 1.0).abs() < 2e-3);
}

/// Goal: `impactlab scene S --to-deck F` writes a deck whose run is the scene's run:
/// the contact force histories are identical.
#[test]
fn scene_and_its_deck_give_the_same_answer() {
    let dir = tempfile::tempdir().unwrap();
    let d = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let scene = root().join("verification/scenes/rod.toml");
    let o = impactlab(&["scene", scene.to_str().unwrap(), "--to-deck", &d("rod-scene.bdf")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("Hertz K = 6.2"));
    assert!(impactlab(&["run", scene.to_str().unwrap(), "--out", &d("a")])
        .status
        .success());
    assert!(impactlab(&["run", &d("rod-scene.bdf"), "--out", &d("b")])
        .status
        .success());
    let force = |dir: &str| -> Vec<String> {
        let h = std::fs::read_to_string(format!("{dir}/history.csv")).unwrap();
        h.lines()
            .skip(1)
            .map(|l| l.split(',').nth(1).unwrap().to_string())
            .collect()
    };
    let (a, b) = (force(&d("a")), force(&d("b")));
    assert_eq!(a.len(), 2501);
    assert_eq!(a, b);
}

/// Goal: the plate scene skips the membrane DOFs (a transverse impact without
/// membrane-bending coupling): the contact force equals the run that solves them to
/// 1e-10 relative, with fewer DOFs; the summary lists the effects simulated and
/// skipped; the run stops 20 µs after separation. (13×13 mesh, for speed.)
#[test]
fn plate_scene_simulates_only_what_it_needs() {
    let dir = tempfile::tempdir().unwrap();
    let text = scene_text("plate.toml")
        .replace("mesh = 49", "mesh = 13")
        .replace("gages = [3325, 4125]", "gages = []");
    let p = write(dir.path(), "plate13.toml", &text);
    let (s, model, _) = impactlab::scene::load(&p).unwrap();
    let opts = impactlab::run::RunOptions::for_scene(&s);
    let skip = run_model(&model, &opts).unwrap();
    let all = run_model(
        &model,
        &impactlab::run::RunOptions {
            skip_inert: false,
            ..opts.clone()
        },
    )
    .unwrap();
    assert!(skip.summary.model.solved_dofs < all.summary.model.solved_dofs);
    let peak = all.summary.contact.peak_force;
    for (x, y) in skip.series.force.iter().zip(&all.series.force) {
        assert!((x - y).abs() <= 1e-10 * peak);
    }
    let e = impactlab::scene::effects(&s, skip.summary.model.inert_dofs_skipped, skip.summary.run.steps_done);
    assert!(e.skipped.iter().any(|x| x.name == "membrane"));
    assert!(e.simulated.iter().any(|x| x.name == "energy ledger"));
    let end = skip.summary.contact.intervals[0][1];
    let last = *skip.series.time.last().unwrap();
    assert!(
        last >= end + 20e-6 && last < end + 21e-6,
        "stopped at {last:e}, separation {end:e}"
    );
}

/// Goal: no ledger asked for, none computed: energy.csv has only its header and the
/// summary's energy entries are null.
#[test]
fn no_ledger_asked_none_computed() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "rod.toml",
        &scene_text("rod.toml").replace("ledger = true", "ledger = false"),
    );
    let out = dir.path().join("o");
    let o = impactlab(&["run", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(out.join("energy.csv")).unwrap().lines().count(),
        1
    );
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert!(s["energy"]["max_relative_error"].is_null());
    assert!(s["effects"]["skipped"]
        .as_array()
        .unwrap()
        .iter()
        .any(|x| x["name"] == "energy ledger"));
}

/// Goal: an effect the model cannot represent is an error (exit 2) that says so.
#[test]
fn unrepresentable_effects_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    for (effect, says) in [
        ("rotary_inertia = true", "rotary_inertia"),
        ("gravity = true", "gravity"),
    ] {
        let p = write(
            dir.path(),
            "s.toml",
            &scene_text("rod.toml").replace("ledger = true", &format!("ledger = true\n{effect}")),
        );
        let o = impactlab(&[
            "run",
            p.to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("s.toml") && err.contains(says), "{err}");
    }
}

/// Goal: a scene's damping (`damping = { ratio, at }`) runs as the structural damping
/// it stands for: its deck carries PARAM G = 2·ratio and W3 = 2π·at, the run books
/// the energy dissipated (the ledger still closing), and the effect is listed as
/// simulated with its ratio. Model: the paper's rod scene, ratio 0.02 at 20 kHz (about
/// the contact's own frequency). A ratio of 1 or more is refused (exit 2).
#[test]
fn a_scenes_damping_runs_as_the_structural_damping_it_stands_for() {
    let dir = tempfile::tempdir().unwrap();
    let text = scene_text("rod.toml").replace(
        "ledger = true ",
        "damping = { ratio = 0.02, at = 20000.0 }\nledger = true ",
    );
    let p = write(dir.path(), "s.toml", &text);
    let deck = dir.path().join("s.bdf");
    let o = impactlab(&["scene", p.to_str().unwrap(), "--to-deck", deck.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let d = std::fs::read_to_string(&deck).unwrap();
    assert!(d.contains("PARAM,G,0.04\nPARAM,W3,125663.70614359173\n"), "{d}");
    let out = dir.path().join("o");
    let o = impactlab(&["run", p.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let dissipated = s["energy"]["damping"]["dissipated"].as_f64().unwrap();
    assert!(
        dissipated > 0.0 && dissipated < s["energy"]["initial"].as_f64().unwrap(),
        "{s}"
    );
    // Newmark's own O(Δt²) balance on the rod (1.6e-5 undamped; measured 1.6e-5).
    assert!(
        s["energy"]["max_relative_error"].as_f64().unwrap() < 1e-4,
        "{}",
        s["energy"]
    );
    assert!(s["effects"]["simulated"]
        .as_array()
        .unwrap()
        .iter()
        .any(|x| x["name"] == "damping" && x["reason"].as_str().unwrap().contains("0.02 of critical")));
    let bad = write(dir.path(), "b.toml", &text.replace("ratio = 0.02", "ratio = 1.5"));
    let o = impactlab(&["run", bad.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("effects.damping.ratio"));
}

/// Goal: options on a scene either apply or are refused. `--scheme newmark` overrides
/// a scene that asks for `energy` (the summary says which ran); `--all-dofs` and
/// `--allow-unknown`, which a scene decides itself, are refused (exit 2) naming the
/// scene and what to set instead.
#[test]
fn command_line_options_on_a_scene_apply_or_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let text = scene_text("rod.toml").replace("scheme = \"newmark\"", "scheme = \"energy\"");
    assert!(text.contains("scheme = \"energy\""));
    let p = write(dir.path(), "rod.toml", &text);
    let scheme_of = |args: &[&str], out: &str| -> String {
        let out = dir.path().join(out);
        let mut all = vec!["run", p.to_str().unwrap(), "--out", out.to_str().unwrap()];
        all.extend_from_slice(args);
        let o = impactlab(&all);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let s: impactlab::run::Summary =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        s.run.scheme.name().to_string()
    };
    assert_eq!(scheme_of(&[], "a"), "energy");
    assert_eq!(scheme_of(&["--scheme", "newmark"], "b"), "newmark");
    for flag in ["--all-dofs", "--allow-unknown"] {
        let o = impactlab(&[
            "run",
            p.to_str().unwrap(),
            flag,
            "--out",
            dir.path().join("c").to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{flag}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("rod.toml") && err.contains("effects.membrane"), "{err}");
    }
}

/// Goal: a mesh the generators cannot number is refused while the scene is read,
/// before any of its deck is generated (10^12 rod elements would otherwise be
/// written out line by line; rod grid 999 would be the impactor's, plate grid ids
/// 1000·row + col repeat past 998 a side).
#[test]
fn a_mesh_too_large_to_number_is_refused_before_it_is_generated() {
    let at = std::path::Path::new("big.toml");
    let rod = scene_text("rod.toml");
    for n in ["998", "1000000000000"] {
        let e = impactlab::scene::parse(at, &rod.replace("elements = 144 ", &format!("elements = {n} ")))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&format!(
                "target.elements must be even, from 2 to 996 (grid 999 is the impactor), not {n}"
            )),
            "{e}"
        );
    }
    let plate = scene_text("plate.toml");
    let mesh = plate.lines().find(|l| l.starts_with("mesh")).unwrap();
    let e = impactlab::scene::parse(at, &plate.replace(mesh, "mesh = 999"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("target.mesh must be odd, from 3 to 997, not 999"), "{e}");
    let s = impactlab::scene::parse(at, &plate.replace(mesh, "mesh = 101")).unwrap();
    let deck = impactlab::scene::to_deck(&s).unwrap();
    assert!(
        deck.contains("EPOINT,1000001"),
        "the indentation point is above every grid id"
    );
    impactlab::model_from_text("big", &deck).unwrap();
}

/// Goal: transverse shear is an effect a scene asks for. Without
/// `target.transverse_shear` the plate is thin and the effect is listed as skipped;
/// with it the deck's PSHELL names a MID3 MAT2 of those moduli, every element is the
/// shear-deformable plate, the effect is listed as simulated, and the softer plate
/// lasts longer in contact. A matrix that is not positive definite is refused, naming
/// the field. Model: the paper's plate scene on a 13 × 13 mesh, G1Z = G2Z = 5.7e5 psi.
#[test]
fn plate_scene_asks_for_transverse_shear() {
    let dir = tempfile::tempdir().unwrap();
    let thin_text = scene_text("plate.toml")
        .replace("mesh = 49", "mesh = 13")
        .replace("gages = [3325, 4125]", "gages = []");
    let shear_text = thin_text.replace("e33 = 1.4e6", "e33 = 1.4e6\ntransverse_shear = [5.7e5, 0.0, 5.7e5]");
    let mut contact = Vec::new();
    for (name, text, on) in [("thin.toml", &thin_text, false), ("shear.toml", &shear_text, true)] {
        let p = write(dir.path(), name, text);
        let (s, model, _) = impactlab::scene::load(&p).unwrap();
        let deck = impactlab::scene::to_deck(&s).unwrap();
        assert_eq!(deck.contains("PSHELL,1,101,0.15,201,1.0,301"), on, "{deck}");
        let run = run_model(&model, &impactlab::run::RunOptions::for_scene(&s)).unwrap();
        let shear_elements = run.summary.model.transverse_shear_elements;
        assert_eq!(shear_elements, on.then_some(169));
        let e = impactlab::scene::effects(&s, 0, 0);
        let listed = if on { &e.simulated } else { &e.skipped };
        assert!(listed.iter().any(|x| x.name == "transverse shear"), "{e:?}");
        let [start, end] = run.summary.contact.intervals[0];
        contact.push(end - start);
    }
    assert!(contact[1] > contact[0], "{contact:?}");
    let p = write(
        dir.path(),
        "bad.toml",
        &thin_text.replace("e33 = 1.4e6", "e33 = 1.4e6\ntransverse_shear = [1.0, 2.0, 1.0]"),
    );
    let err = impactlab::scene::load(&p).map(|_| ()).expect_err("refused").to_string();
    assert!(
        err.contains("target.transverse_shear") && err.contains("positive definite"),
        "{err}"
    );
}

/// A scene striking `deck` (a file beside it) at `strike` (TOML lines of [impactor]).
fn deck_scene(deck: &str, strike: &str) -> String {
    format!(
        "title = \"struck deck\"\nunits = {{ length = \"in\", force = \"lbf\", time = \"s\" }}\n\
         [target]\nkind = \"deck\"\ndeck = \"{deck}\"\n\
         [impactor]\n{strike}\nmass = 8.096e-5\nradius = 0.1875\nmaterial = {{ e = 30.0e6, nu = 0.3 }}\n\
         velocity = 1470.0\n[contact]\nk = 7.779e5\n[run]\ndt = 1e-7\nend = 300e-6\n"
    )
}

/// Goal: an impact anywhere: a scene whose target is the user's own structural deck
/// (the paper's plate, 15×15, its structure alone: SOL 103, no impactor) struck at
/// its centre reproduces the paper's deck on the same mesh. The scene spreads the
/// contact over the centre element's grids by their shape functions there (¼ each)
/// and writes the impactor itself. Reference: `impactlab mesh plate --n 15`, run
/// alike. Tolerance: the contact duration to 1e-5 and the peak force to 2e-4: the
/// paper's deck scales its grids' NOLIN3 loads by 1.945e5 where K/4 = 194475 (its
/// ledger books the 1.3e-4 difference as external work); the scene's are K·Nᵢ to
/// the last bit, so its ledger has no external work at all.
#[test]
fn a_deck_struck_at_its_centre_is_the_papers_plate() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "plate.bdf", &plate_structure(15));
    let scene = write(
        dir.path(),
        "strike.toml",
        &deck_scene("plate.bdf", "at = [0.0, 0.0, 0.0]\ndirection = \"normal\""),
    );
    let (s, model, deck) = impactlab::scene::load(&scene).unwrap();
    assert!(
        deck.contains("$ along (0.0, 0.0, 1.0); contact weights 808: 0.25, 809: 0.25, 909: 0.25, 908: 0.25"),
        "{deck}"
    );
    let r = run_model(&model, &impactlab::run::RunOptions::for_scene(&s)).unwrap();
    let paper = impactlab::model_from_text("plate15.bdf", &impactlab::mesh::plate_deck(15).unwrap()).unwrap();
    let p = common::run(&paper, impactlab::integrate::Scheme::Newmark, None, Some(3000));
    let (a, b) = (r.summary.contact.duration.unwrap(), p.summary.contact.duration.unwrap());
    assert!((a / b - 1.0).abs() < 1e-5, "duration {a} vs {b}");
    let (fa, fb) = (r.summary.contact.peak_force, p.summary.contact.peak_force);
    assert!((fa / fb - 1.0).abs() < 2e-4, "peak {fa} vs {fb}");
    assert_eq!(r.summary.energy.external_work, Some(0.0));
    assert!(r.summary.energy.max_relative_error.unwrap() < 1e-5);
}

/// Goal: a point off the structure is refused, naming the nearest element and how
/// far it is; a direction that is no vector is refused; a grid can be struck.
#[test]
fn a_deck_scene_refuses_a_point_off_the_structure() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "plate.bdf", &plate_structure(9));
    let off = write(
        dir.path(),
        "off.toml",
        &deck_scene("plate.bdf", "at = [3.5, 0.0, 0.0]\ndirection = [0.0, 0.0, 1.0]"),
    );
    let e = impactlab::scene::load(&off).unwrap_err().to_string();
    assert!(e.contains("is on no shell's surface: the nearest is CQUAD4 509"), "{e}");
    let bad = write(
        dir.path(),
        "bad.toml",
        &deck_scene("plate.bdf", "at = [0.0, 0.0, 0.0]\ndirection = [0.0, 0.0, 0.0]"),
    );
    let e = impactlab::scene::load(&bad).unwrap_err().to_string();
    assert!(
        e.contains("impactor.direction must be three numbers, not all zero"),
        "{e}"
    );
    let grid = write(
        dir.path(),
        "grid.toml",
        &deck_scene("plate.bdf", "grid = 505\ndirection = \"normal\""),
    );
    let (_, _, deck) = impactlab::scene::load(&grid).unwrap();
    assert!(deck.contains("contact weights 505: 1.0"), "{deck}");
}

/// Goal: a struck deck keeps its constraints however they are written, and leaves its
/// static loads out. Model: the plate structure (9×9) with its SPC1 cards rewritten
/// as set 2, joined to set 1 by SPCADD, its first edge's grids held by SPC cards
/// instead, and a FORCE and a GRAV in it (a SOL 101 deck's loads). Reference: the
/// plate structure as written, struck alike. Exact: the same DOFs solved, the same
/// contact duration.
#[test]
fn a_struck_deck_keeps_its_spc_and_spcadd_and_leaves_its_loads_out() {
    let dir = tempfile::tempdir().unwrap();
    let plain = plate_structure(9);
    let mut rewritten = String::new();
    for line in plain.lines() {
        if let Some(rest) = line.strip_prefix("SPC1,1,123456,101,THRU,110") {
            assert!(rest.is_empty());
            for g in 101..=110 {
                rewritten += &format!("SPC,2,{g},123456,0.0\n");
            }
        } else if let Some(rest) = line.strip_prefix("SPC1,1,") {
            rewritten += &format!("SPC1,2,{rest}\n");
        } else if line == "BEGIN BULK" {
            rewritten += "BEGIN BULK\nSPCADD,1,2\nFORCE,7,505,,1.0,0.0,0.0,1.0\nGRAV,7,,386.1,0.0,0.0,-1.0\n";
        } else {
            rewritten += line;
            rewritten += "\n";
        }
    }
    assert!(rewritten.contains("SPC,2,110,123456"));
    write(dir.path(), "plain.bdf", &plain);
    write(dir.path(), "rewritten.bdf", &rewritten);
    let strike = "at = [0.0, 0.0, 0.0]\ndirection = \"normal\"";
    let load = |deck: &str| {
        let scene = write(dir.path(), &format!("{deck}.toml"), &deck_scene(deck, strike));
        impactlab::scene::load(&scene).unwrap()
    };
    let ((s, a, _), (_, b, text)) = (load("plain.bdf"), load("rewritten.bdf"));
    assert!(
        text.contains("SPCADD,1,2") && !text.contains("FORCE") && !text.contains("GRAV"),
        "{text}"
    );
    assert_eq!(a.dofs, b.dofs);
    let o = impactlab::run::RunOptions::for_scene(&s);
    let (ra, rb) = (run_model(&a, &o).unwrap(), run_model(&b, &o).unwrap());
    assert_eq!(ra.summary.contact.duration, rb.summary.contact.duration);
}
