//! `wearsim._wearsim`: the Python extension module. A thin layer over the `wearsim` library: arrays
//! in and out as NumPy arrays, library errors as Python exceptions carrying the library's message
//! (`error`), long calls run with the GIL released on a worker thread while the calling thread
//! watches for Ctrl-C. One module per concept: `surface`, `contact` (material, solver, junctions),
//! `sliding`, `study`. The public Python API, with docstrings and units, is the pure-Python package
//! `wearsim` around this module.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::output::{Cell, Table};

mod contact;
mod error;
mod sliding;
mod study;
mod surface;

/// Two arrays returned together (a surface pair, labels and sizes, a spectrum).
type Pair<'py, A, B> = PyResult<(Bound<'py, A>, Bound<'py, B>)>;

/// A square array as (N, values), or a ValueError naming `field`.
fn square<T: numpy::Element + Copy>(field: &str, a: &PyReadonlyArray2<'_, T>) -> PyResult<(usize, Vec<T>)> {
    let shape = a.shape();
    if shape[0] != shape[1] || shape[0] == 0 {
        return Err(PyValueError::new_err(format!(
            "invalid `{field}`: array is {}×{}; it must be square and non-empty",
            shape[0], shape[1]
        )));
    }
    Ok((shape[0], a.as_array().iter().copied().collect()))
}

/// [`square`] for an array that must be `n × n` (the grid of a solver or of another array).
fn square_of(field: &str, a: &PyReadonlyArray2<'_, f64>, n: usize, of: &str) -> PyResult<Vec<f64>> {
    let (m, values) = square(field, a)?;
    if m != n {
        return Err(PyValueError::new_err(format!(
            "invalid `{field}`: grid {m}² differs from the {of}'s {n}²"
        )));
    }
    Ok(values)
}

fn to_array<'py, T: numpy::Element>(py: Python<'py>, n: usize, values: Vec<T>) -> Bound<'py, PyArray2<T>> {
    Array2::from_shape_vec((n, n), values)
        .expect("N² values")
        .into_pyarray(py)
}

/// A serialisable value → Python object (dicts, lists, numbers), through the standard library's
/// `json`.
fn json_to_py<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A table's columns as a dict of 1-D arrays: float64 for numbers with a fraction or undefined
/// cells (NaN), int64 for whole numbers, lists of str for text.
fn table_to_py<'py>(py: Python<'py>, table: &Table) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (c, name) in table.columns.iter().enumerate() {
        let cells: Vec<&Cell> = table.rows.iter().map(|r| &r[c]).collect();
        if cells.iter().all(|x| matches!(x, Cell::Int(_))) {
            let v: Vec<i64> = cells
                .iter()
                .map(|x| if let Cell::Int(i) = x { *i } else { 0 })
                .collect();
            d.set_item(name, v.into_pyarray(py))?;
        } else if cells
            .iter()
            .all(|x| matches!(x, Cell::Int(_) | Cell::Float(_) | Cell::Empty))
        {
            let v: Vec<f64> = cells.iter().map(|x| x.number()).collect();
            d.set_item(name, v.into_pyarray(py))?;
        } else {
            let v: Vec<Option<String>> = cells
                .iter()
                .map(|x| if let Cell::Empty = x { None } else { Some(x.text()) })
                .collect();
            d.set_item(name, v)?;
        }
    }
    Ok(d)
}

#[pymodule]
fn _wearsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", wearsim::VERSION)?;
    m.add("DEFAULT_TOLERANCE", wearsim::contact::DEFAULT_TOLERANCE)?;
    m.add("DEFAULT_MAX_ITERATIONS", wearsim::contact::DEFAULT_MAX_ITERATIONS)?;
    m.add(
        "SERIES_COLUMNS",
        wearsim::output::columns::<wearsim::output::SeriesRow>(),
    )?;
    m.add("WearsimError", m.py().get_type::<error::WearsimError>())?;
    m.add("NotConvergedError", m.py().get_type::<error::NotConvergedError>())?;
    surface::register(m)?;
    contact::register(m)?;
    sliding::register(m)?;
    study::register(m)?;
    Ok(())
}
