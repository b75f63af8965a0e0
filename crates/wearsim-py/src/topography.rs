//! Measured topographies: reading height maps, preparing them, fitting self-affine parameters.

use std::path::PathBuf;

use numpy::{PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::topography::{self, Detrend, FileSurface, Preprocess};

use crate::error::to_py;
use crate::surface::surface_from;
use crate::{field, to_array};

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

/// H, λ_l, λ_u and h_rms estimated from the radially averaged PSD.
#[pyfunction]
fn fit_surface<'py>(py: Python<'py>, heights: PyReadonlyArray2<'py, f64>, length: f64) -> PyResult<Bound<'py, PyAny>> {
    let s = surface_from("heights", &heights, length)?;
    let fit = py.detach(|| topography::fit(&s)).map_err(to_py)?;
    let d = crate::json_to_py(py, &fit)?;
    d.cast::<PyDict>()?;
    Ok(d)
}

/// Metres per unit of a length unit name (m, mm, um, nm, pm, A).
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
    Ok(())
}
