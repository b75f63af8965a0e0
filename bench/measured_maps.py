"""Instrument files to a sliding study and an estimate, with wearsim's commands only.

For each instrument file given, run as a user would (no code of one's own between the steps):

1. ``wearsim surface import FILE --out MAP`` (with ``--fill harmonic`` / ``--resample`` where the
   file has undefined or non-square pixels: the import refuses them otherwise and says which flag),
2. ``wearsim surface fit MAP/heights.npy --out FIT``: the windowed fit and its self-affinity verdict,
3. a study file on periodic pairs carrying the map's measured spectrum (``source = "spectrum"``),
   a box of 256 of the map's pixels, three seeds, a steel-like material whose two d* are 8 and 16
   pixels, three nominal pressures p_N = (1, 2, 4) % of E* h'_rms (h'_rms the RMS slope of the
   composite surface, √2 that of the map: the elastic contact fraction is about 2 p_N/(E* h'_rms),
   so some 2–8 %; E* h'_rms taken at most 2.5 p_m, so p_N ≤ p_m/10),
4. ``wearsim study run`` + ``study collect``, ``wearsim estimate-check`` (the static estimate of
   every sliding job beside it, with its reach warnings), and ``wearsim study run --dry-run`` on a
   copy run with the cost estimate, whose wall time is set against the study's own,

and print one row per file. Used for the table of docs/measured-surfaces.md ("Six instruments")
on SurfaceTopography's MIT-licensed file-format examples (test/file_format_examples of
https://github.com/ContactEngineering/SurfaceTopography)::

    python bench/measured_maps.py --wearsim target/release/wearsim --out /tmp/maps \\
        di-1.di mi-1.mi opd-1.opd plu-1.plu sur-2.sur x3p-2.x3p
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path
from typing import Dict, List

import numpy as np
import pandas as pd

STUDY = """units = "si"
[surface]
source = "spectrum"
map = "map/heights.npy"
map_length = {map_length!r}
grid = 256
length = {length!r}
seed = [1, 2, 3]
[material]
youngs_modulus = 200e9
poisson_ratio = 0.3
shear_strength = 2e9
fracture_energies = [{g1!r}, {g2!r}]
[sliding]
loads = [{f1!r}, {f2!r}, {f3!r}]
distance = 1.0
running_in = 0.5
"""

YOUNGS, POISSON, SHEAR = 200e9, 0.3, 2e9


def run(cmd: List[str], cwd: Path, env: Dict[str, str]) -> str:
    done = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{done.stderr[-3000:]}")
    return done.stdout + done.stderr


def import_map(wearsim: str, file: Path, out: Path, env: Dict[str, str]) -> List[str]:
    """Imports, adding the flag the refusal names (as a user reading the message would)."""
    flags: List[str] = []
    for _ in range(3):
        done = subprocess.run(
            [wearsim, "surface", "import", str(file), "--out", str(out), "--overwrite", *flags],
            env=env,
            capture_output=True,
            text=True,
        )
        if done.returncode == 0:
            return flags
        message = done.stderr
        if "--fill" in message and "--fill" not in flags:
            flags += ["--fill", "harmonic"]
        elif "--resample" in message and "--resample" not in flags:
            flags.append("--resample")
        else:
            raise RuntimeError(f"import of {file} failed:\n{message[-2000:]}")
    raise RuntimeError(f"import of {file} kept failing with {flags}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", type=Path)
    parser.add_argument("--wearsim", required=True)
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args()
    wearsim = str(Path(args.wearsim).resolve())
    env = dict(os.environ, WEARSIM_PYTHON=os.environ.get("WEARSIM_PYTHON", sys.executable))
    quiet = dict(env, WEARSIM_NO_ESTIMATE="1")
    rows = []
    for file in args.files:
        work = args.out / file.stem
        work.mkdir(parents=True, exist_ok=True)
        flags = import_map(wearsim, file.resolve(), work / "map", env)
        imported = json.loads((work / "map" / "import.json").read_text())
        lx = imported["length"][0]
        pixel = imported["pixel_size_m"]
        fit_cmd = [wearsim, "surface", "fit", "map/heights.npy", "--length", repr(lx), "--out", "fit", "--overwrite"]
        run(fit_cmd, work, env)
        fit = json.loads((work / "fit" / "fit.json").read_text())
        box = 256 * pixel
        mu = YOUNGS / (2 * (1 + POISSON))
        g = [d * pixel * SHEAR**2 / (2 * mu) / 3.0 for d in (8, 16)]
        heights = np.load(work / "map" / "heights.npy")
        slope = math.sqrt(2.0) * float(
            np.sqrt(np.mean(np.diff(heights, axis=0) ** 2) + np.mean(np.diff(heights, axis=1) ** 2)) / pixel
        )
        e_star = YOUNGS / (1 - POISSON**2)
        flow = 3 * math.sqrt(3) * SHEAR
        loads = [f * min(e_star * slope, 2.5 * flow) * box * box for f in (0.01, 0.02, 0.04)]
        (work / "study.toml").write_text(
            STUDY.format(map_length=lx, length=box, g1=g[0], g2=g[1], f1=loads[0], f2=loads[1], f3=loads[2])
        )
        dry = run([wearsim, "study", "run", "study.toml", "--out", "dry", "--dry-run"], work, env)
        predicted = re.search(r"estimate: \d+ jobs: (.*?) wall", dry)
        start = time.monotonic()
        run([wearsim, "study", "--quiet", "run", "study.toml", "--out", "study"], work, quiet)
        taken = time.monotonic() - start
        run([wearsim, "study", "collect", "study"], work, quiet)
        run([wearsim, "estimate-check", "study", "--out", "check", "--overwrite", "--min-particles", "5"], work, quiet)
        summary = json.loads((work / "check" / "summary.json").read_text())
        results = pd.read_csv(work / "study" / "results.csv")
        s = summary["summary"]
        rows.append(
            {
                "file": file.name,
                "import flags": " ".join(flags) or "-",
                "grid": "×".join(map(str, imported["heights_grid"])),
                "pixel nm": round(pixel * 1e9, 2),
                "self-affine": fit.get("self_affine"),
                "h'_rms": round(slope, 3),
                "p_N MPa": "/".join(f"{f / box / box / 1e6:.0f}" for f in loads),
                "H": round(fit["fit"]["hurst"], 3) if fit.get("fit") else None,
                "jobs": len(results) // 2,
                "particles in fit (sum)": int(results["particles_in_fit"].sum()),
                "W finite": bool(results["wear_rate"].map(math.isfinite).all()),
                "estimate settings": s["settings"],
                "settings ≥5 particles (errors)": s["error_settings"],
                "W median |error|": s["wear_rate_median_error"],
                "W covered": f"{s['wear_rate_covered']}/{s['with_interval']}",
                "no interval": s["interval_withheld"],
                "reach warnings": sum("calibrat" in str(w) for w in summary["warnings"]),
                "cost predicted": predicted.group(1) if predicted else "?",
                "taken s": round(taken, 1),
            }
        )
        print(rows[-1], flush=True)
    table = pd.DataFrame(rows)
    print(table.to_string(index=False))
    table.to_csv(args.out / "measured_maps.csv", index=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
