//! `wearsim animate`: the sliding run of one load as an animated GIF, like the paper's Video 1. Each
//! frame is the contact map of one step, junctions coloured by their state for one fracture energy:
//! grey below d*, red forming a particle now, orange at or above d* but disabled (its particle is
//! already counted), blue disabled below d*; s and V are written on the frame.

use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::progress::Progress;
use anyhow::{anyhow, Context, Result};
use plotters::prelude::*;
use wearsim::junctions::NO_JUNCTION;
use wearsim::run::SlidingRun;
use wearsim::sliding::StepView;
use wearsim::wear::JunctionState;

use super::load_run;
use crate::figures::{register_font, FONT};
use crate::out::say;

#[derive(clap::Args)]
pub struct Args {
    /// Run file (TOML, see README) with a `[sliding]` table.
    run: PathBuf,
    /// Output file (.gif).
    #[arg(long)]
    out: PathBuf,
    /// Which of the run's loads (0 = first).
    #[arg(long, default_value_t = 0)]
    load_index: usize,
    /// Which of the run's fracture energies sets d* for the colours (0 = first).
    #[arg(long, default_value_t = 0)]
    energy_index: usize,
    /// Frame delay in milliseconds (GIF stores hundredths of a second: 10 … 655350).
    #[arg(long, default_value_t = 80)]
    delay: u32,
    /// Replace --out even when it is a file that `wearsim animate` did not write.
    #[arg(long)]
    overwrite: bool,
}

/// The comment a GIF written by `wearsim animate` carries, which tells a later run that the file is
/// one it may replace.
const GIF_MARK: &[u8] = b"written by wearsim animate";

/// Marks the finished GIF `path` as wearsim's: a comment extension before its trailer.
fn mark_gif(path: &Path) -> std::io::Result<()> {
    let mut f = std::fs::OpenOptions::new().read(true).write(true).open(path)?;
    let len = f.metadata()?.len();
    let mut last = [0u8];
    f.seek(SeekFrom::End(-1))?;
    f.read_exact(&mut last)?;
    if last[0] != 0x3B {
        return Err(std::io::Error::other("the GIF has no trailer"));
    }
    f.set_len(len - 1)?;
    f.seek(SeekFrom::End(0))?;
    f.write_all(&[0x21, 0xFE, GIF_MARK.len() as u8])?;
    f.write_all(GIF_MARK)?;
    f.write_all(&[0x00, 0x3B])?;
    f.sync_all()
}

/// Whether `path` is a GIF that `wearsim animate` wrote (its comment, at the end).
fn is_wearsim_gif(path: &Path) -> bool {
    let Ok(mut f) = std::fs::File::open(path) else {
        return false;
    };
    let mut head = [0u8; 4];
    let mut tail = Vec::new();
    f.read_exact(&mut head).is_ok()
        && &head == b"GIF8"
        && f.seek(SeekFrom::End(-64)).is_ok()
        && f.read_to_end(&mut tail).is_ok()
        && tail.windows(GIF_MARK.len()).any(|w| w == GIF_MARK)
}

/// The run of the one load animated, after checking the arguments against it.
fn one_load(args: &Args) -> Result<wearsim::config::RunConfig> {
    let (run, out, load_index, energy_index, delay_ms) =
        (&args.run, &args.out, args.load_index, args.energy_index, args.delay);
    super::polls_interrupt();
    // The GIF is written beside its name: a folder that is not there is said before any work.
    let folder = wearsim::io::parent_or_dot(out);
    if !folder.is_dir() {
        anyhow::bail!(
            "cannot write {}: the folder {} does not exist; create it or give another --out",
            out.display(),
            folder.display()
        );
    }
    let config = load_run(run)?;
    // Never over an input or a file another command (or the user) made, whatever the spelling.
    wearsim::io::refuse_foreign_file(
        out,
        "animate",
        args.overwrite,
        &super::run_inputs(run, &config),
        is_wearsim_gif,
    )?;
    // Partial GIFs of killed runs beside it.
    wearsim::io::remove_abandoned_siblings(out);
    let mut sliding = wearsim::run::sliding_schedule(&config)
        .with_context(|| format!("run file {}", run.display()))?
        .clone();
    let load = *sliding.loads.get(load_index).ok_or_else(|| {
        anyhow!(
            "invalid `--load-index {load_index}`: the run has {} loads",
            sliding.loads.len()
        )
    })?;
    sliding.loads = vec![load];
    if energy_index >= config.material.fracture_energies.len() {
        anyhow::bail!(
            "invalid `--energy-index {energy_index}`: the run has {} fracture energies",
            config.material.fracture_energies.len()
        );
    }
    if out.extension().and_then(|e| e.to_str()) != Some("gif") {
        anyhow::bail!("invalid `--out {}`: the animation is a .gif file", out.display());
    }
    if !(10..=655_350).contains(&delay_ms) {
        anyhow::bail!(
            "invalid `--delay {delay_ms}`: a GIF frame lasts 10 ms to 655350 ms (it is stored in hundredths of a second)"
        );
    }
    // The run of the one load, derived through the builder, which checks it again.
    config
        .to_builder()
        .sliding(sliding)
        .build()
        .with_context(|| format!("run file {}", run.display()))
}

/// How the grid maps to a frame: pixels of the grid per frame pixel, frame pixels per grid pixel.
#[derive(Clone, Copy)]
struct Layout {
    nx: usize,
    ny: usize,
    step_px: usize,
    scale: u32,
}

/// The colour of a junction's state (the legend of the frame).
fn colour(state: JunctionState) -> RGBColor {
    match state {
        JunctionState::Below => RGBColor(150, 150, 150),
        JunctionState::Forming => RGBColor(220, 30, 30),
        JunctionState::DisabledCritical => RGBColor(245, 150, 20),
        JunctionState::Disabled => RGBColor(40, 90, 200),
    }
}

/// One frame: the junctions of the step coloured by their state under the particle rule of
/// fracture energy `energy`, s, V, N*₊ and d* above them, then the legend.
fn draw_frame<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    view: &StepView,
    energy: usize,
    layout: Layout,
    caption: &dyn Fn(&StepView) -> String,
) -> Result<()> {
    let Layout { nx, ny, step_px, scale } = layout;
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let labels = view.labeller.labels();
    let states = view.junction_states(energy);
    for i in (0..nx).step_by(step_px) {
        for j in (0..ny).step_by(step_px) {
            let l = labels[i * ny + j];
            if l == NO_JUNCTION {
                continue;
            }
            // x (first axis, the sliding direction) runs left to right.
            let (x, y) = (
                (i / step_px) as i32 * scale as i32,
                (j / step_px) as i32 * scale as i32 + 40,
            );
            root.draw(&Rectangle::new(
                [(x, y), (x + scale as i32, y + scale as i32)],
                colour(states[l as usize]).filled(),
            ))
            .map_err(|e| anyhow!("{e}"))?;
        }
    }
    let font = (FONT, 13).into_font().color(&BLACK);
    root.draw_text(&caption(view), &font, (6, 4))
        .map_err(|e| anyhow!("{e}"))?;
    root.draw_text(
        "grey: below d*   red: forming a particle   orange: disabled, ≥ d*   blue: disabled",
        &font,
        (6, 22),
    )
    .map_err(|e| anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow!("{e}"))
}

pub fn run(args: &Args) -> Result<()> {
    let (out, energy_index, delay_ms) = (&args.out, args.energy_index, args.delay);
    register_font();
    let config = one_load(args)?;
    let prepared = SlidingRun::prepare(&config)?.interrupted_by(super::interrupt());
    super::report_surfaces(prepared.surfaces(), true);
    let (nx, ny) = (prepared.grid().nx(), prepared.grid().ny());
    let n = nx.max(ny);
    let layout = Layout {
        nx,
        ny,
        scale: (512 / n).max(1) as u32, // frames of at least 512 px where the grid is smaller
        step_px: (n / 512).max(1),      // and at most about 1024 px where it is larger
    };
    let (width, height) = (
        (nx / layout.step_px) as u32 * layout.scale,
        (ny / layout.step_px) as u32 * layout.scale,
    );
    let d_star = config
        .material
        .critical_diameter(config.material.fracture_energies[energy_index]);
    let length_unit = config.units.length_unit();
    let caption = |view: &StepView| {
        let w = view.record.wear[energy_index];
        format!(
            "s = {:.4} {length_unit}   V = {:.3e}   N*₊ = {}   d* = {:.3e} {length_unit}",
            view.record.s, w.volume, w.n_formed, d_star
        )
    };
    let tmp = wearsim::io::temporary_sibling(out)?;
    let mut frame_error: Option<anyhow::Error> = None;
    {
        let root = crate::raster::Raster::new(
            BitMapBackend::gif(&tmp, (width.max(560), height + 40), delay_ms)
                .map_err(|e| anyhow!("cannot write {}: {e}", out.display()))?,
        )
        .into_drawing_area();
        let progress = Progress::new("animate", "frames", 0);
        let ran = prepared.run(|view| {
            progress.set(view.done as u64, view.total as u64, "");
            if frame_error.is_none() {
                frame_error = draw_frame(&root, view, energy_index, layout, &caption).err();
            }
        });
        progress.finish();
        if let Err(e) = ran {
            frame_error = Some(e.into());
        }
    }
    let finished = match frame_error {
        Some(e) => Err(e),
        None => mark_gif(&tmp)
            .with_context(|| format!("cannot write {}", out.display()))
            .and_then(|()| super::check_interrupt()),
    };
    if let Err(e) = finished {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, out).with_context(|| format!("cannot write {}", out.display()))?;
    say!("wrote {}", out.display());
    Ok(())
}
