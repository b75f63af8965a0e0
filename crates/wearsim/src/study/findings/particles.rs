//! The wear particles (paper §4.1, Fig. 5, Fig. S.1a): how many each material emits, when wear
//! sets in, and which particles carry the wear.

use crate::stats::{count_ratio, judge::smallest, Interval, Region, Side};

use super::rules::{compare, curve_label, key_of, show, Compared, Outcome};
use super::setting::{at_highest_load, curves, curves_differing_in_g, fmt, param, pressures, Pair, Setting};
use super::{finding, Finding, Tally, Unit, Verdict};

/// Particles of the seeds `a` and `b` share, both run in: (particles of a, of b, pairs).
fn shared_counts(a: &Setting, b: &Setting) -> (u64, u64, usize) {
    let shared: Vec<(&Pair, &Pair)> = a
        .pairs
        .iter()
        .filter_map(|p| b.pair(&p.seed).map(|q| (p, q)))
        .filter(|(p, q)| p.run_in() && q.run_in())
        .collect();
    (
        shared.iter().map(|(p, _)| p.particles()).sum(),
        shared.iter().map(|(_, q)| q.particles()).sum(),
        shared.len(),
    )
}

/// §4.1, Fig. S.1a: for large 𝒢 the onset of wear is delayed to higher loads.
pub(super) fn delayed_onset_for_large_g(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let curves = curves(all);
    for (a, b) in curves_differing_in_g(&curves) {
        tally.file(onset(a, b));
    }
    finding(
        "delayed-onset-for-large-g",
        "§4.1, Fig. S.1a: by reducing adhesion (larger 𝒢) even the onset of wear can be delayed to higher loads",
        "per pair of curves at equal τ̃ differing in 𝒢: the ratio of the particles formed in the fit window, N*₊(larger \
         𝒢)/N*₊(smaller 𝒢) summed over the shared run-in pairs, is smaller at the lowest load than at the highest: \
         holds when the two ratios' exact intervals (two Poisson counts) are disjoint in that order, contrary when \
         disjoint the other way; the highest load is the highest where both curves have two shared run-in pairs"
            .into(),
        "pairs of curves",
        tally,
    )
}

/// One pair of curves of the onset finding: `a` the larger 𝒢. It reads the particle counts of the
/// two curves at their lowest load and at the highest where both have two shared run-in pairs.
fn onset(a: &[&Setting], b: &[&Setting]) -> Outcome {
    let label = format!("{} vs {}", curve_label(a), curve_label(b));
    let at = |i: usize| -> Option<(u64, u64, usize, &Setting, &Setting)> {
        let sa = a.get(i)?;
        let sb = b.iter().find(|s| s.pressure == sa.pressure)?;
        let (na, nb, n) = shared_counts(sa, sb);
        Some((na, nb, n, *sa, *sb))
    };
    let top_index = (1..a.len()).rev().find(|&i| at(i).is_some_and(|x| x.2 >= 2));
    let (Some(low), Some(top)) = (at(0), at(top_index.unwrap_or(a.len() - 1))) else {
        return Outcome::undecided(format!("{label}: the curves share no load"));
    };
    let reads = |o: Outcome| {
        o.reads(key_of("rates", low.3.id, low.4.id))
            .reads(key_of("rates", top.3.id, top.4.id))
    };
    if a[0].curve_particles == 0 || b[0].curve_particles == 0 {
        // A curve below the onset of wear at every load of the study says nothing of where its
        // onset lies.
        return reads(Outcome::undecided(format!(
            "{label}: d* = {:.0} px forms no particle at any load of the study: below the onset of wear, no \
             evidence either way",
            if a[0].curve_particles == 0 {
                a[0].d_star_px()
            } else {
                b[0].d_star_px()
            }
        )));
    }
    if low.2 < 2 || top.2 < 2 {
        return reads(Outcome::not_run_in(format!(
            "{label}: {} and {} shared run-in pairs at the lowest load and the highest with run-in pairs",
            low.2, top.2
        )));
    }
    let ratio = |(na, nb, ..): (u64, u64, usize, &Setting, &Setting), k: usize, pairs: usize| -> Option<Interval> {
        let grow = |c: u64| (c as f64 * k as f64 / pairs as f64).round() as u64;
        count_ratio(grow(na), grow(nb))
    };
    let side_at = |k: usize| -> Side {
        match (ratio(low, k, low.2), ratio(top, k, top.2)) {
            (Some(r0), Some(r1)) if r0.high < r1.low => Side::Holds,
            (Some(r0), Some(r1)) if r0.low > r1.high => Side::Contrary,
            _ => Side::Undecided,
        }
    };
    let side = side_at(low.2);
    let show_at = |x: (u64, u64, usize, &Setting, &Setting)| match ratio(x, x.2, x.2) {
        Some(i) => format!(
            "at F_N/(Lx·Ly) = {}: {} vs {} particles, ratio {}",
            param(x.3.pressure),
            x.0,
            x.1,
            show(&i)
        ),
        None => format!("at F_N/(Lx·Ly) = {}: no particle in either", param(x.3.pressure)),
    };
    reads(Outcome::judged(
        side,
        format!("{label}: {}; {}", show_at(low), show_at(top)),
        // With 80 % power from the log ratios where every count is positive; else the counts
        // grown until their intervals part.
        (side == Side::Undecided)
            .then(|| {
                crate::stats::pairs_needed_for_disjoint_ratios((low.0, low.1, low.2), (top.0, top.1, top.2))
                    .or_else(|| smallest(low.2, |k| side_at(k) != Side::Undecided))
            })
            .flatten(),
        // Two intervals compared with each other, not one against a threshold.
        None,
    ))
}

/// The settings at one load of one family, with the hardest-and-least-tough one (largest τ̃ and
/// smallest 𝒢 of that load, when one setting has both) and the softest-and-toughest one.
struct AtLoad<'a> {
    settings: Vec<&'a Setting>,
    hardest_least_tough: Option<&'a Setting>,
    softest_toughest: Option<&'a Setting>,
}

fn at_loads(all: &[Setting]) -> Vec<AtLoad<'_>> {
    let mut families: Vec<&str> = all.iter().map(|s| s.family.as_str()).collect();
    families.sort_unstable();
    families.dedup();
    let mut out = Vec::new();
    for family in families {
        for p in pressures(all) {
            let settings: Vec<&Setting> = all.iter().filter(|s| s.family == family && s.pressure == p).collect();
            if settings.len() < 2 {
                continue;
            }
            let tau = |f: fn(f64, f64) -> f64, init| settings.iter().map(|s| s.shear_strength).fold(init, f);
            let g = |f: fn(f64, f64) -> f64, init| settings.iter().map(|s| s.fracture_energy).fold(init, f);
            let (hardest, softest) = (tau(f64::max, f64::NEG_INFINITY), tau(f64::min, f64::INFINITY));
            let (least_tough, toughest) = (g(f64::min, f64::INFINITY), g(f64::max, f64::NEG_INFINITY));
            let find = |t: f64, e: f64| {
                settings
                    .iter()
                    .copied()
                    .find(|s| s.shear_strength == t && s.fracture_energy == e)
            };
            out.push(AtLoad {
                hardest_least_tough: find(hardest, least_tough),
                softest_toughest: find(softest, toughest),
                settings,
            });
        }
    }
    out
}

/// §4.1, Fig. 5: the hardest and the least tough material wear the least, but form the most
/// particles (much smaller ones). Both halves, against every other setting of the load.
pub(super) fn hardest_least_tough_emits_most_wears_least(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    let mut wear = Tally::default();
    for at in at_loads(all) {
        let Some(x) = at.hardest_least_tough else { continue };
        for y in at.settings.iter().filter(|y| !std::ptr::eq(**y, x)) {
            tally.file(compare(
                x,
                y,
                "emits more",
                Compared::ParticleRate,
                Region::Above(1.0),
                true,
            ));
            if at_highest_load(all, x) {
                wear.file(compare(
                    x,
                    y,
                    "wears less",
                    Compared::WearRate,
                    Region::Below(1.0),
                    true,
                ));
            }
        }
    }
    for u in &mut tally.units {
        u.part = Some("emission half");
    }
    // A study that judges the emission half but no wear half (one load, or no load with two run-in
    // pairs) cannot reproduce the sentence: the missing half is a unit not run in.
    if wear.units.is_empty() && !tally.units.is_empty() {
        wear.file(Outcome::not_run_in(
            "the wear half: judged at the highest load with two run-in pairs of a study of several loads, which \
             this study lacks"
                .into(),
        ));
    }
    for mut u in wear.units {
        u.part = Some("wear half");
        tally.units.push(u);
    }
    let mut f = finding(
        "hardest-least-tough-emits-most-wears-least",
        "§4.1, Fig. 5: the hardest material and the material with the lowest fracture toughness wear the least, but \
         emit the most wear particles (much smaller ones)",
        "two parts, each per load and other setting of it: the setting of the largest τ̃ and smallest 𝒢 of the load \
         against it, paired over the shared run-in pairs (count test where a pair has no particle); the emission \
         half, dN*₊/ds ratio > 1 at every load; the wear half, W ratio < 1 at the highest load with run-in pairs \
         (below it the paper's Fig. 4a has the smaller 𝒢 wearing more at low loads, so that half is judged at the top \
         of the range only). Reproduced only when both halves are; with one τ̃ the hardness reading is untested"
            .into(),
        "comparisons",
        tally,
    );
    let taus = {
        let mut t: Vec<String> = all.iter().map(|s| format!("{:e}", s.shear_strength)).collect();
        t.sort();
        t.dedup();
        t.len()
    };
    if taus == 1 && !f.units.is_empty() {
        f.notes
            .push("one τ̃: the hardness reading of the sentence is untested, only the toughness one".into());
    }
    f
}

/// §4.1: to minimise the emission of fine particles, a soft but tough material.
pub(super) fn soft_tough_fewest_particles(all: &[Setting]) -> Finding {
    let mut tally = Tally::default();
    for at in at_loads(all) {
        let Some(z) = at.softest_toughest else { continue };
        // The comparison with the hardest and least tough setting is Fig. 5's: not counted twice.
        let others = at
            .settings
            .iter()
            .filter(|y| !std::ptr::eq(**y, z) && !at.hardest_least_tough.is_some_and(|x| std::ptr::eq(**y, x)));
        for y in others {
            tally.file(compare(
                z,
                y,
                "emits fewer",
                Compared::ParticleRate,
                Region::Below(1.0),
                true,
            ));
        }
    }
    finding(
        "soft-tough-fewest-particles",
        "§4.1: if one wants to minimise the emission of fine particles, the model suggests a soft but tough material",
        "per load: the setting of the smallest τ̃ and largest 𝒢 of the load against every other setting but the \
         hardest-and-least-tough one (that comparison is Fig. 5's, counted there): dN*₊/ds ratio < 1, paired over the \
         shared run-in pairs or by the count test; a study of two materials per load has no unit of its own"
            .into(),
        "comparisons",
        tally,
    )
}

/// The mean particle volume of a pair, W/(dN*₊/ds) (NaN without particles).
fn particle_volume(p: &Pair) -> f64 {
    p.get("wear_rate") / p.get("particle_rate")
}

/// §4.1: more severe wear is due to the detachment of large wear particles. In the model every
/// particle a junction larger than d* emits has a volume ≈ ω d*³ (Eq. 5), so between settings of
/// different d* the ratio of their mean particle volumes is fixed at (d*₁/d*₂)³ and which of them
/// wears more is the W comparison the crossover finding judges: the ratio is shown against Eq. 5's
/// value and not counted.
pub(super) fn severe_wear_from_large_particles(all: &[Setting]) -> Finding {
    let mut units = Vec::new();
    let mut lines = Vec::new();
    for at in at_loads(all)
        .into_iter()
        .filter(|at| at_highest_load(all, at.settings[0]))
    {
        for (i, a) in at.settings.iter().enumerate() {
            for b in &at.settings[i + 1..] {
                if a.critical_diameter == b.critical_diameter {
                    continue;
                }
                let (large, small) = if a.critical_diameter > b.critical_diameter {
                    (*a, *b)
                } else {
                    (*b, *a)
                };
                let eq5 = (large.critical_diameter / small.critical_diameter).powi(3);
                let ratio = compare(
                    large,
                    small,
                    "larger vs smaller d*",
                    Compared::Derived(particle_volume, "mean particle volume W/(dN*₊/ds)"),
                    Region::Within(eq5, eq5),
                    true,
                )
                .map_text(|text| format!("{text}; Eq. 5's (d*₁/d*₂)³ = {}", fmt(eq5)));
                let mut unit = Unit::of(&ratio);
                unit.outcome = "shown";
                unit.p = None;
                unit.margin = None;
                unit.pairs_to_decide = None;
                unit.rule = format!("= {} by Eq. 5", fmt(eq5));
                lines.push(unit.text.clone());
                units.push(unit);
            }
        }
    }
    let verdict = if units.is_empty() {
        Verdict::NotTestable
    } else {
        Verdict::Cited
    };
    Finding {
        key: "severe-wear-from-large-particles",
        paper: "§4.1: more severe wear is due to the detachment of large wear particles",
        rule: "per pair of settings of different d* at the study's highest load: their mean particle volumes \
               W/(dN*₊/ds), paired over the shared run-in pairs, shown against (d*₁/d*₂)³, the ratio Eq. 5 fixes \
               (every particle ≈ ω d*³); which of them wears more is judged once, by \
               larger-d-star-wears-more-at-high-load (and Fig. 5's wear half), so this finding is not counted"
            .into(),
        observed: if lines.is_empty() {
            "no pair of settings of different d* at the highest load".into()
        } else {
            lines.join("; ")
        },
        verdict,
        counts: (0, 0, 0, 0),
        pairs_to_decide: None,
        units,
        verdict_under_holm: None,
        claim: super::claim("severe-wear-from-large-particles"),
        unit_name: "pairs of settings",
        same_data_as: None,
        reading: None,
        verdicts_by_rule: None,
        notes: Vec::new(),
        cites: Some(
            "Eq. 5 fixes the particle-volume ratio at (d*₁/d*₂)³; which setting wears more is judged once, by \
             the crossover finding (larger d* wears more at high load) and Fig. 5's wear half",
        ),
    }
}
