"""Periodic self-affine rough surfaces (paper §4.1) as NumPy arrays, and their statistics.

Arrays are ``(N, N)`` float64, ``h[i, j]`` with i along the sliding direction x; lengths in the unit
of ``length`` (L in reduced units, m in SI).
"""

from __future__ import annotations

import functools
from typing import Dict, Literal, Tuple

import numpy as np

from . import _wearsim

Generation = Literal["random-phase", "filtered-noise"]


def _float_grid(name: str, a: np.ndarray) -> np.ndarray:
    """A 2-D field (heights, pressure) as a contiguous float64 array, for the extension module."""
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim != 2:
        raise ValueError(f"invalid `{name}`: a 2-D array is needed, got {a.ndim} dimensions")
    return a


def generate_surface(
    grid: int,
    *,
    length: float = 1.0,
    hurst: float = 0.7,
    lambda_lower: float,
    lambda_upper: float,
    rms_height: float,
    seed: int = 0,
    generation: Generation = "random-phase",
) -> np.ndarray:
    """One periodic self-affine surface of ``grid``² pixels over a square of side ``length``.

    Power spectrum ∝ q^(−2(1+H)) between the wavelengths ``lambda_upper`` (roll-off below it) and
    ``lambda_lower`` (cut-off), scaled to exactly ``rms_height``; lengths in the unit of ``length``.
    The same seed gives the same surface whatever the thread count.
    """
    return _wearsim.generate_surface(grid, length, hurst, lambda_lower, lambda_upper, rms_height, seed, generation)


def generate_pair(
    grid: int,
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
    top_seed, bottom_seed = _wearsim.pair_seeds(seed)
    make = functools.partial(
        generate_surface,
        grid,
        length=length,
        hurst=hurst,
        lambda_lower=lambda_lower,
        lambda_upper=lambda_upper,
        rms_height=rms_height,
        generation=generation,
    )
    return make(seed=top_seed), make(seed=bottom_seed)


def surface_statistics(heights: np.ndarray, length: float = 1.0) -> Dict[str, float]:
    """RMS height (unit of the heights) and RMS slope (dimensionless, spectral) of a periodic
    surface of side ``length``, with its grid and pixel size."""
    return _wearsim.surface_statistics(_float_grid("heights", heights), length)


def radial_psd(heights: np.ndarray, length: float = 1.0) -> Tuple[np.ndarray, np.ndarray]:
    """Radially averaged power spectral density: (q, C(q)), q the wavenumber in cycles per
    ``length`` (q = L/λ), C in height² (as ``wearsim surface`` writes it)."""
    return _wearsim.radial_psd(_float_grid("heights", heights), length)


def composite_heights(top: np.ndarray, bottom: np.ndarray, offset: int = 0) -> np.ndarray:
    """Height of Johnson's equivalent rigid surface at a sliding offset of ``offset`` pixels along
    x: ``bottom + np.roll(top, offset, axis=0)``."""
    if offset < 0:
        raise ValueError(f"invalid `offset`: {offset} must be a non-negative number of pixels")
    return _wearsim.composite_heights(_float_grid("top", top), _float_grid("bottom", bottom), offset)
