//! Classical lamination theory: the stiffness of a layered shell (PCOMP) from its plies
//! (MAT8 or MAT1), the stage between the deck and the model builder. The plate element
//! never sees a ply: it gets the laminate's membrane, coupling and bending stiffnesses.
//!
//! Kinematics (Kirchhoff-Love, through the whole thickness): ε(z) = ε⁰ + z·κ, with ε⁰
//! the reference plane's strains and κ its curvatures, engineering shear strains. Each
//! ply is in plane stress with its reduced stiffness in its own axes (1 along the
//! fibres), after Jones, *Mechanics of Composite Materials*, 2nd ed., Eq. 2.61:
//!
//!   Q11 = E1/(1 − ν12ν21), Q22 = E2/(1 − ν12ν21), Q12 = ν12·E2/(1 − ν12ν21),
//!   Q66 = G12, ν21 = ν12·E2/E1,
//!
//! turned to the laminate's axes by its angle θ (counter-clockwise about the normal,
//! from the laminate's x axis to the fibres) as Q̄ = Tᵀ·Q·T, T taking the laminate's
//! strains to the ply's (m = cos θ, n = sin θ; Jones Eq. 2.85 in matrix form):
//!
//!   T = [m² n² mn; n² m² −mn; −2mn 2mn m²−n²].
//!
//! The laminate's stiffnesses per unit width (Jones Eq. 4.22-4.24), plies k from the
//! bottom surface z₀ = Z0 up:
//!
//!   A = Σ Q̄ₖ (zₖ − zₖ₋₁),  B = ½ Σ Q̄ₖ (zₖ² − zₖ₋₁²),  D = ⅓ Σ Q̄ₖ (zₖ³ − zₖ₋₁³),
//!
//! and, where every ply gives G1Z and G2Z, the through-thickness integral of the
//! transverse shear stiffness (yz, xz order as NASTRAN's [Q44 Q45; Q45 Q55]), with no
//! shear correction applied: a plate that uses it chooses its own.
//!
//! Transverse shear stresses through the thickness follow from equilibrium in
//! cylindrical bending (Whitney, J. Composite Materials 7, 1973): with coupling and
//! twisting left out, τxz(z) = −(Qx/D11)·∫ Q̄11 ζ dζ from the bottom surface to z, and
//! τyz likewise with Q̄22, D22 and Qy. They give the interlaminar shear at each ply
//! interface ([`Interface`]) and, through the complementary energy, the laminate's
//! equilibrium shear stiffness ([`equilibrium_shear_stiffness`]), against which the
//! uniform factor 5/6 the plate uses is measured.

use nalgebra::{Matrix2, Matrix3, Vector3};

/// One ply as the lamination sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct Ply {
    /// Plane-stress stiffness in the ply's axes (1 along the fibres, 2 across, 12).
    pub q: Matrix3<f64>,
    /// Transverse shear moduli (G1Z, G2Z), when given.
    pub shear: Option<(f64, f64)>,
    /// Thickness.
    pub t: f64,
    /// Angle from the laminate's x axis to the ply's 1 axis, degrees, counter-clockwise.
    pub theta: f64,
    /// Mass density.
    pub rho: f64,
    /// Its failure criteria (PCOMP's FT and the maximum-stress index; none without FT).
    pub criteria: Vec<crate::damage::Criterion>,
}

/// An orthotropic ply's plane-stress stiffness in its own axes (Jones Eq. 2.61).
pub fn orthotropic_q(e1: f64, e2: f64, nu12: f64, g12: f64) -> Matrix3<f64> {
    let nu21 = nu12 * e2 / e1;
    let d = 1.0 - nu12 * nu21;
    Matrix3::new(e1 / d, nu12 * e2 / d, 0.0, nu12 * e2 / d, e2 / d, 0.0, 0.0, 0.0, g12)
}

/// The matrix T taking strains in the laminate's axes to strains in axes turned by
/// `theta` degrees (engineering shear strains).
pub fn strain_rotation(theta: f64) -> Matrix3<f64> {
    let (n, m) = theta.to_radians().sin_cos();
    Matrix3::new(
        m * m,
        n * n,
        m * n,
        n * n,
        m * m,
        -m * n,
        -2.0 * m * n,
        2.0 * m * n,
        m * m - n * n,
    )
}

/// A ply's transverse shear stiffness [C44 C45; C45 C55] (yz, xz) in the laminate's
/// axes, from its moduli G1Z, G2Z and its angle `theta` degrees (the 2-tensor rotation
/// of diag(G2Z, G1Z)).
fn rotated_shear((g1z, g2z): (f64, f64), theta: f64) -> Matrix2<f64> {
    let (n, m) = theta.to_radians().sin_cos();
    let c44 = g2z * m * m + g1z * n * n;
    let c55 = g1z * m * m + g2z * n * n;
    let c45 = (g1z - g2z) * m * n;
    Matrix2::new(c44, c45, c45, c55)
}

/// A ply's stiffness in the laminate's axes: Q̄ = Tᵀ Q T.
pub fn rotated(q: &Matrix3<f64>, theta: f64) -> Matrix3<f64> {
    let t = strain_rotation(theta);
    t.transpose() * q * t
}

/// A laminate's stiffnesses per unit width in its axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Laminate {
    /// Total thickness.
    pub thickness: f64,
    /// Membrane stiffness A (force/length).
    pub a: Matrix3<f64>,
    /// Membrane-bending coupling B (force).
    pub b: Matrix3<f64>,
    /// Bending stiffness D (force·length).
    pub d: Matrix3<f64>,
    /// Transverse shear stiffness ∫ C̄ dz (force/length), yz then xz, when every ply
    /// gives G1Z and G2Z.
    pub shear: Option<Matrix2<f64>>,
    /// Mass per unit area of the plies, Σ ρ t.
    pub mass_per_area: f64,
}

/// A ply as its results need it: its stiffness in its own axes, the rotation taking
/// strains in the element's axes to its axes, and its bottom and top z from the
/// laminate's mid-plane.
#[derive(Debug, Clone, PartialEq)]
pub struct PlyLayer {
    /// Plane-stress stiffness in the ply's axes.
    pub q: Matrix3<f64>,
    /// T(θ + material angle): element-axes strains to ply-axes strains.
    pub to_ply: Matrix3<f64>,
    /// Bottom and top of the ply, from the mid-plane.
    pub z: [f64; 2],
    /// Its failure criteria (none without FT).
    pub criteria: Vec<crate::damage::Criterion>,
    /// The bond with the ply above it, when there is one and the laminate is
    /// flexible in transverse shear.
    pub interface: Option<Interface>,
}

/// The bond between a ply and the ply above it: where the interlaminar shear
/// stresses are read.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// τxz per unit Qx and τyz per unit Qy there (1/length): −S/D of each direction
    /// of the equilibrium distribution (the module's last paragraph).
    pub per_force: [f64; 2],
    /// The rotation taking (τxz, τyz) in the element's axes to (τ1z, τ2z) in the
    /// axes of the ply below.
    pub to_ply: Matrix2<f64>,
    /// The allowable bond shear stress SB, when the PCOMP gives it with FT.
    pub allowable: Option<f64>,
}

impl Interface {
    /// The interlaminar shear stresses (τ1z, τ2z) in the axes of the ply below, from
    /// the element's transverse shear forces (Qx, Qy) in its axes.
    pub fn stresses(&self, q: [f64; 2]) -> nalgebra::Vector2<f64> {
        self.to_ply * nalgebra::Vector2::new(self.per_force[0] * q[0], self.per_force[1] * q[1])
    }

    /// The bond index max(|τ1z|, |τ2z|)/SB of `stresses` (`None` without SB).
    pub fn bond_index(&self, stresses: &nalgebra::Vector2<f64>) -> Option<f64> {
        Some(stresses.abs().max() / self.allowable?)
    }
}

impl PlyLayer {
    /// Strain (ε11, ε22, γ12) and stress (σ11, σ22, τ12) in the ply's axes at height
    /// `z`, from the laminate's mid-plane strain `e0` and curvature `k` in the element's
    /// axes (Kirchhoff-Love): ε = T·(ε⁰ + z·κ), σ = Q·ε.
    pub fn at(&self, e0: &Vector3<f64>, k: &Vector3<f64>, z: f64) -> (Vector3<f64>, Vector3<f64>) {
        let strain = self.to_ply * (e0 + k * z);
        (strain, self.q * strain)
    }
}

/// The plies of a laminate for its results, bottom to top, in axes from which the
/// plies' reference is turned by `material_angle` degrees (as [`Laminate::new`]); z
/// from the reference plane, the bottom at `z0` (`None`: at −t/2, the mid-plane the
/// reference). When every ply gives G1Z and G2Z, each
/// ply but the top one has its [`Interface`] with the ply above, of bond allowable
/// `bond_allowable`.
pub fn ply_layers(plies: &[Ply], z0: Option<f64>, material_angle: f64, bond_allowable: Option<f64>) -> Vec<PlyLayer> {
    let shear = shear_distributions(plies, material_angle);
    let mut z = z0.unwrap_or(-0.5 * plies.iter().map(|p| p.t).sum::<f64>());
    plies
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let bottom = z;
            z += p.t;
            let interface = shear.as_ref().filter(|_| k + 1 < plies.len()).map(|[xz, yz]| {
                let (n, m) = (p.theta + material_angle).to_radians().sin_cos();
                Interface {
                    per_force: [-xz.tops[k] / xz.d, -yz.tops[k] / yz.d],
                    to_ply: Matrix2::new(m, n, -n, m),
                    allowable: bond_allowable,
                }
            });
            PlyLayer {
                q: p.q,
                to_ply: strain_rotation(p.theta + material_angle),
                z: [bottom, z],
                criteria: p.criteria.clone(),
                interface,
            }
        })
        .collect()
}

/// Why plies make no laminate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LaminateError {
    /// No ply.
    #[error("the laminate has no ply")]
    Empty,
    /// A ply without thickness.
    #[error("ply {0} has no thickness")]
    Thickness(usize),
    /// A ply whose material is neither a MAT8 nor a MAT1.
    #[error("ply {ply} names material {mid}, which is no MAT8 or MAT1")]
    Material {
        /// The ply, from 1 at the bottom.
        ply: usize,
        /// The material id it names.
        mid: i64,
    },
    /// A ply whose material does not give what FT asks.
    #[error("ply {ply} (material {mid}): {source}")]
    Strength {
        /// The ply, from 1 at the bottom.
        ply: usize,
        /// The material id it names.
        mid: i64,
        /// What is missing.
        source: crate::damage::StrengthError,
    },
}

/// The plies of a PCOMP, bottom to top (LAM = SYM mirrored), each from its MAT8 (E1,
/// E2, NU12, G12; G1Z and G2Z when both are given; the allowables for FT) or its MAT1
/// (isotropic: the plane-stress matrix of E, NU, G; rigid in transverse shear, as a
/// PSHELL of that MAT1 without MID3 is; no allowables, so no FT).
pub fn plies_of(
    p: &crate::deck::cards::Pcomp,
    mat1s: &[crate::deck::cards::Mat1],
    mat8s: &[crate::deck::cards::Mat8],
) -> Result<Vec<Ply>, LaminateError> {
    use crate::damage::{ply_criteria, Strength, Theory};
    let theory = p.ft.as_deref().and_then(Theory::from_ft);
    p.stack()
        .iter()
        .enumerate()
        .map(|(k, ply)| {
            let criteria = |strength: Option<&Strength>| match theory {
                None => Ok(Vec::new()),
                Some(t) => ply_criteria(t, strength).map_err(|source| LaminateError::Strength {
                    ply: k + 1,
                    mid: ply.mid,
                    source,
                }),
            };
            if let Some(m) = mat8s.iter().find(|m| m.mid == ply.mid) {
                let strength = Strength {
                    allowables: m.allowables,
                    f12: m.f12,
                    strain: m.strn == 1.0,
                    moduli: [m.e1, m.e2, m.g12],
                };
                Ok(Ply {
                    q: orthotropic_q(m.e1, m.e2, m.nu12, m.g12),
                    shear: m.g1z.zip(m.g2z),
                    t: ply.t,
                    theta: ply.theta,
                    rho: m.rho,
                    criteria: criteria(Some(&strength))?,
                })
            } else if let Some(m) = mat1s.iter().find(|m| m.mid == ply.mid) {
                let q = m.e / (1.0 - m.nu * m.nu);
                Ok(Ply {
                    q: Matrix3::new(q, q * m.nu, 0.0, q * m.nu, q, 0.0, 0.0, 0.0, m.g),
                    shear: None,
                    t: ply.t,
                    theta: ply.theta,
                    rho: m.rho,
                    criteria: criteria(None)?,
                })
            } else {
                Err(LaminateError::Material {
                    ply: k + 1,
                    mid: ply.mid,
                })
            }
        })
        .collect()
}

/// The transverse shear through a laminate as equilibrium distributes it, in one
/// direction of cylindrical bending (xz: bending about y, under Qx; yz under Qy). With
/// membrane-bending coupling and the twisting terms left out (exact for a symmetric
/// cross-ply), the in-plane stress is σ = Q̄ z κ with κ = M/D, and equilibrium
/// ∂σ/∂x + ∂τ/∂z = 0 with ∂M/∂x = Q gives
///
///   τ(z) = −(Q/D) S(z),  S(z) = ∫ Q̄ ζ dζ from the bottom surface to z,
///
/// S vanishing at both surfaces (Whitney, J. Composite Materials 7, 1973; the
/// distribution NASTRAN uses for its interlaminar shear). Equating the
/// complementary shear energy ½∫τ²/C dz to ½Q²/K gives the laminate's equilibrium
/// shear stiffness K = D² / ∫ S²/C dz.
struct ShearDistribution {
    /// The bending stiffness D of the direction.
    d: f64,
    /// S at each ply's top surface, bottom to top.
    tops: Vec<f64>,
    /// ∫ S²/C dz over the thickness.
    energy: f64,
}

/// [`ShearDistribution`] of plies (bottom z, top z, the direction's Q̄ entry, its
/// transverse shear modulus C), S within a ply being c + Q̄ z²/2.
fn shear_distribution(layers: impl Iterator<Item = (f64, f64, f64, f64)> + Clone) -> ShearDistribution {
    let d: f64 = layers
        .clone()
        .map(|(a, b, q, _)| q * (b.powi(3) - a.powi(3)) / 3.0)
        .sum();
    let (mut s_bottom, mut energy, mut tops) = (0.0, 0.0, Vec::new());
    for (a, b, q, g) in layers {
        let c = s_bottom - q * a * a / 2.0;
        let squares = c * c * (b - a) + c * q * (b.powi(3) - a.powi(3)) / 3.0 + q * q * (b.powi(5) - a.powi(5)) / 20.0;
        energy += squares / g;
        s_bottom = c + q * b * b / 2.0;
        tops.push(s_bottom);
    }
    ShearDistribution { d, tops, energy }
}

/// The plies' xz and yz [`ShearDistribution`]s about the mid-plane, in axes from
/// which the plies' reference is turned by `material_angle` degrees; `None` when a
/// ply gives no G1Z, G2Z.
fn shear_distributions(plies: &[Ply], material_angle: f64) -> Option<[ShearDistribution; 2]> {
    let thickness: f64 = plies.iter().map(|p| p.t).sum();
    let mut z = -0.5 * thickness;
    let mut layers = Vec::with_capacity(plies.len());
    for p in plies {
        let c = rotated_shear(p.shear?, p.theta + material_angle);
        let q = rotated(&p.q, p.theta + material_angle);
        layers.push((z, z + p.t, q[(0, 0)], q[(1, 1)], c[(1, 1)], c[(0, 0)]));
        z += p.t;
    }
    let xz = shear_distribution(layers.iter().map(|l| (l.0, l.1, l.2, l.4)));
    let yz = shear_distribution(layers.iter().map(|l| (l.0, l.1, l.3, l.5)));
    Some([xz, yz])
}

/// The transverse shear stiffness (K55 in xz, K44 in yz, force/length) a laminate
/// has when its shear stresses follow from equilibrium (the module's last paragraph)
/// rather than a uniform shear correction. For one isotropic ply it is 5/6 G t, the
/// factor the model builder applies to ∫C̄ dz; for a laminate it shows what that
/// factor misses. `None` when a ply gives no G1Z, G2Z. The plies as
/// [`Laminate::new`] takes them, about the mid-plane.
pub fn equilibrium_shear_stiffness(plies: &[Ply], material_angle: f64) -> Option<(f64, f64)> {
    let [xz, yz] = shear_distributions(plies, material_angle)?;
    Some((xz.d * xz.d / xz.energy, yz.d * yz.d / yz.energy))
}

impl Laminate {
    /// The laminate of `plies`, bottom to top, its bottom surface at `z0` from the
    /// reference plane (`None`: the mid-plane is the reference, z0 = −t/2), expressed
    /// in axes from which the plies' reference (the element's material x axis) is
    /// turned by `material_angle` degrees counter-clockwise: a ply of angle θ has its
    /// fibres at θ + `material_angle` there.
    pub fn new(plies: &[Ply], z0: Option<f64>, material_angle: f64) -> Result<Laminate, LaminateError> {
        if plies.is_empty() {
            return Err(LaminateError::Empty);
        }
        if let Some(k) = plies.iter().position(|p| p.t.is_nan() || p.t <= 0.0) {
            return Err(LaminateError::Thickness(k + 1));
        }
        let thickness: f64 = plies.iter().map(|p| p.t).sum();
        let mut z = z0.unwrap_or(-0.5 * thickness);
        let (mut a, mut b, mut d) = (Matrix3::zeros(), Matrix3::zeros(), Matrix3::zeros());
        let mut shear = Some(Matrix2::zeros());
        let mut mass = 0.0;
        for p in plies {
            let q = rotated(&p.q, p.theta + material_angle);
            let top = z + p.t;
            a += q * (top - z);
            b += q * ((top * top - z * z) / 2.0);
            d += q * ((top.powi(3) - z.powi(3)) / 3.0);
            shear = match (shear, p.shear) {
                (Some(h), Some(g)) => Some(h + rotated_shear(g, p.theta + material_angle) * p.t),
                _ => None,
            };
            mass += p.rho * p.t;
            z = top;
        }
        Ok(Laminate {
            thickness,
            a,
            b,
            d,
            shear,
            mass_per_area: mass,
        })
    }

    /// True when membrane and bending are uncoupled: every B term below 1e-12 of
    /// A·t (a symmetric laminate about the reference plane, to round-off).
    pub fn is_uncoupled(&self) -> bool {
        let scale = self.a.abs().max() * self.thickness;
        self.b.abs().max() <= 1e-12 * scale
    }

    /// The bending stiffness as 12·D/t³ (the equivalent homogeneous plate's bending
    /// material, NASTRAN's MID2 with 12I/T³ = 1).
    pub fn bending_material(&self) -> Matrix3<f64> {
        self.d * (12.0 / self.thickness.powi(3))
    }

    /// The membrane-bending coupling as B/t² (NASTRAN's MID4).
    pub fn coupling_material(&self) -> Matrix3<f64> {
        self.b / self.thickness.powi(2)
    }

    /// The membrane stiffness as A/t (NASTRAN's MID1).
    pub fn membrane_material(&self) -> Matrix3<f64> {
        self.a / self.thickness
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Scotchply 1003 as the issue works it by hand (psi): E1 5.8e6-ish ply.
    fn glass(theta: f64, t: f64) -> Ply {
        Ply {
            q: orthotropic_q(5.6e6, 1.2e6, 0.26, 0.57e6),
            shear: Some((0.57e6, 0.4e6)),
            t,
            theta,
            rho: 1.8e-4,
            criteria: Vec::new(),
        }
    }

    /// Goal: T is Jones' closed form of the rotated stiffness (Eq. 2.85), term by term,
    /// at an angle where every term is nonzero; a turn by 90° swaps the 1- and 2-terms
    /// and changes the signs of the 16 and 26 terms.
    #[test]
    fn rotation_is_joness_closed_form() {
        let q = orthotropic_q(20e6, 1.5e6, 0.3, 0.8e6);
        let (q11, q12, q22, q66) = (q[(0, 0)], q[(0, 1)], q[(1, 1)], q[(2, 2)]);
        for theta in [0.0, 17.0, 30.0, 45.0, -60.0, 90.0] {
            let (n, m) = f64::to_radians(theta).sin_cos();
            let qb = rotated(&q, theta);
            let jones = [
                (
                    (0, 0),
                    q11 * m.powi(4) + 2.0 * (q12 + 2.0 * q66) * m * m * n * n + q22 * n.powi(4),
                ),
                (
                    (0, 1),
                    (q11 + q22 - 4.0 * q66) * m * m * n * n + q12 * (m.powi(4) + n.powi(4)),
                ),
                (
                    (1, 1),
                    q11 * n.powi(4) + 2.0 * (q12 + 2.0 * q66) * m * m * n * n + q22 * m.powi(4),
                ),
                (
                    (0, 2),
                    (q11 - q12 - 2.0 * q66) * m.powi(3) * n + (q12 - q22 + 2.0 * q66) * m * n.powi(3),
                ),
                (
                    (1, 2),
                    (q11 - q12 - 2.0 * q66) * m * n.powi(3) + (q12 - q22 + 2.0 * q66) * m.powi(3) * n,
                ),
                (
                    (2, 2),
                    (q11 + q22 - 2.0 * q12 - 2.0 * q66) * m * m * n * n + q66 * (m.powi(4) + n.powi(4)),
                ),
            ];
            for ((i, j), v) in jones {
                assert_relative_eq!(qb[(i, j)], v, epsilon = 1e-9 * q11);
                assert_relative_eq!(qb[(j, i)], v, epsilon = 1e-9 * q11);
            }
        }
        let (a, b) = (rotated(&q, 30.0), rotated(&q, 120.0));
        assert_relative_eq!(a[(0, 0)], b[(1, 1)], max_relative = 1e-12);
        assert_relative_eq!(a[(0, 2)], -b[(1, 2)], max_relative = 1e-12);
    }

    /// Goal: a cross-ply [0₅/90₅/0₅] (the paper's plate as the issue reads it) has
    /// A = t·(Q11·10/15 + Q22·5/15) along x and no coupling, and D in closed form: the
    /// outer 0° plies, from ±t/2 to ±t/6, carry 26/27 of the bending along x.
    #[test]
    fn cross_ply_in_closed_form() {
        let t = 0.01;
        let stack: Vec<Ply> = (0..15)
            .map(|k| glass(if (5..10).contains(&k) { 90.0 } else { 0.0 }, t))
            .collect();
        let l = Laminate::new(&stack, None, 0.0).unwrap();
        let q = orthotropic_q(5.6e6, 1.2e6, 0.26, 0.57e6);
        let h = 0.15;
        assert_relative_eq!(l.thickness, h, max_relative = 1e-12);
        assert_relative_eq!(
            l.a[(0, 0)],
            h * (q[(0, 0)] * 2.0 / 3.0 + q[(1, 1)] / 3.0),
            max_relative = 1e-12
        );
        assert_relative_eq!(
            l.a[(1, 1)],
            h * (q[(1, 1)] * 2.0 / 3.0 + q[(0, 0)] / 3.0),
            max_relative = 1e-12
        );
        assert!(l.is_uncoupled());
        let d11 = h.powi(3) / 12.0 * (q[(0, 0)] * 26.0 / 27.0 + q[(1, 1)] / 27.0);
        assert_relative_eq!(l.d[(0, 0)], d11, max_relative = 1e-12);
        assert!(l.d[(0, 2)].abs() <= 1e-12 * l.d[(0, 0)], "D16 vanishes to round-off");
        assert_relative_eq!(l.mass_per_area, 1.8e-4 * h, max_relative = 1e-12);
        let s = l.shear.unwrap();
        assert_relative_eq!(s[(0, 0)], t * (10.0 * 0.4e6 + 5.0 * 0.57e6), max_relative = 1e-12);
    }

    /// Goal: an angle-ply [+θ/−θ]s has no A16 and no B, but D16 and D26 of the sign of
    /// the outer ply's Q̄16: D16 = (Q̄16(θ))·(t³/12)·(1 − (1/2)³) from the outer pair;
    /// turning the stack (or the axes) changes their sign.
    #[test]
    fn angle_ply_bending_twist_coupling_has_the_outer_plys_sign() {
        let t = 0.01;
        let theta = 45.0;
        let stack: Vec<Ply> = [theta, -theta, -theta, theta].iter().map(|&a| glass(a, t)).collect();
        let l = Laminate::new(&stack, None, 0.0).unwrap();
        assert!(l.a[(0, 2)].abs() < 1e-9 * l.a[(0, 0)]);
        assert!(l.is_uncoupled());
        let qb = rotated(&glass(0.0, t).q, theta);
        let h = 4.0 * t;
        let d16 = qb[(0, 2)] * h.powi(3) / 12.0 * (1.0 - 0.125) - qb[(0, 2)] * h.powi(3) / 12.0 * 0.125;
        assert_relative_eq!(l.d[(0, 2)], d16, max_relative = 1e-12);
        assert!(l.d[(0, 2)] > 0.0 && l.d[(1, 2)] > 0.0, "{}", l.d);
        let mirrored: Vec<Ply> = [-theta, theta, theta, -theta].iter().map(|&a| glass(a, t)).collect();
        let m = Laminate::new(&mirrored, None, 0.0).unwrap();
        assert_relative_eq!(m.d[(0, 2)], -l.d[(0, 2)], max_relative = 1e-12);
        // The same stack with its reference turned by 90°: 1- and 2-terms swap, 16 and
        // 26 flip.
        let turned = Laminate::new(&stack, None, 90.0).unwrap();
        assert_relative_eq!(turned.d[(0, 0)], l.d[(1, 1)], max_relative = 1e-12);
        assert_relative_eq!(turned.d[(0, 2)], -l.d[(1, 2)], max_relative = 1e-12);
        // Turned by 30°: each ply's fibres at θ + 30°, the one-ply laminate of a 0° ply is
        // that ply turned by +30° (A16 > 0 for fibres stiffer than the matrix).
        let one = Laminate::new(&[glass(0.0, t)], None, 30.0).unwrap();
        let q30 = rotated(&glass(0.0, t).q, 30.0) * t;
        assert_relative_eq!(one.a, q30, max_relative = 1e-12);
        assert!(one.a[(0, 2)] > 0.0, "{}", one.a);
    }

    /// Goal: ply results are the laminate's strain turned into each ply's axes. At a
    /// given height a 0° ply reads (εx, εy, γxy), a 90° ply (εy, εx, −γxy), a 45° ply
    /// ε11 = (εx + εy + γxy)/2; σ = Q·ε; the plies of [0/90/0] sit at ∓t/2 and ∓t/6
    /// from the mid-plane; with the material axis turned by 90° the 0° ply reads as
    /// the 90° one did.
    #[test]
    fn ply_strains_are_the_laminate_strain_in_ply_axes() {
        let t = 0.01;
        let layers = ply_layers(&[glass(0.0, t), glass(90.0, t), glass(0.0, t)], None, 0.0, None);
        assert_relative_eq!(layers[0].z[0], -1.5 * t, max_relative = 1e-15);
        assert_relative_eq!(layers[1].z[0], -0.5 * t, max_relative = 1e-15);
        assert_relative_eq!(layers[2].z[1], 1.5 * t, max_relative = 1e-15);
        let (e0, k) = (Vector3::new(1e-3, -2e-4, 5e-4), Vector3::new(0.3, 0.1, -0.2));
        let z = 0.7 * t;
        let e = e0 + k * z;
        let (s0, q0) = layers[0].at(&e0, &k, z);
        assert_relative_eq!(s0, e, max_relative = 1e-12);
        assert_relative_eq!(q0, layers[0].q * e, max_relative = 1e-12);
        let (s90, _) = layers[1].at(&e0, &k, z);
        assert_relative_eq!(s90, Vector3::new(e[1], e[0], -e[2]), epsilon = 1e-15);
        let (s45, _) = ply_layers(&[glass(45.0, t)], None, 0.0, None)[0].at(&e0, &k, z);
        assert_relative_eq!(s45[0], (e[0] + e[1] + e[2]) / 2.0, max_relative = 1e-12);
        let (turned, _) = ply_layers(&[glass(0.0, t)], None, 90.0, None)[0].at(&e0, &k, z);
        assert_relative_eq!(turned, s90, epsilon = 1e-15);
    }

    /// Goal: an unsymmetric [0/90] couples membrane and bending, B = (t²/8)·(Q22 − Q11)
    /// along x (Jones Eq. 4.24 with plies from −t/2 to 0 and 0 to t/2... each of
    /// thickness t/2: B11 = ½[Q11((0)² − (t/2)²) + Q22((t/2)² − 0)]).
    #[test]
    fn unsymmetric_cross_ply_couples() {
        let t = 0.01;
        let l = Laminate::new(&[glass(0.0, t), glass(90.0, t)], None, 0.0).unwrap();
        let q = glass(0.0, t).q;
        assert!(!l.is_uncoupled());
        assert_relative_eq!(l.b[(0, 0)], 0.5 * (q[(1, 1)] - q[(0, 0)]) * t * t, max_relative = 1e-12);
        assert_relative_eq!(l.b[(1, 1)], -l.b[(0, 0)], max_relative = 1e-12);
    }

    /// Goal: one isotropic ply is the homogeneous plate: A/t and 12D/t³ are its
    /// plane-stress matrix.
    #[test]
    fn one_isotropic_ply_is_the_homogeneous_plate() {
        let (e, nu) = (10.0e6, 0.3);
        let q = orthotropic_q(e, e, nu, e / (2.0 * (1.0 + nu)));
        let l = Laminate::new(
            &[Ply {
                q,
                shear: None,
                t: 0.2,
                theta: 33.0,
                rho: 2.5e-4,
                criteria: Vec::new(),
            }],
            None,
            0.0,
        )
        .unwrap();
        assert_relative_eq!(l.membrane_material(), q, max_relative = 1e-12, epsilon = 1e-6);
        assert_relative_eq!(l.bending_material(), q, max_relative = 1e-12, epsilon = 1e-6);
        assert!(l.shear.is_none());
        assert_eq!(Laminate::new(&[], None, 0.0), Err(LaminateError::Empty));
    }
    /// Goal: the equilibrium-based transverse shear stiffness. Reference: for one
    /// isotropic ply, the parabolic shear stress gives exactly 5/6 G t (Reissner); for
    /// the paper's cross-ply [0₅/90₅/0₅] with G1Z 5.7e5, G2Z 4.59e5 psi, against
    /// 5/6 ∫C̄ dz: the stiff 0° faces carry the bending stress, so the shear stress
    /// peaks in the soft 90° core (xz) and the laminate is softer in xz than the
    /// uniform factor says; printed and bounded. Tolerance: round-off for the
    /// isotropic ply.
    #[test]
    fn equilibrium_shear_stiffness_is_five_sixths_for_one_ply_and_differs_for_the_cross_ply() {
        let (e, nu, g, t) = (1.0e7, 0.3, 1.0e7 / 2.6, 0.2);
        let q = e / (1.0 - nu * nu);
        let iso = Ply {
            q: Matrix3::new(q, q * nu, 0.0, q * nu, q, 0.0, 0.0, 0.0, g),
            shear: Some((g, g)),
            t,
            theta: 30.0,
            rho: 0.0,
            criteria: Vec::new(),
        };
        let (k55, k44) = equilibrium_shear_stiffness(&[iso], 0.0).unwrap();
        assert_relative_eq!(k55, 5.0 / 6.0 * g * t, max_relative = 1e-12);
        assert_relative_eq!(k44, 5.0 / 6.0 * g * t, max_relative = 1e-12);
        let ply = |theta: f64| Ply {
            q: orthotropic_q(5.735e6, 1.2855e6, 0.2231, 5.7e5),
            shear: Some((5.7e5, 4.59e5)),
            t: 0.01,
            theta,
            rho: 1.8e-4,
            criteria: Vec::new(),
        };
        let plies: Vec<Ply> = (0..15)
            .map(|k| ply(if (5..10).contains(&k) { 90.0 } else { 0.0 }))
            .collect();
        let (k55, k44) = equilibrium_shear_stiffness(&plies, 0.0).unwrap();
        let uniform = Laminate::new(&plies, None, 0.0).unwrap().shear.unwrap() * (5.0 / 6.0);
        let (r55, r44) = (k55 / uniform[(1, 1)], k44 / uniform[(0, 0)]);
        eprintln!("cross-ply: equilibrium / (5/6 ∫C̄ dz): xz {r55:.4}, yz {r44:.4}");
        assert!(r55 > 0.9 && r55 < 0.99, "{r55}");
        assert!(r44 > 0.99 && r44 < 1.01, "{r44}");
    }

    /// Goal: the interlaminar shear stresses at the ply interfaces from the transverse
    /// shear forces. Reference: one isotropic plate cut into two plies has the
    /// parabolic τ = 3Q/(2t) at its mid-plane; the cross-ply [0₅/90₅/0₅] at its 0/90
    /// interfaces z = ∓t/6, worked by hand from S(z) = ∫ Q̄ ζ dζ: τxz = Qx·Q11(t²/4 −
    /// t²/36)/(2 D11), τyz likewise with Q22 and D22, D from the three layers; in the
    /// 90° ply's axes τ1z = τyz, τ2z = −τxz. The distribution's S vanishes at the top
    /// surface (equilibrium with no surface shear). Tolerance: round-off.
    #[test]
    fn interlaminar_shear_is_the_equilibrium_distribution_at_each_interface() {
        let (e, nu, t) = (1.0e7, 0.3, 0.2);
        let q = e / (1.0 - nu * nu);
        let half = Ply {
            q: Matrix3::new(q, q * nu, 0.0, q * nu, q, 0.0, 0.0, 0.0, e / 2.6),
            shear: Some((e / 2.6, e / 2.6)),
            t: t / 2.0,
            theta: 0.0,
            rho: 0.0,
            criteria: Vec::new(),
        };
        let layers = ply_layers(&[half.clone(), half], None, 0.0, Some(1.0e3));
        let bond = layers[0].interface.as_ref().unwrap();
        let tau = bond.stresses([2.0, -4.0]);
        assert_relative_eq!(tau[0], 1.5 * 2.0 / t, max_relative = 1e-12);
        assert_relative_eq!(tau[1], -1.5 * 4.0 / t, max_relative = 1e-12);
        assert_relative_eq!(
            bond.bond_index(&tau).unwrap(),
            1.5 * 4.0 / t / 1.0e3,
            max_relative = 1e-12
        );
        assert!(layers[1].interface.is_none(), "the top ply has no bond above it");

        let (q11, q22) = (5.8e6, 1.3e6);
        let ply = |theta: f64| Ply {
            q: Matrix3::new(q11, 2.9e5, 0.0, 2.9e5, q22, 0.0, 0.0, 0.0, 5.7e5),
            shear: Some((5.7e5, 4.59e5)),
            t: 0.01,
            theta,
            rho: 0.0,
            criteria: Vec::new(),
        };
        let plies: Vec<Ply> = (0..15)
            .map(|k| ply(if (5..10).contains(&k) { 90.0 } else { 0.0 }))
            .collect();
        let h: f64 = 0.15;
        let d = |face: f64, core: f64| {
            (2.0 * face * (h.powi(3) / 8.0 - h.powi(3) / 216.0) + core * h.powi(3) / 108.0) / 3.0
        };
        let (d11, d22) = (d(q11, q22), d(q22, q11));
        let lift = h * h / 4.0 - h * h / 36.0;
        let layers = ply_layers(&plies, None, 0.0, None);
        let (qx, qy) = (3.0, 5.0);
        let below = layers[4].interface.as_ref().unwrap().stresses([qx, qy]);
        assert_relative_eq!(below[0], qx * q11 * lift / (2.0 * d11), max_relative = 1e-12);
        assert_relative_eq!(below[1], qy * q22 * lift / (2.0 * d22), max_relative = 1e-12);
        let above = layers[9].interface.as_ref().unwrap().stresses([qx, qy]);
        assert_relative_eq!(above[0], qy * q22 * lift / (2.0 * d22), max_relative = 1e-12);
        assert_relative_eq!(above[1], -qx * q11 * lift / (2.0 * d11), max_relative = 1e-12);
        assert_eq!(layers[4].interface.as_ref().unwrap().bond_index(&below), None);
        let [xz, yz] = shear_distributions(&plies, 0.0).unwrap();
        for s in [xz, yz] {
            assert!(
                s.tops[14].abs() < 1e-12 * s.tops[4].abs(),
                "S at the top surface: {}",
                s.tops[14]
            );
        }
        // Rigid in transverse shear: no interfaces.
        let thin: Vec<Ply> = plies
            .iter()
            .map(|p| Ply {
                shear: None,
                ..p.clone()
            })
            .collect();
        assert!(ply_layers(&thin, None, 0.0, Some(1.0))
            .iter()
            .all(|l| l.interface.is_none()));
    }
}
