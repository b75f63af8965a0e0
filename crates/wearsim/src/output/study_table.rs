//! A study's results as every output reads them, derived once: the tidy table (one row per job
//! and fracture energy), its unit system, its settings with their surface pairs, the pairs whose
//! fit-window results each setting's means are over (the run-in rule and its fallback, here only),
//! and the table of means. `results_aggregated.csv`, the figures, the findings' document and
//! Python's curves all take one [`StudyTable`], so that one quantity of one setting has one value.

use serde_json::json;

use crate::config::Units;
use crate::error::Result;

use super::jobs::{aggregate_over, settings, Settings, TidyRow, FIT_WINDOW_COLUMNS};
use super::tables::{Cell, Table};
use super::units::units_map;

/// A study's tidy table and what is derived from it ([`StudyTable::of`]).
#[derive(Debug, Clone, PartialEq)]
pub struct StudyTable {
    tidy: Table,
    units: Units,
    settings: Settings,
    fit_window_pairs: Vec<Vec<usize>>,
    means: Table,
}

impl StudyTable {
    /// The study of a tidy table (`results.csv`, [`TidyRow`]s), every derived part computed here.
    pub fn of(tidy: Table) -> Self {
        let units = tidy.units();
        let settings = settings(&tidy);
        let fit_window_pairs = fit_window_pairs(&tidy, &settings);
        let means = means(&tidy, &settings, &fit_window_pairs);
        Self {
            tidy,
            units,
            settings,
            fit_window_pairs,
            means,
        }
    }

    /// The tidy table: one row per job and fracture energy.
    pub fn tidy(&self) -> &Table {
        &self.tidy
    }

    /// The unit system of its columns (`units`, reduced where it has none).
    pub fn units(&self) -> Units {
        self.units
    }

    /// Its settings: every input but the surface pair, each with the rows of its pairs.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Per setting (in the order of [`StudyTable::settings`]), the rows whose fit-window results its
    /// means are over: those run in ([`crate::sliding::is_run_in`]; a row without a memory of the
    /// initial contact, such as a static estimate's, counts as run in), or every row of a setting
    /// where none is ([`averaged_pairs`]).
    pub fn fit_window_pairs(&self) -> &[Vec<usize>] {
        &self.fit_window_pairs
    }

    /// The means of its settings as every output gives them (`results_aggregated.csv`, the figures
    /// against load, Python's `wearsim.plot.curves`): the aggregate (mean, min, max, the 95 %
    /// interval of the mean over surface pairs) of the fit-window results over
    /// [`StudyTable::fit_window_pairs`] and of every other result over all pairs, with
    /// `fit_window_pairs` beside `surface_pairs`: how many pairs the fit-window results are over.
    pub fn means(&self) -> &Table {
        &self.means
    }

    /// Writes `results.csv` (tidy), `results_aggregated.csv` (the means) and `results.units.json`
    /// (the unit of every column that has one) into `dir`, together (a failure leaves the earlier
    /// files); returns the row counts of the two tables.
    pub fn write(&self, dir: &std::path::Path) -> Result<(usize, usize)> {
        let unit_map = units_map(
            self.units,
            self.tidy.columns.iter().chain(&self.means.columns).map(String::as_str),
        );
        let units_text =
            serde_json::to_string_pretty(&json!({"units": self.units, "columns": unit_map})).expect("plain data");
        let (tidy_csv, means_csv) = (self.tidy.to_csv(), self.means.to_csv());
        crate::io::write_texts_together(&[
            (&dir.join("results.csv"), &tidy_csv),
            (&dir.join("results_aggregated.csv"), &means_csv),
            (&dir.join("results.units.json"), &units_text),
        ])?;
        Ok((self.tidy.rows.len(), self.means.rows.len()))
    }
}

/// The surface pairs a setting's fit-window means are over, given whether each is run in: those
/// run in, or every pair where none is (the findings count such a setting as not run in, the
/// figures still show it). The one fallback of the study's means and of the findings' figures.
pub fn averaged_pairs(run_in: &[bool]) -> Vec<usize> {
    let kept: Vec<usize> = (0..run_in.len()).filter(|&i| run_in[i]).collect();
    if kept.is_empty() {
        (0..run_in.len()).collect()
    } else {
        kept
    }
}

/// Per setting, the rows of its pairs that [`averaged_pairs`] keeps.
fn fit_window_pairs(tidy: &Table, settings: &Settings) -> Vec<Vec<usize>> {
    let col = |name: &str| tidy.column(name);
    let (left, lengths) = (col("initial_lineages_left"), col("running_in_decay_lengths"));
    let number = |row: &[Cell], c: Option<usize>| c.map(|c| row[c].number()).filter(|x| x.is_finite());
    let run_in = |r: usize| crate::sliding::is_run_in(number(&tidy.rows[r], left), number(&tidy.rows[r], lengths));
    settings
        .groups
        .iter()
        .map(|group| {
            let flags: Vec<bool> = group.rows.iter().map(|&r| run_in(r)).collect();
            averaged_pairs(&flags).into_iter().map(|i| group.rows[i]).collect()
        })
        .collect()
}

/// The means: `tidy` with the fit-window results ([`FIT_WINDOW_COLUMNS`]) of the rows outside
/// `pairs` emptied, aggregated over `settings` (emptying result cells leaves the settings as they
/// are: results are no setting's key), with the `fit_window_pairs` count.
fn means(tidy: &Table, settings: &Settings, pairs: &[Vec<usize>]) -> Table {
    let fit: Vec<usize> = FIT_WINDOW_COLUMNS.iter().filter_map(|c| tidy.column(c)).collect();
    let mut kept = tidy.clone();
    for (group, pairs) in settings.groups.iter().zip(pairs) {
        for &r in group.rows.iter().filter(|&&r| !pairs.contains(&r)) {
            for &c in &fit {
                kept.rows[r][c] = Cell::Empty;
            }
        }
    }
    let mut table = aggregate_over(&kept, settings.clone());
    let at = table
        .column("pairs_with_warnings")
        .map_or(table.columns.len(), |c| c + 1);
    table.columns.insert(at, "fit_window_pairs".into());
    for (row, pairs) in table.rows.iter_mut().zip(pairs) {
        row.insert(at, Cell::Int(pairs.len() as i64));
    }
    table
}

/// Writes the results tables of a study's rows ([`StudyTable::write`]).
pub fn write_results_tables(dir: &std::path::Path, rows: &[TidyRow]) -> Result<(usize, usize)> {
    StudyTable::of(Table::of(rows)).write(dir)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_setting_with_no_pair_run_in_keeps_every_pair() {
        assert_eq!(averaged_pairs(&[true, false, true]), vec![0, 2]);
        assert_eq!(averaged_pairs(&[false, false]), vec![0, 1]);
        assert_eq!(averaged_pairs(&[]), Vec::<usize>::new());
    }
}
