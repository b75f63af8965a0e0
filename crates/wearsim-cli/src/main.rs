//! `wearsim`: the command-line front end. Parses arguments, loads and validates the run file, calls
//! the library and writes results. All numerics live in the `wearsim` library crate.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use serde_json::json;
use wearsim::config::RunConfig;
use wearsim::output::write_text;
use wearsim::surface::{write_npy_bool, write_npy_f64};
use wearsim::{composite_heights, ContactSolver, Surface};

mod bench;
mod plot;
mod slide;
mod study;

#[derive(Parser)]
#[command(
    name = "wearsim",
    version,
    about = "Adhesive wear of rough surfaces in sliding contact (Brink, Frérot & Molinari 2021)"
)]
struct Cli {
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long, global = true)]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Generate (or read) the run's surface pair; write top.npy, bottom.npy and statistics.json.
    Surface {
        /// Run file (TOML, see README).
        run: PathBuf,
        /// Output folder (created if missing).
        #[arg(long)]
        out: PathBuf,
    },
    /// Solve one contact at a normal load and sliding offset; write pressure.npy, contact.npy and
    /// summary.json.
    Contact {
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
    },
    /// Run the sliding wear model on every load of the run file; write summary.json and series.csv.
    Slide {
        /// Run file (TOML, see README) with a [sliding] table.
        run: PathBuf,
        /// Output folder (created if missing).
        #[arg(long)]
        out: PathBuf,
    },
    /// Animate the sliding run of one load as a GIF: contact maps coloured by junction state.
    Animate {
        /// Run file (TOML, see README) with a [sliding] table.
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
        /// Frame delay in milliseconds.
        #[arg(long, default_value_t = 80)]
        delay: u32,
    },
    /// Label the junctions of a contact map (.npy, bool or numbers > 0); write labels.npy and junctions.json.
    Junctions {
        /// Contact map, e.g. the contact.npy written by `wearsim contact`.
        map: PathBuf,
        /// 4 or 8.
        #[arg(long, default_value_t = 4)]
        connectivity: u8,
        /// Output folder (created if missing).
        #[arg(long)]
        out: PathBuf,
    },
    /// Studies: expand a study file into jobs and run them (resumable), or collect the results.
    #[command(subcommand)]
    Study(StudyCommand),
    /// Time the FFT round trip, a cold saturated solve and a warm solve after a one-pixel slide.
    Bench(bench::BenchArgs),
    /// Time a full sliding run (solve / labelling / bookkeeping) and warm steps on a large grid.
    BenchSlide(bench::SlideBenchArgs),
}

#[derive(Subcommand)]
enum StudyCommand {
    /// Run the study's jobs (surface pair × material × load); finished jobs are skipped, so a killed
    /// study resumes. One JSON file per job in DIR/jobs.
    Run {
        /// Study file (a run file whose fields may be lists, or with [[materials]]).
        study: PathBuf,
        /// Study folder (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Run only shard K of N (jobs with index ≡ K−1 mod N); default from SLURM_ARRAY_TASK_ID /
        /// SLURM_ARRAY_TASK_COUNT inside a Slurm job array, else 1/1.
        #[arg(long)]
        shard: Option<String>,
        /// Jobs run at once, sharing the threads (default: one job per thread); 1 for large grids.
        #[arg(long)]
        jobs: Option<usize>,
    },
    /// Draw the paper's figures (PNG and SVG) from a finished study into DIR/figures.
    Plot {
        /// Study folder.
        dir: PathBuf,
    },
    /// Collect the job files into results.csv (tidy) and results_aggregated.csv (mean/min/max over
    /// surface pairs).
    Collect {
        /// Study folder.
        dir: PathBuf,
    },
}

fn main() {
    let cli = Cli::parse();
    if let Some(t) = cli.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(t).build_global() {
            eprintln!("error: --threads: {e}");
            std::process::exit(2);
        }
    }
    let result = match cli.command {
        Command::Surface { run, out } => surface(&run, &out),
        Command::Contact { run, load, offset, out } => contact(&run, load, offset, &out),
        Command::Slide { run, out } => slide::slide(&run, &out),
        Command::Animate {
            run,
            out,
            load_index,
            energy_index,
            delay,
        } => plot::animate(&run, &out, load_index, energy_index, delay),
        Command::Junctions { map, connectivity, out } => slide::junctions(&map, connectivity, &out),
        Command::Study(StudyCommand::Run {
            study,
            out,
            shard,
            jobs,
        }) => study::run(&study, &out, shard.as_deref(), jobs),
        Command::Study(StudyCommand::Collect { dir }) => study::collect(&dir),
        Command::Study(StudyCommand::Plot { dir }) => plot::plot(&dir),
        Command::Bench(args) => bench::run(&args),
        Command::BenchSlide(args) => bench::run_slide(&args),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn load_run(run: &Path) -> Result<RunConfig> {
    RunConfig::from_path(run).with_context(|| format!("run file {}", run.display()))
}

fn create_dir(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))
}

fn statistics(s: &Surface) -> serde_json::Value {
    json!({
        "grid": s.n(),
        "length": s.length(),
        "rms_height": s.rms_height(),
        "rms_slope": s.rms_slope(),
        "psd": s.radial_psd().iter().map(|(q, c)| [*q, *c]).collect::<Vec<_>>(),
    })
}

fn surface(run: &Path, out: &Path) -> Result<()> {
    let config = load_run(run)?;
    let (top, bottom) = config.surfaces()?;
    let unit = config.units.length_unit();
    let stats = json!({
        "software": format!("wearsim {}", wearsim::VERSION),
        "units": config.units,
        "surfaces": config.surfaces,
        "psd_convention": "psd[q] = mean over the shell |q| ∈ [m−½, m+½) of |ĥ(q)|²/N⁴ (variance per Fourier mode, length²); q in units of 2π/L",
        "top": statistics(&top),
        "bottom": statistics(&bottom),
    });
    create_dir(out)?;
    top.write_npy(&out.join("top.npy"))?;
    bottom.write_npy(&out.join("bottom.npy"))?;
    write_text(&out.join("statistics.json"), &serde_json::to_string_pretty(&stats)?)?;
    for (name, s) in [("top", &top), ("bottom", &bottom)] {
        println!(
            "{name:>6}: {n}×{n}, L = {l} {unit}, h_rms = {h:.6e} {unit}, rms slope = {g:.6e}",
            n = s.n(),
            l = s.length(),
            h = s.rms_height(),
            g = s.rms_slope()
        );
    }
    println!("wrote {}", out.display());
    Ok(())
}

fn contact(run: &Path, load: f64, offset: f64, out: &Path) -> Result<()> {
    let config = load_run(run)?;
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
    let mean_pressure = load / area;
    let flow_pressure = config.material.flow_pressure();
    let mut solver = ContactSolver::new(n, top.length(), config.effective_modulus())?;
    solver.options = config.solver;
    let mut heights = vec![0.0; n * n];
    composite_heights(&top, &bottom, shift, &mut heights);
    let mut pressure = vec![0.0; n * n];
    let start = Instant::now();
    let info = solver.solve(&heights, mean_pressure, flow_pressure, &mut pressure)?;
    let seconds = start.elapsed().as_secs_f64();
    let contact: Vec<bool> = pressure.iter().map(|&p| p > 0.0).collect();
    let contact_area = info.contact_pixels as f64 / (n * n) as f64;
    let summary = json!({
        "software": format!("wearsim {}", wearsim::VERSION),
        "units": config.units,
        "load": load,
        "offset": offset,
        "offset_pixels": shift,
        "contact_area": contact_area,
        "contact_pixels": info.contact_pixels,
        "plastic_pixels": info.plastic_pixels,
        "mean_pressure": pressure.iter().sum::<f64>() / (n * n) as f64,
        "approach": info.approach,
        "iterations": info.iterations,
        "convolutions": info.convolutions,
        "residual": info.residual,
        "tolerance": info.tolerance,
        "residual_definition": "max over pixels of the violation of the optimality conditions (|g+c| on free, max(0,-(g+c)) on non-contact, max(0,g+c) on plastic pixels) divided by std(h)",
        "effective_modulus": config.effective_modulus(),
        "modulus_convention": config.modulus.name(),
        "flow_pressure": flow_pressure,
        "critical_diameters": config.material.critical_diameters(),
        "seconds": seconds,
        "material": config.material,
        "surfaces": config.surfaces,
    });
    create_dir(out)?;
    write_npy_f64(&out.join("pressure.npy"), n, &pressure)?;
    write_npy_bool(&out.join("contact.npy"), n, &contact)?;
    write_text(&out.join("summary.json"), &serde_json::to_string_pretty(&summary)?)?;
    println!(
        "contact area {:.6} of L², approach {:.6e}, {} iterations, residual {:.2e} (tolerance {:.0e}), {:.3} s",
        contact_area, info.approach, info.iterations, info.residual, info.tolerance, seconds
    );
    println!("wrote {}", out.display());
    Ok(())
}
