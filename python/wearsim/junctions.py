"""Contact junctions (paper §2–3): connected components of the contact map, periodic in x and y."""

from __future__ import annotations

from dataclasses import dataclass

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

    @property
    def count(self) -> int:
        """Number of junctions."""
        return int(self.pixels.size)

    @property
    def areas(self) -> np.ndarray:
        """A_i = pixels·Δx²."""
        return self.pixels.astype(np.float64) * self.pixel_size**2

    @property
    def diameters(self) -> np.ndarray:
        """Equivalent diameters d_i = 2√(A_i/π) (circular junctions, paper §3)."""
        return 2.0 * np.sqrt(self.areas / np.pi)

    @property
    def volumes(self) -> np.ndarray:
        """Volumes of the spherical particles they would form, v_i = π d_i³/6."""
        return np.pi * self.diameters**3 / 6.0

    def table(self) -> pd.DataFrame:
        """One row per junction: pixels, area, diameter, volume."""
        return pd.DataFrame(
            {"pixels": self.pixels, "area": self.areas, "diameter": self.diameters, "volume": self.volumes}
        )


def label_junctions(contact: np.ndarray, *, connectivity: int = 4, pixel_size: float = 1.0) -> Junctions:
    """Labels the junctions of a contact map (bool, or numbers where > 0 is contact, e.g. a pressure
    field) with 4- or 8-connectivity and periodic boundaries."""
    contact = np.asarray(contact)
    if contact.dtype != np.bool_:
        contact = contact > 0
    if contact.ndim != 2:
        raise ValueError(f"invalid `contact`: a 2-D array is needed, got {contact.ndim} dimensions")
    if not pixel_size > 0:
        raise ValueError(f"invalid `pixel_size`: {pixel_size} must be positive")
    labels, pixels = _wearsim.label_junctions(np.ascontiguousarray(contact), connectivity)
    return Junctions(labels=labels, pixels=pixels, pixel_size=float(pixel_size))
