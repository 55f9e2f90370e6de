//! What the flat shell kinds (CQUAD4, CTRIA3) share: the section a PSHELL or PCOMP
//! resolves to, the discrete-Kirchhoff constraints of their bending, and recovery at
//! the two fibres with its material law.
//!
//! - Discrete Kirchhoff (Batoz, Bathe & Ho, IJNME 15, 1980 for the triangle DKT;
//!   Batoz & Tahar, IJNME 18, 1982 for the quadrilateral DKQ): the rotations of the
//!   normal βx = −∂w/∂x, βy = −∂w/∂y are quadratic over the element (corner and
//!   mid-side nodes), with the Kirchhoff constraints imposed at the corners and
//!   mid-sides and the tangential rotation linear along each side. The mid-side
//!   values are then linear in the corner DOFs (w, θx, θy), θx = ∂w/∂y, θy = −∂w/∂x,
//!   through each side's coefficients a, b, c, d, e ([`side_coefficients`]); the
//!   polygon's shape functions enter only through their values ([`h_vectors`]).
//! - Recovery: fibre strain ε(z) = ε⁰ + z κ at z = ∓T/2, stresses G(MID1) ε⁰ +
//!   G(MID2) κ z (the coupling of an unsymmetric section acts on resultants, not on
//!   the fibre stresses PSHELL's recovery reports).

use super::{Fibre, Measure, Output, Plane, Recovered, Resultant, Transverse};
use nalgebra::{Matrix2, Matrix3, Vector3};

/// A PSHELL (or a PCOMP's laminate) with its materials resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellSection {
    /// Thickness T.
    pub thickness: f64,
    /// Membrane material matrix G(MID1) (stress/strain), if any.
    pub g_membrane: Option<Matrix3<f64>>,
    /// Bending material matrix G(MID2)·(12I/T³), if any: D = this · T³/12.
    pub g_bending: Option<Matrix3<f64>>,
    /// Membrane-bending coupling material matrix G(MID4), if any: B = this · T²
    /// (an unsymmetric laminate's, or PSHELL's MID4).
    pub g_coupling: Option<Matrix3<f64>>,
    /// Transverse shear stiffness Ds (force/length), Q = Ds γ with Q = (Qx, Qy) and
    /// γ = (γxz, γyz): PSHELL's G(MID3)·(TS/T)·T, or a laminate's; `None`: rigid in
    /// transverse shear (the thin plate).
    pub shear: Option<Matrix2<f64>>,
    /// (ρ T + NSM), mass per unit area.
    pub mass_per_area: f64,
}

impl ShellSection {
    /// Membrane stiffness per unit length A = G(MID1)·T.
    pub fn a(&self) -> Option<Matrix3<f64>> {
        self.g_membrane.map(|g| g * self.thickness)
    }

    /// Bending stiffness D = G(MID2)·(12I/T³)·T³/12.
    pub fn d(&self) -> Option<Matrix3<f64>> {
        self.g_bending.map(|g| g * self.thickness.powi(3) / 12.0)
    }

    /// Membrane-bending coupling stiffness B = G(MID4)·T².
    pub fn b(&self) -> Option<Matrix3<f64>> {
        self.g_coupling.map(|g| g * self.thickness.powi(2))
    }

    /// The values a shell of this section recovers, in order: for STRESS, stresses
    /// then strains, for STRAIN, strains; each at fibre Z1 then Z2, components xx, yy,
    /// xy; with the stresses of a section with transverse shear flexibility, then its
    /// transverse shear forces Qx, Qy. For FORCE: Nx, Ny, Nxy, Mx, My, Mxy, then Qx, Qy
    /// of a section with transverse shear flexibility.
    pub fn recovered(&self, what: Output) -> Vec<Recovered> {
        let stress = what == Output::Stress;
        let measures: &[Measure] = match what {
            Output::Stress => &[Measure::Stress, Measure::Strain],
            Output::Strain => &[Measure::Strain],
            Output::Force => {
                let mut v = vec![
                    Resultant::Nx,
                    Resultant::Ny,
                    Resultant::Nxy,
                    Resultant::Mx,
                    Resultant::My,
                    Resultant::Mxy,
                ];
                if self.shear.is_some() {
                    v.extend([Resultant::Qx, Resultant::Qy]);
                }
                return v
                    .into_iter()
                    .map(|r| Recovered {
                        measure: Measure::Force(r),
                        at: None,
                    })
                    .collect();
            }
        };
        let mut v = Vec::new();
        for &measure in measures {
            for f in FIBRES {
                for c in PLANE {
                    v.push(Recovered {
                        measure,
                        at: Some(super::At::Fibre(f, c)),
                    });
                }
            }
        }
        if stress && self.shear.is_some() {
            v.extend([Transverse::Qx, Transverse::Qy].map(|q| Recovered {
                measure: Measure::ShearForce(q),
                at: None,
            }));
        }
        v
    }

    /// The recovered values (in the order of [`ShellSection::recovered`], before any
    /// shear forces) of a membrane strain `em` and curvature `kappa`.
    pub fn recover(&self, em: Vector3<f64>, kappa: Vector3<f64>, what: Output) -> Vec<f64> {
        if what == Output::Force {
            return self.forces(em, kappa).to_vec();
        }
        let stress = what == Output::Stress;
        let h = 0.5 * self.thickness;
        let mut stresses = Vec::new();
        let mut strains = Vec::new();
        for z in [-h, h] {
            let eps: Vector3<f64> = em + kappa * z;
            strains.extend(eps.iter());
            let sm = self.g_membrane.map(|g| g * em).unwrap_or_default();
            let sb = self.g_bending.map(|g| g * kappa * z).unwrap_or_default();
            stresses.extend((sm + sb).iter());
        }
        if stress {
            stresses.extend(strains);
            stresses
        } else {
            strains
        }
    }

    /// The resultants per unit length of a membrane strain `em` and curvature `kappa`:
    /// N = A ε⁰ + B κ, M = Bᵀ ε⁰ + D κ, as (Nx, Ny, Nxy, Mx, My, Mxy).
    pub fn forces(&self, em: Vector3<f64>, kappa: Vector3<f64>) -> [f64; 6] {
        let zero = Matrix3::zeros();
        let (a, b, d) = (
            self.a().unwrap_or(zero),
            self.b().unwrap_or(zero),
            self.d().unwrap_or(zero),
        );
        let n = a * em + b * kappa;
        let m = b.transpose() * em + d * kappa;
        [n[0], n[1], n[2], m[0], m[1], m[2]]
    }

    /// The fibre stresses the section's law gives for the fibre strains at z1 = −T/2
    /// and z2 = +T/2 (six values, in the order of [`ShellSection::recovered`]): the
    /// membrane strain and κ·T/2 from the two fibres, then G1 ε⁰ ∓ G2 κ T/2 at each.
    pub fn material_law(&self, strains: &[f64]) -> Vec<f64> {
        let v = |k: usize| Vector3::new(strains[k], strains[k + 1], strains[k + 2]);
        let (eps1, eps2) = (v(0), v(3));
        let membrane = (eps1 + eps2) * 0.5;
        let bending = (eps2 - eps1) * 0.5;
        let gm = self.g_membrane.unwrap_or_default();
        let gb = self.g_bending.unwrap_or_default();
        let mut out = Vec::with_capacity(6);
        for sign in [-1.0, 1.0] {
            let law = gm * membrane + gb * bending * sign;
            out.extend(law.iter());
        }
        out
    }
}

const FIBRES: [Fibre; 2] = [Fibre::Z1, Fibre::Z2];
const PLANE: [Plane; 3] = [Plane::Xx, Plane::Yy, Plane::Xy];

/// Side coefficients a, b, c, d, e of the discrete-Kirchhoff elements for the sides
/// 1→2, 2→3, …, N→1 of a polygon (x = xᵢ − xⱼ, y = yᵢ − yⱼ, l² = x² + y² along side
/// i→j): a = −x/l², b = ¾xy/l², c = (¼x² − ½y²)/l², d = −y/l², e = (¼y² − ½x²)/l².
pub fn side_coefficients<const N: usize>(xy: &[[f64; 2]; N]) -> [[f64; 5]; N] {
    let mut out = [[0.0; 5]; N];
    for (k, o) in out.iter_mut().enumerate() {
        let (i, j) = (k, (k + 1) % N);
        let x = xy[i][0] - xy[j][0];
        let y = xy[i][1] - xy[j][1];
        let l2 = x * x + y * y;
        *o = [
            -x / l2,
            0.75 * x * y / l2,
            (0.25 * x * x - 0.5 * y * y) / l2,
            -y / l2,
            (0.25 * y * y - 0.5 * x * x) / l2,
        ];
    }
    out
}

/// Hx, Hy (βx = Hx·U, βy = Hy·U, U = (w, θx, θy) at each of the N corners) from the
/// values `n` of the polygon's quadratic shape functions (or of their derivatives):
/// corners 1..N, then the mid-sides of sides 1→2, …, N→1. `hx`, `hy` hold 3N values.
pub fn h_vectors<const N: usize>(n: &[f64], sc: &[[f64; 5]; N], hx: &mut [f64], hy: &mut [f64]) {
    for i in 0..N {
        let m = i; // side starting at corner i
        let l = (i + N - 1) % N; // side ending at corner i
        let (nm, nl) = (n[N + m], n[N + l]);
        let [am, bm, cm, dm, em] = sc[m];
        let [al, bl, cl, dl, el] = sc[l];
        hx[3 * i] = 1.5 * (am * nm - al * nl);
        hx[3 * i + 1] = bm * nm + bl * nl;
        hx[3 * i + 2] = n[i] - cm * nm - cl * nl;
        hy[3 * i] = 1.5 * (dm * nm - dl * nl);
        hy[3 * i + 1] = -n[i] + em * nm + el * nl;
        hy[3 * i + 2] = -hx[3 * i + 1];
    }
}
