"""What the package's command-line entries (``python -m wearsim.fields``, ``python -m
wearsim.measured``, which ``wearsim fields to-netcdf`` and ``wearsim surface import`` run) share:
printing that survives a closed pipe, and the stop signals."""

from __future__ import annotations

import os
import signal
from typing import Any

STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGUSR1, signal.SIGUSR2)


def say(text: str, stream: Any) -> None:
    """Prints a line to ``stream``. A write that fails (a pipe whose reader has gone, ``| head``)
    ends the printing there, silently, and changes nothing else: the work is done and its exit
    status stays what it is (as the ``wearsim`` command does)."""
    try:
        print(text, file=stream, flush=True)
    except OSError:
        # What is left in the stream's buffer goes nowhere at exit, rather than failing again there.
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, stream.fileno())
        except (OSError, ValueError):
            pass


def stop_on_signals() -> None:
    """SIGTERM, SIGHUP, SIGUSR1 and SIGUSR2 (``wearsim`` passes a stop on as SIGTERM; Slurm sends
    them at a time limit) stop the work as Ctrl-C does, once (``KeyboardInterrupt``): its temporary
    file or folder is removed on the way out, and further signals are ignored while it is. A signal
    ignored when the process started (``nohup``) stays ignored."""

    def stop(signum: int, frame: object) -> None:
        for s in STOP_SIGNALS:
            signal.signal(s, signal.SIG_IGN)
        raise KeyboardInterrupt

    for s in STOP_SIGNALS:
        if signal.getsignal(s) is not signal.SIG_IGN:
            signal.signal(s, stop)
