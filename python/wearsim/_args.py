"""Checks of Python arguments that the extension would otherwise refuse with a bare TypeError or
OverflowError: each message names the argument, the value given and the fix."""

from __future__ import annotations

import numbers
from typing import Any, List, Optional, Tuple, Union


def _whole(value: Any) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def grid_size(grid: Any) -> Union[int, Tuple[int, int]]:
    """``grid`` as N (N × N pixels) or (Nx, Ny), whole positive numbers."""
    if _whole(grid) and int(grid) > 0:
        return int(grid)
    if isinstance(grid, (tuple, list)) and len(grid) == 2 and all(_whole(n) and int(n) > 0 for n in grid):
        return int(grid[0]), int(grid[1])
    raise ValueError(
        f"invalid `grid`: {grid!r} is not a pixel count; give a whole number N for N × N pixels "
        "(e.g. 64) or two as (Nx, Ny) (e.g. (128, 64))"
    )


def seed(name: str, value: Any) -> int:
    """A seed: a whole number from 0 to 2⁶⁴ − 1."""
    if _whole(value) and 0 <= int(value) < 2**64:
        return int(value)
    raise ValueError(f"invalid `{name}`: {value!r} is not a seed; give a whole number from 0 to 2**64 - 1")


def count(name: str, value: Any, low: int = 0, high: Optional[int] = None, fix: str = "") -> int:
    """A whole number from ``low`` to ``high`` (a count the extension takes as unsigned)."""
    if _whole(value) and int(value) >= low and (high is None or int(value) <= high):
        return int(value)
    span = f"from {low} to {high}" if high is not None else f"of at least {low}"
    raise ValueError(f"invalid `{name}`: {value!r}; give a whole number {span}{fix}")


def optional_count(name: str, value: Any, low: int = 0, high: Optional[int] = None, fix: str = "") -> Optional[int]:
    """``None``, or a count as :func:`count` checks it."""
    return None if value is None else count(name, value, low, high, fix)


def floats(name: str, values: Any) -> List[float]:
    """A list of numbers; a single number is refused with the fix rather than iterated."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise TypeError(f"invalid `{name}`: {values!r} is one value, a list is needed; give [{values!r}]")
    try:
        return [float(v) for v in values]
    except (TypeError, ValueError) as e:
        raise TypeError(f"invalid `{name}`: {list(values)!r} holds a value that is not a number ({e})") from None
