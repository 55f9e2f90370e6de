//! CBUSH: a spring of six stiffnesses K1..K6 (PBUSH) along the element's axes, at a
//! point of the line between its two grids (or from one grid to ground).
//!
//! The kernel works at the spring's point, in the element's axes: each end's six
//! local DOFs are its grid's motion carried rigidly to that point (the model builder's
//! [`super::Placement`] turns the grid's T1..R3 and adds θ × d for the arm d from the
//! grid to the point). With δ = u_B − u_A of those local DOFs (u_B = 0 for ground),
//! the forces are f = K δ (f_1..f_3 forces, f_4..f_6 moments, each K_i δ_i: MSC's
//! CBUSH forces, positive when B moves along the axis away from A), the strain energy
//! ½ δᵀ K δ and the stiffness [K −K; −K K] on (u_A, u_B): exact for any motion, so the
//! ledger books the spring's energy exactly. No mass. Viscous damping B1..B6 acts
//! alike on the rates: its damping matrix is [B −B; −B B].

use super::{Cell, Family, Kernel, LocalMatrix, Measure, Output, Recovered, Resultant};
use nalgebra::DMatrix;

/// A bushing between one or two grids.
#[derive(Debug, Clone, PartialEq)]
pub struct Bush {
    /// K1..K6, along and about the element's x, y, z.
    pub k: [f64; 6],
    /// B1..B6, viscous damping along and about the same axes.
    pub b: [f64; 6],
    /// Its grids' positions: GA's, then GB's when it has one (none: to ground).
    pub points: Vec<[f64; 3]>,
}

impl Bush {
    /// The block [X −X; −X X] of six values along and about the axes, over its ends
    /// (X alone for a grounded one).
    fn block(&self, x: &[f64; 6]) -> LocalMatrix {
        let ends = self.points.len();
        let at: Vec<(usize, usize)> = (0..ends).flat_map(|g| (0..6).map(move |c| (g, c))).collect();
        let n = at.len();
        let values = DMatrix::from_fn(n, n, |a, b| {
            let (c, d) = (a % 6, b % 6);
            match (c == d, a / 6 == b / 6) {
                (false, _) => 0.0,
                (true, true) => x[c],
                (true, false) => -x[c],
            }
        });
        LocalMatrix { at, values }
    }

    /// δ = u_B − u_A at the spring's point, in the element's axes.
    fn stretch(&self, ue: &[f64]) -> [f64; 6] {
        std::array::from_fn(|c| ue.get(6 + c).copied().unwrap_or(0.0) - ue[c])
    }
}

/// The force resultants a CBUSH recovers, in its axes.
const FORCES: [Resultant; 6] = [
    Resultant::Fx,
    Resultant::Fy,
    Resultant::Fz,
    Resultant::MomentX,
    Resultant::MomentY,
    Resultant::MomentZ,
];

impl Kernel for Bush {
    fn card(&self) -> &'static str {
        "CBUSH"
    }
    fn family(&self) -> Family<'_> {
        Family::Spring
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        vec![self.block(&self.k)]
    }
    fn damping(&self) -> Vec<LocalMatrix> {
        if self.b.iter().all(|&b| b == 0.0) {
            return Vec::new();
        }
        vec![self.block(&self.b)]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let d = self.stretch(ue);
        0.5 * (0..6).map(|c| self.k[c] * d[c] * d[c]).sum::<f64>()
    }
    fn recovered(&self, what: Output) -> Vec<Recovered> {
        match what {
            Output::Force => FORCES
                .iter()
                .map(|&r| Recovered {
                    measure: Measure::Force(r),
                    at: None,
                })
                .collect(),
            Output::Strain | Output::Stress => Vec::new(),
        }
    }
    fn recover(&self, ue: &[f64], what: Output) -> Vec<f64> {
        match what {
            Output::Force => {
                let d = self.stretch(ue);
                (0..6).map(|c| self.k[c] * d[c]).collect()
            }
            Output::Strain | Output::Stress => Vec::new(),
        }
    }
    fn material_law(&self, _strains: &[f64]) -> Option<Vec<f64>> {
        None
    }
    fn eq16_mass(&self) -> Option<f64> {
        None
    }
    fn points(&self) -> Vec<[f64; 3]> {
        self.points.clone()
    }
    fn cell(&self) -> Option<Cell> {
        Some(if self.points.len() == 2 {
            Cell::Line
        } else {
            Cell::Vertex
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: the bushing's energy is ½uᵀKu of its block [K −K; −K K], its forces
    /// K(u_B − u_A), and a grounded one's ½Σ K_i u_i². Exact.
    #[test]
    fn energy_is_its_blocks_quadratic_form() {
        let b = Bush {
            k: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            b: [0.0; 6],
            points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
        };
        let u: Vec<f64> = (0..12).map(|i| 0.1 * i as f64 - 0.4).collect();
        let k = &b.stiffness()[0];
        let uv = nalgebra::DVector::from_vec(u.clone());
        assert!((0.5 * uv.dot(&(&k.values * &uv)) - b.strain_energy(&u)).abs() < 1e-15);
        let forces: Vec<f64> = (0..6).map(|c| b.k[c] * (u[6 + c] - u[c])).collect();
        assert_eq!(b.recover(&u, Output::Force), forces);
        let g = Bush {
            points: vec![[0.0; 3]],
            ..b
        };
        let energy: f64 = (0..6).map(|c| 0.5 * g.k[c] * u[c] * u[c]).sum();
        assert_eq!(g.strain_energy(&u[..6]), energy);
        assert_eq!(g.cell(), Some(Cell::Vertex));
    }
}
