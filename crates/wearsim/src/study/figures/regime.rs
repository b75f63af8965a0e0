//! The wear-regime map, after Pham-Ba & Molinari's wear map (Tribol. Lett. 2021): against the load,
//! for each material (τ̃, 𝒢) and particle rule, the specific wear rate W/F_N and the particles'
//! size, and where a rule of interacting junctions departs from the paper's rule of one junction,
//! one particle (§3): the load from which the paired ratio of their W leaves 1 by its 95 % interval
//! over surface pairs. Below it wear is mild in the paper's sense (independent junctions, particles
//! of about d*); above it junctions act together, the regime the paper's appendix C calls unreliable.

use std::collections::BTreeMap;

use crate::output::{curve_labels, curves, StudyTable, ALONG_A_CURVE};
use crate::stats::mean_interval;

use super::labels::Shown;
use super::model::{log_space_interval, Axis, Color, Figure, LegendEntry, Panel, Point, Series, Style, Swatch};

/// The column that names a run's particle rule.
pub(super) const RULE: &str = "sliding.particle_rule";

/// The paper's rule, the reference of the map.
const PAPER_RULE: &str = crate::wear::OVERLAP.name;

/// How far a ratio's interval must lie from 1 to count as departing: round-off only (two rules
/// that form the same particles give W equal to the last digits).
const ROUND_OFF: f64 = 1e-9;

/// One surface pair of one setting.
struct PairRow {
    seed: String,
    /// W/F_N.
    specific: Option<f64>,
    /// The equivalent diameter of the mean particle, (W/(dN*₊/ds)/ω)^(1/3), over d*.
    size: Option<f64>,
    breakdown: bool,
}

/// One curve: a material setting under one rule, its pairs by nominal pressure.
struct RegimeCurve {
    label: String,
    /// The rule with its parameters, as the run records it.
    rule: String,
    /// The setting without the rule and the load: curves of equal `base` differ in the rule alone.
    base: String,
    by_pressure: BTreeMap<u64, (f64, Vec<PairRow>)>,
}

/// The curves of a tidy table with a particle-rule column of at least two values, one of them the
/// paper's; `None` otherwise.
fn regime_curves(table: &StudyTable) -> Option<Vec<RegimeCurve>> {
    let tidy = table.tidy();
    let rule = tidy.column(RULE)?;
    // The rule as recorded, with its parameters (an empty cell: the default, the paper's rule).
    let rules: Vec<String> = tidy
        .rows
        .iter()
        .map(|r| match r[rule].text() {
            t if t.is_empty() => PAPER_RULE.to_string(),
            t => t,
        })
        .collect();
    let names: Vec<String> = rules.iter().map(|r| rule_name(r)).collect();
    if !names.iter().any(|r| r == PAPER_RULE) || names.iter().all(|r| *r == names[0]) {
        return None;
    }
    let col = |name: &str| tidy.column(name);
    let get = |row: &[crate::output::Cell], name: &str| col(name).map_or(f64::NAN, |c| row[c].number());
    let found = table.settings();
    let base_columns: Vec<usize> = found
        .key_columns
        .iter()
        .copied()
        .filter(|&c| c != rule && !ALONG_A_CURVE.contains(&tidy.columns[c].as_str()))
        .collect();
    let index = curves(tidy).index;
    let labels = curve_labels(tidy);
    let mut out: BTreeMap<usize, RegimeCurve> = BTreeMap::new();
    for (r, row) in tidy.rows.iter().enumerate() {
        let curve = out.entry(index[r]).or_insert_with(|| RegimeCurve {
            label: labels.get(index[r]).cloned().unwrap_or_default(),
            rule: rules[r].clone(),
            base: base_columns
                .iter()
                .map(|&c| row[c].text())
                .collect::<Vec<_>>()
                .join("|"),
            by_pressure: BTreeMap::new(),
        });
        let (w, load, rate) = (get(row, "wear_rate"), get(row, "load"), get(row, "particle_rate"));
        let d = get(row, "critical_diameter");
        let mean_volume = w / rate;
        let pressure = get(row, "nominal_pressure");
        curve
            .by_pressure
            .entry(pressure.to_bits())
            .or_insert_with(|| (pressure, Vec::new()))
            .1
            .push(PairRow {
                // Without a seed column every setting is one pair, the same under every rule.
                seed: col("surface.seed").map_or(String::new(), |c| row[c].text()),
                specific: (w.is_finite() && load > 0.0).then_some(w / load),
                size: (mean_volume.is_finite() && mean_volume > 0.0 && d > 0.0)
                    .then(|| (mean_volume / crate::junctions::particle_volume(1.0)).cbrt() / d),
                breakdown: get(row, "breakdown_measures") > 0.0,
            });
    }
    Some(out.into_values().collect())
}

/// A rule's name without its parameters: "interacting" of "interacting(reach=1, particle=hull)".
fn rule_name(cell: &str) -> String {
    let name = cell.split('(').next().unwrap_or(cell).trim();
    if name.is_empty() { PAPER_RULE } else { name }.to_string()
}

/// The mean over pairs of `value` at each load of a curve, with its 95 % interval in log space.
fn means(c: &RegimeCurve, value: impl Fn(&PairRow) -> Option<f64>) -> Vec<Point> {
    c.by_pressure
        .values()
        .filter_map(|(p, pairs)| {
            let v: Vec<f64> = pairs.iter().filter_map(&value).collect();
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let (low, high) = mean_interval(&v).map_or((f64::NAN, f64::NAN), |i| log_space_interval(mean, i.high));
            (!v.is_empty() && mean.is_finite()).then_some(Point {
                x: *p,
                y: mean,
                low,
                high,
                hollow: false,
                no_wear: v.iter().all(|x| *x <= 0.0),
                breakdown: pairs.iter().any(|q| q.breakdown),
            })
        })
        .collect()
}

/// The paired ratio W(rule)/W(paper's rule) at each load of `c` against its paper-rule curve
/// `paper`: the geometric mean over the pairs where both wore, with its Student-t interval (on the
/// logs); one pair gives the point without an interval.
fn ratios(c: &RegimeCurve, paper: &RegimeCurve) -> Vec<Point> {
    c.by_pressure
        .iter()
        .filter_map(|(key, (p, pairs))| {
            let (_, reference) = paper.by_pressure.get(key)?;
            let logs: Vec<f64> = pairs
                .iter()
                .filter_map(|q| {
                    let r = reference.iter().find(|o| o.seed == q.seed)?;
                    let (a, b) = (q.specific?, r.specific?);
                    (a > 0.0 && b > 0.0).then(|| (a / b).ln())
                })
                .collect();
            if logs.is_empty() {
                return None;
            }
            let mean = logs.iter().sum::<f64>() / logs.len() as f64;
            let (low, high) = mean_interval(&logs).map_or((f64::NAN, f64::NAN), |i| (i.low.exp(), i.high.exp()));
            Some(Point {
                x: *p,
                y: mean.exp(),
                low,
                high,
                hollow: false,
                no_wear: false,
                breakdown: pairs.iter().chain(reference).any(|q| q.breakdown),
            })
        })
        .collect()
}

/// The departure of a rule from the paper's, in words, from its ratios by increasing load: the
/// lowest load whose 95 % interval excludes 1, bracketed by the load below it, with at how many of
/// the loads from there on the interval excludes 1 (a departure that holds, or one load's); a load
/// of one surface pair has no interval and decides nothing, and is counted as such.
pub(super) fn departure(points: &[Point]) -> String {
    let decided = |q: &Point| q.low.is_finite() && q.high.is_finite();
    let departs = |q: &Point| decided(q) && (q.low > 1.0 + ROUND_OFF || q.high < 1.0 - ROUND_OFF);
    let n = crate::output::number;
    let undecided = points.iter().filter(|q| !decided(q)).count();
    let one_pair = match undecided {
        0 => String::new(),
        1 => "; 1 load rests on one surface pair".into(),
        k => format!("; {k} loads rest on one surface pair"),
    };
    let Some(i) = points.iter().position(departs) else {
        return match points.last() {
            None => "no load where both rules wore".into(),
            Some(last) => format!(
                "agrees up to p_N = {} (every 95 % interval includes 1{one_pair})",
                n(last.x)
            ),
        };
    };
    let q = &points[i];
    let from = if i == 0 {
        format!("departs at the lowest load, p_N = {}", n(q.x))
    } else {
        format!("departs between p_N = {} and {}", n(points[i - 1].x), n(q.x))
    };
    let later = &points[i..];
    format!(
        "{from} (W ×{} [{}, {}] there; the interval excludes 1 at {} of the {} loads from there{one_pair})",
        n(q.y),
        n(q.low),
        n(q.high),
        later.iter().filter(|q| departs(q)).count(),
        later.len()
    )
}

/// The curves of the map, with what they are drawn by.
struct Map {
    all: Vec<RegimeCurve>,
    /// The settings without the rule, in order: a curve's colour.
    bases: Vec<String>,
}

impl Map {
    fn is_paper(c: &RegimeCurve) -> bool {
        rule_name(&c.rule) == PAPER_RULE
    }

    /// A curve's colour (its setting) and marker (its rule among the setting's curves).
    fn style(&self, c: &RegimeCurve) -> (Color, usize) {
        let base = self.bases.iter().position(|b| *b == c.base).unwrap_or(0);
        let marker = self
            .all
            .iter()
            .filter(|o| o.base == c.base)
            .position(|o| std::ptr::eq(o, c))
            .unwrap_or(0);
        (Color::Palette(base), marker)
    }

    /// A curve's ratio of W to the paper's rule's on the same setting, per load.
    fn ratio_points(&self, c: &RegimeCurve) -> Vec<Point> {
        self.all
            .iter()
            .find(|o| o.base == c.base && Self::is_paper(o))
            .map_or_else(Vec::new, |p| ratios(c, p))
    }

    /// One series per curve (the paper's rule's left out with `only_others`).
    fn series(&self, points: &dyn Fn(&RegimeCurve) -> Vec<Point>, only_others: bool) -> Vec<Series> {
        self.all
            .iter()
            .filter(|c| !only_others || !Self::is_paper(c))
            .map(|c| {
                let (color, marker) = self.style(c);
                Series {
                    label: c.label.clone(),
                    color,
                    marker,
                    style: Style::Means,
                    points: points(c),
                    reference: false,
                }
            })
            .collect()
    }

    /// W/F_N, the particle size over d*, and W over the paper's rule's, against p_N.
    fn panels(&self, shown: Shown) -> Vec<Panel> {
        let panel = |label: String, series: Vec<Series>| Panel {
            x: shown.load_axis(),
            y: Axis {
                label,
                log: true,
                fallback: (0.1, 10.0),
            },
            x_band: None,
            y_band: None,
            diagonal: false,
            series,
        };
        vec![
            panel(
                format!("specific wear rate W/F_N ({})", shown.unit("specific_wear_rate")),
                self.series(&|c| means(c, |q| q.specific), false),
            ),
            panel(
                "mean particle diameter / d*, (W/(dN*₊/ds)/ω)^(1/3)/d*".into(),
                self.series(&|c| means(c, |q| q.size), false),
            ),
            panel(
                "W(rule)/W(overlap), paired over surface pairs".into(),
                self.series(&|c| self.ratio_points(c), true),
            ),
        ]
    }

    /// Each curve, a rule other than the paper's with where it departs; the rings if any.
    fn legend(&self, panels: &[Panel]) -> Vec<LegendEntry> {
        let mut legend: Vec<LegendEntry> = self
            .all
            .iter()
            .map(|c| {
                let (color, marker) = self.style(c);
                let words = if Self::is_paper(c) {
                    String::new()
                } else {
                    format!(" — {}", departure(&self.ratio_points(c)))
                };
                LegendEntry {
                    label: format!("{}{words}", c.label),
                    color,
                    marker,
                    swatch: Swatch::LineMarker,
                }
            })
            .collect();
        let points = || panels.iter().flat_map(|p| &p.series).flat_map(|s| &s.points);
        if points().any(|q| q.breakdown) {
            legend.push(LegendEntry {
                label: super::BREAKDOWN_LEGEND.into(),
                color: Color::Grey,
                marker: 0,
                swatch: Swatch::Ring,
            });
        }
        legend
    }
}

/// The wear-regime map of a study whose particle rule is an axis with the paper's rule among its
/// values; none for another study (a study plots it only when it varies the rule).
pub(super) fn wear_regime(table: &StudyTable, shown: Shown) -> Option<Figure> {
    let all = regime_curves(table)?;
    let mut bases: Vec<String> = all.iter().map(|c| c.base.clone()).collect();
    bases.sort_unstable();
    bases.dedup();
    let mut others: Vec<&str> = all
        .iter()
        .filter(|c| !Map::is_paper(c))
        .map(|c| c.rule.as_str())
        .collect();
    others.sort_unstable();
    others.dedup();
    let title = format!(
        "wear-regime map: {} against the paper's rule; means over every surface pair (at high loads most pairs are \
         not run in, and the ratio compares the rules on the same contact history)",
        others.join(", ")
    );
    let map = Map { all, bases };
    let panels = map.panels(shown);
    let legend = map.legend(&panels);
    Some(Figure {
        entry: "",
        name: String::new(),
        title,
        panels,
        legend_title: "mean over surface pairs; bars: 95 % confidence interval (Student t; the ratio's on the \
                       logs of the paired ratios); a rule departs where its ratio's interval excludes 1"
            .into(),
        legend,
        note: None,
        report: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64, low: f64, high: f64) -> Point {
        Point {
            low,
            high,
            ..Point::at(x, y)
        }
    }

    #[test]
    fn a_rule_departs_where_its_ratio_leaves_one_and_not_by_round_off() {
        let agree = [at(1.0, 1.0, 1.0 - 1e-14, 1.0 + 1e-14), at(2.0, 1.01, 0.97, 1.05)];
        assert_eq!(
            departure(&agree),
            "agrees up to p_N = 2 (every 95 % interval includes 1)"
        );
        let parts = [agree[0], agree[1], at(4.0, 1.2, 1.1, 1.3), at(8.0, 1.1, 0.9, 1.3)];
        assert_eq!(
            departure(&parts),
            "departs between p_N = 2 and 4 (W ×1.2 [1.1, 1.3] there; the interval excludes 1 at 1 of the 2 loads \
             from there)"
        );
        assert!(departure(&[at(1.0, 0.5, 0.4, 0.6)]).starts_with("departs at the lowest load"));
        assert_eq!(departure(&[]), "no load where both rules wore");
        // One surface pair: no interval, nothing decided, and said.
        let one = [at(1.0, 1.5, f64::NAN, f64::NAN), agree[1]];
        assert_eq!(
            departure(&one),
            "agrees up to p_N = 2 (every 95 % interval includes 1; 1 load rests on one surface pair)"
        );
    }

    #[test]
    fn rule_names_drop_their_parameters() {
        assert_eq!(rule_name("interacting(reach=1, particle=hull)"), "interacting");
        assert_eq!(rule_name("overlap"), "overlap");
        assert_eq!(rule_name(""), "overlap");
    }
}
