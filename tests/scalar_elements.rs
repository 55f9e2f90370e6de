//! Scalar springs and masses (CELAS1-4, CMASS1-4) in the problems they exist for:
//! springs in series under a static force, a mass between two points, and a spring
//! in the paper's rod, whose ledger must close with the spring's energy in it.

use crate::common;

use common::run;
use impactlab::integrate::Scheme;
use impactlab::run::statics::solve;

/// Goal: two springs in series, k1 = 200 between grids 1 and 2 (CELAS1, PELAS) and
/// k2 = 100 from grid 2 to ground (CELAS2), under F = 6 on grid 1: u2 = F/k2 = 0.06,
/// u1 = F(1/k1 + 1/k2) = 0.09, whatever the grids' displacement frames. Model: two
/// grids, every other component held. Reference: statics of springs. Tolerance:
/// round-off of one factorisation (1e-14 relative).
#[test]
fn springs_in_series_share_a_static_force() {
    let deck = "SOL 101\nCEND\nSPC = 1\nLOAD = 1\nBEGIN BULK\n\
                GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nSPC1,1,23456,1,2\n\
                CELAS1,10,7,1,1,2,1\nPELAS,7,200.\nCELAS2,11,100.,2,1\nFORCE,1,1,,6.,1.,0.,0.\nENDDATA\n";
    let d = impactlab::deck::parse_deck_str("springs.bdf", deck, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let (s, _) = solve(&d).unwrap_or_else(|e| panic!("{e}"));
    let (u1, u2) = (s.displacement(1, 1).unwrap(), s.displacement(2, 1).unwrap());
    assert!((u2 - 0.06).abs() < 1e-14 * 0.06, "{u2}");
    assert!((u1 - 0.09).abs() < 1e-14 * 0.09, "{u1}");
    // Clapeyron: the springs store half the work of the force, ½ F u1.
    assert!((s.strain_energy - 0.27).abs() < 1e-14 * 0.27, "{}", s.strain_energy);
}

/// Goal: a CMASS2 of 3 on grid 1's x to ground weighs 3 along x; a CMASS1 of 2
/// between grids 1 and 2 along y ("a scalar mass between two points", kinetic
/// energy ½m(u̇₁ − u̇₂)²) adds nothing to the rigid-body mass, as NASTRAN's grid point
/// weight generator finds. Exact.
#[test]
fn scalar_masses_weigh_as_the_grid_point_weight_generator_weighs_them() {
    let deck = "SOL 101\nCEND\nBEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n\
                CMASS2,20,3.,1,1\nCMASS1,21,8,1,2,2,2\nPMASS,8,2.\nENDDATA\n";
    let d = impactlab::deck::parse_deck_str(
        "masses.bdf",
        deck,
        impactlab::deck::ReadOptions {
            structure: true,
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let r = impactlab::model::check::check(&d);
    assert!(r.takes, "{r:?}");
    assert_eq!(r.weight.unwrap().mass, [3.0, 0.0, 0.0]);
    assert_eq!(
        (r.elements.get("CMASS1"), r.elements.get("CMASS2")),
        (Some(&1), Some(&1))
    );
}

/// Goal: a spring enters a transient run's system consistently (its block on the
/// right DOF, symmetric): the ledger, whose strain energy is ½uᵀKu of the assembled
/// stiffness, closes. Model: the paper's rod with a CELAS2 of 1e4 lbf/in from its far
/// end (grid 145) to ground, which the pulse reaches at about 1.8e-4 s and loads; run
/// to 5e-4 s by the energy-consistent scheme. Reference: energy conservation.
/// Tolerance: 1e-10, the rod's own bound for this scheme (tests/rod_impact.rs). The
/// kernel's own strain energy against its block is the unit test in
/// src/elements/scalar.rs (the ledger reads the matrices, not the kernels' energies).
#[test]
fn a_spring_at_the_rods_end_keeps_the_ledger_closed() {
    let text = impactlab::paper::ROD_DECK.replace("ENDDATA", "CELAS2,9001,1.0+4,145,1\nENDDATA");
    assert_ne!(text, impactlab::paper::ROD_DECK);
    let m = impactlab::model_from_text("rod-spring", &text).unwrap_or_else(|e| panic!("{e}"));
    assert!(m.elements.iter().any(|e| e.kernel.card() == "CELAS2"));
    let r = run(&m, Scheme::Energy, Some(2e-7), Some(2500));
    let e = r.summary.energy.max_relative_error.unwrap();
    assert!(e < 1e-10, "{e}");
}
