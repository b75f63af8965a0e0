//! `wearsim slide` and `wearsim junctions`: the sliding wear model on a run file, and junction
//! labelling of a contact map.

use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use serde_json::json;
use wearsim::config::{RunConfig, Units};
use wearsim::junctions::{JunctionLabeller, NO_JUNCTION};
use wearsim::output::{atomic_write, series_csv, sliding_summary, write_text, RunInputs};
use wearsim::sliding::{run_sliding, schedule, SlidingSetup};

/// Length in the run's unit, and the same for display (µm in SI runs).
fn show_length(units: Units, value: f64) -> String {
    match units {
        Units::Reduced => format!("{value:.5} L"),
        Units::Si => format!("{:.4} µm", value * 1e6),
    }
}

pub fn slide(run: &Path, out: &Path) -> Result<()> {
    let config = RunConfig::from_path(run).with_context(|| format!("run file {}", run.display()))?;
    let Some(sliding) = config.sliding.clone() else {
        bail!(
            "run file {}: a [sliding] table with `loads` is needed for `slide`",
            run.display()
        );
    };
    if config.material.fracture_energies.is_empty() {
        bail!(
            "run file {}: [material] `fracture_energies` is empty; give at least one 𝒢",
            run.display()
        );
    }
    let (top, bottom) = config.surfaces()?;
    let n = top.n();
    if sliding.step >= n || sliding.step_running_in >= n {
        bail!("[sliding] steps must be below the grid size {n}");
    }
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
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))?;
    write_text(&out.join("series.csv"), &series_csv(&runs))?;
    let summary = sliding_summary(&RunInputs::of_run(&config, &sliding), &runs, seconds, steps_per_load);
    write_text(&out.join("summary.json"), &serde_json::to_string_pretty(&summary)?)?;
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

/// Labels the junctions of a contact map (`.npy`, bool or numbers: > 0 is contact) and writes
/// `labels.npy` (int64, −1 outside contact) and `junctions.json` (pixel count per junction).
pub fn junctions(map: &Path, connectivity: u8, out: &Path) -> Result<()> {
    use ndarray::Array2;
    use ndarray_npy::ReadNpyExt;
    wearsim::junctions::check_connectivity(connectivity).context("--connectivity")?;
    let open = || std::fs::File::open(map).with_context(|| format!("cannot open {}", map.display()));
    let flags: Array2<bool> = match Array2::<bool>::read_npy(open()?) {
        Ok(a) => a,
        Err(_) => match Array2::<f64>::read_npy(open()?) {
            Ok(a) => a.mapv(|v| v > 0.0),
            Err(e) => bail!("{}: not a 2D bool or float64 .npy array ({e})", map.display()),
        },
    };
    let (rows, cols) = flags.dim();
    if rows != cols || rows == 0 {
        bail!(
            "{}: contact map is {rows}×{cols}; it must be square and non-empty",
            map.display()
        );
    }
    let flat: Vec<bool> = flags.iter().copied().collect();
    let mut labeller = JunctionLabeller::new(rows, connectivity);
    let count = labeller.label(|k| flat[k]);
    let labels: Vec<i64> = labeller
        .labels()
        .iter()
        .map(|&l| if l == NO_JUNCTION { -1 } else { l as i64 })
        .collect();
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))?;
    let array = ndarray::Array2::from_shape_vec((rows, rows), labels)?;
    atomic_write(&out.join("labels.npy"), |w| {
        use ndarray_npy::WriteNpyExt;
        array.write_npy(w).map_err(std::io::Error::other)
    })?;
    let doc = json!({"software": format!("wearsim {}", wearsim::VERSION), "connectivity": connectivity, "junctions": count, "pixels": labeller.sizes()});
    write_text(&out.join("junctions.json"), &serde_json::to_string_pretty(&doc)?)?;
    println!("{count} junctions; wrote {}", out.display());
    Ok(())
}
