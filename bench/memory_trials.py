"""Memory estimates against measured peaks, for docs/reliability.md: each command's peak resident size
(`/usr/bin/time -f %M`) at several grids, and the estimate wearsim checks before any allocation (read
from its refusal under a 1 MB Slurm allocation, which names the need), with their ratio. Then the
smallest `ulimit -v` under which each command still runs, against the same estimate.

    cargo build --release -p wearsim-cli && python bench/memory_trials.py [--sizes 512,1024,2048,4096]
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WEARSIM = os.environ.get("WEARSIM_BIN", str(ROOT / "target" / "release" / "wearsim"))

RUN = """units = "reduced"
[surface]
grid = {n}
length = 1.0
lambda_lower = {lower}
lambda_upper = 0.25
rms_height = 0.005
seed = 1
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.25e-6, 0.5e-6, 0.75e-6, 1e-6]
[sliding]
loads = [1e-3]
distance = {distance}
running_in = {running_in}
step_running_in = 4
step = 1
"""


def commands(tmp: Path, run: Path, n: int) -> dict:
    return {
        "slide": ["slide", run, "--out", tmp / "o", "--overwrite"],
        "contact": ["contact", run, "--load", "1e-3", "--out", tmp / "o", "--overwrite"],
        "surface": ["surface", run, "--out", tmp / "o", "--overwrite"],
        "study run": ["study", "run", run, "--out", tmp / f"st{n}", "--jobs", "1"],
    }


def peak_mib(args: list) -> float:
    p = subprocess.run(
        ["/usr/bin/time", "-f", "MAXRSS %M", WEARSIM, "--quiet", *map(str, args)], capture_output=True, text=True
    )
    line = [x for x in p.stderr.splitlines() if x.startswith("MAXRSS")][-1]
    if p.returncode != 0:
        raise RuntimeError(p.stderr[-300:])
    return int(line.split()[1]) / 1024


def estimate_mib(args: list) -> float:
    env = {**os.environ, "SLURM_MEM_PER_NODE": "1"}
    p = subprocess.run([WEARSIM, "--quiet", *map(str, args)], capture_output=True, text=True, env=env)
    m = re.search(r"needs about ([0-9.]+) (MiB|GiB)", p.stderr)
    if m is None:
        raise RuntimeError(f"no estimate in: {p.stderr[-300:]}")
    return float(m.group(1)) * (1024 if m.group(2) == "GiB" else 1)


def smallest_ulimit(args: list, low: int, high: int) -> int:
    """The smallest `ulimit -v` (KiB) under which the command succeeds, by bisection."""
    while high - low > max(2048, low // 50):
        mid = (low + high) // 2
        script = f"ulimit -v {mid}; exec {WEARSIM} --quiet {' '.join(map(str, args))}"
        p = subprocess.run(["sh", "-c", script], capture_output=True)
        if p.returncode == 0:
            high = mid
        else:
            low = mid
    return high


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="512,1024,2048,4096")
    parser.add_argument("--ulimit", action="store_true", help="also bisect the smallest ulimit -v")
    args = parser.parse_args()
    print("| command | grid | measured peak (MiB) | estimate (MiB) | estimate / peak |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for n in map(int, args.sizes.split(",")):
            run = tmp / f"r{n}.toml"
            run.write_text(RUN.format(n=n, lower=16 / n, distance=12 / n, running_in=4 / n))
            for name, cmd in commands(tmp, run, n).items():
                peak = peak_mib(cmd)
                estimate = estimate_mib(commands(tmp, run, -n)[name])
                print(f"| {name} | {n}² | {peak:.0f} | {estimate:.0f} | {estimate / peak:.2f} |", flush=True)
                if args.ulimit:
                    need = smallest_ulimit(cmd, 10_000, int(estimate * 1024 * 3) + 200_000)
                    print(f"|   smallest ulimit -v | {n}² | {need / 1024:.0f} | {estimate:.0f} | |", flush=True)


if __name__ == "__main__":
    main()
