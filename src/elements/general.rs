//! GENEL: NASTRAN's general element, a stiffness the deck gives as a matrix over a list
//! of DOFs (grid components in their displacement frames, or scalar points).
//!
//! With the independent DOFs {uᵢ} (m of them) and the dependent {u_d} (n, possibly
//! none), the element's stiffness is (`manual/BULK.TXT`, GENEL)
//!
//! ```text
//! [ fᵢ ]   [   K     −K S  ] [ uᵢ ]
//! [ f_d ] = [ −SᵀK   SᵀK S ] [ u_d ]
//! ```
//!
//! K given, or the inverse of the flexibility Z (the flexibility approach,
//! uᵢ = Z fᵢ + S u_d, f_d = −Sᵀ fᵢ, is the same element). \[S\] carries {u_d}'s rigid
//! motion to {uᵢ}, so that the element is free in every rigid motion {u_d} can express:
//! given on the card, or computed from the grids' positions (S = Rᵢ R_d⁺, R the rigid
//! motions about the first dependent grid read at each DOF; R_d⁺ = R_dᵀ(R_d R_dᵀ)⁻¹,
//! R_d⁻¹ when {u_d} has the six DOFs the manual asks for, and the rigid motions {u_d}
//! spans when it has fewer, as a planar model's three). No mass; no recovered values
//! (NASTRAN prints none for it); strain energy ½uᵀKu, exact.

use super::{Family, Kernel, LocalMatrix, Output, Recovered};
use nalgebra::{DMatrix, DVector, Matrix3};

/// A general element.
#[derive(Debug, Clone, PartialEq)]
pub struct General {
    /// The local DOF of each row and column of `k`: (point index, component 0..6; 0
    /// for a scalar point).
    pub slots: Vec<(usize, usize)>,
    /// The stiffness over {uᵢ, u_d}.
    pub k: DMatrix<f64>,
    /// The points' positions (a scalar point has none).
    pub points: Vec<Option<[f64; 3]>>,
}

/// Why a GENEL's matrices make no element.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeneralError {
    /// Z is singular: no stiffness inverts it.
    #[error("its flexibility matrix Z is singular: no stiffness inverts it")]
    SingularFlexibility,
    /// The dependent DOFs do not fix the rigid motions they are to carry.
    #[error("its UD list does not fix the rigid motions [S] is to carry (R_d R_dᵀ is singular): give [S] on the card")]
    DependentRank,
}

/// The symmetric m × m matrix of a lower triangle given by columns from the diagonal.
pub fn from_lower(m: usize, lower: &[f64]) -> DMatrix<f64> {
    let mut a = DMatrix::zeros(m, m);
    let mut k = 0;
    for c in 0..m {
        for r in c..m {
            a[(r, c)] = lower[k];
            a[(c, r)] = lower[k];
            k += 1;
        }
    }
    a
}

/// The rigid motion read at one DOF of a grid at `x` displaced in frame `t` (columns:
/// its axes in basic), component `c` 1..6, about `x0`: the row of the six rigid
/// motions (translations, then rotations about `x0`, basic) it sees.
pub fn rigid_row(x: [f64; 3], t: &Matrix3<f64>, c: usize, x0: [f64; 3]) -> [f64; 6] {
    let axis = t.column((c - 1) % 3).into_owned();
    let mut row = [0.0; 6];
    if c <= 3 {
        // u = a + θ × d: the translation's axis sees a·axis and θ·(d × axis).
        let d = nalgebra::Vector3::from(x) - nalgebra::Vector3::from(x0);
        let arm = d.cross(&axis);
        row[..3].copy_from_slice(axis.as_slice());
        row[3..].copy_from_slice(arm.as_slice());
    } else {
        row[3..].copy_from_slice(axis.as_slice());
    }
    row
}

/// \[S\] from the rigid motions seen at {uᵢ} (rows of `ri`) and {u_d} (rows of `rd`).
pub fn rigid_s(ri: &DMatrix<f64>, rd: &DMatrix<f64>) -> Result<DMatrix<f64>, GeneralError> {
    let gram = rd * rd.transpose();
    let inv = gram.try_inverse().ok_or(GeneralError::DependentRank)?;
    Ok(ri * rd.transpose() * inv)
}

impl General {
    /// The element of independent stiffness `k` (m × m) and \[S\] (m × n), its DOFs
    /// `slots` ({uᵢ} then {u_d}).
    pub fn new(
        slots: Vec<(usize, usize)>,
        k: DMatrix<f64>,
        s: Option<DMatrix<f64>>,
        points: Vec<Option<[f64; 3]>>,
    ) -> Self {
        let full = match s {
            None => k,
            Some(s) => {
                let (m, n) = (k.nrows(), s.ncols());
                let ks = &k * &s;
                let mut full = DMatrix::zeros(m + n, m + n);
                full.view_mut((0, 0), (m, m)).copy_from(&k);
                full.view_mut((0, m), (m, n)).copy_from(&(-&ks));
                full.view_mut((m, 0), (n, m)).copy_from(&(-ks.transpose()));
                full.view_mut((m, m), (n, n)).copy_from(&(s.transpose() * &ks));
                full
            }
        };
        General { slots, k: full, points }
    }

    /// The stiffness of a flexibility Z.
    pub fn stiffness_of_flexibility(z: DMatrix<f64>) -> Result<DMatrix<f64>, GeneralError> {
        let k = z
            .cholesky()
            .map(|c| c.inverse())
            .ok_or(GeneralError::SingularFlexibility)?;
        Ok(k)
    }

    fn local(&self, ue: &[f64]) -> DVector<f64> {
        DVector::from_iterator(self.slots.len(), self.slots.iter().map(|&(p, c)| ue[6 * p + c]))
    }
}

impl Kernel for General {
    fn card(&self) -> &'static str {
        "GENEL"
    }
    fn family(&self) -> Family<'_> {
        Family::General
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix {
            at: self.slots.clone(),
            values: self.k.clone(),
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let u = self.local(ue);
        0.5 * u.dot(&(&self.k * &u))
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
        self.points.iter().map(|p| p.unwrap_or_default()).collect()
    }
    fn cell(&self) -> Option<super::Cell> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// A cantilever's tip flexibility in the plane (u, v, θz) of length `l`, EA, EI.
    fn tip_flexibility(l: f64, ea: f64, ei: f64) -> DMatrix<f64> {
        DMatrix::from_row_slice(
            3,
            3,
            &[
                l / ea,
                0.0,
                0.0,
                0.0,
                l.powi(3) / (3.0 * ei),
                l * l / (2.0 * ei),
                0.0,
                l * l / (2.0 * ei),
                l / ei,
            ],
        )
    }

    /// Goal: the flexibility approach with the computed \[S\] is the beam element: a
    /// planar beam of length 1 (EA = 6, EI = 0.5, the demonstration deck d01141a's)
    /// given as Z at its end B (its tip flexibility when A is held) with {u_d} = A's
    /// (T1, T2, R3) and \[S\] from the grids' positions. Reference: the Euler-Bernoulli
    /// beam's stiffness, EA/L, 12EI/L³, 6EI/L², 4EI/L, 2EI/L. Tolerance: 1e-12.
    #[test]
    fn a_flexibility_genel_with_computed_s_is_the_beam() {
        let (l, ea, ei) = (1.0, 6.0, 0.5);
        let k = General::stiffness_of_flexibility(tip_flexibility(l, ea, ei)).unwrap();
        let (xb, xa) = ([l, 0.0, 0.0], [0.0, 0.0, 0.0]);
        let t = Matrix3::identity();
        let rows =
            |x, cs: [usize; 3]| DMatrix::from_row_iterator(3, 6, cs.iter().flat_map(|&c| rigid_row(x, &t, c, xa)));
        let s = rigid_s(&rows(xb, [1, 2, 6]), &rows(xa, [1, 2, 6])).unwrap();
        assert_relative_eq!(
            s,
            DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.0, 1.0, l, 0.0, 0.0, 1.0]),
            epsilon = 1e-15
        );
        let e = General::new(
            (0..6).map(|i| (i / 3, i % 3)).collect(),
            k,
            Some(s),
            vec![Some(xb), Some(xa)],
        );
        // Rows and columns: B (u, v, θ) then A (u, v, θ).
        let (a, b12, b6, b4, b2) = (
            ea / l,
            12.0 * ei / l.powi(3),
            6.0 * ei / l / l,
            4.0 * ei / l,
            2.0 * ei / l,
        );
        let beam = DMatrix::from_row_slice(
            6,
            6,
            &[
                a, 0.0, 0.0, -a, 0.0, 0.0, //
                0.0, b12, -b6, 0.0, -b12, -b6, //
                0.0, -b6, b4, 0.0, b6, b2, //
                -a, 0.0, 0.0, a, 0.0, 0.0, //
                0.0, -b12, b6, 0.0, b12, b6, //
                0.0, -b6, b2, 0.0, b6, b4,
            ],
        );
        assert_relative_eq!(e.k, beam, epsilon = 1e-12);
    }

    /// Goal: the element is free in the rigid motions of its dependent DOFs and its
    /// energy is ½uᵀKu. Model: the beam above, moved as a rigid body (u = 0.3, v = −0.2,
    /// θ = 0.1 about A), then bent. Reference: zero energy; ½uᵀKu of the bent state.
    #[test]
    fn rigid_motion_costs_nothing() {
        let k = General::stiffness_of_flexibility(tip_flexibility(2.0, 6.0, 0.5)).unwrap();
        let s = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0, 1.0]);
        let e = General::new(
            vec![(0, 0), (0, 1), (0, 5), (1, 0), (1, 1), (1, 5)],
            k,
            Some(s),
            vec![None, None],
        );
        let mut ue = vec![0.0; 12];
        let (u, v, th) = (0.3, -0.2, 0.1);
        ue[6] = u;
        ue[7] = v;
        ue[11] = th;
        ue[0] = u;
        ue[1] = v + 2.0 * th;
        ue[5] = th;
        assert!(e.strain_energy(&ue).abs() < 1e-14);
        ue[1] += 0.01;
        let x = e.local(&ue);
        assert_relative_eq!(e.strain_energy(&ue), 0.5 * x.dot(&(&e.k * &x)), max_relative = 1e-14);
        assert!(e.strain_energy(&ue) > 0.0);
    }

    /// Goal: the lower triangle by columns fills the symmetric matrix in the manual's
    /// order (KZ11, KZ21, KZ31, KZ22, KZ32, KZ33).
    #[test]
    fn the_lower_triangle_reads_by_columns() {
        let a = from_lower(3, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        assert_eq!(
            a,
            DMatrix::from_row_slice(3, 3, &[1.0, 2.0, 3.0, 2.0, 4.0, 5.0, 3.0, 5.0, 6.0])
        );
    }
}
