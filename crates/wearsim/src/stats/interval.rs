//! 95 % confidence intervals over surface pairs, the unit of replication of a study (paper §4.1:
//! five independent surface pairs per setting).
//!
//! - a mean over pairs: Student t on the pair values, n − 1 degrees of freedom ([`mean_interval`]);
//! - a particle count summed over pairs: exact Poisson (Garwood) ([`poisson_interval`]);
//! - two settings that share their surface pairs (same seeds): the geometric mean of the per-pair
//!   ratios, Student t on the log-ratios ([`paired_ratio`]);
//! - two particle counts over the same sliding distance, where pairs hold too few particles for a
//!   ratio each: the ratio of two Poisson rates, exact conditional (Clopper–Pearson) interval
//!   ([`count_ratio`]).

use statrs::distribution::{Beta, ContinuousCDF, Gamma, StudentsT};

/// The confidence level of every interval wearsim states.
pub const LEVEL: f64 = 0.95;

/// How an interval was obtained: written beside it in tables and findings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Student t on n values (a mean over surface pairs), n − 1 degrees of freedom.
    StudentT,
    /// Exact Poisson (Garwood) on a count.
    Poisson,
    /// Student t on the per-pair log-ratios of two settings, back-transformed (a geometric mean ratio).
    PairedRatio,
    /// Ratio of two Poisson counts over equal sliding distances, exact conditional binomial
    /// (Clopper–Pearson).
    CountRatio,
    /// Welch's t on the log values of two independent sets of surface pairs, back-transformed (a
    /// ratio of geometric means).
    UnpairedRatio,
    /// A ratio of two means over the same surface pairs, percentile interval of a bootstrap that
    /// resamples the pairs: for a quantity that is zero in most pairs, whose log-ratios do not exist
    /// and whose Student-t interval would run below zero.
    PairBootstrap,
}

impl Method {
    /// The method in words, as findings and tables name it.
    pub fn name(self) -> &'static str {
        match self {
            Method::StudentT => "Student t over surface pairs",
            Method::Poisson => "exact Poisson",
            Method::PairedRatio => "paired log-ratio over shared surface pairs, Student t",
            Method::CountRatio => "two Poisson counts, exact conditional test",
            Method::UnpairedRatio => "ratio of geometric means of independent surface pairs, Welch t",
            Method::PairBootstrap => "ratio of means, percentile bootstrap over surface pairs",
        }
    }
}

/// An estimate with its 95 % confidence interval [low, high], from `n` values (pairs, or particles
/// for the count methods).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Interval {
    pub estimate: f64,
    pub low: f64,
    pub high: f64,
    pub n: usize,
    pub method: Method,
}

impl Interval {
    /// The same interval mapped through an increasing function (a change of scale or unit).
    pub fn map(self, f: impl Fn(f64) -> f64) -> Interval {
        Interval {
            estimate: f(self.estimate),
            low: f(self.low),
            high: f(self.high),
            ..self
        }
    }
}

/// The two-sided critical value of Student's t at [`LEVEL`] with `df` degrees of freedom (2.776
/// for 4, 1.960 in the limit).
pub fn t_critical(df: usize) -> f64 {
    let t = StudentsT::new(0.0, 1.0, df.max(1) as f64).expect("a positive number of degrees of freedom");
    t.inverse_cdf(0.5 + LEVEL / 2.0)
}

/// The two-sided critical value of Student's t at [`LEVEL`] with a real number of degrees of
/// freedom (Welch–Satterthwaite).
pub fn t_critical_real(df: f64) -> f64 {
    let t = StudentsT::new(0.0, 1.0, df.max(1.0)).expect("a positive number of degrees of freedom");
    t.inverse_cdf(0.5 + LEVEL / 2.0)
}

/// Sample mean and standard deviation (n − 1 in the denominator) of at least two values.
fn mean_sd(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// The mean of `values` (one per surface pair) with its 95 % Student-t interval; `None` with fewer
/// than two finite values (no spread to measure). Values that are not finite are left out.
pub fn mean_interval(values: &[f64]) -> Option<Interval> {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.len() < 2 {
        return None;
    }
    let (mean, sd) = mean_sd(&v);
    let half = t_critical(v.len() - 1) * sd / (v.len() as f64).sqrt();
    Some(Interval {
        estimate: mean,
        low: mean - half,
        high: mean + half,
        n: v.len(),
        method: Method::StudentT,
    })
}

/// Resamples of [`ratio_of_means`]'s bootstrap: the 2.5 % and 97.5 % quantiles to about ±0.5 % in
/// probability.
pub const BOOTSTRAP_RESAMPLES: usize = 4000;

/// Σa/Σb over surface pairs (a, b) with the 95 % percentile interval of a bootstrap that draws the
/// pairs with replacement ([`BOOTSTRAP_RESAMPLES`] times, a fixed seed: the same numbers on every
/// run). For a numerator that is zero in most pairs (the wear volume V₀ at s = 0 where few pairs have
/// a critical junction then). `None` with fewer than two pairs or a value that is not finite; an
/// interval of zero width (every pair's a is 0) is returned as it is, for the caller to call it what
/// it is: no spread, no evidence.
pub fn ratio_of_means(pairs: &[(f64, f64)]) -> Option<Interval> {
    use rand::{RngExt, SeedableRng};
    if pairs.len() < 2 || pairs.iter().any(|(a, b)| !a.is_finite() || !b.is_finite()) {
        return None;
    }
    let ratio = |sum_a: f64, sum_b: f64| (sum_b > 0.0).then(|| sum_a / sum_b);
    let estimate = ratio(pairs.iter().map(|p| p.0).sum(), pairs.iter().map(|p| p.1).sum())?;
    let mut rng = rand_chacha::ChaCha20Rng::seed_from_u64(0x5eed_b007);
    let mut draws: Vec<f64> = (0..BOOTSTRAP_RESAMPLES)
        .filter_map(|_| {
            let (mut a, mut b) = (0.0, 0.0);
            for _ in 0..pairs.len() {
                let (x, y) = pairs[rng.random_range(0..pairs.len())];
                a += x;
                b += y;
            }
            ratio(a, b)
        })
        .collect();
    draws.sort_by(f64::total_cmp);
    let alpha = (1.0 - LEVEL) / 2.0;
    let quantile = |q: f64| draws[((q * draws.len() as f64) as usize).min(draws.len() - 1)];
    Some(Interval {
        estimate,
        low: quantile(alpha),
        high: quantile(1.0 - alpha),
        n: pairs.len(),
        method: Method::PairBootstrap,
    })
}

/// A particle count with its exact 95 % Poisson interval (Garwood): the quantiles of the gamma
/// distributions of shape k and k + 1.
pub fn poisson_interval(count: u64) -> Interval {
    let alpha = 1.0 - LEVEL;
    let k = count as f64;
    let low = if count == 0 {
        0.0
    } else {
        Gamma::new(k, 1.0).expect("positive shape").inverse_cdf(alpha / 2.0)
    };
    let high = Gamma::new(k + 1.0, 1.0)
        .expect("positive shape")
        .inverse_cdf(1.0 - alpha / 2.0);
    Interval {
        estimate: k,
        low,
        high,
        n: count as usize,
        method: Method::Poisson,
    }
}

/// Two settings compared surface pair by surface pair: `pairs` holds (a, b) of each shared pair.
/// The estimate is the geometric mean of a/b with the 95 % Student-t interval of the mean
/// log-ratio, back-transformed; `None` with fewer than two pairs or where a value is not positive
/// (a pair without a particle has no ratio: compare its counts with [`count_ratio`]).
pub fn paired_ratio(pairs: &[(f64, f64)]) -> Option<Interval> {
    if pairs
        .iter()
        .any(|&(a, b)| !(a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()))
    {
        return None;
    }
    let logs: Vec<f64> = pairs.iter().map(|&(a, b)| (a / b).ln()).collect();
    let i = mean_interval(&logs)?;
    Some(
        Interval {
            method: Method::PairedRatio,
            ..i
        }
        .map(f64::exp),
    )
}

/// Two settings on different surfaces (another box or grid: no pair is shared): the ratio of the
/// geometric means of `a` and `b` with Welch's interval on the log values, back-transformed; `None`
/// with fewer than two positive values on a side, or a value that is not positive.
pub fn unpaired_ratio(a: &[f64], b: &[f64]) -> Option<Interval> {
    if a.len() < 2 || b.len() < 2 || a.iter().chain(b).any(|&x| !(x > 0.0 && x.is_finite())) {
        return None;
    }
    let (la, lb): (Vec<f64>, Vec<f64>) = (a.iter().map(|x| x.ln()).collect(), b.iter().map(|x| x.ln()).collect());
    let (ma, sa) = mean_sd(&la);
    let (mb, sb) = mean_sd(&lb);
    let (va, vb) = (sa * sa / la.len() as f64, sb * sb / lb.len() as f64);
    let se = (va + vb).sqrt();
    let df = (va + vb).powi(2) / (va * va / (la.len() - 1) as f64 + vb * vb / (lb.len() - 1) as f64);
    let half = if se > 0.0 { t_critical_real(df) * se } else { 0.0 };
    let d = ma - mb;
    Some(Interval {
        estimate: d.exp(),
        low: (d - half).exp(),
        high: (d + half).exp(),
        n: la.len() + lb.len(),
        method: Method::UnpairedRatio,
    })
}

/// The ratio of two Poisson rates observed as counts `a` and `b` over equal sliding distances
/// (the fit windows of two settings over the same surface pairs): given a + b, a is binomial with
/// p = ρ/(1 + ρ); the exact (Clopper–Pearson) interval of p gives ρ's. `None` when a + b = 0. The
/// estimate is a/b (infinite when b = 0, and so is the upper bound).
pub fn count_ratio(a: u64, b: u64) -> Option<Interval> {
    let n = a + b;
    if n == 0 {
        return None;
    }
    let alpha = 1.0 - LEVEL;
    let (x, nf) = (a as f64, n as f64);
    let p_low = if a == 0 {
        0.0
    } else {
        Beta::new(x, nf - x + 1.0)
            .expect("positive shapes")
            .inverse_cdf(alpha / 2.0)
    };
    let p_high = if a == n {
        1.0
    } else {
        Beta::new(x + 1.0, nf - x)
            .expect("positive shapes")
            .inverse_cdf(1.0 - alpha / 2.0)
    };
    let odds = |p: f64| if p >= 1.0 { f64::INFINITY } else { p / (1.0 - p) };
    Some(Interval {
        estimate: if b == 0 { f64::INFINITY } else { x / b as f64 },
        low: odds(p_low),
        high: odds(p_high),
        n: n as usize,
        method: Method::CountRatio,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn student_t_interval_of_values_with_a_known_spread() {
        // Five values of mean 10 and sample standard deviation 2: 10 ± 2√2 and three tens
        // (variance 2 · 8 / 4 = 4), so 10 ± t(4) · 2/√5 with t(4) = 2.7764451 (tables).
        let a = 2.0 * 2f64.sqrt();
        let values = [10.0 - a, 10.0, 10.0, 10.0, 10.0 + a];
        let (_, sd) = mean_sd(&values);
        assert!((sd - 2.0).abs() < 1e-12, "sd = {sd}");
        let i = mean_interval(&values).unwrap();
        let half = 2.776_445_105 * 2.0 / 5f64.sqrt();
        assert!((i.estimate - 10.0).abs() < 1e-12);
        assert!(
            (i.high - 10.0 - half).abs() < 1e-6 && (10.0 - i.low - half).abs() < 1e-6,
            "{i:?}"
        );
        assert_eq!((i.n, i.method), (5, Method::StudentT));
        // Tables: t(1) = 12.706, t(9) = 2.262, t(∞) → 1.960.
        assert!((t_critical(1) - 12.706_204_7).abs() < 1e-5);
        assert!((t_critical(9) - 2.262_157_2).abs() < 1e-5);
        assert!((t_critical(100_000) - 1.959_98).abs() < 1e-3);
        // One value, or none finite: no interval.
        assert!(mean_interval(&[1.0]).is_none());
        assert!(mean_interval(&[1.0, f64::NAN]).is_none());
        // No spread: a point interval.
        let flat = mean_interval(&[3.0, 3.0, 3.0]).unwrap();
        assert_eq!((flat.low, flat.high), (3.0, 3.0));
    }

    #[test]
    fn ratio_of_means_bootstraps_the_pairs_and_keeps_a_zero_sample_at_zero_width() {
        // One pair in five with a numerator: Σa/Σb = 10/5 = 2, and a resample without that pair
        // gives 0, so the interval reaches 0 (the chance of missing it in 5 draws is 0.8⁵ = 33 %).
        let pairs = [(10.0, 1.0), (0.0, 1.0), (0.0, 1.0), (0.0, 1.0), (0.0, 1.0)];
        let i = ratio_of_means(&pairs).unwrap();
        assert_eq!(i.estimate, 2.0);
        assert_eq!(i.low, 0.0);
        assert!(i.high > 4.0 && i.high <= 10.0, "{i:?}");
        assert_eq!((i.n, i.method), (5, Method::PairBootstrap));
        // The same numbers on every call (a fixed seed).
        assert_eq!(ratio_of_means(&pairs), Some(i));
        // Every numerator 0: zero width, for the caller to call undecided.
        let zeros = ratio_of_means(&[(0.0, 1.0), (0.0, 2.0), (0.0, 3.0)]).unwrap();
        assert_eq!((zeros.estimate, zeros.low, zeros.high), (0.0, 0.0, 0.0));
        // Equal ratios in every pair: no spread in the resamples either.
        let equal = ratio_of_means(&[(2.0, 1.0), (4.0, 2.0), (6.0, 3.0)]).unwrap();
        assert_eq!((equal.low, equal.high), (2.0, 2.0));
        assert_eq!(ratio_of_means(&[(1.0, 1.0)]), None);
        assert_eq!(ratio_of_means(&[(1.0, 1.0), (f64::NAN, 1.0)]), None);
    }

    #[test]
    fn poisson_interval_matches_the_tables() {
        // Garwood's exact limits (e.g. Ulm 1990): 0 → [0, 3.689]; 1 → [0.0253, 5.572];
        // 10 → [4.795, 18.39]; 80 → [63.4, 99.6].
        let check = |k: u64, lo: f64, hi: f64, tol: f64| {
            let i = poisson_interval(k);
            assert!((i.low - lo).abs() < tol && (i.high - hi).abs() < tol, "{k}: {i:?}");
        };
        check(0, 0.0, 3.6889, 1e-3);
        check(1, 0.0253, 5.5716, 1e-3);
        check(10, 4.7954, 18.3904, 1e-3);
        check(80, 63.44, 99.57, 0.05);
    }

    #[test]
    fn paired_ratio_is_the_geometric_mean_with_a_t_interval_on_the_logs() {
        // The five pairs: W(33 px)/W(16 px) = 0.80, 0.97, 1.28, 2.39, 0.88.
        let pairs: Vec<(f64, f64)> = [0.80, 0.97, 1.28, 2.39, 0.88].iter().map(|&r| (r, 1.0)).collect();
        let i = paired_ratio(&pairs).unwrap();
        let logs: Vec<f64> = pairs.iter().map(|p| p.0.ln()).collect();
        let (m, sd) = mean_sd(&logs);
        assert!((i.estimate - m.exp()).abs() < 1e-12);
        assert!((i.low - (m - t_critical(4) * sd / 5f64.sqrt()).exp()).abs() < 1e-12);
        // It straddles 1: no direction is shown.
        assert!(i.low < 1.0 && i.high > 1.0, "{i:?}");
        // A constant ratio of 2 in every pair: exactly 2.
        let two = paired_ratio(&[(2.0, 1.0), (4.0, 2.0), (6.0, 3.0)]).unwrap();
        assert!((two.low - 2.0).abs() < 1e-12 && (two.high - 2.0).abs() < 1e-12);
        // A pair without wear has no ratio.
        assert!(paired_ratio(&[(0.0, 1.0), (1.0, 1.0)]).is_none());
    }

    #[test]
    fn unpaired_ratio_is_welchs_interval_on_the_logs() {
        // Logs 0, 1 (sd 0.707) against 0, 0, 0 (sd 0): the second adds no variance, df = 1.
        let e = std::f64::consts::E;
        let i = unpaired_ratio(&[1.0, e], &[1.0, 1.0, 1.0]).unwrap();
        let half = 12.706_204_7 * (0.5f64 / 2.0).sqrt();
        assert!((i.estimate - 0.5f64.exp()).abs() < 1e-12);
        assert!((i.high.ln() - 0.5 - half).abs() < 1e-6, "{i:?}");
        assert_eq!(i.method, Method::UnpairedRatio);
        assert!(unpaired_ratio(&[1.0], &[1.0, 2.0]).is_none());
        assert!(unpaired_ratio(&[0.0, 1.0], &[1.0, 2.0]).is_none());
    }

    #[test]
    fn count_ratio_decides_one_particle_against_eighty() {
        let i = count_ratio(1, 80).unwrap();
        assert!((i.estimate - 1.0 / 80.0).abs() < 1e-15);
        assert!(i.high < 0.1 && i.low > 0.0, "{i:?}");
        // Symmetric: the ratio the other way round is the reciprocal interval.
        let j = count_ratio(80, 1).unwrap();
        assert!((j.low * i.high - 1.0).abs() < 1e-9 && (j.high * i.low - 1.0).abs() < 1e-9);
        // Equal counts: straddles 1. No particle on one side: the bound is 0 or ∞.
        let even = count_ratio(10, 10).unwrap();
        assert!(even.low < 1.0 && even.high > 1.0);
        assert_eq!(count_ratio(0, 5).unwrap().low, 0.0);
        assert_eq!(count_ratio(5, 0).unwrap().high, f64::INFINITY);
        assert!(count_ratio(0, 0).is_none());
        // Clopper–Pearson for 3 of 10: p ∈ [0.0667, 0.6525] (tables), so ρ ∈ [0.0715, 1.878].
        let cp = count_ratio(3, 7).unwrap();
        assert!((cp.low - 0.0667 / (1.0 - 0.0667)).abs() < 1e-3, "{cp:?}");
        assert!((cp.high - 0.6525 / (1.0 - 0.6525)).abs() < 1e-2, "{cp:?}");
    }
}
