//! The sliding model: on arrays, or as a run file describes it.

use std::path::PathBuf;
use std::time::Instant;

use numpy::PyReadonlyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::config::RunConfig;
use wearsim::output::{series_rows, sliding_summary, SlidingInputs, Table};
use wearsim::sliding::SlidingConfig;
use wearsim::sliding::{run_sliding, schedule, LoadRun, SlidingSetup};
use wearsim::{ModulusConvention, SolverOptions};

use crate::contact::PyMaterial;
use crate::error::{interruptible, interruptible_with_progress, to_py};
use crate::surface::surface_pair;
use crate::{json_to_py, table_to_py, to_array, Pair};
use numpy::PyArray2;

/// Series columns (name → 1-D array) of a sliding run, the columns of `series.csv`.
fn series_columns<'py>(py: Python<'py>, runs: &[LoadRun]) -> PyResult<Bound<'py, PyDict>> {
    table_to_py(py, &Table::of(&series_rows(runs)))
}

/// Sliding model on two given surfaces. Returns (series columns, summary).
#[pyfunction]
#[pyo3(signature = (top, bottom, length, material, loads, modulus = "half-space", tolerance = wearsim::contact::DEFAULT_TOLERANCE, max_iterations = wearsim::contact::DEFAULT_MAX_ITERATIONS, connectivity = 4, distance = 0.5, running_in = 0.25, step_running_in = 4, step = 1, threads = None, progress = None))]
#[allow(clippy::too_many_arguments)]
fn slide<'py>(
    py: Python<'py>,
    top: PyReadonlyArray2<'py, f64>,
    bottom: PyReadonlyArray2<'py, f64>,
    length: f64,
    material: &PyMaterial,
    loads: Vec<f64>,
    modulus: &str,
    tolerance: f64,
    max_iterations: usize,
    connectivity: u8,
    distance: f64,
    running_in: f64,
    step_running_in: usize,
    step: usize,
    threads: Option<usize>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>)> {
    let (t, b) = surface_pair(&top, &bottom, length)?;
    let n = t.nx();
    let solver = SolverOptions::new(tolerance, max_iterations).map_err(to_py)?;
    wearsim::check::connectivity(connectivity).map_err(to_py)?;
    let convention: ModulusConvention = modulus.parse().map_err(to_py)?;
    let sliding = SlidingConfig::new(loads, distance, running_in, step_running_in, step, Some(n)).map_err(to_py)?;
    let start = Instant::now();
    let runs = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, steps| {
        let setup = SlidingSetup {
            material: &material.inner,
            effective_modulus: material.inner.effective_modulus(convention),
            solver,
            device: Default::default(),
            connectivity,
            sliding: &sliding,
            interrupt: interrupt.clone(),
        };
        run_sliding(&t, &b, &setup, |view| steps.set(view.done, view.total))
    })?;
    let seconds = start.elapsed().as_secs_f64();
    let inputs = SlidingInputs {
        units: Default::default(),
        surfaces: serde_json::json!({
            "source": "arrays",
            "grid": if t.grid().is_square() { serde_json::json!(n) } else { serde_json::json!([n, t.ny()]) },
            "length": if t.grid().is_square() { serde_json::json!(length) } else { serde_json::json!([length, t.grid().length_y()]) },
        }),
        material: &material.inner,
        modulus: convention,
        solver,
        connectivity,
        sliding: &sliding,
        // Arrays may be measured maps: a border jump the periodic solution would see is reported.
        warnings: [("top", &t), ("bottom", &b)]
            .into_iter()
            .filter_map(|(name, s)| wearsim::topography::periodicity(s.heights(), s.nx(), s.ny()).warning(name))
            .collect(),
    };
    let mut summary = sliding_summary(&inputs, &runs, t.pixel_size(), seconds, schedule(n, &sliding).len());
    summary.as_object_mut().expect("an object").remove("units");
    Ok((series_columns(py, &runs)?, json_to_py(py, &summary)?))
}

/// A parsed and validated run file.
#[pyclass(name = "RunFile", module = "wearsim._wearsim", frozen)]
pub struct PyRunFile {
    path: PathBuf,
    config: RunConfig,
}

#[pymethods]
impl PyRunFile {
    #[new]
    fn new(path: PathBuf) -> PyResult<Self> {
        let config = RunConfig::from_path(&path).map_err(to_py)?;
        Ok(Self { path, config })
    }

    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }
    #[getter]
    fn units(&self) -> &'static str {
        self.config.units.length_unit()
    }
    #[getter]
    fn length(&self) -> f64 {
        self.config.length()
    }
    #[getter]
    fn material(&self) -> PyMaterial {
        PyMaterial {
            inner: self.config.material.clone(),
        }
    }
    #[getter]
    fn effective_modulus(&self) -> f64 {
        self.config.effective_modulus()
    }
    #[getter]
    fn modulus(&self) -> &'static str {
        self.config.modulus.name()
    }
    #[getter]
    fn tolerance(&self) -> f64 {
        self.config.solver.tolerance()
    }
    #[getter]
    fn max_iterations(&self) -> usize {
        self.config.solver.max_iterations()
    }
    #[getter]
    fn connectivity(&self) -> u8 {
        self.config.connectivity
    }
    #[getter]
    fn loads(&self) -> Option<Vec<f64>> {
        self.config.sliding.as_ref().map(|s| s.loads.clone())
    }

    /// The top and bottom surfaces (generated or read, as the run file says).
    fn surfaces<'py>(&self, py: Python<'py>) -> Pair<'py, PyArray2<f64>, PyArray2<f64>> {
        let config = &self.config;
        let (t, b) = interruptible(py, None, |_| config.surfaces())?;
        let shape = (t.nx(), t.ny());
        Ok((
            to_array(py, shape, t.into_heights()),
            to_array(py, shape, b.into_heights()),
        ))
    }

    /// The sliding model as `wearsim slide` runs it. Returns (series columns, summary).
    #[pyo3(signature = (threads = None, progress = None))]
    fn slide<'py>(
        &self,
        py: Python<'py>,
        threads: Option<usize>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>)> {
        let config = &self.config;
        let Some(sliding) = config.sliding.as_ref() else {
            return Err(PyValueError::new_err(format!(
                "{}: a [sliding] table with `loads` is needed to slide",
                self.path.display()
            )));
        };
        let start = Instant::now();
        let (runs, n, pixel_size, warnings) =
            interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, steps| {
                let pair = config.surface_pair()?;
                let mut setup = SlidingSetup::from_run(config, sliding);
                setup.interrupt = interrupt.clone();
                let runs = run_sliding(&pair.top, &pair.bottom, &setup, |view| steps.set(view.done, view.total))?;
                Ok((runs, pair.top.nx(), pair.top.pixel_size(), pair.warnings))
            })?;
        let seconds = start.elapsed().as_secs_f64();
        let mut inputs = SlidingInputs::of_run(config, sliding);
        inputs.warnings.extend(warnings);
        let summary = sliding_summary(&inputs, &runs, pixel_size, seconds, schedule(n, sliding).len());
        Ok((series_columns(py, &runs)?, json_to_py(py, &summary)?))
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(slide, m)?)?;
    m.add_class::<PyRunFile>()?;
    Ok(())
}
