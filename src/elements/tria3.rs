//! CTRIA3 flat shell: the triangle twin of CQUAD4 (membrane plus thin-plate bending,
//! coupled when the section is unsymmetric).
//!
//! - Membrane: the constant-strain triangle, DOFs (u, v) per corner, stiffness
//!   Bᵀ A B · area with A = G(MID1)·T (exact: B is constant). Passes the
//!   constant-strain patch test; displacement error O(h²), strain error O(h).
//! - Bending: the discrete-Kirchhoff triangle DKT (Batoz, Bathe & Ho, IJNME 15, 1980),
//!   DOFs (w, θx, θy) per corner with θx = ∂w/∂y, θy = −∂w/∂x; the rotations of the
//!   normal are quadratic (6-node triangle) with the Kirchhoff constraints of
//!   [`super::shell`], so no transverse shear and no shear locking. Curvatures are
//!   linear over the element; stiffness ∫ Bᵀ D B dA with D = G(MID2)·(12I/T³)·T³/12
//!   by the 3-point interior Gauss rule (exact for the quadratic integrand). Passes
//!   the constant-curvature patch test; deflections converge O(h²).
//! - Coupling (unsymmetric sections): ∫ Bmᵀ B Bb dA by the same rule (exact).
//! - Mass: (ρT + NSM)·area/3 lumped to each corner's translations (the row sums of
//!   the linear shape functions); no rotary inertia, as CQUAD4.
//! - Recovery at the centroid, as CQUAD4 (fibre strains ε⁰ ∓ κT/2).

use super::shell::{h_vectors, side_coefficients, ShellSection};
use super::{BadShape, Cell, Kernel, LocalMatrix, Recovered};
use nalgebra::{DMatrix, SMatrix, Vector3};

/// Corner coordinates (x, y) of a triangle, counter-clockwise.
pub type Xy = [[f64; 2]; 3];

/// The 3-point interior Gauss rule on the reference triangle (ξ, η ≥ 0, ξ + η ≤ 1):
/// points and weights (summing to the reference area ½); exact for quadratics.
pub(super) const GAUSS: [(f64, f64, f64); 3] = [
    (1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0),
    (2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0),
    (1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0),
];

/// Jacobian [[x,ξ, y,ξ], [x,η, y,η]] (constant) and its determinant, twice the signed
/// area: positive for corners numbered counter-clockwise.
pub fn jacobian(xy: &Xy) -> ([[f64; 2]; 2], f64) {
    let j = [
        [xy[1][0] - xy[0][0], xy[1][1] - xy[0][1]],
        [xy[2][0] - xy[0][0], xy[2][1] - xy[0][1]],
    ];
    (j, j[0][0] * j[1][1] - j[0][1] * j[1][0])
}

/// (∂/∂x, ∂/∂y) from (∂/∂ξ, ∂/∂η).
pub(super) fn to_xy(j: &[[f64; 2]; 2], det: f64, d_xi: f64, d_eta: f64) -> (f64, f64) {
    (
        (j[1][1] * d_xi - j[0][1] * d_eta) / det,
        (-j[1][0] * d_xi + j[0][0] * d_eta) / det,
    )
}

/// Area.
pub fn area(xy: &Xy) -> f64 {
    0.5 * jacobian(xy).1
}

/// The consistent nodal forces ∫ Nᵢ p dA of a pressure p linear between the corners'
/// values `p`: A/12·(pᵢ + Σⱼ pⱼ), exact. Corners counter-clockwise.
pub fn pressure_loads(xy: &Xy, p: &[f64; 3]) -> [f64; 3] {
    let (a, sum) = (area(xy), p.iter().sum::<f64>());
    p.map(|pi| a / 12.0 * (pi + sum))
}

/// Membrane strain-displacement matrix (constant), DOFs (u1 v1 u2 v2 u3 v3).
pub(super) fn b_membrane(xy: &Xy) -> SMatrix<f64, 3, 6> {
    let (j, det) = jacobian(xy);
    let mut b = SMatrix::<f64, 3, 6>::zeros();
    for (i, (d_xi, d_eta)) in [(-1.0, -1.0), (1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
        let (dx, dy) = to_xy(&j, det, d_xi, d_eta);
        b[(0, 2 * i)] = dx;
        b[(1, 2 * i + 1)] = dy;
        b[(2, 2 * i)] = dy;
        b[(2, 2 * i + 1)] = dx;
    }
    b
}

/// The (ξ, η) derivatives of the 6-node quadratic triangle's shape functions (corners
/// 1-3, then the mid-sides of sides 12, 23, 31), with L1 = 1 − ξ − η, L2 = ξ, L3 = η.
fn quadratic_derivatives(xi: f64, eta: f64) -> ([f64; 6], [f64; 6]) {
    let (l1, l2, l3) = (1.0 - xi - eta, xi, eta);
    (
        [
            1.0 - 4.0 * l1,
            4.0 * l2 - 1.0,
            0.0,
            4.0 * (l1 - l2),
            4.0 * l3,
            -4.0 * l3,
        ],
        [
            1.0 - 4.0 * l1,
            0.0,
            4.0 * l3 - 1.0,
            -4.0 * l2,
            4.0 * l2,
            4.0 * (l1 - l3),
        ],
    )
}

/// Curvature-displacement matrix of the DKT at (ξ, η), DOFs (w, θx, θy) per corner.
fn b_bending(xy: &Xy, xi: f64, eta: f64) -> SMatrix<f64, 3, 9> {
    let sc = side_coefficients(xy);
    let (dxi, deta) = quadratic_derivatives(xi, eta);
    let (mut hx_xi, mut hy_xi, mut hx_eta, mut hy_eta) = ([0.0; 9], [0.0; 9], [0.0; 9], [0.0; 9]);
    h_vectors(&dxi, &sc, &mut hx_xi, &mut hy_xi);
    h_vectors(&deta, &sc, &mut hx_eta, &mut hy_eta);
    let (j, det) = jacobian(xy);
    let mut b = SMatrix::<f64, 3, 9>::zeros();
    for k in 0..9 {
        let (hx_x, hx_y) = to_xy(&j, det, hx_xi[k], hx_eta[k]);
        let (hy_x, hy_y) = to_xy(&j, det, hy_xi[k], hy_eta[k]);
        b[(0, k)] = hx_x;
        b[(1, k)] = hy_y;
        b[(2, k)] = hx_y + hy_x;
    }
    b
}

/// A CTRIA3 in the plane z = `z`, its stiffness matrices computed once.
#[derive(Debug, Clone, PartialEq)]
pub struct Tria3 {
    /// Corner coordinates in the element's plane.
    pub xy: Xy,
    /// The plane's z.
    pub z: f64,
    /// Section and materials.
    pub section: ShellSection,
    k_membrane: Option<SMatrix<f64, 6, 6>>,
    k_bending: Option<SMatrix<f64, 9, 9>>,
    k_coupling: Option<SMatrix<f64, 6, 9>>,
}

impl Tria3 {
    /// The element on corners `xy` (counter-clockwise) in the plane z = `z`.
    pub fn new(xy: Xy, z: f64, section: ShellSection) -> Self {
        let bm = b_membrane(&xy);
        let det = jacobian(&xy).1;
        let (d, b) = (section.d(), section.b());
        let mut kb = SMatrix::<f64, 9, 9>::zeros();
        let mut kmb = SMatrix::<f64, 6, 9>::zeros();
        for &(xi, eta, w) in &GAUSS {
            let bb = b_bending(&xy, xi, eta);
            if let Some(d) = d {
                kb += bb.transpose() * d * bb * (w * det);
            }
            if let Some(b) = b {
                kmb += bm.transpose() * b * bb * (w * det);
            }
        }
        Tria3 {
            k_membrane: section.a().map(|a| bm.transpose() * a * bm * (0.5 * det)),
            k_bending: d.map(|_| kb),
            k_coupling: b.map(|_| kmb),
            xy,
            z,
            section,
        }
    }

    /// The element on three grids' coordinates: refused when they are not in a plane
    /// z = const or not counter-clockwise (non-positive area). A section with
    /// transverse shear flexibility is the DKMT's ([`super::dkmt::ctria3`]).
    pub fn build(points: &[[f64; 3]], section: ShellSection) -> Result<Self, BadShape> {
        Ok(Tria3::new(flat(points)?, points[0][2], section))
    }

    /// Membrane strain (εx, εy, γxy).
    fn membrane_strain(&self, um: &SMatrix<f64, 6, 1>) -> Vector3<f64> {
        b_membrane(&self.xy) * um
    }

    /// Curvatures (βx,x, βy,y, βx,y + βy,x) at the centroid.
    fn curvature(&self, ub: &SMatrix<f64, 9, 1>) -> Vector3<f64> {
        b_bending(&self.xy, 1.0 / 3.0, 1.0 / 3.0) * ub
    }
}

/// Local DOFs of the membrane (u, v of each corner) and of bending (w, θx, θy).
fn membrane_dofs() -> Vec<(usize, usize)> {
    (0..6).map(|k| (k / 2, k % 2)).collect()
}
fn bending_dofs() -> Vec<(usize, usize)> {
    (0..9).map(|k| (k / 3, 2 + k % 3)).collect()
}

/// A triangle's corners in its plane: refused when the grids are not in a plane
/// z = const or not counter-clockwise (non-positive area).
pub(super) fn flat(points: &[[f64; 3]]) -> Result<Xy, BadShape> {
    let xy = super::flat_xy::<3>(points)?;
    if jacobian(&xy).1 <= 0.0 {
        return Err(BadShape("is degenerate or numbered clockwise (non-positive area)"));
    }
    Ok(xy)
}

/// The local displacements' membrane (u, v per corner) and plate (w, θx, θy per
/// corner) parts.
pub(super) fn parts(ue: &[f64]) -> (SMatrix<f64, 6, 1>, SMatrix<f64, 9, 1>) {
    let um = SMatrix::<f64, 6, 1>::from_fn(|k, _| ue[6 * (k / 2) + k % 2]);
    let ub = SMatrix::<f64, 9, 1>::from_fn(|k, _| ue[6 * (k / 3) + 2 + k % 3]);
    (um, ub)
}

fn local<const R: usize, const C: usize>(at: Vec<(usize, usize)>, k: &SMatrix<f64, R, C>) -> LocalMatrix {
    LocalMatrix {
        at,
        values: DMatrix::from_fn(R, C, |i, j| k[(i, j)]),
    }
}

impl Kernel for Tria3 {
    fn card(&self) -> &'static str {
        "CTRIA3"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Shell(&self.section)
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        let mut out = Vec::new();
        if let (Some(km), Some(kb), Some(kmb)) = (&self.k_membrane, &self.k_bending, &self.k_coupling) {
            // Coupled: one matrix over the membrane and bending DOFs.
            let mut k = SMatrix::<f64, 15, 15>::zeros();
            k.fixed_view_mut::<6, 6>(0, 0).copy_from(km);
            k.fixed_view_mut::<9, 9>(6, 6).copy_from(kb);
            k.fixed_view_mut::<6, 9>(0, 6).copy_from(kmb);
            k.fixed_view_mut::<9, 6>(6, 0).copy_from(&kmb.transpose());
            out.push(local([membrane_dofs(), bending_dofs()].concat(), &k));
            return out;
        }
        if let Some(km) = &self.k_membrane {
            out.push(local(membrane_dofs(), km));
        }
        if let Some(kb) = &self.k_bending {
            out.push(local(bending_dofs(), kb));
        }
        out
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        let m = self.section.mass_per_area * area(&self.xy) / 3.0;
        vec![LocalMatrix::translational(&[m; 3])]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let (um, ub) = parts(ue);
        let m = self.k_membrane.map_or(0.0, |k| (um.transpose() * k * um)[0]);
        let b = self.k_bending.map_or(0.0, |k| (ub.transpose() * k * ub)[0]);
        let c = self.k_coupling.map_or(0.0, |k| (um.transpose() * k * ub)[0]);
        0.5 * (m + b) + c
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        self.section.recovered(what)
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let (um, ub) = parts(ue);
        self.section
            .recover(self.membrane_strain(&um), self.curvature(&ub), what)
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
        Some(Cell::Triangle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::Matrix3;

    /// A triangle with no two sides equal and no right angle.
    const SCALENE: Xy = [[0.1, -0.2], [2.3, 0.4], [0.7, 1.9]];

    fn iso(e: f64, nu: f64, t: f64) -> (Matrix3<f64>, Matrix3<f64>) {
        let q = e / (1.0 - nu * nu) * Matrix3::new(1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu));
        (q * t, q * t.powi(3) / 12.0)
    }

    fn section(a: Matrix3<f64>, d: Matrix3<f64>, b: Option<Matrix3<f64>>, t: f64) -> ShellSection {
        ShellSection {
            thickness: t,
            g_membrane: Some(a / t),
            g_bending: Some(d * 12.0 / t.powi(3)),
            g_coupling: b.map(|b| b / (t * t)),
            shear: None,
            mass_per_area: 1.0,
        }
    }

    /// Goal: the DKT bending patch test (Batoz, Bathe & Ho's constant-curvature test)
    /// on a scalene triangle. Reference: w = ½(p x² + 2 r x y + q y²) with nodal
    /// θx = w,y, θy = −w,x has constant curvature κ = (βx,x, βy,y, βx,y + βy,x) =
    /// −(p, q, 2r), which the DKT must give everywhere, not only at its Gauss points.
    /// Tolerance: round-off.
    #[test]
    fn dkt_reproduces_constant_curvature_on_a_scalene_triangle() {
        let (p, q, r) = (2e-3, -1e-3, 7e-4);
        let w = SMatrix::<f64, 9, 1>::from_fn(|k, _| {
            let [x, y] = SCALENE[k / 3];
            match k % 3 {
                0 => 0.5 * (p * x * x + 2.0 * r * x * y + q * y * y),
                1 => r * x + q * y,
                _ => -(p * x + r * y),
            }
        });
        for (xi, eta) in [(1.0 / 6.0, 1.0 / 6.0), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.2, 0.7)] {
            let kappa = b_bending(&SCALENE, xi, eta) * w;
            assert_relative_eq!(kappa, Vector3::new(-p, -q, -2.0 * r), epsilon = 1e-15);
        }
    }

    /// Goal: the membrane patch test and the rigid modes. Reference: u = a x + b y,
    /// v = c x + d y gives the strain (a, d, b + c); the 9×9 DKT stiffness has exactly
    /// three zero eigenvalues (w = a + b x + c y), the 6×6 membrane exactly three (two
    /// translations and the in-plane rotation). Tolerance: round-off.
    #[test]
    fn cst_and_dkt_have_constant_strain_and_exactly_three_rigid_modes_each() {
        let (a_mat, d_mat) = iso(1.0e7, 0.3, 0.1);
        let el = Tria3::new(SCALENE, 0.0, section(a_mat, d_mat, None, 0.1));
        let (a, b, c, d) = (1e-3, -2e-4, 5e-4, 3e-4);
        let um = SMatrix::<f64, 6, 1>::from_fn(|k, _| {
            let p = SCALENE[k / 2];
            if k % 2 == 0 {
                a * p[0] + b * p[1]
            } else {
                c * p[0] + d * p[1]
            }
        });
        assert_relative_eq!(el.membrane_strain(&um), Vector3::new(a, d, b + c), epsilon = 1e-15);
        let zero_modes = |ev: &nalgebra::DVector<f64>| ev.iter().filter(|&&e| e.abs() < 1e-9 * ev.amax()).count();
        let km = el.k_membrane.unwrap();
        let kb = el.k_bending.unwrap();
        let (em, eb) = (
            DMatrix::from_fn(6, 6, |i, j| km[(i, j)]).symmetric_eigenvalues(),
            DMatrix::from_fn(9, 9, |i, j| kb[(i, j)]).symmetric_eigenvalues(),
        );
        assert_eq!((zero_modes(&em), zero_modes(&eb)), (3, 3), "{em} {eb}");
        let rigid = SMatrix::<f64, 9, 1>::from_fn(|k, _| {
            let [x, y] = SCALENE[k / 3];
            [0.3 + 0.2 * x - 0.1 * y, -0.1, -0.2][k % 3]
        });
        assert!((kb * rigid).norm() < 1e-10 * kb.norm());
    }

    /// Goal: the coupled triangle books the laminate's energy. Reference: classical
    /// lamination theory, (½ε⁰ᵀAε⁰ + ε⁰ᵀBκ + ½κᵀDκ)·area for the constant strain and
    /// curvature of the two patch tests together, with an unsymmetric [0/90]'s B.
    /// Tolerance: round-off.
    #[test]
    fn coupled_triangle_books_the_laminates_energy_for_constant_strain_and_curvature() {
        let (a_mat, d_mat) = iso(1.0e7, 0.3, 0.1);
        let b_mat = Matrix3::new(-2.1e3, 0.0, 0.0, 0.0, 2.1e3, 0.0, 0.0, 0.0, 0.0);
        let el = Tria3::new(SCALENE, 0.0, section(a_mat, d_mat, Some(b_mat), 0.1));
        let (a, b, c, d) = (1e-3, -2e-4, 5e-4, 3e-4);
        let (p, q, r) = (2e-3, -1e-3, 7e-4);
        let mut ue = vec![0.0; 18];
        for (g, &[x, y]) in SCALENE.iter().enumerate() {
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
        assert_relative_eq!(el.strain_energy(&ue), density * area(&SCALENE), max_relative = 1e-12);
        let k = el.stiffness();
        assert_eq!(k.len(), 1);
        assert!((&k[0].values - k[0].values.transpose()).norm() <= 1e-14 * k[0].values.norm());
    }

    /// Goal: a triangle numbered clockwise, or off the plane z = const, is refused.
    #[test]
    fn clockwise_or_warped_triangles_are_refused() {
        let (a_mat, d_mat) = iso(1.0e7, 0.3, 0.1);
        let s = section(a_mat, d_mat, None, 0.1);
        let ccw = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(Tria3::build(&ccw, s.clone()).is_ok());
        let cw = [ccw[0], ccw[2], ccw[1]];
        assert!(Tria3::build(&cw, s.clone()).is_err());
        let warped = [ccw[0], ccw[1], [0.0, 1.0, 0.1]];
        assert!(Tria3::build(&warped, s).is_err());
    }
}
