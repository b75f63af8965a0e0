//! The series of a sliding run, one row per step and fracture energy: the columns of `series.csv`,
//! of the Python `slide`'s DataFrame and of a study job's series, declared once in [`SeriesRow`]
//! with their units ([`SeriesRow::UNITS`]) and built from a step's record by one builder
//! ([`SeriesRow::of_step`]); a study's job file keeps part of them per step ([`StepRow`]) and gives
//! its series back through the same builder.

use serde::{Deserialize, Serialize};

use crate::sliding::{LoadRun, StepRecord, WearResult};
use crate::wear::{StaticWear, StepWear};

/// One row of a sliding run's series (`series.csv` of `wearsim slide`, the DataFrame of the Python
/// `slide`): one step of one load for one fracture energy. The first nine columns are the paper's
/// record per step (§3), then the memory of the initial contact and the static model at this step;
/// `iterations` and `residual` are the contact solver's. A column is a field here and its unit an
/// entry of [`SeriesRow::UNITS`] (a test fails otherwise); [`SeriesRow::of_step`] fills it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct SeriesRow {
    /// Normal load F_N.
    pub load: f64,
    /// Fracture energy 𝒢.
    pub fracture_energy: f64,
    /// Sliding distance s in the run's length unit.
    pub s: f64,
    /// Number of junctions N.
    pub junctions: usize,
    /// Real contact area as a fraction of the apparent area Lx·Ly.
    pub contact_area: f64,
    /// N*: junctions with d_i ≥ d* at this step.
    pub n_critical: usize,
    /// N*₊: particles formed so far, s = 0 included.
    pub n_formed: usize,
    /// N*₋ = N*₊ − N*.
    pub n_shrunk: i64,
    /// V: wear volume so far, s = 0 included.
    pub volume: f64,
    /// Junctions descending from a junction present at s = 0 (the memory of the initial contact,
    /// paper §3).
    pub initial_junctions: usize,
    /// Static model on this step's contact map: k_static and W_static/ω (paper §2); a study's job
    /// file keeps k_static only, so W_static/ω is empty in a job's series.
    pub static_wear_coefficient: f64,
    pub static_wear_rate: Option<f64>,
    /// Contact solver iterations of this step (empty in a job's series: job files do not keep it).
    pub iterations: Option<usize>,
    /// Contact solver residual of this step (empty in a job's series).
    pub residual: Option<f64>,
    /// Junctions that wrap the periodic box at this step (full contact, a band across the box):
    /// no particles of the model (paper §3), yet counted in N, V and k_static.
    pub wrapping_junctions: usize,
    /// Junctions of this step that share pixels with two or more junctions of the previous step:
    /// junctions merging, the sign of the paper's high-load breakdown (appendix C); empty in the
    /// series of a job file written before it was kept (and in a `series.csv` written before, read
    /// back).
    #[serde(default)]
    pub merged_junctions: Option<usize>,
    /// The largest junction's equivalent diameter over the box's shorter side (empty as above).
    #[serde(default)]
    pub largest_junction: Option<f64>,
}

impl SeriesRow {
    /// The unit of every column, declared beside the columns: (column, reduced units, SI units);
    /// "" for counts, "1" for ratios. Read by `output::unit_of` for every table and summary.
    pub const UNITS: &'static [(&'static str, &'static str, &'static str)] = &[
        ("load", "E L²", "N"),
        ("fracture_energy", "E L", "J/m²"),
        ("s", "L", "m"),
        ("junctions", "", ""),
        ("contact_area", "1 (fraction of Lx·Ly)", "1 (fraction of Lx·Ly)"),
        ("n_critical", "", ""),
        ("n_formed", "", ""),
        ("n_shrunk", "", ""),
        ("volume", "L³", "m³"),
        ("initial_junctions", "", ""),
        ("static_wear_coefficient", "1", "1"),
        ("static_wear_rate", "L²", "m²"),
        ("iterations", "", ""),
        ("residual", "1", "1"),
        ("wrapping_junctions", "", ""),
        ("merged_junctions", "", ""),
        (
            "largest_junction",
            "1 (fraction of the box's shorter side)",
            "1 (fraction of the box's shorter side)",
        ),
    ];

    /// The row of one step of a load `load` for the fracture energy `fracture_energy`, the
    /// `energy`-th of the run: the one builder of every series.
    pub fn of_step(load: f64, fracture_energy: f64, step: &StepRecord, energy: usize) -> Self {
        let wear = &step.wear[energy];
        let statics = &step.statics[energy];
        SeriesRow {
            load,
            fracture_energy,
            s: step.s,
            junctions: step.junctions,
            contact_area: step.contact_area,
            n_critical: wear.n_critical,
            n_formed: wear.n_formed,
            n_shrunk: wear.n_shrunk(),
            volume: wear.volume,
            initial_junctions: step.initial_junctions,
            static_wear_coefficient: statics.wear_coefficient,
            static_wear_rate: Some(statics.wear_rate_over_omega),
            iterations: Some(step.iterations),
            residual: Some(step.residual),
            wrapping_junctions: step.wrapping_junctions,
            merged_junctions: step.merged_junctions,
            largest_junction: step.largest_junction,
        }
    }
}

/// The series of one load's steps: fracture energy by fracture energy (as `results` lists them),
/// then step.
fn rows_of_load(load: f64, results: &[WearResult], steps: &[StepRecord], rows: &mut Vec<SeriesRow>) {
    for (e, w) in results.iter().enumerate() {
        for st in steps.iter().filter(|st| st.wear.len() > e && st.statics.len() > e) {
            rows.push(SeriesRow::of_step(load, w.fracture_energy, st, e));
        }
    }
}

/// The series of every load and fracture energy: load by load, then fracture energy, then step.
pub fn series_rows(runs: &[LoadRun]) -> Vec<SeriesRow> {
    let mut rows = Vec::new();
    for r in runs {
        rows_of_load(r.load, &r.results, &r.steps, &mut rows);
    }
    rows
}

/// One step of a study's job file: the columns of the series it keeps, those of every fracture
/// energy as lists in the material's order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StepRow {
    pub s: f64,
    pub junctions: usize,
    /// Junctions that wrap the periodic box (no particles of the model, paper §3); 0 in job files
    /// written before it existed.
    #[serde(default)]
    pub wrapping_junctions: usize,
    pub contact_area: f64,
    pub initial_junctions: usize,
    /// Junctions merging and the largest junction against the box (see [`SeriesRow`]); absent in
    /// job files written before they were kept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merged_junctions: Option<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub largest_junction: Option<f64>,
    pub n_critical: Vec<usize>,
    pub n_formed: Vec<usize>,
    pub volume: Vec<f64>,
    pub static_wear_coefficient: Vec<f64>,
}

impl From<&StepRecord> for StepRow {
    fn from(r: &StepRecord) -> Self {
        Self {
            s: r.s,
            junctions: r.junctions,
            wrapping_junctions: r.wrapping_junctions,
            contact_area: r.contact_area,
            initial_junctions: r.initial_junctions,
            merged_junctions: r.merged_junctions,
            largest_junction: r.largest_junction,
            static_wear_coefficient: r.statics.iter().map(|w| w.wear_coefficient).collect(),
            n_critical: r.wear.iter().map(|w| w.n_critical).collect(),
            n_formed: r.wear.iter().map(|w| w.n_formed).collect(),
            volume: r.wear.iter().map(|w| w.volume).collect(),
        }
    }
}

impl From<&StepRow> for crate::sliding::BreakdownStep {
    /// What the breakdown measures read of a job file's step (`sliding::LoadBreakdown::of_steps`).
    fn from(r: &StepRow) -> Self {
        Self {
            junctions: r.junctions,
            contact_area: r.contact_area,
            merged_junctions: r.merged_junctions,
            largest_junction: r.largest_junction,
        }
    }
}

impl StepRow {
    /// The step's record as far as the job file keeps it, for [`SeriesRow::of_step`]: what it does
    /// not keep (the offset, the solver's iterations and residual, W_static/ω and the static N*) is
    /// NaN or 0, and [`job_series_rows`] leaves those columns empty. Fracture energies whose lists
    /// are cut short are left out.
    fn record(&self) -> StepRecord {
        let energies = [
            self.n_critical.len(),
            self.n_formed.len(),
            self.volume.len(),
            self.static_wear_coefficient.len(),
        ]
        .into_iter()
        .min()
        .unwrap_or(0);
        StepRecord {
            offset: 0,
            s: self.s,
            junctions: self.junctions,
            wrapping_junctions: self.wrapping_junctions,
            contact_area: self.contact_area,
            initial_junctions: self.initial_junctions,
            merged_junctions: self.merged_junctions,
            largest_junction: self.largest_junction,
            iterations: 0,
            residual: f64::NAN,
            wear: (0..energies)
                .map(|e| StepWear {
                    n_critical: self.n_critical[e],
                    n_formed: self.n_formed[e],
                    volume: self.volume[e],
                })
                .collect(),
            statics: self.static_wear_coefficient[..energies]
                .iter()
                .map(|&k| StaticWear {
                    wear_coefficient: k,
                    wear_rate_over_omega: f64::NAN,
                    critical_junctions: 0,
                })
                .collect(),
        }
    }
}

/// The series of a study job of load `load` (`wearsim.study.job_series`), ordered and built as a
/// sliding run's; the columns a job file does not keep (W_static/ω, the solver's iterations and
/// residual per step) are empty.
pub fn job_series_rows(load: f64, results: &[WearResult], steps: &[StepRow]) -> Vec<SeriesRow> {
    let records: Vec<StepRecord> = steps.iter().map(StepRow::record).collect();
    let mut rows = Vec::new();
    rows_of_load(load, results, &records, &mut rows);
    for row in &mut rows {
        row.static_wear_rate = None;
        row.iterations = None;
        row.residual = None;
    }
    rows
}

/// N₀(s_r)/N₀(0) of result `w` of a load whose steps are `steps`: as the result has it, or, for a
/// result written before it was kept, counted from the steps.
pub fn lineages_left(steps: &[StepRow], w: &WearResult) -> Option<f64> {
    w.initial_lineages_left
        .or_else(|| crate::sliding::lineages_left(steps.iter().map(|r| (r.s, r.initial_junctions)), w.fit_window_start))
}

/// Every distinct item once, in the order first given (a run's warnings, a series' loads, fracture
/// energies and sliding distances).
pub(crate) fn distinct<T: PartialEq>(items: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut out: Vec<T> = Vec::new();
    for item in items {
        if !out.contains(&item) {
            out.push(item);
        }
    }
    out
}

/// The steps of one load back from its series rows (the inverse of [`job_series_rows`]): the rows of
/// load `load`, one step per sliding distance in their order, with the counts and the volume of
/// each fracture energy of `energies` in its order. The error names a step that lacks one of them
/// (a series filtered by fracture energy, or the rows of another run).
pub fn steps_of_rows(rows: &[SeriesRow], load: f64, energies: &[f64]) -> crate::error::Result<Vec<StepRow>> {
    let mine: Vec<&SeriesRow> = rows.iter().filter(|r| r.load == load).collect();
    distinct(mine.iter().map(|r| r.s))
        .into_iter()
        .map(|s| {
            let at: Vec<&&SeriesRow> = mine.iter().filter(|r| r.s == s).collect();
            let first = at[0];
            let mut step = StepRow {
                s,
                junctions: first.junctions,
                wrapping_junctions: first.wrapping_junctions,
                contact_area: first.contact_area,
                initial_junctions: first.initial_junctions,
                merged_junctions: first.merged_junctions,
                largest_junction: first.largest_junction,
                n_critical: Vec::new(),
                n_formed: Vec::new(),
                volume: Vec::new(),
                static_wear_coefficient: Vec::new(),
            };
            for &g in energies {
                let r = at.iter().find(|r| r.fracture_energy == g).ok_or_else(|| {
                    crate::error::Error::param(
                        "series",
                        format!(
                            "the step at s = {s} of load {load} has no row of fracture energy {g}: pass the run's whole \
                             series with its results"
                        ),
                    )
                })?;
                step.n_critical.push(r.n_critical);
                step.n_formed.push(r.n_formed);
                step.volume.push(r.volume);
                step.static_wear_coefficient.push(r.static_wear_coefficient);
            }
            Ok(step)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_series_column_states_its_unit_once_beside_its_declaration() {
        let columns: Vec<String> = match serde_json::to_value(SeriesRow::default()).unwrap() {
            serde_json::Value::Object(map) => map.keys().cloned().collect(),
            other => panic!("a row serialises to an object, not {other}"),
        };
        let declared: Vec<&str> = SeriesRow::UNITS.iter().map(|u| u.0).collect();
        assert_eq!(declared, columns, "SeriesRow::UNITS lists the columns in their order");
    }

    #[test]
    fn a_job_files_steps_give_the_series_of_the_run_but_what_they_do_not_keep() {
        let step = StepRecord {
            offset: 3,
            s: 0.25,
            junctions: 9,
            wrapping_junctions: 1,
            contact_area: 0.125,
            initial_junctions: 4,
            merged_junctions: None,
            largest_junction: None,
            iterations: 12,
            residual: 1e-9,
            wear: vec![
                StepWear {
                    n_critical: 2,
                    n_formed: 5,
                    volume: 1e-6,
                },
                StepWear {
                    n_critical: 1,
                    n_formed: 2,
                    volume: 3e-7,
                },
            ],
            statics: vec![
                StaticWear {
                    wear_coefficient: 0.5,
                    wear_rate_over_omega: 0.01,
                    critical_junctions: 2,
                };
                2
            ],
        };
        let results = [1e-6, 2e-6].map(|g| WearResult {
            fracture_energy: g,
            ..WearResult::default()
        });
        let run = LoadRun {
            load: 1e-3,
            steps: vec![step.clone()],
            results: results.to_vec(),
            total_iterations: 12,
            max_iterations: 12,
            timing: Default::default(),
            warnings: Vec::new(),
        };
        let from_run = series_rows(&[run]);
        let from_job = job_series_rows(1e-3, &results, &[StepRow::from(&step)]);
        assert_eq!(from_run.len(), 2);
        for (a, b) in from_run.iter().zip(&from_job) {
            let kept = SeriesRow {
                static_wear_rate: None,
                iterations: None,
                residual: None,
                ..*a
            };
            assert_eq!(kept, *b);
            assert!(a.iterations == Some(12) && a.static_wear_rate == Some(0.01));
        }
        assert_eq!((from_run[1].fracture_energy, from_run[1].n_shrunk), (2e-6, 1));
    }
}
