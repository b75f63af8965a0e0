"""The wear models: the static model (Frérot et al. 2018; paper §2) and the sliding model
(paper §3).

The sliding model returns its series as a :class:`pandas.DataFrame` (one row per step, load and
fracture energy, the columns of ``series.csv``) and its summary as a dict (``summary.json`` of
``wearsim slide``: inputs, flow pressure, critical diameters, solver statistics and, under
``"results"``, one entry per load and fracture energy with the wear rate W, its R², the Archard
coefficient k, the particle rate dN*₊/ds, V₀ and the static model's k_static).
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

from . import _args, _wearsim
from ._progress import ProgressArg, callback
from .junctions import Junctions
from .surface import SQUARE_PIXELS, _is_topography, as_heights

#: Columns of the series, in order: those of ``series.csv`` (defined once, in the library).
SERIES_COLUMNS = list(_wearsim.SERIES_COLUMNS)

#: The particle rules a run can name (``particle_rule``; ``[sliding] particle_rule`` in a run file),
#: the paper's (§3) first (defined once, in the library).
PARTICLE_RULES = list(_wearsim.PARTICLE_RULES)


def _particle_rule(rule: Union[str, Mapping[str, Any]]) -> str:
    """A particle rule with its parameters as the library reads it: ``name`` or ``name(key=value, …)``."""
    if isinstance(rule, str):
        return rule
    if not isinstance(rule, Mapping) or not isinstance(rule.get("name"), str):
        raise ValueError(
            f"invalid `particle_rule`: {rule!r} is neither a rule's name nor a mapping with a `name`; "
            'write e.g. "interacting" or {"name": "interacting", "reach": 2}'
        )
    parameters = ", ".join(f"{key}={value}" for key, value in rule.items() if key != "name")
    return f"{rule['name']}({parameters})" if parameters else rule["name"]


def static_wear(junctions: Junctions, critical_diameter: float) -> Dict[str, float]:
    """Static model on one contact solution: ``wear_coefficient`` k_static = Σ_{A_i ≥ A*} A_i / Σ A_i
    and ``wear_rate_over_omega`` = k_static Σ A_i (volume per sliding distance over the shape factor
    ω), with A* = π d*²/4; also the counts ``junctions`` and ``critical_junctions`` (A_i ≥ A*).
    ``critical_diameter`` d* in the unit of the pixel size."""
    return _wearsim.static_wear_model(
        [int(p) for p in junctions.pixels], junctions.pixel_size, float(critical_diameter)
    )


def _series(columns: Dict[str, np.ndarray]) -> pd.DataFrame:
    return pd.DataFrame({c: columns[c] for c in SERIES_COLUMNS})


class ResolutionWarning(UserWarning):
    """A result is under-resolved or undefined: d* or λ_l of a few pixels, no or few particles after
    running-in, a poor fit. The same sentences are in ``summary["warnings"]``."""


def _warn(summary: Dict[str, Any]) -> None:
    for message in summary.get("warnings", []):
        warnings.warn(message, ResolutionWarning, stacklevel=3)


def _pair_length(top: Any, lx_top: float, bottom: Any, lx_bottom: float) -> float:
    """The side Lx of a surface pair passed without ``length``: a topography's (in metres when it
    states its unit); the two topographies of a pair must agree on it."""
    top_sized, bottom_sized = _is_topography(top), _is_topography(bottom)
    if top_sized and bottom_sized and abs(lx_top - lx_bottom) > SQUARE_PIXELS * max(lx_top, lx_bottom):
        raise ValueError(
            f"invalid `bottom`: its side along x is {lx_bottom:.6g} but the top's is {lx_top:.6g} (each in metres "
            "when its topography states a unit); the two surfaces of a pair share one box: give both the same "
            "physical size (and unit), or pass `length`"
        )
    return lx_bottom if bottom_sized and not top_sized else lx_top


def slide(
    top: Any,
    bottom: Any,
    material: _wearsim.Material,
    loads: Sequence[float],
    *,
    length: Optional[float] = None,
    modulus: str = "half-space",
    tolerance: float = _wearsim.DEFAULT_TOLERANCE,
    max_iterations: int = _wearsim.DEFAULT_MAX_ITERATIONS,
    connectivity: int = _wearsim.DEFAULT_CONNECTIVITY,
    distance: float = _wearsim.DEFAULT_DISTANCE,
    running_in: float = _wearsim.DEFAULT_RUNNING_IN,
    step_running_in: int = _wearsim.DEFAULT_STEP_RUNNING_IN,
    step: int = _wearsim.DEFAULT_STEP,
    particle_rule: Union[str, Mapping[str, Any]] = _wearsim.DEFAULT_PARTICLE_RULE,
    device: str = "cpu",
    stopping: str = "settled-map",
    threads: Optional[int] = None,
    progress: ProgressArg = None,
) -> Tuple[pd.DataFrame, Dict[str, Any]]:
    """Slides ``top`` over ``bottom`` along x and runs the sliding wear model for every normal load in
    ``loads`` (F_N, pressure × length²) and every fracture energy of ``material``. ``top`` and
    ``bottom`` are height arrays (length unit) of one shape (Nx, Ny) with side ``length`` along x
    (default 1) and square pixels, or SurfaceTopography topographies, whose physical size gives
    ``length`` (both converted to metres when the topography states its ``unit``; a ``length`` passed
    with one is then taken in metres too). Masked or non-finite heights and non-square pixels are
    refused (see :mod:`wearsim.surface`).

    Schedule (paper §3): offsets from 0 in steps of ``step_running_in`` pixels up to the running-in
    distance ``running_in``·Lx, then in steps of ``step`` pixels up to ``distance``·Lx; each step is a
    contact solve warm-started from the previous one, which stops once its contact map is settled
    (``stopping="settled-map"``; ``"tolerance"`` solves every step to ``tolerance``: the same contact
    maps, and so the same wear results, with about a third more iterations). ``modulus``:
    "half-space" (E* = E/(1−ν²)) or "composite" (E* = E/(2(1−ν²))). ``particle_rule`` names the rule
    that turns each step's junctions into particles, one of :data:`PARTICLE_RULES` (default: the
    paper's, §3), with its parameters as a run file's ``[sliding.particle_rule]`` table gives them:
    ``{"name": "interacting", "reach": 2}``, or written ``"interacting(reach=2)"``. ``device``: where
    the contact solver computes, "cpu" (or "cuda", in builds with a GPU backend); recorded in the
    summary. ``threads`` runs on that many threads (default: all).
    ``progress``: True prints steps done on stderr; a callable gets ``(steps done, total)``.

    Returns ``(series, summary)``: series with the columns :data:`SERIES_COLUMNS` (s in the length
    unit, volume in length³, contact_area as a fraction of Lx Ly), summary as described in the module
    documentation.
    """
    top_heights, lx = as_heights("top", top, length)
    bottom_heights, lx_bottom = as_heights("bottom", bottom, length)
    if length is None:
        lx = _pair_length(top, lx, bottom, lx_bottom)
    columns, summary = _wearsim.slide(
        top_heights,
        bottom_heights,
        lx,
        material,
        _args.floats("loads", loads),
        modulus,
        tolerance,
        _args.count("max_iterations", max_iterations),
        _args.count("connectivity", connectivity, fix=" (4 or 8)"),
        distance,
        running_in,
        _args.count("step_running_in", step_running_in),
        _args.count("step", step),
        _particle_rule(particle_rule),
        device,
        stopping,
        _args.optional_count("threads", threads, 1, fix=", or None for all cores"),
        callback(progress, "slide: step"),
    )
    _warn(summary)
    return _series(columns), summary


class RunFile:
    """A run file (``[surface]``, ``[material]``, ``[contact]``, ``[sliding]`` and
    ``units``), parsed and validated as ``wearsim`` does; relative surface paths resolve against the
    file's folder."""

    def __init__(self, path: Union[str, os.PathLike]) -> None:
        self._run = _wearsim.RunFile(Path(path))

    path = property(lambda self: self._run.path, doc="The run file.")
    units = property(lambda self: self._run.units, doc='Length unit: "L" (reduced) or "m" (SI).')
    length = property(lambda self: self._run.length, doc="Side length L of the surfaces.")
    material = property(lambda self: self._run.material, doc="The run's :class:`wearsim.Material`.")
    effective_modulus = property(lambda self: self._run.effective_modulus, doc="E* under the run's convention.")
    modulus = property(lambda self: self._run.modulus, doc='"half-space" or "composite".')
    tolerance = property(lambda self: self._run.tolerance, doc="Contact solver tolerance.")
    connectivity = property(lambda self: self._run.connectivity, doc="Junction connectivity, 4 or 8.")
    loads = property(lambda self: self._run.loads, doc="Normal loads of [sliding], or None.")
    particle_rule = property(lambda self: self._run.particle_rule, doc="The particle rule of [sliding], or None.")
    device = property(lambda self: self._run.device, doc='Where the contact solver computes: "cpu".')

    def surfaces(self) -> Tuple[np.ndarray, np.ndarray]:
        """The (top, bottom) surfaces, generated or read as the run file says."""
        return self._run.surfaces()

    def slide(
        self, *, threads: Optional[int] = None, progress: ProgressArg = None
    ) -> Tuple[pd.DataFrame, Dict[str, Any]]:
        """The sliding model exactly as ``wearsim slide RUN`` runs it: ``(series, summary)`` equal to
        its ``series.csv`` and ``summary.json`` (timings aside). ``progress`` as for :func:`slide`."""
        threads = _args.optional_count("threads", threads, 1, fix=", or None for all cores")
        columns, summary = self._run.slide(threads, callback(progress, "slide: step"))
        _warn(summary)
        return _series(columns), summary

    def estimate(
        self, *, samples: Optional[int] = None, threads: Optional[int] = None, progress: ProgressArg = None
    ) -> Tuple[pd.DataFrame, Dict[str, Any]]:
        """The static estimate exactly as ``wearsim estimate RUN`` makes it (see :func:`estimate`)."""
        samples = _args.optional_count(
            "samples",
            samples,
            1,
            _wearsim.MAX_ESTIMATE_SAMPLES,
            " static maps per load, or None to choose them by the sampling error",
        )
        threads = _args.optional_count("threads", threads, 1, fix=", or None for all cores")
        columns, summary = self._run.estimate(samples, threads, callback(progress, "estimate: solve"))
        _warn(summary)
        return pd.DataFrame(columns), summary

    def __repr__(self) -> str:
        return f"RunFile({str(self.path)!r})"


def load_run(path: Union[str, os.PathLike]) -> RunFile:
    """Reads and validates a run file."""
    return RunFile(path)


def estimate(
    run: Union[str, os.PathLike, RunFile],
    *,
    samples: Optional[int] = None,
    threads: Optional[int] = None,
    progress: ProgressArg = None,
) -> Tuple[pd.DataFrame, Dict[str, Any]]:
    """A static estimate of the sliding model's wear rate W, Archard coefficient k and particle rate
    dN*₊/ds for every load and fracture energy of a run file, from a few static contact solutions
    instead of a sliding run (Brink, Frérot & Molinari 2021, §5 outlook): N* and the critical
    junctions' mean diameter d̄ from static maps at offsets spread over the box, a critical
    junction's residence R = c₁ d̄ (1 + c₂ θ) with θ = N* d̄²/(Lx Ly), dN*₊/ds = N*/R,
    W = c_v (π/6) d*³ dN*₊/ds and k = W p_m/F_N, the constants calibrated on sliding runs
    (``summary["calibration"]``).

    Returns ``(results, summary)``: one row per load and fracture energy with ``wear_rate``,
    ``wear_coefficient`` and ``particle_rate`` and their ``_low``/``_high`` 95 % interval for a
    sliding run of the same box and distance (NaN where the setting lies outside the calibrated
    domain — measured or other surfaces, a short running-in, a contact fraction or N* per map
    beyond the calibration's —, with ``interval_withheld`` naming why), and the static features
    (``critical_junctions_mean``, its ``critical_junctions_sampling_error``,
    ``mean_critical_diameter``, ``critical_coverage``, ``critical_residence``,
    ``expected_particles``); the summary equals ``wearsim estimate``'s
    ``summary.json`` and is marked ``"model": "estimate"``. ``samples`` fixes the static maps per
    load (1 to 16; default: from 4 until N*'s sampling error is at most 10 %). It is an estimate, not
    a sliding run: it gives no wear-volume curve, running-in or memory, and its warnings (also
    issued as :class:`ResolutionWarning`) say where it rests on few junctions.
    """
    run_file = run if isinstance(run, RunFile) else RunFile(run)
    return run_file.estimate(samples=samples, threads=threads, progress=progress)
