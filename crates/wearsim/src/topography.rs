//! Measured topographies: reading height maps in the common formats, converting their units,
//! preparing them for a periodic contact solution, and fitting the self-affine parameters the
//! paper's model needs.
//!
//! A measured surface is not periodic, but the FFT solver treats every surface as one period of an
//! infinite periodic one: where the heights at opposite borders differ, the periodic surface has a
//! ridge or a cliff there, which carries load and makes junctions that the real surface does not
//! have. `detrend` removes the tilt (a plane) or the form (a quadratic) that causes most of the
//! jump, `taper` brings the heights smoothly to their mean over a fraction of each border (at the
//! cost of flattening that strip), and [`periodicity`] measures what is left. The cleanest route for the
//! paper's model, which assumes periodic self-affine surfaces, is [`fit`]: estimate H, λ_l, λ_u and
//! h_rms from the measurement and generate periodic surfaces with them.

use std::path::Path;

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::io::{read_npy_2d, read_npy_2d_from, NpyType};
use crate::stats::line_fit;
use crate::surface::{Generation, SpectrumParams, Surface};

/// How a measured height map is levelled before use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Detrend {
    /// Heights as read.
    #[default]
    None,
    /// The mean removed.
    Mean,
    /// The least-squares plane removed (tilt of the sample).
    Plane,
    /// The least-squares quadratic removed (tilt and form, e.g. the curvature of a ball).
    Curvature,
}

impl Detrend {
    /// The name written in run files.
    pub fn name(self) -> &'static str {
        match self {
            Detrend::None => "none",
            Detrend::Mean => "mean",
            Detrend::Plane => "plane",
            Detrend::Curvature => "curvature",
        }
    }
}

impl std::str::FromStr for Detrend {
    type Err = Error;

    fn from_str(name: &str) -> Result<Self> {
        match name {
            "none" => Ok(Detrend::None),
            "mean" => Ok(Detrend::Mean),
            "plane" => Ok(Detrend::Plane),
            "curvature" => Ok(Detrend::Curvature),
            other => Err(Error::param(
                "detrend",
                format!("\"{other}\"; use \"none\", \"mean\", \"plane\" or \"curvature\""),
            )),
        }
    }
}

/// The preparation of a measured height map: levelling, then an optional taper.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Preprocess {
    pub detrend: Detrend,
    /// Fraction of each side over which a Tukey window brings the heights to their mean (0: none).
    pub taper: f64,
}

impl Preprocess {
    /// Checks the taper fraction: in [0, 1).
    pub fn validate(&self) -> Result<()> {
        if !(self.taper >= 0.0 && self.taper < 1.0) {
            return Err(Error::param(
                "taper",
                format!("{} must lie in [0, 1) (a fraction of each side)", self.taper),
            ));
        }
        Ok(())
    }
}

/// Metres per unit of a length unit name (`m`, `mm`, `um` or `µm`, `nm`, `pm`, `A` for ångström);
/// `field` names the setting in the error.
pub fn metres_per(field: &str, unit: &str) -> Result<f64> {
    Ok(match unit {
        "m" => 1.0,
        "mm" => 1e-3,
        "um" | "µm" | "μm" | "micron" => 1e-6,
        "nm" => 1e-9,
        "pm" => 1e-12,
        "A" | "Å" => 1e-10,
        other => {
            return Err(Error::param(
                field,
                format!("\"{other}\" is not a length unit wearsim knows; use m, mm, um, nm, pm or A"),
            ))
        }
    })
}

/// A height map read from a file, with the physical size the file states (column files do).
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub rows: usize,
    pub cols: usize,
    /// Heights, row-major, in the file's height unit.
    pub heights: Vec<f64>,
    /// Side along x (rows) and y (columns) from the file's coordinates, in its lateral unit.
    pub lengths: Option<(f64, f64)>,
    /// What was noticed while reading (header lines skipped, …).
    pub notes: Vec<String>,
}

/// Reads a height map: `.npy` (float or integer), `.npz` (the array `heights`, or the only 2D array),
/// or text — a matrix of numbers separated by spaces, tabs, commas or semicolons (`.txt`, `.csv`,
/// `.dat`, `.asc`, …), each line a scan line along x and the lines stacked along y (the layout
/// profilometers export and SurfaceTopography reads), or three columns x, y, z on a regular grid.
/// `.npy`/`.npz` arrays are indexed `[x, y]`, as wearsim writes them. Lines starting with `#`, `%` or
/// `//` are comments; non-numeric lines before the first number are a header and skipped.
pub fn read(path: &Path) -> Result<Measured> {
    match extension(path).as_str() {
        "npy" => {
            let a = read_npy_2d(path, &HEIGHT_TYPES, "a height map")?;
            Ok(a.into())
        }
        "npz" => read_npz(path),
        _ => read_text(path),
    }
}

/// A NumPy array as a height map: `[x, y]`, sizes from the run file.
impl From<crate::io::Npy2> for Measured {
    fn from(a: crate::io::Npy2) -> Self {
        Measured {
            rows: a.rows,
            cols: a.cols,
            heights: a.values,
            lengths: None,
            notes: Vec::new(),
        }
    }
}

fn read_npz(path: &Path) -> Result<Measured> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut archive =
        zip::ZipArchive::new(file).map_err(|e| Error::file(path, format!("not a NumPy .npz archive ({e})")))?;
    let names: Vec<String> = archive
        .file_names()
        .filter_map(|n| n.ok().map(|n| n.into_owned()))
        .collect();
    let arrays: Vec<&String> = names.iter().filter(|n| n.ends_with(".npy")).collect();
    let chosen = arrays
        .iter()
        .find(|n| n.as_str() == "heights.npy")
        .or_else(|| arrays.iter().find(|n| n.as_str() == "height.npy"))
        .copied()
        .or(if arrays.len() == 1 { Some(arrays[0]) } else { None })
        .ok_or_else(|| {
            Error::file(
                path,
                format!(
                    "holds the arrays {}; name the height map `heights` (np.savez(file, heights=h))",
                    arrays
                        .iter()
                        .map(|a| a.trim_end_matches(".npy"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?
        .clone();
    let mut entry = archive
        .by_name(&chosen)
        .map_err(|e| Error::file(path, format!("cannot read {chosen}: {e}")))?;
    // The size the archive states bounds what the header may promise (the reader checks it).
    let size = entry.size();
    let inner = path.join(&chosen);
    let a = read_npy_2d_from(&mut entry, size, &inner, &HEIGHT_TYPES, "a height map")?;
    Ok(a.into())
}

/// Element types a height map may have.
const HEIGHT_TYPES: [NpyType; 5] = [
    NpyType::Float64,
    NpyType::Float32,
    NpyType::Int64,
    NpyType::Int32,
    NpyType::Int16,
];

/// Splits a text line into numbers; `None` when a field is not a number.
fn numbers(line: &str) -> Option<Vec<f64>> {
    let fields: Vec<&str> = line
        .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|f| !f.is_empty())
        .collect();
    if fields.is_empty() {
        return None;
    }
    fields
        .iter()
        .map(|f| {
            f.parse::<f64>()
                .ok()
                .filter(|v| !v.is_nan() || f.eq_ignore_ascii_case("nan"))
        })
        .collect()
}

fn read_text(path: &Path) -> Result<Measured> {
    let text = std::fs::read_to_string(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::InvalidData => Error::file(
            path,
            "is neither a .npy/.npz array nor text; save the height map as .npy, .npz, CSV or whitespace-separated text",
        ),
        _ => Error::io(path, e),
    })?;
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut header = 0;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with('%') || line.starts_with("//") {
            continue;
        }
        match numbers(line) {
            Some(v) => {
                if let Some(first) = rows.first() {
                    if v.len() != first.len() {
                        return Err(Error::file(
                            path,
                            format!(
                                "line {}: {} numbers where the lines before have {}; a height map has the same number \
                                 of values on every line",
                                k + 1,
                                v.len(),
                                first.len()
                            ),
                        ));
                    }
                }
                rows.push(v);
            }
            None if rows.is_empty() && header < 50 => header += 1,
            None => {
                return Err(Error::file(
                    path,
                    format!(
                        "line {}: \"{}\" is not a list of numbers",
                        k + 1,
                        line.chars().take(60).collect::<String>()
                    ),
                ))
            }
        }
    }
    if rows.is_empty() {
        return Err(Error::file(
            path,
            "holds no numbers; expected a height matrix or x y z columns",
        ));
    }
    let mut notes = Vec::new();
    if header > 0 {
        notes.push(format!("skipped {header} header line(s) of {}", path.display()));
    }
    if rows[0].len() == 3 && rows.len() > 3 {
        return columns_to_grid(path, &rows, notes);
    }
    // Each line is a scan line along x, lines stacked along y (as profilometers export and
    // SurfaceTopography reads them): the map is the transpose of the file's matrix.
    let (lines, per_line) = (rows.len(), rows[0].len());
    let mut heights = Vec::with_capacity(lines * per_line);
    for i in 0..per_line {
        heights.extend(rows.iter().map(|line| line[i]));
    }
    Ok(Measured {
        rows: per_line,
        cols: lines,
        heights,
        lengths: None,
        notes,
    })
}

/// x y z columns on a regular grid → a height matrix (rows along x) and the box size.
fn columns_to_grid(path: &Path, rows: &[Vec<f64>], notes: Vec<String>) -> Result<Measured> {
    let axis = |k: usize| -> Result<(Vec<f64>, f64)> {
        let mut v: Vec<f64> = rows.iter().map(|r| r[k]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * (a.abs() + b.abs()).max(1e-300));
        if v.len() < 2 {
            return Err(Error::file(
                path,
                "the x y z columns do not span a grid (one value of x or y)",
            ));
        }
        let step = (v[v.len() - 1] - v[0]) / (v.len() - 1) as f64;
        for w in v.windows(2) {
            if ((w[1] - w[0]) - step).abs() > 1e-6 * step.abs() {
                return Err(Error::file(
                    path,
                    format!(
                        "the {} coordinates are not evenly spaced ({} then {}); resample onto a regular grid",
                        ["x", "y"][k],
                        w[0],
                        w[1]
                    ),
                ));
            }
        }
        Ok((v, step))
    };
    let (xs, dx) = axis(0)?;
    let (ys, dy) = axis(1)?;
    if ((dx - dy) / dx).abs() > 1e-6 {
        return Err(Error::file(
            path,
            format!("the pixels are {dx} × {dy}; wearsim needs square pixels"),
        ));
    }
    let (nx, ny) = (xs.len(), ys.len());
    if rows.len() != nx * ny {
        return Err(Error::file(
            path,
            format!(
                "{} points do not fill the {nx} × {ny} grid their coordinates span",
                rows.len()
            ),
        ));
    }
    let mut heights = vec![f64::NAN; nx * ny];
    for r in rows {
        let i = ((r[0] - xs[0]) / dx).round() as usize;
        let j = ((r[1] - ys[0]) / dy).round() as usize;
        if i >= nx || j >= ny || !heights[i * ny + j].is_nan() {
            return Err(Error::file(
                path,
                format!("the point ({}, {}) is off the grid or given twice", r[0], r[1]),
            ));
        }
        heights[i * ny + j] = r[2];
    }
    Ok(Measured {
        rows: nx,
        cols: ny,
        heights,
        lengths: Some((nx as f64 * dx, ny as f64 * dy)),
        notes,
    })
}

/// Solves the small dense system `a x = b` (Gaussian elimination with partial pivoting).
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        let (upper, lower) = a.split_at_mut(col + 1);
        let pivot_row = &upper[col];
        for (offset, row) in lower.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            for (v, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *v -= f * p;
            }
            b[col + 1 + offset] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        x[row] = (b[row] - (row + 1..n).map(|k| a[row][k] * x[k]).sum::<f64>()) / a[row][row];
    }
    Some(x)
}

/// Levels and tapers a height map in place (`rows × cols`, row-major), as `how` says.
pub fn preprocess(heights: &mut [f64], rows: usize, cols: usize, how: &Preprocess) -> Result<()> {
    how.validate()?;
    let basis: usize = match how.detrend {
        Detrend::None => 0,
        Detrend::Mean => 1,
        Detrend::Plane => 3,
        Detrend::Curvature => 6,
    };
    if basis > 0 {
        // Centred, scaled coordinates keep the normal equations well conditioned.
        let f = |i: usize, j: usize| -> [f64; 6] {
            let x = (i as f64 - (rows as f64 - 1.0) / 2.0) / rows as f64;
            let y = (j as f64 - (cols as f64 - 1.0) / 2.0) / cols as f64;
            [1.0, x, y, x * x, x * y, y * y]
        };
        let mut a = vec![vec![0.0; basis]; basis];
        let mut b = vec![0.0; basis];
        for i in 0..rows {
            for j in 0..cols {
                let phi = f(i, j);
                let z = heights[i * cols + j];
                for p in 0..basis {
                    b[p] += phi[p] * z;
                    for q in 0..basis {
                        a[p][q] += phi[p] * phi[q];
                    }
                }
            }
        }
        let c = solve(a, b).ok_or_else(|| Error::param("detrend", "the height map is too small to fit the trend"))?;
        for i in 0..rows {
            for j in 0..cols {
                let phi = f(i, j);
                heights[i * cols + j] -= (0..basis).map(|p| c[p] * phi[p]).sum::<f64>();
            }
        }
    }
    if how.taper > 0.0 {
        let window = |k: usize, n: usize| -> f64 {
            // Tukey window: cosine ramps over a fraction `taper` of the side, half at each end.
            let ramp = how.taper * n as f64 / 2.0;
            let d = (k as f64 + 0.5).min(n as f64 - k as f64 - 0.5);
            if d >= ramp {
                1.0
            } else {
                0.5 * (1.0 - (std::f64::consts::PI * d / ramp).cos())
            }
        };
        let mean = heights.iter().sum::<f64>() / heights.len() as f64;
        for i in 0..rows {
            for j in 0..cols {
                let h = &mut heights[i * cols + j];
                *h = mean + (*h - mean) * window(i, rows) * window(j, cols);
            }
        }
    }
    Ok(())
}

/// How far a height map is from periodic: the RMS jump across each border (last row to first,
/// last column to first) divided by the RMS step between neighbouring pixels inside. About 1 for a
/// periodic surface; much more means the periodic solution sees a ridge or a cliff at the border.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Periodicity {
    pub border_step_x: f64,
    pub border_step_y: f64,
}

/// Border jumps above this many typical steps draw a warning.
pub const NOT_PERIODIC: f64 = 3.0;

/// Measures the periodicity of a `rows × cols` height map.
pub fn periodicity(heights: &[f64], rows: usize, cols: usize) -> Periodicity {
    let at = |i: usize, j: usize| heights[i * cols + j];
    let rms = |pairs: &mut dyn Iterator<Item = f64>| -> f64 {
        let (s, n) = pairs.fold((0.0, 0usize), |(s, n), d| (s + d * d, n + 1));
        (s / n.max(1) as f64).sqrt()
    };
    let inside_x = rms(&mut (0..rows - 1)
        .flat_map(|i| (0..cols).map(move |j| (i, j)))
        .map(|(i, j)| at(i + 1, j) - at(i, j)));
    let inside_y = rms(&mut (0..rows)
        .flat_map(|i| (0..cols - 1).map(move |j| (i, j)))
        .map(|(i, j)| at(i, j + 1) - at(i, j)));
    let border_x = rms(&mut (0..cols).map(|j| at(0, j) - at(rows - 1, j)));
    let border_y = rms(&mut (0..rows).map(|i| at(i, 0) - at(i, cols - 1)));
    Periodicity {
        border_step_x: border_x / inside_x.max(1e-300),
        border_step_y: border_y / inside_y.max(1e-300),
    }
}

impl Periodicity {
    /// A warning when a border jump is large, with what to do.
    pub fn warning(&self, name: &str) -> Option<String> {
        let worst = self.border_step_x.max(self.border_step_y);
        (worst > NOT_PERIODIC).then(|| {
            format!(
                "{name} is not periodic: the jump across its border is {:.1} (along x) and {:.1} (along y) times the \
                 typical step between neighbouring pixels, so the periodic contact solution sees a ridge there; use \
                 detrend = \"plane\" or \"curvature\", a taper, or `wearsim surface fit` to generate periodic surfaces \
                 with the measured statistics",
                self.border_step_x, self.border_step_y
            )
        })
    }
}

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
    preprocess(&mut heights, nx, ny, &how.preprocess)?;
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
    Ok(Loaded {
        surface,
        notes,
        warnings,
        periodicity,
    })
}

/// The physical size a file states (the span of an x y z column file's coordinates, in its own
/// unit); `None` for arrays, which hold heights only (read without loading the data).
pub fn file_span(path: &Path) -> Result<Option<(f64, f64)>> {
    if is_array(path) {
        return Ok(None);
    }
    Ok(read(path)?.lengths)
}

/// The grid a surface file gives under `how` ([`file_grid`]), from a `.npy` header alone or by
/// reading the file.
pub fn probe_grid(path: &Path, how: &FileSurface) -> Result<Grid> {
    if extension(path) == "npy" {
        let (rows, cols) = crate::io::npy_shape(path, "a height map")?;
        return file_grid(path, rows, cols, None, how).map(|g| g.0);
    }
    let m = read(path)?;
    file_grid(path, m.rows, m.cols, m.lengths, how).map(|g| g.0)
}

fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default()
}

fn is_array(path: &Path) -> bool {
    matches!(extension(path).as_str(), "npy" | "npz")
}

/// Self-affine parameters estimated from a surface's radially averaged PSD.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpectrumFit {
    /// Hurst exponent H from the slope −2(1 + H) of the PSD between the cut-offs.
    pub hurst: f64,
    /// Shortest wavelength λ_l (the high-wavenumber end of the power law).
    pub lambda_lower: f64,
    /// Longest wavelength λ_u (the low-wavenumber end of the power law, or the box).
    pub lambda_upper: f64,
    pub rms_height: f64,
    /// R² of the power-law fit in log–log.
    pub r2: Option<f64>,
    /// Shells of the PSD the fit used.
    pub shells: usize,
}

/// How [`fit`] works, in one sentence for the documents that report a fit.
pub const FIT_METHOD: &str =
    "least-squares line through ln PSD against ln q over the shells that follow it (grown from \
the middle of the spectrum while each shell stays within a factor 2 of the line); slope −2(1+H); λ_l and λ_u where the \
power law ends";

/// Estimates H, λ_l, λ_u and h_rms from the radially averaged PSD of `surface`: the power law is
/// fitted in log–log over the wavenumbers where the PSD follows it (grown from the middle of the
/// spectrum while each shell stays within a factor 2 of the line), and the cut-offs are where it
/// stops following it (the PSD drops or flattens).
pub fn fit(surface: &Surface) -> Result<SpectrumFit> {
    let psd: Vec<(f64, f64)> = surface.radial_psd();
    let peak = psd.iter().map(|p| p.1).fold(0.0f64, f64::max);
    let live: Vec<(f64, f64)> = psd
        .into_iter()
        .filter(|p| p.1 > 1e-12 * peak)
        .map(|(q, c)| (q.ln(), c.ln()))
        .collect();
    if live.len() < 4 {
        return Err(Error::InvalidSurface {
            name: "surface".into(),
            message: "its spectrum has fewer than four non-empty wavenumber shells; nothing to fit".into(),
        });
    }
    let line = |lo: usize, hi: usize| {
        let (x, y): (Vec<f64>, Vec<f64>) = live[lo..=hi].iter().copied().unzip();
        line_fit(&x, &y).map(|f| (f.slope, f.intercept, f.r2))
    };
    // Start from the middle half of the live shells and grow while the PSD follows the line.
    let (mut lo, mut hi) = (
        live.len() / 4,
        (3 * live.len() / 4).max(live.len() / 4 + 2).min(live.len() - 1),
    );
    let tolerance = 2f64.ln();
    while let Some((slope, intercept, _)) = line(lo, hi) {
        let follows = |k: usize| (live[k].1 - (intercept + slope * live[k].0)).abs() < tolerance;
        let mut grew = false;
        if lo > 0 && follows(lo - 1) {
            lo -= 1;
            grew = true;
        }
        if hi + 1 < live.len() && follows(hi + 1) {
            hi += 1;
            grew = true;
        }
        if !grew {
            break;
        }
    }
    // The shells at the ends of the power law straddle the cut-offs (only part of their modes lie
    // inside the band), so the slope comes from the shells between them when there are enough.
    let (a, b) = if hi - lo >= 6 { (lo + 1, hi - 1) } else { (lo, hi) };
    let (slope, _, r2) = line(a, b).ok_or_else(|| Error::InvalidSurface {
        name: "surface".into(),
        message: "its spectrum cannot be fitted by a power law".into(),
    })?;
    let length = surface.length();
    Ok(SpectrumFit {
        hurst: -slope / 2.0 - 1.0,
        lambda_lower: length / live[hi].0.exp(),
        lambda_upper: length / live[lo].0.exp(),
        rms_height: surface.rms_height(),
        r2,
        shells: hi - lo + 1,
    })
}

impl SpectrumFit {
    /// Parameters to generate periodic surfaces with the fitted statistics on `grid`: λ_l raised to
    /// two pixels and λ_u lowered to the box where the fit ran past them (a note says so).
    pub fn spectrum(&self, grid: &Grid) -> (SpectrumParams, Vec<String>) {
        let mut notes = Vec::new();
        let two_pixels = 2.0 * grid.pixel_size();
        let lambda_lower = if self.lambda_lower < two_pixels {
            notes.push(format!(
                "the power law runs to the pixel scale, so λ_l = {:.4e} is set to two pixels ({two_pixels:.4e}): it is \
                 the resolution of the measurement, not a property of the surface",
                self.lambda_lower
            ));
            two_pixels
        } else {
            self.lambda_lower
        };
        let longest = grid.length_x().max(grid.length_y());
        let lambda_upper = if self.lambda_upper > longest {
            notes.push(format!(
                "λ_u = {:.4e} is beyond the box and is set to its side ({longest:.4e}): the measurement is too small \
                 to see where the power law ends at long wavelengths",
                self.lambda_upper
            ));
            longest
        } else {
            self.lambda_upper
        };
        let params = SpectrumParams {
            hurst: self.hurst.clamp(0.01, 1.0),
            lambda_lower,
            lambda_upper,
            rms_height: self.rms_height,
            generation: Generation::RandomPhase,
        };
        if params.hurst != self.hurst {
            notes.push(format!(
                "H = {:.3} is outside (0, 1] and is set to {:.3}",
                self.hurst, params.hurst
            ));
        }
        (params, notes)
    }
}

/// The `[surface]` block of a run file that generates periodic surfaces with `spectrum` on `grid`,
/// headed by a comment saying where the parameters come from; lengths in `unit`.
pub fn surface_block(grid: &Grid, spectrum: &SpectrumParams, seed: u64, source: &str, unit: &str) -> String {
    let sides = |x: String, y: String| if x == y { x } else { format!("[{x}, {y}]") };
    // Whole numbers of the box as written; fitted values to four significant digits.
    format!(
        "# Periodic self-affine surfaces with the statistics of {source}; lengths in {unit}.\n\
         [surface]\n\
         grid = {}\n\
         length = {}\n\
         hurst = {:.4}\n\
         lambda_lower = {:.4e}\n\
         lambda_upper = {:.4e}\n\
         rms_height = {:.4e}\n\
         seed = {seed}\n",
        sides(grid.nx().to_string(), grid.ny().to_string()),
        sides(grid.length_x().to_string(), grid.length_y().to_string()),
        spectrum.hurst,
        spectrum.lambda_lower,
        spectrum.lambda_upper,
        spectrum.rms_height,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitting_recovers_the_parameters_of_generated_surfaces() {
        let (square, oblong) = (Grid::square(512, 1.0).unwrap(), Grid::new(512, 256, 1.0).unwrap());
        for (hurst, lower, upper, generation, grid, seed) in [
            (0.7, 1.0 / 64.0, 1.0 / 4.0, Generation::RandomPhase, square, 3),
            (0.5, 1.0 / 32.0, 1.0 / 8.0, Generation::RandomPhase, square, 3),
            (0.9, 1.0 / 100.0, 1.0 / 5.0, Generation::RandomPhase, square, 3),
            (0.3, 1.0 / 128.0, 1.0 / 4.0, Generation::RandomPhase, square, 4),
            (0.7, 1.0 / 64.0, 1.0 / 4.0, Generation::FilteredNoise, square, 3),
            (0.5, 1.0 / 100.0, 1.0 / 8.0, Generation::FilteredNoise, square, 5),
            (0.8, 1.0 / 64.0, 1.0 / 4.0, Generation::RandomPhase, oblong, 6),
            (0.6, 1.0 / 64.0, 1.0 / 8.0, Generation::FilteredNoise, oblong, 7),
        ] {
            let params = SpectrumParams {
                hurst,
                lambda_lower: lower,
                lambda_upper: upper,
                rms_height: 0.01,
                generation,
            };
            let s = Surface::generate(grid, &params, seed).unwrap();
            let f = fit(&s).unwrap();
            assert!((f.hurst - hurst).abs() <= 0.05, "H {hurst}: {f:?}");
            assert!(
                f.lambda_lower / lower < 1.2 && lower / f.lambda_lower < 1.2,
                "λ_l {lower}: {f:?}"
            );
            assert!(
                f.lambda_upper / upper < 1.2 && upper / f.lambda_upper < 1.2,
                "λ_u {upper}: {f:?}"
            );
            assert!((f.rms_height - 0.01).abs() < 1e-12);
        }
    }

    #[test]
    fn detrending_removes_planes_and_quadratics_and_tapering_reaches_the_mean_at_the_border() {
        let (rows, cols) = (40, 30);
        let mut h: Vec<f64> = (0..rows * cols)
            .map(|k| 3.0 + 0.5 * (k / cols) as f64 - 0.2 * (k % cols) as f64 + 1e-3 * (k as f64).sin())
            .collect();
        let before = periodicity(&h, rows, cols);
        assert!(before.warning("top").is_some());
        preprocess(
            &mut h,
            rows,
            cols,
            &Preprocess {
                detrend: Detrend::Plane,
                taper: 0.0,
            },
        )
        .unwrap();
        assert!(h.iter().all(|v| v.abs() < 1e-2), "plane left");
        let mut q: Vec<f64> = (0..rows * cols)
            .map(|k| ((k / cols) as f64).powi(2) + (k % cols) as f64)
            .collect();
        preprocess(
            &mut q,
            rows,
            cols,
            &Preprocess {
                detrend: Detrend::Curvature,
                taper: 0.0,
            },
        )
        .unwrap();
        assert!(q.iter().all(|v| v.abs() < 1e-8), "quadratic left");
        let mut t: Vec<f64> = (0..rows * cols).map(|k| (k as f64 * 0.7).sin()).collect();
        preprocess(
            &mut t,
            rows,
            cols,
            &Preprocess {
                detrend: Detrend::Mean,
                taper: 0.2,
            },
        )
        .unwrap();
        assert!(t[0].abs() < 0.05 && t[cols / 2].abs() < 0.05);
        assert!(Preprocess {
            detrend: Detrend::None,
            taper: 1.5
        }
        .validate()
        .is_err());
    }

    #[test]
    fn text_matrices_and_columns_are_read_with_their_errors_named() {
        let dir = tempfile::tempdir().unwrap();
        let matrix = dir.path().join("m.csv");
        std::fs::write(&matrix, "# measured\nx,y\n1,2,3\n4,5,6\n").unwrap();
        let m = read(&matrix).unwrap();
        // Lines are scans along x: 3 pixels along x, 2 along y, indexed [x, y].
        assert_eq!(
            (m.rows, m.cols, m.heights.clone()),
            (3, 2, vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0])
        );
        assert_eq!(m.notes.len(), 1);
        std::fs::write(&matrix, "1 2 3\n4 5\n").unwrap();
        let e = read(&matrix).unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("m.csv"), "{e}");
        // Columns on a 4 × 5 grid of pitch 0.5, in any order.
        let xyz = dir.path().join("p.xyz");
        let mut text = String::from("x y z\n");
        for j in (0..5).rev() {
            for i in 0..4 {
                text += &format!("{} {} {}\n", i as f64 * 0.5, j as f64 * 0.5, (10 * i + j) as f64);
            }
        }
        std::fs::write(&xyz, text).unwrap();
        let g = read(&xyz).unwrap();
        assert_eq!((g.rows, g.cols, g.lengths), (4, 5, Some((2.0, 2.5))));
        assert_eq!(g.heights[2 * 5 + 3], 23.0);
        std::fs::write(&xyz, "0 0 1\n0 1 1\n1 0 1\n1 3 1\n").unwrap();
        assert!(read(&xyz).unwrap_err().to_string().contains("evenly spaced"));
        assert!((metres_per("height_unit", "um").unwrap() - 1e-6).abs() < 1e-21);
        assert!(metres_per("height_unit", "inch")
            .unwrap_err()
            .to_string()
            .contains("`height_unit`"));
    }
}
