//! The bushing (CBUSH, PBUSH) in the problems with closed forms: a spring at one end of
//! an arm under a load at the other, and a mass on a grounded bushing in a turned
//! system.

use impactlab::deck::parse_deck_str;
use nalgebra::Vector3;

const PBUSH: &str = "PBUSH,3,K,100.,200.,300.,400.,500.,600.\n";

/// Goal: a CBUSH whose spring sits at GA (S = 0), GA clamped, under a force F along
/// the element's y axis at GB, a distance L away: the spring carries F and the arm's
/// moment F·L about z, so GB moves F/K2 + F·L²/K6 along y and turns F·L/K6 about z
/// (the rigid arm's kinematics), and under a force along x it moves F/K1. With the
/// spring at GB (S = 1) the arm is gone: F/K2. The element's axes: x from GA to GB
/// (turned in space), y in the plane of the orientation vector X. Tolerance:
/// round-off of one factorisation (1e-12 relative).
#[test]
fn a_bushing_at_the_end_of_an_arm_carries_its_moment() {
    let (ga, gb): (Vector3<f64>, Vector3<f64>) = (Vector3::new(1.0, 2.0, 3.0), Vector3::new(2.0, 4.0, 5.0));
    let l = (gb - ga).norm();
    let x = (gb - ga) / l;
    let v = Vector3::new(0.0, 0.0, 1.0);
    let y = (v - x * v.dot(&x)).normalize();
    let z = x.cross(&y);
    for (s, along, expected_u, expected_turn) in [
        (0.0, y, 1.0 / 200.0 + l * l / 600.0, l / 600.0),
        (1.0, y, 1.0 / 200.0, 0.0),
        (0.0, x, 1.0 / 100.0, 0.0),
    ] {
        let deck = format!(
            "SOL 101\nCEND\nSPC = 1\nLOAD = 1\nBEGIN BULK\nGRID,1,,{},{},{}\nGRID,2,,{},{},{}\nSPC1,1,123456,1\n\
             CBUSH,9,3,1,2,0.,0.,1.,,+B\n+B,{s}\n{PBUSH}FORCE,1,2,,1.,{:e},{:e},{:e}\nENDDATA\n",
            ga.x, ga.y, ga.z, gb.x, gb.y, gb.z, along.x, along.y, along.z
        );
        let d = parse_deck_str("bush.bdf", &deck, Default::default()).unwrap_or_else(|e| panic!("{e}"));
        let (sol, _) = impactlab::run::statics::solve(&d).unwrap_or_else(|e| panic!("{e}"));
        let u = Vector3::from_fn(|c, _| sol.displacement(2, c + 1).unwrap());
        let t = Vector3::from_fn(|c, _| sol.displacement(2, c + 4).unwrap());
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-3);
        assert!(
            close(u.dot(&along), expected_u),
            "S = {s}: {} against {expected_u}",
            u.dot(&along)
        );
        assert!(
            close(t.dot(&z), expected_turn),
            "S = {s}: {} against {expected_turn}",
            t.dot(&z)
        );
        // Clapeyron: the spring stores half the work of the force.
        assert!(close(sol.strain_energy, 0.5 * u.dot(&along)), "{}", sol.strain_energy);
    }
}

/// Goal: a CONM2 of mass m and inertia I·𝟙 on a bushing to ground (GB blank) whose
/// axes are system 5's (CID, turned in space) vibrates at λ = K1/m, K2/m, K3/m, K4/I,
/// K5/I, K6/I: the bushing is diagonal in its axes and so is the mass. Tolerance:
/// 1e-12 of the largest root.
#[test]
fn a_mass_on_a_grounded_bushing_vibrates_at_its_stiffnesses_over_its_mass() {
    let (m, i) = (2.0, 0.5);
    let deck = format!(
        "SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,6\n\
         CORD2R,5,0,1.0,2.0,3.0,1.5,2.5,3.8,+C5\n+C5,2.0,1.0,3.3\nGRID,7,,1.0,2.0,3.0\n\
         CBUSH,9,3,7,,,,,5\n{PBUSH}CONM2,11,7,0,{m},,,,,+C1\n+C1,{i},,{i},,,{i}\nENDDATA\n"
    );
    let d = parse_deck_str("bush.bdf", &deck, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let s = impactlab::run::modes::solve(&d).unwrap_or_else(|e| panic!("{e}")).0;
    let mut expected = [100.0 / m, 200.0 / m, 300.0 / m, 400.0 / i, 500.0 / i, 600.0 / i];
    expected.sort_by(f64::total_cmp);
    assert_eq!(s.modes.len(), 6);
    for (mode, e) in s.modes.iter().zip(expected) {
        assert!(
            (mode.eigenvalue - e).abs() <= 1e-12 * 1200.0,
            "mode {}: {} against {e}",
            mode.mode,
            mode.eigenvalue
        );
    }
}
