//! The influence of material properties (paper §4.1, Fig. 4, §6): the level of k, its trend with load,
//! Archard-like wear, and how the wear of a larger d* against a smaller one changes with load.

use crate::stats::{line_fit, mean_interval, LineFit, Region, Side};

use super::rules::{
    all_of, compare, curve_label, exponents_by_seed, judge_values, key_of, pair_exponents, per_setting, show, Compared,
    Outcome,
};
use super::setting::{curves, curves_differing_in_d_star, curves_differing_in_g, d_star_pairs, fmt, param, Setting};
use super::{finding, Finding, Tally};

/// §4.1: k an order of magnitude below the static model's, per setting.
pub(super) fn sliding_k_below_static(all: &[Setting]) -> Finding {
    let tally = per_setting(all, "k_static/k", Region::Above(5.0), |_, p| {
        p.get("static_wear_coefficient_mean") / p.get("wear_coefficient")
    });
    finding(
        "sliding-k-below-static",
        "sliding model (§4.1, Fig. 4): wear rates and wear coefficients are an order of magnitude smaller than in the \
         static model",
        "per setting: k_static (mean over every offset) / k, per pair, > 5 (nearer 10 than 1) by its Student-t interval \
         over the run-in pairs (pairs with k = 0 left out)"
            .into(),
        "settings",
        tally,
    )
}

/// §4.1: k stays below around 0.1, per setting.
pub(super) fn sliding_k_below_0_1(all: &[Setting]) -> Finding {
    let tally = per_setting(all, "k", Region::Below(0.12), |_, p| p.get("wear_coefficient"));
    finding(
        "sliding-k-below-0.1",
        "sliding model (§4.1, Fig. 4): the wear coefficient remains smaller than around 0.1 in all cases",
        "per setting: k < 0.12 (\"around 0.1\") by its Student-t interval over the run-in pairs".into(),
        "settings",
        tally,
    )
}

/// §4.1: k at the high end of dry sliding experiments (10⁻⁶ … 10⁻¹).
pub(super) fn sliding_k_in_dry_sliding_range(all: &[Setting]) -> Finding {
    let tally = per_setting(all, "k", Region::Above(0.01), |_, p| p.get("wear_coefficient"));
    finding(
        "sliding-k-high-end-of-experiments",
        "sliding model (§4.1): k resides in the high end of reported values for dry sliding, k = 10⁻⁶ to 10⁻¹",
        "per setting: k > 10⁻² (the upper two decades of 10⁻⁶ … 10⁻¹; the upper bound is the k < 0.12 finding) by its \
         Student-t interval over the run-in pairs"
            .into(),
        "settings",
        tally,
    )
}

/// §6: an Archard-like wear behaviour is approximately recovered: W ∝ F_N^m with m near 1.
pub(super) fn archard_like(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for c in curves(all).into_iter().filter(|c| c.len() >= 2) {
        let m = pair_exponents(&c, true, |_, p| p.get("wear_rate"));
        let region = Region::Within(2.0 / 3.0, 1.5);
        tally.file(
            judge_values(&curve_label(&c), "m of W ∝ F_N^m", &m, region, "", c[0].pairs.len())
                .reads(key_of("slopes W", c[0].curve, c[0].curve)),
        );
    }
    finding(
        "archard-like",
        "§6: an Archard-like wear behaviour (W ∝ F_N) is approximately recovered",
        "per curve: the exponent m of W ∝ F_N^m, fitted per surface pair in log–log over the loads where the pair is \
         run in and wears (two loads or more), within [2/3, 3/2] (Archard's m = 1 within a factor 1.5) by its \
         Student-t interval over pairs"
            .into(),
        "curves",
        tally,
    )
}

/// The load at which a curve's k (mean over its run-in pairs) is largest, in words. A setting
/// without a run-in pair with a wear coefficient has no mean (not a mean of 0); a curve without any
/// run-in pair takes the mean over all its pairs and says so.
fn k_maximum(c: &[&Setting]) -> String {
    let any_run_in = c.iter().any(|s| !s.run_in_pairs().is_empty());
    let mean_k = |s: &Setting| {
        let pairs: Vec<&super::setting::Pair> = if any_run_in {
            s.run_in_pairs()
        } else {
            s.pairs.iter().collect()
        };
        let k: Vec<f64> = pairs
            .iter()
            .map(|p| p.get("wear_coefficient"))
            .filter(|k| k.is_finite())
            .collect();
        if k.is_empty() {
            f64::NAN
        } else {
            k.iter().sum::<f64>() / k.len() as f64
        }
    };
    let (i, best) = c
        .iter()
        .enumerate()
        .map(|(i, s)| (i, mean_k(s)))
        .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
    if !best.is_finite() {
        return "no mean k: no pair has a wear coefficient".into();
    }
    if best <= 0.0 {
        // No particle at any load: k = 0 throughout has no maximum to place.
        return "k = 0 at every load (no particle formed): no maximum".into();
    }
    let where_ = if i == 0 {
        "at the lowest load: the maximum lies at or below it"
    } else if i + 1 == c.len() {
        "at the highest load: the maximum lies at or above it"
    } else {
        "inside the load range"
    };
    let over = if any_run_in {
        ""
    } else {
        " (over all pairs: none is run in)"
    };
    format!(
        "largest mean k = {}{over} at F_N/(Lx·Ly) = {}, {where_}",
        fmt(best),
        param(c[i].pressure)
    )
}

/// §4.1: k increases with load to a maximum. Per pair k = W p_m/F_N, so its slope over load is
/// Archard's exponent less one: the same data as `archard-like`, listed under it.
pub(super) fn k_rises_with_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for c in curves(all).into_iter().filter(|c| c.len() >= 2) {
        let m = pair_exponents(&c, true, |_, p| p.get("wear_coefficient"));
        let note = format!("; {}", k_maximum(&c));
        let overall = judge_values(
            &curve_label(&c),
            "d ln k / d ln F_N",
            &m,
            Region::Above(0.0),
            &note,
            c[0].pairs.len(),
        );
        let outcome = match overall.side {
            Some(Side::Holds) | None => overall,
            _ => rise_then_fall(&c, overall),
        };
        tally.file(outcome.reads(key_of("slopes W", c[0].curve, c[0].curve)));
    }
    finding(
        "k-rises-with-load",
        "§4.1, Fig. 4: the wear coefficient increases with F_N to a maximum value of k",
        "per curve: the slope d ln k / d ln F_N fitted per surface pair in log–log over the loads where the pair is run \
         in and wears, > 0 (rising, its maximum at or above the study's loads) by its Student-t interval over pairs; \
         with three loads or more, a rise over the two lowest loads and a fall over the two highest (per pair, \
         each interval clear of 0) holds too (a maximum inside the loads), and a fall then a rise is contrary (a \
         minimum); a curve that falls over all the loads is past its maximum, which the study's loads do not reach: \
         undecided, not contrary. The load of the largest mean k is given with each curve"
            .into(),
        "curves",
        tally,
    )
}

/// A curve whose k does not rise over all its loads, read as the sentence "increases to a
/// maximum" allows: rise then fall (holds), fall then rise (contrary), or past its maximum
/// (undecided). The slopes over the lowest two and the highest two run-in loads, per pair.
fn rise_then_fall(c: &[&Setting], overall: Outcome) -> Outcome {
    let falls = overall.side == Some(Side::Contrary);
    let segment = |high: bool| -> Vec<f64> {
        c[0].pairs
            .iter()
            .filter_map(|p| {
                let points: Vec<(f64, f64)> = c
                    .iter()
                    .filter_map(|s| {
                        s.pair(&p.seed)
                            .filter(|q| q.run_in())
                            .map(|q| (s.pressure, q.get("wear_coefficient")))
                    })
                    .filter(|(_, k)| k.is_finite() && *k > 0.0)
                    .collect();
                if points.len() < 3 {
                    return None;
                }
                let (a, b) = if high {
                    (points[points.len() - 2], points[points.len() - 1])
                } else {
                    (points[0], points[1])
                };
                Some((b.1 / a.1).ln() / (b.0 / a.0).ln())
            })
            .collect()
    };
    let (low, high) = (mean_interval(&segment(false)), mean_interval(&segment(true)));
    let label = overall
        .text
        .split_once(": ")
        .map_or(String::new(), |(l, _)| l.to_string());
    let segments = |l: &crate::stats::Interval, h: &crate::stats::Interval| {
        format!(
            "slope over the two lowest loads {}, over the two highest {}",
            show(l),
            show(h)
        )
    };
    if let (Some(l), Some(h)) = (low, high) {
        let region = Region::Above(0.0);
        if l.low > 0.0 && h.high < 0.0 {
            let text = format!(
                "{label}: rises then falls, a maximum inside the loads: {}",
                segments(&l, &h)
            );
            return Outcome::by_interval(l, "d ln k / d ln F_N, two lowest loads", region, text, None);
        }
        if l.high < 0.0 && h.low > 0.0 {
            let text = format!("{label}: falls then rises, a minimum: {}", segments(&l, &h));
            return Outcome::by_interval(l, "d ln k / d ln F_N, two lowest loads", region, text, None);
        }
    }
    if falls {
        let mut past = overall.map_text(|t| {
            format!("{t}: falls over the study's loads, past its maximum (the rise lies below them), not contrary")
        });
        past.side = Some(Side::Undecided);
        past.needed = None;
        return past;
    }
    overall
}

/// §4.1: the increase of k with F_N is slower for tougher materials, which reach their maximum of k
/// at higher F_N.
pub(super) fn tougher_reaches_k_max_later(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let curves = curves(all);
    for (a, b) in curves_differing_in_g(&curves) {
        let (ma, mb) = (
            exponents_by_seed(a, true, |_, p| p.get("wear_coefficient")),
            exponents_by_seed(b, true, |_, p| p.get("wear_coefficient")),
        );
        let diff: Vec<f64> = ma
            .iter()
            .filter_map(|(seed, x)| mb.iter().find(|(s, _)| s == seed).map(|(_, y)| x - y))
            .collect();
        let label = format!("{} vs {}", curve_label(a), curve_label(b));
        // k = W p_m/F_N: the difference of two curves' slopes of k is that of their slopes of W,
        // the crossover's statistic.
        tally.file(
            judge_values(
                &label,
                "d ln k/d ln F_N (tougher) − (less tough)",
                &diff,
                Region::Above(0.0),
                "",
                a[0].pairs.len(),
            )
            .reads(key_of("slopes W difference", a[0].curve, b[0].curve)),
        );
    }
    finding(
        "tougher-reaches-k-max-later",
        "§4.1, Fig. 4a: the increase of k with F_N is slower for tougher materials and they reach their maximum of k at \
         higher F_N",
        "per pair of curves at equal τ̃ differing in 𝒢: the per-pair difference of the slopes d ln k / d ln F_N (tougher \
         minus less tough, each fitted per surface pair over the run-in loads) > 0 by its Student-t interval over the \
         shared pairs: at the study's loads the tougher one's k rises faster or falls slower, its maximum lying at a \
         higher load"
            .into(),
        "pairs of curves",
        tally,
    )
}

/// §4.1, Fig. 4a–b: "wear rates at higher loads are usually higher for materials with larger d*",
/// beside "at low loads, the systems with smaller fracture energy wear more": the curves cross. Judged
/// as a crossover: per pair of curves differing in 𝒢 or τ̃ alone, the ratio W(larger d*)/W(smaller d*)
/// grows with the load, per surface pair; where the study's loads bracket it, the load at which the
/// ratio crosses 1 is given with its interval. No load is called high for lying above the others.
pub(super) fn larger_d_star_wears_more_at_high_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let curves = curves(all);
    for (larger, smaller, what) in curves_differing_in_d_star(&curves) {
        tally.file(crossover(larger, smaller, what));
    }
    finding(
        "larger-d-star-wears-more-at-high-load",
        "sliding model (§4.1, Fig. 4a–b): wear rates at higher loads are usually higher for materials with larger d* \
         (and at low loads the systems with smaller fracture energy wear more: the curves cross)",
        "per pair of curves against load differing in 𝒢 or in τ̃ alone, two parts that must both hold: the slope of \
         ln[W(larger d*)/W(smaller d*)] against ln F_N, fitted per surface pair over the loads where both are run in \
         and wear (a pair needs two such loads), > 0 by its Student-t interval over the pairs (the larger d* gains on \
         the smaller with load); and the larger d* seen wearing more, W(larger d*)/W(smaller d*) > 1 at the highest \
         load where both have two run-in pairs (paired, or by the count test). Where the study's loads bracket it, \
         the load where the ratio crosses 1 (per pair, from its fitted line) is given with its interval (geometric \
         mean over the pairs, Student t on the logs)"
            .into(),
        "pairs of curves",
        tally,
    )
}

/// One pair of curves judged as a crossover ([`larger_d_star_wears_more_at_high_load`]).
fn crossover(larger: &[&Setting], smaller: &[&Setting], what: &str) -> Outcome {
    let label = format!("{} vs {} ({what})", curve_label(larger), curve_label(smaller));
    let fits = |run_in: bool| -> Vec<LineFit> {
        larger[0]
            .pairs
            .iter()
            .filter_map(|p| {
                let (x, y): (Vec<f64>, Vec<f64>) = larger
                    .iter()
                    .filter_map(|a| {
                        let b = smaller.iter().find(|b| b.pressure == a.pressure)?;
                        let (pa, pb) = (a.pair(&p.seed)?, b.pair(&p.seed)?);
                        let ratio = pa.get("wear_rate") / pb.get("wear_rate");
                        let ok = (!run_in || pa.run_in() && pb.run_in()) && ratio.is_finite() && ratio > 0.0;
                        ok.then(|| (a.pressure.ln(), ratio.ln()))
                    })
                    .unzip();
                line_fit(&x, &y)
            })
            .collect()
    };
    let fitted = fits(true);
    if fitted.len() < 2 && fits(false).len() >= 2 {
        return Outcome::not_run_in(format!(
            "{label}: {} pairs with two run-in loads where both wear",
            fitted.len()
        ))
        .reads(key_of("slopes W difference", larger[0].curve, smaller[0].curve));
    }
    let slopes: Vec<f64> = fitted.iter().map(|f| f.slope).collect();
    let note = crossing_note(larger, &fitted);
    let trend = judge_values(
        "trend",
        "d ln[W(larger d*)/W(smaller d*)]/d ln F_N",
        &slopes,
        Region::Above(0.0),
        &note,
        larger[0].pairs.len(),
    )
    .reads(key_of("slopes W difference", larger[0].curve, smaller[0].curve));
    // The larger d* seen wearing more: at the highest load where both have two run-in pairs.
    let top = larger.iter().rev().find_map(|a| {
        let b = smaller.iter().find(|b| b.pressure == a.pressure)?;
        let shared = a
            .pairs
            .iter()
            .filter(|p| p.run_in() && b.pair(&p.seed).is_some_and(|q| q.run_in()));
        (shared.count() >= 2).then_some((*a, *b))
    });
    let seen = match top {
        Some((a, b)) => compare(
            a,
            b,
            "the larger d* wears more at the highest run-in load",
            Compared::WearRate,
            Region::Above(1.0),
            true,
        ),
        None => Outcome::not_run_in("no load where both curves have two run-in pairs".into()),
    };
    all_of(&label, vec![trend, seen])
}

/// "; W ratio = 1 at F_N/(Lx·Ly) = 2e-3 [1.6e-3, 2.5e-3]" where every pair's fitted ratio rises and
/// the pairs' crossings lie, on average, within the curve's loads; else on which side of them.
fn crossing_note(curve: &[&Setting], fitted: &[LineFit]) -> String {
    if fitted.len() < 2 || fitted.iter().any(|f| f.slope <= 0.0) {
        return String::new();
    }
    let logs: Vec<f64> = fitted.iter().map(|f| -f.intercept / f.slope).collect();
    let Some(i) = mean_interval(&logs) else {
        return String::new();
    };
    let (lo, hi) = (curve[0].pressure, curve[curve.len() - 1].pressure);
    let at = i.map(f64::exp);
    let beyond = if at.low < lo || at.high > hi {
        " (its interval reaches beyond the study's loads)"
    } else {
        ""
    };
    if at.estimate < lo || at.estimate > hi {
        format!(
            "; the pairs' fitted ratios cross 1 {} the study's loads, at F_N/(Lx·Ly) ≈ {} (geometric mean over the \
             pairs)",
            if at.estimate < lo { "below" } else { "above" },
            fmt(at.estimate)
        )
    } else {
        format!("; W ratio = 1 at F_N/(Lx·Ly) = {}{beyond}", show(&at))
    }
}

/// §4.1, Fig. 4a: at low loads, the smaller 𝒢 wears more; read as reduced adhesion (a larger 𝒢),
/// the reason the paper gives for experiments one or two orders of magnitude below its k. Judged at
/// the lowest load of the settings' family.
pub(super) fn smaller_g_wears_more_at_low_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let lowest = |s: &Setting| {
        all.iter()
            .filter(|x| x.family == s.family)
            .map(|x| x.pressure)
            .fold(f64::INFINITY, f64::min)
    };
    let pairs = d_star_pairs(all)
        .into_iter()
        .filter(|(a, _, what)| *what == "via 𝒢" && a.pressure == lowest(a));
    for (a, b, _) in pairs {
        tally.file(compare(
            b,
            a,
            "smaller vs larger 𝒢",
            Compared::WearRate,
            Region::Above(1.0),
            true,
        ));
    }
    finding(
        "smaller-g-wears-more-at-low-load",
        "sliding model (§4.1, Fig. 4a): at low loads, the systems with smaller fracture energy wear more; reduced \
         adhesion (a larger 𝒢) reduces wear at low loads, the paper's reading of experiments one or two orders of \
         magnitude below its k",
        "per pair of settings at the study's lowest load, differing in 𝒢 alone: W(smaller 𝒢)/W(larger 𝒢) > 1, paired \
         over the shared run-in surface pairs, or by the count test (W as ω d*³ times the particles, Eq. 5) where a \
         pair has no particle"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// §4.1: at F_N = 2.5×10⁻³ E L², 𝒢 = 10⁻⁶ E L has not yet surpassed 𝒢 = 0.75×10⁻⁶ E L in W.
pub(super) fn toughest_not_yet_ahead(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let near = |x: f64, y: f64| (x / y - 1.0).abs() < 1e-9;
    for a in all
        .iter()
        .filter(|s| s.pressure == super::setting::highest_run_in_load(all, &s.family) && near(s.fracture_energy, 1e-6))
    {
        let top = a.pressure;
        for b in all.iter().filter(|s| {
            s.pressure == top
                && near(s.fracture_energy, 0.75e-6)
                && s.family == a.family
                && s.shear_strength == a.shear_strength
        }) {
            tally.file(compare(
                a,
                b,
                "𝒢 = 10⁻⁶ vs 0.75×10⁻⁶",
                Compared::WearRate,
                Region::Below(1.0),
                true,
            ));
        }
    }
    finding(
        "toughest-not-yet-ahead",
        "§4.1: the simulation with 𝒢 = 10⁻⁶ E L, whose k still increases at F_N = 2.5×10⁻³ E L², has not yet \
         surpassed 𝒢 = 0.75×10⁻⁶ E L in wear rate",
        "at the study's highest load with run-in pairs, per pair of settings of equal τ̃ with 𝒢 = 10⁻⁶ and 0.75×10⁻⁶ (reduced units): \
         W(10⁻⁶)/W(0.75×10⁻⁶) < 1, paired over the shared run-in pairs or by the count test; a study without both has \
         no unit"
            .into(),
        "pairs of settings",
        tally,
    )
}
