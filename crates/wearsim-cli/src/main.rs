//! `wearsim`: the command-line front end. Parses arguments, calls the library and says what it
//! wrote; one file per subcommand under `commands/`, the figures in `figures.rs`. All numerics and
//! every result document live in the `wearsim` library crate. Everything it prints goes through
//! [`out`], which survives a closed pipe; `println!` and `eprintln!` (which panic there) are denied.
#![deny(clippy::print_stdout, clippy::print_stderr)]

use clap::{Parser, Subcommand};

mod commands;
mod figures;
mod out;
mod progress;
mod raster;

use out::tell;

use commands::{animate, bench, contact, estimate, fields, junctions, plot, slide, study, surface};

#[derive(Parser)]
#[command(
    name = "wearsim",
    version,
    about = "Adhesive wear of rough surfaces in sliding contact (Brink, Frérot & Molinari 2021)"
)]
struct Cli {
    /// Worker threads (default: all cores; at most four per core). Results do not depend on it.
    #[arg(long, global = true)]
    threads: Option<usize>,
    /// Show no progress.
    #[arg(long, global = true)]
    quiet: bool,
    /// Show progress as plain lines (at least every 30 s) even on a terminal, as in a batch log.
    #[arg(long, global = true)]
    log: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Generate (or read) the run's surface pair; write top.npy, bottom.npy and statistics.json.
    Surface(surface::Args),
    /// Solve one contact at a normal load and sliding offset (periodic or free boundary); write
    /// pressure.npy, contact.npy, displacement.npy, gap.npy and summary.json.
    Contact(contact::Args),
    /// Run the sliding wear model on every load of the run file; write summary.json and series.csv.
    Slide(slide::Args),
    /// Estimate W, k and dN*₊/ds of every load from a few static contact solutions instead of
    /// sliding (minutes instead of hours on large boxes); write summary.json and results.csv,
    /// marked as an estimate, with 95 % intervals.
    Estimate(estimate::Args),
    /// Compare the static estimate with the finished sliding jobs of a study folder (errors,
    /// coverage of the intervals); with --fit, fit its constants on them.
    EstimateCheck(estimate::CheckArgs),
    /// Draw the figures of one `slide` run folder into DIR/figures (PNG, SVG and their numbers as
    /// CSV), per load: the wear volume V(s) with its fitted line (the paper's Fig. 3), the particle
    /// counts N*₊, N*, N*₋ (appendix B) and the memory of the initial contact N₀(s). A study folder
    /// is drawn by `wearsim study plot`.
    Plot(plot::SlideArgs),
    /// Animate the sliding run of one load as a GIF: contact maps coloured by junction state.
    Animate(animate::Args),
    /// Label the junctions of a contact map (.npy, bool or numbers > 0); write labels.npy and
    /// junctions.json.
    Junctions(junctions::Args),
    /// Fields stores of `slide --save-fields`: convert to NetCDF-4 with CF attributes.
    #[command(subcommand)]
    Fields(FieldsCommand),
    /// Studies: expand a study file into jobs and run them (resumable), collect the results, draw
    /// the paper's figures.
    #[command(subcommand)]
    Study(StudyCommand),
    /// Time the FFT round trip, a cold saturated solve and a warm solve after a one-pixel slide.
    Bench(bench::Args),
    /// Time a full sliding run (solve / labelling / bookkeeping) and warm steps on a large grid.
    BenchSlide(bench::SlideArgs),
}

#[derive(Subcommand)]
enum FieldsCommand {
    /// Convert DIR/fields.zarr to a NetCDF-4 file with CF attributes (units, long names, x and y
    /// coordinates in L or m) for MATLAB's ncread, ParaView and xarray. Runs the Python package
    /// (`python -m wearsim.fields`), which needs `pip install "wearsim[fields]"`.
    ToNetcdf(fields::ToNetcdfArgs),
}

#[derive(Subcommand)]
enum StudyCommand {
    /// Run the study's jobs (surface pair × material × load); finished jobs are skipped, so a killed
    /// study resumes. One JSON file per job in DIR/jobs.
    Run(study::RunArgs),
    /// Collect the job files into results.csv (tidy) and results_aggregated.csv (mean/min/max over
    /// surface pairs).
    Collect(study::CollectArgs),
    /// Draw the paper's figures (PNG and SVG) from a finished study into DIR/figures.
    Plot(plot::Args),
}

fn main() {
    let cli = Cli::parse();
    progress::configure(cli.quiet, cli.log);
    if let Some(requested) = cli.threads {
        let threads = match wearsim::check::threads(requested) {
            Ok((t, note)) => {
                if let Some(note) = note {
                    tell!("warning: --threads: {note}");
                }
                t
            }
            Err(e) => {
                tell!("error: --threads: {e}");
                std::process::exit(2);
            }
        };
        if let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(threads).build_global() {
            tell!("error: --threads: {e}");
            std::process::exit(2);
        }
    }
    // The pool is made before any work, so that its threads' stacks count in the memory checks.
    let _ = rayon::ThreadPoolBuilder::new().build_global();
    commands::handle_signals();
    let result = match cli.command {
        Command::Surface(args) => surface::run(&args),
        Command::Contact(args) => contact::run(&args),
        Command::Slide(args) => slide::run(&args),
        Command::Estimate(args) => estimate::run(&args),
        Command::EstimateCheck(args) => estimate::check(&args),
        Command::Plot(args) => plot::run_slide(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Junctions(args) => junctions::run(&args),
        Command::Fields(FieldsCommand::ToNetcdf(args)) => fields::to_netcdf(&args),
        Command::Study(StudyCommand::Run(args)) => study::run(&args),
        Command::Study(StudyCommand::Collect(args)) => study::collect(&args),
        Command::Study(StudyCommand::Plot(args)) => plot::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::BenchSlide(args) => bench::run_slide(&args),
    };
    let stopped = commands::stop_signal();
    if let Err(e) = result {
        let interrupted = e
            .chain()
            .any(|c| matches!(c.downcast_ref::<wearsim::Error>(), Some(wearsim::Error::Interrupted)));
        match (interrupted, stopped) {
            (true, Some(sig)) => tell!("error: stopped by {}", commands::signal_name(sig)),
            _ => tell!("error: {}", message(&e)),
        }
        std::process::exit(match (interrupted, stopped) {
            (true, Some(sig)) => 128 + sig,
            (true, None) => 130,
            _ => 1,
        });
    }
}

/// The error and its causes on one line, each cause once (library errors already quote the
/// message of the error they wrap, and a library I/O error says the system's error in words, so
/// its source is not repeated).
fn message(e: &anyhow::Error) -> String {
    let mut text = String::new();
    let mut explained = false;
    for cause in e.chain() {
        let part = cause.to_string();
        let skip = explained && cause.downcast_ref::<std::io::Error>().is_some();
        explained = matches!(cause.downcast_ref::<wearsim::Error>(), Some(wearsim::Error::Io { .. }));
        if !skip && !text.contains(&part) {
            if !text.is_empty() {
                text.push_str(": ");
            }
            text.push_str(&part);
        }
    }
    text
}
