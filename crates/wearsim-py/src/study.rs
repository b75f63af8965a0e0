//! Studies: expansion, local runs, single jobs for Dask workers, collection.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::config::InputRecord;
use wearsim::output::{JobResult, Table};
use wearsim::study::{self, Job, Study};

use crate::error::{interruptible, interruptible_with_progress, to_py};
use crate::{json_to_py, table_to_py};

/// One row of `Study.jobs()`: the input columns of the tidy results table.
#[derive(Default, serde::Serialize)]
struct JobRow {
    job: usize,
    material: String,
    #[serde(flatten)]
    inputs: InputRecord,
    load: f64,
}

/// An expanded study file.
#[pyclass(name = "Study", module = "wearsim._wearsim", frozen)]
pub struct PyStudy {
    study: Study,
    /// The study file's text and the folder its relative paths resolve against: what a Dask
    /// worker needs to expand the same study.
    text: String,
    base: PathBuf,
}

impl PyStudy {
    fn job(&self, index: usize) -> PyResult<&Job> {
        self.study.jobs.get(index).ok_or_else(|| {
            PyValueError::new_err(format!(
                "invalid job index {index}: the study has {} jobs",
                self.study.jobs.len()
            ))
        })
    }
}

#[pymethods]
impl PyStudy {
    /// Expands study-file text whose relative paths resolve against `base`.
    #[new]
    fn new(text: String, base: PathBuf) -> PyResult<Self> {
        let study = study::expand(&text, &base).map_err(to_py)?;
        Ok(Self { study, text, base })
    }

    #[getter]
    fn text(&self) -> &str {
        &self.text
    }
    #[getter]
    fn base(&self) -> PathBuf {
        self.base.clone()
    }
    #[getter]
    fn hash(&self) -> &str {
        &self.study.hash
    }
    fn __len__(&self) -> usize {
        self.study.jobs.len()
    }

    /// Columns (name → values) of one row per job: index, material, every input and the load.
    fn jobs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let rows: Vec<JobRow> = self
            .study
            .jobs
            .iter()
            .map(|job| JobRow {
                job: job.index,
                material: job.material.clone(),
                inputs: job.inputs(),
                load: job.load(),
            })
            .collect();
        table_to_py(py, &Table::of(&rows))
    }

    /// Prepares a result folder (as `wearsim study run` does) and returns the indices of the jobs
    /// without a result file; existing files are checked to belong to this study.
    fn prepare(&self, py: Python<'_>, out: PathBuf) -> PyResult<Vec<usize>> {
        let study = &self.study;
        let base = &self.base;
        interruptible(py, None, |_| {
            study::prepare_folder(&out, study, base)?;
            let mut pending = Vec::new();
            for job in &study.jobs {
                if !matches!(study::stored_result(job, &out)?, study::Stored::Done(_)) {
                    pending.push(job.index);
                }
            }
            Ok(pending)
        })
    }

    /// Runs the jobs of shard `shard` = (k, count) that have no result file, `workers` at a time
    /// (default: one per thread, as `wearsim study run`, fewer where memory is short). Returns a dict:
    /// computed, skipped, claimed_elsewhere (job indices another run is computing), recomputed
    /// (job files that could not be read, with the reason), notes.
    #[pyo3(signature = (out, workers = None, shard = None, threads = None, progress = None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        out: PathBuf,
        workers: Option<usize>,
        shard: Option<(usize, usize)>,
        threads: Option<usize>,
        progress: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let study = &self.study;
        let base = &self.base;
        let jobs: Vec<&Job> = match shard {
            None => study.jobs.iter().collect(),
            Some((k, count)) if count >= 1 && (1..=count).contains(&k) => study::shard(&study.jobs, k, count),
            Some((k, count)) => {
                return Err(PyValueError::new_err(format!(
                    "invalid `shard`: ({k}, {count}) needs 1 ≤ k ≤ count"
                )))
            }
        };
        let (summary, note) = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, done_jobs| {
            let requested = workers.unwrap_or_else(rayon::current_num_threads).max(1);
            let (workers, note) = study::workers_for_memory(&jobs, requested)?;
            study::prepare_folder(&out, study, base)?;
            // Jobs save their state every few minutes, so a job killed part-way resumes.
            let every = Some(wearsim::sliding::CHECKPOINT_EVERY);
            let summary = study::run_jobs(&out, &jobs, workers, every, interrupt, |p| {
                done_jobs.set(p.jobs_done, p.jobs_total)
            })?;
            Ok((summary, note))
        })?;
        json_to_py(
            py,
            &serde_json::json!({
                "computed": summary.computed,
                "skipped": summary.skipped,
                "claimed_elsewhere": summary.claimed_elsewhere,
                "recomputed": summary.recomputed,
                "notes": note.into_iter().collect::<Vec<_>>(),
            }),
        )
    }

    /// Runs job `index` and returns its result as JSON text (what its job file holds); writes nothing.
    #[pyo3(signature = (index, threads = None))]
    fn run_job(&self, py: Python<'_>, index: usize, threads: Option<usize>) -> PyResult<String> {
        let job = self.job(index)?;
        let result = interruptible(py, threads, |interrupt| study::run_job(job, interrupt))?;
        Ok(result.to_json())
    }

    /// Stores a job result (JSON text from `run_job`) in a result folder, after checking that it
    /// was computed for this study's job `index`.
    fn write_result(&self, out: PathBuf, index: usize, result: &str) -> PyResult<()> {
        let job = self.job(index)?;
        let parsed = JobResult::from_json(result)
            .map_err(|e| PyValueError::new_err(format!("invalid `result`: not a job result ({e})")))?;
        if !job.is_result_of(&parsed) {
            return Err(PyValueError::new_err(format!(
                "invalid `result`: it was computed for job {} ({}), not for job {index} ({})",
                parsed.index, parsed.material, job.material
            )));
        }
        study::write_result(&out, &parsed).map_err(to_py)
    }
}

/// Collects a finished study folder into results.csv and results_aggregated.csv; returns the row
/// counts.
#[pyfunction]
fn collect_study(out: PathBuf) -> PyResult<(usize, usize)> {
    study::collect(&out).map_err(to_py)
}

/// The series of finished job `job` of a study folder as columns (name → values): the library's
/// rows of its job file, one per fracture energy and step.
#[pyfunction]
fn job_series<'py>(py: Python<'py>, out: PathBuf, job: usize) -> PyResult<Bound<'py, PyDict>> {
    let result = wearsim::output::read_job_file(&study::job_path(&out, job)).map_err(to_py)?;
    table_to_py(py, &Table::of(&result.series_rows()))
}

/// The figures of a finished study folder (the library's registry, `wearsim study plot`'s): one
/// dict per figure (entry, name, title, panels, legend, legend_title, note) with its numbers as
/// CSV under "csv"; `names` picks registry entries, `job` the job whose series are drawn.
#[pyfunction]
#[pyo3(signature = (out, job=None, names=None))]
fn study_figures<'py>(
    py: Python<'py>,
    out: PathBuf,
    job: Option<usize>,
    names: Option<Vec<String>>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let found = study::figures::study_folder_figures(&out, job, names.as_deref()).map_err(to_py)?;
    crate::tables::figures_to_py(py, &found.figures)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyStudy>()?;
    m.add_function(wrap_pyfunction!(study_figures, m)?)?;
    m.add_function(wrap_pyfunction!(collect_study, m)?)?;
    m.add_function(wrap_pyfunction!(job_series, m)?)?;
    Ok(())
}
