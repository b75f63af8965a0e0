//! The findings as documents: findings.md (its opening table, what qualifies the verdicts, the
//! shared data, the running-in, the rules), findings_units.csv, and the table the documentation
//! keeps. Both front ends write [`document`]'s text, so that one study gives one findings.md.

use crate::output::{sliding_rows, StudyTable};
use crate::sliding::{RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT};
use crate::stats::{Method, LEVEL};

use super::{findings, setting, Finding, Unit, Verdict};

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

/// findings.md and findings_units.csv of a study, as `wearsim study plot` and Python's
/// `wearsim.plot.study_figures` write them.
#[derive(Debug, Clone)]
pub struct FindingsDocument {
    /// The findings judged (none where the study holds no sliding run).
    pub findings: Vec<Finding>,
    /// findings.md: the title, what of the study is not judged, then [`markdown`].
    pub markdown: String,
    /// findings_units.csv ([`units_csv`]).
    pub units_csv: String,
}

/// The paper's findings on a study as the documents both front ends write. The findings are
/// judged on the runs of the sliding model only: a static estimate (or any other model) is no
/// sliding run, and the document says which rows it leaves out.
pub fn document(table: &StudyTable) -> FindingsDocument {
    let tidy = table.tidy();
    let (sliding, others) = sliding_rows(tidy);
    let found = if sliding.rows.is_empty() {
        Vec::new()
    } else {
        findings(tidy)
    };
    let note = match (others, sliding.rows.len()) {
        (0, _) => String::new(),
        (_, 0) => "This study holds no run of the sliding model (its `sliding.model` is another, such as \
                   \"estimate\": static estimates): the paper's findings are judged on sliding runs, so none is \
                   judged here. Its figures draw the other models' results, labelled by model (\"static \
                   estimate\").\n\n"
            .to_string(),
        (n, _) => format!(
            "{n} rows of this study are not sliding runs (their `sliding.model` is another, such as \"estimate\": \
             static estimates); the findings below are judged on its sliding jobs only.\n\n"
        ),
    };
    FindingsDocument {
        markdown: format!(
            "# The paper's findings on this study\n\nBrink, Frérot & Molinari (2021).\n\n{note}{}",
            markdown(&found)
        ),
        units_csv: units_csv(&found),
        findings: found,
    }
}
