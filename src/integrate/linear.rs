//! Sparse Cholesky of the constant effective matrix: factorised once, solved every
//! step without allocating (faer's supernodal LLᵀ with AMD ordering, workspace kept).

use super::SolveError;
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
    pub factor_time: Duration,
    pub solve_time: Duration,
    pub solves: usize,
}

impl Factor {
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
}
