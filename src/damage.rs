//! Damage onset in a struck laminate, from the plate's stiffness and the interface's
//! toughness: the quasi-static delamination threshold load.
//!
//! A point-loaded plate whose contact force reaches
//!
//!   F_crit = π √(32 D* G_IIc / 9)
//!
//! grows a mode II delamination (an existing small one at the mid-plane grows
//! unstably): Davies & Zhang, "Impact damage prediction in carbon composite
//! structures", Int. J. Impact Engng 16 (1995) 149-170, in the form Olsson gives it
//! ("Analytical prediction of large mass impact damage in composite laminates",
//! Composites A 32 (2001) 1207-1215). The constant is independent of the plate's size
//! and boundary: the threshold is a property of the laminate and its interface.
//! Restatements of Davies and Zhang in E, h and ν, P_c² = 8π²Eh³G_IIc/(9(1 − ν²)),
//! give √3 more with D = Eh³/(12(1 − ν²)); the form above is the one used here, and
//! the summary names it.
//!
//! D* is the orthotropic plate's effective bending stiffness for a point load,
//! D* = √(D11 D22 (A + 1)/2), A = (D12 + 2D66)/√(D11 D22) (Olsson, the same stiffness
//! as the infinite plate's impedance in [`crate::physics::analytic::plate_impedance`]):
//! the isotropic plate with D* deflects under a point load as the orthotropic one does,
//! and the threshold was derived for an isotropic plate. It equals D for an isotropic
//! plate and lies between √(D11 D22)·√(1/2) and √(D11 D22) for usual laminates; the
//! paper's cross-ply (A = 0.51) has D* = 0.87 √(D11 D22).
//!
//! G_IIc is the user's: no card carries it. It is given in the deck's units
//! (force/length, the energy per unit area of crack).
//!
//! Not modelled: Olsson's dynamic threshold for small-mass impacts (a higher load when
//! the impactor is light next to the plate's mass in play, Olsson, Donadon & Falzon,
//! Int. J. Solids Struct. 43 (2006) 3124-3141).

use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// The delamination threshold of a laminate, as `summary.json` gives it.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DelaminationOnset {
    /// The mode II interlaminar fracture toughness used, force/length.
    pub g_iic: f64,
    /// The effective bending stiffness D*, force·length.
    pub effective_bending_stiffness: f64,
    /// F_crit = π √(32 D* G_IIc / 9), force.
    pub critical_force: f64,
    /// The formula, for the reader.
    pub formula: String,
}

/// D* = √(D11 D22 (A + 1)/2), A = (D12 + 2 D66)/√(D11 D22), of a bending matrix
/// D (D11, D22, D12 and D66 = D(2, 2); D16 and D26 left out).
pub fn effective_bending_stiffness(d: &Matrix3<f64>) -> f64 {
    let (d11, d22, d12, d66) = (d[(0, 0)], d[(1, 1)], d[(0, 1)], d[(2, 2)]);
    let a = (d12 + 2.0 * d66) / (d11 * d22).sqrt();
    (d11 * d22 * (a + 1.0) / 2.0).sqrt()
}

/// The quasi-static delamination threshold of a plate of bending matrix `d` whose
/// interface has mode II toughness `g_iic`.
pub fn delamination_onset(d: &Matrix3<f64>, g_iic: f64) -> DelaminationOnset {
    let d_star = effective_bending_stiffness(d);
    DelaminationOnset {
        g_iic,
        effective_bending_stiffness: d_star,
        critical_force: std::f64::consts::PI * (32.0 * d_star * g_iic / 9.0).sqrt(),
        formula: "F_crit = pi*sqrt(32*D*G_IIc/9) (Davies & Zhang 1995, as Olsson 2001), \
                  D* = sqrt(D11*D22*(A+1)/2), A = (D12+2*D66)/sqrt(D11*D22)"
            .into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: for an isotropic plate D* = D (A = 1), and F_crit follows the closed form:
    /// a 4 mm quasi-isotropic carbon/epoxy plate (E 50 GPa, ν 0.3, G_IIc 800 J/m²)
    /// has D = 293.0 N·m and F_crit = π√(32·293.0·800/9) = 2.868 kN.
    #[test]
    fn isotropic_plate_threshold_is_the_closed_form() {
        let (e, nu, h): (f64, f64, f64) = (50e9, 0.3, 4e-3);
        let d0 = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
        let d = Matrix3::new(d0, nu * d0, 0.0, nu * d0, d0, 0.0, 0.0, 0.0, (1.0 - nu) / 2.0 * d0);
        assert!((effective_bending_stiffness(&d) / d0 - 1.0).abs() < 1e-14);
        let f = delamination_onset(&d, 800.0);
        assert!((d0 - 293.04).abs() < 0.01, "{d0}");
        assert!((f.critical_force - 2868.2).abs() < 0.05, "{}", f.critical_force);
        // F_crit grows as √G_IIc and √D.
        let f4 = delamination_onset(&(d * 4.0), 800.0).critical_force;
        assert!((f4 / f.critical_force - 2.0).abs() < 1e-14);
    }

    /// Goal: D* of the paper's cross-ply (MAT2 201: 5.7e6, 1.4e6, 2.9e5, 5.7e5 psi at
    /// 0.15 in) sits below √(D11 D22) as its A < 1 says: A = 0.506, D* = 0.868 √(D11 D22).
    #[test]
    fn cross_ply_effective_stiffness_is_below_the_geometric_mean() {
        let t3 = 0.15f64.powi(3) / 12.0;
        let d = Matrix3::new(5.7e6, 2.9e5, 0.0, 2.9e5, 1.4e6, 0.0, 0.0, 0.0, 5.7e5) * t3;
        let g = (d[(0, 0)] * d[(1, 1)]).sqrt();
        let a = (d[(0, 1)] + 2.0 * d[(2, 2)]) / g;
        assert!((a - 0.506).abs() < 1e-3, "{a}");
        let ratio = effective_bending_stiffness(&d) / g;
        assert!((ratio - 0.868).abs() < 1e-3, "{ratio}");
    }
}
