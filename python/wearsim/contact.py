"""The saturated-pressure contact solver (paper §2 and appendix A).

Contact of a rigid surface of heights h with an elastic half-space of effective modulus E*,
pressure bounded by the flow pressure p_m (0 ≤ p ≤ p_m), mean pressure F_N/(Lx Ly). Solved by a
bound-constrained conjugate gradient on FFT boundary elements; exact zeros outside the contact.
Grids are Nx × Ny square pixels; ``length`` is the side Lx along the first axis.

The half-space is periodic (``boundary="periodic"``, the paper's model, used for sliding) or has a
free boundary around the map (``boundary="free"``: the map is surrounded by an unloaded half-space,
for measured maps, which are not periodic; Hockney's zero-padded FFT, 2Nx × 2Ny, four times the
work).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional, Tuple, Union

import numpy as np

from . import _wearsim
from .surface import _float_grid, _is_topography, as_heights


@dataclass(frozen=True)
class ContactResult:
    """One contact solution.

    ``pressure`` is in the unit of E (reduced: E; SI: Pa); ``approach``, ``displacement``, ``gap``
    and lengths in the unit of L (reduced: L; SI: m).
    """

    #: Contact pressure p, (Nx, Ny) float64, exactly 0 outside the contact.
    pressure: np.ndarray
    #: Surface displacement of the half-space u = 𝒦p, (Nx, Ny) float64 (zero mean when periodic).
    displacement: np.ndarray
    #: Gap g = 𝒦p − h + δ, δ = max(h) − approach: the separation of the rigid surface and the
    #: deformed half-space, (Nx, Ny) float64. 0 on contact pixels below p_m, ≥ 0 outside the contact,
    #: ≤ 0 (interpenetration taken up by plastic flow) where p = p_m, each to within
    #: ``residual`` × std(h).
    gap: np.ndarray
    #: Conjugate-gradient iterations.
    iterations: int
    #: Convolutions (FFT round trips) in all.
    convolutions: int
    #: Final residual: largest pixel-wise violation of the optimality conditions / std(h).
    residual: float
    #: Tolerance the residual had to reach.
    tolerance: float
    #: Rigid-body approach since first contact, max(h) − c (length unit).
    approach: float
    #: Pixels in contact (p > 0) and at the flow pressure (p = p_m).
    contact_pixels: int
    plastic_pixels: int
    #: Real contact area as a fraction of the apparent area Lx Ly.
    contact_area: float
    #: Mean pressure F_N/(Lx Ly).
    mean_pressure: float
    #: Wall-clock seconds of the solve.
    seconds: float

    @property
    def contact(self) -> np.ndarray:
        """Contact map, (Nx, Ny) bool: p > 0."""
        return _wearsim.contact_map(self.pressure)


class ContactSolver:
    """FFT contact solver for one grid. Plans and buffers are made once: reuse one solver for many
    solves on the same grid (e.g. the steps of a slide, warm-started from the previous pressure).

    ``grid`` is N (an N × N grid) or (Nx, Ny); ``length`` the side Lx along x of the box (length
    unit; pixels are square, so Ly = Lx Ny/Nx); ``effective_modulus`` E* (unit of pressure; see
    :meth:`wearsim.Material.effective_modulus`); ``boundary`` ``"periodic"`` or ``"free"`` (see the
    module documentation); ``device`` where the solver computes, ``"cpu"`` (``"cuda"``, an NVIDIA GPU,
    is refused by builds without a GPU backend, which this release is).
    """

    def __init__(
        self,
        grid: Union[int, Tuple[int, int]],
        length: float,
        effective_modulus: float,
        *,
        tolerance: float = _wearsim.DEFAULT_TOLERANCE,
        max_iterations: int = _wearsim.DEFAULT_MAX_ITERATIONS,
        boundary: str = "periodic",
        device: str = "cpu",
    ) -> None:
        self._solver = _wearsim.ContactSolver(
            grid, length, effective_modulus, tolerance, max_iterations, boundary, device
        )

    shape = property(lambda self: self._solver.shape, doc="Grid (Nx, Ny).")
    length = property(lambda self: self._solver.length, doc="Side length Lx along x.")
    effective_modulus = property(lambda self: self._solver.effective_modulus, doc="E*.")
    tolerance = property(lambda self: self._solver.tolerance, doc="Tolerance on the residual.")
    boundary = property(lambda self: self._solver.boundary, doc='"periodic" or "free".')
    device = property(lambda self: self._solver.device, doc='Where the solver computes: "cpu".')

    def solve(
        self,
        heights: Any,
        load: float,
        *,
        flow_pressure: float = np.inf,
        initial_pressure: Optional[np.ndarray] = None,
    ) -> ContactResult:
        """Solves the contact of the rigid surface ``heights`` (length unit) at normal load
        ``load`` = F_N (pressure × length², e.g. E·L² or N) with the pressure bounded by
        ``flow_pressure`` (``inf``: elastic). ``initial_pressure`` warm-starts the solve (e.g. the
        previous step's pressure); without it the solve starts from a uniform pressure.

        ``heights`` is an array, or a SurfaceTopography topography: one that states its unit is
        taken in metres (as :func:`wearsim.heights_and_length` gives it), and its side must be the
        solver's ``length``.

        Raises ``ValueError`` for bad input (NaN heights, a load at or above p_m Lx Ly, a topography
        of another side, …) and :class:`wearsim.NotConvergedError` when the iteration limit is
        reached.
        """
        if _is_topography(heights):
            heights, side = as_heights("heights", heights)
            if not math.isclose(side, self.length, rel_tol=1e-9):
                raise ValueError(
                    f"invalid `heights`: the topography's side along x is {side:.6g} (in metres where it states its "
                    f"unit), the solver's length is {self.length:.6g}; make the solver with length={side!r}, or use "
                    "solve_contact, which takes the side from the topography"
                )
        p0 = None if initial_pressure is None else _float_grid("initial_pressure", initial_pressure)
        pressure, displacement, gap, info = self._solver.solve(
            _float_grid("heights", heights), float(load), float(flow_pressure), p0
        )
        return ContactResult(pressure=pressure, displacement=displacement, gap=gap, **info)

    def displacement(self, pressure: np.ndarray) -> np.ndarray:
        """Surface displacement 𝒦p of the half-space under ``pressure`` (length unit; zero mean when
        periodic)."""
        return self._solver.displacement(_float_grid("pressure", pressure))


def solve_contact(
    heights: Any,
    load: float,
    *,
    effective_modulus: float,
    length: Optional[float] = None,
    flow_pressure: float = np.inf,
    initial_pressure: Optional[np.ndarray] = None,
    tolerance: float = _wearsim.DEFAULT_TOLERANCE,
    max_iterations: int = _wearsim.DEFAULT_MAX_ITERATIONS,
    boundary: str = "periodic",
) -> ContactResult:
    """One contact solve (see :meth:`ContactSolver.solve`); for many solves on one grid, keep a
    :class:`ContactSolver`. ``boundary="free"`` solves a map that is not periodic (a measured one)
    as surrounded by an unloaded half-space.

    ``heights`` is an array with its side ``length`` along x (default 1), or a SurfaceTopography
    topography, whose physical size gives the side (heights and side in metres where it states its
    unit; a ``length`` given with it overrides the side, in metres too), as
    :func:`wearsim.heights_and_length` reads it."""
    heights, length = as_heights("heights", heights, length)
    solver = ContactSolver(
        (heights.shape[0], heights.shape[1]),
        length,
        effective_modulus,
        tolerance=tolerance,
        max_iterations=max_iterations,
        boundary=boundary,
    )
    return solver.solve(heights, load, flow_pressure=flow_pressure, initial_pressure=initial_pressure)
