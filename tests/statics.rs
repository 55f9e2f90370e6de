//! Linear statics (SOL 101) through `impactlab run`: a cantilever strip against
//! Euler-Bernoulli's closed forms, the static loads (FORCE, MOMENT, PLOAD4, GRAV,
//! LOAD) against pyNastran's load summation and the model's own mass, and the
//! refusals a static or transient deck earns.

use crate::common;

use common::impactlab;
use impactlab::run::statics::{solve, StaticSolution};
use std::path::Path;

fn static_deck(text: &str) -> StaticSolution {
    let d = impactlab::deck::parse_deck_str("s.bdf", text, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    solve(&d).unwrap_or_else(|e| panic!("{e}")).0
}

/// A cantilever strip along x, length 10, width 1, thickness 0.1, E = 1e7, ν = 0, on
/// n CQUAD4 (clamped at x = 0, grids 1..=n+1 on y = 0 and 101.. on y = 1), loaded
/// by `loads` (bulk cards of set 1; TIP and TIP2 stand for the two tip grids).
fn strip(n: usize, loads: &str) -> String {
    let mut d = String::from(
        "$ Units: in, lbf, s\nSOL 101\nCEND\n  SPC = 1\n  LOAD = 1\nBEGIN BULK\nMAT1,1,1.0+7,,0.0,0.1\nPSHELL,1,1,0.1,1\n",
    );
    for i in 0..=n {
        let x = 10.0 * i as f64 / n as f64;
        d += &format!("GRID,{},,{x:?},0.0,0.0\nGRID,{},,{x:?},1.0,0.0\n", i + 1, i + 101);
    }
    for i in 0..n {
        d += &format!("CQUAD4,{},1,{},{},{},{}\n", i + 1, i + 1, i + 2, i + 102, i + 101);
    }
    d += "SPC1,1,123456,1,101\n";
    d += &loads
        .replace("TIP2", &(n + 101).to_string())
        .replace("TIP", &(n + 1).to_string());
    d + "ENDDATA\n"
}

/// The tip's mean deflection (T3 of its two grids).
fn tip(s: &StaticSolution, n: usize) -> f64 {
    let g = (n + 1) as i64;
    0.5 * (s.displacement(g, 3).unwrap() + s.displacement(g + 100, 3).unwrap())
}

/// Goal: the static path answers Euler-Bernoulli's cantilever exactly where the
/// element can. Model: [`strip`] with ν = 0 (a beam of EI = E·b·t³/12). Reference:
/// P L³/3EI under an end force P = 1 (two FORCEs of ½) and M L²/2EI under an end
/// moment M = 1 (two MOMENTs of ½ about y, sagging). The DKQ's bending is cubic along
/// its sides, so both are exact on any mesh: tolerance 1e-9 relative (round-off of
/// the factorisation, whose residual the solution reports), on 1, 4 and 10 elements.
#[test]
fn a_cantilever_strip_takes_an_end_force_and_moment_exactly() {
    let ei = 1.0e7 * 0.1f64.powi(3) / 12.0;
    for n in [1, 4, 10] {
        let force = static_deck(&strip(
            n,
            "FORCE,1,TIP,,0.5,0.0,0.0,-1.0\nFORCE,1,TIP2,,0.5,0.0,0.0,-1.0\n",
        ));
        let exact = 1000.0 / (3.0 * ei);
        assert!(
            (-tip(&force, n) / exact - 1.0).abs() < 1e-9,
            "n = {n}: {}",
            tip(&force, n)
        );
        assert!(force.residual < 1e-9, "{}", force.residual);
        let moment = static_deck(&strip(
            n,
            "MOMENT,1,TIP,,0.5,0.0,1.0,0.0\nMOMENT,1,TIP2,,0.5,0.0,1.0,0.0\n",
        ));
        let exact = 100.0 / (2.0 * ei);
        assert!(
            (-tip(&moment, n) / exact - 1.0).abs() < 1e-9,
            "n = {n}: {}",
            tip(&moment, n)
        );
    }
}

/// Goal: a PCOMP whose Z0 puts its plies off the grids' plane (an offset laminate)
/// couples membrane and bending as an eccentric bar does. Model: [`strip`] on 1 and 4
/// elements with its PSHELL replaced by a PCOMP of one ply (the MAT1, t = 0.1) whose
/// mid-plane sits zc = Z0 + t/2 above the grids (zc = 0.02, then −0.02), pulled along
/// x by N = 1 at the grids (two FORCEs of ½). Reference: the laminate about the grids'
/// plane, A = E t, B = E t zc, D = E (t³/12 + t zc²) (ν = 0): the load's moment −zc N
/// about y lifts the tip by zc N L²/2EI (I = t³/12), and the grids' plane stretches
/// by N L (1 + 12 zc²/t²)/E t. Constant strain and curvature: exact on any mesh,
/// tolerance 1e-9 relative. With the offset ignored (Z0 = −t/2) the tip stays on the
/// axis, so the test fails if Z0 is dropped.
#[test]
fn an_offset_laminate_bends_under_a_load_in_its_reference_plane() {
    let (e, t, l) = (1.0e7, 0.1, 10.0);
    let ei = e * t * t * t / 12.0;
    for n in [1, 4] {
        for zc in [0.02, -0.02] {
            let deck = strip(n, "FORCE,1,TIP,,0.5,1.0,0.0,0.0\nFORCE,1,TIP2,,0.5,1.0,0.0,0.0\n").replace(
                "PSHELL,1,1,0.1,1\n",
                &format!("PCOMP,1,{:?}\n,1,0.1,0.0\n", zc - 0.5 * t),
            );
            let s = static_deck(&deck);
            let lift = zc * l * l / (2.0 * ei);
            assert!(
                (tip(&s, n) / lift - 1.0).abs() < 1e-9,
                "n = {n}, zc = {zc}: {}",
                tip(&s, n)
            );
            let g = (n + 1) as i64;
            let stretch = 0.5 * (s.displacement(g, 1).unwrap() + s.displacement(g + 100, 1).unwrap());
            let exact = l * (1.0 + 12.0 * zc * zc / (t * t)) / (e * t);
            assert!((stretch / exact - 1.0).abs() < 1e-9, "n = {n}, zc = {zc}: {stretch}");
        }
    }
}

/// Goal: PLOAD4's consistent forces converge on the uniformly loaded cantilever at the
/// element's order. Model: [`strip`] on 4, 8, 16 elements under a pressure q = 2 (a
/// line load of 2 along the strip), positive along the shells' normal (+z). Reference:
/// q b L⁴/8EI. The nodal forces carry no moments, so the tip deflection converges as
/// h²: the observed order from the three meshes within 0.1 of 2, and the finest mesh
/// within 0.2 %.
#[test]
fn a_cantilever_strip_under_pressure_converges_at_order_two() {
    let ei = 1.0e7 * 0.1f64.powi(3) / 12.0;
    let exact = 2.0 * 1.0e4 / (8.0 * ei);
    let errors: Vec<f64> = [4, 8, 16]
        .iter()
        .map(|&n| {
            let s = static_deck(&strip(n, &format!("PLOAD4,1,1,2.0,,,,THRU,{n}\n")));
            assert!((s.applied[2] - 20.0).abs() < 1e-12, "{:?}", s.applied);
            (tip(&s, n) / exact - 1.0).abs()
        })
        .collect();
    let order = (errors[1] / errors[2]).log2();
    eprintln!("errors {errors:?}, order {order}");
    assert!((order - 2.0).abs() < 0.1, "order {order}: {errors:?}");
    assert!(errors[2] < 2e-3, "{errors:?}");
}

/// A curved panel (the structure of `impactlab mesh panel --n 5 --radius 10`, its grids
/// displaced in a CORD2C about the cylinder's axis) with every static load kind, as a
/// LOAD combination selected by LOAD = 9.
fn loaded_panel(dir: &Path) -> std::path::PathBuf {
    let deck = impactlab::mesh::panel_deck(5, 10.0, impactlab::mesh::Cells::Quad4).unwrap();
    let mut out = String::from(
        "$ Units: in, lbf, s\nSOL 101\nCEND\n  SPC = 1\n  LOAD = 9\nBEGIN BULK\n\
         CORD2C,5,0,0.0,0.0,10.0,0.0,1.0,10.0\n,1.0,0.0,10.0\n\
         CORD2R,6,0,1.0,2.0,3.0,1.5,2.0,4.0\n,2.0,3.0,3.0\n\
         FORCE,1,303,6,3.0,0.2,-1.0,0.5\nMOMENT,1,404,0,2.0,1.0,0.0,0.0\n\
         FORCE,4,303,5,3.0,0.2,-1.0,0.5\n\
         PLOAD4,2,101,5.0\nPLOAD4,2,201,1.5,,,,THRU,205\nGRAV,3,,386.1,0.0,0.6,-0.8\n\
         PLOAD4,5,303,2.0,,,,,,,,0,1.0,1.0,0.0\nPLOAD4,6,303,2.0\n\
         LOAD,9,2.0,1.0,1,0.5,2,-1.0,3\n",
    );
    for line in deck.lines() {
        let structural = ["GRID,", "CQUAD4,", "PSHELL,", "MAT2,", "+A101", "SPC1,"]
            .iter()
            .any(|c| line.starts_with(c));
        if !structural || line.starts_with("GRID,999,") || line.ends_with(",999") {
            continue;
        }
        out += line;
        out += if line.starts_with("GRID,") { ",5\n" } else { "\n" };
    }
    out += "ENDDATA\n";
    let p = dir.join("loaded-panel.bdf");
    std::fs::write(&p, out).unwrap();
    p
}

/// pyNastran's resultant of load set `sid` of a deck about the origin (forces and
/// moments, basic), GRAV left out; `None` where pyNastran is not installed (outside CI).
fn pynastran_resultant(path: &Path, sid: i64) -> Option<[f64; 6]> {
    let script = "import json, sys\n\
                  from pyNastran.bdf.bdf import read_bdf\n\
                  from pyNastran.bdf.mesh_utils.loads import sum_forces_moments\n\
                  m = read_bdf(sys.argv[1], debug=None)\n\
                  f, mo = sum_forces_moments(m, [0.0, 0.0, 0.0], int(sys.argv[2]), include_grav=False)\n\
                  print(json.dumps([float(x) for x in list(f) + list(mo)]))\n";
    let sid = sid.to_string();
    common::pynastran_json(script, &[path.as_os_str(), sid.as_ref()])
}

/// Goal: the static loads are what NASTRAN means by them, on a curved panel whose grids
/// are displaced in a cylindrical system. Model: [`loaded_panel`]: a FORCE in a turned
/// CORD2R and a MOMENT (set 1), PLOAD4s along the shells' normals, one of a THRU range
/// (set 2), a GRAV (set 3), combined by LOAD 9 = 2·(1·set 1 + 0.5·set 2 − 1·set 3);
/// a FORCE directed in the grid's own CORD2C (set 4); a PLOAD4 along a direction
/// vector (set 5) and the same pressure along the normal (set 6). References:
/// pyNastran's `sum_forces_moments` (an independent implementation) for the resultant
/// of sets 1 and 2 about the origin; the GRAV set's force is the model's mass
/// (`impactlab check`'s, itself checked against pyNastran's) times the acceleration; a
/// FORCE in a cylindrical system is directed by its axes at the grid (NASTRAN's rule),
/// so in the grid's CD frame, the same system at the same point, its components are
/// F·N as written; a PLOAD4's (N1, N2, N3) gives the direction, not the magnitude
/// (NASTRAN's Quick Reference Guide), so set 5's force is set 6's magnitude along N.
/// pyNastran reads a cylindrical FORCE's N as a location and ignores a PLOAD4's N, and
/// puts a varying pressure's resultant at the centroid: those are not compared with it
/// (the consistent forces' moments are checked in `model::loads`' own tests).
/// Tolerance: 1e-10 of the largest component (round-off of the frames and of summing
/// the pressures' consistent forces, which sum to p·A exactly on flat facets).
#[test]
fn static_loads_sum_to_pynastrans_resultant_and_gravity_to_the_mass() {
    let dir = tempfile::tempdir().unwrap();
    let path = loaded_panel(dir.path());
    let text = std::fs::read_to_string(&path).unwrap();
    let with = |load: &str| static_deck(&text.replace("  LOAD = 9", load));
    let (s1, s2, s3) = (with("  LOAD = 1"), with("  LOAD = 2"), with("  LOAD = 3"));
    let four = impactlab::deck::parse_deck_str("p.bdf", &text.replace("  LOAD = 9", "  LOAD = 4"), Default::default())
        .unwrap();
    let (structure, _) = impactlab::model::build_structure(&four).unwrap();
    let loads = impactlab::model::loads::static_load(&four, &structure).unwrap();
    let f = loads[&303];
    for (k, v) in [0.6, -3.0, 1.5, 0.0, 0.0, 0.0].iter().enumerate() {
        assert!((f[k] - v).abs() < 1e-12, "FORCE in the grid's CORD2C: {f:?}");
    }
    let (s5, s6) = (with("  LOAD = 5"), with("  LOAD = 6"));
    let magnitude = s6.applied[..3].iter().map(|x| x * x).sum::<f64>().sqrt();
    let along = [magnitude / 2f64.sqrt(), magnitude / 2f64.sqrt(), 0.0];
    for k in 0..3 {
        assert!(
            (s5.applied[k] - along[k]).abs() < 1e-12 * magnitude,
            "PLOAD4 along N: {:?} vs {along:?}",
            s5.applied
        );
    }
    let combined = with("  LOAD = 9");
    for k in 0..6 {
        let expected = 2.0 * (s1.applied[k] + 0.5 * s2.applied[k] - s3.applied[k]);
        assert!(
            (combined.applied[k] - expected).abs() <= 1e-12 * expected.abs().max(1.0),
            "LOAD 9 component {k}: {} vs {expected}",
            combined.applied[k]
        );
    }
    let d = impactlab::deck::read_deck(&path, impactlab::deck::ReadOptions::default()).unwrap();
    let (structure, _) = impactlab::model::build_structure(&d).unwrap();
    let mass = structure.mass_properties().mass[0];
    let g = [0.0, 386.1 * 0.6, -386.1 * 0.8];
    for (ours, a) in s3.applied.iter().zip(g) {
        assert!(
            (ours - mass * a).abs() <= 1e-12 * mass * 386.1,
            "GRAV: {ours} vs {}",
            mass * a
        );
    }
    for (sid, ours) in [(1, &s1), (2, &s2)] {
        let Some(theirs) = pynastran_resultant(&path, sid) else {
            return;
        };
        let scale = theirs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (k, (a, b)) in ours.applied.iter().zip(theirs).enumerate() {
            assert!(
                (a - b).abs() <= 1e-10 * scale,
                "set {sid} component {k}: {a} vs pyNastran's {b}"
            );
        }
    }
}

/// Goal: `impactlab run` answers a static deck: its displacements in the grids' CD
/// frames and a summary, with the run's other flags refused. Model: [`strip`] under
/// an end force. Reference: the cantilever's P L³/3EI (as in the test above), read
/// back from `displacements.csv`.
#[test]
fn impactlab_run_solves_a_static_deck_and_refuses_transient_flags() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("strip.bdf");
    std::fs::write(
        &deck,
        strip(4, "FORCE,1,TIP,,0.5,0.0,0.0,-1.0\nFORCE,1,TIP2,,0.5,0.0,0.0,-1.0\n"),
    )
    .unwrap();
    let out = dir.path().join("out");
    let o = impactlab(&["run", deck.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(stdout.contains("linear static") && stdout.contains("lbf"), "{stdout}");
    let csv = std::fs::read_to_string(out.join("displacements.csv")).unwrap();
    assert!(csv.starts_with("grid,cd,T1,T2,T3,R1,R2,R3\n"), "{csv}");
    let row: Vec<&str> = csv.lines().find(|l| l.starts_with("5,")).unwrap().split(',').collect();
    let w: f64 = row[4].parse().unwrap();
    let exact = 1000.0 / (3.0 * 1.0e7 * 0.1f64.powi(3) / 12.0);
    assert!((-w / exact - 1.0).abs() < 1e-9, "{w}");
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["solution"], "linear static (SOL 101)");
    assert_eq!(summary["autospc"], 8, "the free grids' drilling rotations");
    let o = impactlab(&["run", deck.to_str().unwrap(), "--dt", "1e-6"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--dt applies to a transient run"));
}

/// Goal: what a static or transient deck may not mix is refused with the card and
/// where it is: a transient deck's FORCE and LOAD selection, a static deck without
/// LOAD, a LOAD naming a LOAD, a PLOAD4 on an element that does not exist, a set with
/// no load card, a GRAV in a cylindrical system, a FORCE in an undefined one.
#[test]
fn static_loads_are_refused_where_they_do_not_belong() {
    let transient =
        impactlab::paper::ROD_DECK.replace("BEGIN BULK", "  LOAD = 1\nBEGIN BULK\nFORCE,1,2,,1.0,1.0,0.0,0.0");
    let e = impactlab::model_from_text("rod.bdf", &transient)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("FORCE is a static load") && e.contains("LOAD = 1 is a static load"),
        "{e}"
    );
    let solve_err = |text: String| {
        let d = impactlab::deck::parse_deck_str("s.bdf", &text, Default::default()).unwrap_or_else(|e| panic!("{e}"));
        solve(&d).unwrap_err().to_string()
    };
    let e = solve_err(strip(2, "FORCE,1,TIP,,1.0,0.0,0.0,-1.0\n").replace("  LOAD = 1\n", ""));
    assert!(e.contains("needs a load: LOAD = n"), "{e}");
    let e = solve_err(strip(
        2,
        "FORCE,2,TIP,,1.0,0.0,0.0,-1.0\nLOAD,3,1.0,1.0,2\nLOAD,1,1.0,1.0,3\n",
    ));
    assert!(e.contains("LOAD 1 names set 3, which is itself a LOAD"), "{e}");
    let e = solve_err(strip(2, "PLOAD4,1,7,1.0\n"));
    assert!(e.contains("loads element 7, which does not exist"), "{e}");
    let e = solve_err(strip(2, "FORCE,1,TIP,,1.0,0.0,0.0,-1.0\n").replace("  LOAD = 1", "  LOAD = 4"));
    assert!(e.contains("LOAD = 4: set 4 has no FORCE"), "{e}");
    let cylindrical = "CORD2C,5,0,0.0,0.0,0.0,0.0,0.0,1.0\n,1.0,0.0,0.0\nGRAV,1,5,386.1,0.0,0.0,-1.0\n";
    let e = solve_err(strip(2, cylindrical));
    assert!(
        e.contains("GRAV 1 is given in system 5, which is not rectangular"),
        "{e}"
    );
    let e = solve_err(strip(2, "FORCE,1,TIP,9,1.0,0.0,0.0,-1.0\n"));
    assert!(
        e.contains("FORCE names coordinate system 9, which is not defined"),
        "{e}"
    );
}

/// Goal: a shell's pressure acting off its grids reaches them with its moment.
/// Model: the ZOFFS strip of verification/shell-offset (reference plane 0.3 above its
/// grids) and its twin (shells on grids 0.3 above, each tied whole to the grid below
/// by an RBE2), loaded by a PLOAD4 of 2.0 on every element along +x (CID 0, N = (1,
/// 0, 0)), not along the normal. Reference: the applied resultant is the traction's,
/// F = (20, 0, 0) and a moment about the origin with My = 0.3·20 = 6 (its line of
/// action 0.3 above the grids), and the two strips deflect alike. Tolerance:
/// round-off.
#[test]
fn an_offset_pressure_reaches_its_grids_with_its_moment() {
    let root = common::root().join("reference-data/decks/beams");
    let pressure = |name: &str| {
        let text = std::fs::read_to_string(root.join(name)).unwrap();
        let text: String = text
            .lines()
            .filter(|l| !l.starts_with("FORCE"))
            .map(|l| {
                if l == "ENDDATA" {
                    "PLOAD4,1,1,2.0,,,,THRU,4\n,0,1.0,0.0,0.0\nENDDATA\n".to_string()
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        static_deck(&text)
    };
    let (offset, twin) = (pressure("shell-offset.bdf"), pressure("shell-offset-twin.bdf"));
    for s in [&offset, &twin] {
        let want = [20.0, 0.0, 0.0, 0.0, 6.0, -10.0];
        for (c, w) in want.iter().enumerate() {
            assert!((s.applied[c] - w).abs() < 1e-12 * 20.0, "{}: {:?}", s.deck, s.applied);
        }
    }
    let tip = |s: &StaticSolution| [s.displacement(104, 1).unwrap(), s.displacement(104, 3).unwrap()];
    let (a, b) = (tip(&offset), tip(&twin));
    assert!(a[1].abs() > 0.0, "the moment bends the strip: {a:?}");
    for c in 0..2 {
        assert!((a[c] - b[c]).abs() <= 1e-12 * a[c].abs(), "{a:?} vs {b:?}");
    }
}

/// Goal: the general element (GENEL) in every form the manual gives, as NASTRAN-95's
/// demonstration deck d01141a uses them: a cantilever of length 6 (EA = 6, EI = 0.5)
/// built from five GENELs of length 1 (a flexibility Z with no UD; a 6 × 6 K; K with
/// UD and [S]; K with UD and [S] computed from the grids; Z with UD and [S]) and one
/// CBAR, clamped at grid 1 and loaded at grid 7, its two SUBCASEs solved on one
/// factorisation. Reference: under the axial load (SUBCASE 1, LOAD 1) the sum of the elements' axial flexibilities as the deck writes them
/// (GENEL 1's Z11 = .1666667, GENEL 5's .166666: the tip moves 1 − 6.3e-7, as
/// NASTRAN-95 printed, 9.999993E-01), to 1e-12; under the transverse one (SUBCASE 2)
/// Euler-Bernoulli's closed forms, exact for an end load, v = P x²(3L − x)/6EI and
/// θ = P x(2L − x)/2EI (NASTRAN-95 printed v = 5.666667, 21.33333, 45, 74.66666,
/// 108.3333, 144), to 1e-6 of the largest value: the deck's flexibilities are given to
/// six and seven digits (observed: 2.1e-8 of v's, 1.1e-7 of θ's largest).
#[test]
fn nastran95_genel_cantilever_answers_euler_bernoulli_exactly() {
    let (l, ei) = (6.0, 0.5);
    // Each element's axial flexibility as the deck writes it: GENEL 1's Z11 and
    // GENEL 5's to 7 and 6 digits, K11 = 6 = EA/L for the others and the CBAR.
    let flexibilities = [0.1666667, 1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0, 0.166666, 1.0 / 6.0];
    // NASTRAN-95's deck as it is: SUBCASE 1 the axial load, SUBCASE 2 the transverse.
    let deck = impactlab::deck::read_deck(
        &common::root().join("reference-data/nastran95-demos/inp/d01141a.inp"),
        Default::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (solutions, _) = impactlab::run::statics::solve_subcases(&deck).unwrap_or_else(|e| panic!("{e}"));
    let [axial, bending] = &solutions[..] else {
        panic!("{} solutions", solutions.len())
    };
    assert_eq!((axial.subcase, bending.subcase), (Some(1), Some(2)));
    for g in 1..=7 {
        let x = (g - 1) as f64;
        let u = axial.displacement(g, 1).unwrap();
        let u0: f64 = flexibilities[..g as usize - 1].iter().sum();
        assert!((u - u0).abs() < 1e-12, "grid {g}: u = {u}, the deck's {u0}");
        let (v, th) = (bending.displacement(g, 2).unwrap(), bending.displacement(g, 6).unwrap());
        let (v0, th0) = (x * x * (3.0 * l - x) / (6.0 * ei), x * (2.0 * l - x) / (2.0 * ei));
        assert!((v - v0).abs() < 1e-6 * 144.0, "grid {g}: v = {v}, exact {v0}");
        assert!((th - th0).abs() < 1e-6 * 36.0, "grid {g}: θ = {th}, exact {th0}");
    }
}

/// Goal: SUBCASEs as NASTRAN reads them: a SUBCASE takes the LOAD and SPC above the
/// first SUBCASE unless it selects its own, each is solved on the one factorisation
/// of its constraint set. Model: [`strip`] on 4 elements, FORCE set 1 the end force
/// (P = 1), set 2 twice it. Reference: the tip's deflection P L³/3EI for SUBCASE 1
/// (LOAD = 1 from above), twice it for SUBCASE 2 (LOAD = 2), to 1e-9; then SUBCASE 2
/// with its own SPC set, the strip propped at mid-length: a clamped-pinned span a
/// under the overhang's moment 2P·b turns 2P·b·a/4EI at the prop, so the tip (b
/// beyond it) deflects 2P(b²a/4 + b³/3)/EI = 2P·7L³/96EI for a = b = L/2.
/// SUBCASE 1 is unchanged, and the solutions stay in SUBCASE order.
#[test]
fn subcases_inherit_the_selections_above_them_and_share_one_factorisation() {
    let loads = "FORCE,1,TIP,,0.5,0.0,0.0,-1.0\nFORCE,1,TIP2,,0.5,0.0,0.0,-1.0\n\
                 FORCE,2,TIP,,1.0,0.0,0.0,-1.0\nFORCE,2,TIP2,,1.0,0.0,0.0,-1.0\n";
    let deck = strip(4, loads).replace("  LOAD = 1\n", "  LOAD = 1\nSUBCASE 1\nSUBCASE 2\n  LOAD = 2\n");
    let d = impactlab::deck::parse_deck_str("s.bdf", &deck, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let (s, _) = impactlab::run::statics::solve_subcases(&d).unwrap_or_else(|e| panic!("{e}"));
    let ei = 1.0e7 * 0.1f64.powi(3) / 12.0;
    let exact = 1000.0 / (3.0 * ei);
    assert_eq!(
        (s[0].subcase, s[0].load_set, s[1].subcase, s[1].load_set),
        (Some(1), 1, Some(2), 2)
    );
    assert!((-tip(&s[0], 4) / exact - 1.0).abs() < 1e-9, "{}", tip(&s[0], 4));
    assert!((-tip(&s[1], 4) / (2.0 * exact) - 1.0).abs() < 1e-9, "{}", tip(&s[1], 4));
    let other_spc = deck
        .replace("SUBCASE 2\n", "SUBCASE 2\n  SPC = 2\n")
        .replace("ENDDATA", "SPC1,2,123456,1,101\nSPC1,2,3,3,103\nENDDATA");
    let d = impactlab::deck::parse_deck_str("s.bdf", &other_spc, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let (s, _) = impactlab::run::statics::solve_subcases(&d).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((s[0].subcase, s[1].subcase), (Some(1), Some(2)));
    assert!((-tip(&s[0], 4) / exact - 1.0).abs() < 1e-9, "{}", tip(&s[0], 4));
    let propped = 2.0 * 7.0 * 1000.0 / (96.0 * ei);
    assert!((-tip(&s[1], 4) / propped - 1.0).abs() < 1e-9, "{}", tip(&s[1], 4));
    assert_eq!(s[1].displacement(3, 3), Some(0.0), "the prop holds");
}

/// Goal: enforced displacements as NASTRAN poses them: an SPC's D and an SPCD of the
/// LOAD set (which overrides the SPC's value), applied exactly. Model: [`strip`] on 4
/// elements with its tip's T3 held by SPC (set 1 with the root's SPC1) and no force:
/// the tip moved by δ = −0.01 through the SPC's D, then through an SPCD of load set 1
/// over an SPC of D = 0.5 (which the SPCD overrides). Reference: a cantilever whose
/// tip is moved with no moment there, v(x) = δ x²(3L − x)/2L³ (cubic, so exact on the
/// DKQ strip), to 1e-9 of δ at every grid along the strip.
#[test]
fn enforced_displacements_by_spc_and_spcd_move_the_tip_exactly() {
    let delta = -0.01;
    let by_spc = strip(
        4,
        &format!("SPC,1,TIP,3,{delta:?},TIP2,3,{delta:?}\nFORCE,1,TIP,,0.0,0.0,0.0,1.0\n"),
    );
    let by_spcd = strip(
        4,
        &format!("SPC,1,TIP,3,0.5,TIP2,3,0.5\nSPCD,1,TIP,3,{delta:?},TIP2,3,{delta:?}\nFORCE,1,TIP,,0.0,0.0,0.0,1.0\n"),
    );
    for deck in [by_spc, by_spcd] {
        let s = static_deck(&deck);
        for i in 0..=4 {
            let x = 2.5 * i as f64;
            let exact = delta * x * x * (30.0 - x) / (2.0 * 1000.0);
            for g in [i + 1, i + 101] {
                let v = s.displacement(g, 3).unwrap();
                assert!((v - exact).abs() < 1e-9 * delta.abs(), "grid {g}: {v}, exact {exact}");
            }
        }
    }
}

/// Goal: NASTRAN-95's pressure cards load a flat rectangular mesh as PLOAD4 does:
/// PLOAD on an element's four grids (four corner triangles of P/2, each P·A/3 to its
/// grids) and PLOAD2 on the element (read as a PLOAD4) both give a quarter of P·A to
/// each corner of a rectangle. Model: [`strip`] on 4 elements under P = 2. Reference:
/// the PLOAD4 solution, to 1e-12 of its tip deflection.
#[test]
fn pload_and_pload2_load_a_rectangle_as_pload4_does() {
    let n = 4;
    let by = |cards: String| tip(&static_deck(&strip(n, &cards)), n);
    let reference = by((1..=n).map(|e| format!("PLOAD4,1,{e},2.0\n")).collect());
    let pload: String = (1..=n)
        .map(|i| format!("PLOAD,1,2.0,{},{},{},{}\n", i, i + 1, i + 101, i + 100))
        .collect();
    let pload2 = format!("PLOAD2,1,2.0,1,THRU,{n}\n");
    for (name, cards) in [("PLOAD", pload), ("PLOAD2", pload2)] {
        let t = by(cards);
        assert!((t / reference - 1.0).abs() < 1e-12, "{name}: {t}, PLOAD4 {reference}");
    }
    assert!(reference > 0.0);
}
