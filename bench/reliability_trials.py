"""Reliability trials of the `wearsim` CLI, as a user would meet them, counted for docs/reliability.md.

Classes: bad inputs (every run-file and study-file field set to bad values, bad command-line
arguments, broken .npy files), kill -9 of a study and resume, concurrent runs on one folder, a disk
that fills up (a file-size limit), signals (SIGINT, SIGTERM), huge sizes. Each trial's outcome is
classified: a clear error (exit 1 or 2, one line naming something), accepted (exit 0, consistent
outputs), a panic (exit 101), an abort (134 or a signal), a hang (over the time limit), data loss
(outputs mixed, half-written, or a finished result lost), or silently wrong (exit 0 with results
that are not the model's, or with no word that they are not).

The second round (``--second-round`` runs it alone) adds: spreadsheet CSV (a byte-order mark,
decimal commas), full contact (a junction around the periodic box), study axes (repeated values,
two-number grids), arguments (--jobs 0, three or negative --length), messages of the first round's
unclear errors, `surface fit` on surfaces wearsim generated, and the same dimensionless run at extreme SI
length scales.

The third round (``--third-round`` runs it alone; bench/reliability_third_round.py) adds folders and
files that are not wearsim's, partial files of killed runs, damaged checkpoints and edited job files,
memory limits (ulimit, Slurm) and huge compressed inputs, stop signals to every command, Slurm time
limits, a loose solver tolerance, its unclear messages and the Python API items.

    cargo build --release -p wearsim-cli
    python bench/reliability_trials.py [--quick | --second-round | --third-round]
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import random
import signal
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Optional, Tuple

from reliability_common import ROOT, RUN, STUDY, WEARSIM, Outcome, classify, results, run, toml

BAD = [
    "0",
    "-1",
    "1e308",
    "5e-324",
    "nan",
    "inf",
    "-inf",
    '"text"',
    "[]",
    "[1, 2]",
    "true",
    "18446744073709551615",
    "0.5",
    "3",
    "100000",
]


def bad_inputs(tmp: Path, tally: dict, quick: bool) -> None:
    commands = [["slide"], ["surface"]] if not quick else [["slide"]]
    for section, keys in RUN.items():
        for key in keys:
            for value in BAD + ["<missing>"]:
                mutated = json.loads(json.dumps(RUN))
                drop = ()
                if value == "<missing>":
                    drop = (section, key)
                else:
                    mutated[section][key] = value
                path = tmp / "run.toml"
                path.write_text(toml(mutated, drop))
                for command in commands:
                    out = tmp / f"out-{section}-{key}"
                    p = run([*command, str(path), "--out", str(out)], timeout=120)
                    o = classify(p, out)
                    what = f"{section}.{key} = {value} ({command[0]})"
                    tally[("bad run-file values", o.kind)].append(f"{what}: {o.detail}")
                    subprocess.run(["rm", "-rf", str(out)])
    # Unknown keys and broken TOML.
    path = tmp / "run.toml"
    for text in [toml(RUN, extra="[extra]\nx = 1\n"), toml(RUN).replace("grid", "grdi"), "[surface\n", "", "x = "]:
        path.write_text(text)
        o = classify(run(["slide", str(path), "--out", str(tmp / "o")]))
        tally[("bad run files", o.kind)].append(o.detail)
    # Command-line arguments.
    path.write_text(toml(RUN))
    cases = [
        ["contact", str(path), "--load", v, "--out", str(tmp / "c")] for v in ["0", "-1", "nan", "inf", "1", "x"]
    ] + [
        ["contact", str(path), "--load", "1e-3", "--offset", v, "--out", str(tmp / "c")]
        for v in ["-1", "1e20", "nan", "1.0", "0.5001"]
    ]
    cases += [["--threads", v, "slide", str(path), "--out", str(tmp / "t")] for v in ["0", "3000", "-1", "x"]]
    cases += [["junctions", str(path), "--connectivity", v, "--out", str(tmp / "j")] for v in ["0", "6", "300"]]
    cases += [["bench", "--sizes", v] for v in ["16", "63", "100000", "0"]]
    cases += [["animate", str(path), "--out", str(tmp / "a.gif"), "--delay", v] for v in ["0", "700000"]]
    cases += [["study", "run", str(path), "--out", str(tmp / "s"), "--shard", v] for v in ["0/2", "3/2", "x", "1/0"]]
    for args in cases:
        o = classify(run(args, timeout=120))
        tally[("bad arguments", o.kind)].append(f"{' '.join(args[:1] + args[-2:])}: {o.detail}")
        for d in ["c", "t", "j", "s"]:
            subprocess.run(["rm", "-rf", str(tmp / d)])
    # Broken .npy surfaces (the fuzzing corpus).
    for npy in sorted((ROOT / "crates/wearsim/tests/fuzz-corpus/npy").iterdir()):
        text = toml({**RUN, "surface": {"top": f'"{npy}"', "bottom": f'"{npy}"', "length": "1.0"}})
        path.write_text(text)
        o = classify(run(["contact", str(path), "--load", "1e-3", "--out", str(tmp / "n")]))
        tally[("broken .npy files", o.kind)].append(f"{npy.name}: {o.detail}")
        subprocess.run(["rm", "-rf", str(tmp / "n")])


def kills_and_concurrency(tmp: Path, tally: dict, trials: int) -> None:
    study = tmp / "study.toml"
    study.write_text(STUDY.replace("grid = 64", "grid = 128"))
    reference = tmp / "reference"
    run(["study", "run", str(study), "--out", str(reference)])
    expected = results(reference)
    rng = random.Random(1)
    for t in range(trials):
        out = tmp / f"killed{t}"
        quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
        child = subprocess.Popen([WEARSIM, "study", "run", str(study), "--out", str(out)], **quiet)
        time.sleep(rng.uniform(0.05, 1.0))
        child.kill()
        child.wait()
        p = run(["study", "run", str(study), "--out", str(out)])
        ok = p is not None and p.returncode == 0 and results(out) == expected
        tally[("kill -9 during a study, then resume", "accepted" if ok else "data loss")].append(f"trial {t}")
    for t in range(trials):
        out = tmp / f"concurrent{t}"
        children = [
            subprocess.Popen(
                [WEARSIM, "study", "run", str(study), "--out", str(out), "--jobs", "1"],
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
            )
            for _ in range(2)
        ]
        outs = [c.communicate() for c in children]
        computed = sum(int(o[0].decode().split("computed ")[1].split()[0]) for o in outs if b"computed" in o[0])
        jobs = len(list((reference / "jobs").glob("job-*.json")))
        ok = all(c.returncode == 0 for c in children) and computed == jobs and results(out) == expected
        tally[("two full runs on one folder at once", "accepted" if ok else "data loss")].append(f"trial {t}")
    for t in range(max(1, trials // 2)):
        out = tmp / f"shards{t}"
        children = []
        for k in range(1, 9):
            time.sleep(rng.uniform(0.0, 0.05))
            children.append(
                subprocess.Popen(
                    [WEARSIM, "study", "run", str(study), "--out", str(out), "--shard", f"{k}/8", "--jobs", "1"],
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.PIPE,
                )
            )
        codes = [c.wait() for c in children]
        ok = all(c == 0 for c in codes) and results(out) == expected
        tally[("eight staggered shards on one folder", "accepted" if ok else "data loss")].append(f"trial {t}")


def disk_full_and_signals(tmp: Path, tally: dict, trials: int) -> None:
    path = tmp / "run.toml"
    path.write_text(toml(RUN).replace("loads = [1e-3]", "loads = [5e-4, 1e-3]"))
    for command, extra in [("surface", []), ("slide", []), ("contact", ["--load", "1e-3"])]:
        out = tmp / f"full-{command}"
        p = run([command, str(path), *extra, "--out", str(out)])
        before = {f.name: f.read_bytes() for f in out.iterdir()}
        for blocks in [1, 2, 8, 32]:
            script = f"trap '' XFSZ; ulimit -f {blocks}; exec {WEARSIM} {command} {path} {' '.join(extra)} --out {out}"
            p = subprocess.run(["sh", "-c", script], capture_output=True)
            after = {f.name: f.read_bytes() for f in out.iterdir()}
            hidden = [f for f in tmp.iterdir() if f.name.startswith(".")]
            intact = after == before or (p.returncode == 0)
            kind = "data loss" if not intact or hidden else ("clear error" if p.returncode else "accepted")
            tally[("disk full (file-size limit)", kind)].append(f"{command}, {blocks} blocks")
    big = tmp / "big.toml"
    big.write_text(
        toml(RUN)
        .replace("grid = 64", "grid = 256")
        .replace("lambda_lower = 0.0625", "lambda_lower = 0.03125")
        .replace("loads = [1e-3]", "loads = [5e-4, 1e-3, 2e-3]")
    )
    for t in range(trials):
        for sig in (signal.SIGINT, signal.SIGTERM):
            out = tmp / f"sig{t}"
            child = subprocess.Popen(
                [WEARSIM, "slide", str(big), "--out", str(out)],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.PIPE,
                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),  # not the shell's "ignored"
            )
            time.sleep(0.2 + 0.3 * t)
            child.send_signal(sig)
            child.wait()
            # Stopped: status 128 + the signal, no folder, only the checkpoint saved on the way out.
            hidden = [f for f in tmp.iterdir() if f.name.startswith(".") and f.name != f".sig{t}.checkpoint"]
            clean = (child.returncode == 128 + sig and not out.exists()) or child.returncode == 0
            kind = "clear error" if clean and not hidden else "data loss"
            (tmp / f".sig{t}.checkpoint").unlink(missing_ok=True)
            tally[("SIGINT / SIGTERM during a slide", kind)].append(f"{sig.name} after {0.2 + 0.3 * t:.1f} s")
            subprocess.run(["rm", "-rf", str(out)])


def huge_sizes(tmp: Path, tally: dict) -> None:
    path = tmp / "run.toml"
    for grid in ["100000", "65536", "40000", "1000000000"]:
        path.write_text(toml(RUN).replace("grid = 64", f"grid = {grid}"))
        for command in ["slide", "surface", "contact"]:
            extra = ["--load", "1e-3"] if command == "contact" else []
            o = classify(run([command, str(path), *extra, "--out", str(tmp / "h")]))
            tally[("huge sizes", o.kind)].append(f"{command} grid {grid}: {o.detail}")
        study = tmp / "h.toml"
        study.write_text(STUDY.replace("grid = 64", f"grid = {grid}"))
        o = classify(run(["study", "run", str(study), "--out", str(tmp / "hs")]))
        if (tmp / "hs").exists():
            o = Outcome("data loss", "study folder made before the refusal")
        tally[("huge sizes", o.kind)].append(f"study run grid {grid}: {o.detail}")
    for sizes in ["100000", "65536"]:
        o = classify(run(["bench", "--sizes", sizes]))
        tally[("huge sizes", o.kind)].append(f"bench {sizes}: {o.detail}")


def _fit(tmp: Path, surface: Path, out: str) -> dict | None:
    p = run(["surface", "fit", str(surface), "--length", "1.0", "--detrend", "none", "--out", str(tmp / out)])
    if p is None or p.returncode != 0:
        return None
    fit = json.loads((tmp / out / "fit.json").read_text())["fit"]
    subprocess.run(["rm", "-rf", str(tmp / out)])
    return fit


def second_round(tmp: Path, tally: dict) -> None:
    """The classes of the second round of trials (see the module documentation)."""
    # Spreadsheet CSV: the same 64 × 64 map as Excel and European spreadsheets save it.
    surface = tmp / "gen.toml"
    surface.write_text(toml({k: v for k, v in RUN.items() if k in ("surface", "material")}))
    run(["surface", str(surface), "--out", str(tmp / "g")])
    import numpy as np  # the trials need NumPy only for the CSV dialects

    h = np.load(tmp / "g" / "top.npy")
    lines = [[f"{v:.9e}" for v in row] for row in h.T]
    plain = tmp / "plain.csv"
    plain.write_text("\n".join(",".join(r) for r in lines) + "\n")
    reference = _fit(tmp, plain, "f")
    dialects = {
        "byte-order mark": ("\ufeff" + "\n".join(",".join(r) for r in lines) + "\n", True),
        "decimal commas, semicolons": ("\n".join(";".join(v.replace(".", ",") for v in r) for r in lines), True),
        "decimal commas, tabs": ("\n".join("\t".join(v.replace(".", ",") for v in r) for r in lines), True),
        "decimal commas, CRLF, BOM": (
            "\ufeff" + "\r\n".join(";".join(v.replace(".", ",") for v in r) for r in lines),
            True,
        ),
        "decimal commas, spaces": ("\n".join(" ".join(v.replace(".", ",") for v in r) for r in lines), False),
    }
    for name, (text, readable) in dialects.items():
        path = tmp / "dialect.csv"
        path.write_text(text, encoding="utf-8")
        p = run(["surface", "fit", str(path), "--length", "1.0", "--detrend", "none", "--out", str(tmp / "d")])
        o = classify(p)
        if o.kind == "accepted":
            fit = json.loads((tmp / "d" / "fit.json").read_text())["fit"]
            same = reference is not None and all(
                abs(fit[k] - reference[k]) <= 1e-9 * abs(reference[k]) for k in ("rms_height", "hurst")
            )
            o = Outcome("accepted" if same and readable else "silently wrong", name)
        tally[("spreadsheet CSV", o.kind)].append(f"{name}: {o.detail}")
        subprocess.run(["rm", "-rf", str(tmp / "d")])
    # Full contact near p_m = 3√3 τ̃: a junction around the box must be flagged.
    for load in ["0.0515", "0.05", "1e-3"]:
        path = tmp / "full.toml"
        text = toml(RUN).replace("loads = [1e-3]", f"loads = [{load}]").replace("distance = 0.5", "distance = 0.3")
        path.write_text(text)
        out = tmp / "full"
        o = classify(run(["slide", str(path), "--out", str(out)], timeout=300))
        if o.kind == "accepted":
            summary = json.loads((out / "summary.json").read_text())
            wrapped = "wraps the periodic box" in json.dumps(summary)
            area = max(float(line.split(",")[4]) for line in (out / "series.csv").read_text().splitlines()[1:])
            flagged = wrapped or area < 1.0  # full contact must be flagged
            o = Outcome(
                "accepted" if flagged else "silently wrong", f"F_N = {load}: contact area {area:.3f}, flagged {wrapped}"
            )
        tally[("full contact", o.kind)].append(o.detail)
        subprocess.run(["rm", "-rf", str(out)])
    # Study axes: repeated values and two-number grids must be refused, not run.
    for name, edit in [
        ("seed = [1, 1, 2]", ("seed = [1, 2, 3]", "seed = [1, 1, 2]")),
        ("loads = [1e-3, 1e-3]", ("loads = [5e-4, 1e-3]", "loads = [1e-3, 1e-3]")),
        ("grid = [64, 32]", ("grid = 64", "grid = [64, 32]")),
        ("length = [1.0, 0.5]", ("length = 1.0", "length = [1.0, 0.5]")),
        ('units = ["si", "reduced"]', ("[surface]", 'units = ["si", "reduced"]\n[surface]')),
    ]:
        study = tmp / "axes.toml"
        study.write_text(STUDY.replace(*edit))
        out = tmp / "axes"
        o = classify(run(["study", "run", str(study), "--out", str(out)], timeout=300))
        if o.kind == "accepted":
            o = Outcome("silently wrong", f"{name} ran")
        tally[("study axes", o.kind)].append(f"{name}: {o.detail}")
        subprocess.run(["rm", "-rf", str(out)])
    # Arguments.
    path = tmp / "run.toml"
    path.write_text(toml(RUN))
    study = tmp / "one.toml"
    study.write_text(toml(RUN))
    npy = tmp / "g" / "top.npy"
    long_name = tmp / ("a" * 250)
    cases = [
        ("--jobs 0", ["study", "run", str(study), "--out", str(tmp / "j0"), "--jobs", "0"]),
        ("three --length", ["surface", "fit", str(npy), "--length", "1", "--length", "1", "--length", "1"]),
        ("--length -1", ["surface", "fit", str(npy), "--length", "-1"]),
        ("--load -1e-3", ["contact", str(path), "--load", "-1e-3", "--out", str(tmp / "c")]),
        ("study collect of a plain folder", ["study", "collect", str(tmp / "g")]),
        ("study collect /dev/null", ["study", "collect", "/dev/null"]),
        ("study plot of a missing folder", ["study", "plot", str(tmp / "missing")]),
        ("a 250-character --out", ["surface", str(path), "--out", str(long_name)]),
        ("a directory as the run file", ["slide", str(tmp / "g"), "--out", str(tmp / "x")]),
        ("a directory as the height map", ["surface", "fit", str(tmp / "g"), "--length", "1"]),
    ]
    for name, args in cases:
        o = classify(run(args, timeout=300))
        if name == "a 250-character --out" and o.kind == "accepted":
            o = Outcome("accepted", "")
        elif o.kind == "clear error" and (".tmp" in o.detail or "os error" in o.detail or "1-0" in o.detail):
            o = Outcome("unclear error", o.detail)
        tally[("arguments and messages", o.kind)].append(f"{name}: {o.detail}")
        for d in ["j0", "c", "x", long_name.name]:
            subprocess.run(["rm", "-rf", str(tmp / d)])
    env = {**os.environ, "SLURM_ARRAY_TASK_ID": "1", "SLURM_ARRAY_TASK_COUNT": "0"}
    o = classify(run(["study", "run", str(study), "--out", str(tmp / "sl")], env=env))
    if "1-0" in o.detail or "K/0" in o.detail:
        o = Outcome("unclear error", o.detail)
    tally[("arguments and messages", o.kind)].append(f"Slurm count 0: {o.detail}")

    # Extreme SI scales: the same dimensionless run at L = 1e-80 … 1e80 m gives the scaled results
    # (W/L², k, dN*₊/ds·L); beyond the representable range it is refused.
    def scaled_run(length: float) -> str:
        return (
            f'units = "si"\n[surface]\ngrid = 64\nlength = {length:e}\nhurst = 0.7\nlambda_lower = {length / 16:e}\n'
            f"lambda_upper = {length / 4:e}\nrms_height = {0.005 * length:e}\nseed = 1\n[material]\n"
            f"youngs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n"
            f"fracture_energies = [{2.5e-7 * length:e}]\n"
            f"[sliding]\nloads = [{1e-3 * length * length:e}]\n"
        )

    def reduced(length: float) -> Optional[Tuple[float, ...]]:
        path = tmp / "scale.toml"
        path.write_text(scaled_run(length))
        out = tmp / "scale"
        p = run(["slide", str(path), "--out", str(out)], timeout=300)
        if p.returncode != 0:
            return None
        r = json.loads((out / "summary.json").read_text())["results"][0]
        subprocess.run(["rm", "-rf", str(out)])
        if r["wear_rate"] is None or r["wear_rate_r2"] is None:
            return (float("nan"),)
        return (r["wear_rate"] / length**2, r["wear_rate_r2"], r["wear_coefficient"], r["particle_rate"] * length)

    unit = reduced(1.0)
    for length in [1e-80, 1e-40, 1e40, 1e80]:
        got = reduced(length)
        same = unit is not None and got is not None and all(abs(a - b) <= 1e-9 * abs(a) for a, b in zip(unit, got))
        tally[("extreme SI scales", "accepted" if same else "silently wrong")].append(f"L = {length:e} m: {got}")
    for length in [1e-95, 1e95]:
        path = tmp / "scale.toml"
        path.write_text(scaled_run(length))
        o = classify(run(["slide", str(path), "--out", str(tmp / "scale")], timeout=300))
        if o.kind == "clear error" and "1e-90" not in o.detail:
            o = Outcome("unclear error", o.detail)
        elif o.kind == "accepted":
            o = Outcome("silently wrong", f"L = {length:e} m ran")
        tally[("extreme SI scales", o.kind)].append(f"L = {length:e} m: {o.detail}")
        subprocess.run(["rm", "-rf", str(tmp / "scale")])
    # surface fit on surfaces wearsim generated (512², both methods): H within ±0.05, cut-offs ×1.2.
    for generation in ["random-phase", "filtered-noise"]:
        for hurst, lower in [("0.8", "0.015625"), ("0.7", "0.03125"), ("0.5", "0.015625")]:
            text = toml({k: v for k, v in RUN.items() if k in ("surface", "material")})
            text = text.replace("grid = 64", "grid = 512").replace("hurst = 0.7", f"hurst = {hurst}")
            text = text.replace("lambda_lower = 0.0625", f"lambda_lower = {lower}")
            text = text.replace('"random-phase"', f'"{generation}"')
            surface.write_text(text)
            run(["surface", str(surface), "--out", str(tmp / "s512")])
            fit = _fit(tmp, tmp / "s512" / "top.npy", "f512")
            if fit is None:
                tally[("surface fit of generated surfaces", "clear error")].append(f"{generation} H {hurst}")
                continue
            good = (
                abs(fit["hurst"] - float(hurst)) <= 0.05
                and 1 / 1.2 < fit["lambda_lower"] / float(lower) < 1.2
                and 1 / 1.2 < fit["lambda_upper"] / 0.25 < 1.2
            )
            detail = (
                f"{generation} H {hurst} λ_l {lower}: fitted H {fit['hurst']:.3f}, "
                f"λ_l {fit['lambda_lower']:.4g}, λ_u {fit['lambda_upper']:.4g}"
            )
            tally[("surface fit of generated surfaces", "accepted" if good else "silently wrong")].append(detail)
            subprocess.run(["rm", "-rf", str(tmp / "s512")])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer trials")
    parser.add_argument("--verbose", action="store_true", help="list every trial")
    parser.add_argument("--second-round", action="store_true", help="only the classes of the second round")
    parser.add_argument("--third-round", action="store_true", help="only the classes of the third round")
    args = parser.parse_args()
    tally: dict = collections.defaultdict(list)
    start = time.time()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        if not (args.second_round or args.third_round):
            bad_inputs(tmp, tally, args.quick)
            kills_and_concurrency(tmp, tally, 3 if args.quick else 10)
            disk_full_and_signals(tmp, tally, 2 if args.quick else 5)
            huge_sizes(tmp, tally)
        if not args.third_round:
            second_round(tmp, tally)
        if not args.second_round:
            from reliability_third_round import third_round

            third_round(tmp, tally, args.quick)
    classes = sorted({c for c, _ in tally})
    kinds = ["accepted", "clear error", "unclear error", "panic", "abort", "hang", "data loss", "silently wrong"]
    kinds.append("ignored signal")
    print(f"| class | trials | {' | '.join(kinds)} |")
    print("|---|---|" + "---|" * len(kinds))
    for c in classes:
        counts = [len(tally[(c, k)]) for k in kinds]
        print(f"| {c} | {sum(counts)} | {' | '.join(map(str, counts))} |")
    totals = [sum(len(tally[(c, k)]) for c in classes) for k in kinds]
    print(f"| **all** | {sum(totals)} | {' | '.join(map(str, totals))} |")
    for k in ["unclear error", "panic", "abort", "hang", "data loss", "silently wrong", "ignored signal"]:
        for c in classes:
            for detail in tally[(c, k)]:
                print(f"{k}: {c}: {detail}")
    if args.verbose:
        for (c, k), details in sorted(tally.items()):
            for detail in details:
                print(f"{c} / {k}: {detail}")
    print(f"{time.time() - start:.0f} s")


if __name__ == "__main__":
    main()
