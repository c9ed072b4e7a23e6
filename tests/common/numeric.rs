//! Numeric helpers of the simulation tests.

/// max |aᵢ − bᵢ|.
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Least-squares slope of log(y) against log(x): the measured order of
/// convergence when x is a step and y an error, the proportionality
/// exponent when x is a tolerance.
pub fn loglog_slope(x: &[f64], y: &[f64]) -> f64 {
    let xs: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ys: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = xs.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}
