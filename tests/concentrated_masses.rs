//! Concentrated masses: CONM1's general 6×6 matrix at a grid, turned from its system's
//! axes, against the generalised eigenproblem of a grid on six springs and against a
//! CONM2 written out as NASTRAN's manual writes one.

use impactlab::deck::{parse_deck_str, Deck, ReadOptions};
use impactlab::run::modes::solve;
use nalgebra::{Matrix3, Matrix6, Vector3};

/// System 5: a CORD2R with origin A = (1, 2, 3), its z axis towards B and C in its xz
/// plane.
const CORD5: &str = "CORD2R,5,0,1.0,2.0,3.0,1.5,2.5,3.8,+C5\n+C5,2.0,1.0,3.3\n";

/// System 5's axes (columns, basic), from A, B and C by the CORD2R rule.
fn axes5() -> Matrix3<f64> {
    let (a, b, c) = (
        Vector3::new(1.0, 2.0, 3.0),
        Vector3::new(1.5, 2.5, 3.8),
        Vector3::new(2.0, 1.0, 3.3),
    );
    let z = (b - a).normalize();
    let x = ((c - a) - z * (c - a).dot(&z)).normalize();
    Matrix3::from_columns(&[x, z.cross(&x), z])
}

/// Grid 7 at (1, 2, 3) held along each basic component by a CELAS2 of 100·i (i = 1..6),
/// carrying `mass` (cards), normal modes by EIGRL for all six roots.
fn on_springs(mass: &str, param: &str) -> Deck {
    let mut d =
        format!("SOL 103\nCEND\nMETHOD = 1\nBEGIN BULK\nEIGRL,1,,,6\n{param}{CORD5}GRID,7,,1.0,2.0,3.0\n{mass}");
    for i in 1..=6 {
        d.push_str(&format!("CELAS2,{i},{}.,7,{i}\n", 100 * i));
    }
    d.push_str("ENDDATA\n");
    parse_deck_str(
        "masses.bdf",
        &d,
        ReadOptions {
            structure: true,
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// A CONM1 card in system 5 of the symmetric matrix `m`, its lower triangle by rows
/// in free field.
fn conm1(eid: i64, m: &Matrix6<f64>) -> String {
    let lower: Vec<String> = (0..6)
        .flat_map(|r| (0..=r).map(move |c| (r, c)))
        .map(|(r, c)| format!("{:e}", m[(r, c)]))
        .collect();
    format!(
        "CONM1,{eid},7,5,{},+M1\n+M1,{},+M2\n+M2,{}\n",
        lower[..5].join(","),
        lower[5..13].join(","),
        lower[13..].join(",")
    )
}

/// Goal: a CONM1 ("a 6x6 symmetric mass matrix", `manual/BULK.TXT`, in "any selected
/// coordinate system", `manual/INTR.TXT`) in a turned system is the mass
/// Λ M Λᵀ (Λ = diag(R, R), R the system's axes) on the grid's basic DOFs: the grid on
/// six springs K = diag(100, …, 600) vibrates at the roots of det(K − λ Λ M Λᵀ) = 0,
/// solved here by nalgebra's symmetric eigen-solver on K^{-1/2} Λ M Λᵀ K^{-1/2}, an
/// independent path. M: all 21 terms given, positive definite. Tolerance: 1e-12 of
/// the largest root (round-off). PARAM WTMASS 0.5 multiplies every term, CONM1's
/// included (`manual/BULK.TXT`, PARAM WTMASS): every root doubles.
#[test]
fn a_grid_on_springs_vibrates_at_the_roots_of_its_turned_conm1() {
    let lower = [
        2.0, 0.1, 3.0, -0.2, 0.3, 4.0, 0.05, 0.4, -0.3, 5.0, 0.2, -0.1, 0.15, 0.3, 6.0, 0.25, -0.2, 0.1, 0.05, 0.3, 7.0,
    ];
    let mut m = Matrix6::zeros();
    let mut k = 0;
    for r in 0..6 {
        for c in 0..=r {
            m[(r, c)] = lower[k];
            m[(c, r)] = lower[k];
            k += 1;
        }
    }
    let mut lambda = Matrix6::zeros();
    lambda.fixed_view_mut::<3, 3>(0, 0).copy_from(&axes5());
    lambda.fixed_view_mut::<3, 3>(3, 3).copy_from(&axes5());
    let basic = lambda * m * lambda.transpose();
    let scale = Matrix6::from_diagonal(&nalgebra::Vector6::from_fn(|i, _| {
        1.0 / (100.0 * (i + 1) as f64).sqrt()
    }));
    let mut expected: Vec<f64> = (scale * basic * scale)
        .symmetric_eigenvalues()
        .iter()
        .map(|mu| 1.0 / mu)
        .collect();
    expected.sort_by(f64::total_cmp);
    for (param, factor) in [("", 1.0), ("PARAM,WTMASS,0.5\n", 2.0)] {
        let s = solve(&on_springs(&conm1(11, &m), param))
            .unwrap_or_else(|e| panic!("{e}"))
            .0;
        assert_eq!(s.modes.len(), 6);
        let top = factor * expected[5];
        for (mode, e) in s.modes.iter().zip(&expected) {
            assert!(
                (mode.eigenvalue - factor * e).abs() <= 1e-12 * top,
                "WTMASS factor {factor}, mode {}: {} against {}",
                mode.mode,
                mode.eigenvalue,
                factor * e
            );
        }
    }
}

/// Goal: a CONM2 and the CONM1 the manual says it is are one mass. The manual's
/// correspondence (`manual/INTR.TXT`: CONM2's "I11, I21, I22, I31, I32, and I33 ...
/// correspond to M44, M54, M55, M64, M65, and M66 on CONM1 (M54 = -Ixy, M64 = -Ixz,
/// M65 = -Iyz) with sign changes on the off-diagonal terms") and CONM2's matrix with
/// its offset X (`manual/BULK.TXT`, CONM2 remark 4: m·I, the coupling m[X]×ᵀ and
/// BI11 = I11 + M(X2² + X3²), BI21 = I21 + M·X1·X2, …), both in system 5: the grid
/// point weight generator's answer (`check`) and the six roots on springs agree.
/// Tolerance: 1e-12 relative (round-off of the two paths' turns).
#[test]
fn a_conm2_written_out_as_a_conm1_is_the_same_mass() {
    let (mass, x, i) = (2.5, [0.3, -0.2, 0.1], [1.0, 0.1, 2.0, 0.2, 0.3, 3.0]);
    let conm2 = format!(
        "CONM2,11,7,5,{mass},{},{},{},,+C1\n+C1,{},{},{},{},{},{}\n",
        x[0], x[1], x[2], i[0], i[1], i[2], i[3], i[4], i[5]
    );
    let [x1, x2, x3] = x;
    let [i11, i21, i22, i31, i32, i33] = i;
    let bi = |i: f64, a: f64, b: f64| i + mass * (a * a + b * b);
    let m = Matrix6::from_row_slice(&[
        mass,
        0.0,
        0.0,
        0.0,
        mass * x3,
        -mass * x2,
        0.0,
        mass,
        0.0,
        -mass * x3,
        0.0,
        mass * x1,
        0.0,
        0.0,
        mass,
        mass * x2,
        -mass * x1,
        0.0,
        0.0,
        -mass * x3,
        mass * x2,
        bi(i11, x2, x3),
        -(i21 + mass * x1 * x2),
        -(i31 + mass * x1 * x3),
        mass * x3,
        0.0,
        -mass * x1,
        -(i21 + mass * x1 * x2),
        bi(i22, x1, x3),
        -(i32 + mass * x2 * x3),
        -mass * x2,
        mass * x1,
        0.0,
        -(i31 + mass * x1 * x3),
        -(i32 + mass * x2 * x3),
        bi(i33, x1, x2),
    ]);
    assert_eq!(m, m.transpose());
    let (a, b) = (on_springs(&conm2, ""), on_springs(&conm1(11, &m), ""));
    let (ra, rb) = (impactlab::model::check::check(&a), impactlab::model::check::check(&b));
    assert!(ra.takes && rb.takes, "{ra:?}\n{rb:?}");
    let (wa, wb) = (ra.weight.unwrap(), rb.weight.unwrap());
    let close = |p: f64, q: f64, scale: f64| (p - q).abs() <= 1e-12 * scale;
    for c in 0..3 {
        assert!(close(wa.mass[c], wb.mass[c], mass), "{wa:?}\n{wb:?}");
        assert!(
            close(wa.centre.unwrap()[c], wb.centre.unwrap()[c], 4.0),
            "{wa:?}\n{wb:?}"
        );
        for d in 0..3 {
            assert!(close(wa.inertia[c][d], wb.inertia[c][d], 3.0), "{wa:?}\n{wb:?}");
        }
    }
    let (sa, sb) = (solve(&a).unwrap().0, solve(&b).unwrap().0);
    let top = sa.modes[5].eigenvalue;
    for (p, q) in sa.modes.iter().zip(&sb.modes) {
        assert!(
            close(p.eigenvalue, q.eigenvalue, top),
            "{} against {}",
            p.eigenvalue,
            q.eigenvalue
        );
    }
}
