//! `wearsim._wearsim`: the Python extension module. A thin layer over the `wearsim` library: arrays
//! in and out as NumPy arrays, library errors as Python exceptions carrying the library's message,
//! long calls run with the GIL released on a worker thread while the calling thread watches for
//! Ctrl-C (a KeyboardInterrupt raises the library's interrupt flag, and the call returns once the
//! computation has stopped). The public Python API, with docstrings and units, is the pure-Python
//! package `wearsim` around this module.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::time::{Duration, Instant};

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use wearsim::config::{RunConfig, SlidingConfig};
use wearsim::junctions::{check_connectivity, JunctionLabeller, NO_JUNCTION};
use wearsim::output::{sliding_summary, RunInputs};
use wearsim::sliding::{run_sliding, schedule, series, LoadRun, SlidingSetup};
use wearsim::study::{self, Job, Study};
use wearsim::wear::static_wear;
use wearsim::{Error, Interrupt, Material, ModulusConvention, SolverOptions, SpectrumParams, Surface};

/// Two arrays returned together (a surface pair, labels and sizes, a spectrum).
type Pair<'py, A, B> = PyResult<(Bound<'py, A>, Bound<'py, B>)>;

create_exception!(_wearsim, WearsimError, PyException, "Base class of wearsim's errors.");
create_exception!(
    _wearsim,
    NotConvergedError,
    WearsimError,
    "The contact solver reached its iteration limit before its tolerance."
);

/// Library error → Python exception: bad input is a `ValueError`, file trouble an `OSError`, a
/// solver that does not converge a `NotConvergedError`; the message is the library's.
fn to_py(e: Error) -> PyErr {
    let message = e.to_string();
    match e {
        Error::Io { .. } => PyOSError::new_err(message),
        Error::NotConverged { .. } => NotConvergedError::new_err(message),
        Error::Interrupted => pyo3::exceptions::PyKeyboardInterrupt::new_err(message),
        Error::InvalidParameter { .. }
        | Error::InvalidSurface { .. }
        | Error::Config(_)
        | Error::InfeasibleLoad { .. } => PyValueError::new_err(message),
    }
}

/// Steps or jobs done so far and their total, updated by the worker thread and reported to a Python
/// callback by the calling thread.
#[derive(Default)]
struct Progress {
    done: AtomicUsize,
    total: AtomicUsize,
}

impl Progress {
    fn set(&self, done: usize, total: usize) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(done, Ordering::Relaxed);
    }
}

/// Runs `work` on a worker thread with the GIL released. Every 50 ms the calling thread checks for
/// signals; on Ctrl-C it raises the interrupt flag, waits for the work to stop and re-raises the
/// KeyboardInterrupt. `threads`, when given, runs the work on a pool of that many threads.
fn interruptible<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    work: impl FnOnce(&Interrupt) -> wearsim::Result<T> + Send,
) -> PyResult<T> {
    interruptible_with_progress(py, threads, None, |interrupt, _| work(interrupt))
}

/// [`interruptible`] with progress: when `callback` is given, the calling thread calls
/// `callback(done, total)` whenever the work has advanced its [`Progress`], and once at the end. An
/// exception in the callback stops the work like Ctrl-C and is raised.
fn interruptible_with_progress<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    callback: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&Interrupt, &Progress) -> wearsim::Result<T> + Send,
) -> PyResult<T> {
    let interrupt = Interrupt::default();
    let progress = Progress::default();
    let pool = match threads {
        Some(0) => return Err(PyValueError::new_err("invalid `threads`: must be at least 1")),
        Some(t) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("cannot start {t} threads: {e}")))?,
        ),
        None => None,
    };
    let mut reported = 0;
    let mut report = || -> PyResult<()> {
        let done = progress.done.load(Ordering::Relaxed);
        match callback {
            Some(f) if done != reported => {
                reported = done;
                f.call1((done, progress.total.load(Ordering::Relaxed))).map(|_| ())
            }
            _ => Ok(()),
        }
    };
    let (tx, rx) = channel();
    std::thread::scope(|scope| {
        let flag = interrupt.clone();
        let (pool, progress) = (&pool, &progress);
        scope.spawn(move || {
            let result = match pool {
                Some(p) => p.install(|| work(&flag, progress)),
                None => work(&flag, progress),
            };
            let _ = tx.send(result);
        });
        // The receiver is moved into each detached wait and handed back (it is Send, not Sync).
        let mut rx = rx;
        loop {
            let (back, received) = py.detach(move || {
                let r = rx.recv_timeout(Duration::from_millis(50));
                (rx, r)
            });
            rx = back;
            match received {
                Ok(result) => {
                    let value = result.map_err(to_py)?;
                    report()?;
                    return Ok(value);
                }
                Err(RecvTimeoutError::Timeout) => {
                    if let Err(stop) = py.check_signals().and_then(|_| report()) {
                        interrupt.request();
                        let _ = py.detach(move || rx.recv());
                        return Err(stop);
                    }
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(PyRuntimeError::new_err(
                        "wearsim's worker thread stopped without a result",
                    ))
                }
            }
        }
    })
}

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

fn modulus_convention(name: &str) -> PyResult<ModulusConvention> {
    match name {
        "half-space" => Ok(ModulusConvention::HalfSpace),
        "composite" => Ok(ModulusConvention::Composite),
        other => Err(PyValueError::new_err(format!(
            "invalid `modulus`: \"{other}\"; use \"half-space\" (E* = E/(1−ν²)) or \"composite\" (E* = E/(2(1−ν²)))"
        ))),
    }
}

/// JSON text → Python object (dicts, lists, numbers), through the standard library's `json`.
fn json_to_py<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (value.to_string(),))
}

// ---------------------------------------------------------------------------------------------
// Surfaces

#[pyfunction]
#[pyo3(signature = (grid, length, hurst, lambda_lower, lambda_upper, rms_height, seed, generation = "random-phase"))]
#[allow(clippy::too_many_arguments)]
fn generate_surface<'py>(
    py: Python<'py>,
    grid: usize,
    length: f64,
    hurst: f64,
    lambda_lower: f64,
    lambda_upper: f64,
    rms_height: f64,
    seed: u64,
    generation: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let generation = match generation {
        "random-phase" => wearsim::Generation::RandomPhase,
        "filtered-noise" => wearsim::Generation::FilteredNoise,
        other => {
            return Err(PyValueError::new_err(format!(
                "invalid `generation`: \"{other}\"; use \"random-phase\" or \"filtered-noise\""
            )))
        }
    };
    let params = SpectrumParams {
        hurst,
        lambda_lower,
        lambda_upper,
        rms_height,
        generation,
    };
    params.validate(grid, length).map_err(to_py)?;
    let surface = interruptible(py, None, |_| Surface::generate(grid, length, &params, seed))?;
    Ok(to_array(py, grid, surface.heights().to_vec()))
}

#[pyfunction]
fn pair_seeds(seed: u64) -> (u64, u64) {
    wearsim::surface::pair_seeds(seed)
}

fn surface_from(field: &str, heights: &PyReadonlyArray2<'_, f64>, length: f64) -> PyResult<Surface> {
    let (n, values) = square(field, heights)?;
    Surface::new(field, n, length, values).map_err(to_py)
}

/// The top and bottom surfaces of a slide, on one grid.
fn surface_pair(
    top: &PyReadonlyArray2<'_, f64>,
    bottom: &PyReadonlyArray2<'_, f64>,
    length: f64,
) -> PyResult<(Surface, Surface)> {
    let t = surface_from("top", top, length)?;
    let values = square_of("bottom", bottom, t.n(), "top")?;
    let b = Surface::new("bottom", t.n(), length, values).map_err(to_py)?;
    Ok((t, b))
}

#[pyfunction]
fn surface_statistics<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    length: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = surface_from("heights", &heights, length)?;
    let d = PyDict::new(py);
    d.set_item("grid", s.n())?;
    d.set_item("length", s.length())?;
    d.set_item("pixel_size", s.pixel_size())?;
    d.set_item("rms_height", s.rms_height())?;
    d.set_item("rms_slope", s.rms_slope())?;
    Ok(d)
}

#[pyfunction]
fn radial_psd<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    length: f64,
) -> Pair<'py, PyArray1<f64>, PyArray1<f64>> {
    let s = surface_from("heights", &heights, length)?;
    let psd = s.radial_psd();
    let (q, c): (Vec<f64>, Vec<f64>) = psd.into_iter().unzip();
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
    let n = t.n();
    let mut out = vec![0.0; n * n];
    wearsim::composite_heights(&t, &b, offset, &mut out);
    Ok(to_array(py, n, out))
}

// ---------------------------------------------------------------------------------------------
// Material

/// Elastic and adhesive-wear properties of the (identical) materials of both surfaces.
///
/// youngs_modulus E (reduced: 1; SI: Pa), poisson_ratio ν in (−1, 0.5), shear_strength τ̃ (unit of
/// E), fracture_energies 𝒢 (reduced: E·L; SI: J/m²; one wear bookkeeping each), geometry_factor f
/// of paper eq. (1), 3 by default. Derived: flow_pressure p_m = 3√3 τ̃, critical_diameters
/// d* = 2 f 𝒢 μ / τ̃² (length unit), effective_modulus(modulus) E*.
#[pyclass(name = "Material", module = "wearsim._wearsim", frozen)]
#[derive(Clone)]
struct PyMaterial {
    inner: Material,
}

#[pymethods]
impl PyMaterial {
    #[new]
    #[pyo3(signature = (youngs_modulus, poisson_ratio, shear_strength, fracture_energies = Vec::new(), geometry_factor = 3.0))]
    fn new(
        youngs_modulus: f64,
        poisson_ratio: f64,
        shear_strength: f64,
        fracture_energies: Vec<f64>,
        geometry_factor: f64,
    ) -> PyResult<Self> {
        Material::new(
            youngs_modulus,
            poisson_ratio,
            shear_strength,
            fracture_energies,
            geometry_factor,
        )
        .map(|inner| Self { inner })
        .map_err(to_py)
    }

    #[getter]
    fn youngs_modulus(&self) -> f64 {
        self.inner.youngs_modulus
    }
    #[getter]
    fn poisson_ratio(&self) -> f64 {
        self.inner.poisson_ratio
    }
    #[getter]
    fn shear_strength(&self) -> f64 {
        self.inner.shear_strength
    }
    #[getter]
    fn fracture_energies(&self) -> Vec<f64> {
        self.inner.fracture_energies.clone()
    }
    #[getter]
    fn geometry_factor(&self) -> f64 {
        self.inner.geometry_factor
    }
    #[getter]
    fn shear_modulus(&self) -> f64 {
        self.inner.shear_modulus()
    }
    #[getter]
    fn flow_pressure(&self) -> f64 {
        self.inner.flow_pressure()
    }
    #[getter]
    fn critical_diameters(&self) -> Vec<f64> {
        self.inner.critical_diameters()
    }
    fn critical_diameter(&self, fracture_energy: f64) -> PyResult<f64> {
        wearsim::material::positive("fracture_energy", fracture_energy).map_err(to_py)?;
        Ok(self.inner.critical_diameter(fracture_energy))
    }
    #[pyo3(signature = (modulus = "half-space"))]
    fn effective_modulus(&self, modulus: &str) -> PyResult<f64> {
        Ok(self.inner.effective_modulus(modulus_convention(modulus)?))
    }
    fn __repr__(&self) -> String {
        let m = &self.inner;
        format!(
            "Material(youngs_modulus={:e}, poisson_ratio={}, shear_strength={:e}, fracture_energies={:?}, geometry_factor={})",
            m.youngs_modulus, m.poisson_ratio, m.shear_strength, m.fracture_energies, m.geometry_factor
        )
    }
}

// ---------------------------------------------------------------------------------------------
// Contact

/// FFT contact solver for one grid, reused across solves (plans and buffers are made once).
#[pyclass(name = "ContactSolver", module = "wearsim._wearsim")]
struct PyContactSolver {
    inner: wearsim::ContactSolver,
}

#[pymethods]
impl PyContactSolver {
    #[new]
    #[pyo3(signature = (grid, length, effective_modulus, tolerance = wearsim::contact::DEFAULT_TOLERANCE, max_iterations = wearsim::contact::DEFAULT_MAX_ITERATIONS))]
    fn new(grid: usize, length: f64, effective_modulus: f64, tolerance: f64, max_iterations: usize) -> PyResult<Self> {
        let options = SolverOptions::new(tolerance, max_iterations).map_err(to_py)?;
        let mut inner = wearsim::ContactSolver::new(grid, length, effective_modulus).map_err(to_py)?;
        inner.options = options;
        Ok(Self { inner })
    }

    #[getter]
    fn grid(&self) -> usize {
        self.inner.n()
    }
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length()
    }
    #[getter]
    fn effective_modulus(&self) -> f64 {
        self.inner.effective_modulus()
    }
    #[getter]
    fn tolerance(&self) -> f64 {
        self.inner.options.tolerance
    }
    #[getter]
    fn max_iterations(&self) -> usize {
        self.inner.options.max_iterations
    }

    /// Returns (pressure, info dict); see the Python wrapper for the meaning.
    #[pyo3(signature = (heights, load, flow_pressure = f64::INFINITY, initial_pressure = None))]
    fn solve<'py>(
        &mut self,
        py: Python<'py>,
        heights: PyReadonlyArray2<'py, f64>,
        load: f64,
        flow_pressure: f64,
        initial_pressure: Option<PyReadonlyArray2<'py, f64>>,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyDict>)> {
        let n = self.inner.n();
        let h = square_of("heights", &heights, n, "solver")?;
        let mut pressure = match initial_pressure {
            None => vec![0.0; n * n],
            Some(p0) => square_of("initial_pressure", &p0, n, "solver")?,
        };
        let area = self.inner.length() * self.inner.length();
        let solver = &mut self.inner;
        let start = Instant::now();
        let info = interruptible(py, None, |interrupt| {
            solver.interrupt = interrupt.clone();
            let r = solver.solve(&h, load / area, flow_pressure, &mut pressure);
            solver.interrupt = Interrupt::default();
            r
        })?;
        let d = PyDict::new(py);
        d.set_item("iterations", info.iterations)?;
        d.set_item("convolutions", info.convolutions)?;
        d.set_item("residual", info.residual)?;
        d.set_item("tolerance", info.tolerance)?;
        d.set_item("approach", info.approach)?;
        d.set_item("contact_pixels", info.contact_pixels)?;
        d.set_item("plastic_pixels", info.plastic_pixels)?;
        d.set_item("contact_area", info.contact_pixels as f64 / (n * n) as f64)?;
        d.set_item("mean_pressure", load / area)?;
        d.set_item("seconds", start.elapsed().as_secs_f64())?;
        Ok((to_array(py, n, pressure), d))
    }

    /// Displacement 𝒦p of a pressure field (zero mean).
    fn displacement<'py>(
        &mut self,
        py: Python<'py>,
        pressure: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let n = self.inner.n();
        let p = square_of("pressure", &pressure, n, "solver")?;
        let mut out = vec![0.0; n * n];
        let solver = &mut self.inner;
        py.detach(|| solver.apply_influence(&p, &mut out));
        Ok(to_array(py, n, out))
    }
}

// ---------------------------------------------------------------------------------------------
// Junctions and the static model

/// Labels of a contact map (−1 outside contact) and the pixel count of every junction.
#[pyfunction]
#[pyo3(signature = (contact, connectivity = 4))]
fn label_junctions<'py>(
    py: Python<'py>,
    contact: PyReadonlyArray2<'py, bool>,
    connectivity: u8,
) -> Pair<'py, PyArray2<i64>, PyArray1<u64>> {
    check_connectivity(connectivity).map_err(to_py)?;
    let (n, flags) = square("contact", &contact)?;
    let (labels, sizes) = py.detach(|| {
        let mut labeller = JunctionLabeller::new(n, connectivity);
        labeller.label(|k| flags[k]);
        let labels: Vec<i64> = labeller
            .labels()
            .iter()
            .map(|&l| if l == NO_JUNCTION { -1 } else { l as i64 })
            .collect();
        let sizes: Vec<u64> = labeller.sizes().iter().map(|&s| s as u64).collect();
        (labels, sizes)
    });
    Ok((to_array(py, n, labels), sizes.into_pyarray(py)))
}

/// Static model (SPEC §5) on the junction pixel counts of one contact map.
#[pyfunction]
fn static_wear_model<'py>(
    py: Python<'py>,
    junction_pixels: Vec<usize>,
    pixel_size: f64,
    critical_diameter: f64,
) -> PyResult<Bound<'py, PyDict>> {
    wearsim::material::positive("pixel_size", pixel_size).map_err(to_py)?;
    wearsim::material::positive("critical_diameter", critical_diameter).map_err(to_py)?;
    let junctions: Vec<_> = junction_pixels
        .iter()
        .map(|&p| wearsim::junctions::Junction::new(p, pixel_size))
        .collect();
    let w = static_wear(&junctions, critical_diameter);
    let d = PyDict::new(py);
    d.set_item("wear_coefficient", w.wear_coefficient)?;
    d.set_item("wear_rate_over_omega", w.wear_rate_over_omega)?;
    d.set_item("junctions", junctions.len())?;
    d.set_item("critical_junctions", w.critical_junctions)?;
    Ok(d)
}

// ---------------------------------------------------------------------------------------------
// Sliding

/// Series columns (name → 1-D array) of a sliding run.
fn series_columns<'py>(py: Python<'py>, runs: &[LoadRun]) -> PyResult<Bound<'py, PyDict>> {
    let rows = series(runs);
    let d = PyDict::new(py);
    macro_rules! column {
        ($name:ident) => {
            d.set_item(
                stringify!($name),
                rows.iter().map(|r| r.$name).collect::<Vec<_>>().into_pyarray(py),
            )?;
        };
    }
    column!(load);
    column!(fracture_energy);
    column!(s);
    column!(junctions);
    column!(contact_area);
    column!(iterations);
    column!(residual);
    column!(n_critical);
    column!(n_formed);
    column!(n_shrunk);
    column!(volume);
    Ok(d)
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
    let n = t.n();
    let solver = SolverOptions::new(tolerance, max_iterations).map_err(to_py)?;
    check_connectivity(connectivity).map_err(to_py)?;
    let convention = modulus_convention(modulus)?;
    let sliding = SlidingConfig::new(loads, distance, running_in, step_running_in, step, Some(n)).map_err(to_py)?;
    let start = Instant::now();
    let runs = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, steps| {
        let setup = SlidingSetup {
            material: &material.inner,
            effective_modulus: material.inner.effective_modulus(convention),
            solver,
            connectivity,
            sliding: &sliding,
            interrupt: interrupt.clone(),
        };
        run_sliding(&t, &b, &setup, |view| steps.set(view.done, view.total))
    })?;
    let seconds = start.elapsed().as_secs_f64();
    let inputs = RunInputs {
        units: Default::default(),
        surfaces: serde_json::json!({"source": "arrays", "grid": n, "length": length}),
        material: &material.inner,
        modulus: convention,
        solver,
        connectivity,
        sliding: &sliding,
    };
    let mut summary = sliding_summary(&inputs, &runs, seconds, schedule(n, &sliding).len());
    summary.as_object_mut().expect("an object").remove("units");
    Ok((series_columns(py, &runs)?, json_to_py(py, &summary)?))
}

/// A parsed and validated run file.
#[pyclass(name = "RunFile", module = "wearsim._wearsim", frozen)]
struct PyRunFile {
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
        self.config.solver.tolerance
    }
    #[getter]
    fn max_iterations(&self) -> usize {
        self.config.solver.max_iterations
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
        Ok((
            to_array(py, t.n(), t.heights().to_vec()),
            to_array(py, b.n(), b.heights().to_vec()),
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
        let (runs, n) = interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, steps| {
            let (top, bottom) = config.surfaces()?;
            let mut setup = SlidingSetup::from_run(config, sliding);
            setup.interrupt = interrupt.clone();
            Ok((
                run_sliding(&top, &bottom, &setup, |view| steps.set(view.done, view.total))?,
                top.n(),
            ))
        })?;
        let seconds = start.elapsed().as_secs_f64();
        let summary = sliding_summary(
            &RunInputs::of_run(config, sliding),
            &runs,
            seconds,
            schedule(n, sliding).len(),
        );
        Ok((series_columns(py, &runs)?, json_to_py(py, &summary)?))
    }
}

// ---------------------------------------------------------------------------------------------
// Studies

/// An expanded study file.
#[pyclass(name = "Study", module = "wearsim._wearsim", frozen)]
struct PyStudy {
    study: Study,
    /// The study file's text and the folder its relative paths resolve against: what a Dask
    /// worker needs to expand the same study.
    text: String,
    base: PathBuf,
}

impl PyStudy {
    fn job(&self, index: usize) -> PyResult<&Job> {
        self.study.jobs.get(index).ok_or_else(|| {
            PyValueError::new_err(format!(
                "invalid job index {index}: the study has {} jobs",
                self.study.jobs.len()
            ))
        })
    }
}

#[pymethods]
impl PyStudy {
    /// Expands study-file text whose relative paths resolve against `base`.
    #[new]
    fn new(text: String, base: PathBuf) -> PyResult<Self> {
        let study = study::expand(&text, &base).map_err(to_py)?;
        Ok(Self { study, text, base })
    }

    #[getter]
    fn text(&self) -> &str {
        &self.text
    }
    #[getter]
    fn base(&self) -> PathBuf {
        self.base.clone()
    }
    #[getter]
    fn hash(&self) -> &str {
        &self.study.hash
    }
    fn __len__(&self) -> usize {
        self.study.jobs.len()
    }

    /// One dict per job: index, material, every input and the load.
    fn jobs<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.study
            .jobs
            .iter()
            .map(|job| {
                let d = PyDict::new(py);
                d.set_item("job", job.index)?;
                d.set_item("material", &job.material)?;
                for (k, v) in job.inputs() {
                    d.set_item(k, v)?;
                }
                d.set_item("load", job.load())?;
                Ok(d)
            })
            .collect()
    }

    /// Prepares a result folder (as `wearsim study run` does) and returns the indices of the jobs
    /// without a result file; existing files are checked to belong to this study.
    fn prepare(&self, py: Python<'_>, out: PathBuf) -> PyResult<Vec<usize>> {
        let study = &self.study;
        let base = &self.base;
        interruptible(py, None, |_| {
            study::prepare_folder(&out, study, base)?;
            let mut pending = Vec::new();
            for job in &study.jobs {
                if study::job_path(&out, job.index).is_file() {
                    job.read_result(&out)?;
                } else {
                    pending.push(job.index);
                }
            }
            Ok(pending)
        })
    }

    /// Runs the jobs of shard `shard` = (k, count) that have no result file, `workers` at a time
    /// (default: one per thread, as `wearsim study run`). Returns (computed, skipped).
    #[pyo3(signature = (out, workers = None, shard = None, threads = None, progress = None))]
    fn run(
        &self,
        py: Python<'_>,
        out: PathBuf,
        workers: Option<usize>,
        shard: Option<(usize, usize)>,
        threads: Option<usize>,
        progress: Option<Bound<'_, PyAny>>,
    ) -> PyResult<(usize, usize)> {
        let study = &self.study;
        let base = &self.base;
        let jobs: Vec<&Job> = match shard {
            None => study.jobs.iter().collect(),
            Some((k, count)) if count >= 1 && (1..=count).contains(&k) => study::shard(&study.jobs, k, count),
            Some((k, count)) => {
                return Err(PyValueError::new_err(format!(
                    "invalid `shard`: ({k}, {count}) needs 1 ≤ k ≤ count"
                )))
            }
        };
        interruptible_with_progress(py, threads, progress.as_ref(), |interrupt, done_jobs| {
            study::prepare_folder(&out, study, base)?;
            let workers = workers.unwrap_or_else(rayon::current_num_threads).max(1);
            study::run_jobs(&out, &jobs, workers, interrupt, |done, total| {
                done_jobs.set(done, total)
            })
        })
    }

    /// Runs job `index` and returns its result as JSON text (what its job file holds); writes nothing.
    #[pyo3(signature = (index, threads = None))]
    fn run_job(&self, py: Python<'_>, index: usize, threads: Option<usize>) -> PyResult<String> {
        let job = self.job(index)?;
        let result = interruptible(py, threads, |interrupt| study::run_job(job, interrupt))?;
        serde_json::to_string(&result).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Stores a job result (JSON text from `run_job`) in a result folder, after checking that it
    /// was computed for this study's job `index`.
    fn write_result(&self, out: PathBuf, index: usize, result: &str) -> PyResult<()> {
        let job = self.job(index)?;
        let parsed: study::JobResult = serde_json::from_str(result)
            .map_err(|e| PyValueError::new_err(format!("invalid `result`: not a job result ({e})")))?;
        if parsed.index != job.index || parsed.material != job.material || parsed.parameters != job.parameters() {
            return Err(PyValueError::new_err(format!(
                "invalid `result`: it was computed for job {} ({}), not for job {index} ({})",
                parsed.index, parsed.material, job.material
            )));
        }
        study::write_result(&out, &parsed).map_err(to_py)
    }
}

/// Collects a finished study folder into results.csv and results_aggregated.csv; returns the row
/// counts.
#[pyfunction]
fn collect_study(out: PathBuf) -> PyResult<(usize, usize)> {
    study::collect(&out).map_err(to_py)
}

#[pymodule]
fn _wearsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", wearsim::VERSION)?;
    m.add("DEFAULT_TOLERANCE", wearsim::contact::DEFAULT_TOLERANCE)?;
    m.add("DEFAULT_MAX_ITERATIONS", wearsim::contact::DEFAULT_MAX_ITERATIONS)?;
    m.add("WearsimError", m.py().get_type::<WearsimError>())?;
    m.add("NotConvergedError", m.py().get_type::<NotConvergedError>())?;
    m.add_function(wrap_pyfunction!(generate_surface, m)?)?;
    m.add_function(wrap_pyfunction!(pair_seeds, m)?)?;
    m.add_function(wrap_pyfunction!(surface_statistics, m)?)?;
    m.add_function(wrap_pyfunction!(radial_psd, m)?)?;
    m.add_function(wrap_pyfunction!(composite_heights, m)?)?;
    m.add_function(wrap_pyfunction!(label_junctions, m)?)?;
    m.add_function(wrap_pyfunction!(static_wear_model, m)?)?;
    m.add_function(wrap_pyfunction!(slide, m)?)?;
    m.add_function(wrap_pyfunction!(collect_study, m)?)?;
    m.add_class::<PyMaterial>()?;
    m.add_class::<PyContactSolver>()?;
    m.add_class::<PyRunFile>()?;
    m.add_class::<PyStudy>()?;
    Ok(())
}
