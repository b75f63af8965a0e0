//! Surfaces: generation, statistics, the composite height of a sliding offset.

use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::output::SurfaceStatistics;
use wearsim::{Generation, SpectrumParams, Surface};

use crate::error::{interruptible, to_py};
use crate::{field, field_of, json_to_py, to_array, GridSize, Pair};

#[pyfunction]
#[pyo3(signature = (grid, length, hurst, lambda_lower, lambda_upper, rms_height, seed, generation = "random-phase"))]
#[allow(clippy::too_many_arguments)] // the keyword arguments of the Python function, one each
fn generate_surface<'py>(
    py: Python<'py>,
    grid: GridSize,
    length: f64,
    hurst: f64,
    lambda_lower: f64,
    lambda_upper: f64,
    rms_height: f64,
    seed: u64,
    generation: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let generation: Generation = generation.parse().map_err(to_py)?;
    let params = SpectrumParams {
        hurst,
        lambda_lower,
        lambda_upper,
        rms_height,
        generation,
    };
    let grid = grid.grid(length)?;
    params.validate(&grid).map_err(to_py)?;
    let surface = interruptible(py, None, |_| Surface::generate(grid, &params, seed))?;
    Ok(to_array(py, (grid.nx(), grid.ny()), surface.into_heights()))
}

#[pyfunction]
fn pair_seeds(seed: u64) -> (u64, u64) {
    wearsim::surface::pair_seeds(seed)
}

/// A checked surface from an array whose side along x (the first axis) is `length`.
pub fn surface_from(name: &str, heights: &PyReadonlyArray2<'_, f64>, length: f64) -> PyResult<Surface> {
    let ((rows, cols), values) = field(name, heights)?;
    Surface::from_array(name, rows, cols, length, values).map_err(to_py)
}

/// The top and bottom surfaces of a slide, on one grid.
pub fn surface_pair(
    top: &PyReadonlyArray2<'_, f64>,
    bottom: &PyReadonlyArray2<'_, f64>,
    length: f64,
) -> PyResult<(Surface, Surface)> {
    let t = surface_from("top", top, length)?;
    let values = field_of("bottom", bottom, (t.nx(), t.ny()), "top")?;
    let b = Surface::new("bottom", t.grid(), values).map_err(to_py)?;
    Ok((t, b))
}

/// Grid, length, pixel size, RMS height and RMS slope (the statistics `wearsim surface` writes,
/// without the PSD, which `radial_psd` returns as arrays).
#[pyfunction]
fn surface_statistics<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    length: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let s = surface_from("heights", &heights, length)?;
    let stats = json_to_py(py, &SurfaceStatistics::of(&s))?;
    stats.cast::<PyDict>()?.del_item("psd")?;
    Ok(stats)
}

#[pyfunction]
fn radial_psd<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    length: f64,
) -> Pair<'py, PyArray1<f64>, PyArray1<f64>> {
    let s = surface_from("heights", &heights, length)?;
    let (q, c): (Vec<f64>, Vec<f64>) = s.radial_psd().into_iter().unzip();
    Ok((q.into_pyarray(py), c.into_pyarray(py)))
}

#[pyfunction]
fn composite_heights<'py>(
    py: Python<'py>,
    top: PyReadonlyArray2<'py, f64>,
    bottom: PyReadonlyArray2<'py, f64>,
    offset: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (t, b) = surface_pair(&top, &bottom, 1.0)?;
    let mut out = vec![0.0; t.grid().pixels()];
    wearsim::composite_heights(&t, &b, offset, &mut out);
    Ok(to_array(py, (t.nx(), t.ny()), out))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(generate_surface, m)?)?;
    m.add_function(wrap_pyfunction!(pair_seeds, m)?)?;
    m.add_function(wrap_pyfunction!(surface_statistics, m)?)?;
    m.add_function(wrap_pyfunction!(radial_psd, m)?)?;
    m.add_function(wrap_pyfunction!(composite_heights, m)?)?;
    Ok(())
}
