//! Where a run's two surfaces come from (generated, read from files, or arrays the caller holds),
//! resolved from the `[surface]` table of a run file.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::check::positive;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::surface::{pair_seeds, SpectrumParams, Surface};
use crate::topography::{metres_per, FileSurface, MeasuredPsd, Preprocess, Window};

use super::raw::{PerSide, RawSurface, Units};

#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceSource {
    /// Generated from spectral parameters and one seed (top and bottom seeds derived from it).
    Generated {
        grid: Grid,
        spectrum: SpectrumParams,
        seed: u64,
    },
    /// Read from height-map files (paths resolved against the run file's folder), in any format
    /// [`crate::topography::read`] knows.
    Files {
        top: PathBuf,
        bottom: PathBuf,
        /// Side along x in the run's length unit (given, or from the file's coordinates).
        length: f64,
        /// Side along y, when the run file gives it.
        length_y: Option<f64>,
        /// The file's height unit and x y coordinate unit as written in the run file.
        height_unit: Option<String>,
        lateral_unit: Option<String>,
        preprocess: Preprocess,
    },
    /// Two height arrays the caller holds (the Python `slide` on arrays), on `grid`, whose side
    /// along x is `length` as the caller gave it; nothing to generate or read.
    Arrays { grid: Grid, length: f64 },
    /// Generated on `grid` from the measured 2D PSD of the height map `map` (`source =
    /// "spectrum"`, [`crate::topography::MeasuredPsd`]), with random phases from one seed (top and
    /// bottom seeds derived from it).
    Spectrum {
        grid: Grid,
        /// The map, resolved against the run file's folder; any format [`crate::topography::read`]
        /// knows.
        map: PathBuf,
        /// The map's side along x in the run's length unit (given, or from its coordinates).
        map_length: f64,
        height_unit: Option<String>,
        lateral_unit: Option<String>,
        /// The window of the map's PSD; absent: Hann when the map is not periodic, none when it is.
        window: Option<Window>,
        seed: u64,
    },
}

impl SurfaceSource {
    /// The files the surfaces are read from or made of (none for generated surfaces and arrays):
    /// inputs that an output folder may not hold, and whose contents enter a study's hash.
    pub fn input_files(&self) -> Vec<&Path> {
        match self {
            SurfaceSource::Files { top, bottom, .. } => vec![top.as_path(), bottom.as_path()],
            SurfaceSource::Spectrum { map, .. } => vec![map.as_path()],
            SurfaceSource::Generated { .. } | SurfaceSource::Arrays { .. } => Vec::new(),
        }
    }
}

impl SurfaceSource {
    /// The kind of these surfaces as the static estimate's reach sees it
    /// ([`crate::estimate::run_reach_warnings`]), on `grid`: any source but the generator is
    /// outside the calibration's spectrum.
    pub fn estimate_kind(&self, grid: Grid) -> crate::estimate::SurfaceKind {
        use crate::estimate::SurfaceKind;
        match self {
            SurfaceSource::Generated { spectrum, .. } => SurfaceKind::Generated {
                hurst: spectrum.hurst,
                lower_cutoff_pixels: spectrum.lambda_lower / grid.pixel_size(),
                upper_cutoff_box: spectrum.lambda_upper / grid.length_x(),
                upper_cutoff: spectrum.lambda_upper,
            },
            SurfaceSource::Files { .. } => SurfaceKind::Other("read from height-map files (a measured map)".into()),
            SurfaceSource::Arrays { .. } => SurfaceKind::Other("height arrays given by the caller".into()),
            SurfaceSource::Spectrum { .. } => {
                SurfaceKind::Other("generated from a measured map's spectrum (source = \"spectrum\")".into())
            }
        }
    }
}

/// One value for a square grid, `[x, y]` for a rectangular one (as a run file writes it).
fn per_side<T: serde::Serialize + PartialEq>(x: T, y: T) -> serde_json::Value {
    if x == y {
        serde_json::json!(x)
    } else {
        serde_json::json!([x, y])
    }
}

impl serde::Serialize for SurfaceSource {
    /// As a run file writes it: `grid` and `length` one value when square, `[x, y]` otherwise.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        match self {
            SurfaceSource::Generated { grid, spectrum, seed } => {
                map.serialize_entry("source", "generated")?;
                map.serialize_entry("grid", &per_side(grid.nx(), grid.ny()))?;
                map.serialize_entry("length", &per_side(grid.length_x(), grid.length_y()))?;
                map.serialize_entry("spectrum", spectrum)?;
                map.serialize_entry("seed", seed)?;
            }
            SurfaceSource::Files {
                top,
                bottom,
                length,
                length_y,
                height_unit,
                lateral_unit,
                preprocess,
            } => {
                map.serialize_entry("source", "files")?;
                map.serialize_entry("top", top)?;
                map.serialize_entry("bottom", bottom)?;
                match length_y {
                    Some(ly) => map.serialize_entry("length", &[length, ly])?,
                    None => map.serialize_entry("length", length)?,
                }
                if let Some(u) = height_unit {
                    map.serialize_entry("height_unit", u)?;
                }
                if let Some(u) = lateral_unit {
                    map.serialize_entry("lateral_unit", u)?;
                }
                if *preprocess != Preprocess::default() {
                    map.serialize_entry("detrend", preprocess.detrend.name())?;
                    map.serialize_entry("taper", &preprocess.taper)?;
                }
            }
            SurfaceSource::Spectrum {
                grid,
                map: file,
                map_length,
                height_unit,
                lateral_unit,
                window,
                seed,
            } => {
                // As a run file writes it, so that it reads back.
                map.serialize_entry("source", "spectrum")?;
                map.serialize_entry("map", file)?;
                map.serialize_entry("map_length", map_length)?;
                map.serialize_entry("grid", &per_side(grid.nx(), grid.ny()))?;
                map.serialize_entry("length", &per_side(grid.length_x(), grid.length_y()))?;
                if let Some(u) = height_unit {
                    map.serialize_entry("height_unit", u)?;
                }
                if let Some(u) = lateral_unit {
                    map.serialize_entry("lateral_unit", u)?;
                }
                if let Some(w) = window {
                    map.serialize_entry("window", w.name())?;
                }
                map.serialize_entry("seed", seed)?;
            }
            SurfaceSource::Arrays { grid, length } => {
                map.serialize_entry("source", "arrays")?;
                map.serialize_entry("grid", &per_side(grid.nx(), grid.ny()))?;
                if grid.is_square() {
                    map.serialize_entry("length", length)?;
                } else {
                    map.serialize_entry("length", &[*length, grid.length_y()])?;
                }
            }
        }
        map.end()
    }
}

/// The two surfaces of a run, with notes on how files were read and warnings about them.
#[derive(Debug, Clone)]
pub struct SurfacePair {
    /// Shared, so that a run and the few steps that measure its cost slide on the same surfaces
    /// without a copy.
    pub top: std::sync::Arc<Surface>,
    pub bottom: std::sync::Arc<Surface>,
    pub notes: Vec<String>,
    pub warnings: Vec<String>,
}

impl SurfacePair {
    /// The two surfaces, owned (a copy only of one still shared elsewhere).
    pub fn into_surfaces(self) -> (Surface, Surface) {
        let own = |s: std::sync::Arc<Surface>| std::sync::Arc::try_unwrap(s).unwrap_or_else(|s| (*s).clone());
        (own(self.top), own(self.bottom))
    }

    /// Two surfaces handed over as arrays (a [`SurfaceSource::Arrays`] run). They may be measured
    /// maps, so each is checked for periodicity as a file is, named "top" and "bottom" in the
    /// warnings.
    pub fn of_arrays(top: Surface, bottom: Surface) -> Self {
        let warnings = [("top", &top), ("bottom", &bottom)]
            .into_iter()
            .filter_map(|(name, s)| crate::topography::periodicity(s.heights(), s.nx(), s.ny()).warning(name))
            .collect();
        Self {
            top: std::sync::Arc::new(top),
            bottom: std::sync::Arc::new(bottom),
            notes: Vec::new(),
            warnings,
        }
    }
}

/// Whether the surface files a run names must exist when it is read: for a run about to be
/// computed they must; a finished study's stored runs are read back without them (its results are
/// collected without the surfaces).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceFiles {
    MustExist,
    Recorded,
}

/// Factor from the unit of a file's x y coordinates (`lateral_unit`, else `height_unit`) to the
/// run's length unit: metres in SI runs, none in reduced runs.
pub(super) fn lateral_scale(units: Units, lateral_unit: &Option<String>, height_unit: &Option<String>) -> Result<f64> {
    match (units, lateral_unit.as_ref().or(height_unit.as_ref())) {
        (Units::Si, Some(u)) => metres_per("lateral_unit", u),
        _ => Ok(1.0),
    }
}

fn missing_length() -> Error {
    missing(
        "length",
        "give the physical size of the height maps, length = Lx or [Lx, Ly] along their first and second axes (only \
         x y z column files state it themselves, and the maps `wearsim surface import` writes, in a run of units = \
         \"si\", while they are at hand)",
    )
}

pub(super) fn missing(field: &str, hint: &str) -> Error {
    Error::run_file(format!("[surface] `{field}` is missing; {hint}"))
}

/// The grid of generated surfaces: `grid = N` with `length = L` (square) or `[Lx, Ly]` (Ny from
/// square pixels), or `grid = [Nx, Ny]` with `length = Lx` or `[Lx, Ly]`.
pub(super) fn generated_grid(grid: PerSide<usize>, length: PerSide<f64>) -> Result<Grid> {
    match (grid, length) {
        (PerSide::Both(n), PerSide::Both(l)) => Grid::square(n, l),
        (PerSide::Each([nx, ny]), PerSide::Both(lx)) => Grid::new(nx, ny, lx),
        (PerSide::Each([nx, ny]), PerSide::Each([lx, ly])) => Grid::with_lengths(nx, ny, lx, ly),
        (PerSide::Both(nx), PerSide::Each([lx, ly])) => {
            positive("length", lx)?;
            positive("length", ly)?;
            let ny = nx as f64 * ly / lx;
            if (ny - ny.round()).abs() > 1e-9 * ny {
                return Err(Error::param(
                    "grid",
                    format!(
                        "{nx} pixels along x over length = [{lx}, {ly}] gives {ny} pixels along y, not a whole number; \
                         give grid = [Nx, Ny] with Lx/Nx = Ly/Ny"
                    ),
                ));
            }
            Grid::with_lengths(nx, ny.round() as usize, lx, ly)
        }
    }
}

/// The source of surfaces read from files: units converted to the run's, the size resolved
/// (from `length`, or the coordinates of a column file when the files exist).
pub(super) fn files_source(
    s: &RawSurface,
    units: Units,
    top: PathBuf,
    bottom: PathBuf,
    files: SurfaceFiles,
    notes: &mut Vec<String>,
) -> Result<SurfaceSource> {
    for (field, value) in [
        ("grid", s.grid.is_some()),
        ("hurst", s.hurst.is_some()),
        ("lambda_lower", s.lambda_lower.is_some()),
        ("lambda_upper", s.lambda_upper.is_some()),
        ("rms_height", s.rms_height.is_some()),
        ("seed", s.seed.is_some()),
        ("generation", s.generation.is_some()),
    ] {
        if value {
            return Err(Error::run_file(format!(
                "[surface] `{field}` has no meaning when `top` and `bottom` are read from files; remove it"
            )));
        }
    }
    for (field, unit) in [("height_unit", &s.height_unit), ("lateral_unit", &s.lateral_unit)] {
        if let Some(u) = unit {
            metres_per(field, u)?;
            if units != Units::Si {
                return Err(Error::run_file(format!(
                    "[surface] `{field}` = \"{u}\" converts the file to metres, which needs units = \"si\"; in \
                     reduced units give the heights in the unit of `length` and remove `{field}`"
                )));
            }
        }
    }
    let preprocess = Preprocess {
        detrend: s.detrend.unwrap_or_default(),
        taper: s.taper.unwrap_or(0.0),
    };
    preprocess.validate()?;
    // One spelling per file, so that job files and the study's stored base agree however the
    // study was named on the command line.
    let (top, bottom) = (crate::io::canonical_path(&top), crate::io::canonical_path(&bottom));
    for p in [&top, &bottom] {
        if files == SurfaceFiles::MustExist && !p.is_file() {
            if p.exists() {
                crate::topography::regular_file(p)?;
            }
            return Err(Error::file(
                p,
                "surface file not found (paths are relative to the run file)",
            ));
        }
    }
    let (length, length_y) = files_length(s, units, &top, notes)?;
    positive("length", length)?;
    Ok(SurfaceSource::Files {
        top,
        bottom,
        length,
        length_y,
        height_unit: s.height_unit.clone(),
        lateral_unit: s.lateral_unit.clone(),
        preprocess,
    })
}

/// The source of a run's surfaces from its `[surface]` table: files (both `top` and `bottom`,
/// resolved against `base`) or generated (neither), with the keys that do not belong to that choice
/// refused by name.
pub(super) fn surface_source(
    s: &RawSurface,
    units: Units,
    base: &Path,
    files: SurfaceFiles,
    notes: &mut Vec<String>,
) -> Result<SurfaceSource> {
    let by_keys = if s.top.is_some() || s.bottom.is_some() {
        "files"
    } else {
        "generated"
    };
    match s.source.as_deref() {
        Some("spectrum") => return spectrum_source(s, units, base, files, notes),
        None => {}
        Some(named) if named == by_keys => {}
        Some(named @ ("files" | "generated")) => {
            return Err(Error::run_file(format!(
                "[surface] `source` = \"{named}\" but the keys describe {by_keys} surfaces: {}",
                if named == "files" {
                    "give `top` and `bottom`"
                } else {
                    "remove `top` and `bottom`"
                }
            )))
        }
        Some(other) => {
            return Err(Error::run_file(format!(
                "[surface] `source` = \"{other}\"; use \"generated\", \"files\" or \"spectrum\" (periodic surfaces \
                 carrying the measured PSD of `map`)"
            )))
        }
    }
    for (field, value) in [
        ("map", s.map.is_some()),
        ("map_length", s.map_length.is_some()),
        ("window", s.window.is_some()),
    ] {
        if value {
            return Err(Error::run_file(format!(
                "[surface] `{field}` applies to source = \"spectrum\" (surfaces generated from a measured map's PSD); \
                 add source = \"spectrum\" or remove it"
            )));
        }
    }
    match (&s.top, &s.bottom) {
        (Some(top), Some(bottom)) => files_source(s, units, base.join(top), base.join(bottom), files, notes),
        (None, None) => generated_source(s),
        _ => Err(Error::run_file(
            "[surface] give both `top` and `bottom` files, or neither (to generate the surfaces)",
        )),
    }
}

/// The source of generated self-affine surfaces (neither `top` nor `bottom`): the keys of files
/// refused by name, the grid and the spectrum given (H = 0.7 by default) and checked on it.
fn generated_source(s: &RawSurface) -> Result<SurfaceSource> {
    for (field, value) in [
        ("height_unit", s.height_unit.is_some()),
        ("lateral_unit", s.lateral_unit.is_some()),
        ("detrend", s.detrend.is_some()),
        ("taper", s.taper.is_some()),
    ] {
        if value {
            return Err(Error::run_file(format!(
                "[surface] `{field}` applies to surfaces read from files (`top` and `bottom`); remove it"
            )));
        }
    }
    let grid = generated_grid(
        s.grid
            .ok_or_else(|| missing("grid", "give the number of pixels per side, e.g. 512"))?,
        s.length.unwrap_or(PerSide::Both(1.0)),
    )?;
    let spectrum = SpectrumParams {
        hurst: s.hurst.unwrap_or(0.7),
        lambda_lower: s
            .lambda_lower
            .ok_or_else(|| missing("lambda_lower", "e.g. 16 pixels, 16·length/grid"))?,
        lambda_upper: s
            .lambda_upper
            .ok_or_else(|| missing("lambda_upper", "e.g. length/16"))?,
        rms_height: s.rms_height.ok_or_else(|| missing("rms_height", "e.g. 0.005·length"))?,
        generation: s.generation.unwrap_or_default(),
    };
    spectrum.validate(&grid)?;
    Ok(SurfaceSource::Generated {
        grid,
        spectrum,
        seed: s.seed.unwrap_or(0),
    })
}

/// The keys of a `source = "spectrum"` table: those of the other sources refused by name, and the
/// map's units only with units = "si".
fn spectrum_keys(s: &RawSurface, units: Units) -> Result<()> {
    for (field, value) in [
        ("hurst", s.hurst.is_some()),
        ("lambda_lower", s.lambda_lower.is_some()),
        ("lambda_upper", s.lambda_upper.is_some()),
        ("rms_height", s.rms_height.is_some()),
        ("generation", s.generation.is_some()),
        ("top", s.top.is_some()),
        ("bottom", s.bottom.is_some()),
        ("detrend", s.detrend.is_some()),
        ("taper", s.taper.is_some()),
    ] {
        if value {
            return Err(Error::run_file(format!(
                "[surface] `{field}` has no meaning with source = \"spectrum\" (the surfaces carry the measured PSD of \
                 `map`, levelled by a plane under a Hann window or by its mean without one); remove it"
            )));
        }
    }
    for (field, unit) in [("height_unit", &s.height_unit), ("lateral_unit", &s.lateral_unit)] {
        if let Some(u) = unit {
            metres_per(field, u)?;
            if units != Units::Si {
                return Err(Error::run_file(format!(
                    "[surface] `{field}` = \"{u}\" converts the map to metres, which needs units = \"si\"; in reduced \
                     units give its heights in the unit of `length` and remove `{field}`"
                )));
            }
        }
    }
    Ok(())
}

/// The source of surfaces generated from the measured PSD of a map (`source = "spectrum"`): the
/// map's path resolved against `base`, its units checked as a file's, its size given or read from
/// its coordinates; the keys of the other sources refused by name.
fn spectrum_source(
    s: &RawSurface,
    units: Units,
    base: &Path,
    files: SurfaceFiles,
    notes: &mut Vec<String>,
) -> Result<SurfaceSource> {
    spectrum_keys(s, units)?;
    let map = s.map.as_ref().ok_or_else(|| {
        missing(
            "map",
            "give the measured height map whose PSD the surfaces carry, e.g. map = \"heights.npy\" (as `wearsim \
             surface import` writes it; relative to the run file)",
        )
    })?;
    let map = crate::io::canonical_path(&base.join(map));
    if files == SurfaceFiles::MustExist && !map.is_file() {
        if map.exists() {
            crate::topography::regular_file(&map)?;
        }
        return Err(Error::file(
            &map,
            "[surface] `map`: height map not found (paths are relative to the run file)",
        ));
    }
    let map_length = spectrum_map_length(s, units, &map, notes)?;
    positive("map_length", map_length)?;
    let cells = s.grid.ok_or_else(|| {
        missing(
            "grid",
            "give the number of pixels per side of the generated surfaces, e.g. 256",
        )
    })?;
    let length = spectrum_box(s.length, cells, map_length, units, &map, notes)?;
    let grid = generated_grid(cells, length)?;
    Ok(SurfaceSource::Spectrum {
        grid,
        map,
        map_length,
        height_unit: s.height_unit.clone(),
        lateral_unit: s.lateral_unit.clone(),
        window: s.window,
        seed: s.seed.unwrap_or(0),
    })
}

/// The sides of an imported map from its import record ([`crate::topography::imported_length`]),
/// in metres: only for a run in SI units, whose length unit they are.
fn imported_sides(path: &Path, units: Units) -> Result<Option<[f64; 2]>> {
    if units != Units::Si {
        return Ok(None);
    }
    crate::topography::imported_length(path)
}

/// The number of pixels along x (the first axis) of a map as given, before any cropping.
fn map_columns(map: &Path) -> Result<usize> {
    match crate::topography::array_shape(map)? {
        Some((rows, _)) => Ok(rows),
        None => Ok(crate::topography::read(map)?.rows),
    }
}

/// The sides of surfaces read from files: `length` as given, else the import record of a map that
/// `wearsim surface import` wrote (in SI runs), else the span of a column file's coordinates.
fn files_length(s: &RawSurface, units: Units, top: &Path, notes: &mut Vec<String>) -> Result<(f64, Option<f64>)> {
    Ok(match s.length {
        Some(PerSide::Both(l)) => (l, None),
        Some(PerSide::Each([lx, ly])) => {
            positive("length", ly)?;
            (lx, Some(ly))
        }
        // A map that `wearsim surface import` wrote has its size in the import's record, in
        // metres; a column file states its size in its coordinates (a stored run whose files are
        // gone cannot be asked).
        None if top.is_file() => match imported_sides(top, units)? {
            Some([lx, ly]) => {
                notes.push(format!(
                    "[surface] length = [{lx:.6e}, {ly:.6e}] m, the box of the imported map {} (its import.json)",
                    top.display()
                ));
                (lx, Some(ly))
            }
            None => match crate::topography::file_span(top)? {
                Some((x, _)) => (x * lateral_scale(units, &s.lateral_unit, &s.height_unit)?, None),
                None => return Err(missing_length()),
            },
        },
        None => return Err(missing_length()),
    })
}

/// The side along x of a spectrum's map: `map_length` as given, else the import record of a map
/// that `wearsim surface import` wrote (in SI runs), else the span of a column file's coordinates.
fn spectrum_map_length(s: &RawSurface, units: Units, map: &Path, notes: &mut Vec<String>) -> Result<f64> {
    Ok(match s.map_length {
        Some(l) => l,
        None if map.is_file() => match imported_sides(map, units)? {
            Some([lx, _]) => {
                notes.push(format!(
                    "[surface] map_length = {lx:.6e} m, the side of the imported map {} (its import.json)",
                    map.display()
                ));
                lx
            }
            None => match crate::topography::file_span(map)? {
                Some((x, _)) => x * lateral_scale(units, &s.lateral_unit, &s.height_unit)?,
                None => {
                    return Err(missing(
                        "map_length",
                        "give the map's side along its first axis in the run's length unit (only x y z column files \
                         and the maps `wearsim surface import` writes, in a run of units = \"si\", state it themselves)",
                    ))
                }
            },
        },
        None => {
            return Err(missing(
                "map_length",
                "give the map's side along its first axis in the run's length unit",
            ))
        }
    })
}

/// The box of surfaces generated from a map's spectrum: `length` as given, else `cells` pixels of
/// the map's own size, Δ = map_length/Nx of the map.
fn spectrum_box(
    length: Option<PerSide<f64>>,
    cells: PerSide<usize>,
    map_length: f64,
    units: Units,
    map: &Path,
    notes: &mut Vec<String>,
) -> Result<PerSide<f64>> {
    Ok(match length {
        Some(length) => length,
        // The box at the map's pixel size, Δ = map_length/Nx of the map.
        None if map.is_file() => {
            let pixel = map_length / map_columns(map)? as f64;
            let (sides, length) = match cells {
                PerSide::Both(n) => (
                    format!("{n} × Δ = {:.6e}", n as f64 * pixel),
                    PerSide::Both(n as f64 * pixel),
                ),
                PerSide::Each([nx, ny]) => (
                    format!(
                        "[{nx}, {ny}] × Δ = [{:.6e}, {:.6e}]",
                        nx as f64 * pixel,
                        ny as f64 * pixel
                    ),
                    PerSide::Each([nx as f64 * pixel, ny as f64 * pixel]),
                ),
            };
            notes.push(format!(
                "[surface] length = {sides} {}: the box at the map's pixel size Δ = map_length/Nx = {pixel:.6e} {}",
                units.length_unit(),
                units.length_unit()
            ));
            length
        }
        None => {
            return Err(missing(
                "length",
                "give the side of the generated surfaces' box, e.g. the map's side (`map_length`); left out, the box \
                 is `grid` pixels of the map's size, which needs the map at hand",
            ))
        }
    })
}

/// How the surface files of `surfaces` are read in a run of `units` (units and preparation); an
/// error for surfaces not read from files.
pub(super) fn file_surface_of(surfaces: &SurfaceSource, units: Units) -> Result<FileSurface> {
    let SurfaceSource::Files {
        length,
        length_y,
        height_unit,
        lateral_unit,
        preprocess,
        ..
    } = surfaces
    else {
        return Err(Error::run_file("[surface] the surfaces are not read from files"));
    };
    let height_scale = match (units, height_unit) {
        (Units::Si, Some(u)) => metres_per("height_unit", u)?,
        _ => 1.0,
    };
    Ok(FileSurface {
        height_scale,
        lateral_scale: lateral_scale(units, lateral_unit, height_unit)?,
        length_x: Some(*length),
        length_y: *length_y,
        preprocess: *preprocess,
    })
}

/// Refuses a surface pair on `grid` that does not fit in the memory this process may use.
pub(super) fn check_pair_memory(grid: Grid) -> Result<()> {
    crate::check::memory(
        "generating the surface pair",
        grid.nx(),
        grid.ny(),
        crate::check::SURFACE_ARRAYS,
    )
}

/// A pair of self-affine surfaces generated with `spectrum` on `grid`, seeds derived from `seed`.
pub(super) fn generated_pair(grid: Grid, spectrum: &SpectrumParams, seed: u64) -> Result<SurfacePair> {
    check_pair_memory(grid)?;
    let (top_seed, bottom_seed) = pair_seeds(seed);
    // One after the other (each FFT is parallel inside): the peak memory is then the same whatever
    // the threads and the load ([`crate::check::SURFACE_ARRAYS`]); at once, it depended on whether a
    // second worker woke in time.
    let top = Surface::generate(grid, spectrum, top_seed)?;
    let bottom = Surface::generate(grid, spectrum, bottom_seed)?;
    Ok(SurfacePair {
        top: Arc::new(top),
        bottom: Arc::new(bottom),
        notes: Vec::new(),
        warnings: Vec::new(),
    })
}

/// A pair of periodic surfaces on `grid` carrying the measured PSD of `map` (read as `how` says),
/// with a note on what they carry of it. The map's periodicity warning is left out: the surfaces
/// made of it are periodic.
pub(super) fn spectrum_pair(
    map: &Path,
    how: &FileSurface,
    grid: Grid,
    window: Option<Window>,
    seed: u64,
) -> Result<SurfacePair> {
    let loaded = crate::topography::load(map, how)?;
    let name = map.display().to_string();
    if loaded.flat {
        return Err(crate::topography::flat_map(
            &name,
            how.preprocess.detrend,
            loaded.surface.rms_height(),
        ));
    }
    let psd = MeasuredPsd::of_map(&loaded.surface, window)?;
    let window = psd.window();
    let (top, bottom) = psd.generate_pair(grid, seed)?;
    let mut notes = loaded.notes;
    notes.push(format!(
        "{name}: the surfaces carry its measured PSD ({} window, {} × {} modes) on a {} × {} grid of box \
         {:e} × {:e}: h_rms = {:.4e} (the map's: {:.4e})",
        window.name(),
        psd.grid().nx(),
        psd.grid().ny(),
        grid.nx(),
        grid.ny(),
        grid.length_x(),
        grid.length_y(),
        psd.carried_rms(&grid),
        psd.rms_height()
    ));
    notes.extend(psd.notes(&grid, &name));
    Ok(SurfacePair {
        top: Arc::new(top),
        bottom: Arc::new(bottom),
        notes,
        warnings: Vec::new(),
    })
}

/// The surfaces of files `top` and `bottom`, read as `how` says: an error when their grids differ.
pub(super) fn file_pair(top: &Path, bottom: &Path, how: &FileSurface) -> Result<SurfacePair> {
    let t = crate::topography::load(top, how)?;
    let b = crate::topography::load(bottom, how)?;
    if t.surface.grid() != b.surface.grid() {
        let (tg, bg) = (t.surface.grid(), b.surface.grid());
        return Err(Error::InvalidSurface {
            name: bottom.display().to_string(),
            message: format!(
                "its grid, {} × {} pixels of {:e}, differs from the top surface's, {} × {} pixels of {:e}",
                bg.nx(),
                bg.ny(),
                bg.pixel_size(),
                tg.nx(),
                tg.ny(),
                tg.pixel_size()
            ),
        });
    }
    let notes = t.notes.into_iter().chain(b.notes).collect();
    let warnings = t.warnings.into_iter().chain(b.warnings).collect();
    Ok(SurfacePair {
        top: Arc::new(t.surface),
        bottom: Arc::new(b.surface),
        notes,
        warnings,
    })
}
