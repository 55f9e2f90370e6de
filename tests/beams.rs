//! Beams against an independent reader: PBARL section constants against pyNastran's
//! section formulas, and a deck of CBARs, PBARL sections and offset CONM2s weighed
//! against pyNastran's mass_properties.

use crate::common;

use impactlab::elements::section::{constants, Shape};

/// pyNastran's A, I1, I2, I12 of each PBARL section (its `_bar_areaL`), and J of a
/// ROD and a TUBE (its `PBARL.J`); `None` (and a note) where pyNastran cannot run,
/// except under CI, where that fails.
fn pynastran_sections(cases: &[(&str, Vec<f64>)]) -> Option<Vec<Vec<Option<f64>>>> {
    let json = serde_json::to_string(
        &cases
            .iter()
            .map(|(t, d)| (t.to_string(), d.clone()))
            .collect::<Vec<_>>(),
    )
    .unwrap();
    let script = "import json, sys\n\
         from pyNastran.bdf.bdf import BDF\n\
         from pyNastran.bdf.cards.properties.bars import _bar_areaL\n\
         m = BDF(debug=None)\n\
         m.add_mat1(1, 1.0e7, None, 0.3)\n\
         out = []\n\
         for k, (t, d) in enumerate(json.loads(sys.argv[1])):\n\
         \x20   r = [None if x is None else float(x) for x in _bar_areaL('PBARL', t, d, None)]\n\
         \x20   p = m.add_pbarl(100 + k, 1, t, d)\n\
         \x20   r.append(float(p.J()) if t in ('ROD', 'TUBE') else None)\n\
         \x20   out.append(r)\n\
         print(json.dumps(out))\n";
    common::pynastran_json(script, &[std::ffi::OsStr::new(&json)])
}

/// Goal: each PBARL section's constants against pyNastran's formulas, written
/// independently from NASTRAN's figures. Reference: pyNastran 1.4's section
/// functions. Tolerance: 1e-12 relative (both are sums of a few products).
///
/// Compared: A of all ten; I1, I2, I12 of BAR, BOX, ROD, TUBE; I2 of I and T; I12 of L;
/// J of ROD and TUBE. Left out, each where pyNastran's formula is not the section's
/// (our values agree with the outline's moments by Green's theorem, in the unit
/// tests, so the difference is pyNastran's): I1 of I (its top flange's own term takes
/// the height where the flange's width belongs: off by (DIM1 − DIM3)·DIM6³/12), I1 of
/// T, I1 and I2 of L (a leg's own term takes the leg's length to the mid-line of the
/// other); CHAN, HAT, Z, whose moments pyNastran does not compute; the Z's area, which
/// pyNastran gives as 11.9 for a Z of 2.6; J of the others, which pyNastran gives as
/// the polar moment I1 + I2 (a box's Bredt constant is 7.71 where that is 11.5).
#[test]
fn pbarl_sections_match_pynastrans_formulas() {
    let dims: Vec<(&str, Vec<f64>)> = vec![
        ("BAR", vec![2.0, 3.0]),
        ("BOX", vec![4.0, 3.0, 0.2, 0.3]),
        ("ROD", vec![1.5]),
        ("TUBE", vec![2.0, 1.5]),
        ("I", vec![6.0, 3.0, 4.0, 0.2, 0.3, 0.4]),
        ("T", vec![3.0, 4.0, 0.3, 0.2]),
        ("L", vec![3.0, 4.0, 0.3, 0.2]),
        ("CHAN", vec![3.0, 4.0, 0.3, 0.2]),
        ("HAT", vec![4.0, 0.2, 2.0, 1.0]),
        ("Z", vec![3.0, 0.2, 0.3, 4.0]),
    ];
    let Some(theirs) = pynastran_sections(&dims) else {
        return;
    };
    let compared: &[(&str, &[usize])] = &[
        ("BAR", &[0, 1, 2, 3]),
        ("BOX", &[0, 1, 2, 3]),
        ("ROD", &[0, 1, 2, 3, 4]),
        ("TUBE", &[0, 1, 2, 3, 4]),
        ("I", &[0, 2, 3]),
        ("T", &[0, 2, 3]),
        ("L", &[0, 3]),
        ("CHAN", &[0]),
        ("HAT", &[0]),
    ];
    let mut count = 0;
    for ((name, d), t) in dims.iter().zip(&theirs) {
        let c = constants(Shape::named(name).unwrap(), d).unwrap();
        let ours = [c.area, c.i1, c.i2, c.i12, c.j];
        let Some((_, which)) = compared.iter().find(|(n, _)| n == name) else {
            continue;
        };
        let scale = c.area.max(c.i1).max(c.i2);
        for &k in *which {
            let theirs = t[k].unwrap_or_else(|| panic!("{name}: pyNastran gives no value {k}"));
            assert!(
                (ours[k] - theirs).abs() <= 1e-12 * scale,
                "{name} [A, I1, I2, I12, J][{k}]: {} vs pyNastran {theirs}",
                ours[k]
            );
            count += 1;
        }
    }
    assert_eq!(count, 28);
}

/// Goal: a deck's mass and centre of gravity with CBARs (PBARL with NSM, one offset
/// from its grids by WA/WB) and CONM2s offset from their grids in a turned CID and by
/// a basic location (CID = −1), against pyNastran's mass_properties. Reference:
/// pyNastran 1.4, which puts a CBAR's mass midway between its grids whatever its
/// offsets: its centre is moved here by the offset bar's mass times its offset
/// (m = (ρA + NSM)L, A = 0.64 for the BOX, down 0.5). Tolerance: 1e-12 of the mass,
/// and of the size for the centre.
#[test]
fn offset_bars_and_masses_weigh_as_pynastran_weighs_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("weigh.bdf");
    std::fs::write(
        &path,
        "SOL 101\nCEND\nBEGIN BULK\n\
         MAT1,1,3.0+7,,0.3,7.3-4\n\
         PBARL,1,1,,BOX\n,2.0,1.0,0.1,0.15,0.02\n\
         CORD2R,5,,1.0,2.0,0.0,1.0,2.0,1.0,\n,2.0,3.0,0.0\n\
         GRID,1,,0.0,0.0,0.0\nGRID,2,,4.0,0.0,0.0\nGRID,3,,8.0,1.0,0.0\n\
         CBAR,1,1,1,2,0.0,0.0,1.0\n,,,0.0,0.0,-0.5,0.0,0.0,-0.5\n\
         CBAR,2,1,2,3,0.0,0.0,1.0\n\
         CONM2,11,2,5,0.25,0.3,-0.1,0.4\n\
         CONM2,12,3,-1,0.5,8.5,1.5,0.7\n\
         ENDDATA\n",
    )
    .unwrap();
    let script = "import json, sys\n\
         from pyNastran.bdf.bdf import BDF\n\
         from pyNastran.bdf.mesh_utils.mass_properties import mass_properties\n\
         m = BDF(debug=None)\n\
         m.read_bdf(sys.argv[1], xref=True)\n\
         r = mass_properties(m)\n\
         print(json.dumps([float(r[0]), [float(x) for x in r[1]]]))\n";
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_impactlab"))
        .args(["check", path.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(o.status.code(), Some(0), "{r:#}");
    let w = &r["weight"];
    let Some((m, c)): Option<(f64, [f64; 3])> = common::pynastran_json(script, &[path.as_os_str()]) else {
        return;
    };
    let num = |v: &serde_json::Value| v.as_f64().unwrap();
    assert!(
        (num(&w["mass"][0]) - m).abs() <= 1e-12 * m,
        "mass {} vs {m}",
        w["mass"][0]
    );
    let offset_bar = (7.3e-4 * 0.64 + 0.02) * 4.0;
    let c = [c[0], c[1], c[2] - offset_bar * 0.5 / m];
    for k in 0..3 {
        assert!(
            (num(&w["centre"][k]) - c[k]).abs() <= 1e-12 * 10.0,
            "cg {} vs {c:?}",
            w["centre"]
        );
    }
}

/// Goal: case control's FORCE (and its other name ELFORCE) writes a beam's end
/// resultants, and STRESS alone does not. Model: the paper's plate on a 9×9 mesh with
/// one blade stiffener, as `impactlab mesh plate --stiffeners 1` writes it (STRESS on
/// the centre bar, FORCE on it too), run 300 steps; then its FORCE renamed ELFORCE,
/// and removed. Reference: the bar's axial force at each end is EA times the mean of
/// its four point strains (C, D, E, F at the rectangle's corners, where the linear
/// strain field averages to the centroid's), at every step. Tolerance: 1e-9 of the
/// largest |N| (the two are computed by different paths).
#[test]
fn force_request_writes_a_bars_resultants() {
    use impactlab::elements::{At, End, Measure, Recovered, Resultant};
    use impactlab::mesh::{stiffened_plate_deck, Cells, Stiffeners};
    use impactlab::run::Column;
    let blade = Stiffeners::blade(1);
    let text = stiffened_plate_deck(9, Cells::Quad4, &blade).unwrap();
    assert!(text.contains("  FORCE = 21"), "{text}");
    let bar = text
        .lines()
        .find_map(|l| l.strip_prefix("  SET 21 = "))
        .unwrap()
        .parse::<i64>()
        .unwrap();
    let force = |end, r| Column::Element {
        eid: bar,
        value: Recovered {
            measure: Measure::Force(r),
            at: Some(At::End(end)),
        },
    };
    for (name, deck) in [
        ("force", text.clone()),
        ("elforce", text.replace("  FORCE = 21", "  ELFORCE = 21")),
    ] {
        let model = impactlab::model_from_text(name, &deck).unwrap();
        let run = common::run(&model, impactlab::integrate::Scheme::Newmark, None, Some(300));
        let names = run.history_names();
        let by_name = |n: &str| -> Vec<f64> {
            let j = names
                .iter()
                .position(|x| x == n)
                .unwrap_or_else(|| panic!("{name}: no column {n}"));
            run.history.iter().map(|r| r[j]).collect()
        };
        for (end, e) in [(End::A, 0), (End::B, 1)] {
            let n = run.column_values(&force(end, Resultant::Axial)).unwrap();
            let m1 = run.column(&force(end, Resultant::Moment1)).unwrap();
            assert!(
                run.history_header()[m1].ends_with("[lbf*in]"),
                "{}",
                run.history_header()[m1]
            );
            let strains: Vec<Vec<f64>> = ["c", "d", "e", "f"]
                .iter()
                .map(|p| by_name(&format!("strain_{bar}_{}_{p}", ["a", "b"][e])))
                .collect();
            let peak = n.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(peak > 0.0, "{name}: the bar carries no axial force");
            let area = blade.width * blade.height;
            for (k, nk) in n.iter().enumerate() {
                let mean = strains.iter().map(|s| s[k]).sum::<f64>() / 4.0;
                assert!((nk - blade.e * area * mean).abs() <= 1e-9 * peak, "{name} step {k}");
            }
        }
    }
    let model = impactlab::model_from_text("stress-only", &text.replace("  FORCE = 21\n", "")).unwrap();
    let run = common::run(&model, impactlab::integrate::Scheme::Newmark, None, Some(2));
    assert!(run.column(&force(End::A, Resultant::Axial)).is_none());
    assert!(run.history_names().contains(&format!("stress_{bar}_a_c")));
}
