//! Running a study's jobs: each job a sliding run on its own surfaces, several jobs at once sharing
//! the threads, finished jobs skipped.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use crate::error::{Error, Interrupt, Result};
use crate::output::{JobResult, Provenance, StepRow};
use crate::sliding::{run_sliding, SlidingSetup};
use crate::study::expand::Job;
use crate::study::store::{job_path, read_result, write_result};

/// Runs one job; a raised `interrupt` stops it with [`Error::Interrupted`].
pub fn run_job(job: &Job, interrupt: &Interrupt) -> Result<JobResult> {
    let start = std::time::Instant::now();
    let run = &job.run;
    let sliding = run
        .sliding
        .as_ref()
        .ok_or_else(|| Error::param("loads", "job without [sliding]"))?;
    let (top, bottom) = run.surfaces()?;
    let mut setup = SlidingSetup::from_run(run, sliding);
    setup.interrupt = interrupt.clone();
    let mut runs = run_sliding(&top, &bottom, &setup, |_| {})?;
    let r = runs.pop().ok_or_else(|| Error::param("loads", "job without a load"))?;
    Ok(JobResult {
        provenance: Provenance::current(),
        index: job.index,
        material: job.material.clone(),
        inputs: job.inputs(),
        load: r.load,
        flow_pressure: run.material.flow_pressure(),
        effective_modulus: run.effective_modulus(),
        results: r.results,
        steps: r.steps.iter().map(StepRow::from).collect(),
        total_iterations: r.total_iterations,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Jobs of shard `k` of `count` (1-based k): indices ≡ k − 1 (mod count).
pub fn shard(jobs: &[Job], k: usize, count: usize) -> Vec<&Job> {
    jobs.iter().filter(|j| j.index % count == k - 1).collect()
}

/// Runs the given jobs with `workers` jobs at once, the threads of the current rayon pool shared
/// between them (one worker: every thread on each job, for large grids; as many workers as threads:
/// one thread per job, for many small jobs), skipping jobs whose file exists. `progress(done, total)`
/// is called after each job. A raised `interrupt` stops the jobs under way (finished job files stay,
/// so a later run resumes) and returns [`Error::Interrupted`]. Returns (computed, skipped).
pub fn run_jobs(
    dir: &Path,
    jobs: &[&Job],
    workers: usize,
    interrupt: &Interrupt,
    progress: impl Fn(usize, usize) + Sync,
) -> Result<(usize, usize)> {
    // A finished job is skipped only once its file is confirmed to be this job's.
    let mut pending: Vec<&Job> = Vec::new();
    for &job in jobs {
        if job_path(dir, job.index).is_file() {
            read_result(job, dir)?;
        } else {
            pending.push(job);
        }
    }
    let skipped = jobs.len() - pending.len();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let first_error: Mutex<Option<Error>> = Mutex::new(None);
    let workers = workers.clamp(1, pending.len().max(1));
    let threads_per_worker = (rayon::current_num_threads() / workers).max(1);
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads_per_worker)
                    .build()
                    .expect("a worker's thread pool");
                loop {
                    if first_error.lock().map(|e| e.is_some()).unwrap_or(true) {
                        return;
                    }
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    let Some(job) = pending.get(i) else { return };
                    let outcome = pool
                        .install(|| run_job(job, interrupt))
                        .and_then(|result| write_result(dir, &result));
                    match outcome {
                        Ok(()) => progress(done.fetch_add(1, Ordering::SeqCst) + 1, pending.len()),
                        Err(e) => {
                            let e = match e {
                                Error::Interrupted => e,
                                e => Error::Job {
                                    index: job.index,
                                    material: job.material.clone(),
                                    load: job.load(),
                                    source: Box::new(e),
                                },
                            };
                            if let Ok(mut slot) = first_error.lock() {
                                slot.get_or_insert(e);
                            }
                            return;
                        }
                    }
                }
            });
        }
    });
    if let Some(e) = first_error.into_inner().ok().flatten() {
        return Err(e);
    }
    Ok((done.into_inner(), skipped))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::expand::{expand, tests::STUDY};

    #[test]
    fn shards_partition_the_jobs() {
        let s = expand(STUDY, Path::new(".")).unwrap();
        let mut all: Vec<usize> = (1..=4).flat_map(|k| shard(&s.jobs, k, 4)).map(|j| j.index).collect();
        all.sort();
        assert_eq!(all, (0..18).collect::<Vec<_>>());
    }
}
