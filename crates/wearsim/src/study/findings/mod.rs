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
mod document;
mod kim;
mod materials;
mod particles;
mod rules;
mod setting;
mod sliding;
mod static_model;

use crate::output::Table;
use crate::stats::{t_critical, Interval, Method, Region, Side, LEVEL};
pub use document::{
    claim, comparison_table, count_line, document, markdown, method_statement, needed_study, units_csv,
    FindingsDocument, CELL_CHARACTERS,
};
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

/// Appendix B's Eq. 5 / W per setting, as the finding "equation-5-slightly-below-w" reads it, for
/// the figure that draws it against load: (curve, nominal pressure F_N/(Lx·Ly), the Student-t
/// interval of the mean over the run-in pairs, pairs with W = 0 left out); over all pairs of a
/// setting where none is run in, as the other figures against load (`output::StudyTable::means`). None
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
