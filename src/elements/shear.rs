//! CSHEAR: NASTRAN's four-node shear panel, a quadrilateral plate that carries only
//! shear in its own plane (the webs of ribs and spars, whose flanges are rods).
//!
//! Formulation (NASTRAN-95's shear panel, after Garvey's theory of tapered panels):
//! the panel has one deformation, carried by shear flows along its four edges that
//! balance each other; the corner forces of that state act along the panel's
//! diagonals. With the panel in its mean plane (normal along the diagonals' cross
//! product, x along side 1-2 there, corners at (0, 0), (x2, 0), (x3, y3), (x4, y4)),
//! the corner force at corner i is aᵢ·wᵢ per unit of the state's amplitude, wᵢ the unit
//! in-plane direction of the diagonal through i (1→3 at corners 1 and 3, 2→4 at 2
//! and 4) and
//!
//! a₁ = −a₃ = −½ x2 y4 l13 / (x4 y3 − x3 y4),
//! a₂ = −a₄ = ½ x2 y3 l24 / (x4 y3 − x3 y4 − x2 (y3 − y4)).
//!
//! The stiffness is of rank one, K = a aᵀ / 2Z over the corners' translations
//! (a the twelve components aᵢ wᵢ), 2Z the panel's flexibility: the complementary
//! energy of its shear flows. For a parallelogram of area A, Z = A/2Gt (1 + 2d²/(1+ν))
//! with d its skew; for a trapezoid and a general quadrilateral, the closed forms of
//! the tapered panel, which take the shear flows' variation across the panel and the
//! normal stresses that go with it (through ν) into account. For a rectangle,
//! ½ uᵀKu = ½ G t A γ², the plate's own shear energy (see the tests).
//!
//! No bending, no extension, no drilling stiffness: a shear panel adds nothing to a
//! grid's rotations or to the out-of-plane motion of a flat panel, as NASTRAN's. Mass
//! is NASTRAN's lumped mass for its quadrilaterals: at each corner (ρt + NSM)/6 times
//! the area of the triangle it makes with its two neighbours plus the panel's area,
//! on its translations; the corners' masses sum to (ρt + NSM)·A.
//!
//! Recovery: the panel's shear flow amplitude, q = aᵀu/2Z (force per length: the
//! shear flow of a parallelogram, uniform over it), and its mean shear stress q/t
//! with the strain q/Gt.

use super::{BadShape, Cell, Kernel, LocalMatrix, Measure, Recovered};
use nalgebra::{DMatrix, Vector3};

/// Material and thickness of a shear panel (PSHEAR with its MAT1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanelSection {
    /// Shear modulus G.
    pub g: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
    /// Thickness t.
    pub t: f64,
    /// Mass density ρ.
    pub rho: f64,
    /// Non-structural mass per unit area.
    pub nsm: f64,
}

/// A shear panel on four grids.
#[derive(Debug, Clone, PartialEq)]
pub struct ShearPanel {
    /// Corner coordinates (basic), in connection order.
    pub x: [[f64; 3]; 4],
    /// Section and material.
    pub section: PanelSection,
    /// The corner force directions times their magnitudes, aᵢ·wᵢ (basic), per unit
    /// of the shear state.
    a: [[f64; 3]; 4],
    /// The flexibility 2Z.
    flexibility: f64,
    /// The lumped mass at each corner.
    masses: [f64; 4],
}

/// The in-plane coordinates of the corners in the panel's mean plane and its axes
/// (x along the projection of side 1-2, z along d13 × d24) and projected area.
struct Frame {
    x2: f64,
    x3: f64,
    y3: f64,
    x4: f64,
    y4: f64,
    i: Vector3<f64>,
    j: Vector3<f64>,
    area: f64,
}

fn frame(x: &[[f64; 3]; 4]) -> Result<Frame, BadShape> {
    let p = x.map(Vector3::from);
    let (d13, d24) = (p[2] - p[0], p[3] - p[1]);
    let n = d13.cross(&d24);
    let size = d13.norm().max(d24.norm());
    if n.norm() <= 1e-12 * size * size {
        return Err(BadShape(
            "is degenerate: its diagonals are parallel or its corners coincide",
        ));
    }
    let k = n.normalize();
    let side = p[1] - p[0];
    let side = side - k * side.dot(&k);
    if side.norm() <= 1e-12 * size {
        return Err(BadShape("is degenerate: its side G1-G2 stands normal to its plane"));
    }
    let i = side.normalize();
    let j = k.cross(&i);
    let (v3, v4) = (p[2] - p[0], p[3] - p[0]);
    Ok(Frame {
        x2: side.norm(),
        x3: i.dot(&v3),
        y3: j.dot(&v3),
        x4: i.dot(&v4),
        y4: j.dot(&v4),
        i,
        j,
        area: 0.5 * n.norm(),
    })
}

/// The panel's flexibility 2Z for shear modulus `g`, Poisson's ratio `nu`, thickness
/// `t`: parallelogram, trapezoid (either pair of sides parallel within 1 %, NASTRAN's
/// test) or general quadrilateral.
fn flexibility(f: &Frame, g: f64, nu: f64, t: f64) -> f64 {
    let Frame { x2, x3, y3, x4, y4, .. } = *f;
    let nuc = 1.0 / (1.0 + nu);
    let twice_gt = 2.0 * g * t;
    // Side 3-4 parallel to side 1-2; side 1-4 parallel to side 2-3.
    let p12 = (y3 - y4).abs() < 0.01 * (x3 - x4).abs();
    let p23 = (y4 * (x3 - x2) - y3 * x4).abs() < 0.01 * (x4 * (x3 - x2) + y4 * y3).abs();
    let z = match (p12, p23) {
        (true, true) => {
            let d = -0.5 * (x4 / y4 + (x3 - x2) / y3 + (y3 - y4) / (x3 - x4));
            f.area / twice_gt * (1.0 + 2.0 * d * d * nuc)
        }
        (true, false) => {
            // Sides 1-4 and 2-3 meet at (xp, yp); distances from it along y.
            let den = y3 * x4 - y4 * (x3 - x2);
            let (xp, yp) = (x2 * y3 * x4 / den, x2 * y3 * y4 / den);
            let p = [yp, yp, yp - y3, yp - y4];
            let (sa, c) = ((x2 - xp) / yp, -xp / yp);
            p[0] * p[1] * f.area / (p[2] * p[3] * twice_gt) * (1.0 + 2.0 / 3.0 * nuc * (sa * sa + sa * c + c * c))
        }
        (false, true) => {
            // Sides 1-2 and 3-4 meet at (xq, 0); distances from it normal to side 1-4.
            let d = -0.5 * (x4 / y4 + (x3 - x2) / y3);
            let xq = x4 - y4 * (x3 - x4) / (y3 - y4);
            let s = 1.0 / (1.0 + d * d).sqrt();
            let p = [xq * s, (xq - x2) * s, (xq - x3 - d * y3) * s, (xq - x4 - d * y4) * s];
            let b = ((xq - x4) * d + y4) / (xq - x4 - y4 * d);
            p[0] * p[1] * f.area / (p[2] * p[3] * twice_gt) * (1.0 + 2.0 / 3.0 * nuc * (b * b + b * d + d * d))
        }
        (false, false) => {
            let xq = x4 - (x3 - x4) / (y3 - y4) * y4;
            let den = y3 * x4 - y4 * (x3 - x2);
            let (xp, yp) = (x2 * y3 * x4 / den, x2 * y3 * y4 / den);
            let xl = ((xq - xp).powi(2) + yp * yp).sqrt();
            let d = (xq - xp) / yp;
            let s = yp / xl;
            let p = [xq * s, (xq - x2) * s, (xq - x3 - d * y3) * s, (xq - x4 - d * y4) * s];
            let c = xl / p[0] - d;
            let b = xl / p[3] - c;
            let a = xl / p[1] - d;
            let w = |u: f64, v: f64| {
                (u + v + 2.0 / 3.0 * (u.powi(3) + v.powi(3)) + 0.2 * (u.powi(5) + v.powi(5))) * (u + v).abs().ln()
            };
            let ff = 0.5 * p[0] * p[1] * p[2] * p[3] / (xl * xl)
                * (w(a, b) + w(c, d) - w(b, c) - w(d, a)
                    + 0.1 * ((a * a - c * c) * (b.powi(3) - d.powi(3)) + (b * b - d * d) * (a.powi(3) - c.powi(3)))
                    - 0.2 * ((a - c) * (b.powi(4) - d.powi(4)) + (b - d) * (a.powi(4) - c.powi(4))));
            p[0] * p[1] / (p[2] * p[3] * twice_gt) * (f.area + 4.0 * nuc * (ff - 2.0 / 3.0 * f.area))
        }
    };
    2.0 * z
}

impl ShearPanel {
    /// The panel on four grids' coordinates: refused when degenerate or when an
    /// interior angle is 180° or more (NASTRAN's own refusal, CSHEAR remark 3).
    pub fn build(points: &[[f64; 3]], section: PanelSection) -> Result<Self, BadShape> {
        let x = [points[0], points[1], points[2], points[3]];
        let f = frame(&x)?;
        let Frame { x2, x3, y3, x4, y4, .. } = f;
        if y3 <= 0.0 || y4 <= 0.0 || x3 <= y3 * x4 / y4 || x4 >= x2 - (x2 - x3) * y4 / y3 {
            return Err(BadShape(
                "is not convex: an interior angle is 180° or more, or its corners do not run around it in order",
            ));
        }
        let (l13, l24) = ((x3 * x3 + y3 * y3).sqrt(), ((x4 - x2).powi(2) + y4 * y4).sqrt());
        let den = x4 * y3 - x3 * y4;
        let a1 = -0.5 * x2 * y4 * l13 / den;
        let a2 = 0.5 * x2 * y3 * l24 / (den - x2 * (y3 - y4));
        let w13 = f.i * (x3 / l13) + f.j * (y3 / l13);
        let w24 = f.i * ((x4 - x2) / l24) + f.j * (y4 / l24);
        let a = [w13 * a1, w24 * a2, w13 * -a1, w24 * -a2].map(|v| [v.x, v.y, v.z]);
        let s = section;
        let per_area = (s.rho * s.t + s.nsm) / 6.0;
        let masses = std::array::from_fn(|k| {
            let p = |m: usize| Vector3::from(x[(k + m) % 4]);
            let corner = 0.5 * (p(3) - p(0)).cross(&(p(1) - p(0))).norm();
            per_area * (corner + f.area)
        });
        Ok(ShearPanel {
            x,
            section,
            a,
            flexibility: flexibility(&f, s.g, s.nu, s.t),
            masses,
        })
    }

    /// The shear state's amplitude aᵀu from the local displacements.
    fn amplitude(&self, ue: &[f64]) -> f64 {
        (0..4)
            .map(|k| (0..3).map(|c| self.a[k][c] * ue[6 * k + c]).sum::<f64>())
            .sum()
    }

    /// The panel's area (projected onto its mean plane).
    pub fn area(&self) -> f64 {
        frame(&self.x).map(|f| f.area).unwrap_or(0.0)
    }
}

impl Kernel for ShearPanel {
    fn card(&self) -> &'static str {
        "CSHEAR"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Panel(&self.section)
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        let at: Vec<(usize, usize)> = (0..4).flat_map(|k| (0..3).map(move |c| (k, c))).collect();
        let v: Vec<f64> = self.a.iter().flatten().copied().collect();
        vec![LocalMatrix {
            values: DMatrix::from_fn(12, 12, |r, c| v[r] * v[c] / self.flexibility),
            at,
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix::translational(&self.masses)]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        0.5 * self.amplitude(ue).powi(2) / self.flexibility
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        let mean = |measure| Recovered { measure, at: None };
        match what {
            super::Output::Stress => vec![mean(Measure::Stress), mean(Measure::Strain)],
            super::Output::Strain => vec![mean(Measure::Strain)],
            super::Output::Force => vec![mean(Measure::Force(super::Resultant::Nxy))],
        }
    }
    fn material_law(&self, strains: &[f64]) -> Option<Vec<f64>> {
        Some(vec![self.section.g * strains[0]])
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let q = self.amplitude(ue) / self.flexibility;
        let s = &self.section;
        match what {
            super::Output::Stress => vec![q / s.t, q / (s.g * s.t)],
            super::Output::Strain => vec![q / (s.g * s.t)],
            super::Output::Force => vec![q],
        }
    }
    fn eq16_mass(&self) -> Option<f64> {
        Some(self.masses.iter().sum())
    }
    fn points(&self) -> Vec<[f64; 3]> {
        self.x.to_vec()
    }
    fn cell(&self) -> Option<Cell> {
        Some(Cell::Quad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const S: PanelSection = PanelSection {
        g: 4.0e6,
        nu: 0.3,
        t: 0.1,
        rho: 2.5e-4,
        nsm: 0.0,
    };

    fn panel(x: [[f64; 3]; 4]) -> ShearPanel {
        ShearPanel::build(&x, S).unwrap()
    }

    fn displacements(u: impl Fn([f64; 3]) -> [f64; 3], x: &[[f64; 3]; 4]) -> Vec<f64> {
        x.iter().flat_map(|&p| u(p).into_iter().chain([0.0; 3])).collect()
    }

    /// Goal: a rectangular panel in pure shear stores the plate's shear energy.
    /// Model: a 3 × 2 rectangle, tilted out of the basic axes, under u = γ/2 (y, x)
    /// in its plane. Reference: ½ G t A γ², and shear flow G t γ. Tolerance: round-off.
    #[test]
    fn a_rectangle_in_pure_shear_stores_half_g_t_a_gamma_squared() {
        let (i, j) = (Vector3::new(0.6, 0.8, 0.0), Vector3::new(0.0, 0.0, 1.0));
        let at = |x: f64, y: f64| (i * x + j * y).into();
        let x = [at(0.0, 0.0), at(3.0, 0.0), at(3.0, 2.0), at(0.0, 2.0)];
        let p = panel(x);
        let gamma = 1e-3;
        let u = |q: [f64; 3]| {
            let q = Vector3::from(q);
            let (lx, ly) = (q.dot(&i), q.dot(&j));
            (i * (0.5 * gamma * ly) + j * (0.5 * gamma * lx)).into()
        };
        let ue = displacements(u, &x);
        assert_relative_eq!(
            p.strain_energy(&ue),
            0.5 * S.g * S.t * 6.0 * gamma * gamma,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            p.recover(&ue, super::super::Output::Force)[0].abs(),
            S.g * S.t * gamma,
            max_relative = 1e-12
        );
    }

    /// Goal: the panel resists shear only: rigid motions and stretches along its sides
    /// of a rectangle cost nothing, out-of-plane motion of a flat panel nothing.
    /// Model: the 3 × 2 rectangle in the basic XY plane. Reference: zero energy for
    /// translations, an in-plane rotation, u = (εx, 0), v = (0, εy) and any w.
    /// Tolerance: 1e-12 of the shear state's energy.
    #[test]
    fn a_rectangle_costs_nothing_but_shear() {
        let x = [[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [3.0, 2.0, 0.0], [0.0, 2.0, 0.0]];
        let p = panel(x);
        let scale = p.strain_energy(&displacements(|q| [q[1], q[0], 0.0], &x));
        let free: [&dyn Fn([f64; 3]) -> [f64; 3]; 5] = [
            &|_| [1.0, -2.0, 0.5],
            &|q| [-q[1], q[0], 0.0],
            &|q| [q[0], 0.0, 0.0],
            &|q| [0.0, q[1], 0.0],
            &|q| [0.0, 0.0, q[0] * q[1]],
        ];
        for u in free {
            assert!(p.strain_energy(&displacements(u, &x)) < 1e-12 * scale);
        }
    }

    /// Goal: the tapered panels' flexibilities tend to the parallelogram's as the panel
    /// tends to one, so the three closed forms are one function of the shape. Model: a
    /// unit square whose corner 3 moves by ε along x (sides 3-4 and 1-2 stay parallel),
    /// along y (sides 1-4 and 2-3 stay parallel) or along the diagonal (a general
    /// quadrilateral), ε = 0.16 halved to 0.02, above NASTRAN's 1 % switch to the
    /// parallelogram's form. Reference: the square's 2Z = A/Gt. Order: the change is
    /// of first order in ε (the panel's area changes by ε/2), so it halves with ε. The
    /// second-order term is as large for the general quadrilateral (observed orders
    /// 0.64, 0.80, 0.90 over the three halvings; 1.12, 1.06, 1.03 for the panel with
    /// sides 1-4 and 2-3 parallel): each halving's observed order is nearer 1 than the
    /// last, and the last is within 0.15 of it.
    #[test]
    fn tapered_flexibilities_tend_to_the_parallelograms_at_first_order() {
        let unit = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let square = flexibility(&frame(&unit).unwrap(), S.g, S.nu, S.t);
        assert_relative_eq!(square, 1.0 / (S.g * S.t), max_relative = 1e-12);
        for (dx, dy) in [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            let change = |eps: f64| {
                let mut x = unit;
                x[2] = [1.0 + dx * eps, 1.0 + dy * eps, 0.0];
                flexibility(&frame(&x).unwrap(), S.g, S.nu, S.t) / square - 1.0
            };
            let changes = [0.16, 0.08, 0.04, 0.02].map(change);
            let orders: Vec<f64> = changes.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
            assert!(
                orders.windows(2).all(|w| (w[1] - 1.0).abs() < (w[0] - 1.0).abs()) && (orders[2] - 1.0).abs() < 0.15,
                "({dx}, {dy}): changes {changes:?}, orders {orders:?}"
            );
        }
    }

    /// Goal: the lumped masses sum to the panel's mass, a rectangle's equal at its
    /// corners. Reference: ρ t A. Tolerance: round-off.
    #[test]
    fn lumped_masses_sum_to_the_panels_mass() {
        let p = panel([[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [3.0, 2.0, 0.0], [0.0, 2.0, 0.0]]);
        for m in p.masses {
            assert_relative_eq!(m, 0.25 * S.rho * S.t * 6.0, max_relative = 1e-12);
        }
        let q = panel([[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [3.0, 2.0, 0.0], [0.5, 1.5, 0.0]]);
        assert_relative_eq!(
            q.masses.iter().sum::<f64>(),
            S.rho * S.t * q.area(),
            max_relative = 1e-12
        );
    }

    /// Goal: a panel whose interior angle reaches 180° is refused, as NASTRAN refuses it.
    #[test]
    fn a_concave_panel_is_refused() {
        let x = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.0, 2.0, 0.0]];
        assert!(ShearPanel::build(&x, S).is_err());
    }
}
