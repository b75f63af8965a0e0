//! `wearsim estimate`: the static estimate of W, k and dN*₊/ds from a few contact solutions;
//! `wearsim estimate-check`: the estimate against the sliding runs of a study, and the fit of its
//! constants.

use std::path::PathBuf;

use anyhow::{Context, Result};
use wearsim::config::Units;
use wearsim::estimate::{Calibration, Sampling, CALIBRATION, MAX_SAMPLES};
use wearsim::io::{write_json, write_text, OutputDir};
use wearsim::output::{Table, ESTIMATE_NOTICE};
use wearsim::run::SlidingRun;
use wearsim::study::compare::{compare, fit_warnings, map_jobs, refuse_output_in_study, CheckOutcome};

use super::load_run;
use super::slide::{report_critical_diameters, with_unit};
use crate::out::{say, tell};
use crate::progress::Progress;

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README) with a `[sliding]` table: its loads, and the sliding distance of
    /// the run whose 95 % interval is given.
    run: PathBuf,
    #[command(flatten)]
    output: super::OutputFolder,
    /// Static maps per load (1 to 16; default: the run file's `estimate_samples`, else from 4 until
    /// N*'s sampling error is at most 10 %).
    #[arg(long, value_name = "K")]
    samples: Option<usize>,
}

#[derive(clap::Args)]
pub struct CheckArgs {
    /// Study folder of finished sliding jobs (`wearsim study run`); unfinished jobs are left out.
    dir: PathBuf,
    /// Output folder for comparison.csv and summary.json.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
    /// Fit the constants on these runs and print them; comparison.csv and the summary's `summary`
    /// then use the fitted constants (`summary_with_calibration_in_use` the library's).
    #[arg(long)]
    fit: bool,
    /// Settings the median and worst errors are taken over: at least this many particles in the
    /// sliding run's fit window (fewer scatter by Poisson alone). The coverage of the interval is
    /// counted over every setting, whatever its particles.
    #[arg(long, default_value_t = 20)]
    min_particles: usize,
    /// Static maps per job (default: the study's `estimate_samples`, else chosen by the sampling
    /// error, as `estimate` does).
    #[arg(long, value_name = "K")]
    samples: Option<usize>,
}

fn maybe(units: Units, quantity: &str, value: Option<f64>) -> String {
    value.map_or("undefined".into(), |v| with_unit(units, quantity, v))
}

fn interval(units: Units, quantity: &str, lo: Option<f64>, hi: Option<f64>) -> String {
    match (lo, hi) {
        (Some(lo), Some(hi)) => format!(
            " [{}, {}]",
            with_unit(units, quantity, lo),
            with_unit(units, quantity, hi)
        ),
        _ => "".into(),
    }
}

/// What a result says where it has no interval although W is defined.
fn withheld(r: &wearsim::estimate::EstimateResult) -> String {
    r.interval_withheld
        .as_ref()
        .map_or(String::new(), |why| format!(" (no 95 % interval: {why})"))
}

pub fn run(args: &Args) -> Result<()> {
    let run = &args.run;
    super::polls_interrupt();
    let config = load_run(run)?;
    wearsim::run::sliding_schedule(&config).with_context(|| format!("run file {}", run.display()))?;
    let sampling = Sampling::of(args.samples.or(config.estimate_samples)).context("--samples")?;
    let grid = config.grid()?;
    wearsim::check::memory("an estimate", grid.nx(), grid.ny(), wearsim::check::CONTACT_ARRAYS)?;
    let out = OutputDir::begin(
        &args.output.out,
        "estimate",
        args.output.overwrite.replace,
        &super::run_inputs(run, &config),
    )?;
    let prepared = SlidingRun::prepare(&config)?.interrupted_by(super::interrupt());
    super::report_surfaces(prepared.surfaces(), false);
    let units = config.units;
    report_critical_diameters(&prepared);
    let loads = prepared.sliding().loads.len();
    let progress = Progress::new("estimate", "solves", (loads * MAX_SAMPLES) as u64);
    let outcome = prepared.estimate(sampling, &config.estimate_calibration(), |done, most| {
        progress.set(done as u64, most as u64, "static maps")
    });
    progress.finish();
    let outcome = outcome?;
    write_text(&out.join("results.csv"), &outcome.results_csv())?;
    write_json(&out.join("summary.json"), &outcome.summary())?;
    super::check_interrupt()?;
    out.commit()?;
    say!("ESTIMATE ({ESTIMATE_NOTICE})");
    for l in &outcome.loads {
        for r in &l.results {
            say!(
                "F_N = {}, d* = {}: W = {}{}, k = {}{}, dN*₊/ds = {}{}; N* = {:.2} (sampling error {}), d̄ = {}{}",
                with_unit(units, "load", l.load),
                with_unit(units, "critical_diameter", r.critical_diameter),
                maybe(units, "wear_rate", r.wear_rate),
                interval(units, "wear_rate", r.wear_rate_low, r.wear_rate_high),
                maybe(units, "wear_coefficient", r.wear_coefficient),
                interval(
                    units,
                    "wear_coefficient",
                    r.wear_coefficient_low,
                    r.wear_coefficient_high
                ),
                maybe(units, "particle_rate", r.particle_rate),
                interval(units, "particle_rate", r.particle_rate_low, r.particle_rate_high),
                r.critical_junctions_mean,
                r.critical_junctions_sampling_error
                    .map_or("undefined".into(), |e| format!("{:.1} %", 100.0 * e)),
                maybe(units, "mean_critical_diameter", r.mean_critical_diameter),
                withheld(r),
            );
        }
    }
    for w in &outcome.warnings {
        tell!("warning: {w}");
    }
    say!(
        "{} static maps per load (intervals: 95 % for a sliding run of this box and distance), {} loads in {:.1} s; \
         wrote {}",
        outcome.samples,
        loads,
        outcome.seconds,
        args.output.out.display()
    );
    Ok(())
}

/// The constants fitted by `estimate-check --fit`, and the run-file line that estimates with them.
fn print_fitted(c: &Calibration) {
    say!(
        "fitted on {} settings ({} particles): residence_factor (c₁) = {:.3}, merging_factor (c₂) = {:.2}, \
         volume_factor (c_v) = {:.3}, rate_spread = {:.3}, wear_spread = {:.3}",
        c.settings,
        c.particles,
        c.residence_factor,
        c.merging_factor,
        c.volume_factor,
        c.rate_spread,
        c.wear_spread
    );
    say!(
        "to estimate with them, add to the [sliding] table of a run file or study of these surfaces:\n  \
         estimate_constants = {{ residence_factor = {:?}, merging_factor = {:?}, volume_factor = {:?}, rate_spread = \
         {:?}, wear_spread = {:?} }}",
        c.residence_factor,
        c.merging_factor,
        c.volume_factor,
        c.rate_spread,
        c.wear_spread
    );
}

/// Warnings printed in full before the rest is left to summary.json.
const WARNINGS_SHOWN: usize = 12;

pub fn check(args: &CheckArgs) -> Result<()> {
    super::polls_interrupt();
    if let Some(k) = args.samples {
        Sampling::of(Some(k)).context("--samples")?;
    }
    let inputs = refuse_output_in_study(&args.out, &args.dir)?;
    let inputs: Vec<&std::path::Path> = inputs.iter().map(PathBuf::as_path).collect();
    let out = OutputDir::begin(&args.out, "estimate-check", args.overwrite.replace, &inputs)?;
    let progress = Progress::new("estimate-check", "jobs", 0);
    let mapped = map_jobs(&args.dir, args.samples, super::interrupt(), |done, total| {
        progress.set(done as u64, total as u64, "jobs estimated")
    });
    progress.finish();
    let mapped = mapped?;
    let (jobs, left_out) = (&mapped.jobs, mapped.left_out);
    if left_out > 0 {
        tell!("note: {left_out} jobs of the study are unfinished or estimates, and are left out");
    }
    let mut warnings = mapped.warning_lines();
    // Said before the fit, which may fail on the settings they concern.
    for w in warnings.iter().take(WARNINGS_SHOWN) {
        tell!("warning: {w}");
    }
    if warnings.len() > WARNINGS_SHOWN {
        tell!(
            "warning: … and {} more, in {}/summary.json (`warnings`)",
            warnings.len() - WARNINGS_SHOWN,
            args.out.display()
        );
    }
    let fitted = if args.fit {
        let rows = compare(jobs, &CALIBRATION);
        // Said before the fit, which may fail on the same settings.
        for w in fit_warnings(&rows) {
            tell!("warning: {w}");
            warnings.push(w);
        }
        let points: Vec<_> = rows.iter().map(|r| r.point()).collect();
        Some(Calibration::fit(&points)?)
    } else {
        None
    };
    let check = CheckOutcome::of(jobs, fitted, args.min_particles);
    write_text(&out.join("comparison.csv"), &Table::of(&check.rows).to_csv())?;
    write_json(
        &out.join("summary.json"),
        &check.document(&args.dir, &mapped, args.samples, &warnings),
    )?;
    super::check_interrupt()?;
    out.commit()?;
    if let Some(c) = check.fitted {
        print_fitted(&c);
        for line in check.summary.describe("with the fitted constants") {
            say!("{line}");
        }
    }
    for line in check.in_use.describe("with the constants in use") {
        say!("{line}");
    }
    say!("wrote {}", args.out.display());
    Ok(())
}
