//! Shells in three dimensions: the paper's plate turned in space, with and without
//! coordinate systems, against the flat plate; the curved panel's flat limit; ply
//! orientation. (The static tests of MacNeal and Harder's shell obstacle course and
//! the closed cylinder's frequencies are verification cases: `verification/
//! scordelis-lo`, `pinched-cylinder`, `pinched-hemisphere`, `panel-flat-limit`.)

use crate::common;

use impactlab::integrate::Scheme;
use impactlab::model::Model;
use impactlab::run::RunResult;
use nalgebra::{Matrix3, Rotation3, Vector3};

fn model(name: &str, text: &str) -> Model {
    impactlab::model_from_text(name, text).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The comma-separated fields of a free-field line.
fn fields(line: &str) -> Vec<String> {
    line.split(',').map(|f| f.trim().to_string()).collect()
}

fn real(s: &str) -> f64 {
    s.parse().unwrap_or_else(|_| panic!("{s} is a real"))
}

/// The paper's plate deck on an n×n mesh with every GRID (the impactor's too) turned
/// by `r` and moved by `shift`, and displaced in CORD2R 7, the plate's own axes turned
/// the same way: every other card as it was.
fn turned_with_cord(deck: &str, r: &Matrix3<f64>, shift: Vector3<f64>) -> String {
    let mut out = String::new();
    for line in deck.lines() {
        if line.starts_with("GRID,") {
            let f = fields(line);
            let p = r * Vector3::new(real(&f[3]), real(&f[4]), real(&f[5])) + shift;
            out.push_str(&format!("GRID,{},,{:?},{:?},{:?},7\n", f[1], p.x, p.y, p.z));
        } else if line == "BEGIN BULK" {
            let (a, b, c) = (shift, shift + r.column(2), shift + r.column(0));
            out.push_str(&format!(
                "BEGIN BULK\nCORD2R,7,0,{:?},{:?},{:?},{:?},{:?},{:?}\n,{:?},{:?},{:?}\n",
                a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z
            ));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// A component after the plate's axes x, y, z are laid along basic y, z, x.
fn cycled(c: char) -> char {
    match c {
        '1' => '2',
        '2' => '3',
        '3' => '1',
        '4' => '5',
        '5' => '6',
        '6' => '4',
        other => other,
    }
}

fn cycled_list(s: &str) -> String {
    let mut v: Vec<char> = s.chars().map(cycled).collect();
    v.sort();
    v.into_iter().collect()
}

/// The paper's plate deck with its normal along basic x and no coordinate system:
/// the plate's x, y, z laid along basic y, z, x, every component in the deck
/// renumbered to match (SPC1, GRDSET PS, NOLIN3, TF, TIC) and the impactor's inertia
/// with it.
fn normal_along_x(deck: &str) -> String {
    let mut out = String::new();
    for line in deck.lines() {
        let mut f = fields(line);
        match f[0].as_str() {
            "GRID" => {
                let (x, y, z) = (f[3].clone(), f[4].clone(), f[5].clone());
                f[3] = z;
                f[4] = x;
                f[5] = y;
            }
            "SPC1" => f[2] = cycled_list(&f[2]),
            "GRDSET" => f[7] = cycled_list(&f[7]),
            "NOLIN3" => f[3] = cycled_list(&f[3]),
            "TIC" => f[3] = cycled_list(&f[3]),
            "+CON2-2" => {
                // I11, I22, I33 of the plate's axes: basic x is the plate's z.
                let (i11, i22, i33) = (f[1].clone(), f[3].clone(), f[6].clone());
                f[1] = i33;
                f[3] = i11;
                f[6] = i22;
            }
            t if t.starts_with("+TF-") => f[2] = cycled_list(&f[2]),
            _ => {}
        }
        out.push_str(&f.join(","));
        out.push('\n');
    }
    out
}

/// Every history column of `b` against `a`'s of the same name (`rename` maps `a`'s
/// names to `b`'s), within `tol` of the largest peak in `a` of the same quantity at
/// the same grid or element (`disp_505_*`, `stress_505_*`): a column is formed from
/// the same displacements as its siblings, so its round-off is theirs (the flat
/// plate's in-plane displacements are exactly zero, its centre's shear stress 1e-9 of
/// the normal stresses there); the energy ledger too.
fn same_history(a: &RunResult, b: &RunResult, rename: impl Fn(&str) -> String, tol: f64) {
    let (na, nb) = (a.history_names(), b.history_names());
    assert_eq!(na.len(), nb.len());
    assert_eq!(a.history.len(), b.history.len());
    let peak_of = |i: usize| a.history.iter().map(|r| r[i].abs()).fold(0.0, f64::max);
    let kind = |n: &str| n.split('_').take(2).collect::<Vec<_>>().join("_");
    for (i, name) in na.iter().enumerate() {
        let j = nb
            .iter()
            .position(|n| *n == rename(name))
            .unwrap_or_else(|| panic!("no column {} in {nb:?}", rename(name)));
        let peak = (0..na.len())
            .filter(|&k| kind(&na[k]) == kind(name))
            .map(peak_of)
            .fold(0.0, f64::max);
        let diff = a
            .history
            .iter()
            .zip(&b.history)
            .map(|(ra, rb)| (ra[i] - rb[j]).abs())
            .fold(0.0, f64::max);
        assert!(diff <= tol * peak, "{name}: differs by {diff:e}, peak {peak:e}");
    }
    for (ea, eb) in a.energy.iter().zip(&b.energy) {
        assert!(
            (ea.total - eb.total).abs() <= tol * ea.total,
            "{} vs {}",
            ea.total,
            eb.total
        );
        assert!((ea.se_target - eb.se_target).abs() <= tol * ea.total);
        assert!((ea.ke_target - eb.ke_target).abs() <= tol * ea.total);
        assert!((ea.ke_target_eq16 - eb.ke_target_eq16).abs() <= tol * ea.total);
        let p = a.energy.iter().map(|e| e.momentum.abs()).fold(0.0, f64::max);
        assert!(
            (ea.momentum - eb.momentum).abs() <= tol * p,
            "{} vs {}",
            ea.momentum,
            eb.momentum
        );
    }
}

/// Goal: frame invariance. Model: the paper's plate (9×9 mesh, its MAT2 section and
/// contact, Newmark, the deck's Δt, 1500 steps) flat in the basic XY plane, and the
/// same plate turned by an arbitrary rotation and moved, each grid displaced in a
/// CORD2R along the turned plate (so every SPC1, NOLIN3, TF and TIC of the deck means
/// what it meant; its DISP and NLLOAD columns are named in that frame, `_cd7`).
/// Reference: the flat plate's own history and ledger (momentum and Eq. 16 included).
/// Tolerance: 1e-9 of the peaks (see [`same_history`]): the turned model differs
/// only by round-off of the coordinates (about 1e-15 relative), which the solve
/// amplifies by the system's conditioning.
#[test]
fn the_plate_turned_in_space_in_its_own_frame_gives_the_flat_plates_history() {
    let flat = impactlab::mesh::plate_deck(9).unwrap();
    let r = Rotation3::from_euler_angles(0.7, -0.4, 2.2).into_inner();
    let turned = turned_with_cord(&flat, &r, Vector3::new(3.0, -2.0, 11.0));
    let (mf, mt) = (model("flat.bdf", &flat), model("turned.bdf", &turned));
    let a = common::run(&mf, Scheme::Newmark, None, Some(1500));
    let b = common::run(&mt, Scheme::Newmark, None, Some(1500));
    assert!(a.summary.contact.duration.is_some());
    same_history(
        &a,
        &b,
        |n| {
            n.to_string()
                + if n.contains("_T") || n.contains("_R") {
                    "_cd7"
                } else {
                    ""
                }
        },
        1e-9,
    );
}

/// Goal: the same without any coordinate system. Model: the plate of the test above
/// with its normal along basic x (its x, y, z along basic y, z, x), every component
/// of the deck renumbered to match. Reference: the flat plate's history, its T1, T2,
/// T3 (R1, R2, R3) columns read as T2, T3, T1 (R2, R3, R1) (strains and stresses are in the element's own axes: x along G1→G2,
/// the same on both). Tolerance: 1e-9 of each column's peak, as above.
#[test]
fn the_plate_with_its_normal_along_basic_x_gives_the_flat_plates_history() {
    let flat = impactlab::mesh::plate_deck(9).unwrap();
    let along_x = normal_along_x(&flat);
    let (mf, mx) = (model("flat.bdf", &flat), model("along-x.bdf", &along_x));
    let a = common::run(&mf, Scheme::Newmark, None, Some(1500));
    let b = common::run(&mx, Scheme::Newmark, None, Some(1500));
    let rename = |n: &str| {
        for (from, to) in [
            ("T1", "T2"),
            ("T2", "T3"),
            ("T3", "T1"),
            ("R1", "R2"),
            ("R2", "R3"),
            ("R3", "R1"),
        ] {
            if let Some(stem) = n.strip_suffix(&format!("_{from}")) {
                return format!("{stem}_{to}");
            }
        }
        n.to_string()
    };
    same_history(&a, &b, rename, 1e-9);
}

/// Contact duration and peak force of a run.
fn contact(r: &RunResult) -> (f64, f64) {
    (
        r.summary.contact.duration.expect("the contact ends"),
        r.summary.contact.peak_force,
    )
}

/// Goal: the curved panel's flat limit. Model: the paper's plate (15×15 mesh, its
/// section, contact and impactor) wrapped onto a cylinder of radius 10⁴ spans (6e4
/// in; `impactlab mesh panel`), against the flat plate, each run by every implicit
/// scheme at the deck's Δt for 3000 steps. Reference: the flat plate's contact
/// duration and peak force, and its ledger's largest energy error. Tolerance: 0.1 %
/// on both contact numbers (the panel's sag at the plate's edge is 7.5e-5 in, its
/// membrane-bending coupling of order span/R = 1e-4); the energy error no more than
/// the flat plate's plus 1e-9 (the same schemes on the same equations).
#[test]
fn a_panel_of_radius_ten_thousand_spans_is_the_flat_plate() {
    let flat = model("flat.bdf", &impactlab::mesh::plate_deck(15).unwrap());
    let panel = model(
        "panel.bdf",
        &impactlab::mesh::panel_deck(15, 6.0e4, impactlab::mesh::Cells::Quad4).unwrap(),
    );
    for scheme in [Scheme::Newmark, Scheme::Energy, Scheme::Nastran] {
        let (a, b) = (
            common::run(&flat, scheme, None, Some(3000)),
            common::run(&panel, scheme, None, Some(3000)),
        );
        let ((ta, fa), (tb, fb)) = (contact(&a), contact(&b));
        assert!((tb / ta - 1.0).abs() < 1e-3, "{scheme:?}: duration {tb} vs {ta}");
        assert!((fb / fa - 1.0).abs() < 1e-3, "{scheme:?}: peak {fb} vs {fa}");
        let (ea, eb) = (
            a.summary.energy.max_relative_error.unwrap(),
            b.summary.energy.max_relative_error.unwrap(),
        );
        assert!(
            eb <= ea + 1e-9,
            "{scheme:?}: energy error {eb} vs the flat plate's {ea}"
        );
    }
}

/// Goal: the drilling supports change nothing they should not, and the inert-DOF
/// reduction finds the curved panel's membrane live. Model: the panel of the test
/// above (R = 6e4 in, where every grid's rotations are nearly singular about the
/// normal and get a drilling spring) and a panel of R = 10 in (where the facets'
/// angles stiffen every rotation but on the straight edges x = ±3 in, whose two
/// shells are coplanar, and at the corners: clamped here, so no spring acts), each
/// run again with every drilling spring 1000 times stiffer. Reference: the first run. Tolerance: 1e-6 of
/// the peak force and contact duration (the spring holds a rotation that nothing
/// else in a flat region moves; near-flat, its coupling is of order (span/R)²).
#[test]
fn the_drilling_supports_do_not_change_the_answer() {
    for (radius, acting) in [(6.0e4, true), (10.0, false)] {
        let deck = impactlab::mesh::panel_deck(9, radius, impactlab::mesh::Cells::Quad4).unwrap();
        let m = model("panel.bdf", &deck);
        let drills: Vec<_> = m
            .elements
            .iter()
            .filter(|e| e.kind::<impactlab::elements::drill::Drill>().is_some())
            .collect();
        let free = drills
            .iter()
            .filter(|e| e.dofs[0][3..].iter().any(|d| d.is_some()))
            .count();
        assert_eq!(
            free > 0,
            acting,
            "R = {radius}: {} drilling supports, {free} on free grids",
            drills.len()
        );
        let mut stiff = m.clone();
        for e in std::sync::Arc::make_mut(&mut stiff.elements).iter_mut() {
            if let Some(d) = e.kind_mut::<impactlab::elements::drill::Drill>() {
                d.k *= 1000.0;
            }
        }
        let (a, b) = (
            common::run(&m, Scheme::Newmark, None, Some(2500)),
            common::run(&stiff, Scheme::Newmark, None, Some(2500)),
        );
        let ((ta, fa), (tb, fb)) = (contact(&a), contact(&b));
        assert!(
            (tb / ta - 1.0).abs() < 1e-6 && (fb / fa - 1.0).abs() < 1e-6,
            "R = {radius}: {ta} {fa} vs {tb} {fb}"
        );
        // The curved panel's membrane is coupled to its bending: nothing is inert
        // but what no load reaches (the flat plate drops its 2 in-plane DOFs a grid).
        let flat = common::run(
            &model("flat.bdf", &impactlab::mesh::plate_deck(9).unwrap()),
            Scheme::Newmark,
            None,
            Some(10),
        );
        assert!(flat.summary.model.inert_dofs_skipped >= 2 * 8 * 8);
        assert!(
            a.summary.model.inert_dofs_skipped < 8 * 8,
            "R = {radius}: {}",
            a.summary.model.inert_dofs_skipped
        );
    }
}

/// The paper's plate (9×9) as a one-ply laminate of glass/epoxy (the cross-ply deck's
/// MAT8) at `ply` degrees, every CQUAD4 with `orientation` in its THETA/MCID field
/// (`""` blank), and `extra` bulk cards.
fn one_ply_plate(ply: f64, orientation: &str, extra: &str) -> String {
    let deck = impactlab::mesh::plate_deck(9).unwrap();
    let mut out = String::new();
    for line in deck.lines() {
        if line.starts_with("CQUAD4,") {
            out.push_str(&format!("{line},{orientation}\n"));
        } else if line == impactlab::mesh::PAPER_PSHELL {
            out.push_str(&format!(
                "PCOMP,1\n,8,0.15,{ply:?}\nMAT8,8,5.735+6,1.2855+6,0.2231,5.7+5,,,1.8-4\n{extra}"
            ));
        } else if !line.starts_with("MAT2,") && !line.starts_with("+A101") {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Goal: THETA and MCID orient the plies as NASTRAN does (the material x axis is the
/// G1→G2 side turned by THETA counter-clockwise about the normal, or the x axis of
/// system MCID projected onto the element; a PCOMP's ply angles add to it). Model:
/// the one-ply plate of [`one_ply_plate`], Newmark, 800 steps: the ply at 0° with
/// THETA = 30.0, with MCID = 9 (a CORD2R turned 30° about z) and with THETA = −330.0,
/// against the ply at 30° with THETA blank; the same on the plate turned in space
/// (its CORD2R 7, as in the frame-invariance test). Reference: the ply at 30°.
/// Tolerance: 1e-9 of the peaks (round-off of the angles' sines). The ply at −30°
/// (what a flipped THETA would give) is the mirror image of the ply at 30° across the
/// plate's x = 0 line: its contact force is the same, but its in-plane shear
/// stresses change sign, by far more than the tolerance, so the comparison can fail.
#[test]
fn theta_and_mcid_turn_the_plies_as_the_ply_angle_does() {
    let cord = "CORD2R,9,0,0.0,0.0,0.0,0.0,0.0,1.0\n,0.8660254037844387,0.5,0.0\n";
    let run = |d: &str| common::run(&model("ply.bdf", d), Scheme::Newmark, None, Some(800));
    let reference = run(&one_ply_plate(30.0, "", ""));
    for (what, deck) in [
        ("THETA 30", one_ply_plate(0.0, "30.0", "")),
        ("MCID 9", one_ply_plate(0.0, "9", cord)),
        ("THETA -330", one_ply_plate(0.0, "-330.0", "")),
    ] {
        eprintln!("{what}");
        same_history(&reference, &run(&deck), |n| n.to_string(), 1e-9);
    }
    let flipped = run(&one_ply_plate(-30.0, "", ""));
    let names = reference.history_names();
    let j = names.iter().position(|n| n == "stress_505_z1_xy").unwrap();
    let peak = reference.history.iter().map(|r| r[j].abs()).fold(0.0, f64::max);
    let gap = reference
        .history
        .iter()
        .zip(&flipped.history)
        .map(|(a, b)| (a[j] - b[j]).abs())
        .fold(0.0, f64::max);
    assert!(
        gap > 0.5 * peak,
        "the ply's angle must show in the shear stress: {gap} vs peak {peak}"
    );
    let r = Rotation3::from_euler_angles(0.7, -0.4, 2.2).into_inner();
    let turned = turned_with_cord(&one_ply_plate(0.0, "30.0", ""), &r, Vector3::new(3.0, -2.0, 11.0));
    let cd7 = |n: &str| {
        n.to_string()
            + if n.contains("_T") || n.contains("_R") {
                "_cd7"
            } else {
                ""
            }
    };
    same_history(&reference, &run(&turned), cd7, 1e-9);
}
