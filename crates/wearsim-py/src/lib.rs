//! `wearsim._wearsim`: the Python extension module. A thin layer over the `wearsim` library: arrays
//! in and out as NumPy arrays, library errors as Python exceptions carrying the library's message
//! (`error`), long calls run with the GIL released on a worker thread while the calling thread
//! watches for Ctrl-C. One module per concept: `surface`, `topography` (measured height maps),
//! `contact` (material, solver, junctions), `junctions` (their geometry),
//! `sliding`, `study`, `tables` (what the library derives from a study's tables for figures). The public Python API, with docstrings and units, is the pure-Python package
//! `wearsim` around this module.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::output::{Cell, Table};

mod contact;
mod error;
mod junctions;
mod sliding;
mod study;
mod surface;
mod tables;
mod topography;

/// Two arrays returned together (a surface pair, labels and sizes, a spectrum).
type Pair<'py, A, B> = PyResult<(Bound<'py, A>, Bound<'py, B>)>;

/// A grid size from Python: `N` (square) or `(Nx, Ny)`; any integers, so that a negative or zero
/// size is refused by the grid's own rule with its message, not by a failed conversion.
#[derive(FromPyObject, Clone, Copy)]
enum GridSize {
    Square(i64),
    Sides((i64, i64)),
}

impl GridSize {
    fn sides(self) -> PyResult<(usize, usize)> {
        let (nx, ny) = match self {
            GridSize::Square(n) => (n, n),
            GridSize::Sides(s) => s,
        };
        let side = |n: i64| {
            usize::try_from(n).map_err(|_| {
                PyValueError::new_err(format!(
                    "invalid `grid`: {n} must be a positive even number of pixels ≥ 16 (powers of two are fastest)"
                ))
            })
        };
        Ok((side(nx)?, side(ny)?))
    }

    /// The grid of these sides whose side along x is `length_x`.
    fn grid(self, length_x: f64) -> PyResult<wearsim::Grid> {
        let (nx, ny) = self.sides()?;
        wearsim::Grid::new(nx, ny, length_x).map_err(error::to_py)
    }
}

/// A non-empty 2-D array as ((rows, cols), values), or a ValueError naming `field`.
fn field<T: numpy::Element + Copy>(name: &str, a: &PyReadonlyArray2<'_, T>) -> PyResult<((usize, usize), Vec<T>)> {
    let shape = a.shape();
    if shape[0] == 0 || shape[1] == 0 {
        return Err(PyValueError::new_err(format!(
            "invalid `{name}`: the array is empty ({}×{})",
            shape[0], shape[1]
        )));
    }
    Ok(((shape[0], shape[1]), a.as_array().iter().copied().collect()))
}

/// [`field`] for an array that must have `shape` (the grid of a solver or of another array).
fn field_of(name: &str, a: &PyReadonlyArray2<'_, f64>, shape: (usize, usize), of: &str) -> PyResult<Vec<f64>> {
    let (s, values) = field(name, a)?;
    if s != shape {
        return Err(PyValueError::new_err(format!(
            "invalid `{name}`: shape {}×{} differs from the {of}'s {}×{}",
            s.0, s.1, shape.0, shape.1
        )));
    }
    Ok(values)
}

fn to_array<'py, T: numpy::Element>(py: Python<'py>, shape: (usize, usize), values: Vec<T>) -> Bound<'py, PyArray2<T>> {
    Array2::from_shape_vec(shape, values)
        .expect("rows × cols values")
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
    m.add("DEFAULT_CONNECTIVITY", wearsim::junctions::DEFAULT_CONNECTIVITY)?;
    m.add("MIN_GRID", wearsim::check::MIN_GRID)?;
    m.add("DEFAULT_DISTANCE", wearsim::sliding::DEFAULT_DISTANCE)?;
    m.add("DEFAULT_RUNNING_IN", wearsim::sliding::DEFAULT_RUNNING_IN)?;
    m.add("DEFAULT_STEP_RUNNING_IN", wearsim::sliding::DEFAULT_STEP_RUNNING_IN)?;
    m.add("DEFAULT_STEP", wearsim::sliding::DEFAULT_STEP)?;
    m.add("DEFAULT_PARTICLE_RULE", wearsim::wear::DEFAULT_PARTICLE_RULE.name)?;
    m.add("MAX_ESTIMATE_SAMPLES", wearsim::estimate::MAX_SAMPLES)?;
    m.add(
        "PARTICLE_RULES",
        wearsim::wear::PARTICLE_RULES.iter().map(|k| k.name).collect::<Vec<_>>(),
    )?;
    m.add(
        "SERIES_COLUMNS",
        wearsim::output::columns::<wearsim::output::SeriesRow>(),
    )?;
    m.add("WearsimError", m.py().get_type::<error::WearsimError>())?;
    m.add("NotConvergedError", m.py().get_type::<error::NotConvergedError>())?;
    surface::register(m)?;
    topography::register(m)?;
    contact::register(m)?;
    sliding::register(m)?;
    study::register(m)?;
    tables::register(m)?;
    junctions::register(m)?;
    Ok(())
}
