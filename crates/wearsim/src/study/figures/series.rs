//! The figures of sliding series against the sliding distance (Fig. 3, appendix B's Fig. B.9a and
//! the memory of the initial contact of §3), of one job of a study or of runs outside one.

use std::borrow::Cow;

use crate::output::{job_series_rows, lineages_left, number, pretty, JobResult, SeriesRow, StepRow};
use crate::sliding::{WearResult, RUN_IN_DECAY_LENGTHS, RUN_IN_LINEAGES_LEFT};
use crate::stats::mean_interval;

use super::labels::Shown;
use super::model::{
    fit_line, line_series, one_panel, Axis, Band, Color, Figure, LegendEntry, Panel, Point, Series, Style, Swatch,
};

/// What the figures of one job's sliding series say instead when that job is a static estimate.
pub(super) const NO_SERIES: &str =
    "this job is a static estimate: it takes no sliding step, so it has no wear-volume curve, \
particle counts or memory of the initial contact (those are the sliding model's; `--job` picks a sliding job)";

/// What the series figures say when only the tidy table was given.
pub(super) const NO_JOB_FILES: &str =
    "this figure draws one job's sliding series, which are in the study's job files: \
draw it from the study folder";

/// A series figure of a study: `draw` given the job shown and every surface pair of its setting;
/// a note without job files or for a job of the static estimate.
pub(super) fn of_study(
    series: Option<&(&JobResult, Vec<&JobResult>)>,
    shown: Shown,
    draw: fn(&SeriesOf, &[SeriesOf], Shown) -> Figure,
) -> Figure {
    match series {
        None => Figure::note(NO_JOB_FILES),
        Some((job, _)) if !job.model().slides() => Figure::note(NO_SERIES),
        Some((job, pairs)) => {
            let pairs: Vec<SeriesOf> = pairs.iter().map(|r| SeriesOf::of_job(r, shown)).collect();
            draw(&SeriesOf::of_job(job, shown), &pairs, shown)
        }
    }
}

/// What the series figures (fig3, appB, memory) draw of one job of a study, or of one run outside
/// one ([`run_figure`](super::run_figure)): its steps at one load, its results per fracture energy, and the words that
/// name it.
pub(super) struct SeriesOf<'a> {
    pub(super) load: f64,
    pub(super) steps: Cow<'a, [StepRow]>,
    pub(super) results: Cow<'a, [WearResult]>,
    /// Who it is, in titles: "job 3 (Si3N4), surface pair 2, τ̃ = 0.012 E, p_N = 0.001 E", or a
    /// run's load.
    pub(super) who: String,
    /// What the memory figure's title says it draws: "every surface pair — " and who without
    /// the pair, or a run's load.
    pub(super) setting: String,
    /// Its name among the memory figure's curves: "pair 2", "job 3", or a run's label.
    pub(super) name: String,
}

impl<'a> SeriesOf<'a> {
    pub(super) fn of_job(r: &'a JobResult, shown: Shown) -> Self {
        Self {
            load: r.load,
            steps: Cow::Borrowed(&r.steps),
            results: Cow::Borrowed(&r.results),
            who: who(r, shown, true),
            setting: format!("every surface pair — {}", who(r, shown, false)),
            name: r
                .inputs
                .seed
                .map_or(format!("job {}", r.index), |s| format!("pair {s}")),
        }
    }
}

/// "job 3 (Si3N4), surface pair 2, τ̃ = 0.012 E, p_N = 0.001 E".
pub(super) fn who(r: &JobResult, shown: Shown, with_pair: bool) -> String {
    let seed = match r.inputs.seed {
        Some(s) if with_pair => format!(", surface pair {s}"),
        _ => String::new(),
    };
    let material = if r.material == "material" {
        String::new()
    } else {
        format!(" ({})", r.material)
    };
    format!(
        "job {}{material}{seed}, τ̃ = {}, p_N = {} {}",
        r.index,
        shown.stress(r.inputs.shear_strength),
        number(r.inputs.nominal_pressure(r.load)),
        shown.unit("nominal_pressure")
    )
}

/// Whether a job's pair is run in by the findings' rule (paper §3): at most
/// [`RUN_IN_LINEAGES_LEFT`] of the junction lineages of s = 0 left where its fit window starts
/// (where none was there to count, its fit window after [`RUN_IN_DECAY_LENGTHS`] decay lengths ℓ);
/// the findings set a pair that is not aside.
pub(super) fn run_in_words(r: &SeriesOf) -> String {
    let first = r.results.first();
    let left = first.and_then(|w| lineages_left(&r.steps, w));
    let lengths = first.and_then(|w| w.running_in_decay_lengths);
    // The findings' rule decides; the words say what it read.
    let run_in = crate::sliding::is_run_in(left, lengths);
    let why = match (left, lengths) {
        (Some(left), lengths) => format!(
            "{:.0} % of the lineages of s = 0 left at the fit window{}{}",
            100.0 * left,
            lengths.map_or(String::new(), |x| format!(", {} ℓ", number(x))),
            if run_in {
                String::new()
            } else {
                format!("; over {:.0} %", 100.0 * RUN_IN_LINEAGES_LEFT)
            }
        ),
        (None, Some(x)) => format!(
            "fit window from {} ℓ, {} {RUN_IN_DECAY_LENGTHS}",
            number(x),
            if run_in { "at least" } else { "under" }
        ),
        (None, None) => "no lineage of s = 0 to follow and no decay fitted: the memory of the initial contact is \
                         gone by the first step"
            .into(),
    };
    if run_in {
        format!("run in ({why})")
    } else {
        format!("not run in ({why}): the findings set this pair aside")
    }
}

/// Fig. 3: V(s) of one job per fracture energy, with the results' line W·s + b fitted over the fit
/// window, and the running-in shaded.
pub(super) fn wear_volume(r: &SeriesOf, shown: Shown) -> Figure {
    let fit_start = r.results.first().map_or(0.0, |w| w.fit_window_start);
    let s_max = r.steps.last().map_or(1.0, |st| st.s);
    let mut legend = vec![LegendEntry {
        label: "running-in (not fitted)".into(),
        color: Color::Light,
        marker: 0,
        swatch: Swatch::Band,
    }];
    let mut series = Vec::new();
    for (e, w) in r.results.iter().enumerate() {
        let color = Color::Palette(e);
        let label = format!(
            "V, 𝒢 = {} {} (d* = {})",
            pretty(w.fracture_energy),
            shown.unit("fracture_energy"),
            shown.length(w.critical_diameter)
        );
        let v = r
            .steps
            .iter()
            .filter_map(|st| Some(Point::at(st.s, *st.volume.get(e)?)))
            .collect();
        series.push(line_series(label.clone(), color, false, 2, v));
        legend.push(LegendEntry {
            label,
            color,
            marker: 0,
            swatch: Swatch::Line { dashed: false },
        });
        if let (Some(slope), Some(intercept)) = (w.wear_rate, w.wear_volume_intercept) {
            let r2 = w
                .wear_rate_r2
                .map_or("undefined (no particle)".into(), |x| format!("{x:.3}"));
            let label = format!("fit: W = {} {}, R² = {r2}", number(slope), shown.unit("wear_rate"));
            let fit = vec![Point::at(0.0, intercept), Point::at(s_max, intercept + slope * s_max)];
            series.push(fit_line(label.clone(), color, fit));
            legend.push(LegendEntry {
                label,
                color,
                marker: 0,
                swatch: Swatch::Line { dashed: true },
            });
        }
    }
    let mut panels = one_panel(
        shown.distance_axis(),
        Axis {
            label: format!("wear volume V ({})", shown.unit("volume")),
            log: false,
            fallback: (0.0, 1.0),
        },
        series,
    );
    panels[0].x_band = Some(Band {
        low: 0.0,
        high: fit_start,
        color: Color::Light,
    });
    Figure {
        entry: "",
        name: String::new(),
        title: format!("wear volume V(s) — {}; {}", r.who, run_in_words(r)),
        panels,
        legend_title: String::new(),
        legend,
        note: None,
        report: Vec::new(),
    }
}

/// One count of appendix B: its value in a series row, dashed, the line's width, what it is.
pub(super) type Count = (fn(&SeriesRow) -> f64, bool, u32, &'static str);

/// Appendix B (Fig. B.9a): N*₊ (solid), N* (dashed) and N*₋ = N*₊ − N* (thin) of one job against s,
/// per fracture energy, from the library's series rows.
pub(super) fn particle_counts(r: &SeriesOf, shown: Shown) -> Figure {
    let rows: Vec<SeriesRow> = job_series_rows(r.load, &r.results, &r.steps);
    let (mut series, mut legend) = (Vec::new(), Vec::new());
    for (e, w) in r.results.iter().enumerate() {
        let color = Color::Palette(e);
        let mine: Vec<&SeriesRow> = rows
            .iter()
            .filter(|row| row.fracture_energy == w.fracture_energy)
            .collect();
        let d = if w.critical_diameter.is_finite() {
            format!("d* = {}", shown.length(w.critical_diameter))
        } else {
            format!("𝒢 = {} {}", pretty(w.fracture_energy), shown.unit("fracture_energy"))
        };
        let counts: [Count; 3] = [
            (|r| r.n_formed as f64, false, 2, "N*₊ (particles formed)"),
            (|r| r.n_critical as f64, true, 2, "N* (junctions ≥ d* now)"),
            (|r| r.n_shrunk as f64, false, 1, "N*₋ (thin)"),
        ];
        for (value, dashed, width, what) in counts {
            let label = format!("{what}, {d}");
            let points = mine.iter().map(|row| Point::at(row.s, value(row))).collect();
            series.push(line_series(label.clone(), color, dashed, width, points));
            legend.push(LegendEntry {
                label,
                color,
                marker: 0,
                swatch: Swatch::Line { dashed },
            });
        }
    }
    Figure {
        entry: "",
        name: String::new(),
        title: format!(
            "particles formed N*₊, critical junctions N*, N*₋ = N*₊ − N* — {}",
            r.who
        ),
        panels: one_panel(
            shown.distance_axis(),
            Axis {
                label: "number of junctions".into(),
                log: false,
                fallback: (0.0, 1.0),
            },
            series,
        ),
        legend_title: String::new(),
        legend,
        note: None,
        report: Vec::new(),
    }
}

/// One surface pair of the memory figure: N₀(s), its fit while it expects a junction or more, its
/// legend entry, and its decay length ℓ where it has a fit.
pub(super) fn memory_of_pair(i: usize, r: &SeriesOf, shown: Shown) -> (Vec<Series>, LegendEntry, Option<f64>) {
    let color = Color::Palette(i);
    let points = r
        .steps
        .iter()
        .map(|st| Point::at(st.s, st.initial_junctions as f64))
        .collect();
    let pair = &r.name;
    let mut label = format!("{pair}: N₀(s)");
    let mut series = vec![line_series(label.clone(), color, false, 2, points)];
    let first = r.results.first();
    let fit = first.and_then(|w| Some((w.memory_decay_length?, w.memory_fit_initial_junctions?)));
    if let Some((decay_length, initial)) = fit {
        let curve = r
            .steps
            .iter()
            .map(|st| Point::at(st.s, initial * (-st.s / decay_length).exp()))
            .take_while(|p| p.y >= 1.0)
            .collect();
        series.push(fit_line(format!("{pair}: fit"), color, curve));
        let r2 = first
            .and_then(|w| w.memory_decay_r2)
            .map_or("undefined".into(), |x| format!("{x:.2}"));
        let run_in = first
            .and_then(|w| w.running_in_decay_lengths)
            .map_or(String::new(), |x| format!(", s_r = {} ℓ", number(x)));
        label = format!(
            "{label}, fit ℓ = {} {} (R² = {r2}{run_in})",
            number(decay_length),
            shown.unit("length")
        );
    }
    // Where the pair's fit window starts: its N₀ there, the count the run-in rule reads.
    if let Some(w) = first {
        let at_start = r.steps.iter().find(|st| st.s >= w.fit_window_start);
        if let Some(st) = at_start.filter(|st| st.initial_junctions > 0) {
            series.push(Series {
                label: format!("{pair}: N₀(s_r), where the running-in ends"),
                color,
                marker: 0,
                style: Style::Markers,
                points: vec![Point::at(st.s, st.initial_junctions as f64)],
                reference: false,
            });
        }
        if let Some(left) = lineages_left(&r.steps, w) {
            label = format!("{label}, N₀(s_r)/N₀(0) = {:.0} %", 100.0 * left);
        }
    }
    let run_in = run_in_words(r);
    let verdict = run_in.split(" (").next().unwrap_or(&run_in);
    label = format!("{label} — {verdict}");
    let entry = LegendEntry {
        label,
        color,
        marker: 0,
        swatch: Swatch::Line { dashed: false },
    };
    (series, entry, fit.map(|f| f.0))
}

/// The memory of the initial contact (§3): N₀(s) of every surface pair of one setting, each with its
/// fitted N₀(0) e^(−s/ℓ) (dashed, while it expects a junction or more), and the mean ℓ with its 95 %
/// interval over the pairs as the legend's title.
pub(super) fn memory(pairs: &[SeriesOf], shown: Shown) -> Figure {
    // The fit window of every pair starts at the run's running-in distance: shaded before it.
    let fit_start = pairs
        .first()
        .and_then(|r| r.results.first())
        .map_or(0.0, |w| w.fit_window_start);
    let mut legend = vec![LegendEntry {
        label: format!(
            "running-in (not fitted): the fit window starts at s = {} {}",
            number(fit_start),
            shown.unit("length")
        ),
        color: Color::Light,
        marker: 0,
        swatch: Swatch::Band,
    }];
    let (mut series, mut lengths) = (Vec::new(), Vec::new());
    for (i, r) in pairs.iter().enumerate() {
        let (mine, entry, length) = memory_of_pair(i, r, shown);
        series.extend(mine);
        legend.push(entry);
        lengths.extend(length);
    }
    let markers = format!(
        "; markers: each pair's N₀ where its fit window starts (run in with at most {:.0} % of N₀(0) left)",
        100.0 * RUN_IN_LINEAGES_LEFT
    );
    let legend_title = match mean_interval(&lengths) {
        Some(i) => format!(
            "mean ℓ = {} [{}, {}] {} (95 % interval, Student t over {} pairs); dashed: each pair's fit{markers}",
            number(i.estimate),
            number(i.low),
            number(i.high),
            shown.unit("length"),
            i.n
        ),
        None => format!("dashed: each pair's fit N₀(0) e^(−s/ℓ){markers}"),
    };
    let title = match pairs.first() {
        Some(r) => format!("memory of the initial contact, {}", r.setting),
        None => "memory of the initial contact".into(),
    };
    Figure {
        entry: "",
        name: String::new(),
        title,
        panels: vec![Panel {
            x_band: Some(Band {
                low: 0.0,
                high: fit_start,
                color: Color::Light,
            }),
            ..one_panel(
                shown.distance_axis(),
                Axis {
                    label: "junctions descending from s = 0, N₀".into(),
                    log: true,
                    fallback: (0.5, 10.0),
                },
                series,
            )
            .remove(0)
        }],
        legend_title,
        legend,
        note: None,
        report: Vec::new(),
    }
}
