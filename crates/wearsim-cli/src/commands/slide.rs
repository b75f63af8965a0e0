//! `wearsim slide`: the sliding wear model on every load of a run file.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use wearsim::config::Units;
use wearsim::io::{write_json, write_text};
use wearsim::output::{series_csv, sliding_summary, SlidingInputs};
use wearsim::sliding::{run_sliding, schedule, SlidingSetup};

use super::{create_dir, load_run};

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README) with a [sliding] table.
    run: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    out: PathBuf,
}

/// Length in the run's unit, and the same for display (µm in SI runs).
pub fn show_length(units: Units, value: f64) -> String {
    match units {
        Units::Reduced => format!("{value:.5} L"),
        Units::Si => format!("{:.4} µm", value * 1e6),
    }
}

pub fn run(args: &Args) -> Result<()> {
    let (run, out) = (&args.run, &args.out);
    let config = load_run(run)?;
    let Some(sliding) = config.sliding.clone() else {
        bail!(
            "run file {}: a [sliding] table with `loads` is needed for `slide`",
            run.display()
        );
    };
    let (top, bottom) = config.surfaces()?;
    let n = top.n();
    let flow_pressure = config.material.flow_pressure();
    let diameters = config.material.critical_diameters();
    eprintln!(
        "flow pressure p_m = {flow_pressure:.6e} ({})",
        if config.units == Units::Si { "Pa" } else { "E" }
    );
    for (g, d) in config.material.fracture_energies.iter().zip(&diameters) {
        eprintln!(
            "𝒢 = {g:.4e}: critical diameter d* = {} ({:.1} px)",
            show_length(config.units, *d),
            d / top.pixel_size()
        );
    }
    let steps_per_load = schedule(n, &sliding).len();
    let setup = SlidingSetup::from_run(&config, &sliding);
    let bar = if std::io::stderr().is_terminal() {
        let b = indicatif::ProgressBar::new((steps_per_load * sliding.loads.len()) as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} steps, {per_sec}, {eta} left")
                .expect("valid template"),
        );
        Some(b)
    } else {
        None
    };
    let start = Instant::now();
    let runs = run_sliding(&top, &bottom, &setup, |view| {
        let (done, total) = (view.done, view.total);
        if let Some(b) = &bar {
            b.set_position(done as u64);
        } else if done % steps_per_load == 0 {
            eprintln!(
                "load {}/{} done ({done}/{total} steps, {:.1} s)",
                done / steps_per_load,
                sliding.loads.len(),
                start.elapsed().as_secs_f64()
            );
        }
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let seconds = start.elapsed().as_secs_f64();
    create_dir(out)?;
    write_text(&out.join("series.csv"), &series_csv(&runs))?;
    let summary = sliding_summary(
        &SlidingInputs::of_run(&config, &sliding),
        &runs,
        seconds,
        steps_per_load,
    );
    write_json(&out.join("summary.json"), &summary)?;
    for r in &runs {
        for w in &r.results {
            println!(
                "F_N = {:.4e}, d* = {}: W = {:.4e} (R² = {:.3}), k = {:.4e}, dN*₊/ds = {:.4e}, V₀ = {:.4e}, k_static = {:.4}",
                r.load,
                show_length(config.units, w.critical_diameter),
                w.wear_rate,
                w.wear_rate_r2,
                w.wear_coefficient,
                w.particle_rate,
                w.initial_volume,
                w.static_wear_coefficient
            );
        }
    }
    println!(
        "{} steps in {seconds:.1} s; wrote {}",
        steps_per_load * runs.len(),
        out.display()
    );
    Ok(())
}
