//! Running a study's jobs: each job a sliding run on its own surfaces, several jobs at once sharing
//! the threads, finished jobs skipped.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use crate::error::{Error, Interrupt, Result};
use crate::estimate::{Sampling, MAX_SAMPLES};
use crate::io::refresh_claim;
use crate::model::WearModel;
use crate::output::{JobResult, Provenance, StepRow};
use crate::run::SlidingRun;
use crate::sliding::{Checkpointing, Resumed};
use crate::study::expand::Job;
use crate::study::store::{stored_result, write_result, Claim, Stored, CLAIM_REFRESH};

/// Runs one job; a raised `interrupt` stops it with [`Error::Interrupted`].
pub fn run_job(job: &Job, interrupt: &Interrupt) -> Result<JobResult> {
    run_job_observed(job, interrupt, None, || {}, |_| {})
}

/// Path of job `index`'s checkpoint in a study folder (see [`crate::sliding::Checkpointing`]).
pub fn checkpoint_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("jobs").join(format!("job-{index:06}.checkpoint"))
}

/// Sliding steps of a job (its schedule on its grid), for progress in steps; for a job of the
/// static estimate, the most static solves it may take.
pub fn job_steps(job: &Job) -> usize {
    let (Some(s), Ok(grid)) = (job.run.sliding.as_ref(), job.run.grid()) else {
        return 0;
    };
    match job.run.model {
        WearModel::Sliding => s.offsets(grid.nx()).len() * s.loads.len(),
        WearModel::Estimate => {
            let maps = match Sampling::of(job.run.estimate_samples) {
                Ok(Sampling::Fixed(k)) => k,
                _ => MAX_SAMPLES,
            };
            maps * s.loads.len()
        }
    }
}

/// [`run_job`], calling `on_step` after every sliding step (progress of a long job), saving its
/// state and resuming from it as `checkpointing` says (`on_checkpoint` is told what became of the
/// checkpoint: resumed, set aside, saved when stopped, not written). The job is a sliding run like
/// any other ([`SlidingRun`]), and its job file keeps every warning of it, its surfaces' included.
pub fn run_job_observed(
    job: &Job,
    interrupt: &Interrupt,
    checkpointing: Option<&Checkpointing>,
    on_step: impl Fn(),
    on_checkpoint: impl FnMut(&Resumed),
) -> Result<JobResult> {
    let run = &job.run;
    match run.model {
        WearModel::Sliding => {}
        WearModel::Estimate => return estimate_job(job, interrupt, on_step),
    }
    let mut outcome =
        SlidingRun::prepare(run)?
            .interrupted_by(interrupt)
            .run_resumable(checkpointing, on_checkpoint, |_| on_step())?;
    let r = outcome
        .runs
        .pop()
        .ok_or_else(|| Error::param("loads", "job without a load"))?;
    Ok(JobResult {
        results: r.results,
        steps: r.steps.iter().map(StepRow::from).collect(),
        total_iterations: r.total_iterations,
        ..job_result(job, r.load, outcome.seconds, outcome.warnings)
    })
}

/// The job file of `job` at `load` without results: what every job's file says of the job, its
/// material and the run's time and warnings, whichever model made the results.
pub(crate) fn job_result(job: &Job, load: f64, seconds: f64, warnings: Vec<String>) -> JobResult {
    JobResult {
        format: crate::output::JOB_FORMAT,
        provenance: Provenance::current(),
        index: job.index,
        material: job.material.clone(),
        inputs: job.inputs(),
        load,
        flow_pressure: job.run.material.flow_pressure(),
        effective_modulus: job.run.effective_modulus(),
        results: Vec::new(),
        steps: Vec::new(),
        total_iterations: 0,
        seconds,
        warnings,
        estimates: Vec::new(),
    }
}

/// A job of the static estimate (`[sliding] model = "estimate"`): its static maps, the estimate in
/// the sliding model's result columns for the tables, and the estimate itself with its intervals.
/// `on_step` is called after every static solve.
fn estimate_job(job: &Job, interrupt: &Interrupt, on_step: impl Fn()) -> Result<JobResult> {
    let run = &job.run;
    let sampling = Sampling::of(run.estimate_samples)?;
    let mut outcome = SlidingRun::prepare(run)?.interrupted_by(interrupt).estimate(
        sampling,
        &run.estimate_calibration(),
        |_, _| on_step(),
    )?;
    let l = outcome
        .loads
        .pop()
        .ok_or_else(|| Error::param("loads", "job without a load"))?;
    Ok(JobResult {
        results: l
            .results
            .iter()
            .enumerate()
            .map(|(e, r)| r.as_wear_result(l.samples.first().map(|m| &m.counts[e])))
            .collect(),
        total_iterations: l.samples.iter().map(|s| s.iterations).sum(),
        estimates: l.results,
        ..job_result(job, l.load, outcome.seconds, outcome.warnings)
    })
}

/// Jobs of shard `k` of `count` (1-based k): indices ≡ k − 1 (mod count).
pub fn shard(jobs: &[Job], k: usize, count: usize) -> Vec<&Job> {
    jobs.iter().filter(|j| j.index % count == k - 1).collect()
}

/// How far a run of a study's jobs is: jobs finished by this run, and sliding steps done (of
/// finished and running jobs) against the steps of every pending job, so that a study of a few
/// large jobs shows progress between jobs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StudyProgress {
    pub jobs_done: usize,
    pub jobs_total: usize,
    pub steps_done: usize,
    pub steps_total: usize,
}

/// What a run of a study's jobs did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunSummary {
    /// Jobs computed by this run.
    pub computed: usize,
    /// Jobs whose result file was there already.
    pub skipped: usize,
    /// Jobs another live run was computing (their claim files said so) and that had no job file yet
    /// when this run ended: left undone by this run.
    pub claimed_elsewhere: Vec<usize>,
    /// Job files that could not be read and were computed again, with the reason.
    pub recomputed: Vec<String>,
    /// What became of the jobs' checkpoints where it needs saying: one set aside (damaged, of other
    /// inputs) or one that could not be written (a full disk), per job.
    pub checkpoint_warnings: Vec<String>,
}

/// The jobs of `jobs` left to compute: those without a job file and those whose file cannot be
/// read (counted in the summary with the reason); the others are counted as skipped, the claim and
/// checkpoint a killed run left beside a finished job removed.
fn pending_jobs<'j>(dir: &Path, jobs: &[&'j Job]) -> Result<(Vec<&'j Job>, RunSummary)> {
    let mut summary = RunSummary::default();
    let mut pending = Vec::new();
    for &job in jobs {
        match stored_result(job, dir)? {
            Stored::Done(_) => {
                summary.skipped += 1;
                Claim::release_abandoned(dir, job.index, &checkpoint_path(dir, job.index));
            }
            Stored::Missing => pending.push(job),
            Stored::Unreadable(why) => {
                summary.recomputed.push(why);
                pending.push(job);
            }
        }
    }
    Ok((pending, summary))
}

/// Refreshes the claims of the jobs under way every [`CLAIM_REFRESH`] until `stop`, so that other
/// runs sharing the folder see them alive.
fn keep_claims_fresh(stop: &std::sync::atomic::AtomicBool, held: &Mutex<Vec<PathBuf>>) {
    let mut since = std::time::Instant::now();
    while !stop.load(Ordering::Relaxed) {
        std::thread::sleep(std::time::Duration::from_millis(200));
        if since.elapsed() >= CLAIM_REFRESH {
            if let Ok(paths) = held.lock() {
                for p in paths.iter() {
                    refresh_claim(p);
                }
            }
            since = std::time::Instant::now();
        }
    }
}

/// Runs one claimed job (resuming from and saving its checkpoint when `checkpoint_every` is set) and
/// writes its job file; the checkpoint is removed once the file is in place. What became of a
/// checkpoint that was not used or could not be written goes to `notes`.
fn run_and_store(
    job: &Job,
    dir: &Path,
    checkpoint_every: Option<std::time::Duration>,
    interrupt: &Interrupt,
    notes: &Mutex<Vec<String>>,
    on_step: impl Fn(),
) -> Result<()> {
    let checkpointing = checkpoint_every.map(|every| Checkpointing {
        path: checkpoint_path(dir, job.index),
        every,
    });
    let on_checkpoint = |r: &Resumed| {
        let note = match r {
            Resumed::Ignored(why) => format!("job {}: checkpoint not used: {why}", job.index),
            Resumed::NotSaved(why) => format!("job {}: checkpoint not saved: {why}", job.index),
            _ => return,
        };
        if let Ok(mut notes) = notes.lock() {
            notes.push(note);
        }
    };
    run_job_observed(job, interrupt, checkpointing.as_ref(), on_step, on_checkpoint)
        .and_then(|r| write_result(dir, &r))?;
    if let Some(c) = &checkpointing {
        let _ = std::fs::remove_file(&c.path);
    }
    Ok(())
}

/// Runs the given jobs with `workers` jobs at once, the threads of the current rayon pool shared
/// between them (one worker: every thread on each job, for large grids; as many workers as threads:
/// one thread per job, for many small jobs). A job whose file exists is skipped; one that another
/// run has claimed is left to it; every other is claimed, computed, written and released, so runs
/// sharing a folder compute each job once. A failing job does not stop the others: the finished
/// ones are written and [`Error::JobsFailed`] names the failed ones, which a new run retries.
/// `progress` is called after every sliding step and every job. A raised `interrupt` stops the jobs under way
/// (finished job files stay, so a later run resumes) and returns [`Error::Interrupted`]. With
/// `checkpoint_every`, each job saves its state that often beside its job file, and a job killed
/// part-way resumes from it in the next run (the file is removed once the job file is written).
pub fn run_jobs(
    dir: &Path,
    jobs: &[&Job],
    workers: usize,
    checkpoint_every: Option<std::time::Duration>,
    interrupt: &Interrupt,
    progress: impl Fn(StudyProgress) + Sync,
) -> Result<RunSummary> {
    let (pending, summary) = pending_jobs(dir, jobs)?;
    let queue = JobQueue {
        dir,
        pending: &pending,
        checkpoint_every,
        interrupt,
        next: AtomicUsize::new(0),
        done: AtomicUsize::new(0),
        steps_done: AtomicUsize::new(0),
        failed: Mutex::new(Vec::new()),
        elsewhere: Mutex::new(Vec::new()),
        held: Mutex::new(Vec::new()),
        notes: Mutex::new(Vec::new()),
    };
    let steps_total: usize = pending.iter().map(|j| job_steps(j)).sum();
    let report = |jobs_done: usize| {
        progress(StudyProgress {
            jobs_done,
            jobs_total: pending.len(),
            steps_done: queue.steps_done.load(Ordering::Relaxed).min(steps_total),
            steps_total,
        })
    };
    let stop = std::sync::atomic::AtomicBool::new(false);
    let workers = workers.clamp(1, pending.len().max(1));
    let threads_per_worker = (rayon::current_num_threads() / workers).max(1);
    std::thread::scope(|scope| -> Result<()> {
        scope.spawn(|| keep_claims_fresh(&stop, &queue.held));
        let handles: Vec<_> = (0..workers)
            .map(|_| scope.spawn(|| queue.work(threads_per_worker, &report)))
            .collect();
        let mut first: Result<()> = Ok(());
        for h in handles {
            let r = h.join().unwrap_or_else(|_| Err(lock_error()));
            if first.is_ok() {
                first = r;
            }
        }
        stop.store(true, Ordering::Relaxed);
        first
    })?;
    queue.into_summary(summary, jobs.len())
}

/// The error of a lock that a panicking worker of [`run_jobs`] left poisoned.
fn lock_error() -> Error {
    Error::param("study", "a worker of the study runner panicked")
}

/// The jobs [`run_jobs`] computes and what its workers share: the next job to take, the counts
/// of jobs and steps done, the jobs failed or claimed by another run, the claims held and the
/// checkpoints' notes.
struct JobQueue<'a> {
    dir: &'a Path,
    pending: &'a [&'a Job],
    checkpoint_every: Option<std::time::Duration>,
    interrupt: &'a Interrupt,
    next: AtomicUsize,
    done: AtomicUsize,
    steps_done: AtomicUsize,
    failed: Mutex<Vec<Error>>,
    elsewhere: Mutex<Vec<usize>>,
    held: Mutex<Vec<PathBuf>>,
    notes: Mutex<Vec<String>>,
}

impl JobQueue<'_> {
    /// One worker: takes the next pending job until none is left, on a pool of `threads`; claims,
    /// computes, stores and releases it, or leaves it to the run that claimed it. `report(jobs
    /// done)` after every step and job.
    fn work(&self, threads: usize, report: &(impl Fn(usize) + Sync)) -> Result<()> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Error::param("threads", format!("cannot start a worker's threads: {e}")))?;
        loop {
            self.interrupt.check()?;
            let i = self.next.fetch_add(1, Ordering::SeqCst);
            let Some(job) = self.pending.get(i) else { return Ok(()) };
            let Some(claim) = Claim::take(self.dir, job.index)? else {
                self.elsewhere.lock().map_err(|_| lock_error())?.push(job.index);
                continue;
            };
            // Another run may have finished the job between our look and our claim.
            if matches!(stored_result(job, self.dir)?, Stored::Done(_)) {
                continue;
            }
            self.held
                .lock()
                .map_err(|_| lock_error())?
                .push(claim.path().to_path_buf());
            let on_step = || {
                self.steps_done.fetch_add(1, Ordering::Relaxed);
                report(self.done.load(Ordering::Relaxed));
            };
            let outcome = pool.install(|| {
                run_and_store(
                    job,
                    self.dir,
                    self.checkpoint_every,
                    self.interrupt,
                    &self.notes,
                    on_step,
                )
            });
            self.held
                .lock()
                .map_err(|_| lock_error())?
                .retain(|p| p != claim.path());
            drop(claim);
            match outcome {
                Ok(()) => report(self.done.fetch_add(1, Ordering::SeqCst) + 1),
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(e) => self.failed.lock().map_err(|_| lock_error())?.push(Error::Job {
                    index: job.index,
                    material: job.material.clone(),
                    load: job.load(),
                    source: Box::new(e),
                }),
            }
        }
    }

    /// `summary` (of the jobs already done) completed with what the workers did: an error naming the
    /// failed jobs among `total`, if any failed.
    fn into_summary(self, mut summary: RunSummary, total: usize) -> Result<RunSummary> {
        summary.computed = self.done.into_inner();
        summary.checkpoint_warnings = self.notes.into_inner().map_err(|_| lock_error())?;
        summary.claimed_elsewhere = self.elsewhere.into_inner().map_err(|_| lock_error())?;
        // Those the other runs finished meanwhile are done; the rest are left undone by this run.
        summary
            .claimed_elsewhere
            .retain(|&i| !crate::study::store::job_path(self.dir, i).is_file());
        summary.claimed_elsewhere.sort_unstable();
        let mut failed = self.failed.into_inner().map_err(|_| lock_error())?;
        if !failed.is_empty() {
            failed.sort_by_key(|e| if let Error::Job { index, .. } = e { *index } else { 0 });
            return Err(Error::JobsFailed { failed, total });
        }
        Ok(summary)
    }
}

/// How many of `jobs` can run at once in this machine's memory: `workers`, or fewer with a note saying
/// so; an error (before anything is written) when not even one job fits.
pub fn workers_for_memory(jobs: &[&Job], workers: usize) -> Result<(usize, Option<String>)> {
    if workers == 0 {
        return Err(Error::param(
            "jobs",
            "0 jobs at once would run nothing: give 1 or more (1 for large grids), or leave it out for one job per \
             thread",
        ));
    }
    // The job of the largest need: its grid and its arrays (the run's and its particle rule's).
    let mut largest = (0, 0, crate::check::SLIDING_ARRAYS);
    for job in jobs {
        let grid = job.run.grid()?;
        let arrays = job
            .run
            .sliding
            .as_ref()
            .map_or(crate::check::SLIDING_ARRAYS, |s| s.memory_arrays());
        if grid.pixels() as f64 * arrays > (largest.0 * largest.1) as f64 * largest.2 {
            largest = (grid.nx(), grid.ny(), arrays);
        }
    }
    if largest.0 == 0 {
        return Ok((workers, None));
    }
    crate::check::memory("one job of this study", largest.0, largest.1, largest.2)?;
    let per_job = crate::check::memory_need(largest.0, largest.1, largest.2) - crate::check::BASE_MEMORY;
    match crate::check::memory_room() {
        Some(room) if per_job * workers as f64 + crate::check::BASE_MEMORY > room.bytes as f64 => {
            let fit = (((room.bytes as f64 - crate::check::BASE_MEMORY) / per_job) as usize).max(1);
            Ok((
                fit,
                Some(format!(
                    "{workers} jobs of {}×{} pixels at once would not fit in the {:.1} GiB this process may use ({}); \
                     running {fit} at a time",
                    largest.0,
                    largest.1,
                    room.bytes as f64 / (1u64 << 30) as f64,
                    room.limit
                )),
            ))
        }
        _ => Ok((workers, None)),
    }
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

    // Here rather than in the store's tests: the job file is made by `job_result`, a layer above.
    #[test]
    fn a_job_file_of_another_model_in_a_jobs_place_names_both_models() {
        use crate::study::expand::{expand, tests::STUDY};
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("jobs")).unwrap();
        let sliding = expand(STUDY, Path::new(".")).unwrap();
        let estimate = expand(
            &STUDY.replace("loads = [5e-4, 1e-3]", "loads = [5e-4, 1e-3]\nmodel = \"estimate\""),
            Path::new("."),
        )
        .unwrap();
        let r = job_result(&estimate.jobs[0], estimate.jobs[0].load(), 1.0, Vec::new());
        crate::study::store::write_result(dir.path(), &r).unwrap();
        let e = crate::study::store::stored_result(&sliding.jobs[0], dir.path())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("a result of model \"estimate\" where this job is one of model \"sliding\"")
                && e.contains("`sliding.model`: \"estimate\" in the file, none in the job"),
            "{e}"
        );
    }
}
