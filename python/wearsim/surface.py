"""Rough surfaces as NumPy arrays: periodic self-affine surfaces (paper §4.1), measured height
maps read and prepared, and the self-affine parameters fitted to either.

Arrays are ``(Nx, Ny)`` float64 with square pixels, ``h[i, j]`` with i along the sliding direction
x; ``length`` is the side Lx along x, in the unit of lengths (L in reduced units, m in SI).
Functions that take heights also take a SurfaceTopography topography object (its
``heights()`` and ``physical_sizes``), so every instrument format SurfaceTopography reads works. A
topography that states its ``unit`` (µm, nm, …) is converted to metres, heights and size alike, so
that it meets SI material properties; one without a unit is taken as it is.
"""

from __future__ import annotations

import functools
import os
import warnings
from typing import Any, Dict, Literal, Optional, Tuple, Union

import numpy as np

from . import _args, _wearsim

Generation = Literal["random-phase", "filtered-noise"]


GridSize = Union[int, Tuple[int, int]]
Detrend = Literal["none", "mean", "plane", "curvature"]


def _float_grid(name: str, a: Any) -> np.ndarray:
    """A 2-D field (heights, pressure; any array-like) as a contiguous float64 array, for the
    extension module."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim != 2:
        raise ValueError(f"invalid `{name}`: a 2-D array is needed, got {a.ndim} dimensions")
    return a


def _is_topography(obj: Any) -> bool:
    """Whether ``obj`` looks like a SurfaceTopography topography (heights() and physical_sizes)."""
    return callable(getattr(obj, "heights", None)) and hasattr(obj, "physical_sizes")


def as_heights(name: str, surface: Any, length: Optional[float] = None) -> Tuple[np.ndarray, float]:
    """``(heights, length)`` of an array-like with its side ``length`` (default 1), or of a
    SurfaceTopography topography, whose ``physical_sizes`` give the side; a topography with a
    ``unit`` comes back in metres (a ``length`` passed here is taken in metres too)."""
    if _is_topography(surface):
        heights = _float_grid(name, surface.heights())
        if not np.all(np.isfinite(heights)):
            raise ValueError(
                f"invalid `{name}`: the topography has missing or non-finite heights; fill or crop them "
                "(SurfaceTopography's interpolate_undefined_data, or a crop) first"
            )
        unit = getattr(surface, "unit", None)
        scale = _wearsim.metres_per(str(unit)) if unit else 1.0
        if scale != 1.0:
            heights = heights * scale
        sizes = surface.physical_sizes
        if length is None:
            if sizes is None:
                raise ValueError(f"invalid `{name}`: the topography has no physical size; pass `length`")
            length = float(sizes[0]) * scale
        return heights, float(length)
    return _float_grid(name, surface), 1.0 if length is None else float(length)


def generate_surface(
    grid: GridSize,
    *,
    length: float = 1.0,
    hurst: float = 0.7,
    lambda_lower: float,
    lambda_upper: float,
    rms_height: float,
    seed: int = 0,
    generation: Generation = "random-phase",
) -> np.ndarray:
    """One periodic self-affine surface of ``grid`` pixels (N for N × N, or (Nx, Ny)) with side
    ``length`` along x and square pixels.

    Power spectrum ∝ q^(−2(1+H)) between the wavelengths ``lambda_upper`` (roll-off below it) and
    ``lambda_lower`` (cut-off), scaled to exactly ``rms_height``; lengths in the unit of ``length``.
    The same seed gives the same surface whatever the thread count.
    """
    return _wearsim.generate_surface(
        _args.grid_size(grid),
        length,
        hurst,
        lambda_lower,
        lambda_upper,
        rms_height,
        _args.seed("seed", seed),
        generation,
    )


def generate_pair(
    grid: GridSize,
    *,
    length: float = 1.0,
    hurst: float = 0.7,
    lambda_lower: float,
    lambda_upper: float,
    rms_height: float,
    seed: int = 0,
    generation: Generation = "random-phase",
) -> Tuple[np.ndarray, np.ndarray]:
    """The (top, bottom) surface pair of a run file with this ``seed``: two independent surfaces
    whose seeds are derived from ``seed`` exactly as ``wearsim surface`` does."""
    top_seed, bottom_seed = _wearsim.pair_seeds(_args.seed("seed", seed))
    make = functools.partial(
        generate_surface,
        _args.grid_size(grid),
        length=length,
        hurst=hurst,
        lambda_lower=lambda_lower,
        lambda_upper=lambda_upper,
        rms_height=rms_height,
        generation=generation,
    )
    return make(seed=top_seed), make(seed=bottom_seed)


def surface_statistics(heights: Any, length: Optional[float] = None) -> Dict[str, float]:
    """RMS height (unit of the heights) and RMS slope (dimensionless, spectral) of a periodic
    surface of side ``length`` along x (default 1, or a topography's size), with its grid (pixels
    along x and y) and pixel size."""
    h, lx = as_heights("heights", heights, length)
    return _wearsim.surface_statistics(h, lx)


def radial_psd(heights: Any, length: Optional[float] = None) -> Tuple[np.ndarray, np.ndarray]:
    """Radially averaged power spectral density: (q, C(q)), q the wavenumber in cycles per
    ``length`` along x (q = Lx/λ), C in height² (as ``wearsim surface`` writes it)."""
    h, lx = as_heights("heights", heights, length)
    return _wearsim.radial_psd(h, lx)


def read_surface(
    path: Union[str, "os.PathLike[str]"],
    *,
    length: Union[None, float, Tuple[float, float]] = None,
    height_unit: Optional[str] = None,
    lateral_unit: Optional[str] = None,
    detrend: Detrend = "none",
    taper: float = 0.0,
) -> Tuple[np.ndarray, float]:
    """Reads a height map as a run file's ``top``/``bottom`` is read: ``.npy``, ``.npz``, a text or
    CSV matrix, or x y z columns on a regular grid. Returns ``(heights, length)``, length the side
    along x.

    ``length``: the physical size, Lx or (Lx, Ly), in the unit of the result; column files state it
    themselves. ``height_unit`` (m, mm, um, nm, pm, A) converts the heights to metres, and
    ``lateral_unit`` (default ``height_unit``) the coordinates of a column file. Odd sides lose their
    last row or column. ``detrend`` removes the mean, the plane or a quadratic; ``taper`` brings a
    fraction of each side smoothly to the mean (see :func:`preprocess_surface`). A surface far from
    periodic draws a warning (see :func:`periodicity`).
    """
    lx, ly = (length if isinstance(length, tuple) else (length, None)) if length is not None else (None, None)
    height_scale = 1.0 if height_unit is None else _wearsim.metres_per(height_unit)
    lateral = lateral_unit if lateral_unit is not None else height_unit
    lateral_scale = 1.0 if lateral is None else _wearsim.metres_per(lateral)
    heights, lx_read, _notes, warned = _wearsim.read_surface(
        os.fspath(path), lx, ly, height_scale, lateral_scale, detrend, taper
    )
    for w in warned:
        warnings.warn(w, stacklevel=2)
    return heights, lx_read


def preprocess_surface(heights: Any, *, detrend: Detrend = "plane", taper: float = 0.0) -> np.ndarray:
    """A levelled copy of a measured height map: ``detrend`` removes the mean, the least-squares
    plane (tilt) or quadratic (tilt and form); ``taper`` (a fraction of each side, 0 to 1) applies a
    Tukey window that brings the borders smoothly to the mean, so that the periodic contact solution
    sees no ridge at the border, at the cost of flattening that strip."""
    h, _ = as_heights("heights", heights)
    return _wearsim.preprocess_surface(h, detrend, taper)


def periodicity(heights: Any) -> Tuple[float, float]:
    """How far a height map is from periodic: the RMS jump across the border along x and along y,
    each divided by the RMS step between neighbouring pixels inside (about 1 when periodic; above 3,
    ``wearsim`` warns)."""
    h, _ = as_heights("heights", heights)
    return _wearsim.periodicity(h)


def fit_surface(heights: Any, length: Optional[float] = None) -> Dict[str, Any]:
    """Self-affine parameters of a surface from its radially averaged PSD C(q) (paper §4.1:
    C(q) ∝ q^(−2(1+H)) between q = 2π/λ_u and 2π/λ_l).

    The floor of the PSD is left out first: shells below 1e-12 of the peak (round-off) and shells
    within a factor 10 of the median PSD over the outermost half octave of wavenumbers (round-off
    beyond λ_l of a band-limited surface, white noise of a measurement). The power law is fitted on
    the widest band of at least 6 shells over an octave that follows one line in log–log, falls
    faster than q⁻¹ and lies under no longer wavelength (the leakage of a levelled map beyond λ_l
    does), so that a floor is never read as the self-affine band. A spectrum without such a band
    raises ``ValueError``.

    Returns ``hurst`` H (from the slope −2(1+H)), ``lambda_lower`` and ``lambda_upper`` (where the
    PSD leaves the power law at short and long wavelengths), ``rms_height``, ``r2`` of the log–log
    fit, the number of ``shells`` it used and their wavenumbers ``fitted_q`` (first and last,
    q = 2π/λ in radians per unit length), the shells left out at longer wavelengths than λ_u
    (``shells_longer``) and at shorter wavelengths than λ_l (``shells_shorter``), and ``floor``, the
    floor's level relative to the power law at λ_l. Pass the parameters to :func:`generate_pair` to
    get periodic surfaces with the measured statistics (the paper's model assumes periodic
    self-affine surfaces)."""
    h, lx = as_heights("heights", heights, length)
    return _wearsim.fit_surface(h, lx)


def composite_heights(top: np.ndarray, bottom: np.ndarray, offset: int = 0) -> np.ndarray:
    """Height of Johnson's equivalent rigid surface at a sliding offset of ``offset`` pixels along
    x: ``bottom + np.roll(top, offset, axis=0)``."""
    if offset < 0:
        raise ValueError(f"invalid `offset`: {offset} must be a non-negative number of pixels")
    return _wearsim.composite_heights(_float_grid("top", top), _float_grid("bottom", bottom), offset)
