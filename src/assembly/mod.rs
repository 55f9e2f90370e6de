//! Assembly: element matrices scattered into global sparse matrices over the solved
//! DOFs (constrained DOFs are simply dropped: homogeneous SPCs).

mod reduce;

pub use reduce::drop_inert;

use crate::model::Model;
use faer::sparse::{SparseColMat, Triplet};

/// Global stiffness and mass as triplet lists (duplicates summed when compressed).
#[derive(Debug, Clone)]
pub struct System {
    /// Number of solved DOFs.
    pub n: usize,
    /// Stiffness entries (row, column, value) of every element.
    pub k: Vec<Triplet<usize, usize, f64>>,
    /// Mass entries (row, column, value) of every element.
    pub m: Vec<Triplet<usize, usize, f64>>,
    /// Compressed K and M, for products.
    pub k_csc: SparseColMat<usize, f64>,
    /// Compressed M.
    pub m_csc: SparseColMat<usize, f64>,
    /// The diagonal of M when M is diagonal (lumped masses, no rotary inertia coupling).
    pub m_lumped: Option<Vec<f64>>,
}

/// Assembles K and M of a model over its solved DOFs, element by element through
/// [`crate::elements::Element::scatter`]: no element kind is named here.
pub fn assemble(model: &Model) -> System {
    let n = model.n();
    let mut k = Vec::new();
    let mut m = Vec::new();
    for e in &model.elements {
        e.scatter(&mut k, &mut m);
    }
    let triplets = |v: Vec<(usize, usize, f64)>| -> Vec<Triplet<usize, usize, f64>> {
        v.into_iter().map(|(i, j, x)| Triplet::new(i, j, x)).collect()
    };
    let (k, m) = (triplets(k), triplets(m));
    let k_csc = SparseColMat::try_new_from_triplets(n, n, &k).expect("indices are in range");
    let m_csc = SparseColMat::try_new_from_triplets(n, n, &m).expect("indices are in range");
    let lumped = m.iter().all(|t| t.row == t.col || t.val == 0.0);
    let mut sys = System {
        m_lumped: None,
        n,
        k,
        m,
        k_csc,
        m_csc,
    };
    if lumped {
        sys.m_lumped = Some(sys.m_diag());
    }
    sys
}

impl System {
    /// a·M + b·K, compressed.
    pub fn combine(&self, a: f64, b: f64) -> SparseColMat<usize, f64> {
        let t: Vec<_> = self
            .m
            .iter()
            .map(|t| Triplet::new(t.row, t.col, a * t.val))
            .chain(self.k.iter().map(|t| Triplet::new(t.row, t.col, b * t.val)))
            .collect();
        SparseColMat::try_new_from_triplets(self.n, self.n, &t).expect("indices are in range")
    }

    /// y = K x
    pub fn k_mul(&self, x: &[f64], y: &mut [f64]) {
        mul(&self.k_csc, x, y);
    }

    /// y = M x
    pub fn m_mul(&self, x: &[f64], y: &mut [f64]) {
        match &self.m_lumped {
            Some(d) => y.iter_mut().zip(d.iter().zip(x)).for_each(|(y, (d, x))| *y = d * x),
            None => mul(&self.m_csc, x, y),
        }
    }

    /// Diagonal of M.
    pub fn m_diag(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n];
        for t in &self.m {
            if t.row == t.col {
                d[t.row] += t.val;
            }
        }
        d
    }

    /// Diagonal of K.
    pub fn k_diag(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n];
        for t in &self.k {
            if t.row == t.col {
                d[t.row] += t.val;
            }
        }
        d
    }
}

/// y = A x for a compressed sparse column matrix.
pub fn mul(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    y.iter_mut().for_each(|v| *v = 0.0);
    let a = a.as_ref();
    let cp = a.symbolic().col_ptr();
    let ri = a.symbolic().row_idx();
    let vals = a.val();
    for j in 0..a.ncols() {
        let xj = x[j];
        if xj == 0.0 {
            continue;
        }
        for p in cp[j]..cp[j + 1] {
            y[ri[p]] += vals[p] * xj;
        }
    }
}

/// The lowest `count` natural frequencies (rad/time) of a small model with lumped mass,
/// dense: the massless DOFs (a plate's rotations) condensed out statically, then the
/// symmetric eigenproblem M^(-1/2) K_c M^(-1/2) in the DOFs with mass. For verification
/// models of a few thousand DOFs; None when the massless block is singular.
pub fn lowest_frequencies(model: &Model, count: usize) -> Option<Vec<f64>> {
    use nalgebra::{DMatrix, DVector};
    let sys = assemble(model);
    let n = sys.n;
    let mut k = DMatrix::<f64>::zeros(n, n);
    for t in &sys.k {
        k[(t.row, t.col)] += t.val;
    }
    let mass = sys.m_diag();
    let w: Vec<usize> = (0..n).filter(|&i| mass[i] > 0.0).collect();
    let r: Vec<usize> = (0..n).filter(|&i| mass[i] <= 0.0).collect();
    let sub = |a: &[usize], b: &[usize]| DMatrix::from_fn(a.len(), b.len(), |i, j| k[(a[i], b[j])]);
    let krr = sub(&r, &r).cholesky()?;
    let kwr = sub(&w, &r);
    let kc = sub(&w, &w) - &kwr * krr.solve(&kwr.transpose());
    let s = DVector::from_iterator(w.len(), w.iter().map(|&i| 1.0 / mass[i].sqrt()));
    let a = DMatrix::from_fn(w.len(), w.len(), |i, j| s[i] * kc[(i, j)] * s[j]);
    let mut ev: Vec<f64> = a.symmetric_eigenvalues().iter().map(|l| l.max(0.0).sqrt()).collect();
    ev.sort_by(f64::total_cmp);
    ev.truncate(count);
    Some(ev)
}
