//! `wearsim junctions`: junction labels of a contact map.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use wearsim::io::{read_npy_2d, write_json, write_npy_i64, NpyType, OutputDir};
use wearsim::junctions::{JunctionLabeller, NO_JUNCTION};
use wearsim::output::junctions_summary;

use crate::out::say;

#[derive(clap::Args)]
pub struct Args {
    /// Contact map (.npy: bool, or numbers where > 0 is contact, e.g. the contact.npy or
    /// pressure.npy written by `wearsim contact`).
    map: PathBuf,
    /// 4 or 8.
    #[arg(long, default_value_t = wearsim::junctions::DEFAULT_CONNECTIVITY)]
    connectivity: u8,
    #[command(flatten)]
    output: super::OutputFolder,
}

/// Labels the junctions of a contact map and writes `labels.npy` (int64, −1 outside contact) and
/// `junctions.json` (pixel count per junction).
pub fn run(args: &Args) -> Result<()> {
    let (map, connectivity) = (&args.map, args.connectivity);
    wearsim::check::connectivity(connectivity).context("--connectivity")?;
    let accepted = [
        NpyType::Bool,
        NpyType::Float64,
        NpyType::Float32,
        NpyType::Int64,
        NpyType::Int32,
        NpyType::Int16,
        NpyType::Int8,
        NpyType::UInt8,
    ];
    let array = read_npy_2d(map, &accepted, "a contact map")?;
    let (rows, cols) = (array.rows, array.cols);
    if rows == 0 || cols == 0 {
        bail!("{}: the contact map is empty ({rows}×{cols})", map.display());
    }
    if let Some(k) = array.values.iter().position(|v| v.is_nan()) {
        bail!(
            "{}: the contact map holds NaN at ({}, {}); a contact map is bool, or numbers where > 0 is contact",
            map.display(),
            k / cols,
            k % cols
        );
    }
    let out = OutputDir::begin(
        &args.output.out,
        "junctions",
        args.output.overwrite.replace,
        &[map.as_path()],
    )?;
    if rows.saturating_mul(cols) >= u32::MAX as usize {
        bail!(
            "{}: a {rows}×{cols} map has more pixels than 32-bit junction labels can index",
            map.display()
        );
    }
    let mut labeller = JunctionLabeller::new(rows, cols, connectivity);
    let count = labeller.label(|k| wearsim::contact::in_contact(array.values[k]));
    let labels: Vec<i64> = labeller
        .labels()
        .iter()
        .map(|&l| if l == NO_JUNCTION { -1 } else { l as i64 })
        .collect();
    write_npy_i64(&out.join("labels.npy"), rows, cols, &labels)?;
    write_json(
        &out.join("junctions.json"),
        &junctions_summary(connectivity, labeller.sizes()),
    )?;
    out.commit()?;
    say!("{count} junctions; wrote {}", args.output.out.display());
    Ok(())
}
