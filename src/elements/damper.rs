//! CVISC: a viscous damper along the line of its two grids (PVISC: C1 extensional,
//! C2 rotational).
//!
//! With n the unit vector from G1 to G2 (basic axes), the damper's force is
//! C1·n·(n·(u̇₂ − u̇₁)) on the translations and its moment C2·n·(n·(θ̇₂ − θ̇₁)) on
//! the rotations: damping blocks [D −D; −D D] with D = C1·nnᵀ (translations) and
//! C2·nnᵀ (rotations), as a CROD's stiffness is formed with EA/L and GJ/L. No
//! stiffness, no mass, no recovered values; it dissipates ∫ u̇ᵀCu̇ dt, which the
//! schemes book.

use super::{Cell, Family, Kernel, LocalMatrix, Output, Recovered};
use nalgebra::{DMatrix, Vector3};

/// A viscous damper between two grids.
#[derive(Debug, Clone, PartialEq)]
pub struct Viscous {
    /// Its grids' positions (basic).
    pub x: [[f64; 3]; 2],
    /// C1: extensional damping.
    pub extension: f64,
    /// C2: rotational damping.
    pub rotation: f64,
}

impl Kernel for Viscous {
    fn card(&self) -> &'static str {
        "CVISC"
    }
    fn family(&self) -> Family<'_> {
        Family::Damper
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn damping(&self) -> Vec<LocalMatrix> {
        let n = (Vector3::from(self.x[1]) - Vector3::from(self.x[0])).normalize();
        let at: Vec<(usize, usize)> = (0..2).flat_map(|g| (0..6).map(move |c| (g, c))).collect();
        let values = DMatrix::from_fn(12, 12, |a, b| {
            let (ca, cb) = (a % 6, b % 6);
            if (ca < 3) != (cb < 3) {
                return 0.0;
            }
            let coefficient = if ca < 3 { self.extension } else { self.rotation };
            let sign = if a / 6 == b / 6 { 1.0 } else { -1.0 };
            sign * coefficient * n[ca % 3] * n[cb % 3]
        });
        vec![LocalMatrix { at, values }]
    }
    fn strain_energy(&self, _ue: &[f64]) -> f64 {
        0.0
    }
    fn recovered(&self, _what: Output) -> Vec<Recovered> {
        Vec::new()
    }
    fn recover(&self, _ue: &[f64], _what: Output) -> Vec<f64> {
        Vec::new()
    }
    fn material_law(&self, _strains: &[f64]) -> Option<Vec<f64>> {
        None
    }
    fn eq16_mass(&self) -> Option<f64> {
        None
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

    /// Goal: the damper dissipates only the rate of stretch along its line:
    /// u̇ᵀCu̇ = C1 (n·Δu̇)² + C2 (n·Δθ̇)², nothing for motion across the line or a
    /// rigid translation. Exact to round-off.
    #[test]
    fn dissipates_the_rate_of_stretch_along_its_line() {
        let d = Viscous {
            x: [[0.0; 3], [3.0, 4.0, 0.0]],
            extension: 2.0,
            rotation: 0.5,
        };
        let c = &d.damping()[0].values;
        let rate = |v: &[f64; 12]| {
            let v = nalgebra::DVector::from_row_slice(v);
            v.dot(&(c * &v))
        };
        let mut v = [0.0; 12];
        v[6] = 0.3;
        v[7] = 0.4;
        v[9] = 0.6;
        v[10] = 0.8;
        assert!((rate(&v) - (2.0 * 0.5f64.powi(2) + 0.5 * 1.0)).abs() < 1e-15);
        let across = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.4, 0.3, 0.7, 0.0, 0.0, 0.0];
        assert!(rate(&across).abs() < 1e-15);
        let rigid = [0.1, 0.2, 0.3, 0.0, 0.0, 0.0, 0.1, 0.2, 0.3, 0.0, 0.0, 0.0];
        assert!(rate(&rigid).abs() < 1e-15);
    }
}
