//! The support of a grid's drilling rotation: a shell has no stiffness about its own
//! normal (NASTRAN's QUAD4 and TRIA3 neither, with PARAM K6ROT 0), so where the shells
//! at a grid all lie in one plane, the grid's rotation about their common normal is
//! stiffened by nothing.
//!
//! A flat shell in the basic XY plane leaves R3 without stiffness, and that DOF is
//! then dropped as inert or constrained by the deck (the paper's GRDSET PS 6). Out of
//! the XY plane the unstiffened direction is no one component, so the model gives each
//! such grid a spring along it, as NASTRAN's grid-point singularity processing
//! (AUTOSPC) constrains it when it is one component: the grid's 3×3 rotational
//! stiffness (summed over its shells, in its displacement frame) is split into
//! eigenpairs, and every direction whose stiffness is below [`SINGULAR`] times the
//! largest gets a spring of [`SPRING`] times the largest along it.
//!
//! Nothing the shells compute depends on that spring: in a flat region the drilling
//! rotation is coupled to no other DOF (membrane and bending leave it out), so it
//! stays zero whatever holds it; the spring only makes the system nonsingular. Its
//! stored energy is booked like any element's (`tests/shells_3d.rs` shows it is zero
//! on a turned plate and that a thousandfold spring changes no result beyond round-off
//! on a curved panel near the flat limit).

use super::{Kernel, LocalMatrix, Recovered};
use nalgebra::{DMatrix, Matrix3};

/// A direction of a grid's rotational stiffness below this fraction of the largest
/// is unstiffened: NASTRAN's default singularity ratio for grid-point singularity
/// processing (PARAM EPZERO, 1e-8).
pub const SINGULAR: f64 = 1e-8;

/// The drilling spring as a fraction of the grid's largest rotational stiffness.
pub const SPRING: f64 = 1e-6;

/// A spring on a grid's rotations, `k` over (R1, R2, R3) in its displacement frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Drill {
    /// The grid's basic position.
    pub x: [f64; 3],
    /// The spring's stiffness over R1, R2, R3.
    pub k: Matrix3<f64>,
}

impl Drill {
    /// The spring a grid needs for its summed rotational stiffness `k` (in its
    /// displacement frame), or `None` when every direction is stiffened.
    pub fn for_rotations(x: [f64; 3], k: &Matrix3<f64>) -> Option<Self> {
        let eig = crate::numerics::symmetric_eigen(*k);
        let largest = eig.eigenvalues.amax();
        if largest.is_nan() || largest <= 0.0 {
            return None;
        }
        let mut spring = Matrix3::zeros();
        for (i, &l) in eig.eigenvalues.iter().enumerate() {
            if l < SINGULAR * largest {
                let v = eig.eigenvectors.column(i);
                spring += v * v.transpose() * (SPRING * largest);
            }
        }
        (spring != Matrix3::zeros()).then_some(Drill { x, k: spring })
    }
}

impl Kernel for Drill {
    fn card(&self) -> &'static str {
        "drilling support"
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix {
            at: (3..6).map(|c| (0, c)).collect(),
            values: DMatrix::from_fn(3, 3, |i, j| self.k[(i, j)]),
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let t = nalgebra::Vector3::new(ue[3], ue[4], ue[5]);
        0.5 * (t.transpose() * self.k * t)[0]
    }
    fn recovered(&self, _what: super::Output) -> Vec<Recovered> {
        Vec::new()
    }
    fn recover(&self, _ue: &[f64], _what: super::Output) -> Vec<f64> {
        Vec::new()
    }
    fn material_law(&self, _strains: &[f64]) -> Option<Vec<f64>> {
        None
    }
    fn eq16_mass(&self) -> Option<f64> {
        None
    }
    fn points(&self) -> Vec<[f64; 3]> {
        vec![self.x]
    }
    fn cell(&self) -> Option<super::Cell> {
        None
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Support
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: the spring goes exactly where the rotations are unstiffened. Reference: a
    /// rotational stiffness diag(a, b, 0) turned by R has its null direction along R's
    /// third column; a full-rank one needs none. Tolerance: round-off of the
    /// eigen-solver.
    #[test]
    fn the_spring_acts_along_the_unstiffened_direction_only() {
        let r = nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1).into_inner();
        let k = r * Matrix3::from_diagonal(&nalgebra::Vector3::new(4.0, 2.5, 0.0)) * r.transpose();
        let d = Drill::for_rotations([0.0; 3], &k).unwrap();
        let n = r.column(2);
        let expected = n * n.transpose() * (SPRING * 4.0);
        assert!((d.k - expected).norm() < 1e-14 * 4.0, "{} vs {expected}", d.k);
        let full = r * Matrix3::from_diagonal(&nalgebra::Vector3::new(4.0, 2.5, 1e-3)) * r.transpose();
        assert!(Drill::for_rotations([0.0; 3], &full).is_none());
    }
}
