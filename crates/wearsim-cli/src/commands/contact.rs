//! `wearsim contact`: one contact solve at a load and a sliding offset.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use wearsim::io::{write_json, write_npy_bool, write_npy_f64};
use wearsim::output::{contact_summary, ContactRecord};
use wearsim::{composite_heights, ContactSolver};

use super::{create_dir, load_run};

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README).
    run: PathBuf,
    /// Normal load F_N in the run's units (E·L² reduced, N in SI).
    #[arg(long)]
    load: f64,
    /// Sliding offset of the top surface along x, in the run's length unit (a whole number of pixels).
    #[arg(long, default_value_t = 0.0)]
    offset: f64,
    /// Output folder (created if missing).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: &Args) -> Result<()> {
    let (load, offset, out) = (args.load, args.offset, &args.out);
    let config = load_run(&args.run)?;
    let (top, bottom) = config.surfaces()?;
    let n = top.n();
    let dx = top.pixel_size();
    let pixels = offset / dx;
    if !pixels.is_finite() || pixels < 0.0 || (pixels - pixels.round()).abs() > 1e-6 {
        bail!(
            "invalid `--offset`: {offset} is not a non-negative whole number of pixels (Δx = {dx} {})",
            config.units.length_unit()
        );
    }
    if !(load.is_finite() && load > 0.0) {
        bail!("invalid `--load`: {load} must be a finite positive normal force");
    }
    let shift = pixels.round() as usize % n;
    let area = top.length() * top.length();
    let mut solver = ContactSolver::new(n, top.length(), config.effective_modulus())?.with_options(config.solver);
    let mut heights = vec![0.0; n * n];
    composite_heights(&top, &bottom, shift, &mut heights);
    let mut pressure = vec![0.0; n * n];
    let start = Instant::now();
    let info = solver.solve(&heights, load / area, config.material.flow_pressure(), &mut pressure)?;
    let record = ContactRecord::new(&info, &pressure, start.elapsed().as_secs_f64());
    let contact: Vec<bool> = pressure.iter().map(|&p| p > 0.0).collect();
    create_dir(out)?;
    write_npy_f64(&out.join("pressure.npy"), n, n, &pressure)?;
    write_npy_bool(&out.join("contact.npy"), n, n, &contact)?;
    write_json(
        &out.join("summary.json"),
        &contact_summary(&config, load, offset, shift, &record),
    )?;
    println!(
        "contact area {:.6} of L², approach {:.6e}, {} iterations, residual {:.2e} (tolerance {:.0e}), {:.3} s",
        record.contact_area, record.approach, record.iterations, record.residual, record.tolerance, record.seconds
    );
    println!("wrote {}", out.display());
    Ok(())
}
