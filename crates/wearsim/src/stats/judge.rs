//! Whether an interval decides a rule, and how many surface pairs would: a rule holds when its 95 %
//! interval lies wholly on the paper's side of the threshold, is contrary when it lies wholly on the
//! other side, and is undecided otherwise (a difference smaller than the spread between surface
//! pairs decides nothing).

use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

use super::interval::{count_ratio, t_critical, t_critical_real, Interval, LEVEL};

/// The power at which the pairs-needed functions plan: with that many pairs, a study whose pairs
/// keep the observed mean and spread decides the rule in 80 % of its repetitions (the usual planning
/// power; the interval's own level is [`LEVEL`]).
pub const POWER: f64 = 0.8;

/// The one-sided Student-t quantile at [`POWER`] (0.941 for 4 degrees of freedom, 0.842 in the
/// limit): what the distance to the threshold needs beyond the interval's half-width.
fn t_power(df: f64) -> f64 {
    let t = StudentsT::new(0.0, 1.0, df.max(1.0)).expect("a positive number of degrees of freedom");
    t.inverse_cdf(POWER)
}

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
/// with [`POWER`] if the pair values kept the mean and the spread of `values`: the smallest n ≥ 2
/// with (t₀.₉₇₅(n − 1) + t₀.₈(n − 1)) · sd/√n below the distance from the mean to the threshold.
/// `None` when the mean lies on the threshold, with fewer than two values, or beyond [`MAX_PAIRS`].
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
    let decides = |k: usize| (t_critical(k - 1) + t_power((k - 1) as f64)) * sd / (k as f64).sqrt() < effect;
    smallest(2, decides)
}

/// The number of surface pairs per side at which Welch's interval of two independent sets of values
/// (`a` and `b`, on the scale `region` is stated in: logs of a ratio) would decide `region` with
/// [`POWER`], if each side kept its mean and spread; `None` when the difference lies on the threshold, a side has fewer
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
        se == 0.0 || (t_critical_real(df) + t_power(df)) * se < effect
    };
    smallest(2, decides)
}

/// The number of surface pairs at which two particle counts, `a` and `b` observed over `pairs`
/// pairs and growing in proportion to the pairs, would decide `region` for `scale` · a/b: where both
/// counts are positive, with [`POWER`] (the log of the ratio of two Poisson counts, of standard error
/// √(1/a + 1/b)); where one is 0, when the count test of [`count_ratio`] at the grown counts decides
/// it. `None` when the observed ratio lies on the threshold or beyond [`MAX_PAIRS`].
pub fn pairs_needed_for_counts(a: u64, b: u64, pairs: usize, scale: f64, region: Region) -> Option<usize> {
    if pairs == 0 || a + b == 0 {
        return None;
    }
    let grow = |c: u64, k: usize| (c as f64 * k as f64 / pairs as f64).round() as u64;
    if a > 0 && b > 0 {
        let effect = region.map(f64::ln).distance((scale * a as f64 / b as f64).ln());
        if effect <= 0.0 || !effect.is_finite() {
            return None;
        }
        let z = Normal::standard();
        let margin = z.inverse_cdf(0.5 + LEVEL / 2.0) + z.inverse_cdf(POWER);
        let decides = |k: usize| {
            let (ak, bk) = (grow(a, k).max(1) as f64, grow(b, k).max(1) as f64);
            margin * (1.0 / ak + 1.0 / bk).sqrt() < effect
        };
        return smallest(pairs, decides);
    }
    let decides = |k: usize| {
        count_ratio(grow(a, k), grow(b, k))
            .is_some_and(|i| region.side_of(scale * i.low, scale * i.high) != Side::Undecided)
    };
    smallest(pairs, decides)
}

/// The number of surface pairs at which two ratios of particle counts, `first` = (a₀, b₀, n₀) and
/// `second` = (a₁, b₁, n₁), counts a and b observed over n pairs and growing in proportion to the
/// pairs, would have disjoint 95 % intervals with [`POWER`]: the log ratios' distance d against
/// z₀.₉₇₅ (se₀ + se₁) + z_power √(se₀² + se₁²), se = √(1/a + 1/b) at the grown counts. `None` with a
/// zero count (no log ratio to extrapolate: the caller keeps its own search), equal ratios, or
/// beyond [`MAX_PAIRS`].
pub fn pairs_needed_for_disjoint_ratios(first: (u64, u64, usize), second: (u64, u64, usize)) -> Option<usize> {
    let counts = [first.0, first.1, second.0, second.1];
    if first.2 == 0 || second.2 == 0 || counts.contains(&0) {
        return None;
    }
    let ln_ratio = |(a, b, _): (u64, u64, usize)| (a as f64 / b as f64).ln();
    let distance = (ln_ratio(second) - ln_ratio(first)).abs();
    if distance == 0.0 || !distance.is_finite() {
        return None;
    }
    let z = Normal::standard();
    let (level, power) = (z.inverse_cdf(0.5 + LEVEL / 2.0), z.inverse_cdf(POWER));
    let se = |(a, b, n): (u64, u64, usize), k: usize| {
        let grow = |c: u64| (c as f64 * k as f64 / n as f64).max(1.0);
        (1.0 / grow(a) + 1.0 / grow(b)).sqrt()
    };
    smallest(first.2.min(second.2), |k| {
        let (s0, s1) = (se(first, k), se(second, k));
        level * (s0 + s1) + power * (s0 * s0 + s1 * s1).sqrt() < distance
    })
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
    fn the_pairs_needed_to_part_two_count_ratios_have_80_percent_power() {
        // 10 vs 20 and 30 vs 15 particles over 5 pairs: log ratios ∓ln 2, distance 1.386; at k pairs
        // (1.960 (√0.75 + √0.5) + 0.842 √1.25)/√k = 4.024/√k, under 1.386 first at k = 9 (1.423 at 8).
        assert_eq!(pairs_needed_for_disjoint_ratios((10, 20, 5), (30, 15, 5)), Some(9));
        assert_eq!(pairs_needed_for_disjoint_ratios((30, 15, 5), (10, 20, 5)), Some(9));
        // Fewer pairs observed at one load: its counts grow faster.
        assert!(pairs_needed_for_disjoint_ratios((10, 20, 5), (30, 15, 3)).unwrap() < 9);
        // A zero count has no log ratio; equal ratios never part.
        assert_eq!(pairs_needed_for_disjoint_ratios((0, 20, 5), (30, 15, 5)), None);
        assert_eq!(pairs_needed_for_disjoint_ratios((10, 20, 5), (15, 30, 5)), None);
    }

    #[test]
    fn the_pairs_needed_decide_at_the_observed_mean_and_spread_with_80_percent_power() {
        // Mean 1, sample sd 1 (values 0, 1, 2), threshold 0: (t₀.₉₇₅(n−1) + t₀.₈(n−1))/√n < 1 first
        // at n = 10 ((2.262 + 0.883)/√10 = 0.995; (2.306 + 0.889)/3 = 1.065 at 9).
        let values = [0.0, 1.0, 2.0];
        assert_eq!(pairs_needed(&values, Region::Above(0.0)), Some(10));
        // Half the time (the interval's own half-width alone, t(n−1)/√n < 1) 7 pairs would do: 7
        // pairs of exactly the observed mean and spread decide it, 6 do not.
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
        // Decided by a wide margin: a few pairs.
        assert_eq!(pairs_needed(&[10.0, 10.5, 11.0], Region::Above(0.0)), Some(2));
    }

    #[test]
    fn the_pairs_needed_for_two_counts_grow_with_the_counts() {
        // 8 against 12 particles over 5 pairs (ratio 0.67): undecided; many more pairs decide it.
        let n = pairs_needed_for_counts(8, 12, 5, 1.0, Region::Below(1.0)).unwrap();
        assert!(n > 5, "{n}");
        let grow = |c: u64| (c as f64 * n as f64 / 5.0).round() as u64;
        assert!(count_ratio(grow(8), grow(12)).unwrap().high < 1.0);
        // At 80 % power: (1.960 + 0.842) √(1/a + 1/b) < |ln(2/3)| = 0.405 needs 1/a + 1/b < 0.0209:
        // 80 against 120 particles, 50 pairs (49 pairs give 78 and 118).
        assert_eq!(n, 50);
        // Equal counts never decide a ratio of 1.
        assert_eq!(pairs_needed_for_counts(10, 10, 5, 1.0, Region::Below(1.0)), None);
    }
}
