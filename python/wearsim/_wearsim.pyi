"""Type stubs of the compiled extension `wearsim._wearsim` (crates/wearsim-py). Use the public API
of the `wearsim` package; this layer takes contiguous float64 arrays."""

from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "ContactSolver",
    "DEFAULT_CONNECTIVITY",
    "DEFAULT_DISTANCE",
    "DEFAULT_MAX_ITERATIONS",
    "DEFAULT_PARTICLE_RULE",
    "DEFAULT_RUNNING_IN",
    "DEFAULT_STEP",
    "DEFAULT_STEP_RUNNING_IN",
    "DEFAULT_TOLERANCE",
    "FIGURES",
    "INTERVAL_LEVEL",
    "KIM_EXPERIMENTAL_K",
    "KIM_SEVERITY_FIT",
    "MAX_ESTIMATE_SAMPLES",
    "MIN_GRID",
    "Material",
    "NotConvergedError",
    "PAPER_SEVERITY_FIT",
    "PARTICLE_RULES",
    "RESOLVED_PARTICLES",
    "RunFile",
    "SERIES_COLUMNS",
    "Study",
    "WearsimError",
    "__version__",
    "aggregate",
    "collect_study",
    "composite_heights",
    "contact_map",
    "curve_labels",
    "curves",
    "equal_critical_diameter",
    "findings",
    "fit_surface",
    "generate_surface",
    "has_kim_materials",
    "job_series",
    "junction_geometry",
    "label_junctions",
    "line_fit",
    "mean_interval",
    "metres_per",
    "pair_seeds",
    "periodicity",
    "poisson_interval",
    "poor_fit_warning",
    "power_law_fit",
    "preprocess_surface",
    "radial_psd",
    "read_surface",
    "run_figure",
    "series_job",
    "severity_fits",
    "slide",
    "spectrum_pair",
    "static_wear_model",
    "study_figures",
    "surface_statistics",
    "table_figures",
    "unit_of",
]

__version__: str
DEFAULT_TOLERANCE: float
DEFAULT_MAX_ITERATIONS: int
DEFAULT_CONNECTIVITY: int
MIN_GRID: int
DEFAULT_DISTANCE: float
DEFAULT_RUNNING_IN: float
DEFAULT_STEP_RUNNING_IN: int
DEFAULT_STEP: int
DEFAULT_PARTICLE_RULE: str
MAX_ESTIMATE_SAMPLES: int
PARTICLE_RULES: List[str]
SERIES_COLUMNS: List[str]
INTERVAL_LEVEL: float
KIM_EXPERIMENTAL_K: Tuple[float, float]
FIGURES: List[Tuple[str, str]]
KIM_SEVERITY_FIT: Tuple[float, float]
PAPER_SEVERITY_FIT: Tuple[float, float]
RESOLVED_PARTICLES: float

class WearsimError(Exception): ...
class NotConvergedError(WearsimError): ...

_F64Array = npt.NDArray[np.float64]

def generate_surface(
    grid: Union[int, Tuple[int, int]],
    length: float,
    hurst: float,
    lambda_lower: float,
    lambda_upper: float,
    rms_height: float,
    seed: int,
    generation: str = "random-phase",
) -> _F64Array: ...
def pair_seeds(seed: int) -> Tuple[int, int]: ...
def surface_statistics(heights: _F64Array, length: float) -> Dict[str, float]: ...
def radial_psd(heights: _F64Array, length: float) -> Tuple[_F64Array, _F64Array]: ...
def composite_heights(top: _F64Array, bottom: _F64Array, offset: int) -> _F64Array: ...
def metres_per(unit: str) -> float: ...
def read_surface(
    path: str,
    length: Optional[float] = None,
    length_y: Optional[float] = None,
    height_scale: float = 1.0,
    lateral_scale: float = 1.0,
    detrend: str = "none",
    taper: float = 0.0,
) -> Tuple[_F64Array, float, List[str], List[str]]: ...
def preprocess_surface(heights: _F64Array, detrend: str = "plane", taper: float = 0.0) -> _F64Array: ...
def periodicity(heights: _F64Array) -> Tuple[float, float]: ...
def fit_surface(
    heights: _F64Array, length: float, measured_pixel: Optional[Tuple[float, float]] = None
) -> Dict[str, Any]: ...
def poor_fit_warning(r2: Optional[float]) -> Optional[str]: ...
def spectrum_pair(
    map: _F64Array,
    length: float,
    grid: Union[int, Tuple[int, int]],
    box_length: float,
    seed: int,
    window: Optional[str] = None,
) -> Tuple[_F64Array, _F64Array, List[str]]: ...
def contact_map(pressure: _F64Array) -> npt.NDArray[np.bool_]: ...
def label_junctions(
    contact: npt.NDArray[np.bool_], connectivity: int = ...
) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.uint64], npt.NDArray[np.bool_]]: ...
def static_wear_model(junction_pixels: List[int], pixel_size: float, critical_diameter: float) -> Dict[str, float]: ...
def slide(
    top: _F64Array,
    bottom: _F64Array,
    length: float,
    material: Material,
    loads: List[float],
    modulus: str = "half-space",
    tolerance: float = ...,
    max_iterations: int = ...,
    connectivity: int = ...,
    distance: float = ...,
    running_in: float = ...,
    step_running_in: int = ...,
    step: int = ...,
    particle_rule: str = ...,
    device: str = "cpu",
    stopping: str = "settled-map",
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], None]] = None,
) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]: ...
def collect_study(out: Path) -> Tuple[int, int]: ...
def job_series(out: Path, job: int) -> Dict[str, Any]: ...
def junction_geometry(pixels: List[int], pixel_size: float) -> Tuple[_F64Array, _F64Array, _F64Array]: ...
def curves(columns: Dict[str, List[Any]]) -> Tuple[List[int], List[str]]: ...
def aggregate(columns: Dict[str, List[Any]]) -> Dict[str, Any]: ...
def equal_critical_diameter(curves: List[Tuple[float, float, float]], tolerance: float) -> List[List[int]]: ...
def unit_of(units: str, quantity: str) -> str: ...
def power_law_fit(x: List[float], y: List[float]) -> Optional[Tuple[float, float, Optional[float]]]: ...
def line_fit(x: List[float], y: List[float]) -> Optional[Tuple[float, float, Optional[float]]]: ...
def series_job(job: List[int], particles_in_fit: List[int]) -> Optional[int]: ...
def mean_interval(values: List[float]) -> Optional[Tuple[float, float, float, int]]: ...
def poisson_interval(count: int) -> Tuple[float, float, float]: ...
def curve_labels(columns: Dict[str, List[Any]]) -> List[str]: ...
def has_kim_materials(columns: Dict[str, List[Any]]) -> bool: ...
def severity_fits(
    columns: Dict[str, List[Any]],
) -> Tuple[List[Dict[str, Any]], Optional[Tuple[float, float, Optional[float]]]]: ...
def findings(columns: Dict[str, List[Any]]) -> Tuple[List[Dict[str, Any]], str, str]: ...
def table_figures(columns: Dict[str, List[Any]], names: Optional[List[str]] = None) -> List[Dict[str, Any]]: ...
def study_figures(out: Path, job: Optional[int] = None, names: Optional[List[str]] = None) -> List[Dict[str, Any]]: ...
def run_figure(
    entry: str,
    runs: List[Tuple[str, Dict[str, List[Any]], Optional[Dict[str, List[Any]]]]],
    load: Optional[float] = None,
    length_unit: str = "L",
) -> Dict[str, Any]: ...

@final
class Material:
    """Elastic and adhesive-wear properties of the (identical) materials of both surfaces.

    youngs_modulus E (reduced: 1; SI: Pa), poisson_ratio ν in (−1, 0.5), shear_strength τ̃ (unit of
    E), fracture_energies 𝒢 (reduced: E·L; SI: J/m²), geometry_factor f of eq. (1) (default 3).
    """

    def __new__(
        cls,
        youngs_modulus: float,
        poisson_ratio: float,
        shear_strength: float,
        fracture_energies: List[float] = ...,
        geometry_factor: float = 3.0,
    ) -> Material: ...
    @property
    def youngs_modulus(self) -> float: ...
    @property
    def poisson_ratio(self) -> float: ...
    @property
    def shear_strength(self) -> float: ...
    @property
    def fracture_energies(self) -> List[float]: ...
    @property
    def geometry_factor(self) -> float: ...
    @property
    def shear_modulus(self) -> float:
        """μ = E/(2(1+ν)) (unit of E)."""
    @property
    def flow_pressure(self) -> float:
        """p_m = 3√3 τ̃ (unit of E), the pressure bound of the saturated contact."""
    @property
    def critical_diameters(self) -> List[float]:
        """d* = 2 f 𝒢 μ / τ̃² per fracture energy (length unit), paper eq. (1)."""
    def critical_diameter(self, fracture_energy: float) -> float: ...
    def effective_modulus(self, modulus: str = "half-space") -> float:
        """E* = E/(1−ν²) ("half-space") or E/(2(1−ν²)) ("composite")."""

@final
class ContactSolver:
    def __new__(
        cls,
        grid: Union[int, Tuple[int, int]],
        length: float,
        effective_modulus: float,
        tolerance: float = ...,
        max_iterations: int = ...,
        boundary: str = ...,
        device: str = ...,
    ) -> ContactSolver: ...
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def length(self) -> float: ...
    @property
    def effective_modulus(self) -> float: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def max_iterations(self) -> int: ...
    @property
    def boundary(self) -> str: ...
    @property
    def device(self) -> str: ...
    def solve(
        self,
        heights: _F64Array,
        load: float,
        flow_pressure: float = ...,
        initial_pressure: Optional[_F64Array] = None,
    ) -> Tuple[_F64Array, _F64Array, _F64Array, Dict[str, Any]]: ...
    def displacement(self, pressure: _F64Array) -> _F64Array: ...

@final
class RunFile:
    def __new__(cls, path: Path) -> RunFile: ...
    @property
    def path(self) -> Path: ...
    @property
    def units(self) -> str: ...
    @property
    def length(self) -> float: ...
    @property
    def material(self) -> Material: ...
    @property
    def effective_modulus(self) -> float: ...
    @property
    def modulus(self) -> str: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def max_iterations(self) -> int: ...
    @property
    def connectivity(self) -> int: ...
    @property
    def loads(self) -> Optional[List[float]]: ...
    @property
    def particle_rule(self) -> Optional[str]: ...
    @property
    def device(self) -> str: ...
    def surfaces(self) -> Tuple[_F64Array, _F64Array]: ...
    def slide(
        self, threads: Optional[int] = None, progress: Optional[Callable[[int, int], None]] = None
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]: ...
    def estimate(
        self,
        samples: Optional[int] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[int, int], None]] = None,
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]: ...

@final
class Study:
    def __new__(cls, text: str, base: Path) -> Study: ...
    @property
    def text(self) -> str: ...
    @property
    def base(self) -> Path: ...
    @property
    def hash(self) -> str: ...
    def __len__(self) -> int: ...
    def jobs(self) -> Dict[str, Any]: ...
    def prepare(self, out: Path) -> List[int]: ...
    def run(
        self,
        out: Path,
        workers: Optional[int] = None,
        shard: Optional[Tuple[int, int]] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[int, int], None]] = None,
    ) -> Dict[str, Any]: ...
    def run_job(self, index: int, threads: Optional[int] = None) -> str: ...
    def write_result(self, out: Path, index: int, result: str) -> None: ...
