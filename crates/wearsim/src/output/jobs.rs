//! Study job files and the results tables collected from them (tidy and aggregated).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::config::InputRecord;
use crate::error::{Error, Result};
use crate::estimate::EstimateResult;
use crate::model::WearModel;
use crate::sliding::{not_run_in, BreakdownStep, InitialContactMemory, LoadBreakdown, LoadOfRun, WearResult};

use super::provenance::Provenance;
use super::series::{job_series_rows, SeriesRow, StepRow};
use super::tables::{columns, Cell, Table};

/// The format of the job files this version writes; raised whenever what identifies a job or what
/// a job file holds changes (3: results hold `fit_window_start`, `wear_volume_intercept` and
/// `memory_fit_initial_junctions`).
pub const JOB_FORMAT: u32 = 3;

/// What a study's job file holds: which job it is (checked when the file is read back, so that a
/// file can never be attributed to another job), and its results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobResult {
    /// The job-file format ([`JOB_FORMAT`]); files of another format come from another version of
    /// wearsim and are not mixed with this one's.
    #[serde(default)]
    pub format: u32,
    pub provenance: Provenance,
    pub index: usize,
    pub material: String,
    /// Every input of the job.
    pub inputs: InputRecord,
    pub load: f64,
    pub flow_pressure: f64,
    pub effective_modulus: f64,
    pub results: Vec<WearResult>,
    /// Per step: s, junctions, contact area, memory; per fracture energy: n_critical, n_formed,
    /// volume and the static model.
    pub steps: Vec<StepRow>,
    pub total_iterations: usize,
    pub seconds: f64,
    /// What makes a result of this job under-resolved or undefined.
    pub warnings: Vec<String>,
    /// A job of the static estimate (`sliding.model = "estimate"`): the estimate of every
    /// fracture energy with its intervals; `results` then holds the estimate's W, k, dN*₊/ds, N*,
    /// N and static model in the sliding model's columns, and `steps` is empty. Absent for sliding jobs.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub estimates: Vec<EstimateResult>,
}

impl JobResult {
    /// The job file's text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("job results serialise")
    }

    /// Parses a job file's text, with the memory of the initial contact fitted again from its steps
    /// ([`JobResult::refit_memory`]).
    pub fn from_json(text: &str) -> std::result::Result<Self, serde_json::Error> {
        let mut job: JobResult = serde_json::from_str(text)?;
        job.refit_memory();
        Ok(job)
    }

    /// The memory of the initial contact (ℓ, its R² and N₀(0), the running-in in decay lengths, the
    /// lineages left) and the warning of a load not run in, computed again from the job's steps by
    /// this version's fit, [`InitialContactMemory::of_steps`]: a job file written by an earlier
    /// version (an unweighted ℓ fit) is judged as this version's run would be. The steps are what the
    /// run measured; these are fitted from them. A job of a model that takes no sliding step (the
    /// static estimate) is left as it is.
    pub fn refit_memory(&mut self) {
        let Some(fit_start) = self.results.first().map(|w| w.fit_window_start) else {
            return;
        };
        if !self.model().slides() {
            return;
        }
        let points: Vec<(f64, usize)> = self.steps.iter().map(|r| (r.s, r.initial_junctions)).collect();
        let memory = InitialContactMemory::of_steps(&points, fit_start);
        for w in &mut self.results {
            memory.apply_to(w);
        }
        let opening = not_run_in(self.load);
        let warning = memory.warning(self.load, fit_start, self.inputs.length);
        let at = self.warnings.iter().position(|m| m.starts_with(&opening));
        match (at, warning) {
            (Some(i), Some(m)) => self.warnings[i] = m,
            (Some(i), None) => {
                self.warnings.remove(i);
            }
            (None, Some(m)) => {
                // Where a run puts it: before the load's other warnings.
                let load = format!("F_N = {:.4e}", self.load);
                let i = self
                    .warnings
                    .iter()
                    .position(|m| m.starts_with(&load))
                    .unwrap_or(self.warnings.len());
                self.warnings.insert(i, m);
            }
            (None, None) => {}
        }
        self.refill_breakdown(fit_start);
    }

    /// The breakdown measures of the job's load over its fit window (appendix C), computed again
    /// from its steps as [`crate::sliding::LoadBreakdown::of_steps`] does in a run, with N*'s growth
    /// as the file (or the study's collection) gives it, and the load's breakdown warning made again.
    fn refill_breakdown(&mut self, fit_start: f64) {
        let from = fit_start - 1e-9 * fit_start.abs().max(f64::MIN_POSITIVE);
        let measures = LoadBreakdown::of_steps(self.steps.iter().filter(|r| r.s >= from).map(BreakdownStep::from));
        for w in &mut self.results {
            measures.apply_to(w);
        }
        crate::sliding::replace_warning(self.load, &self.results, &mut self.warnings);
    }
}

impl JobResult {
    /// The job's series (`wearsim.study.job_series`): fracture energy by fracture energy, then
    /// step, as the series of a sliding run is ordered, with its columns; those a job file does not
    /// keep (W_static/ω, the solver's iterations and residual per step) are empty.
    pub fn series_rows(&self) -> Vec<SeriesRow> {
        job_series_rows(self.load, &self.results, &self.steps)
    }

    /// The wear model that made it (its inputs record the model when it is not the default).
    pub fn model(&self) -> WearModel {
        self.inputs.model.unwrap_or_default()
    }
}

/// N*'s growth with load across a study's sliding jobs (appendix C,
/// [`crate::sliding::critical_junction_growth`]): the jobs that differ in the load alone (the same
/// surface pair, material and every other input) form one run of several loads, as in one
/// `slide`; each job's results gain `critical_junction_growth` and their count of breakdown
/// measures, and its breakdown warning is made again. Jobs of a model that takes no sliding step
/// (static estimates) are left out.
pub fn growth_across_jobs(jobs: &mut [JobResult]) {
    let mut runs: BTreeMap<String, Vec<LoadOfRun>> = BTreeMap::new();
    for job in jobs.iter_mut().filter(|j| j.model().slides()) {
        let key = format!(
            "{}\u{1f}{}",
            job.material,
            serde_json::to_string(&job.inputs).expect("plain data")
        );
        runs.entry(key).or_default().push(LoadOfRun {
            load: job.load,
            results: &mut job.results,
            warnings: &mut job.warnings,
        });
    }
    for loads in runs.values_mut() {
        crate::sliding::growth_across(loads);
    }
}

/// One row of a study's tidy table (`results.csv`): one job × fracture energy, with every input of
/// the job, the load and the results.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct TidyRow {
    pub job: usize,
    pub material: String,
    #[serde(flatten)]
    pub inputs: InputRecord,
    pub load: f64,
    /// The nominal pressure p_N = F_N/(Lx·Ly), the load axis of the paper's figures (in E).
    pub nominal_pressure: f64,
    /// The nominal area Lx·Ly of the box, which the figures divide rates by (per unit nominal area).
    pub nominal_area: f64,
    #[serde(flatten)]
    pub result: WearResult,
    pub flow_pressure: f64,
    /// The specific wear rate K = W/F_N (mm³/(N·m) in SI, 1/E in reduced units);
    /// empty with W.
    pub specific_wear_rate: Option<f64>,
    /// The contact severity S_c = p_N √h_rms / K_Ic of appendix F, with the mode-I fracture
    /// toughness K_Ic = √(𝒢 E/(1 − ν²)) of this row's 𝒢; the abscissa of the fit W = α S_cⁿ.
    /// Empty on measured surfaces (no h_rms among the inputs).
    pub contact_severity: Option<f64>,
    /// The job's warnings that concern this row (its fracture energy, or all of them), joined by
    /// "; "; empty when the result is well resolved.
    pub warnings: String,
}

impl TidyRow {
    /// The rows of one job file, one per fracture energy.
    pub fn of_job(result: &JobResult) -> Vec<TidyRow> {
        result
            .results
            .iter()
            .map(|w| {
                // A warning that names a fracture energy belongs to that row only.
                let tag = format!("𝒢 = {:.4e}", w.fracture_energy);
                let mine: Vec<&str> = result
                    .warnings
                    .iter()
                    .filter(|m| m.contains(&tag) || !m.contains("𝒢 = "))
                    .map(String::as_str)
                    .collect();
                let p = &result.inputs;
                let nominal_pressure = p.nominal_pressure(result.load);
                let toughness =
                    (w.fracture_energy * p.youngs_modulus / (1.0 - p.poisson_ratio * p.poisson_ratio)).sqrt();
                TidyRow {
                    job: result.index,
                    material: result.material.clone(),
                    inputs: result.inputs.clone(),
                    load: result.load,
                    nominal_pressure,
                    nominal_area: p.nominal_area(),
                    result: w.clone(),
                    flow_pressure: result.flow_pressure,
                    specific_wear_rate: w
                        .wear_rate
                        .map(|rate| super::units::specific_wear_rate(p.units, rate, result.load)),
                    contact_severity: p.rms_height.map(|h| nominal_pressure * h.sqrt() / toughness),
                    warnings: mine.join("; "),
                }
            })
            .collect()
    }
}

/// Columns of the tidy table that vary between surface pairs of one setting and are averaged over
/// in the aggregated table: the results.
fn result_columns() -> Vec<String> {
    let mut c: Vec<String> = columns::<WearResult>()
        .into_iter()
        .filter(|c| c != "fracture_energy")
        .collect();
    c.push("flow_pressure".into());
    c.push("specific_wear_rate".into());
    c
}

/// The rows of a tidy table that are runs of the paper's sliding model, and how many rows were left
/// out. A row is kept by what its model is (`sliding.model` names a model that
/// [feeds the findings](WearModel::feeds_findings); an empty cell, or no such column, is the
/// default model): the static estimate's rows, and those of a model name not known here, are left
/// out. The paper's findings and the fits of appendix F are about the sliding model, so they read
/// these rows only.
pub fn sliding_rows(tidy: &Table) -> (Table, usize) {
    let mut sliding = tidy.clone();
    let Some(m) = tidy.column("sliding.model") else {
        return (sliding, 0);
    };
    sliding.rows.retain(|r| WearModel::in_findings(&r[m].text()));
    let left_out = tidy.rows.len() - sliding.rows.len();
    (sliding, left_out)
}

/// Columns that neither identify a setting nor are averaged: the job index, the seed, the warnings.
pub const NOT_A_SETTING: [&str; 3] = ["job", "surface.seed", "warnings"];

/// Columns that name no curve of the paper's figures (a setting against load): the load and what
/// follows from it with the setting's other inputs, which change along a curve, and the nominal area
/// Lx·Ly, which follows from the box (its inputs name the curve) and is no setting of its own.
pub const ALONG_A_CURVE: [&str; 4] = ["load", "nominal_pressure", "contact_severity", "nominal_area"];

/// The curves of a table of settings (tidy or aggregated): the grouping of every figure of the
/// paper that draws a quantity against load.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Curves {
    /// Per row of the table, the index of its curve: its setting (every column but those
    /// [`NOT_A_SETTING`], the results and those [`ALONG_A_CURVE`]), numbered in order of first
    /// appearance.
    pub index: Vec<usize>,
    /// The setting columns that tell the curves apart (take more than one value), in table order:
    /// the study's axes but the load, what a curve's label names; a named material's properties
    /// (`material.*` columns with one value per material) are left to its name.
    pub settings: Vec<String>,
}

/// Whether a column of a tidy or aggregated table is a setting that names a curve: neither
/// [`NOT_A_SETTING`] nor [`ALONG_A_CURVE`], nor a result (`results` lists them), nor a column the
/// aggregation adds.
fn names_a_curve(column: &str, results: &[String]) -> bool {
    let added = [
        "curve",
        "surface_pairs",
        "pairs_with_warnings",
        "fit_window_pairs",
        "interval_method",
    ];
    !NOT_A_SETTING.contains(&column)
        && !ALONG_A_CURVE.contains(&column)
        && !added.contains(&column)
        && !results
            .iter()
            .any(|r| column == r || AGGREGATE_SUFFIXES.iter().any(|s| column == format!("{r}{s}")))
}

/// The curves of a tidy or aggregated table ([`Curves`]).
pub fn curves(table: &Table) -> Curves {
    let results = result_columns();
    let keys: Vec<usize> = (0..table.columns.len())
        .filter(|&i| names_a_curve(&table.columns[i], &results))
        .collect();
    let mut numbers: BTreeMap<Vec<String>, usize> = BTreeMap::new();
    let index = table
        .rows
        .iter()
        .map(|row| {
            let key: Vec<String> = keys.iter().map(|&k| row[k].text()).collect();
            let next = numbers.len();
            *numbers.entry(key).or_insert(next)
        })
        .collect();
    let varying: Vec<usize> = keys
        .into_iter()
        .filter(|&k| table.rows.iter().any(|r| r[k] != table.rows[0][k]))
        .collect();
    // A named material stands for its properties: a `material.*` column that takes one value per
    // material does not tell its curves apart beyond the name.
    let material = table.column("material").filter(|m| varying.contains(m));
    let by_material = |k: usize| {
        material.is_some_and(|m| {
            table.columns[k].starts_with("material.")
                && table
                    .rows
                    .iter()
                    .all(|r| table.rows.iter().filter(|o| o[m] == r[m]).all(|o| o[k] == r[k]))
        })
    };
    let settings = varying
        .iter()
        .filter(|&&k| !by_material(k))
        .map(|&k| table.columns[k].clone())
        .collect();
    Curves { index, settings }
}

/// What Figs. 4c and 5c of the paper compare of a curve: its d*, τ̃ and 𝒢.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveMaterial {
    pub critical_diameter: f64,
    pub shear_strength: f64,
    pub fracture_energy: f64,
}

/// The groups of curves of (nearly) equal d* that Figs. 4c and 5c of the paper compare: curves
/// sorted by d*, a group holding those within `1 + tolerance` of its smallest d*, kept when it has
/// two curves or more that differ in τ̃ or 𝒢. Indices into `curves`, each group by increasing d*.
pub fn equal_critical_diameter(curves: &[CurveMaterial], tolerance: f64) -> Vec<Vec<usize>> {
    let mut sorted: Vec<usize> = (0..curves.len()).collect();
    sorted.sort_by(|&a, &b| curves[a].critical_diameter.total_cmp(&curves[b].critical_diameter));
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for i in sorted {
        match groups.last_mut() {
            Some(g) if curves[i].critical_diameter <= (1.0 + tolerance) * curves[g[0]].critical_diameter => g.push(i),
            _ => groups.push(vec![i]),
        }
    }
    groups
        .into_iter()
        .filter(|g| {
            let first = curves[g[0]];
            g.len() >= 2
                && g.iter().any(|&i| {
                    curves[i].shear_strength != first.shear_strength
                        || curves[i].fracture_energy != first.fracture_energy
                })
        })
        .collect()
}

/// The job whose series a study's figures show when none is asked for (Fig. 3, appendix B, the
/// memory of the initial contact): the one that formed the most particles in its fit window, for
/// any fracture energy, the lowest job index among equals. `particles` holds (job index,
/// particles in the fit window) per job and fracture energy, as the tidy table's rows do; `None`
/// without rows.
pub fn series_job(particles: impl IntoIterator<Item = (usize, usize)>) -> Option<usize> {
    particles
        .into_iter()
        .min_by_key(|&(job, n)| (std::cmp::Reverse(n), job))
        .map(|(job, _)| job)
}

/// Result columns that the aggregated table also sums over the surface pairs, as `{column}_total`
/// with its exact Poisson interval: the particles in the fit window, the count that a comparison of
/// two settings with few particles tests (two Poisson rates).
pub const TOTALLED: [&str; 1] = ["particles_in_fit"];

/// The statistics the aggregated table gives of every result column over the surface pairs, as
/// `{column}{suffix}`: the mean, the extremes and the 95 % interval of the mean.
pub const STATISTICS: [&str; 5] = ["_mean", "_min", "_max", "_ci_low", "_ci_high"];

/// The suffixes of the columns the aggregated table adds to a result column (its [`STATISTICS`],
/// and for those [`TOTALLED`] the sum and its interval).
pub const AGGREGATE_SUFFIXES: [&str; 8] = [
    "_mean",
    "_min",
    "_max",
    "_ci_low",
    "_ci_high",
    "_total",
    "_total_ci_low",
    "_total_ci_high",
];

/// How the aggregated table's intervals are computed, as its `interval_method` column states it.
pub fn interval_method() -> String {
    format!(
        "{:.0} % confidence interval of the mean over surface pairs, {} (n - 1 degrees of freedom; empty with one \
         pair); {}_total: {}",
        crate::stats::LEVEL * 100.0,
        crate::stats::Method::StudentT.name(),
        TOTALLED[0],
        crate::stats::Method::Poisson.name()
    )
}

/// The settings of a tidy table: the columns that identify one (every column but the job index,
/// the seed, the warnings and the results) and, per setting in order of first appearance, its key
/// cells, its curve ([`curves`]) and the indices of its rows (one per surface pair). The grouping
/// of the aggregated table and of the findings.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub key_columns: Vec<usize>,
    /// The result columns, whose values vary between the surface pairs of a setting.
    pub value_columns: Vec<usize>,
    pub groups: Vec<SettingRows>,
}

/// One setting of a tidy table ([`Settings`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SettingRows {
    pub key: Vec<Cell>,
    pub curve: usize,
    pub rows: Vec<usize>,
}

/// The settings of a tidy table ([`Settings`]).
pub fn settings(tidy: &Table) -> Settings {
    let values = result_columns();
    let value_columns: Vec<usize> = values.iter().filter_map(|c| tidy.column(c)).collect();
    let key_columns: Vec<usize> = (0..tidy.columns.len())
        .filter(|i| !value_columns.contains(i) && !NOT_A_SETTING.contains(&tidy.columns[*i].as_str()))
        .collect();
    let curve_of_row = curves(tidy).index;
    let mut order: BTreeMap<Vec<String>, usize> = BTreeMap::new();
    let mut groups: Vec<SettingRows> = Vec::new();
    for (r, (row, &curve)) in tidy.rows.iter().zip(&curve_of_row).enumerate() {
        let key: Vec<Cell> = key_columns.iter().map(|&i| row[i].clone()).collect();
        let text: Vec<String> = key.iter().map(Cell::text).collect();
        let g = *order.entry(text).or_insert_with(|| {
            groups.push(SettingRows {
                key,
                curve,
                rows: Vec::new(),
            });
            groups.len() - 1
        });
        groups[g].rows.push(r);
    }
    Settings {
        key_columns,
        value_columns,
        groups,
    }
}

/// The statistics of one result column over the surface pairs of a setting, in the order of
/// [`STATISTICS`] (then the total and its Poisson interval when `totalled`); empty cells where the
/// column is undefined in every pair, and an empty interval with one pair.
fn statistics(v: &[f64], totalled: bool) -> Vec<Cell> {
    let cells = if totalled { 8 } else { 5 };
    if v.is_empty() {
        return vec![Cell::Empty; cells];
    }
    let sum = v.iter().sum::<f64>();
    let mean = sum / v.len() as f64;
    let min = v.iter().copied().fold(f64::INFINITY, f64::min);
    let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut line = vec![Cell::Float(mean), Cell::Float(min), Cell::Float(max)];
    match crate::stats::mean_interval(v) {
        Some(i) => line.extend([Cell::Float(i.low), Cell::Float(i.high)]),
        None => line.extend([Cell::Empty, Cell::Empty]),
    }
    if totalled {
        let count = crate::stats::poisson_interval(sum.round().max(0.0) as u64);
        line.extend([Cell::Float(sum), Cell::Float(count.low), Cell::Float(count.high)]);
    }
    line
}

/// The aggregated table of a tidy table: one row per setting ([`settings`]), then `curve`, the index
/// of the row's curve ([`curves`]: its setting but the load, the one grouping every figure uses),
/// the number of surface pairs, the number of them with a warning, and the statistics of every
/// result column over the pairs ([`STATISTICS`]: mean, min, max and the 95 % Student-t interval of
/// the mean; for those [`TOTALLED`] also the sum, `_total`, with its exact Poisson interval), and
/// last `interval_method`, the intervals' method in words. Rows keep the order in which settings
/// first appear; undefined results (empty cells) are left out of the statistics.
pub fn aggregate(tidy: &Table) -> Table {
    aggregate_over(tidy, settings(tidy))
}

/// [`aggregate`] of `tidy` over its settings `found` (computed once by the caller).
pub(crate) fn aggregate_over(tidy: &Table, found: Settings) -> Table {
    let warnings = tidy.column("warnings");
    let mut columns: Vec<String> = found.key_columns.iter().map(|&i| tidy.columns[i].clone()).collect();
    columns.push("curve".into());
    columns.push("surface_pairs".into());
    columns.push("pairs_with_warnings".into());
    for &i in &found.value_columns {
        let c = &tidy.columns[i];
        columns.extend(STATISTICS.iter().map(|s| format!("{c}{s}")));
        if TOTALLED.contains(&c.as_str()) {
            columns.extend(["_total", "_total_ci_low", "_total_ci_high"].map(|s| format!("{c}{s}")));
        }
    }
    columns.push("interval_method".into());
    let method = interval_method();
    let rows = found
        .groups
        .into_iter()
        .map(|group| {
            let members: Vec<&Vec<Cell>> = group.rows.iter().map(|&r| &tidy.rows[r]).collect();
            let mut line = group.key;
            line.push(Cell::Int(group.curve as i64));
            line.push(Cell::Int(members.len() as i64));
            let warned = warnings.map_or(0, |w| members.iter().filter(|m| !m[w].text().is_empty()).count());
            line.push(Cell::Int(warned as i64));
            for &i in &found.value_columns {
                let v: Vec<f64> = members.iter().map(|m| m[i].number()).filter(|x| !x.is_nan()).collect();
                line.extend(statistics(&v, TOTALLED.contains(&tidy.columns[i].as_str())));
            }
            line.push(Cell::Text(method.clone()));
            line
        })
        .collect();
    Table { columns, rows }
}

/// The results of a sliding run measured over its fit window (after running-in): what the findings
/// read on the run-in surface pairs only. The breakdown measures, also over the fit window, are not
/// among them: a pair not run in still shows where its contact merges (the figures ring a load where
/// any pair is in the breakdown regime).
pub const FIT_WINDOW_COLUMNS: [&str; 10] = [
    "wear_rate",
    "wear_rate_r2",
    "wear_volume_intercept",
    "wear_coefficient",
    "particle_rate",
    "wear_rate_estimate",
    "particles_in_fit",
    "junctions_mean",
    "critical_junctions_mean",
    "critical_residence",
];

/// Reads a job file, with the fix in the message when it cannot be used.
pub fn read_job_file(path: &std::path::Path) -> Result<JobResult> {
    let text = crate::io::read_text(path)?;
    JobResult::from_json(&text).map_err(|e| {
        Error::file(
            path,
            format!(
                "not a readable job result ({e}); it was cut short or written by another version of wearsim: delete \
                 it and run the study again to recompute that job"
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Units;
    use crate::output::units::unit_of;

    #[test]
    fn columns_come_from_the_row_types() {
        // The series' columns are pinned beside their units (`output::series`).
        let tidy = columns::<TidyRow>();
        assert_eq!(&tidy[..3], ["job", "material", "units"]);
        assert!(tidy.contains(&"surface.seed".to_string()) && tidy.contains(&"wear_rate".to_string()));
        assert_eq!(tidy.last().map(String::as_str), Some("warnings"));
    }

    #[test]
    fn aggregation_groups_over_seeds_and_skips_undefined_results() {
        let row = |job: usize, seed: u64, wear_rate: Option<f64>| TidyRow {
            job,
            material: "m".into(),
            inputs: InputRecord {
                seed: Some(seed),
                ..InputRecord::default()
            },
            load: 1e-3,
            nominal_pressure: 1e-3,
            nominal_area: 1.0,
            contact_severity: None,
            result: WearResult {
                wear_rate,
                particles_in_fit: 4 * job + 1,
                ..WearResult::default()
            },
            flow_pressure: 0.05,
            specific_wear_rate: wear_rate.map(|w| w / 1e-3),
            warnings: if wear_rate.is_none() {
                "no particle".into()
            } else {
                String::new()
            },
        };
        let tidy = Table::of(&[row(0, 1, Some(1.0)), row(1, 2, Some(3.0)), row(2, 3, None)]);
        let agg = aggregate(&tidy);
        assert_eq!(agg.rows.len(), 1);
        assert_eq!(agg.rows[0][agg.column("curve").unwrap()], Cell::Int(0));
        let at = |name: &str| agg.rows[0][agg.column(name).unwrap()].clone();
        assert_eq!(
            (at("surface_pairs"), at("pairs_with_warnings")),
            (Cell::Int(3), Cell::Int(1))
        );
        assert_eq!(
            (at("wear_rate_mean"), at("wear_rate_min"), at("wear_rate_max")),
            (Cell::Float(2.0), Cell::Float(1.0), Cell::Float(3.0))
        );
        assert!(agg.column("surface.seed").is_none() && agg.column("job").is_none());
        // The particles summed over the pairs (1 + 5 + 9), beside their statistics; no other totals.
        assert_eq!(at("particles_in_fit_total"), Cell::Float(15.0));
        assert_eq!(at("particles_in_fit_max"), Cell::Float(9.0));
        assert_eq!(
            agg.columns.iter().filter(|c| c.ends_with("_total")).count(),
            TOTALLED.len()
        );
        // The 95 % interval of the mean over the two defined pairs (1 and 3: sd √2, t(1) = 12.706):
        // 2 ± 12.706; of the particles' mean (1, 5, 9: sd 4, t(2) = 4.303): 5 ± 4.303 · 4/√3; of
        // their total, exact Poisson: 15 → [8.395, 24.74].
        let close = |name: &str, want: f64, tol: f64| {
            let got = at(name).number();
            assert!((got - want).abs() < tol, "{name} = {got}, expected {want}");
        };
        close("wear_rate_ci_low", 2.0 - 12.706_204_7, 1e-5);
        close("wear_rate_ci_high", 2.0 + 12.706_204_7, 1e-5);
        close("particles_in_fit_ci_high", 5.0 + 4.302_652_7 * 4.0 / 3f64.sqrt(), 1e-5);
        close("particles_in_fit_total_ci_low", 8.3954, 1e-3);
        close("particles_in_fit_total_ci_high", 24.7402, 1e-3);
        assert!(at("interval_method").text().contains("Student t"));
        // Every added column has a unit, or is a count: none is left to a silent default.
        assert_eq!(unit_of(Units::Reduced, "wear_rate_ci_low"), "L²");
    }

    #[test]
    fn the_series_job_has_the_most_particles_and_the_lowest_index_among_equals() {
        assert_eq!(series_job([(0, 3), (0, 7), (1, 2), (2, 7), (3, 1)]), Some(0));
        assert_eq!(series_job([(5, 0), (4, 0)]), Some(4));
        assert_eq!(series_job([(0, 1), (1, 8), (1, 0)]), Some(1));
        assert_eq!(series_job(std::iter::empty()), None);
    }

    /// A job file of a 2 × 1 L box (E = 1, ν = 0.5, h_rms = 0.04) under F_N = 0.01 with 𝒢 = 3e-6.
    fn job(index: usize, load: f64, shear_strength: f64) -> JobResult {
        JobResult {
            format: JOB_FORMAT,
            provenance: Provenance::current(),
            index,
            material: "m".into(),
            inputs: InputRecord {
                length: 2.0,
                length_y: Some(1.0),
                rms_height: Some(0.04),
                youngs_modulus: 1.0,
                poisson_ratio: 0.5,
                shear_strength,
                ..InputRecord::default()
            },
            load,
            flow_pressure: 0.05,
            effective_modulus: 1.0,
            results: vec![WearResult {
                fracture_energy: 3e-6,
                ..WearResult::default()
            }],
            steps: Vec::new(),
            total_iterations: 0,
            seconds: 0.0,
            warnings: Vec::new(),
            estimates: Vec::new(),
        }
    }

    #[test]
    fn nominal_pressure_and_contact_severity_by_hand() {
        let row = &TidyRow::of_job(&job(0, 0.01, 0.01))[0];
        // p_N = F_N/(Lx·Ly) = 0.01/2; K_Ic = √(3e-6 · 1/(1 − 0.25)) = 2e-3; S_c = p_N √0.04 / K_Ic.
        assert!((row.nominal_pressure - 0.005).abs() < 1e-15);
        let s_c = row.contact_severity.unwrap();
        assert!((s_c - 0.005 * 0.2 / 2e-3).abs() < 1e-12, "S_c = {s_c}");
        assert_eq!(unit_of(Units::Reduced, "nominal_pressure"), "E");
        assert_eq!(unit_of(Units::Si, "contact_severity_mean"), "1");
        let measured = TidyRow::of_job(&JobResult {
            inputs: InputRecord {
                rms_height: None,
                ..job(0, 0.01, 0.01).inputs
            },
            ..job(0, 0.01, 0.01)
        });
        assert_eq!(measured[0].contact_severity, None);
    }

    /// Steps of one load: 40 lineages of s = 0 halving every 0.01 down to one that persists.
    fn decaying_steps() -> Vec<StepRow> {
        let step = |s: f64, initial_junctions: usize| StepRow {
            s,
            junctions: 40,
            wrapping_junctions: 0,
            contact_area: 0.1,
            initial_junctions,
            merged_junctions: None,
            largest_junction: None,
            volume: vec![0.0],
            static_wear_coefficient: vec![0.3],
            n_critical: vec![0],
            n_formed: vec![0],
        };
        [40, 20, 10, 5, 2, 1, 1, 1, 1]
            .iter()
            .enumerate()
            .map(|(i, &n)| step(0.01 * i as f64, n))
            .collect()
    }

    #[test]
    fn a_job_file_read_back_has_its_memory_fitted_again_from_its_steps() {
        // At s_r = 0.02, 10 of the 40 lineages are left.
        let steps = decaying_steps();
        let points: Vec<(f64, usize)> = steps.iter().map(|r| (r.s, r.initial_junctions)).collect();
        let expected = InitialContactMemory::of_steps(&points, 0.02);
        let mut current = WearResult {
            fit_window_start: 0.02,
            ..WearResult::default()
        };
        expected.apply_to(&mut current);
        // The breakdown measures, as a run gives them over its fit window (s ≥ 0.02).
        LoadBreakdown::of_steps(steps.iter().filter(|r| r.s >= 0.02 - 1e-12).map(BreakdownStep::from))
            .apply_to(&mut current);
        assert_eq!(current.breakdown_measures, Some(0));
        let written = JobResult {
            results: vec![current.clone()],
            steps,
            warnings: vec![
                "d* = 3.6 px: under-resolved".into(),
                expected.warning(0.01, 0.02, 1.0).unwrap(),
                "F_N = 1.0000e-2, 𝒢 = 3.0000e-6: few".into(),
            ],
            ..job(0, 0.01, 0.01)
        };
        // This version's file reads back as written.
        assert_eq!(JobResult::from_json(&written.to_json()).unwrap(), written);
        // An earlier file: an unweighted ℓ, no count, the earlier wording of the warning (in place).
        let earlier = JobResult {
            results: vec![WearResult {
                memory_decay_length: Some(0.05),
                memory_decay_r2: Some(0.4),
                memory_fit_initial_junctions: Some(9.0),
                running_in_decay_lengths: Some(0.4),
                initial_lineages_left: None,
                ..current.clone()
            }],
            warnings: vec![
                written.warnings[0].clone(),
                "F_N = 1.0000e-2: not run in: the memory of the initial contact decays over ℓ = 5.0000e-2, with 67 \
                 % of the junction lineages of s = 0 expected still present"
                    .into(),
                written.warnings[2].clone(),
            ],
            ..written.clone()
        };
        let read = JobResult::from_json(&earlier.to_json()).unwrap();
        assert_eq!(read.results, written.results);
        assert_eq!(read.warnings, written.warnings);
        assert_eq!(read.results[0].initial_lineages_left, Some(0.25));
        // A file that said nothing of run-in gets the warning before its load's others; one run in
        // by this version's fit loses it.
        let silent = JobResult {
            warnings: vec![written.warnings[0].clone(), written.warnings[2].clone()],
            ..earlier.clone()
        };
        assert_eq!(
            JobResult::from_json(&silent.to_json()).unwrap().warnings,
            written.warnings
        );
        let run_in = JobResult {
            results: vec![WearResult {
                fit_window_start: 0.05,
                ..earlier.results[0].clone()
            }],
            ..earlier
        };
        let read = JobResult::from_json(&run_in.to_json()).unwrap();
        assert_eq!(read.warnings, silent.warnings);
        assert_eq!(read.results[0].initial_lineages_left, Some(1.0 / 40.0));
    }

    #[test]
    fn a_jobs_series_is_one_row_per_fracture_energy_and_step() {
        let step = |s: f64, n_critical: Vec<usize>, n_formed: Vec<usize>| StepRow {
            s,
            junctions: 7,
            wrapping_junctions: 0,
            contact_area: 0.1,
            initial_junctions: 5,
            merged_junctions: None,
            largest_junction: None,
            volume: n_formed.iter().map(|&n| n as f64 * 1e-6).collect(),
            static_wear_coefficient: vec![0.3, 0.2],
            n_critical,
            n_formed,
        };
        let result = JobResult {
            results: vec![
                WearResult {
                    fracture_energy: 1e-6,
                    ..WearResult::default()
                },
                WearResult {
                    fracture_energy: 2e-6,
                    ..WearResult::default()
                },
            ],
            steps: vec![step(0.0, vec![2, 1], vec![2, 1]), step(0.5, vec![1, 0], vec![4, 2])],
            ..job(0, 0.01, 0.01)
        };
        let rows = result.series_rows();
        let key: Vec<(f64, f64, i64, f64)> = rows
            .iter()
            .map(|r| (r.fracture_energy, r.s, r.n_shrunk, r.static_wear_coefficient))
            .collect();
        assert_eq!(
            key,
            [
                (1e-6, 0.0, 0, 0.3),
                (1e-6, 0.5, 3, 0.3),
                (2e-6, 0.0, 0, 0.2),
                (2e-6, 0.5, 2, 0.2)
            ]
        );
        assert!(rows.iter().all(|r| r.load == 0.01 && r.initial_junctions == 5));
        assert_eq!(rows[3].volume, 2e-6);
        assert!(rows
            .iter()
            .all(|r| r.static_wear_rate.is_none() && r.iterations.is_none() && r.residual.is_none()));
    }

    #[test]
    fn equal_critical_diameters_group_within_the_tolerance() {
        let curve = |critical_diameter: f64, shear_strength: f64, fracture_energy: f64| CurveMaterial {
            critical_diameter,
            shear_strength,
            fracture_energy,
        };
        let curves = [
            curve(0.0100, 0.012, 1e-6),
            curve(0.0050, 0.008, 1e-6),
            curve(0.0114, 0.008, 2e-6),
            // Within 15 % of 0.005 but of the same τ̃ and 𝒢 as its neighbour: no comparison.
            curve(0.0056, 0.008, 1e-6),
            // 16 % above 0.01: a group of its own.
            curve(0.0116, 0.010, 1e-6),
        ];
        assert_eq!(equal_critical_diameter(&curves, 0.15), [vec![0, 2]]);
        assert_eq!(equal_critical_diameter(&curves, 0.2), [vec![0, 2, 4]]);
        assert!(equal_critical_diameter(&curves, 0.0).is_empty());
    }

    #[test]
    fn a_curve_is_a_setting_against_load() {
        let rows: Vec<TidyRow> = [job(0, 0.01, 0.01), job(1, 0.02, 0.01), job(2, 0.01, 0.02)]
            .iter()
            .flat_map(TidyRow::of_job)
            .collect();
        let agg = aggregate(&Table::of(&rows));
        let curve = agg.column("curve").unwrap();
        let curves: Vec<Cell> = agg.rows.iter().map(|r| r[curve].clone()).collect();
        assert_eq!(curves, [Cell::Int(0), Cell::Int(0), Cell::Int(1)]);
        // The same curves from the tidy table (one row per job here) and from the aggregated one,
        // told apart by τ̃ alone
        // (the load runs along a curve, the results do not name one).
        let tidy = Table::of(&rows);
        let (of_tidy, of_aggregated) = (super::curves(&tidy), super::curves(&agg));
        assert_eq!(of_tidy.index, [0, 0, 1]);
        assert_eq!(of_aggregated.index, of_tidy.index);
        assert_eq!(of_tidy.settings, ["material.shear_strength"]);
        assert_eq!(of_aggregated.settings, of_tidy.settings);
        // Named materials: their properties go with the name, an axis within one material does not.
        let named = |job: JobResult, material: &str| {
            let mut rows = TidyRow::of_job(&job);
            rows.iter_mut().for_each(|r| r.material = material.into());
            rows
        };
        let mut rows = named(job(0, 0.01, 0.01), "A");
        rows.extend(named(job(1, 0.01, 0.02), "B"));
        assert_eq!(super::curves(&Table::of(&rows)).settings, ["material"]);
        rows.extend(named(job(2, 0.01, 0.03), "B"));
        let both = super::curves(&Table::of(&rows));
        assert_eq!(both.settings, ["material", "material.shear_strength"]);
        assert_eq!(both.index, [0, 1, 2]);
    }
}
