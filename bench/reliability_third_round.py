"""The third round of reliability trials (``python bench/reliability_trials.py --third-round``): folders
and files that are not wearsim's, checkpoints and job files that lie, limits a cluster sets, signals
every command must obey, and the messages and Python API items of that round. Each trial is
classified as in the first rounds, with one more kind: ``ignored signal`` (a command that ran on to
exit 0 well after a stop signal, or that did not stop within 10 s)."""

from __future__ import annotations

import json
import os
import random
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import reliability_common as rt

SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGUSR1, signal.SIGUSR2)


def _default_signals() -> None:
    # A campaign started from a background shell passes SIGINT on ignored; the trials want it live.
    for s in (*SIGNALS, signal.SIGHUP):
        signal.signal(s, signal.SIG_DFL)


def popen(args: list, **kw) -> subprocess.Popen:
    kw.setdefault("stdout", subprocess.DEVNULL)
    kw.setdefault("stderr", subprocess.PIPE)
    return subprocess.Popen([rt.WEARSIM, *map(str, args)], preexec_fn=_default_signals, **kw)


def hidden(folder: Path, allowed: tuple = ()) -> list:
    return [p.name for p in folder.iterdir() if p.name.startswith(".") and p.name not in allowed]


def sliding_run(grid: int = 64, loads: str = "[1e-3]", extra: str = "") -> str:
    return (
        rt.toml(rt.RUN)
        .replace("grid = 64", f"grid = {grid}")
        .replace("lambda_lower = 0.0625", f"lambda_lower = {min(16 / grid, 0.0625)}")
        .replace("loads = [1e-3]", f"loads = {loads}")
        + extra
    )


def folders_and_files(tmp: Path, tally: dict) -> None:
    """Folders and files that are not ours: each trial must be refused with the file intact."""
    run_path = tmp / "run.toml"
    run_path.write_text(sliding_run())
    study = tmp / "study.toml"
    study.write_text(rt.STUDY)
    cls = "folders and files not wearsim's"

    def refused(name: str, args: list, keep: Path, cwd: Path = tmp) -> None:
        before = keep.read_bytes() if keep.is_file() else sorted(p.name for p in keep.rglob("*"))
        p = subprocess.run([rt.WEARSIM, *map(str, args)], capture_output=True, cwd=cwd)
        after = keep.read_bytes() if keep.is_file() else sorted(p.name for p in keep.rglob("*"))
        o = rt.classify(p)
        kind = "data loss" if after != before else ("accepted" if o.kind == "accepted" else o.kind)
        tally[(cls, kind)].append(f"{name}: {o.detail}")

    mine = tmp / "mine"
    mine.mkdir()
    (mine / "results.csv").write_text("my,own\n")
    refused("study run into a folder holding the user's results.csv", ["study", "run", study, "--out", mine], mine)
    rt.run(["study", "run", str(study), "--out", str(tmp / "res")])
    refused("slide into a finished study's folder", ["slide", run_path, "--out", tmp / "res"], tmp / "res")
    rt.run(["slide", str(run_path), "--out", str(tmp / "sl")])
    refused("study run into a slide's folder", ["study", "run", study, "--out", tmp / "sl"], tmp / "sl")
    (tmp / "sl" / "notes.txt").write_text("mine")
    refused("slide into its folder holding the user's notes.txt", ["slide", run_path, "--out", tmp / "sl"], tmp / "sl")
    gif_run = tmp / "run.gif"
    gif_run.write_text(sliding_run())
    (tmp / "link.gif").symlink_to(gif_run)
    for spelling in ["run.gif", "./run.gif", "link.gif", str(gif_run)]:
        refused(
            f"animate run.gif --out {spelling} --overwrite",
            ["animate", "run.gif", "--out", spelling, "--overwrite"],
            gif_run,
        )
    (tmp / "sub").mkdir()
    refused(
        "animate from another cwd, --out ../run.gif",
        ["animate", gif_run, "--out", "../run.gif"],
        gif_run,
        cwd=tmp / "sub",
    )
    theirs = tmp / "theirs.gif"
    theirs.write_bytes(b"GIF89a someone else's")
    refused("animate --out a GIF it did not write", ["animate", run_path, "--out", theirs], theirs)
    rt.run(["slide", str(run_path), "--out", str(tmp / "fs"), "--save-fields"])
    store = tmp / "fs" / "fields.zarr"
    python = os.environ.get("WEARSIM_PYTHON", sys.executable)
    for target in [tmp / "fs" / "summary.json", store / ".zattrs", store / ".zgroup", run_path]:
        refused(
            f"fields to-netcdf onto {target.relative_to(tmp)}",
            ["fields", "to-netcdf", store, target, "--python", python],
            target,
        )
    refused(
        "fields to-netcdf onto ./fs/fields.zarr/.zattrs --overwrite (inside its input)",
        ["fields", "to-netcdf", store, "./fs/fields.zarr/.zattrs", "--overwrite", "--python", python],
        store / ".zattrs",
    )


def partial_files(tmp: Path, tally: dict) -> None:
    """Partial files of killed runs and claims a full disk left empty: removed, never blocking."""
    cls = "partial files and empty claims"
    host = socket.gethostname()
    run_path = tmp / "pf.toml"
    run_path.write_text(sliding_run(128, "[5e-4, 1e-3]"))
    for t in range(3):
        out = tmp / f"anim{t}.gif"
        child = popen(["animate", run_path, "--out", out])
        time.sleep(0.5 + 0.3 * t)
        child.kill()
        child.wait()
        p = rt.run(["animate", str(run_path), "--out", str(out)])
        left = [n for n in hidden(tmp) if n.startswith(f".{out.name}.")]
        ok = p is not None and p.returncode == 0 and not left
        tally[(cls, "accepted" if ok else "data loss")].append(f"animate killed after {0.5 + 0.3 * t:.1f} s: {left}")
    for t in range(2):
        out = tmp / f"ck{t}"
        stale = tmp / f"..ck{t}.checkpoint.{host}.4000000000-0.tmp"
        stale.write_bytes(b"wearsim sliding checkpoint 3\n cut")
        p = rt.run(["slide", str(run_path), "--out", str(out)])
        ok = p is not None and p.returncode == 0 and not stale.exists()
        tally[(cls, "accepted" if ok else "data loss")].append(f"a checkpoint's temporary file of a killed save: {ok}")
    for command, extra in [("slide", []), ("surface", []), ("contact", ["--load", "1e-3"])]:
        out = tmp / f"claim-{command}"
        script = f"trap '' XFSZ; ulimit -f 0; exec {rt.WEARSIM} {command} {run_path} {' '.join(extra)} --out {out}"
        subprocess.run(["sh", "-c", script], capture_output=True)
        p = rt.run([command, str(run_path), *extra, "--out", str(out)])
        o = rt.classify(p)
        kind = "accepted" if o.kind == "accepted" else "unclear error"
        tally[(cls, kind)].append(f"{command} retried at once after a full disk left its claim: {o.detail}")


def stopped_checkpoint(tmp: Path, run_path: Path, out: Path, after: float) -> bytes | None:
    child = popen(["slide", run_path, "--out", out, "--checkpoint-every", "1h"])
    time.sleep(after)
    child.send_signal(signal.SIGTERM)
    child.wait()
    checkpoint = out.parent / f".{out.name}.checkpoint"
    return checkpoint.read_bytes() if checkpoint.exists() else None


def damaged_checkpoints(tmp: Path, tally: dict, trials: int) -> None:
    """A checkpoint saved by a stopped run, then damaged: never resumed, the run starts over."""
    cls = "damaged checkpoints"
    run_path = tmp / "lie.toml"
    run_path.write_text(sliding_run(128, "[5e-4, 1e-3, 2e-3]"))
    start = time.monotonic()
    rt.run(["slide", str(run_path), "--out", str(tmp / "lie-ref")])
    duration = time.monotonic() - start
    expected = (tmp / "lie-ref" / "series.csv").read_bytes()
    out = tmp / "lie"
    saved = None
    for part in (0.4, 0.2, 0.1):  # stopped part-way (a loaded machine runs slower or faster)
        saved = saved or stopped_checkpoint(tmp, run_path, out, part * duration)
    if saved is None:
        tally[(cls, "unclear error")].append("no checkpoint saved by a stopped run: nothing to damage")
        return
    rng = random.Random(3)
    body = saved.index(b"{")
    damages = []
    for _ in range(trials):
        k = rng.randrange(body, len(saved))
        flipped = bytearray(saved)
        flipped[k] ^= 1 << rng.randrange(8)
        damages.append((f"bit flipped at byte {k}", bytes(flipped)))
    digits = [k for k in range(body, min(len(saved), body + 20000)) if chr(saved[k]).isdigit()]
    for k in rng.sample(digits, min(trials, len(digits))):
        changed = bytearray(saved)
        changed[k] = ord("7") if changed[k] != ord("7") else ord("3")
        damages.append((f"digit changed at byte {k}", bytes(changed)))
    nan = bytearray(saved)
    nan[-80:-72] = b"\x00\x00\x00\x00\x00\x00\xf8\x7f"
    damages.append(("NaN bytes in the pressure", bytes(nan)))
    checkpoint = tmp / ".lie.checkpoint"
    for name, data in damages:
        checkpoint.write_bytes(data)
        p = rt.run(["slide", str(run_path), "--out", str(out), "--overwrite"])
        err = p.stderr.decode() if p else ""
        same = p is not None and p.returncode == 0 and (out / "series.csv").read_bytes() == expected
        if "resuming" in err:
            kind = "silently wrong" if not same else "accepted"
        else:
            kind = "accepted" if same and "checkpoint not used" in err else "silently wrong"
        tally[(cls, kind)].append(f"{name}: {err.strip().splitlines()[0] if err else ''}")


def edited_job_files(tmp: Path, tally: dict) -> None:
    """Job files edited to results no run gives: named by collect, recomputed by study run."""
    cls = "edited job files"
    study = tmp / "jobs.toml"
    study.write_text(rt.STUDY.replace("fracture_energies = [0.5e-6]", "fracture_energies = [0.25e-6, 1e-6]"))
    folder = tmp / "jobs"
    rt.run(["study", "run", str(study), "--out", str(folder)])
    reference = rt.results(folder)
    job = folder / "jobs" / "job-000002.json"
    original = job.read_text()
    doc = json.loads(original)
    doc.pop("checksum", None)

    def edited(f) -> str:
        d = json.loads(json.dumps(doc))
        f(d)
        return json.dumps(d)

    w = doc["results"][0]["wear_rate"]
    cases = {
        '"results": []': edited(lambda d: d.__setitem__("results", [])),
        "a negative wear rate": edited(lambda d: d["results"][0].__setitem__("wear_rate", -1e-3)),
        "R² = 7": edited(lambda d: d["results"][1].__setitem__("wear_rate_r2", 7.0)),
        "a volume that falls": edited(lambda d: d["steps"][-1]["volume"].__setitem__(0, 0.0)),
        "a contact area of 2": edited(lambda d: d["steps"][3].__setitem__("contact_area", 2.0)),
        "one digit of W changed, checksum kept": original.replace(repr(w)[:6], repr(w)[:5] + "9", 1),
        "one result of the two removed": edited(lambda d: d["results"].pop()),
    }
    for name, text in cases.items():
        job.write_text(text)
        p = rt.run(["study", "collect", str(folder)])
        named = p is not None and p.returncode != 0 and "job-000002.json" in p.stderr.decode()
        kind = "clear error" if named else "silently wrong"
        again = rt.run(["study", "run", str(study), "--out", str(folder)])
        if again is None or again.returncode != 0 or rt.results(folder) != reference:
            kind = "data loss"
        tally[(cls, kind)].append(f"{name}: {p.stderr.decode().strip()[-160:] if p else ''}")
    # R² of a fit with no particle: null, never a number.
    cls = "undefined R²"
    for seed in range(1, 7):
        path = tmp / "r2.toml"
        path.write_text(
            sliding_run(64, "[5e-4, 1e-3, 2e-3]")
            .replace("seed = 1", f"seed = {seed}")
            .replace("fracture_energies = [0.5e-6]", "fracture_energies = [0.3e-6, 3e-6, 30e-6]")
        )
        rt.run(["slide", str(path), "--out", str(tmp / "r2"), "--overwrite"])
        results = json.loads((tmp / "r2" / "summary.json").read_text())["results"]
        bad = [
            r for r in results if r["particles_in_fit"] == 0 and (r["wear_rate_r2"] is not None or r["wear_rate"] != 0)
        ]
        tally[(cls, "silently wrong" if bad else "accepted")].append(f"surface pair {seed}: {len(bad)} defined")


def zeros_npz(path: Path, rows: int, cols: int) -> None:
    """An .npz of `heights`, rows × cols zeros, deflated (written with zlib, no NumPy needed)."""
    import zipfile

    header = f"{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, {cols}), }}"
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED, allowZip64=True) as z:
        with z.open("heights.npy", "w", force_zip64=True) as f:
            f.write(b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + header.encode())
            row = bytes(cols * 8)
            for _ in range(rows):
                f.write(row)


def limits(tmp: Path, tally: dict) -> None:
    cls = "memory limits"
    for grid in [2048, 4096]:
        path = tmp / f"mem{grid}.toml"
        path.write_text(
            sliding_run(grid)
            .replace("distance = 0.5", "distance = 0.05")
            .replace("running_in = 0.25", "running_in = 0.02")
        )
        study = tmp / f"mem{grid}s.toml"
        study.write_text(path.read_text().replace("seed = 1", "seed = [1, 2]"))
        for limit in ["ulimit -v 400000", "SLURM_MEM_PER_NODE=300", "SLURM_MEM_PER_CPU=100 SLURM_CPUS_ON_NODE=2"]:
            for command, extra in [("slide", []), ("contact", ["--load", "1e-3"]), ("surface", []), ("study run", [])]:
                target = study if command == "study run" else path
                out = tmp / "mem-out"
                prefix = f"{limit}; exec" if limit.startswith("ulimit") else f"exec env {limit}"
                script = f"{prefix} {rt.WEARSIM} {command} {target} {' '.join(extra)} --out {out}"
                p = subprocess.run(["sh", "-c", script], capture_output=True, timeout=600)
                o = rt.classify(p)
                if o.kind == "clear error" and "MiB" not in o.detail and "GiB" not in o.detail:
                    o = rt.Outcome("unclear error", o.detail)
                tally[(cls, o.kind)].append(f"{command} {grid}² under {limit}: {o.detail[-150:]}")
                subprocess.run(["rm", "-rf", str(out)])
    cls = "compressed and large inputs"
    for rows in [4000, 8000]:
        npz = tmp / f"zeros{rows}.npz"
        zeros_npz(npz, rows, rows)
        path = tmp / "npz.toml"
        path.write_text(
            f'[surface]\ntop = "{npz}"\nbottom = "{npz}"\nlength = 1.0\n[material]\nyoungs_modulus = 1.0\n'
            "poisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-6]\n"
        )
        for args in (
            ["surface", str(path), "--out", str(tmp / "npz-out")],
            ["surface", "fit", str(npz), "--length", "1"],
        ):
            start = time.monotonic()
            p = subprocess.run(
                [rt.WEARSIM, *args], capture_output=True, env={**os.environ, "SLURM_MEM_PER_NODE": "100"}
            )
            o = rt.classify(p)
            if o.kind == "clear error" and time.monotonic() - start > 5:
                o = rt.Outcome("unclear error", f"refused only after {time.monotonic() - start:.0f} s")
            tally[(cls, o.kind)].append(
                f"{' '.join(args[:2])} of {rows}² zeros ({npz.stat().st_size} bytes): {o.detail[-120:]}"
            )
    cls = "names"
    for name, good in [
        ('"steel\\nhard"', False),
        (f'"{"x" * 60000}"', False),
        ('"tab\\there"', False),
        (f'"{"x" * 100}"', True),
        ('"Si₃N₄, 1200 °C"', True),
    ]:
        path = tmp / "names.toml"
        path.write_text(rt.STUDY.replace("[material]", f"[[materials]]\nname = {name}"))
        p = rt.run(["study", "run", str(path), "--out", str(tmp / "names-out")])
        o = rt.classify(p)
        if o.kind == "accepted" and not good:
            o = rt.Outcome("silently wrong", "ran")
        elif o.kind == "clear error" and ("`name`" not in o.detail or len(o.detail) > 400):
            o = rt.Outcome("unclear error", o.detail[:200])
        tally[(cls, o.kind)].append(f"{name[:20]}: {o.detail[:150]}")
        subprocess.run(["rm", "-rf", str(tmp / "names-out")])


def signals_everywhere(tmp: Path, tally: dict) -> None:
    """Every command stopped by each stop signal while at work: exit 128 + n, nothing half-written."""
    cls = "stop signals, every command"
    big = tmp / "sig.toml"
    big.write_text(sliding_run(1024, "[5e-4, 1e-3]"))
    fit = tmp / "sig-fit.toml"  # a 2048² map: `surface fit` at work for a few tenths of a second
    fit.write_text(sliding_run(2048))
    rt.run(["surface", str(fit), "--out", str(tmp / "sig-s")])
    study = tmp / "sigs.toml"
    study.write_text(sliding_run(64, "[5e-4, 1e-3, 2e-3]").replace("seed = 1", "seed = [1, 2, 3, 4, 5, 6, 7, 8]"))
    rt.run(["study", "run", str(study), "--out", str(tmp / "sig-study")])
    rt.run(["study", "collect", str(tmp / "sig-study")])
    short = tmp / "sig-short.toml"  # a store of a few steps to convert
    short.write_text(
        big.read_text().replace("distance = 0.5", "distance = 0.02").replace("running_in = 0.25", "running_in = 0.01")
    )
    rt.run(["slide", str(short), "--out", str(tmp / "sig-f"), "--save-fields"], timeout=600)
    python = os.environ.get("WEARSIM_PYTHON", sys.executable)
    commands = {
        "surface": (["surface", big, "--out", tmp / "o-surface"], tmp / ".o-surface.claim"),
        "surface fit": (["surface", "fit", tmp / "sig-s" / "top.npy", "--length", "1", "--out", tmp / "o-fit"], None),
        "contact": (["contact", big, "--load", "1e-3", "--out", tmp / "o-contact"], tmp / ".o-contact.claim"),
        "slide": (["slide", big, "--out", tmp / "o-slide"], tmp / ".o-slide.claim"),
        "animate": (["animate", big, "--out", tmp / "o-anim.gif"], None),
        "study run": (["study", "run", study, "--out", tmp / "o-study", "--jobs", "1"], None),
        "study collect": (["study", "collect", tmp / "sig-study"], None),
        "study plot": (["study", "plot", tmp / "sig-study"], None),
        "bench": (["bench", "--sizes", "1024,1024"], None),
        "fields to-netcdf": (
            ["fields", "to-netcdf", tmp / "sig-f" / "fields.zarr", tmp / "o.nc", "--python", python],
            None,
        ),
    }
    rng = random.Random(7)
    for name, (args, marker) in commands.items():
        # Commands without a marker are stopped part-way through their own duration, measured first.
        duration = 1.0
        if name in ("surface fit", "study collect", "study plot"):
            start = time.monotonic()
            subprocess.run([rt.WEARSIM, *map(str, args)], capture_output=True)
            duration = time.monotonic() - start
        for sig in SIGNALS:
            child = popen(args)
            start = time.monotonic()
            if marker is not None:
                while not marker.exists() and child.poll() is None and time.monotonic() - start < 30:
                    time.sleep(0.002)
            else:
                time.sleep(min(0.3, rng.uniform(0.3, 0.7) * duration))
            sent = time.monotonic()
            child.send_signal(sig)
            try:
                child.wait(timeout=10)
            except subprocess.TimeoutExpired:
                child.kill()
                child.wait()
                tally[(cls, "ignored signal")].append(f"{name}, {sig.name}: still running 10 s later")
                continue
            took = time.monotonic() - sent
            err = child.stderr.read().decode(errors="replace") if child.stderr else ""
            stray = [n for n in hidden(tmp) if not n.endswith(".checkpoint") and not n.startswith(".sig")]
            stray += [n for n in hidden(tmp / "sig-study") if n != ".wearsim.json"]
            if child.returncode == 0:
                kind = "ignored signal" if took > 1.0 else "accepted"
            elif child.returncode in (128 + sig, -sig) and not stray:  # -sig: stopped before its handler was set
                kind = "clear error"
            elif child.returncode == 128 + sig:
                kind = "data loss"
            else:
                kind = rt.classify(subprocess.CompletedProcess(args, child.returncode, b"", err.encode())).kind
            tally[(cls, kind)].append(f"{name}, {sig.name}: status {child.returncode} in {took:.2f} s {stray}")
            for leftover in ["o-surface", "o-fit", "o-contact", "o-slide", "o-anim.gif", "o-study", "o.nc"]:
                subprocess.run(["rm", "-rf", str(tmp / leftover)])
            for ck in tmp.glob(".o-*.checkpoint"):
                ck.unlink()


def slurm_time_limits(tmp: Path, tally: dict, trials: int) -> None:
    """A Slurm time limit (SIGTERM, a grace period, SIGKILL) or --signal=USR1: nothing lost."""
    cls = "Slurm time limit, then resubmit"
    path = tmp / "slurm.toml"
    path.write_text(sliding_run(128, "[5e-4, 1e-3, 2e-3]"))
    start = time.monotonic()
    rt.run(["slide", str(path), "--out", str(tmp / "slurm-ref")])
    duration = time.monotonic() - start  # each run is stopped part-way through it
    expected = (tmp / "slurm-ref" / "series.csv").read_bytes()
    rng = random.Random(5)
    for t in range(trials):
        sig = [signal.SIGTERM, signal.SIGUSR1][t % 2]
        out = tmp / f"slurm{t}"
        child = popen(["slide", path, "--out", out])  # the default 5 min between checkpoints
        time.sleep(rng.uniform(0.2, 0.8) * duration)
        child.send_signal(sig)
        try:
            child.wait(timeout=2)  # the grace period
        except subprocess.TimeoutExpired:
            child.kill()
            child.wait()
        err = child.stderr.read().decode() if child.stderr else ""
        again = rt.run(["slide", str(path), "--out", str(out)])
        same = again is not None and again.returncode == 0 and (out / "series.csv").read_bytes() == expected
        resumed = again is not None and "resuming" in again.stderr.decode()
        stopped = child.returncode != 0  # stopped part-way: its work must not be lost
        kind = "accepted" if same and (resumed or not stopped) else ("data loss" if not same else "silently wrong")
        if stopped and not resumed:
            kind = "data loss"  # the work before the stop was lost
        tally[(cls, kind)].append(f"slide, {sig.name}: status {child.returncode}, resumed {resumed}; {err[-80:]}")
    study = tmp / "slurm-study.toml"
    study.write_text(sliding_run(128, "[5e-4, 1e-3]").replace("seed = 1", "seed = [1, 2]"))
    start = time.monotonic()
    rt.run(["study", "run", str(study), "--out", str(tmp / "slurm-sref"), "--jobs", "1"])
    duration = time.monotonic() - start
    expected_table = rt.results(tmp / "slurm-sref")
    for t in range(max(1, trials // 2)):
        out = tmp / f"slurm-study{t}"
        child = popen(["study", "run", study, "--out", out, "--jobs", "1"])
        time.sleep(rng.uniform(0.2, 0.8) * duration)
        child.send_signal(signal.SIGTERM)
        child.wait()
        rt.run(["study", "run", str(study), "--out", str(out)])
        same = rt.results(out) == expected_table
        tally[(cls, "accepted" if same else "data loss")].append(f"study run, SIGTERM: status {child.returncode}")
    cls = "checkpoint that cannot be written"
    for t, how in enumerate(["a folder in its place", "a file-size limit"]):
        out = tmp / f"nock{t}"
        if how.startswith("a folder"):
            (tmp / f".nock{t}.checkpoint").mkdir()
            (tmp / f".nock{t}.checkpoint" / "x").write_text("")
            p = rt.run(["slide", str(path), "--out", str(out), "--checkpoint-every", "0s"])
        else:
            script = f"trap '' XFSZ; ulimit -f 200; exec {rt.WEARSIM} slide {path} --out {out} --checkpoint-every 0s"
            p = subprocess.run(["sh", "-c", script], capture_output=True)
        err = p.stderr.decode()
        same = p.returncode == 0 and (out / "series.csv").read_bytes() == expected
        kind = (
            "accepted"
            if same and "checkpoint not saved" in err
            else ("data loss" if p.returncode else "silently wrong")
        )
        tally[(cls, kind)].append(f"{how}: status {p.returncode}")


def tolerance_and_messages(tmp: Path, tally: dict) -> None:
    cls = "solver tolerance"
    for tol in ["1e-8", "1e-6", "1e-5", "1e-3", "0.1", "0.5", "0.9"]:
        path = tmp / "tol.toml"
        path.write_text(sliding_run(64).replace("tolerance = 1e-8", f"tolerance = {tol}"))
        p = rt.run(["slide", str(path), "--out", str(tmp / "tol"), "--overwrite"])
        warned = p is not None and "[contact] tolerance" in p.stderr.decode()
        loose = float(tol) > 1e-6
        kind = "accepted" if p is not None and p.returncode == 0 and warned == loose else "silently wrong"
        tally[(cls, kind)].append(f"tolerance {tol}: warned {warned}")
    cls = "messages of the third round"
    afile = tmp / "afile"
    afile.write_text("x")
    path = tmp / "msg.toml"
    path.write_text(sliding_run(64))
    jobs_file = tmp / "jobsfile"
    jobs_file.mkdir()
    (jobs_file / "jobs").write_text("")
    study = tmp / "msg-study.toml"
    study.write_text(rt.STUDY)
    dev = tmp / "dev.toml"
    dev.write_text(rt.toml({**rt.RUN, "surface": {"top": '"/dev/zero"', "bottom": '"/dev/zero"', "length": "1.0"}}))
    cases = [
        ("--out afile/sub", ["slide", str(path), "--out", str(afile / "sub")], "is a file, not a folder"),
        ("a study folder whose jobs is a file", ["study", "run", str(study), "--out", str(jobs_file)], "jobs"),
        (
            "/dev/zero as a surface",
            ["contact", str(dev), "--load", "1e-3", "--out", str(tmp / "dz")],
            "not a regular file",
        ),
        ("surface fit /dev/zero", ["surface", "fit", "/dev/zero", "--length", "1"], "not a regular file"),
    ]
    for name, args, words in cases:
        o = rt.classify(rt.run(args, timeout=60))
        if o.kind != "clear error" or words not in o.detail or "os error" in o.detail:
            o = rt.Outcome("unclear error" if o.kind != "hang" else "hang", o.detail)
        tally[(cls, o.kind)].append(f"{name}: {o.detail[:160]}")
    # A measured pair with a constant offset of 1e6 and no levelling: the same contact as without.
    rt.run(["surface", str(path), "--out", str(tmp / "off")])
    import numpy as np

    areas = []
    for offset in [0.0, 1e6, -3e7]:
        for name in ["top", "bottom"]:
            np.save(tmp / f"{name}{offset}.npy", np.load(tmp / "off" / f"{name}.npy") + offset)
        run_path = tmp / "offset.toml"
        run_path.write_text(
            rt.toml(
                {
                    **rt.RUN,
                    "surface": {
                        "top": f'"{tmp}/top{offset}.npy"',
                        "bottom": f'"{tmp}/bottom{offset}.npy"',
                        "length": "1.0",
                    },
                }
            )
        )
        p = rt.run(["contact", str(run_path), "--load", "1e-3", "--out", str(tmp / "offc"), "--overwrite"])
        o = rt.classify(p)
        if o.kind == "accepted":
            areas.append(json.loads((tmp / "offc" / "summary.json").read_text())["contact_area"])
            same = abs(areas[-1] - areas[0]) < 1e-9
            o = rt.Outcome("accepted" if same else "silently wrong", f"area {areas[-1]}")
        elif "did not converge" in o.detail:
            o = rt.Outcome("unclear error", o.detail[:160])
        tally[(cls, o.kind)].append(f"offset {offset:g}, no levelling: {o.detail}")
    # study plot on a full disk names the file it could not write.
    tiny = tmp / "plotstudy"
    rt.run(["study", "run", str(study), "--out", str(tiny)])
    for blocks in [4, 64]:
        script = f"trap '' XFSZ; ulimit -f {blocks}; exec {rt.WEARSIM} study plot {tiny}"
        p = subprocess.run(["sh", "-c", script], capture_output=True)
        o = rt.classify(p)
        if o.kind == "clear error" and not any(w in o.detail for w in (".png", ".svg", ".md", ".csv", "figures")):
            o = rt.Outcome("unclear error", o.detail[:160])
        tally[(cls, o.kind)].append(f"study plot under a {blocks}-block file limit: {o.detail[:160]}")


PYTHON_CHECKS = r"""
import copy, pickle, sys, threading, tomllib, os
from concurrent.futures import ThreadPoolExecutor
import numpy as np
import wearsim
out = {}
def check(name, f):
    try:
        out[name] = "accepted" if f() else "silently wrong"
    except Exception as e:
        out[name] = f"error: {type(e).__name__}: {str(e)[:150]}"
m = wearsim.Material(1.0, 0.3, 0.01, [1e-6])
s = wearsim.ContactSolver(64, 1.0, 1.0)
open("run.toml", "w").write(
    "[surface]\ngrid = 64\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\nseed = 1\n"
    "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-6]\n"
)
r = wearsim.RunFile("run.toml")
for name, obj in [("Material", m), ("RunFile", r), ("ContactSolver", s)]:
    check(f"pickle {name}", lambda: type(pickle.loads(pickle.dumps(obj))) is type(obj))
    check(f"deepcopy {name}", lambda: type(copy.deepcopy(obj)) is type(obj))
t, b = wearsim.generate_pair(64, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005, seed=1)
ref = s.solve(t - b, 1e-3).pressure
with ThreadPoolExecutor(4) as pool:
    got = list(pool.map(lambda _: s.solve(t - b, 1e-3).pressure, range(8)))
check("one ContactSolver from 4 threads", lambda: all(np.array_equal(g, ref) for g in got))
def refused(f, words):
    try:
        f()
    except ValueError as e:
        return words in str(e) and "convert" not in str(e)
    return False
check("ContactSolver(-4)", lambda: refused(lambda: wearsim.ContactSolver(-4, 1.0, 1.0), "`grid`"))
inf_pixel = lambda: wearsim.label_junctions(np.ones((8, 8), bool), pixel_size=float("inf"))
check("label_junctions(pixel_size=inf)", lambda: refused(inf_pixel, "`pixel_size`"))
extra = tomllib.loads(open(sys.argv[1]).read())["project"]["optional-dependencies"]["fields"]
check("the fields extra installs h5py", lambda: any(x.startswith("h5py") for x in extra))
print(repr(out))
"""


def python_api(tmp: Path, tally: dict) -> None:
    cls = "Python API"
    python = os.environ.get("WEARSIM_PYTHON", sys.executable)
    p = subprocess.run(
        [python, "-c", PYTHON_CHECKS, str(rt.ROOT / "pyproject.toml")], capture_output=True, text=True, cwd=tmp
    )
    if p.returncode != 0:
        tally[(cls, "unclear error")].append(f"the checks did not run: {p.stderr[-300:]}")
        return
    for name, verdict in eval(p.stdout.strip().splitlines()[-1]).items():
        kind = verdict if verdict in ("accepted", "silently wrong") else "unclear error"
        tally[(cls, kind)].append(f"{name}: {verdict}")
    # The NetCDF file's permissions follow the umask.
    store = tmp / "fs" / "fields.zarr"
    if store.exists():
        out = tmp / "mode.nc"
        script = f"umask 022; exec {rt.WEARSIM} fields to-netcdf {store} {out} --python {python}"
        q = subprocess.run(["sh", "-c", script], capture_output=True)
        mode = out.stat().st_mode & 0o777 if out.exists() else None
        tally[(cls, "accepted" if q.returncode == 0 and mode == 0o644 else "silently wrong")].append(
            f"NetCDF file mode under umask 022: {oct(mode) if mode is not None else q.stderr.decode()[-120:]}"
        )


def third_round(tmp: Path, tally: dict, quick: bool) -> None:
    """The classes of the third round (module documentation)."""
    for step in (
        lambda: folders_and_files(tmp, tally),
        lambda: partial_files(tmp, tally),
        lambda: damaged_checkpoints(tmp, tally, 4 if quick else 12),
        lambda: edited_job_files(tmp, tally),
        lambda: limits(tmp, tally),
        lambda: signals_everywhere(tmp, tally),
        lambda: slurm_time_limits(tmp, tally, 4 if quick else 8),
        lambda: tolerance_and_messages(tmp, tally),
        lambda: python_api(tmp, tally),
    ):
        step()
