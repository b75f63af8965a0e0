"""Contact junctions (paper §2–3): connected components of the contact map, periodic in x and y."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Tuple

import numpy as np
import pandas as pd

from . import _wearsim


@dataclass(frozen=True)
class Junctions:
    """Labelled junctions of one contact map. Areas and diameters in the unit of ``pixel_size``."""

    #: Junction index of every pixel, (Nx, Ny) int64, −1 outside the contact. Junctions are numbered
    #: in the row-major order of their first pixel.
    labels: np.ndarray
    #: Pixel count of every junction.
    pixels: np.ndarray
    #: Pixel side Δx = L/N.
    pixel_size: float
    #: Whether each junction wraps the periodic box along x and along y, (count, 2) bool. A junction
    #: that closes on itself around the box (full contact, a band across it) has no finite extent:
    #: it is no particle of the model (paper §3), and its diameter and volume mean nothing.
    wraps: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=bool))

    @property
    def wrapping(self) -> np.ndarray:
        """Whether each junction wraps the periodic box (along x or y)."""
        if not self.wraps.size:
            return np.zeros(self.pixels.size, dtype=bool)
        return np.asarray(self.wraps.any(axis=1))

    @property
    def count(self) -> int:
        """Number of junctions."""
        return int(self.pixels.size)

    def _geometry(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        return _wearsim.junction_geometry(self.pixels.tolist(), self.pixel_size)

    @property
    def areas(self) -> np.ndarray:
        """A_i = pixels·Δx² (the library's, as the wear model uses it)."""
        return self._geometry()[0]

    @property
    def diameters(self) -> np.ndarray:
        """Equivalent diameters d_i = 2√(A_i/π) (circular junctions, paper §3)."""
        return self._geometry()[1]

    @property
    def volumes(self) -> np.ndarray:
        """Volumes of the spherical particles they would form, v_i = π d_i³/6."""
        return self._geometry()[2]

    def table(self) -> pd.DataFrame:
        """One row per junction: pixels, area, diameter, volume, and whether it wraps the box along x
        and y (such a junction is no particle of the model)."""
        wraps = self.wraps if self.wraps.size else np.zeros((self.pixels.size, 2), dtype=bool)
        area, diameter, volume = self._geometry()
        return pd.DataFrame(
            {
                "pixels": self.pixels,
                "area": area,
                "diameter": diameter,
                "volume": volume,
                "wraps_x": wraps[:, 0],
                "wraps_y": wraps[:, 1],
            }
        )


def label_junctions(
    contact: np.ndarray, *, connectivity: int = _wearsim.DEFAULT_CONNECTIVITY, pixel_size: float = 1.0
) -> Junctions:
    """Labels the junctions of a contact map (bool, or numbers where > 0 is contact, e.g. a pressure
    field) with 4- or 8-connectivity and periodic boundaries.

    A junction that wraps the periodic box (``Junctions.wraps``) is flagged and warned about
    (``RuntimeWarning``): it is no particle of the model (paper §3), so its diameter and volume are
    not those of a particle. A NaN or masked pixel is neither contact nor no contact, so a map with
    one is refused (``ValueError``), as ``wearsim junctions`` refuses it."""
    if np.ma.isMaskedArray(contact) and np.ma.getmaskarray(contact).any():
        raise ValueError(
            f"invalid `contact`: a masked array with {int(np.ma.getmaskarray(contact).sum())} masked pixel(s), "
            "which are neither contact nor no contact: fill them (e.g. `contact.filled(0)`) or crop them"
        )
    contact = np.asarray(contact)
    if contact.ndim != 2:
        raise ValueError(f"invalid `contact`: a 2-D array is needed, got {contact.ndim} dimensions")
    if contact.dtype != np.bool_:
        if np.issubdtype(contact.dtype, np.floating):
            undefined = np.isnan(contact)
            if undefined.any():
                i, j = np.argwhere(undefined)[0]
                raise ValueError(
                    f"invalid `contact`: the contact map holds NaN at ({i}, {j}) ({int(undefined.sum())} pixel(s)); "
                    "a contact map is bool, or numbers where > 0 is contact: fill or crop the undefined pixels"
                )
        contact = contact > 0
    if not (math.isfinite(pixel_size) and pixel_size > 0):
        raise ValueError(f"invalid `pixel_size`: {pixel_size} must be a finite positive number")
    labels, pixels, wraps = _wearsim.label_junctions(np.ascontiguousarray(contact), connectivity)
    if wraps.any():
        which = np.flatnonzero(wraps.any(axis=1))
        warnings.warn(
            f"junction(s) {which.tolist()} wrap the periodic box ({int(pixels[which].sum())} of {contact.size} "
            "pixels in contact): a junction around the box is no particle of the model (paper §3), so its "
            "diameter and volume are not a particle's; see `Junctions.wraps`",
            RuntimeWarning,
            stacklevel=2,
        )
    return Junctions(labels=labels, pixels=pixels, pixel_size=float(pixel_size), wraps=wraps)
