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
}
