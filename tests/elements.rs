//! The element interface: what the ledger books is what assembly assembled, for every
//! element kind.

use impactlab::assembly::assemble;
use impactlab::deck::{parse_deck_str, ReadOptions};
use impactlab::ledger::strain_energy;
use impactlab::model::build_model;
use std::collections::BTreeSet;

/// Goal: the ledger's target strain energy is ½uᵀKu of the assembled K whatever the
/// element kinds. Model: a 2×2 CQUAD4 plate with membrane and bending (MID1, MID2),
/// two CRODs (one in the plane, one out of it, so axial and torsion terms enter) and a
/// CONM2 with rotary inertia; one edge clamped. Reference: ½uᵀKu with K from
/// assembly, at a displacement with every solved DOF nonzero. Tolerance: 1e-12
/// relative (round-off of a sum of a few hundred terms).
#[test]
fn strain_energy_is_half_utku_for_a_model_with_every_element_kind() {
    let mut d = String::from("SOL 9\nCEND\nTSTEP = 1\nSPC = 1\nBEGIN BULK\nTSTEP,1,1,1.0-6,1\n");
    for r in 0..3 {
        for c in 0..3 {
            d += &format!("GRID,{},,{}.0,{}.0,0.0\n", 10 * r + c + 1, c, r);
        }
    }
    d += "GRID,100,,2.0,2.0,1.5\nSPC1,1,123456,1,2,3\n";
    for r in 0..2 {
        for c in 0..2 {
            let g = 10 * r + c + 1;
            d += &format!("CQUAD4,{},1,{},{},{},{}\n", g, g, g + 1, g + 11, g + 10);
        }
    }
    d += "PSHELL,1,1,0.1,2,1.0\nMAT1,1,1.0+7,,0.3,0.1\nMAT1,2,2.0+7,,0.25,0.1\n";
    d += "CROD,50,5,21,22\nCROD,51,5,23,100\nPROD,5,3,0.2,0.01\nMAT1,3,3.0+7,,0.3,0.3\n";
    d += "CONM2,60,100,0,2.0,,,,\n,0.1,0.0,0.2,0.0,0.0,0.3\nENDDATA\n";
    let deck = parse_deck_str("every-kind.bdf", &d, ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let model = build_model(&deck).unwrap_or_else(|e| panic!("{e}")).0;
    let cards: BTreeSet<&str> = model.elements.iter().map(|e| e.kernel.card()).collect();
    assert_eq!(cards, BTreeSet::from(["CONM2", "CQUAD4", "CROD"]));
    let sys = assemble(&model);
    let n = model.n();
    let u: Vec<f64> = (0..n).map(|i| 1e-3 * (1.0 + (i as f64 * 0.7).sin())).collect();
    let mut ku = vec![0.0; n];
    sys.k_mul(&u, &mut ku);
    let reference = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
    let booked = strain_energy(&model, &u);
    assert!(reference > 0.0);
    assert!(
        ((booked - reference) / reference).abs() < 1e-12,
        "ledger {booked:e} vs ½uᵀKu {reference:e}"
    );
    // Every kind with stiffness contributes: removing an element's share changes it.
    for e in model.elements.iter() {
        let share = e.strain_energy(&u);
        match e.kernel.card() {
            "CONM2" => assert_eq!(share, 0.0),
            card => assert!(share > 1e-6 * reference, "{card} {}: {share:e}", e.eid),
        }
    }
}

/// Goal: an element's kinetic energy is ½vᵀM_e v of the mass it hands to assembly, so
/// the elements' sum is ½vᵀMv of the assembled M, also where offsets couple a mass's
/// translations to its grid's rotations. Model: the paper's plate on a 5×5 mesh with
/// one blade stiffener (CBARs offset from their grids) and the impactor's CONM2.
/// Reference: ½vᵀMv by the assembled M's product, at a velocity with every solved DOF
/// nonzero. Tolerance: 1e-12 relative (round-off of a sum of a few hundred terms).
#[test]
fn element_kinetic_energies_add_up_to_half_vtmv() {
    let deck =
        impactlab::mesh::stiffened_plate_deck(5, impactlab::mesh::Cells::Quad4, &impactlab::mesh::Stiffeners::blade(1))
            .unwrap();
    let model = impactlab::model_from_text("stiffened", &deck).unwrap();
    let sys = assemble(&model);
    let v: Vec<f64> = (0..model.n()).map(|i| ((i as f64) * 0.37 + 0.1).cos()).collect();
    let mut mv = vec![0.0; model.n()];
    sys.m_mul(&v, &mut mv);
    let expected = 0.5 * v.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>();
    let sum: f64 = model.elements.iter().map(|e| e.kinetic_energy(&v)).sum();
    assert!(
        model
            .elements
            .iter()
            .any(|e| e.kernel.card() == "CBAR" && e.placement.is_some()),
        "the stiffener's bars are offset"
    );
    assert!((sum / expected - 1.0).abs() < 1e-12, "{sum} vs {expected}");
}
