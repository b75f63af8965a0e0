//! The sliding model: on arrays, or as a run file describes it.

use std::path::PathBuf;

use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::config::{RunConfig, SurfacePair, SurfaceSource, Units};
use wearsim::estimate::Sampling;
use wearsim::junctions::DEFAULT_CONNECTIVITY;
use wearsim::output::{estimate_rows, Table};
use wearsim::run::{SlidingOutcome, SlidingRun};
use wearsim::sliding::{SlidingConfig, DEFAULT_DISTANCE, DEFAULT_RUNNING_IN, DEFAULT_STEP, DEFAULT_STEP_RUNNING_IN};
use wearsim::wear::{ParticleRuleSpec, DEFAULT_PARTICLE_RULE};
use wearsim::{Device, SolverOptions};

use crate::contact::PyMaterial;
use crate::error::{interruptible, interruptible_with_progress, to_py};
use crate::surface::surface_pair;
use crate::{json_to_py, table_to_py, to_array, Pair};
use numpy::PyArray2;

/// Series columns (name → 1-D array) and summary of a sliding run.
fn series_and_summary<'py>(
    py: Python<'py>,
    outcome: &SlidingOutcome,
) -> PyResult<(Bound<'py, PyDict>, serde_json::Value)> {
    Ok((table_to_py(py, &Table::of(&outcome.series_rows()))?, outcome.summary()))
}

/// Sliding model on two given surfaces. Returns (series columns, summary).
#[pyfunction]
#[pyo3(signature = (top, bottom, length, material, loads, modulus = "half-space", tolerance = wearsim::contact::DEFAULT_TOLERANCE, max_iterations = wearsim::contact::DEFAULT_MAX_ITERATIONS, connectivity = DEFAULT_CONNECTIVITY, distance = DEFAULT_DISTANCE, running_in = DEFAULT_RUNNING_IN, step_running_in = DEFAULT_STEP_RUNNING_IN, step = DEFAULT_STEP, particle_rule = DEFAULT_PARTICLE_RULE.name, device = "cpu", stopping = "settled-map", threads = None, progress = None))]
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
    particle_rule: &str,
    device: &str,
    stopping: &str,
    threads: Option<usize>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>)> {
    let (t, b) = surface_pair(&top, &bottom, length)?;
    let rule: ParticleRuleSpec = particle_rule.parse().map_err(to_py)?;
    let device: Device = device.parse().map_err(to_py)?;
    device.available().map_err(to_py)?;
    let grid = t.grid();
    let solver = SolverOptions::new(tolerance, max_iterations).map_err(to_py)?;
    wearsim::check::connectivity(connectivity).map_err(to_py)?;
    // The run these arrays and settings describe, built in memory as a run file would be.
    let config = RunConfig::builder(SurfaceSource::Arrays { grid, length }, material.inner.clone())
        .units(Units::Reduced)
        .modulus(modulus.parse().map_err(to_py)?)
        .solver(solver)
        .connectivity(connectivity)
        .device(device)
        .sliding(
            SlidingConfig::new(loads, distance, running_in, step_running_in, step, Some(grid.nx()))
                .map_err(to_py)?
                .with_particle_rule(rule),
        )
        .stopping(stopping.parse().map_err(to_py)?)
        .model(wearsim::model::WearModel::Sliding)
        .build()
        .map_err(to_py)?;
    let pair = SurfacePair::of_arrays(t, b);
    let outcome = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, steps| {
        SlidingRun::with_surfaces(&config, pair)?
            .interrupted_by(interrupt)
            .run(|view| steps.set(view.done, view.total))
    })?;
    let (series, mut summary) = series_and_summary(py, &outcome)?;
    // Arrays carry no unit system: their summary names none.
    summary.as_object_mut().expect("an object").remove("units");
    Ok((series, json_to_py(py, &summary)?))
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

    /// Pickling and copying (multiprocessing, joblib, Dask): the run file read again from its path
    /// (absolute, so that another working folder reads the same file).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, pyo3::types::PyType>, (PathBuf,)) {
        (slf.get_type(), (wearsim::io::canonical_path(&slf.get().path),))
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
    fn particle_rule(&self) -> Option<String> {
        self.config.sliding.as_ref().map(|s| s.particle_rule.to_string())
    }
    #[getter]
    fn device(&self) -> &'static str {
        self.config.device.name()
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
        let outcome = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, steps| {
            SlidingRun::prepare(config)?
                .interrupted_by(interrupt)
                .run(|view| steps.set(view.done, view.total))
        })?;
        let (series, summary) = series_and_summary(py, &outcome)?;
        Ok((series, json_to_py(py, &summary)?))
    }

    /// The static estimate exactly as `wearsim estimate RUN` makes it: (results columns, summary).
    #[pyo3(signature = (samples = None, threads = None, progress = None))]
    fn estimate<'py>(
        &self,
        py: Python<'py>,
        samples: Option<usize>,
        threads: Option<usize>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>)> {
        let config = &self.config;
        wearsim::run::sliding_schedule(config).map_err(to_py)?;
        let sampling = Sampling::of(samples.or(config.estimate_samples)).map_err(to_py)?;
        let outcome = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, solves| {
            SlidingRun::prepare(config)?.interrupted_by(interrupt).estimate(
                sampling,
                &config.estimate_calibration(),
                |done, most| solves.set(done, most),
            )
        })?;
        let rows = estimate_rows(&outcome.loads, config.units);
        Ok((table_to_py(py, &Table::of(&rows))?, json_to_py(py, &outcome.summary())?))
    }
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(slide, m)?)?;
    m.add_class::<PyRunFile>()?;
    Ok(())
}
