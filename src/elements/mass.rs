//! CONM2: concentrated mass at a grid, in the basic system, without offset.
//! Mass on the three translations; the inertia matrix [I11 −I21 −I31; …] on the
//! rotations (NASTRAN's sign convention for products of inertia). No stiffness, no
//! strain energy, nothing recovered; drawn as a vertex in field output.

/// Rotational inertia matrix from (I11, I21, I22, I31, I32, I33).
pub fn inertia_matrix(i: [f64; 6]) -> [[f64; 3]; 3] {
    let [i11, i21, i22, i31, i32, i33] = i;
    [[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]]
}

use super::{Cell, Kernel, LocalMatrix, Recovered};
use nalgebra::DMatrix;

/// A CONM2 at a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMass {
    /// Location of the grid.
    pub x: [f64; 3],
    /// The mass, on each translation.
    pub mass: f64,
    /// (I11, I21, I22, I31, I32, I33).
    pub inertia: [f64; 6],
}

impl Kernel for PointMass {
    fn card(&self) -> &'static str {
        "CONM2"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Point { mass: self.mass }
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        let j = inertia_matrix(self.inertia);
        vec![
            LocalMatrix::diagonal((0..3).map(|c| ((0, c), self.mass))),
            LocalMatrix {
                at: (3..6).map(|c| (0, c)).collect(),
                values: DMatrix::from_fn(3, 3, |a, b| j[a][b]),
            },
        ]
    }
    fn strain_energy(&self, _ue: &[f64]) -> f64 {
        0.0
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
    fn cell(&self) -> Option<Cell> {
        Some(Cell::Vertex)
    }
}
