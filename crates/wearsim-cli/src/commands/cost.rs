//! Cost estimates before the work (`slide`, `study run` and their `--dry-run`, `bench --calibrate`):
//! wall time and peak memory on this machine from the library's cost model (`wearsim::cost`), so
//! that a Slurm job's `--time` and `--mem` can be sized before it is submitted.

use anyhow::{Context, Result};
use wearsim::config::RunConfig;
use wearsim::cost::{cache_dir, Calibration, Estimate, IterationProbe, SlurmRequest, StepIterations};
use wearsim::run::SlidingRun;
use wearsim::study::Job;

use crate::out::{say, tell};

/// This machine's calibration: the cached one, or measured now (about ten seconds) and cached.
pub fn calibration() -> Result<Calibration> {
    let dir = cache_dir();
    match dir.as_deref().map(Calibration::cached) {
        Some(Ok(Some(c))) => return Ok(c),
        Some(Err(e)) => tell!("note: {e}; this machine is calibrated again"),
        _ => {}
    }
    tell!(
        "calibrating this machine for cost estimates on {} (about ten seconds, once per machine, wearsim version \
         and thread count)",
        counted(rayon::current_num_threads(), "thread")
    );
    measure_and_save(dir)
}

fn measure_and_save(dir: Option<std::path::PathBuf>) -> Result<Calibration> {
    let c = Calibration::measure(super::interrupt()).context("calibration of the cost estimates")?;
    match dir {
        Some(dir) => match c.save(&dir) {
            Ok(path) => tell!("calibration cached in {}", path.display()),
            Err(e) => tell!("note: the calibration is not cached: {e}"),
        },
        None => tell!("note: neither $XDG_CACHE_HOME nor $HOME is set: the calibration is not cached"),
    }
    Ok(c)
}

/// `wearsim bench --calibrate`: measures anew, caches and prints the calibration.
pub fn recalibrate() -> Result<()> {
    let c = measure_and_save(cache_dir())?;
    say!("{}", serde_json::to_string_pretty(&c)?);
    Ok(())
}

/// "1 thread", "2 threads".
fn counted(n: usize, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

/// A duration for people: seconds, minutes or hours.
fn duration(seconds: f64) -> String {
    if seconds < 90.0 {
        format!("{seconds:.0} s")
    } else if seconds < 5400.0 {
        format!("{:.0} min", seconds / 60.0)
    } else {
        format!("{:.1} h", seconds / 3600.0)
    }
}

/// Bytes in MiB or GiB.
fn memory(bytes: f64) -> String {
    let mib = bytes / (1u64 << 20) as f64;
    if mib < 1024.0 {
        format!("{mib:.0} MiB")
    } else {
        format!("{:.1} GiB", mib / 1024.0)
    }
}

/// What an estimate assumes, one line; `measured`: its iterations were measured on the run's own
/// surfaces.
fn assumptions(c: &Calibration, measured: bool) -> String {
    let loaded = match c.load_average {
        Some(l) if l > 0.5 * c.cores as f64 => format!(
            "; measured while the machine was busy (load average {l:.1} on {} cores), so estimates run high: \
             `wearsim bench --calibrate` on an idle machine measures again",
            c.cores
        ),
        _ => String::new(),
    };
    format!(
        "assumes {} and the machine as free as at its calibration ({}, {} days ago), {}{loaded}",
        counted(c.threads, "thread"),
        c.machine,
        c.age_days(),
        if measured {
            "iterations per step as measured on the run's own surfaces at its heaviest load (lighter loads take \
             fewer)"
        } else {
            "iterations as on the paper's roughness"
        }
    )
}

/// The iterations of a run's steps measured on its own surfaces ([`SlidingRun::probe_iterations`]).
fn probe(config: &RunConfig) -> Result<IterationProbe> {
    SlidingRun::prepare(config)
        .and_then(|run| run.interrupted_by(super::interrupt()).probe_iterations())
        .context("measuring the iterations of a few steps on the run's own surfaces")
}

/// A job's surfaces less their seed, as a key: the pairs of one spectrum on one grid share a probe.
fn surface_kind(job: &Job) -> Result<String> {
    let mut surfaces = serde_json::to_value(&job.run.surfaces)?;
    if let Some(fields) = surfaces.as_object_mut() {
        fields.remove("seed");
    }
    Ok(surfaces.to_string())
}

/// One line: iterations per step measured against those the calibration assumes.
fn measured_line(p: &IterationProbe, assumed: &StepIterations, e: &Estimate) -> String {
    let i = p.iterations;
    format!(
        "iterations per step measured on the run's own surfaces at F_N = {:.4e} ({} steps in {:.1} s): cold {:.0}, \
         running-in {:.1}, after it {:.1}; assumed from the paper's roughness: {:.0}, {:.1}, {:.1}; {:.0} iterations \
         over the run where {:.0} were assumed ({:.2}×)",
        p.load,
        p.steps,
        p.seconds,
        i.cold,
        i.coarse,
        i.fine,
        assumed.cold,
        assumed.coarse,
        assumed.fine,
        e.iterations,
        e.assumed_iterations,
        e.iterations / e.assumed_iterations.max(1e-300)
    )
}

/// Set (non-empty) in the environment, runs print no estimate and calibrate nothing; a dry run
/// still estimates.
pub const NO_ESTIMATE: &str = "WEARSIM_NO_ESTIMATE";

fn skipped(dry_run: bool) -> bool {
    !dry_run && std::env::var_os(NO_ESTIMATE).is_some_and(|v| !v.is_empty())
}

/// Prints the estimate of a run before it starts. An estimate that cannot be made is an error on a
/// dry run (it is all the dry run does) and a note otherwise (the run goes on), unless the
/// calibration was interrupted (Ctrl-C stops the command).
pub fn report_run(run: &SlidingRun, dry_run: bool) -> Result<()> {
    if skipped(dry_run) {
        return Ok(());
    }
    lenient(print_run(run).map(|_| ()), dry_run)
}

/// [`report_run`] for a study's jobs.
pub fn report_study(jobs: &[&Job], workers: usize, dry_run: bool) -> Result<()> {
    if skipped(dry_run) {
        return Ok(());
    }
    lenient(print_study(jobs, workers), dry_run)
}

fn lenient(result: Result<()>, dry_run: bool) -> Result<()> {
    match result {
        Err(e) if !dry_run && !is_interrupted(&e) => {
            tell!("note: no cost estimate: {e:#}");
            Ok(())
        }
        other => other,
    }
}

fn is_interrupted(e: &anyhow::Error) -> bool {
    e.chain()
        .any(|c| matches!(c.downcast_ref::<wearsim::Error>(), Some(wearsim::Error::Interrupted)))
}

/// Prints the estimate of a prepared sliding run, its iterations measured on its own surfaces (the
/// run then slides on the same surfaces: they are made once).
pub fn print_run(run: &SlidingRun) -> Result<Estimate> {
    let config = run.config();
    let sliding = config.sliding.as_ref().context("a [sliding] table is needed")?;
    let grid = config.grid()?;
    let c = calibration()?;
    let probe = run
        .probe_iterations()
        .context("measuring the iterations of a few steps on the run's own surfaces")?;
    let e = c.estimate_measured(grid, sliding, config.stopping, Some(probe.iterations));
    tell!("  {}", measured_line(&probe, &c.iterations(grid, config.stopping), &e));
    tell!(
        "estimate: {} steps at {}×{} ({} per load × {}, about {:.1} iterations per step): {} wall on {} \
         ({:.2} CPU hours), peak memory {}; Slurm: {}",
        e.steps,
        grid.nx(),
        grid.ny(),
        e.steps / sliding.loads.len(),
        counted(sliding.loads.len(), "load"),
        e.iterations / e.steps as f64,
        duration(e.seconds),
        counted(e.threads, "thread"),
        e.cpu_hours(),
        memory(e.peak_memory),
        SlurmRequest::with_margins(e.seconds, e.peak_memory)
    );
    tell!("  ({})", assumptions(&c, true));
    Ok(e)
}

/// The notes on the jobs the cost model leaves out: it sizes sliding steps, so the jobs of a model
/// that takes none are counted apart.
fn note_jobs_left_out(jobs: &[&Job]) {
    for model in wearsim::model::WearModel::ALL {
        let n = jobs.iter().filter(|j| j.run.model == model).count();
        if let (Some(note), true) = (model.cost_note(), n > 0) {
            tell!(
                "note: {} of {} are not in the cost estimate: {note}",
                counted(n, "job"),
                model.description()
            );
        }
    }
}

/// The jobs to probe: one per kind of surface (its key), at the heaviest load of its jobs (the
/// load, and the job's position in `jobs`).
fn probe_choices(jobs: &[&Job]) -> Result<Vec<(String, f64, usize)>> {
    // One probe per kind of surface (the source less its seed: the spectrum, the grid, the files),
    // at the heaviest load of its jobs: surface pairs of one spectrum differ in their iterations by
    // far less than the factor the cost model allows, and a study of forty pairs at 4096² would
    // otherwise probe for many minutes before it starts.
    let mut probes: Vec<(String, f64, usize)> = Vec::new();
    for (k, job) in jobs.iter().enumerate() {
        let key = surface_kind(job)?;
        let load = job
            .run
            .sliding
            .as_ref()
            .map_or(0.0, |s| s.loads.iter().copied().fold(0.0, f64::max));
        match probes.iter_mut().find(|(other, _, _)| *other == key) {
            Some(p) if p.1 < load => *p = (key, load, k),
            Some(_) => {}
            None => probes.push((key, load, k)),
        }
    }
    Ok(probes)
}

/// Prints the estimate of a study's (shard's) jobs run `workers` at a time on this machine's
/// threads.
pub fn print_study(jobs: &[&Job], workers: usize) -> Result<()> {
    note_jobs_left_out(jobs);
    let jobs: Vec<&Job> = jobs.iter().copied().filter(|j| j.run.model.slides()).collect();
    if jobs.is_empty() {
        return Ok(());
    }
    let c = calibration()?;
    let probes = probe_choices(&jobs)?;
    let mut measured = Vec::with_capacity(probes.len());
    let mut probe_seconds = 0.0;
    let mut iterations = (0.0, 0.0);
    for (key, _, k) in &probes {
        let p = probe(&jobs[*k].run).with_context(|| format!("job {}", jobs[*k].index))?;
        probe_seconds += p.seconds;
        measured.push((key.clone(), p.iterations));
    }
    let mut estimates = Vec::with_capacity(jobs.len());
    for job in &jobs {
        let sliding = job.run.sliding.as_ref().context("a study job has a [sliding] table")?;
        let key = surface_kind(job)?;
        let m = measured.iter().find(|(k, _)| *k == key).map(|(_, i)| *i);
        let e = c.estimate_measured(job.run.grid()?, sliding, job.run.stopping, m);
        iterations = (iterations.0 + e.iterations, iterations.1 + e.assumed_iterations);
        estimates.push(e);
    }
    tell!(
        "  iterations measured on the jobs' own surfaces (one pair of each of {} surface kind(s), the other \
         seeds taking about as many; a cold solve and a few steps at the heaviest load, {probe_seconds:.1} s): {:.0} over the jobs where the paper's roughness gives {:.0} ({:.2}×)",
        probes.len(),
        iterations.0,
        iterations.1,
        iterations.0 / iterations.1.max(1e-300)
    );
    // Jobs side by side share the threads: about the wall time of running them one after another on
    // all threads (side by side is, if anything, a little faster).
    let seconds: f64 = estimates.iter().map(|e| e.seconds).sum();
    let longest = estimates.iter().map(|e| e.seconds).fold(0.0, f64::max);
    let per_job = estimates.iter().map(|e| e.peak_memory).fold(0.0, f64::max);
    let peak = per_job * workers.min(jobs.len()) as f64;
    tell!(
        "estimate: {}: {} wall on {} ({:.2} CPU hours; the longest job {}), peak memory {} ({} per job, {} \
         at once); Slurm, this shard: {}",
        counted(jobs.len(), "job"),
        duration(seconds),
        counted(c.threads, "thread"),
        seconds * c.threads as f64 / 3600.0,
        duration(longest),
        memory(peak),
        memory(per_job),
        workers.min(jobs.len()),
        SlurmRequest::with_margins(seconds, peak)
    );
    tell!(
        "  (jobs already done are skipped when the study runs; {})",
        assumptions(&c, true)
    );
    Ok(())
}
