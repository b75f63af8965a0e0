"""Progress reporting of long calls: ``progress=True`` prints a line on stderr; a callable receives
``(done, total)`` (steps of a slide, jobs of a study) from the calling thread."""

from __future__ import annotations

import sys
import time
from typing import Callable, Optional, Union

ProgressArg = Union[bool, Callable[[int, int], None], None]


class TextProgress:
    """``label done/total (percent), elapsed, remaining`` rewritten in place on stderr."""

    def __init__(self, label: str) -> None:
        self.label = label
        self.start = time.perf_counter()

    def __call__(self, done: int, total: int) -> None:
        elapsed = time.perf_counter() - self.start
        left = elapsed / done * (total - done) if done else float("nan")
        end = "\n" if done >= total else ""
        sys.stderr.write(
            f"\r{self.label} {done}/{total} ({100 * done / max(total, 1):.0f} %), "
            f"{elapsed:.0f} s elapsed, {left:.0f} s left{end}"
        )
        sys.stderr.flush()


def callback(progress: ProgressArg, label: str) -> Optional[Callable[[int, int], None]]:
    """The callback for a ``progress`` argument: None, a text reporter, or the user's callable."""
    if progress is None or progress is False:
        return None
    if progress is True:
        return TextProgress(label)
    if callable(progress):
        return progress
    raise ValueError(f"invalid `progress`: {progress!r}; give True, False or a callable(done, total)")
