//! The sliding model (paper §3, Fig. 3, appendix B): V(s) after running-in, the memory of the initial
//! contact, and Eq. 5. Sliding quantities are judged on the surface pairs that are run in.

use crate::sliding::{RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT};
use crate::stats::{mean_interval, pairs_needed, poisson_linear_r2, ratio_of_means, Region, Side};

use super::rules::{on_run_in_pairs, pair_exponents, per_setting, show, Outcome};
use super::setting::{contact_histories, fmt, history_curves, Pair, Setting};
use super::{finding, Finding, Numbers, Tally, Verdict};

/// How far below the R² of an exactly linear record of its particles a pair's R² of V(s) may lie
/// and V(s) still count as linear: 0.1.
const R2_SHORTFALL: f64 = 0.1;

/// §3, Fig. 3: V(s) linear after running-in, per setting. A stepped V(s) of few particles cannot
/// reach R² = 1 however linear the wear, so each pair's R² is read against the R² an exactly
/// linear (Poisson) emission of its own particle count gives ([`poisson_linear_r2`]).
pub(super) fn volume_linear_after_running_in(all: &[Setting]) -> Finding {
    let tally = per_setting(
        all,
        "R² of V(s) − R² of a linear record",
        Region::Above(-R2_SHORTFALL),
        |_, p| p.get("wear_rate_r2") - poisson_linear_r2(p.particles()),
    );
    finding(
        "volume-linear-after-running-in",
        "sliding model (§3, Fig. 3): the wear volume increases linearly with the sliding distance after a running-in \
         period",
        format!(
            "per setting: per run-in pair, the R² of the line fitted to V(s) over the fit window less the R² an exactly \
             linear wear of the same number of particles is expected to give (particles of one volume formed as a \
             Poisson process of constant rate: 0.50, 0.69, 0.78, 0.88 for 1, 2, 3, 6 particles), > −{R2_SHORTFALL} by \
             its Student-t interval over the pairs (pairs without a particle have no R² and are left out): holds \
             when V(s) is as straight as linear wear of that many particles can be, contrary when it is bent \
             beyond it"
        ),
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
    let mut f = finding(
        "initial-volume-much-larger-than-increments",
        "sliding model (§3, Fig. 3): the instantaneous wear volume V₀ is much higher than the increments δV",
        "per setting: V₀ over the mean increment of a one-pixel step, V₀/(W·Δx), > 5 over the run-in pairs (pairs \
         with W = 0 left out): the mean of the pairs' ratios by its Student-t interval; where V₀ = 0 in most pairs \
         (no critical junction at s = 0), the ratio of the means ΣV₀/Σ(W·Δx) by a bootstrap over the pairs; where \
         V₀ = 0 in every pair, undecided (no spread: no evidence)"
            .into(),
        "settings",
        tally,
    );
    // The convention that decides these units, said where it does.
    let zero = f
        .units
        .iter()
        .filter(|u| u.text.contains("V₀/(W·Δx) = 0 in each"))
        .count();
    if zero > 0 {
        let (h, c, i, n) = f.counts;
        f.notes.push(format!(
            "{zero} of its units have V₀ = 0 in every pair (no junction of d* at s = 0) and count as inconclusive, \
             no spread being no evidence; counted contrary instead, the verdict would be {}",
            Verdict::of_counts(h, c + zero, h + c + i + n).name()
        ));
    }
    f
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

/// §3: the running-in is a safety margin after which the system is run in. The paper's running-in
/// is L/4; a study's own (often shorter, in a smaller box) is what its pairs show, so this is a
/// diagnostic of the study, one row per contact history, and not a verdict on the paper.
pub(super) fn running_in_sufficient(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for s in contact_histories(all) {
        let line = format!("{}: {}", s.history_label(), s.run_in_table_row());
        tally.file(Outcome::judged(Side::Undecided, line, None, None));
    }
    let running_in: Vec<String> = {
        let mut r: Vec<f64> = all.iter().map(|s| s.running_in).filter(|r| r.is_finite()).collect();
        r.sort_by(f64::total_cmp);
        r.dedup();
        r.iter().map(|x| fmt(*x)).collect()
    };
    let mut f = finding(
        "running-in-sufficient",
        "sliding model (§3): the running-in (L/4 in the paper) is a safety margin after which the system is \
         definitely run in",
        format!(
            "per contact history: how many surface pairs this study's running-in (s_r = {}{}) runs in, by the lineages \
             of s = 0 left where the fit window starts (at most {:.0} %, the findings' rule), and by s_r ≥ \
             {RUN_IN_DECAY_LENGTHS} of the pair's own fitted decay lengths ℓ; a measure of this study's running-in, \
             not of the paper's L/4, so it is shown and not counted",
            running_in.join(", "),
            if running_in.is_empty() { "" } else { " of the box side" },
            RUN_IN_LINEAGES_LEFT * 100.0
        ),
        "contact histories",
        tally,
    );
    for u in &mut f.units {
        u.outcome = "shown";
    }
    f.observed = f.units.iter().map(|u| u.text.as_str()).collect::<Vec<_>>().join("; ");
    f.verdict = if f.units.is_empty() {
        Verdict::NotTestable
    } else {
        Verdict::Diagnostic
    };
    f.counts = (0, 0, 0, 0);
    f.pairs_to_decide = None;
    f.verdict_under_holm = None;
    f
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
                Outcome::judged(
                    side,
                    format!("{label}: exponent of ℓ ∝ F_N^m = {} ({} pairs)", show(&i), i.n),
                    (side == Side::Undecided).then(|| pairs_needed(&m, towards)).flatten(),
                    // Its margin: from 0 (the side the estimate lies on), or, where ℓ is practically
                    // uniform, inside ±UNIFORM.
                    Some(Numbers {
                        quantity: "exponent of ℓ ∝ F_N^m".into(),
                        interval: i,
                        region: if side == Side::Contrary {
                            Region::Within(-UNIFORM, UNIFORM)
                        } else {
                            towards
                        },
                    }),
                )
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
        tally.file(if outcome.side.is_some() {
            outcome.map_text(|text| size(&text))
        } else {
            outcome
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
