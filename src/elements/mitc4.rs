//! CQUAD4 with transverse shear flexibility: the MITC4 plate (Bathe & Dvorkin, "A
//! four-node plate bending element based on Mindlin/Reissner plate theory and a mixed
//! interpolation", IJNME 21, 1985), with the bilinear membrane of [`super::quad4`].
//! Chosen for a CQUAD4 whose section has a transverse shear stiffness (PSHELL MID3,
//! or a PCOMP whose plies all give G1Z and G2Z); without one, CQUAD4 is the thin DKQ.
//!
//! - Kinematics (Reissner-Mindlin): u = z βx, v = z βy with the rotations of the
//!   normal βx = θy, βy = −θx (NASTRAN's θx, θy; in the thin limit βx = −∂w/∂x,
//!   βy = −∂w/∂y, as the DKQ); w, θx, θy bilinear. Curvatures κ = (βx,x, βy,y,
//!   βx,y + βy,x), transverse shear strains γ = (γxz, γyz) = (w,x + βx, w,y + βy).
//! - Mixed interpolation (the MITC part, which removes shear locking): the covariant
//!   shear strains γξ = x,ξ γxz + y,ξ γyz and γη are sampled at the mid-sides
//!   (γξ at η = ±1, γη at ξ = ±1) and interpolated linearly across, then taken back to
//!   x, y through the Jacobian. Bending ∫ Bbᵀ D Bb dA, shear ∫ Bsᵀ Ds Bs dA,
//!   membrane-bending coupling ∫ Bmᵀ B Bb dA, all 2×2 Gauss (full integration: the
//!   element has exactly the three rigid plate modes, no spurious zero-energy mode).
//!   Passes the constant-curvature and constant-shear patch tests; converges O(h²) in
//!   deflection, to the thin plate as t/L → 0 without locking.
//! - Ds: the section's transverse shear stiffness (force/length), Q = Ds γ.
//! - Mass: as the thin CQUAD4, (ρT + NSM) lumped to the translations, no rotary
//!   inertia (NASTRAN's lumped mass): the rotations carry none, so the implicit
//!   schemes run it and the explicit one refuses it (the rotations have no mass),
//!   as for the thin plate.
//! - Recovery at the centre, as the thin CQUAD4: fibre strains ε⁰ ∓ κ T/2; with the
//!   stresses (a STRESS request) also the transverse shear forces (Qx, Qy) = Ds γ at
//!   the centre, from the tied shear strains (constant-shear exact, O(h) in general).

use super::quad4::{area, flat, lumped_mass, membrane_stiffness, membrane_strain, parts, Xy};
use super::shell::ShellSection;
use super::{BadShape, Cell, Kernel, LocalMatrix, Recovered};
use nalgebra::{DMatrix, Matrix2, SMatrix, Vector2, Vector3};

const G: f64 = 0.577_350_269_189_625_8;
const GAUSS: [(f64, f64); 4] = [(-G, -G), (G, -G), (G, G), (-G, G)];
const CORNER: [(f64, f64); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];

/// Bilinear shape functions and their (ξ, η) derivatives.
fn bilinear(xi: f64, eta: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let mut n = [0.0; 4];
    let mut dxi = [0.0; 4];
    let mut deta = [0.0; 4];
    for (i, &(a, b)) in CORNER.iter().enumerate() {
        n[i] = 0.25 * (1.0 + a * xi) * (1.0 + b * eta);
        dxi[i] = 0.25 * a * (1.0 + b * eta);
        deta[i] = 0.25 * b * (1.0 + a * xi);
    }
    (n, dxi, deta)
}

/// Jacobian [[x,ξ, y,ξ], [x,η, y,η]] at (ξ, η).
fn jacobian(xy: &Xy, xi: f64, eta: f64) -> Matrix2<f64> {
    let (_, dxi, deta) = bilinear(xi, eta);
    let mut j = Matrix2::zeros();
    for i in 0..4 {
        j[(0, 0)] += dxi[i] * xy[i][0];
        j[(0, 1)] += dxi[i] * xy[i][1];
        j[(1, 0)] += deta[i] * xy[i][0];
        j[(1, 1)] += deta[i] * xy[i][1];
    }
    j
}

/// Curvature-displacement matrix at (ξ, η), DOFs (w, θx, θy) per corner, and the
/// Jacobian determinant.
fn b_bending(xy: &Xy, xi: f64, eta: f64) -> (SMatrix<f64, 3, 12>, f64) {
    let (_, dxi, deta) = bilinear(xi, eta);
    let j = jacobian(xy, xi, eta);
    let jinv = j.try_inverse().expect("a positive Jacobian");
    let mut b = SMatrix::<f64, 3, 12>::zeros();
    for i in 0..4 {
        let d = jinv * Vector2::new(dxi[i], deta[i]);
        let (nx, ny) = (d[0], d[1]);
        // βx = Σ Nᵢ θyᵢ, βy = −Σ Nᵢ θxᵢ.
        b[(0, 3 * i + 2)] = nx;
        b[(1, 3 * i + 1)] = -ny;
        b[(2, 3 * i + 2)] = ny;
        b[(2, 3 * i + 1)] = -nx;
    }
    (b, j.determinant())
}

/// The covariant shear strains (γξ, γη) at (ξ, η) from the displacement
/// interpolation directly: rows over (w, θx, θy) per corner.
fn covariant_shear(xy: &Xy, xi: f64, eta: f64) -> SMatrix<f64, 2, 12> {
    let (n, dxi, deta) = bilinear(xi, eta);
    let j = jacobian(xy, xi, eta);
    let mut b = SMatrix::<f64, 2, 12>::zeros();
    for i in 0..4 {
        for (r, dn) in [(0, dxi[i]), (1, deta[i])] {
            // γr = ∂w/∂r + x,r βx + y,r βy, with βx = θy, βy = −θx.
            b[(r, 3 * i)] = dn;
            b[(r, 3 * i + 1)] = -j[(r, 1)] * n[i];
            b[(r, 3 * i + 2)] = j[(r, 0)] * n[i];
        }
    }
    b
}

/// The MITC4 shear strain-displacement matrix at (ξ, η): (γxz, γyz) from the
/// covariant strains tied at the mid-sides, and the Jacobian determinant.
fn b_shear(xy: &Xy, xi: f64, eta: f64) -> (SMatrix<f64, 2, 12>, f64) {
    let (a, c) = (covariant_shear(xy, 0.0, 1.0), covariant_shear(xy, 0.0, -1.0));
    let (d, b) = (covariant_shear(xy, 1.0, 0.0), covariant_shear(xy, -1.0, 0.0));
    let mut nat = SMatrix::<f64, 2, 12>::zeros();
    for k in 0..12 {
        nat[(0, k)] = 0.5 * (1.0 + eta) * a[(0, k)] + 0.5 * (1.0 - eta) * c[(0, k)];
        nat[(1, k)] = 0.5 * (1.0 + xi) * d[(1, k)] + 0.5 * (1.0 - xi) * b[(1, k)];
    }
    let j = jacobian(xy, xi, eta);
    let jinv = j.try_inverse().expect("a positive Jacobian");
    (jinv * nat, j.determinant())
}

/// The plate stiffness (bending and transverse shear), DOFs (w, θx, θy) per corner.
pub fn plate_stiffness(xy: &Xy, d: &nalgebra::Matrix3<f64>, ds: &Matrix2<f64>) -> SMatrix<f64, 12, 12> {
    let mut k = SMatrix::<f64, 12, 12>::zeros();
    for &(xi, eta) in &GAUSS {
        let (bb, det) = b_bending(xy, xi, eta);
        let (bs, _) = b_shear(xy, xi, eta);
        k += (bb.transpose() * d * bb + bs.transpose() * ds * bs) * det;
    }
    k
}

/// A CQUAD4 with transverse shear flexibility (MITC4) in the plane z = `z`.
#[derive(Debug, Clone, PartialEq)]
pub struct Mitc4 {
    /// Corner coordinates in the element's plane.
    pub xy: Xy,
    /// The plane's z.
    pub z: f64,
    /// Section and materials (with its transverse shear stiffness).
    pub section: ShellSection,
    /// The whole stiffness over the membrane DOFs (u, v per corner) then the plate's
    /// (w, θx, θy per corner).
    k: SMatrix<f64, 20, 20>,
}

impl Mitc4 {
    /// The element; `section.shear` must be given.
    pub fn new(xy: Xy, z: f64, section: ShellSection) -> Self {
        let mut k = SMatrix::<f64, 20, 20>::zeros();
        if let Some(a) = section.a() {
            k.fixed_view_mut::<8, 8>(0, 0).copy_from(&membrane_stiffness(&xy, &a));
        }
        let d = section.d().unwrap_or_default();
        let ds = section.shear.unwrap_or_default();
        k.fixed_view_mut::<12, 12>(8, 8)
            .copy_from(&plate_stiffness(&xy, &d, &ds));
        if let Some(b) = section.b() {
            let mut kmb = SMatrix::<f64, 8, 12>::zeros();
            for &(xi, eta) in &GAUSS {
                let (bm, det) = super::quad4::b_membrane(&xy, xi, eta);
                let (bb, _) = b_bending(&xy, xi, eta);
                kmb += bm.transpose() * b * bb * det;
            }
            k.fixed_view_mut::<8, 12>(0, 8).copy_from(&kmb);
            k.fixed_view_mut::<12, 8>(8, 0).copy_from(&kmb.transpose());
        }
        Mitc4 { xy, z, section, k }
    }

    /// The element on four grids' coordinates (counter-clockwise): refused as the thin
    /// CQUAD4 refuses them.
    pub fn build(points: &[[f64; 3]], section: ShellSection) -> Result<Self, BadShape> {
        Ok(Mitc4::new(flat(points)?, points[0][2], section))
    }

    /// Transverse shear forces (Qx, Qy) = Ds γ at the element centre.
    pub fn shear_forces(&self, ue: &[f64]) -> Vector2<f64> {
        let (_, ub) = parts(ue);
        let ds = self.section.shear.unwrap_or_default();
        ds * (b_shear(&self.xy, 0.0, 0.0).0 * ub)
    }
}

/// The CQUAD4 card's kernel: MITC4 when the section has a transverse shear stiffness,
/// the thin DKQ otherwise.
pub fn cquad4(points: &[[f64; 3]], section: ShellSection) -> Result<Box<dyn super::BoxedKernel>, BadShape> {
    if section.shear.is_some() {
        Ok(Box::new(Mitc4::build(points, section)?))
    } else {
        Ok(Box::new(super::quad4::Quad4::build(points, section)?))
    }
}

fn dofs() -> Vec<(usize, usize)> {
    let membrane = (0..8).map(|k| (k / 2, k % 2));
    let plate = (0..12).map(|k| (k / 3, 2 + k % 3));
    membrane.chain(plate).collect()
}

fn local_vector(ue: &[f64]) -> SMatrix<f64, 20, 1> {
    let (um, ub) = parts(ue);
    SMatrix::<f64, 20, 1>::from_fn(|k, _| if k < 8 { um[k] } else { ub[k - 8] })
}

impl Kernel for Mitc4 {
    fn card(&self) -> &'static str {
        "CQUAD4"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Shell(&self.section)
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix {
            at: dofs(),
            values: DMatrix::from_fn(20, 20, |i, j| self.k[(i, j)]),
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        let m = lumped_mass(&self.xy, self.section.mass_per_area);
        vec![LocalMatrix::translational(&m)]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let u = local_vector(ue);
        0.5 * (u.transpose() * self.k * u)[0]
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        self.section.recovered(what)
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let (um, ub) = parts(ue);
        let kappa: Vector3<f64> = b_bending(&self.xy, 0.0, 0.0).0 * ub;
        let mut out = self.section.recover(membrane_strain(&self.xy, &um), kappa, what);
        if what != super::Output::Strain && self.section.shear.is_some() {
            out.extend(self.shear_forces(ue).iter());
        }
        out
    }
    fn material_law(&self, strains: &[f64]) -> Option<Vec<f64>> {
        Some(self.section.material_law(strains))
    }
    fn eq16_mass(&self) -> Option<f64> {
        Some(self.section.mass_per_area * area(&self.xy))
    }
    fn points(&self) -> Vec<[f64; 3]> {
        self.xy.iter().map(|p| [p[0], p[1], self.z]).collect()
    }
    fn cell(&self) -> Option<Cell> {
        Some(Cell::Quad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::Matrix3;

    /// A distorted quadrilateral (no two sides parallel).
    const DISTORTED: Xy = [[0.0, 0.0], [2.0, 0.3], [2.4, 1.7], [0.3, 1.2]];

    fn iso(e: f64, nu: f64, t: f64) -> (Matrix3<f64>, Matrix2<f64>) {
        let q = e / (1.0 - nu * nu) * Matrix3::new(1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu));
        let g = e / (2.0 * (1.0 + nu));
        (q * t.powi(3) / 12.0, Matrix2::identity() * (5.0 / 6.0) * g * t)
    }

    /// Nodal (w, θx, θy) of a plate field w(x, y) with rotations βx(x, y), βy(x, y).
    fn nodal(
        w: impl Fn(f64, f64) -> f64,
        bx: impl Fn(f64, f64) -> f64,
        by: impl Fn(f64, f64) -> f64,
    ) -> SMatrix<f64, 12, 1> {
        SMatrix::<f64, 12, 1>::from_fn(|k, _| {
            let [x, y] = DISTORTED[k / 3];
            match k % 3 {
                0 => w(x, y),
                1 => -by(x, y), // θx = −βy
                _ => bx(x, y),  // θy = βx
            }
        })
    }

    /// Goal: the constant-curvature patch test. Reference: rotations linear in x, y,
    /// βx = a x + c y, βy = c x + b y, with w chosen so that γ = 0
    /// (w = −½(a x² + 2c x y + b y²)), give κ = (a, b, 2c) and no shear strain anywhere
    /// on a distorted element. Tolerance: round-off.
    #[test]
    fn mitc4_reproduces_constant_curvature_without_shear_on_a_distorted_element() {
        let (a, b, c) = (2e-3, -1e-3, 7e-4);
        let u = nodal(
            |x, y| -0.5 * (a * x * x + 2.0 * c * x * y + b * y * y),
            |x, y| a * x + c * y,
            |x, y| c * x + b * y,
        );
        for (xi, eta) in [(0.0, 0.0), (G, -G), (0.9, -0.7), (-0.3, 0.8)] {
            let kappa = b_bending(&DISTORTED, xi, eta).0 * u;
            assert_relative_eq!(kappa, Vector3::new(a, b, 2.0 * c), epsilon = 1e-15);
            let gamma = b_shear(&DISTORTED, xi, eta).0 * u;
            assert!(gamma.norm() < 1e-15, "γ = {gamma}");
        }
    }

    /// Goal: the constant-shear patch test. Reference: w = p x + q y with zero
    /// rotations has γ = (p, q) everywhere and no curvature. Tolerance: round-off.
    #[test]
    fn mitc4_reproduces_constant_transverse_shear_on_a_distorted_element() {
        let (p, q) = (3e-3, -2e-3);
        let u = nodal(|x, y| p * x + q * y, |_, _| 0.0, |_, _| 0.0);
        for (xi, eta) in [(0.0, 0.0), (G, -G), (0.9, -0.7), (-0.3, 0.8)] {
            assert_relative_eq!(b_shear(&DISTORTED, xi, eta).0 * u, Vector2::new(p, q), epsilon = 1e-15);
            assert!((b_bending(&DISTORTED, xi, eta).0 * u).norm() < 1e-15);
        }
    }

    /// Goal: the recovered transverse shear forces are the section's Ds times the
    /// shear strain. Reference: the constant-shear field above, (Qx, Qy) = Ds (p, q),
    /// named shear_force_E_qx and _qy after the stresses and strains; none without
    /// a stress request. Tolerance: round-off.
    #[test]
    fn mitc4_recovers_the_transverse_shear_forces_of_a_constant_shear_field() {
        let (p, q) = (3e-3, -2e-3);
        let (d, ds) = iso(1.0e7, 0.3, 0.1);
        let ds = ds + Matrix2::new(0.0, 1.0e4, 1.0e4, 0.0);
        let section = ShellSection {
            thickness: 0.1,
            g_membrane: None,
            g_bending: Some(d * 12.0 / 0.1f64.powi(3)),
            g_coupling: None,
            shear: Some(ds),
            mass_per_area: 1.0,
        };
        let el = Mitc4::new(DISTORTED, 0.0, section);
        let w = nodal(|x, y| p * x + q * y, |_, _| 0.0, |_, _| 0.0);
        let mut ue = vec![0.0; 24];
        for k in 0..12 {
            ue[6 * (k / 3) + 2 + k % 3] = w[k];
        }
        let names = el.recovered(crate::elements::Output::Stress);
        let values = el.recover(&ue, crate::elements::Output::Stress);
        assert_eq!(names.len(), values.len());
        assert_eq!(names[names.len() - 2].name(7), "shear_force_7_qx");
        let want = ds * Vector2::new(p, q);
        assert_relative_eq!(values[values.len() - 2], want[0], max_relative = 1e-12);
        assert_relative_eq!(values[values.len() - 1], want[1], max_relative = 1e-12);
        assert_eq!(el.recovered(crate::elements::Output::Strain).len(), 6);
        let forces = el.recover(&ue, crate::elements::Output::Force);
        assert_eq!(forces[6..], values[values.len() - 2..]);
    }

    /// Goal: no spurious zero-energy mode. Reference: a free plate element has exactly
    /// three rigid motions (w = a + b x + c y with βx = −b, βy = −c); the 12×12 plate
    /// stiffness must have exactly three zero eigenvalues on a distorted element, for
    /// a thick and a thin plate. Tolerance: an eigenvalue below 1e-9 of the largest
    /// counts as zero.
    #[test]
    fn mitc4_has_exactly_three_zero_energy_modes() {
        for t in [0.5, 0.005] {
            let (d, ds) = iso(1.0e7, 0.3, t);
            let k = plate_stiffness(&DISTORTED, &d, &ds);
            let ev = k.symmetric_eigenvalues();
            let zero = ev.iter().filter(|&&e| e.abs() < 1e-9 * ev.amax()).count();
            assert_eq!(zero, 3, "t = {t}: eigenvalues {ev}");
            let rigid = nodal(|x, y| 0.3 + 0.2 * x - 0.1 * y, |_, _| -0.2, |_, _| 0.1);
            assert!((k * rigid).norm() < 1e-9 * k.norm());
        }
    }
}
