//! Every column any table emits has a declared unit (a count's or a text's is declared too, as
//! ""): the series of a run and of a study job, the job file's steps, the tidy and aggregated
//! results tables, and the units blocks of a run's summary. A new column without a unit fails here.

use std::path::Path;

use wearsim::config::{RunConfig, Units};
use wearsim::output::{aggregate, columns, declared_unit, SeriesRow, StepRow, Table, TidyRow};
use wearsim::run::SlidingRun;

fn undeclared<'a>(columns: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    columns
        .into_iter()
        .filter(|c| {
            [Units::Reduced, Units::Si]
                .iter()
                .any(|&u| declared_unit(u, c).is_none())
        })
        .map(str::to_string)
        .collect()
}

#[test]
fn every_column_of_every_table_has_a_declared_unit() {
    let series = columns::<SeriesRow>();
    assert!(
        undeclared(series.iter().map(String::as_str)).is_empty(),
        "series: {:?}",
        undeclared(series.iter().map(String::as_str))
    );
    let tidy = Table::of(&[TidyRow::default()]);
    let aggregated = aggregate(&tidy);
    for (name, table) in [("results.csv", &tidy), ("results_aggregated.csv", &aggregated)] {
        let missing = undeclared(table.columns.iter().map(String::as_str));
        assert!(missing.is_empty(), "{name}: no unit for {missing:?}");
    }
    let step = StepRow {
        s: 0.0,
        junctions: 0,
        wrapping_junctions: 0,
        contact_area: 0.0,
        initial_junctions: 0,
        merged_junctions: None,
        largest_junction: None,
        n_critical: vec![],
        n_formed: vec![],
        volume: vec![],
        static_wear_coefficient: vec![],
    };
    let keys: Vec<String> = serde_json::to_value(step)
        .unwrap()
        .as_object()
        .unwrap()
        .keys()
        .cloned()
        .collect();
    let missing = undeclared(keys.iter().map(String::as_str));
    assert!(missing.is_empty(), "a job file's steps: no unit for {missing:?}");
    // The static estimate's results.csv and `estimate-check`'s comparison.csv.
    for (name, cols) in [
        ("an estimate's results.csv", columns::<wearsim::output::EstimateRow>()),
        ("comparison.csv", columns::<wearsim::study::compare::ComparisonRow>()),
    ] {
        let missing = undeclared(cols.iter().map(String::as_str));
        assert!(missing.is_empty(), "{name}: no unit for {missing:?}");
    }
}

#[test]
fn a_runs_summary_gives_the_unit_of_every_result_and_series_column_that_has_one() {
    let text = "[surface]\ngrid = 32\nlambda_lower = 0.125\nlambda_upper = 0.5\nrms_height = 0.01\nseed = 3\n\
                [material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n\
                fracture_energies = [0.25e-6]\n[sliding]\nloads = [2e-3]\n";
    let config = RunConfig::from_toml(text, Path::new(".")).unwrap();
    let outcome = SlidingRun::prepare(&config).unwrap().run(|_| {}).unwrap();
    let summary = outcome.summary();
    let series = &summary["units_of_series"];
    for c in columns::<SeriesRow>() {
        let unit = declared_unit(Units::Reduced, &c).unwrap();
        assert_eq!(series.get(&c).and_then(|v| v.as_str()).unwrap_or(""), unit, "{c}");
    }
    let results = summary["results"][0].as_object().unwrap();
    for key in results.keys() {
        let unit = declared_unit(Units::Reduced, key).unwrap_or_else(|| panic!("{key} has no unit"));
        assert_eq!(
            summary["units_of_results"]
                .get(key)
                .and_then(|v| v.as_str())
                .unwrap_or(""),
            unit,
            "{key}"
        );
    }
}
