//! Normal modes (SOL 103, NASTRAN-95's SOL 3) in the problems with exact answers:
//! spring-mass chains held at one end and free at both, two chains side by side
//! (every root twice), the roots of a plate against a dense eigen-solver, and the
//! hinged plate of NASTRAN-95's demonstration decks against its theory on two meshes.

mod common;

use common::{impactlab, root};
use impactlab::deck::{parse_deck_str, read_deck};
use impactlab::run::modes::{solve, ModalSolution};

/// A chain of `n` masses `m` on scalar points `first..first+n`, joined by springs
/// `k` (CELAS2, CMASS2), the first held to ground through a spring too when `held`.
fn chain(first: i64, n: i64, k: f64, m: f64, held: bool) -> String {
    let mut b = format!("SPOINT,{first},THRU,{}\n", first + n - 1);
    for i in 0..n {
        let p = first + i;
        b.push_str(&format!("CMASS2,{},{m},{p}\n", 1000 + p));
        if i > 0 {
            b.push_str(&format!("CELAS2,{},{k},{},,{p}\n", 2000 + p, p - 1));
        } else if held {
            b.push_str(&format!("CELAS2,{},{k},{p}\n", 2000 + p));
        }
    }
    b
}

fn modes(bulk: &str, eigrl: &str) -> ModalSolution {
    let text = format!("SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\n{eigrl}\n{bulk}ENDDATA\n");
    let d = parse_deck_str("chain.bdf", &text, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    solve(&d).unwrap_or_else(|e| panic!("{e}")).0
}

/// Goal: the roots of a chain of n = 30 masses m = 2 and springs k = 5e3, held at one
/// end, are λ_j = (4k/m) sin²((2j − 1)π / (2(2n + 1))), j = 1..n (the discrete
/// string's, exact), all n of them found (the Krylov space spans the whole chain), each
/// to 1e-12 of the largest; each eigenvector of unit generalised mass (EIGRL's
/// default NORM) and with a residual at round-off.
#[test]
fn spring_mass_chain_held_at_one_end() {
    let (n, k, m) = (30, 5e3, 2.0);
    let s = modes(&chain(1, n, k, m, true), &format!("EIGRL,1,,,{n}"));
    assert_eq!(s.modes.len(), n as usize);
    let top = 4.0 * k / m;
    for (j, mode) in s.modes.iter().enumerate() {
        let x = (2 * j + 1) as f64 * std::f64::consts::PI / (2.0 * (2 * n + 1) as f64);
        let exact = top * x.sin().powi(2);
        assert!(
            (mode.eigenvalue - exact).abs() <= 1e-12 * top,
            "mode {}: {} against {exact}",
            mode.mode,
            mode.eigenvalue
        );
        assert!((mode.generalized_mass - 1.0).abs() < 1e-12, "{}", mode.generalized_mass);
        assert!(
            mode.residual < 1e-10,
            "mode {}: residual {:e}",
            mode.mode,
            mode.residual
        );
    }
    assert_eq!(s.shift, 0.0, "a held chain's K is positive definite: no shift");
}

/// Goal: a chain free at both ends has a rigid-body root, λ = 0 (found to 1e-10 of the
/// largest root: K is singular, so the Lanczos shift is negative), then λ_j = (4k/m)
/// sin²(jπ/2n); two such chains side by side (disconnected) have every root twice,
/// and both copies are found (the recurrence starts again when the first chain's
/// Krylov space is exhausted). EIGRL V2 bounds the roots asked for: those up to
/// 0.1 of the top frequency.
#[test]
fn two_free_chains_have_every_root_twice() {
    let (n, k, m) = (12, 1e4, 0.5);
    let top = 4.0 * k / m;
    let exact = |j: usize| top * (j as f64 * std::f64::consts::PI / (2.0 * n as f64)).sin().powi(2);
    let one = modes(&chain(1, n, k, m, false), &format!("EIGRL,1,,,{n}"));
    assert!(one.shift < 0.0);
    assert!(
        one.modes[0].eigenvalue.abs() <= 1e-10 * top,
        "{}",
        one.modes[0].eigenvalue
    );
    for (j, mode) in one.modes.iter().enumerate().skip(1) {
        assert!(
            (mode.eigenvalue - exact(j)).abs() <= 1e-11 * top,
            "{j}: {}",
            mode.eigenvalue
        );
    }
    let both = format!("{}{}", chain(1, n, k, m, false), chain(101, n, k, m, false));
    let f2 = (0.1 * top).sqrt() / (2.0 * std::f64::consts::PI);
    let s = modes(&both, &format!("EIGRL,1,,{f2}"));
    let wanted: Vec<usize> = (0..n as usize).filter(|&j| exact(j) <= 0.1 * top).collect();
    assert_eq!(s.modes.len(), 2 * wanted.len(), "{:?}", s.modes);
    for (i, mode) in s.modes.iter().enumerate() {
        let e = exact(wanted[i / 2]);
        assert!(
            (mode.eigenvalue - e).abs() <= 1e-10 * top,
            "root {i}: {} against {e}",
            mode.eigenvalue
        );
    }
}

/// Goal: the Lanczos roots of a plate are the dense eigen-solver's
/// ([`impactlab::assembly::frequencies_of`]: the massless rotations condensed out,
/// then every root of the rest, an independent method) to 1e-10. Model: NASTRAN-95's
/// hinged plate, 10×20 QUAD4 (d03011a), the 10 lowest roots (EIGR GIV with ND = 10).
#[test]
fn plate_roots_are_the_dense_solvers() {
    let inp = root().join("reference-data/nastran95-demos/inp/d03011a.inp");
    let text = std::fs::read_to_string(&inp).unwrap();
    // Its METHOD's EIGR asks for 3 roots by inverse power; ask for 10 by Givens.
    let text = text
        .replace("METHOD = 5 ", "METHOD = 99 ")
        .replace("BEGIN BULK", "BEGIN BULK\nEIGR,99,GIV,0.,,,10,,,+E99\n+E99,MASS");
    let d = parse_deck_str("d03011a", &text, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let (s, _) = solve(&d).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.modes.len(), 10);
    let (structure, _) = impactlab::model::build_structure(&d).unwrap();
    let dense =
        impactlab::assembly::frequencies_of(&structure.elements, structure.dofs.len(), 10).expect("condensable");
    for (m, w) in s.modes.iter().zip(&dense) {
        assert!(
            (m.radians - w).abs() <= 1e-10 * w,
            "mode {}: {} against {w}",
            m.mode,
            m.radians
        );
    }
}

/// Goal: the hinged plate's first frequency converges to the theory its deck states
/// (9.068997e-1, `d03011a.inp`'s comments: a square plate, hinged, a half modelled) at
/// the QUAD4's second order: the 20×40 mesh (d03012a) is 4× nearer than the 10×20
/// (d03011a); observed order log₂(e₁/e₂) within 0.2 of 2. Both decks are NASTRAN-95's
/// own, run as written (`impactlab run`).
#[test]
fn hinged_plate_converges_at_second_order() {
    let theory = 9.068997e-1;
    let first = |name: &str| {
        let d = read_deck(
            &root().join(format!("reference-data/nastran95-demos/inp/{name}.inp")),
            Default::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        solve(&d).unwrap_or_else(|e| panic!("{e}")).0.modes[0].cycles
    };
    let (e1, e2) = ((first("d03011a") - theory).abs(), (first("d03012a") - theory).abs());
    let order = (e1 / e2).log2();
    assert!((order - 2.0).abs() < 0.2, "errors {e1:e}, {e2:e}: order {order}");
}

/// Goal: `impactlab run` on a normal modes deck writes modes.csv (a row a root),
/// shapes.csv and summary.json, and refuses a transient run's flags.
#[test]
fn run_writes_the_roots_and_refuses_transient_flags() {
    let inp = root().join("reference-data/nastran95-demos/inp/d03011a.inp");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = impactlab(&["run", inp.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("modes.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4, "{csv}");
    assert!(csv.starts_with("mode,eigenvalue,radians,cycles,generalized_mass,generalized_stiffness,residual\n"));
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["solution"], "normal modes (SOL 103)");
    assert_eq!(summary["normalised"], "unit largest component");
    let shapes = std::fs::read_to_string(out.join("shapes.csv")).unwrap();
    assert!(shapes.lines().skip(1).all(|l| l.split(',').count() == 9));
    let o = impactlab(&["run", inp.to_str().unwrap(), "--steps", "10"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--steps applies to a transient run"));
}

/// Goal: from F1 = 0 every root is wanted, rigid-body roots included, though round-off
/// leaves them of either sign. Model: a free rod (two CRODs along x) beside a free
/// chain of masses 2, 2, 1 and springs k = 5e3 (`fuzz/seeds/modes-chain.bdf`, EIGR GIV
/// F1 = 0, ND = 3, NORM POINT on the rod): two rigid-body roots, zero to 1e-12 of the
/// rod's top root, then the chain's first, k(5 − √5)/4 (det(K − λM) = 0 of the 3×3
/// chain), to 1e-12.
#[test]
fn rigid_body_roots_of_either_sign_are_kept_from_f1_zero() {
    let d = read_deck(&root().join("fuzz/seeds/modes-chain.bdf"), Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let (s, _) = solve(&d).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.modes.len(), 3, "{:?}", s.modes);
    let top = 8e10;
    assert!(
        s.modes[..2].iter().all(|m| m.eigenvalue.abs() <= 1e-12 * top),
        "{:?}",
        s.modes
    );
    let exact = 5e3 * (5.0 - 5f64.sqrt()) / 4.0;
    assert!(
        (s.modes[2].eigenvalue - exact).abs() <= 1e-12 * exact,
        "{}",
        s.modes[2].eigenvalue
    );
    assert!(s.modes.iter().all(|m| m.residual < 1e-14), "{:?}", s.modes);
}
