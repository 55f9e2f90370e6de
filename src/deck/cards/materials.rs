//! Materials: MAT1 (isotropic), MAT2 (anisotropic plate), MAT8 (orthotropic ply).

use super::*;

/// MAT1: an isotropic material.
#[derive(Debug, Clone)]
pub struct Mat1 {
    /// Material id (field 2).
    pub mid: i64,
    /// Young's modulus E (field 3).
    pub e: f64,
    /// Shear modulus G (field 4).
    pub g: f64,
    /// Poisson's ratio NU (field 5).
    pub nu: f64,
    /// Mass density RHO (field 6).
    pub rho: f64,
    /// Thermal expansion coefficient A (field 7; 0.0 when blank).
    pub alpha: f64,
    /// Reference temperature TREF (field 8; 0.0 when blank): a temperature load
    /// strains the material by A·(T − TREF).
    pub tref: f64,
    /// Structural damping coefficient GE (field 9; 0.0 when blank).
    pub ge: f64,
    /// The card.
    pub at: CardRef,
}

/// Anisotropic 2-D material: `[G11 G12 G13; G12 G22 G23; G13 G23 G33]`.
#[derive(Debug, Clone)]
pub struct Mat2 {
    /// Material id (field 2).
    pub mid: i64,
    /// The symmetric material matrix, from G11, G12, G13, G22, G23, G33 (fields 3-8).
    pub g: [[f64; 3]; 3],
    /// Mass density RHO (field 9).
    pub rho: f64,
    /// Structural damping coefficient GE (continuation field 6; 0.0 when blank).
    pub ge: f64,
    /// The card.
    pub at: CardRef,
}

/// MAT8: an orthotropic material for shells (a ply), in its own axes 1 (fibre) and 2.
#[derive(Debug, Clone)]
pub struct Mat8 {
    /// Material id (field 2).
    pub mid: i64,
    /// Modulus along the fibres E1 (field 3).
    pub e1: f64,
    /// Modulus across the fibres E2 (field 4).
    pub e2: f64,
    /// Poisson's ratio NU12 (field 5): strain in 2 over strain in 1 under stress in 1.
    pub nu12: f64,
    /// In-plane shear modulus G12 (field 6).
    pub g12: f64,
    /// Transverse shear moduli G1Z, G2Z (fields 7, 8); `None` when blank.
    pub g1z: Option<f64>,
    /// See `g1z`.
    pub g2z: Option<f64>,
    /// Mass density RHO (field 9).
    pub rho: f64,
    /// Allowables Xt, Xc, Yt, Yc, S (continuation fields 5-9); `None` when blank.
    pub allowables: [Option<f64>; 5],
    /// The Tsai-Wu interaction term F12 (second continuation, field 3).
    pub f12: Option<f64>,
    /// STRN (second continuation, field 4): 1.0 when the allowables are strains.
    pub strn: f64,
    /// Structural damping coefficient GE (second continuation, field 2; 0.0 when
    /// blank).
    pub ge: f64,
    /// The card.
    pub at: CardRef,
}

/// MAT1.
pub(super) fn card_mat1(r: &mut Reader, b: &mut Bulk) {
    let e = r.real_opt(1, "E");
    let g = r.real_opt(2, "G");
    let nu = r.real_opt(3, "NU");
    let rho = r.real_or(4, "RHO", 0.0);
    let alpha = r.real_or(5, "A", 0.0);
    let tref = r.real_or(6, "TREF", 0.0);
    let ge = r.real_or(7, "GE", 0.0);
    r.non_negative(7, "GE", ge);
    let (e, g, nu) = match (e, g, nu) {
        (Some(e), Some(g), Some(nu)) => (e, g, nu),
        (Some(e), None, Some(nu)) => (e, e / (2.0 * (1.0 + nu)), nu),
        (Some(e), Some(g), None) => (e, g, e / (2.0 * g) - 1.0),
        (None, Some(g), Some(nu)) => (2.0 * g * (1.0 + nu), g, nu),
        (Some(e), None, None) => (e, 0.0, 0.0),
        _ => {
            if r.ok {
                r.fail(1, "E", "MAT1 needs E, or two of E, G and NU");
            }
            (0.0, 0.0, 0.0)
        }
    };
    if r.ok {
        if e <= 0.0 {
            r.fail(1, "E", format!("Young's modulus must be positive (E = {e})"));
        }
        if !(-1.0..0.5).contains(&nu) {
            r.fail(3, "NU", format!("Poisson's ratio must lie in (-1, 0.5) (NU = {nu})"));
        }
        r.non_negative(4, "RHO", rho);
    }
    let m = Mat1 {
        mid: r.id(0, "MID"),
        e,
        g,
        nu,
        rho,
        alpha,
        tref,
        ge,
        at: r.at(),
    };
    if r.ok {
        b.mat1s.push(m);
    }
}

/// MAT2.
pub(super) fn card_mat2(r: &mut Reader, b: &mut Bulk) {
    let v: Vec<f64> = (1..=6)
        .map(|k| r.real_or(k, ["", "G11", "G12", "G13", "G22", "G23", "G33"][k], 0.0))
        .collect();
    let rho = r.real_or(7, "RHO", 0.0);
    r.non_negative(7, "RHO", rho);
    for (k, name) in [
        (8, "A1"),
        (9, "A2"),
        (10, "A3"),
        (11, "TREF"),
        (13, "ST"),
        (14, "SC"),
        (15, "SS"),
    ] {
        r.real_opt(k, name);
    }
    let ge = r.real_or(12, "GE", 0.0);
    r.non_negative(12, "GE", ge);
    let g = [[v[0], v[1], v[2]], [v[1], v[3], v[4]], [v[2], v[4], v[5]]];
    let m = Mat2 {
        mid: r.id(0, "MID"),
        g,
        rho,
        ge,
        at: r.at(),
    };
    if r.ok {
        b.mat2s.push(m);
    }
}

/// MAT8: MID E1 E2 NU12 G12 G1Z G2Z RHO / A1 A2 TREF Xt Xc Yt Yc S / GE F12 STRN.
/// E1, E2 and G12 are required and positive, NU12 must leave the ply's compliance
/// positive definite (NU12² < E1/E2); the allowables, when given, are positive (Xc
/// and Yc as magnitudes, as NASTRAN takes them); a blank Xc is Xt and a blank Yc is
/// Yt (NASTRAN's defaults), with a warning.
pub(super) fn card_mat8(r: &mut Reader, b: &mut Bulk) {
    let mid = r.id(0, "MID");
    let e1 = r.real(1, "E1");
    let e2 = r.real(2, "E2");
    let nu12 = r.real_or(3, "NU12", 0.0);
    let g12 = r.real(4, "G12");
    let g1z = r.real_opt(5, "G1Z");
    let g2z = r.real_opt(6, "G2Z");
    let rho = r.real_or(7, "RHO", 0.0);
    for (k, name, v) in [(1, "E1", e1), (2, "E2", e2), (4, "G12", g12)] {
        r.positive(k, name, v);
    }
    if let Some(v) = g1z {
        r.positive(5, "G1Z", v);
    }
    if let Some(v) = g2z {
        r.positive(6, "G2Z", v);
    }
    r.non_negative(7, "RHO", rho);
    if r.ok && nu12 * nu12 >= e1 / e2 {
        r.fail(
            3,
            "NU12",
            format!(
                "NU12² = {:e} must be below E1/E2 = {:e}: the ply's stiffness would not be positive definite",
                nu12 * nu12,
                e1 / e2
            ),
        );
    }
    for (k, name) in [(8, "A1"), (9, "A2"), (10, "TREF")] {
        r.real_opt(k, name);
    }
    let ge = r.real_or(16, "GE", 0.0);
    r.non_negative(16, "GE", ge);
    let names = ["Xt", "Xc", "Yt", "Yc", "S"];
    // Xc and Yc are magnitudes; NASTRAN-95 writes them "Real" of either sign (MAT8).
    let mut allowables: [Option<f64>; 5] = std::array::from_fn(|i| {
        let v = r.real_opt(11 + i, names[i]);
        match v {
            Some(v) if (i == 1 || i == 3) && v < 0.0 => Some(-v),
            Some(v) => {
                r.positive(11 + i, names[i], v);
                Some(v)
            }
            None => None,
        }
    });
    // A blank compressive allowable is the tensile one, as NASTRAN takes it.
    for (c, t) in [(1, 0), (3, 2)] {
        if let (None, Some(tension)) = (allowables[c], allowables[t]) {
            allowables[c] = Some(tension);
            r.warn(
                11 + c,
                names[c],
                format!(
                    "is blank: {} = {} = {tension:e}, as NASTRAN takes it",
                    names[c], names[t]
                ),
            );
        }
    }
    let f12 = r.real_opt(17, "F12");
    let strn = r.real_or(18, "STRN", 0.0);
    if strn != 0.0 && strn != 1.0 {
        r.fail(
            18,
            "STRN",
            "must be blank, 0.0 (stress allowables) or 1.0 (strain allowables)",
        );
    }
    r.extra_fields(19);
    let m = Mat8 {
        mid,
        e1,
        e2,
        nu12,
        g12,
        g1z,
        g2z,
        rho,
        allowables,
        f12,
        strn,
        ge,
        at: r.at(),
    };
    if r.ok {
        b.mat8s.push(m);
    }
}
