//! Small numerics shared by every stage: interpolation, zero crossings, least-squares
//! slopes, medians. Plain functions of slices; nothing here knows about models.

/// Linear interpolation of samples y(t) at x; zero outside (t₀, t_last] (a signal
/// that starts at rest and is recorded until it ends).
pub fn interp(t: &[f64], y: &[f64], x: f64) -> f64 {
    if t.is_empty() || x <= t[0] || x > t[t.len() - 1] {
        return 0.0;
    }
    let k = t.partition_point(|&s| s < x).max(1);
    let w = (x - t[k - 1]) / (t[k] - t[k - 1]);
    y[k - 1] * (1.0 - w) + y[k] * w
}

/// The time where y crosses zero between samples k−1 and k, by linear interpolation.
pub fn crossing(t: &[f64], y: &[f64], k: usize) -> f64 {
    let (y0, y1) = (y[k - 1], y[k]);
    if y1 == y0 {
        return t[k];
    }
    t[k - 1] + (t[k] - t[k - 1]) * (y0 / (y0 - y1))
}

/// Least-squares slope of y against x.
pub fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// Observed order of convergence: the least-squares slope of log(error) against
/// log(step), over the pairs with a positive step and a finite error above `floor`
/// (errors at round-off say nothing about the order); NaN with fewer than `min` pairs.
pub fn order(steps: &[f64], errors: &[f64], floor: f64, min: usize) -> f64 {
    let (lx, ly): (Vec<f64>, Vec<f64>) = steps
        .iter()
        .zip(errors)
        .filter(|(h, e)| **h > 0.0 && **e > floor && e.is_finite())
        .map(|(h, e)| (h.ln(), e.ln()))
        .unzip();
    if lx.len() < min {
        return f64::NAN;
    }
    slope(&lx, &ly)
}

/// The order p and the Richardson extrapolation w∞ of a quantity w on three meshes of
/// sizes `h` (coarse to fine), from w(h) = w∞ + C hᵖ: p solves
/// (w₁ − w₂)/(w₂ − w₃) = (h₁ᵖ − h₂ᵖ)/(h₂ᵖ − h₃ᵖ) for the ratio's magnitude, in closed
/// form when the meshes refine by one factor (p = ln|ratio| / ln(h₁/h₂)), otherwise by
/// bisection over 0.1 ≤ p ≤ 8. Where the changes alternate in sign (a negative
/// ratio) no such p exists and the pair says nothing: the caller checks the sign.
pub fn three_mesh_order(h: [f64; 3], w: [f64; 3]) -> (f64, f64) {
    let ratio = ((w[0] - w[1]) / (w[1] - w[2])).abs();
    let (r1, r2) = (h[0] / h[1], h[1] / h[2]);
    let p = if (r1 - r2).abs() <= 1e-12 * r1 {
        ratio.ln() / r1.ln()
    } else {
        let g = |p: f64| (h[0].powf(p) - h[1].powf(p)) / (h[1].powf(p) - h[2].powf(p)) - ratio;
        let (mut lo, mut hi) = (0.1, 8.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if g(lo) * g(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let extrapolated = w[2] - (w[1] - w[2]) * h[2].powf(p) / (h[1].powf(p) - h[2].powf(p));
    (p, extrapolated)
}

/// Median of a sample (the upper one of an even count).
pub fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// Index and value of the largest item (the first of equals).
pub fn argmax(it: impl Iterator<Item = f64>) -> (usize, f64) {
    it.enumerate()
        .fold((0, f64::NEG_INFINITY), |a, (k, v)| if v > a.1 { (k, v) } else { a })
}

/// Runs `first` on this thread and `second` on a second one at once, and returns
/// both results: how a stage splits its work over the machine's two cores. The
/// split is the caller's, fixed by the sizes (never by the cores there are), so
/// that the round-off is the same on any machine.
pub fn both<A, B: Send>(first: impl FnOnce() -> A, second: impl FnOnce() -> B + Send) -> (A, B) {
    std::thread::scope(|s| {
        let second = s.spawn(second);
        (first(), second.join().expect("the second core's share"))
    })
}

/// Column `c` of a matrix as a slice.
pub fn column(m: faer::MatRef<'_, f64>, c: usize) -> &[f64] {
    m.col(c).try_as_col_major().expect("a column of a Mat").as_slice()
}

/// Column `c` of a matrix as a slice, to change.
pub fn column_mut(m: faer::MatMut<'_, f64>, c: usize) -> &mut [f64] {
    m.col_mut(c)
        .try_as_col_major_mut()
        .expect("a column of a Mat")
        .as_slice_mut()
}

/// The eigenpairs of a symmetric matrix, each eigenvector with its own eigenvalue,
/// checked. nalgebra's `symmetric_eigen` can hand a vector another vector's eigenvalue
/// (its issue 1109, open): on the paper's free rod with every mode kept, the modal
/// engine's two lowest held modes came back swapped. Where a vector's Rayleigh quotient
/// and its eigenvalue disagree past 1e-10 of the largest, every vector is given its
/// quotient. Its QR iteration can also run without end (its issue 1025, open): it is
/// given at most 30 sweeps a root (LAPACK's `dsteqr` allows as many). What comes out
/// is checked, ‖AY − YΛ‖ at most 1e-10 of the largest |λ| and ‖YᵀY − I‖ at most 1e-10
/// (entry by entry: a backward-stable decomposition leaves about n·ε, under 1e-13 for
/// the few hundred rows of a held-mode problem, and the faults seen leave 6.5e-6 and
/// more); where the iteration stopped or the check fails, faer's
/// `self_adjoint_eigen` decomposes `a` instead. Where nalgebra's decomposition is
/// sound (every model run here), it is returned as it comes, in nalgebra's order.
pub fn symmetric_eigen<D>(a: nalgebra::OMatrix<f64, D, D>) -> nalgebra::SymmetricEigen<f64, D>
where
    D: nalgebra::DimSub<nalgebra::U1>,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D>
        + nalgebra::allocator::Allocator<nalgebra::DimDiff<D, nalgebra::U1>>
        + nalgebra::allocator::Allocator<D>,
{
    let sweeps = 30 * a.nrows().max(1);
    checked(a.clone().try_symmetric_eigen(f64::EPSILON, sweeps), &a)
}

/// The eigenvalues of a symmetric matrix, those of [`symmetric_eigen`] (bit for bit
/// those of nalgebra's `symmetric_eigenvalues`, which iterates without a bound, where
/// its decomposition is sound).
pub fn symmetric_eigenvalues<D>(a: nalgebra::OMatrix<f64, D, D>) -> nalgebra::OVector<f64, D>
where
    D: nalgebra::DimSub<nalgebra::U1>,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D>
        + nalgebra::allocator::Allocator<nalgebra::DimDiff<D, nalgebra::U1>>
        + nalgebra::allocator::Allocator<D>,
{
    symmetric_eigen(a).eigenvalues
}

/// nalgebra's decomposition of `a` (`None`: its iteration stopped) paired, kept when
/// it decomposes `a`, faer's otherwise (see [`symmetric_eigen`]).
fn checked<D>(
    eig: Option<nalgebra::SymmetricEigen<f64, D>>,
    a: &nalgebra::OMatrix<f64, D, D>,
) -> nalgebra::SymmetricEigen<f64, D>
where
    D: nalgebra::Dim,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D> + nalgebra::allocator::Allocator<D>,
{
    eig.map(|eig| paired(eig, a))
        .filter(|eig| decomposes(eig, a))
        .unwrap_or_else(|| faer_eigen(a))
}

/// `eig` is an eigendecomposition of `a` to 1e-10 (see [`symmetric_eigen`]).
fn decomposes<D>(eig: &nalgebra::SymmetricEigen<f64, D>, a: &nalgebra::OMatrix<f64, D, D>) -> bool
where
    D: nalgebra::Dim,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D> + nalgebra::allocator::Allocator<D>,
{
    let (y, values) = (&eig.eigenvectors, &eig.eigenvalues);
    let scale = values.amax();
    let ay = a * y;
    let residual = (0..y.ncols())
        .map(|c| (ay.column(c) - y.column(c) * values[c]).amax())
        .fold(0.0_f64, f64::max);
    let gram = y.transpose() * y;
    let orthogonality = (0..y.ncols())
        .flat_map(|c| (0..y.nrows()).map(move |r| (r, c)))
        .map(|(r, c)| (gram[(r, c)] - if r == c { 1.0 } else { 0.0 }).abs())
        .fold(0.0_f64, f64::max);
    // NaN fails both.
    residual <= 1e-10 * scale && orthogonality <= 1e-10
}

/// The eigenpairs of symmetric `a` by faer's `self_adjoint_eigen` (eigenvalues
/// ascending), as nalgebra's type; NaN where faer's fails too (a matrix with a NaN).
fn faer_eigen<D>(a: &nalgebra::OMatrix<f64, D, D>) -> nalgebra::SymmetricEigen<f64, D>
where
    D: nalgebra::Dim,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D> + nalgebra::allocator::Allocator<D>,
{
    let n = a.nrows();
    let (rows, cols) = a.shape_generic();
    match faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)]).self_adjoint_eigen(faer::Side::Lower) {
        Ok(eig) => {
            let (u, s) = (eig.U(), eig.S().column_vector());
            nalgebra::SymmetricEigen {
                eigenvectors: nalgebra::OMatrix::from_fn_generic(rows, cols, |i, j| u[(i, j)]),
                eigenvalues: nalgebra::OVector::from_fn_generic(rows, nalgebra::Const::<1>, |i, _| s[i]),
            }
        }
        Err(_) => nalgebra::SymmetricEigen {
            eigenvectors: nalgebra::OMatrix::from_element_generic(rows, cols, f64::NAN),
            eigenvalues: nalgebra::OVector::from_element_generic(rows, nalgebra::Const::<1>, f64::NAN),
        },
    }
}

/// `eig` with each vector given its Rayleigh quotient in `a` when some vector's
/// quotient and eigenvalue disagree (see [`symmetric_eigen`]).
fn paired<D>(
    mut eig: nalgebra::SymmetricEigen<f64, D>,
    a: &nalgebra::OMatrix<f64, D, D>,
) -> nalgebra::SymmetricEigen<f64, D>
where
    D: nalgebra::Dim,
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D> + nalgebra::allocator::Allocator<D>,
{
    let quotients: Vec<f64> = eig.eigenvectors.column_iter().map(|y| y.dot(&(a * y))).collect();
    let scale = eig.eigenvalues.amax();
    if quotients
        .iter()
        .zip(eig.eigenvalues.iter())
        .any(|(q, l)| (q - l).abs() > 1e-10 * scale)
    {
        eig.eigenvalues.iter_mut().zip(quotients).for_each(|(l, q)| *l = q);
    }
    eig
}

/// Σ a_i·b_i over the shorter length, in eight partial sums (lane i mod 8) added
/// pairwise at the end: eight independent chains of additions instead of one, which
/// the compiler vectorises. Its round-off is that of eight sums of N/8 terms.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for i in 0..8 {
            acc[i] += x[i] * y[i];
        }
    }
    for (i, (x, y)) in ra.iter().zip(rb).enumerate() {
        acc[i] += x * y;
    }
    ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: each helper on a case with a known answer.
    #[test]
    fn helpers_on_known_answers() {
        let t = [0.0, 1.0, 2.0];
        let y = [0.0, 2.0, -2.0];
        assert_eq!(interp(&t, &y, 0.5), 1.0);
        assert_eq!(interp(&t, &y, 2.5), 0.0);
        assert_eq!(crossing(&t, &y, 2), 1.5);
        let h = [0.1, 0.05, 0.025];
        let e: Vec<f64> = h.iter().map(|x: &f64| 3.0 * x * x).collect();
        assert!((order(&h, &e, 0.0, 3) - 2.0).abs() < 1e-12);
        assert!(order(&h, &e, 1.0, 3).is_nan());
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(argmax([1.0, 5.0, 5.0, 2.0].into_iter()), (1, 5.0));
    }

    /// Goal: three meshes give the order and the limit of w = w∞ + C hᵖ exactly.
    /// Model: w = 1 + 3h² on h = 4, 2, 1 (one refinement factor: the closed form) and on
    /// h = 1/24, 1/36, 1/48 (two factors: the bisection), and w = 2 − h^1.5 on the
    /// first. Reference: p and w∞ as built. Tolerance: 1e-12 (the bisection's width is
    /// 8·2⁻¹⁰⁰; the rest is round-off).
    #[test]
    fn three_meshes_give_the_order_and_the_limit() {
        let on = |h: [f64; 3], f: &dyn Fn(f64) -> f64| super::three_mesh_order(h, h.map(f));
        for h in [[4.0, 2.0, 1.0], [1.0 / 24.0, 1.0 / 36.0, 1.0 / 48.0]] {
            let (p, w) = on(h, &|h| 1.0 + 3.0 * h * h);
            assert!((p - 2.0).abs() < 1e-12 && (w - 1.0).abs() < 1e-12, "{h:?}: {p} {w}");
        }
        let (p, w) = on([4.0, 2.0, 1.0], &|h| 2.0 - h.powf(1.5));
        assert!((p - 1.5).abs() < 1e-12 && (w - 2.0).abs() < 1e-12, "{p} {w}");
    }

    /// Goal: an eigendecomposition whose vectors carry each other's eigenvalues (as
    /// nalgebra's issue 1109 returns them) is paired again, and a correct one is kept
    /// bit for bit. Model: a symmetric 3 × 3 with distinct eigenvalues, its
    /// decomposition with the first two eigenvalues swapped. Reference: A v = λ v for
    /// every pair, to 1e-12 of the largest eigenvalue.
    #[test]
    fn eigenvalues_are_paired_with_their_own_vectors() {
        let a = nalgebra::Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, -0.25, 0.5, -0.25, 1.0);
        let right = a.symmetric_eigen();
        let kept = symmetric_eigen(a);
        assert_eq!(kept.eigenvalues, right.eigenvalues);
        assert_eq!(kept.eigenvectors, right.eigenvectors);
        let mut swapped = right;
        swapped.eigenvalues.swap_rows(0, 1);
        let residual = |e: &nalgebra::SymmetricEigen<f64, nalgebra::U3>| {
            (0..3)
                .map(|i| {
                    let v = e.eigenvectors.column(i);
                    (a * v - v * e.eigenvalues[i]).norm()
                })
                .fold(0.0_f64, f64::max)
        };
        let top = right.eigenvalues.amax();
        assert!(residual(&swapped) > 0.1 * top, "the swap is a fault");
        let mended = paired(swapped, &a);
        assert!(residual(&mended) <= 1e-12 * top, "{}", residual(&mended));
    }

    /// Goal: a decomposition that is not one (vectors that are no eigenvectors, or an
    /// iteration that stopped) is replaced by faer's, and the matrix of nalgebra's
    /// issue 1109 comes out right. Models: a symmetric 3 × 3 whose first two
    /// eigenvectors are turned by 30° in their plane (orthonormal still, so only the
    /// check against A sees it); the issue's 4 × 4 (its numbers as published).
    /// Reference: A v = λ v for every pair, to 1e-12 of the largest |λ|, and YᵀY = I.
    /// (Measured on the issue's matrix with nalgebra 0.33.3: its decomposition alone
    /// leaves 6.5e-6, ours 2.7e-16.) Where nalgebra's decomposition is sound (three
    /// smooth symmetric matrices), the eigenvalues alone are its unbounded ones bit for
    /// bit.
    #[test]
    fn a_decomposition_that_is_none_is_replaced_by_faers() {
        fn sound<D>(e: &nalgebra::SymmetricEigen<f64, D>, a: &nalgebra::OMatrix<f64, D, D>) -> f64
        where
            D: nalgebra::Dim,
            nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D> + nalgebra::allocator::Allocator<D>,
        {
            let y = &e.eigenvectors;
            let worst = (0..y.ncols())
                .map(|i| (a * y.column(i) - y.column(i) * e.eigenvalues[i]).amax())
                .fold(0.0_f64, f64::max);
            let gram = y.transpose() * y;
            assert!(
                (gram - nalgebra::OMatrix::identity_generic(y.shape_generic().1, y.shape_generic().1)).amax() < 1e-13
            );
            worst / e.eigenvalues.amax()
        }
        let a = nalgebra::Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, -0.25, 0.5, -0.25, 1.0);
        let right = a.symmetric_eigen();
        let mut turned = right;
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (y0, y1) = (
            right.eigenvectors.column(0).into_owned(),
            right.eigenvectors.column(1).into_owned(),
        );
        turned.eigenvectors.set_column(0, &(y0 * c + y1 * s));
        turned.eigenvectors.set_column(1, &(y1 * c - y0 * s));
        assert!(sound(&turned, &a) > 0.01, "the turn is a fault");
        assert!(!decomposes(&paired(turned, &a), &a), "the pairing alone mends it");
        for (what, e) in [("turned", checked(Some(turned), &a)), ("stopped", checked(None, &a))] {
            assert!(sound(&e, &a) <= 1e-12, "{what}: {:e}", sound(&e, &a));
        }
        let kept = checked(Some(right), &a);
        assert_eq!(
            (kept.eigenvalues, kept.eigenvectors),
            (right.eigenvalues, right.eigenvectors)
        );
        #[rustfmt::skip]
        let issue = nalgebra::Matrix4::new(
            -19884.07, -10.07188, 11.277279, -188560.63,
            -10.07188, 12.518197, 1.3770627, -102.97504,
            11.277279, 1.3770627, 14.587362, 113.26099,
            -188560.63, -102.97504, 113.26099, -1788112.3,
        );
        let theirs = issue.symmetric_eigen();
        for n in [3, 6, 20] {
            let b = nalgebra::DMatrix::from_fn(n, n, |i, j| ((i * 7 + j * 3) as f64).sin());
            let b = &b + b.transpose();
            let bits = |v: nalgebra::DVector<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(symmetric_eigenvalues(b.clone())),
                bits(b.symmetric_eigenvalues()),
                "n = {n}"
            );
        }
        let ours = symmetric_eigen(issue);
        assert!(
            sound(&ours, &issue) <= 1e-12,
            "{:e}, nalgebra's alone {:e}",
            sound(&ours, &issue),
            sound(&theirs, &issue)
        );
    }
}
