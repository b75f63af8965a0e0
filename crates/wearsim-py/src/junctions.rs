//! The geometry of junctions from their pixel counts (paper §3: circular junctions, spherical
//! particles), as the library computes it for the wear model.

use numpy::{IntoPyArray, PyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use wearsim::junctions::Junction;

/// Areas, diameters and volumes of junctions.
type Geometry<'py> = PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
)>;

/// Per junction of `pixels` pixels of side `pixel_size`: the area A = pixels·Δx², the equivalent
/// diameter d = 2√(A/π) and the volume of the particle it would form, v = π d³/6.
#[pyfunction]
fn junction_geometry(py: Python<'_>, pixels: Vec<u64>, pixel_size: f64) -> Geometry<'_> {
    if !(pixel_size > 0.0 && pixel_size.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "invalid `pixel_size`: {pixel_size} must be positive"
        )));
    }
    let junctions: Vec<Junction> = pixels.iter().map(|&n| Junction::new(n as usize, pixel_size)).collect();
    let column = |f: fn(&Junction) -> f64| junctions.iter().map(f).collect::<Vec<f64>>().into_pyarray(py);
    Ok((column(|j| j.area), column(|j| j.diameter), column(|j| j.volume)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(junction_geometry, m)?)?;
    Ok(())
}
