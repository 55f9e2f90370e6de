//! Damped transient decks (CDAMP, CVISC, CBUSH's B, PARAM G with W3, PARAM ALPHA1
//! and ALPHA2) run by `impactlab run` as a user runs them: each against the damped
//! spring-mass's closed form, and their ledger closing with the energy dissipated.

use crate::common;

use impactlab::verify::printed::{read_run_histories, Histories};

/// Writes `deck` into `dir` and runs it with `scheme` and `extra` arguments into
/// `dir/out`: that directory and the command's output.
fn run_in(
    dir: &std::path::Path,
    deck: &str,
    scheme: &str,
    extra: &[&str],
) -> (std::path::PathBuf, std::process::Output) {
    let path = dir.join("deck.bdf");
    std::fs::write(&path, deck).unwrap();
    let out = dir.join("out");
    let mut args = vec![
        "run",
        path.to_str().unwrap(),
        "--scheme",
        scheme,
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let o = common::impactlab(&args);
    (out, o)
}

/// Runs a deck (written into a temporary directory) with `scheme` and `extra`
/// arguments: its displacement histories, summary and `energy.csv` header, or its
/// standard error when it fails.
fn run(deck: &str, scheme: &str, extra: &[&str]) -> Result<(Histories, serde_json::Value, String), String> {
    let dir = tempfile::tempdir().unwrap();
    let (out, o) = run_in(dir.path(), deck, scheme, extra);
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).into_owned());
    }
    let summary = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let energy = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    let header = energy.lines().next().unwrap().to_string();
    Ok((read_run_histories(&out).unwrap(), summary, header))
}

/// The spring of [`spring_mass`]: CELAS2 k = 100 on SPOINT 1.
const SPRING: &str = "CELAS2,1,100.,1\n";

/// A scalar spring-mass (CELAS2 k = 100, CMASS2 m = 1 on SPOINT 1: ω = 10) released
/// at rest from u0 = 0.01 (TIC), 2000 steps of 1e-3 (about 3 periods), with `damping`
/// cards added.
fn spring_mass(damping: &str) -> String {
    oscillator(SPRING, damping)
}

/// [`spring_mass`] with its spring given by `spring` (k = 100 on SPOINT 1).
fn oscillator(spring: &str, damping: &str) -> String {
    format!(
        "SOL 9\nCEND\nDISP = ALL\nIC = 1\nTSTEP = 1\nBEGIN BULK\nSPOINT,1\n{spring}CMASS2,2,1.0,1\n\
         TIC,1,1,0,0.01\nTSTEP,1,2000,1.0-3,1\n{damping}ENDDATA\n"
    )
}

/// u0 e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t): the damped oscillator released at rest.
fn released(u0: f64, omega: f64, zeta: f64, t: f64) -> f64 {
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    u0 * (-zeta * omega * t).exp() * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin())
}

/// The largest difference of a history from the closed form with ζ = 0.02, relative
/// to u0.
fn worst(u: &[(f64, f64)]) -> f64 {
    u.iter()
        .map(|&(t, v)| (v - released(0.01, 10.0, 0.02, t)).abs() / 0.01)
        .fold(0.0, f64::max)
}

/// Goal: a spring-damper-mass decays as the closed form whichever way its damping is
/// given: a scalar damper (CDAMP2, b = 0.4: ζ = b/(2mω) = 0.02), structural damping
/// turned viscous (PARAM G 0.04 at W3 = 10 = ω: c = G·k/W3 = 0.4, as the manual's
/// equivalence at W3), Rayleigh damping (ALPHA1 = 0.2, ALPHA2 = 0.002: ζ = α₁/(2ω) +
/// α₂ω/2 = 0.01 + 0.01), a damper on a property (CDAMP1 with PDAMP), and the
/// spring's own structural damping GE = 0.04 turned viscous at PARAM W4 = 10 = ω (on
/// a CELAS2, and on a CELAS1's PELAS: c = GE·k/W4 = 0.4). Reference:
/// u = u0 e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t). Tolerance: 2e-3 of u0 over three
/// periods at 63 steps a period (the trapezoidal rule's phase error, (ωΔt)²/12 =
/// 8.3e-6 of the 20 radians run, moves u by up to 1.7e-4 of u0); the four ways
/// agree to 1e-12 of u0 (the same C, summed
/// in another order), and the ledger closes to round-off (1e-12) with the energy
/// dissipated written in `energy.csv` and the summary.
#[test]
fn a_spring_damper_mass_decays_as_the_closed_form_however_it_is_damped() {
    let ways = [
        (SPRING, "CDAMP2,3,0.4,1\n"),
        (SPRING, "PARAM,G,0.04\nPARAM,W3,10.0\n"),
        (SPRING, "PARAM,ALPHA1,0.2\nPARAM,ALPHA2,0.002\n"),
        (SPRING, "CDAMP1,3,7,1\nPDAMP,7,0.4\n"),
        ("CELAS2,1,100.,1,,,,0.04\n", "PARAM,W4,10.0\n"),
        ("CELAS1,1,8,1\nPELAS,8,100.,0.04\n", "PARAM,W4,10.0\n"),
    ];
    let mut first: Option<Vec<(f64, f64)>> = None;
    for (spring, way) in ways {
        let (h, summary, header) =
            run(&oscillator(spring, way), "newmark", &[]).unwrap_or_else(|e| panic!("{spring}{way}: {e}"));
        let u = &h.series[&(1, 0)];
        assert_eq!(u.len(), 2001);
        let w = worst(u);
        assert!(w < 2e-3, "{way}: {w:e}");
        match &first {
            None => first = Some(u.clone()),
            Some(f) => {
                let d = f.iter().zip(u).map(|(a, b)| (a.1 - b.1).abs()).fold(0.0, f64::max);
                assert!(d < 1e-12 * 0.01, "{way}: {d:e} from the CDAMP2 run");
            }
        }
        assert!(header.contains("dissipated_damping ["), "{header}");
        let e = &summary["energy"];
        assert!(e["max_relative_error"].as_f64().unwrap() < 1e-12, "{way}: {e}");
        let dissipated = e["damping"]["dissipated"].as_f64().unwrap();
        let left = e["final_total"].as_f64().unwrap();
        let initial = e["initial"].as_f64().unwrap();
        assert!(((left + dissipated) - initial).abs() < 1e-12 * initial, "{way}: {e}");
        // e^(−2ζωt) = e^(−0.8) of the energy is left at t = 2, about: 0.55 dissipated.
        assert!((0.5..0.6).contains(&(dissipated / initial)), "{way}: {e}");
    }
}

/// Goal: an undamped deck writes no dissipation: no `dissipated_damping` column and no
/// `energy.damping` in the summary (existing outputs unchanged); a PARAM G without
/// W3 is left out with a warning, as NASTRAN's transient solutions leave it out.
#[test]
fn an_undamped_deck_writes_no_dissipation_and_g_without_w3_is_left_out() {
    let (_, summary, header) = run(&spring_mass(""), "newmark", &[]).unwrap();
    assert!(!header.contains("dissipated"), "{header}");
    assert!(summary["energy"].get("damping").is_none(), "{summary}");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("g.bdf");
    std::fs::write(&path, spring_mass("PARAM,G,0.04\n")).unwrap();
    let out = dir.path().join("out");
    let o = common::impactlab(&["run", path.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("PARAM G 4e-2 without W3"), "{stderr}");
    let energy = std::fs::read_to_string(out.join("energy.csv")).unwrap();
    assert!(!energy.lines().next().unwrap().contains("dissipated"));
}

/// Goal: the line dampers damp along their line. Model: a grid (T1 free) carrying a
/// CONM2 of mass 1 on a CELAS2 of k = 100 along x, with a CVISC of C1 = 0.4 from a
/// clamped grid (along x: ζ = 0.02), or a CBUSH to ground with K1 = 100 and B1 = 0.4
/// in place of both, or with its GE = 0.04 turned viscous at PARAM W4 = 10 in place of
/// B1 (GE·K1/W4 = 0.4). Reference: the closed form above, 2e-3 of u0. A CVISC across the
/// motion (along y) does not damp it: the undamped u0 cos ωt to 2e-3.
#[test]
fn line_dampers_damp_along_their_line() {
    let grids = "GRID,1,,0.0,0.0,0.0,,123456\nGRID,2,,1.0,0.0,0.0,,23456\nGRID,3,,1.0,1.0,0.0,,123456\n\
                 CONM2,9,2,,1.0\nTIC,1,2,1,0.01\n";
    let along = format!("{grids}CELAS2,1,100.,2,1\nCVISC,5,6,1,2\nPVISC,6,0.4,0.0\n");
    let bush = format!("{grids}CBUSH,5,6,2,,,,,0\nPBUSH,6,K,100.0,,,,,,+P\n+P,B,0.4\n");
    let bush_ge = format!("{grids}CBUSH,5,6,2,,,,,0\nPBUSH,6,K,100.0,,,,,,+P\n+P,GE,0.04\nPARAM,W4,10.0\n");
    for deck in [&along, &bush, &bush_ge] {
        let text = spring_mass("").replace("SPOINT,1\nCELAS2,1,100.,1\nCMASS2,2,1.0,1\nTIC,1,1,0,0.01\n", deck);
        let (h, summary, _) = run(&text, "energy", &[]).unwrap_or_else(|e| panic!("{deck}: {e}"));
        let w = worst(&h.series[&(2, 1)]);
        assert!(w < 2e-3, "{deck}: {w:e}");
        assert!(summary["energy"]["max_relative_error"].as_f64().unwrap() < 1e-12);
        assert_eq!(summary["energy"]["damping"]["elements"], 1);
    }
    let across = format!("{grids}CELAS2,1,100.,2,1\nCVISC,5,6,3,2\nPVISC,6,0.4,0.0\n");
    let text = spring_mass("").replace("SPOINT,1\nCELAS2,1,100.,1\nCMASS2,2,1.0,1\nTIC,1,1,0,0.01\n", &across);
    let (h, _, _) = run(&text, "energy", &[]).unwrap();
    let undamped = h.series[&(2, 1)]
        .iter()
        .map(|&(t, v)| (v - 0.01 * (10.0 * t).cos()).abs() / 0.01)
        .fold(0.0, f64::max);
    assert!(undamped < 2e-3, "{undamped:e}");
}

/// Goal: what damping cannot be run as asked is refused with the reason, never run
/// otherwise damped: a negative GE (it would feed energy in) and a damping PARAM given
/// twice.
#[test]
fn damping_that_cannot_be_run_as_asked_is_refused() {
    let e = run(
        &oscillator("CELAS2,1,100.,1,,,,-0.04\n", "PARAM,W4,10.0\n"),
        "newmark",
        &[],
    )
    .unwrap_err();
    assert!(
        e.contains("CELAS2 field 8 (GE)") && e.contains("must not be negative"),
        "{e}"
    );
    let e = run(
        &spring_mass("PARAM,G,0.04\nPARAM,G,0.05\nPARAM,W3,10.0\n"),
        "newmark",
        &[],
    )
    .unwrap_err();
    assert!(e.contains("PARAM G is set twice"), "{e}");
}

/// Runs `deck` (with the 49 × 49 plate mesh beside it when it includes it) for 300
/// steps of its TSTEP with the `energy` scheme: the columns of its `history.csv`
/// (contact force, displacements, strains) and its summary.
fn short_run(deck: &str) -> (Vec<(String, Vec<f64>)>, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let mesh = "plate-mesh-49x49.bdf";
    std::fs::copy(
        common::root().join("reference-data/decks").join(mesh),
        dir.path().join(mesh),
    )
    .unwrap();
    let (out, o) = run_in(
        dir.path(),
        &deck.replace("TSTEP, 1,2000,", "TSTEP, 1,300,"),
        "energy",
        &[],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let mut csv = csv::Reader::from_path(out.join("history.csv")).unwrap();
    let mut columns: Vec<(String, Vec<f64>)> = csv
        .headers()
        .unwrap()
        .iter()
        .map(|h| (h.to_string(), Vec::new()))
        .collect();
    for row in csv.records() {
        for (c, v) in columns.iter_mut().zip(row.unwrap().iter()) {
            c.1.push(v.parse().unwrap());
        }
    }
    (columns, summary)
}

/// Goal: the elements' structural damping GE, turned viscous at PARAM W4 as NASTRAN's
/// transient solutions turn it (C += Σ (GE/W4)·K_e), comes from where NASTRAN takes
/// it: a rod's MAT1, a PSHELL's MID1 material (a MAT2), a PCOMP's own GE. Model: the
/// paper's rod, its plate and the plate as a laminate (300 steps), each with GE = 0.02
/// on its one material or laminate and W4 = 1e5 rad/s. Reference: the same deck with
/// PARAM G = 0.02 turned viscous at W3 = 1e5 instead, which damps every element alike
/// (C += (G/W3)·K): every history column within 1e-10 of its largest value and the
/// energy dissipated within 1e-10 relative (the same C, assembled element by element
/// rather than scaled from K: measured bit for bit on this machine, a bound that
/// leaves room for another summation order); every element is counted among the damping ones, and the ledger closes
/// to round-off. Without W4 the GE is left out with a warning (undamped, as NASTRAN).
#[test]
fn element_ge_at_w4_damps_as_param_g_at_w3_when_every_element_has_it() {
    let root = common::root().join("reference-data/decks");
    let read = |name: &str| std::fs::read_to_string(root.join(name)).unwrap();
    let cases = [
        ("rod", read("rod.bdf"), "2.5-4,,,,+MAT1-1", "2.5-4,,,0.02,+MAT1-1", 144),
        ("plate", read("plate.bdf"), "5.0E-13\n", "5.0E-13,,0.02\n", 2401),
        (
            "pcomp",
            read("plate-pcomp.bdf"),
            "PCOMP,1,,,,,,,,+P0",
            "PCOMP,1,,,,,,0.02,,+P0",
            2401,
        ),
    ];
    for (name, deck, from, to, elements) in cases {
        assert!(deck.contains(from), "{name}");
        let with_g = deck.replace("ENDDATA", "PARAM,G,0.02\nPARAM,W3,1.0+5\nENDDATA");
        let with_ge = deck.replace(from, to).replace("ENDDATA", "PARAM,W4,1.0+5\nENDDATA");
        let (hg, sg) = short_run(&with_g);
        let (he, se) = short_run(&with_ge);
        assert_eq!(hg.len(), he.len(), "{name}");
        for ((column, g), (_, e)) in hg.iter().zip(&he) {
            assert_eq!(g.len(), e.len(), "{name} {column}");
            let scale = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let d = g.iter().zip(e).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(d <= 1e-10 * scale, "{name} {column}: {d:e} of {scale:e}");
        }
        let (dg, de) = (&sg["energy"]["damping"], &se["energy"]["damping"]);
        let (g, e) = (dg["dissipated"].as_f64().unwrap(), de["dissipated"].as_f64().unwrap());
        assert!(g > 0.0 && (g - e).abs() <= 1e-10 * g, "{name}: {dg} / {de}");
        assert_eq!(de["elements"], elements, "{name}: {de}");
        assert_eq!(de["stiffness_coefficient"], 0.0, "{name}: {de}");
        assert!(de["from"][0].as_str().unwrap().contains("PARAM W4"), "{name}: {de}");
        assert!(se["energy"]["max_relative_error"].as_f64().unwrap() < 1e-12, "{name}");
    }
    let rod = read("rod.bdf");
    let dir = tempfile::tempdir().unwrap();
    let (out, o) = run_in(
        dir.path(),
        &rod.replace("2.5-4,,,,+MAT1-1", "2.5-4,,,0.02,+MAT1-1"),
        "newmark",
        &[],
    );
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("144 elements have a structural damping GE (MAT1 is the first)"),
        "{stderr}"
    );
    let (u, _, _) = run(&rod, "newmark", &[]).unwrap();
    assert_eq!(
        read_run_histories(&out).unwrap().series,
        u.series,
        "GE without W4 is left out"
    );
}

/// Goal: the convolution engine runs a damped structure: its kernels are the damped
/// target's trapezoidal response, so the contact history is the direct run's to
/// round-off; its ledger, the contact's work on the target, cannot split the
/// target's energy from its damping's, and says so (D not known apart: NaN in
/// `energy.csv`, null in the summary) while still closing. Model: the paper's rod with
/// mass- and stiffness-proportional damping (ALPHA1 = 1e3, ALPHA2 = 1e-7: ALPHA1
/// damps the impactor too, which the engine steps with its share a₁m). Reference: the
/// direct run: peak force and contact duration within 1e-12 relative (measured
/// 5.2e-14 and 4.4e-15).
#[test]
fn the_convolution_engine_runs_a_damped_structure() {
    let rod = std::fs::read_to_string(common::root().join("reference-data/decks/rod.bdf")).unwrap();
    let damped = rod.replace("ENDDATA", "PARAM,ALPHA1,1.0+3\nPARAM,ALPHA2,1.0-7\nENDDATA");
    let (_, direct, _) = run(&damped, "energy", &[]).unwrap();
    let (_, conv, header) = run(&damped, "energy", &["--engine", "convolution"]).unwrap();
    for key in ["duration", "peak_force"] {
        let (d, c) = (
            direct["contact"][key].as_f64().unwrap(),
            conv["contact"][key].as_f64().unwrap(),
        );
        assert!((d - c).abs() <= 1e-12 * d, "{key}: direct {d:e}, convolution {c:e}");
    }
    assert!(direct["energy"]["damping"]["dissipated"].as_f64().unwrap() > 0.0);
    assert!(conv["energy"]["damping"]["dissipated"].is_null(), "{}", conv["energy"]);
    assert!(header.contains("dissipated_damping"));
    assert!(
        conv["energy"]["max_relative_error"].as_f64().unwrap() < 1e-10,
        "{}",
        conv["energy"]
    );
}

/// Goal: the modal engine runs a damped structure with its damping reduced, C_r =
/// TᵀCT, and its ledger closes with the dissipation. Model: the paper's rod with
/// stiffness-proportional damping (ALPHA2 = 1e-7: ζ = α₂ω/2 = 4e-3 at ω = 7.9e4
/// rad/s, a cycle of about twice the contact time). Reference: the direct run of the
/// same deck: contact
/// duration and peak force within 1e-3 (the modal engine's bound on the plate),
/// both dissipating, the modal ledger closing to 1e-10.
#[test]
fn the_modal_engine_reduces_the_damping_and_closes_its_ledger() {
    let rod = std::fs::read_to_string(common::root().join("reference-data/decks/rod.bdf")).unwrap();
    let damped = rod.replace("ENDDATA", "PARAM,ALPHA2,1.0-7\nENDDATA");
    let (_, direct, _) = run(&damped, "energy", &[]).unwrap();
    let (_, modal, _) = run(&damped, "energy", &["--engine", "modal"]).unwrap();
    for key in ["duration", "peak_force"] {
        let (d, m) = (
            direct["contact"][key].as_f64().unwrap(),
            modal["contact"][key].as_f64().unwrap(),
        );
        assert!((d - m).abs() <= 1e-3 * d, "{key}: direct {d:e}, modal {m:e}");
    }
    for s in [&direct, &modal] {
        assert!(s["energy"]["damping"]["dissipated"].as_f64().unwrap() > 0.0);
        assert!(
            s["energy"]["max_relative_error"].as_f64().unwrap() < 1e-10,
            "{}",
            s["energy"]
        );
    }
}

/// Goal: Rayleigh damping gives the modes of a real structure the damping ratios MSC
/// defines, ζ = ALPHA1/(2ω) + ALPHA2·ω/2, so that a user can set them. Model: the
/// paper's plate (49 × 49 CQUAD4, clamped) with PARAM ALPHA1 = 500 and ALPHA2 =
/// 2e-7 (the two terms equal at ω = √(ALPHA1/ALPHA2) = 5e4 rad/s). Reference: each of the
/// plate's two lowest modes φ (shift-and-invert Lanczos on its K and M), its ratio
/// φᵀCφ/(2ω φᵀMφ) with the C `impactlab` assembles. Tolerance 1e-9 relative (the
/// eigenvectors' round-off).
#[test]
fn rayleigh_damping_gives_the_plates_modes_their_ratios() {
    use impactlab::eigen::{lanczos, LanczosParams, Roots};
    let plate = std::fs::read_to_string(common::root().join("reference-data/decks/plate.bdf")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plate.bdf");
    std::fs::write(
        &path,
        plate.replace("ENDDATA", "PARAM,ALPHA1,500.0\nPARAM,ALPHA2,2.0-7\nENDDATA"),
    )
    .unwrap();
    let mesh = "plate-mesh-49x49.bdf";
    std::fs::copy(
        common::root().join("reference-data/decks").join(mesh),
        dir.path().join(mesh),
    )
    .unwrap();
    let model = impactlab::load_deck(&path, Default::default()).unwrap().0;
    let full = impactlab::assembly::assemble(&model);
    // The structure alone: the impactor's free DOF (a rigid-body root) left out.
    let target = model.target_mask();
    let mut map = vec![None; model.n()];
    let mut labels = Vec::new();
    for i in (0..model.n()).filter(|&i| target[i]) {
        map[i] = Some(labels.len());
        labels.push(model.dofs[i]);
    }
    let sys = full.restricted(&map, labels.len());
    assert!(sys.damped());
    let roots = Roots {
        above: f64::NEG_INFINITY,
        below: None,
        count: Some(2),
    };
    let pairs = lanczos(&sys, &labels, &roots, &LanczosParams::default()).unwrap();
    let n = sys.n;
    for (lambda, phi) in pairs.values.iter().zip(&pairs.vectors) {
        let omega = lambda.sqrt();
        let (mut cphi, mut mphi) = (vec![0.0; n], vec![0.0; n]);
        sys.c_mul(phi, &mut cphi);
        sys.m_mul(phi, &mut mphi);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let zeta = dot(phi, &cphi) / (2.0 * omega * dot(phi, &mphi));
        let expected = 500.0 / (2.0 * omega) + 2e-7 * omega / 2.0;
        assert!(
            (zeta - expected).abs() <= 1e-9 * expected,
            "ω {omega:e}: ζ {zeta:e}, expected {expected:e}"
        );
    }
}

/// Goal: a part moved only through a damper is not dropped as inert. Model: two
/// scalar points, the first a mass on a spring released from a displacement, the
/// second a mass joined to the first by a CDAMP2 alone (no spring, no coupled mass).
/// Reference: the second point moves (its largest displacement is not zero), and the
/// momentum the damper passes it shows in its history; the run's DOFs are both
/// solved (none inert).
#[test]
fn a_part_moved_only_through_a_damper_is_solved() {
    let deck = "SOL 9\nCEND\nDISP = ALL\nIC = 1\nTSTEP = 1\nBEGIN BULK\nSPOINT,1,2\nCELAS2,1,100.,1\n\
                CMASS2,2,1.0,1\nCMASS2,3,1.0,2\nCDAMP2,4,0.4,1,,2\nTIC,1,1,0,0.01\nTSTEP,1,200,1.0-3,1\nENDDATA\n";
    let (h, summary, _) = run(deck, "newmark", &[]).unwrap();
    assert_eq!(summary["model"]["inert_dofs_skipped"], 0, "{}", summary["model"]);
    let moved = h.series[&(2, 0)].iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
    assert!(moved > 1e-6, "point 2 moved {moved:e}");
}
