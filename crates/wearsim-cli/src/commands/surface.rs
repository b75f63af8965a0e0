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
    /// Unit of the heights (m, mm, um, nm, pm, A, or another SI prefix of the metre, Gm to fm): the
    /// results are then in metres (SI runs).
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
    /// Native pixel size of a map resampled onto finer pixels, in the unit of --length: once for
    /// both axes, or `--measured-pixel DX --measured-pixel DY`. The fit then uses only the measured
    /// wavevectors, |q_x| ≤ π/DX and |q_y| ≤ π/DY (beyond them the pixels are interpolated).
    /// Default: the native pixels recorded in import.json beside a map DIR/heights.npy that
    /// `wearsim surface import --resample` wrote.
    #[arg(long, num_args = 1, value_name = "PIXEL")]
    measured_pixel: Vec<f64>,
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
        "wearsim.measured",
        &["SurfaceTopography"],
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
    super::run_child(command, "the import", &args.out)
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

/// The native pixel sizes [Δx, Δy] of a map resampled onto finer pixels, in the map's length unit,
/// with where they come from: `--measured-pixel`, or the import.json that `wearsim surface import`
/// wrote beside the map when the map is that folder's heights.npy and it was resampled (the
/// native pixels as a multiple of the map's own, so that the map's length unit does not matter).
/// None when neither says so: the whole stored spectrum is measured.
fn measured_pixel(args: &FitArgs, grid: &Grid) -> Result<Option<([f64; 2], String)>> {
    match args.measured_pixel.as_slice() {
        [] => {}
        &[p] => return Ok(Some(([p, p], "--measured-pixel".into()))),
        &[px, py] => return Ok(Some(([px, py], "--measured-pixel".into()))),
        more => bail!(
            "--measured-pixel given {} times: a height map has two axes; give `--measured-pixel D` for both or \
             `--measured-pixel DX --measured-pixel DY`",
            more.len()
        ),
    }
    if args.file.file_name().is_none_or(|n| n != "heights.npy") {
        return Ok(None);
    }
    let record_path = args.file.with_file_name("import.json");
    let Ok(text) = std::fs::read_to_string(&record_path) else {
        return Ok(None);
    };
    let record: serde_json::Value = match serde_json::from_str(&text) {
        Ok(r) => r,
        Err(_) => return Ok(None),
    };
    if record["written_by"] != "wearsim surface import" || record["resampled"].is_null() {
        return Ok(None);
    }
    let shown = record_path.display();
    let number = |v: &serde_json::Value, what: &str| -> Result<f64> {
        v.as_f64()
            .filter(|x| x.is_finite() && *x > 0.0)
            .with_context(|| format!("{shown}: `{what}` is not a positive number; give --measured-pixel"))
    };
    let native = [
        number(&record["pixel_size"][0], "pixel_size")?,
        number(&record["pixel_size"][1], "pixel_size")?,
    ];
    let metres = number(&record["metres_per_unit"], "metres_per_unit")?;
    let pixel = number(&record["pixel_size_m"], "pixel_size_m")?;
    let heights_grid = [&record["heights_grid"][0], &record["heights_grid"][1]].map(serde_json::Value::as_u64);
    if heights_grid != [Some(grid.nx() as u64), Some(grid.ny() as u64)] {
        bail!(
            "{shown} describes a {} × {} map, not this {} × {} one, so its native pixel sizes do not apply; give \
             --measured-pixel (or move the map out of the folder that `wearsim surface import` wrote)",
            record["heights_grid"][0],
            record["heights_grid"][1],
            grid.nx(),
            grid.ny()
        );
    }
    let unit = record["unit"].as_str().unwrap_or("");
    let own = grid.pixel_size();
    Ok(Some((
        native.map(|p| own * p * metres / pixel),
        format!(
            "{shown}: `wearsim surface import --resample` put native pixels of {:.6e} × {:.6e} {unit} on square \
             pixels of {pixel:.6e} m",
            native[0], native[1]
        ),
    )))
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

/// The fit in numbers: its band of wavenumbers, what it left out, the band's h_rms against the
/// whole map's, the rms slope of the generated surfaces against the map's, the x/y power ratio and
/// the periodicity of the prepared map.
fn report_fit(
    fit: &topography::SpectrumFit,
    slopes: Option<&topography::SlopeComparison>,
    periodicity: &topography::Periodicity,
) {
    let slope = slopes.map_or_else(String::new, |s| {
        format!(
            "; rms slope of the generated surfaces {:.4e}, of the map {:.4e} ({:+.0} %)",
            s.generated,
            s.map,
            100.0 * s.change()
        )
    });
    say!(
        "fitted C(q) ∝ q^−2(1+H) over q = {:.4e} … {:.4e} (2π/λ, {} shells, {} window), R² = {} (log–log PSD); \
         left out: {} shells at longer wavelengths than λ_u and {} at shorter than λ_l, down to the floor \
         (round-off or noise) at {:.1e} of the power law at λ_l; h_rms of the band {:.4e}, of the whole map {:.4e} \
         ({:.1} % of its variance outside the band){slope}; x/y power ratio {:.2}; periodicity of the prepared map: \
         border jumps {:.1} (x) and {:.1} (y) typical steps",
        fit.fitted_q[0],
        fit.fitted_q[1],
        fit.shells,
        fit.window.name(),
        fit.r2.map_or("undefined".into(), |r| format!("{r:.4}")),
        fit.shells_longer,
        fit.shells_shorter,
        fit.floor,
        fit.rms_height,
        fit.map_rms_height,
        100.0 * fit.out_of_band_share,
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

/// What a fit gives a run file: the `[surface]` block, the generation parameters, the notes and the
/// rms slopes of the map and of the surfaces the parameters generate.
type Fitted = (String, SpectrumParams, Vec<String>, Option<topography::SlopeComparison>);

/// The `[surface]` block of a fit, with the generation parameters it gives on the map's grid and
/// the notes on what they adjust and leave out (the variance outside the band, when it is much;
/// the change of rms slope, likewise): the self-affine block, or for a spectrum that is not
/// self-affine `spectrum_block` with the fit kept below as comments. The fit is reported.
fn fitted_block(
    fit: &topography::SpectrumFit,
    verdict: &topography::Verdict,
    loaded: &topography::Loaded,
    seed: u64,
    source: &str,
    unit: &str,
    spectrum_block: &str,
) -> Fitted {
    let grid = loaded.surface.grid();
    let (params, mut fit_notes) = fit.spectrum(&grid);
    for note in &fit_notes {
        tell!("warning: {note}");
    }
    let block = topography::surface_block(&grid, &params, seed, source, unit.trim_matches(['(', ')']));
    let slopes = topography::SlopeComparison::of(&loaded.surface, &params).ok();
    report_fit(fit, slopes.as_ref(), &loaded.periodicity);
    for note in fit
        .out_of_band_note()
        .into_iter()
        .chain(slopes.as_ref().and_then(topography::SlopeComparison::note))
    {
        tell!("note: {note}");
        fit_notes.push(note);
    }
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
    (block, params, fit_notes, slopes)
}

/// The note of the native pixels of a resampled map (`measured`: with where they come from), in
/// `unit`: the fit takes only the wavevectors they measured.
fn note_measured(measured: Option<&([f64; 2], String)>, unit: &str) {
    if let Some(([px, py], from)) = measured {
        tell!(
            "note: the map was resampled onto finer pixels than it was measured with ({from}): the fit uses only the \
             measured wavevectors, |q_x| ≤ π/Δx and |q_y| ≤ π/Δy of the native pixels Δx = {px:.4e}, Δy = {py:.4e} \
             {u} (beyond them the pixels are interpolated)",
            u = unit.trim_matches(['(', ')'])
        );
    }
}

/// The note of a spectrum that is not self-affine (`verdict` says why): the block printed carries
/// its measured PSD, with the self-affine fit as comments where there is one (`fitted`); of a
/// `resampled` map, the whole stored spectrum (a run file takes no native pixel).
fn note_not_self_affine(source: &str, verdict: &topography::Verdict, fitted: bool, resampled: bool) {
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
    if resampled {
        tell!(
            "note: the source = \"spectrum\" block carries the map's whole stored spectrum, the interpolated \
             wavevectors beyond the native pixels' Nyquist wavenumbers included (a run file takes no native pixel)"
        );
    }
}

/// The map of `surface fit` read as `how` says, with its notes printed, and its file's name. A flat
/// map has no spectrum to fit or to carry: refused here rather than in a run file that reads its
/// block.
fn load_map(args: &FitArgs, how: &FileSurface) -> Result<(topography::Loaded, String)> {
    // The library's errors name the file already.
    let loaded = topography::load(&args.file, how)?;
    for note in &loaded.notes {
        tell!("note: {note}");
    }
    let source = args
        .file
        .file_name()
        .map_or_else(|| args.file.display().to_string(), |n| n.to_string_lossy().into());
    if loaded.flat {
        let rms = loaded.surface.rms_height();
        return Err(topography::flat_map(&source, how.preprocess.detrend, rms).into());
    }
    Ok((loaded, source))
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
    let (loaded, source) = load_map(args, &how)?;
    let surface = &loaded.surface;
    let grid = surface.grid();
    let unit = if args.height_unit.is_some() {
        "m"
    } else {
        "(file units)"
    };
    let measured = measured_pixel(args, &grid)?;
    note_measured(measured.as_ref(), unit);
    let fitted = topography::fit_measured(surface, measured.as_ref().map(|m| m.0));
    let verdict = match &fitted {
        Ok(fit) => fit.verdict(),
        Err(e) => topography::Verdict::no_band(&e.to_string()),
    };
    // The window of the fit's PSD, else the one the map would be taken under.
    let window = fitted
        .as_ref()
        .map_or_else(|_| topography::Window::for_map(surface), |f| f.window);
    let spectrum_block = spectrum_block(args, &grid, window, unit);
    let (block, spectrum, notes, slopes) = match &fitted {
        Ok(fit) => {
            let (block, params, notes, slopes) =
                fitted_block(fit, &verdict, &loaded, args.seed, &source, unit, &spectrum_block);
            (block, Some(params), notes, slopes)
        }
        Err(_) => (spectrum_block.clone(), None, Vec::new(), None),
    };
    if !verdict.self_affine {
        note_not_self_affine(&source, &verdict, fitted.is_ok(), measured.is_some());
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
            slopes.as_ref(),
            measured.as_ref().map(|m| m.1.as_str()),
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
