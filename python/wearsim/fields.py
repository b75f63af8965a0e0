"""The fields store of ``wearsim slide --save-fields`` (``fields.zarr``): opened as an xarray Dataset,
and converted to NetCDF-4 with CF attributes for programs that do not read Zarr (MATLAB's
``ncread``, ParaView, Panoply, netCDF-C tools, xarray with any NetCDF engine).

Needs the ``fields`` extra (``pip install "wearsim[fields]"``: xarray, zarr, h5netcdf and h5py).

The NetCDF file holds per load and sliding step (dimensions ``load``, ``s``, ``x``, ``y``):

- ``pressure``: contact pressure p (reduced: E; SI: Pa), exactly 0 outside the contact;
- ``contact``: 1 where p > 0, else 0 (byte, CF ``flag_values``/``flag_meanings``);
- ``junctions``: label of the junction of each pixel (0: no contact; junctions wrap around the
  periodic borders), 32-bit integers;

with coordinates ``load`` (F_N; reduced: E·L², SI: N), ``s`` (sliding distance; L or m),
``offset`` (the same in pixels), ``x`` and ``y`` (pixel positions, ``axis`` X and Y; L or m). Each
variable has ``units`` and ``long_name``; global attributes give the CF convention, the unit
system, the software, the paper and the run's provenance (JSON text). SI runs carry UDUNITS units
(Pa, m, N); reduced runs carry the symbols of their unit system (E, L, E L^2), which no UDUNITS
parser knows. MATLAB's ``ncread`` returns the dimensions reversed: ``ncread(f, "pressure")`` is
Ny × Nx × steps × loads.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, Dict, Hashable, List, Literal, Optional, Union

import numpy as np

from ._entry import say as _say
from ._entry import stop_on_signals as _stop_on_signals
from ._wearsim import __version__

if TYPE_CHECKING:  # pragma: no cover
    import xarray

PAPER = (
    "Brink, Frérot & Molinari, A parameter-free mechanistic model of the adhesive wear process of rough "
    "surfaces in sliding contact, J. Mech. Phys. Solids 147 (2021) 104238, doi:10.1016/j.jmps.2020.104238"
)


def _xarray():
    try:
        import xarray
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError('wearsim.fields needs xarray, zarr, h5netcdf and h5py: pip install "wearsim[fields]"') from e
    return xarray


def open_fields(path: Union[str, Path]) -> "xarray.Dataset":
    """Opens the fields store ``path`` (``DIR/fields.zarr`` of ``wearsim slide --save-fields``)
    lazily as an xarray Dataset (dimensions load, s, x, y; units as attributes)."""
    xr = _xarray()
    path = Path(path)
    if not (path / ".zgroup").is_file():
        raise FileNotFoundError(
            f"{path} is not a fields store (no .zgroup); give the fields.zarr folder written by "
            "`wearsim slide --save-fields`"
        )
    return xr.open_zarr(path)


def _unit(text: str) -> str:
    # NetCDF readers expect ASCII unit strings.
    return text.replace("²", "^2").replace("³", "^3")


def to_cf(ds: "xarray.Dataset") -> "xarray.Dataset":
    """The fields Dataset with CF-1.8 attributes and NetCDF-4 types (see the module documentation)."""
    out = ds.copy()
    for name, var in out.variables.items():
        attrs = dict(var.attrs)
        if "units" in attrs:
            attrs["units"] = _unit(str(attrs["units"]))
        out[name].attrs = attrs
    for name, axis in [("x", "X"), ("y", "Y")]:
        if name in out.coords:
            out[name].attrs["axis"] = axis
    if "contact" in out:
        attrs = dict(out["contact"].attrs)
        out["contact"] = out["contact"].astype(np.int8)
        attrs.update(flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="no_contact contact")
        out["contact"].attrs = attrs
    if "junctions" in out:
        attrs = dict(out["junctions"].attrs)
        pixels = int(np.prod([out.sizes[d] for d in ("x", "y") if d in out.sizes]))
        # Labels are at most the pixel count, so 32-bit signed integers hold them (for ParaView and
        # netCDF-3 style readers, which have no unsigned types).
        if pixels < 2**31:
            out["junctions"] = out["junctions"].astype(np.int32)
        out["junctions"].attrs = attrs
    attrs = dict(ds.attrs)
    provenance = attrs.pop("provenance", None)
    system = attrs.pop("units", None)
    out.attrs = {
        "Conventions": "CF-1.8",
        "title": TITLE,
        "institution": "",
        "source": f"wearsim {__version__}",
        "references": PAPER,
        "unit_system": "reduced (E = 1, L = 1)" if system == "reduced" else str(system),
        **{k: (json.dumps(v) if isinstance(v, (dict, list)) else v) for k, v in attrs.items()},
    }
    if not out.attrs["institution"]:
        del out.attrs["institution"]
    if provenance is not None:
        out.attrs["provenance"] = json.dumps(provenance)
    return out


TITLE = "Per-step contact fields of a wearsim sliding run"


def _written_by_to_netcdf(path: Path) -> bool:
    """Whether ``path`` is a NetCDF file that :func:`to_netcdf` wrote (its source and references)."""
    try:
        import h5py  # type: ignore[import-untyped]

        with h5py.File(path, "r") as f:
            source, references = f.attrs.get("source"), f.attrs.get("references")
    except Exception:  # not HDF5, unreadable, h5py missing: not one of ours
        return False
    text = [v.decode() if isinstance(v, bytes) else str(v) for v in (source, references)]
    return text[0].startswith("wearsim ") and text[1] == PAPER


def _check_out(store: Path, out: Path, overwrite: bool) -> None:
    """Refuses an ``out`` inside the store (or the store itself), a folder, and an existing file that
    this conversion did not write unless ``overwrite``: never over another command's output (a
    ``summary.json``), an input, or a file of the user's, whatever the spelling of the path."""
    real_out, real_store = out.resolve(), store.resolve()
    if real_out == real_store or real_store in real_out.parents:
        raise ValueError(f"{out} is inside the fields store {store}: writing there would damage it; give another path")
    if real_out.is_dir():
        raise IsADirectoryError(f"{out} is a folder, where the NetCDF file to write is needed; give a file path")
    if real_out.exists() and not overwrite and not _written_by_to_netcdf(real_out):
        raise FileExistsError(
            f"{out} exists and was not written by `wearsim fields to-netcdf`; give another path, or overwrite=True "
            "(--overwrite) to replace it"
        )


def _temporary_sibling(out: Path) -> Path:
    """``.NAME.HOST.PID-0.tmp`` beside ``out``: the name ``wearsim`` gives its temporary files, whose
    host and process tell a later run that a killed conversion left it (and remove it)."""
    return out.parent / f".{out.name}.{socket.gethostname()}.{os.getpid()}-0.tmp"


def to_netcdf(
    store: Union[str, Path],
    out: Union[str, Path],
    *,
    engine: Literal["h5netcdf", "netcdf4"] = "h5netcdf",
    complevel: int = 1,
    overwrite: bool = False,
) -> Path:
    """Converts the fields store ``store`` (``DIR/fields.zarr``) to the NetCDF-4 file ``out`` with CF
    attributes (module documentation), compressed with zlib at ``complevel`` (0 for none). The file
    is written beside ``out`` and renamed into place, so a failed conversion leaves no partial file;
    it gets the permissions of any new file (the umask's). An existing ``out`` is replaced only when
    an earlier conversion wrote it, or with ``overwrite``; one inside the store never. Returns
    ``out``."""
    out = Path(out)
    _check_out(Path(store), out, overwrite)
    cf = to_cf(open_fields(store))
    if engine not in ("h5netcdf", "netcdf4"):
        raise ValueError(f"invalid `engine`: {engine!r}; NetCDF-4 is written by 'h5netcdf' or 'netcdf4'")
    encoding: Dict[Hashable, Dict[str, Any]] = {}
    for name in cf.data_vars:
        enc: Dict[str, Any] = {"zlib": True, "complevel": complevel} if complevel > 0 else {}
        sizes = cf[name].sizes
        if {"x", "y"} <= set(sizes):
            # One chunk per map: readers slice one step at a time.
            enc["chunksizes"] = tuple(sizes[d] if d in ("x", "y") else 1 for d in cf[name].dims)
        encoding[name] = enc
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = _temporary_sibling(out)
    # Created as any new file is (mode 0666 less the umask), not 0600 as a temporary file would be.
    os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666))
    try:
        cf.to_netcdf(tmp, engine=engine, format="NETCDF4", encoding=encoding)
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return out


def main(argv: Optional[List[str]] = None) -> int:
    """``python -m wearsim.fields to-netcdf STORE OUT`` (what ``wearsim fields to-netcdf`` runs)."""
    parser = argparse.ArgumentParser(
        prog="python -m wearsim.fields",
        description="Fields stores of `wearsim slide --save-fields`: convert to NetCDF-4.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    conv = sub.add_parser("to-netcdf", help="convert a fields.zarr store to NetCDF-4 with CF attributes")
    conv.add_argument("store", type=Path, help="DIR/fields.zarr of `wearsim slide --save-fields`")
    conv.add_argument("out", type=Path, help="NetCDF file to write (e.g. fields.nc)")
    conv.add_argument("--complevel", type=int, default=1, help="zlib level, 0 for none (default 1)")
    conv.add_argument("--overwrite", action="store_true", help="replace OUT even when another program wrote it")
    args = parser.parse_args(argv)
    _stop_on_signals()
    try:
        path = to_netcdf(args.store, args.out, complevel=args.complevel, overwrite=args.overwrite)
    except (ImportError, OSError, ValueError) as e:
        _say(f"error: {e}", sys.stderr)
        return 1
    except KeyboardInterrupt:
        _say("error: stopped by a signal; nothing was written", sys.stderr)
        return 130
    _say(f"wrote {path}", sys.stdout)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
