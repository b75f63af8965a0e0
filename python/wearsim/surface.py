"""Rough surfaces as NumPy arrays: periodic self-affine surfaces (paper §4.1), measured height
maps read and prepared, the self-affine parameters fitted to either (with a verdict on whether the
spectrum is self-affine), and periodic surfaces that carry a measured map's 2D spectrum.

Arrays are ``(Nx, Ny)`` float64 with square pixels, ``h[i, j]`` with i along the sliding direction
x; ``length`` is the side Lx along x, in the unit of lengths (L in reduced units, m in SI), so an
array passed with its ``length`` is square-pixel by definition (Ly = Lx Ny/Nx).

Functions that take heights also take a SurfaceTopography topography object (its
``heights()``, ``physical_sizes`` and ``unit``), so every instrument format SurfaceTopography reads
works. A topography that states its ``unit`` (µm, nm, …) is converted to metres, heights and size
alike, so that it meets SI material properties; one without a unit is taken as it is.
:func:`heights_and_length` gives both in that one unit; :func:`preprocess_surface` returns heights
only (in metres for a topography with a unit, while its ``physical_sizes`` stay in its own unit).

Every height must be defined: masked pixels (a ``numpy.ma.MaskedArray``, as SurfaceTopography
returns for a map with undefined data), NaN and infinities are refused with their count; fill them
(SurfaceTopography's ``interpolate_undefined_data()``) or crop them away first. A topography whose
pixels are not square (``physical_sizes[0]/nb_grid_pts[0]`` ≠ ``physical_sizes[1]/nb_grid_pts[1]``)
is refused too: resample it onto square pixels, or crop it and pass the array with its ``length``.
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
Window = Literal["hann", "none"]


#: Relative difference between a topography's pixel sizes along x and y beyond which its pixels are
#: not square.
SQUARE_PIXELS = 1e-6

_FILL = (
    "fill them (SurfaceTopography's `topography.interpolate_undefined_data()`) or crop the map to a region "
    "without them, and pass that"
)


def _float_grid(name: str, a: Any) -> np.ndarray:
    """A 2-D field (heights, pressure; any array-like) as a contiguous float64 array, for the
    extension module, with every value defined: a masked pixel (``numpy.ma``, as SurfaceTopography
    returns undefined data), NaN or an infinity is refused with their count, never read."""
    masked = 0
    if np.ma.isMaskedArray(a):
        masked = int(np.ma.count_masked(a))
        a = np.ma.getdata(a)
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim != 2:
        raise ValueError(f"invalid `{name}`: a 2-D array is needed, got {a.ndim} dimensions")
    if masked == 0 and np.isfinite(a).all():
        return a
    bad = int(np.count_nonzero(~np.isfinite(a)))
    what = []
    if masked:
        what.append(f"{masked} masked (undefined)")
    if bad:
        what.append(f"{bad} NaN or infinite")
    raise ValueError(
        f"invalid `{name}`: {' and '.join(what)} of its {a.size} pixels ({a.shape[0]}×{a.shape[1]}); "
        f"wearsim needs every value defined: {_FILL}"
    )


def _is_topography(obj: Any) -> bool:
    """Whether ``obj`` looks like a SurfaceTopography topography (heights() and physical_sizes)."""
    return callable(getattr(obj, "heights", None)) and hasattr(obj, "physical_sizes")


def _square_pixels(name: str, sizes: Any, grid: Tuple[int, int], unit: str) -> None:
    """Refuses a topography whose pixels are not square (its physical sizes over its grid points)."""
    if sizes is None or len(sizes) < 2:
        return
    (lx, ly), (nx, ny) = (float(sizes[0]), float(sizes[1])), grid
    px, py = lx / nx, ly / ny
    if abs(px - py) > SQUARE_PIXELS * max(abs(px), abs(py)):
        u = f" {unit}" if unit else ""
        raise ValueError(
            f"invalid `{name}`: the topography's pixels are not square: {px:.6g}{u} along x "
            f"(physical_sizes[0] / nb_grid_pts[0] = {lx:g} / {nx}) and {py:.6g}{u} along y "
            f"({ly:g} / {ny}); wearsim's grids have square pixels, so its side along y would be taken as "
            f"{px * ny:.6g}{u} instead of {ly:g}{u}: resample it onto square pixels (e.g. evaluate "
            "SurfaceTopography's `topography.interpolate_bicubic()` on a square grid), or crop it, and pass "
            "the array with `length`, its side along x"
        )


def as_heights(name: str, surface: Any, length: Optional[float] = None) -> Tuple[np.ndarray, float]:
    """``(heights, length)`` of an array-like with its side ``length`` along x (default 1; its pixels
    are square by definition), or of a SurfaceTopography topography, whose ``physical_sizes`` give
    the side. A topography with a ``unit`` comes back in metres, heights and side alike; a
    ``length`` passed with it overrides its size and is taken in metres too. Masked or non-finite
    heights and a topography with non-square pixels are refused (``ValueError`` naming ``name``)."""
    if not _is_topography(surface):
        return _float_grid(name, surface), 1.0 if length is None else float(length)
    heights = _float_grid(name, surface.heights())
    unit = getattr(surface, "unit", None)
    unit = str(unit) if unit else ""
    scale = _wearsim.metres_per(unit) if unit else 1.0
    if scale != 1.0:
        heights = heights * scale
    sizes = surface.physical_sizes
    grid = getattr(surface, "nb_grid_pts", None)
    grid = heights.shape if grid is None else tuple(grid)
    _square_pixels(name, sizes, (int(grid[0]), int(grid[1])), unit)
    if length is None:
        if sizes is None:
            raise ValueError(f"invalid `{name}`: the topography has no physical size; pass `length`")
        return heights, float(sizes[0]) * scale
    length = float(length)
    if scale != 1.0 and sizes is not None and length == float(sizes[0]):
        raise ValueError(
            f"invalid `length` of `{name}`: {length:g} is the topography's side in its unit ({unit}), but a "
            f"`length` passed with a topography that states its unit is taken in metres, as its heights are "
            f"converted (its side is {length * scale:.6g} m); leave `length` out to use the topography's size"
        )
    return heights, length


def heights_and_length(surface: Any, length: Optional[float] = None) -> Tuple[np.ndarray, float]:
    """``(heights, length)`` of a height map in one unit, as every function here takes it: a
    SurfaceTopography topography that states its ``unit`` gives heights and its side along x in
    metres (its ``physical_sizes`` stay in its own unit); one without a unit, or an array with its
    ``length`` (default 1), gives them as they are. Pass the pair on, e.g.
    ``h, lx = heights_and_length(t)`` then ``slide(preprocess_surface(h), ..., length=lx)``.

    Refuses (``ValueError``) masked or non-finite heights and non-square pixels (see the module
    documentation)."""
    return as_heights("surface", surface, length)


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


def spectrum_pair(
    map: Any,
    length: Optional[float] = None,
    *,
    grid: GridSize,
    box_length: Optional[float] = None,
    seed: int = 0,
    window: Optional[Window] = None,
) -> Tuple[np.ndarray, np.ndarray]:
    """The (top, bottom) surface pair of a run file with ``[surface] source = "spectrum"`` whose
    ``map`` is this height map: two periodic surfaces of ``grid`` pixels (N for N × N, or
    (Nx, Ny)) and side ``box_length`` along x (default: the map's side; square pixels) that carry
    the measured 2D PSD of ``map`` as it is (a lay, a roll-off, a peak: not only a power law), with
    random phases. The same ``seed`` gives the same surfaces, bit for bit, as ``wearsim surface`` on
    such a run file (top and bottom seeds derived from it as :func:`generate_pair` derives them).
    Use it where :func:`fit_surface` finds the spectrum not self-affine.

    ``map`` is an array with its side ``length`` along x (default 1), or a SurfaceTopography
    topography (its size, in metres when it states its unit, as :func:`heights_and_length` gives
    it); ``box_length`` is in that same unit. Every height must be defined and the pixels square
    (see the module documentation). ``window``: ``"hann"`` (plane levelled, Hann window: a map
    that is not periodic, whose border jump would leak power into every wavevector) or ``"none"``
    (mean levelled: a periodic map); by default chosen from the map's periodicity, as the run file
    does. The map's PSD is that of its own wavevectors: a box larger than the map, or a pixel
    smaller than its, carries no power beyond them; each is said in a ``UserWarning``. A grid with
    no wavevector in the measured band raises ``ValueError``.
    """
    h, lx = as_heights("map", map, length)
    grid = _args.grid_size(grid)
    box = lx if box_length is None else float(box_length)
    top, bottom, notes = _wearsim.spectrum_pair(h, lx, grid, box, _args.seed("seed", seed), window)
    for note in notes:
        warnings.warn(note, stacklevel=2)
    return top, bottom


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
    themselves. ``height_unit`` (m, mm, um, nm, pm, A; also Gm, Mm, km, cm, fm) converts the heights
    to metres, and ``lateral_unit`` (default ``height_unit``) the coordinates of a column file. Odd
    sides lose their last row or column. ``detrend`` removes the mean, the plane or a quadratic;
    ``taper`` brings a fraction of each side smoothly to the mean (see :func:`preprocess_surface`). A surface far from
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
    sees no ridge at the border, at the cost of flattening that strip.

    Returns heights only: an array's in its own unit, a topography's in metres when it states its
    ``unit`` (its ``physical_sizes`` stay in the file's unit, so take the side from
    :func:`heights_and_length`, which gives it in metres too, not from ``physical_sizes``)."""
    h, _ = as_heights("heights", heights)
    return _wearsim.preprocess_surface(h, detrend, taper)


def periodicity(heights: Any) -> Tuple[float, float]:
    """How far a height map is from periodic: the RMS jump across the border along x and along y,
    each divided by the RMS step between neighbouring pixels inside (about 1 when periodic; above 3,
    ``wearsim`` warns)."""
    h, _ = as_heights("heights", heights)
    return _wearsim.periodicity(h)


def fit_surface(
    heights: Any,
    length: Optional[float] = None,
    *,
    detrend: Detrend = "plane",
    taper: float = 0.0,
    measured_pixel: Union[None, float, Tuple[float, float]] = None,
) -> Dict[str, Any]:
    """Self-affine parameters of a surface from its radially averaged PSD C(q) (paper §4.1:
    C(q) ∝ q^(−2(1+H)) between q = 2π/λ_u and 2π/λ_l), fitted as ``wearsim surface fit`` fits a
    file, with its verdict on whether the spectrum is self-affine at all.

    The map is levelled first, as the CLI does: ``detrend`` (default ``"plane"``, the CLI's
    ``--detrend``: a tilt would put its power into the longest wavelengths and be read as the
    roughness and λ_u) and ``taper`` (default 0, its ``--taper``), as :func:`preprocess_surface`;
    ``detrend="none"`` fits the heights as given.

    ``rms_height`` is the h_rms of the self-affine band, not of the whole map: the square root of
    the map's variance held by the modes 2π/λ_u ≤ |q| ≤ 2π/λ_l (λ_l and λ_u as ``spectrum`` gives
    them), from its PSD as measured (Hann-windowed for a map that is not periodic, as below, and
    normalised so that it sums to the map's variance). The paper's surfaces (§4.1) hold the power
    law between λ_u and λ_l and nothing else, so that is the h_rms that gives generated surfaces
    the measured PSD level in the band; the whole map's would add the variance outside it (a
    waviness or form beyond λ_u, noise beyond λ_l). ``map_rms_height`` is the whole levelled map's,
    and ``out_of_band_share`` the share of its variance outside the band,
    1 − (rms_height/map_rms_height)² (0 at least); above 10 %, ``notes`` says so. ``rms_slope``:
    ``map`` and ``generated``, the rms slopes of the map and of a surface the fitted parameters
    generate on its grid (forward differences inside the map); a change over 10 % is in ``notes``
    too. A flat map (one value, or a plane levelled away) is refused: its spectrum is zero.

    ``measured_pixel``: the native pixel size of a map resampled onto finer pixels than it was
    measured with (what ``wearsim surface import --resample`` records in import.json as
    ``pixel_size``, there in its ``unit``), one value for both axes or ``(dx, dy)``, in the unit of
    the fit's lengths (that of ``length``: metres for a topography that states its unit). Beyond the
    native Nyquist wavenumber π/dx along x or π/dy along y the resampled map's pixels are
    interpolated and its spectrum is the interpolation's, so the fit (floor, band, slope, λ_l, the
    x/y power ratio, the band's h_rms) uses only the wavevectors with |q_x| ≤ π/dx and
    |q_y| ≤ π/dy; ``measured_pixel`` in the result says which. Default: the whole stored spectrum is
    measured.

    The PSD of a map that is not periodic (border jumps above 3 typical steps, see
    :func:`periodicity`) is taken under a Hann window, after levelling by a plane: the jump at its
    borders would otherwise leak power ∝ q⁻² into every shell and bias H low. A periodic map (a
    generated surface) is taken as it is. ``window`` says which.

    The floor of the PSD is left out first: shells below 1e-12 of the peak (round-off) and shells
    within a factor 10 of the median PSD over the outermost half octave of wavenumbers (round-off
    beyond λ_l of a band-limited surface, white noise of a measurement). The power law is fitted on
    the widest band of at least 6 shells over an octave that follows one line in log–log, falls
    faster than q⁻¹ and lies under no longer wavelength (the leakage of a levelled map beyond λ_l
    does), so that a floor is never read as the self-affine band. A spectrum without such a band
    raises ``ValueError``; a fit with R² < 0.9 warns (``UserWarning``) that H is a rough estimate.

    The verdict: ``self_affine`` is true when the spectrum is isotropic (within a factor 2 between
    the power of wavevectors along x and along y), has no peak (no shell 5 times above the power
    law beyond its scatter), H lies in (0, 1], the band spans at least two octaves (a factor 4) of wavenumbers and
    R² ≥ 0.9; ``reasons`` says, one sentence each, which of these failed. A spectrum that is not
    self-affine warns (``UserWarning``, with the reasons): the self-affine parameters leave out
    what it is, and :func:`spectrum_pair` generates periodic pairs that carry its measured 2D PSD
    instead (a run file's ``source = "spectrum"``).

    Returns what ``wearsim surface fit`` writes in its fit.json for the same map: the fit's fields
    (its ``"fit"``) ``hurst`` H (from the slope −2(1+H)), ``lambda_lower`` and ``lambda_upper``
    (where the PSD leaves the power law at short and long wavelengths), ``rms_height`` (the band's),
    ``map_rms_height``, ``out_of_band_share``, ``measured_pixel`` (``[dx, dy]`` or None), ``r2`` of
    the log–log fit, the number of ``shells`` it used and their wavenumbers ``fitted_q`` (first and
    last, q = 2π/λ in radians per unit length), the shells left out at longer wavelengths than λ_u
    (``shells_longer``) and at shorter wavelengths than λ_l (``shells_shorter``), ``floor``, the
    floor's level relative to the power law at λ_l, ``window`` (``"hann"`` or ``"none"``),
    ``anisotropy`` (the x/y power ratio over the fitted shells) and ``peak`` (how far the highest
    shell stands above the power law beyond its scatter); and beside them ``spectrum``, the
    parameters a run generates from the fit on this grid (λ_l raised to two pixels and λ_u lowered
    to the box where the fit ran past them, as ``notes`` says, with the band's h_rms),
    ``self_affine`` and ``reasons``.
    Lengths are in the unit of the heights (metres for a topography that states its unit). Pass
    the parameters to :func:`generate_pair` to get periodic surfaces with the measured statistics
    (the paper's model assumes periodic self-affine surfaces)."""
    h, lx = as_heights("heights", heights, length)
    h = _wearsim.preprocess_surface(h, detrend, taper)
    native: Optional[Tuple[float, float]] = None
    if measured_pixel is not None:
        pixel = np.atleast_1d(np.asarray(measured_pixel, dtype=np.float64))
        if pixel.ndim != 1 or pixel.size not in (1, 2):
            raise ValueError(
                f"invalid `measured_pixel`: {measured_pixel!r}; give one native pixel size for both axes or (dx, dy)"
            )
        native = (float(pixel[0]), float(pixel[-1]))
    fit = _wearsim.fit_surface(h, lx, native)
    poor_fit = _wearsim.poor_fit_warning(fit.get("r2"))
    if poor_fit is not None:
        warnings.warn(poor_fit, stacklevel=2)
    if not fit.get("self_affine", True):
        warnings.warn(
            f"the spectrum is not self-affine ({'; '.join(fit.get('reasons', []))}): the self-affine parameters "
            "leave that out; wearsim.spectrum_pair(map, ...) generates periodic pairs that carry the measured 2D "
            'PSD instead (a run file\'s [surface] source = "spectrum")',
            stacklevel=2,
        )
    return fit


def composite_heights(top: Any, bottom: Any, offset: int = 0) -> np.ndarray:
    """Height of Johnson's equivalent rigid surface at a sliding offset of ``offset`` pixels along
    x: ``bottom + np.roll(top, offset, axis=0)``. Each body is an array or a SurfaceTopography
    topography (in metres where it states its unit, as :func:`heights_and_length` reads it)."""
    if offset < 0:
        raise ValueError(f"invalid `offset`: {offset} must be a non-negative number of pixels")
    top_heights, _ = as_heights("top", top)
    bottom_heights, _ = as_heights("bottom", bottom)
    return _wearsim.composite_heights(top_heights, bottom_heights, offset)
