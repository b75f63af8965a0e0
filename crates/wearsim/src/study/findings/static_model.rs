//! The static model (paper §2, Fig. 2): the critical-length-scale criterion applied to every contact
//! map of the sliding run, each map on its own. Its numbers are means over every offset, so they need
//! no running-in and are judged on every surface pair.

use crate::stats::Region;

use super::rules::{all_of, compare, curve_label, judge_values, pair_exponents, Compared};
use super::setting::{curves, Setting};
use super::{finding, Finding, Tally};

/// §2, Fig. 2: k_static grows with load, towards 1.
pub(super) fn static_k_below_one_and_rising(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for c in curves(all).into_iter().filter(|c| c.len() >= 2) {
        let column = "static_wear_coefficient_mean";
        let (first, last) = (c[0], c[c.len() - 1]);
        // Rising: per pair, k_static at the highest load minus at the lowest.
        let rise: Vec<f64> = first
            .pairs
            .iter()
            .filter_map(|p| last.pair(&p.seed).map(|q| q.get(column) - p.get(column)))
            .collect();
        let mut parts = vec![judge_values(
            "rise from the lowest to the highest load",
            "Δk_static",
            &rise,
            Region::Above(0.0),
            "",
            first.pairs.len(),
        )];
        // Below 1 at every load (the highest is the binding one, but each load is its own unit).
        for s in &c {
            let k: Vec<f64> = s.pairs.iter().map(|p| p.get(column)).collect();
            parts.push(judge_values(
                &format!("at F_N/(Lx·Ly) = {}", super::setting::param(s.pressure)),
                "k_static",
                &k,
                Region::Below(1.0),
                "",
                s.pairs.len(),
            ));
        }
        tally.file(all_of(&curve_label(&c), parts));
    }
    finding(
        "static-k-below-one-and-rising",
        "static model (§2, Fig. 2): the wear coefficient increases with load, tending towards a limit of one",
        "per curve (one setting against load): the per-pair rise of k_static (mean over every offset) from the lowest \
         to the highest load > 0, and k_static < 1 at every load, each by its Student-t interval over pairs; holds \
         when all parts hold"
            .into(),
        "curves",
        tally,
    )
}

/// §2: the static model's wear rate is superlinear in the load.
pub(super) fn static_wear_superlinear(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for c in curves(all).into_iter().filter(|c| c.len() >= 2) {
        let m = pair_exponents(&c, false, |_, p| p.get("static_wear_rate_mean"));
        let label = curve_label(&c);
        tally.file(judge_values(
            &label,
            "m of W_static ∝ F_N^m",
            &m,
            Region::Above(1.0),
            "",
            c[0].pairs.len(),
        ));
    }
    finding(
        "static-wear-superlinear",
        "static model (§2, Fig. 2): the wear rate is superlinear",
        "per curve: the exponent m of W_static ∝ F_N^m, fitted per surface pair in log–log over the curve's loads \
         (loads with W_static = 0 left out), > 1 by its Student-t interval over pairs"
            .into(),
        "curves",
        tally,
    )
}

/// §2, Fig. 2b: the harder material wears more at equal 𝒢 and load (against Archard's law).
pub(super) fn static_wear_grows_with_hardness(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for a in all {
        for b in all {
            if a.family == b.family
                && a.fracture_energy == b.fracture_energy
                && a.pressure == b.pressure
                && a.shear_strength > b.shear_strength
            {
                let q = Compared::Column("static_wear_rate_mean", "W_static/ω");
                tally.file(compare(a, b, "harder vs softer", q, Region::Above(1.0), false));
            }
        }
    }
    finding(
        "static-wear-grows-with-hardness",
        "static model (§2, Fig. 2b): the wear rate increases with increasing hardness, which contradicts Archard's \
         law",
        "per pair of settings at equal 𝒢 and load differing in τ̃: W_static(harder)/W_static(softer) > 1, paired over \
         the shared surface pairs (geometric mean of the per-pair ratios; paired differences > 0 where a pair has \
         W_static = 0)"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// §2, Fig. 2a: the wear rate increases with decreasing fracture energy.
pub(super) fn static_wear_falls_with_toughness(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for a in all {
        for b in all {
            if a.family == b.family
                && a.shear_strength == b.shear_strength
                && a.pressure == b.pressure
                && a.fracture_energy < b.fracture_energy
            {
                let q = Compared::Column("static_wear_rate_mean", "W_static/ω");
                tally.file(compare(a, b, "less vs more tough", q, Region::Above(1.0), false));
            }
        }
    }
    finding(
        "static-wear-falls-with-toughness",
        "static model (§2, Fig. 2a): the wear rate increases with decreasing fracture energy",
        "per pair of settings at equal τ̃ and load differing in 𝒢: W_static(smaller 𝒢)/W_static(larger 𝒢) > 1, paired \
         over the shared surface pairs (paired differences where a pair has W_static = 0)"
            .into(),
        "pairs of settings",
        tally,
    )
}
