//! The paper's findings (Brink, Frérot & Molinari 2021, §2–4, §6 and appendix B) judged on a study's
//! tidy table with statistics: the surface pair is the unit of replication, every rule reads a 95 %
//! interval over pairs (`stats`) and holds when the interval lies on the paper's side of its
//! threshold, is contrary when it lies on the other side and inconclusive otherwise; a unit whose
//! surface pairs are not run in (fewer than two whose fit window starts after 3 of their own decay
//! lengths) is counted as not run in. Every unit of the study lands in one count, and the verdict
//! follows from the counts ([`Tally::verdict`]). `wearsim study plot` prints them and writes
//! `figures/findings.md`.
//!
//! - `setting`: the settings and their surface pairs, and the groupings the rules compare;
//! - `rules`: one unit judged (per setting, two settings pair by pair or by a count test, a trend
//!   over load per pair);
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
use crate::sliding::RUN_IN_DECAY_LENGTHS;
use crate::stats::{Method, LEVEL};

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
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Partly => "partly reproduced",
            Verdict::NotReproduced => "not reproduced",
            Verdict::Inconclusive => "inconclusive",
            Verdict::NotTestable => "not testable here",
        }
    }
}

/// One finding of the paper judged on a study.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Finding {
    /// Short name, stable (tests refer to it).
    pub key: &'static str,
    /// What the paper reports, with its section.
    pub paper: &'static str,
    /// The rule: the unit, what is compared, the threshold and the interval's method.
    pub rule: String,
    /// What the study shows: the counts, then the units with their intervals.
    pub observed: String,
    pub verdict: Verdict,
    /// (holds, contrary, inconclusive, not run in).
    pub counts: (usize, usize, usize, usize),
    /// For an inconclusive verdict: the surface pairs per setting (at the study's box and loads)
    /// that would decide at least half of the units at the effects and spreads observed; `None`
    /// when no number of pairs would (effects of zero, units not run in).
    pub pairs_to_decide: Option<usize>,
}

/// Particles in a setting's fit window, summed over its surface pairs, below which the figures draw
/// its fitted rates hollow (a handful of events, ≳ 20 % Poisson noise). No verdict depends on it:
/// the findings read intervals.
pub const RESOLVED_PARTICLES: f64 = 20.0;

/// How each unit of a finding came out: every unit of the study lands in exactly one list, with
/// its label and numbers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tally {
    pub holds: Vec<String>,
    pub contrary: Vec<String>,
    /// Undecided by its interval, with the surface pairs that would decide it, when any number would.
    pub inconclusive: Vec<(String, Option<usize>)>,
    /// Fewer than two surface pairs whose fit window starts after [`RUN_IN_DECAY_LENGTHS`] decay lengths.
    pub not_run_in: Vec<String>,
}

impl Tally {
    pub fn total(&self) -> usize {
        self.holds.len() + self.contrary.len() + self.inconclusive.len() + self.not_run_in.len()
    }

    fn decided(&self) -> usize {
        self.holds.len() + self.contrary.len()
    }

    /// The verdict from the counts alone: with fewer than half of all units decided, the study is
    /// inconclusive whatever the decided ones say.
    pub fn verdict(&self) -> Verdict {
        let (holds, contrary) = (self.holds.len(), self.contrary.len());
        if self.total() == 0 {
            Verdict::NotTestable
        } else if 2 * self.decided() < self.total() {
            Verdict::Inconclusive
        } else if contrary == 0 {
            Verdict::Reproduced
        } else if holds > contrary {
            Verdict::Partly
        } else {
            Verdict::NotReproduced
        }
    }

    /// The surface pairs that would decide enough inconclusive units for half of all to be decided
    /// (the k-th smallest of their needed pairs); `None` unless the verdict is inconclusive and
    /// more pairs can decide it.
    pub fn pairs_to_decide(&self) -> Option<usize> {
        if self.verdict() != Verdict::Inconclusive {
            return None;
        }
        let missing = self.total().div_ceil(2) - self.decided();
        let mut needed: Vec<usize> = self.inconclusive.iter().filter_map(|(_, n)| *n).collect();
        needed.sort_unstable();
        needed.get(missing.checked_sub(1)?).copied()
    }

    /// "holds in 4 of 6 settings: …; contrary in 1: …; inconclusive in 1: … (7 pairs would decide
    /// it); not run in: 0".
    pub fn summary(&self, unit: &str) -> String {
        let list = |v: &[String]| {
            if v.is_empty() {
                String::new()
            } else {
                format!(": {}", v.join("; "))
            }
        };
        let undecided: Vec<String> = self
            .inconclusive
            .iter()
            .map(|(line, needed)| match needed {
                Some(n) => format!("{line}, {n} pairs would decide it"),
                None => format!(
                    "{line}, no number of pairs named (an effect of about zero, none up to 100,000 pairs; fewer \
                     than two pairs with a value; or a sample without spread or judged by a bootstrap, which the \
                     count of pairs does not extrapolate)"
                ),
            })
            .collect();
        format!(
            "holds in {} of {} {unit}{}; contrary in {}{}; inconclusive in {}{}; not run in: {}{}",
            self.holds.len(),
            self.total(),
            list(&self.holds),
            self.contrary.len(),
            list(&self.contrary),
            self.inconclusive.len(),
            list(&undecided),
            self.not_run_in.len(),
            list(&self.not_run_in)
        )
    }
}

fn finding(key: &'static str, paper: &'static str, rule: String, unit: &str, tally: Tally) -> Finding {
    Finding {
        key,
        paper,
        rule,
        observed: tally.summary(unit),
        verdict: tally.verdict(),
        counts: (
            tally.holds.len(),
            tally.contrary.len(),
            tally.inconclusive.len(),
            tally.not_run_in.len(),
        ),
        pairs_to_decide: tally.pairs_to_decide(),
    }
}

/// The paper's findings judged on a study's tidy table (`results.csv`), each under its rule.
pub fn findings(tidy: &Table) -> Vec<Finding> {
    // The findings are the sliding model's: rows of the static estimate are not judged.
    let (sliding, _) = crate::output::sliding_rows(tidy);
    let all = setting::settings(&sliding);
    vec![
        static_model::static_k_below_one_and_rising(&all),
        static_model::static_wear_superlinear(&all),
        static_model::static_wear_grows_with_hardness(&all),
        static_model::static_wear_falls_with_toughness(&all),
        sliding::volume_linear_after_running_in(&all),
        sliding::initial_volume_much_larger_than_increments(&all),
        sliding::running_in_steeper(&all),
        sliding::memory_decays_exponentially(&all),
        sliding::running_in_sufficient(&all),
        sliding::decay_length_varies_with_load(&all),
        sliding::equation_5_slightly_below_w(&all),
        materials::sliding_k_below_static(&all),
        materials::sliding_k_below_0_1(&all),
        materials::sliding_k_in_dry_sliding_range(&all),
        materials::archard_like(&all),
        materials::k_rises_with_load(&all),
        materials::tougher_reaches_k_max_later(&all),
        materials::larger_d_star_wears_more_at_high_load(&all),
        materials::smaller_g_wears_more_at_low_load(&all),
        materials::toughest_not_yet_ahead(&all),
        particles::delayed_onset_for_large_g(&all),
        particles::hardest_least_tough_emits_most_wears_least(&all),
        particles::soft_tough_fewest_particles(&all),
        particles::severe_wear_from_large_particles(&all),
        kim::kim_hierarchy(&all),
        kim::kim_k_above_experiments(&all),
        appendix::appendix_a_discretization(&all),
        appendix::appendix_c_box_size(&all),
        appendix::appendix_c_more_spots_not_more_wear(&all),
        appendix::appendix_d_lambda_lower(&all),
        appendix::appendix_e_rms_height(&all),
    ]
}

/// The level and the methods of every interval, as findings.md and the documentation state them.
pub fn method_statement() -> String {
    format!(
        "Every interval is a {:.0} % confidence interval over surface pairs, the unit of replication: a mean \
         over pairs by {}; two settings of the study, which share their surface pairs (same seeds), by the {} (the \
         geometric mean of the per-pair ratios), or, where a pair has no particle, by the {} on the particles summed \
         over the shared pairs (W as ω d*³ times the count, Eq. 5); a trend over load by the exponent of a power law \
         fitted per surface pair (least squares in log–log), with its Student-t interval over pairs; a quantity \
         that is zero in most pairs as a ratio of means by a {}. A unit holds when its interval lies on the \
         paper's side of the rule's threshold, is contrary when it lies on the other side, and is inconclusive \
         otherwise (always when every pair gives 0: no spread is no evidence), with the surface pairs that would \
         decide it if the pairs kept the observed mean and spread. A surface pair is run in when its fit window starts after \
         {RUN_IN_DECAY_LENGTHS} of its own decay lengths ℓ of the memory of the initial contact (paper §3); \
         sliding quantities are judged on the run-in pairs (the line says how many), and a unit with fewer than \
         two is counted as not run in. The verdict follows from the counts: reproduced when it holds in every \
         decided unit and at least half are decided, partly when it holds in more than it is contrary in, not \
         reproduced otherwise, inconclusive when fewer than half are decided (the last column gives the pairs \
         per setting that would decide it), not testable when the study has no unit.",
        LEVEL * 100.0,
        Method::StudentT.name(),
        Method::PairedRatio.name(),
        Method::CountRatio.name(),
        "percentile bootstrap over surface pairs"
    )
}

/// The findings as Markdown: how the units are counted, then one table row per finding with its rule.
pub fn markdown(findings: &[Finding]) -> String {
    let mut text = format!(
        "{}\n\n| finding (paper) | rule | this study | verdict | pairs to decide |\n|---|---|---|---|---|\n",
        method_statement()
    );
    for f in findings {
        let (h, c, i, n) = f.counts;
        let decide = match (f.verdict, f.pairs_to_decide) {
            (Verdict::Inconclusive, Some(p)) => format!("{p}"),
            (Verdict::Inconclusive, None) => "more pairs alone do not decide it".into(),
            _ => "—".into(),
        };
        text += &format!(
            "| {} | {} | {} | {} ({h} holds, {c} contrary, {i} inconclusive, {n} not run in) | {decide} |\n",
            f.paper,
            f.rule.replace('|', "/"),
            f.observed.replace('|', "/"),
            f.verdict.name()
        );
    }
    text
}

#[cfg(test)]
mod tests;
