//! The condensed contact equation of the implicit schemes.
//!
//! After the linear solve the new indentation satisfies h(α) = α − α* − s·ψ(α) = 0,
//! with α* the indentation of the contact-free predictor, s = c·A⁻¹g (< 0 for a
//! repulsive contact) and ψ the scheme's load factor, nondecreasing in α. Then h is
//! increasing and its root lies in [α* + s·ψ(α*), α*]: Newton's method safeguarded by
//! bisection inside that bracket always converges, to the last bit; it stops when a
//! Newton step moves α by less than a unit in the last place (quadratic convergence:
//! 2-4 iterations per contact step).

/// Solves h(α) = 0 with ψ and its derivative given; returns (α, iterations), or None
/// if 200 iterations did not shrink the bracket to round-off.
pub fn solve(alpha_star: f64, s: f64, psi: impl Fn(f64) -> (f64, f64)) -> Option<(f64, usize)> {
    let h = |a: f64| {
        let (p, dp) = psi(a);
        (a - alpha_star - s * p, 1.0 - s * dp)
    };
    let (h_star, _) = h(alpha_star);
    if h_star == 0.0 {
        return Some((alpha_star, 0));
    }
    let (mut lo, mut hi) = if h_star > 0.0 {
        (alpha_star + s * psi(alpha_star).0, alpha_star)
    } else {
        // Only when s > 0 (attractive loads): search upward.
        let mut step = alpha_star.abs().max(1e-300);
        let mut hi = alpha_star + step;
        while h(hi).0 < 0.0 {
            step *= 2.0;
            hi = alpha_star + step;
            if !hi.is_finite() {
                return None;
            }
        }
        (alpha_star, hi)
    };
    let mut a = hi;
    for it in 1..=200 {
        let (f, df) = h(a);
        if f == 0.0 {
            return Some((a, it));
        }
        if f > 0.0 {
            hi = a;
        } else {
            lo = a;
        }
        let newton = a - f / df;
        // Converged: the Newton step no longer moves α by a unit in the last place.
        // (Without this test a converged Newton estimate equal to the bracket's end
        // failed the strict bracket test below, and the bracket was halved from a lower
        // end that never moved until it collapsed: ~22 iterations instead of 2-4.)
        if df > 0.0 && (newton - a).abs() <= f64::EPSILON * a.abs() {
            return Some((a, it));
        }
        a = if df > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo <= 4.0 * f64::EPSILON * lo.abs().max(hi.abs()) || a == lo || a == hi {
            return Some((a, it));
        }
    }
    None
}

/// Five-point Gauss-Legendre nodes and weights on [0, 1].
pub(super) const GL5: [(f64, f64); 5] = [
    (0.046_910_077_030_668, 0.118_463_442_528_095),
    (0.230_765_344_947_158, 0.239_314_335_249_683),
    (0.5, 0.284_444_444_444_444),
    (0.769_234_655_052_842, 0.239_314_335_249_683),
    (0.953_089_922_969_332, 0.118_463_442_528_095),
];

/// Discrete gradient of W (W' = φ) between a0 and a1: (W(a1) − W(a0))/(a1 − a0).
/// When the two are close and on the same side of 0 the difference quotient loses
/// digits, so the mean of φ over the interval is integrated by Gauss-Legendre
/// instead (exact to round-off there: φ is smooth away from 0).
pub fn discrete_gradient(a0: f64, a1: f64, w: impl Fn(f64) -> f64, phi: impl Fn(f64) -> f64) -> f64 {
    let d = a1 - a0;
    let scale = a0.abs().max(a1.abs());
    if d == 0.0 {
        return phi(a0);
    }
    if d.abs() < 1e-2 * scale && (a0 > 0.0) == (a1 > 0.0) {
        return GL5.iter().map(|&(x, wt)| wt * phi(a0 + x * d)).sum();
    }
    (w(a1) - w(a0)) / d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hertz(a: f64) -> (f64, f64) {
        if a > 0.0 {
            (a.powf(1.5), 1.5 * a.sqrt())
        } else {
            (0.0, 0.0)
        }
    }

    #[test]
    fn root_satisfies_the_equation_to_round_off() {
        // The iterations each takes (measured): Newton stopped as soon as a step moves α
        // by less than an ulp. A stopping test that never fires costs iterations (10, 10,
        // 8: the bracket's own end test stops them).
        let most = [9, 10, 5, 0, 0];
        for (k, &(astar, s)) in [(1e-3, -1e4), (1e-12, -1e9), (5.0, -0.1), (-1e-3, -1e4), (1e-300, -1.0)]
            .iter()
            .enumerate()
        {
            let (a, iterations) = solve(astar, s, hertz).unwrap();
            assert!(iterations <= most[k], "{astar} {s}: {iterations} iterations");
            let r = a - astar - s * hertz(a).0;
            assert!(r.abs() <= 8.0 * f64::EPSILON * astar.abs(), "{astar} {s}: residual {r}");
            if astar <= 0.0 {
                assert_eq!(a, astar);
            }
        }
    }

    #[test]
    fn discrete_gradient_is_the_secant_of_w() {
        let w = |a: f64| if a > 0.0 { a.powf(2.5) / 2.5 } else { 0.0 };
        let phi = |a: f64| hertz(a).0;
        for &(a0, a1) in &[(1e-3, 1.0001e-3), (1e-3, 2e-3), (-1e-3, 1e-3), (2e-3, -1e-4)] {
            let dg = discrete_gradient(a0, a1, w, phi);
            let exact = (w(a1) - w(a0)) / (a1 - a0);
            assert!((dg - exact).abs() <= 1e-9 * exact.abs(), "{a0} {a1}: {dg} vs {exact}");
        }
    }

    /// Goal: for nearly equal indentations (d/α = 1e-10) the discrete gradient is the
    /// mean of φ over the interval to round-off, where the difference quotient of W
    /// would lose about ten digits. Reference: φ at the midpoint (the interval is so
    /// short that the mean and the midpoint value agree to 1e-20). Tolerance 1e-13.
    #[test]
    fn discrete_gradient_of_close_pairs_keeps_its_digits() {
        let w = |a: f64| if a > 0.0 { a.powf(2.5) / 2.5 } else { 0.0 };
        let phi = |a: f64| hertz(a).0;
        let (a0, a1) = (1e-3, 1e-3 * (1.0 + 1e-10));
        let dg = discrete_gradient(a0, a1, w, phi);
        let mid = phi(0.5 * (a0 + a1));
        assert!((dg - mid).abs() <= 1e-13 * mid, "{dg} vs {mid}");
        let quotient = (w(a1) - w(a0)) / (a1 - a0);
        assert!(
            (quotient - mid).abs() > 1e-10 * mid,
            "the quotient alone would not do: {quotient}"
        );
    }
}
