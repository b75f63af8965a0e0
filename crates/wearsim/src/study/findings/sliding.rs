//! The sliding model (paper §3, Fig. 3, appendix B): V(s) after running-in, the memory of the initial
//! contact, and Eq. 5. Sliding quantities are judged on the surface pairs that are run in.

use crate::sliding::{RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT};
use crate::stats::{mean_interval, pairs_needed, ratio_of_means, Region, Side};

use super::rules::{on_run_in_pairs, pair_exponents, per_setting, show, Outcome};
use super::setting::{contact_histories, fmt, history_curves, Pair, Setting};
use super::{finding, Finding, Numbers, Tally};

/// §3, Fig. 3: V(s) linear after running-in, per setting.
pub(super) fn volume_linear_after_running_in(all: &[Setting]) -> Finding {
    let tally = per_setting(all, "R² of V(s)", Region::Above(0.9), |_, p| p.get("wear_rate_r2"));
    finding(
        "volume-linear-after-running-in",
        "sliding model (§3, Fig. 3): the wear volume increases linearly with the sliding distance after a running-in \
         period",
        "per setting: R² of the line fitted to V(s) over the fit window > 0.9, by its Student-t interval over the \
         run-in pairs (pairs without a particle have no R² and are left out)"
            .into(),
        "settings",
        tally,
    )
}

/// §3, Fig. 3: V₀ much larger than the later increments, per setting.
pub(super) fn initial_volume_much_larger_than_increments(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for s in all {
        tally.file(initial_volume_ratio(s));
    }
    finding(
        "initial-volume-much-larger-than-increments",
        "sliding model (§3, Fig. 3): the instantaneous wear volume V₀ is much higher than the increments δV",
        "per setting: V₀ over the mean increment of a one-pixel step, V₀/(W·Δx), > 5 over the run-in pairs (pairs \
         with W = 0 left out): the mean of the pairs' ratios by its Student-t interval; where V₀ = 0 in most pairs \
         (no critical junction at s = 0), the ratio of the means ΣV₀/Σ(W·Δx) by a bootstrap over the pairs; where \
         V₀ = 0 in every pair, undecided (no spread: no evidence)"
            .into(),
        "settings",
        tally,
    )
}

/// One setting of [`initial_volume_much_larger_than_increments`].
fn initial_volume_ratio(s: &Setting) -> Outcome {
    let value = |s: &Setting, p: &Pair| p.get("initial_volume") / (p.get("wear_rate") * s.pixel_size);
    let region = Region::Above(5.0);
    let run = s.run_in_pairs();
    let pairs: Vec<(f64, f64)> = run
        .iter()
        .map(|p| (p.get("initial_volume"), p.get("wear_rate") * s.pixel_size))
        .filter(|(v0, wdx)| v0.is_finite() && wdx.is_finite() && *wdx > 0.0)
        .collect();
    let zeros = pairs.iter().filter(|(v0, _)| *v0 == 0.0).count();
    if run.len() < 2 || s.pairs.len() < 2 || 2 * zeros <= pairs.len() || zeros == pairs.len() {
        return on_run_in_pairs(s, "V₀/(W·Δx)", region, value);
    }
    match ratio_of_means(&pairs) {
        Some(i) => {
            let text = format!(
                "{}: ΣV₀/Σ(W·Δx) = {} (V₀ = 0 in {zeros} of {} run-in pairs; bootstrap over the pairs)",
                s.label(),
                show(&i),
                pairs.len()
            );
            Outcome::by_interval(i, "ΣV₀/Σ(W·Δx)", region, text, None)
        }
        None => on_run_in_pairs(s, "V₀/(W·Δx)", region, value),
    }
}

/// §3, Fig. 3: during running-in V(s) can rise more steeply than after it.
pub(super) fn running_in_steeper(all: &[Setting]) -> Finding {
    // The mean slope over the running-in, (V(s_r) − V₀)/s_r with V(s_r) on the fitted line W s_r + b,
    // over the slope after it: 1 + (b − V₀)/(W s_r).
    let tally = per_setting(all, "running-in slope / W", Region::Above(1.0), |_, p| {
        let (w, b, v0, s_r) = (
            p.get("wear_rate"),
            p.get("wear_volume_intercept"),
            p.get("initial_volume"),
            p.get("fit_window_start"),
        );
        1.0 + (b - v0) / (w * s_r)
    });
    finding(
        "running-in-steeper",
        "sliding model (§3, Fig. 3): after a running-in period, in which the increase can be steeper",
        "per setting: the mean slope of V(s) over the running-in, (V(s_r) − V₀)/s_r with V(s_r) = W s_r + b on the \
         fitted line, over W, > 1 by its Student-t interval over the run-in pairs (pairs with W = 0 left out)"
            .into(),
        "settings",
        tally,
    )
}

/// §3: the number of contacts present at s = 0 decays exponentially, per contact history.
pub(super) fn memory_decays_exponentially(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for s in contact_histories(all) {
        let r2: Vec<f64> = s.pairs.iter().map(|p| p.get("memory_decay_r2")).collect();
        let lengths: Vec<String> = s.pairs.iter().map(|p| fmt(p.get("memory_decay_length"))).collect();
        let note = format!("; ℓ per pair = {}", lengths.join(", "));
        tally.file(super::rules::judge_values(
            &s.history_label(),
            "R² of ln N₀(s)",
            &r2,
            Region::Above(0.8),
            &note,
            s.pairs.len(),
        ));
    }
    finding(
        "memory-decays-exponentially",
        "sliding model (§3): the number of remaining contacts that were present at s = 0 decays exponentially with \
         sliding distance",
        "per contact history (one τ̃ and load: the memory does not depend on 𝒢): R² of the line fitted to ln N₀(s) of \
         each surface pair (weighted by N₀, the inverse of ln N₀'s Poisson variance) > 0.8, by its Student-t \
         interval over pairs"
            .into(),
        "contact histories",
        tally,
    )
}

/// §3: the running-in is a safety margin after which the system is run in, per surface pair.
pub(super) fn running_in_sufficient(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for s in contact_histories(all) {
        for p in &s.pairs {
            let r = p.decay_lengths();
            let left = p.lineages_left();
            let line = format!(
                "{}, pair {}: {}s_r = {} ℓ, ℓ = {}",
                s.history_label(),
                p.seed,
                if left.is_finite() {
                    format!("{:.0} % of the lineages of s = 0 left at s_r, ", 100.0 * left)
                } else {
                    String::new()
                },
                fmt(r),
                fmt(p.get("memory_decay_length"))
            );
            // One measurement per pair, no interval: its side as it is.
            tally.file(Outcome::Judged {
                side: if p.run_in() { Side::Holds } else { Side::Contrary },
                text: line,
                needed: None,
                numbers: None,
            });
        }
    }
    finding(
        "running-in-sufficient",
        "sliding model (§3): the running-in is a safety margin after which the system is definitely run in",
        format!(
            "per surface pair and contact history: at most {:.0} % of the junction lineages of s = 0 left where the \
             fit window starts (s_r), counted in the pair's steps (where not counted, s_r ≥ {RUN_IN_DECAY_LENGTHS} of the \
             pair's own fitted decay lengths ℓ, which aims at the same e^−3); one count per pair, read without an \
             interval",
            RUN_IN_LINEAGES_LEFT * 100.0
        ),
        "pairs",
        tally,
    )
}

/// §3: the decay constant is not uniform for different normal loads.
pub(super) fn decay_length_varies_with_load(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    // Practically uniform: ℓ changes by less than a factor 10^0.1 = 1.26 over a tenfold load.
    const UNIFORM: f64 = 0.1;
    for c in history_curves(all).into_iter().filter(|c| c.len() >= 2) {
        let m = pair_exponents(&c, false, |_, p| p.get("memory_decay_length"));
        let label = format!(
            "{} ({} loads)",
            c[0].history_label().split(", F_N").next().unwrap_or(""),
            c.len()
        );
        let outcome = match mean_interval(&m) {
            Some(i) => {
                let side = if i.low > 0.0 || i.high < 0.0 {
                    Side::Holds
                } else if i.low > -UNIFORM && i.high < UNIFORM {
                    Side::Contrary
                } else {
                    Side::Undecided
                };
                let towards = if i.estimate >= 0.0 {
                    Region::Above(0.0)
                } else {
                    Region::Below(0.0)
                };
                Outcome::Judged {
                    side,
                    text: format!("{label}: exponent of ℓ ∝ F_N^m = {} ({} pairs)", show(&i), i.n),
                    needed: (side == Side::Undecided).then(|| pairs_needed(&m, towards)).flatten(),
                    // Its margin: from 0 (the side the estimate lies on), or, where ℓ is practically
                    // uniform, inside ±UNIFORM.
                    numbers: Some(Numbers {
                        quantity: "exponent of ℓ ∝ F_N^m".into(),
                        interval: i,
                        region: if side == Side::Contrary {
                            Region::Within(-UNIFORM, UNIFORM)
                        } else {
                            towards
                        },
                    }),
                }
            }
            None => Outcome::undecided(format!("{label}: ℓ fitted at two loads in {} pairs only", m.len())),
        };
        tally.file(outcome);
    }
    finding(
        "decay-length-varies-with-load",
        "sliding model (§3): the decay constant is not uniform for different surfaces or normal loads",
        format!(
            "per τ̃ (contact histories against load): the exponent m of ℓ ∝ F_N^m, fitted per surface pair in log–log; \
             holds when its Student-t interval excludes 0, contrary when it lies within ±{UNIFORM} (ℓ practically \
             uniform); the spread between surfaces is shown by the per-pair ℓ of the memory finding"
        ),
        "τ̃",
        tally,
    )
}

/// Where appendix B's "slightly underestimates" puts Eq. 5 / W: [0.6, 1].
pub(crate) const EQUATION_5_OVER_W: (f64, f64) = (0.6, 1.0);

/// Eq. 5 / W of one surface pair (NaN where W = 0).
pub(super) fn equation_5_over_w(p: &Pair) -> f64 {
    p.get("wear_rate_estimate") / p.get("wear_rate")
}

/// Appendix B (Fig. B.9b): Eq. 5 slightly underestimates W, per setting; with it, the particles'
/// cube-mean diameter d̄ = d* (W / Eq. 5)^(1/3), d* as the typical particle size (§3.1, §6).
pub(super) fn equation_5_slightly_below_w(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let (low, high) = EQUATION_5_OVER_W;
    for s in all {
        let outcome = on_run_in_pairs(s, "Eq. 5 / W", Region::Within(low, high), |_, p| equation_5_over_w(p));
        // The same numbers read as a size: d̄/d* = (W / Eq. 5)^(1/3).
        let size = |text: &str| -> String {
            let ratios: Vec<f64> = s
                .run_in_pairs()
                .iter()
                .map(|p| p.get("wear_rate") / p.get("wear_rate_estimate"))
                .filter(|v| v.is_finite())
                .collect();
            match mean_interval(&ratios) {
                Some(i) => format!(
                    "{text}; d̄/d* = (W/Eq. 5)^(1/3) = {}",
                    show(&i.map(|x| x.max(0.0).cbrt()))
                ),
                None => text.to_string(),
            }
        };
        tally.file(match outcome {
            judged @ Outcome::Judged { .. } => judged.map_text(|text| size(&text)),
            other => other,
        });
    }
    finding(
        "equation-5-slightly-below-w",
        "appendix B (Fig. B.9b): ω d*³ dN*₊/ds (Eq. 5) slightly underestimates the summed wear rate; d* is not only \
         the minimum but probably also the common particle size (§3.1, §6)",
        format!(
            "per setting: Eq. 5 / W in [{low}, {high}] by its Student-t interval over the run-in pairs (pairs with W = 0 \
             left out); the same numbers give the particles' cube-mean diameter d̄ = d* (W / Eq. 5)^(1/3), shown beside \
             it, not counted apart"
        ),
        "settings",
        tally,
    )
}
