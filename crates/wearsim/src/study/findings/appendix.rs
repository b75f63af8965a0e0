//! The appendices' robustness checks (paper appendices A, C, D, E): settings that differ in one
//! study axis alone (the grid, the box, λ_l, h_rms), compared at equal load. Settings on the same
//! surfaces (λ_l, h_rms: the same seeds and box) are compared pair by pair; settings on other
//! surfaces (another grid or box) as independent sets of pairs (Welch).

use crate::stats::Region;

use crate::sliding::{CRITICAL_GROWTH_LIMIT, GROWTH_REFERENCE_JUNCTIONS, LARGEST_JUNCTION_LIMIT, MERGED_SHARE_LIMIT};
use crate::stats::Side;

use super::rules::{all_of, compare, compare_unpaired, Compared, Outcome};
use super::setting::{differ_only_in, fmt, param, Pair, Setting};
use super::{finding, Finding, Tally, Verdict};

/// A setting's value of an input column (NaN when empty).
fn cell(s: &Setting, column: &str) -> f64 {
    s.family_cells
        .get(column)
        .and_then(|c| c.parse().ok())
        .unwrap_or(f64::NAN)
}

/// Pairs (a, b) of settings at equal load that differ in `axes` alone, with `first(a, b)`.
fn pairs<'a>(
    all: &'a [Setting],
    axes: &[&str],
    first: impl Fn(&Setting, &Setting) -> bool,
) -> Vec<(&'a Setting, &'a Setting)> {
    let mut out = Vec::new();
    for a in all {
        for b in all {
            if a.load == b.load && differ_only_in(a, b, axes) && first(a, b) {
                out.push((a, b));
            }
        }
    }
    out
}

const BOX: [&str; 4] = ["surface.length", "surface.length_y", "surface.grid", "surface.grid_y"];

/// Appendix A: λ_l/Δx = 32 gives the same W as 16 (a finer grid on the same box).
pub(super) fn appendix_a_discretization(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let finer = |a: &Setting, b: &Setting| {
        cell(a, "surface.length") == cell(b, "surface.length") && cell(a, "surface.grid") > cell(b, "surface.grid")
    };
    for (a, b) in pairs(all, &["surface.grid", "surface.grid_y"], finer) {
        tally.file(compare_unpaired(
            a,
            b,
            "finer vs coarser grid",
            Compared::WearRate,
            Region::Within(0.8, 1.25),
        ));
    }
    finding(
        "appendix-a-discretization",
        "appendix A: λ_l/Δx = 32 gives the same wear rate as 16 within the spread of the surface pairs",
        "per pair of settings at equal load differing in the grid alone (same box): W(finer)/W(coarser) within [0.8, \
         1.25], the surfaces being other realisations: ratio of geometric means with Welch's interval, or the count \
         test per pair and fit-window distance"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// Appendix C: boxes agree in W up to a load, above which the smaller box's W falls behind.
pub(super) fn appendix_c_box_size(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let larger = |a: &Setting, b: &Setting| a.length > b.length;
    for (a, b) in pairs(all, &BOX, larger) {
        // The paper's breakdown at F_N ≈ 0.5×10⁻³ E L² on boxes L and L/2: at the larger box's
        // nominal pressure 0.5×10⁻³ E.
        let outcome = if a.pressure <= 0.5e-3 {
            compare_unpaired(
                b,
                a,
                "smaller vs larger box, low load",
                Compared::WearRate,
                Region::Within(0.8, 1.25),
            )
        } else {
            compare_unpaired(
                b,
                a,
                "smaller vs larger box, high load",
                Compared::WearRate,
                Region::Below(1.0),
            )
        };
        tally.file(outcome);
    }
    finding(
        "appendix-c-box-size",
        "appendix C: the wear rates of two box sizes are comparable up to a given load (F_N ≈ 0.5×10⁻³ E L² for \
         boxes L and L/2), after which the smaller box's wear rate breaks down",
        "per pair of settings at equal F_N differing in the box alone: W(smaller box)/W(larger box) within [0.8, \
         1.25] where the larger box's F_N/(Lx·Ly) ≤ 0.5×10⁻³ E, and < 1 above; independent pairs (Welch on the logs, \
         or the count test per pair and fit-window distance)"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// Appendix C: the larger surface has more contact spots, but does not wear more.
pub(super) fn appendix_c_more_spots_not_more_wear(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let larger = |a: &Setting, b: &Setting| a.length > b.length;
    for (a, b) in pairs(all, &BOX, larger) {
        let spots = compare_unpaired(
            a,
            b,
            "more spots",
            Compared::Column("junctions_mean", "N"),
            Region::Above(1.0),
        );
        let wear = compare_unpaired(a, b, "not more wear", Compared::WearRate, Region::Below(1.25));
        tally.file(all_of(&format!("F_N = {}", param(a.load)), vec![spots, wear]));
    }
    finding(
        "appendix-c-more-spots-not-more-wear",
        "appendix C: the larger surface has more contact spots, but does not wear more",
        "per pair of settings at equal F_N differing in the box alone: N(larger)/N(smaller) > 1 and W(larger)/W(smaller) \
         < 1.25 (not more than a quarter more), independent pairs (Welch on the logs, or the count test); holds when \
         both hold"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// Appendix C: the loads past the breakdown, where junctions merge and N* stops growing linearly,
/// whose data the paper treats as unreliable: per setting with a pair in that regime, the measures
/// over its pairs. Shown, not counted: a mark on the data, not a verdict on the paper.
pub(super) fn breakdown_regime(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let range = |pairs: &[&Pair], column: &str, scale: f64| {
        let v: Vec<f64> = pairs
            .iter()
            .map(|p| p.get(column) * scale)
            .filter(|x| x.is_finite())
            .collect();
        match (v.iter().copied().reduce(f64::min), v.iter().copied().reduce(f64::max)) {
            (Some(lo), Some(hi)) => format!("{}–{}", fmt(lo), fmt(hi)),
            _ => "—".into(),
        }
    };
    // Settings that differ in a study axis the labels do not name (the particle rule: the same
    // contact histories) give the same line; it is shown once.
    let mut shown = std::collections::BTreeSet::new();
    for s in all.iter().filter(|s| !s.breakdown_pairs().is_empty()) {
        let pairs: Vec<&Pair> = s.pairs.iter().collect();
        let line = format!(
            "{}: merged junctions {} %, largest junction {} of the box, N*/F_N {} of its best at a lower load, real \
             contact {} % (over the pairs)",
            s.label(),
            range(&pairs, "merged_junction_share", 100.0),
            range(&pairs, "largest_junction_max", 1.0),
            range(&pairs, "critical_junction_growth", 1.0),
            range(&pairs, "contact_area_mean", 100.0),
        );
        if shown.insert(line.clone()) {
            tally.file(Outcome::judged(Side::Undecided, line, None, None));
        }
    }
    let mut f = finding(
        "breakdown-regime",
        "appendix C: above a load junctions start to merge and N* breaks down from its linear scaling with F_N; \
         \"the contacts are expected to interact if they come closer together … we have to treat data after this \
         'breakdown' as unreliable\"",
        format!(
            "per setting with a surface pair in the breakdown regime: a pair is when, over its fit window, at least \
             {:.0} % of its junctions formed by merging, or its largest junction spans at least {} of the box's \
             shorter side, or N*/F_N has fallen below {} of its largest value at a lower load on the same surfaces \
             (a lower load with N* ≥ {}); a mark on the data, shown and not counted",
            100.0 * MERGED_SHARE_LIMIT,
            LARGEST_JUNCTION_LIMIT,
            CRITICAL_GROWTH_LIMIT,
            GROWTH_REFERENCE_JUNCTIONS
        ),
        "settings",
        tally,
    );
    for u in &mut f.units {
        u.outcome = "shown";
    }
    f.observed = if f.units.is_empty() {
        "no load of the study lies in the breakdown regime".into()
    } else {
        f.units.iter().map(|u| u.text.as_str()).collect::<Vec<_>>().join("; ")
    };
    f.verdict = Verdict::Diagnostic;
    f.counts = (0, 0, 0, 0);
    f.pairs_to_decide = None;
    f.verdict_under_holm = None;
    f
}

/// Appendix D: W is robust against λ_l.
pub(super) fn appendix_d_lambda_lower(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let smaller = |a: &Setting, b: &Setting| cell(a, "surface.lambda_lower") < cell(b, "surface.lambda_lower");
    for (a, b) in pairs(all, &["surface.lambda_lower"], smaller) {
        tally.file(compare(
            a,
            b,
            "smaller vs larger λ_l",
            Compared::WearRate,
            Region::Within(0.8, 1.25),
            true,
        ));
    }
    finding(
        "appendix-d-lambda-lower",
        "appendix D (§3.4): the model is robust against the short-wavelength cut-off λ_l (plasticity smooths it out)",
        "per pair of settings at equal load differing in λ_l alone: W(smaller λ_l)/W(larger λ_l) within [0.8, 1.25], \
         paired over the shared surface pairs (same seeds and box), or by the count test"
            .into(),
        "pairs of settings",
        tally,
    )
}

/// Appendix E: h_rms has at most a very small influence on W.
pub(super) fn appendix_e_rms_height(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let smaller = |a: &Setting, b: &Setting| cell(a, "surface.rms_height") < cell(b, "surface.rms_height");
    for (a, b) in pairs(all, &["surface.rms_height"], smaller) {
        tally.file(compare(
            a,
            b,
            "smaller vs larger h_rms",
            Compared::WearRate,
            Region::Within(0.95, 1.05),
            true,
        ));
    }
    finding(
        "appendix-e-rms-height",
        "appendix E (§4.1): the wear rates do not change between two values of h_rms",
        "per pair of settings at equal load differing in h_rms alone: W(smaller h_rms)/W(larger h_rms) within [0.95, \
         1.05], paired over the shared surface pairs (the same surfaces scaled), or by the count test"
            .into(),
        "pairs of settings",
        tally,
    )
}
