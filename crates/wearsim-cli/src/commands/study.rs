//! `wearsim study run | collect`: studies on the local machine or as a Slurm job array.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use wearsim::study::{collect as collect_study, expand, prepare_folder, run_jobs, shard};

#[derive(clap::Args)]
pub struct RunArgs {
    /// Study file (a run file whose fields may be lists, or with [[materials]]).
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
    if let (Ok(id), Ok(count)) = (
        std::env::var("SLURM_ARRAY_TASK_ID"),
        std::env::var("SLURM_ARRAY_TASK_COUNT"),
    ) {
        let min: usize = std::env::var("SLURM_ARRAY_TASK_MIN")
            .ok()
            .and_then(|m| m.parse().ok())
            .unwrap_or(0);
        let id: usize = id.parse().context("SLURM_ARRAY_TASK_ID is not a number")?;
        return parse(&(id - min.min(id) + 1).to_string(), &count).context("Slurm job array");
    }
    Ok((1, 1))
}

pub fn run(args: &RunArgs) -> Result<()> {
    let (study_path, out, shard_arg, workers) = (&args.study, &args.out, args.shard.as_deref(), args.jobs);
    let text = std::fs::read_to_string(study_path).with_context(|| format!("cannot read {}", study_path.display()))?;
    let base = study_path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let study = expand(&text, base).with_context(|| format!("study file {}", study_path.display()))?;
    let (k, n) = resolve_shard(shard_arg)?;
    prepare_folder(out, &study, base)?;
    let jobs = shard(&study.jobs, k, n);
    let workers = workers.unwrap_or_else(rayon::current_num_threads);
    eprintln!(
        "study {}: {} jobs, shard {k}/{n} holds {}; {workers} workers",
        study.hash,
        study.jobs.len(),
        jobs.len()
    );
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new(0);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} jobs, {eta} left").expect("valid template"),
        );
        b
    });
    let (computed, skipped) = run_jobs(out, &jobs, workers, &Default::default(), |done, total| match &bar {
        Some(b) => {
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
        None => eprintln!("job {done}/{total} done"),
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    println!(
        "computed {computed} jobs, skipped {skipped} already done; results in {}",
        out.join("jobs").display()
    );
    Ok(())
}

pub fn collect(args: &CollectArgs) -> Result<()> {
    let dir = &args.dir;
    let (rows, groups) = collect_study(dir).with_context(|| format!("study folder {}", dir.display()))?;
    println!(
        "wrote {} ({rows} rows) and {} ({groups} rows)",
        dir.join("results.csv").display(),
        dir.join("results_aggregated.csv").display()
    );
    Ok(())
}
