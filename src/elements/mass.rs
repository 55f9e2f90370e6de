//! Concentrated masses at a grid: CONM2 and CONM1. No stiffness, no strain energy,
//! nothing recovered; drawn as a vertex in field output.
//!
//! - CONM2, in the basic system, without offset (the model builder turns and offsets
//!   it): mass on the three translations; the inertia matrix [I11 −I21 −I31; …] on
//!   the rotations (NASTRAN's sign convention for products of inertia).
//! - CONM1: the card's 6×6 symmetric matrix over T1..R3, in its own axes (the model
//!   builder turns it from CID's axes to the grid's), as written: NASTRAN's theoretical
//!   manual puts no sign convention on it (`manual/INTR.TXT`: "The notation on the
//!   CONM1 card is explicit").

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

/// A CONM1 at a grid: a 6×6 symmetric mass matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct MassMatrix {
    /// Location of the grid.
    pub x: [f64; 3],
    /// The matrix over T1..R3.
    pub m: [[f64; 6]; 6],
}

impl MassMatrix {
    /// The matrix of a lower triangle given by rows (M11; M21, M22; … M66).
    pub fn from_lower(x: [f64; 3], lower: &[f64; 21]) -> Self {
        let mut m = [[0.0; 6]; 6];
        let by_rows = (0..6).flat_map(|r| (0..=r).map(move |c| (r, c)));
        for ((r, c), &v) in by_rows.zip(lower) {
            m[r][c] = v;
            m[c][r] = v;
        }
        MassMatrix { x, m }
    }
}

impl Kernel for MassMatrix {
    fn card(&self) -> &'static str {
        "CONM1"
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::MassMatrix
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix {
            at: (0..6).map(|c| (0, c)).collect(),
            values: DMatrix::from_fn(6, 6, |a, b| self.m[a][b]),
        }]
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
