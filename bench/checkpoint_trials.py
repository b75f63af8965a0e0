"""Kill-and-resume trials of a checkpointed `wearsim slide`, counted for docs/reliability.md.

One uninterrupted run gives the reference series.csv; each trial starts the same run, stops it at a
random moment, runs the same command again, and compares the resumed series.csv with the reference
byte for byte. A trial whose run finished before the stop is counted apart. `--stop` says how:

- `kill`: a checkpoint after every step, SIGKILL at a random moment after the first one;
- `term`, `usr1`: the default five minutes between checkpoints (none falls within the run), then
  SIGTERM (a Slurm time limit) or SIGUSR1 (`--signal=USR1@…`): only the state saved on the way out
  can resume it;
- `term-kill`: SIGTERM, then SIGKILL after a grace period of `--grace` seconds, as Slurm does.

    cargo build --release -p wearsim-cli && python bench/checkpoint_trials.py [--grid 512] [--trials 5] [--stop term]
"""

from __future__ import annotations

import argparse
import os
import random
import signal
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
    parser.add_argument("--stop", choices=["kill", "term", "usr1", "term-kill"], default="kill")
    parser.add_argument("--grace", type=float, default=1.0, help="seconds between SIGTERM and SIGKILL (term-kill)")
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
        every = "0s" if args.stop == "kill" else "5m"
        command = [WEARSIM, "slide", str(run), "--out", str(out), "--quiet", "--checkpoint-every", every]
        counts = {"stopped part-way": 0, "resumed identical": 0, "resumed different": 0, "started over": 0}
        counts["finished first"] = 0

        def live_signals() -> None:  # not the "ignored" SIGINT of a background shell
            for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGUSR1):
                signal.signal(sig, signal.SIG_DFL)

        for trial in range(args.trials):
            subprocess.run(["rm", "-rf", str(out)], check=True)
            checkpoint.unlink(missing_ok=True)
            child = subprocess.Popen(command, stderr=subprocess.DEVNULL, preexec_fn=live_signals)
            if args.stop == "kill":
                while not checkpoint.exists() and child.poll() is None:
                    time.sleep(0.01)
            time.sleep(rng.uniform(0.05 * duration, 0.8 * duration))
            if child.poll() is not None:
                counts["finished first"] += 1
                continue
            if args.stop == "kill":
                child.kill()
            else:
                child.send_signal(signal.SIGUSR1 if args.stop == "usr1" else signal.SIGTERM)
                try:
                    child.wait(timeout=args.grace if args.stop == "term-kill" else None)
                except subprocess.TimeoutExpired:
                    child.kill()
            child.wait()
            counts["stopped part-way"] += 1
            resumed = subprocess.run(command, stderr=subprocess.PIPE, text=True, check=True)
            note = next((line for line in resumed.stderr.splitlines() if "resuming" in line), "no resume note")
            same = (out / "series.csv").read_bytes() == reference
            counts["resumed identical" if same else "resumed different"] += 1
            if note == "no resume note":
                counts["started over"] += 1
            verdict = "identical" if same else "DIFFERS"
            print(
                f"trial {trial + 1}: status {child.returncode}; {note}; series.csv {verdict}; "
                f"checkpoint left: {checkpoint.exists()}"
            )
        print(", ".join(f"{k}: {v}" for k, v in counts.items()))


if __name__ == "__main__":
    main()
