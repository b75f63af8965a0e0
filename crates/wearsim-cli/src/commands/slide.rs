//! `wearsim slide`: the sliding wear model on every load of a run file.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use wearsim::config::Units;
use wearsim::io::{write_json, write_text, OutputDir};
use wearsim::output::{series_csv, sliding_summary, unit_of, SlidingInputs};
use wearsim::sliding::{run_sliding, SlidingSetup};

use super::load_run;
use crate::progress::Progress;

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README) with a [sliding] table.
    run: PathBuf,
    /// Output folder (created if missing; an earlier `slide` there is replaced whole).
    #[arg(long)]
    out: PathBuf,
    /// Replace the output folder even when it holds another command's results or other files.
    #[arg(long)]
    overwrite: bool,
}

/// A value with the unit of the run's system, e.g. `1.2e-3 m²`.
pub fn with_unit(units: Units, quantity: &str, value: f64) -> String {
    let unit = unit_of(units, quantity);
    if unit.is_empty() {
        format!("{value:.4e}")
    } else {
        format!("{value:.4e} {unit}")
    }
}

/// An optional value with its unit, or "undefined".
fn maybe(units: Units, quantity: &str, value: Option<f64>) -> String {
    value.map_or("undefined".into(), |v| with_unit(units, quantity, v))
}

pub fn run(args: &Args) -> Result<()> {
    let run = &args.run;
    let config = load_run(run)?;
    let Some(sliding) = config.sliding.clone() else {
        bail!(
            "run file {}: a [sliding] table with `loads` is needed for `slide`",
            run.display()
        );
    };
    // The output folder is made (and checked) before any work.
    let out = OutputDir::begin(&args.out, "slide", args.overwrite)?;
    let pair = config.surface_pair()?;
    super::report_surfaces(&pair, false);
    let (top, bottom) = (&pair.top, &pair.bottom);
    let n = top.nx();
    sliding.check_grid(n)?;
    let units = config.units;
    eprintln!(
        "flow pressure p_m = {}",
        with_unit(units, "flow_pressure", config.material.flow_pressure())
    );
    for (g, d) in config
        .material
        .fracture_energies
        .iter()
        .zip(config.material.critical_diameters())
    {
        eprintln!(
            "𝒢 = {}: critical diameter d* = {} ({:.1} px)",
            with_unit(units, "fracture_energy", *g),
            with_unit(units, "critical_diameter", d),
            d / top.pixel_size()
        );
    }
    let steps_per_load = sliding.offsets(n).len();
    let mut setup = SlidingSetup::from_run(&config, &sliding);
    setup.interrupt = super::interrupt().clone();
    let progress = Progress::new("slide", "steps", (steps_per_load * sliding.loads.len()) as u64);
    let start = Instant::now();
    let runs = run_sliding(top, bottom, &setup, |view| {
        let note = format!("load {}/{}", view.load_index + 1, sliding.loads.len());
        progress.set(view.done as u64, view.total as u64, &note);
    });
    progress.finish();
    let runs = runs?;
    let seconds = start.elapsed().as_secs_f64();
    let mut inputs = SlidingInputs::of_run(&config, &sliding);
    inputs.warnings.extend(pair.warnings.iter().cloned());
    let summary = sliding_summary(&inputs, &runs, top.pixel_size(), seconds, steps_per_load);
    write_text(&out.join("series.csv"), &series_csv(&runs))?;
    write_json(&out.join("summary.json"), &summary)?;
    out.commit()?;
    for r in &runs {
        for w in &r.results {
            println!(
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
    if let Some(warnings) = summary["warnings"].as_array() {
        for w in warnings.iter().filter_map(|w| w.as_str()) {
            eprintln!("warning: {w}");
        }
    }
    println!(
        "{} steps in {seconds:.1} s; wrote {}",
        steps_per_load * runs.len(),
        args.out.display()
    );
    Ok(())
}
