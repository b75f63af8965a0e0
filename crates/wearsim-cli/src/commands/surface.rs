//! `wearsim surface`: the run's surface pair and its statistics; `wearsim surface fit`: the
//! self-affine parameters of a measured height map, as a run file's `[surface]` block;
//! `wearsim surface import`: an instrument file (any format SurfaceTopography reads, and the
//! counter-body's with `--bottom`) as the maps a run file reads, delegated to the Python package
//! (`python -m wearsim.measured`).

use std::path::PathBuf;
use std::process::Command;

use anyhow::{bail, Context, Result};
use wearsim::io::{write_json, write_text, OutputDir};
use wearsim::output::{surface_fit_summary, surface_summary, SurfaceStatistics};
use wearsim::surface::pair_seeds;
use wearsim::surface::SpectrumParams;
use wearsim::topography::{self, Detrend, FileSurface, Preprocess};
use wearsim::{Grid, Surface};

use super::load_run;
use crate::out::{say, say_part, tell};

#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    #[command(subcommand)]
    action: Option<Action>,
    /// Run file (TOML, see README).
    #[arg(required = true)]
    run: Option<PathBuf>,
    /// Output folder (created if missing; an earlier `surface` there is replaced whole).
    #[arg(long, required = true)]
    out: Option<PathBuf>,
    #[command(flatten)]
    overwrite: super::Overwrite,
}

#[derive(clap::Subcommand)]
enum Action {
    /// Estimate H, λ_l, λ_u and h_rms of a measured height map from its radially averaged PSD (the
    /// power law C(q) ∝ q^−2(1+H) fitted on the band above the floor of round-off or noise, λ_l and
    /// λ_u where the PSD leaves it); print (and with --out write) the `[surface]` block of a run file
    /// that generates periodic surfaces with them, and with --generate the synthetic pair itself.
    Fit(FitArgs),
    /// Turn an instrument height map (AFM .di, confocal .plu, ISO 25178 .x3p, Wyko .opd, Digital
    /// Surf .sur, .mi and every other format SurfaceTopography reads) into DIR/heights.npy (metres,
    /// i along x), DIR/bottom.npy (the counter-body: the map of --bottom FILE2, else the map rotated
    /// by 180° about its centre) and DIR/import.json (what was done, and a ready `[surface]` block
    /// with both). Runs in Python with SurfaceTopography (`pip install "wearsim[measured]"`).
    Import(ImportArgs),
}

#[derive(clap::Args)]
struct ImportArgs {
    /// The instrument file.
    file: PathBuf,
    /// Output folder: heights.npy, bottom.npy and import.json (written beside and renamed into
    /// place).
    #[arg(long)]
    out: PathBuf,
    /// The counter-body's instrument file, imported with the same options into DIR/bottom.npy; it
    /// must end on the same grid and pixel size as FILE. Without it, bottom.npy is FILE's map
    /// rotated by 180° about its centre: the measured lay, spectrum and height distribution, and no
    /// pixel facing its own copy at any sliding offset.
    #[arg(long, value_name = "FILE2")]
    bottom: Option<PathBuf>,
    /// Fill undefined (unmeasured) pixels with this method of SurfaceTopography's
    /// interpolate_undefined_data (harmonic); without it a map with undefined pixels is refused.
    #[arg(long, value_parser = ["harmonic"])]
    fill: Option<String>,
    /// Resample a map with non-square pixels onto square pixels of the smaller pixel size (without
    /// it such a map is refused).
    #[arg(long)]
    resample: bool,
    /// Levelling: none, mean, plane or curvature.
    #[arg(long, default_value = "plane", value_parser = ["none", "mean", "plane", "curvature"])]
    detrend: String,
    /// The channel to read (index; default: the file's default channel).
    #[arg(long)]
    channel: Option<usize>,
    /// The Python interpreter with the wearsim package and its `measured` extra installed
    /// (`pip install "wearsim[measured]"`); default: $WEARSIM_PYTHON, else python3.
    #[arg(long)]
    python: Option<PathBuf>,
    /// Replace DIR even when it is not a folder that `surface import` wrote.
    #[arg(long)]
    overwrite: bool,
}

#[derive(clap::Args)]
struct FitArgs {
    /// Height map: .npy, .npz, a text or CSV matrix, or x y z columns.
    file: PathBuf,
    /// Physical size along the first axis, or both sides (`--length LX --length LY`); column files
    /// state it themselves.
    #[arg(long, num_args = 1, allow_hyphen_values = true)]
    length: Vec<f64>,
    /// Unit of the heights (m, mm, um, nm, pm, A): the results are then in metres (SI runs).
    #[arg(long)]
    height_unit: Option<String>,
    /// Unit of a column file's x y coordinates (default: the height unit).
    #[arg(long)]
    lateral_unit: Option<String>,
    /// Levelling before the fit: none, mean, plane or curvature. A tilt or a form would dominate the
    /// long wavelengths of the spectrum.
    #[arg(long, default_value = "plane")]
    detrend: String,
    /// Fraction of each side brought smoothly to the mean before the fit (0: none).
    #[arg(long, default_value_t = 0.0)]
    taper: f64,
    /// Seed written into the block (and used by --generate).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Output folder: surface.toml (the block) and fit.json.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also write the synthetic periodic pair (top.npy, bottom.npy) into --out and print its
    /// statistics.
    #[arg(long, requires = "out")]
    generate: bool,
    #[command(flatten)]
    overwrite: super::Overwrite,
}

pub fn run(args: &Args) -> Result<()> {
    match &args.action {
        Some(Action::Fit(fit)) => return run_fit(fit),
        Some(Action::Import(import)) => return run_import(import),
        None => {}
    }
    let (Some(run), Some(out)) = (&args.run, &args.out) else {
        bail!("give a run file and --out, or `wearsim surface fit FILE`");
    };
    let config = load_run(run)?;
    let dir = OutputDir::begin(out, "surface", args.overwrite.replace, &super::run_inputs(run, &config))?;
    let pair = config.surface_pair()?;
    super::report_surfaces(&pair, true);
    let (top, bottom) = (pair.top, pair.bottom);
    let unit = config.units.length_unit();
    let stats = [SurfaceStatistics::of(&top), SurfaceStatistics::of(&bottom)];
    top.write_npy(&dir.join("top.npy"))?;
    bottom.write_npy(&dir.join("bottom.npy"))?;
    write_json(
        &dir.join("statistics.json"),
        &surface_summary(&config, &stats[0], &stats[1]),
    )?;
    dir.commit()?;
    for (name, s) in [("top", &stats[0]), ("bottom", &stats[1])] {
        print_statistics(name, s, unit);
    }
    say!("wrote {}", out.display());
    Ok(())
}

fn print_statistics(name: &str, s: &SurfaceStatistics, unit: &str) {
    say!(
        "{name:>6}: {nx}×{ny} pixels, {lx} × {ly} {unit}, h_rms = {h:.6e} {unit}, rms slope = {g:.6e}",
        nx = s.grid,
        ny = s.grid_y,
        lx = s.length,
        ly = s.length_y,
        h = s.rms_height,
        g = s.rms_slope
    );
}

fn run_import(args: &ImportArgs) -> Result<()> {
    super::polls_interrupt();
    for file in std::iter::once(&args.file).chain(&args.bottom) {
        if !file.is_file() {
            bail!("{}: no such file", file.display());
        }
    }
    // Asked before any folder is made, so that the error says what to install.
    let python = super::python_with(
        args.python.as_deref(),
        "import wearsim.measured, SurfaceTopography",
        "measured",
        "the import",
    )?;
    // Temporary folders of killed imports beside it.
    wearsim::io::remove_abandoned_siblings(&args.out);
    super::check_interrupt()?;
    let mut command = Command::new(&python);
    command.args(["-m", "wearsim.measured", "--detrend", &args.detrend]);
    if let Some(fill) = &args.fill {
        command.args(["--fill", fill]);
    }
    if args.resample {
        command.arg("--resample");
    }
    if let Some(channel) = args.channel {
        command.args(["--channel", &channel.to_string()]);
    }
    if args.overwrite {
        command.arg("--overwrite");
    }
    if let Some(bottom) = &args.bottom {
        // One argument, so that a name starting with '-' is not read as an option.
        let mut arg = std::ffi::OsString::from("--bottom=");
        arg.push(bottom);
        command.arg(arg);
    }
    // `--` so that a file or folder whose name starts with '-' is not read as an option.
    command.arg("--").arg(&args.file).arg(&args.out);
    // A stop signal is passed on: the import removes its temporary folder and exits.
    super::run_child(command, "the import")
}

/// How `surface fit` reads its file: the units, the sides given (at most two, each positive) and the
/// levelling.
fn file_surface(args: &FitArgs) -> Result<FileSurface> {
    let scale = |field: &str, unit: &Option<String>| -> Result<f64> {
        Ok(match unit {
            Some(u) => topography::metres_per(field, u)?,
            None => 1.0,
        })
    };
    let lateral = args.lateral_unit.clone().or_else(|| args.height_unit.clone());
    let detrend: Detrend = args.detrend.parse().context("--detrend")?;
    let how = FileSurface {
        height_scale: scale("height_unit", &args.height_unit)?,
        lateral_scale: scale("lateral_unit", &lateral)?,
        length_x: args.length.first().copied(),
        length_y: args.length.get(1).copied(),
        preprocess: Preprocess {
            detrend,
            taper: args.taper,
        },
    };
    if args.length.len() > 2 {
        anyhow::bail!(
            "--length given {} times ({}): a height map has two sides; give `--length LX` for a square pixel grid or \
             `--length LX --length LY`",
            args.length.len(),
            args.length.iter().map(|l| l.to_string()).collect::<Vec<_>>().join(", ")
        );
    }
    for &l in &args.length {
        wearsim::check::positive("length", l).context("--length")?;
    }
    Ok(how)
}

/// The `[surface]` block that carries the map's spectrum as measured, for a spectrum that is not
/// self-affine: the map as this command read it (its path made absolute, so that a run file
/// anywhere finds it), with the units and size it was given.
fn spectrum_block(args: &FitArgs, grid: &Grid, window: topography::Window, unit: &str) -> String {
    let mut extra = Vec::new();
    if let Some(l) = args.length.first() {
        extra.push(format!("map_length = {l}"));
    }
    if let Some(u) = &args.height_unit {
        extra.push(format!("height_unit = \"{u}\""));
    }
    if let Some(u) = &args.lateral_unit {
        extra.push(format!("lateral_unit = \"{u}\""));
    }
    let map_path = std::fs::canonicalize(&args.file).unwrap_or_else(|_| args.file.clone());
    topography::spectrum_block(
        &map_path.display().to_string(),
        grid,
        window,
        args.seed,
        &extra,
        unit.trim_matches(['(', ')']),
    )
}

/// The fit in numbers: its band of wavenumbers, what it left out, the x/y power ratio and the
/// periodicity of the prepared map.
fn report_fit(fit: &topography::SpectrumFit, periodicity: &topography::Periodicity) {
    say!(
        "fitted C(q) ∝ q^−2(1+H) over q = {:.4e} … {:.4e} (2π/λ, {} shells, {} window), R² = {} (log–log PSD); \
         left out: {} shells at longer wavelengths than λ_u and {} at shorter than λ_l, down to the floor \
         (round-off or noise) at {:.1e} of the power law at λ_l; x/y power ratio {:.2}; periodicity of the \
         prepared map: border jumps {:.1} (x) and {:.1} (y) typical steps",
        fit.fitted_q[0],
        fit.fitted_q[1],
        fit.shells,
        fit.window.name(),
        fit.r2.map_or("undefined".into(), |r| format!("{r:.4}")),
        fit.shells_longer,
        fit.shells_shorter,
        fit.floor,
        fit.anisotropy,
        periodicity.border_step_x,
        periodicity.border_step_y
    );
}

/// A generated pair in `dir` (top.npy, bottom.npy) with `seed`: self-affine with `params`, else
/// carrying the measured PSD of `surface` (under `window`); the statistics of each printed.
fn write_pair(
    dir: &OutputDir,
    surface: &Surface,
    params: Option<&SpectrumParams>,
    window: topography::Window,
    seed: u64,
    unit: &str,
) -> Result<()> {
    let grid = surface.grid();
    let (a, b) = pair_seeds(seed);
    let psd = topography::MeasuredPsd::of(surface, window)?;
    for (name, seed) in [("top", a), ("bottom", b)] {
        let s = match params {
            Some(params) => Surface::generate(grid, params, seed)?,
            None => psd.generate(grid, seed)?,
        };
        s.write_npy(&dir.join(&format!("{name}.npy")))?;
        print_statistics(name, &SurfaceStatistics::of(&s), unit);
    }
    Ok(())
}

/// The `[surface]` block of a fit, with the generation parameters it gives on the map's grid and
/// the notes on what they leave out: the self-affine block, or for a spectrum that is not
/// self-affine `spectrum_block` with the fit kept below as comments. The fit is reported.
fn fitted_block(
    fit: &topography::SpectrumFit,
    verdict: &topography::Verdict,
    loaded: &topography::Loaded,
    seed: u64,
    source: &str,
    unit: &str,
    spectrum_block: &str,
) -> (String, SpectrumParams, Vec<String>) {
    let grid = loaded.surface.grid();
    let (params, fit_notes) = fit.spectrum(&grid);
    for note in &fit_notes {
        tell!("warning: {note}");
    }
    let block = topography::surface_block(&grid, &params, seed, source, unit.trim_matches(['(', ')']));
    report_fit(fit, &loaded.periodicity);
    if let Some(w) = fit.poor_fit_warning() {
        tell!("warning: {w}");
    }
    let block = if verdict.self_affine {
        block
    } else {
        // One [surface] table per run file: the spectrum's, with the self-affine fit kept
        // below as comments for its numbers.
        let commented: String = block.lines().map(|l| format!("# {l}\n")).collect();
        format!("{spectrum_block}\n# The self-affine fit, which leaves out what the spectrum is not:\n{commented}")
    };
    (block, params, fit_notes)
}

/// The note of a spectrum that is not self-affine (`verdict` says why): the block printed carries
/// its measured PSD, with the self-affine fit as comments where there is one (`fitted`).
fn note_not_self_affine(source: &str, verdict: &topography::Verdict, fitted: bool) {
    tell!(
        "note: the spectrum of {source} is not self-affine ({}); the block below generates periodic surfaces that \
         carry its measured 2D PSD (source = \"spectrum\"){}",
        verdict.reasons.join("; "),
        if fitted {
            ", with the self-affine fit kept as comments"
        } else {
            ""
        }
    );
}

fn run_fit(args: &FitArgs) -> Result<()> {
    let how = file_surface(args)?;
    let dir = match &args.out {
        Some(out) => Some(OutputDir::begin(
            out,
            "surface-fit",
            args.overwrite.replace,
            &[args.file.as_path()],
        )?),
        None => None,
    };
    // The library's errors name the file already.
    let loaded = topography::load(&args.file, &how)?;
    for note in &loaded.notes {
        tell!("note: {note}");
    }
    let surface = &loaded.surface;
    let grid = surface.grid();
    let unit = if args.height_unit.is_some() {
        "m"
    } else {
        "(file units)"
    };
    let source = args
        .file
        .file_name()
        .map_or_else(|| args.file.display().to_string(), |n| n.to_string_lossy().into());
    let fitted = topography::fit(surface);
    let verdict = match &fitted {
        Ok(fit) => fit.verdict(),
        Err(e) => topography::Verdict::no_band(&e.to_string()),
    };
    // The window of the fit's PSD, else the one the map would be taken under.
    let window = fitted
        .as_ref()
        .map_or_else(|_| topography::Window::for_map(surface), |f| f.window);
    let spectrum_block = spectrum_block(args, &grid, window, unit);
    let (block, spectrum, notes) = match &fitted {
        Ok(fit) => {
            let (block, params, notes) =
                fitted_block(fit, &verdict, &loaded, args.seed, &source, unit, &spectrum_block);
            (block, Some(params), notes)
        }
        Err(_) => (spectrum_block.clone(), None, Vec::new()),
    };
    if !verdict.self_affine {
        note_not_self_affine(&source, &verdict, fitted.is_ok());
    }
    if args.height_unit.is_some() {
        say!("# in a run file with units = \"si\"");
    }
    say_part!("{block}");
    let Some(dir) = dir else { return Ok(()) };
    write_text(&dir.join("surface.toml"), &block)?;
    write_json(
        &dir.join("fit.json"),
        &surface_fit_summary(
            &args.file,
            &how.preprocess,
            unit,
            &grid,
            fitted.as_ref().ok().zip(spectrum.as_ref()),
            &verdict,
            &notes,
        ),
    )?;
    if args.generate {
        // The self-affine parameters where the spectrum is self-affine, else the spectrum itself.
        let params = spectrum.as_ref().filter(|_| verdict.self_affine);
        write_pair(&dir, surface, params, window, args.seed, unit)?;
    }
    dir.commit()?;
    say!("wrote {}", args.out.as_ref().expect("an output folder").display());
    Ok(())
}
