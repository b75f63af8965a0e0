//! `wearsim study run | collect`: studies on the local machine or as a Slurm job array.

use std::path::{Path, PathBuf};

use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use wearsim::study::{
    collect as collect_study, expand, prepare_folder, run_jobs, shard, workers_for_memory, Job, RunSummary,
};

use crate::out::{say, tell};

#[derive(clap::Args)]
pub struct RunArgs {
    /// Study file (a run file whose fields may be lists, or with `[[materials]]`).
    study: PathBuf,
    /// Study folder (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Run only shard K of N (jobs with index ≡ K−1 mod N); default from SLURM_ARRAY_TASK_ID /
    /// SLURM_ARRAY_TASK_COUNT inside a Slurm job array, else 1/1.
    #[arg(long)]
    shard: Option<String>,
    /// Jobs run at once, sharing the threads (default: one job per thread); 1 for large grids.
    #[arg(long)]
    jobs: Option<usize>,
    /// Each job saves its state this often (e.g. 30s, 5m, 1h) beside its job file, so that a job
    /// killed part-way (a Slurm wall-time limit) resumes in the next run to the results of an
    /// uninterrupted one; the checkpoint is removed once the job file is written.
    #[arg(long, default_value = "5m", value_parser = humantime::parse_duration, value_name = "DURATION")]
    checkpoint_every: std::time::Duration,
    /// Print the cost estimate of this shard's jobs (wall time, CPU hours, peak memory, Slurm --time
    /// and --mem) and stop: no study folder is made (every run prints it before it starts).
    #[arg(long)]
    dry_run: bool,
}

#[derive(clap::Args)]
pub struct CollectArgs {
    /// Study folder.
    dir: PathBuf,
}

/// `K/N` from `--shard`, else from a Slurm job array, else 1/1.
fn resolve_shard(arg: Option<&str>) -> Result<(usize, usize)> {
    let parse = |k: &str, n: &str| -> Result<(usize, usize)> {
        let (k, n): (usize, usize) = (k.trim().parse()?, n.trim().parse()?);
        if n == 0 || k == 0 || k > n {
            bail!("invalid shard {k}/{n}: need 1 ≤ K ≤ N");
        }
        Ok((k, n))
    };
    if let Some(a) = arg {
        let (k, n) = a
            .split_once('/')
            .with_context(|| format!("invalid `--shard {a}`: write K/N, e.g. 2/8"))?;
        return parse(k, n).with_context(|| format!("invalid `--shard {a}`"));
    }
    if let Ok(id) = std::env::var("SLURM_ARRAY_TASK_ID") {
        return slurm_shard(&id, |name| std::env::var(name).ok());
    }
    Ok((1, 1))
}

/// The shard of a Slurm job-array task: its position among the array's evenly spaced task IDs
/// (`--array=1-320`, `--array=0-99:4`), from SLURM_ARRAY_TASK_ID/MIN/STEP/COUNT. An array whose IDs
/// are not evenly spaced (`--array=3,7,9`) cannot say the position; the shard must then be given.
fn slurm_shard(id: &str, var: impl Fn(&str) -> Option<String>) -> Result<(usize, usize)> {
    let number = |name: &str, value: Option<String>| -> Result<usize> {
        let value = value.with_context(|| format!("{name} is not set inside this Slurm job array"))?;
        value
            .trim()
            .parse()
            .with_context(|| format!("{name} = {value:?} is not a whole number"))
    };
    // Unset is `None`; set to something that is no whole number is an error naming it.
    let optional = |name: &str| var(name).map(|v| number(name, Some(v))).transpose();
    let id = number("SLURM_ARRAY_TASK_ID", Some(id.to_string()))?;
    let count = number("SLURM_ARRAY_TASK_COUNT", var("SLURM_ARRAY_TASK_COUNT"))?;
    let Some(min) = optional("SLURM_ARRAY_TASK_MIN")? else {
        bail!(
            "Slurm job array: SLURM_ARRAY_TASK_ID = {id} and SLURM_ARRAY_TASK_COUNT = {count} are set but \
             SLURM_ARRAY_TASK_MIN is not, so the position of task {id} in the array (its shard) is unknown; give \
             --shard K/{count} (K of {count} shards, e.g. --shard 1/{count} for the array's first task), or set \
             SLURM_ARRAY_TASK_MIN to the array's first task ID"
        );
    };
    let max = optional("SLURM_ARRAY_TASK_MAX")?;
    let step = optional("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
    if count == 0 {
        bail!(
            "Slurm job array: SLURM_ARRAY_TASK_COUNT = 0 for task {id}, so its shard is unknown; give --shard K/N \
             (K of N shards, e.g. --shard 1/4), or submit with --array=1-N"
        );
    }
    let offset = id
        .checked_sub(min)
        .with_context(|| format!("SLURM_ARRAY_TASK_ID {id} is below SLURM_ARRAY_TASK_MIN {min}"))?;
    let evenly = offset % step == 0 && offset / step < count && max.is_none_or(|max| min + (count - 1) * step == max);
    if !evenly {
        bail!(
            "Slurm job array: task {id} of an array of {count} tasks from {min} to {} (step {step}) is not at an evenly \
             spaced position, so its shard is unknown; use a range such as --array=1-{count} or give --shard K/{count}",
            max.map_or("?".into(), |m| m.to_string())
        );
    }
    Ok((offset / step + 1, count))
}

pub fn run(args: &RunArgs) -> Result<()> {
    super::polls_interrupt();
    let (study_path, out, shard_arg, workers) = (&args.study, &args.out, args.shard.as_deref(), args.jobs);
    let text = std::fs::read_to_string(study_path).with_context(|| format!("cannot read {}", study_path.display()))?;
    let base = study_path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let study = expand(&text, base).with_context(|| format!("study file {}", study_path.display()))?;
    for warning in &study.warnings {
        tell!("warning: study file {}: {warning}", study_path.display());
    }
    let (k, n) = resolve_shard(shard_arg)?;
    let jobs = shard(&study.jobs, k, n);
    let requested = workers.unwrap_or_else(rayon::current_num_threads);
    let (workers, note) = workers_for_memory(&jobs, requested)?;
    if let Some(note) = note {
        tell!("note: {note}");
    }
    super::cost::report_study(&jobs, workers, args.dry_run)?;
    if args.dry_run {
        report_conversions(&jobs);
        return report_warnings_before_run(&jobs);
    }
    report_conversions(&jobs);
    // The study file is an input too: a study folder holding it would overwrite or mix with it.
    wearsim::io::refuse_inputs_inside(out, &[study_path.as_path()])?;
    prepare_folder(out, &study, base)?;
    tell!(
        "study {}: {} jobs, shard {k}/{n} holds {}; {workers} workers",
        study.hash,
        study.jobs.len(),
        jobs.len()
    );
    // Progress in sliding steps over every pending job (a study of a few 4096² jobs moves between
    // jobs too), with the jobs finished beside it.
    let progress = Progress::new("study", "steps", 0);
    let outcome = run_jobs(
        out,
        &jobs,
        workers,
        Some(args.checkpoint_every),
        super::interrupt(),
        |p| {
            progress.set(
                p.steps_done as u64,
                p.steps_total as u64,
                &format!("{}/{} jobs done", p.jobs_done, p.jobs_total),
            )
        },
    );
    progress.finish();
    if let (Err(wearsim::Error::Interrupted), Some(sig)) = (&outcome, super::stop_signal()) {
        tell!(
            "{}: the finished jobs are saved in {} and the jobs under way saved their state beside them; the same \
             command run again resumes",
            super::signal_name(sig),
            out.join("jobs").display()
        );
    }
    report_run(out, &outcome?);
    Ok(())
}

/// The study file's values given in another form than the model's inputs (a hardness, a pressure),
/// each conversion once with the jobs it was made for.
fn report_conversions(jobs: &[&Job]) {
    for (note, of) in by_jobs(jobs, |job| Ok(job.run.conversions.clone())).unwrap_or_default() {
        tell!("{note} ({of})");
    }
}

/// What the jobs would warn about before their first step (d* against the pixel and the box, the
/// solver's tolerance), each warning once with the jobs it concerns: what a dry run says before
/// the work, as `slide --dry-run` does.
fn report_warnings_before_run(jobs: &[&Job]) -> Result<()> {
    let warned = by_jobs(jobs, |job| {
        let grid = job.run.grid().with_context(|| job.describe())?;
        Ok(wearsim::run::warnings_before_run(&job.run, grid, &[]))
    })?;
    for (warning, of) in warned {
        tell!("warning: {warning} ({of})");
    }
    Ok(())
}

/// Each distinct line that `lines` gives for the jobs, in the order first given, with "job 3" or
/// "jobs 0–1, 4 (3 of 12)" for the jobs that gave it.
fn by_jobs(jobs: &[&Job], lines: impl Fn(&Job) -> Result<Vec<String>>) -> Result<Vec<(String, String)>> {
    let mut found: Vec<(String, Vec<usize>)> = Vec::new();
    for job in jobs {
        for line in lines(job)? {
            match found.iter_mut().find(|(l, _)| *l == line) {
                Some((_, of)) => of.push(job.index),
                None => found.push((line, vec![job.index])),
            }
        }
    }
    Ok(found
        .into_iter()
        .map(|(line, of)| {
            // As estimate-check writes its warnings' jobs: as ranges (the jobs are in index order).
            let which = match of.as_slice() {
                [one] => format!("job {one}"),
                _ if of.len() == jobs.len() => format!("all {} jobs", jobs.len()),
                _ => format!(
                    "jobs {} ({} of {})",
                    wearsim::study::compare::job_ranges(&of),
                    of.len(),
                    jobs.len()
                ),
            };
            (line, which)
        })
        .collect())
}

/// What a study run did: the checkpoints' and recomputed jobs' warnings, the jobs computed and
/// skipped, and the jobs left to another run on folder `out` with who holds them.
fn report_run(out: &Path, summary: &RunSummary) {
    for note in &summary.checkpoint_warnings {
        tell!("warning: {note}");
    }
    for why in &summary.recomputed {
        tell!("warning: recomputed a job whose file could not be read: {why}");
    }
    say!(
        "computed {} jobs, skipped {} already done; results in {}",
        summary.computed,
        summary.skipped,
        out.join("jobs").display()
    );
    if !summary.claimed_elsewhere.is_empty() {
        tell!(
            "warning: {} jobs of this shard are not computed: another run on this folder claims them and had not \
             finished them when this run ended; run the same command again once that run has finished (a claim not \
             refreshed for {} min is taken over), then `wearsim study collect`:",
            summary.claimed_elsewhere.len(),
            wearsim::study::store::CLAIM_EXPIRY.as_secs() / 60
        );
        for &i in &summary.claimed_elsewhere {
            let holder = wearsim::study::store::Claim::holder(out, i)
                .unwrap_or_else(|| "its claim is gone, the job is not done".into());
            tell!("  job {i}: {holder}");
        }
    }
}

pub fn collect(args: &CollectArgs) -> Result<()> {
    let dir = &args.dir;
    let (rows, groups) = collect_study(dir)?;
    say!(
        "wrote {} ({rows} rows) and {} ({groups} rows)",
        dir.join("results.csv").display(),
        dir.join("results_aggregated.csv").display()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::slurm_shard;

    fn env(vars: &'static [(&'static str, &'static str)]) -> impl Fn(&str) -> Option<String> {
        move |name| vars.iter().find(|(k, _)| *k == name).map(|(_, v)| v.to_string())
    }

    #[test]
    fn slurm_arrays_with_a_step_give_the_position_and_lists_are_refused() {
        let plain = env(&[
            ("SLURM_ARRAY_TASK_COUNT", "320"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "320"),
        ]);
        assert_eq!(slurm_shard("1", &plain).unwrap(), (1, 320));
        assert_eq!(slurm_shard("320", &plain).unwrap(), (320, 320));
        // --array=1-320:2 → 160 tasks 1, 3, …, 319.
        let stepped = env(&[
            ("SLURM_ARRAY_TASK_COUNT", "160"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "319"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
        ]);
        assert_eq!(slurm_shard("3", &stepped).unwrap(), (2, 160));
        assert_eq!(slurm_shard("319", &stepped).unwrap(), (160, 160));
        // --array=3,7,9: not evenly spaced.
        let list = env(&[
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "3"),
            ("SLURM_ARRAY_TASK_MAX", "9"),
        ]);
        let e = slurm_shard("7", &list).unwrap_err().to_string();
        assert!(e.contains("--shard K/3"), "{e}");
        // A count of 0 (a broken environment) asks for --shard, never for an empty range.
        let zero = env(&[("SLURM_ARRAY_TASK_COUNT", "0"), ("SLURM_ARRAY_TASK_MIN", "1")]);
        let e = slurm_shard("1", &zero).unwrap_err().to_string();
        assert!(
            e.contains("--shard K/N") && !e.contains("1-0") && !e.contains("K/0"),
            "{e}"
        );
    }

    #[test]
    fn a_missing_or_garbled_array_variable_is_named_never_guessed() {
        // Task 1 of --array=1-2 without SLURM_ARRAY_TASK_MIN: not shard 2/2.
        let no_min = env(&[("SLURM_ARRAY_TASK_COUNT", "2"), ("SLURM_ARRAY_TASK_MAX", "2")]);
        let e = slurm_shard("1", &no_min).unwrap_err().to_string();
        assert!(
            e.contains("SLURM_ARRAY_TASK_MIN is not") && e.contains("--shard K/2"),
            "{e}"
        );
        for (name, value) in [
            ("SLURM_ARRAY_TASK_MIN", "one"),
            ("SLURM_ARRAY_TASK_MAX", "2x"),
            ("SLURM_ARRAY_TASK_STEP", "-1"),
        ] {
            let vars: Vec<(&str, &str)> = [
                ("SLURM_ARRAY_TASK_COUNT", "2"),
                ("SLURM_ARRAY_TASK_MIN", "1"),
                ("SLURM_ARRAY_TASK_MAX", "2"),
            ]
            .into_iter()
            .filter(|(k, _)| *k != name)
            .chain([(name, value)])
            .collect();
            let var = |n: &str| vars.iter().find(|(k, _)| *k == n).map(|(_, v)| v.to_string());
            let e = format!("{:#}", slurm_shard("1", var).unwrap_err());
            assert!(e.contains(&format!("{name} = \"{value}\"")), "{e}");
        }
    }
}
