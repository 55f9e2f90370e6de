//! Scalar elements (CELAS1-4, CMASS1-4, CDAMP1-4): a spring, a mass or a viscous
//! damper between two DOFs, each a component of a grid (in its displacement frame)
//! or a scalar point, or between one DOF and ground.
//!
//! A spring of stiffness k: K = k [1 −1; −1 1] on (u₁, u₂), strain energy
//! ½k(u₁ − u₂)², force k(u₁ − u₂) (NASTRAN's ELFORCE of a CELAS, positive in
//! tension). A mass m: M = m [1 −1; −1 1] on the same pair, as NASTRAN's CMASS
//! ("a scalar mass ... between two points": its kinetic energy ½m(u̇₁ − u̇₂)²); one
//! grounded terminal leaves the 1×1 block k or m on the other. A damper of
//! coefficient b: C = b [1 −1; −1 1], its force b(u̇₁ − u̇₂). Exact for any motion
//! (no discretisation), so the ledger books the spring's energy and the mass's
//! kinetic energy exactly.

use super::{Cell, Family, Kernel, LocalMatrix, Measure, Output, Recovered, Resultant};
use nalgebra::DMatrix;

/// The cards of the scalar elements.
pub const CARDS: [&str; 12] = [
    "CELAS1", "CELAS2", "CELAS3", "CELAS4", "CMASS1", "CMASS2", "CMASS3", "CMASS4", "CDAMP1", "CDAMP2", "CDAMP3",
    "CDAMP4",
];

/// The static name of a scalar element's card (`CELAS2`), from its card's name.
pub fn card_name(card: &str) -> &'static str {
    CARDS.iter().find(|c| **c == card).copied().unwrap_or("CELAS")
}

/// Spring, mass or damper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScalarKind {
    /// A spring of this stiffness.
    Spring(f64),
    /// A mass.
    Mass(f64),
    /// A viscous damper of this coefficient.
    Damper(f64),
}

/// A scalar element over one or two terminals.
#[derive(Debug, Clone, PartialEq)]
pub struct Scalar {
    /// Its card (CELAS1 ... CMASS4).
    pub card: &'static str,
    /// Spring or mass, and its value.
    pub kind: ScalarKind,
    /// The local DOF of each terminal: (terminal index, component 0..6; 0 for a
    /// scalar point).
    pub slots: Vec<(usize, usize)>,
    /// The terminals' positions (a scalar point has none: `None`).
    pub points: Vec<Option<[f64; 3]>>,
}

impl Scalar {
    /// The 1×1 or 2×2 block of value `v` over the terminals.
    fn block(&self, v: f64) -> LocalMatrix {
        let n = self.slots.len();
        LocalMatrix {
            at: self.slots.clone(),
            values: DMatrix::from_fn(n, n, |a, b| if a == b { v } else { -v }),
        }
    }

    /// u₁ − u₂ (u₁ with one terminal) from the local displacements.
    fn stretch(&self, ue: &[f64]) -> f64 {
        let u = |k: usize| self.slots.get(k).map(|&(t, c)| ue[6 * t + c]).unwrap_or(0.0);
        u(0) - u(1)
    }
}

impl Kernel for Scalar {
    fn card(&self) -> &'static str {
        self.card
    }
    fn family(&self) -> Family<'_> {
        Family::Scalar
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        match self.kind {
            ScalarKind::Spring(k) => vec![self.block(k)],
            ScalarKind::Mass(_) | ScalarKind::Damper(_) => Vec::new(),
        }
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        match self.kind {
            ScalarKind::Mass(m) => vec![self.block(m)],
            ScalarKind::Spring(_) | ScalarKind::Damper(_) => Vec::new(),
        }
    }
    fn damping(&self) -> Vec<LocalMatrix> {
        match self.kind {
            ScalarKind::Damper(b) => vec![self.block(b)],
            ScalarKind::Spring(_) | ScalarKind::Mass(_) => Vec::new(),
        }
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        match self.kind {
            ScalarKind::Spring(k) => 0.5 * k * self.stretch(ue).powi(2),
            ScalarKind::Mass(_) | ScalarKind::Damper(_) => 0.0,
        }
    }
    fn recovered(&self, what: Output) -> Vec<Recovered> {
        match (self.kind, what) {
            (ScalarKind::Spring(_), Output::Force) => vec![Recovered {
                measure: Measure::Force(Resultant::Axial),
                at: None,
            }],
            _ => Vec::new(),
        }
    }
    fn recover(&self, ue: &[f64], what: Output) -> Vec<f64> {
        match (self.kind, what) {
            (ScalarKind::Spring(k), Output::Force) => vec![k * self.stretch(ue)],
            _ => Vec::new(),
        }
    }
    fn material_law(&self, _strains: &[f64]) -> Option<Vec<f64>> {
        None
    }
    fn eq16_mass(&self) -> Option<f64> {
        None
    }
    fn points(&self) -> Vec<[f64; 3]> {
        self.points.iter().map(|p| p.unwrap_or_default()).collect()
    }
    fn cell(&self) -> Option<Cell> {
        match (self.points.as_slice(), self.kind) {
            ([Some(_), Some(_)], _) => Some(Cell::Line),
            ([Some(_)], ScalarKind::Mass(_)) => Some(Cell::Vertex),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: a spring between two grid components and one to ground store ½k(u₁−u₂)²
    /// and ½ku₁², the energy of their stiffness blocks, exactly.
    #[test]
    fn spring_energy_is_its_blocks_quadratic_form() {
        let s = Scalar {
            card: "CELAS2",
            kind: ScalarKind::Spring(3.0),
            slots: vec![(0, 2), (1, 0)],
            points: vec![Some([0.0; 3]), Some([1.0, 0.0, 0.0])],
        };
        let mut ue = [0.0; 12];
        ue[2] = 0.5;
        ue[6] = -0.25;
        assert_eq!(s.strain_energy(&ue), 0.5 * 3.0 * 0.75f64.powi(2));
        assert_eq!(s.recover(&ue, Output::Force), [3.0 * 0.75]);
        let k = &s.stiffness()[0];
        let u = nalgebra::DVector::from_vec(vec![0.5, -0.25]);
        assert_eq!(0.5 * u.dot(&(&k.values * &u)), s.strain_energy(&ue));
        let grounded = Scalar {
            slots: vec![(0, 0)],
            points: vec![None],
            ..s
        };
        assert_eq!(grounded.strain_energy(&[2.0, 0.0, 0.0, 0.0, 0.0, 0.0]), 6.0);
        assert_eq!(grounded.cell(), None);
    }
}
