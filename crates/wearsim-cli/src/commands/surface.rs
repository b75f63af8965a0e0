//! `wearsim surface`: the run's surface pair and its statistics.

use std::path::PathBuf;

use anyhow::Result;
use wearsim::io::{write_json, OutputDir};
use wearsim::output::{surface_summary, SurfaceStatistics};

use super::load_run;

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README).
    run: PathBuf,
    /// Output folder (created if missing; an earlier `surface` there is replaced whole).
    #[arg(long)]
    out: PathBuf,
    /// Replace the output folder even when it holds another command's results or other files.
    #[arg(long)]
    overwrite: bool,
}

pub fn run(args: &Args) -> Result<()> {
    let config = load_run(&args.run)?;
    let out = OutputDir::begin(&args.out, "surface", args.overwrite)?;
    let (top, bottom) = config.surfaces()?;
    let unit = config.units.length_unit();
    let stats = [SurfaceStatistics::of(&top), SurfaceStatistics::of(&bottom)];
    top.write_npy(&out.join("top.npy"))?;
    bottom.write_npy(&out.join("bottom.npy"))?;
    write_json(
        &out.join("statistics.json"),
        &surface_summary(&config, &stats[0], &stats[1]),
    )?;
    out.commit()?;
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
