"""Python call overhead: the same slide from the CLI (`wearsim slide RUN --out DIR`, a whole process)
and from Python (`wearsim.load_run(RUN).slide()`, and `wearsim.slide(top, bottom, ...)` on arrays),
alternated and repeated in one run; prints the best and median wall-clock seconds, the CPU seconds
(all threads; the CLI's from its process accounting) and their ratios to the CLI. On a shared
machine wall-clock times of one route vary by ±20 % between repeats: compare the best times and the
CPU times, which steal time does not inflate.

    pip install .        # the package, from the repository root
    python bench/python_overhead.py [--grid 256] [--repeats 3]

Paper roughness at the given grid, τ̃ = 0.01 E, two loads, two fracture energies, the default
schedule (running-in ¼ L in 4-pixel steps, then 1-pixel steps up to ½ L).
"""

import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import wearsim

ROOT = Path(__file__).resolve().parents[1]
WEARSIM = ROOT / "target" / "release" / "wearsim"

RUN = """
[surface]
grid = {n}
lambda_lower = {lam}
lambda_upper = 0.25
rms_height = 0.005
seed = 1
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6, 1e-6]
[sliding]
loads = [5e-4, 1e-3]
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=256)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if not WEARSIM.is_file():
        sys.exit(f"{WEARSIM} not found: cargo build --release -p wearsim-cli")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        run_path = tmp / "run.toml"
        run_path.write_text(RUN.format(n=args.grid, lam=16 / args.grid))
        run = wearsim.load_run(run_path)
        top, bottom = run.surfaces()
        wall = {"cli": [], "python_run_file": [], "python_arrays": []}
        cpu = {k: [] for k in wall}

        def children_cpu():
            r = resource.getrusage(resource.RUSAGE_CHILDREN)
            return r.ru_utime + r.ru_stime

        for r in range(args.repeats):
            t, c = time.perf_counter(), children_cpu()
            subprocess.run(
                [str(WEARSIM), "slide", str(run_path), "--out", str(tmp / f"cli{r}")], check=True, capture_output=True
            )
            wall["cli"].append(time.perf_counter() - t)
            cpu["cli"].append(children_cpu() - c)
            t, c = time.perf_counter(), time.process_time()
            series, summary = run.slide()
            wall["python_run_file"].append(time.perf_counter() - t)
            cpu["python_run_file"].append(time.process_time() - c)
            t, c = time.perf_counter(), time.process_time()
            wearsim.slide(top, bottom, run.material, run.loads)
            wall["python_arrays"].append(time.perf_counter() - t)
            cpu["python_arrays"].append(time.process_time() - c)
        steps = len(series) // 2  # two fracture energies share every step
    print(f"slide, grid {args.grid}², {steps} contact solutions, {args.repeats} repeats, seconds:")
    print(f"{'route':<42}{'best':>8}{'median':>8}{'CPU':>8}{'best/CLI':>10}{'CPU/CLI':>9}")
    for name, label in [
        ("cli", "CLI process: wearsim slide RUN --out DIR"),
        ("python_run_file", "Python: wearsim.load_run(RUN).slide()"),
        ("python_arrays", "Python: wearsim.slide(top, bottom, ...)"),
    ]:
        best, med, c = min(wall[name]), statistics.median(wall[name]), statistics.median(cpu[name])
        print(
            f"{label:<42}{best:>8.3f}{med:>8.3f}{c:>8.3f}"
            f"{best / min(wall['cli']):>10.3f}{c / statistics.median(cpu['cli']):>9.3f}"
        )


if __name__ == "__main__":
    main()
