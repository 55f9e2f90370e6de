//! Assembly: element matrices scattered into global sparse matrices over the solved
//! DOFs (constrained DOFs are simply dropped: homogeneous SPCs).

mod reduce;

pub use reduce::drop_inert;

use crate::model::Model;
use crate::numerics::{column, column_mut};
use faer::reborrow::ReborrowMut;
use faer::sparse::{SparseColMat, SparseRowMat, SymbolicSparseColMat, Triplet};
use faer::{MatMut, MatRef};

/// Global stiffness, mass and viscous damping as triplet lists (duplicates summed
/// when compressed).
#[derive(Debug, Clone)]
pub struct System {
    /// Number of solved DOFs.
    pub n: usize,
    /// Stiffness entries (row, column, value) of every element.
    pub k: Vec<Triplet<usize, usize, f64>>,
    /// Mass entries (row, column, value) of every element.
    pub m: Vec<Triplet<usize, usize, f64>>,
    /// Viscous damping entries (row, column, value): the damping elements' and the
    /// model's proportional damping ([`crate::model::Damping`]); empty for an
    /// undamped structure.
    pub c: Vec<Triplet<usize, usize, f64>>,
    /// C for products, when there is damping.
    c_lower: Option<LowerRows>,
    /// Compressed K, exactly symmetric: its upper triangle mirrors the lower, the
    /// triangle the factorisation reads (element matrices computed in floating point
    /// are symmetric only to round-off).
    pub k_csc: SparseColMat<usize, f64>,
    /// K for products.
    k_lower: LowerRows,
    /// M for products, where it is not lumped.
    m_lower: LowerRows,
    /// The diagonal of M when M is diagonal (lumped masses, no rotary inertia coupling, no coupled mass).
    pub m_lumped: Option<Vec<f64>>,
}

/// Assembles K, M and C of a model over its solved DOFs, element by element through
/// [`crate::elements::Element::scatter`] (no element kind is named here), C with the
/// model's proportional damping, C = Σ C_e + a₁M + a₂K ([`crate::model::Damping`]).
pub fn assemble(model: &Model) -> System {
    assembled(&model.elements, model.n(), model.damping.as_ref())
}

/// Assembles K, M and C of `elements` over `n` solved DOFs (a structure built alone,
/// [`crate::model::Structure`]): C is the damping elements' alone.
pub fn assemble_elements(elements: &[crate::elements::Element], n: usize) -> System {
    assembled(elements, n, None)
}

/// K, M and C of `elements`, C with the proportional damping `proportional` added.
fn assembled(elements: &[crate::elements::Element], n: usize, proportional: Option<&crate::model::Damping>) -> System {
    let mut k = Vec::new();
    let mut m = Vec::new();
    let mut c = Vec::new();
    for e in elements {
        e.scatter(&mut k, &mut m);
        e.scatter_damping(&mut c);
    }
    let triplets = |v: Vec<(usize, usize, f64)>| -> Vec<Triplet<usize, usize, f64>> {
        v.into_iter().map(|(i, j, x)| Triplet::new(i, j, x)).collect()
    };
    let mut sys = System::from_triplets(n, triplets(k), triplets(m));
    let mut c = triplets(c);
    if let Some(d) = proportional {
        for (of, a) in [(&sys.m, d.mass), (&sys.k, d.stiffness)] {
            if a != 0.0 {
                c.extend(scaled(of, a));
            }
        }
    }
    sys.set_damping(c);
    sys
}

/// The entries `v`, each times `a`.
fn scaled(v: &[Triplet<usize, usize, f64>], a: f64) -> impl Iterator<Item = Triplet<usize, usize, f64>> + '_ {
    v.iter().map(move |t| Triplet::new(t.row, t.col, a * t.val))
}

/// The coefficients of an effective matrix a·M + b·C + c·K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Combination {
    /// Of M.
    pub mass: f64,
    /// Of C (nothing when the system is undamped).
    pub damping: f64,
    /// Of K.
    pub stiffness: f64,
}

impl System {
    /// The system of these element entries over `n` DOFs.
    fn from_triplets(n: usize, k: Vec<Triplet<usize, usize, f64>>, m: Vec<Triplet<usize, usize, f64>>) -> System {
        let by_rows =
            |lower: &SparseColMat<usize, f64>| lower.to_row_major().expect("a transpose fits where the matrix did");
        let k_lower_by_columns = lower_triangle(n, &k);
        let k_lower_by_rows = by_rows(&k_lower_by_columns);
        let k_csc = mirrored(&k_lower_by_columns, &k_lower_by_rows);
        let k_lower = LowerRows::new(&k_lower_by_rows);
        let m_lower = LowerRows::new(&by_rows(&lower_triangle(n, &m)));
        let lumped = m.iter().all(|t| t.row == t.col || t.val == 0.0);
        let mut sys = System {
            m_lumped: None,
            n,
            k,
            m,
            c: Vec::new(),
            c_lower: None,
            k_csc,
            k_lower,
            m_lower,
        };
        if lumped {
            sys.m_lumped = Some(sys.m_diag());
        }
        sys
    }

    /// The system of symmetric K, M and C given by their entries (row, column,
    /// value), both triangles, as elements scatter theirs: a reduced model's, whose
    /// coordinates are not an element's (C empty when undamped).
    pub fn from_entries(
        n: usize,
        k: Vec<(usize, usize, f64)>,
        m: Vec<(usize, usize, f64)>,
        c: Vec<(usize, usize, f64)>,
    ) -> System {
        let triplets = |v: Vec<(usize, usize, f64)>| -> Vec<Triplet<usize, usize, f64>> {
            v.into_iter().map(|(i, j, x)| Triplet::new(i, j, x)).collect()
        };
        let mut sys = System::from_triplets(n, triplets(k), triplets(m));
        sys.set_damping(triplets(c));
        sys
    }

    /// Sets C from its entries (both triangles); an empty list (or one of zeros)
    /// leaves the system undamped.
    fn set_damping(&mut self, c: Vec<Triplet<usize, usize, f64>>) {
        if c.iter().all(|t| t.val == 0.0) {
            self.c = Vec::new();
            self.c_lower = None;
            return;
        }
        let lower = lower_triangle(self.n, &c);
        self.c_lower = Some(LowerRows::new(
            &lower.to_row_major().expect("a transpose fits where the matrix did"),
        ));
        self.c = c;
    }

    /// True when the system has viscous damping.
    pub fn damped(&self) -> bool {
        self.c_lower.is_some()
    }

    /// The system over the DOFs `map` keeps (`map[i]`: DOF i's new number, `None`
    /// to drop it), `n` of them: the element entries between kept DOFs, renumbered,
    /// in their order. The same entries, in the same order, as assembling the model
    /// with the dropped DOFs unsolved: so the same sums, to the bit.
    pub fn restricted(&self, map: &[Option<usize>], n: usize) -> System {
        let keep = |v: &[Triplet<usize, usize, f64>]| -> Vec<Triplet<usize, usize, f64>> {
            v.iter()
                .filter_map(|t| Some(Triplet::new(map[t.row]?, map[t.col]?, t.val)))
                .collect()
        };
        let mut sys = System::from_triplets(n, keep(&self.k), keep(&self.m));
        sys.set_damping(keep(&self.c));
        sys
    }

    /// a·M + b·C + c·K (the coefficients of `x`), compressed.
    pub fn combine(&self, x: Combination) -> SparseColMat<usize, f64> {
        let mut t: Vec<_> = scaled(&self.m, x.mass).collect();
        t.extend(scaled(&self.k, x.stiffness));
        if x.damping != 0.0 {
            t.extend(scaled(&self.c, x.damping));
        }
        compressed(self.n, &t, |_, _| true)
    }

    /// y = C x (zero when undamped).
    pub fn c_mul(&self, x: &[f64], y: &mut [f64]) {
        match &self.c_lower {
            Some(c) => c.mul(x, y),
            None => y.fill(0.0),
        }
    }

    /// xᵀ C x (zero when undamped), `work` a vector of n for C x.
    pub fn c_norm(&self, x: &[f64], work: &mut [f64]) -> f64 {
        if !self.damped() {
            return 0.0;
        }
        self.c_mul(x, work);
        crate::numerics::dot(x, work)
    }

    /// y = K x
    pub fn k_mul(&self, x: &[f64], y: &mut [f64]) {
        self.k_lower.mul(x, y);
    }

    /// Y = K X, X's columns at once; each column as [`System::k_mul`] makes it.
    pub fn k_mul_columns(&self, x: MatRef<'_, f64>, y: MatMut<'_, f64>) {
        self.k_lower.mul_columns(x, y);
    }

    /// Y = M X, X's columns at once; each column as [`System::m_mul`] makes it.
    pub fn m_mul_columns(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        match &self.m_lumped {
            Some(_) => (0..x.ncols()).for_each(|c| self.m_mul(column(x, c), column_mut(y.rb_mut(), c))),
            None => self.m_lower.mul_columns(x, y),
        }
    }

    /// Y = C X, X's columns at once; each column as [`System::c_mul`] makes it.
    pub fn c_mul_columns(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        match &self.c_lower {
            Some(c) => c.mul_columns(x, y),
            None => y.fill(0.0),
        }
    }

    /// y = M x
    pub fn m_mul(&self, x: &[f64], y: &mut [f64]) {
        match &self.m_lumped {
            Some(d) => y.iter_mut().zip(d.iter().zip(x)).for_each(|(y, (d, x))| *y = d * x),
            None => self.m_lower.mul(x, y),
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

/// The lower triangle (row ≥ column) of the summed triplets `t`, compressed: the
/// whole matrix compressed first, so that each entry is summed as in it.
fn lower_triangle(n: usize, t: &[Triplet<usize, usize, f64>]) -> SparseColMat<usize, f64> {
    compressed(n, t, |row, col| row >= col)
}

/// The summed triplets `t` over n × n, compressed, the entries `keep` keeps: faer's
/// `SparseColMat::try_new_from_triplets` to the bit, and faster. Its order of the
/// sums is kept (each column's entries taken in input order and sorted by row with
/// the same unstable sort of the same indices, its duplicates summed in the sorted
/// order), since a sum of three or more entries depends on it; but each column's rows
/// and values are gathered next to each other first, so that its sort reads them in
/// cache, where faer's reads every key from the whole list, and the columns are sorted
/// in two halves, each on its own core. (On the 199 × 199 panel's 23 million stiffness
/// entries the assembly took 1.7 s against 2.2 s, and the structure's restricted system
/// 0.9 s against 1.8 s.)
fn compressed(
    n: usize,
    t: &[Triplet<usize, usize, f64>],
    keep: impl Fn(usize, usize) -> bool + Sync,
) -> SparseColMat<usize, f64> {
    let mut start = vec![0usize; n + 1];
    for e in t {
        assert!(e.row < n && e.col < n, "entry ({}, {}) outside {n} × {n}", e.row, e.col);
        start[e.col + 1] += 1;
    }
    for j in 0..n {
        start[j + 1] += start[j];
    }
    let (mut rows, mut vals) = (vec![0usize; t.len()], vec![0.0f64; t.len()]);
    let mut next = start.clone();
    for e in t {
        let at = &mut next[e.col];
        rows[*at] = e.row;
        vals[*at] = e.val;
        *at += 1;
    }
    // Columns [a, b): their kept rows and summed values, each column's count.
    let columns = |a: usize, b: usize| {
        let (mut idx, mut val, mut count) = (Vec::new(), Vec::new(), Vec::with_capacity(b - a));
        let mut order: Vec<usize> = Vec::new();
        for j in a..b {
            let (r, v) = (&rows[start[j]..start[j + 1]], &vals[start[j]..start[j + 1]]);
            order.clear();
            order.extend(0..r.len());
            order.sort_unstable_by_key(|&p| r[p]);
            let before = idx.len();
            let mut prev = usize::MAX;
            for &p in &order {
                if r[p] == prev {
                    if let Some(last) = val.last_mut().filter(|_| keep(prev, j)) {
                        *last += v[p];
                    }
                    continue;
                }
                prev = r[p];
                if keep(prev, j) {
                    idx.push(prev);
                    val.push(v[p]);
                }
            }
            count.push(idx.len() - before);
        }
        (idx, val, count)
    };
    let half = n / 2;
    let ((mut idx, mut val, mut count), (idx_b, val_b, count_b)) =
        crate::numerics::both(|| columns(0, half), || columns(half, n));
    idx.extend(idx_b);
    val.extend(val_b);
    count.extend(count_b);
    let mut ptr = Vec::with_capacity(n + 1);
    ptr.push(0);
    for c in count {
        ptr.push(ptr.last().copied().unwrap_or(0) + c);
    }
    SparseColMat::new(SymbolicSparseColMat::new_checked(n, n, ptr, None, idx), val)
}

/// The symmetric matrix whose lower triangle is `lower`, given by columns and by
/// rows: its column j is the lower triangle's row j (rows up to the diagonal) followed
/// by the lower triangle's column j below the diagonal, both already sorted.
fn mirrored(lower: &SparseColMat<usize, f64>, lower_rows: &SparseRowMat<usize, f64>) -> SparseColMat<usize, f64> {
    let (cp, ri, cv) = (lower.symbolic().col_ptr(), lower.symbolic().row_idx(), lower.val());
    let (rp, ci, rv) = (
        lower_rows.symbolic().row_ptr(),
        lower_rows.symbolic().col_idx(),
        lower_rows.val(),
    );
    let n = lower.ncols();
    let (mut ptr, mut idx, mut val) = (vec![0], Vec::new(), Vec::new());
    for j in 0..n {
        idx.extend_from_slice(&ci[rp[j]..rp[j + 1]]);
        val.extend_from_slice(&rv[rp[j]..rp[j + 1]]);
        for p in (cp[j]..cp[j + 1]).filter(|&p| ri[p] > j) {
            idx.push(ri[p]);
            val.push(cv[p]);
        }
        ptr.push(idx.len());
    }
    SparseColMat::new(SymbolicSparseColMat::new_checked(n, n, ptr, None, idx), val)
}

/// A symmetric sparse matrix for y = A x, stored as its lower triangle by rows: half
/// the values, and each column as its distance left of the diagonal in 16 bits where
/// the matrix's band allows (32-bit columns otherwise): a quarter of the bytes of the
/// whole matrix, which is what a product costs once the factor's solves have pushed
/// the matrix out of cache (on the plate, caches flushed between products: 0.15 ms,
/// 3.8× faster than the whole matrix scattered by columns).
#[derive(Debug, Clone)]
struct LowerRows {
    row_ptr: Vec<usize>,
    columns: Columns,
    val: Vec<f64>,
}

/// The column of each stored entry of a [`LowerRows`].
#[derive(Debug, Clone)]
enum Columns {
    /// i − j, for a band narrower than 2¹⁶.
    Band(Vec<u16>),
    /// j.
    Wide(Vec<u32>),
}

impl LowerRows {
    /// The symmetric matrix whose lower triangle, by rows, is `lower`.
    fn new(lower: &SparseRowMat<usize, f64>) -> LowerRows {
        let (row_ptr, ci) = (lower.symbolic().row_ptr().to_vec(), lower.symbolic().col_idx());
        let cols: Vec<(usize, usize)> = (0..lower.nrows())
            .flat_map(|i| ci[row_ptr[i]..row_ptr[i + 1]].iter().map(move |&j| (i, j)))
            .collect();
        let val = lower.val().to_vec();
        let columns = match cols.iter().map(|&(i, j)| u16::try_from(i - j)).collect() {
            Ok(band) => Columns::Band(band),
            Err(_) => Columns::Wide(
                cols.iter()
                    .map(|&(_, j)| u32::try_from(j).expect("fewer than 2³² DOFs (the memory check refuses far fewer)"))
                    .collect(),
            ),
        };
        LowerRows { row_ptr, columns, val }
    }

    /// y = A x. Row i adds a_ij x_j (j ≤ i) into y_i and a_ij x_i into y_j (j < i), so
    /// each y_i is summed in column order, as a product row by row over the whole
    /// matrix would sum it: the same round-off.
    fn mul(&self, x: &[f64], y: &mut [f64]) {
        match &self.columns {
            Columns::Band(d) => self.mul_by(d, |i, d| i - d as usize, x, y),
            Columns::Wide(c) => self.mul_by(c, |_, j| j as usize, x, y),
        }
    }

    /// Y = A X: [`LowerRows::mul`] for eight columns at a time, the entries read
    /// once for the eight and the eight columns' terms of a row side by side (so that
    /// one entry's eight products are one vector operation); each column's sums in
    /// `mul`'s order (the same round-off).
    fn mul_columns(&self, x: MatRef<'_, f64>, mut y: MatMut<'_, f64>) {
        let n = x.nrows();
        let (mut xs, mut ys) = (vec![[0.0; 8]; n], vec![[0.0; 8]; n]);
        for first in (0..x.ncols()).step_by(8) {
            let width = 8.min(x.ncols() - first);
            for k in 0..width {
                for (row, &v) in xs.iter_mut().zip(column(x, first + k)) {
                    row[k] = v;
                }
            }
            for row in xs.iter_mut() {
                row[width..].fill(0.0);
            }
            match &self.columns {
                Columns::Band(d) => self.mul_rows_by(d, |i, d| i - d as usize, &xs, &mut ys),
                Columns::Wide(c) => self.mul_rows_by(c, |_, j| j as usize, &xs, &mut ys),
            }
            for k in 0..width {
                for (v, row) in column_mut(y.rb_mut(), first + k).iter_mut().zip(&ys) {
                    *v = row[k];
                }
            }
        }
    }

    /// `mul_by` over eight columns held row by row.
    fn mul_rows_by<C: Copy>(&self, cols: &[C], column: impl Fn(usize, C) -> usize, x: &[[f64; 8]], y: &mut [[f64; 8]]) {
        for (i, xi) in x.iter().enumerate() {
            let range = self.row_ptr[i]..self.row_ptr[i + 1];
            let mut acc = [0.0; 8];
            for (&c, &a) in cols[range.clone()].iter().zip(&self.val[range]) {
                let j = column(i, c);
                let xj = &x[j];
                for k in 0..8 {
                    acc[k] += a * xj[k];
                }
                if j < i {
                    let yj = &mut y[j];
                    for k in 0..8 {
                        yj[k] += a * xi[k];
                    }
                }
            }
            y[i] = acc;
        }
    }

    fn mul_by<C: Copy>(&self, cols: &[C], column: impl Fn(usize, C) -> usize, x: &[f64], y: &mut [f64]) {
        for (i, &xi) in x.iter().enumerate() {
            let range = self.row_ptr[i]..self.row_ptr[i + 1];
            let mut acc = 0.0;
            for (&c, &a) in cols[range.clone()].iter().zip(&self.val[range]) {
                let j = column(i, c);
                acc += a * x[j];
                if j < i {
                    y[j] += a * xi;
                }
            }
            y[i] = acc;
        }
    }
}

/// The lowest `count` natural frequencies (rad/time) of `elements` over `n` solved DOFs
/// with lumped mass, dense: the massless DOFs (a plate's rotations) condensed out
/// statically, then the symmetric eigenproblem M^(-1/2) K_c M^(-1/2) in the DOFs with
/// mass. An eigen-solver independent of [`crate::eigen::lanczos`], for models of a few
/// thousand DOFs at most (n³ operations); None when the massless block is singular.
pub fn frequencies_of(elements: &[crate::elements::Element], n: usize, count: usize) -> Option<Vec<f64>> {
    use nalgebra::{DMatrix, DVector};
    let sys = assemble_elements(elements, n);
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
    let mut ev: Vec<f64> = crate::numerics::symmetric_eigenvalues(a)
        .iter()
        .map(|l| l.max(0.0).sqrt())
        .collect();
    ev.sort_by(f64::total_cmp);
    ev.truncate(count);
    Some(ev)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compression is faer's to the bit, where the order of a sum matters: 18 000
    /// positions drawn 40 000 times, one to three copies a draw, of magnitudes 1e-8 to
    /// 1e8 (so that another order of a sum rounds differently), some 1 300 entries a
    /// column (past the sort's small-slice path).
    #[test]
    fn compressed_triplets_are_faers_bit_for_bit() {
        let n = 300;
        let mut t = Vec::new();
        let mut seed = 12345u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..40_000 {
            let (r, c) = ((next() % n as u64) as usize, (next() % 60) as usize * 5);
            let scale = 10f64.powi((next() % 17) as i32 - 8);
            let x = (next() % 1_000_003) as f64 / 1_000_003.0 - 0.3;
            for _ in 0..1 + next() % 3 {
                t.push(Triplet::new(r, c, scale * x));
            }
        }
        let faer = SparseColMat::try_new_from_triplets(n, n, &t).unwrap();
        let ours = compressed(n, &t, |_, _| true);
        assert_eq!(ours.symbolic().col_ptr(), faer.symbolic().col_ptr());
        assert_eq!(ours.symbolic().row_idx(), faer.symbolic().row_idx());
        let unlike = |a: &[f64], b: &[f64]| a.iter().zip(b).filter(|(x, y)| x.to_bits() != y.to_bits()).count();
        assert_eq!(unlike(ours.val(), faer.val()), 0, "of {} entries", faer.val().len());
        // Summed in input order instead, some entries differ: the order is tested.
        let mut in_order = std::collections::BTreeMap::new();
        for e in &t {
            *in_order.entry((e.col, e.row)).or_insert(0.0) += e.val;
        }
        let differ = in_order
            .values()
            .zip(ours.val())
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert!(differ > 0, "no sum depends on its order: the test cannot see one");
        let lower = compressed(n, &t, |r, c| r >= c);
        let expected: Vec<f64> = (0..n)
            .flat_map(|j| {
                let (cp, ri) = (faer.symbolic().col_ptr(), faer.symbolic().row_idx());
                (cp[j]..cp[j + 1]).filter(move |&p| ri[p] >= j)
            })
            .map(|p| faer.val()[p])
            .collect();
        assert_eq!(lower.val().len(), expected.len());
        assert_eq!(unlike(lower.val(), &expected), 0);
    }

    /// The product of eleven columns at once (a chunk of eight and three) is each
    /// column's alone, bit for bit.
    fn columns_as_alone(a: &LowerRows, n: usize) {
        let x = faer::Mat::<f64>::from_fn(n, 11, |i, c| ((i * (c + 3)) as f64 * 0.37).sin() + c as f64);
        let mut y = faer::Mat::<f64>::from_fn(n, 11, |_, _| f64::NAN);
        a.mul_columns(x.as_ref(), y.as_mut());
        for c in 0..11 {
            let mut alone = vec![f64::NAN; n];
            a.mul(column(x.as_ref(), c), &mut alone);
            assert_eq!(column(y.as_ref(), c), &alone[..], "column {c}");
        }
    }

    /// Goal: the product from the lower triangle is the symmetric matrix's product,
    /// to the last bit of a row-by-row sum in column order, and so is the product of
    /// columns at once, column by column. Model: a 40×40 symmetric matrix with a
    /// scattered pattern, some rows empty, built from triplets whose upper entries
    /// differ from their mirror in the last bits (as element matrices do): the lower
    /// triangle must win.
    #[test]
    fn lower_triangle_product_is_the_symmetric_product_bit_for_bit() {
        let n = 40;
        let mut t = Vec::new();
        for i in 0..n {
            if i % 7 == 3 {
                continue;
            }
            t.push(Triplet::new(i, i, 4.0 + i as f64));
            for j in (0..i).filter(|j| (i * 31 + j * 17) % 5 == 0 && j % 7 != 3) {
                let a = ((i * j) as f64).sin();
                t.push(Triplet::new(i, j, a));
                t.push(Triplet::new(j, i, a * (1.0 + f64::EPSILON)));
            }
        }
        let lower_csc = lower_triangle(n, &t);
        let lower_rows = lower_csc.to_row_major().unwrap();
        let sym = mirrored(&lower_csc, &lower_rows);
        let dense = |i: usize, j: usize| {
            let (r, c) = if i >= j { (i, j) } else { (j, i) };
            t.iter()
                .filter(|e| e.row == r && e.col == c)
                .map(|e| e.val)
                .sum::<f64>()
        };
        let x: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
        let expected: Vec<f64> = (0..n)
            .map(|i| {
                (0..n)
                    .filter(|&j| dense(i, j) != 0.0)
                    .fold(0.0, |acc, j| acc + dense(i, j) * x[j])
            })
            .collect();
        let mut y = vec![f64::NAN; n];
        let lower = LowerRows::new(&lower_rows);
        assert!(matches!(lower.columns, Columns::Band(_)));
        lower.mul(&x, &mut y);
        assert_eq!(y, expected);
        columns_as_alone(&lower, n);
        for j in 0..n {
            for p in sym.symbolic().col_ptr()[j]..sym.symbolic().col_ptr()[j + 1] {
                assert_eq!(
                    sym.val()[p],
                    dense(sym.symbolic().row_idx()[p], j),
                    "({}, {j})",
                    sym.symbolic().row_idx()[p]
                );
            }
        }
    }

    /// Goal: a band too wide for 16-bit distances keeps 32-bit columns and the same
    /// product, alone and for columns at once. Model: 70 000 springs to ground, the last DOF also coupled to the first.
    #[test]
    fn a_band_wider_than_16_bits_multiplies_as_well() {
        let n = 70_000;
        let mut t: Vec<_> = (0..n).map(|i| Triplet::new(i, i, 2.0 + i as f64)).collect();
        t.push(Triplet::new(n - 1, 0, -1.5));
        t.push(Triplet::new(0, n - 1, -1.5));
        let m = LowerRows::new(&lower_triangle(n, &t).to_row_major().unwrap());
        assert!(matches!(m.columns, Columns::Wide(_)));
        let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 * 1e-3).collect();
        let mut y = vec![0.0; n];
        m.mul(&x, &mut y);
        columns_as_alone(&m, n);
        for i in [0, 1, n / 2, n - 1] {
            let coupled = match i {
                0 => -1.5 * x[n - 1],
                i if i == n - 1 => -1.5 * x[0],
                _ => 0.0,
            };
            let expected = (2.0 + i as f64) * x[i] + coupled;
            assert_eq!(y[i], expected, "row {i}");
        }
    }
}
