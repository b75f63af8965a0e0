//! A run's surface file turned into a surface: units, physical size, cropping to even sides,
//! preparation, with notes and warnings.

use std::path::Path;

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::surface::Surface;

use super::formats::{array_shape, is_array, read};
use super::prepare::{periodicity, preprocess, Detrend, Periodicity, Preprocess};

/// How a surface file of a run is turned into a surface: units, physical size and preparation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FileSurface {
    /// Factor from the file's height unit to the run's length unit (1 when the file is already in it).
    pub height_scale: f64,
    /// Factor from the unit of the file's x y coordinates (column files) to the run's length unit.
    pub lateral_scale: f64,
    /// Side along x (the first array axis) in the run's length unit; from the file when absent.
    pub length_x: Option<f64>,
    /// Side along y; checked against square pixels when given.
    pub length_y: Option<f64>,
    pub preprocess: Preprocess,
}

/// A surface read from a file and prepared, with notes of what was done to it and warnings about
/// what it will do to the results.
#[derive(Debug, Clone)]
pub struct Loaded {
    pub surface: Surface,
    pub notes: Vec<String>,
    pub warnings: Vec<String>,
    /// Periodicity of the prepared surface.
    pub periodicity: Periodicity,
    /// Whether the map is flat: one value, or a plane that the levelling left as round-off. Such a
    /// map is a body of a run (a flat counter-face), but its spectrum is zero
    /// ([`super::prepare::flat_map`]).
    pub flat: bool,
}

/// The grid a `rows × cols` height map of a file gives: odd sides lose their last row or column
/// (the FFT needs even sides; a note says so), the pixel size comes from the run's `length` or the
/// file's coordinates. Returns the grid, the rows and columns kept, and notes.
pub fn file_grid(
    path: &Path,
    rows: usize,
    cols: usize,
    file_lengths: Option<(f64, f64)>,
    how: &FileSurface,
) -> Result<(Grid, Vec<String>)> {
    let name = path.display().to_string();
    if rows == 0 || cols == 0 {
        return Err(Error::InvalidSurface {
            name,
            message: format!("the height map is empty ({rows} × {cols})"),
        });
    }
    let mut notes = Vec::new();
    let pixel = match (how.length_x, file_lengths) {
        (Some(lx), Some((fx, fy))) => {
            let (fx, fy) = (fx * how.lateral_scale, fy * how.lateral_scale);
            if ((lx - fx) / lx).abs() > 1e-6 {
                return Err(Error::InvalidSurface {
                    name,
                    message: format!(
                        "its coordinates span {fx:e} × {fy:e} but the run file says length = {lx:e}; leave `length` out to \
                         use the file's, or correct it"
                    ),
                });
            }
            lx / rows as f64
        }
        (Some(lx), None) => lx / rows as f64,
        (None, Some((fx, _))) => fx * how.lateral_scale / rows as f64,
        (None, None) => {
            // Run files are checked for `length` before; this is `surface fit` or Python's reader.
            return Err(Error::param(
                "length",
                format!(
                    "missing: {name} holds heights only, so give its physical size along its first and second axes \
                     (`--length LX [--length LY]`, or `length=(Lx, Ly)` in Python)"
                ),
            ));
        }
    };
    if let Some(ly) = how.length_y {
        let dy = ly / cols as f64;
        if ((dy - pixel) / pixel).abs() > 1e-6 {
            return Err(Error::param(
                "length",
                format!(
                    "{name} is {rows} × {cols} pixels, so length = [{:e}, {ly:e}] gives pixels of {pixel:e} × {dy:e}; \
                     wearsim needs square pixels (Lx/Nx = Ly/Ny)",
                    pixel * rows as f64
                ),
            ));
        }
    }
    let (nx, ny) = (rows - rows % 2, cols - cols % 2);
    if (nx, ny) != (rows, cols) {
        notes.push(format!(
            "{name}: {rows} × {cols} pixels cropped to {nx} × {ny} (the FFT needs an even number of pixels per side)"
        ));
    }
    let grid = Grid::new(nx, ny, pixel * nx as f64).map_err(|e| Error::InvalidSurface {
        name: name.clone(),
        message: format!("a {rows} × {cols} height map: {e}"),
    })?;
    Ok((grid, notes))
}

/// Reads a surface file of a run ([`read`]), converts its units, crops it to even sides and prepares
/// it ([`preprocess`]); notes say what was done, and a warning when it is far from periodic.
pub fn load(path: &Path, how: &FileSurface) -> Result<Loaded> {
    let name = path.display().to_string();
    let m = read(path)?;
    let (grid, mut notes) = file_grid(path, m.rows, m.cols, m.lengths, how)?;
    notes.extend(m.notes);
    let (nx, ny) = (grid.nx(), grid.ny());
    let mut heights = Vec::with_capacity(nx * ny);
    for i in 0..nx {
        heights.extend_from_slice(&m.heights[i * m.cols..i * m.cols + ny]);
    }
    if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
        return Err(Error::InvalidSurface {
            name,
            message: format!(
                "height at x index {}, y index {} is {} (a missing point); fill or crop non-finite pixels before use",
                k / ny,
                k % ny,
                heights[k]
            ),
        });
    }
    if how.height_scale != 1.0 {
        heights.iter_mut().for_each(|h| *h *= how.height_scale);
    }
    let spread = heights.iter().fold(0.0f64, |m, h| m.max(h.abs()));
    preprocess(&mut heights, nx, ny, &how.preprocess)?;
    if how.preprocess.detrend == Detrend::None {
        if let Some(note) = remove_offset(&mut heights) {
            notes.push(format!("{name}: {note}"));
        }
    }
    if how.preprocess.detrend != Detrend::None || how.preprocess.taper > 0.0 {
        notes.push(format!(
            "{name}: detrend = \"{}\", taper = {}",
            how.preprocess.detrend.name(),
            how.preprocess.taper
        ));
    }
    let periodicity = periodicity(&heights, nx, ny);
    let warnings = periodicity.warning(&name).into_iter().collect();
    let surface = Surface::new(&name, grid, heights)?;
    let flat = super::prepare::is_flat(surface.rms_height(), spread);
    Ok(Loaded {
        surface,
        notes,
        warnings,
        periodicity,
        flat,
    })
}

/// Removes the mean height of a map not levelled otherwise (levelling removes it) where it is larger
/// than the roughness: it changes nothing in the contact (the approach takes up any constant
/// offset) but, left in, costs the solver the digits of the roughness (heights of 1e6 ± 1e-3 leave
/// it 7 of its 16, and it does not converge). A smaller mean is kept, so that a map wearsim wrote
/// reads back bit for bit.
fn remove_offset(heights: &mut [f64]) -> Option<String> {
    let n = heights.len() as f64;
    let mean = heights.iter().sum::<f64>() / n;
    let rms = (heights.iter().map(|h| (h - mean) * (h - mean)).sum::<f64>() / n).sqrt();
    // Not larger (or not a number): kept.
    if mean.abs().partial_cmp(&rms) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    heights.iter_mut().for_each(|h| *h -= mean);
    Some(format!(
        "its mean height {mean:e}, larger than its roughness (h_rms = {rms:e}), was removed: a constant offset changes \
         nothing in the contact"
    ))
}

/// The physical size a file states (the span of an x y z column file's coordinates, in its own
/// unit); `None` for arrays, which hold heights only (read without loading the data).
pub fn file_span(path: &Path) -> Result<Option<(f64, f64)>> {
    if is_array(path) {
        return Ok(None);
    }
    Ok(read(path)?.lengths)
}

/// The sides [Lx, Ly] in metres that `wearsim surface import` recorded for the map `path`: when
/// `path` is a `.npy` body that the import wrote (named in its `import.json`, `written_by` "wearsim
/// surface import") and the record's grid is the array's shape. `None` otherwise, or when the
/// record cannot be read as one (the run file's `length` is then needed, as for any array).
pub fn imported_length(path: &Path) -> Result<Option<[f64; 2]>> {
    if super::formats::extension(path) != "npy" {
        return Ok(None);
    }
    let Ok(text) = std::fs::read_to_string(path.with_file_name("import.json")) else {
        return Ok(None);
    };
    let Ok(record) = serde_json::from_str::<serde_json::Value>(&text) else {
        return Ok(None);
    };
    if record["written_by"] != "wearsim surface import" {
        return Ok(None);
    }
    // Only the bodies the import wrote (`bodies`; before it recorded them, heights.npy alone): another
    // array of the same shape in the folder is not the measured map.
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
    let bodies = &record["bodies"];
    let written = if bodies.is_object() {
        ["top", "bottom"].iter().any(|b| bodies[b]["file"] == name)
    } else {
        name == "heights.npy"
    };
    if !written {
        return Ok(None);
    }
    let side = |i: usize| record["length"][i].as_f64().filter(|l| l.is_finite() && *l > 0.0);
    let grid = |i: usize| record["heights_grid"][i].as_u64().and_then(|n| usize::try_from(n).ok());
    let (Some(lx), Some(ly), Some(nx), Some(ny)) = (side(0), side(1), grid(0), grid(1)) else {
        return Ok(None);
    };
    Ok((array_shape(path)? == Some((nx, ny))).then_some([lx, ly]))
}

/// The grid a surface file gives under `how` ([`file_grid`]), from a `.npy` header alone or by
/// reading the file.
pub fn probe_grid(path: &Path, how: &FileSurface) -> Result<Grid> {
    if let Some((rows, cols)) = array_shape(path)? {
        return file_grid(path, rows, cols, None, how).map(|g| g.0);
    }
    let m = read(path)?;
    file_grid(path, m.rows, m.cols, m.lengths, how).map(|g| g.0)
}
