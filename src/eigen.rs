//! Real eigenvalues of a structure, K φ = λ M φ, by shift-and-invert Lanczos.
//!
//! Scheme: the Lanczos recurrence on the operator A = (K − σM)⁻¹ M in the
//! M-inner product, with full re-orthogonalisation (classical Gram-Schmidt, repeated
//! when a pass cancels: "twice is enough") against every Lanczos vector, as Ericsson
//! and Ruhe's spectral transformation Lanczos method (Math. Comp. 35, 1980), the
//! method of MSC's Lanczos
//! and of ARPACK's shift-invert mode (there implicitly restarted; here unrestarted).
//! The eigenvalues θ of A are 1/(λ − σ): the roots nearest σ converge first. K − σM is
//! factorised once by the sparse Cholesky factorisation the implicit schemes use, so
//! σ lies below every root: σ = 0 when K is positive definite, and a small negative
//! shift when it is not (a free structure's rigid-body modes, λ = 0, are then found
//! with the rest). The start vector is A applied to a fixed pseudo-random vector, so
//! that it has no component along M's null space (massless DOFs have infinite roots).
//! A Lanczos vector that comes out (numerically) zero means the Krylov space is
//! invariant: the recurrence goes on from a new start vector orthogonal to all before
//! it (the tridiagonal matrix is then block diagonal), which finds the other copies of
//! a repeated root and the roots of disconnected parts.
//!
//! A known limit: on a free structure the shift is tiny against the elastic roots, so
//! the θ of its rigid-body roots is some 10⁶ times the elastic ones, and the test for an
//! exhausted Krylov space (β at most 1e-10 of the largest α) sits only about ten times
//! below an ordinary elastic β. On two identical free chains side by side
//! (tests/modes.rs) another rounding of the re-orthogonalisation (matrix-vector
//! products instead of these dot products) left the exhaustion unseen and moved a
//! repeated root by 5e-10 of the top root, five times the test's bound.
//!
//! Massless DOFs (a shell's rotations) make M singular, and the M-inner product does
//! not see a vector's component along its null space: the recurrence's round-off there
//! grows by about α/β a step. A kills that component, so every Ritz vector is
//! purified, x = A Q s/θ, one more solve a root (Nour-Omid, Parlett, Ericsson and
//! Jensen, Math. Comp. 48, 1987); the roots, from T, are not affected. With every root
//! of a small plate kept, the modal engine is then the direct run to round-off
//! (7e-13; 6e-8 in the rotations without). Where those DOFs have no term of M at all
//! (lumped masses), nothing reads a Lanczos vector there, and the vectors are kept at
//! zero there: the growth, left alone, overflowed after some hundreds of steps and
//! turned the recurrence to NaN (a 19×19 curved panel lost its 568 converged roots by
//! step 954; it now extracts 635 and its modal run is the direct run to 5e-8).
//!
//! A Ritz pair (θ, Q s) of the tridiagonal T_j is accepted when its residual in the
//! operator, |β_{j+1} s_j|, is at most `tolerance`·θ; its eigenvalue is then exact to
//! about the square of that (Parlett, The Symmetric Eigenvalue Problem, 13-2). The
//! roots asked for are taken when every Ritz value below them has been accepted, and
//! again at the next test (ten steps later) with the same values, since a root the
//! start vector hardly excites may converge late. Cost: one solve with the factor and
//! three M products a step, 4 n j operations to re-orthogonalise step j, the
//! tridiagonal's values (j² by implicit QL) a test, the Ritz vectors as one matrix
//! product at the end, and the j vectors of n stored: it is meant for tens to a few
//! hundred roots, not for all of a large model's.

use crate::assembly::System;
use crate::integrate::linear::Factor;
use crate::integrate::SolveError;
use crate::model::DofLabel;
use crate::numerics::dot;
use nalgebra::DMatrix;

/// Which roots are wanted, as eigenvalues λ = ω².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roots {
    /// Roots below this are not wanted (found, and dropped); −∞ for all (a rigid-body
    /// root is zero to round-off, of either sign).
    pub above: f64,
    /// Roots above this are not wanted.
    pub below: Option<f64>,
    /// At most this many roots (the lowest of those in range).
    pub count: Option<usize>,
}

/// How the extraction runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LanczosParams {
    /// A Ritz pair is accepted when its residual is at most this times its θ.
    pub tolerance: f64,
    /// Lanczos steps between convergence tests (a test costs O(j²) at step j, against
    /// the O(n j) of the step's re-orthogonalisation).
    pub test_every: usize,
    /// At most this many Lanczos vectors stored (n doubles each): an extraction that
    /// has not converged when it reaches them fails ([`SolveError::Memory`]).
    pub max_vectors: Option<usize>,
}

impl Default for LanczosParams {
    fn default() -> Self {
        LanczosParams {
            tolerance: 1e-10,
            test_every: 10,
            max_vectors: None,
        }
    }
}

/// Roots found.
#[derive(Debug, Clone)]
pub struct Eigenpairs {
    /// The eigenvalues λ = ω², ascending.
    pub values: Vec<f64>,
    /// Their eigenvectors over the solved DOFs, each of unit generalised mass φᵀMφ.
    pub vectors: Vec<Vec<f64>>,
    /// The backward error of each: ‖Kφ − λMφ‖ / ((‖K‖ + |λ|‖M‖)‖φ‖), the norms
    /// estimated by the largest diagonal terms (a rigid-body root's is not divided by
    /// its own tiny ‖Kφ‖).
    pub residuals: Vec<f64>,
    /// The shift σ.
    pub shift: f64,
    /// Lanczos steps taken.
    pub steps: usize,
    /// Times the recurrence started again from a new vector.
    pub restarts: usize,
    /// Time spent factorising K − σM.
    pub factor_time: std::time::Duration,
    /// Time spent in solves with the factor.
    pub solve_time: std::time::Duration,
    /// Time spent in all, factorisation included.
    pub time: std::time::Duration,
}

/// A fixed pseudo-random sequence in [−1, 1) (SplitMix64), so that runs repeat.
struct Start(u64);

impl Start {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The roots of `sys` (K and M over the solved DOFs `labels`) that `roots` asks for.
pub fn lanczos(
    sys: &System,
    labels: &[DofLabel],
    roots: &Roots,
    params: &LanczosParams,
) -> Result<Eigenpairs, SolveError> {
    let t0 = std::time::Instant::now();
    let n = sys.n;
    if n == 0 {
        return Ok(Eigenpairs {
            values: Vec::new(),
            vectors: Vec::new(),
            residuals: Vec::new(),
            shift: 0.0,
            steps: 0,
            restarts: 0,
            factor_time: Default::default(),
            solve_time: Default::default(),
            time: Default::default(),
        });
    }
    let (mut factor, shift) = factorise(sys, labels)?;
    let m_mul = |x: &[f64]| {
        let mut y = vec![0.0; n];
        sys.m_mul(x, &mut y);
        y
    };
    let op = |factor: &mut Factor, x: &[f64]| {
        let mut y = m_mul(x);
        factor.solve_in_place(&mut y);
        y
    };
    // DOFs with neither a row nor a column of M (a shell's massless rotations): no
    // M-product or M-inner product reads a vector there, nor A = (K − σM)⁻¹M, so
    // nothing the extraction computes depends on a Lanczos vector's values there. The
    // recurrence's round-off there grows by about α/β a step, unchecked (to 1e240 of
    // the vectors after 550 steps on a curved panel), until it overflows and the
    // products turn NaN: each Lanczos vector is kept at zero there. The Ritz vectors
    // take their values there from the purification below.
    let massless = massless_dofs(sys);
    let mut rng = Start(0x1D_2C_3B_4A);
    // Lanczos vectors q_i (M-orthonormal), the tridiagonal's α_i and β_i (β_i couples
    // q_{i-1} and q_i; 0 where the recurrence restarted).
    let mut q = Columns::new(n);
    let (mut alpha, mut beta) = (Vec::<f64>::new(), Vec::<f64>::new());
    let mut restarts = 0;
    let mut w = Vec::new();
    let mut last: Option<Vec<f64>> = None;
    let mut norm_scale = 0.0_f64;
    let mut next_test = params.test_every.max(1);
    // The most roots in the range a test has accepted: the end must hold them all.
    let mut seen = 0;
    // Whether the vectors span the whole space with mass: T's roots are then exact.
    let mut spanned = false;
    loop {
        // The next Lanczos vector: w normalised, or a new start when w has vanished.
        let mut b = if w.is_empty() {
            0.0
        } else {
            dot(&w, &m_mul(&w)).max(0.0).sqrt()
        };
        if q.is_empty() || b <= 1e-10 * norm_scale {
            if !q.is_empty() {
                restarts += 1;
            }
            let mut fresh = None;
            for _ in 0..3 {
                let x: Vec<f64> = (0..n).map(|_| rng.next()).collect();
                let mut v = op(&mut factor, &x);
                let size = dot(&v, &m_mul(&v)).max(0.0).sqrt();
                orthogonalise(&mut v, &q, &m_mul);
                let left = dot(&v, &m_mul(&v)).max(0.0).sqrt();
                if left > 1e-8 * size {
                    fresh = Some((v, left));
                    break;
                }
            }
            // The whole space with mass is spanned.
            let Some((v, left)) = fresh else {
                spanned = true;
                break;
            };
            w = v;
            b = left;
            if !q.is_empty() {
                beta.push(0.0);
            }
        } else {
            beta.push(b);
        }
        let mut qj: Vec<f64> = w.iter().map(|x| x / b).collect();
        massless.iter().for_each(|&i| qj[i] = 0.0);
        let mq = m_mul(&qj);
        w = {
            let mut y = mq.clone();
            factor.solve_in_place(&mut y);
            y
        };
        let a = dot(&w, &mq);
        for (wi, qi) in w.iter_mut().zip(&qj) {
            *wi -= a * qi;
        }
        if let (Some(prev), Some(&bj)) = (q.last(), beta.last().filter(|_| alpha.len() == beta.len())) {
            for (wi, pi) in w.iter_mut().zip(prev) {
                *wi -= bj * pi;
            }
        }
        alpha.push(a);
        norm_scale = norm_scale.max(a.abs());
        q.push(&qj);
        orthogonalise(&mut w, &q, &m_mul);
        let j = q.len();
        let full = params.max_vectors.is_some_and(|m| j >= m) && j < n;
        if j == n || j >= next_test || full {
            next_test = j + params.test_every.max(1);
            let next = dot(&w, &m_mul(&w)).max(0.0).sqrt();
            let (values, accepted) = ritz(&alpha, &beta, next, shift, roots, params, false);
            seen = seen.max(accepted.len());
            if let Some(v) = values {
                if j == n || last.as_ref().is_some_and(|l| same(l, &v, params.tolerance)) {
                    break;
                }
                last = Some(v);
            } else {
                last = None;
            }
            if full {
                return Err(SolveError::Memory {
                    what: format!("{j} Lanczos vectors of {n} DOFs, before the roots asked for converged"),
                    bytes: (j * n * 8) as u64,
                });
            }
        }
    }
    let next = dot(&w, &m_mul(&w)).max(0.0).sqrt();
    // ‖K‖ and ‖M‖ estimated by their largest diagonal terms (lower bounds).
    let largest = |d: Vec<f64>| d.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    let (k_norm, m_norm) = (largest(sys.k_diag()), largest(sys.m_diag()));
    let (_, pairs) = ritz(
        &alpha,
        &beta,
        if q.len() == n || spanned { 0.0 } else { next },
        shift,
        roots,
        params,
        true,
    );
    if pairs.len() < seen {
        return Err(SolveError::Lanczos {
            steps: q.len(),
            found: pairs.len(),
            seen,
        });
    }
    let mut out = Eigenpairs {
        values: Vec::new(),
        vectors: Vec::new(),
        residuals: Vec::new(),
        shift,
        steps: q.len(),
        restarts,
        factor_time: factor.factor_time,
        solve_time: factor.solve_time,
        time: Default::default(),
    };
    // The Ritz vectors Q S: a matrix product for each block of 32 roots (beside the
    // Lanczos vectors and the roots' own, only a block's is stored twice).
    let j = q.len();
    let s = faer::Mat::<f64>::from_fn(j, pairs.len(), |r, c| pairs[c].1[r]);
    let mut block = faer::Mat::<f64>::zeros(n, 0);
    for (c, (lambda, _)) in pairs.into_iter().enumerate() {
        if c % 32 == 0 {
            let width = 32.min(s.ncols() - c);
            block = faer::Mat::<f64>::zeros(n, width);
            faer::linalg::matmul::matmul(
                block.as_mut(),
                faer::Accum::Replace,
                q.mat(),
                s.as_ref().subcols(c, width),
                1.0,
                faer::Par::Seq,
            );
            // Purification: Q s carries a component along M's null space, which the
            // M-inner product does not see: the recurrence's round-off there grows by
            // about α/β a step (on a curved panel's massless rotations, to 1e240 of
            // the vector in 550 steps). A = (K − σM)⁻¹M maps it to zero, so each Ritz
            // vector is A Q s/θ, solved for the block's roots at once (Nour-Omid,
            // Parlett, Ericsson and Jensen, Math. Comp. 48, 1987); θ goes with the
            // M-normalisation below.
            for k in 0..width {
                let mx = m_mul(block.col(k).try_as_col_major().expect("a column of a Mat").as_slice());
                block.col_mut(k).iter_mut().zip(mx).for_each(|(b, m)| *b = m);
            }
            factor.solve_columns_in_place(block.as_mut());
        }
        let mut x: Vec<f64> = block.col(c % 32).iter().copied().collect();
        let mx = m_mul(&x);
        let g = dot(&x, &mx).sqrt();
        x.iter_mut().for_each(|v| *v /= g);
        let mut kx = vec![0.0; n];
        sys.k_mul(&x, &mut kx);
        let r: f64 = kx
            .iter()
            .zip(&mx)
            .map(|(k, m)| (k - lambda * m / g).powi(2))
            .sum::<f64>()
            .sqrt();
        let scale = (k_norm + lambda.abs() * m_norm) * dot(&x, &x).sqrt();
        out.residuals.push(if scale > 0.0 { r / scale } else { r });
        out.values.push(lambda);
        out.vectors.push(x);
    }
    out.time = t0.elapsed();
    Ok(out)
}

/// The DOFs M has no nonzero term in the row or column of.
fn massless_dofs(sys: &System) -> Vec<usize> {
    let mut has_mass = vec![false; sys.n];
    for t in sys.m.iter().filter(|t| t.val != 0.0) {
        has_mass[t.row] = true;
        has_mass[t.col] = true;
    }
    (0..sys.n).filter(|&i| !has_mass[i]).collect()
}

/// The lowest `count` natural frequencies ω = √λ (radians per the deck's time unit) of
/// a model's structure by [`lanczos`], ascending: the DOFs with neither stiffness nor
/// mass left out (as a normal modes run leaves them), a rigid-body root as 0.
pub fn lowest_frequencies(model: &crate::model::Model, count: usize) -> Result<Vec<f64>, SolveError> {
    let full = crate::assembly::assemble(model);
    let (k, m) = (full.k_diag(), full.m_diag());
    let mut map = vec![None; model.n()];
    let mut labels = Vec::new();
    for i in (0..model.n()).filter(|&i| k[i] != 0.0 || m[i] != 0.0) {
        map[i] = Some(labels.len());
        labels.push(model.dofs[i]);
    }
    let sys = full.restricted(&map, labels.len());
    let roots = Roots {
        above: f64::NEG_INFINITY,
        below: None,
        count: Some(count),
    };
    let pairs = lanczos(&sys, &labels, &roots, &LanczosParams::default())?;
    Ok(pairs.values.iter().map(|l| l.max(0.0).sqrt()).collect())
}

/// The scale of a structure's highest roots: the largest K_ii/M_ii over the DOFs
/// with mass (0 when none has).
pub fn highest_root_scale(sys: &System) -> f64 {
    let (k, m) = (sys.k_diag(), sys.m_diag());
    k.iter()
        .zip(&m)
        .filter(|(_, &m)| m > 0.0)
        .map(|(k, m)| k / m)
        .fold(0.0_f64, f64::max)
}

/// K − σM factorised, and σ: σ = 0 when K is positive definite, else a shift below
/// the rigid-body roots, small against the structure's highest roots
/// ([`highest_root_scale`]).
pub fn factorise(sys: &System, labels: &[DofLabel]) -> Result<(Factor, f64), SolveError> {
    match Factor::new(&sys.k_csc, labels) {
        Ok(f) => Ok((f, 0.0)),
        Err(SolveError::Mechanism { .. }) => {
            let shift = -1e-8 * highest_root_scale(sys).max(f64::MIN_POSITIVE);
            Ok((
                Factor::effective(
                    sys,
                    crate::assembly::Combination {
                        mass: -shift,
                        damping: 0.0,
                        stiffness: 1.0,
                    },
                    labels,
                )?,
                shift,
            ))
        }
        Err(e) => Err(e),
    }
}

/// Vectors of one length n stored one after another (column-major n × len), so that
/// a product with all of them is one matrix product.
pub struct Columns {
    n: usize,
    data: Vec<f64>,
}

impl Columns {
    /// No vectors yet, each of length `n`.
    pub fn new(n: usize) -> Self {
        Columns { n, data: Vec::new() }
    }

    /// How many vectors.
    pub fn len(&self) -> usize {
        self.data.len() / self.n.max(1)
    }

    /// No vectors.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Adds a vector of length n.
    pub fn push(&mut self, v: &[f64]) {
        debug_assert_eq!(v.len(), self.n);
        self.data.extend_from_slice(v);
    }

    /// The last vector.
    pub fn last(&self) -> Option<&[f64]> {
        (!self.is_empty()).then(|| &self.data[self.data.len() - self.n..])
    }

    /// Vector `i`.
    pub fn col(&self, i: usize) -> &[f64] {
        &self.data[i * self.n..(i + 1) * self.n]
    }

    /// Vector `i`, to change.
    pub fn col_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.data[i * self.n..(i + 1) * self.n]
    }

    /// The vectors in order.
    pub fn iter(&self) -> impl Iterator<Item = &[f64]> {
        self.data.chunks_exact(self.n.max(1))
    }

    /// The vectors as the columns of an n × len matrix.
    pub fn mat(&self) -> faer::MatRef<'_, f64> {
        faer::MatRef::from_column_major_slice(&self.data, self.n, self.len())
    }
}

/// Makes `w` M-orthogonal to every vector of `q`: classical Gram-Schmidt, a second
/// pass only when the first removed more than half of w's squared M-norm (Kahan's
/// test: a pass that leaves at least 1/√2 of the norm leaves w orthogonal to working
/// precision; Parlett, The Symmetric Eigenvalue Problem, 6-9). A Lanczos vector
/// usually passes at once: the recurrence has already made it nearly orthogonal, and
/// each pass streams every stored vector twice.
pub fn orthogonalise(w: &mut [f64], q: &Columns, m_mul: &impl Fn(&[f64]) -> Vec<f64>) {
    let mut mw = m_mul(w);
    let mut before = dot(w, &mw);
    let mut c = vec![0.0; q.len()];
    for _ in 0..2 {
        for (i, qi) in q.iter().enumerate() {
            c[i] = dot(qi, &mw);
        }
        for (qi, ci) in q.iter().zip(&c) {
            for (wk, qk) in w.iter_mut().zip(qi) {
                *wk -= ci * qk;
            }
        }
        mw = m_mul(w);
        let after = dot(w, &mw);
        if after >= 0.5 * before {
            break;
        }
        before = after;
    }
}

/// The same wanted roots, to `tol` relative.
fn same(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= tol.sqrt() * x.abs().max(y.abs()).max(f64::MIN_POSITIVE))
}

type Pairs = Vec<(f64, nalgebra::DVector<f64>)>;

/// The Ritz values of T (α on its diagonal, β beside it; `next` the residual norm
/// after the last step) as roots λ = σ + 1/θ, ascending: the wanted ones when all
/// of them, and every root below them, are accepted (`None` while not); and the
/// wanted ones accepted so far, each with its eigenvector of T when `vectors` is set
/// (an empty vector when not).
fn ritz(
    alpha: &[f64],
    beta: &[f64],
    next: f64,
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
    vectors: bool,
) -> (Option<Vec<f64>>, Pairs) {
    let j = alpha.len();
    if !vectors {
        // The values and the last components of the vectors only: O(j²), where the
        // dense solve below is O(j³) and dominated a long extraction's tests.
        let (values, last) = tridiagonal_values(alpha, beta);
        let (complete, wanted) = ritz_values(&values, &last, next, shift, roots, params);
        let accepted = wanted.iter().map(|&(l, _)| (l, nalgebra::DVector::zeros(0))).collect();
        return (complete, accepted);
    }
    let t = DMatrix::from_fn(j, j, |r, c| {
        if r == c {
            alpha[r]
        } else if r == c + 1 {
            beta[c]
        } else if c == r + 1 {
            beta[r]
        } else {
            0.0
        }
    });
    let e = t.symmetric_eigen();
    let last: Vec<f64> = (0..j).map(|i| e.eigenvectors[(j - 1, i)]).collect();
    let (values, wanted) = ritz_values(e.eigenvalues.as_slice(), &last, next, shift, roots, params);
    let pairs = wanted
        .iter()
        .map(|&(l, i)| (l, e.eigenvectors.column(i).into_owned()))
        .collect();
    (values, pairs)
}

/// The wanted roots λ = σ + 1/θ from the Ritz values θ of T and the last component of
/// each of their vectors (see [`ritz`]): all of them when they and every root below
/// them are accepted (`None` while not), and each with its index in `theta`.
fn ritz_values(
    theta: &[f64],
    last: &[f64],
    next: f64,
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
) -> (Option<Vec<f64>>, Vec<(f64, usize)>) {
    let top = theta.iter().fold(0.0_f64, |a, &b| a.max(b.abs()));
    // θ ≤ 0 (to round-off) belongs to no finite root.
    let mut found: Vec<(f64, bool, usize)> = (0..theta.len())
        .filter(|&i| theta[i] > 1e-12 * top)
        .map(|i| {
            let accepted = (next * last[i]).abs() <= params.tolerance * theta[i];
            (shift + 1.0 / theta[i], accepted, i)
        })
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut wanted = Vec::new();
    let mut complete = false;
    for &(lambda, accepted, i) in &found {
        if !accepted {
            break;
        }
        if roots.below.is_some_and(|b| lambda > b) || roots.count.is_some_and(|c| wanted.len() == c) {
            complete = true;
            break;
        }
        if lambda >= roots.above {
            wanted.push((lambda, i));
        }
    }
    // Every root is found when the space is spanned (next = 0 at the last step).
    if next == 0.0 && found.iter().all(|f| f.1) {
        complete = true;
    }
    (complete.then(|| wanted.iter().map(|w| w.0).collect()), wanted)
}

/// The eigenvalues of the symmetric tridiagonal matrix with `alpha` on its diagonal
/// and `beta` beside it, and the last component of each unit eigenvector: the
/// implicit QL algorithm with Wilkinson's shift (Bowdler, Martin, Reinsch and
/// Wilkinson, Numer. Math. 11, 1968: tql2), its rotations applied to the last row
/// of the eigenvector matrix only. A zero β splits the matrix; its blocks converge
/// apart.
fn tridiagonal_values(alpha: &[f64], beta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = alpha.len();
    let mut d = alpha.to_vec();
    let mut e: Vec<f64> = beta.iter().copied().chain(std::iter::once(0.0)).take(n).collect();
    let mut z = vec![0.0; n];
    if n > 0 {
        z[n - 1] = 1.0;
    }
    for l in 0..n {
        for _ in 0..60 {
            let mut m = l;
            while m + 1 < n && e[m].abs() > f64::EPSILON * (d[m].abs() + d[m + 1].abs()) {
                m += 1;
            }
            if m == l {
                break;
            }
            let mut g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let mut r = g.hypot(1.0);
            g = d[m] - d[l] + e[l] / (g + r.copysign(g));
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut split = false;
            for i in (l..m).rev() {
                let f = s * e[i];
                let b = c * e[i];
                r = f.hypot(g);
                e[i + 1] = r;
                if r == 0.0 {
                    d[i + 1] -= p;
                    e[m] = 0.0;
                    split = true;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                r = (d[i] - g) * s + 2.0 * c * b;
                p = s * r;
                d[i + 1] = g + p;
                g = c * r - b;
                let zf = z[i + 1];
                z[i + 1] = s * z[i] + c * zf;
                z[i] = c * z[i] - s * zf;
            }
            if split {
                continue;
            }
            d[l] -= p;
            e[l] = g;
            e[m] = 0.0;
        }
    }
    (d, z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: the QL values and last components are the dense solver's, on a
    /// tridiagonal matrix of 40 rows with scattered diagonal, a zero β splitting it in
    /// two, and a nearly repeated pair: values to 1e-13 of the largest, last
    /// components to 1e-10 in magnitude (a vector's sign is free).
    #[test]
    fn tridiagonal_ql_is_the_dense_solution() {
        let n = 40;
        let alpha: Vec<f64> = (0..n).map(|i| ((i * 7) % 11) as f64 + 0.5 * (i as f64).sin()).collect();
        let mut beta: Vec<f64> = (0..n - 1).map(|i| 0.3 + ((i * 5) % 7) as f64 * 0.1).collect();
        beta[17] = 0.0;
        beta[30] = 1e-9;
        let (values, last) = tridiagonal_values(&alpha, &beta);
        let t = DMatrix::from_fn(n, n, |r, c| match r.abs_diff(c) {
            0 => alpha[r],
            1 => beta[r.min(c)],
            _ => 0.0,
        });
        let e = t.symmetric_eigen();
        let top = e.eigenvalues.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let mut ours: Vec<(f64, f64)> = values.iter().copied().zip(last.iter().map(|x| x.abs())).collect();
        let mut dense: Vec<(f64, f64)> = (0..n)
            .map(|i| (e.eigenvalues[i], e.eigenvectors[(n - 1, i)].abs()))
            .collect();
        ours.sort_by(|a, b| a.0.total_cmp(&b.0));
        dense.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (a, b) in ours.iter().zip(&dense) {
            assert!((a.0 - b.0).abs() <= 1e-13 * top, "{a:?} vs {b:?}");
            assert!((a.1 - b.1).abs() <= 1e-10, "{a:?} vs {b:?}");
        }
    }
}
