//! Job files → the study's tables: `results.csv` (one row per job × fracture energy) and
//! `results_aggregated.csv` (mean, min and max over surface pairs).

use std::path::Path;

use crate::error::{Error, Result};
use crate::output::{write_results_tables, JobResult, TidyRow};
use crate::study::expand::{expand_stored, Study};
use crate::study::store::{job_path, read_result, stored_study};

/// Reads a study folder: the stored study, expanded, and every job's result in job order, with N*'s
/// growth with load across the jobs of one surface pair ([`crate::output::growth_across_jobs`]).
/// Fails naming the missing jobs when the study is unfinished.
pub fn load_results(dir: &Path) -> Result<(Study, Vec<JobResult>)> {
    let (text, base) = stored_study(dir)?;
    let study = expand_stored(&text, &base)?;
    let missing: Vec<usize> = study
        .jobs
        .iter()
        .map(|j| j.index)
        .filter(|&i| !job_path(dir, i).is_file())
        .collect();
    if let Some(first) = missing.first() {
        return Err(Error::StudyFolder {
            dir: dir.into(),
            message: format!(
                "{} of {} jobs have no result yet (first: {first}); run `wearsim study run` again to finish them",
                missing.len(),
                study.jobs.len()
            ),
        });
    }
    let mut results = study
        .jobs
        .iter()
        .map(|job| read_result(job, dir))
        .collect::<Result<Vec<_>>>()?;
    crate::output::growth_across_jobs(&mut results);
    Ok((study, results))
}

/// Collects the job files of a study folder into `results.csv` (one row per job × fracture energy:
/// every input of the job, the load, and the results) and `results_aggregated.csv` (mean, min and
/// max over surface pairs, i.e. over `surface.seed`). Returns the number of rows of each. Fails
/// naming the missing jobs when the study is unfinished.
pub fn collect(dir: &Path) -> Result<(usize, usize)> {
    let (_, results) = load_results(dir)?;
    let rows: Vec<TidyRow> = results.iter().flat_map(TidyRow::of_job).collect();
    write_results_tables(dir, &rows)
}
