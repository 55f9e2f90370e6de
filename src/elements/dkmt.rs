//! CTRIA3 with transverse shear flexibility: the discrete Kirchhoff-Mindlin triangle
//! DKMT (Katili, "A new discrete Kirchhoff-Mindlin element based on Mindlin-Reissner
//! plate theory and assumed shear strain fields", IJNME 36, 1993), the shear-deformable
//! twin of the thin triangle's DKT, with its membrane (CST) and coupling.
//!
//! - Kinematics (Reissner-Mindlin): DOFs (w, θx, θy) per corner, the rotations of the
//!   normal βx = θy, βy = −θx, shear strain γ = ∇w + β, curvature
//!   κ = (βx,x, βy,y, βx,y + βy,x), as the MITC4 plate.
//! - Rotations: linear between the corners plus, on each side k (corner i → j, unit
//!   tangent sₖ, length Lₖ), a quadratic bubble 4LᵢLⱼ·Δₖ·sₖ along the side: the DKT's
//!   space (normal rotation linear, tangential rotation quadratic along each side).
//!   Curvatures are linear over the element.
//! - Shear: each side's tangential shear strain γₛₖ is its exact mean,
//!   cₖ + ⅔Δₖ with cₖ = (wⱼ − wᵢ)/Lₖ + sₖ·(βᵢ + βⱼ)/2, and the side's Timoshenko-beam
//!   equilibrium links it to the bubble: Qₛ = Dₛ βₛ'' = −8DₛΔₖ/Lₖ², γₛₖ = Qₛ/Sₛ, so
//!   Δₖ = −(3/2) cₖ/(1 + φₖ), γₛₖ = cₖ φₖ/(1 + φₖ), φₖ = 12Dₛ/(SₛLₖ²), with Dₛ = mᵀDm
//!   (m = (sx², sy², 2sx·sy)) the section's bending stiffness along the side and
//!   Sₛ = sᵀ Ds s its shear stiffness (Katili's isotropic φ, written for any D and
//!   Ds). Δₖ depends on the side alone, so neighbours of one section agree on it (the
//!   rotations are continuous). (Batoz & Katili's DST, which takes the shear force
//!   from the element's own moment gradient instead, was measured and set aside: its
//!   bubbles differ between neighbours, and on an orthotropic plate, D11 ≠ D22, its
//!   Navier frequency stalls 0.4 % below Mindlin's at t/a = 1/5 as the mesh refines.)
//!   The shear field over the element is the linear field with
//!   constant tangential component γₛₖ on each side (the MITC3 assumed strain,
//!   γ = (γ̄x − c(y − yc), γ̄y + c(x − xc))).
//! - Limits: as t/L → 0, φ → 0 and the element is the DKT with the shear energy
//!   vanishing like (t/L)² (tested: no locking); as L/t → 0, Δ → 0 and it is the
//!   linear triangle with the MITC3 shear field.
//! - Stiffness: ∫ (Bbᵀ D Bb + Bsᵀ Ds Bs) dA by the 3-point interior Gauss rule
//!   (exact: both integrands are quadratic). Exactly the three rigid modes (tested);
//!   passes the constant-curvature patch test; Navier frequencies of isotropic and
//!   orthotropic Mindlin plates converge at order 2 or faster (tests/plate_element.rs).
//! - Coupling (unsymmetric sections): ∫ Bmᵀ B Bb dA by the same rule.
//! - Mass: as the thin CTRIA3, (ρT + NSM)·area/3 lumped to each corner's
//!   translations, no rotary inertia (NASTRAN's lumped mass): the implicit schemes run
//!   it, the explicit one refuses it.
//! - Recovery at the centroid, as the thin CTRIA3 (fibre strains ε⁰ ∓ κT/2); with the
//!   stresses also (Qx, Qy) = Ds γ at the centroid.

use super::shell::ShellSection;
use super::tria3::{area, b_membrane, flat, jacobian, parts, to_xy, Xy, GAUSS};
use super::{BadShape, Cell, Kernel, LocalMatrix, Recovered};
use nalgebra::{DMatrix, Matrix2, Matrix3, SMatrix, Vector2, Vector3};

/// The corners (i, j) of sides 1→2, 2→3, 3→1.
const SIDES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// The geometry of a triangle the DKMT needs, computed once.
struct Geometry {
    /// (∂Lᵢ/∂x, ∂Lᵢ/∂y) of the area coordinates.
    grad: [[f64; 2]; 3],
    /// Unit tangent and length of each side.
    sides: [([f64; 2], f64); 3],
}

impl Geometry {
    fn of(xy: &Xy) -> Self {
        let (j, det) = jacobian(xy);
        let grad = [(-1.0, -1.0), (1.0, 0.0), (0.0, 1.0)].map(|(a, b)| {
            let (x, y) = to_xy(&j, det, a, b);
            [x, y]
        });
        let sides = SIDES.map(|(i, k)| {
            let (dx, dy) = (xy[k][0] - xy[i][0], xy[k][1] - xy[i][1]);
            let l = dx.hypot(dy);
            ([dx / l, dy / l], l)
        });
        Geometry { grad, sides }
    }

    /// Curvature of the corner DOFs' linear rotations (constant), DOFs (w, θx, θy) per
    /// corner.
    fn b_corners(&self) -> SMatrix<f64, 3, 9> {
        let mut b = SMatrix::<f64, 3, 9>::zeros();
        for (i, [nx, ny]) in self.grad.iter().enumerate() {
            // βx = Σ Lᵢ θyᵢ, βy = −Σ Lᵢ θxᵢ.
            b[(0, 3 * i + 2)] = *nx;
            b[(1, 3 * i + 1)] = -ny;
            b[(2, 3 * i + 2)] = *ny;
            b[(2, 3 * i + 1)] = -nx;
        }
        b
    }

    /// Curvature of the side bubbles at area coordinates `l`, per Δₖ.
    fn b_bubbles(&self, l: [f64; 3]) -> Matrix3<f64> {
        let mut b = Matrix3::zeros();
        for (k, &(i, j)) in SIDES.iter().enumerate() {
            let ([sx, sy], _) = self.sides[k];
            // ∇(4 Lᵢ Lⱼ).
            let px = 4.0 * (l[j] * self.grad[i][0] + l[i] * self.grad[j][0]);
            let py = 4.0 * (l[j] * self.grad[i][1] + l[i] * self.grad[j][1]);
            b[(0, k)] = sx * px;
            b[(1, k)] = sy * py;
            b[(2, k)] = sx * py + sy * px;
        }
        b
    }

    /// Each side's mean tangential shear strain of the corner DOFs alone,
    /// (wⱼ − wᵢ)/Lₖ + sₖ·(βᵢ + βⱼ)/2.
    fn c_sides(&self) -> SMatrix<f64, 3, 9> {
        let mut c = SMatrix::<f64, 3, 9>::zeros();
        for (k, &(i, j)) in SIDES.iter().enumerate() {
            let ([sx, sy], l) = self.sides[k];
            c[(k, 3 * i)] -= 1.0 / l;
            c[(k, 3 * j)] += 1.0 / l;
            for g in [i, j] {
                // sₖ·β = sx θy − sy θx.
                c[(k, 3 * g + 1)] -= 0.5 * sy;
                c[(k, 3 * g + 2)] += 0.5 * sx;
            }
        }
        c
    }
}

/// The plate matrices over the corner DOFs (w, θx, θy): the bubble amplitudes
/// Δ = A u and the linked shear field's parameters p = P u.
struct Plate {
    geometry: Geometry,
    /// Δ per corner DOF.
    a: SMatrix<f64, 3, 9>,
    /// The shear field's (γ̄x, γ̄y, c) per corner DOF: γ = (γ̄x − c (y − yc), γ̄y + c (x − xc))
    /// about the centroid (xc, yc).
    p: SMatrix<f64, 3, 9>,
    /// The centroid.
    centre: [f64; 2],
}

impl Plate {
    fn new(xy: &Xy, d: &Matrix3<f64>, ds: &Matrix2<f64>) -> Result<Self, BadShape> {
        let geometry = Geometry::of(xy);
        let centre = [0, 1].map(|c| (xy[0][c] + xy[1][c] + xy[2][c]) / 3.0);
        let c = geometry.c_sides();
        let mut a = SMatrix::<f64, 3, 9>::zeros();
        let mut gamma = SMatrix::<f64, 3, 9>::zeros();
        let mut t = Matrix3::zeros();
        for (k, &(i, j)) in SIDES.iter().enumerate() {
            let ([sx, sy], l) = geometry.sides[k];
            // The side's bending stiffness (moment M_ss per curvature κ_ss) and shear
            // stiffness (Q_s per γ_s).
            let m = Vector3::new(sx * sx, sy * sy, 2.0 * sx * sy);
            let d_s = (m.transpose() * d * m)[0];
            let s_s = (Vector2::new(sx, sy).transpose() * ds * Vector2::new(sx, sy))[0];
            if s_s <= 0.0 || d_s < 0.0 {
                return Err(BadShape(
                    "has a transverse shear stiffness that is not positive along a side",
                ));
            }
            let phi = 12.0 * d_s / (s_s * l * l);
            a.set_row(k, &(c.row(k) * (-1.5 / (1.0 + phi))));
            gamma.set_row(k, &(c.row(k) * (phi / (1.0 + phi))));
            let mid = [0.5 * (xy[i][0] + xy[j][0]), 0.5 * (xy[i][1] + xy[j][1])];
            t[(k, 0)] = sx;
            t[(k, 1)] = sy;
            t[(k, 2)] = -sx * (mid[1] - centre[1]) + sy * (mid[0] - centre[0]);
        }
        let t_inv = t
            .try_inverse()
            .ok_or(BadShape("is degenerate (its sides' tangents do not span the plane)"))?;
        Ok(Plate {
            geometry,
            a,
            p: t_inv * gamma,
            centre,
        })
    }

    /// Curvature-displacement matrix at (ξ, η).
    fn b_bending(&self, xi: f64, eta: f64) -> SMatrix<f64, 3, 9> {
        self.geometry.b_corners() + self.geometry.b_bubbles([1.0 - xi - eta, xi, eta]) * self.a
    }

    /// Shear strain-displacement matrix (γxz, γyz) at (x, y).
    fn b_shear(&self, x: f64, y: f64) -> SMatrix<f64, 2, 9> {
        let r = SMatrix::<f64, 2, 3>::new(1.0, 0.0, -(y - self.centre[1]), 0.0, 1.0, x - self.centre[0]);
        r * self.p
    }
}

/// A CTRIA3 with transverse shear flexibility (DKMT) in the plane z = `z`.
#[derive(Debug, Clone, PartialEq)]
pub struct Dkmt {
    /// Corner coordinates in the element's plane.
    pub xy: Xy,
    /// The plane's z.
    pub z: f64,
    /// Section and materials (with its transverse shear stiffness).
    pub section: ShellSection,
    /// Curvature at the centroid per plate DOF.
    b_centre: SMatrix<f64, 3, 9>,
    /// Shear force (Qx, Qy) at the centroid per plate DOF.
    b_shear: SMatrix<f64, 2, 9>,
    /// The whole stiffness over the membrane DOFs (u, v per corner) then the plate's
    /// (w, θx, θy per corner).
    k: SMatrix<f64, 15, 15>,
}

impl Dkmt {
    /// The element; `section.shear` must be given.
    pub fn new(xy: Xy, z: f64, section: ShellSection) -> Result<Self, BadShape> {
        let d = section.d().unwrap_or_default();
        let ds = section.shear.ok_or(BadShape("has no transverse shear stiffness"))?;
        let plate = Plate::new(&xy, &d, &ds)?;
        let det = jacobian(&xy).1;
        let bm = b_membrane(&xy);
        let mut k = SMatrix::<f64, 15, 15>::zeros();
        if let Some(a) = section.a() {
            k.fixed_view_mut::<6, 6>(0, 0)
                .copy_from(&(bm.transpose() * a * bm * (0.5 * det)));
        }
        let mut kb = SMatrix::<f64, 9, 9>::zeros();
        let mut kmb = SMatrix::<f64, 6, 9>::zeros();
        let b = section.b();
        for &(xi, eta, w) in &GAUSS {
            let bb = plate.b_bending(xi, eta);
            let [x, y] = [0, 1].map(|c| xy[0][c] + xi * (xy[1][c] - xy[0][c]) + eta * (xy[2][c] - xy[0][c]));
            let bs = plate.b_shear(x, y);
            kb += (bb.transpose() * d * bb + bs.transpose() * ds * bs) * (w * det);
            if let Some(b) = b {
                kmb += bm.transpose() * b * bb * (w * det);
            }
        }
        k.fixed_view_mut::<9, 9>(6, 6).copy_from(&kb);
        k.fixed_view_mut::<6, 9>(0, 6).copy_from(&kmb);
        k.fixed_view_mut::<9, 6>(6, 0).copy_from(&kmb.transpose());
        Ok(Dkmt {
            b_centre: plate.b_bending(1.0 / 3.0, 1.0 / 3.0),
            b_shear: ds * plate.b_shear(plate.centre[0], plate.centre[1]),
            xy,
            z,
            section,
            k,
        })
    }

    /// The element on three grids' coordinates: refused as the thin CTRIA3 refuses
    /// them.
    pub fn build(points: &[[f64; 3]], section: ShellSection) -> Result<Self, BadShape> {
        Dkmt::new(flat(points)?, points[0][2], section)
    }

    /// Transverse shear forces (Qx, Qy) = Ds γ at the centroid.
    pub fn shear_forces(&self, ue: &[f64]) -> Vector2<f64> {
        self.b_shear * parts(ue).1
    }

    /// The plate's 9×9 stiffness over (w, θx, θy) per corner.
    pub fn plate_stiffness(&self) -> SMatrix<f64, 9, 9> {
        self.k.fixed_view::<9, 9>(6, 6).into_owned()
    }
}

/// The CTRIA3 card's kernel: the DKMT when the section has a transverse shear
/// stiffness, the thin DKT otherwise.
pub fn ctria3(points: &[[f64; 3]], section: ShellSection) -> Result<Box<dyn super::BoxedKernel>, BadShape> {
    if section.shear.is_some() {
        Ok(Box::new(Dkmt::build(points, section)?))
    } else {
        Ok(Box::new(super::tria3::Tria3::build(points, section)?))
    }
}

fn dofs() -> Vec<(usize, usize)> {
    let membrane = (0..6).map(|k| (k / 2, k % 2));
    let plate = (0..9).map(|k| (k / 3, 2 + k % 3));
    membrane.chain(plate).collect()
}

impl Kernel for Dkmt {
    fn card(&self) -> &'static str {
        "CTRIA3"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Shell(&self.section)
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix {
            at: dofs(),
            values: DMatrix::from_fn(15, 15, |i, j| self.k[(i, j)]),
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        let m = self.section.mass_per_area * area(&self.xy) / 3.0;
        vec![LocalMatrix::translational(&[m; 3])]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let (um, ub) = parts(ue);
        let u = SMatrix::<f64, 15, 1>::from_fn(|k, _| if k < 6 { um[k] } else { ub[k - 6] });
        0.5 * (u.transpose() * self.k * u)[0]
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        self.section.recovered(what)
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let (um, ub) = parts(ue);
        let mut out = self
            .section
            .recover(b_membrane(&self.xy) * um, self.b_centre * ub, what);
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
        Some(Cell::Triangle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::tria3::Tria3;
    use approx::assert_relative_eq;

    /// A triangle with no two sides equal and no right angle.
    const SCALENE: Xy = [[0.1, -0.2], [2.3, 0.4], [0.7, 1.9]];

    fn section(e: f64, nu: f64, t: f64, kappa: f64) -> ShellSection {
        let q = e / (1.0 - nu * nu) * Matrix3::new(1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu));
        let g = e / (2.0 * (1.0 + nu));
        ShellSection {
            thickness: t,
            g_membrane: Some(q),
            g_bending: Some(q),
            g_coupling: None,
            shear: Some(Matrix2::identity() * kappa * g * t),
            mass_per_area: 1.0,
        }
    }

    /// Nodal plate DOFs (w, θx, θy) of a field w(x, y), βx(x, y), βy(x, y).
    fn nodal(
        xy: &Xy,
        w: impl Fn(f64, f64) -> f64,
        bx: impl Fn(f64, f64) -> f64,
        by: impl Fn(f64, f64) -> f64,
    ) -> SMatrix<f64, 9, 1> {
        SMatrix::<f64, 9, 1>::from_fn(|k, _| {
            let [x, y] = xy[k / 3];
            match k % 3 {
                0 => w(x, y),
                1 => -by(x, y),
                _ => bx(x, y),
            }
        })
    }

    /// Goal: the constant-curvature patch test on a scalene triangle. Reference:
    /// rotations linear in x, y (βx = a x + c y, βy = c x + b y) with the w that makes
    /// γ = 0 give κ = (a, b, 2c) and γ = 0 everywhere, however thick the
    /// plate. Tolerance: round-off.
    #[test]
    fn dkmt_reproduces_constant_curvature_without_shear() {
        let (a, b, c) = (2e-3, -1e-3, 7e-4);
        let u = nodal(
            &SCALENE,
            |x, y| -0.5 * (a * x * x + 2.0 * c * x * y + b * y * y),
            |x, y| a * x + c * y,
            |x, y| c * x + b * y,
        );
        let s = section(1.0e7, 0.3, 0.5, 5.0 / 6.0);
        let plate = Plate::new(&SCALENE, &s.d().unwrap(), &s.shear.unwrap()).unwrap();
        for (xi, eta) in [(1.0 / 3.0, 1.0 / 3.0), (0.0, 0.0), (1.0, 0.0), (0.2, 0.7)] {
            assert_relative_eq!(
                plate.b_bending(xi, eta) * u,
                Vector3::new(a, b, 2.0 * c),
                epsilon = 1e-15
            );
        }
        for [x, y] in [[0.5, 0.3], [1.9, 0.4], [0.8, 1.5]] {
            assert!(
                (plate.b_shear(x, y) * u).norm() < 1e-15,
                "γ = {}",
                plate.b_shear(x, y) * u
            );
        }
    }

    /// Goal: no spurious zero-energy mode. Reference: a free plate element has exactly
    /// the three rigid motions w = a + b x + c y, βx = −b, βy = −c. The 9×9 plate
    /// stiffness must have exactly three zero eigenvalues, thick and thin.
    /// Tolerance: an eigenvalue below 1e-9 of the largest counts as zero.
    #[test]
    fn dkmt_has_exactly_three_zero_energy_modes() {
        for t in [0.5, 0.005] {
            let el = Dkmt::new(SCALENE, 0.0, section(1.0e7, 0.3, t, 5.0 / 6.0)).unwrap();
            let k = el.plate_stiffness();
            let ev = k.symmetric_eigenvalues();
            let zero = ev.iter().filter(|&&e| e.abs() < 1e-9 * ev.amax()).count();
            assert_eq!(zero, 3, "t = {t}: eigenvalues {ev}");
            let rigid = nodal(&SCALENE, |x, y| 0.3 + 0.2 * x - 0.1 * y, |_, _| -0.2, |_, _| 0.1);
            assert!((k * rigid).norm() < 1e-9 * k.norm());
        }
    }

    /// Goal: the thin limit is the DKT, reached like (t/L)², so the element cannot
    /// lock. Model: the scalene triangle, isotropic, t from 1e-1 to 1e-4 of its size.
    /// Reference: the thin CTRIA3's DKT bending stiffness on the same section.
    /// Assertions: the relative difference of the 9×9 plate stiffnesses falls by 100
    /// (± 5 %) per decade of t and is below 1e-6 at t = 1e-4.
    #[test]
    fn dkmt_tends_to_the_dkt_like_thickness_squared() {
        let diff = |t: f64| {
            let s = section(1.0e7, 0.3, t, 5.0 / 6.0);
            let dkmt = Dkmt::new(SCALENE, 0.0, s.clone()).unwrap().plate_stiffness();
            let thin = ShellSection { shear: None, ..s };
            let dkt = Tria3::new(SCALENE, 0.0, thin).stiffness();
            let dkt = &dkt[1].values;
            let dkt = SMatrix::<f64, 9, 9>::from_fn(|i, j| dkt[(i, j)]);
            (dkmt - dkt).norm() / dkt.norm()
        };
        let d: Vec<f64> = [1e-1, 1e-2, 1e-3, 1e-4].map(diff).to_vec();
        eprintln!("‖K_DKMT − K_DKT‖/‖K_DKT‖ at t = 1e-1..1e-4: {d:?}");
        for w in d.windows(2) {
            assert!((w[0] / w[1] / 100.0 - 1.0).abs() < 0.05, "{d:?}");
        }
        assert!(d[3] < 1e-6, "{d:?}");
    }

    /// Goal: the shear field honours both of each side's relations. Reference: along
    /// side k the field's tangential component is constant and equals the side's exact
    /// mean shear strain cₖ + ⅔Δₖ (kinematics) and −⅔φₖΔₖ (the side's Timoshenko-beam
    /// equilibrium); (Qx, Qy) = Ds γ at the centroid, named as the MITC4's.
    /// Tolerance: round-off.
    #[test]
    fn dkmt_shear_field_honours_each_sides_kinematics_and_equilibrium() {
        let s = section(1.0e7, 0.3, 0.4, 5.0 / 6.0);
        let el = Dkmt::new(SCALENE, 0.0, s.clone()).unwrap();
        let (d, ds) = (s.d().unwrap(), s.shear.unwrap());
        let plate = Plate::new(&SCALENE, &d, &ds).unwrap();
        let mut ue = vec![0.0; 18];
        for (k, v) in [1e-3, 2e-3, -1e-3, -2e-3, 5e-4, 1e-3, 4e-3, -3e-3, 2e-4]
            .iter()
            .enumerate()
        {
            ue[6 * (k / 3) + 2 + k % 3] = *v;
        }
        let ub = parts(&ue).1;
        let (delta, c) = (plate.a * ub, plate.geometry.c_sides() * ub);
        for (k, &(i, j)) in SIDES.iter().enumerate() {
            let ([sx, sy], l) = plate.geometry.sides[k];
            let phi = 12.0 * d[(0, 0)] / (ds[(0, 0)] * l * l); // isotropic: Dₛ = D, Sₛ = κGt
            for f in [0.1, 0.5, 0.8] {
                let [x, y] = [0, 1].map(|a| SCALENE[i][a] + f * (SCALENE[j][a] - SCALENE[i][a]));
                let gamma = plate.b_shear(x, y) * ub;
                let tangential = sx * gamma[0] + sy * gamma[1];
                assert_relative_eq!(tangential, c[k] + 2.0 / 3.0 * delta[k], epsilon = 1e-15);
                assert_relative_eq!(tangential, -2.0 / 3.0 * phi * delta[k], epsilon = 1e-15);
            }
        }
        let q = el.shear_forces(&ue);
        let centre = [0, 1].map(|a| (SCALENE[0][a] + SCALENE[1][a] + SCALENE[2][a]) / 3.0);
        assert_relative_eq!(q, ds * (plate.b_shear(centre[0], centre[1]) * ub), max_relative = 1e-14);
        let names = el.recovered(crate::elements::Output::Stress);
        assert_eq!(names[names.len() - 1].name(4), "shear_force_4_qy");
        let values = el.recover(&ue, crate::elements::Output::Stress);
        assert_relative_eq!(values[values.len() - 2], q[0], max_relative = 1e-14);
    }
}
