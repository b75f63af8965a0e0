//! The paper's findings (Brink, Frérot & Molinari 2021, §2–4, §6 and appendix B) judged on a study's
//! tidy table with statistics: the surface pair is the unit of replication, every rule reads a 95 %
//! interval over pairs (`stats`) and holds when the interval lies on the paper's side of its
//! threshold, is contrary when it lies on the other side and inconclusive otherwise. Sliding
//! quantities are judged on the pairs that are run in (at most 5 % of the junction lineages of s = 0
//! left where the fit window starts); a unit with fewer than two is counted as not run in, and a
//! verdict that another run-in rule would change is rule-dependent. Each statistic is counted once
//! (`judge_once`); the verdict follows from the counted units (`Verdict::of_counts`).
//! `wearsim study plot` prints them and writes `figures/findings.md` ([`markdown`]).
//!
//! - `setting`: the settings and their surface pairs, and the groupings the rules compare;
//! - `rules`: one unit judged (per setting, two settings pair by pair or by a count test, a trend
//!   over load per pair), with the statistics it reads;
//! - `static_model`, `sliding`, `materials`, `particles`, `kim`, `appendix`: one
//!   function per finding, its rule beside it.

mod appendix;
mod kim;
mod materials;
mod particles;
mod rules;
mod setting;
mod sliding;
mod static_model;

use crate::output::Table;
use crate::sliding::{RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT};
use crate::stats::{t_critical, Interval, Method, Region, Side, LEVEL};
pub use setting::RunInRule;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Whether a study reproduces a finding of the paper, from the counts of a [`Tally`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// Holds in every decided unit, and at least half of all units are decided.
    Reproduced,
    /// Holds in more decided units than it is contrary in, and at least half are decided.
    Partly,
    /// Contrary in at least as many decided units as it holds in, and at least half are decided.
    NotReproduced,
    /// Fewer than half of the units are decided (inconclusive or not run in): no verdict either way.
    Inconclusive,
    /// No unit of the study speaks to the finding.
    NotTestable,
    /// The finding restates what another finding's comparison or an equation of the model fixes:
    /// its numbers are shown against that value and it is not counted again.
    Cited,
    /// Every unit reads a statistic that a finding above it already counts ("same data as"): its
    /// own reading is shown ([`Finding::reading`]) and it is not counted again.
    SameData,
    /// Another defensible run-in rule would give another verdict ([`Finding::verdicts_by_rule`]):
    /// inconclusive in the counts.
    RuleDependent,
    /// A measure of the study itself (its running-in), shown and not counted.
    Diagnostic,
}

impl Verdict {
    /// The verdict of a finding whose units hold in `holds` and are contrary in `contrary` of
    /// `total`: with fewer than half of them decided, inconclusive whatever the decided ones say.
    pub(crate) fn of_counts(holds: usize, contrary: usize, total: usize) -> Verdict {
        if total == 0 {
            Verdict::NotTestable
        } else if 2 * (holds + contrary) < total {
            Verdict::Inconclusive
        } else if contrary == 0 {
            Verdict::Reproduced
        } else if holds > contrary {
            Verdict::Partly
        } else {
            Verdict::NotReproduced
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Partly => "partly reproduced",
            Verdict::NotReproduced => "not reproduced",
            Verdict::Inconclusive => "inconclusive",
            Verdict::NotTestable => "not testable here",
            Verdict::Cited => "shown, not counted",
            Verdict::SameData => "same data as another",
            Verdict::RuleDependent => "rule-dependent",
            Verdict::Diagnostic => "diagnostic, not counted",
        }
    }
}

/// One finding of the paper judged on a study.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Finding {
    /// Short name, stable (tests refer to it).
    pub key: &'static str,
    /// The paper's claim in a few words (at most 60 characters), for the opening table.
    pub claim: &'static str,
    /// What the paper reports, with its section.
    pub paper: &'static str,
    /// The rule: the unit, what is compared, the threshold and the interval's method.
    pub rule: String,
    /// What a unit is ("settings", "pairs of curves").
    pub unit_name: &'static str,
    /// What the study shows: the counts, then the counted units with their intervals.
    pub observed: String,
    pub verdict: Verdict,
    /// (holds, contrary, inconclusive, not run in) over the counted units: a unit that reads a
    /// statistic another finding counts is listed, not counted.
    pub counts: (usize, usize, usize, usize),
    /// For an inconclusive verdict: the surface pairs per setting (at the study's box and loads)
    /// that would decide at least half of the units at the effects and spreads observed; `None`
    /// when no number of pairs would (effects of zero, units not run in).
    pub pairs_to_decide: Option<usize>,
    /// Every unit with its numbers, in the order judged (`findings_units.csv`).
    pub units: Vec<Unit>,
    /// The verdict when the units' Student-t p-values are Holm-adjusted within the finding (a unit
    /// decided at 95 % alone but not after the adjustment counted inconclusive), when it differs.
    pub verdict_under_holm: Option<Verdict>,
    /// For a [`Verdict::Cited`] finding: what fixes its numbers and which finding judges its
    /// comparison.
    pub cites: Option<&'static str>,
    /// For a [`Verdict::SameData`] finding: the finding that counts its statistic, and the verdict
    /// its own units would give.
    pub same_data_as: Option<&'static str>,
    pub reading: Option<Verdict>,
    /// For a [`Verdict::RuleDependent`] finding: its verdict with a pair run in by the lineages
    /// left (the findings' rule), by s_r ≥ 3 ℓ, and with every pair kept.
    pub verdicts_by_rule: Option<[Verdict; 3]>,
    /// What else a reader must know to read the verdict (a part not judged on its own, a
    /// convention that decides units).
    pub notes: Vec<String>,
}

/// The interval that decided a unit, with the quantity it is of and the region the rule asks of it.
#[derive(Debug, Clone, PartialEq)]
pub struct Numbers {
    pub quantity: String,
    pub interval: Interval,
    pub region: Region,
}

impl Numbers {
    /// The threshold nearest the estimate (a region between two bounds has two).
    fn threshold(&self) -> f64 {
        match self.region {
            Region::Above(t) | Region::Below(t) => t,
            Region::Within(a, b) => {
                if (self.interval.estimate - a).abs() <= (self.interval.estimate - b).abs() {
                    a
                } else {
                    b
                }
            }
        }
    }

    /// How far the interval lies clear of the rule's threshold, in the quantity's own units:
    /// positive when it lies wholly on one side (the unit is decided), negative by how far it
    /// reaches across the nearer threshold when it is undecided.
    pub fn margin(&self) -> f64 {
        let (low, high) = (self.interval.low, self.interval.high);
        let clear = |t: f64| {
            if low > t {
                low - t
            } else if high < t {
                t - high
            } else {
                -(t - low).min(high - t)
            }
        };
        match self.region {
            Region::Above(t) | Region::Below(t) => clear(t),
            Region::Within(a, b) => match self.region.side(&self.interval) {
                Side::Holds => (low - a).min(b - high),
                Side::Contrary => clear(a).max(clear(b)),
                Side::Undecided => [a, b]
                    .into_iter()
                    .map(clear)
                    .filter(|m| *m < 0.0)
                    .fold(f64::NEG_INFINITY, f64::max),
            },
        }
    }

    /// The two-sided p-value of the interval's Student-t test against the nearer threshold (on the
    /// log scale for a paired ratio), recovered from the interval itself: below 1 − LEVEL exactly
    /// when the interval excludes the threshold. `None` for the other methods (exact counts,
    /// Welch, bootstrap), whose intervals are not a t statistic of n − 1 degrees of freedom.
    pub fn p_value(&self) -> Option<f64> {
        let i = &self.interval;
        let scale = |x: f64| if i.method == Method::PairedRatio { x.ln() } else { x };
        if !matches!(i.method, Method::StudentT | Method::PairedRatio) || i.n < 2 {
            return None;
        }
        let se = (scale(i.high) - scale(i.estimate)) / t_critical(i.n - 1);
        if se.is_nan() || se <= 0.0 {
            return None;
        }
        let t = (scale(i.estimate) - scale(self.threshold())) / se;
        let dist = StudentsT::new(0.0, 1.0, (i.n - 1) as f64).ok()?;
        Some((2.0 * (1.0 - dist.cdf(t.abs()))).clamp(0.0, 1.0))
    }
}

/// One unit of a finding as `findings_units.csv` lists it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Unit {
    /// What the unit is (a setting, two settings, a curve), as its line begins.
    pub label: String,
    /// holds, contrary, inconclusive or not run in; "shown" for the units of a
    /// [`Verdict::Cited`] finding, which are not counted.
    pub outcome: &'static str,
    /// The quantity judged, its estimate and 95 % interval, and over how many pairs (or
    /// particles, for a count test) it was taken; empty where no interval decided the unit.
    pub quantity: String,
    pub estimate: Option<f64>,
    pub low: Option<f64>,
    pub high: Option<f64>,
    pub n: Option<usize>,
    pub method: String,
    /// The rule's side of its threshold ("> 1", "in [0.6, 1]").
    pub rule: String,
    /// Two-sided Student-t p-value against the nearer threshold, alone and Holm-adjusted over the
    /// finding's units that have one.
    pub p: Option<f64>,
    pub p_holm: Option<f64>,
    /// [`Numbers::margin`].
    pub margin: Option<f64>,
    /// Surface pairs that would decide an undecided unit.
    pub pairs_to_decide: Option<usize>,
    /// The unit's whole line: the numbers, the pairs left out and why.
    pub text: String,
    /// The part of a two-part finding the unit belongs to ("emission", "wear"), if any.
    pub part: Option<&'static str>,
    /// The finding above this one that already counts the statistic this unit reads: then the
    /// unit is listed with its reading and not counted here.
    pub same_data_as: Option<&'static str>,
    /// The statistics the unit reads (`rules::key_of`).
    #[serde(skip)]
    pub data: Vec<String>,
}

impl Unit {
    /// Whether the unit is counted in its finding's verdict: not shown only, not the same data as
    /// a finding above.
    pub fn counted(&self) -> bool {
        self.same_data_as.is_none() && self.outcome != "shown"
    }
}

impl Unit {
    fn of(outcome: &rules::Outcome) -> Unit {
        let text = outcome.text().to_string();
        let label = text.split_once(": ").map_or(text.as_str(), |(l, _)| l).to_string();
        let outcome_name = match outcome.side {
            Some(Side::Holds) => "holds",
            Some(Side::Contrary) => "contrary",
            Some(Side::Undecided) => "inconclusive",
            None => "not run in",
        };
        let needed = outcome.needed;
        let numbers = outcome.numbers();
        Unit {
            label,
            outcome: outcome_name,
            quantity: numbers.map_or(String::new(), |n| n.quantity.clone()),
            estimate: numbers.map(|n| n.interval.estimate),
            low: numbers.map(|n| n.interval.low),
            high: numbers.map(|n| n.interval.high),
            n: numbers.map(|n| n.interval.n),
            method: numbers.map_or(String::new(), |n| n.interval.method.name().to_string()),
            rule: numbers.map_or(String::new(), |n| rule_text(n.region)),
            p: numbers.and_then(Numbers::p_value),
            p_holm: None,
            margin: numbers.map(Numbers::margin),
            pairs_to_decide: needed,
            text,
            part: None,
            same_data_as: None,
            data: outcome.data.clone(),
        }
    }
}

/// The rule's side of its threshold in words, its numbers as the findings print them: "> 1",
/// "in [0.667, 1.5]".
fn rule_text(region: Region) -> String {
    match region {
        Region::Above(t) => format!("> {}", setting::fmt(t)),
        Region::Below(t) => format!("< {}", setting::fmt(t)),
        Region::Within(a, b) => format!("in [{}, {}]", setting::fmt(a), setting::fmt(b)),
    }
}

/// Holm's step-down adjustment of the p-values of a finding's counted units (those that have one),
/// filled into `p_holm`.
fn holm(units: &mut [Unit]) {
    for u in units.iter_mut() {
        u.p_holm = None;
    }
    let mut order: Vec<usize> = (0..units.len())
        .filter(|&k| units[k].p.is_some() && units[k].counted())
        .collect();
    order.sort_by(|&a, &b| units[a].p.unwrap_or(1.0).total_cmp(&units[b].p.unwrap_or(1.0)));
    let m = order.len();
    let mut running: f64 = 0.0;
    for (rank, &k) in order.iter().enumerate() {
        let adjusted = ((m - rank) as f64 * units[k].p.unwrap_or(1.0)).min(1.0);
        running = running.max(adjusted);
        units[k].p_holm = Some(running);
    }
}

/// Particles in a setting's fit window, summed over its surface pairs, below which the figures draw
/// its fitted rates hollow (a handful of events, ≳ 20 % Poisson noise). No verdict depends on it:
/// the findings read intervals.
pub const RESOLVED_PARTICLES: f64 = 20.0;

/// The units of a finding as they are filed, in order, each with its outcome and numbers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tally {
    pub units: Vec<Unit>,
}

/// (holds, contrary, inconclusive, not run in) of the counted units of `units`; with `part`, of
/// that part's only.
fn counts_of<'u>(units: impl Iterator<Item = &'u Unit> + Clone) -> (usize, usize, usize, usize) {
    let n = |o: &str| units.clone().filter(|u| u.counted() && u.outcome == o).count();
    (n("holds"), n("contrary"), n("inconclusive"), n("not run in"))
}

/// The verdict of counts (holds, contrary, inconclusive, not run in).
fn verdict_of(c: (usize, usize, usize, usize)) -> Verdict {
    Verdict::of_counts(c.0, c.1, c.0 + c.1 + c.2 + c.3)
}

/// The verdict of a finding of several parts that must all hold (Fig. 5: emits the most and wears
/// the least): reproduced only when every part is; not reproduced when a part is not; inconclusive
/// when a part is inconclusive or has no counted unit of its own; partly otherwise.
fn verdict_of_parts(parts: &[Verdict]) -> Verdict {
    if parts.iter().all(|v| *v == Verdict::Reproduced) {
        Verdict::Reproduced
    } else if parts.contains(&Verdict::NotReproduced) {
        Verdict::NotReproduced
    } else if parts
        .iter()
        .any(|v| !matches!(v, Verdict::Reproduced | Verdict::Partly))
    {
        Verdict::Inconclusive
    } else {
        Verdict::Partly
    }
}

impl Finding {
    /// The counts, the verdict, the Holm-adjusted verdict, the pairs that would decide it and the
    /// summary, from the units as they are filed and marked (counted or the same data as a finding
    /// above). A finding of several parts is reproduced only when each part is
    /// ([`verdict_of_parts`]).
    fn recount(&mut self) {
        if matches!(self.verdict, Verdict::Cited | Verdict::Diagnostic) {
            return;
        }
        holm(&mut self.units);
        self.counts = counts_of(self.units.iter());
        let mut parts: Vec<&'static str> = self.units.iter().filter_map(|u| u.part).collect();
        parts.dedup();
        let part_verdict = |part: &str| verdict_of(counts_of(self.units.iter().filter(|u| u.part == Some(part))));
        let counted = self.units.iter().any(Unit::counted);
        self.verdict = if parts.len() > 1 && counted {
            verdict_of_parts(&parts.iter().map(|p| part_verdict(p)).collect::<Vec<_>>())
        } else {
            verdict_of(self.counts)
        };
        self.same_data_as = None;
        self.reading = None;
        if !counted && !self.units.is_empty() {
            self.same_data_as = self.units.iter().find_map(|u| u.same_data_as);
            let own = |o: &str| self.units.iter().filter(|u| u.outcome == o).count();
            self.reading = Some(Verdict::of_counts(own("holds"), own("contrary"), self.units.len()));
            self.verdict = Verdict::SameData;
        }
        self.notes.retain(|n| !n.starts_with("parts: "));
        if parts.len() > 1 {
            let each: Vec<String> = parts
                .iter()
                .map(|p| {
                    let c = counts_of(self.units.iter().filter(|u| u.part == Some(*p)));
                    let shared: Vec<&str> = self
                        .units
                        .iter()
                        .filter(|u| u.part == Some(*p))
                        .filter_map(|u| u.same_data_as)
                        .collect();
                    let also = match shared.first() {
                        Some(k) => format!(", {} more units the same data as {k}", shared.len()),
                        None => String::new(),
                    };
                    format!(
                        "{p}: {} ({}/{}/{}/{}{also})",
                        part_verdict(p).name(),
                        c.0,
                        c.1,
                        c.2,
                        c.3
                    )
                })
                .collect();
            self.notes.insert(0, format!("parts: {}", each.join("; ")));
        }
        let under_holm = {
            let still = |o: &str| {
                self.units
                    .iter()
                    .filter(|u| u.counted() && u.outcome == o && !u.p_holm.is_some_and(|p| p >= 1.0 - LEVEL))
                    .count()
            };
            let (h, c, i, n) = self.counts;
            Verdict::of_counts(still("holds"), still("contrary"), h + c + i + n)
        };
        self.verdict_under_holm = (parts.len() <= 1 && counted && under_holm != self.verdict).then_some(under_holm);
        self.pairs_to_decide = self.pairs_needed();
        self.observed = self.summary();
    }

    /// The surface pairs that would decide enough inconclusive units for half of all to be decided
    /// (the k-th smallest of their needed pairs); `None` unless the verdict is inconclusive and
    /// more pairs can decide it.
    fn pairs_needed(&self) -> Option<usize> {
        if self.verdict != Verdict::Inconclusive {
            return None;
        }
        let (h, c, i, n) = self.counts;
        let missing = (h + c + i + n).div_ceil(2).checked_sub(h + c)?;
        let mut needed: Vec<usize> = self
            .units
            .iter()
            .filter(|u| u.counted() && u.outcome == "inconclusive")
            .filter_map(|u| u.pairs_to_decide)
            .collect();
        needed.sort_unstable();
        needed.get(missing.checked_sub(1)?).copied()
    }

    /// "holds in 4 of 6 settings: …; contrary in 1: …; inconclusive in 1: … (7 pairs would decide
    /// it); not run in: 0", then the units that read another finding's statistic.
    fn summary(&self) -> String {
        let lines = |o: &str| -> Vec<String> {
            self.units
                .iter()
                .filter(|u| u.counted() && u.outcome == o)
                .map(|u| match (o, u.pairs_to_decide) {
                    ("inconclusive", Some(n)) => format!("{}, {n} pairs would decide it (80 % power)", u.text),
                    _ => u.text.clone(),
                })
                .collect()
        };
        let list = |v: Vec<String>| {
            if v.is_empty() {
                String::new()
            } else {
                format!(": {}", v.join("; "))
            }
        };
        let (h, c, i, n) = self.counts;
        let mut text = format!(
            "holds in {h} of {} {}{}; contrary in {c}{}; inconclusive in {i}{}; not run in: {n}{}",
            h + c + i + n,
            self.unit_name,
            list(lines("holds")),
            list(lines("contrary")),
            list(lines("inconclusive")),
            list(lines("not run in"))
        );
        let shared: Vec<String> = self
            .units
            .iter()
            .filter_map(|u| {
                u.same_data_as
                    .map(|k| format!("{} ({}, same data as {k})", u.text, u.outcome))
            })
            .collect();
        if !shared.is_empty() {
            text += &format!("; listed, not counted: {}", shared.join("; "));
        }
        text
    }
}

/// A finding judged on its filed units (`tally`), counted as they are; `judge_once` then marks
/// the units whose statistic a finding above counts, and [`findings`] the verdicts another run-in
/// rule would change.
fn finding(key: &'static str, paper: &'static str, rule: String, unit_name: &'static str, tally: Tally) -> Finding {
    let mut f = Finding {
        key,
        claim: claim(key),
        paper,
        rule,
        unit_name,
        observed: String::new(),
        verdict: Verdict::NotTestable,
        counts: (0, 0, 0, 0),
        pairs_to_decide: None,
        units: tally.units,
        verdict_under_holm: None,
        cites: None,
        same_data_as: None,
        reading: None,
        verdicts_by_rule: None,
        notes: Vec::new(),
    };
    f.recount();
    f
}

/// Each statistic counted once: a unit reading a statistic (`Unit::data`) that a unit of a finding
/// above it counts is marked the same data as that finding and not counted again; a finding all of
/// whose units are so marked is [`Verdict::SameData`]. The order of [`findings_of`] decides which
/// finding counts a shared statistic: the one whose sentence is about it most directly comes first.
fn judge_once(found: &mut [Finding]) {
    let mut owner: std::collections::BTreeMap<String, &'static str> = std::collections::BTreeMap::new();
    for f in found.iter_mut() {
        if matches!(f.verdict, Verdict::Cited | Verdict::Diagnostic) {
            continue;
        }
        for u in &mut f.units {
            u.same_data_as = u
                .data
                .iter()
                .find_map(|k| owner.get(k).copied().filter(|o| *o != f.key));
        }
        for u in f.units.iter().filter(|u| u.counted()) {
            for k in &u.data {
                owner.entry(k.clone()).or_insert(f.key);
            }
        }
        f.recount();
    }
}

/// Checks what `judge_once` promises on a study's findings: no statistic counted by two findings,
/// and every unit listed as the same data naming a finding that counts that statistic. `Err` names
/// the first statistic or unit that breaks it.
pub fn check_counted_once(findings: &[Finding]) -> Result<(), String> {
    let mut owner: std::collections::BTreeMap<&str, &str> = std::collections::BTreeMap::new();
    for f in findings {
        for u in f.units.iter().filter(|u| u.counted()) {
            for k in &u.data {
                if let Some(other) = owner.insert(k, f.key).filter(|o| *o != f.key) {
                    return Err(format!("{k} is counted by {other} and by {}", f.key));
                }
            }
        }
    }
    for f in findings {
        for u in &f.units {
            if let Some(other) = u.same_data_as {
                if !u.data.iter().any(|k| owner.get(k.as_str()) == Some(&other)) {
                    return Err(format!(
                        "{}: {} is listed as {other}'s data, which {other} does not count",
                        f.key, u.label
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The three run-in rules a verdict is read under: the findings' (the lineages left), the decay
/// lengths (s_r ≥ 3 ℓ), and no exclusion (every pair).
pub const RUN_IN_RULES: [RunInRule; 3] = [RunInRule::LineagesLeft, RunInRule::DecayLengths, RunInRule::All];

/// The paper's findings judged on a study's tidy table (`results.csv`), each under its rule, a
/// surface pair run in by the lineages left, each statistic counted once (`judge_once`); a
/// verdict that s_r ≥ 3 ℓ or keeping every pair would change is [`Verdict::RuleDependent`], with the
/// three verdicts.
pub fn findings(tidy: &Table) -> Vec<Finding> {
    // The findings are the sliding model's: rows of the static estimate are not judged.
    let (sliding, _) = crate::output::sliding_rows(tidy);
    let mut by_rule = RUN_IN_RULES.map(|rule| {
        let mut f = findings_of(&setting::settings(&sliding, rule));
        judge_once(&mut f);
        f
    });
    let [found, decay, every] = &mut by_rule;
    for (k, f) in found.iter_mut().enumerate() {
        let three = [f.verdict, decay[k].verdict, every[k].verdict];
        let counted = !matches!(
            f.verdict,
            Verdict::NotTestable | Verdict::Cited | Verdict::SameData | Verdict::Diagnostic
        );
        if counted && three.iter().any(|v| *v != f.verdict) {
            f.verdicts_by_rule = Some(three);
            f.verdict = Verdict::RuleDependent;
            f.verdict_under_holm = None;
            f.pairs_to_decide = None;
        }
    }
    std::mem::take(found)
}

fn findings_of(all: &[setting::Setting]) -> Vec<Finding> {
    vec![
        static_model::static_k_below_one_and_rising(all),
        static_model::static_wear_superlinear(all),
        static_model::static_wear_grows_with_hardness(all),
        static_model::static_wear_falls_with_toughness(all),
        sliding::volume_linear_after_running_in(all),
        sliding::initial_volume_much_larger_than_increments(all),
        sliding::running_in_steeper(all),
        sliding::memory_decays_exponentially(all),
        sliding::running_in_sufficient(all),
        sliding::decay_length_varies_with_load(all),
        sliding::equation_5_slightly_below_w(all),
        materials::sliding_k_below_static(all),
        materials::sliding_k_below_0_1(all),
        materials::sliding_k_in_dry_sliding_range(all),
        materials::archard_like(all),
        materials::k_rises_with_load(all),
        materials::larger_d_star_wears_more_at_high_load(all),
        materials::tougher_reaches_k_max_later(all),
        materials::smaller_g_wears_more_at_low_load(all),
        materials::toughest_not_yet_ahead(all),
        particles::delayed_onset_for_large_g(all),
        particles::hardest_least_tough_emits_most_wears_least(all),
        particles::soft_tough_fewest_particles(all),
        particles::severe_wear_from_large_particles(all),
        kim::kim_hierarchy(all),
        kim::kim_k_above_experiments(all),
        appendix::appendix_a_discretization(all),
        appendix::appendix_c_box_size(all),
        appendix::appendix_c_more_spots_not_more_wear(all),
        appendix::appendix_d_lambda_lower(all),
        appendix::appendix_e_rms_height(all),
        appendix::breakdown_regime(all),
    ]
}

/// The paper's claim of a finding in at most 60 characters, for findings.md's opening table.
pub fn claim(key: &str) -> &'static str {
    match key {
        "static-k-below-one-and-rising" => "static k rises with load towards 1 (§2)",
        "static-wear-superlinear" => "static W superlinear in load (§2)",
        "static-wear-grows-with-hardness" => "static W grows with hardness (§2, Fig. 2b)",
        "static-wear-falls-with-toughness" => "static W falls as 𝒢 grows (§2, Fig. 2a)",
        "volume-linear-after-running-in" => "V(s) linear after running-in (§3, Fig. 3)",
        "initial-volume-much-larger-than-increments" => "V₀ much larger than the increments δV (§3)",
        "running-in-steeper" => "V(s) can rise more steeply in running-in (§3)",
        "memory-decays-exponentially" => "contacts of s = 0 decay exponentially (§3)",
        "running-in-sufficient" => "this study's running-in (a diagnostic)",
        "decay-length-varies-with-load" => "decay length not uniform over loads (§3)",
        "equation-5-slightly-below-w" => "Eq. 5 slightly below W; d* the particle size (B)",
        "sliding-k-below-static" => "sliding k an order below static k (§4.1)",
        "sliding-k-below-0.1" => "sliding k below about 0.1 (§4.1)",
        "sliding-k-high-end-of-experiments" => "k at the high end of dry sliding, > 10⁻² (§4.1)",
        "archard-like" => "Archard-like W ∝ F_N (§6)",
        "k-rises-with-load" => "k rises with F_N to a maximum (§4.1)",
        "larger-d-star-wears-more-at-high-load" => "larger d* wears more at high load: crossover (§4.1)",
        "tougher-reaches-k-max-later" => "tougher materials reach k's maximum later (§4.1)",
        "smaller-g-wears-more-at-low-load" => "smaller 𝒢 wears more at low load (§4.1)",
        "toughest-not-yet-ahead" => "𝒢 = 10⁻⁶ not yet ahead of 0.75×10⁻⁶ (§4.1)",
        "delayed-onset-for-large-g" => "larger 𝒢 delays the onset of wear (Fig. S.1a)",
        "hardest-least-tough-emits-most-wears-least" => "hardest, least tough: most particles, least W (Fig. 5)",
        "soft-tough-fewest-particles" => "soft but tough: fewest fine particles (§4.1)",
        "severe-wear-from-large-particles" => "severe wear from large particles (§4.1)",
        "kim-hierarchy" => "Al₂O₃ wears most, Si₃N₄ least (§4.2)",
        "kim-k-above-experiments" => "k 2–3 orders above Kim's experiments (§4.2)",
        "appendix-a-discretization" => "λ_l/Δx = 32 gives the W of 16 (appendix A)",
        "appendix-c-box-size" => "two boxes agree up to a load (appendix C)",
        "appendix-c-more-spots-not-more-wear" => "larger box: more spots, not more W (appendix C)",
        "appendix-d-lambda-lower" => "W robust against λ_l (appendix D)",
        "appendix-e-rms-height" => "W unchanged by h_rms (appendix E)",
        "breakdown-regime" => "loads past the breakdown, data unreliable (appendix C)",
        _ => "",
    }
}

/// The level and the methods of every interval, as findings.md and the documentation state them.
pub fn method_statement() -> String {
    format!(
        "Every interval is a {:.0} % confidence interval over surface pairs, the unit of replication: a mean \
         over pairs by {}; two settings of the study, which share their surface pairs (same seeds), by the {} (the \
         geometric mean of the per-pair ratios), or, where a pair has no particle, by the {} on the particles summed \
         over the shared pairs (W as ω d*³ times the count, Eq. 5); a count of 0 against n from a setting that forms \
         no particle at any load of the study is undecided (below the onset of wear, not evidence of fewer fine \
         particles); a trend over load by the exponent of a power law fitted per surface pair (least squares in \
         log–log), with its Student-t interval over pairs; a quantity that is zero in most pairs as a ratio of means \
         by a {}. A unit holds when its interval lies on the paper's side of the rule's threshold, is contrary when \
         it lies on the other side, and is inconclusive otherwise (always when every pair gives 0: no spread is no \
         evidence), with the surface pairs that would decide it with 80 % power if the pairs kept the observed mean \
         and spread. A surface pair is run in when at most {:.0} % of the junction lineages present at s = 0 are \
         left where its fit window starts, counted in its steps (paper §3: the memory of the initial contact has \
         faded); sliding quantities are judged on the run-in pairs, and a unit with fewer than two is counted as not \
         run in. \"The highest load\" of a sentence is the highest load of the study at which at least two pairs \
         are run in. Every finding is also judged under the two other defensible rules, a fit window starting \
         after {RUN_IN_DECAY_LENGTHS} of the pair's own fitted decay lengths ℓ, and no exclusion (every pair): a \
         verdict that either would change is rule-dependent, inconclusive in the counts, with the three verdicts. \
         Each statistic is counted once: a unit that reads a statistic a finding above it already counts (k = W \
         p_m/F_N, so the slope of k over load is Archard's exponent less one; the slope of W(larger d*)/W(smaller \
         d*) is the difference of two exponents; a particle count is one count whichever sentence reads it) is \
         listed as the same data as that finding and not counted again, and a finding all of whose units are so \
         listed is not counted. The verdict follows from the counted units: reproduced when it holds in every \
         decided unit and at least half are decided, partly when it holds in more than it is contrary in, not \
         reproduced otherwise, inconclusive when fewer than half are decided (with the pairs per setting that \
         would decide it), not testable when the study has no unit; a finding of two parts (Fig. 5: emits the \
         most and wears the least) is reproduced only when both parts are. Each interval is read at {:.0} % on its \
         own; where a finding has several units, their Student-t p-values are also Holm-adjusted within the \
         finding, and a verdict the adjustment would change says so. A finding whose numbers an equation of the \
         model fixes, and whose comparison another finding judges, is shown against that value and not counted \
         (\"shown, not counted\"); the running-in of the study is a diagnostic, not a verdict.",
        LEVEL * 100.0,
        Method::StudentT.name(),
        Method::PairedRatio.name(),
        Method::CountRatio.name(),
        "percentile bootstrap over surface pairs",
        RUN_IN_LINEAGES_LEFT * 100.0,
        LEVEL * 100.0
    )
}

/// For a finding a study cannot test: what a study needs to test it, and the study file of this
/// repository that has it.
pub fn needed_study(key: &str) -> &'static str {
    match key {
        "static-wear-grows-with-hardness" => {
            "settings differing in τ̃ alone (studies/paper-evidence.toml: τ̃ = 0.008 and 0.012 E)"
        }
        "hardest-least-tough-emits-most-wears-least" | "soft-tough-fewest-particles" => {
            "several τ̃ and 𝒢 at one load (studies/paper-evidence.toml: two τ̃ × four 𝒢)"
        }
        "static-wear-falls-with-toughness"
        | "smaller-g-wears-more-at-low-load"
        | "delayed-onset-for-large-g"
        | "larger-d-star-wears-more-at-high-load"
        | "severe-wear-from-large-particles"
        | "tougher-reaches-k-max-later" => {
            "curves against load differing in 𝒢 alone (studies/paper-evidence.toml: four 𝒢, five loads up to \
             2.5×10⁻³ E)"
        }
        "toughest-not-yet-ahead" => {
            "𝒢 = 0.75 and 10⁻⁶ E L at 2.5×10⁻³ E (studies/paper-evidence.toml; the paper's box: \
             studies/paper-reduced.toml)"
        }
        "kim-hierarchy" | "kim-k-above-experiments" => "Kim's ceramics (studies/kim1986-window.toml)",
        "appendix-a-discretization" => "two pixel sizes (studies/appendix-discretization-reduced.toml)",
        "appendix-c-box-size" | "appendix-c-more-spots-not-more-wear" => {
            "two boxes at one pixel size (studies/appendix-area-reduced.toml)"
        }
        "appendix-d-lambda-lower" | "appendix-e-rms-height" => {
            "two λ_l and two h_rms (studies/appendix-lambda-h-reduced.toml)"
        }
        "decay-length-varies-with-load" | "archard-like" | "k-rises-with-load" | "static-wear-superlinear" => {
            "several loads with run-in surface pairs (studies/paper-window.toml)"
        }
        _ => "sliding runs whose surface pairs run in and form particles (studies/paper-window.toml)",
    }
}

impl Finding {
    /// The unit a reader looks at first: of a reproduced finding the weakest holding unit (the one
    /// nearest its threshold); of a partly or not reproduced one the contrary unit nearest its
    /// threshold; of an inconclusive one the undecided unit nearest to deciding; of one that reads
    /// another's data, the first of its units.
    pub fn deciding_unit(&self) -> Option<&Unit> {
        let side = match self.verdict {
            Verdict::Reproduced => "holds",
            Verdict::Partly | Verdict::NotReproduced => "contrary",
            Verdict::Inconclusive | Verdict::RuleDependent => "inconclusive",
            Verdict::Cited => "shown",
            Verdict::SameData | Verdict::Diagnostic => return self.units.first(),
            Verdict::NotTestable => return None,
        };
        let counted = |u: &&Unit| u.counted() || self.verdict == Verdict::Cited;
        let on_side = self.units.iter().filter(counted).filter(|u| u.outcome == side);
        let with_margin = on_side.clone().filter(|u| u.margin.is_some());
        let best = match side {
            // The least negative margin: the undecided unit nearest to deciding.
            "inconclusive" => with_margin.max_by(|a, b| a.margin.unwrap_or(0.0).total_cmp(&b.margin.unwrap_or(0.0))),
            _ => with_margin.min_by(|a, b| a.margin.unwrap_or(0.0).total_cmp(&b.margin.unwrap_or(0.0))),
        };
        best.or_else(|| on_side.clone().next())
            .or_else(|| self.units.iter().find(|u| u.counted()))
    }

    /// The verdict in words, with what qualifies it: the three run-in rules' verdicts of a
    /// rule-dependent one, the finding whose data another reads.
    pub fn verdict_text(&self) -> String {
        match (self.verdict, self.verdicts_by_rule, self.same_data_as) {
            (Verdict::RuleDependent, Some([l, d, a]), _) => format!(
                "rule-dependent: {} by the lineages left, {} by s_r ≥ {RUN_IN_DECAY_LENGTHS} ℓ, {} with every pair",
                l.name(),
                d.name(),
                a.name()
            ),
            (Verdict::SameData, _, Some(other)) => format!(
                "same data as {other}, not counted (its own units: {})",
                self.reading.unwrap_or(Verdict::Inconclusive).name()
            ),
            (v, ..) => v.name().to_string(),
        }
    }

    /// What kind of result the finding is, in words: reproduced; contrary, naming the units;
    /// inconclusive, with the pairs that would decide it; not testable, with the study that can;
    /// with the run-in rules' verdicts, the Holm adjustment and the notes where they qualify it.
    pub fn kind(&self) -> String {
        let (h, c, i, n) = self.counts;
        let total = h + c + i + n;
        let mut contrary: Vec<String> = self
            .units
            .iter()
            .filter(|u| u.counted() && u.outcome == "contrary")
            .map(|u| u.label.clone())
            .collect();
        if contrary.len() > 3 {
            let more = contrary.len() - 3;
            contrary.truncate(3);
            contrary.push(format!("{more} more in findings_units.csv"));
        }
        let mut kind = match self.verdict {
            Verdict::Reproduced => format!("reproduced: holds in all {h} decided of {total} units"),
            Verdict::Partly | Verdict::NotReproduced => format!(
                "{}: holds in {h}, contrary in {c} of {total} units (contrary: {})",
                self.verdict.name(),
                contrary.join("; ")
            ),
            Verdict::Inconclusive => match self.pairs_to_decide {
                Some(p) => format!("inconclusive: {p} surface pairs per setting would decide it (80 % power)"),
                None => "inconclusive: more surface pairs alone do not decide it".to_string(),
            },
            Verdict::RuleDependent => format!("{}; inconclusive in the counts", self.verdict_text()),
            Verdict::SameData => self.verdict_text(),
            Verdict::NotTestable => format!("this study cannot show it; it needs {}", needed_study(self.key)),
            Verdict::Cited => format!("not counted: {}", self.cites.unwrap_or("restates another finding")),
            Verdict::Diagnostic if self.key == "breakdown-regime" => {
                "a mark on this study's data (the loads the paper treats as unreliable), not a verdict on the paper"
                    .to_string()
            }
            Verdict::Diagnostic => "a measure of this study's running-in, not a verdict on the paper".to_string(),
        };
        if let Some(v) = self.verdict_under_holm {
            kind += &format!(" — {} once the p-values are Holm-adjusted within the finding", v.name());
        }
        for note in &self.notes {
            kind += &format!(" — {note}");
        }
        kind
    }
}

/// At most `max` characters of `text`, cut with "…".
fn at_most(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        text.to_string()
    } else {
        let mut cut: String = text.chars().take(max - 1).collect();
        cut.push('…');
        cut
    }
}

/// "k = 0.089 [0.071, 0.107] (rule > 0.05)" of a unit, or its line where no interval decided it.
fn unit_number(u: &Unit) -> String {
    match (u.estimate, u.low, u.high) {
        (Some(e), Some(l), Some(h)) => format!(
            "{}: {} = {} [{}, {}] (rule {})",
            u.label,
            u.quantity,
            setting::fmt(e),
            setting::fmt(l),
            setting::fmt(h),
            u.rule
        ),
        _ => u.text.clone(),
    }
}

/// The longest cell findings.md's opening table holds.
pub const CELL_CHARACTERS: usize = 300;

/// The count line of a study's findings: how many are counted, each on statistics no other counts
/// (the independent results), by verdict; how many read another's data; how many the study cannot
/// test.
pub fn count_line(findings: &[Finding]) -> String {
    let n = |v: Verdict| findings.iter().filter(|f| f.verdict == v).count();
    let counted = findings
        .iter()
        .filter(|f| {
            !matches!(
                f.verdict,
                Verdict::NotTestable | Verdict::Cited | Verdict::SameData | Verdict::Diagnostic
            )
        })
        .count();
    format!(
        "{} findings; {counted} independent results (each statistic counted once): {} reproduced, {} partly \
         reproduced, {} not reproduced, {} inconclusive, {} rule-dependent (inconclusive in the counts); {} read \
         the same data as a finding above them and are not counted again; {} not testable here; {} shown or a \
         diagnostic, not counted.",
        findings.len(),
        n(Verdict::Reproduced),
        n(Verdict::Partly),
        n(Verdict::NotReproduced),
        n(Verdict::Inconclusive),
        n(Verdict::RuleDependent),
        n(Verdict::SameData),
        n(Verdict::NotTestable),
        n(Verdict::Cited) + n(Verdict::Diagnostic)
    )
}

/// findings.md's list of the findings whose units read another finding's data.
fn shared_data(findings: &[Finding]) -> String {
    let mut text = String::new();
    let shared: Vec<String> = findings
        .iter()
        .filter_map(|f| {
            let others: Vec<String> = f
                .units
                .iter()
                .filter_map(|u| u.same_data_as)
                .fold(Vec::<&str>::new(), |mut v, k| {
                    if !v.contains(&k) {
                        v.push(k);
                    }
                    v
                })
                .into_iter()
                .map(|k| format!("`{k}`"))
                .collect();
            let listed = f.units.iter().filter(|u| u.same_data_as.is_some()).count();
            (listed > 0).then(|| {
                format!(
                    "- `{}` reads {listed} of its {} units from the same data as {}: listed, not counted{}",
                    f.key,
                    f.units.len(),
                    others.join(", "),
                    if f.verdict == Verdict::SameData {
                        " (so the finding is not counted)"
                    } else {
                        ""
                    }
                )
            })
        })
        .collect();
    if !shared.is_empty() {
        text += &format!("\n## The same data read by several findings\n\n{}\n", shared.join("\n"));
    }
    text
}

/// findings.md's running-in table: the diagnostic's row per contact history.
fn running_in_table(findings: &[Finding]) -> String {
    let mut text = String::new();
    if let Some(run_in) = findings
        .iter()
        .find(|f| f.verdict == Verdict::Diagnostic && f.key == "running-in-sufficient")
    {
        text += &format!(
            "\n## Running-in, per contact history (a diagnostic)\n\n{}\n\n| contact history | pairs run in, and per \
             pair the lineages of s = 0 left at s_r and s_r/ℓ |\n|---|---|\n",
            run_in.rule
        );
        for u in &run_in.units {
            let rest = u.text.split_once(": ").map_or(u.text.as_str(), |(_, r)| r);
            text += &format!("| {} | {} |\n", u.label.replace('|', "/"), rest.replace('|', "/"));
        }
    }
    text
}

/// The findings as Markdown: the count line; the opening table, one row per finding of five short
/// columns (key, the claim, the verdict, the counts, the number that decides it); what qualifies
/// the verdicts; the statistics read by more than one finding; the running-in of every contact
/// history; each finding's rule; then how the units are counted. Every unit's numbers are in
/// `findings_units.csv`.
pub fn markdown(findings: &[Finding]) -> String {
    let cell = |t: &str| at_most(&t.replace('|', "/").replace('\n', " "), CELL_CHARACTERS);
    let mut text = format!(
        "{}\n\n| finding | claim | verdict | holds / contrary / inconclusive / not run in | the deciding unit, 95 % \
         interval |\n|---|---|---|---|---|\n",
        count_line(findings)
    );
    for f in findings {
        let (h, c, i, n) = f.counts;
        text += &format!(
            "| `{}` | {} | {} | {h} / {c} / {i} / {n} | {} |\n",
            f.key,
            cell(f.claim),
            cell(&f.verdict_text()),
            cell(&f.deciding_unit().map_or("—".to_string(), unit_number))
        );
    }
    text += "\nThe deciding unit is, for a reproduced finding, its holding unit nearest the threshold; for a partly \
             or not reproduced one, its contrary unit nearest the threshold; for an inconclusive one, the \
             undecided unit nearest to deciding.\n";
    let qualified: Vec<String> = findings
        .iter()
        .filter(|f| {
            f.verdict_under_holm.is_some()
                || !f.notes.is_empty()
                || f.verdict == Verdict::RuleDependent
                || f.pairs_to_decide.is_some()
                || matches!(f.verdict, Verdict::Partly | Verdict::NotReproduced)
        })
        .map(|f| format!("- `{}`: {}", f.key, f.kind()))
        .collect();
    if !qualified.is_empty() {
        text += &format!("\n## What qualifies the verdicts\n\n{}\n", qualified.join("\n"));
    }
    text += &shared_data(findings);
    text += &running_in_table(findings);
    text += "\n## The rules\n\n";
    for f in findings {
        text += &format!("- `{}` ({}): {}. {}\n", f.key, f.unit_name, f.paper, f.rule);
    }
    text += &format!(
        "\n## How the units are counted\n\n{}\n\nEvery unit's numbers, p-values (alone and Holm-adjusted within its \
         finding), margin and the finding whose data it reads are in findings_units.csv.\n",
        method_statement()
    );
    text
}

/// The table of every finding on several studies, as the documentation keeps it (the paper
/// comparison checks its copy against this by test): per study the verdict in words, the counts
/// (holds / contrary / inconclusive / not run in) and what qualifies it (the Holm adjustment, the
/// notes), then each study's count line.
pub fn comparison_table(studies: &[(&str, &[Finding])]) -> String {
    let mut text = String::from("| finding |");
    for (name, _) in studies {
        text += &format!(" {name} |");
    }
    text += "\n|---|";
    text += &"---|".repeat(studies.len());
    text += "\n";
    let Some((_, first)) = studies.first() else {
        return text;
    };
    for (k, f) in first.iter().enumerate() {
        text += &format!("| `{}` |", f.key);
        for (_, found) in studies {
            let Some(g) = found.get(k).filter(|g| g.key == f.key) else {
                text += " — |";
                continue;
            };
            let (h, c, i, n) = g.counts;
            let mut cell = format!("{} ({h}/{c}/{i}/{n})", g.verdict_text());
            if let Some(v) = g.verdict_under_holm {
                cell += &format!("; {} once Holm-adjusted", v.name());
            }
            for note in &g.notes {
                cell += &format!("; {note}");
            }
            text += &format!(" {} |", cell.replace('|', "/"));
        }
        text += "\n";
    }
    text += "\n";
    for (name, found) in studies {
        text += &format!("- {name}: {}\n", count_line(found));
    }
    text
}

/// One column of `findings_units.csv`: its name and its cell of a finding's unit.
type UnitColumn = (&'static str, fn(&Finding, &Unit) -> String);

fn cell(x: Option<f64>) -> String {
    x.map_or(String::new(), |v| format!("{v}"))
}

/// The columns of `findings_units.csv`, each named once beside what fills it.
const UNIT_COLUMNS: [UnitColumn; 17] = [
    ("finding", |f, _| f.key.to_string()),
    ("unit", |_, u| u.label.clone()),
    ("outcome", |_, u| u.outcome.to_string()),
    ("quantity", |_, u| u.quantity.clone()),
    ("estimate", |_, u| cell(u.estimate)),
    ("low", |_, u| cell(u.low)),
    ("high", |_, u| cell(u.high)),
    ("n", |_, u| u.n.map_or(String::new(), |n| n.to_string())),
    ("method", |_, u| u.method.clone()),
    ("rule", |_, u| u.rule.clone()),
    ("p", |_, u| cell(u.p)),
    ("p_holm", |_, u| cell(u.p_holm)),
    ("margin", |_, u| cell(u.margin)),
    ("pairs_to_decide", |_, u| {
        u.pairs_to_decide.map_or(String::new(), |n| n.to_string())
    }),
    ("part", |_, u| u.part.unwrap_or("").to_string()),
    ("same_data_as", |_, u| u.same_data_as.unwrap_or("").to_string()),
    ("line", |_, u| u.text.clone()),
];

/// Every unit of every finding, one row each: `findings_units.csv`, which `wearsim study plot`
/// writes beside findings.md (columns: finding, then [`Unit`]'s fields).
pub fn units_csv(findings: &[Finding]) -> String {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(UNIT_COLUMNS.iter().map(|(name, _)| *name))
        .expect("writing to memory");
    for f in findings {
        for u in &f.units {
            w.write_record(UNIT_COLUMNS.iter().map(|(_, value)| value(f, u)))
                .expect("writing to memory");
        }
    }
    String::from_utf8(w.into_inner().expect("writing to memory")).expect("UTF-8 text")
}

/// Appendix B's Eq. 5 / W per setting, as the finding "equation-5-slightly-below-w" reads it, for
/// the figure that draws it against load: (curve, nominal pressure F_N/(Lx·Ly), the Student-t
/// interval of the mean over the run-in pairs, pairs with W = 0 left out); over all pairs of a
/// setting where none is run in, as the other figures against load (`output::run_in_rows`). None
/// where fewer than two pairs have W > 0.
pub(crate) fn equation_5_over_w(tidy: &Table) -> Vec<(usize, f64, Option<Interval>)> {
    setting::settings(tidy, setting::RunInRule::LineagesLeft)
        .iter()
        .map(|s| {
            let ratios: Vec<f64> = s.figure_pairs().iter().map(|p| sliding::equation_5_over_w(p)).collect();
            (s.curve, s.pressure, crate::stats::mean_interval(&ratios))
        })
        .collect()
}

/// The range Eq. 5 / W lies in where Eq. 5 "slightly underestimates" W (appendix B).
pub(crate) const EQUATION_5_OVER_W: (f64, f64) = sliding::EQUATION_5_OVER_W;

#[cfg(test)]
mod tests;
