//! The series figures of sliding runs outside a study: from tables a front end holds (Python's
//! `slide` results) or from a `slide` run folder.

use std::borrow::Cow;

use crate::config::Units;
use crate::error::{Error, Result};
use crate::output::{distinct, number, steps_of_rows, Cell, SeriesRow, Table};
use crate::sliding::WearResult;

use super::labels::Shown;
use super::model::Figure;
use super::series::SeriesOf;
use super::{spec, Build, FigureSpec, Layout, FIGURES};

/// One sliding run as the series figures take it outside a study ([`run_figure`]): its series (the
/// columns of [`SeriesRow`]: `series.csv`, the data frame of Python's `slide`, a job's series) and
/// its results (the columns of [`WearResult`] and `load`: `summary["results"]` of a run, or the
/// job's rows of a study's tidy table), and its name in the memory figure's legend.
pub struct RunTables<'a> {
    pub label: &'a str,
    pub series: &'a Table,
    /// Required by the figures that draw a fit (fig3, memory); appB without them names each curve
    /// by its fracture energy instead of its d*.
    pub results: Option<&'a Table>,
}

/// A result row with its load, as a run's summary and a study's tidy table give it.
#[derive(serde::Deserialize)]
pub(super) struct ResultOfLoad {
    pub(super) load: f64,
    #[serde(flatten)]
    pub(super) result: WearResult,
}

/// The load of a run's series rows that `load` names (matched as Python's `np.isclose(…,
/// rtol=1e-12)`: a load typed back from its printed form), or the series' last.
pub(super) fn load_of_series(rows: &[SeriesRow], load: Option<f64>) -> Result<f64> {
    let loads = distinct(rows.iter().map(|r| r.load));
    match load {
        None => loads
            .last()
            .copied()
            .ok_or_else(|| Error::param("series", "it has no row")),
        Some(asked) => loads
            .iter()
            .copied()
            .find(|&l| (l - asked).abs() <= 1e-12 * asked.abs())
            .ok_or_else(|| {
                let have: Vec<String> = loads.iter().map(|&l| number(l)).collect();
                Error::param(
                    "load",
                    format!(
                        "the series has no load {}: its loads are {}",
                        number(asked),
                        have.join(", ")
                    ),
                )
            }),
    }
}

/// The results of `run` at `load`; without results, where the figure does not `need` them, the
/// fracture energies of the series in its order with nothing fitted (and d* unknown). An error
/// where none is left.
pub(super) fn results_of_run(run: &RunTables, rows: &[SeriesRow], load: f64, need: bool) -> Result<Vec<WearResult>> {
    let results: Vec<WearResult> = match run.results {
        Some(table) => table
            .records::<ResultOfLoad>("results")?
            .into_iter()
            .filter(|r| r.load == load)
            .map(|r| r.result)
            .collect(),
        None if !need => distinct(rows.iter().filter(|r| r.load == load).map(|r| r.fracture_energy))
            .into_iter()
            .map(|g| WearResult {
                fracture_energy: g,
                critical_diameter: f64::NAN,
                ..WearResult::default()
            })
            .collect(),
        None => Vec::new(),
    };
    if results.is_empty() {
        return Err(Error::param(
            "results",
            format!(
                "{} of load {}: pass the run's results (`summary[\"results\"]` of a run, or the job's rows of the \
                 tidy table), whose fits (W and its intercept, the fit window, ℓ) the figure draws",
                if run.results.is_some() {
                    "none of its rows is"
                } else {
                    "none given, and the figure needs those"
                },
                number(load)
            ),
        ));
    }
    Ok(results)
}

/// The series of `run`, one of `runs`, at load `load` (default: its series' last) as the series
/// figures take it; without results, an error where the figure `needs_results`.
pub(super) fn series_of_run<'a>(
    run: &RunTables,
    runs: usize,
    load: Option<f64>,
    needs_results: bool,
    shown: Shown,
) -> Result<SeriesOf<'a>> {
    let rows: Vec<SeriesRow> = run.series.records("series")?;
    let load = load_of_series(&rows, load)?;
    let results = results_of_run(run, &rows, load, needs_results)?;
    let energies: Vec<f64> = results.iter().map(|w| w.fracture_energy).collect();
    let steps = steps_of_rows(&rows, load, &energies)?;
    let who = format!("F_N = {} {}", number(load), shown.unit("load"));
    Ok(SeriesOf {
        load,
        steps: Cow::Owned(steps),
        results: Cow::Owned(results),
        setting: if runs > 1 {
            format!("{runs} runs — {who}")
        } else {
            who.clone()
        },
        who,
        name: run.label.to_string(),
    })
}

/// A series figure — `fig3` (V(s) with the fitted line), `appB` (N*₊, N*, N*₋) or `memory` (N₀(s)
/// with its fit) — of sliding runs outside a study, as Python's `wearsim.plot.wear_volume`,
/// `particle_counts` and `memory` draw them: at load `load` (default: the last of the first run's
/// series), per fracture energy of the results at that load; fig3 and appB draw the first run,
/// memory every run, as a study's memory figure draws every surface pair of a setting. The lines
/// are the results' fits (W and its intercept, the fit window, ℓ): a figure fits nothing of its own.
pub fn run_figure(entry: &str, runs: &[RunTables], load: Option<f64>, units: Units) -> Result<Figure> {
    let (spec, draw, fits) = match spec(entry) {
        Some(
            spec @ FigureSpec {
                build: Build::Series { draw, fits },
                ..
            },
        ) => (spec, *draw, *fits),
        _ => {
            let series: Vec<&str> = FIGURES
                .iter()
                .filter(|f| f.layout() == Layout::Series)
                .map(|f| f.name)
                .collect();
            return Err(Error::param(
                "figure",
                format!("{entry:?} is not a figure of one run's series: {}", series.join(", ")),
            ));
        }
    };
    let shown = Shown { system: units };
    let series: Vec<SeriesOf> = runs
        .iter()
        .map(|run| series_of_run(run, runs.len(), load, fits, shown))
        .collect::<Result<_>>()?;
    let first = series.first().ok_or_else(|| Error::param("series", "no run given"))?;
    Ok(spec.stamp(vec![draw(first, &series, shown)]).remove(0))
}

/// The series figures (fig3, appB, memory: [`run_figure`]) of one `slide` run folder, from its
/// `series.csv` and the results of its `summary.json`, for every load of the run (names suffixed
/// `_load1`, `_load2`, … in the run's order where it has several), in the run's units. An error
/// names the file that is missing or not a sliding run's (an estimate's folder has no series).
pub fn slide_folder_figures(dir: &std::path::Path) -> Result<Vec<Figure>> {
    let summary_path = dir.join("summary.json");
    let summary: serde_json::Value = serde_json::from_str(&crate::io::read_text(&summary_path)?)
        .map_err(|e| Error::file(&summary_path, format!("not a run's summary ({e})")))?;
    if summary
        .get("model")
        .and_then(|m| m.as_str())
        .is_some_and(|m| m != "sliding")
    {
        return Err(Error::file(
            &summary_path,
            "the summary of a static estimate, which has no series to draw (`wearsim plot` draws a `slide` folder; \
             a study's estimates are drawn by `wearsim study plot`)",
        ));
    }
    let units: Units = serde_json::from_value(summary["units"].clone())
        .map_err(|e| Error::file(&summary_path, format!("no `units` of a run ({e})")))?;
    let records = summary["results"].as_array().ok_or_else(|| {
        Error::file(
            &summary_path,
            "no `results` of a sliding run: it is not the summary.json of `wearsim slide` (a study folder is drawn by \
             `wearsim study plot`)",
        )
    })?;
    let mut columns: Vec<String> = Vec::new();
    for r in records {
        for key in r.as_object().into_iter().flat_map(|o| o.keys()) {
            if !columns.contains(key) {
                columns.push(key.clone());
            }
        }
    }
    let results = Table {
        rows: records
            .iter()
            .map(|r| columns.iter().map(|c| Cell::of(&r[c])).collect())
            .collect(),
        columns,
    };
    let series_path = dir.join("series.csv");
    let series = Table::from_csv(&crate::io::read_text(&series_path)?)
        .map_err(|e| Error::file(&series_path, format!("not a run's series ({e})")))?;
    let loads = distinct(
        series
            .column("load")
            .map_or(Vec::new(), |c| series.rows.iter().map(|r| r[c].number()).collect()),
    );
    if loads.is_empty() {
        return Err(Error::file(
            &series_path,
            "no step of any load: the run has no series to draw",
        ));
    }
    let run = RunTables {
        label: "this run",
        series: &series,
        results: Some(&results),
    };
    let mut figures = Vec::new();
    for (i, &load) in loads.iter().enumerate() {
        for entry in ["fig3", "appB", "memory"] {
            let mut figure = run_figure(entry, std::slice::from_ref(&run), Some(load), units)?;
            if loads.len() > 1 {
                figure.name = format!("{}_load{}", figure.name, i + 1);
            }
            figures.push(figure);
        }
    }
    Ok(figures)
}
