"""Instrument height maps (AFM ``.di``, confocal ``.plu``, ISO 25178 ``.x3p``, Wyko ``.opd``, Digital
Surf ``.sur``, ``.mi`` and every other format SurfaceTopography reads) turned into the maps a run
file reads: ``wearsim surface import FILE --out DIR [--bottom FILE2]`` runs :func:`import_topography`
(``python -m wearsim.measured FILE DIR [--bottom FILE2]``).

Needs the ``measured`` extra (``pip install "wearsim[measured]"``: SurfaceTopography).

The folder ``DIR`` gets

- ``heights.npy``: float64 heights in metres, the (Nx, Ny) array ``h[i, j]`` with i along x, as
  wearsim reads it. SurfaceTopography's ``heights()`` has the same orientation (its first index
  runs along x, ``physical_sizes[0]``), so the array is written as it comes, never transposed;
- ``bottom.npy``: the counter-body, on the same grid: the second instrument file ``FILE2``
  (``bottom``), imported with the same options, or without one the map rotated by 180° about its
  centre, ``h_b[i, j] = h[Nx−1−i, Ny−1−j]`` (:data:`ROTATED`);
- ``import.json``: what was done (source, reader, channel, grid, size and unit, pixel sizes, the
  conversion to metres, undefined pixels, resampling, levelling, cropping, the side in metres; the
  same for the second map under ``bottom_map``; ``bodies``: the file of each body and the rule that
  made the bottom one) and ``surface_toml``, a ready ``[surface]`` block: ``top = "DIR/heights.npy"``,
  ``bottom = "DIR/bottom.npy"`` with ``length = Lx`` in a run file with ``units = "si"``.

Undefined pixels are refused unless ``fill`` names how to fill them (SurfaceTopography's
``interpolate_undefined_data``: ``"harmonic"``); non-square pixels are refused unless ``resample``,
which puts the map on square pixels of the smaller pixel size (bicubic interpolation for a periodic
topography, linear otherwise, within the measured span); the tilt is removed (``detrend``, as
:func:`wearsim.preprocess_surface` does); an odd side loses its last row or column, as a run file's
reader does. A second map must end on the first one's grid and pixel size, else it is refused.

The rotated copy: a run's composite surface is ``bottom + roll(top, offset)`` along x, each body's
heights taken out of its own material towards the other, as an instrument measures them. The copy
keeps their sign (a negated copy would make the measured valleys peaks and reverse the skewness)
and is turned in the plane only: its heights are the measured ones, rearranged, so each body has
the measured height distribution; a half turn maps the 2D power spectrum onto itself
(``C(−q) = C(q)`` for real heights), so the spectrum and the lay direction, an oblique one too, are
kept, where a mirror image would turn an oblique lay to the opposite angle. On an even grid no pixel
of the copy faces its own measured value at any offset, and for random roughness (random phases)
the two bodies' heights are then correlated at any offset only as much as two independent
measurements of that size may be by chance; the same map for both bodies is perfectly correlated at
offset 0. A regular texture symmetric under a half turn (one sinusoid, a regular array of dimples) is
its own rotated copy up to a shift: give such a counter-body's own map, or generate independent pairs
with the measured spectrum (``source = "spectrum"``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import socket
import sys
import warnings
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._entry import say as _say
from ._entry import stop_on_signals as _stop_on_signals
from ._wearsim import MIN_GRID, __version__
from ._wearsim import metres_per as _metres_per
from .surface import SQUARE_PIXELS, Detrend, heights_and_length, preprocess_surface, read_surface

#: Fill methods of SurfaceTopography's ``interpolate_undefined_data`` (1.27).
FILL_METHODS = ("harmonic",)
DETRENDS = ("none", "mean", "plane", "curvature")
WRITER = "wearsim surface import"
#: The file of each body in the folder: the map as the top body, the counter-body as the bottom one.
TOP_FILE, BOTTOM_FILE = "heights.npy", "bottom.npy"
#: The rule that makes the bottom body without a second map (``import.json``'s ``bodies``).
ROTATED = "the map rotated by 180° about its centre"
#: A filled map whose undefined pixels are more than this share of it is mostly invented by the
#: fill: the import warns, with the share (``import.json``'s ``undefined_share``).
FILLED_WARNING = 0.1
#: Extensions of the height maps a run file and ``wearsim surface fit`` read themselves (NumPy
#: arrays and text matrices), which state no physical size: they need no import.
READ_DIRECTLY = ("npy", "npz", "txt", "csv", "dat", "asc")

Say = Callable[[str], None]


class MeasuredMapWarning(UserWarning):
    """What an import says of a map it wrote (a fill that invents much of it): also in
    ``import.json``'s ``warnings``."""


def _surface_topography():
    try:
        import SurfaceTopography  # type: ignore[import-untyped]
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError('wearsim.measured needs SurfaceTopography: pip install "wearsim[measured]"') from e
    return SurfaceTopography


def _written_by_import(path: Path) -> bool:
    """Whether the folder ``path`` is one that :func:`import_topography` wrote (its import.json)."""
    try:
        with open(path / "import.json", encoding="utf-8") as f:
            return json.load(f).get("written_by") == WRITER
    except (OSError, ValueError, AttributeError):
        return False


def _check_out(sources: Sequence[Path], out: Path, overwrite: bool) -> None:
    """Refuses an ``out`` that is or holds one of the source files or the current folder (whatever
    the spelling), one below a file (``scan.txt/sub``), and, unless ``overwrite``, one that exists
    and is not a folder this import wrote."""
    for above in out.absolute().parents:
        if above.exists():
            if not above.is_dir():
                raise ValueError(f"{out} lies inside {above}, which is a file, not a folder; give an --out in a folder")
            break
    real_out = out.resolve()
    held = [("the instrument file", source.resolve()) for source in sources]
    for what, real in held + [("the current folder", Path.cwd().resolve())]:
        if real == real_out or real_out in real.parents:
            raise ValueError(f"{out} is or holds {what}, which the import would replace; give another folder")
    if out.exists() or out.is_symlink():
        if not overwrite and not (out.is_dir() and _written_by_import(out)):
            what = "a folder" if out.is_dir() else "a file"
            raise FileExistsError(
                f"{out} exists and is {what} that `{WRITER}` did not write; give another folder, or overwrite=True "
                "(--overwrite) to replace it"
            )


def _sibling(out: Path, k: int) -> Path:
    """``.NAME.HOST.PID-K.tmp`` beside ``out``: the name ``wearsim`` gives its temporary files and
    folders, whose host and process tell a later run that a killed import left it (and remove it)."""
    return out.parent / f".{out.name}.{socket.gethostname()}.{os.getpid()}-{k}.tmp"


def _last_position(n: int, pixel: float) -> float:
    """The last sample's position of a non-periodic map of ``n`` pixels of size ``pixel``,
    ``(n − 1)·pixel``, lowered by round-off where needed so that SurfaceTopography's own test of its
    domain, ``position / pixel ≤ n − 1``, holds (with pixels of 2 µm, ``(n − 1)·2e-6 / 2e-6`` can
    exceed ``n − 1`` by one unit in the last place, and the interpolation refuses the point)."""
    last = (n - 1) * pixel
    while last / pixel > n - 1:
        last = float(np.nextafter(last, 0.0))
    return last


def _resample(topo: Any, say: Say) -> Any:
    """The topography on square pixels of its smaller pixel size, evaluated with SurfaceTopography's
    interpolation: bicubic for a periodic topography (the period kept), linear for a measured one,
    on the points inside its measured span (a side shrinks by less than a pixel)."""
    from SurfaceTopography import Topography  # type: ignore[import-untyped]

    (nx, ny), (lx, ly) = topo.nb_grid_pts, topo.physical_sizes
    # The pixel sizes SurfaceTopography interpolates with (a file may state them apart from its size).
    px, py = (float(v) for v in topo.pixel_size)
    p = min(px, py)
    periodic = bool(topo.is_periodic)
    if periodic:
        mx, my = round(lx / p), round(ly / p)
        interpolate = topo.interpolate_bicubic()
    else:
        # The last sample lies at (n − 1)·pixel: no point beyond it (that would be extrapolation).
        mx = int(math.floor((nx - 1) * px / p + 1e-9)) + 1
        my = int(math.floor((ny - 1) * py / p + 1e-9)) + 1
        interpolate = topo.interpolate_linear()
    x, y = np.meshgrid(np.arange(mx) * p, np.arange(my) * p, indexing="ij")
    if not periodic:  # round-off at the last sample
        x, y = np.minimum(x, _last_position(nx, px)), np.minimum(y, _last_position(ny, py))
    h = np.asarray(interpolate(x, y), dtype=np.float64).reshape(mx, my)
    out = Topography(h, (mx * p, my * p), unit=topo.unit, periodic=periodic)
    u = f" {topo.unit}" if topo.unit else ""
    say(
        f"resampled: {nx}×{ny} pixels of {px:.6g}{u} × {py:.6g}{u} onto {mx}×{my} square pixels of {p:.6g}{u} "
        f"({'bicubic, periodic' if periodic else 'linear'}); size {mx * p:.6g}{u} × {my * p:.6g}{u}"
    )
    return out


def _likely_reader(source: Path) -> Optional[str]:
    """The name of SurfaceTopography's reader of files with ``source``'s extension (``.di``:
    ``DIReader``), if one has it."""
    from SurfaceTopography.IO import readers  # type: ignore[import-untyped]

    suffix = source.suffix.lower().lstrip(".")
    for reader in readers:
        extensions = [str(e).lower() for e in getattr(reader, "_file_extensions", None) or []]
        if suffix and (suffix == str(getattr(reader, "_format", "")).lower() or suffix in extensions):
            return str(reader.__name__)
    return None


def _unreadable(source: Path, error: Exception) -> str:
    """The message of a file no reader of SurfaceTopography opened: one line first (the file looks
    damaged or is of no format read, and what the reader of its extension said), every reader's
    answer after it."""
    text = str(error).strip()
    tried = dict(re.findall(r"^tried (\w+): \n (.*?)(?=\n\ntried |\Z)", text, flags=re.S | re.M))
    if not tried:
        return f"{source} could not be read: {text}"
    likely = _likely_reader(source)
    if likely in tried:
        said = tried[likely].strip().splitlines()[0] if tried[likely].strip() else "(no message)"
        lead = (
            f"{source} looks damaged, or is in no format SurfaceTopography reads: its reader of "
            f"{source.suffix} files, {likely}, said: {said}"
        )
    else:
        lead = (
            f"{source} is in no format SurfaceTopography reads (no reader takes {source.suffix or 'its'} files, and "
            f"none of the {len(tried)} tried recognised it), or looks damaged"
        )
    cascade = "\n".join(f"  {line}" for line in text.splitlines() if line.strip())
    return f"{lead}\nevery reader's answer:\n{cascade}"


def _plain_map(source: Path) -> str:
    return (
        f"{source} is a plain height map that states no physical size, which wearsim reads without an "
        'import: name it in a run file (`[surface] top = FILE` with `length`, or `source = "spectrum"` '
        "with `map = FILE` and `map_length`) or give it to `wearsim surface fit FILE --length L`"
    )


def _read_directly(source: Path) -> bool:
    """Whether ``source`` is a plain map (a ``.npy``/``.npz`` array, a text or CSV matrix) that a run
    file reads itself."""
    if source.suffix.lower().lstrip(".") not in READ_DIRECTLY:
        return False
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # its periodicity, say: the map is only looked at
            read_surface(source, length=1.0)
    except Exception:  # not one: the readers' answers say why
        return False
    return True


def _open(st: Any, source: Path) -> Any:
    """SurfaceTopography's reader of ``source``, refusing what is no height map: an empty file, a
    file no reader opens (:func:`_unreadable`), and one that only the reader of SRTM elevation
    tiles takes (it reads any file of a square number of 16-bit values)."""
    if source.stat().st_size == 0:
        raise ValueError(f"{source} is empty (0 bytes): there is no height map to import")
    try:
        reader = st.open_topography(os.fspath(source))
    except Exception as e:  # CannotDetectFileFormat, or a reader's own error
        if _read_directly(source):
            raise ValueError(_plain_map(source)) from None
        raise ValueError(_unreadable(source, e)) from None
    if type(reader).__name__ == "HGTReader" and source.suffix.lower() != ".hgt":
        raise ValueError(
            f"{source} is in no instrument format SurfaceTopography reads, or looks damaged: only its reader of SRTM "
            "elevation tiles (.hgt), which takes any file of a square number of 16-bit values, opened it, and that "
            "is no measured surface"
        )
    return reader


def _is_length_unit(unit: Any) -> bool:
    try:
        return isinstance(unit, str) and bool(unit) and _metres_per(unit) > 0
    except ValueError:
        return False


def _channel_of(source: Path, reader: Any, channel: Optional[int]) -> Tuple[int, Any]:
    """The index and the channel information of the channel to read (default: the reader's own),
    refused when it is no height channel (its unit no length: an AFM's phase or amplitude error),
    naming the height channels."""
    channels = reader.channels

    def names(indices: Sequence[int]) -> str:
        return ", ".join(f"{i} ({channels[i].name!r})" for i in indices)

    index = reader.default_channel.index if channel is None else int(channel)
    if not 0 <= index < len(channels):
        raise ValueError(
            f"invalid `channel`: {index}; {source} has {len(channels)} channel(s): {names(range(len(channels)))}"
        )
    info = channels[index]
    unit = getattr(info, "unit", None)
    # A channel that states no unit is read as it is (the unit is asked for further on).
    if unit is not None and not _is_length_unit(unit):
        heights = [i for i, c in enumerate(channels) if _is_length_unit(getattr(c, "unit", None))]
        # SurfaceTopography gives a channel of other values its unit as (lateral, of the values).
        values = (unit[1] if len(unit) > 1 else None) if isinstance(unit, (tuple, list)) else unit
        if values:
            what = f"its values are in {values}, not a length"
        else:
            what = "its values state no unit" + (f" (its sides are in {unit[0]})" if unit else "")
        which = (
            f"its height channels (a unit of length) are {names(heights)}: give --channel (channel=) one of them"
            if heights
            else "it has no channel in a unit of length"
        )
        raise ValueError(f"channel {index} ({info.name!r}) of {source} is not a height channel: {what}; {which}")
    return index, info


def _read_map(
    st: Any,
    source: Path,
    *,
    fill: Optional[str],
    resample: bool,
    detrend: Detrend,
    channel: Optional[int],
    say: Say,
) -> Tuple[np.ndarray, Dict[str, Any]]:
    """The heights of the instrument file ``source`` in metres (square pixels, even sides, levelled)
    and the record of what was done to them: the keys of one map in ``import.json``."""
    reader = _open(st, source)
    channels = reader.channels
    index, info = _channel_of(source, reader, channel)
    if getattr(info, "physical_sizes", True) is None:
        if source.suffix.lower().lstrip(".") in READ_DIRECTLY:
            raise ValueError(_plain_map(source))
        raise ValueError(
            f"{source}, channel {index}, states no physical size; read it with SurfaceTopography's "
            "`read_topography(path, physical_sizes=(sx, sy), unit=...)` and pass "
            "`wearsim.heights_and_length(topography)` on"
        )
    try:
        topo = reader.topography(channel_index=index)
    except Exception as e:  # a header read whole, its data cut short or damaged
        raise ValueError(
            f"{source} looks damaged: {type(reader).__name__} read its header but not its heights: {e}"
        ) from None
    fmt = reader.format() if callable(getattr(reader, "format", None)) else None
    say(f"read {source}: {type(reader).__name__} ({fmt}), channel {index} ({info.name!r}) of {len(channels)}")
    if topo.dim != 2:
        raise ValueError(f"{source}, channel {index}, is a line scan; wearsim needs a 2-D height map")
    unit = str(topo.unit) if topo.unit else ""
    if not unit:
        raise ValueError(
            f"{source}, channel {index}, states no unit of length, so its heights cannot be put in metres; "
            "read it with SurfaceTopography's `read_topography(path, unit=...)` and pass "
            "`wearsim.heights_and_length(topography)` on"
        )
    grid = [int(n) for n in topo.nb_grid_pts]
    sizes = [float(s) for s in topo.physical_sizes]
    pixel = [sizes[0] / grid[0], sizes[1] / grid[1]]
    say(
        f"grid {grid[0]}×{grid[1]}, size {sizes[0]:.6g} × {sizes[1]:.6g} {unit}, "
        f"pixels {pixel[0]:.6g} × {pixel[1]:.6g} {unit}"
    )
    record: Dict[str, Any] = {
        "source": os.fspath(source.resolve()),
        "format": fmt,
        "reader": type(reader).__name__,
        "channel": index,
        "channel_name": info.name,
        "channels": len(channels),
        "grid": grid,
        "physical_sizes": sizes,
        "unit": unit,
        "pixel_size": pixel,
        "is_periodic": bool(topo.is_periodic),
    }

    raw = topo.heights()
    # Masked pixels (SurfaceTopography's undefined data) and any NaN or infinity left unmasked.
    undefined = int(np.count_nonzero(np.ma.getmaskarray(raw) | ~np.isfinite(np.ma.getdata(raw))))
    total = grid[0] * grid[1]
    record["undefined_pixels"] = undefined
    record["undefined_share"] = undefined / total
    record["fill"] = None
    record["warnings"] = []
    if undefined == total:
        raise ValueError(
            f"{source}, channel {index}: none of its {total} pixels is measured (every one is undefined); there is "
            "no height map to import"
        )
    if undefined:
        if fill is None:
            raise ValueError(
                f"{source}: {undefined} of its {total} pixels are undefined ({100 * undefined / total:.3g} %, not "
                f"measured); fill them with --fill {'|'.join(FILL_METHODS)} (fill={FILL_METHODS[0]!r}: "
                "SurfaceTopography's interpolate_undefined_data), or crop them away"
            )
        topo = topo.interpolate_undefined_data(method=fill)
        record["fill"] = fill
        say(f"filled {undefined} undefined pixels ({fill}), {100 * undefined / total:.3g} % of the map")
        if undefined > FILLED_WARNING * total:
            record["warnings"].append(
                f"{source}: {100 * undefined / total:.3g} % of the map ({undefined} of {total} pixels) was not "
                f"measured and is invented by the {fill} fill, a smooth interpolation with no roughness of its "
                "own: the contact, the junctions and the wear there are the fill's, not the surface's; crop the map "
                "to its measured part where you can"
            )

    square = abs(pixel[0] - pixel[1]) <= SQUARE_PIXELS * max(abs(pixel[0]), abs(pixel[1]))
    record["resampled"] = None
    if not square:
        if not resample:
            # A text matrix states its size but not its grid: one cut short has stretched pixels.
            cut = (
                "; a text matrix that lost rows (a file cut short) reads with stretched pixels too: check that "
                "it holds every scan line first"
                if record["reader"] in ("AscReader", "XYZReader")
                else ""
            )
            raise ValueError(
                f"{source}: its pixels are not square, {pixel[0]:.6g} {unit} along x and {pixel[1]:.6g} {unit} "
                "along y; wearsim's grids have square pixels: --resample (resample=True) puts the map on square "
                f"pixels of the smaller size{cut}"
            )
        topo = _resample(topo, say)
        record["resampled"] = {
            "grid": [int(n) for n in topo.nb_grid_pts],
            "physical_sizes": [float(s) for s in topo.physical_sizes],
            "pixel_size": float(topo.physical_sizes[0] / topo.nb_grid_pts[0]),
            "method": "bicubic" if topo.is_periodic else "linear",
        }

    # Heights and side in metres, by the library's own rules (unit, square pixels, defined values).
    h, lx = heights_and_length(topo)
    factor = float(lx / float(topo.physical_sizes[0]))
    record["metres_per_unit"] = factor
    if factor != 1.0:
        say(f"converted {unit} to metres (× {factor:g})")
    nx, ny = h.shape
    pitch = lx / nx
    cx, cy = nx - nx % 2, ny - ny % 2
    record["cropped"] = None
    if (cx, cy) != (nx, ny):
        h = h[:cx, :cy]
        record["cropped"] = {"from": [nx, ny], "to": [cx, cy]}
        say(f"cropped the odd side(s): {nx}×{ny} to {cx}×{cy} pixels (the FFT solver needs even sides)")
    if cx < MIN_GRID or cy < MIN_GRID:
        raise ValueError(
            f"{source}: {cx}×{cy} pixels (after the import's steps) are too few for a height map: every reader of "
            f"wearsim needs at least {MIN_GRID} pixels a side (the FFT solver and the periodic junction labelling)"
        )
    h = preprocess_surface(h, detrend=detrend)
    record["detrend"] = detrend
    if detrend != "none":
        say(f"levelled: detrend {detrend}")
    record["heights_grid"] = [cx, cy]
    record["length"] = [cx * pitch, cy * pitch]
    record["pixel_size_m"] = pitch
    record["rms_height_m"] = _rms(h)
    return h, record


def _rms(h: np.ndarray) -> float:
    return float(np.sqrt(np.mean((h - h.mean()) ** 2)))


def _check_same_grid(first: Dict[str, Any], second: Dict[str, Any]) -> None:
    """Refuses a second map that does not end on the first one's grid and pixel size (a run's two
    bodies share one grid and one side), naming both and the way to make them agree."""
    grids = first["heights_grid"], second["heights_grid"]
    pitches = first["pixel_size_m"], second["pixel_size_m"]
    same_pixel = abs(pitches[0] - pitches[1]) <= SQUARE_PIXELS * max(pitches)
    if grids[0] == grids[1] and same_pixel:
        return

    def described(r: Dict[str, Any]) -> str:
        (nx, ny), (lx, ly), (px, py) = r["heights_grid"], r["length"], r["pixel_size"]
        read = f"read as {r['grid'][0]}×{r['grid'][1]} pixels of {px:.6g} × {py:.6g} {r['unit']}"
        return f"{nx}×{ny} pixels of {r['pixel_size_m']:.6g} m, {lx:.6g} m × {ly:.6g} m ({read})"

    fixes = []
    if grids[0] != grids[1]:
        nx, ny = min(grids[0][0], grids[1][0]), min(grids[0][1], grids[1][1])
        fixes.append(
            f"crop both to {nx}×{ny} pixels (in Python: t = SurfaceTopography.read_topography(FILE); "
            f"Topography(t.heights()[:{nx}, :{ny}], ({nx} * px, {ny} * py), unit=t.unit).to_netcdf(...), px and py "
            "its pixel sizes)"
        )
    if not same_pixel:
        fixes.append(
            "resample one map onto the other's pixel size (SurfaceTopography's interpolate_bicubic or "
            "interpolate_linear on the other's points, written back with to_netcdf)"
        )
    raise ValueError(
        f"the two bodies' maps differ after the import: {first['source']} gives {described(first)}, the second map "
        f"{second['source']} (--bottom) gives {described(second)}; a run's two bodies share one grid and one pixel "
        f"size: {', or '.join(fixes)}, then import the two again"
    )


def import_topography(
    path: Union[str, "os.PathLike[str]"],
    out: Union[str, "os.PathLike[str]"],
    *,
    bottom: Union[str, "os.PathLike[str]", None] = None,
    fill: Optional[str] = None,
    resample: bool = False,
    detrend: Detrend = "plane",
    channel: Optional[int] = None,
    overwrite: bool = False,
    say: Optional[Say] = None,
) -> Dict[str, Any]:
    """Reads the instrument file ``path`` with SurfaceTopography (its channel ``channel``, default
    the reader's default channel) and writes the folder ``out`` with ``heights.npy`` (metres, i
    along x), ``bottom.npy`` and ``import.json`` (module documentation); returns the content of
    ``import.json``.

    ``bottom.npy`` is the counter-body: the instrument file ``bottom``, read and processed with the
    same options, which must end on the same grid and pixel size as ``path`` (else ``ValueError``,
    naming both); without it, the map rotated by 180° about its centre,
    ``h_b[i, j] = h[Nx−1−i, Ny−1−j]``: the measured lay, spectrum and height distribution, and no
    pixel facing its own copy at any sliding offset (module documentation).

    Refuses (``ValueError``) a map with undefined pixels unless ``fill`` (``"harmonic"``) and one
    with no measured pixel at all, one with non-square pixels unless ``resample``, one under
    :data:`MIN_GRID` pixels a side after these steps, a line scan, a topography that states no unit,
    a channel whose unit is no length (naming the height channels), an empty file, a file no reader
    opens (its first line says the file looks damaged or is of no format read, with what the reader
    of its extension said; every reader's answer follows), one only the SRTM tile reader opens, a
    plain ``.npy`` or text map without a size (read directly by a run file), and a ``bottom`` that
    is ``path`` itself. Where ``fill`` invents more than :data:`FILLED_WARNING` of a map, a
    :class:`MeasuredMapWarning` (a ``UserWarning``; and a ``warning:`` line to ``say``) gives the
    share; ``import.json`` keeps ``undefined_share`` and ``warnings``. The folder is written beside
    ``out`` and renamed into place: a failed import leaves nothing. An existing ``out`` is replaced
    only when an earlier import wrote it, or with ``overwrite``; one that is or holds ``path`` or
    ``bottom`` never. ``say`` gets one line per action (default: none)."""
    st = _surface_topography()
    say = say or (lambda _line: None)
    source, out = Path(path), Path(out)
    second = None if bottom is None else Path(bottom)
    _check_inputs(source, second, detrend, fill)
    _check_out([source] if second is None else [source, second], out, overwrite)
    options: Dict[str, Any] = {"fill": fill, "resample": resample, "detrend": detrend, "channel": channel}
    h, hb, first, bottom_map = _read_bodies(st, source, second, options, say)
    record = _import_record(st, (h, hb), (first, bottom_map), second, out)
    # Every warning of the import, both maps', in import.json and said (a warning also for an API caller).
    for warning in record["warnings"]:
        say(f"warning: {warning}")
        warnings.warn(warning, MeasuredMapWarning, stacklevel=2)
    made = record["bodies"]["bottom"]["made_from"]
    if second is None:
        say(
            f"bottom body: {made}: the measured lay, spectrum and height distribution, and no pixel facing its "
            "own copy at any sliding offset (--bottom FILE2 imports the counter-body's own map)"
        )
    else:
        cx, cy = first["heights_grid"]
        say(f"bottom body: {made}, on the same {cx}×{cy} grid")
    _write_folder(out, h, hb, record)
    (cx, cy), (lx, ly) = first["heights_grid"], first["length"]
    say(
        f"wrote {out / TOP_FILE} (top body) and {out / BOTTOM_FILE} (bottom body), {cx}×{cy} pixels in metres, "
        f"and {out / 'import.json'}; Lx = {lx:.6g} m, Ly = {ly:.6g} m"
    )
    say("for a run file (paths relative to the run file's folder):")
    for line in record["surface_toml"].splitlines():
        say(f"  {line}")
    return record


def _check_inputs(source: Path, second: Optional[Path], detrend: Detrend, fill: Optional[str]) -> None:
    """The options and the files of an import, checked before anything is read."""
    if detrend not in DETRENDS:
        raise ValueError(f"invalid `detrend`: {detrend!r}; use one of {', '.join(DETRENDS)}")
    if fill is not None and fill not in FILL_METHODS:
        raise ValueError(f"invalid `fill`: {fill!r}; SurfaceTopography fills with {', '.join(FILL_METHODS)}")
    for file in [source] if second is None else [source, second]:
        if not file.is_file():
            raise FileNotFoundError(f"{file}: no such file")
    if second is not None and second.resolve() == source.resolve():
        raise ValueError(
            f"the second map (--bottom) is {source} itself: the two bodies would be one map, perfectly correlated "
            f"at offset 0; give the counter-body's own map, or leave it out for {ROTATED}"
        )


def _read_bodies(
    st: Any, source: Path, second: Optional[Path], options: Dict[str, Any], say: Say
) -> Tuple[np.ndarray, np.ndarray, Dict[str, Any], Optional[Dict[str, Any]]]:
    """The two bodies' heights and the records of their maps: the top from ``source``; the bottom
    from ``second`` on the same grid, or the top rotated by 180° (``bottom_map`` None)."""
    if second is None:
        h, first = _read_map(st, source, say=say, **options)
        return h, np.ascontiguousarray(h[::-1, ::-1]), first, None
    h, first = _read_map(st, source, say=lambda line: say(f"top: {line}"), **options)
    hb, bottom_map = _read_map(st, second, say=lambda line: say(f"bottom: {line}"), **options)
    _check_same_grid(first, bottom_map)
    return h, hb, first, bottom_map


def _import_record(
    st: Any,
    heights: Tuple[np.ndarray, np.ndarray],
    maps: Tuple[Dict[str, Any], Optional[Dict[str, Any]]],
    second: Optional[Path],
    out: Path,
) -> Dict[str, Any]:
    """The content of ``import.json``: the top map's record, the bottom map's (of the file
    ``second``, or none for the rotated top), what each body is made from, every warning of both
    maps, and the lines of a run file's ``[surface]``."""
    (h, hb), (first, bottom_map) = heights, maps
    if bottom_map is None or second is None:
        rule, made = "rotated-180", f"{ROTATED} (h_b[i, j] = h[Nx−1−i, Ny−1−j])"
        comment = ROTATED
    else:
        rule, made = "second-map", f"the second map {bottom_map['source']}"
        comment = f"the second map {json.dumps(second.name, ensure_ascii=False)}"
    lx, ly = first["length"]
    return {
        "written_by": WRITER,
        "wearsim": __version__,
        "surface_topography": getattr(st, "__version__", None),
        **first,
        "bottom_map": bottom_map,
        "bodies": {
            "top": {"file": TOP_FILE, "source": first["source"], "made_from": "the map", "rms_height_m": _rms(h)},
            "bottom": {
                "file": BOTTOM_FILE,
                "source": first["source"] if bottom_map is None else bottom_map["source"],
                "rule": rule,
                "made_from": made,
                "rms_height_m": _rms(hb),
            },
        },
        "warnings": first["warnings"] + ([] if bottom_map is None else bottom_map["warnings"]),
        "surface_toml": (
            'units = "si"\n'
            "[surface]\n"
            f"top = {json.dumps(os.fspath(out / TOP_FILE))}\n"
            f"bottom = {json.dumps(os.fspath(out / BOTTOM_FILE))}  # {comment}\n"
            f"length = {lx!r}  # m, along x (Ly = {ly:.6g} m)\n"
        ),
    }


def _write_folder(out: Path, h: np.ndarray, hb: np.ndarray, record: Dict[str, Any]) -> None:
    """Writes the folder ``out`` (the two bodies and ``import.json``) beside it and renames it into
    place, replacing an earlier one: a failed write leaves the earlier folder, or nothing."""
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp, old = _sibling(out, 0), _sibling(out, 1)
    try:
        tmp.mkdir()
        np.save(tmp / TOP_FILE, np.ascontiguousarray(h, dtype=np.float64))
        np.save(tmp / BOTTOM_FILE, np.ascontiguousarray(hb, dtype=np.float64))
        with open(tmp / "import.json", "w", encoding="utf-8") as f:
            json.dump(record, f, indent=2, ensure_ascii=False)
            f.write("\n")
        if out.exists() or out.is_symlink():
            os.replace(out, old)
        os.replace(tmp, out)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        if old.exists() and not out.exists():
            os.replace(old, out)
        raise
    if old.is_dir() and not old.is_symlink():
        shutil.rmtree(old, ignore_errors=True)
    elif old.exists() or old.is_symlink():
        old.unlink()


def main(argv: Optional[List[str]] = None) -> int:
    """``python -m wearsim.measured FILE OUT [--bottom FILE2]`` (what ``wearsim surface import`` runs)."""
    parser = argparse.ArgumentParser(
        prog="python -m wearsim.measured",
        description="Turn an instrument height map (any format SurfaceTopography reads) into the maps of a run's two "
        "bodies, as wearsim reads them.",
    )
    parser.add_argument("file", type=Path, help="instrument file (.x3p, .di, .plu, .opd, .sur, .mi, ...)")
    parser.add_argument("out", type=Path, help="folder to write: heights.npy, bottom.npy and import.json")
    parser.add_argument(
        "--bottom",
        type=Path,
        metavar="FILE2",
        help="the counter-body's instrument file, imported the same way into OUT/bottom.npy "
        "(default: the map rotated by 180° about its centre)",
    )
    parser.add_argument("--fill", choices=FILL_METHODS, help="fill undefined pixels (default: refuse them)")
    parser.add_argument("--resample", action="store_true", help="resample non-square pixels onto square ones")
    parser.add_argument("--detrend", choices=DETRENDS, default="plane", help="levelling (default plane)")
    parser.add_argument("--channel", type=int, help="channel index (default: the reader's default channel)")
    parser.add_argument("--overwrite", action="store_true", help="replace OUT even when another program wrote it")
    args = parser.parse_args(argv)
    _stop_on_signals()

    def line(text: str) -> None:
        # Warnings on the error stream, as wearsim's commands print them; the rest on stdout.
        _say(text, sys.stderr if text.startswith("warning: ") else sys.stdout)

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeasuredMapWarning)  # said by `line` already
            import_topography(
                args.file,
                args.out,
                bottom=args.bottom,
                fill=args.fill,
                resample=args.resample,
                detrend=args.detrend,
                channel=args.channel,
                overwrite=args.overwrite,
                say=line,
            )
    except KeyboardInterrupt:
        _say("error: stopped by a signal; nothing was written", sys.stderr)
        return 130
    except Exception as e:  # a reader's own error (a damaged file) included: one line, no traceback
        _say(f"error: {e}", sys.stderr)
        return 1
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
