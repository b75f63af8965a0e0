//! `wearsim surface`: the run's surface pair and its statistics.

use std::path::PathBuf;

use anyhow::Result;
use wearsim::io::write_json;
use wearsim::output::{surface_summary, SurfaceStatistics};

use super::{create_dir, load_run};

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README).
    run: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    out: PathBuf,
}

pub fn run(args: &Args) -> Result<()> {
    let config = load_run(&args.run)?;
    let (top, bottom) = config.surfaces()?;
    let unit = config.units.length_unit();
    let stats = [SurfaceStatistics::of(&top), SurfaceStatistics::of(&bottom)];
    create_dir(&args.out)?;
    top.write_npy(&args.out.join("top.npy"))?;
    bottom.write_npy(&args.out.join("bottom.npy"))?;
    write_json(
        &args.out.join("statistics.json"),
        &surface_summary(&config, &stats[0], &stats[1]),
    )?;
    for (name, s) in [("top", &stats[0]), ("bottom", &stats[1])] {
        println!(
            "{name:>6}: {n}×{n}, L = {l} {unit}, h_rms = {h:.6e} {unit}, rms slope = {g:.6e}",
            n = s.grid,
            l = s.length,
            h = s.rms_height,
            g = s.rms_slope
        );
    }
    println!("wrote {}", args.out.display());
    Ok(())
}
