//! The figures of a small hand-made study (jobs expanded from a study file, results made up): every
//! entry of the registry gives its figures, rates are per unit area with the interval of the mean,
//! points align by row, Kim's band only for Kim's ceramics, the memory figure every pair.

use std::path::Path;

use super::model::log_space_interval;
use super::*;
use crate::config::Units;
use crate::output::StudyTable;
use crate::output::{Cell, Provenance, StepRow, TidyRow, JOB_FORMAT, KIM_EXPERIMENTAL_K};
use crate::sliding::WearResult;
use crate::study::expand::Job;

const REDUCED: &str = r#"
units = "reduced"
[surface]
grid = 64
length = 0.5
hurst = 0.7
lambda_lower = 0.0625
lambda_upper = 0.125
rms_height = 0.005
seed = [1, 2, 3]
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.012]
fracture_energies = [0.5e-6, 1e-6]
[sliding]
loads = [2.5e-4, 5e-4]
distance = 0.5
running_in = 0.25
"#;

const KIM: &str = r#"
units = "si"
[surface]
grid = 64
length = 50e-6
hurst = 0.7
lambda_lower = 6.25e-6
lambda_upper = 25e-6
seed = [1, 2]
[[materials]]
name = "SiC"
youngs_modulus = 392e9
poisson_ratio = 0.16
shear_strength = 4.80e9
fracture_energies = [45.00]
surface = { rms_height = 5.0e-6 }
[[materials]]
name = "Al2O3"
youngs_modulus = 343e9
poisson_ratio = 0.25
shear_strength = 3.37e9
fracture_energies = [46.65]
surface = { rms_height = 20.0e-6 }
[sliding]
loads = [0.3125, 0.625]
distance = 0.5
running_in = 0.25
"#;

/// Made-up results of one job: W growing with the load and the seed, a few steps of series.
fn result_of(job: &Job) -> JobResult {
    let inputs = job.inputs();
    let (load, seed) = (job.load(), inputs.seed.unwrap_or(1) as f64);
    let energies = &job.run.material.fracture_energies;
    let scale = inputs.length * inputs.length;
    let results: Vec<WearResult> = energies
        .iter()
        .enumerate()
        .map(|(e, &g)| {
            let w = scale * 1e-4 * (load / 2.5e-4 * scale.recip()).powf(1.2) * (1.0 + 0.1 * seed) / (1 + e) as f64;
            WearResult {
                fracture_energy: g,
                critical_diameter: inputs.length * 0.02 * (1 + e) as f64,
                wear_rate: Some(w),
                wear_rate_r2: Some(0.95),
                wear_volume_intercept: Some(w * 0.1),
                fit_window_start: 0.25 * inputs.length,
                wear_coefficient: Some(0.05 * (1.0 + 0.1 * seed)),
                particle_rate: Some(100.0 / (1 + e) as f64),
                wear_rate_estimate: Some(0.9 * w),
                particles_in_fit: 10 + 5 * e,
                initial_volume: 20.0 * w,
                static_wear_coefficient_mean: 0.5,
                static_wear_rate_mean: 5.0 * w,
                junctions_mean: 30.0,
                critical_junctions_mean: 3.0,
                memory_decay_length: Some(0.05 * inputs.length * seed),
                memory_decay_r2: Some(0.9),
                memory_fit_initial_junctions: Some(20.0),
                running_in_decay_lengths: Some(5.0 / seed),
                // Every lineage of s = 0 gone by the fit window: run in (`decaying` makes seeds 2
                // and 3 keep some).
                initial_lineages_left: Some(0.0),
                ..WearResult::default()
            }
        })
        .collect();
    let steps = (0..6)
        .map(|k| StepRow {
            s: k as f64 * 0.1 * inputs.length,
            junctions: 30,
            wrapping_junctions: 0,
            contact_area: 0.1,
            initial_junctions: 20usize >> k,
            merged_junctions: None,
            largest_junction: None,
            n_critical: vec![3; energies.len()],
            n_formed: vec![2 + k; energies.len()],
            volume: results
                .iter()
                .map(|w| w.initial_volume + w.wear_rate.unwrap_or(0.0) * k as f64)
                .collect(),
            static_wear_coefficient: vec![0.5; energies.len()],
        })
        .collect();
    JobResult {
        format: JOB_FORMAT,
        provenance: Provenance::current(),
        index: job.index,
        material: job.material.clone(),
        inputs,
        load,
        flow_pressure: 3.0 * 3f64.sqrt() * job.run.material.shear_strength,
        effective_modulus: 1.0,
        results,
        steps,
        total_iterations: 0,
        seconds: 1.0,
        warnings: Vec::new(),
        estimates: Vec::new(),
    }
}

/// A study's job results and its tidy table.
fn study(text: &str) -> (Vec<JobResult>, Table) {
    let study = crate::study::expand::expand(text, Path::new(".")).expect("the test study expands");
    let results: Vec<JobResult> = study.jobs.iter().map(result_of).collect();
    let rows: Vec<TidyRow> = results.iter().flat_map(TidyRow::of_job).collect();
    (results, Table::of(&rows))
}

/// The study with the lineages of s = 0 left at the fit window as the fitted decay expects,
/// e^(−5/seed): seed 1 run in (0.7 %), seeds 2 and 3 not (8 % and 19 %).
fn decaying(text: &str) -> (Vec<JobResult>, Table) {
    let (mut results, _) = study(text);
    for r in &mut results {
        let seed = r.inputs.seed.unwrap_or(1) as f64;
        for w in &mut r.results {
            w.initial_lineages_left = Some((-5.0 / seed).exp());
        }
    }
    let rows: Vec<TidyRow> = results.iter().flat_map(TidyRow::of_job).collect();
    (results, Table::of(&rows))
}

fn figures(text: &str, names: &[&str]) -> Vec<Figure> {
    let (results, tidy) = study(text);
    let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
    study_figures(&StudyTable::of(tidy.clone()), &results, None, Some(&names)).unwrap()
}

fn named<'a>(figures: &'a [Figure], name: &str) -> &'a Figure {
    figures
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no figure {name}"))
}

#[test]
fn every_entry_of_the_registry_gives_its_figures_under_their_names() {
    let (results, tidy) = study(REDUCED);
    let all = study_figures(&StudyTable::of(tidy.clone()), &results, None, None).unwrap();
    let names: Vec<&str> = all.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "fig2_static_model",
            "fig3_wear_volume",
            "fig4_sliding_wear",
            "fig4c_constant_d_star_1",
            "fig4c_constant_d_star_2",
            "fig5_particle_rate",
            "fig6_kim_comparison",
            "appB_particle_counts",
            "appB_eq5_against_w",
            "appC_junctions",
            "appC_critical_junctions",
            "appF_contact_severity",
            "memory_of_initial_contact",
        ]
    );
    for f in &all {
        assert!(f.note.is_none(), "{}: {:?}", f.name, f.note);
        assert!(
            f.panels.iter().all(|p| p.series.iter().any(|s| !s.points.is_empty())),
            "{}",
            f.name
        );
        assert!(FIGURES.iter().any(|e| e.name == f.entry), "{}", f.name);
        // The CSV holds every point once, with its panel's axis labels.
        let points: usize = f.panels.iter().flat_map(|p| &p.series).map(|s| s.points.len()).sum();
        let csv = f.to_csv();
        assert_eq!(
            csv.lines().filter(|l| l.contains(",point,")).count(),
            points,
            "{}",
            f.name
        );
    }
    // Without job files the series figures say where their data is; an unknown name is refused.
    let table_only = study_figures(&StudyTable::of(tidy.clone()), &[], None, Some(&["fig3".into()])).unwrap();
    assert!(table_only[0].note.as_deref().unwrap().contains("job files"));
    let err = study_figures(&StudyTable::of(tidy.clone()), &results, None, Some(&["fig9".into()])).unwrap_err();
    assert!(err.to_string().contains("fig2, fig3"), "{err}");
    // An entry asked for by name that this study cannot show (no particle-rule axis) is a note,
    // under the entry's name and file stem.
    let regime = study_figures(
        &StudyTable::of(tidy.clone()),
        &results,
        None,
        Some(&["wear-regime".into()]),
    )
    .unwrap();
    assert_eq!(
        (regime.len(), regime[0].entry, regime[0].name.as_str()),
        (1, "wear-regime", "wear_regime")
    );
    assert!(regime[0].note.as_deref().unwrap().contains("nothing for wear-regime"));
    // Unasked, it is left out.
    let all = study_figures(&StudyTable::of(tidy.clone()), &results, None, None).unwrap();
    assert!(all.iter().all(|f| f.entry != "wear-regime"));
}

#[test]
fn rates_are_per_unit_area_with_intervals_and_kims_band_only_for_kims_ceramics() {
    let fig = figures(REDUCED, &["fig4", "fig6"]);
    let fig4 = named(&fig, "fig4_sliding_wear");
    // A box of 0.5 × 0.5 L: W divided by its area 0.25; the bars are the 95 % interval of the mean
    // of the three pairs (1.1, 1.2, 1.3 times a base: mean 1.2, sd 0.1, t(2) = 4.303).
    let p = fig4.panels[0].series[0].points[0];
    let plain = p.y * 0.25;
    let base = plain / 1.2;
    assert!((p.y - base * 1.2 / 0.25).abs() < 1e-12 * p.y, "{p:?}");
    // On its log axis the interval is drawn in log space: mean ×/÷ e^(t·se/mean), positive and
    // symmetric about the mean there.
    let half = 4.302_652_7 * 0.1 / 3f64.sqrt() * base / 0.25;
    let factor = (half / p.y).exp();
    assert!(fig4.panels[0].y.log);
    assert!((p.high - p.y * factor).abs() < 1e-6 * p.high, "{p:?}");
    assert!((p.low - p.y / factor).abs() < 1e-6 * p.low, "{p:?}");
    assert!(fig4.panels[0].y.label.contains("per unit nominal area"));
    assert_eq!(fig4.legend_title, MEANS_ON_LOG_AXES);
    // The specific wear rate K = W/F_N is a panel in SI only: W/(Lx·Ly) over p_N, in mm³/(N·m).
    assert_eq!(fig4.panels.len(), 2);
    let kim = figures(KIM, &["fig4"]);
    let si4 = named(&kim, "fig4_sliding_wear");
    assert_eq!(si4.panels.len(), 3);
    assert!(
        si4.panels[2].y.label.contains("K = W / F_N (mm³/(N·m))"),
        "{}",
        si4.panels[2].y.label
    );
    assert_eq!(si4.panels[0].series.len(), si4.panels[2].series.len());
    assert!(si4.panels[2].series.iter().all(|s| !s.points.is_empty()));
    for (w, k) in si4.panels[0].series.iter().zip(&si4.panels[2].series) {
        assert_eq!(w.points.len(), k.points.len());
        for (pw, pk) in w.points.iter().zip(&k.points) {
            assert!((pk.y / (pw.y / pw.x * 1e9) - 1.0).abs() < 1e-9, "{pw:?} {pk:?}");
        }
    }
    // A spread wider than the mean: the linear interval reaches below zero, the drawn one does not.
    assert_eq!(log_space_interval(1.0, 3.0), ((-2f64).exp(), 2f64.exp()));
    assert!(log_space_interval(0.0, 1.0).0.is_nan() && log_space_interval(1.0, f64::NAN).1.is_nan());
    // 10 particles per pair at 𝒢₁ (30 summed over three pairs): resolved; Fig. 2 is not fitted.
    assert!(fig4.panels[0].series.iter().flat_map(|s| &s.points).all(|q| !q.hollow));
    assert!(named(&fig, "fig6_kim_comparison").panels[0].y_band.is_none());
    // Kim's ceramics: the band, and appendix F with the paper's fits beside them.
    let kim = figures(KIM, &["fig6", "appF"]);
    let band = named(&kim, "fig6_kim_comparison").panels[0].y_band.clone().unwrap();
    assert_eq!((band.low, band.high), KIM_EXPERIMENTAL_K);
    let app_f = named(&kim, "appF_contact_severity");
    assert!(app_f
        .legend
        .iter()
        .any(|e| e.label.contains("fit to their experiments")));
    // What a front end prints of it: the fit over all materials, then one line per material.
    assert_eq!(app_f.report[0], format!("contact severity fit, {}", app_f.title));
    assert!(app_f.report.len() > 1 && app_f.report.iter().all(|l| !l.contains("fit to their experiments")));
    assert!(named(&kim, "fig6_kim_comparison").report.is_empty());
}

#[test]
fn fig3_says_a_pair_without_a_memory_to_follow_is_run_in_as_the_findings_count_it() {
    let (mut results, tidy) = study(REDUCED);
    // No junction of s = 0 in any step, no decay fitted: the findings count the pair as run in.
    for st in &mut results[0].steps {
        st.initial_junctions = 0;
    }
    for w in &mut results[0].results {
        (w.initial_lineages_left, w.running_in_decay_lengths) = (None, None);
    }
    let job = results[0].index;
    let title = study_figures(
        &StudyTable::of(tidy.clone()),
        &results,
        Some(job),
        Some(&["fig3".into()]),
    )
    .unwrap()[0]
        .title
        .clone();
    assert!(title.ends_with("; run in (no lineage of s = 0 to follow and no decay fitted: the memory of the initial contact is gone by the first step)"), "{title}");
}

#[test]
fn the_rates_against_load_are_means_over_the_run_in_pairs_as_in_the_findings() {
    let (results, tidy) = decaying(REDUCED);
    let fig = study_figures(
        &StudyTable::of(tidy.clone()),
        &results,
        None,
        Some(&["fig4".into(), "fig2".into()]),
    )
    .unwrap();
    let fig4 = named(&fig, "fig4_sliding_wear");
    assert!(
        fig4.title.contains("means over the run-in surface pairs"),
        "{}",
        fig4.title
    );
    // Only pair 1 is run in: W is its value (1.1 times the base), without an interval.
    let p = fig4.panels[0].series[0].points[0];
    let all = named(&figures(REDUCED, &["fig4"]), "fig4_sliding_wear").panels[0].series[0].points[0];
    assert!((p.y / all.y - 1.1 / 1.2).abs() < 1e-12, "{p:?} against {all:?}");
    assert!(p.low.is_nan() && p.high.is_nan(), "{p:?}");
    // The static model is over every pair, run in or not.
    let static_of = |f: &[Figure]| named(f, "fig2_static_model").panels[0].series[0].points[0];
    assert_eq!(static_of(&fig), static_of(&figures(REDUCED, &["fig2"])));
}

#[test]
fn junctions_are_one_curve_per_setting_and_fits_do_not_span_the_axes() {
    let (results, mut tidy) = study(REDUCED);
    // Two τ̃ × two 𝒢: four curves of N*, two of N (it does not depend on 𝒢), with or without the job
    // column (a table made by hand).
    for _ in 0..2 {
        let fig = study_figures(&StudyTable::of(tidy.clone()), &[], None, Some(&["appC".into()])).unwrap();
        assert_eq!(named(&fig, "appC_junctions").panels[0].series.len(), 2);
        assert_eq!(named(&fig, "appC_critical_junctions").panels[0].series.len(), 4);
        if let Some(job) = tidy.column("job") {
            tidy.columns.remove(job);
            tidy.rows.iter_mut().for_each(|r| {
                r.remove(job);
            });
        }
    }
    // Fitted lines are drawn over the data; the data alone span the axes.
    let fig = study_figures(
        &StudyTable::of(tidy.clone()),
        &results,
        Some(0),
        Some(&["fig3".into(), "memory".into()]),
    )
    .unwrap();
    for f in &fig {
        for s in &f.panels[0].series {
            assert_eq!(s.reference, s.label.contains("fit"), "{}: {}", f.name, s.label);
        }
    }
}

#[test]
fn equation_5_pairs_w_and_its_estimate_of_the_same_row() {
    let fig = figures(REDUCED, &["appB-eq5"]);
    // The made-up estimate is 0.9 W in every row: a point off that line pairs two rows.
    for s in &fig[0].panels[0].series {
        assert!(!s.points.is_empty());
        for q in &s.points {
            assert!((q.y / q.x - 0.9).abs() < 1e-12, "{q:?}");
        }
    }
    // Beside it, Eq. 5 / W against load per curve as the finding reads it (0.9 in every pair, with no
    // spread), over the range of "slightly underestimates".
    let ratios = &fig[0].panels[1];
    assert!(!ratios.y.log && ratios.x.label.contains("nominal pressure"));
    let band = ratios.y_band.clone().unwrap();
    assert_eq!((band.low, band.high), (0.6, 1.0));
    assert_eq!(ratios.series.len(), fig[0].panels[0].series.len());
    for s in &ratios.series {
        // F_N = 2.5 and 5×10⁻⁴ on a box of 0.5 × 0.5 L.
        let x: Vec<f64> = s.points.iter().map(|q| q.x).collect();
        assert!(
            (x[0] - 1e-3).abs() < 1e-15 && (x[1] - 2e-3).abs() < 1e-15 && x.len() == 2,
            "{x:?}"
        );
        for q in &s.points {
            assert!((q.y - 0.9).abs() < 1e-12 && (q.low - 0.9).abs() < 1e-12, "{q:?}");
        }
    }
    assert!(fig[0].legend_title.contains("slightly underestimates"));
}

#[test]
fn the_memory_figure_shows_every_pair_of_the_setting() {
    let (results, tidy) = decaying(REDUCED);
    let table = StudyTable::of(tidy.clone());
    let fig = study_figures(&table, &results, Some(0), Some(&["memory".into()])).unwrap();
    let labels: Vec<&str> = fig[0].panels[0]
        .series
        .iter()
        .filter(|s| {
            s.style
                == (Style::Line {
                    dashed: false,
                    width: 2,
                })
        })
        .map(|s| s.label.as_str())
        .collect();
    assert_eq!(labels, ["pair 1: N₀(s)", "pair 2: N₀(s)", "pair 3: N₀(s)"]);
    assert!(fig[0].legend_title.starts_with("mean ℓ = "), "{}", fig[0].legend_title);
    // Each pair says whether the findings count it as run in (e^(−5/seed) of the lineages left against
    // 5 %), and the running-in before the fit window is shaded.
    let verdicts: Vec<bool> = fig[0].legend[1..]
        .iter()
        .map(|e| e.label.ends_with("— run in"))
        .collect();
    assert_eq!(verdicts, [true, false, false], "{:?}", fig[0].legend);
    assert!(fig[0].legend[2].label.ends_with("— not run in"));
    // Each pair's N₀ where its fit window starts is marked, and its legend says how much of N₀(0)
    // is left there.
    let marks: Vec<&Series> = fig[0].panels[0]
        .series
        .iter()
        .filter(|s| s.style == Style::Markers)
        .collect();
    assert_eq!(marks.len(), 3);
    let start = results[0].results[0].fit_window_start;
    for (mark, r) in marks.iter().zip(&results) {
        let at = r.steps.iter().find(|st| st.s >= start).unwrap();
        assert_eq!(
            (mark.points[0].x, mark.points[0].y),
            (at.s, at.initial_junctions as f64)
        );
    }
    assert!(
        fig[0].legend[1].label.contains("N₀(s_r)/N₀(0) = 1 %"),
        "{}",
        fig[0].legend[1].label
    );
    assert!(fig[0]
        .legend_title
        .contains("markers: each pair's N₀ where its fit window starts"));
    let band = fig[0].panels[0].x_band.clone().unwrap();
    assert_eq!((band.low, band.high), (0.0, 0.25 * 0.5));
    // Fig. 3 says it of its job.
    let fig3 = |job| {
        study_figures(
            &StudyTable::of(tidy.clone()),
            &results,
            Some(job),
            Some(&["fig3".into()]),
        )
        .unwrap()[0]
            .title
            .clone()
    };
    assert!(
        fig3(0).ends_with("; run in (1 % of the lineages of s = 0 left at the fit window, 5 ℓ)"),
        "{}",
        fig3(0)
    );
    let pair_2 = results.iter().find(|r| r.inputs.seed == Some(2)).unwrap().index;
    assert!(
        fig3(pair_2).contains("; not run in (8 % of the lineages of s = 0 left at the fit window, 2.5 ℓ; over 5 %)"),
        "{}",
        fig3(pair_2)
    );
}

/// The series figures of one run outside a study (Python's `wear_volume`, `particle_counts`,
/// `memory`) are the study's figures of the same series: the same plotted numbers, read back from
/// the run's tables as a user passes them.
#[test]
fn a_runs_series_figures_plot_the_numbers_of_the_studys() {
    let (results, tidy) = decaying(REDUCED);
    let pairs = pairs_of(&results, &results[0]);
    assert_eq!(pairs.len(), 3);
    let job = pairs[0];
    // A run's tables as Python hands them over: the series rows, the results with their load.
    let tables = |r: &JobResult| {
        let series = Table::of(&r.series_rows());
        let mut results = Table::of(&r.results);
        results.columns.push("load".into());
        for row in &mut results.rows {
            row.push(Cell::Float(r.load));
        }
        (series, results)
    };
    let of_job: Vec<(Table, Table)> = pairs.iter().map(|r| tables(r)).collect();
    let runs: Vec<RunTables> = of_job
        .iter()
        .zip(&pairs)
        .map(|((series, results), r)| RunTables {
            label: if r.inputs.seed == Some(1) { "pair 1" } else { "another" },
            series,
            results: Some(results),
        })
        .collect();
    for (entry, name) in [
        ("fig3", "fig3_wear_volume"),
        ("appB", "appB_particle_counts"),
        ("memory", "memory_of_initial_contact"),
    ] {
        let study = study_figures(
            &StudyTable::of(tidy.clone()),
            &results,
            Some(job.index),
            Some(&[entry.into()]),
        )
        .unwrap();
        let run = run_figure(entry, &runs, None, Units::Reduced).unwrap();
        assert_eq!(run.name, name);
        let points = |f: &Figure| -> Vec<Vec<(f64, f64)>> {
            f.panels[0]
                .series
                .iter()
                .map(|s| s.points.iter().map(|p| (p.x, p.y)).collect())
                .collect()
        };
        assert_eq!(points(&run), points(&study[0]), "{entry}");
        assert_eq!(run.panels[0].x_band, study[0].panels[0].x_band, "{entry}");
        assert!(run.title.contains("F_N = "), "{}", run.title);
    }
    // The run's wear-volume figure says whether it is run in, as the study's does.
    let study = study_figures(
        &StudyTable::of(tidy.clone()),
        &results,
        Some(job.index),
        Some(&["fig3".into()]),
    )
    .unwrap();
    let words = |t: &str| t.split("; ").last().unwrap().to_string();
    let run = run_figure("fig3", &runs[..1], None, Units::Reduced).unwrap();
    assert_eq!(words(&run.title), words(&study[0].title));
}

/// A run's figure without results, at a load it does not have, of a figure that is not a series
/// figure, or of a series cut short: refused, each saying why.
#[test]
fn a_runs_series_figures_name_what_they_lack() {
    let (results, _) = decaying(REDUCED);
    let job = &results[0];
    let series = Table::of(&job.series_rows());
    let mut with_load = Table::of(&job.results);
    with_load.columns.push("load".into());
    for row in &mut with_load.rows {
        row.push(Cell::Float(job.load));
    }
    let of_job = [(series, with_load)];
    let runs = [RunTables {
        label: "pair 1",
        series: &of_job[0].0,
        results: Some(&of_job[0].1),
    }];
    // appB without results names its curves by 𝒢; fig3 and memory need them, and say so.
    let bare = [RunTables {
        label: "bare",
        series: &of_job[0].0,
        results: None,
    }];
    let counts = run_figure("appB", &bare, None, Units::Reduced).unwrap();
    assert!(counts.legend[0].label.contains("𝒢 = "), "{:?}", counts.legend[0]);
    for entry in ["fig3", "memory"] {
        let err = run_figure(entry, &bare, None, Units::Reduced).unwrap_err().to_string();
        assert!(err.contains("results") && err.contains("summary[\"results\"]"), "{err}");
    }
    // A load the series does not have, a figure that is not a series figure, a series cut short.
    let err = run_figure("appB", &runs[..1], Some(0.5), Units::Reduced)
        .unwrap_err()
        .to_string();
    assert!(err.contains("no load 0.5") && err.contains("its loads are"), "{err}");
    let err = run_figure("fig4", &runs[..1], None, Units::Reduced)
        .unwrap_err()
        .to_string();
    assert!(err.contains("fig3, appB, memory"), "{err}");
    let mut cut = of_job[0].0.clone();
    cut.rows.pop();
    let err = run_figure(
        "appB",
        &[RunTables {
            label: "cut",
            series: &cut,
            results: Some(&of_job[0].1),
        }],
        None,
        Units::Reduced,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("has no row of fracture energy"), "{err}");
}

#[test]
fn rates_per_area_are_labelled_by_what_they_are_in_si() {
    let si = Shown { system: Units::Si };
    let w = si.per_area("wear_rate", "W");
    assert!(
        w.contains("wear depth per sliding distance, m/m") && !w.contains("m²/m²"),
        "{w}"
    );
    let n = si.per_area("particle_rate", "dN*₊/ds");
    assert!(n.contains("particles per m slid per m², 1/m³"), "{n}");
    let reduced = Shown { system: Units::Reduced }.per_area("particle_rate", "dN*₊/ds");
    assert!(reduced.contains("a box L × L"), "{reduced}");
}

#[test]
fn the_wear_regime_map_pairs_each_rule_with_the_papers_and_says_where_it_departs() {
    // No particle-rule axis: no map, and asked for by name, a note that says so.
    let none = figures(REDUCED, &["wear-regime"]);
    assert_eq!(none.len(), 1);
    assert!(none[0].panels.is_empty(), "{:?}", none[0].note);
    assert!(none[0].note.as_deref().unwrap().contains("particle_rule axis"));
    let text = REDUCED.replace(
        "running_in = 0.25",
        "running_in = 0.25\nparticle_rule = [\"overlap\", \"interacting\"]",
    );
    let (mut results, _) = study(&text);
    // The interacting rule wears half as much again at the higher load, in every pair, and one
    // pair of the paper's rule lies in the breakdown regime there.
    for r in &mut results {
        let interacting = r
            .inputs
            .particle_rule
            .as_deref()
            .is_some_and(|p| p.starts_with("interacting"));
        for w in &mut r.results {
            w.breakdown_measures = Some(0);
            if r.load > 3e-4 && interacting {
                w.wear_rate = w.wear_rate.map(|x| 1.5 * x);
            }
            if r.load > 3e-4 && !interacting && r.inputs.seed == Some(2) {
                w.breakdown_measures = Some(1);
            }
        }
    }
    let rows: Vec<TidyRow> = results.iter().flat_map(TidyRow::of_job).collect();
    let tidy = Table::of(&rows);
    let names = vec!["wear-regime".to_string()];
    let all = study_figures(&StudyTable::of(tidy.clone()), &results, None, Some(&names)).unwrap();
    let map = named(&all, "wear_regime");
    assert_eq!(map.panels.len(), 3);
    // Two τ̃ × two 𝒢 × two rules on the first two panels, the four interacting curves on the third.
    assert_eq!(map.panels[0].series.len(), 8);
    assert_eq!(map.panels[2].series.len(), 4);
    for s in &map.panels[2].series {
        let ratios: Vec<f64> = s.points.iter().map(|q| q.y).collect();
        assert_eq!(ratios.len(), 2, "{}", s.label);
        assert!(
            (ratios[0] - 1.0).abs() < 1e-12 && (ratios[1] - 1.5).abs() < 1e-12,
            "{ratios:?}"
        );
        // Paired on the same surfaces: no spread, so an interval of one point.
        assert!((s.points[1].low - 1.5).abs() < 1e-9, "{:?}", s.points[1]);
        assert!(s.points[1].breakdown && !s.points[0].breakdown);
    }
    let departing: Vec<&LegendEntry> = map
        .legend
        .iter()
        .filter(|e| e.label.contains("departs between"))
        .collect();
    assert_eq!(departing.len(), 4, "{:?}", map.legend);
    assert!(map.legend.iter().any(|e| e.swatch == Swatch::Ring));
    // The particle size over d*: W/(dN*₊/ds) is ω d_p³.
    let first = &map.panels[1].series[0].points[0];
    assert!(first.y.is_finite() && first.y > 0.0);
    assert!(map
        .to_csv()
        .lines()
        .next()
        .unwrap()
        .ends_with(",hollow,no_wear,breakdown"));
}

#[test]
fn the_figures_and_the_aggregated_table_give_one_mean_per_setting() {
    // Seeds 2 and 3 are not run in: the fit window's means are over seed 1 in both.
    let (results, tidy) = decaying(REDUCED);
    let means = StudyTable::of(tidy.clone()).means().clone();
    let figures = study_figures(
        &StudyTable::of(tidy.clone()),
        &results,
        None,
        Some(&["fig4".to_string()]),
    )
    .unwrap();
    let wear = &figures[0].panels[0];
    let labels = crate::output::curve_labels(&tidy);
    let col = |name: &str| means.column(name).unwrap();
    let (curve, pressure, area, w, pairs, kept) = (
        col("curve"),
        col("nominal_pressure"),
        col("nominal_area"),
        col("wear_rate_mean"),
        col("surface_pairs"),
        col("fit_window_pairs"),
    );
    for row in &means.rows {
        assert_eq!((row[pairs].number(), row[kept].number()), (3.0, 1.0));
        let label = &labels[row[curve].number() as usize];
        let series = wear.series.iter().find(|s| &s.label == label).unwrap();
        let point = series.points.iter().find(|q| q.x == row[pressure].number()).unwrap();
        assert_eq!(point.y, row[w].number() / row[area].number(), "{label}");
    }
}
