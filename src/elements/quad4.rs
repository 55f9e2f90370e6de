//! CQUAD4 flat shell: membrane plus thin-plate bending, no coupling (MID4 blank).
//!
//! - Membrane: bilinear isoparametric quadrilateral, DOFs (u, v) per corner, stiffness
//!   ∫ Bᵀ A B dA with A = G(MID1)·T, 2×2 Gauss quadrature. Passes the constant-strain
//!   patch test; displacement error O(h²).
//! - Bending: the discrete-Kirchhoff quadrilateral DKQ (Batoz & Tahar, IJNME 18, 1982),
//!   DOFs (w, θx, θy) per corner with θx = ∂w/∂y, θy = −∂w/∂x. The rotations of the
//!   normal βx = −∂w/∂x, βy = −∂w/∂y are quadratic (8-node serendipity) with the
//!   Kirchhoff constraints imposed at corners and mid-sides, so there is no transverse
//!   shear and no shear locking: right in the thin limit that NASTRAN's PSHELL with
//!   MID3 blank means. Curvatures κ = (βx,x, βy,y, βx,y + βy,x), stiffness
//!   ∫ Bᵀ D B dA with D = G(MID2)·(12I/T³)·T³/12, 2×2 Gauss. Passes the constant-curvature
//!   patch test; deflections converge O(h²).
//! - Anisotropic terms (G13, G23) are kept; material axes are the basic x and y.
//! - Mass: (ρT + NSM) lumped to the translations by row sums, m_i = (ρT + NSM)∫N_i dA;
//!   no rotary inertia (NASTRAN's default lumped mass).
//! - Recovery at the centre: fibre strain ε(z) = ε_m + z κ (z from the mid-plane).

use super::shell::{h_vectors, side_coefficients, ShellSection};
use super::{BadShape, Cell, Kernel, LocalMatrix, Recovered};
use nalgebra::{DMatrix, Matrix3, SMatrix, Vector3};
use std::sync::OnceLock;

/// Corner coordinates (x, y) of a quadrilateral, counter-clockwise.
pub type Xy = [[f64; 2]; 4];

/// 2×2 Gauss points and unit weights.
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

/// Jacobian [[x,ξ, y,ξ], [x,η, y,η]] and its determinant.
fn jacobian(xy: &Xy, xi: f64, eta: f64) -> ([[f64; 2]; 2], f64) {
    let (_, dxi, deta) = bilinear(xi, eta);
    let mut j = [[0.0; 2]; 2];
    for i in 0..4 {
        j[0][0] += dxi[i] * xy[i][0];
        j[0][1] += dxi[i] * xy[i][1];
        j[1][0] += deta[i] * xy[i][0];
        j[1][1] += deta[i] * xy[i][1];
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    (j, det)
}

/// (∂/∂x, ∂/∂y) from (∂/∂ξ, ∂/∂η).
fn to_xy(j: &[[f64; 2]; 2], det: f64, d_xi: f64, d_eta: f64) -> (f64, f64) {
    (
        (j[1][1] * d_xi - j[0][1] * d_eta) / det,
        (-j[1][0] * d_xi + j[0][0] * d_eta) / det,
    )
}

/// Smallest Jacobian determinant over the corners: non-positive means a degenerate or
/// wrongly ordered (clockwise, concave) element.
pub fn min_jacobian(xy: &Xy) -> f64 {
    CORNER
        .iter()
        .map(|&(a, b)| jacobian(xy, a, b).1)
        .fold(f64::INFINITY, f64::min)
}

/// Area by 2×2 Gauss quadrature of the Jacobian (exact for a bilinear map).
pub fn area(xy: &Xy) -> f64 {
    GAUSS.iter().map(|&(a, b)| jacobian(xy, a, b).1).sum()
}

/// Membrane strain-displacement matrix at (ξ, η), DOFs (u1 v1 … u4 v4).
pub(super) fn b_membrane(xy: &Xy, xi: f64, eta: f64) -> (SMatrix<f64, 3, 8>, f64) {
    let (_, dxi, deta) = bilinear(xi, eta);
    let (j, det) = jacobian(xy, xi, eta);
    let mut b = SMatrix::<f64, 3, 8>::zeros();
    for i in 0..4 {
        let (dx, dy) = to_xy(&j, det, dxi[i], deta[i]);
        b[(0, 2 * i)] = dx;
        b[(1, 2 * i + 1)] = dy;
        b[(2, 2 * i)] = dy;
        b[(2, 2 * i + 1)] = dx;
    }
    (b, det)
}

/// Membrane stiffness Bᵀ A B integrated 2×2, DOFs (u1 v1 … u4 v4); `a` = G·T.
pub fn membrane_stiffness(xy: &Xy, a: &Matrix3<f64>) -> SMatrix<f64, 8, 8> {
    let mut k = SMatrix::<f64, 8, 8>::zeros();
    for &(xi, eta) in &GAUSS {
        let (b, det) = b_membrane(xy, xi, eta);
        k += b.transpose() * a * b * det;
    }
    k
}

/// Membrane strain (εx, εy, γxy) at the element centre.
pub fn membrane_strain(xy: &Xy, u: &SMatrix<f64, 8, 1>) -> Vector3<f64> {
    b_membrane(xy, 0.0, 0.0).0 * u
}

/// The (ξ, η) derivatives of the 8-node serendipity functions (corners 1-4, mid-sides
/// 5-8 on sides 12, 23, 34, 41): the DKQ's rotations interpolate with them, and its
/// curvatures need only their derivatives.
fn serendipity_derivatives(xi: f64, eta: f64) -> ([f64; 8], [f64; 8]) {
    let mut dxi = [0.0; 8];
    let mut deta = [0.0; 8];
    for (i, &(a, b)) in CORNER.iter().enumerate() {
        dxi[i] = 0.25 * a * (1.0 + b * eta) * (2.0 * a * xi + b * eta);
        deta[i] = 0.25 * b * (1.0 + a * xi) * (a * xi + 2.0 * b * eta);
    }
    for (k, b) in [(4, -1.0), (6, 1.0)] {
        dxi[k] = -xi * (1.0 + b * eta);
        deta[k] = 0.5 * (1.0 - xi * xi) * b;
    }
    for (k, a) in [(5, 1.0), (7, -1.0)] {
        dxi[k] = 0.5 * a * (1.0 - eta * eta);
        deta[k] = -eta * (1.0 + a * xi);
    }
    (dxi, deta)
}

/// Curvature-displacement matrix of the DKQ at (ξ, η).
fn b_bending(xy: &Xy, xi: f64, eta: f64) -> (SMatrix<f64, 3, 12>, f64) {
    let sc = side_coefficients(xy);
    let (dxi, deta) = serendipity_derivatives(xi, eta);
    let (mut hx_xi, mut hy_xi, mut hx_eta, mut hy_eta) = ([0.0; 12], [0.0; 12], [0.0; 12], [0.0; 12]);
    h_vectors(&dxi, &sc, &mut hx_xi, &mut hy_xi);
    h_vectors(&deta, &sc, &mut hx_eta, &mut hy_eta);
    let (j, det) = jacobian(xy, xi, eta);
    let mut b = SMatrix::<f64, 3, 12>::zeros();
    for k in 0..12 {
        let (hx_x, hx_y) = to_xy(&j, det, hx_xi[k], hx_eta[k]);
        let (hy_x, hy_y) = to_xy(&j, det, hy_xi[k], hy_eta[k]);
        b[(0, k)] = hx_x;
        b[(1, k)] = hy_y;
        b[(2, k)] = hx_y + hy_x;
    }
    (b, det)
}

/// Bending stiffness Bᵀ D B integrated 2×2, DOFs (w, θx, θy) at each corner.
pub fn bending_stiffness(xy: &Xy, d: &Matrix3<f64>) -> SMatrix<f64, 12, 12> {
    let mut k = SMatrix::<f64, 12, 12>::zeros();
    for &(xi, eta) in &GAUSS {
        let (b, det) = b_bending(xy, xi, eta);
        k += b.transpose() * d * b * det;
    }
    k
}

/// Membrane-bending coupling Bmᵀ B Bb integrated 2×2 (`b` = the laminate's coupling
/// stiffness, N = A ε⁰ + B κ, M = B ε⁰ + D κ): rows the membrane DOFs (u1 v1 … u4 v4),
/// columns the bending DOFs (w, θx, θy at each corner). The element's stiffness is then
/// [Km Kmb; Kmbᵀ Kb], its energy ½ ε⁰ᵀAε⁰ + ε⁰ᵀBκ + ½ κᵀDκ over the area.
pub fn coupling_stiffness(xy: &Xy, b: &Matrix3<f64>) -> SMatrix<f64, 8, 12> {
    let mut k = SMatrix::<f64, 8, 12>::zeros();
    for &(xi, eta) in &GAUSS {
        let (bm, det) = b_membrane(xy, xi, eta);
        let (bb, _) = b_bending(xy, xi, eta);
        k += bm.transpose() * b * bb * det;
    }
    k
}

/// Curvatures (βx,x, βy,y, βx,y + βy,x) at the element centre.
pub fn curvature(xy: &Xy, w: &SMatrix<f64, 12, 1>) -> Vector3<f64> {
    b_bending(xy, 0.0, 0.0).0 * w
}

/// The consistent nodal forces ∫ Nᵢ p dA of a pressure p interpolated from the
/// corners' values `p` by the element's own shape functions, 2×2 Gauss points
/// (Nᵢ·p·det J is at most cubic in each of ξ, η, so exact). Corners counter-clockwise.
pub fn pressure_loads(xy: &Xy, p: &[f64; 4]) -> [f64; 4] {
    let mut f = [0.0; 4];
    for &(xi, eta) in &GAUSS {
        let (n, _, _) = bilinear(xi, eta);
        let det = jacobian(xy, xi, eta).1;
        let pressure: f64 = n.iter().zip(p).map(|(n, p)| n * p).sum();
        for i in 0..4 {
            f[i] += n[i] * pressure * det;
        }
    }
    f
}

/// Row-sum lumped nodal masses for a mass per unit area.
pub fn lumped_mass(xy: &Xy, mass_per_area: f64) -> [f64; 4] {
    let mut m = [0.0; 4];
    for &(xi, eta) in &GAUSS {
        let (n, _, _) = bilinear(xi, eta);
        let det = jacobian(xy, xi, eta).1;
        for i in 0..4 {
            m[i] += mass_per_area * n[i] * det;
        }
    }
    m
}

/// A CQUAD4 in the plane z = `z`. The upper triangles of its stiffness matrices are
/// kept (packed, row by row) for the strain energy the ledger books every step: half
/// the memory of the full matrices, which is what a step's pass over all elements
/// costs. They are computed when first needed: `impactlab check` builds every element
/// and needs none of them.
#[derive(Debug, Clone, PartialEq)]
pub struct Quad4 {
    /// Corner coordinates in the element's plane.
    pub xy: Xy,
    /// The plane's z.
    pub z: f64,
    /// Section and materials.
    pub section: ShellSection,
    kept: OnceLock<Box<Kept>>,
}

/// A [`Quad4`]'s stiffness as the ledger uses it.
#[derive(Debug, Clone, PartialEq)]
struct Kept {
    membrane: Option<[f64; 36]>,
    bending: Option<[f64; 78]>,
    coupling: Option<SMatrix<f64, 8, 12>>,
}

impl Quad4 {
    /// The element on four grids' coordinates (counter-clockwise): refused when they
    /// are not in a plane z = const, or the element is degenerate, concave or
    /// numbered clockwise.
    pub fn build(points: &[[f64; 3]], section: ShellSection) -> Result<Self, BadShape> {
        Ok(Quad4::new(flat(points)?, points[0][2], section))
    }

    /// The element (its stiffness matrices computed once, when first needed).
    pub fn new(xy: Xy, z: f64, section: ShellSection) -> Self {
        Quad4 {
            xy,
            z,
            section,
            kept: OnceLock::new(),
        }
    }

    fn kept(&self) -> &Kept {
        self.kept.get_or_init(|| {
            let (xy, section) = (&self.xy, &self.section);
            Box::new(Kept {
                membrane: section.a().map(|a| pack(&membrane_stiffness(xy, &a))),
                bending: section.d().map(|d| pack(&bending_stiffness(xy, &d))),
                coupling: section.b().map(|b| coupling_stiffness(xy, &b)),
            })
        })
    }
}

/// The upper triangle of an N×N matrix, row by row (P = N(N+1)/2 values).
fn pack<const N: usize, const P: usize>(k: &SMatrix<f64, N, N>) -> [f64; P] {
    let mut p = [0.0; P];
    let mut idx = 0;
    for i in 0..N {
        for j in i..N {
            p[idx] = k[(i, j)];
            idx += 1;
        }
    }
    p
}

/// uᵀKu of a symmetric K packed by [`pack`]; rows of zero displacement are skipped.
fn quad_form(p: &[f64], u: &[f64]) -> f64 {
    let n = u.len();
    let (mut s, mut idx) = (0.0, 0);
    for i in 0..n {
        let ui = u[i];
        if ui == 0.0 {
            idx += n - i;
            continue;
        }
        let mut row = 0.5 * p[idx] * ui;
        for j in i + 1..n {
            row += p[idx + j - i] * u[j];
        }
        s += 2.0 * ui * row;
        idx += n - i;
    }
    s
}

/// Local DOFs of the membrane (u, v of each corner) and of bending (w, θx, θy).
fn membrane_dofs() -> Vec<(usize, usize)> {
    (0..8).map(|k| (k / 2, k % 2)).collect()
}
fn bending_dofs() -> Vec<(usize, usize)> {
    (0..12).map(|k| (k / 3, 2 + k % 3)).collect()
}

fn local<const N: usize>(at: Vec<(usize, usize)>, k: &SMatrix<f64, N, N>) -> LocalMatrix {
    LocalMatrix {
        at,
        values: DMatrix::from_fn(N, N, |i, j| k[(i, j)]),
    }
}

/// A quadrilateral's corners in its plane: refused when the grids are not in a plane
/// z = const, or the element is degenerate, concave or numbered clockwise.
pub(super) fn flat(points: &[[f64; 3]]) -> Result<Xy, BadShape> {
    let xy = super::flat_xy::<4>(points)?;
    if min_jacobian(&xy) <= 0.0 {
        return Err(BadShape(
            "is degenerate, concave or numbered clockwise (non-positive Jacobian)",
        ));
    }
    Ok(xy)
}

/// The local displacements' membrane (u, v per corner) and plate (w, θx, θy per
/// corner) parts.
pub(super) fn parts(ue: &[f64]) -> (SMatrix<f64, 8, 1>, SMatrix<f64, 12, 1>) {
    let um = SMatrix::<f64, 8, 1>::from_fn(|k, _| ue[6 * (k / 2) + k % 2]);
    let ub = SMatrix::<f64, 12, 1>::from_fn(|k, _| ue[6 * (k / 3) + 2 + k % 3]);
    (um, ub)
}

impl Kernel for Quad4 {
    fn card(&self) -> &'static str {
        "CQUAD4"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Shell(&self.section)
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        // Full matrices as the kernels compute them (assembly runs once).
        let mut out = Vec::new();
        if let (Some(a), Some(d), Some(b)) = (self.section.a(), self.section.d(), self.section.b()) {
            let kmb = &coupling_stiffness(&self.xy, &b);
            // Coupled: one matrix over the membrane and bending DOFs.
            let (km, kb) = (membrane_stiffness(&self.xy, &a), bending_stiffness(&self.xy, &d));
            let mut k = SMatrix::<f64, 20, 20>::zeros();
            k.fixed_view_mut::<8, 8>(0, 0).copy_from(&km);
            k.fixed_view_mut::<12, 12>(8, 8).copy_from(&kb);
            k.fixed_view_mut::<8, 12>(0, 8).copy_from(kmb);
            k.fixed_view_mut::<12, 8>(8, 0).copy_from(&kmb.transpose());
            out.push(local([membrane_dofs(), bending_dofs()].concat(), &k));
            return out;
        }
        if let Some(a) = self.section.a() {
            out.push(local(membrane_dofs(), &membrane_stiffness(&self.xy, &a)));
        }
        if let Some(d) = self.section.d() {
            out.push(local(bending_dofs(), &bending_stiffness(&self.xy, &d)));
        }
        out
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        let m = lumped_mass(&self.xy, self.section.mass_per_area);
        vec![LocalMatrix::translational(&m)]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let (um, ub) = parts(ue);
        let kept = self.kept();
        let m = kept.membrane.as_ref().map_or(0.0, |k| quad_form(k, um.as_slice()));
        let b = kept.bending.as_ref().map_or(0.0, |k| quad_form(k, ub.as_slice()));
        match &kept.coupling {
            Some(k) => 0.5 * (m + b) + (um.transpose() * k * ub)[0],
            None => 0.5 * (m + b),
        }
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        self.section.recovered(what)
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let (um, ub) = parts(ue);
        self.section
            .recover(membrane_strain(&self.xy, &um), curvature(&self.xy, &ub), what)
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

    /// Goal: the packed quadratic form is uᵀKu of the full matrix (DKQ bending of a
    /// skewed quad, every entry of u nonzero, then with zeros). Tolerance 1e-13
    /// relative: round-off of a 78-term sum.
    #[test]
    fn packed_quadratic_form_is_utku() {
        let xy: Xy = [[0.0, 0.0], [2.0, 0.1], [2.2, 1.9], [-0.1, 2.0]];
        let d = Matrix3::new(3.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 0.7);
        let k = bending_stiffness(&xy, &d);
        let p: [f64; 78] = pack(&k);
        for zeros in [false, true] {
            let u = SMatrix::<f64, 12, 1>::from_fn(|i, _| {
                if zeros && i % 3 == 1 {
                    0.0
                } else {
                    (i as f64 * 0.37).sin()
                }
            });
            let full = (u.transpose() * k * u)[0];
            let packed = quad_form(&p, u.as_slice());
            assert!(((packed - full) / full).abs() < 1e-13, "{packed} vs {full}");
        }
    }
    use super::*;
    use approx::assert_relative_eq;

    /// A distorted quadrilateral (no two sides parallel).
    const DISTORTED: Xy = [[0.0, 0.0], [2.0, 0.3], [2.4, 1.7], [0.3, 1.2]];

    fn iso(e: f64, nu: f64, t: f64) -> (Matrix3<f64>, Matrix3<f64>) {
        let q = e / (1.0 - nu * nu) * Matrix3::new(1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu));
        (q * t, q * t.powi(3) / 12.0)
    }

    /// Goal: membrane patch test on one distorted element. Reference: u = a x + b y,
    /// v = c x + d y gives constant strain (a, d, b + c) and zero stiffness work for
    /// rigid motion. Tolerance: round-off.
    #[test]
    fn membrane_reproduces_constant_strain_on_a_distorted_element() {
        let (a_mat, _) = iso(1.0e7, 0.3, 0.1);
        let (a, b, c, d) = (1e-3, -2e-4, 5e-4, 3e-4);
        let u = SMatrix::<f64, 8, 1>::from_fn(|k, _| {
            let p = DISTORTED[k / 2];
            if k % 2 == 0 {
                a * p[0] + b * p[1]
            } else {
                c * p[0] + d * p[1]
            }
        });
        for &(xi, eta) in &GAUSS {
            let e = b_membrane(&DISTORTED, xi, eta).0 * u;
            assert_relative_eq!(e, Vector3::new(a, d, b + c), epsilon = 1e-15);
        }
        let k = membrane_stiffness(&DISTORTED, &a_mat);
        let rigid = SMatrix::<f64, 8, 1>::from_fn(|k, _| {
            let p = DISTORTED[k / 2];
            if k % 2 == 0 {
                1.0 - 0.2 * p[1]
            } else {
                0.5 + 0.2 * p[0]
            }
        });
        assert!((k * rigid).norm() < 1e-9 * k.norm());
    }

    /// Goal: DKQ bending patch test. Reference: w = ½(p x² + 2 r x y + q y²) has constant
    /// curvature, and the DKQ (with nodal θx = w,y, θy = −w,x) must give
    /// κ = (βx,x, βy,y, 2βx,y) = −(p, q, 2r) everywhere. Tolerance: round-off.
    #[test]
    fn dkq_reproduces_constant_curvature_on_a_distorted_element() {
        let (p, q, r) = (2e-3, -1e-3, 7e-4);
        let w = SMatrix::<f64, 12, 1>::from_fn(|k, _| {
            let [x, y] = DISTORTED[k / 3];
            match k % 3 {
                0 => 0.5 * (p * x * x + 2.0 * r * x * y + q * y * y),
                1 => r * x + q * y,    // θx = w,y
                _ => -(p * x + r * y), // θy = −w,x
            }
        });
        for &(xi, eta) in GAUSS.iter().chain([(0.0, 0.0), (0.9, -0.7)].iter()) {
            let kappa = b_bending(&DISTORTED, xi, eta).0 * w;
            assert_relative_eq!(kappa, Vector3::new(-p, -q, -2.0 * r), epsilon = 1e-15);
        }
    }

    /// Goal: rigid motions of the plate cost no bending energy. Reference: w = a + b x + c y
    /// with θx = c, θy = −b. Tolerance: round-off.
    #[test]
    fn dkq_has_three_rigid_body_modes() {
        let (_, d) = iso(1.0e7, 0.3, 0.1);
        let k = bending_stiffness(&DISTORTED, &d);
        let w = SMatrix::<f64, 12, 1>::from_fn(|k, _| {
            let [x, y] = DISTORTED[k / 3];
            [0.3 + 0.2 * x - 0.1 * y, -0.1, -0.2][k % 3]
        });
        assert!((k * w).norm() < 1e-10 * k.norm());
        // …and exactly three: the 12×12 stiffness has rank 9.
        let ev = k.symmetric_eigenvalues();
        let tiny = ev.iter().filter(|&&e| e.abs() < 1e-9 * ev.amax()).count();
        assert_eq!(tiny, 3, "eigenvalues {ev}");
    }

    /// Goal: membrane-bending coupling patch test. Reference: classical lamination
    /// theory, the energy density ½ε⁰ᵀAε⁰ + ε⁰ᵀBκ + ½κᵀDκ of a constant membrane strain
    /// ε⁰ and curvature κ, times the area: the coupled element's strain energy is that
    /// for the fields of the two patch tests above together (the coupling term alone
    /// is area·ε⁰ᵀBκ), with an unsymmetric [0/90]'s B. Tolerance: round-off.
    #[test]
    fn coupled_element_books_the_laminates_energy_for_constant_strain_and_curvature() {
        let (a_mat, d_mat) = iso(1.0e7, 0.3, 0.1);
        let b_mat = Matrix3::new(-2.1e3, 0.0, 0.0, 0.0, 2.1e3, 0.0, 0.0, 0.0, 0.0);
        let section = ShellSection {
            thickness: 0.1,
            g_membrane: Some(a_mat / 0.1),
            g_bending: Some(d_mat * 12.0 / 0.1f64.powi(3)),
            g_coupling: Some(b_mat / 0.01),
            shear: None,
            mass_per_area: 1.0,
        };
        let el = Quad4::new(DISTORTED, 0.0, section);
        let (a, b, c, d) = (1e-3, -2e-4, 5e-4, 3e-4);
        let (p, q, r) = (2e-3, -1e-3, 7e-4);
        let mut ue = vec![0.0; 24];
        for (g, &[x, y]) in DISTORTED.iter().enumerate() {
            ue[6 * g] = a * x + b * y;
            ue[6 * g + 1] = c * x + d * y;
            ue[6 * g + 2] = 0.5 * (p * x * x + 2.0 * r * x * y + q * y * y);
            ue[6 * g + 3] = r * x + q * y;
            ue[6 * g + 4] = -(p * x + r * y);
        }
        let (e0, kappa) = (Vector3::new(a, d, b + c), Vector3::new(-p, -q, -2.0 * r));
        let density = 0.5 * (e0.transpose() * a_mat * e0)[0]
            + (e0.transpose() * b_mat * kappa)[0]
            + 0.5 * (kappa.transpose() * d_mat * kappa)[0];
        let area = area(&DISTORTED);
        assert_relative_eq!(el.strain_energy(&ue), density * area, max_relative = 1e-12);
        let (um, ub) = parts(&ue);
        let coupling = (um.transpose() * coupling_stiffness(&DISTORTED, &b_mat) * ub)[0];
        assert_relative_eq!(
            coupling,
            (e0.transpose() * b_mat * kappa)[0] * area,
            max_relative = 1e-12
        );
        // The assembled matrix is the one coupled block, symmetric to round-off.
        let k = el.stiffness();
        assert_eq!(k.len(), 1);
        let kv = &k[0].values;
        assert!((kv - kv.transpose()).norm() <= 1e-14 * kv.norm());
    }

    #[test]
    fn lumped_mass_adds_up_to_the_element_mass() {
        let m = lumped_mass(&DISTORTED, 3.0);
        assert_relative_eq!(m.iter().sum::<f64>(), 3.0 * area(&DISTORTED), max_relative = 1e-14);
        assert!(min_jacobian(&DISTORTED) > 0.0);
    }
}
