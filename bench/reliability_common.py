"""What the rounds of reliability trials share (bench/reliability_trials.py and the rounds it runs,
bench/reliability_third_round.py, bench/reliability_fourth_round.py): the `wearsim` binary, the run
file of every trial, running a command and classifying its outcome. Each round imports this module;
none imports another round's script for it.
"""

from __future__ import annotations

import collections
import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WEARSIM = os.environ.get("WEARSIM_BIN", str(ROOT / "target" / "release" / "wearsim"))

RUN = {
    "surface": {
        "grid": "64",
        "length": "1.0",
        "hurst": "0.7",
        "lambda_lower": "0.0625",
        "lambda_upper": "0.25",
        "rms_height": "0.005",
        "seed": "1",
        "generation": '"random-phase"',
    },
    "material": {
        "youngs_modulus": "1.0",
        "poisson_ratio": "0.3",
        "shear_strength": "0.01",
        "fracture_energies": "[0.5e-6]",
        "geometry_factor": "3.0",
    },
    "contact": {"modulus": '"half-space"', "tolerance": "1e-8", "max_iterations": "20000", "connectivity": "4"},
    "sliding": {"loads": "[1e-3]", "distance": "0.5", "running_in": "0.25", "step_running_in": "4", "step": "1"},
}
Outcome = collections.namedtuple("Outcome", "kind detail")


def toml(run: dict, drop: tuple = (), extra: str = "") -> str:
    lines = []
    for section, keys in run.items():
        lines.append(f"[{section}]")
        lines += [f"{k} = {v}" for k, v in keys.items() if (section, k) != drop]
    return "\n".join(lines) + "\n" + extra


def classify(p: subprocess.CompletedProcess | None, out: Path | None = None) -> Outcome:
    if p is None:
        return Outcome("hang", "")
    err = p.stderr.decode(errors="replace").strip()
    if p.returncode == 0:
        return Outcome("accepted", "")
    if p.returncode == 101 or "panicked" in err:
        return Outcome("panic", err[-300:])
    if p.returncode < 0 or p.returncode in (134, 137, 139):
        return Outcome("abort", f"status {p.returncode}: {err[-300:]}")
    # The error line (command-line errors add a usage hint after it).
    last = next((line for line in err.splitlines() if line.startswith("error:")), err.splitlines()[-1] if err else "")
    clear = last.startswith("error:") and len(last) > 20 and "Os {" not in err and "panicked" not in err
    if out is not None and out.exists() and not (out / ".wearsim.json").exists():
        return Outcome("data loss", f"half-written {out}")
    return Outcome("clear error" if clear else "unclear error", last)


def run(args: list[str], timeout: float = 120, **kw) -> subprocess.CompletedProcess | None:
    try:
        return subprocess.run([WEARSIM, *args], capture_output=True, timeout=timeout, **kw)
    except subprocess.TimeoutExpired:
        return None


STUDY = toml(RUN).replace("seed = 1", "seed = [1, 2, 3]").replace("loads = [1e-3]", "loads = [5e-4, 1e-3]")


def results(folder: Path) -> str:
    p = run(["study", "collect", str(folder)])
    assert p is not None and p.returncode == 0, p and p.stderr
    return (folder / "results.csv").read_text()


def print_report(trials: list, outcomes: list, detail: int = 200) -> None:
    """The table of a round's trials by class and outcome (as docs/reliability.md shows it), then
    every trial that is neither accepted nor a clear error, with the first ``detail`` characters of
    what it said."""
    classes = sorted({t["class"] for t in trials})
    count = collections.Counter((t["class"], t["outcome"]) for t in trials)
    print(f"| class | trials | {' | '.join(outcomes)} |")
    print("|---|---|" + "---|" * len(outcomes))
    for c in classes:
        counts = [count[(c, k)] for k in outcomes]
        print(f"| {c} | {sum(counts)} | {' | '.join(map(str, counts))} |")
    totals = [sum(count[(c, k)] for c in classes) for k in outcomes]
    print(f"| **all** | {sum(totals)} | {' | '.join(map(str, totals))} |")
    print()
    for t in trials:
        if t["outcome"] not in ("accepted", "clear error"):
            print(f"- {t['outcome']}: {t['class']}: {t['name']}: {t['detail'][:detail]}")
