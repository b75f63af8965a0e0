//! Small statistics shared by the wear fits and the spectrum fits: least-squares lines and
//! mean ± standard deviation.

/// A least-squares line y = slope·x + intercept and its coefficient of determination R² (absent
/// when y does not vary, where R² is undefined).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineFit {
    pub slope: f64,
    pub intercept: f64,
    pub r2: Option<f64>,
}

/// Least-squares line through (x, y); `None` with fewer than two points or x without spread.
pub fn line_fit(x: &[f64], y: &[f64]) -> Option<LineFit> {
    if x.len() < 2 || x.len() != y.len() {
        return None;
    }
    let m = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / m, y.iter().sum::<f64>() / m);
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let syy: f64 = y.iter().map(|b| (b - my) * (b - my)).sum();
    if sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let ss_res = syy - slope * sxy;
    let r2 = (syy > 0.0).then(|| 1.0 - ss_res / syy);
    Some(LineFit {
        slope,
        intercept: my - slope * mx,
        r2,
    })
}

/// Mean and (population) standard deviation.
pub fn mean_std(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let n = values.clone().count().max(1) as f64;
    let mean = values.clone().sum::<f64>() / n;
    let var = values.map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    (mean, var.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_fit_is_exact_on_a_line_and_undefined_without_spread() {
        let x = [0.0, 1.0, 2.0, 3.0];
        let f = line_fit(&x, &[1.0, 3.0, 5.0, 7.0]).unwrap();
        assert!((f.slope - 2.0).abs() < 1e-14 && (f.r2.unwrap() - 1.0).abs() < 1e-14);
        assert!((f.intercept - 1.0).abs() < 1e-14);
        // Constant y: slope 0, R² undefined (not 1).
        let flat = line_fit(&x, &[2.0; 4]).unwrap();
        assert_eq!((flat.slope, flat.r2), (0.0, None));
        assert!(line_fit(&[1.0], &[1.0]).is_none());
        assert!(line_fit(&[1.0, 1.0], &[1.0, 2.0]).is_none());
    }
}
