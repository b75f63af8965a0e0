//! `wearsim contact`: one contact solve at a load and a sliding offset, written as the fields other
//! programs read (pressure, contact map, displacement and gap as `.npy`) and a summary.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use wearsim::io::{write_json, write_npy_bool, write_npy_f64, OutputDir};
use wearsim::output::{contact_summary, ContactRecord};
use wearsim::{composite_heights, Boundary, ContactSolver, Grid};

use super::load_run;
use crate::out::{say, tell};

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
    /// Boundary of the elastic half-space at the map's edges: `periodic` (the paper's model, the
    /// default, or the run file's `[contact] boundary`) or `free` (the map surrounded by an unloaded
    /// half-space: measured maps, which are not periodic; zero-padded FFT, 4× the work).
    #[arg(long, value_parser = ["periodic", "free"])]
    boundary: Option<String>,
    /// Output folder (created if missing; an earlier `contact` there is replaced whole). Holds
    /// pressure.npy, contact.npy, displacement.npy (𝒦p), gap.npy (g = 𝒦p − h + δ: 0 in elastic
    /// contact, ≥ 0 outside, ≤ 0 where plastic) and summary.json with their units.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    overwrite: super::Overwrite,
}

/// The sliding offset asked for, in whole pixels and in the length unit `unit`: `--offset-px`, or
/// `--offset` rounded to pixels (with a note when it is not whole); 0 by default.
fn offset_of(args: &Args, grid: &Grid, unit: &str) -> Result<(usize, f64)> {
    let (n, length, dx) = (grid.nx(), grid.length_x(), grid.pixel_size());
    Ok(match (args.offset, args.offset_px) {
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
            let Some(o) = grid.offset_pixels(offset) else {
                bail!(
                    "invalid `--offset`: {offset} {unit} is not within one period [0, Lx = {length} {unit}); the \
                     surfaces are periodic, so give the offset modulo Lx"
                );
            };
            if !o.is_whole() {
                tell!(
                    "note: --offset {offset} {unit} is {:.3} pixels (Δx = {dx:e} {unit}); using {} pixels = {} {unit}",
                    o.pixels,
                    o.shift,
                    o.shift as f64 * dx
                );
            }
            (o.shift, o.shift as f64 * dx)
        }
    })
}

pub fn run(args: &Args) -> Result<()> {
    super::polls_interrupt();
    let load = args.load;
    let config = load_run(&args.run)?;
    if !(load.is_finite() && load > 0.0) {
        bail!("invalid `--load`: {load} must be a finite positive normal force");
    }
    let grid = config.grid()?;
    wearsim::check::load("--load", load, grid.area(), config.material.flow_pressure())?;
    let (n, ny) = (grid.nx(), grid.ny());
    let unit = config.units.length_unit();
    let (shift, offset) = offset_of(args, &grid, unit)?;
    let boundary = match &args.boundary {
        Some(name) => name.parse::<Boundary>()?,
        None => config.boundary,
    };
    if !boundary.allows_offset(shift) {
        bail!(
            "invalid `--offset`/`--offset-px`: a sliding offset wraps the top surface around the periodic box, which a free boundary \
             does not have; give offset 0 with `boundary = free`, or slide with the periodic boundary"
        );
    }
    let arrays = match boundary {
        Boundary::Periodic => wearsim::check::CONTACT_ARRAYS,
        Boundary::Free => wearsim::check::CONTACT_FREE_ARRAYS,
    };
    wearsim::check::memory("a contact solve", n, ny, arrays)?;
    let out = OutputDir::begin(
        &args.out,
        "contact",
        args.overwrite.replace,
        &super::run_inputs(&args.run, &config),
    )?;
    let pair = config.surface_pair()?;
    super::report_surfaces(&pair, true);
    let (top, bottom) = (pair.top, pair.bottom);
    let mut solver = ContactSolver::on_device(config.device, grid, config.effective_modulus(), boundary)?
        .with_options(config.solver)
        .with_interrupt(super::interrupt().clone());
    let mut heights = vec![0.0; n * ny];
    composite_heights(&top, &bottom, shift, &mut heights);
    let mut pressure = vec![0.0; n * ny];
    let start = Instant::now();
    let info = solver.solve(
        &heights,
        grid.mean_pressure(load),
        config.material.flow_pressure(),
        &mut pressure,
    )?;
    let record = ContactRecord::new(&info, &pressure, start.elapsed().as_secs_f64());
    let contact = wearsim::contact::contact_map(&pressure);
    let fields = solver.gap_and_displacement(&heights, &pressure, &info)?;
    write_npy_f64(&out.join("pressure.npy"), n, ny, &pressure)?;
    write_npy_bool(&out.join("contact.npy"), n, ny, &contact)?;
    write_npy_f64(&out.join("displacement.npy"), n, ny, &fields.displacement)?;
    write_npy_f64(&out.join("gap.npy"), n, ny, &fields.gap)?;
    write_json(
        &out.join("summary.json"),
        &contact_summary(&config, load, offset, shift, boundary, &record),
    )?;
    super::check_interrupt()?;
    out.commit()?;
    say!(
        "contact area {:.6} of the apparent area, approach {:.6e} {unit}, {} iterations, residual {:.2e} (tolerance {:.0e}), {:.3} s",
        record.contact_area, record.approach, record.iterations, record.residual, record.tolerance, record.seconds
    );
    say!("wrote {}", args.out.display());
    Ok(())
}
