//! `wearsim slide`: the sliding wear model on every load of a run file.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use wearsim::config::{RunConfig, Units};
use wearsim::io::{write_json, write_text, OutputDir};
use wearsim::model::WearModel;
use wearsim::output::{unit_of, FieldSelection, FieldsWriter};
use wearsim::run::{SlidingOutcome, SlidingRun};
use wearsim::sliding::{Checkpointing, Resumed};

use super::load_run;
use crate::out::{say, tell};
use crate::progress::Progress;

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README) with a `[sliding]` table.
    run: PathBuf,
    #[command(flatten)]
    output: super::OutputFolder,
    /// Also write the per-step contact pressure, contact map and junction labels to
    /// OUT/fields.zarr (Zarr, chunked and compressed; `xarray.open_zarr` opens it with
    /// coordinates load, s, x, y and units).
    #[arg(long)]
    save_fields: bool,
    /// Keep the fields of these loads only (indices into `loads`, from 0; default: all).
    #[arg(long, value_delimiter = ',', requires = "save_fields", value_name = "I,J,…")]
    fields_loads: Vec<usize>,
    /// Keep the fields of every K-th step only (s = 0 always; default: every step).
    #[arg(long, default_value_t = 1, requires = "save_fields", value_name = "K")]
    fields_every: usize,
    /// Save the run's state this often (e.g. 30s, 5m, 1h) beside OUT, as .OUT.checkpoint, so that
    /// the same command run again after a kill (a Slurm wall-time limit) resumes from it to the
    /// results of an uninterrupted run; removed once the results are written. Not with
    /// --save-fields (the fields of the steps before a kill are not kept).
    #[arg(long, default_value = "5m", value_parser = humantime::parse_duration, value_name = "DURATION")]
    checkpoint_every: std::time::Duration,
    /// Print the cost estimate (wall time, peak memory, Slurm --time and --mem) and stop: nothing
    /// is computed or written (every run prints it before it starts).
    #[arg(long)]
    dry_run: bool,
}

/// The checkpoint file of a run into `out`: `.NAME.checkpoint` beside it.
pub fn checkpoint_path(out: &std::path::Path) -> PathBuf {
    let name = out
        .file_name()
        .map_or("out".into(), |n| n.to_string_lossy().to_string());
    wearsim::io::parent_or_dot(out).join(format!(".{name}.checkpoint"))
}

/// Says on stderr what became of the checkpoint `path`.
pub fn report_checkpoint(path: &std::path::Path, resumed: &Resumed) {
    match resumed {
        Resumed::Fresh => {}
        Resumed::At { done, total } => tell!("resuming from the checkpoint after {done} of {total} steps"),
        Resumed::Ignored(why) => tell!("warning: checkpoint not used: {why}"),
        Resumed::Saved { done, total } => tell!(
            "saved the state after {done} of {total} steps in {}: the same command run again resumes from it",
            path.display()
        ),
        Resumed::NotSaved(why) => tell!("warning: checkpoint not saved: {why}"),
    }
}

/// A value with the unit of the run's system, e.g. `1.2e-3 m²` (none for counts and ratios).
pub fn with_unit(units: Units, quantity: &str, value: f64) -> String {
    let unit = unit_of(units, quantity);
    if unit.is_empty() || unit == "1" {
        format!("{value:.4e}")
    } else {
        format!("{value:.4e} {unit}")
    }
}

/// Says on stderr the critical diameter d* of every fracture energy of the run, with its unit and
/// in pixels of its grid (the library's `SlidingRun::critical_diameters`).
pub fn report_critical_diameters(prepared: &SlidingRun) {
    let units = prepared.config().units;
    for c in prepared.critical_diameters() {
        tell!(
            "𝒢 = {}: critical diameter d* = {} ({:.1} px)",
            with_unit(units, "fracture_energy", c.fracture_energy),
            with_unit(units, "critical_diameter", c.diameter),
            c.pixels
        );
    }
}

/// An optional value with its unit, or "undefined".
fn maybe(units: Units, quantity: &str, value: Option<f64>) -> String {
    value.map_or("undefined".into(), |v| with_unit(units, quantity, v))
}

/// The fields store of `--save-fields`, its size before compression said first.
fn fields_writer(args: &Args, out: &OutputDir, prepared: &SlidingRun) -> Result<FieldsWriter> {
    let (grid, sliding, offsets) = (prepared.grid(), prepared.sliding(), prepared.offsets());
    let selection = FieldSelection {
        loads: args.fields_loads.clone(),
        every: args.fields_every,
    };
    let raw = FieldsWriter::raw_bytes(grid, sliding.loads.len(), offsets.len(), &selection);
    tell!(
        "fields: {:.1} MB before compression (13 bytes per pixel and kept step), into {}",
        raw as f64 / 1e6,
        args.output.out.join("fields.zarr").display()
    );
    Ok(FieldsWriter::create(
        &out.join("fields.zarr"),
        grid,
        prepared.config().units,
        &sliding.loads,
        &offsets,
        &selection,
        prepared.inputs().to_json(),
    )?)
}

/// One line per load and fracture energy: W, k, dN*₊/ds, V₀ and the static model.
fn print_results(units: Units, runs: &[wearsim::sliding::LoadRun]) {
    for r in runs {
        for w in &r.results {
            say!(
                "F_N = {}, d* = {}: W = {} (R² = {}), k = {}, dN*₊/ds = {}, V₀ = {}, k_static = {:.4} (s = 0), {:.4} ± {:.4} \
                 (all offsets)",
                with_unit(units, "load", r.load),
                with_unit(units, "critical_diameter", w.critical_diameter),
                maybe(units, "wear_rate", w.wear_rate),
                w.wear_rate_r2.map_or("undefined".into(), |r2| format!("{r2:.3}")),
                maybe(units, "wear_coefficient", w.wear_coefficient),
                maybe(units, "particle_rate", w.particle_rate),
                with_unit(units, "initial_volume", w.initial_volume),
                w.static_wear_coefficient,
                w.static_wear_coefficient_mean,
                w.static_wear_coefficient_std,
            );
        }
    }
}

/// The note of a run file whose model takes no sliding step (`slide` runs the sliding model
/// whatever it names): which commands make what it asks for.
fn note_other_model(model: WearModel) {
    let makers = model
        .command()
        .map_or("study jobs".into(), |c| format!("`wearsim {c}` and study jobs"));
    tell!(
        "note: the run file asks for {} (`[sliding] model = \"{}\"`), which {makers} make; `slide` runs the \
         sliding model",
        model.description(),
        model.name()
    );
}

/// The output folder, made (and checked) before any work; none for a dry run, which writes nothing.
fn output_folder(args: &Args, config: &RunConfig) -> Result<Option<OutputDir>> {
    if args.dry_run {
        return Ok(None);
    }
    let folder = OutputDir::begin(
        &args.output.out,
        "slide",
        args.output.overwrite.replace,
        &super::run_inputs(&args.run, config),
    )?;
    Ok(Some(folder))
}

pub fn run(args: &Args) -> Result<()> {
    let run = &args.run;
    super::polls_interrupt();
    let config = load_run(run)?;
    wearsim::run::sliding_schedule(&config).with_context(|| format!("run file {}", run.display()))?;
    if !config.model.slides() {
        note_other_model(config.model);
    }
    let interrupt = super::interrupt();
    let out = output_folder(args, &config)?;
    // The surfaces are made once: the cost estimate measures a few steps on them, and the run
    // slides on them.
    let prepared = SlidingRun::prepare(&config)?.interrupted_by(interrupt);
    // The estimate comes before the run: a dry run on a login node sizes a job for the nodes it will
    // run on.
    super::cost::report_run(&prepared, args.dry_run)?;
    let Some(out) = out else {
        // What the run would warn about before its first step (d* against the pixel and the box,
        // the run file's, the surfaces'), said by the dry run too.
        report_critical_diameters(&prepared);
        for w in prepared.warnings() {
            tell!("warning: {w}");
        }
        return Ok(());
    };
    super::report_surfaces(prepared.surfaces(), false);
    let sliding = prepared.sliding();
    let units = config.units;
    tell!(
        "flow pressure p_m = {}",
        with_unit(units, "flow_pressure", config.material.flow_pressure())
    );
    report_critical_diameters(&prepared);
    let steps_per_load = prepared.offsets().len();
    let mut fields = if args.save_fields {
        Some(fields_writer(args, &out, &prepared)?)
    } else {
        None
    };
    let progress = Progress::new("slide", "steps", prepared.total_steps() as u64);
    let mut fields_error = None;
    let checkpointing = (!args.save_fields).then(|| Checkpointing {
        path: checkpoint_path(out.target()),
        every: args.checkpoint_every,
    });
    let report = |r: &Resumed| report_checkpoint(&checkpoint_path(out.target()), r);
    let outcome = prepared.run_resumable(checkpointing.as_ref(), report, |view| {
        let note = format!("load {}/{}", view.load_index + 1, sliding.loads.len());
        progress.set(view.done as u64, view.total as u64, &note);
        if let (Some(f), None) = (fields.as_mut(), fields_error.as_ref()) {
            let (load_index, step_index, labeller) = (view.load_index, view.step_index, view.labeller);
            if let Err(e) = f.record(load_index, step_index, view.pressure(), labeller.labels()) {
                // Stop the run: its outputs could not all be written.
                fields_error = Some(e);
                interrupt.request();
            }
        }
    });
    progress.finish();
    if let Some(e) = fields_error {
        return Err(e.into());
    }
    let outcome = outcome?;
    if let Some(f) = fields {
        f.finish()?;
    }
    write_text(&out.join("series.csv"), &outcome.series_csv())?;
    write_json(&out.join("summary.json"), &outcome.summary())?;
    super::check_interrupt()?;
    out.commit()?;
    // The results are in place: the state they were resumed from is no longer needed.
    if let Some(c) = &checkpointing {
        let _ = std::fs::remove_file(&c.path);
    }
    print_outcome(units, &outcome, steps_per_load, &args.output.out);
    Ok(())
}

/// The results of a finished slide, its warnings, and the steps and time it took (`steps_per_load`
/// per load) with the folder written.
fn print_outcome(units: Units, outcome: &SlidingOutcome, steps_per_load: usize, out: &Path) {
    print_results(units, &outcome.runs);
    for w in &outcome.warnings {
        tell!("warning: {w}");
    }
    say!(
        "{} steps in {:.1} s; wrote {}",
        steps_per_load * outcome.runs.len(),
        outcome.seconds,
        out.display()
    );
}
