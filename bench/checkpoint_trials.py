"""Kill-and-resume trials of a checkpointed `wearsim slide`, counted for docs/reliability.md.

One uninterrupted run gives the reference series.csv; each trial starts the same run with a
checkpoint after every step, kills it with SIGKILL (as a Slurm wall-time limit does) at a random
moment after its first checkpoint, runs the same command again, and compares the resumed series.csv
with the reference byte for byte. A trial whose run finished before the kill is counted apart.

    cargo build --release -p wearsim-cli && python bench/checkpoint_trials.py [--grid 512] [--trials 5]
"""

from __future__ import annotations

import argparse
import os
import random
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WEARSIM = os.environ.get("WEARSIM_BIN", str(ROOT / "target" / "release" / "wearsim"))

RUN = """
[surface]
grid = {grid}
length = 1.0
hurst = 0.7
lambda_lower = {lambda_lower}
lambda_upper = 0.25
rms_height = 0.005
seed = 7
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.25e-6, 1e-6]
[sliding]
loads = [5e-4, 1e-3]
distance = {distance}
running_in = {running_in}
step_running_in = 8
step = 4
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=512)
    parser.add_argument("--trials", type=int, default=5)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        n = args.grid
        run = work / "run.toml"
        # A short schedule: 8-pixel steps over 32 pixels of running-in, then 4-pixel steps to 64.
        run.write_text(
            RUN.format(grid=n, lambda_lower=16 / n, distance=64 / n, running_in=32 / n),
        )
        start = time.monotonic()
        subprocess.run([WEARSIM, "slide", str(run), "--out", str(work / "ref"), "--quiet"], check=True)
        duration = time.monotonic() - start
        reference = (work / "ref" / "series.csv").read_bytes()
        print(f"{n}² reference run: {duration:.1f} s")
        out, checkpoint = work / "out", work / ".out.checkpoint"
        command = [WEARSIM, "slide", str(run), "--out", str(out), "--quiet", "--checkpoint-every", "0s"]
        counts = {"killed after a checkpoint": 0, "resumed identical": 0, "resumed different": 0, "finished first": 0}
        for trial in range(args.trials):
            subprocess.run(["rm", "-rf", str(out)], check=True)
            child = subprocess.Popen(command, stderr=subprocess.DEVNULL)
            while not checkpoint.exists() and child.poll() is None:
                time.sleep(0.01)
            time.sleep(rng.uniform(0.0, 0.8 * duration))
            if child.poll() is not None:
                counts["finished first"] += 1
                continue
            child.kill()
            child.wait()
            counts["killed after a checkpoint"] += 1
            resumed = subprocess.run(command, stderr=subprocess.PIPE, text=True, check=True)
            note = next((line for line in resumed.stderr.splitlines() if "resuming" in line), "no resume note")
            same = (out / "series.csv").read_bytes() == reference
            counts["resumed identical" if same else "resumed different"] += 1
            verdict = "identical" if same else "DIFFERS"
            print(f"trial {trial + 1}: {note}; series.csv {verdict}; checkpoint left: {checkpoint.exists()}")
        print(", ".join(f"{k}: {v}" for k, v in counts.items()))


if __name__ == "__main__":
    main()
