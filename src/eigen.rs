//! Real eigenvalues of a structure, K φ = λ M φ, by shift-and-invert block Lanczos.
//!
//! Scheme: the block Lanczos recurrence, four vectors a step (`BLOCK`), on the
//! operator A = (K − σM)⁻¹ M in the M-inner product, with full re-orthogonalisation
//! (classical Gram-Schmidt as matrix products, repeated when a pass cancels: "twice
//! is enough") against every Lanczos vector: Ericsson and Ruhe's spectral
//! transformation (Math. Comp. 35, 1980) in blocks, as Grimes, Lewis and Simon's
//! shifted block Lanczos (SIAM J. Matrix Anal. Appl. 15, 1994), the method of MSC's
//! Lanczos (here with one shift and unrestarted). A step is A Q_k = Q_{k−1} B_kᵀ +
//! Q_k A_k + Q_{k+1} B_{k+1}: one solve with the factor for the block's four columns
//! (faer's supernodal solve reads the factor once for them; two columns on each of
//! two cores, [`Factor::solve_columns_in_place`]) and a re-orthogonalisation that
//! reads the stored vectors once for all four (each half of their rows on its own
//! core, [`tall_gram`], [`tall_update`]), where one vector a step read them once a
//! vector; T is block tridiagonal, a band matrix.
//! The eigenvalues θ of A are 1/(λ − σ): the roots nearest σ converge first. K − σM is
//! factorised once by the sparse Cholesky factorisation the implicit schemes use, so
//! σ lies below every root: σ = 0 when K is positive definite, and a small negative
//! shift when it is not (a free structure's rigid-body modes, λ = 0, are then found
//! with the rest). The start block is A applied to fixed pseudo-random vectors, so
//! that it has no component along M's null space (massless DOFs have infinite roots).
//! A column of the next block that comes out (numerically) zero means the Krylov
//! space is invariant along it: a new start vector orthogonal to all before it takes
//! its place (T then splits there), which finds the other copies of a root repeated
//! more often than the block is wide and the roots of disconnected parts. A root
//! repeated up to four times is found in one Krylov space.
//!
//! A known limit: on a free structure the shift is tiny against the elastic roots, so
//! the θ of its rigid-body roots is some 10⁶ times the elastic ones, and the test for an
//! exhausted Krylov space (a column's norm at most 1e-10 of the largest diagonal term
//! of A_k) sits only about ten times below an ordinary elastic coupling. On two
//! identical free chains side by side (tests/modes.rs), one vector a step with another
//! rounding of its re-orthogonalisation left the exhaustion unseen and moved a repeated
//! root by 5e-10 of the top root, five times the test's bound; blocks of four hold
//! both copies from the start. The same range of θ costs a free structure's highest
//! roots their accuracy when most of its roots are asked for (the paper's rod, 143 of
//! its 145: backward errors to 1.2e-3): [`lanczos`] then extracts them again from a
//! second shift, half the lowest elastic root below zero, where no θ is more than
//! twice the lowest elastic root's.
//!
//! Massless DOFs (a shell's rotations) make M singular, and the M-inner product does
//! not see a vector's component along its null space: the recurrence's round-off there
//! grows by about α/β a step. A kills that component, so every Ritz vector is
//! purified, x = A Q s/θ, one more solve a root (Nour-Omid, Parlett, Ericsson and
//! Jensen, Math. Comp. 48, 1987); the roots, from T, are not affected. With every root
//! of a small plate kept, the modal engine is then the direct run to round-off
//! (7e-13; 6e-8 in the rotations without). Where those DOFs have no term of M at all
//! (lumped masses), nothing reads a Lanczos vector there: the vectors are stored on
//! the DOFs with mass alone, and A is applied as M's product there, the solve over
//! every DOF, and the solution's rows with mass kept. A curved panel's rotations are
//! half its DOFs: its re-orthogonalisation and Ritz vectors read half the storage.
//! (Kept over every DOF, the round-off there grew by α/β a step, overflowed after
//! some hundreds of steps and turned the recurrence to NaN: a 19×19 curved panel lost
//! its 568 converged roots by step 954; it now extracts 635 and its modal run is the
//! direct run to 5e-8.)
//!
//! A Ritz pair (θ, Q s) of T_j is accepted when its residual in the operator,
//! ‖B_{k+1} s_k‖ (s_k the last block's components of s), is at most `tolerance`·θ; its
//! eigenvalue is then exact to about the square of that (Parlett, The Symmetric
//! Eigenvalue Problem, 13-2). The roots asked for are taken when every Ritz value below
//! them has been accepted, and again at the next test (ten or more vectors later) with
//! the same values, since a root the start block hardly excites may converge late. The
//! next test comes no sooner than as many vectors as Ritz values in the range are not
//! yet accepted (each needs a vector or more: the paper's plate's 372 vectors take 12
//! tests, not 31). A test reduces the band T to tridiagonal by rotations (O(j² p), p
//! the block's width) and takes the values by implicit QL, both applied to the last
//! block's rows of the eigenvectors only; the roots taken at the end are those the
//! last test accepted. Their vectors of T are the tridiagonal's, by inverse iteration
//! for the wanted values alone (O(j) a vector, clusters kept orthogonal), rotated
//! back; nalgebra's dense QR formed all j of them (O(j³), 6 % of the plate's modal
//! run). Each root's vector is returned with its largest entry positive. The vectors
//! of the first block sample the orthogonality that full re-orthogonalisation keeps:
//! each new block is checked against them, and past √ε the extraction stops with an
//! error (a fault in the re-orthogonalisation: without it, it ran on without end,
//! forming copies of the converged roots). Cost:
//! one block solve and the block's M products a step, 4 n j operations to
//! re-orthogonalise a block at j vectors (as two matrix products), the tests, the Ritz
//! vectors as one matrix product at the end, and the j vectors stored, n the DOFs with
//! mass. Blocks
//! need more vectors than one vector a step (the paper's plate: 372 against 320 for
//! its 163 roots) but each costs less. It is meant for tens to a few hundred roots,
//! not for all of a large model's.

use crate::assembly::System;
use crate::integrate::linear::Factor;
use crate::integrate::SolveError;
use crate::model::DofLabel;
use crate::numerics::{both, column, column_mut, dot};
use faer::linalg::matmul::matmul;
use faer::{Accum, Par};
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
    /// Lanczos vectors between convergence tests, at least (a test costs O(j² p) at j
    /// vectors in blocks of p, against the O(n j p) of the block's
    /// re-orthogonalisation), and at least as many as the Ritz values that may be
    /// wanted roots and are not yet accepted.
    pub test_every: usize,
    /// At most this many Lanczos vectors stored (a double for each DOF with mass
    /// each): an extraction that has not converged when it reaches them fails
    /// ([`SolveError::Memory`]).
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
    /// Their eigenvectors over the solved DOFs, each of unit generalised mass φᵀMφ and
    /// its largest entry positive.
    pub vectors: Vec<Vec<f64>>,
    /// The backward error of each: ‖Kφ − λMφ‖ / ((‖K‖ + |λ|‖M‖)‖φ‖), the norms
    /// estimated by the largest diagonal terms (a rigid-body root's is not divided by
    /// its own tiny ‖Kφ‖).
    pub residuals: Vec<f64>,
    /// The shift σ.
    pub shift: f64,
    /// Lanczos vectors formed (four a block step).
    pub lanczos_vectors: usize,
    /// New start vectors taken where the Krylov space was invariant.
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

/// The roots of `sys` (K and M over the solved DOFs `labels`) that `roots` asks for;
/// a free structure's again from a second shift where the first leaves some
/// inaccurate (see the module's notes).
pub fn lanczos(
    sys: &System,
    labels: &[DofLabel],
    roots: &Roots,
    params: &LanczosParams,
) -> Result<Eigenpairs, SolveError> {
    if sys.n == 0 {
        return Ok(Eigenpairs {
            values: Vec::new(),
            vectors: Vec::new(),
            residuals: Vec::new(),
            shift: 0.0,
            lanczos_vectors: 0,
            restarts: 0,
            factor_time: Default::default(),
            solve_time: Default::default(),
            time: Default::default(),
        });
    }
    lanczos_factored(sys, labels, roots, params, &|_| {}).map(|(pairs, _)| pairs)
}

/// [`lanczos`] with the factor of K − σM the roots were found with (σ their
/// [`Eigenpairs::shift`]), for a caller's own solves, telling `report` how far it has
/// come at each convergence test. A system of at least one DOF.
pub fn lanczos_factored(
    sys: &System,
    labels: &[DofLabel],
    roots: &Roots,
    params: &LanczosParams,
    report: &dyn Fn(Extracted),
) -> Result<(Eigenpairs, Factor), SolveError> {
    let (mut factor, shift) = factorise(sys, labels)?;
    let first = lanczos_with(sys, &mut factor, shift, roots, params, report)?;
    // A free structure whose roots come out inaccurate (the module's notes): again from
    // half its lowest elastic root below zero, kept when its worst root is better (the
    // first's factor dropped meanwhile, and made again if the first is kept).
    let worst = |p: &Eigenpairs| p.residuals.iter().copied().fold(0.0_f64, f64::max);
    let elastic = first.values.iter().copied().find(|&l| l >= rigid_below(sys));
    let (Some(elastic), true) = (elastic, shift < 0.0 && worst(&first) > INACCURATE) else {
        return Ok((first, factor));
    };
    drop(factor);
    let again = -0.5 * elastic;
    let second = factor_at(sys, labels, again)
        .and_then(|mut f| lanczos_with(sys, &mut f, again, roots, params, report).map(|p| (p, f)));
    let (mut kept, other, factor) = match second {
        Ok((second, f)) if worst(&second) < worst(&first) => (second, first, f),
        Ok((second, _)) => (first, second, factor_at(sys, labels, shift)?),
        Err(_) => return Ok((first, factor_at(sys, labels, shift)?)),
    };
    kept.lanczos_vectors += other.lanczos_vectors;
    kept.restarts += other.restarts;
    kept.factor_time += other.factor_time;
    kept.solve_time += other.solve_time;
    kept.time += other.time;
    Ok((kept, factor))
}

/// One extraction with K − σM factorised by [`factorise`] or [`factor_at`] (a system
/// of at least one DOF), telling `report` how far it has come at each convergence test.
fn lanczos_with(
    sys: &System,
    factor: &mut Factor,
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
    report: &dyn Fn(Extracted),
) -> Result<Eigenpairs, SolveError> {
    extract(sys, factor, shift, roots, params, report, |w, q, m_mul| {
        orthogonalise_columns(w, q, &m_mul)
    })
}

/// How far an extraction has come, told at each convergence test and once more when it
/// has converged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Extracted {
    /// Lanczos vectors formed.
    pub vectors: usize,
    /// Roots in the range asked for that the test accepted.
    pub roots: usize,
    /// The extraction has converged: these are the roots, whose vectors it forms now.
    pub converged: bool,
}

/// How a step's new block is made M-orthogonal to the stored Lanczos vectors, and its
/// M-image: [`orthogonalise_columns`] (the tests put faults in its place).
type Reorthogonalise = fn(faer::MatMut<'_, f64>, &Columns, &dyn Fn(&[f64]) -> Vec<f64>) -> faer::Mat<f64>;

/// [`lanczos_with`], each step's block re-orthogonalised by `reorthogonalise`.
fn extract(
    sys: &System,
    factor: &mut Factor,
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
    report: &dyn Fn(Extracted),
    reorthogonalise: Reorthogonalise,
) -> Result<Eigenpairs, SolveError> {
    let t0 = std::time::Instant::now();
    let n = sys.n;
    let solved_before = factor.solve_time;
    // DOFs with neither a row nor a column of M (a shell's massless rotations): no
    // M-product or M-inner product reads a vector there, nor A = (K − σM)⁻¹M, so
    // nothing the extraction computes depends on a Lanczos vector's values there: the
    // vectors are stored on the DOFs with mass alone (see the module's notes). The
    // Ritz vectors take their values there from the purification below.
    let rows = MassRows::new(sys);
    let nm = rows.len();
    let m_mul = |x: &[f64]| rows.m_mul(sys, x);
    let mut fresh = Fresh {
        rng: Start(0x1D_2C_3B_4A),
        rows: &rows,
    };
    // The Lanczos vectors (M-orthonormal, block after block), and T's blocks: A_k on
    // the diagonal, B_{k+1} (upper trapezoidal, block k+1's width × block k's) below.
    let mut q = Columns::new(nm);
    let mut diag: Vec<DMatrix<f64>> = Vec::new();
    let mut sub: Vec<DMatrix<f64>> = Vec::new();
    let mut restarts = 0;
    let mut norm_scale = 0.0_f64;
    let mut next_test = params.test_every.max(1);
    let mut last: Option<Vec<f64>> = None;
    // The most roots in the range a test has accepted: the end must hold them all.
    let mut seen = 0;
    // The first block: BLOCK fresh vectors.
    let first = BLOCK.min(nm);
    let (mut block, _, _) = next_block(
        faer::Mat::zeros(nm, first),
        faer::Mat::zeros(nm, first),
        &q,
        0.0,
        &mut fresh,
        factor,
        &m_mul,
    );
    loop {
        let width = block.q.ncols();
        if width == 0 {
            // Nothing new with mass is left: the whole space with mass is spanned, and
            // T's roots are exact.
            break;
        }
        // W = A Q_k = (K − σM)⁻¹ M Q_k, one solve for the block's columns.
        let mq = &block.mq;
        let mut w = rows.solve_columns(factor, mq.as_ref());
        // A_k = Q_kᵀ M W, symmetric but for round-off.
        let mut a = faer::Mat::<f64>::zeros(width, width);
        matmul(a.as_mut(), Accum::Replace, mq.transpose(), w.as_ref(), 1.0, Par::Seq);
        let a = DMatrix::from_fn(width, width, |r, c| 0.5 * (a[(r, c)] + a[(c, r)]));
        (0..width).for_each(|i| norm_scale = norm_scale.max(a[(i, i)].abs()));
        // W ← W − Q_k A_k − Q_{k−1} B_kᵀ.
        let ak = faer::Mat::<f64>::from_fn(width, width, |r, c| a[(r, c)]);
        matmul(w.as_mut(), Accum::Add, block.q.as_ref(), ak.as_ref(), -1.0, Par::Seq);
        if let Some(b) = sub.last() {
            let prev = q.mat().subcols(q.len() - b.ncols(), b.ncols());
            let bt = faer::Mat::<f64>::from_fn(b.ncols(), b.nrows(), |r, c| b[(c, r)]);
            matmul(w.as_mut(), Accum::Add, prev, bt.as_ref(), -1.0, Par::Seq);
        }
        for c in 0..width {
            q.push(column(block.q.as_ref(), c));
        }
        diag.push(a);
        let mw = reorthogonalise(w.as_mut(), &q, &m_mul);
        let (next, b, new) = next_block(w, mw, &q, norm_scale, &mut fresh, factor, &m_mul);
        restarts += new;
        sub.push(b);
        block = next;
        let j = q.len();
        // The new block against the first, a sample of the orthogonality that full
        // re-orthogonalisation keeps at round-off (at most 3e-16 on every model of the
        // tests): past √ε (Simon's semi-orthogonality, under which the Ritz values are
        // still as accurate) the recurrence has lost it, and would run on forming
        // copies of the roots it has converged.
        let loss = (0..block.q.ncols())
            .flat_map(|c| (0..first.min(j)).map(move |i| (i, c)))
            .map(|(i, c)| dot(q.col(i), column(block.mq.as_ref(), c)).abs())
            .fold(0.0_f64, f64::max);
        if loss > f64::EPSILON.sqrt() {
            return Err(SolveError::Orthogonality { vectors: j, loss });
        }
        let spanned = block.q.ncols() == 0;
        let full = params.max_vectors.is_some_and(|m| j + block.q.ncols() > m) && !spanned;
        if j >= next_test || full || spanned {
            let (theta, residual, _) = block_ritz_values(&diag, &sub, false);
            let (values, accepted) = ritz_values(&theta, &residual, spanned, shift, roots, params);
            next_test = j + params
                .test_every
                .max(1)
                .max(pending(&theta, &residual, shift, roots, params, &accepted));
            seen = seen.max(accepted.len());
            report(Extracted {
                vectors: j,
                roots: accepted.len(),
                converged: false,
            });
            if let Some(v) = values {
                if spanned || last.as_ref().is_some_and(|l| same(l, &v, params.tolerance)) {
                    break;
                }
                last = Some(v);
            } else {
                last = None;
            }
            if full {
                return Err(SolveError::Memory {
                    what: format!("{j} Lanczos vectors of {nm} DOFs with mass, before the roots asked for converged"),
                    bytes: (j * nm * 8) as u64,
                });
            }
        }
    }
    // ‖K‖ and ‖M‖ estimated by their largest diagonal terms (lower bounds).
    let largest = |d: Vec<f64>| d.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    let (k_norm, m_norm) = (largest(sys.k_diag()), largest(sys.m_diag()));
    let pairs = ritz_pairs(&diag, &sub, block.q.ncols() == 0, shift, roots, params);
    if pairs.len() < seen {
        return Err(SolveError::Lanczos {
            vectors: q.len(),
            found: pairs.len(),
            seen,
        });
    }
    report(Extracted {
        vectors: q.len(),
        roots: pairs.len(),
        converged: true,
    });
    let mut out = Eigenpairs {
        values: Vec::new(),
        vectors: Vec::new(),
        residuals: Vec::new(),
        shift,
        lanczos_vectors: q.len(),
        restarts,
        factor_time: factor.factor_time,
        solve_time: Default::default(),
        time: Default::default(),
    };
    // The Ritz vectors Q S: a matrix product for each block of 32 roots (beside the
    // Lanczos vectors and the roots' own, only a block's is stored twice).
    let j = q.len();
    let s = faer::Mat::<f64>::from_fn(j, pairs.len(), |r, c| pairs[c].1[r]);
    // Roots' vectors M-normalised, each one's largest entry (the first of equal size)
    // positive (a root's vector does not depend on the start vectors or the solver's
    // internals, but for round-off), and their backward errors; x comes as A Q s, so
    // that its θ goes with the normalisation. The products with M and K are made for
    // the columns at once (each column's as alone).
    let finish = |lambdas: &[f64], x: faer::MatRef<'_, f64>| -> Vec<(Vec<f64>, f64)> {
        let w = x.ncols();
        let mut x = x.to_owned();
        let mut mx = faer::Mat::<f64>::zeros(n, w);
        sys.m_mul_columns(x.as_ref(), mx.as_mut());
        let g: Vec<f64> = (0..w)
            .map(|c| {
                let xc = column(x.as_ref(), c);
                let largest = xc.iter().fold(0.0_f64, |a, &b| if b.abs() > a.abs() { b } else { a });
                dot(xc, column(mx.as_ref(), c)).sqrt().copysign(largest)
            })
            .collect();
        for (c, g) in g.iter().enumerate() {
            column_mut(x.as_mut(), c).iter_mut().for_each(|v| *v /= g);
        }
        let mut kx = faer::Mat::<f64>::zeros(n, w);
        sys.k_mul_columns(x.as_ref(), kx.as_mut());
        (0..w)
            .map(|c| {
                let (lambda, g, xc) = (lambdas[c], g[c], column(x.as_ref(), c));
                let r: f64 = column(kx.as_ref(), c)
                    .iter()
                    .zip(column(mx.as_ref(), c))
                    .map(|(k, m)| (k - lambda * m / g).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let scale = (k_norm + lambda.abs() * m_norm) * dot(xc, xc).sqrt();
                (xc.to_vec(), if scale > 0.0 { r / scale } else { r })
            })
            .collect()
    };
    for first in (0..pairs.len()).step_by(32) {
        let width = 32.min(pairs.len() - first);
        let mut stored = faer::Mat::<f64>::zeros(nm, width);
        tall_update(stored.as_mut(), q.mat(), s.as_ref().subcols(first, width), 1.0);
        // Purification: Q s carries a component along M's null space, which the
        // M-inner product does not see: the recurrence's round-off there grows by
        // about α/β a step (on a curved panel's massless rotations, to 1e240 of
        // the vector in 550 steps). A = (K − σM)⁻¹M maps it to zero, so each Ritz
        // vector is A Q s/θ, solved for the block's roots at once over every DOF
        // (Nour-Omid, Parlett, Ericsson and Jensen, Math. Comp. 48, 1987); θ goes
        // with the M-normalisation.
        let mut ritz = faer::Mat::<f64>::zeros(n, width);
        for k in 0..width {
            rows.scatter(
                &rows.m_mul(sys, column(stored.as_ref(), k)),
                column_mut(ritz.as_mut(), k),
            );
        }
        factor.solve_columns_in_place(ritz.as_mut());
        // Each half of the block's roots finished on its own core.
        let finished = |ks: std::ops::Range<usize>| -> Vec<(Vec<f64>, f64)> {
            let lambdas: Vec<f64> = ks.clone().map(|k| pairs[first + k].0).collect();
            finish(&lambdas, ritz.as_ref().subcols(ks.start, ks.len()))
        };
        let half = width / 2;
        let (top, bottom) = both(|| finished(0..half), || finished(half..width));
        for (k, (x, residual)) in top.into_iter().chain(bottom).enumerate() {
            out.residuals.push(residual);
            out.values.push(pairs[first + k].0);
            out.vectors.push(x);
        }
    }
    out.solve_time = factor.solve_time - solved_before;
    out.time = t0.elapsed() + factor.factor_time;
    Ok(out)
}

/// Lanczos vectors a step adds: four, whose solve with the factor costs about two
/// single solves (faer's supernodal solve reads the factor once for them all), and
/// whose re-orthogonalisation reads the stored vectors once for all four.
const BLOCK: usize = 4;

/// New start vectors: A applied to a fixed pseudo-random vector, so that it has no
/// component along M's null space, on the DOFs with mass.
struct Fresh<'a> {
    rng: Start,
    rows: &'a MassRows,
}

/// The DOFs with a term of M in their row or column, on which the Lanczos vectors are
/// stored: every product and inner product with M reads them alone.
struct MassRows {
    /// The solved DOFs.
    n: usize,
    /// The DOFs with mass, ascending.
    rows: Vec<usize>,
    /// M's diagonal on them, when M is diagonal.
    lumped: Option<Vec<f64>>,
}

impl MassRows {
    fn new(sys: &System) -> Self {
        let mut has_mass = vec![false; sys.n];
        for t in sys.m.iter().filter(|t| t.val != 0.0) {
            has_mass[t.row] = true;
            has_mass[t.col] = true;
        }
        let rows: Vec<usize> = (0..sys.n).filter(|&i| has_mass[i]).collect();
        let lumped = sys.m_lumped.as_ref().map(|d| rows.iter().map(|&i| d[i]).collect());
        MassRows { n: sys.n, rows, lumped }
    }

    /// How many.
    fn len(&self) -> usize {
        self.rows.len()
    }

    /// A vector over every DOF on these.
    fn gather(&self, x: &[f64]) -> Vec<f64> {
        self.rows.iter().map(|&i| x[i]).collect()
    }

    /// `full` ← the vector `x` on these, zero elsewhere.
    fn scatter(&self, x: &[f64], full: &mut [f64]) {
        full.fill(0.0);
        self.rows.iter().zip(x).for_each(|(&i, &v)| full[i] = v);
    }

    /// M x, both on these.
    fn m_mul(&self, sys: &System, x: &[f64]) -> Vec<f64> {
        match &self.lumped {
            Some(d) => d.iter().zip(x).map(|(d, x)| d * x).collect(),
            None => {
                let mut full = vec![0.0; self.n];
                self.scatter(x, &mut full);
                let mut y = vec![0.0; self.n];
                sys.m_mul(&full, &mut y);
                self.gather(&y)
            }
        }
    }

    /// (K − σM)⁻¹ applied to the columns of `mx` (M-images on these), on these: one
    /// solve over every DOF for them all.
    fn solve_columns(&self, factor: &mut Factor, mx: faer::MatRef<'_, f64>) -> faer::Mat<f64> {
        let mut full = faer::Mat::<f64>::zeros(self.n, mx.ncols());
        for c in 0..mx.ncols() {
            self.scatter(column(mx, c), column_mut(full.as_mut(), c));
        }
        factor.solve_columns_in_place(full.as_mut());
        faer::Mat::from_fn(self.len(), mx.ncols(), |r, c| full[(self.rows[r], c)])
    }

    /// [`MassRows::solve_columns`] for one vector.
    fn solve(&self, factor: &mut Factor, mx: &[f64]) -> Vec<f64> {
        let mut full = vec![0.0; self.n];
        self.scatter(mx, &mut full);
        factor.solve_in_place(&mut full);
        self.gather(&full)
    }
}

/// A block of Lanczos vectors (the columns of `q`) with their M-images.
struct Block {
    q: faer::Mat<f64>,
    mq: faer::Mat<f64>,
}

/// The next block from W (already M-orthogonal to `q`) and its M-image MW:
/// W = Q_{k+1} B_{k+1}, by modified Gram-Schmidt in the M-inner product (twice,
/// "twice is enough") over W's columns, the M-images carried along. A column whose
/// M-norm left is at most 1e-10 of `norm_scale` (the largest |A_k|: the operator's
/// norm) means the Krylov space is invariant along it: a fresh vector, M-orthogonal to
/// all before it, takes its place, with B's entry zero there (T then splits there).
/// When three fresh vectors in turn have nothing left (under 1e-8 of their size) the
/// whole space with mass is spanned: such columns add nothing to the block (it is
/// empty when nothing is left), but the columns after them still give B their
/// entries along it (without them T misses couplings: a chain of 30 springs, spanned
/// in the middle of a block, had its 7th root's residual at 5e-10). Returns the block, B_{k+1} (its width × W's) and how many fresh
/// vectors it took.
fn next_block(
    w: faer::Mat<f64>,
    mw: faer::Mat<f64>,
    q: &Columns,
    norm_scale: f64,
    fresh: &mut Fresh<'_>,
    factor: &mut Factor,
    m_mul: &impl Fn(&[f64]) -> Vec<f64>,
) -> (Block, DMatrix<f64>, usize) {
    let (n, width) = (w.nrows(), w.ncols());
    let mut out: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    let mut b = DMatrix::<f64>::zeros(width, width);
    let mut taken = 0;
    let mut spanned = false;
    for c in 0..width {
        let (mut v, mut mv) = (column(w.as_ref(), c).to_vec(), column(mw.as_ref(), c).to_vec());
        let before = dot(&v, &mv);
        remove_block(&mut v, &mut mv, pairs(&out), |r, h| b[(r, c)] += h);
        // Kahan's test over all vectors before this one: where the block's own
        // removed more than half of the squared norm, what is left is again made
        // orthogonal to the stored vectors (it has their round-off) and the block's.
        if dot(&v, &mv) < 0.5 * before {
            let m = orthogonalise_columns(faer::MatMut::from_column_major_slice_mut(&mut v, n, 1), q, m_mul);
            mv = column(m.as_ref(), 0).to_vec();
            remove_block(&mut v, &mut mv, pairs(&out), |r, h| b[(r, c)] += h);
        }
        let norm = dot(&v, &mv).max(0.0).sqrt();
        if norm > 1e-10 * norm_scale && norm_scale > 0.0 {
            b[(out.len(), c)] = norm;
            v.iter_mut().chain(mv.iter_mut()).for_each(|x| *x /= norm);
        } else {
            // Past the whole space, the rest of W's columns still give B its entries.
            let Some(f) = (!spanned)
                .then(|| fresh_vector(fresh, q, &out, factor, m_mul))
                .flatten()
            else {
                spanned = true;
                continue;
            };
            (v, mv) = f;
            if !q.is_empty() {
                taken += 1;
            }
        }
        out.push((v, mv));
    }
    let block = Block {
        q: faer::Mat::from_fn(n, out.len(), |r, c| out[c].0[r]),
        mq: faer::Mat::from_fn(n, out.len(), |r, c| out[c].1[r]),
    };
    let b = b.rows(0, out.len()).into_owned();
    (block, b, taken)
}

/// Takes from v (with its M-image mv) its M-components along the block's vectors
/// (each with its M-image), one after another (modified Gram-Schmidt), telling
/// `coefficient` each one removed by the vector's index.
pub fn remove_block<'a>(
    v: &mut [f64],
    mv: &mut [f64],
    block: impl IntoIterator<Item = (&'a [f64], &'a [f64])>,
    mut coefficient: impl FnMut(usize, f64),
) {
    for (r, (u, mu)) in block.into_iter().enumerate() {
        let h = dot(u, mv);
        coefficient(r, h);
        v.iter_mut().zip(u).for_each(|(x, y)| *x -= h * y);
        mv.iter_mut().zip(mu).for_each(|(x, y)| *x -= h * y);
    }
}

/// Vectors with their M-images, as slices.
fn pairs(block: &[(Vec<f64>, Vec<f64>)]) -> impl Iterator<Item = (&[f64], &[f64])> {
    block.iter().map(|(u, mu)| (u.as_slice(), mu.as_slice()))
}

/// A fresh start vector M-orthonormal to `q` and `block`, with its M-image, or `None`
/// when three in turn have nothing left (see [`next_block`]).
fn fresh_vector(
    fresh: &mut Fresh<'_>,
    q: &Columns,
    block: &[(Vec<f64>, Vec<f64>)],
    factor: &mut Factor,
    m_mul: &impl Fn(&[f64]) -> Vec<f64>,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let (rows, n) = (fresh.rows, q.n);
    for _ in 0..3 {
        // Drawn over every DOF, as the sequence always was; M reads those with mass.
        let x: Vec<f64> = (0..rows.n).map(|_| fresh.rng.next()).collect();
        let mut v = rows.solve(factor, &m_mul(&rows.gather(&x)));
        let size = dot(&v, &m_mul(&v)).max(0.0).sqrt();
        // Against the stored vectors and the block's, twice over ("twice is enough").
        let mut mv = Vec::new();
        for _ in 0..2 {
            let m = orthogonalise_columns(faer::MatMut::from_column_major_slice_mut(&mut v, n, 1), q, m_mul);
            mv = column(m.as_ref(), 0).to_vec();
            remove_block(&mut v, &mut mv, pairs(block), |_, _| {});
        }
        let left = dot(&v, &mv).max(0.0).sqrt();
        if left > 1e-8 * size {
            v.iter_mut().chain(mv.iter_mut()).for_each(|x| *x /= left);
            return Some((v, mv));
        }
    }
    None
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

/// Below this a root is a rigid-body root: zero to the round-off of the largest
/// K_ii/M_ii ([`highest_root_scale`]), far below any elastic root of a mesh (the rod
/// of 144 elements: its lowest is 1e-4 of it).
pub fn rigid_below(sys: &System) -> f64 {
    1e-12 * highest_root_scale(sys)
}

/// A root's backward error ([`Eigenpairs::residuals`]) past which it is inaccurate:
/// 100 times what the acceptance test leaves (a Ritz pair's residual at most 1e-10 of
/// θ; the demonstration decks' roots come out at 1e-16).
pub const INACCURATE: f64 = 1e-8;

/// K − σM factorised, and σ: σ = 0 when K is positive definite, else a shift below
/// the rigid-body roots, small against the structure's highest roots
/// ([`highest_root_scale`]).
pub fn factorise(sys: &System, labels: &[DofLabel]) -> Result<(Factor, f64), SolveError> {
    match Factor::new(&sys.k_csc, labels) {
        Ok(f) => Ok((f, 0.0)),
        Err(SolveError::Mechanism { .. }) => {
            let shift = -1e-8 * highest_root_scale(sys).max(f64::MIN_POSITIVE);
            Ok((factor_at(sys, labels, shift)?, shift))
        }
        Err(e) => Err(e),
    }
}

/// K − σM factorised.
fn factor_at(sys: &System, labels: &[DofLabel], shift: f64) -> Result<Factor, SolveError> {
    Factor::effective(
        sys,
        crate::assembly::Combination {
            mass: -shift,
            damping: 0.0,
            stiffness: 1.0,
        },
        labels,
    )
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

    /// No vectors yet, each of length `n`, with room for `count` of them.
    pub fn with_capacity(n: usize, count: usize) -> Self {
        Columns {
            n,
            data: Vec::with_capacity(n * count),
        }
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

/// Row halves of tall products: below this many multiply-adds a product is one.
const HALVES_FROM: usize = 1 << 20;

/// Where a product over n rows splits: in two halves from [`HALVES_FROM`]
/// multiply-adds, whatever the machine, so that its round-off does not depend on the
/// cores it runs on.
fn halves(n: usize, work: usize) -> usize {
    if work >= HALVES_FROM {
        n / 2
    } else {
        n
    }
}

/// Aᵀ B for tall A (n × k) and B (n × j), as the sum of the two row halves' products,
/// the second half's on a second thread: the stored Lanczos vectors are read by two
/// cores at once.
pub fn tall_gram(a: faer::MatRef<'_, f64>, b: faer::MatRef<'_, f64>) -> faer::Mat<f64> {
    let (n, k, j) = (a.nrows(), a.ncols(), b.ncols());
    let h = halves(n, n * k * j);
    let product = |a: faer::MatRef<'_, f64>, b: faer::MatRef<'_, f64>| {
        let mut c = faer::Mat::<f64>::zeros(k, j);
        matmul(c.as_mut(), Accum::Replace, a.transpose(), b, 1.0, Par::Seq);
        c
    };
    if h == n {
        return product(a, b);
    }
    let (top, bottom) = both(
        || product(a.subrows(0, h), b.subrows(0, h)),
        || product(a.subrows(h, n - h), b.subrows(h, n - h)),
    );
    top + bottom
}

/// W ← W + α Q C for tall W (n × k) and Q (n × j), each row half on its own thread.
pub fn tall_update(w: faer::MatMut<'_, f64>, q: faer::MatRef<'_, f64>, c: faer::MatRef<'_, f64>, alpha: f64) {
    let n = w.nrows();
    let h = halves(n, n * q.ncols() * c.ncols());
    let product = |w: faer::MatMut<'_, f64>, q: faer::MatRef<'_, f64>| {
        matmul(w, Accum::Add, q, c, alpha, Par::Seq);
    };
    if h == n {
        return product(w, q);
    }
    let (top, bottom) = w.split_at_row_mut(h);
    both(
        || product(top, q.subrows(0, h)),
        || product(bottom, q.subrows(h, n - h)),
    );
}

/// Makes the columns of `w` M-orthogonal to every vector of `q`, and returns their
/// M-image: classical Gram-Schmidt as two matrix products (C = Qᵀ M W, W ← W − Q C),
/// a second pass only when the first removed more than half of a column's squared
/// M-norm (Kahan's test: a pass that leaves at least 1/√2 of the norm leaves the column
/// orthogonal to working precision; Parlett, The Symmetric Eigenvalue Problem, 6-9). A
/// Lanczos block usually passes at once: the recurrence has already made it nearly
/// orthogonal. Each pass reads every stored vector twice, for all of W's columns at
/// once.
pub fn orthogonalise_columns(
    mut w: faer::MatMut<'_, f64>,
    q: &Columns,
    m_mul: &impl Fn(&[f64]) -> Vec<f64>,
) -> faer::Mat<f64> {
    let (n, k) = (w.nrows(), w.ncols());
    let m_of = |w: faer::MatRef<'_, f64>| {
        let mut mw = faer::Mat::<f64>::zeros(n, k);
        for c in 0..k {
            let y = m_mul(column(w, c));
            mw.col_mut(c).iter_mut().zip(y).for_each(|(a, b)| *a = b);
        }
        mw
    };
    let norms = |w: faer::MatRef<'_, f64>, mw: &faer::Mat<f64>| -> Vec<f64> {
        (0..k).map(|c| dot(column(w, c), column(mw.as_ref(), c))).collect()
    };
    let mut mw = m_of(w.as_ref());
    if q.is_empty() {
        return mw;
    }
    let mut before = norms(w.as_ref(), &mw);
    // Cᵀ = (MW)ᵀ Q, so that the product packs the small factor, not Q.
    for _ in 0..2 {
        let coefficients = tall_gram(mw.as_ref(), q.mat());
        tall_update(w.as_mut(), q.mat(), coefficients.transpose(), -1.0);
        mw = m_of(w.as_ref());
        let after = norms(w.as_ref(), &mw);
        if after.iter().zip(&before).all(|(a, b)| *a >= 0.5 * b) {
            break;
        }
        before = after;
    }
    mw
}

/// The Ritz values that may yet be wanted roots (in the range asked for, not more than
/// the count asked for less those `accepted`) and are not accepted. Each needs a Lanczos
/// vector or more to converge (the paper's plate: two a root near its end), and there
/// are no more of them than roots in the range (Cauchy's interlacing: T's k-th largest
/// θ is at most A's), so a test that many vectors on, and no sooner, skips tests that
/// cannot succeed and comes at most that many vectors after the extraction converged.
fn pending(
    theta: &[f64],
    residual: &[f64],
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
    accepted: &[(f64, usize)],
) -> usize {
    let floor = roots.below.map_or(0.0, |b| 1.0 / (b - shift));
    let left = (0..theta.len())
        .filter(|&i| theta[i] > 0.0 && theta[i] >= floor && residual[i] > params.tolerance * theta[i])
        .count();
    roots.count.map_or(left, |c| left.min(c.saturating_sub(accepted.len())))
}

/// The same wanted roots, to `tol` relative.
fn same(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= tol.sqrt() * x.abs().max(y.abs()).max(f64::MIN_POSITIVE))
}

type Pairs = Vec<(f64, Vec<f64>)>;

/// A symmetric band matrix of order `j`: its lower triangle within `band` + 1 of the
/// diagonal (one more than its band, for the bulge a rotation makes), by diagonals.
struct Band {
    j: usize,
    band: usize,
    lower: Vec<f64>,
}

impl Band {
    fn new(j: usize, band: usize) -> Self {
        Band {
            j,
            band,
            lower: vec![0.0; (band + 2) * j],
        }
    }

    fn at(&self, r: usize, c: usize) -> usize {
        let (r, c) = if r >= c { (r, c) } else { (c, r) };
        debug_assert!(r - c <= self.band + 1, "({r}, {c}) outside the band {}", self.band);
        (r - c) * self.j + c
    }

    fn get(&self, r: usize, c: usize) -> f64 {
        self.lower[self.at(r, c)]
    }

    fn set(&mut self, r: usize, c: usize, v: f64) {
        let i = self.at(r, c);
        self.lower[i] = v;
    }
}

/// T, the block tridiagonal matrix of `diag` and `sub` (A_k on the diagonal, B_{k+1}
/// below), as a band matrix as wide as its widest block.
fn block_tridiagonal(diag: &[DMatrix<f64>], sub: &[DMatrix<f64>]) -> Band {
    let j: usize = diag.iter().map(|a| a.nrows()).sum();
    let mut t = Band::new(j, diag.iter().map(|a| a.nrows()).max().unwrap_or(0));
    let mut off = 0;
    for (k, a) in diag.iter().enumerate() {
        let w = a.nrows();
        for r in 0..w {
            for c in 0..=r {
                t.set(off + r, off + c, a[(r, c)]);
            }
        }
        if off + w < j {
            let b = &sub[k];
            // B is upper trapezoidal: its row r starts at column r.
            for r in 0..b.nrows() {
                for c in r..b.ncols() {
                    t.set(off + w + r, off + c, b[(r, c)]);
                }
            }
        }
        off += w;
    }
    t
}

/// T's reduction to tridiagonal: its diagonal, its sub-diagonal and (when asked) the
/// rotations of [`band_to_tridiagonal`].
struct Reduced {
    alpha: Vec<f64>,
    beta: Vec<f64>,
    rotations: Vec<(usize, f64, f64)>,
}

/// The Ritz values θ of T and the residual of each Ritz pair, ‖B_{k+1} s_k‖ (s_k the
/// last block's components of its unit eigenvector of T): T reduced to tridiagonal by
/// [`band_to_tridiagonal`], then [`tridiagonal_values`], with the reductions'
/// rotations applied to the last block's rows of the eigenvector matrix only. O(j² p)
/// for j vectors in blocks of p, where a dense solve is O(j³). Also the reduction,
/// its rotations recorded when `record`.
fn block_ritz_values(diag: &[DMatrix<f64>], sub: &[DMatrix<f64>], record: bool) -> (Vec<f64>, Vec<f64>, Reduced) {
    let mut t = block_tridiagonal(diag, sub);
    let j = t.j;
    let p = diag.last().map_or(0, |a| a.nrows());
    let mut rows: Vec<Vec<f64>> = (0..p)
        .map(|r| {
            let mut e = vec![0.0; j];
            e[j - p + r] = 1.0;
            e
        })
        .collect();
    let mut rotations = Vec::new();
    let (alpha, beta) = band_to_tridiagonal(&mut t, &mut rows, record.then_some(&mut rotations));
    let theta = tridiagonal_values(&alpha, &beta, &mut rows);
    let b = sub.last().expect("a block was taken");
    let residual = (0..j)
        .map(|i| {
            (0..b.nrows())
                .map(|r| (0..p).map(|c| b[(r, c)] * rows[c][i]).sum::<f64>().powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    (theta, residual, Reduced { alpha, beta, rotations })
}

/// The wanted roots λ = σ + 1/θ of T, each with its unit eigenvector of T: the Ritz
/// values and residuals of [`block_ritz_values`] (those the last test read), taken as
/// [`ritz_values`] takes them; the tridiagonal's eigenvectors for the wanted θ alone by
/// [`tridiagonal_vectors`], and the reduction's rotations applied to them. (nalgebra's
/// dense solver on the tridiagonal formed all j eigenvectors, O(j³), for the wanted
/// ones; faer's dense solver on T itself gave vectors as accurate in norm, but their
/// last components, which the residual reads, only to about 1e-8 of θ on the paper's
/// plate: it accepted 102 of its 163 converged roots.)
fn ritz_pairs(
    diag: &[DMatrix<f64>],
    sub: &[DMatrix<f64>],
    exhausted: bool,
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
) -> Pairs {
    if diag.is_empty() {
        return Vec::new();
    }
    let (theta, residual, t) = block_ritz_values(diag, sub, true);
    let (_, wanted) = ritz_values(&theta, &residual, exhausted, shift, roots, params);
    let values: Vec<f64> = wanted.iter().map(|&(_, i)| theta[i]).collect();
    let vectors = tridiagonal_vectors(&t.alpha, &t.beta, &values);
    wanted
        .into_iter()
        .zip(vectors)
        .map(|((lambda, _), mut s)| {
            // T's eigenvector Z u: the reduction's rotations applied to u in reverse.
            for &(p, c, sn) in t.rotations.iter().rev() {
                let (x, y) = (s[p], s[p + 1]);
                s[p] = c * x - sn * y;
                s[p + 1] = sn * x + c * y;
            }
            (lambda, s)
        })
        .collect()
}

/// Unit eigenvectors of the symmetric tridiagonal matrix with `alpha` on its diagonal
/// and `beta` beside it, for its eigenvalues `values` (as [`tridiagonal_values`] gives
/// them): inverse iteration, as LAPACK's dstein (Dhillon's survey, 1998; Wilkinson,
/// The Algebraic Eigenvalue Problem, 5.54). T − θI is factorised by Gaussian
/// elimination with partial pivoting (a pivot under ε‖T‖ taken as ε‖T‖), and three
/// solves from a fixed pseudo-random start: with θ exact to round-off, the first
/// already grows the wanted vector by about 1/ε against the rest, and the vector's
/// residual is then about ε‖T‖, as QR's. Values closer than 1e-3‖T‖ to the one before
/// form a cluster, whose vectors are kept orthogonal to each other at every solve
/// (and a value equal to the one before moved by 10 ε|θ|, so that a repeated root's
/// copies are solved apart): O(j) a vector, O(j k²) for a cluster of k.
fn tridiagonal_vectors(alpha: &[f64], beta: &[f64], values: &[f64]) -> Vec<Vec<f64>> {
    let j = alpha.len();
    let norm = (0..j)
        .map(|i| alpha[i].abs() + if i > 0 { beta[i - 1].abs() } else { 0.0 } + beta.get(i).map_or(0.0, |b| b.abs()))
        .fold(0.0_f64, f64::max);
    let tiny = f64::EPSILON * norm.max(f64::MIN_POSITIVE);
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut out: Vec<Vec<f64>> = vec![Vec::new(); values.len()];
    let mut rng = Start(0x5EED_7A1E);
    let mut cluster: Vec<usize> = Vec::new();
    let mut last: Option<f64> = None;
    for &w in &order {
        let mut theta = values[w];
        if let Some(l) = last {
            if theta - l > 1e-3 * norm {
                cluster.clear();
            }
            if theta - l < 10.0 * f64::EPSILON * theta.abs() {
                theta = l + 10.0 * f64::EPSILON * theta.abs().max(tiny);
            }
        }
        last = Some(theta);
        // T − θI = P L U: U's diagonal and two above it, L's multipliers, and whether
        // each step swapped its two rows.
        let (mut d, mut u1, mut u2) = (vec![0.0; j], vec![0.0; j], vec![0.0; j]);
        let (mut l, mut swap) = (vec![0.0; j], vec![false; j]);
        let guard = |v: f64| if v.abs() < tiny { tiny.copysign(v) } else { v };
        let mut diag = alpha[0] - theta;
        let mut up = beta.first().copied().unwrap_or(0.0);
        for i in 0..j {
            if i + 1 == j {
                d[i] = guard(diag);
                break;
            }
            let (below, next_diag, next_up) = (beta[i], alpha[i + 1] - theta, beta.get(i + 1).copied().unwrap_or(0.0));
            if below.abs() > diag.abs() {
                // Row i + 1 becomes the pivot row.
                swap[i] = true;
                d[i] = below;
                u1[i] = next_diag;
                u2[i] = next_up;
                let m = diag / below;
                l[i] = m;
                diag = up - m * next_diag;
                up = -m * next_up;
            } else {
                let pivot = guard(diag);
                d[i] = pivot;
                u1[i] = up;
                let m = below / pivot;
                l[i] = m;
                diag = next_diag - m * up;
                up = next_up;
            }
        }
        // Three solves, each from a vector orthogonal to the cluster's, and the last
        // result made orthogonal to them once more; unit length after each.
        let mut x: Vec<f64> = (0..j).map(|_| rng.next()).collect();
        for solve in [true, true, true, false] {
            for &c in &cluster {
                let h = dot(&out[c], &x);
                x.iter_mut().zip(&out[c]).for_each(|(a, b)| *a -= h * b);
            }
            if solve {
                // Forward: L⁻¹ with the row swaps.
                for i in 0..j.saturating_sub(1) {
                    if swap[i] {
                        x.swap(i, i + 1);
                    }
                    x[i + 1] -= l[i] * x[i];
                }
                // Back: U⁻¹.
                for i in (0..j).rev() {
                    let mut v = x[i];
                    if i + 1 < j {
                        v -= u1[i] * x[i + 1];
                    }
                    if i + 2 < j {
                        v -= u2[i] * x[i + 2];
                    }
                    x[i] = v / d[i];
                }
            }
            let size = dot(&x, &x).sqrt();
            x.iter_mut().for_each(|v| *v /= size);
        }
        out[w] = x;
        cluster.push(w);
    }
    out
}

/// The wanted roots λ = σ + 1/θ from the Ritz values θ of T and the residual of each
/// Ritz pair: a pair is accepted when its residual is at most `tolerance`·θ; all of the
/// wanted roots when they and every root below them are accepted (`None` while not),
/// and each accepted one with its index in `theta`. When the space is `exhausted`
/// (every vector with mass spanned) T's roots are exact.
fn ritz_values(
    theta: &[f64],
    residual: &[f64],
    exhausted: bool,
    shift: f64,
    roots: &Roots,
    params: &LanczosParams,
) -> (Option<Vec<f64>>, Vec<(f64, usize)>) {
    let top = theta.iter().fold(0.0_f64, |a, &b| a.max(b.abs()));
    // θ ≤ 0 (to round-off) belongs to no finite root.
    let mut found: Vec<(f64, bool, usize)> = (0..theta.len())
        .filter(|&i| theta[i] > 1e-12 * top)
        .map(|i| {
            let accepted = exhausted || residual[i] <= params.tolerance * theta[i];
            (shift + 1.0 / theta[i], accepted, i)
        })
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut wanted = Vec::new();
    let mut complete = exhausted;
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
    (complete.then(|| wanted.iter().map(|w| w.0).collect()), wanted)
}

/// A symmetric band matrix reduced to tridiagonal by Givens rotations, chasing each
/// bulge down the band (Schwarz, Numer. Math. 12, 1968; LAPACK's dsbtrd): O(j² band)
/// work. Returns the diagonal and the sub-diagonal; each rotation is also applied to
/// the columns of the `rows` (rows of the eigenvector matrix, so that they end as the
/// same rows of Z with T = Z tridiag Zᵀ) and, when asked, recorded as (p, c, s): the
/// rotation [c s; −s c] in the plane (p, p + 1). `t` is overwritten.
fn band_to_tridiagonal(
    t: &mut Band,
    rows: &mut [Vec<f64>],
    mut rotations: Option<&mut Vec<(usize, f64, f64)>>,
) -> (Vec<f64>, Vec<f64>) {
    let (j, band) = (t.j, t.band);
    // The similarity G t Gᵀ of the rotation [c s; −s c] in the plane (p, p + 1), over
    // the entries that can be nonzero: within band + 1 of the diagonal.
    let mut rotate = |t: &mut Band, p: usize, c: f64, s: f64| {
        let q = p + 1;
        let (lo, hi) = (q.saturating_sub(band + 1), (p + band + 2).min(j));
        for k in lo..hi {
            if k == p || k == q {
                continue;
            }
            let (x, y) = (t.get(p, k), t.get(q, k));
            t.set(p, k, c * x + s * y);
            t.set(q, k, -s * x + c * y);
        }
        let (a, b, d) = (t.get(p, p), t.get(q, p), t.get(q, q));
        t.set(p, p, c * c * a + 2.0 * c * s * b + s * s * d);
        t.set(q, q, s * s * a - 2.0 * c * s * b + c * c * d);
        t.set(q, p, (c * c - s * s) * b + c * s * (d - a));
        for z in rows.iter_mut() {
            let (x, y) = (z[p], z[q]);
            z[p] = c * x + s * y;
            z[q] = -s * x + c * y;
        }
        if let Some(r) = rotations.as_deref_mut() {
            r.push((p, c, s));
        }
    };
    // The rotation in the plane (p, p + 1) that zeros t(p + 1, k) against t(p, k).
    let mut zero = |t: &mut Band, p: usize, k: usize| {
        let (x, y) = (t.get(p, k), t.get(p + 1, k));
        if y != 0.0 {
            let r = pythag(x, y);
            rotate(t, p, x / r, y / r);
            t.set(p + 1, k, 0.0);
        }
    };
    if band > 1 {
        for k in 0..j.saturating_sub(2) {
            for i in ((k + 2)..=(k + band).min(j - 1)).rev() {
                zero(t, i - 1, k);
                // The bulge at (i + band, i − 1), chased down the band.
                let mut at = i;
                while at + band < j {
                    zero(t, at + band - 1, at - 1);
                    at += band;
                }
            }
        }
    }
    let alpha = (0..j).map(|i| t.get(i, i)).collect();
    let beta = (0..j.saturating_sub(1)).map(|i| t.get(i + 1, i)).collect();
    (alpha, beta)
}

/// √(a² + b²) without overflow or underflow in the squares (one division where the
/// C library's hypot takes pains over the last bit).
fn pythag(a: f64, b: f64) -> f64 {
    let (a, b) = (a.abs(), b.abs());
    let (big, small) = if a >= b { (a, b) } else { (b, a) };
    if big == 0.0 {
        return 0.0;
    }
    let r = small / big;
    big * (1.0 + r * r).sqrt()
}

/// The eigenvalues of the symmetric tridiagonal matrix with `alpha` on its diagonal
/// and `beta` beside it: the implicit QL algorithm with Wilkinson's shift (Bowdler,
/// Martin, Reinsch and Wilkinson, Numer. Math. 11, 1968: tql2), its rotations applied
/// to the given `rows` of the eigenvector matrix only (the last row of the identity
/// gives the last component of each unit eigenvector). A zero β splits the matrix; its
/// blocks converge apart.
fn tridiagonal_values(alpha: &[f64], beta: &[f64], rows: &mut [Vec<f64>]) -> Vec<f64> {
    let n = alpha.len();
    let mut d = alpha.to_vec();
    let mut e: Vec<f64> = beta.iter().copied().chain(std::iter::once(0.0)).take(n).collect();
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
            let mut r = pythag(g, 1.0);
            g = d[m] - d[l] + e[l] / (g + r.copysign(g));
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut split = false;
            for i in (l..m).rev() {
                let f = s * e[i];
                let b = c * e[i];
                r = pythag(f, g);
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
                for z in rows.iter_mut() {
                    let zf = z[i + 1];
                    z[i + 1] = s * z[i] + c * zf;
                    z[i] = c * z[i] - s * zf;
                }
            }
            if split {
                continue;
            }
            d[l] -= p;
            e[l] = g;
            e[m] = 0.0;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of `n` unit masses joined by unit springs, the first held to the ground
    /// by one, the last free, and its roots in closed form: λ_j = 4 sin²((2j − 1)π /
    /// (2(2n + 1))), j = 1..n (the fixed-free string of beads; Gantmacher and Krein,
    /// Oscillation Matrices and Kernels, II §1).
    fn fixed_free_chain(n: usize) -> (System, Vec<DofLabel>, Vec<f64>) {
        let mut k = Vec::new();
        for i in 0..n {
            k.push((i, i, if i + 1 < n { 2.0 } else { 1.0 }));
            if i + 1 < n {
                k.push((i, i + 1, -1.0));
                k.push((i + 1, i, -1.0));
            }
        }
        let m = (0..n).map(|i| (i, i, 1.0)).collect();
        let labels = (0..n)
            .map(|i| DofLabel {
                point: i as i64 + 1,
                comp: 1,
            })
            .collect();
        let exact = (1..=n)
            .map(|j| {
                let x = (2 * j - 1) as f64 * std::f64::consts::PI / (2 * (2 * n + 1)) as f64;
                4.0 * x.sin().powi(2)
            })
            .collect();
        (System::from_entries(n, k, m, Vec::new()), labels, exact)
    }

    /// Goal: a fault in the re-orthogonalisation stops the extraction with the
    /// orthogonality error, not with wrong roots or without end. Model: the fixed-free
    /// chain of 2 000 beads, its lowest 200 roots asked for, against the closed form.
    /// Sound, they are found to 1e-12 of the largest asked for (measured 4.2e-13: an
    /// accepted root is exact to about the square of the 1e-10 acceptance, and what is
    /// left is round-off, ε‖K‖ ≈ 9e-16 being 9e-15 of the 200th root, 0.0974). With each step's
    /// block only given its M-image (no re-orthogonalisation against the stored
    /// vectors: the three-term recurrence alone, which loses orthogonality as Ritz
    /// values converge, Paige 1971), the newest block's overlap with the first passes
    /// √ε and the extraction stops with [`SolveError::Orthogonality`] (measured: at 16
    /// vectors, 1.5e-5; the sound run takes 412). Without the check the faulty run went
    /// on past four times the sound run's vectors: it is bounded there, so that it
    /// fails with the memory error rather than running on.
    #[test]
    fn a_fault_in_the_reorthogonalisation_stops_the_extraction() {
        let (sys, labels, exact) = fixed_free_chain(2000);
        let roots = Roots {
            above: f64::NEG_INFINITY,
            below: None,
            count: Some(200),
        };
        let params = LanczosParams::default();
        let (mut factor, shift) = factorise(&sys, &labels).unwrap();
        let sound = lanczos_with(&sys, &mut factor, shift, &roots, &params, &|_| {}).unwrap();
        assert_eq!(sound.values.len(), 200);
        let worst = sound
            .values
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs() / exact[199])
            .fold(0.0_f64, f64::max);
        assert!(worst < 1e-12, "sound extraction off the closed form by {worst:e}");
        let none: Reorthogonalise = |w, _, m_mul| orthogonalise_columns(w, &Columns::new(0), &m_mul);
        // Bounded, so that without the check it fails rather than running on.
        let bounded = LanczosParams {
            max_vectors: Some(4 * sound.lanczos_vectors),
            ..params
        };
        match extract(&sys, &mut factor, shift, &roots, &bounded, &|_| {}, none) {
            Err(SolveError::Orthogonality { vectors, loss }) => {
                assert!(loss > f64::EPSILON.sqrt(), "{vectors} vectors, loss {loss:e}")
            }
            Err(e) => panic!("another error: {e}"),
            Ok(p) => panic!(
                "no error: {} roots from {} vectors, the first {:?}",
                p.values.len(),
                p.lanczos_vectors,
                &p.values[..5]
            ),
        }
    }

    /// Goal: the products in row halves are the whole products, to round-off (1e-14
    /// of the largest term's size), on an odd number of rows (the halves unequal),
    /// above and below the size where they split; and each half is computed (a
    /// fault that drops the second half's rows or its share of the sum fails).
    #[test]
    fn products_in_row_halves_are_the_whole_products() {
        let mut rng = Start(7);
        for (n, k, j) in [(20_001, 4, 30), (31, 4, 5)] {
            let a = faer::Mat::<f64>::from_fn(n, k, |_, _| rng.next());
            let q = faer::Mat::<f64>::from_fn(n, j, |_, _| rng.next());
            let c = faer::Mat::<f64>::from_fn(j, k, |_, _| rng.next());
            assert_eq!(halves(n, n * k * j) < n, n > 1000, "where the products split");
            let mut whole = faer::Mat::<f64>::zeros(k, j);
            matmul(whole.as_mut(), Accum::Replace, a.transpose(), q.as_ref(), 1.0, Par::Seq);
            let gram = tall_gram(a.as_ref(), q.as_ref());
            let scale = n as f64;
            assert!((&gram - &whole).norm_max() <= 1e-14 * scale, "AᵀQ");
            let mut w = a.clone();
            let mut expected = a.clone();
            matmul(expected.as_mut(), Accum::Add, q.as_ref(), c.as_ref(), -0.5, Par::Seq);
            tall_update(w.as_mut(), q.as_ref(), c.as_ref(), -0.5);
            assert!((&w - &expected).norm_max() <= 1e-14 * j as f64, "W − ½QC");
        }
    }

    /// Goal: the band reduction and QL give a block tridiagonal T's values and the
    /// residuals ‖B s_k‖ of the dense solver, on three blocks of four and seven of
    /// three (a block narrowing, as where the space runs out), with upper-trapezoidal
    /// B and one B zero (T split there): values to 1e-13 of the largest, residuals to
    /// 1e-10 (B's entries are of order 1).
    #[test]
    fn band_reduction_gives_the_dense_ritz_values_and_residuals() {
        let mut rng = Start(7);
        let widths = [4, 4, 4, 3, 3, 3, 3, 3, 3, 3];
        let diag: Vec<DMatrix<f64>> = widths
            .iter()
            .enumerate()
            .map(|(k, &w)| {
                let a = DMatrix::from_fn(w, w, |_, _| rng.next());
                &a + a.transpose() + DMatrix::from_diagonal_element(w, w, k as f64)
            })
            .collect();
        let sub: Vec<DMatrix<f64>> = (0..widths.len())
            .map(|k| {
                let (r, c) = (widths.get(k + 1).copied().unwrap_or(3), widths[k]);
                DMatrix::from_fn(r, c, |i, j| if i <= j && k != 5 { rng.next() } else { 0.0 })
            })
            .collect();
        let (theta, residual, _) = block_ritz_values(&diag, &sub, false);
        let band = block_tridiagonal(&diag, &sub);
        assert_eq!(band.band, 4);
        let j = band.j;
        let t = faer::Mat::<f64>::from_fn(j, j, |r, c| if r.abs_diff(c) <= 5 { band.get(r, c) } else { 0.0 });
        let e = t.self_adjoint_eigen(faer::Side::Lower).unwrap();
        let b = sub.last().unwrap();
        let mut dense: Vec<(f64, f64)> = (0..j)
            .map(|i| {
                let r: f64 = (0..b.nrows())
                    .map(|r| (0..3).map(|c| b[(r, c)] * e.U()[(j - 3 + c, i)]).sum::<f64>().powi(2))
                    .sum();
                (e.S().column_vector()[i], r.sqrt())
            })
            .collect();
        let mut ours: Vec<(f64, f64)> = theta.into_iter().zip(residual).collect();
        ours.sort_by(|a, b| a.0.total_cmp(&b.0));
        dense.sort_by(|a, b| a.0.total_cmp(&b.0));
        let top = dense.iter().fold(0.0f64, |a, b| a.max(b.0.abs()));
        for (a, d) in ours.iter().zip(&dense) {
            assert!((a.0 - d.0).abs() <= 1e-13 * top, "{a:?} vs {d:?}");
            assert!((a.1 - d.1).abs() <= 1e-10, "{a:?} vs {d:?}");
        }
    }

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
        let mut rows = vec![(0..n).map(|i| if i == n - 1 { 1.0 } else { 0.0 }).collect::<Vec<f64>>()];
        let values = tridiagonal_values(&alpha, &beta, &mut rows);
        let last = &rows[0];
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

    /// Goal: inverse iteration gives unit eigenvectors with residuals ‖T x − θ x‖ of
    /// round-off (1e-13 of ‖T‖) and orthogonal to 1e-12, on a tridiagonal matrix of 60
    /// rows made of two identical blocks (β zero between them: every root twice, as
    /// two identical free structures give), a third block whose roots are 1e-6 of the
    /// largest and closer than 1e-3 of it to each other (one cluster, as a Lanczos T's
    /// high roots are), and a nearly repeated pair; the values from the QL.
    #[test]
    fn inverse_iteration_gives_orthogonal_vectors_of_repeated_and_clustered_roots() {
        let block: Vec<f64> = (0..20)
            .map(|i| ((i * 7) % 11) as f64 + 0.5 * (i as f64).sin())
            .collect();
        let off: Vec<f64> = (0..19).map(|i| 0.3 + ((i * 5) % 7) as f64 * 0.1).collect();
        let mut alpha = block.clone();
        alpha.extend(&block);
        alpha.extend((0..20).map(|i| 1e-6 * (1.0 + 0.1 * i as f64)));
        let mut beta = off.clone();
        beta.push(0.0);
        beta.extend(&off);
        beta.push(1e-12);
        beta.extend((0..19).map(|i| if i == 9 { 1e-14 } else { 1e-8 }));
        let n = alpha.len();
        let values = tridiagonal_values(&alpha, &beta, &mut []);
        let vectors = tridiagonal_vectors(&alpha, &beta, &values);
        let norm = 11.5 + 2.0;
        for (theta, x) in values.iter().zip(&vectors) {
            assert!((dot(x, x) - 1.0).abs() < 1e-14);
            let r: f64 = (0..n)
                .map(|i| {
                    let mut tx = alpha[i] * x[i];
                    if i > 0 {
                        tx += beta[i - 1] * x[i - 1];
                    }
                    if i + 1 < n {
                        tx += beta[i] * x[i + 1];
                    }
                    (tx - theta * x[i]).powi(2)
                })
                .sum::<f64>()
                .sqrt();
            assert!(r <= 1e-13 * norm, "θ {theta:e}: residual {r:e}");
        }
        for a in 0..n {
            for b in 0..a {
                let c = dot(&vectors[a], &vectors[b]).abs();
                assert!(
                    c <= 1e-12,
                    "vectors {a} and {b} ({:e}, {:e}): {c:e}",
                    values[a],
                    values[b]
                );
            }
        }
    }
}
