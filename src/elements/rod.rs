//! CROD: two-node axial and torsional rod.
//!
//! Formulation: linear shape functions (exact for uniform EA and GJ, so the element
//! stiffness is exact and no quadrature is needed); axial stiffness EA/L along the
//! element axis, torsion GJ/L about it. Mass on the translational DOFs, m = (ρA +
//! NSM)·L: lumped, m/2 at each end (NASTRAN's default), or coupled when the deck asks
//! (PARAM COUPMASS, CPROD, CPTUBE): the consistent mass of linear shape functions,
//! m/6 [2 1; 1 2] along each of the three directions alike, as NASTRAN-95 builds it
//! (its rod routine's consistent mass matrix). No rotary inertia either way.
//! Recovery: axial strain (e·(u2 − u1))/L, constant over the element; its resultants
//! N = EA ε and T = GJ (e·(θ2 − θ1))/L.

use super::{BadShape, Cell, Kernel, LocalMatrix, Measure, Recovered};
use nalgebra::{DMatrix, SMatrix, Vector3};

/// Section and material of a rod.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodSection {
    /// Young's modulus E.
    pub e: f64,
    /// Shear modulus G.
    pub g: f64,
    /// Cross-section area A.
    pub area: f64,
    /// Torsional constant J.
    pub torsion: f64,
    /// Mass density ρ.
    pub rho: f64,
    /// Non-structural mass per unit length.
    pub nsm: f64,
    /// The mass coupled (consistent), not lumped.
    pub coupled_mass: bool,
}

/// Unit axis and length from end 1 to end 2.
pub fn axis(x1: [f64; 3], x2: [f64; 3]) -> (Vector3<f64>, f64) {
    let d = Vector3::from(x2) - Vector3::from(x1);
    let l = d.norm();
    (d / l, l)
}

/// Stiffness in global axes for DOFs [T1 T2 T3 R1 R2 R3] of end 1 then end 2.
pub fn stiffness(x1: [f64; 3], x2: [f64; 3], s: &RodSection) -> SMatrix<f64, 12, 12> {
    let (e, l) = axis(x1, x2);
    let ee = e * e.transpose();
    let mut k = SMatrix::<f64, 12, 12>::zeros();
    let ka = s.e * s.area / l;
    let kt = s.g * s.torsion / l;
    for (r0, c0, sign) in [(0, 0, 1.0), (0, 6, -1.0), (6, 0, -1.0), (6, 6, 1.0)] {
        for i in 0..3 {
            for j in 0..3 {
                k[(r0 + i, c0 + j)] += sign * ka * ee[(i, j)];
                k[(r0 + 3 + i, c0 + 3 + j)] += sign * kt * ee[(i, j)];
            }
        }
    }
    k
}

/// Lumped mass at each end (applied to all three translations).
pub fn lumped_mass(x1: [f64; 3], x2: [f64; 3], s: &RodSection) -> f64 {
    let (_, l) = axis(x1, x2);
    0.5 * (s.rho * s.area + s.nsm) * l
}

/// Total element mass.
pub fn mass(x1: [f64; 3], x2: [f64; 3], s: &RodSection) -> f64 {
    2.0 * lumped_mass(x1, x2, s)
}

/// Strain energy from the end displacements [T1 T2 T3 R1 R2 R3] of each end.
/// Computed from the relative displacement along the axis (Eq. 17 of the paper),
/// so a large rigid-body motion costs no accuracy.
pub fn strain_energy(x1: [f64; 3], x2: [f64; 3], s: &RodSection, d1: [f64; 6], d2: [f64; 6]) -> f64 {
    let (e, l) = axis(x1, x2);
    let mut stretch = 0.0;
    let mut twist = 0.0;
    for k in 0..3 {
        stretch += e[k] * (d2[k] - d1[k]);
        twist += e[k] * (d2[k + 3] - d1[k + 3]);
    }
    0.5 * s.e * s.area / l * stretch * stretch + 0.5 * s.g * s.torsion / l * twist * twist
}

/// Axial strain from the end translations.
pub fn axial_strain(x1: [f64; 3], x2: [f64; 3], u1: [f64; 3], u2: [f64; 3]) -> f64 {
    let (e, l) = axis(x1, x2);
    e.dot(&(Vector3::from(u2) - Vector3::from(u1))) / l
}

/// A CROD between two grids.
#[derive(Debug, Clone, PartialEq)]
pub struct Rod {
    /// The card it comes from: CROD, CONROD or CTUBE (one element, three ways of
    /// giving its section).
    pub card: &'static str,
    /// End coordinates.
    pub x: [[f64; 3]; 2],
    /// Section and material.
    pub section: RodSection,
}

impl Rod {
    /// The rod between two grids' coordinates: refused when they coincide.
    pub fn build(points: &[[f64; 3]], section: RodSection) -> Result<Self, BadShape> {
        let x = [points[0], points[1]];
        if x[0] == x[1] {
            return Err(BadShape("has zero length (its grids coincide)"));
        }
        Ok(Rod {
            card: "CROD",
            x,
            section,
        })
    }

    /// The rod as the element of another card (CONROD, CTUBE).
    pub fn of_card(mut self, card: &'static str) -> Self {
        self.card = card;
        self
    }

    /// Its length.
    pub fn length(&self) -> f64 {
        axis(self.x[0], self.x[1]).1
    }
}

fn end(ue: &[f64], k: usize) -> [f64; 6] {
    std::array::from_fn(|c| ue[6 * k + c])
}

impl Kernel for Rod {
    fn card(&self) -> &'static str {
        self.card
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Rod {
            section: &self.section,
            length: self.length(),
        }
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        let k = stiffness(self.x[0], self.x[1], &self.section);
        vec![LocalMatrix {
            at: (0..12).map(|i| (i / 6, i % 6)).collect(),
            values: DMatrix::from_fn(12, 12, |i, j| k[(i, j)]),
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        let m = lumped_mass(self.x[0], self.x[1], &self.section);
        if !self.section.coupled_mass {
            return vec![LocalMatrix::translational(&[m; 2])];
        }
        // (2m_end)/6 [2 1; 1 2] on each direction: m_end·2/3 and m_end/3.
        let at: Vec<(usize, usize)> = (0..6).map(|i| (i / 3, i % 3)).collect();
        let values = DMatrix::from_fn(6, 6, |i, j| match (i % 3 == j % 3, i / 3 == j / 3) {
            (true, true) => 2.0 * m / 3.0,
            (true, false) => m / 3.0,
            _ => 0.0,
        });
        vec![LocalMatrix { at, values }]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        strain_energy(self.x[0], self.x[1], &self.section, end(ue, 0), end(ue, 1))
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        let axial = |measure| Recovered { measure, at: None };
        match what {
            super::Output::Stress => vec![axial(Measure::Stress), axial(Measure::Strain)],
            super::Output::Strain => vec![axial(Measure::Strain)],
            super::Output::Force => vec![
                axial(Measure::Force(super::Resultant::Axial)),
                axial(Measure::Force(super::Resultant::Torque)),
            ],
        }
    }
    fn material_law(&self, strains: &[f64]) -> Option<Vec<f64>> {
        Some(vec![self.section.e * strains[0]])
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let t = |k: usize| -> [f64; 3] { std::array::from_fn(|c| ue[6 * k + c]) };
        let r = |k: usize| -> [f64; 3] { std::array::from_fn(|c| ue[6 * k + 3 + c]) };
        let eps = axial_strain(self.x[0], self.x[1], t(0), t(1));
        let s = &self.section;
        match what {
            super::Output::Stress => vec![s.e * eps, eps],
            super::Output::Strain => vec![eps],
            // N = EA ε; T = GJ times the twist rate, the rotations' difference along
            // the axis over the length (the rate is the axial strain of the rotations).
            super::Output::Force => vec![
                s.e * s.area * eps,
                s.g * s.torsion * axial_strain(self.x[0], self.x[1], r(0), r(1)),
            ],
        }
    }
    fn eq16_mass(&self) -> Option<f64> {
        Some(mass(self.x[0], self.x[1], &self.section))
    }
    fn points(&self) -> Vec<[f64; 3]> {
        self.x.to_vec()
    }
    fn cell(&self) -> Option<Cell> {
        Some(Cell::Line)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const S: RodSection = RodSection {
        e: 10.0e6,
        g: 3.76e6,
        area: 0.196,
        torsion: 6.14e-3,
        rho: 2.5e-4,
        nsm: 0.0,
        coupled_mass: false,
    };

    /// Goal: the element is a spring EA/L along its axis and stress-free in rigid motion.
    /// Model: one inclined rod. Reference: K·u for a rigid translation is zero, for a
    /// stretch δ along the axis the end force is EA δ / L. Tolerance: round-off.
    #[test]
    fn inclined_rod_is_an_axial_spring_with_rigid_body_modes() {
        let (x1, x2) = ([0.0, 0.0, 0.0], [3.0, 4.0, 0.0]);
        let k = stiffness(x1, x2, &S);
        let mut rigid = SMatrix::<f64, 12, 1>::zeros();
        for i in [0, 6] {
            rigid[i] = 1.0;
            rigid[i + 1] = -2.0;
            rigid[i + 2] = 0.5;
        }
        assert!((k * rigid).norm() < 1e-9 * k.norm());
        let mut stretch = SMatrix::<f64, 12, 1>::zeros();
        stretch[6] = 0.6e-3;
        stretch[7] = 0.8e-3; // 1e-3 along the axis (0.6, 0.8)
        let f = k * stretch;
        let expected = S.e * S.area / 5.0 * 1e-3;
        assert_relative_eq!(f[6] * 0.6 + f[7] * 0.8, expected, max_relative = 1e-12);
        assert_relative_eq!(
            axial_strain(x1, x2, [0.0; 3], [0.6e-3, 0.8e-3, 0.0]),
            1e-3 / 5.0,
            max_relative = 1e-12
        );
    }

    #[test]
    fn strain_energy_is_half_u_k_u() {
        let (x1, x2) = ([0.0, 0.0, 0.0], [1.0, 2.0, 2.0]);
        let d1 = [1e-3, -2e-3, 5e-4, 1e-2, 0.0, -3e-3];
        let d2 = [4e-3, 1e-3, -1e-3, 0.0, 2e-2, 1e-3];
        let u = SMatrix::<f64, 12, 1>::from_iterator(d1.iter().chain(d2.iter()).copied());
        let k = stiffness(x1, x2, &S);
        let half_uku = 0.5 * (u.transpose() * k * u)[(0, 0)];
        assert_relative_eq!(strain_energy(x1, x2, &S, d1, d2), half_uku, max_relative = 1e-12);
    }

    #[test]
    fn lumped_mass_is_half_the_element_mass() {
        let m = lumped_mass([0.0; 3], [0.25, 0.0, 0.0], &S);
        assert_relative_eq!(m, 0.5 * 2.5e-4 * 0.196 * 0.25, max_relative = 1e-15);
    }
}
