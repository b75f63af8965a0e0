//! The material, the contact solver, and junctions with the static model.

use std::sync::{Mutex, MutexGuard};
use std::time::Instant;

use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wearsim::junctions::{JunctionLabeller, NO_JUNCTION};
use wearsim::output::ContactRecord;
use wearsim::wear::static_wear;
use wearsim::{Boundary, Interrupt, Material, ModulusConvention, SolverOptions};

use crate::error::{interruptible, to_py};
use crate::{field, field_of, json_to_py, to_array, GridSize};

/// Elastic and adhesive-wear properties of the (identical) materials of both surfaces.
///
/// youngs_modulus E (reduced: 1; SI: Pa), poisson_ratio ν in (−1, 0.5), shear_strength τ̃ (unit of
/// E), fracture_energies 𝒢 (reduced: E·L; SI: J/m²; one wear bookkeeping each), geometry_factor f
/// of paper eq. (1), 3 by default. Derived: flow_pressure p_m = 3√3 τ̃, critical_diameters
/// d* = 2 f 𝒢 μ / τ̃² (length unit), effective_modulus(modulus) E*.
#[pyclass(name = "Material", module = "wearsim._wearsim", frozen)]
#[derive(Clone)]
pub struct PyMaterial {
    pub inner: Material,
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
        wearsim::check::positive("fracture_energy", fracture_energy).map_err(to_py)?;
        Ok(self.inner.critical_diameter(fracture_energy))
    }
    #[pyo3(signature = (modulus = "half-space"))]
    fn effective_modulus(&self, modulus: &str) -> PyResult<f64> {
        Ok(self
            .inner
            .effective_modulus(modulus.parse::<ModulusConvention>().map_err(to_py)?))
    }
    /// Pickling and copying (multiprocessing, joblib, Dask): made again from its inputs.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, pyo3::types::PyType>, (f64, f64, f64, Vec<f64>, f64))> {
        let m = &slf.get().inner;
        Ok((
            slf.get_type(),
            (
                m.youngs_modulus,
                m.poisson_ratio,
                m.shear_strength,
                m.fracture_energies.clone(),
                m.geometry_factor,
            ),
        ))
    }
    fn __repr__(&self) -> String {
        let m = &self.inner;
        format!(
            "Material(youngs_modulus={:e}, poisson_ratio={}, shear_strength={:e}, fracture_energies={:?}, geometry_factor={})",
            m.youngs_modulus, m.poisson_ratio, m.shear_strength, m.fracture_energies, m.geometry_factor
        )
    }
}

/// A solve's pressure, displacement and gap fields and its record.
type Solution<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyAny>,
);

/// FFT contact solver for one grid, reused across solves (plans and buffers are made once). One
/// solver used from several threads solves one call at a time (its buffers are shared): calls wait
/// for each other, outside the GIL. Pickled or copied, it is made again from its settings.
#[pyclass(name = "ContactSolver", module = "wearsim._wearsim", frozen)]
pub struct PyContactSolver {
    inner: Mutex<wearsim::ContactSolver>,
    grid: wearsim::Grid,
    /// What it was made with, for pickling.
    args: SolverArgs,
}

/// The arguments a solver was made with.
type SolverArgs = ((usize, usize), f64, f64, f64, usize, &'static str, &'static str);

impl PyContactSolver {
    /// The solver, locked for one call (waiting for another thread's call to finish).
    fn lock(&self) -> PyResult<MutexGuard<'_, wearsim::ContactSolver>> {
        self.inner.lock().map_err(|_| {
            pyo3::exceptions::PyRuntimeError::new_err(
                "this ContactSolver failed in another thread during a call; make a new one",
            )
        })
    }
}

#[pymethods]
impl PyContactSolver {
    #[new]
    #[pyo3(signature = (grid, length, effective_modulus, tolerance = wearsim::contact::DEFAULT_TOLERANCE, max_iterations = wearsim::contact::DEFAULT_MAX_ITERATIONS, boundary = "periodic", device = "cpu"))]
    fn new(
        grid: GridSize,
        length: f64,
        effective_modulus: f64,
        tolerance: f64,
        max_iterations: usize,
        boundary: &str,
        device: &str,
    ) -> PyResult<Self> {
        let options = SolverOptions::new(tolerance, max_iterations).map_err(to_py)?;
        let boundary = boundary.parse::<Boundary>().map_err(to_py)?;
        let device = device.parse::<wearsim::Device>().map_err(to_py)?;
        let grid = grid.grid(length)?;
        let inner = wearsim::ContactSolver::on_device(device, grid, effective_modulus, boundary)
            .map_err(to_py)?
            .with_options(options);
        let args = (
            (grid.nx(), grid.ny()),
            length,
            effective_modulus,
            tolerance,
            max_iterations,
            boundary.name(),
            device.name(),
        );
        Ok(Self {
            inner: Mutex::new(inner),
            grid,
            args,
        })
    }

    /// Pickling and copying (multiprocessing, joblib, Dask): a new solver of the same settings.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, pyo3::types::PyType>, SolverArgs) {
        (slf.get_type(), slf.get().args)
    }

    /// (Nx, Ny).
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.args.0
    }
    /// Side along x, Lx.
    #[getter]
    fn length(&self) -> f64 {
        self.args.1
    }
    #[getter]
    fn effective_modulus(&self) -> f64 {
        self.args.2
    }
    #[getter]
    fn tolerance(&self) -> f64 {
        self.args.3
    }
    #[getter]
    fn max_iterations(&self) -> usize {
        self.args.4
    }
    /// "periodic" or "free".
    #[getter]
    fn boundary(&self) -> &'static str {
        self.args.5
    }
    /// "cpu".
    #[getter]
    fn device(&self) -> &'static str {
        self.args.6
    }

    /// Returns (pressure, displacement, gap, info dict); see the Python wrapper for the meaning.
    #[pyo3(signature = (heights, load, flow_pressure = f64::INFINITY, initial_pressure = None))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        heights: PyReadonlyArray2<'py, f64>,
        load: f64,
        flow_pressure: f64,
        initial_pressure: Option<PyReadonlyArray2<'py, f64>>,
    ) -> PyResult<Solution<'py>> {
        let shape = self.shape();
        let h = field_of("heights", &heights, shape, "solver")?;
        let mut pressure = match initial_pressure {
            None => vec![0.0; shape.0 * shape.1],
            Some(p0) => field_of("initial_pressure", &p0, shape, "solver")?,
        };
        let start = Instant::now();
        // Locked outside the GIL: a thread waiting for another's call never holds the GIL it needs.
        let (info, fields, seconds) = interruptible(py, None, |interrupt| {
            let mut solver = match self.inner.lock() {
                Ok(s) => s,
                Err(_) => {
                    return Err(wearsim::Error::param(
                        "solver",
                        "failed in another thread; make a new one",
                    ))
                }
            };
            solver.set_interrupt(interrupt.clone());
            let r = solver.solve(&h, self.grid.mean_pressure(load), flow_pressure, &mut pressure);
            solver.set_interrupt(Interrupt::default());
            let info = r?;
            let seconds = start.elapsed().as_secs_f64();
            let fields = solver.gap_and_displacement(&h, &pressure, &info)?;
            Ok((info, fields, seconds))
        })?;
        let d = json_to_py(py, &ContactRecord::new(&info, &pressure, seconds))?;
        Ok((
            to_array(py, shape, pressure),
            to_array(py, shape, fields.displacement),
            to_array(py, shape, fields.gap),
            d,
        ))
    }

    /// Displacement 𝒦p of a pressure field (zero mean when periodic).
    fn displacement<'py>(
        &self,
        py: Python<'py>,
        pressure: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let shape = self.shape();
        let p = field_of("pressure", &pressure, shape, "solver")?;
        let mut out = vec![0.0; shape.0 * shape.1];
        py.detach(|| -> PyResult<()> {
            self.lock()?.apply_influence(&p, &mut out);
            Ok(())
        })?;
        Ok(to_array(py, shape, out))
    }
}

/// Labels, pixel counts and wrap flags of the junctions of one contact map.
type Labelled<'py> = PyResult<(
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray2<bool>>,
)>;

/// Labels of a contact map (−1 outside contact), the pixel count of every junction, and whether it
/// wraps the periodic box along x and along y (one row per junction).
#[pyfunction]
#[pyo3(signature = (contact, connectivity = wearsim::junctions::DEFAULT_CONNECTIVITY))]
fn label_junctions<'py>(py: Python<'py>, contact: PyReadonlyArray2<'py, bool>, connectivity: u8) -> Labelled<'py> {
    wearsim::check::connectivity(connectivity).map_err(to_py)?;
    let ((rows, cols), flags) = field("contact", &contact)?;
    if rows.saturating_mul(cols) >= u32::MAX as usize {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "invalid `contact`: {rows}×{cols} pixels are more than 32-bit junction labels can index"
        )));
    }
    let (labels, sizes, wraps) = py.detach(|| {
        let mut labeller = JunctionLabeller::new(rows, cols, connectivity);
        labeller.label(|k| flags[k]);
        let labels: Vec<i64> = labeller
            .labels()
            .iter()
            .map(|&l| if l == NO_JUNCTION { -1 } else { l as i64 })
            .collect();
        let sizes: Vec<u64> = labeller.sizes().iter().map(|&s| s as u64).collect();
        let wraps: Vec<bool> = (0..sizes.len())
            .flat_map(|id| {
                let (x, y) = labeller.wraps(id);
                [x, y]
            })
            .collect();
        (labels, sizes, wraps)
    });
    let count = sizes.len();
    Ok((
        to_array(py, (rows, cols), labels),
        sizes.into_pyarray(py),
        to_array(py, (count, 2), wraps),
    ))
}

/// The contact map of a pressure field: p > 0, as `wearsim contact` writes it.
#[pyfunction]
fn contact_map<'py>(py: Python<'py>, pressure: PyReadonlyArray2<'py, f64>) -> PyResult<Bound<'py, PyArray2<bool>>> {
    let (shape, p) = field("pressure", &pressure)?;
    Ok(to_array(py, shape, wearsim::contact::contact_map(&p)))
}

/// Static model (paper §2, Frérot et al. 2018) on the junction pixel counts of one contact map.
#[pyfunction]
fn static_wear_model<'py>(
    py: Python<'py>,
    junction_pixels: Vec<usize>,
    pixel_size: f64,
    critical_diameter: f64,
) -> PyResult<Bound<'py, PyDict>> {
    wearsim::check::positive("pixel_size", pixel_size).map_err(to_py)?;
    wearsim::check::positive("critical_diameter", critical_diameter).map_err(to_py)?;
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

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMaterial>()?;
    m.add_class::<PyContactSolver>()?;
    m.add_function(wrap_pyfunction!(contact_map, m)?)?;
    m.add_function(wrap_pyfunction!(label_junctions, m)?)?;
    m.add_function(wrap_pyfunction!(static_wear_model, m)?)?;
    Ok(())
}
