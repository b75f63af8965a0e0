//! Measured topographies: reading height maps, preparing them, fitting self-affine parameters.

use std::path::PathBuf;

use numpy::{PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::check;
use wearsim::topography::{self, Detrend, FileSurface, MeasuredPsd, Preprocess, Window};

use crate::error::{interruptible, to_py};
use crate::surface::surface_from;
use crate::{field, to_array, GridSize};

/// What `read_surface` returns: heights, length along x, notes, warnings.
type ReadSurface<'py> = (Bound<'py, PyArray2<f64>>, f64, Vec<String>, Vec<String>);

/// Reads and prepares a height map as a run file's `top`/`bottom` would be: returns (heights,
/// length along x, notes, warnings). Scales convert the file's units to the caller's.
#[pyfunction]
#[pyo3(signature = (path, length = None, length_y = None, height_scale = 1.0, lateral_scale = 1.0, detrend = "none", taper = 0.0))]
#[allow(clippy::too_many_arguments)] // the keyword arguments of the Python function, one each
fn read_surface<'py>(
    py: Python<'py>,
    path: PathBuf,
    length: Option<f64>,
    length_y: Option<f64>,
    height_scale: f64,
    lateral_scale: f64,
    detrend: &str,
    taper: f64,
) -> PyResult<ReadSurface<'py>> {
    let detrend: Detrend = detrend.parse().map_err(to_py)?;
    let how = FileSurface {
        height_scale,
        lateral_scale,
        length_x: length,
        length_y,
        preprocess: Preprocess { detrend, taper },
    };
    let loaded = py.detach(|| topography::load(&path, &how)).map_err(to_py)?;
    let s = loaded.surface;
    let (shape, lx) = ((s.nx(), s.ny()), s.length());
    Ok((to_array(py, shape, s.into_heights()), lx, loaded.notes, loaded.warnings))
}

/// Levels and tapers a height map (a copy).
#[pyfunction]
#[pyo3(signature = (heights, detrend = "plane", taper = 0.0))]
fn preprocess_surface<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    detrend: &str,
    taper: f64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let detrend: Detrend = detrend.parse().map_err(to_py)?;
    let (shape, mut values) = field("heights", &heights)?;
    topography::preprocess(&mut values, shape.0, shape.1, &Preprocess { detrend, taper }).map_err(to_py)?;
    Ok(to_array(py, shape, values))
}

/// The jumps across the borders along x and y, in units of the typical step between neighbours.
#[pyfunction]
fn periodicity(heights: PyReadonlyArray2<'_, f64>) -> PyResult<(f64, f64)> {
    let (shape, values) = field("heights", &heights)?;
    if shape.0 < 2 || shape.1 < 2 {
        return Err(pyo3::exceptions::PyValueError::new_err(
            "invalid `heights`: at least 2 × 2 pixels are needed",
        ));
    }
    let p = topography::periodicity(&values, shape.0, shape.1);
    Ok((p.border_step_x, p.border_step_y))
}

/// H, λ_l, λ_u and h_rms (the band's) estimated from the radially averaged PSD, with what `wearsim
/// surface fit` writes beside them in fit.json: the fit's fields, `spectrum` (the parameters a run
/// generates from it on this grid), `notes` (what those adjust, and the share of the variance the
/// band leaves out and the change of rms slope, when they are much), `rms_slope` (`map` and
/// `generated`, by forward differences inside the map), `self_affine` and `reasons` (the
/// verdict). `measured_pixel`: the native pixel sizes (Δx, Δy) of a map resampled onto finer
/// pixels, whose measured wavevectors alone are fitted.
#[pyfunction]
#[pyo3(signature = (heights, length, measured_pixel = None))]
fn fit_surface<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    length: f64,
    measured_pixel: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyAny>> {
    let s = surface_from("heights", &heights, length)?;
    let measured_pixel = measured_pixel.map(|(x, y)| [x, y]);
    let fit = py
        .detach(|| topography::fit_measured(&s, measured_pixel))
        .map_err(to_py)?;
    let (spectrum, mut notes) = fit.spectrum(&s.grid());
    let slopes = topography::SlopeComparison::of(&s, &spectrum).ok();
    notes.extend(fit.out_of_band_note());
    notes.extend(slopes.as_ref().and_then(topography::SlopeComparison::note));
    let verdict = fit.verdict();
    let d = crate::json_to_py(py, &fit)?;
    let dict = d.cast::<PyDict>()?;
    dict.set_item("spectrum", crate::json_to_py(py, &spectrum)?)?;
    dict.set_item("self_affine", verdict.self_affine)?;
    dict.set_item("reasons", verdict.reasons)?;
    dict.set_item("notes", notes)?;
    dict.set_item("rms_slope", crate::json_to_py(py, &slopes)?)?;
    Ok(d)
}

/// The warning of a PSD fit of R² `r2` that follows a power law poorly, as `wearsim surface fit`
/// prints it; None for a good fit.
#[pyfunction]
#[pyo3(signature = (r2))]
fn poor_fit_warning(r2: Option<f64>) -> Option<String> {
    topography::poor_fit_warning(r2)
}

/// What `spectrum_pair` returns: top, bottom, notes on what the target grid leaves out.
type SpectrumPairOut<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>, Vec<String>);

/// The (top, bottom) pair of a `source = "spectrum"` run with `seed`: periodic surfaces on `grid`
/// (side `box_length` along x) carrying the measured 2D PSD of `map` (side `length` along x),
/// made by the library function the run file's pair is made by; with the notes on what the grid
/// leaves out of the measured band.
#[pyfunction]
#[pyo3(signature = (map, length, grid, box_length, seed, window = None))]
fn spectrum_pair<'py>(
    py: Python<'py>,
    map: PyReadonlyArray2<'py, f64>,
    length: f64,
    grid: GridSize,
    box_length: f64,
    seed: u64,
    window: Option<&str>,
) -> PyResult<SpectrumPairOut<'py>> {
    let window: Option<Window> = window.map(str::parse).transpose().map_err(to_py)?;
    let map = surface_from("map", &map, length)?;
    let target = grid.grid(box_length)?;
    check::memory(
        "generating the surface pair",
        target.nx(),
        target.ny(),
        check::SURFACE_ARRAYS,
    )
    .map_err(to_py)?;
    let (top, bottom, notes) = interruptible(py, None, |_| {
        let psd = MeasuredPsd::of_map(&map, window)?;
        let (top, bottom) = psd.generate_pair(target, seed)?;
        Ok((top, bottom, psd.notes(&target, "`map`")))
    })?;
    let shape = (target.nx(), target.ny());
    Ok((
        to_array(py, shape, top.into_heights()),
        to_array(py, shape, bottom.into_heights()),
        notes,
    ))
}

/// Metres per unit of a length unit name (Gm, Mm, km, m, cm, mm, um, nm, A, pm, fm).
#[pyfunction]
fn metres_per(unit: &str) -> PyResult<f64> {
    topography::metres_per("unit", unit).map_err(to_py)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(metres_per, m)?)?;
    m.add_function(wrap_pyfunction!(read_surface, m)?)?;
    m.add_function(wrap_pyfunction!(preprocess_surface, m)?)?;
    m.add_function(wrap_pyfunction!(periodicity, m)?)?;
    m.add_function(wrap_pyfunction!(fit_surface, m)?)?;
    m.add_function(wrap_pyfunction!(poor_fit_warning, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum_pair, m)?)?;
    Ok(())
}
