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
}

impl Verdict {
    /// The verdict of a finding whose units hold in `holds` and are contrary in `contrary` of
    /// `total`: with fewer than half of them decided, inconclusive whatever the decided ones say.
    fn of_counts(holds: usize, contrary: usize, total: usize) -> Verdict {
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
    /// Every unit with its numbers, in the order judged (`findings_units.csv`).
    pub units: Vec<Unit>,
    /// The verdict when the units' Student-t p-values are Holm-adjusted within the finding (a unit
    /// decided at 95 % alone but not after the adjustment counted inconclusive), when it differs.
    pub verdict_under_holm: Option<Verdict>,
    /// For a [`Verdict::Cited`] finding: what fixes its numbers and which finding judges its
    /// comparison.
    pub cites: Option<&'static str>,
    /// The verdict when a surface pair counts as run in by the decay lengths (s_r ≥ 3 ℓ,
    /// [`RunInRule::DecayLengths`]) instead of the lineages left, when it differs.
    pub verdict_under_decay_lengths: Option<Verdict>,
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
}

impl Unit {
    fn of(outcome: &rules::Outcome) -> Unit {
        let text = outcome.text().to_string();
        let label = text.split_once(": ").map_or(text.as_str(), |(l, _)| l).to_string();
        let (outcome_name, needed) = match outcome {
            rules::Outcome::Judged { side, needed, .. } => (
                match side {
                    Side::Holds => "holds",
                    Side::Contrary => "contrary",
                    Side::Undecided => "inconclusive",
                },
                *needed,
            ),
            rules::Outcome::NotRunIn(_) => ("not run in", None),
        };
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

/// Holm's step-down adjustment of the p-values of a finding's units (those that have one), filled
/// into `p_holm`.
fn holm(units: &mut [Unit]) {
    let mut order: Vec<usize> = (0..units.len()).filter(|&k| units[k].p.is_some()).collect();
    order.sort_by(|&a, &b| units[a].p.unwrap_or(1.0).total_cmp(&units[b].p.unwrap_or(1.0)));
    let m = order.len();
    let mut running: f64 = 0.0;
    for (rank, &k) in order.iter().enumerate() {
        let adjusted = ((m - rank) as f64 * units[k].p.unwrap_or(1.0)).min(1.0);
        running = running.max(adjusted);
        units[k].p_holm = Some(running);
    }
}

/// The verdict once every unit decided at 95 % alone whose Holm-adjusted p-value is not below
/// 1 − LEVEL is counted inconclusive.
fn verdict_under_holm(units: &[Unit]) -> Verdict {
    let still_decided = |outcome: &str| {
        units
            .iter()
            .filter(|u| u.outcome == outcome && !u.p_holm.is_some_and(|p| p >= 1.0 - LEVEL))
            .count()
    };
    Verdict::of_counts(still_decided("holds"), still_decided("contrary"), units.len())
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
    /// Every unit filed, in order, with its numbers.
    pub units: Vec<Unit>,
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
        Verdict::of_counts(self.holds.len(), self.contrary.len(), self.total())
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
                Some(n) => format!("{line}, {n} pairs would decide it (80 % power)"),
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

fn finding(key: &'static str, paper: &'static str, rule: String, unit: &str, mut tally: Tally) -> Finding {
    holm(&mut tally.units);
    let under_holm = verdict_under_holm(&tally.units);
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
        verdict_under_holm: (under_holm != tally.verdict()).then_some(under_holm),
        units: tally.units,
        cites: None,
        verdict_under_decay_lengths: None,
    }
}

/// The paper's findings judged on a study's tidy table (`results.csv`), each under its rule, a
/// surface pair run in by the lineages left; a verdict that the decay-length rule would change
/// says so.
pub fn findings(tidy: &Table) -> Vec<Finding> {
    // The findings are the sliding model's: rows of the static estimate are not judged.
    let (sliding, _) = crate::output::sliding_rows(tidy);
    let mut found = findings_of(&setting::settings(&sliding, RunInRule::LineagesLeft));
    let other = findings_of(&setting::settings(&sliding, RunInRule::DecayLengths));
    for (f, o) in found.iter_mut().zip(other) {
        f.verdict_under_decay_lengths = (o.verdict != f.verdict).then_some(o.verdict);
    }
    found
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
        materials::tougher_reaches_k_max_later(all),
        materials::larger_d_star_wears_more_at_high_load(all),
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
         decide it with 80 % power if the pairs kept the observed mean and spread. A surface pair is run in when at most {:.0} % of the \
         junction lineages present at s = 0 are left where its fit window starts, counted in its steps (paper §3: \
         the memory of the initial contact has faded); a verdict that the other defensible rule, a fit window \
         starting after {RUN_IN_DECAY_LENGTHS} of the pair's own fitted decay lengths ℓ, would change says so; \
         sliding quantities are judged on the run-in pairs (the line says how many), and a unit with fewer than \
         two is counted as not run in. The verdict follows from the counts: reproduced when it holds in every \
         decided unit and at least half are decided, partly when it holds in more than it is contrary in, not \
         reproduced otherwise, inconclusive when fewer than half are decided (the last column gives the pairs \
         per setting that would decide it), not testable when the study has no unit. Each interval is read at \
         {:.0} % on its own; where a finding has several units, their Student-t p-values are also Holm-adjusted \
         within the finding, and a verdict the adjustment would change says so. A finding whose numbers an equation \
         of the model fixes, and whose comparison another finding judges, is shown against that value and not \
         counted (\"shown, not counted\").",
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
    /// The unit a reader looks at first: on the verdict's side, the one nearest to its threshold
    /// (the weakest holding unit of a reproduced finding, the weakest contrary one of a
    /// not-reproduced one); of an inconclusive finding, the undecided unit nearest to deciding.
    pub fn deciding_unit(&self) -> Option<&Unit> {
        let side = match self.verdict {
            Verdict::Reproduced | Verdict::Partly => "holds",
            Verdict::NotReproduced => "contrary",
            Verdict::Inconclusive => "inconclusive",
            Verdict::Cited => "shown",
            Verdict::NotTestable => return None,
        };
        let on_side = self.units.iter().filter(|u| u.outcome == side);
        let with_margin = on_side.clone().filter(|u| u.margin.is_some());
        let best = match side {
            // The least negative margin: the undecided unit nearest to deciding.
            "inconclusive" => with_margin.max_by(|a, b| a.margin.unwrap_or(0.0).total_cmp(&b.margin.unwrap_or(0.0))),
            _ => with_margin.min_by(|a, b| a.margin.unwrap_or(0.0).total_cmp(&b.margin.unwrap_or(0.0))),
        };
        best.or_else(|| on_side.clone().next())
    }

    /// What kind of result the finding is, in words: reproduced; contrary, i.e. a departure of
    /// this implementation (or of this study's box) from the paper's model, naming the units;
    /// inconclusive, with the pairs that would decide it; not testable, with the study that can.
    pub fn kind(&self) -> String {
        let (h, c, i, n) = self.counts;
        let total = h + c + i + n;
        let mut contrary: Vec<String> = self
            .units
            .iter()
            .filter(|u| u.outcome == "contrary")
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
                "{}: holds in {h}, contrary in {c} of {total} units (a departure from the paper's model in this \
                 implementation or this study's box: {})",
                self.verdict.name(),
                contrary.join("; ")
            ),
            Verdict::Inconclusive => match self.pairs_to_decide {
                Some(p) => format!("inconclusive: {p} surface pairs per setting would decide it (80 % power)"),
                None => "inconclusive: more surface pairs alone do not decide it".to_string(),
            },
            Verdict::NotTestable => format!("this study cannot show it; it needs {}", needed_study(self.key)),
            Verdict::Cited => format!("not counted: {}", self.cites.unwrap_or("restates another finding")),
        };
        if let Some(v) = self.verdict_under_holm {
            kind += &format!(" — {} once the p-values are Holm-adjusted within the finding", v.name());
        }
        if let Some(v) = self.verdict_under_decay_lengths {
            kind += &format!(
                " — {} if a pair counts as run in by s_r ≥ {RUN_IN_DECAY_LENGTHS} ℓ instead of the lineages left",
                v.name()
            );
        }
        kind
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

/// The findings as Markdown: one line per finding (the paper's sentence, the verdict, the number
/// that decides it, what kind of result it is), how the units are counted, then the table of every
/// finding with its rule and all its units (`findings_units.csv` has each unit's numbers).
pub fn markdown(findings: &[Finding]) -> String {
    let mut text = String::from(
        "| finding (paper) | verdict | the deciding unit, with its 95 % interval | what kind of result |\n|---|---|---|---|\n",
    );
    for f in findings {
        text += &format!(
            "| {} | {} | {} | {} |\n",
            f.paper,
            f.verdict.name(),
            f.deciding_unit().map_or("—".to_string(), unit_number).replace('|', "/"),
            f.kind().replace('|', "/")
        );
    }
    text += &format!(
        "\nThe deciding unit is, on the verdict's side, the one nearest to its threshold (of an inconclusive \
         finding, the undecided one nearest to deciding). Every unit's numbers, p-values (alone and Holm-adjusted \
         within its finding) and margin are in findings_units.csv.\n\n{}\n\n| finding (paper) | rule | this study | \
         verdict | pairs to decide |\n|---|---|---|---|---|\n",
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

/// One column of `findings_units.csv`: its name and its cell of a finding's unit.
type UnitColumn = (&'static str, fn(&Finding, &Unit) -> String);

fn cell(x: Option<f64>) -> String {
    x.map_or(String::new(), |v| format!("{v}"))
}

/// The columns of `findings_units.csv`, each named once beside what fills it.
const UNIT_COLUMNS: [UnitColumn; 15] = [
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
            let run_in = s.run_in_pairs();
            let pairs: Vec<&setting::Pair> = if run_in.is_empty() {
                s.pairs.iter().collect()
            } else {
                run_in
            };
            let ratios: Vec<f64> = pairs.iter().map(|p| sliding::equation_5_over_w(p)).collect();
            (s.curve, s.pressure, crate::stats::mean_interval(&ratios))
        })
        .collect()
}

/// The range Eq. 5 / W lies in where Eq. 5 "slightly underestimates" W (appendix B).
pub(crate) const EQUATION_5_OVER_W: (f64, f64) = sliding::EQUATION_5_OVER_W;

#[cfg(test)]
mod tests;
