//! The structure's mass, centre of gravity and inertia, as NASTRAN's grid point weight
//! generator (GPWG) gives them for the whole model.
//!
//! The rigid-body mass matrix about the basic origin is `M₀ = Σₑ Dₑᵀ Mₑ Dₑ` over every
//! element's mass matrices (in its grids' displacement frames), where `D` takes a rigid
//! motion of the structure (a translation U and a rotation Θ about the origin, basic
//! components) to each grid's DOFs: `[Tᵀ(U − [x]×Θ); TᵀΘ]`, x the grid's basic
//! position and T its frame. From its blocks: the mass m (M₀'s translational diagonal,
//! the same in x, y and z for lumped and concentrated masses), the first moments
//! S = (M₀[5,1], M₀[3,2], M₀[4,0]) (its lower-left block is Σ m[x]×), the centre of
//! gravity c = S/m, and the inertia about c, `I = I₀ − m(|c|²𝟙 − c cᵀ)` with I₀ M₀'s
//! rotational block (the parallel-axis theorem). Inertias are the tensor's: moments
//! on the diagonal, products of inertia with their minus sign off it.

use crate::elements::Element;
use nalgebra::{Matrix3, Matrix6, SMatrix, Vector3};

/// A structure's mass properties.
#[derive(Debug, Clone, PartialEq)]
pub struct MassProperties {
    /// The mass along basic x, y, z (equal for lumped and concentrated masses).
    pub mass: [f64; 3],
    /// The centre of gravity, basic coordinates (`None` without mass).
    pub centre: Option<[f64; 3]>,
    /// The inertia tensor about the centre of gravity, basic axes.
    pub inertia: [[f64; 3]; 3],
    /// Its principal moments, ascending.
    pub principal: [f64; 3],
    /// The rigid-body mass matrix about the basic origin, M₀.
    pub rigid_body: [[f64; 6]; 6],
}

/// The mass properties of `elements`, their grids at `position(g)` (basic) and
/// displaced in `frame(g)` (axes as columns, basic components).
pub fn mass_properties(
    elements: &[Element],
    position: impl Fn(i64) -> Option<[f64; 3]>,
    frame: impl Fn(i64) -> Matrix3<f64>,
) -> MassProperties {
    let mut sum = RigidBodyMass::default();
    for e in elements {
        sum.add(e, &position, &frame);
    }
    sum.properties()
}

/// The rigid-body mass matrix about the basic origin, `M₀ = Σₑ Dₑᵀ Mₑ Dₑ`, summed
/// element by element (so that a structure's elements need not be held at once).
#[derive(Debug, Clone, Default)]
pub struct RigidBodyMass {
    m0: Matrix6<f64>,
}

impl RigidBodyMass {
    /// Adds an element's mass, its grids at `position(g)` (basic) and displaced in
    /// `frame(g)` (axes as columns, basic components).
    pub fn add(
        &mut self,
        e: &Element,
        position: &impl Fn(i64) -> Option<[f64; 3]>,
        frame: &impl Fn(i64) -> Matrix3<f64>,
    ) {
        // A scalar point (no position) has no place in the rigid-body mass.
        let at: Vec<Option<[f64; 3]>> = e.grids.iter().map(|&g| position(g)).collect();
        let d: Vec<SMatrix<f64, 6, 6>> = e
            .grids
            .iter()
            .zip(&at)
            .map(|(&g, x)| {
                let (x, t) = (Vector3::from(x.unwrap_or_default()), frame(g));
                let mut rigid = Matrix6::identity();
                rigid.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-x.cross_matrix()));
                let mut turn = Matrix6::zeros();
                turn.fixed_view_mut::<3, 3>(0, 0).copy_from(&t.transpose());
                turn.fixed_view_mut::<3, 3>(3, 3).copy_from(&t.transpose());
                turn * rigid
            })
            .collect();
        let full = match e.mass_or_lumped() {
            // A lumped mass: the diagonal terms of the loop below, in its order.
            Ok(m) => {
                for (g, &m) in m.iter().enumerate() {
                    if m != 0.0 && at[g].is_some() {
                        for c in 0..3 {
                            self.m0 += d[g].row(c).transpose() * d[g].row(c) * m;
                        }
                    }
                }
                return;
            }
            Err(full) => full,
        };
        for l in full {
            for (a, &(ga, ca)) in l.at.iter().enumerate() {
                for (b, &(gb, cb)) in l.at.iter().enumerate() {
                    let v = l.values[(a, b)];
                    if v != 0.0 && at[ga].is_some() && at[gb].is_some() {
                        self.m0 += d[ga].row(ca).transpose() * d[gb].row(cb) * v;
                    }
                }
            }
        }
    }

    /// The mass, centre of gravity and inertia of what was added.
    pub fn properties(&self) -> MassProperties {
        let m0 = self.m0;
        let mass = [m0[(0, 0)], m0[(1, 1)], m0[(2, 2)]];
        let s = Vector3::new(m0[(5, 1)], m0[(3, 2)], m0[(4, 0)]);
        let m = mass[0];
        let centre = (m > 0.0).then(|| s / m);
        let i0 = m0.fixed_view::<3, 3>(3, 3).into_owned();
        let inertia = match centre {
            Some(c) => i0 - (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * m,
            None => i0,
        };
        let mut principal: Vec<f64> = crate::numerics::symmetric_eigenvalues(inertia)
            .iter()
            .copied()
            .collect();
        principal.sort_by(f64::total_cmp);
        MassProperties {
            mass,
            centre: centre.map(|c| [c.x, c.y, c.z]),
            inertia: std::array::from_fn(|i| std::array::from_fn(|j| inertia[(i, j)])),
            principal: [principal[0], principal[1], principal[2]],
            rigid_body: std::array::from_fn(|i| std::array::from_fn(|j| m0[(i, j)])),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::mass::PointMass;

    /// Goal: two point masses give the textbook answers. Reference: m = 2 at (1, 0, 0)
    /// and m = 1 at (−2, 3, 0): total 3, centre (0, 1, 0); about it the masses sit at
    /// (1, −1, 0) and (−2, 2, 0), so Ixx = 2·1 + 1·4 = 6, Iyy = 2·1 + 1·4 = 6,
    /// Izz = 2·2 + 1·8 = 12, Ixy = −(2·(1)(−1) + 1·(−2)(2)) = 6; one grid displaced in
    /// a turned frame changes nothing. Tolerance: round-off.
    #[test]
    fn two_point_masses_have_their_textbook_centre_and_inertia() {
        let pm = |x: [f64; 3], mass: f64| PointMass {
            x,
            mass,
            inertia: [0.0; 6],
        };
        let elements = vec![
            Element::new(1, vec![1], vec![[None; 6]], pm([1.0, 0.0, 0.0], 2.0)),
            Element::new(2, vec![2], vec![[None; 6]], pm([-2.0, 3.0, 0.0], 1.0)),
        ];
        let position = |g: i64| Some(if g == 1 { [1.0, 0.0, 0.0] } else { [-2.0, 3.0, 0.0] });
        let turned = nalgebra::Rotation3::from_euler_angles(0.3, 0.2, -0.9).into_inner();
        for frame in [Matrix3::identity(), turned] {
            let p = mass_properties(
                &elements,
                position,
                |g| if g == 2 { frame } else { Matrix3::identity() },
            );
            let c = p.centre.unwrap();
            assert!((p.mass[0] - 3.0).abs() < 1e-14 && (p.mass[2] - 3.0).abs() < 1e-14);
            assert!((c[0]).abs() < 1e-14 && (c[1] - 1.0).abs() < 1e-14 && c[2].abs() < 1e-14);
            let want = [[6.0, 6.0, 0.0], [6.0, 6.0, 0.0], [0.0, 0.0, 12.0]];
            let worst = p
                .inertia
                .iter()
                .flatten()
                .zip(want.iter().flatten())
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(worst < 1e-12, "{:?}", p.inertia);
        }
    }
}
