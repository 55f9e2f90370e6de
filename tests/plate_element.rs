//! The CQUAD4 (bilinear membrane + DKQ bending) on textbook plate problems.
//! Patch tests on a distorted element live with the element (src/elements/quad4.rs).

use impactlab::assembly::assemble;
use impactlab::deck::{parse_deck_str, ReadOptions};
use impactlab::integrate::linear::Factor;
use impactlab::model::{build_model, DofLabel, Model};

/// A square plate a × a on an n × n mesh; `edge` are the SPC1 components on the boundary;
/// `ps` the GRDSET PS; `mat` the material cards, PSHELL with MID1 = 1, MID2 = 2.
fn square_plate(n: usize, a: f64, edge: &str, ps: &str, mat: &str, t: f64) -> Model {
    let cards = format!("PSHELL,1,1,{t:?},2,1.0\n{mat}");
    let d = impactlab::mesh::square_plate_deck(n, a, edge, ps, &cards);
    let deck = parse_deck_str("plate.bdf", &d, ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    build_model(&deck).unwrap_or_else(|e| panic!("{e}")).0
}

const E: f64 = 1.0e7;
const NU: f64 = 0.3;
const T: f64 = 0.1;

fn iso() -> String {
    format!("MAT1,1,{E:?},,{NU:?},1.0\nMAT1,2,{E:?},,{NU:?},1.0")
}

/// Static centre deflection under a unit point load.
fn centre_deflection(n: usize, edge: &str) -> f64 {
    let m = square_plate(n, 1.0, edge, "6", &iso(), T);
    let sys = assemble(&m);
    let k = sys.k_csc.clone();
    let mut f = Factor::new(&k, &m.dofs).expect("restrained plate");
    let centre = DofLabel {
        point: (1000 * (n / 2 + 1) + n / 2 + 1) as i64,
        comp: 3,
    };
    let i = m.dofs.iter().position(|d| *d == centre).unwrap();
    let mut x = vec![0.0; m.n()];
    x[i] = 1.0;
    f.solve_in_place(&mut x);
    x[i]
}

fn d_iso() -> f64 {
    E * T.powi(3) / (12.0 * (1.0 - NU * NU))
}

/// Observed order from three meshes halving h: log2((w1 − w2)/(w2 − w3)).
fn observed_order(w: &[f64]) -> f64 {
    ((w[0] - w[1]) / (w[1] - w[2])).log2()
}

/// Goal: DKQ converges to the thin-plate solution at second order.
/// Model: clamped square isotropic plate (a = 1, t = 0.1, E = 1e7, ν = 0.3), unit centre
/// load, meshes 8, 16, 32, 64. Reference: w = 0.00560 P a²/D (Timoshenko &
/// Woinowsky-Krieger, table 55; 0.005612 to four digits). Assertions: observed order
/// from the last three meshes 2 ± 0.3 (DKQ is O(h²); a point load's logarithmic
/// curvature singularity makes the centre deflection error O(h² ln h), measured order
/// 1.73 on 16-32-64, and 1.4 / 1.65 on the coarser triples),
/// Richardson extrapolation within 0.5 % of 0.005612, the finest mesh within 1 % of 0.00560.
#[test]
fn clamped_square_plate_centre_load_converges_at_second_order() {
    let w: Vec<f64> = [8, 16, 32, 64]
        .iter()
        .map(|&n| centre_deflection(n, "123456") * d_iso())
        .collect();
    let p = observed_order(&w[1..]);
    let extrapolated = w[3] + (w[3] - w[2]) / (2f64.powf(p) - 1.0);
    eprintln!("clamped: w·D/(P a²) = {w:?}, order {p:.3}, extrapolated {extrapolated:.6}");
    assert!((p - 2.0).abs() < 0.3, "order {p}, {w:?}");
    assert!((extrapolated - 0.005612).abs() < 0.005 * 0.005612, "{extrapolated}");
    assert!((w[3] - 0.00560).abs() < 0.01 * 0.00560, "{}", w[3]);
}

/// Goal: the same for simple supports. Model: as above with w = 0 on the edges and the
/// rotations free. Reference: w = 0.01160 P a²/D (Timoshenko & Woinowsky-Krieger,
/// Navier series: 0.011601). Assertions as for the clamped plate (measured order 1.73,
/// extrapolated 0.011599).
#[test]
fn simply_supported_square_plate_centre_load_converges_at_second_order() {
    let w: Vec<f64> = [4, 8, 16, 32]
        .iter()
        .map(|&n| centre_deflection(n, "123") * d_iso())
        .collect();
    let p = observed_order(&w[1..]);
    let extrapolated = w[3] + (w[3] - w[2]) / (2f64.powf(p) - 1.0);
    eprintln!("simply supported: w·D/(P a²) = {w:?}, order {p:.3}, extrapolated {extrapolated:.6}");
    assert!((p - 2.0).abs() < 0.3, "order {p}, {w:?}");
    assert!((extrapolated - 0.011601).abs() < 0.005 * 0.011601, "{extrapolated}");
    assert!((w[3] - 0.01160).abs() < 0.01 * 0.01160, "{}", w[3]);
}

/// Goal: bending stiffness and lumped mass give the right dynamics for an orthotropic
/// plate. Model: simply supported square plate a = 6 in, t = 0.15 in, specially
/// orthotropic MAT2 (G11 = 5.7e6, G12 = 2.9e5, G22 = 1.4e6, G33 = 5.7e5 psi,
/// ρ = 1.8e-4: the paper's bending material without its tiny G13, G23), bending only.
/// Reference: Navier, ω_mn = π² √[(D11 m⁴/a⁴ + 2(D12 + 2D66) m²n²/a²b² + D22 n⁴/b⁴)/ρh].
/// Assertions: the modes (1,1), (1,2), (2,1) converge at order 2 ± 0.4 from the 8 × 8
/// to the 16 × 16 and 32 × 32 meshes, and the 32 × 32 values are within 1 % of Navier.
#[test]
fn simply_supported_orthotropic_plate_natural_frequencies_match_navier() {
    let (a, t, rho): (f64, f64, f64) = (6.0, 0.15, 1.8e-4);
    let g = [5.7e6, 2.9e5, 0.0, 1.4e6, 0.0, 5.7e5];
    let d = |x: f64| x * t.powi(3) / 12.0;
    let (d11, d12, d22, d66) = (d(g[0]), d(g[1]), d(g[3]), d(g[5]));
    let navier = |m: f64, n: f64| {
        std::f64::consts::PI.powi(2)
            * ((d11 * m.powi(4) + 2.0 * (d12 + 2.0 * d66) * m * m * n * n + d22 * n.powi(4)) / a.powi(4) / (rho * t))
                .sqrt()
    };
    let mut exact = [navier(1.0, 1.0), navier(1.0, 2.0), navier(2.0, 1.0)];
    exact.sort_by(|x, y| x.partial_cmp(y).unwrap());
    // The library's closed form (the navier_frequencies check's reference) is this one.
    let lib = impactlab::physics::analytic::navier_frequencies(a, rho * t, [d11, d22, d12, d66], 3);
    for (l, e) in lib.iter().zip(&exact) {
        assert!((l - e).abs() < 1e-12 * e, "{l} vs {e}");
    }
    let f = |n: usize| {
        let m = impactlab::mesh::navier_plate(n, a, t, g, rho, None, Cells::Quad4).unwrap();
        impactlab::eigen::lowest_frequencies(&m, 3).unwrap()
    };
    let (f8, f16, f32) = (f(8), f(16), f(32));
    for k in 0..3 {
        let err = |f: &[f64]| (f[k] - exact[k]).abs();
        let (p1, p2) = ((err(&f8) / err(&f16)).log2(), (err(&f16) / err(&f32)).log2());
        eprintln!(
            "mode {k}: ω 8/16/32 = {:.1} {:.1} {:.1}, Navier {:.1}, orders {p1:.2} {p2:.2}",
            f8[k], f16[k], f32[k], exact[k]
        );
        for p in [p1, p2] {
            assert!(
                (p - 2.0).abs() < 0.4,
                "mode {k}: orders {p1} {p2} ({} {} {} vs {})",
                f8[k],
                f16[k],
                f32[k],
                exact[k]
            );
        }
        assert!(
            err(&f32) < 0.01 * exact[k],
            "mode {k}: {} vs Navier {}",
            f32[k],
            exact[k]
        );
    }
}

/// The lowest natural frequency ω (rad/s) of a simply supported isotropic square plate
/// a × a, thickness t, on an n × n mesh of `cells` whose PSHELL names MID3 (the MAT1's
/// G, TS/T blank: 0.833333): the shear-deformable plate (MITC4 quadrilaterals, or the
/// squares cut into DKMT triangles). The supports are Navier's
/// ("hard" simple support): w = 0 and the rotation along the edge fixed (on x = 0, a
/// the rotation βy, R1; on y = 0, a, βx, R2). A Mindlin plate with the edge rotation
/// free ("soft") has boundary layers and a lower frequency than Navier's series.
fn mindlin_plate_frequency(n: usize, a: f64, t: f64, cells: Cells) -> f64 {
    let cards = format!("PSHELL,1,1,{t:?},1,1.0,1\nMAT1,1,{E:?},,{NU:?},{RHO:?}");
    let deck = impactlab::mesh::square_plate_deck(n, a, "3", "126", &cards)
        .replace("ENDDATA", &format!("{}ENDDATA", impactlab::mesh::hard_supports(n)));
    let m = impactlab::model_from_text("mindlin-plate", &cells.cut(deck)).unwrap_or_else(|e| panic!("{e}"));
    assert!(m.elements.iter().all(|e| e.kernel.card() == cells.card()));
    impactlab::eigen::lowest_frequencies(&m, 1).unwrap()[0]
}

use impactlab::mesh::Cells;

const RHO: f64 = 2.5e-4;
/// PSHELL's TS/T when blank: the shear correction factor.
const KAPPA: f64 = 0.833333;

/// Mode (1,1) of the simply supported square plate: (Kirchhoff ω, first-order shear
/// deformation ω). With no rotary inertia (NASTRAN's lumped mass, as the element's),
/// eliminating the rotations from Mindlin's equations for w = W sin(πx/a) sin(πy/a)
/// gives ω² = ω_K² / (1 + D k²/(κ G t)), k² = 2π²/a², ω_K² = D k⁴/(ρ t).
fn mode_11(a: f64, t: f64) -> (f64, f64) {
    let d = E * t.powi(3) / (12.0 * (1.0 - NU * NU));
    let g = E / (2.0 * (1.0 + NU));
    let k2 = 2.0 * (std::f64::consts::PI / a).powi(2);
    let kirchhoff = (d * k2 * k2 / (RHO * t)).sqrt();
    (kirchhoff, kirchhoff / (1.0 + d * k2 / (KAPPA * g * t)).sqrt())
}

/// Goal: the shear plate oscillates at the first-order shear deformation frequency,
/// converging with the mesh at the element's order. Model: simply supported square
/// isotropic plate a = 1 (E = 1e7, ν = 0.3, ρ = 2.5e-4), t/a = 1/20 and 1/5, PSHELL
/// with MID3, meshes 8, 16, 32 of CQUAD4 (MITC4) and of CTRIA3 (DKMT, each square cut
/// in two). Reference: Mindlin's mode (1,1) without rotary inertia ([`mode_11`]).
/// Assertions: observed order above 1.6 from 8-16 and 16-32 (measured 1.99 to 2.00
/// for MITC4, 2.02 to 2.20 for DKMT); the 32 × 32 mesh within 0.1 % (measured
/// −6.6e-4 MITC4, −2.9e-4 DKMT at 1/5: either element's shear stiffness 2 % off moves
/// ω by about 0.18 % there and fails it). At t/a = 1/5 the thin plate's ω is 10.7 % too high (the
/// closed forms' ratio √(1 + π²(t/a)²/(3κ(1 − ν))) − 1); at 1/20, 0.70 %.
#[test]
fn simply_supported_thick_plate_frequency_matches_mindlin() {
    for (t, cells) in [0.05, 0.2]
        .into_iter()
        .flat_map(|t| [(t, Cells::Quad4), (t, Cells::Tria3)])
    {
        let (kirchhoff, mindlin) = mode_11(1.0, t);
        let w: Vec<f64> = [8, 16, 32]
            .iter()
            .map(|&n| mindlin_plate_frequency(n, 1.0, t, cells))
            .collect();
        let err = |k: usize| (w[k] - mindlin).abs();
        let (p1, p2) = ((err(0) / err(1)).log2(), (err(1) / err(2)).log2());
        eprintln!(
            "{} t/a = {t}: ω 8/16/32 = {w:?}, Mindlin {mindlin:.3}, Kirchhoff {kirchhoff:.3} ({:+.2} %), orders {p1:.2} {p2:.2}",
            cells.card(),
            100.0 * (kirchhoff / mindlin - 1.0)
        );
        for p in [p1, p2] {
            assert!(p > 1.6, "t/a = {t}: orders {p1} {p2}, {w:?} vs {mindlin}");
        }
        assert!(err(2) < 1e-3 * mindlin, "t/a = {t}: {} vs {mindlin}", w[2]);
    }
    let thick = mode_11(1.0, 0.2);
    assert!((thick.0 / thick.1 - 1.107).abs() < 1e-3, "{thick:?}");
}

/// Goal: the orthotropic shear plate oscillates at the first-order shear deformation
/// frequency, converging with the mesh at the element's order, thick and moderately
/// thin. Model: simply supported square plate a = 1 of the paper's bending material
/// (MAT2 G11 = 5.7e6, G12 = 2.9e5, G22 = 1.4e6, G33 = 5.7e5 psi, ρ = 1.8e-4) with a
/// MID3 MAT2 of the cross-ply's average transverse shear moduli (G11 = 5.33e5 in xz,
/// G22 = 4.96e5 in yz, TS/T blank), t/a = 1/20 and 1/5, Navier's hard supports,
/// meshes 8, 16, 32. Reference: Mindlin's Navier solution for a specially orthotropic
/// plate, no rotary inertia ([`impactlab::physics::analytic::mindlin_navier_frequencies`],
/// K55 = κ G11 t, K44 = κ G22 t). Both elements, as above. Assertions: observed order
/// above 1.6 from 8-16 and 16-32 (MITC4 1.98 to 2.00; DKMT 2.2 to 3.5, its thin
/// and thick errors of opposite sign); the 32 × 32 mesh within 0.1 %; the thin (Kirchhoff) frequency is printed
/// against it (shear matters more in the orthotropic plate, whose bending stiffness
/// is ten times its transverse shear modulus in xz).
#[test]
fn simply_supported_orthotropic_thick_plate_frequency_matches_mindlin() {
    use impactlab::physics::analytic::{mindlin_navier_frequencies, navier_frequencies};
    let (a, rho) = (1.0, 1.8e-4);
    let (g11, g12, g22, g66, s11, s22) = (5.7e6, 2.9e5, 1.4e6, 5.7e5, 5.33e5, 4.96e5);
    for (t, cells) in [0.05f64, 0.2]
        .into_iter()
        .flat_map(|t| [(t, Cells::Quad4), (t, Cells::Tria3)])
    {
        let d = |x: f64| x * t.powi(3) / 12.0;
        let dd = [d(g11), d(g22), d(g12), d(g66)];
        let mindlin = mindlin_navier_frequencies(a, rho * t, dd, [KAPPA * s11 * t, KAPPA * s22 * t], 1)[0];
        let kirchhoff = navier_frequencies(a, rho * t, dd, 1)[0];
        let w: Vec<f64> = [8, 16, 32]
            .iter()
            .map(|&n| {
                let cards = format!(
                    "PSHELL,1,1,{t:?},1,1.0,3\nMAT2,1,{g11:?},{g12:?},0.0,{g22:?},0.0,{g66:?},{rho:?}\n\
                     MAT2,3,{s11:?},0.0,,{s22:?}"
                );
                let deck = impactlab::mesh::square_plate_deck(n, a, "3", "126", &cards)
                    .replace("ENDDATA", &format!("{}ENDDATA", impactlab::mesh::hard_supports(n)));
                let m = impactlab::model_from_text("mindlin-orthotropic", &cells.cut(deck))
                    .unwrap_or_else(|e| panic!("{e}"));
                assert!(m
                    .elements
                    .iter()
                    .all(|e| e.kernel.card() == cells.card() && e.kernel.family().shell().unwrap().shear.is_some()));
                impactlab::eigen::lowest_frequencies(&m, 1).unwrap()[0]
            })
            .collect();
        let err = |k: usize| (w[k] - mindlin).abs();
        let (p1, p2) = ((err(0) / err(1)).log2(), (err(1) / err(2)).log2());
        eprintln!(
            "{} orthotropic t/a = {t}: ω 8/16/32 = {w:?}, Mindlin {mindlin:.3}, Kirchhoff {kirchhoff:.3} ({:+.2} %), \
             orders {p1:.2} {p2:.2}",
            cells.card(),
            100.0 * (kirchhoff / mindlin - 1.0)
        );
        for p in [p1, p2] {
            assert!(p > 1.6, "t/a = {t}: orders {p1} {p2}, {w:?} vs {mindlin}");
        }
        assert!(err(2) < 1e-3 * mindlin, "t/a = {t}: {} vs {mindlin}", w[2]);
        assert!(kirchhoff > mindlin);
    }
}

/// Goal: no shear locking, for either element. Model: as above on a 16 × 16 mesh
/// (CQUAD4, then CTRIA3), t/a from 1/10 to 1/10 000. Reference: Mindlin's ω, which tends to Kirchhoff's as (t/a)². A locking
/// element stiffens without bound as t/a falls (its shear energy cannot vanish under
/// bending): its ω/ω_Mindlin grows like a/(n t). Assertions: ω/ω_Mindlin within 1 % of
/// the same number at every t/a (the mesh's error alone, no t-dependence), and the
/// shear part of ω (ω/√(D/ρt) at t minus at 1/10 000) falls by 100 ± 10 % from
/// t/a = 1/100 to 1/1000: the thin plate is reached like (t/a)². (From 1/10 to 1/100
/// the ratio is 96 for MITC4 and 113 for DKMT: at t/a = 1/10, t is 1.6 element
/// sizes, before the asymptotic range.)
#[test]
fn shear_plate_does_not_lock_as_it_thins() {
    let ts = [1e-1, 1e-2, 1e-3, 1e-4];
    for cells in [Cells::Quad4, Cells::Tria3] {
        let ratio: Vec<f64> = ts
            .iter()
            .map(|&t| mindlin_plate_frequency(16, 1.0, t, cells) / mode_11(1.0, t).1)
            .collect();
        eprintln!("{}: ω/ω_Mindlin at t/a = {ts:?}: {ratio:?}", cells.card());
        for r in &ratio {
            assert!((r / ratio[3] - 1.0).abs() < 0.01 && (r - 1.0).abs() < 0.01, "{ratio:?}");
        }
        // ω normalised by the thin plate's scaling √(D/ρt) ∝ t.
        let scaled: Vec<f64> = ts
            .iter()
            .map(|&t| mindlin_plate_frequency(16, 1.0, t, cells) / t)
            .collect();
        let (d1, d2) = (scaled[3] - scaled[1], scaled[3] - scaled[2]);
        eprintln!(
            "{}: shear part at t/a = 1/100 and 1/1000: {d1:e} {d2:e}, ratio {:.1}",
            cells.card(),
            d1 / d2
        );
        assert!((d1 / d2 / 100.0 - 1.0).abs() < 0.1, "{d1} {d2}");
    }
}

/// Goal: a PCOMP on the generated triangle meshes is laid up as on the quadrilaterals.
/// NASTRAN measures ply angles from each element's G1→G2 side, so every generated
/// triangle starts on its side along x. Model: the paper's 9×9 plate in CTRIA3 with
/// the cross-ply of `study::mesh::CROSS_PLY` for its PSHELL, and the simply supported
/// square plate cut by `mesh::in_triangles`. Reference: the same laminate on the
/// CQUAD4 plate (G1→G2 along x). Assertions: every triangle's G1→G2 side is along
/// x, and every element's bending matrix equals the quadrilateral's to round-off.
#[test]
fn a_laminate_on_the_generated_triangles_is_laid_up_as_on_the_quadrilaterals() {
    use impactlab::mesh::{plate_deck_with, Edges};
    let cross_ply = |cells: Cells| {
        let deck = plate_deck_with(9, Edges::Clamped, cells).unwrap().replace(
            &format!("{}\n", impactlab::mesh::PAPER_PSHELL),
            &format!("{}\n", impactlab::study::mesh::CROSS_PLY),
        );
        impactlab::model_from_text("cross-ply", &deck).unwrap_or_else(|e| panic!("{e}"))
    };
    let bending = |m: &impactlab::model::Model| -> Vec<nalgebra::Matrix3<f64>> {
        m.elements
            .iter()
            .filter_map(|e| e.kernel.family().shell().and_then(|s| s.g_bending))
            .collect()
    };
    let (quads, triangles) = (cross_ply(Cells::Quad4), cross_ply(Cells::Tria3));
    let reference = bending(&quads)[0];
    let sections = bending(&triangles);
    assert_eq!(sections.len(), 2 * 81);
    for g in &sections {
        assert!((g - reference).norm() <= 1e-12 * reference.norm(), "{g} vs {reference}");
    }
    let navier = impactlab::mesh::navier_plate(4, 1.0, 0.1, [1.0, 0.0, 0.0, 1.0, 0.0, 1.0], 1.0, None, Cells::Tria3);
    for m in [&triangles, &navier.unwrap()] {
        for e in m.elements.iter().filter(|e| e.kernel.card() == "CTRIA3") {
            let p = e.kernel.points();
            assert!((p[1][1] - p[0][1]).abs() < 1e-12, "element {}: {p:?}", e.eid);
        }
    }
}
