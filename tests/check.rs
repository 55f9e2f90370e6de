//! `impactlab check`: will impactlab take a deck? Its structure alone, counted and
//! weighed against an independent reader (pyNastran's mass_properties), and every
//! card it does not take.

use crate::common;

use common::impactlab;
use serde_json::Value;
use std::path::Path;

/// A structural deck of the kind `check` is for: SOL 103 with an EIGRL, a PARAM and a
/// FORCE; a cylindrical system 5 (its axis along basic y through (0, 0, 10)) in which
/// the grids are located (CP) and displaced (CD); 4×3 CQUAD4 on the cylinder of
/// radius 10 (PSHELL with NSM); two CONM2 with products of inertia; the first arc
/// edge clamped through SPCADD 20 of SPC1 10. `shells` false leaves out the CQUAD4s.
fn structural_deck(shells: bool) -> String {
    let mut d = String::from(
        "$ Units: in, lbf, s\nSOL 103\nCEND\n  SPC = 20\n  METHOD = 1\nBEGIN BULK\nEIGRL,1,,,5\n\
         PARAM,AUTOSPC,YES\nCORD2C,5,0,0.0,0.0,10.0,0.0,1.0,10.0\n,1.0,0.0,10.0\n",
    );
    for i in 0..5 {
        for j in 0..4 {
            d.push_str(&format!(
                "GRID,{},5,10.0,{:?},{:?},5\n",
                100 * j + i + 1,
                -20.0 + 10.0 * i as f64,
                2.0 * j as f64
            ));
        }
    }
    if shells {
        for i in 0..4 {
            for j in 0..3 {
                let g = 100 * j + i + 1;
                d.push_str(&format!("CQUAD4,{g},1,{g},{},{},{}\n", g + 1, g + 101, g + 100));
            }
        }
    }
    d.push_str(
        "PSHELL,1,1,0.1,1,,,,0.01\nMAT1,1,1.0+7,,0.3,0.1\n\
         CONM2,901,3,0,2.5,,,,,+C1\n+C1,1.0,0.1,2.0,0.2,0.3,3.0\n\
         CONM2,902,303,0,1.5,,,,,+C2\n+C2,0.5,-0.2,0.7,0.1,0.05,0.9\n\
         SPC1,10,123456,1,THRU,5\nSPCADD,20,10\nFORCE,7,103,0,1.0,0.0,0.0,1.0\nENDDATA\n",
    );
    d
}

fn check_json(path: &Path) -> (i32, Value) {
    let o = impactlab(&["check", path.to_str().unwrap(), "--json"]);
    let v = serde_json::from_slice(&o.stdout).unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&o.stderr)));
    (o.status.code().unwrap(), v)
}

/// pyNastran's mass properties of a deck: (mass, cg, [Ixx, Iyy, Izz, Ixy, Ixz, Iyz]
/// about the cg), of the CONM2s alone when `masses_only`; `None` (and a note) where
/// pyNastran cannot run it, except under CI, where that fails.
fn pynastran(path: &Path, masses_only: bool) -> Option<(f64, [f64; 3], [f64; 6])> {
    let script = format!(
        "import json, sys\n\
         from pyNastran.bdf.bdf import BDF\n\
         from pyNastran.bdf.mesh_utils.mass_properties import mass_properties\n\
         m = BDF(debug=None)\n\
         m.read_bdf(sys.argv[1], xref=True)\n\
         r = mass_properties(m{})\n\
         print(json.dumps([float(r[0]), [float(x) for x in r[1]], [float(x) for x in r[2]]]))\n",
        if masses_only {
            ", element_ids=[], mass_ids=list(m.masses)"
        } else {
            ""
        }
    );
    common::pynastran_json(&script, &[path.as_os_str()])
}

/// Goal: `check` reads a structural deck with no impactor and answers for it: exit 0,
/// its grids, elements by kind, DOFs (the SPCADD's clamped edge: 5 grids × 6), the
/// cylindrical system with the grids located and displaced in it, and the cards that
/// do not change the structure (EIGRL, FORCE, PARAM) listed as ignored with their
/// count and first line. Its mass and centre of gravity against pyNastran's
/// mass_properties, an independent reader of the same deck: equal to 1e-12 (both
/// are exact sums: a lumped shell mass's first moment is ∫ρx dA, pyNastran's element
/// mass at the centroid of each rectangle is too). Its inertia about the centre of
/// gravity against pyNastran's on the CONM2s alone (pyNastran puts a shell's mass at
/// its centroid, NASTRAN's weight generator and impactlab at its grids, so with the
/// shells the two differ by the elements' own inertia): to 1e-12 of the largest
/// moment about the origin (the parallel-axis subtraction's round-off).
#[test]
fn check_answers_for_a_structural_deck_as_pynastran_weighs_it() {
    let dir = tempfile::tempdir().unwrap();
    let full = dir.path().join("shell.bdf");
    let masses = dir.path().join("masses.bdf");
    std::fs::write(&full, structural_deck(true)).unwrap();
    std::fs::write(&masses, structural_deck(false)).unwrap();
    let (code, r) = check_json(&full);
    assert_eq!(code, 0, "{r:#}");
    assert_eq!(r["takes"], true);
    assert_eq!(r["solution"], "103");
    assert_eq!(r["grids"], 20);
    assert_eq!(r["elements"]["CQUAD4"], 12);
    assert_eq!(r["elements"]["CONM2"], 2);
    assert_eq!(r["constrained_dofs"], 30);
    assert_eq!(r["free_dofs"], 90);
    assert_eq!(r["systems"][0]["kind"], "cylindrical");
    assert_eq!(r["systems"][0]["located"], 20);
    assert_eq!(r["systems"][0]["displaced"], 20);
    let ignored: Vec<&str> = r["ignored"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["card"].as_str().unwrap())
        .collect();
    assert_eq!(ignored, ["EIGRL", "FORCE", "PARAM"]);
    assert_eq!(r["ignored"][1]["first_line"], "FORCE,7,103,0,1.0,0.0,0.0,1.0");
    assert!(r["unsupported"].as_array().unwrap().is_empty());
    let w = &r["weight"];
    let num = |v: &Value| v.as_f64().unwrap();
    if let Some((m, c, _)) = pynastran(&full, false) {
        assert!(
            (num(&w["mass"][0]) - m).abs() <= 1e-12 * m,
            "mass {} vs {m}",
            w["mass"][0]
        );
        for k in 0..3 {
            assert!(
                (num(&w["centre"][k]) - c[k]).abs() <= 1e-12 * 10.0,
                "cg {} vs {c:?}",
                w["centre"]
            );
        }
    }
    let (_, r) = check_json(&masses);
    let w = &r["weight"];
    // pyNastran weighs the CONM2s alone of the full deck (it refuses a deck without
    // elements); impactlab weighs the deck without its shells.
    if let Some((m, _, i)) = pynastran(&full, true) {
        assert!((num(&w["mass"][0]) - m).abs() <= 1e-12 * m);
        let scale = 4.0 * 10.0f64.hypot(10.0).powi(2);
        for (k, (a, b)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)].iter().enumerate() {
            let ours = num(&w["inertia"][*a][*b]);
            assert!((ours - i[k]).abs() <= 1e-12 * scale, "I{a}{b}: {ours} vs {}", i[k]);
        }
    }
}

/// Goal: `check` says no, and why, to a deck it does not take: an RBAR (which would
/// change the structure) is listed as not supported with its count and first line,
/// and the exit code is 2; a property that does not exist is an error naming the
/// card, exit 2, with the report of what was read.
#[test]
fn check_refuses_what_it_cannot_take_and_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let deck = structural_deck(true).replace(
        "ENDDATA",
        "RBAR,77,1,2,123456\nRBAR,78,2,3,123456\nCHEXA,79,1,1,2,3,4,5,6,\n,7,8\nENDDATA",
    );
    let path = dir.path().join("rigid.bdf");
    std::fs::write(&path, &deck).unwrap();
    let o = impactlab(&["check", path.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(out.contains("not supported   RBAR ×2 (first at "), "{out}");
    assert!(out.contains("RBAR,77,1,2,123456"), "{out}");
    assert!(out.contains("not supported   CHEXA ×1"), "{out}");
    assert!(
        out.contains("impactlab does not take this deck: 2 kind(s) of card"),
        "{out}"
    );
    let broken = structural_deck(true).replace("CQUAD4,1,1,", "CQUAD4,1,9,");
    std::fs::write(&path, broken).unwrap();
    let o = impactlab(&["check", path.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(
        out.contains("CQUAD4 1 references property 9 (PSHELL or PCOMP), which does not exist"),
        "{out}"
    );
    assert!(out.contains("the structure does not build: 1 error(s)"), "{out}");
}
