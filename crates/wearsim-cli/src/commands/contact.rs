//! `wearsim contact`: one contact solve at a load and a sliding offset.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use wearsim::io::{write_json, write_npy_bool, write_npy_f64, OutputDir};
use wearsim::output::{contact_summary, ContactRecord};
use wearsim::{composite_heights, ContactSolver};

use super::load_run;

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README).
    run: PathBuf,
    /// Normal load F_N in the run's units (E·L² reduced, N in SI).
    #[arg(long, allow_hyphen_values = true)]
    load: f64,
    /// Sliding offset of the top surface along x, in the run's length unit, within one period
    /// [0, Lx); rounded to whole pixels (with a note when it is not one).
    #[arg(long, conflicts_with = "offset_px", allow_hyphen_values = true)]
    offset: Option<f64>,
    /// Sliding offset in pixels along x, within one period [0, Nx).
    #[arg(long)]
    offset_px: Option<usize>,
    /// Output folder (created if missing; an earlier `contact` there is replaced whole).
    #[arg(long)]
    out: PathBuf,
    /// Replace the output folder even when it holds another command's results or other files.
    #[arg(long)]
    overwrite: bool,
}

pub fn run(args: &Args) -> Result<()> {
    let load = args.load;
    let config = load_run(&args.run)?;
    if !(load.is_finite() && load > 0.0) {
        bail!("invalid `--load`: {load} must be a finite positive normal force");
    }
    let grid = config.grid()?;
    wearsim::check::load(load, grid.area(), config.material.flow_pressure())?;
    let (n, ny, length, dx) = (grid.nx(), grid.ny(), grid.length_x(), grid.pixel_size());
    let unit = config.units.length_unit();
    let (shift, offset) = match (args.offset, args.offset_px) {
        (_, Some(px)) => {
            if px >= n {
                bail!(
                    "invalid `--offset-px`: {px} is not within one period of {n} pixels; give 0 … {}",
                    n - 1
                );
            }
            (px, px as f64 * dx)
        }
        (offset, None) => {
            let offset = offset.unwrap_or(0.0);
            if !offset.is_finite() || offset < 0.0 || offset >= length {
                bail!(
                    "invalid `--offset`: {offset} {unit} is not within one period [0, Lx = {length} {unit}); the \
                     surfaces are periodic, so give the offset modulo Lx"
                );
            }
            let pixels = offset / dx;
            let shift = (pixels.round() as usize) % n;
            if (pixels - pixels.round()).abs() > 1e-6 {
                eprintln!(
                    "note: --offset {offset} {unit} is {pixels:.3} pixels (Δx = {dx:e} {unit}); using {shift} pixels = {} {unit}",
                    shift as f64 * dx
                );
            }
            (shift, shift as f64 * dx)
        }
    };
    let out = OutputDir::begin(
        &args.out,
        "contact",
        args.overwrite,
        &super::run_inputs(&args.run, &config),
    )?;
    let pair = config.surface_pair()?;
    super::report_surfaces(&pair, true);
    let (top, bottom) = (pair.top, pair.bottom);
    let mut solver = ContactSolver::new(grid, config.effective_modulus())?
        .with_options(config.solver)
        .with_interrupt(super::interrupt().clone());
    let mut heights = vec![0.0; n * ny];
    composite_heights(&top, &bottom, shift, &mut heights);
    let mut pressure = vec![0.0; n * ny];
    let start = Instant::now();
    let info = solver.solve(
        &heights,
        load / grid.area(),
        config.material.flow_pressure(),
        &mut pressure,
    )?;
    let record = ContactRecord::new(&info, &pressure, start.elapsed().as_secs_f64());
    let contact: Vec<bool> = pressure.iter().map(|&p| p > 0.0).collect();
    write_npy_f64(&out.join("pressure.npy"), n, ny, &pressure)?;
    write_npy_bool(&out.join("contact.npy"), n, ny, &contact)?;
    write_json(
        &out.join("summary.json"),
        &contact_summary(&config, load, offset, shift, &record),
    )?;
    out.commit()?;
    println!(
        "contact area {:.6} of the apparent area, approach {:.6e} {unit}, {} iterations, residual {:.2e} (tolerance {:.0e}), {:.3} s",
        record.contact_area, record.approach, record.iterations, record.residual, record.tolerance, record.seconds
    );
    println!("wrote {}", args.out.display());
    Ok(())
}
