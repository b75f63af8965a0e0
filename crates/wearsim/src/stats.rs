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
///
/// The sums are taken on x and y divided by powers of two near their largest magnitudes: exact
/// divisions, so the result is the plain least-squares one bit for bit, but its squares neither
/// underflow nor overflow, and a run in SI units at any representable length scale (wear volumes
/// of 1e-200 m³ or 1e200 m³) fits as its dimensionless twin does.
pub fn line_fit(x: &[f64], y: &[f64]) -> Option<LineFit> {
    if x.len() < 2 || x.len() != y.len() {
        return None;
    }
    let (sx, sy) = (power_of_two_scale(x), power_of_two_scale(y));
    let m = x.len() as f64;
    let (mx, my) = (
        x.iter().map(|a| a / sx).sum::<f64>() / m,
        y.iter().map(|b| b / sy).sum::<f64>() / m,
    );
    let sxx: f64 = x.iter().map(|a| (a / sx - mx) * (a / sx - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a / sx - mx) * (b / sy - my)).sum();
    let syy: f64 = y.iter().map(|b| (b / sy - my) * (b / sy - my)).sum();
    if sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let ss_res = syy - slope * sxy;
    let r2 = (syy > 0.0).then(|| 1.0 - ss_res / syy);
    Some(LineFit {
        slope: slope * (sy / sx),
        intercept: (my - slope * mx) * sy,
        r2,
    })
}

/// 2^⌊log₂ max|v|⌋ (1 where every value is 0 or one is not finite): dividing by it is exact.
fn power_of_two_scale(values: &[f64]) -> f64 {
    let largest = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest > 0.0 && largest.is_finite() {
        2f64.powi(largest.log2().floor() as i32)
    } else {
        1.0
    }
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

    #[test]
    fn line_fit_is_the_same_at_every_scale_and_bit_for_bit_at_unit_scale() {
        let x = [0.0, 0.3, 0.7, 1.1, 1.6];
        let y = [0.2, 0.9, 1.4, 2.6, 3.1];
        let unit = line_fit(&x, &y).unwrap();
        // The plain formula, as before the scaling: identical bits.
        let m = 5.0;
        let (mx, my) = (x.iter().sum::<f64>() / m, y.iter().sum::<f64>() / m);
        let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
        let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
        assert_eq!(unit.slope, sxy / sxx);
        assert_eq!(unit.intercept, my - sxy / sxx * mx);
        for (sx, sy) in [(1e-150, 1e-200), (1e150, 1e200), (1e-100, 1e150), (3e-7, 7e11)] {
            let xs: Vec<f64> = x.iter().map(|v| v * sx).collect();
            let ys: Vec<f64> = y.iter().map(|v| v * sy).collect();
            let f = line_fit(&xs, &ys).unwrap();
            assert!((f.slope * sx / sy / unit.slope - 1.0).abs() < 1e-12, "{sx:e} {sy:e}");
            assert!((f.intercept / sy / unit.intercept - 1.0).abs() < 1e-12, "{sx:e} {sy:e}");
            assert!((f.r2.unwrap() - unit.r2.unwrap()).abs() < 1e-12, "{sx:e} {sy:e}");
        }
    }
}
