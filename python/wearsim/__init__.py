"""wearsim: adhesive wear of rough surfaces in dry sliding, after Brink, Frérot & Molinari,
J. Mech. Phys. Solids 147 (2021) 104238, for NumPy users.

The data flow follows the paper, one module per step:

- :mod:`wearsim.surface`: periodic self-affine surfaces (NumPy arrays), measured height maps read
  and prepared, their statistics and fitted self-affine parameters, and periodic pairs that carry
  a measured map's 2D spectrum;
- :class:`Material`: elastic and adhesive-wear properties, flow pressure p_m = 3√3 τ̃ and
  critical diameter d*;
- :mod:`wearsim.contact`: the saturated-pressure FFT contact solver;
- :mod:`wearsim.junctions`: junctions (periodic connected components of the contact map);
- :mod:`wearsim.wear`: the static model and the sliding model (pandas series, summary dict);
- :mod:`wearsim.study`: study files, run locally or as Dask tasks, collected into tidy tables;
- :mod:`wearsim.plot`: the paper's figures on matplotlib, from a study's tidy table;
- :mod:`wearsim.measured`: instrument height maps (every format SurfaceTopography reads) imported as
  a run's two bodies; :mod:`wearsim.fields`: the per-step fields of a sliding run as xarray and
  NetCDF.

Units: every quantity is in the unit system of its inputs. In reduced units E = 1 and L = 1
(pressures in E, lengths in L, loads in E·L², fracture energies in E·L); in SI, Pa, m, N and J/m².

Long calls release the GIL and stop on Ctrl-C (KeyboardInterrupt).
"""

from typing import TYPE_CHECKING, Any

from . import contact, junctions, plot, study, surface, wear
from ._wearsim import (
    DEFAULT_CONNECTIVITY,
    DEFAULT_DISTANCE,
    DEFAULT_MAX_ITERATIONS,
    DEFAULT_PARTICLE_RULE,
    DEFAULT_RUNNING_IN,
    DEFAULT_STEP,
    DEFAULT_STEP_RUNNING_IN,
    DEFAULT_TOLERANCE,
    Material,
    NotConvergedError,
    WearsimError,
    __version__,
)
from .contact import ContactResult, ContactSolver, solve_contact
from .junctions import Junctions, label_junctions
from .surface import (
    composite_heights,
    fit_surface,
    generate_pair,
    generate_surface,
    heights_and_length,
    periodicity,
    preprocess_surface,
    radial_psd,
    read_surface,
    spectrum_pair,
    surface_statistics,
)
from .wear import ResolutionWarning, RunFile, estimate, load_run, slide, static_wear

if TYPE_CHECKING:
    from . import fields, measured
else:

    def __getattr__(name: str) -> Any:
        """``wearsim.measured`` and ``wearsim.fields``, imported on first use: imported with the
        package, they would already be loaded when ``python -m wearsim.measured`` (what ``wearsim
        surface import`` runs) starts them as a program, which Python warns about."""
        if name in ("measured", "fields"):
            import importlib

            return importlib.import_module(f".{name}", __name__)
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "DEFAULT_CONNECTIVITY",
    "DEFAULT_DISTANCE",
    "DEFAULT_MAX_ITERATIONS",
    "DEFAULT_PARTICLE_RULE",
    "DEFAULT_RUNNING_IN",
    "DEFAULT_STEP",
    "DEFAULT_STEP_RUNNING_IN",
    "DEFAULT_TOLERANCE",
    "ContactResult",
    "ContactSolver",
    "Junctions",
    "Material",
    "NotConvergedError",
    "ResolutionWarning",
    "RunFile",
    "WearsimError",
    "__version__",
    "composite_heights",
    "contact",
    "estimate",
    "fields",
    "fit_surface",
    "generate_pair",
    "generate_surface",
    "heights_and_length",
    "junctions",
    "label_junctions",
    "load_run",
    "measured",
    "periodicity",
    "plot",
    "preprocess_surface",
    "radial_psd",
    "read_surface",
    "slide",
    "solve_contact",
    "spectrum_pair",
    "static_wear",
    "study",
    "surface",
    "surface_statistics",
    "wear",
]
