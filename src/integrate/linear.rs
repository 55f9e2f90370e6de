//! Sparse Cholesky of the constant effective matrix: factorised once, solved every
//! step without allocating (faer's supernodal LLᵀ with AMD ordering, workspace kept).

use super::SolveError;
use crate::assembly::{Combination, System};
use crate::model::DofLabel;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::LltError;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::SparseColMat;
use faer::{Conj, MatMut, Par, Side};
use std::time::{Duration, Instant};

/// A factorised symmetric positive definite matrix.
pub struct Factor {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    work: MemBuffer,
    /// Time spent factorising.
    pub factor_time: Duration,
    /// Time spent in solves.
    pub solve_time: Duration,
    /// Solves done.
    pub solves: usize,
}

impl Factor {
    /// Assembles the effective matrix a·M + b·C + c·K of `sys` and factorises it: a
    /// scheme's set-up, all of it counted as factorisation time.
    pub fn effective(sys: &System, x: Combination, labels: &[DofLabel]) -> Result<Self, SolveError> {
        let t0 = Instant::now();
        let mut factor = Factor::new(&sys.combine(x), labels)?;
        factor.factor_time = t0.elapsed();
        Ok(factor)
    }

    /// Factorises `a` (full symmetric storage; the lower triangle is read). A
    /// non-positive pivot is reported as a mechanism at the DOF it belongs to.
    pub fn new(a: &SparseColMat<usize, f64>, labels: &[DofLabel]) -> Result<Self, SolveError> {
        let t0 = Instant::now();
        // A DOF with nothing on its diagonal is a mechanism whatever the ordering.
        let n = a.nrows();
        let mut diag = vec![0.0; n];
        let ar = a.as_ref();
        for (j, d) in diag.iter_mut().enumerate() {
            for p in ar.symbolic().col_ptr()[j]..ar.symbolic().col_ptr()[j + 1] {
                if ar.symbolic().row_idx()[p] == j {
                    *d += ar.val()[p];
                }
            }
        }
        if let Some(i) = diag.iter().position(|&d| d <= 0.0) {
            return Err(SolveError::Mechanism {
                dof: labels[i].to_string(),
            });
        }
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| SolveError::Linear(format!("{e:?}")))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let mut buf = MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        let res = symbolic.factorize_numeric_llt(
            &mut values,
            a.as_ref(),
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut buf),
            Default::default(),
        );
        if let Err(e) = res {
            return Err(match e {
                LltError::NonPositivePivot { index } => {
                    // faer 0.24.4 reports the simplicial pivot 1-based and the
                    // supernodal one 0-based, both in the permuted ordering.
                    let index = match symbolic.raw() {
                        faer::sparse::linalg::cholesky::SymbolicCholeskyRaw::Simplicial(_) => index - 1,
                        faer::sparse::linalg::cholesky::SymbolicCholeskyRaw::Supernodal(_) => index,
                    };
                    let original = symbolic.perm().map(|p| p.arrays().0[index]).unwrap_or(index);
                    SolveError::Mechanism {
                        dof: labels[original].to_string(),
                    }
                }
            });
        }
        let work = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, par));
        Ok(Factor {
            symbolic,
            values,
            work,
            factor_time: t0.elapsed(),
            solve_time: Duration::ZERO,
            solves: 0,
        })
    }

    /// x ← A⁻¹ x
    pub fn solve_in_place(&mut self, x: &mut [f64]) {
        let t0 = Instant::now();
        let n = x.len();
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.work),
        );
        self.solves += 1;
        self.solve_time += t0.elapsed();
    }

    /// X ← A⁻¹ X for the columns of X at once, in two halves (the first ⌊k/2⌋ columns
    /// and the rest), the second on a second thread: each half reads the factor once
    /// for its columns, and two cores read it at once. The halves do not depend on the
    /// machine, nor so the round-off.
    pub fn solve_columns_in_place(&mut self, x: MatMut<'_, f64>) {
        let t0 = Instant::now();
        let k = x.ncols();
        let llt = LltRef::new(&self.symbolic, &self.values);
        let solve = |x: MatMut<'_, f64>| {
            let mut work = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(x.ncols(), Par::Seq));
            llt.solve_in_place_with_conj(Conj::No, x, Par::Seq, MemStack::new(&mut work));
        };
        if k >= 2 {
            let (a, b) = x.split_at_col_mut(k / 2);
            crate::numerics::both(|| solve(a), || solve(b));
        } else {
            solve(x);
        }
        self.solves += k;
        self.solve_time += t0.elapsed();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::Triplet;

    /// Goal: a singular block is reported at one of its own DOFs, whatever the fill-
    /// reducing ordering. Model: an arrow matrix (DOF 0 coupled to all) whose leaves
    /// 3..6 form a singular chain (a free-free spring chain with no mass); DOFs 0..3
    /// are positive definite. The failing pivot must name a DOF of the chain.
    #[test]
    fn non_positive_pivot_names_a_dof_of_the_singular_block() {
        let n = 7;
        let mut t = Vec::new();
        for i in 0..3 {
            t.push(Triplet::new(i, i, 10.0));
        }
        for i in 1..3 {
            t.push(Triplet::new(0, i, 1.0));
            t.push(Triplet::new(i, 0, 1.0));
        }
        for i in 3..6 {
            // spring between i and i+1
            for (a, b, v) in [(i, i, 1.0), (i + 1, i + 1, 1.0), (i, i + 1, -1.0), (i + 1, i, -1.0)] {
                t.push(Triplet::new(a, b, v));
            }
        }
        let a = SparseColMat::try_new_from_triplets(n, n, &t).unwrap();
        let labels: Vec<DofLabel> = (0..n)
            .map(|i| DofLabel {
                point: i as i64,
                comp: 1,
            })
            .collect();
        match Factor::new(&a, &labels) {
            Err(SolveError::Mechanism { dof }) => {
                assert!(
                    ["grid 3 T1", "grid 4 T1", "grid 5 T1", "grid 6 T1"].contains(&dof.as_str()),
                    "{dof}"
                )
            }
            _ => panic!("expected a mechanism"),
        }
    }
}
