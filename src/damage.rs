//! Damage onset in a struck laminate: the quasi-static delamination threshold load,
//! from the plate's stiffness and the interface's toughness, and the plies' failure
//! indices, from their stresses or strains and allowables.
//!
//! # Delamination onset
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
//!
//! # Ply failure indices
//!
//! The theories PCOMP's FT names (HILL, HOFF, TSAI, STRN, the words of the NASTRAN
//! PCOMP card), for a ply in plane stress (σ1, σ2, τ12) in its axes, with the MAT8's
//! allowables Xt, Xc, Yt, Yc (the compressive ones as magnitudes, as MAT8 takes them)
//! and S. Solvers differ in details; where a form leaves a choice, the one made here is
//! stated:
//!
//! - HILL (Tsai-Hill; Jones, *Mechanics of Composite Materials*, 2nd ed., §2.9.3, with
//!   sign-dependent allowables): FI = σ1²/X² − σ1σ2/X² + σ2²/Y² + τ12²/S², X = Xt when
//!   σ1 ≥ 0, else Xc, and Y likewise from σ2; the interaction term uses the same X as
//!   the σ1² term.
//! - HOFF (Hoffman, J. Compos. Mater. 1 (1967) 200-206): FI = (1/Xt − 1/Xc)σ1 +
//!   (1/Yt − 1/Yc)σ2 + σ1²/(Xt Xc) + σ2²/(Yt Yc) − σ1σ2/(Xt Xc) + τ12²/S².
//! - TSAI (Tsai-Wu, J. Compos. Mater. 5 (1971) 58-80): FI = F1σ1 + F2σ2 + F11σ1² +
//!   F22σ2² + F66τ12² + 2F12σ1σ2, F1 = 1/Xt − 1/Xc, F11 = 1/(Xt Xc), F2 and F22
//!   likewise from Y, F66 = 1/S², F12 the MAT8's; a blank F12 is 0, as NASTRAN-95's
//!   Tsai-Wu index takes it (then the index has no σ1σ2 term), and the model builder
//!   says so in a warning.
//! - STRN (maximum strain): FI = max(ε1/Xt or −ε1/Xc, ε2/Yt or −ε2/Yc, |γ12|/S) with
//!   strain allowables (MAT8 STRN = 1.0); stress allowables are turned into strain
//!   allowables by the ply's moduli (Xt/E1, …, S/G12), the strain a uniaxial stress at
//!   the allowable makes.
//! - The maximum-stress index, the same on stresses, beside any theory whose ply has
//!   stress allowables.
//!
//! Each reaches 1 on its failure envelope: a uniaxial stress at an allowable gives 1
//! in every theory. The quadratic ones are not ratios: doubling the stress quadruples
//! HILL's index, and HOFF's and TSAI's linear terms make theirs depend on the sign.
//! A theory whose allowables are missing is an input error ([`StrengthError`]), never
//! a silent zero.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// The delamination threshold of a laminate, as `summary.json` gives it.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
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

/// A failure theory: PCOMP's FT, or the maximum-stress index.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Theory {
    /// Tsai-Hill (FT = HILL).
    Hill,
    /// Hoffman (FT = HOFF).
    Hoffman,
    /// Tsai-Wu (FT = TSAI).
    TsaiWu,
    /// Maximum strain (FT = STRN).
    MaxStrain,
    /// Maximum stress.
    MaxStress,
}

impl Theory {
    /// The theory FT names (HILL, HOFF, TSAI, STRN).
    pub fn from_ft(ft: &str) -> Option<Theory> {
        match ft {
            "HILL" => Some(Theory::Hill),
            "HOFF" => Some(Theory::Hoffman),
            "TSAI" => Some(Theory::TsaiWu),
            "STRN" => Some(Theory::MaxStrain),
            _ => None,
        }
    }

    /// Its name: FT's word, or `MAXSTRESS`.
    pub fn name(self) -> &'static str {
        match self {
            Theory::Hill => "HILL",
            Theory::Hoffman => "HOFF",
            Theory::TsaiWu => "TSAI",
            Theory::MaxStrain => "STRN",
            Theory::MaxStress => "MAXSTRESS",
        }
    }
}

/// A ply's strength as its MAT8 gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Strength {
    /// Xt, Xc, Yt, Yc, S (Xc and Yc as magnitudes); `None` when blank.
    pub allowables: [Option<f64>; 5],
    /// The Tsai-Wu interaction term F12.
    pub f12: Option<f64>,
    /// True when the allowables are strains (MAT8 STRN = 1.0).
    pub strain: bool,
    /// The ply's moduli E1, E2, G12.
    pub moduli: [f64; 3],
}

/// Why a ply's strength cannot give a theory's index.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StrengthError {
    /// An allowable the theory needs is blank.
    #[error("FT = {theory} needs the allowable {field}, which is blank")]
    Missing {
        /// The theory.
        theory: &'static str,
        /// The MAT8 field.
        field: &'static str,
    },
    /// The allowables are strains, the theory reads stresses.
    #[error("FT = {0} reads stresses, but the allowables are strains (STRN = 1.0)")]
    StrainAllowables(&'static str),
    /// The ply's material carries no allowables (a MAT1 ply).
    #[error("FT = {0} needs allowables, which only a MAT8 ply has")]
    NoAllowables(&'static str),
}

/// One theory's index for one ply: the allowables resolved for what it reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criterion {
    /// The theory.
    pub theory: Theory,
    /// Xt, Xc, Yt, Yc, S: strains for [`Theory::MaxStrain`], else stresses.
    allow: [f64; 5],
    /// F12 (Tsai-Wu only).
    f12: f64,
}

impl Criterion {
    /// The criterion of `theory` for a ply of `strength`.
    pub fn new(theory: Theory, strength: Option<&Strength>) -> Result<Criterion, StrengthError> {
        let s = strength.ok_or(StrengthError::NoAllowables(theory.name()))?;
        let names = ["Xt", "Xc", "Yt", "Yc", "S"];
        let mut allow = [0.0; 5];
        for (k, a) in s.allowables.iter().enumerate() {
            allow[k] = a.ok_or(StrengthError::Missing {
                theory: theory.name(),
                field: names[k],
            })?;
        }
        if theory == Theory::MaxStrain {
            if !s.strain {
                let [e1, e2, g12] = s.moduli;
                allow = [
                    allow[0] / e1,
                    allow[1] / e1,
                    allow[2] / e2,
                    allow[3] / e2,
                    allow[4] / g12,
                ];
            }
        } else if s.strain {
            return Err(StrengthError::StrainAllowables(theory.name()));
        }
        let f12 = match theory {
            Theory::TsaiWu => s.f12.unwrap_or(0.0),
            _ => 0.0,
        };
        Ok(Criterion { theory, allow, f12 })
    }

    /// The failure index of a ply point with `strain` (ε1, ε2, γ12) and `stress` (σ1,
    /// σ2, τ12) in the ply's axes. The quadratic terms are formed from the ratios of
    /// stress to allowable (σ1/X · σ1/X, not σ1²/X²), so that an allowable below
    /// 1e-154 does not underflow X² to 0 and make an unstressed ply's index 0/0.
    pub fn index(&self, strain: &Vector3<f64>, stress: &Vector3<f64>) -> f64 {
        let [xt, xc, yt, yc, s] = self.allow;
        let (s1, s2, t) = (stress[0], stress[1], stress[2]);
        let largest = |v: &Vector3<f64>| {
            let along = |x: f64, tension: f64, compression: f64| {
                if x >= 0.0 {
                    x / tension
                } else {
                    -x / compression
                }
            };
            along(v[0], xt, xc).max(along(v[1], yt, yc)).max(v[2].abs() / s)
        };
        match self.theory {
            Theory::Hill => {
                let x = if s1 >= 0.0 { xt } else { xc };
                let y = if s2 >= 0.0 { yt } else { yc };
                (s1 / x) * (s1 / x - s2 / x) + (s2 / y).powi(2) + (t / s).powi(2)
            }
            Theory::Hoffman => {
                (1.0 / xt - 1.0 / xc) * s1
                    + (1.0 / yt - 1.0 / yc) * s2
                    + (s1 / xt) * (s1 / xc - s2 / xc)
                    + (s2 / yt) * (s2 / yc)
                    + (t / s).powi(2)
            }
            Theory::TsaiWu => {
                (1.0 / xt - 1.0 / xc) * s1
                    + (1.0 / yt - 1.0 / yc) * s2
                    + (s1 / xt) * (s1 / xc)
                    + (s2 / yt) * (s2 / yc)
                    + (t / s).powi(2)
                    + 2.0 * self.f12 * s1 * s2
            }
            Theory::MaxStrain => largest(strain),
            Theory::MaxStress => largest(stress),
        }
    }
}

/// The criteria of a ply under FT = `theory`: that theory's, then the maximum-stress
/// index when the allowables are stresses.
pub fn ply_criteria(theory: Theory, strength: Option<&Strength>) -> Result<Vec<Criterion>, StrengthError> {
    let mut out = vec![Criterion::new(theory, strength)?];
    if theory != Theory::MaxStress && strength.is_some_and(|s| !s.strain) {
        out.push(Criterion::new(Theory::MaxStress, strength)?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A glass/epoxy ply's strength, psi (round values of that material's order), with
    /// F12 = −½√(F11 F22).
    fn strength() -> Strength {
        let (xt, xc, yt, yc) = (1.54e5, 8.85e4, 4.5e3, 1.71e4);
        Strength {
            allowables: [Some(xt), Some(xc), Some(yt), Some(yc), Some(1.04e4)],
            f12: Some(-0.5 / (xt * xc * yt * yc).sqrt()),
            strain: false,
            moduli: [5.6e6, 1.2e6, 0.6e6],
        }
    }

    fn stress(s1: f64, s2: f64, t: f64) -> Vector3<f64> {
        Vector3::new(s1, s2, t)
    }

    /// Goal: an unstressed ply's index is 0 in every theory however small its
    /// allowables (1e-300: X² underflows to 0, so σ²/X² would be 0/0), a stressed one's
    /// is never NaN, and scaling stresses and allowables together (by 1e-200, below
    /// where X² underflows) leaves every index as it was, to 1e-15 relative (the few
    /// roundings of the ratios; scaling by a power of ten is not exact in binary).
    #[test]
    fn tiny_allowables_give_zero_at_zero_stress_and_no_nan() {
        let index = |theory: Theory, allowable: f64, s: Vector3<f64>| {
            let strength = Strength {
                allowables: [Some(allowable); 5],
                f12: Some(0.0),
                strain: false,
                moduli: [5.6e6, 1.2e6, 0.6e6],
            };
            Criterion::new(theory, Some(&strength))
                .unwrap()
                .index(&Vector3::zeros(), &s)
        };
        let sigma = stress(0.3, -0.2, 0.1);
        for theory in [Theory::Hill, Theory::Hoffman, Theory::TsaiWu, Theory::MaxStress] {
            for allowable in [1.0, 1e-200, 1e-300] {
                assert_eq!(
                    index(theory, allowable, Vector3::zeros()),
                    0.0,
                    "{theory:?} {allowable:e}"
                );
                assert!(!index(theory, allowable, sigma).is_nan(), "{theory:?} {allowable:e}");
            }
            let (unit, scaled) = (index(theory, 1.0, sigma), index(theory, 1e-200, sigma * 1e-200));
            assert!(
                (scaled - unit).abs() < 1e-15 * unit.abs().max(1.0),
                "{theory:?}: {scaled} vs {unit}"
            );
        }
    }

    /// Goal: every theory's index is 1 under a uniaxial stress at each allowable, in
    /// tension and in compression, and under pure shear at S (for STRN, the strain that
    /// stress makes): the theories' envelopes pass through the allowables.
    #[test]
    fn a_uniaxial_stress_at_an_allowable_is_index_one_in_every_theory() {
        let s = strength();
        let [xt, xc, yt, yc, sh] = s.allowables.map(Option::unwrap);
        let [e1, e2, g12] = s.moduli;
        for theory in [
            Theory::Hill,
            Theory::Hoffman,
            Theory::TsaiWu,
            Theory::MaxStrain,
            Theory::MaxStress,
        ] {
            let c = Criterion::new(theory, Some(&s)).unwrap();
            for sig in [
                stress(xt, 0.0, 0.0),
                stress(-xc, 0.0, 0.0),
                stress(0.0, yt, 0.0),
                stress(0.0, -yc, 0.0),
                stress(0.0, 0.0, sh),
                stress(0.0, 0.0, -sh),
            ] {
                // The strain of a uniaxial stress, Poisson's strain left out (STRN reads
                // each component against its own allowable).
                let eps = stress(sig[0] / e1, sig[1] / e2, sig[2] / g12);
                let fi = c.index(&eps, &sig);
                assert!((fi - 1.0).abs() < 1e-12, "{theory:?} at {sig:?}: {fi}");
            }
        }
    }

    /// Goal: the theories differ where they should. HILL is quadratic (twice the stress,
    /// four times the index) and picks its allowables by sign; HOFF and TSAI have linear
    /// terms (a compressive σ2 at half Yc is far from failure, a tensile one at Yt/2
    /// nearer); TSAI's F12 couples σ1 and σ2 and HOFF's coupling is −σ1σ2/(Xt Xc); the
    /// maximum-stress index is the largest ratio.
    #[test]
    fn the_theories_differ_where_their_forms_do() {
        let s = strength();
        let [xt, xc, yt, yc, sh] = s.allowables.map(Option::unwrap);
        let z = Vector3::zeros();
        let at = |t: Theory, sig: Vector3<f64>| Criterion::new(t, Some(&s)).unwrap().index(&z, &sig);
        let sig = stress(0.3 * xt, -0.2 * yc, 0.4 * sh);
        let hill = (0.3f64.powi(2) * xt * xt + 0.3 * xt * 0.2 * yc) / (xt * xt) + 0.04 + 0.16;
        assert!((at(Theory::Hill, sig) - hill).abs() < 1e-12);
        assert!((at(Theory::Hill, sig * 2.0) - 4.0 * hill).abs() < 1e-12);
        let hoff = (1.0 / xt - 1.0 / xc) * 0.3 * xt - (1.0 / yt - 1.0 / yc) * 0.2 * yc
            + (0.09 * xt * xt + 0.3 * xt * 0.2 * yc) / (xt * xc)
            + 0.04 * yc * yc / (yt * yc)
            + 0.16;
        assert!((at(Theory::Hoffman, sig) - hoff).abs() < 1e-12);
        let f12 = s.f12.unwrap();
        let tsai = hoff - 0.3 * xt * 0.2 * yc / (xt * xc) - 2.0 * f12 * 0.3 * xt * 0.2 * yc;
        assert!((at(Theory::TsaiWu, sig) - tsai).abs() < 1e-12);
        assert!((at(Theory::MaxStress, sig) - 0.4).abs() < 1e-15);
        // Half the transverse allowable: compression is safer under the linear terms.
        let (c, t) = (
            at(Theory::TsaiWu, stress(0.0, -0.5 * yc, 0.0)),
            at(Theory::TsaiWu, stress(0.0, 0.5 * yt, 0.0)),
        );
        assert!(c < 0.0 && t > 0.0, "{c} {t}");
    }

    /// Goal: missing allowables are named, never read as zero: a blank Yc for HILL,
    /// strain allowables for a stress theory, a ply with no MAT8 (a blank F12 for TSAI
    /// is NASTRAN's 0, the index then Tsai-Wu's without its interaction term);
    /// strain allowables serve STRN as given, with no maximum-stress index beside it.
    #[test]
    fn missing_allowables_are_errors_that_name_the_field() {
        let mut s = strength();
        s.allowables[3] = None;
        let e = Criterion::new(Theory::Hill, Some(&s)).unwrap_err();
        assert_eq!(e.to_string(), "FT = HILL needs the allowable Yc, which is blank");
        let mut s = strength();
        s.f12 = None;
        assert!(Criterion::new(Theory::Hoffman, Some(&s)).is_ok());
        let blank = Criterion::new(Theory::TsaiWu, Some(&s)).unwrap();
        s.f12 = Some(0.0);
        let zero = Criterion::new(Theory::TsaiWu, Some(&s)).unwrap();
        assert_eq!(blank, zero);
        s.f12 = Some(-1e-10);
        assert_ne!(Criterion::new(Theory::TsaiWu, Some(&s)).unwrap(), zero);
        let mut s = strength();
        s.strain = true;
        s.allowables = [0.02, 0.015, 0.004, 0.012, 0.018].map(Some);
        assert!(matches!(
            Criterion::new(Theory::Hoffman, Some(&s)),
            Err(StrengthError::StrainAllowables("HOFF"))
        ));
        let c = ply_criteria(Theory::MaxStrain, Some(&s)).unwrap();
        assert_eq!(c.len(), 1);
        let fi = c[0].index(&stress(-0.0075, 0.0, 0.0), &Vector3::zeros());
        assert!((fi - 0.5).abs() < 1e-15, "{fi}");
        assert_eq!(ply_criteria(Theory::Hill, Some(&strength())).unwrap().len(), 2);
        assert!(matches!(
            Criterion::new(Theory::Hill, None),
            Err(StrengthError::NoAllowables("HILL"))
        ));
    }

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
