//! Whether an interval decides a rule, and how many surface pairs would: a rule holds when its 95 %
//! interval lies wholly on the paper's side of the threshold, is contrary when it lies wholly on the
//! other side, and is undecided otherwise (a difference smaller than the spread between surface
//! pairs decides nothing).

use super::interval::{count_ratio, t_critical, t_critical_real, Interval};

/// The paper's side of a rule's threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Region {
    /// Above the threshold (strictly).
    Above(f64),
    /// Below the threshold (strictly).
    Below(f64),
    /// Between two bounds, inclusive.
    Within(f64, f64),
}

/// What an interval says of a rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The whole interval lies on the paper's side.
    Holds,
    /// The whole interval lies on the other side.
    Contrary,
    /// The interval reaches both sides.
    Undecided,
}

/// The pairs a search for the needed number of pairs tries at most.
pub const MAX_PAIRS: usize = 100_000;

impl Region {
    /// Where the interval [low, high] lies.
    pub fn side_of(self, low: f64, high: f64) -> Side {
        let (holds, contrary) = match self {
            Region::Above(t) => (low > t, high <= t),
            Region::Below(t) => (high < t, low >= t),
            Region::Within(a, b) => (a <= low && high <= b, high < a || low > b),
        };
        match (holds, contrary) {
            (true, _) => Side::Holds,
            (_, true) => Side::Contrary,
            _ => Side::Undecided,
        }
    }

    /// Where an interval lies.
    pub fn side(self, i: &Interval) -> Side {
        self.side_of(i.low, i.high)
    }

    /// The rule's side in words: "> 1", "< 0.12", "in [0.6, 1]".
    pub fn describe(self) -> String {
        match self {
            Region::Above(t) => format!("> {t}"),
            Region::Below(t) => format!("< {t}"),
            Region::Within(a, b) => format!("in [{a}, {b}]"),
        }
    }

    /// The same region through an increasing function (the log of a ratio's threshold).
    pub fn map(self, f: impl Fn(f64) -> f64) -> Region {
        match self {
            Region::Above(t) => Region::Above(f(t)),
            Region::Below(t) => Region::Below(f(t)),
            Region::Within(a, b) => Region::Within(f(a), f(b)),
        }
    }

    /// The distance from `x` to the nearest boundary of the region (0 on it).
    fn distance(self, x: f64) -> f64 {
        match self {
            Region::Above(t) | Region::Below(t) => (x - t).abs(),
            Region::Within(a, b) => (x - a).abs().min((x - b).abs()),
        }
    }
}

/// The number of surface pairs whose Student-t interval would decide `region` (hold or be contrary)
/// if the pair values kept the mean and the spread of `values`: the smallest n ≥ 2 with
/// t(n − 1) · sd/√n below the distance from the mean to the threshold. `None` when the mean lies on
/// the threshold, with fewer than two values, or beyond [`MAX_PAIRS`].
pub fn pairs_needed(values: &[f64], region: Region) -> Option<usize> {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.len() < 2 {
        return None;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let sd = (v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0)).sqrt();
    let effect = region.distance(mean);
    if effect <= 0.0 || !effect.is_finite() {
        return None;
    }
    let decides = |k: usize| t_critical(k - 1) * sd / (k as f64).sqrt() < effect;
    smallest(2, decides)
}

/// The number of surface pairs per side at which Welch's interval of two independent sets of values
/// (`a` and `b`, on the scale `region` is stated in: logs of a ratio) would decide `region`, if each
/// side kept its mean and spread; `None` when the difference lies on the threshold, a side has fewer
/// than two values, or beyond [`MAX_PAIRS`].
pub fn pairs_needed_unpaired(a: &[f64], b: &[f64], region: Region) -> Option<usize> {
    let stats = |v: &[f64]| {
        let n = v.len() as f64;
        let m = v.iter().sum::<f64>() / n;
        (m, v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0))
    };
    if a.len() < 2 || b.len() < 2 {
        return None;
    }
    let ((ma, va), (mb, vb)) = (stats(a), stats(b));
    let effect = region.distance(ma - mb);
    if effect <= 0.0 || !effect.is_finite() {
        return None;
    }
    let decides = |k: usize| {
        let n = k as f64;
        let (sa, sb) = (va / n, vb / n);
        let se = (sa + sb).sqrt();
        let df = (sa + sb).powi(2) / ((sa * sa + sb * sb) / (n - 1.0));
        se == 0.0 || t_critical_real(df) * se < effect
    };
    smallest(2, decides)
}

/// The number of surface pairs at which two particle counts, `a` and `b` observed over `pairs`
/// pairs and growing in proportion to the pairs, would decide `region` for `scale` · a/b (the
/// count test of [`count_ratio`]); `None` when the observed ratio lies on the threshold or beyond
/// [`MAX_PAIRS`].
pub fn pairs_needed_for_counts(a: u64, b: u64, pairs: usize, scale: f64, region: Region) -> Option<usize> {
    if pairs == 0 || a + b == 0 {
        return None;
    }
    let decides = |k: usize| {
        let grow = |c: u64| (c as f64 * k as f64 / pairs as f64).round() as u64;
        count_ratio(grow(a), grow(b)).is_some_and(|i| region.side_of(scale * i.low, scale * i.high) != Side::Undecided)
    };
    smallest(pairs, decides)
}

/// The smallest k ≥ `from` (up to [`MAX_PAIRS`]) for which `decides` holds, assuming it keeps
/// holding above: doubling, then bisection. The search behind the pairs-needed functions, for rules
/// that combine intervals of their own.
pub fn smallest(from: usize, decides: impl Fn(usize) -> bool) -> Option<usize> {
    let mut hi = from.max(2);
    while !decides(hi) {
        if hi >= MAX_PAIRS {
            return None;
        }
        hi = (hi * 2).min(MAX_PAIRS);
    }
    let mut lo = from.max(2);
    if decides(lo) {
        return Some(lo);
    }
    // decides(lo) is false, decides(hi) true.
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if decides(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

#[cfg(test)]
mod tests {
    use super::super::interval::mean_interval;
    use super::*;

    #[test]
    fn an_interval_holds_is_contrary_or_undecided() {
        let r = Region::Below(0.12);
        assert_eq!(r.side_of(0.05, 0.11), Side::Holds);
        assert_eq!(r.side_of(0.13, 0.2), Side::Contrary);
        assert_eq!(r.side_of(0.1, 0.13), Side::Undecided);
        let w = Region::Within(0.6, 1.0);
        assert_eq!(w.side_of(0.7, 0.95), Side::Holds);
        assert_eq!(w.side_of(1.01, 1.2), Side::Contrary);
        assert_eq!(w.side_of(0.9, 1.1), Side::Undecided);
        assert_eq!(Region::Above(1.0).side_of(1.2, f64::INFINITY), Side::Holds);
        assert_eq!(w.describe(), "in [0.6, 1]");
    }

    #[test]
    fn the_pairs_needed_decide_at_the_observed_mean_and_spread() {
        // Mean 1, sample sd 1 (values 0, 1, 2), threshold 0: t(n−1)/√n < 1 first at n = 7
        // (t(6) = 2.447, 2.447/√7 = 0.925; t(5) = 2.571, 2.571/√6 = 1.050).
        let values = [0.0, 1.0, 2.0];
        assert_eq!(pairs_needed(&values, Region::Above(0.0)), Some(7));
        // Those 7 pairs of the same mean and spread do decide it; 6 do not.
        let spread = |n: usize| -> Vec<f64> {
            // n values of mean 1 and sample sd 1.
            let raw: Vec<f64> = (0..n).map(|i| i as f64).collect();
            let i = mean_interval(&raw).unwrap();
            let sd = (raw.iter().map(|x| (x - i.estimate).powi(2)).sum::<f64>() / (n as f64 - 1.0)).sqrt();
            raw.iter().map(|x| 1.0 + (x - i.estimate) / sd).collect()
        };
        assert!(mean_interval(&spread(7)).unwrap().low > 0.0);
        assert!(mean_interval(&spread(6)).unwrap().low < 0.0);
        // On the threshold: no number of pairs decides it.
        assert_eq!(pairs_needed(&values, Region::Above(1.0)), None);
        // Already decided by its own pairs: their number or fewer.
        assert_eq!(pairs_needed(&[10.0, 10.5, 11.0], Region::Above(0.0)), Some(2));
    }

    #[test]
    fn the_pairs_needed_for_two_counts_grow_with_the_counts() {
        // 8 against 12 particles over 5 pairs (ratio 0.67): undecided; many more pairs decide it.
        let n = pairs_needed_for_counts(8, 12, 5, 1.0, Region::Below(1.0)).unwrap();
        assert!(n > 5, "{n}");
        let grow = |c: u64| (c as f64 * n as f64 / 5.0).round() as u64;
        assert!(count_ratio(grow(8), grow(12)).unwrap().high < 1.0);
        // Equal counts never decide a ratio of 1.
        assert_eq!(pairs_needed_for_counts(10, 10, 5, 1.0, Region::Below(1.0)), None);
    }
}
