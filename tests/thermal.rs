//! Thermal loads on shells, rods and bars (TEMPP1, TEMP, TEMPD) in the problems with
//! closed forms: a plate clamped all round under a uniform gradient and expansion
//! stays where it is; a plate held at one corner curls and expands freely; a rod
//! and a bar expand by the mean of their grids' temperatures.

use impactlab::deck::parse_deck_str;
use impactlab::run::statics::{solve, StaticSolution};

/// A 4×4 plate of side 2 (grids 1..25 row by row, corner 1 at the origin), turned
/// by 30° about basic x so that every kernel works in its own axes; CQUAD4s, or each
/// square split into two CTRIA3s; PSHELL of MAT1 (E 1e7, ν 0.3, α 1e-5, TREF 20),
/// thick (MID3, transverse shear flexible) or thin. Its temperature set 5: TEMPP1
/// T = 70, T′ = 40 on every element. Grid 5 is displaced in system 9, the plate's
/// own axes (x along basic x, z its normal). `spc` holds grids.
fn plate(trias: bool, thick: bool, spc: &str) -> String {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let mut d = format!(
        "SOL 101\nCEND\nSPC = 1\nTEMPERATURE(LOAD) = 5\nBEGIN BULK\n{spc}CORD2R,9,0,0.,0.,0.,0.,{:e},{:e},+S9\n+S9,1.,0.,0.\n",
        -s,
        c
    );
    for j in 0..5 {
        for i in 0..5 {
            let (x, y) = (0.5 * i as f64, 0.5 * j as f64);
            // Grid 5 is displaced in system 9, the plate's own axes.
            let cd = if 5 * j + i + 1 == 5 { "9" } else { "" };
            d.push_str(&format!("GRID,{},,{x:?},{:e},{:e},{cd}\n", 5 * j + i + 1, y * c, y * s));
        }
    }
    let mut eid = 0;
    for j in 0..4 {
        for i in 0..4 {
            let g = 5 * j + i + 1;
            let corners = [g, g + 1, g + 6, g + 5];
            if trias {
                for t in [[0, 1, 2], [0, 2, 3]] {
                    eid += 1;
                    let [a, b, cc] = t.map(|k| corners[k]);
                    d.push_str(&format!("CTRIA3,{eid},10,{a},{b},{cc}\n"));
                }
            } else {
                eid += 1;
                let [a, b, cc, dd] = corners;
                d.push_str(&format!("CQUAD4,{eid},10,{a},{b},{cc},{dd}\n"));
            }
        }
    }
    d.push_str(&format!("TEMPP1,5,1,70.,40.,,,,,+T\n+T,2,THRU,{eid}\n"));
    d.push_str(if thick {
        "PSHELL,10,1,0.1,1,,1\n"
    } else {
        "PSHELL,10,1,0.1,1\n"
    });
    d.push_str("MAT1,1,1.0+7,,0.3,,1.0-5,20.\nENDDATA\n");
    d
}

fn solved(text: &str) -> StaticSolution {
    let d = parse_deck_str("thermal.bdf", text, Default::default()).unwrap_or_else(|e| panic!("{e}"));
    solve(&d).unwrap_or_else(|e| panic!("{e}")).0
}

/// The four kinds of plate: CQUAD4 (MITC4) and CTRIA3 (DKMT), thin and thick.
const KINDS: [(bool, bool); 4] = [(false, false), (false, true), (true, false), (true, true)];

/// Goal: a plate clamped on its whole boundary under a uniform temperature T and
/// gradient T′ stays where it is: the thermal moment and membrane force are uniform,
/// so the clamps take them and nothing inside moves (the classical result, Boley &
/// Weiner's for a clamped plate). A load whose rotations did not match its
/// deflection (a sign slip in θ = ±∂w/∂…) would bend the interior. Tolerance:
/// 1e-12 of the free curl's and expansion's size over the plate.
#[test]
fn a_clamped_plate_under_uniform_temperature_and_gradient_stays_put() {
    let spc = "SPC1,1,123456,1,THRU,5\nSPC1,1,123456,21,THRU,25\nSPC1,1,123456,6,11,16,10,15,20\n";
    let scale = 1e-5 * 40.0 * 2.0 * 2.0 + 1e-5 * 50.0 * 2.0;
    for (trias, thick) in KINDS {
        let s = solved(&plate(trias, thick, spc));
        let largest = s
            .grids
            .iter()
            .flat_map(|g| g.u.iter().map(|v| v.abs()))
            .fold(0.0, f64::max);
        assert!(
            largest <= 1e-12 * scale,
            "trias {trias}, thick {thick}: a clamped plate moved {largest:e}"
        );
    }
}

/// Goal: a plate held at its corner grid 1 (all six components) and, against turning
/// in its plane (its shells have no drilling stiffness), at grid 5 along its in-plane
/// y (system 9's T2, where the free deformation has none) deforms
/// exactly as its temperature says and stays stress-free: in its own plane (x along
/// basic x, y turned 30° about it) the expansion ε = α(T − TREF) = 5e-4 stretches it,
/// u = ε(x − x₁), and the gradient curls it, w = −κ|r − r₁|²/2 with κ = αT′ = 4e-4,
/// θx = ∂w/∂y, θy = −∂w/∂x; its far corner moves away from the hotter face's side,
/// w < 0 (the hotter +z face is the longer: the plate is convex towards +z).
/// Tolerance: 1e-8 of the curl's size: round-off of a system whose stiffnesses span
/// nine decades (membrane E·t ≈ 1e6 to the drilling springs, 1e-6 of the bending
/// stiffness ≈ 1e-3); seen: 1e-10.
#[test]
fn a_plate_held_at_one_corner_curls_and_expands_freely() {
    let (eps, kappa) = (1e-5 * 50.0, 1e-5 * 40.0);
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    for (trias, thick) in KINDS {
        let sol = solved(&plate(trias, thick, "SPC1,1,123456,1\nSPC1,1,2,5\n"));
        let scale = kappa * 8.0 / 2.0;
        for g in &sol.grids {
            let (x, y) = (g.position[0], g.position[1] * c + g.position[2] * s);
            let w = -kappa * (x * x + y * y) / 2.0;
            // In the plate's axes: translations (u, v, w), rotations (θx, θy).
            let local = [eps * x, eps * y, w, -kappa * y, kappa * x];
            let to_basic = |a: f64, b: f64, n: f64| [a, b * c - n * s, b * s + n * c];
            let t = to_basic(local[0], local[1], local[2]);
            let r = to_basic(local[3], local[4], 0.0);
            for k in 0..3 {
                assert!(
                    (g.basic[k] - t[k]).abs() <= 1e-8 * scale,
                    "trias {trias}, thick {thick}: grid {} T{} {} against {}",
                    g.grid,
                    k + 1,
                    g.basic[k],
                    t[k]
                );
                assert!(
                    (g.rotation[k] - r[k]).abs() <= 1e-8 * kappa * 2.0,
                    "trias {trias}, thick {thick}: grid {} R{} {} against {}",
                    g.grid,
                    k + 1,
                    g.rotation[k],
                    r[k]
                );
            }
        }
        let far = &sol.grids[24];
        let normal = -far.basic[1] * s + far.basic[2] * c;
        assert!(normal < 0.0, "the far corner moved {normal} along the plate's normal");
    }
}

/// Goal: a rod (CROD) and a bar (CBAR), each held at one end, under grid temperatures
/// (TEMP 100 at the held grid, 200 at the other; TEMPD 50 for the rest, TREF 0) grow
/// by α·L·(T₁ + T₂)/2, the mean of their grids' temperatures (TEMP remark 5: "a
/// simple average of the connecting grid point temperatures"; a bar's temperature
/// varies linearly between its ends). Tolerance: round-off (1e-12 relative).
#[test]
fn a_rod_and_a_bar_grow_by_the_mean_of_their_grids_temperatures() {
    let deck = "SOL 101\nCEND\nSPC = 1\nTEMP(LOAD) = 7\nBEGIN BULK\n\
                GRID,1,,0.,0.,0.\nGRID,2,,3.,0.,0.\nGRID,3,,0.,5.,0.\nGRID,4,,3.,5.,0.\n\
                SPC1,1,123456,1,3\nSPC1,1,23456,2,4\n\
                CROD,1,10,1,2\nPROD,10,1,0.2,0.01\nCBAR,2,20,3,4,0.,0.,1.\nPBAR,20,1,0.2,0.01,0.01,0.02\n\
                MAT1,1,1.0+7,,0.3,,1.0-5,0.\nTEMP,7,1,100.,2,200.\nTEMPD,7,50.\nENDDATA\n";
    let s = solved(deck);
    let rod = s.displacement(2, 1).unwrap();
    let bar = s.displacement(4, 1).unwrap();
    let rod_expected = 1e-5 * 3.0 * 150.0;
    let bar_expected = 1e-5 * 3.0 * 50.0;
    assert!(
        (rod - rod_expected).abs() <= 1e-12 * rod_expected,
        "{rod} against {rod_expected}"
    );
    assert!(
        (bar - bar_expected).abs() <= 1e-12 * bar_expected,
        "{bar} against {bar_expected}"
    );
}
