//! The influence of material properties (paper §4.1, Fig. 4, §6): the level of k, its trend with load,
//! Archard-like wear, and which d* wears more at low and high loads.

use crate::stats::Region;

use super::rules::{compare, curve_label, exponents_by_seed, judge_values, pair_exponents, per_setting, Compared};
use super::setting::{curves, curves_differing_in_g, d_star_pairs, fmt, high, param, Setting};
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
        tally.file(judge_values(
            &curve_label(&c),
            "m of W ∝ F_N^m",
            &m,
            region,
            "",
            c[0].pairs.len(),
        ));
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

/// §4.1: k increases with load (up to a maximum).
pub(super) fn k_rises_with_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for c in curves(all).into_iter().filter(|c| c.len() >= 2) {
        let m = pair_exponents(&c, true, |_, p| p.get("wear_coefficient"));
        let note = format!("; {}", k_maximum(&c));
        let label = curve_label(&c);
        tally.file(judge_values(
            &label,
            "d ln k / d ln F_N",
            &m,
            Region::Above(0.0),
            &note,
            c[0].pairs.len(),
        ));
    }
    finding(
        "k-rises-with-load",
        "§4.1, Fig. 4: the wear coefficient increases with F_N to a maximum value of k",
        "per curve: the slope d ln k / d ln F_N fitted per surface pair in log–log over the loads where the pair is run \
         in and wears, > 0 (below the maximum) by its Student-t interval over pairs; < 0 is contrary (the curve is past \
         its maximum over the study's loads); the load of the largest mean k is given with each curve"
            .into(),
        "curves",
        tally,
    )
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
        tally.file(judge_values(
            &label,
            "d ln k/d ln F_N (tougher) − (less tough)",
            &diff,
            Region::Above(0.0),
            "",
            a[0].pairs.len(),
        ));
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

/// §4.1, Fig. 4a–b: at high loads, the larger d* wears more.
pub(super) fn larger_d_star_wears_more_at_high_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for (a, b, what) in d_star_pairs(all).into_iter().filter(|(a, ..)| high(all, a.pressure)) {
        tally.file(compare(a, b, what, Compared::WearRate, Region::Above(1.0), true));
    }
    finding(
        "larger-d-star-wears-more-at-high-load",
        "sliding model (§4.1, Fig. 4a–b): wear rates at higher loads are usually higher for materials with larger d*",
        "per pair of settings at one load in the upper half of the study's loads, differing in 𝒢 or in τ̃ alone: \
         W(larger d*)/W(smaller d*) > 1, paired over the shared run-in surface pairs, or by the count test where a pair \
         has no particle"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// §4.1, Fig. 4a: at low loads, the smaller 𝒢 wears more; read as reduced adhesion (a larger 𝒢),
/// the reason the paper gives for experiments one or two orders of magnitude below its k.
pub(super) fn smaller_g_wears_more_at_low_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let pairs = d_star_pairs(all)
        .into_iter()
        .filter(|(a, _, what)| *what == "via 𝒢" && !high(all, a.pressure));
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
        "per pair of settings at one load in the lower half of the study's loads, differing in 𝒢 alone: W(smaller \
         𝒢)/W(larger 𝒢) > 1, paired over the shared run-in surface pairs, or by the count test (W as ω d*³ times the \
         particles, Eq. 5) where a pair has no particle"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// §4.1: at F_N = 2.5×10⁻³ E L², 𝒢 = 10⁻⁶ E L has not yet surpassed 𝒢 = 0.75×10⁻⁶ E L in W.
pub(super) fn toughest_not_yet_ahead(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let top = super::setting::pressures(all).last().copied().unwrap_or(f64::NAN);
    let near = |x: f64, y: f64| (x / y - 1.0).abs() < 1e-9;
    for a in all
        .iter()
        .filter(|s| s.pressure == top && near(s.fracture_energy, 1e-6))
    {
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
        "at the study's highest load, per pair of settings of equal τ̃ with 𝒢 = 10⁻⁶ and 0.75×10⁻⁶ (reduced units): \
         W(10⁻⁶)/W(0.75×10⁻⁶) < 1, paired over the shared run-in pairs or by the count test; a study without both has \
         no unit"
            .into(),
        "pairs of settings",
        tally,
    )
}
