"""The fourth round of reliability trials: what the round after the static estimate changes, and its
combinations (estimate with studies, shards, signals, caches, pipes).

    python bench/reliability_fourth_round.py --wearsim target/release/wearsim [--python PY] [--out report.json]

Classes: output folders of ``estimate-check`` spelled onto its inputs (and the other commands onto
theirs, as a control); a closed pipe on stdout and stderr (``| head -1``) for every command; silently
wrong estimates and studies (changed surface files, model and sampling lists, a junction around the
box, under-resolved d*, ``estimate_samples``, the automatic sampling, the findings' numbers, NaN
maps); claim files of other processes; an edited cost-calibration cache; unclear messages (an
edited stored study, Slurm variables, a job file of the other model, ``samples=-1``, a full disk
under ``study plot``); and combinations (stop signals to estimates and mixed studies, shards of a
mixed study, ``estimate-check`` beside a running study, a closed pipe under shards).

Each trial gets exactly one outcome, as in docs/reliability.md: accepted (the right behaviour, the
check passed), clear error (non-zero, one line naming the thing, inputs intact), unclear error,
panic (101 or "panicked at"), abort (killed by a signal, 134), hang (over the trial's time limit,
at most 60 s), data loss (an input or result changed or removed that should not have been),
silently wrong (exit 0 with a wrong, duplicated or unflagged result), ignored signal, or not run
(the Python trials when the interpreter has no ``wearsim``). 64²–256² grids; a few minutes on two
cores. Every run has a private ``HOME`` and ``XDG_CACHE_HOME``; only the cache trials run without
``WEARSIM_NO_ESTIMATE``.
"""

from __future__ import annotations

import argparse
import collections
import hashlib
import json
import os
import random
import re
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import reliability_common as rt

OUTCOMES = [
    "accepted",
    "clear error",
    "unclear error",
    "panic",
    "abort",
    "hang",
    "data loss",
    "silently wrong",
    "ignored signal",
    "not run",
]
SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGUSR1, signal.SIGUSR2)
TIMEOUT = 60

WEARSIM = "wearsim"
PYTHON = sys.executable
ENV: dict = {}
TRIALS: list = []


def record(cls: str, name: str, command, outcome: str, detail: str = "") -> None:
    assert outcome in OUTCOMES, outcome
    if not isinstance(command, str):
        command = " ".join(map(str, command))
    TRIALS.append({"class": cls, "name": name, "command": command, "outcome": outcome, "detail": detail[:600]})


def _default_signals() -> None:
    for s in (*SIGNALS, signal.SIGHUP, signal.SIGPIPE):
        signal.signal(s, signal.SIG_DFL)


def run(args: list, cwd=None, env=None, timeout: float = TIMEOUT) -> subprocess.CompletedProcess | None:
    try:
        return subprocess.run(
            [WEARSIM, *map(str, args)],
            capture_output=True,
            cwd=cwd,
            env=env or ENV,
            timeout=timeout,
            preexec_fn=_default_signals,
        )
    except subprocess.TimeoutExpired:
        return None


def sh(script: str, cwd=None, env=None, timeout: float = TIMEOUT) -> subprocess.CompletedProcess | None:
    try:
        return subprocess.run(["sh", "-c", script], capture_output=True, cwd=cwd, env=env or ENV, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def popen(args: list, **kw) -> subprocess.Popen:
    kw.setdefault("stdout", subprocess.DEVNULL)
    kw.setdefault("stderr", subprocess.PIPE)
    kw.setdefault("env", ENV)
    return subprocess.Popen([WEARSIM, *map(str, args)], preexec_fn=_default_signals, **kw)


def err(p: subprocess.CompletedProcess | None) -> str:
    return p.stderr.decode(errors="replace") if p is not None else ""


def out(p: subprocess.CompletedProcess | None) -> str:
    return p.stdout.decode(errors="replace") if p is not None else ""


def classify(p: subprocess.CompletedProcess | None) -> rt.Outcome:
    """rt.classify with a panic recognised anywhere in stderr."""
    if p is not None and "panicked" in err(p):
        return rt.Outcome("panic", err(p)[-300:])
    return rt.classify(p)


def error_line(p) -> str:
    e = err(p).strip()
    return next((line for line in e.splitlines() if line.startswith("error:")), e.splitlines()[-1] if e else "")


def refused_naming(p, *words: str) -> rt.Outcome:
    """A refusal counts as clear only when its message names every one of `words` (any case)."""
    o = classify(p)
    if o.kind == "clear error" and not all(w.lower() in err(p).lower() for w in words):
        return rt.Outcome("unclear error", o.detail)
    return o


def hashes(root: Path) -> dict:
    found = {}
    for dirpath, _, files in os.walk(root):
        for f in files:
            path = Path(dirpath) / f
            if path.is_symlink() or not path.is_file():
                continue
            found[str(path.relative_to(root))] = hashlib.sha256(path.read_bytes()).hexdigest()
    return found


def lost(before: dict, after: dict) -> list:
    return [k for k, v in before.items() if after.get(k) != v]


def hidden(folder: Path) -> list:
    return [p.name for p in folder.iterdir() if p.name.startswith(".") and p.name != ".wearsim.json"]


def run_file(grid: int = 64, loads: str = "[1e-3]", extra: str = "", **fields) -> str:
    text = (
        rt.toml(rt.RUN)
        .replace("grid = 64", f"grid = {grid}")
        .replace("lambda_lower = 0.0625", f"lambda_lower = {min(16 / grid, 0.0625)}")
        .replace("loads = [1e-3]", f"loads = {loads}")
    )
    for key, value in fields.items():
        text = re.sub(rf"(?m)^{key} = .*$", f"{key} = {value}", text)
    return text + extra


def files_run(top: str, bottom: str, loads: str = "[5e-4, 1e-3]", extra: str = "", **fields) -> str:
    """A run or study file whose surfaces are files."""
    run = {**rt.RUN, "surface": {"top": f'"{top}"', "bottom": f'"{bottom}"', "length": "1.0"}}
    text = rt.toml(run).replace("loads = [1e-3]", f"loads = {loads}")
    for key, value in fields.items():
        text = re.sub(rf"(?m)^{key} = .*$", f"{key} = {value}", text)
    return text + extra


def csv_rows(path: Path) -> list:
    import csv

    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def collect(folder: Path) -> str | None:
    p = run(["study", "collect", folder])
    if p is None or p.returncode != 0 or not (folder / "results.csv").exists():
        return None
    return (folder / "results.csv").read_text()


def job_files(folder: Path) -> list:
    return sorted((folder / "jobs").glob("job-*.json"))


# ---------------------------------------------------------------------------------------------
# 1. Data loss by output folders


def file_study_tree(root: Path) -> Path:
    """root/surf (a pair of surface files and a note), root/studies/fs.toml (a study of them),
    root/work/ST (the study run)."""
    (root / "surf").mkdir(parents=True)
    (root / "studies").mkdir()
    (root / "work").mkdir()
    gen = root / "gen.toml"
    gen.write_text(run_file(64))
    run(["surface", gen, "--out", root / "gen"])
    for name in ["top", "bottom"]:
        shutil.copy(root / "gen" / f"{name}.npy", root / "surf" / f"{name}.npy")
    shutil.rmtree(root / "gen")
    gen.unlink()
    (root / "surf" / "notes.txt").write_text("where these surfaces were measured\n")
    (root / "studies" / "fs.toml").write_text(
        files_run("../surf/top.npy", "../surf/bottom.npy", fracture_energies="[0.25e-6, 0.5e-6]")
    )
    (root / "studies" / "run.toml").write_text(files_run("../surf/top.npy", "../surf/bottom.npy"))
    p = run(["study", "run", root / "studies" / "fs.toml", "--out", root / "work" / "ST"])
    assert p is not None and p.returncode == 0, err(p)
    return root


def copy_tree(src: Path, dst: Path) -> None:
    """A copy of a tree made by :func:`file_study_tree`, as a user would make it by copying the
    project, with its study run again in the copy (a study folder records the absolute paths of its
    surface files, so a copied study folder still reads the original's surfaces)."""
    shutil.copytree(src, dst, symlinks=True, ignore=lambda d, names: ["ST"] if Path(d).name == "work" else [])
    p = run(["study", "run", dst / "studies" / "fs.toml", "--out", dst / "work" / "ST"])
    assert p is not None and p.returncode == 0, err(p)


def output_folders(tmp: Path) -> None:
    cls = "1 output folders onto inputs"
    pristine = tmp / "of-pristine"
    targets = [
        ("ST/jobs", "ST/jobs"),
        ("ST/jobs", "ST/jobs/"),
        ("ST/jobs", "./ST/jobs"),
        ("ST/jobs", "{work}/ST/jobs"),
        ("ST/jobs", "lnjobs"),
        ("ST", "ST"),
        ("ST", "ST/"),
        ("ST", "{work}/ST"),
        ("ST", "ST/jobs/.."),
        ("ST", "lnst"),
        ("surface files' folder", "../surf"),
        ("surface files' folder", "../surf/"),
        ("surface files' folder", "{root}/surf"),
        ("surface files' folder", "lnsurf"),
        ("parent of ST", "."),
        ("parent of ST", "{work}"),
        ("parent of ST", "../work/"),
        ("study file's folder", "../studies"),
        ("study file's folder", "{root}/studies/"),
    ]
    k = 0

    def fresh() -> Path:
        nonlocal k
        k += 1
        root = tmp / f"of{k}"
        copy_tree(pristine, root)
        work = root / "work"
        (work / "lnjobs").symlink_to("ST/jobs")
        (work / "lnst").symlink_to("ST")
        (work / "lnsurf").symlink_to("../surf")
        return root

    def trial(name: str, args: list, cwd_rel: str = "work", expect_ok: bool = False) -> None:
        root = fresh()
        args = [str(a).format(root=root, work=root / "work") for a in args]
        before = hashes(root)
        p = run(args, cwd=root / cwd_rel)
        after = hashes(root)
        gone = lost(before, after)
        o = classify(p)
        if gone:
            kind, detail = "data loss", f"{len(gone)} files changed or removed: {gone[:4]}; status {p and p.returncode}"
        elif expect_ok:
            kind, detail = o.kind, o.detail
        elif o.kind == "accepted":
            kind, detail = "silently wrong", "written into a folder of its inputs"
        else:
            kind, detail = o.kind, o.detail
        name = name.replace("{root}", "<abs>").replace("{work}", "<abs>/work")
        record(cls, name, ["wearsim", *args], kind, detail)
        shutil.rmtree(root, ignore_errors=True)

    for overwrite in (False, True):
        for what, spelling in targets:
            extra = ["--overwrite"] if overwrite else []
            trial(
                f"estimate-check ST --out {spelling} ({what}){' --overwrite' if overwrite else ''}",
                ["estimate-check", "ST", "--out", spelling, *extra],
            )
    for dir_spelling, spelling in [
        ("lnst", "ST/jobs"),
        ("./ST/", "lnjobs"),
        ("{work}/ST", "../work/ST/jobs"),
        ("ST/jobs/..", "ST"),
    ]:
        trial(
            f"estimate-check {dir_spelling} --out {spelling} --overwrite (the study spelled another way)",
            ["estimate-check", dir_spelling, "--out", spelling, "--overwrite"],
        )
    trial("control: estimate-check ST --out a new folder", ["estimate-check", "ST", "--out", "cmp"], expect_ok=True)
    # The other commands onto their inputs (refused already).
    controls = [
        (
            "slide ../studies/run.toml --out ../studies --overwrite",
            ["slide", "../studies/run.toml", "--out", "../studies"],
        ),
        (
            "estimate ../studies/run.toml --out ../surf --overwrite",
            ["estimate", "../studies/run.toml", "--out", "../surf"],
        ),
        ("estimate run.toml --out . --overwrite (in studies/)", ["estimate", "run.toml", "--out", "."]),
        (
            "surface fit ../surf/top.npy --out ../surf --overwrite",
            ["surface", "fit", "../surf/top.npy", "--length", "1", "--out", "../surf"],
        ),
        ("study run ../studies/fs.toml --out ../surf", ["study", "run", "../studies/fs.toml", "--out", "../surf"]),
        (
            "study run ../studies/fs.toml --out ../studies",
            ["study", "run", "../studies/fs.toml", "--out", "../studies"],
        ),
    ]
    for name, args in controls:
        if "--overwrite" in name:
            args = [*args, "--overwrite"]
        trial(f"control: {name}", args, cwd_rel="studies" if "(in studies/)" in name else "work")
    # study plot writes into its study folder's figures/: the study's job files stay as they were.
    root = fresh()
    before = {k: v for k, v in hashes(root).items() if "figures" not in k}
    p = run(["study", "plot", "ST"], cwd=root / "work")
    gone = lost(before, hashes(root))
    kind = "data loss" if gone else classify(p).kind
    record(cls, "control: study plot ST keeps the study's files", "wearsim study plot ST", kind, str(gone[:4]))


# ---------------------------------------------------------------------------------------------
# 2. Closed pipe


def read_then_close(args: list, lines: int, cwd: Path, timeout: float = TIMEOUT) -> tuple:
    """Runs wearsim with stdout and stderr into one pipe, reads `lines` lines (0: none), closes the
    pipe and waits. Returns (status or None for a hang, what was read)."""
    child = subprocess.Popen(
        [WEARSIM, *map(str, args)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        cwd=cwd,
        env=ENV,
        preexec_fn=_default_signals,
    )
    got = b""
    deadline = time.monotonic() + timeout
    fd = child.stdout.fileno()
    while got.count(b"\n") < lines and time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], 0.2)
        if ready:
            chunk = os.read(fd, 4096)
            if not chunk:
                break
            got += chunk
    child.stdout.close()
    try:
        status = child.wait(timeout=max(1.0, deadline - time.monotonic()))
    except subprocess.TimeoutExpired:
        child.kill()
        child.wait()
        status = None
    return status, got.decode(errors="replace")


def closed_pipe(tmp: Path) -> None:
    cls = "2 closed pipe"
    d = tmp / "pipe"
    d.mkdir()
    (d / "run.toml").write_text(run_file(64))
    (d / "study.toml").write_text(run_file(64, "[5e-4, 1e-3]", seed="[1, 2]"))
    run(["surface", d / "run.toml", "--out", d / "s"])
    run(["contact", d / "run.toml", "--load", "1e-3", "--out", d / "c"])
    copy_tree(tmp / "of-pristine", d / "fs")
    st = d / "fs" / "work" / "ST"
    commands = {
        "slide": (["slide", "run.toml", "--out", "o"], "o/summary.json"),
        "estimate": (["estimate", "run.toml", "--out", "o", "--samples", "4"], "o/results.csv"),
        "estimate-check": (["estimate-check", st, "--out", "o"], "o/comparison.csv"),
        "contact": (["contact", "run.toml", "--load", "1e-3", "--out", "o"], "o/summary.json"),
        "surface": (["surface", "run.toml", "--out", "o"], "o/statistics.json"),
        "surface fit": (["surface", "fit", "s/top.npy", "--length", "1", "--out", "o"], "o/fit.json"),
        "junctions": (["junctions", "c/contact.npy", "--out", "o"], "o/junctions.json"),
        "study run": (["study", "run", "study.toml", "--out", "o"], "o/jobs/job-000003.json"),
        "study collect": (["study", "collect", "o"], "o/results.csv"),
        "study plot": (["study", "plot", "o"], "o/figures"),
        "bench": (["bench", "--sizes", "64,128", "--fft-repeats", "1", "--json", "o.json"], "o.json"),
        "bench-slide": (
            ["bench-slide", "--n", "64", "--warm-n", "128", "--warm-steps", "2", "--estimate-samples", "2"],
            None,
        ),
        "animate": (["animate", "run.toml", "--out", "o.gif"], "o.gif"),
    }
    for name, (args, result) in commands.items():
        for log, lines in [(True, 1), (False, 1), (True, 0)]:
            for leftover in ["o", "o.json", "o.gif"]:
                subprocess.run(["rm", "-rf", str(d / leftover)])
            if name in ("study collect", "study plot"):
                shutil.copytree(st, d / "o", symlinks=True)
            full = (["--log"] if log else []) + args
            status, got = read_then_close(full, lines, d)
            written = result is None or (d / result).exists()
            ck = [n for n in hidden(d) if n.startswith(".o")]
            what = f"{name}{' --log' if log else ''}, {'one line read' if lines else 'closed at once'}"
            if status is None:
                kind = "hang"
            elif status == 101 or "panicked" in got:
                kind = "panic"
            elif status < 0 or status == 134:
                kind = "abort"
            elif status == 0 and written and not ck:
                kind = "accepted"
            elif status == 0:
                kind = "silently wrong"
            elif not written or ck:
                kind = "data loss"  # the computation is lost: the command must be run again
            else:
                kind = "unclear error"
            record(
                cls, what, ["wearsim", *full, "| head -%d" % lines], kind, f"status {status}, written {written} {ck}"
            )


# ---------------------------------------------------------------------------------------------
# 3. Silently wrong: estimates and studies


def estimate_and_studies(tmp: Path) -> None:
    cls = "3 silently wrong: estimate and studies"
    # a. estimate-check after the study's surface files changed.
    import_np = "import numpy as np, sys\n"
    for what, change in [
        ("top.npy changed", "a = np.load(sys.argv[1]); a[5:9, 5:9] += 0.01; np.save(sys.argv[1], a)"),
        ("bottom.npy changed", "a = np.load(sys.argv[2]); np.save(sys.argv[2], a * 1.5)"),
        ("both changed", "[np.save(f, np.load(f)[::-1].copy()) for f in sys.argv[1:3]]"),
        ("top.npy rewritten unchanged (control)", "np.save(sys.argv[1], np.load(sys.argv[1]))"),
    ]:
        root = tmp / f"ch-{len(TRIALS)}"
        copy_tree(tmp / "of-pristine", root)
        q = subprocess.run(
            [PYTHON, "-c", import_np + change, root / "surf" / "top.npy", root / "surf" / "bottom.npy"],
            capture_output=True,
        )
        if q.returncode != 0:
            record(cls, f"estimate-check after {what}", "python (numpy)", "not run", q.stderr.decode()[-200:])
            continue
        p = run(["estimate-check", root / "work" / "ST", "--out", root / "cmp"])
        control = "control" in what
        named = any(w in err(p) for w in ("top.npy", "bottom.npy", "changed", "surface"))
        o = classify(p)
        if o.kind == "accepted":
            kind = "accepted" if control or named else "silently wrong"
        elif control:
            # NumPy rewrites the header: the bytes change though the heights do not, and the study's
            # hash covers the bytes; a refusal that says a surface file changed is clear, not wrong.
            kind = "clear error" if o.kind == "clear error" and named else o.kind
        else:
            kind = "clear error" if o.kind == "clear error" and named else o.kind
            kind = "unclear error" if kind == "clear error" and not named else kind
        record(
            cls,
            f"estimate-check after {what}",
            "wearsim estimate-check ST --out cmp",
            kind,
            error_line(p) or out(p)[-200:],
        )
    # b. lists the model ignores: must be refused (naming the setting and the model) or make distinct jobs.
    d = tmp / "lists"
    d.mkdir()
    cases = [
        (
            'model ["sliding", "estimate"], estimate_samples [4, 8]',
            'model = ["sliding", "estimate"]\nestimate_samples = [4, 8]\n',
        ),
        ('model "sliding", estimate_samples [4, 8]', 'model = "sliding"\nestimate_samples = [4, 8]\n'),
        (
            'model "estimate", estimate_samples [4, 8] (distinct, control)',
            'model = "estimate"\nestimate_samples = [4, 8]\n',
        ),
        (
            'model "estimate", step_running_in [2, 4]',
            'model = "estimate"\nestimate_samples = 4\n',
            "step_running_in",
            "[2, 4]",
        ),
        ('model "estimate", step [1, 2]', 'model = "estimate"\nestimate_samples = 4\n', "step", "[1, 2]"),
        (
            'model ["sliding", "estimate"], running_in [0.125, 0.25]',
            'model = ["sliding", "estimate"]\nestimate_samples = 4\n',
            "running_in",
            "[0.125, 0.25]",
        ),
    ]
    for t, case in enumerate(cases):
        name, extra = case[0], case[1]
        text = run_file(64, "[1e-3]") + extra
        text = text.replace("[sliding]\n", "[sliding]\n", 1)
        if len(case) > 2:
            text = re.sub(rf"(?m)^{case[2]} = .*$", f"{case[2]} = {case[3]}", text)
        # the extra keys belong to [sliding], the file's last table
        path = d / f"l{t}.toml"
        path.write_text(text)
        folder = d / f"l{t}"
        p = run(["study", "run", path, "--out", folder])
        o = classify(p)
        if o.kind == "accepted":
            results = collections.Counter()
            for job in job_files(folder):
                doc = json.loads(job.read_text())
                # An estimate's intervals (`estimates`) depend on running_in: part of what it gives.
                results[json.dumps([doc.get("results"), doc.get("estimates")], sort_keys=True)] += 1
            dup = [n for n in results.values() if n > 1]
            kind = "silently wrong" if dup else "accepted"
            detail = f"{len(job_files(folder))} jobs, {sum(dup)} with the results of another"
        else:
            setting = "estimate_samples" if "estimate_samples [" in name else (case[2] if len(case) > 2 else "")
            o = refused_naming(p, setting, "model") if o.kind == "clear error" else o
            kind, detail = o.kind, o.detail
            if "control" in name and kind in ("clear error", "unclear error"):
                kind = "unclear error"
        record(cls, f"study of {name}", f"wearsim study run {path.name}", kind, detail)
    # c. a junction around the periodic box: never a critical junction without a word.
    flat = d / "flat.npy"
    ridge = d / "ridge.npy"
    subprocess.run(
        [
            PYTHON,
            "-c",
            f"import numpy as np; np.save('{flat}', np.zeros((64, 64))); x = np.arange(64) / 64; "
            f"np.save('{ridge}', np.repeat((0.002 * np.cos(2 * np.pi * x))[:, None], 64, axis=1))",
        ],
        capture_output=True,
    )
    wraps = [
        ("flat surfaces", files_run(str(flat), str(flat), "[1e-3]")),
        ("flat surfaces, two loads", files_run(str(flat), str(flat), "[5e-4, 2e-3]")),
        ("a load near full contact (0.5 p_m)", run_file(64, "[0.04]")),
        ("rms height 1e-6 L", run_file(64, "[1e-3]", rms_height="1e-6")),
        ("a ridge along y (a band of contact across the box)", files_run(str(ridge), str(flat), "[1e-3]")),
        ("a ridge along y, a heavier load", files_run(str(ridge), str(flat), "[4e-3]")),
    ]
    for name, text in wraps:
        path = d / "wrap.toml"
        path.write_text(text)
        slide = run(["slide", path, "--out", d / "wrap-slide", "--overwrite"])
        p = run(["estimate", path, "--out", d / "wrap-est", "--overwrite", "--samples", "4"])
        o = classify(p)
        said = "wrap" in err(p).lower() or "periodic box" in err(p).lower() or "around the box" in err(p).lower()
        slide_said = "wrap" in err(slide).lower() or "periodic box" in err(slide).lower()
        if o.kind == "accepted":
            rows = (d / "wrap-est" / "results.csv").read_text().splitlines()
            head = rows[0].split(",")
            col = head.index("critical_junctions_mean") if "critical_junctions_mean" in head else None
            counted = [float(r.split(",")[col] or 0) for r in rows[1:]] if col is not None else []
            critical = any(c > 0 for c in counted)
            kind = "silently wrong" if critical and not said else "accepted"
            detail = f"N* {counted}, warned {said} (slide warned {slide_said})"
        else:
            kind, detail = o.kind, o.detail
        record(cls, f"estimate with a junction around the box: {name}", "wearsim estimate wrap.toml", kind, detail)
    # d. estimate-check --fit on runs with d* of a pixel or two: a word on the resolution.
    for g, px in [("0.68e-6", "about 1 px"), ("1.35e-6", "about 2 px")]:
        study = d / f"dstar{g}.toml"
        study.write_text(run_file(64, "[5e-4, 1e-3, 2e-3]", seed="[1, 2]", fracture_energies=f"[{g}]"))
        folder = d / f"dstar{g}"
        run(["study", "run", study, "--out", folder], timeout=120)
        with_slide = json.loads(job_files(folder)[0].read_text()) if job_files(folder) else {}
        p = run(["estimate-check", folder, "--out", d / f"fit{g}", "--fit"])
        o = classify(p)
        said = any(w in (err(p) + out(p)).lower() for w in ("resol", "pixel", " px"))
        dstar = re.findall(r'"critical_diameters?"\s*:\s*\[?([0-9.e-]+)', json.dumps(with_slide))
        if o.kind == "accepted":
            kind = "accepted" if said else "silently wrong"
        else:
            kind = o.kind if (o.kind != "clear error" or said) else "unclear error"
        record(
            cls,
            f"estimate-check --fit, d* {px}",
            f"wearsim estimate-check {folder.name} --fit",
            kind,
            f"warned {said}; d* {dstar[:1]}; {o.detail}",
        )
    # e. estimate-check on a study with estimate_samples: uses it.
    for k in (2, 4):
        study = d / f"es{k}.toml"
        study.write_text(run_file(64, "[5e-4, 1e-3]", seed="[1, 2]") + f"estimate_samples = {k}\n")
        folder = d / f"es{k}"
        run(["study", "run", study, "--out", folder])
        a = run(["estimate-check", folder, "--out", d / f"es{k}-a"])
        b = run(["estimate-check", folder, "--out", d / f"es{k}-b", "--samples", str(k)])
        if a is None or b is None or a.returncode or b.returncode:
            record(
                cls,
                f"estimate-check of a study with estimate_samples = {k}",
                "wearsim estimate-check",
                classify(a).kind,
                error_line(a) + error_line(b),
            )
            continue
        same = (d / f"es{k}-a" / "comparison.csv").read_text() == (d / f"es{k}-b" / "comparison.csv").read_text()
        summary = json.loads((d / f"es{k}-a" / "summary.json").read_text())
        maps = [r.get("static_maps") for r in csv_rows(d / f"es{k}-a" / "comparison.csv")]
        recorded = summary.get("samples") == k or (maps and all(m == str(k) for m in maps))
        kind = "accepted" if same and recorded else "silently wrong"
        record(
            cls,
            f"estimate-check of a study with estimate_samples = {k}",
            f"wearsim estimate-check {folder.name}",
            kind,
            f"same as --samples {k}: {same}; samples recorded: {recorded}",
        )
    # f. automatic sampling: each sampling error at most 10 % or a warning.
    for seed, loads, g in [
        (1, "[1e-3]", "[0.5e-6]"),
        (2, "[5e-4]", "[0.25e-6]"),
        (3, "[2e-3]", "[1e-6]"),
        (4, "[2.5e-4]", "[2e-6]"),
        (5, "[1e-3, 2e-3]", "[4e-6]"),
        (6, "[5e-4]", "[0.125e-6, 8e-6]"),
    ]:
        path = d / "auto.toml"
        path.write_text(run_file(64, loads, seed=str(seed), fracture_energies=g))
        p = run(["estimate", path, "--out", d / "auto", "--overwrite"])
        o = classify(p)
        if o.kind != "accepted":
            record(cls, f"automatic sampling, seed {seed}", "wearsim estimate auto.toml", o.kind, o.detail)
            continue
        rows = csv_rows(d / "auto" / "results.csv")
        errors = [float(r["critical_junctions_sampling_error"] or "nan") for r in rows]
        warned = "sampling error" in err(p).lower() or "10 %" in err(p)
        # an undefined error (no critical junction) needs its own word: W undefined, no junction reaches d*
        undefined_said = "undefined" in err(p) or "no junction" in err(p)
        good = all(e <= 0.10 or (e != e and undefined_said) for e in errors) or warned
        record(
            cls,
            f"automatic sampling, seed {seed}, loads {loads}, G {g}",
            "wearsim estimate auto.toml",
            "accepted" if good else "silently wrong",
            f"sampling errors {[round(e, 3) for e in errors]}, warned {warned}",
        )
    # g. findings' largest mean k against results.csv.
    for name, extra, g in [
        ("sliding", "", "[0.5e-6]"),
        ("mixed", 'model = ["sliding", "estimate"]\nestimate_samples = 4\n', "[0.5e-6]"),
        ("two curves", "", "[0.5e-6, 1e-6]"),
    ]:
        study = d / f"find-{name}.toml"
        study.write_text(run_file(64, "[2.5e-4, 5e-4, 1e-3, 2e-3]", seed="[1, 2]", fracture_energies=g) + extra)
        folder = d / f"find-{name}"
        run(["study", "run", study, "--out", folder], timeout=120)
        table = collect(folder)
        p = run(["study", "plot", folder], timeout=120)
        texts = "".join(f.read_text() for f in folder.rglob("*.md"))
        found = []
        for m in re.finditer(r"largest mean k = ([0-9.eE+-]+) at F_N/\(Lx·Ly\) = ([0-9.eE+-]+),", texts):
            curve = re.findall(r"𝒢 = ([0-9.eE+-]+)", texts[: m.start()])
            found.append((float(m.group(1)), float(curve[-1]) if curve else None))
        if table is None or not found:
            record(
                cls,
                f"findings' largest mean k ({name} study)",
                "wearsim study plot",
                classify(p).kind if p and p.returncode else "unclear error",
                f"no finding found: {error_line(p)}",
            )
            continue
        # The finding's mean: over the sliding rows of pairs run in (no "not run in" warning).
        by_load: dict = collections.defaultdict(list)
        for r in csv_rows(folder / "results.csv"):
            if r.get("sliding.model", "") not in ("", "sliding") or "not run in" in r.get("warnings", ""):
                continue
            if r["wear_coefficient"]:
                by_load[(float(r["fracture_energy"]), float(r["load"]))].append(float(r["wear_coefficient"]))
        checks = []
        for stated, curve in found:
            means = [sum(v) / len(v) for (g, _), v in by_load.items() if curve is None or abs(g - curve) <= 1e-3 * g]
            best = max(means) if means else float("nan")
            checks.append((stated, curve, best, abs(stated - best) <= 0.01 * abs(best)))
        agree = bool(checks) and all(c[3] for c in checks)
        record(
            cls,
            f"findings' largest mean k ({name} study)",
            "wearsim study plot",
            "accepted" if agree else "silently wrong",
            "; ".join(f"𝒢 {c}: stated {s:.4g}, results.csv {b:.4g}" for s, c, b, _ in checks),
        )
    # h. NaN in a contact map: Python refuses it as the CLI does.
    np_nan = d / "nan.npy"
    subprocess.run(
        [
            PYTHON,
            "-c",
            f"import numpy as np; a = np.zeros((16, 16)); a[3:6, 3:6] = 1; a[0, 0] = np.nan; np.save('{np_nan}', a)",
        ],
        capture_output=True,
    )
    p = run(["junctions", np_nan, "--out", d / "nanj"])
    o = refused_naming(p, "nan")
    record(cls, "wearsim junctions on a map with NaN (control)", "wearsim junctions nan.npy", o.kind, o.detail)
    for name, code in [
        ("one NaN", "a = np.zeros((16, 16)); a[3:6, 3:6] = 1; a[0, 0] = np.nan"),
        ("all NaN", "a = np.full((16, 16), np.nan)"),
        ("one NaN, float32", "a = np.zeros((16, 16), np.float32); a[3:6, 3:6] = 1; a[7, 7] = np.nan"),
        ("one NaN, Fortran order", "a = np.asfortranarray(np.ones((16, 16))); a[9, 2] = np.nan"),
    ]:
        python_trial(cls, f"wearsim.label_junctions on a map with {name}", f"{code}\nwearsim.label_junctions(a)", "nan")


def python_trial(cls: str, name: str, code: str, words: str, cwd: Path | None = None) -> None:
    """A Python snippet that must raise ValueError naming `words`."""
    prog = "import numpy as np, wearsim\n" + code + "\nprint('NO ERROR')\n"
    probe = subprocess.run([PYTHON, "-c", "import wearsim, numpy"], capture_output=True)
    if probe.returncode != 0:
        record(cls, name, f"{PYTHON} -c ...", "not run", "no wearsim in this Python")
        return
    p = subprocess.run([PYTHON, "-c", prog], capture_output=True, text=True, cwd=cwd, timeout=TIMEOUT)
    last = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""
    if p.returncode == 0:
        kind = "silently wrong"
    elif "panicked" in p.stderr or "PanicException" in p.stderr:
        kind = "panic"
    elif p.returncode < 0:
        kind = "abort"
    elif words.lower() in last.lower():
        kind = "clear error"
    else:
        kind = "unclear error"
    record(cls, name, code.replace("\n", "; "), kind, last or p.stdout[-200:])


# ---------------------------------------------------------------------------------------------
# 4. Claims


def claims(tmp: Path) -> None:
    cls = "4 claims of other processes"
    d = tmp / "claims"
    d.mkdir()
    study = d / "study.toml"
    study.write_text(run_file(64, "[1e-3]", seed="[1, 2]"))
    pristine = d / "pristine"
    run(["study", "run", study, "--out", pristine])
    host = socket.gethostname()
    sleeper = subprocess.Popen(["sleep", "300"])
    old = time.time() - 3600
    cases = [
        # name, content, mtime, the claim must be respected (a live, refreshed claim)
        ("pid of a live `sleep`, claim an hour old", f"{host} {sleeper.pid}\n", old, False),
        ("pid of a live `sleep`, fresh claim", f"{host} {sleeper.pid}\n", None, True),
        ("pid 1, claim an hour old", f"{host} 1\n", old, False),
        ("pid 1, fresh claim", f"{host} 1\n", None, True),
        ("pid of the campaign itself, an hour old", f"{host} {os.getpid()}\n", old, False),
        ("pid of a process that is gone (control)", f"{host} 4000000000\n", None, False),
        ("garbage content, an hour old", "\x00\x01garbage\xff", old, False),
        ("garbage content, fresh", "garbage that is no claim", None, None),
        ("another host, an hour old", "elsewhere.cluster 12\n", old, False),
        ("another host, fresh", "elsewhere.cluster 12\n", None, True),
    ]
    for t, (name, content, mtime, respected) in enumerate(cases):
        folder = d / f"c{t}"
        shutil.copytree(pristine, folder)
        job = job_files(folder)[-1]
        job.unlink()
        claim = job.with_suffix(".claim")
        claim.write_bytes(content.encode("latin-1"))
        if mtime is not None:
            os.utime(claim, (mtime, mtime))
        p = run(["study", "run", study, "--out", folder])
        computed = job.exists()
        said = any(w in out(p) + err(p) for w in ("another run", "claim", "held"))
        named_claim = claim.name in out(p) + err(p) or "pid" in (out(p) + err(p)).lower()
        o = classify(p)
        if o.kind != "accepted":
            kind = o.kind
        elif respected is True:
            kind = "accepted" if not computed and said else "silently wrong"
        elif respected is False:
            if computed:
                kind = "accepted"
            else:
                kind = "clear error" if named_claim else "silently wrong"
        else:
            kind = "accepted" if computed or said else "silently wrong"
        line = (out(p) + err(p)).strip().splitlines()
        record(
            cls,
            name,
            f"wearsim study run study.toml --out {folder.name} (claim: {content!r})",
            kind,
            f"computed {computed}; {line[-1] if line else ''}",
        )
    sleeper.kill()
    sleeper.wait()


# ---------------------------------------------------------------------------------------------
# 5. The cost-calibration cache


def wall_seconds(text: str) -> float | None:
    m = re.search(r"(-?[0-9.]+|NaN|inf|-inf) (s|min|h) wall", text)
    if not m:
        return None
    return float(m.group(1)) * {"s": 1, "min": 60, "h": 3600}[m.group(2)]


def caches(tmp: Path) -> None:
    cls = "5 cost-calibration cache"
    d = tmp / "cache"
    d.mkdir()
    big = d / "big.toml"
    big.write_text(run_file(4096, "[1e-3]"))
    env = {k: v for k, v in ENV.items() if k != "WEARSIM_NO_ESTIMATE"}
    xdg = d / "xdg"

    def with_cache(x: Path) -> dict:
        return {**env, "XDG_CACHE_HOME": str(x), "HOME": str(x.parent)}

    calibrations = {}
    for threads in (2, 1):
        p = run(["--threads", threads, "bench", "--calibrate"], env=with_cache(xdg), timeout=180)
        if p is None or p.returncode:
            record(
                cls, f"calibration on {threads} threads", "wearsim bench --calibrate", classify(p).kind, error_line(p)
            )
            return
        calibrations[threads] = json.loads(out(p))
    files = {json.loads(f.read_text())["threads"]: f.name for f in (xdg / "wearsim").glob("*.json")}

    def dry(x: Path, threads: int) -> subprocess.CompletedProcess | None:
        return run(
            ["--threads", threads, "slide", big, "--out", d / "never", "--dry-run"], env=with_cache(x), timeout=120
        )

    reference = {t: wall_seconds(err(dry(xdg, t))) for t in (2, 1)}
    if not all(reference.values()):
        record(
            cls,
            "a fresh calibration's estimate",
            "wearsim slide big.toml --dry-run",
            "unclear error",
            "no wall time printed",
        )
        return
    pristine = {t: (xdg / "wearsim" / files[t]).read_text() for t in (2, 1)}

    def edit(doc: dict, f) -> str:
        doc = json.loads(json.dumps(doc))
        f(doc)
        return json.dumps(doc, indent=2)

    two = json.loads(pristine[2])
    a = two["seconds_per_iteration"]["settled-map"]
    exp = re.search(r"e-?\d+", repr(a))
    bumped = float(repr(a).replace(exp.group(0), f"e{int(exp.group(0)[1:]) + 3}")) if exp else a * 1000
    mutations = {
        "one exponent changed (a, settled map, ×1000)": edit(
            two, lambda c: c["seconds_per_iteration"].__setitem__("settled-map", bumped)
        ),
        "one exponent changed (a, tolerance rule, unused by this run)": edit(
            two,
            lambda c: c["seconds_per_iteration"].__setitem__(
                "tolerance", c["seconds_per_iteration"]["tolerance"] * 1e3
            ),
        ),
        "a negative (settled map)": edit(two, lambda c: c["seconds_per_iteration"].__setitem__("settled-map", -a)),
        "a of 1e-30": edit(two, lambda c: c["seconds_per_iteration"].__setitem__("settled-map", 1e-30)),
        "NaN for a": edit(two, lambda c: c["seconds_per_iteration"].__setitem__("settled-map", float("nan"))),
        "null for a": edit(two, lambda c: c["seconds_per_iteration"].__setitem__("settled-map", None)),
        "fine-step iterations ×1000": edit(
            two,
            lambda c: [
                r["step_iterations"].__setitem__("fine", r["step_iterations"]["fine"] * 1000) for r in c["runs"]
            ],
        ),
        "fine-step iterations negative": edit(
            two, lambda c: [r["step_iterations"].__setitem__("fine", -r["step_iterations"]["fine"]) for r in c["runs"]]
        ),
        "no calibration runs": edit(two, lambda c: c.__setitem__("runs", [])),
        "truncated file": pristine[2][: len(pristine[2]) // 2],
        "checksum changed": edit(
            two, lambda c: c.__setitem__("checksum", ("0" * 16 if c.get("checksum") != "0" * 16 else "1" * 16))
        ),
    }
    trials = [(name, text, 2) for name, text in mutations.items()]
    trials += [("swapped: the 1-thread calibration in the 2-thread file", pristine[1], 2)]
    trials += [("swapped: the 2-thread calibration in the 1-thread file", pristine[2], 1)]
    for t, (name, text, threads) in enumerate(trials):
        x = d / f"x{t}" / ".cache"
        shutil.copytree(xdg, x)
        (x / "wearsim" / files[threads]).write_text(text)
        p = dry(x, threads)
        o = classify(p)
        wall = wall_seconds(err(p))
        ratio = wall / reference[threads] if wall else None
        noted = any(w in err(p).lower() for w in ("calibrating", "set aside", "not used", "recalibrat"))
        if o.kind != "accepted":
            kind = o.kind
        elif ratio is None or ratio != ratio:
            kind = "silently wrong"
        elif 0.2 <= ratio <= 5:
            kind = "accepted"
        else:
            kind = "silently wrong"
        record(
            cls,
            name,
            f"wearsim --threads {threads} slide big.toml (4096²) --dry-run",
            kind,
            f"wall {wall} s against {reference[threads]} s fresh (×{ratio and round(ratio, 3)}), "
            f"noted {noted}; {o.detail}",
        )


# ---------------------------------------------------------------------------------------------
# 6. Unclear messages


def messages(tmp: Path) -> None:
    cls = "6 unclear messages"
    d = tmp / "msg"
    d.mkdir()
    study = d / "study.toml"
    study.write_text(run_file(64, "[1e-3]", seed="[1, 2]"))
    pristine = d / "pristine"
    run(["study", "run", study, "--out", pristine])
    for name, change in [
        ("a value changed in the stored study.toml", lambda t: t.replace("rms_height = 0.005", "rms_height = 0.006")),
        ("a comment added to the stored study.toml", lambda t: "# mine\n" + t),
        ("the stored study.toml emptied", lambda t: ""),
    ]:
        folder = d / f"e{len(TRIALS)}"
        shutil.copytree(pristine, folder)
        stored = folder / "study.toml"
        if not stored.exists():
            record(cls, name, "wearsim study collect", "not run", "no stored study.toml")
            continue
        stored.write_text(change(stored.read_text()))
        jobs_before = hashes(folder / "jobs")
        p = run(["study", "collect", folder])
        o = classify(p)
        text = err(p).lower()
        if o.kind == "clear error":
            bad = "delete" in text or "remove" in text or "recompute" in text and "job-" in text
            o = rt.Outcome("unclear error" if bad or "study.toml" not in text else "clear error", o.detail)
        if lost(jobs_before, hashes(folder / "jobs")):
            o = rt.Outcome("data loss", "job files changed")
        record(cls, f"study collect after {name}", f"wearsim study collect {folder.name}", o.kind, o.detail)
    # Slurm variables.
    for name, extra, expect in [
        (
            "SLURM_ARRAY_TASK_ID=1 COUNT=2 without MIN",
            {"SLURM_ARRAY_TASK_ID": "1", "SLURM_ARRAY_TASK_COUNT": "2"},
            "SLURM_ARRAY_TASK_MIN",
        ),
        (
            "SLURM_ARRAY_TASK_MIN=one",
            {"SLURM_ARRAY_TASK_ID": "1", "SLURM_ARRAY_TASK_COUNT": "2", "SLURM_ARRAY_TASK_MIN": "one"},
            "SLURM_ARRAY_TASK_MIN",
        ),
        (
            "SLURM_ARRAY_TASK_STEP=x",
            {
                "SLURM_ARRAY_TASK_ID": "1",
                "SLURM_ARRAY_TASK_COUNT": "2",
                "SLURM_ARRAY_TASK_MIN": "1",
                "SLURM_ARRAY_TASK_STEP": "x",
            },
            "SLURM_ARRAY_TASK_STEP",
        ),
    ]:
        folder = d / f"slurm{len(TRIALS)}"
        p = run(["study", "run", study, "--out", folder], env={**ENV, **extra})
        o = classify(p)
        shard = re.search(r"shard (\d+)/(\d+)", err(p))
        if o.kind == "accepted":
            kind = "accepted" if shard and shard.group(1) == "1" else "silently wrong"
            detail = f"ran shard {shard and shard.group(0)}"
        else:
            o = refused_naming(p, expect) if o.kind == "clear error" else o
            kind, detail = o.kind, o.detail
        record(cls, name, f"{' '.join(f'{k}={v}' for k, v in extra.items())} wearsim study run", kind, detail)
    for value in ["17592186044416", "18446744073709551615"]:
        p = run(
            ["slide", d / "study.toml", "--out", d / "mem", "--overwrite", "--dry-run"],
            env={**ENV, "SLURM_MEM_PER_NODE": value},
        )
        one = d / "one.toml"
        one.write_text(run_file(64))
        p = run(["slide", one, "--out", d / "mem", "--overwrite"], env={**ENV, "SLURM_MEM_PER_NODE": value})
        o = classify(p)
        if re.search(r"\b0 (MiB|MB|bytes)", err(p)):
            o = rt.Outcome("unclear error", o.detail or "says 0 MiB")
        record(cls, f"SLURM_MEM_PER_NODE={value}", "wearsim slide one.toml", o.kind, o.detail)
    # An estimate job file copied into a sliding job's slot.
    mixed = d / "mixed.toml"
    mixed.write_text(run_file(64, "[1e-3]") + 'model = ["sliding", "estimate"]\nestimate_samples = 4\n')
    folder = d / "mixed"
    p = run(["study", "run", mixed, "--out", folder])
    models = {}
    for job in job_files(folder):
        text = job.read_text()
        models[job] = "estimate" if '"estimate"' in text else "sliding"
    sliding = [j for j, m in models.items() if m == "sliding"]
    estimate = [j for j, m in models.items() if m == "estimate"]
    if not sliding or not estimate:
        record(
            cls,
            "an estimate job file in a sliding job's slot",
            "wearsim study collect",
            "not run",
            f"mixed study not made: {error_line(p)}",
        )
    else:
        shutil.copy(estimate[0], sliding[0])
        for command in (["study", "collect", folder], ["study", "run", mixed, "--out", folder]):
            before = sliding[0].read_bytes()
            p = run(command)
            o = classify(p)
            if o.kind == "clear error":
                o = refused_naming(p, "estimate", "sliding")
            elif o.kind == "accepted":
                recomputed = sliding[0].read_bytes() != before and '"estimate"' not in sliding[0].read_text()
                said = sliding[0].name in err(p)
                o = rt.Outcome(
                    "accepted" if recomputed and said else "silently wrong", f"recomputed {recomputed}, named {said}"
                )
            record(
                cls,
                f"an estimate job file in a sliding job's slot: {command[1]}",
                " ".join(map(str, command[:2])),
                o.kind,
                o.detail,
            )
            shutil.copy(estimate[0], sliding[0])
    # Python: samples=-1 names `samples`.
    one = d / "py.toml"
    one.write_text(run_file(64))
    for value in ["-1", "0", "17"]:
        python_trial(
            cls, f"wearsim.estimate(run, samples={value})", f"wearsim.estimate('{one}', samples={value})", "`samples`"
        )
    # study plot under a file-size limit.
    for blocks in [50, 8]:
        folder = d / f"plot{blocks}"
        shutil.copytree(pristine, folder)
        p = sh(f"trap '' XFSZ; ulimit -f {blocks}; exec {WEARSIM} study plot {folder}")
        o = classify(p)
        if o.kind == "clear error":
            text = err(p)
            good = (
                "backend" not in text.lower()
                and ("figures" in text or str(folder) in text)
                and any(w in text.lower() for w in ("full", "file size", "file-size", "too large", "no space"))
            )
            o = rt.Outcome("clear error" if good else "unclear error", o.detail)
        record(cls, f"study plot under ulimit -f {blocks}", f"ulimit -f {blocks}; wearsim study plot", o.kind, o.detail)


# ---------------------------------------------------------------------------------------------
# 7. Combinations


def stop_and_rerun(
    cls: str, name: str, args: list, result, reference: str, duration: float, sig, rng, parent: Path
) -> None:
    """Stops `args` with `sig` part-way, checks nothing is half-written, reruns, compares."""
    child = popen(args)
    time.sleep(rng.uniform(0.2, 0.8) * duration)
    sent = time.monotonic()
    child.send_signal(sig)
    try:
        child.wait(timeout=10)
    except subprocess.TimeoutExpired:
        child.kill()
        child.wait()
        record(cls, f"{name}, {sig.name}", args, "ignored signal", "still running 10 s later")
        return
    took = time.monotonic() - sent
    e = child.stderr.read().decode(errors="replace") if child.stderr else ""
    stray = [n for n in hidden(parent) if ".tmp" in n or n.endswith(".claim")]
    status = child.returncode
    again = run(args, timeout=120)
    got = result()
    same = again is not None and again.returncode == 0 and got == reference
    if status == 101 or "panicked" in e:
        kind = "panic"
    elif status < 0:
        kind = "abort"
    elif status == 0 and took > 1.0:
        kind = "ignored signal"
    elif status not in (0, 128 + sig):
        kind = "unclear error"
    elif stray:
        kind = "data loss"
    elif not same:
        kind = "silently wrong" if again is not None and again.returncode == 0 else "data loss"
    else:
        kind = "accepted"
    record(
        cls,
        f"{name}, {sig.name}",
        args,
        kind,
        f"status {status} after {took:.2f} s, stray {stray}, rerun same {same}; {e.strip()[-120:]}",
    )


def combinations(tmp: Path) -> None:
    cls = "7 combinations"
    d = tmp / "comb"
    d.mkdir()
    rng = random.Random(11)
    # Signals to estimate, estimate-check and a mixed study.
    est = d / "est.toml"
    est.write_text(run_file(256, "[5e-4, 1e-3, 2e-3]"))
    ref = d / "est-ref"
    start = time.monotonic()
    run(["estimate", est, "--out", ref, "--samples", "8"], timeout=120)
    est_duration = time.monotonic() - start
    study = d / "ck.toml"
    study.write_text(run_file(128, "[5e-4, 1e-3]", seed="[1, 2]"))
    run(["study", "run", study, "--out", d / "ck"], timeout=120)
    start = time.monotonic()
    run(["estimate-check", d / "ck", "--out", d / "ck-ref", "--samples", "16"], timeout=120)
    check_duration = time.monotonic() - start
    mixed = d / "mixed.toml"
    mixed.write_text(
        run_file(128, "[5e-4, 1e-3]", seed="[1, 2]") + 'model = ["sliding", "estimate"]\nestimate_samples = 4\n'
    )
    start = time.monotonic()
    p = run(["study", "run", mixed, "--out", d / "mixed-ref", "--jobs", "1"], timeout=120)
    mixed_duration = time.monotonic() - start
    mixed_ok = p is not None and p.returncode == 0
    mixed_ref = collect(d / "mixed-ref") if mixed_ok else None

    def text(path: Path):
        return lambda: path.read_text() if path.exists() else None

    for sig in SIGNALS:
        o = d / f"est-{sig.name}"
        stop_and_rerun(
            cls,
            "estimate stopped",
            ["estimate", est, "--out", o, "--samples", "8"],
            text(o / "results.csv"),
            (ref / "results.csv").read_text(),
            est_duration,
            sig,
            rng,
            d,
        )
        o = d / f"ck-{sig.name}"
        stop_and_rerun(
            cls,
            "estimate-check stopped",
            ["estimate-check", d / "ck", "--out", o, "--samples", "16"],
            text(o / "comparison.csv"),
            (d / "ck-ref" / "comparison.csv").read_text(),
            check_duration,
            sig,
            rng,
            d,
        )
        o = d / f"mixed-{sig.name}"
        if not mixed_ok:
            record(
                cls,
                f"mixed study stopped, {sig.name}",
                "wearsim study run mixed.toml",
                "not run",
                f"the mixed study is refused: {error_line(p)}",
            )
            continue
        stop_and_rerun(
            cls,
            "mixed study run stopped",
            ["study", "run", mixed, "--out", o, "--jobs", "1"],
            lambda o=o: collect(o),
            mixed_ref,
            mixed_duration,
            sig,
            rng,
            d,
        )
    # Shards of a mixed study, then collect: every job once.
    if mixed_ok:
        for name, shards in [("--shard 1/2, 2/2", ["1/2", "2/2"]), ("--shard 2/3, 1/3, 3/3", ["2/3", "1/3", "3/3"])]:
            o = d / f"shards{len(shards)}"
            statuses = [run(["study", "run", mixed, "--out", o, "--shard", s]) for s in shards]
            table = collect(o)
            ok = all(s is not None and s.returncode == 0 for s in statuses)
            kind = "accepted" if ok and table == mixed_ref else ("silently wrong" if ok else classify(statuses[0]).kind)
            record(
                cls,
                f"mixed study in shards {name}, then collect",
                "wearsim study run mixed.toml --shard ...",
                kind,
                f"same as one run: {table == mixed_ref}",
            )
        # Slurm array tasks of the same study.
        o = d / "shards-slurm"
        statuses = [
            run(
                ["study", "run", mixed, "--out", o],
                env={
                    **ENV,
                    "SLURM_ARRAY_TASK_ID": str(i),
                    "SLURM_ARRAY_TASK_COUNT": "2",
                    "SLURM_ARRAY_TASK_MIN": "1",
                    "SLURM_ARRAY_TASK_MAX": "2",
                },
            )
            for i in (1, 2)
        ]
        table = collect(o)
        ok = all(s is not None and s.returncode == 0 for s in statuses)
        record(
            cls,
            "mixed study as a Slurm array of 2, then collect",
            "SLURM_ARRAY_TASK_ID=1,2 wearsim study run",
            "accepted" if ok and table == mixed_ref else "silently wrong",
            f"same: {table == mixed_ref}",
        )
    # estimate-check while a study still runs on the folder.
    slow = d / "slow.toml"
    slow.write_text(run_file(128, "[2.5e-4, 5e-4, 1e-3, 2e-3]", seed="[1, 2, 3]"))
    for t, delay in enumerate([0.5, 1.5, 3.0]):
        folder = d / f"slow{t}"
        child = popen(["study", "run", slow, "--out", folder, "--jobs", "1"])
        time.sleep(delay)
        p = run(["estimate-check", folder, "--out", d / f"slow{t}-cmp"])
        child.wait(timeout=300)
        o = classify(p)
        if o.kind == "accepted":
            summary = json.loads((d / f"slow{t}-cmp" / "summary.json").read_text())
            compared = summary.get("jobs_compared", 0)
            rows = (d / f"slow{t}-cmp" / "comparison.csv").read_text().splitlines()[1:]
            finished = len(job_files(folder))
            kind = "accepted" if compared <= finished else "silently wrong"
            detail = f"{compared} jobs compared ({len(rows)} rows) of {finished} finished at the end"
        elif o.kind == "clear error" and any(w in o.detail for w in ("JSON", "EOF", "expected", "parse")):
            kind, detail = "unclear error", o.detail
        else:
            kind, detail = o.kind, o.detail
        record(cls, f"estimate-check {delay} s into a running study", "wearsim estimate-check slowN", kind, detail)
    # A closed pipe under shards of a mixed study.
    if mixed_ok:
        for log in (True, False):
            o = d / f"pipe-shards{log}"
            statuses = []
            for s in ["1/2", "2/2"]:
                status, _ = read_then_close(
                    (["--log"] if log else []) + ["study", "run", mixed, "--out", o, "--shard", s], 1, d
                )
                statuses.append(status)
            table = collect(o)
            if any(s is None for s in statuses):
                kind = "hang"
            elif any(s == 101 for s in statuses):
                kind = "panic"
            elif all(s == 0 for s in statuses):
                kind = "accepted" if table == mixed_ref else "silently wrong"
            else:
                kind = "data loss" if table != mixed_ref else "unclear error"
            record(
                cls,
                f"closed pipe under --shard 1/2, 2/2{' --log' if log else ''}",
                "wearsim study run --shard K/2 | head -1",
                kind,
                f"statuses {statuses}, collected same {table == mixed_ref}",
            )


def main() -> None:
    global WEARSIM, PYTHON, ENV
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--wearsim", required=True, help="the wearsim binary to try")
    parser.add_argument("--python", default=sys.executable, help="a Python with wearsim and numpy installed")
    parser.add_argument("--out", type=Path, help="write every trial as JSON here")
    parser.add_argument("--only", help="classes to run, comma-separated numbers (default: all)")
    args = parser.parse_args()
    WEARSIM = str(Path(args.wearsim).resolve())
    rt.WEARSIM = WEARSIM
    PYTHON = args.python
    only = set(args.only.split(",")) if args.only else None
    start = time.time()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        home = tmp / "home"
        (home / ".cache").mkdir(parents=True)
        ENV = {**os.environ, "HOME": str(home), "XDG_CACHE_HOME": str(home / ".cache"), "WEARSIM_NO_ESTIMATE": "1"}
        for k in [k for k in ENV if k.startswith("SLURM_")]:
            del ENV[k]
        os.environ.update({"HOME": ENV["HOME"], "XDG_CACHE_HOME": ENV["XDG_CACHE_HOME"], "WEARSIM_NO_ESTIMATE": "1"})
        file_study_tree(tmp / "of-pristine")
        steps = [
            ("1", output_folders),
            ("2", closed_pipe),
            ("3", estimate_and_studies),
            ("4", claims),
            ("5", caches),
            ("6", messages),
            ("7", combinations),
        ]
        for number, step in steps:
            if only is None or number in only:
                t0 = time.time()
                step(tmp)
                print(f"class {number}: {time.time() - t0:.0f} s", file=sys.stderr)
    elapsed = time.time() - start
    rt.print_report(TRIALS, OUTCOMES)
    print(f"\n{len(TRIALS)} trials in {elapsed:.0f} s with {WEARSIM}")
    if args.out:
        args.out.write_text(
            json.dumps({"wearsim": WEARSIM, "seconds": round(elapsed), "trials": TRIALS}, indent=1, ensure_ascii=False)
        )


if __name__ == "__main__":
    main()
