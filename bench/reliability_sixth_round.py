"""The sixth round of reliability trials: the path every user with their own surface takes —
``wearsim surface import`` on the instrument formats SurfaceTopography reads, ``surface fit`` and
``estimate`` on what it imported, and the Python route (``wearsim.measured``, the contact solver
and the surface functions given a SurfaceTopography topography).

    python bench/reliability_sixth_round.py --wearsim target/release/wearsim [--python PY] [--out report.json]

``--python`` (default: this interpreter) must have ``wearsim`` with its ``measured`` extra
(SurfaceTopography): the files are written with SurfaceTopography's own writers (NetCDF, ISO 25178
``.x3p``, Gwyddion ``.gwy``, text matrices) and the repository's AFM file
``examples/measured/di-3.di`` (Bruker/Digital Instruments) is read as shipped. Classes:

1. formats: each writer × units × periodic or not × shapes (odd sides, 16², under 16 pixels a
   side) × pixels (square, 1 × 2, 1 × 1.5, 1 × 2.1875 with and without ``--resample``); the imported
   heights are checked against the file's, in metres, levelled, cropped to even sides, [x, y];
2. undefined pixels: none, one, 30 %, half, all, with and without ``--fill harmonic``;
3. damaged and foreign files: each format cut at 10, 50 and 90 %, random bytes under each
   extension, an empty file, plain ``.npy`` and text maps without a size;
4. channels of the AFM file: each index, and one past the last;
5. the Python child of ``surface import``: an interpreter that hangs (each stop signal, and the
   time-out), one that exits 0 doing nothing, one without the package; ``--out`` below a file, onto
   a folder of the user's, onto the input;
6. ``surface fit`` and ``estimate`` on imported maps (the fit's block run by ``wearsim surface``;
   an SI run file on the imported bodies estimated), a flat map, a plane;
7. the Python route: ``solve_contact``, ``ContactSolver.solve``, ``composite_heights``,
   ``fit_surface``, ``spectrum_pair`` and ``heights_and_length`` given a topography;
   ``wearsim.measured`` after ``import wearsim``; the import's warnings as Python warnings.

Outcomes, as in docs/reliability.md: accepted (the right result, checked), clear error (non-zero,
the first line names the file or field and the cause, nothing written), unclear error, crash-hang
(a panic, a Python traceback, a kill, or over the time limit), data loss (an input or a folder of the
user's changed or removed, or a half-written output), silently wrong (exit 0 with a wrong or
unflagged result).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import reliability_common as rt

ROOT = Path(__file__).resolve().parents[1]
DI = ROOT / "examples" / "measured" / "di-3.di"
OUTCOMES = ["accepted", "clear error", "unclear error", "crash-hang", "data loss", "silently wrong"]
TIMEOUT = 120
WEARSIM = "wearsim"
PYTHON = sys.executable
ENV: dict = {}
TRIALS: list = []


def record(cls: str, name: str, outcome: str, detail: str = "") -> None:
    assert outcome in OUTCOMES, outcome
    TRIALS.append({"class": cls, "name": name, "outcome": outcome, "detail": detail[:600]})


def run(args: list, timeout: float = TIMEOUT, env=None) -> subprocess.CompletedProcess | None:
    try:
        return subprocess.run(
            [WEARSIM, *map(str, args)], capture_output=True, text=True, timeout=timeout, env=env or ENV
        )
    except subprocess.TimeoutExpired:
        return None


def py(code: str, timeout: float = TIMEOUT) -> subprocess.CompletedProcess | None:
    try:
        return subprocess.run([PYTHON, "-c", code], capture_output=True, text=True, timeout=timeout, env=ENV)
    except subprocess.TimeoutExpired:
        return None


def refusal(p: subprocess.CompletedProcess | None, out: Path | None, *words: str) -> tuple[str, str]:
    """A refusal: clear when its first error line names every one of ``words`` and nothing was
    written; a traceback, a panic or a time-out is a crash-hang."""
    if p is None:
        return "crash-hang", "time-out"
    e = p.stderr
    if "Traceback" in e or "panicked" in e or p.returncode < 0 or p.returncode in (101, 134, 137, 139):
        return "crash-hang", e[-400:]
    if p.returncode == 0:
        return "silently wrong", "accepted: " + p.stdout[-300:]
    first = next((line for line in e.splitlines() if line.startswith("error:")), "")
    if out is not None and out.exists():
        return "data loss", f"{out} written by a failed import"
    if first and all(w.lower() in first.lower() for w in words):
        return "clear error", first
    return "unclear error", first or e[-300:]


# The writers of SurfaceTopography a map can be written with here (the .di file is read as shipped).
WRITERS = {"nc": "to_netcdf", "x3p": "to_x3p", "gwy": "to_gwy", "txt": "to_matrix"}

WRITE = """
import numpy as np, sys, json
from SurfaceTopography import Topography
for spec in json.load(open(sys.argv[1])):
    rng = np.random.default_rng(spec["seed"])
    nx, ny = spec["shape"]
    x, y = np.arange(nx)[:, None] * spec["pixel"][0], np.arange(ny)[None, :] * spec["pixel"][1]
    lx, ly = nx * spec["pixel"][0], ny * spec["pixel"][1]
    h = 0.05 * np.sin(2 * np.pi * x / lx * 3) * np.cos(2 * np.pi * y / ly * 2)
    h = h + 0.01 * rng.normal(size=(nx, ny)) + 0.02 * x / lx
    if spec.get("plane"):
        h = 0.01 * x + 0.03 * y
    mask = np.zeros((nx, ny), bool)
    k = int(round(spec.get("undefined", 0) * nx * ny))
    mask.ravel()[rng.permutation(nx * ny)[:k]] = True
    if spec.get("block"):
        mask[:, : ny // 2] = True
    data = np.ma.masked_array(h, mask=mask) if mask.any() else h
    t = Topography(data, (lx, ly), unit=spec["unit"], periodic=spec["periodic"])
    getattr(t, spec["writer"])(spec["path"])
    np.save(spec["path"] + ".truth.npy", h)
"""

# Each import checked against the heights written: in metres, levelled, cropped to even sides, [x, y]
# (a plane resampled onto square pixels: the same plane); the bottom body the map turned by 180°.
CHECK = """
import numpy as np, sys, json, wearsim
results = []
for out, truth, scale, plane in json.load(open(sys.argv[1])):
    a = np.load(out + "/heights.npy")
    r = json.load(open(out + "/import.json"))
    h = np.load(truth) * scale
    nx, ny = a.shape
    if r["resampled"] is None:
        want = wearsim.preprocess_surface(h[:nx, :ny], detrend=r["detrend"])
        ok = np.allclose(a, want, rtol=1e-6, atol=1e-9 * np.abs(want).max())
    else:
        p = r["resampled"]["pixel_size"] * r["metres_per_unit"]
        x, y = np.arange(nx)[:, None] * p, np.arange(ny)[None, :] * p
        # The plane's slopes are dimensionless: the same in metres whatever unit the file is in.
        ok = plane and np.allclose(a, 0.01 * x + 0.03 * y, rtol=1e-6, atol=1e-15)
    b = np.load(out + "/bottom.npy")
    ok = ok and np.array_equal(b, a[::-1, ::-1]) and nx % 2 == 0 and ny % 2 == 0 and min(nx, ny) >= 16
    results.append([bool(ok), [nx, ny]])
print(json.dumps(results))
"""

METRES = {"nm": 1e-9, "um": 1e-6, "mm": 1e-3, "m": 1.0}
MATERIAL = "[material]\nyoungs_modulus = 3e11\npoisson_ratio = 0.25\nshear_strength = 3e9\nfracture_energies = [1.0]\n"


def batch(program: str, items: list, tmp: Path) -> subprocess.CompletedProcess:
    """Runs ``program`` once on a JSON list of ``items`` (one Python start for many files)."""
    listing = tmp / f"batch-{len(TRIALS)}-{time.monotonic_ns()}.json"
    listing.write_text(json.dumps(items))
    p = subprocess.run([PYTHON, "-c", program, str(listing)], capture_output=True, text=True, env=ENV)
    if p.returncode != 0:
        print(f"batch failed: {p.stderr[-500:]}", file=sys.stderr)
    return p


def spec_of(path: Path, **spec) -> dict:
    return {
        "seed": 1,
        "periodic": False,
        "unit": "um",
        "pixel": (1.0, 1.0),
        "shape": (64, 64),
        **spec,
        "path": str(path),
    }


def write(path: Path, **spec) -> bool:
    return batch(WRITE, [spec_of(path, **spec)], path.parent).returncode == 0


def import_(path: Path, out: Path, *extra: str) -> subprocess.CompletedProcess | None:
    return run(["surface", "import", path, "--out", out, "--python", PYTHON, *extra])


def formats(tmp: Path) -> None:
    cls = "1 formats, units, shapes, pixels"
    square = [((64, 64), (1.0, 1.0), False), ((65, 63), (0.5, 0.5), True), ((16, 16), (1.0, 1.0), False)]
    small = [((15, 64), (1.0, 1.0), False), ((2, 64), (1.0, 1.0), False)]
    ratios = [((40, 30), (1.0, 2.0), False), ((52, 49), (1.0, 1.5), False), ((40, 32), (1.0, 2.1875), False)]
    plan = [("nc", u, c) for u in ("nm", "m") for c in square + small + ratios]
    plan += [("x3p", u, c) for u in ("um", "mm") for c in square + ratios]
    plan += [("gwy", "um", c) for c in square + small[:1]] + [("txt", "um", c) for c in square]
    specs = []
    for k, (ext, unit, (shape, pixel, periodic)) in enumerate(plan):
        specs.append(
            spec_of(
                tmp / f"f{k}.{ext}",
                shape=shape,
                pixel=pixel,
                unit=unit,
                periodic=periodic,
                writer=WRITERS[ext],
                plane=pixel[0] != pixel[1],
            )
        )
    batch(WRITE, specs, tmp)
    checks, names = [], []
    for k, (ext, unit, (shape, pixel, periodic)) in enumerate(plan):
        f = Path(specs[k]["path"])
        if not f.exists():
            continue
        plane = pixel[0] != pixel[1]
        name = f"{ext} {unit} {shape[0]}×{shape[1]} pixels {pixel[0]}×{pixel[1]}{' periodic' if periodic else ''}"
        for extra in [()] if not plane else [(), ("--resample", "--detrend", "none")]:
            out = tmp / f"o{k}{len(extra)}"
            trial = f"{name} {' '.join(extra)}".strip()
            p = import_(f, out, *extra)
            too_small = min(shape) - min(shape) % 2 < 16
            if too_small or (plane and not extra):
                record(cls, trial, *refusal(p, out, "16 pixels" if too_small else "not square"))
            elif p is None or p.returncode != 0:
                record(cls, trial, *refusal(p, out, f.name))
            else:
                # gwy files hold metres whatever the unit they were given in.
                checks.append([str(out), str(f) + ".truth.npy", METRES[unit], plane])
                names.append(trial)
    c = batch(CHECK, checks, tmp)
    results = json.loads(c.stdout) if c.returncode == 0 else [[False, None]] * len(names)
    for trial, (ok, grid) in zip(names, results):
        record(cls, trial, "accepted" if ok else "silently wrong", f"grid {grid}")


def undefined(tmp: Path) -> None:
    cls = "2 undefined pixels"
    # (share, whether the undefined pixels are one block, half the map, rather than scattered)
    shares = [(0.0, False), (1 / 4096, False), (0.3, False), (0.5, True), (1.0, False)]
    batch(
        WRITE,
        [spec_of(tmp / f"u{a}.x3p", undefined=0 if b else a, block=b, writer="to_x3p", unit="nm") for a, b in shares],
        tmp,
    )
    for share, _block in shares:
        f = tmp / f"u{share}.x3p"
        for fill in ((), ("--fill", "harmonic")):
            out = tmp / f"uo{share}{len(fill)}"
            p = import_(f, out, *fill)
            name = f"{100 * share:.3g} % undefined{' --fill harmonic' if fill else ''}"
            if share == 1.0:
                record(cls, name, *refusal(p, out, "none of its", "measured"))
            elif share > 0 and not fill:
                record(cls, name, *refusal(p, out, "undefined", "--fill"))
            elif p is None or p.returncode != 0:
                record(cls, name, *refusal(p, out, f.name))
            else:
                r = json.loads((out / "import.json").read_text())
                warned = "warning:" in p.stderr and "invented" in p.stderr
                ok = abs(r["undefined_share"] - round(share * 4096) / 4096) < 1e-12 and warned == (share > 0.1)
                record(cls, name, "accepted" if ok else "silently wrong", p.stderr[-300:])


def damaged(tmp: Path) -> None:
    cls = "3 damaged and foreign files"
    batch(WRITE, [spec_of(tmp / f"whole.{ext}", writer=writer) for ext, writer in WRITERS.items()], tmp)
    sources = {ext: (tmp / f"whole.{ext}").read_bytes() for ext in WRITERS if (tmp / f"whole.{ext}").exists()}
    sources["di"] = DI.read_bytes()
    for ext, data in sources.items():
        for cut in (0.1, 0.5, 0.9):
            f = tmp / f"cut{int(100 * cut)}.{ext}"
            f.write_bytes(data[: int(len(data) * cut)])
            out = tmp / f"co{ext}{cut}"
            p = import_(f, out)
            if p is not None and p.returncode == 0:
                # A cut text matrix is a smaller map: accepted only if it says it read fewer rows.
                record(
                    cls, f"{ext} cut at {cut:.0%}", "accepted" if ext == "txt" else "silently wrong", p.stdout[-200:]
                )
                continue
            kind, detail = refusal(p, out, f.name)
            # A text matrix cut between rows reads as a smaller map with stretched pixels: the
            # refusal must say that a cut file does that, not only point to --resample.
            if kind == "clear error" and "not square" in detail and "cut short" not in detail:
                kind = "unclear error"
            record(cls, f"{ext} cut at {cut:.0%}", kind, detail)
        f = tmp / f"noise.{ext}"
        f.write_bytes(os.urandom(2 * 64 * 64))
        out = tmp / f"no{ext}"
        record(cls, f"random bytes as .{ext}", *refusal(import_(f, out), out, f.name))
    for name, body in [("empty.dat", b""), ("noise.bin", os.urandom(8192))]:
        f = tmp / name
        f.write_bytes(body)
        out = tmp / f"o-{name}"
        record(cls, name, *refusal(import_(f, out), out, f.name))
    import numpy as np

    np.save(tmp / "plain.npy", np.random.default_rng(0).normal(size=(64, 64)))
    (tmp / "plain.csv").write_text("\n".join(",".join("0.1" for _ in range(32)) for _ in range(32)))
    for name in ("plain.npy", "plain.csv"):
        out = tmp / f"o-{name}"
        record(cls, f"{name} (no size)", *refusal(import_(tmp / name, out), out, "without an import"))


def channels(tmp: Path) -> None:
    cls = "4 channels"
    for channel, want in [
        (0, None),
        (1, "not a height channel"),
        (2, "not a height channel"),
        (3, None),
        (4, "channel"),
    ]:
        out = tmp / f"ch{channel}"
        p = import_(DI, out, "--channel", str(channel))
        if want is None:
            ok = p is not None and p.returncode == 0 and (out / "heights.npy").exists()
            record(cls, f"di channel {channel}", "accepted" if ok else refusal(p, out)[0], p.stderr[-200:] if p else "")
        else:
            record(cls, f"di channel {channel}", *refusal(p, out, want))


def script(path: Path, body: str) -> Path:
    path.write_text(f"#!/bin/sh\n{body}\n")
    path.chmod(0o755)
    return path


def children(tmp: Path) -> None:
    cls = "5 the import's Python child and its folder"
    f = tmp / "child.nc"
    write(f, writer="to_netcdf")
    hang = script(tmp / "hang", "exec sleep 100")
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGUSR1, signal.SIGHUP):
        out = tmp / f"h{int(sig)}"
        child = subprocess.Popen(
            [WEARSIM, "surface", "import", f, "--out", out, "--python", hang],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            env=ENV,
            preexec_fn=lambda: [signal.signal(s, signal.SIG_DFL) for s in (signal.SIGINT, signal.SIGHUP)],
        )
        time.sleep(0.5)
        sent = time.time()
        child.send_signal(sig)
        try:
            _, e = child.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            child.kill()
            record(cls, f"{sig.name} while the interpreter hangs", "crash-hang", "ignored")
            continue
        ok = child.returncode == 128 + sig and time.time() - sent < 5 and not out.exists() and "lacks" not in e
        record(cls, f"{sig.name} while the interpreter hangs", "accepted" if ok else "unclear error", e[-200:])
    out = tmp / "timeout"
    p = run(["surface", "import", f, "--out", out, "--python", hang], env={**ENV, "WEARSIM_PYTHON_TIMEOUT": "1"})
    record(cls, "an interpreter that never answers", *refusal(p, out, "did not answer"))
    silent = script(tmp / "silent", "exit 0")
    out = tmp / "silent-out"
    p = run(["surface", "import", f, "--out", out, "--python", silent])
    record(cls, "an interpreter that exits 0 doing nothing", *refusal(p, out, "wrote nothing"))
    out = tmp / "false-out"
    record(
        cls,
        "an interpreter without the package",
        *refusal(
            run(["surface", "import", f, "--out", out, "--python", "/bin/false"]), out, "lacks the wearsim package"
        ),
    )
    (tmp / "a-file.txt").write_text("keep")
    out = tmp / "a-file.txt" / "sub"
    p = import_(f, out)
    record(cls, "--out below a file", *refusal(p, None, "is a file, not a folder"))
    mine = tmp / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("keep")
    p = import_(f, mine)
    kind, detail = refusal(p, None, "--overwrite")
    if (mine / "notes.txt").read_text() != "keep":
        kind = "data loss"
    record(cls, "--out onto a folder of the user's", kind, detail)
    p = import_(f, tmp, "--overwrite")
    kind, detail = refusal(p, None, "instrument file")
    record(cls, "--out holding the input, --overwrite", kind if f.exists() else "data loss", detail)
    for repeat in range(2):
        out = tmp / "again"
        p = import_(f, out)
        ok = (
            p is not None
            and p.returncode == 0
            and sorted(x.name for x in out.iterdir()) == ["bottom.npy", "heights.npy", "import.json"]
        )
        record(
            cls,
            f"an import into its own folder ({repeat + 1})",
            "accepted" if ok else "unclear error",
            p.stderr[-200:] if p else "",
        )


def fit_and_estimate(tmp: Path) -> None:
    cls = "6 surface fit and estimate on imported maps"
    maps = [("nc", "to_netcdf", "um"), ("x3p", "to_x3p", "nm"), ("gwy", "to_gwy", "um")]
    batch(WRITE, [spec_of(tmp / f"fe.{e}", writer=w, unit=u, shape=(128, 128)) for e, w, u in maps], tmp)
    for ext, writer, _unit in [*maps, ("di", None, None)]:
        f = DI if writer is None else tmp / f"fe.{ext}"
        out = tmp / f"fe-{ext}"
        p = import_(f, out)
        if p is None or p.returncode != 0:
            record(cls, f"{ext}: import", *refusal(p, out, f.name))
            continue
        r = json.loads((out / "import.json").read_text())
        lx = r["length"][0]
        fit_out = tmp / f"fit-{ext}"
        p = run(["surface", "fit", out / "heights.npy", "--length", repr(lx), "--out", fit_out, "--generate"])
        if p is None or p.returncode != 0:
            record(cls, f"{ext}: surface fit", *refusal(p, None, "heights.npy"))
        else:
            fj = json.loads((fit_out / "fit.json").read_text())
            said = "rms slope" in p.stdout or "rms_slope" in fj and fj["rms_slope"] is None
            ok = said and (fit_out / "top.npy").exists()
            record(cls, f"{ext}: surface fit --generate", "accepted" if ok else "silently wrong", p.stdout[-200:])
            run_file = tmp / f"fit-{ext}.toml"
            run_file.write_text('units = "si"\n' + (fit_out / "surface.toml").read_text() + MATERIAL)
            p = run(["surface", run_file, "--out", tmp / f"gen-{ext}"])
            record(
                cls,
                f"{ext}: the fit's block run",
                "accepted" if p is not None and p.returncode == 0 else refusal(p, None)[0],
                p.stderr[-200:] if p else "",
            )
        hrms = r["rms_height_m"]
        slope_run = tmp / f"est-{ext}.toml"
        slope_run.write_text(
            r["surface_toml"].replace(str(out), str(out))
            + "[material]\nyoungs_modulus = 3e11\npoisson_ratio = 0.25\nhardness = 2e10\nfracture_energies = [1.0]\n"
            + f"[sliding]\npressures = [{3e11 * 0.01 * max(hrms / r['pixel_size_m'], 1e-3):.4e}]\n"
        )
        p = run(["estimate", slope_run, "--out", tmp / f"est-{ext}", "--samples", "4"])
        if p is not None and p.returncode == 0:
            ok = (tmp / f"est-{ext}" / "summary.json").exists()
            record(
                cls, f"{ext}: estimate on the imported bodies", "accepted" if ok else "silently wrong", p.stderr[-200:]
            )
        else:
            record(cls, f"{ext}: estimate on the imported bodies", *refusal(p, None, "pressure"))
    import numpy as np

    np.save(tmp / "flat.npy", np.full((64, 64), 2.5))
    np.save(tmp / "plane.npy", 0.01 * np.arange(64)[:, None] + 0.003 * np.arange(64)[None, :])
    for name in ("flat.npy", "plane.npy"):
        out = tmp / f"fit-{name}"
        p = run(["surface", "fit", tmp / name, "--length", "1e-5", "--out", out])
        record(cls, f"surface fit of {name}", *refusal(p, out, "flat", "spectrum is zero"))


PY_ROUTE = r"""
import json, sys, warnings, numpy as np, wearsim
from SurfaceTopography import Topography
results = {}
g = wearsim.generate_surface(64, length=32.0, hurst=0.8, lambda_lower=2.0, lambda_upper=16.0, rms_height=0.1, seed=3)
t = Topography(g, (32.0, 32.0), unit="um")
h, lx = wearsim.heights_and_length(t)
results["heights_and_length"] = bool(np.allclose(h, g * 1e-6) and abs(lx - 32e-6) < 1e-18)
e, load = 1e11, 1e-3 * 1e11 * lx * lx
def attempt(name, f):
    try:
        results[name] = bool(f())
    except Exception as x:
        results[name] = f"{type(x).__name__}: {x}"
ref = wearsim.solve_contact(h, load, effective_modulus=e, length=lx)
same = np.array_equal
attempt("solve_contact", lambda: same(wearsim.solve_contact(t, load, effective_modulus=e).pressure, ref.pressure))
attempt("ContactSolver.solve", lambda: same(wearsim.ContactSolver(64, lx, e).solve(t, load).pressure, ref.pressure))
attempt("composite_heights", lambda: same(wearsim.composite_heights(t, t, 5), wearsim.composite_heights(h, h, 5)))
attempt("fit_surface", lambda: abs(wearsim.fit_surface(t)["hurst"] - wearsim.fit_surface(h, lx)["hurst"]) < 1e-12)
attempt("fit_surface rms_slope", lambda: set(wearsim.fit_surface(t)["rms_slope"]) == {"map", "generated"})
attempt("spectrum_pair", lambda: same(wearsim.spectrum_pair(t, grid=64, seed=1)[0],
                                     wearsim.spectrum_pair(h, lx, grid=64, seed=1)[0]))
attempt("wearsim.measured", lambda: callable(wearsim.measured.import_topography))
attempt("wearsim.fields", lambda: wearsim.fields.__name__ == "wearsim.fields")
def flagged():
    m = np.ma.masked_array(g, mask=np.zeros_like(g, bool))
    m.mask[:, :40] = True
    Topography(m, (32.0, 32.0), unit="um").to_netcdf(sys.argv[1] + "/holes.nc")
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        wearsim.measured.import_topography(sys.argv[1] + "/holes.nc", sys.argv[1] + "/holes", fill="harmonic")
    return any("invented" in str(x.message) for x in w)
attempt("import warning as a Python warning", flagged)
def refused():
    try:
        wearsim.ContactSolver(64, 32.0, e).solve(t, load)
    except ValueError as x:
        return "the solver's length" in str(x)
    return False
attempt("a topography of another side refused", refused)
print(json.dumps(results))
"""


def python_route(tmp: Path) -> None:
    cls = "7 the Python route"
    try:
        p = subprocess.run([PYTHON, "-c", PY_ROUTE, str(tmp)], capture_output=True, text=True, timeout=TIMEOUT, env=ENV)
    except subprocess.TimeoutExpired:
        record(cls, "the Python route", "crash-hang", "time-out")
        return
    if p.returncode != 0:
        record(cls, "the Python route", "crash-hang", p.stderr[-400:])
        return
    for name, value in json.loads(p.stdout.strip().splitlines()[-1]).items():
        if value is True:
            record(cls, name, "accepted")
        elif value is False:
            record(cls, name, "silently wrong")
        else:
            record(cls, name, "unclear error", value)


def main() -> None:
    global WEARSIM, PYTHON, ENV
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--wearsim", required=True, help="the wearsim binary to try")
    parser.add_argument("--python", default=sys.executable, help="a Python with wearsim[measured] installed")
    parser.add_argument("--out", type=Path, help="write every trial as JSON here")
    parser.add_argument("--only", help="classes to run, comma-separated numbers (default: all)")
    args = parser.parse_args()
    WEARSIM = str(Path(args.wearsim).resolve())
    PYTHON = args.python
    only = set(args.only.split(",")) if args.only else None
    start = time.time()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        (tmp / "home" / ".cache").mkdir(parents=True)
        ENV = {**os.environ, "HOME": str(tmp / "home"), "XDG_CACHE_HOME": str(tmp / "home" / ".cache")}
        ENV["WEARSIM_NO_ESTIMATE"] = "1"
        steps = [formats, undefined, damaged, channels, children, fit_and_estimate, python_route]
        for number, step in enumerate(steps, 1):
            if only is None or str(number) in only:
                t0 = time.time()
                work = tmp / str(number)
                work.mkdir()
                step(work)
                shutil.rmtree(work, ignore_errors=True)
                print(f"class {number}: {time.time() - t0:.0f} s", file=sys.stderr)
    elapsed = time.time() - start
    rt.print_report(TRIALS, OUTCOMES, 300)
    print(f"\n{len(TRIALS)} trials in {elapsed:.0f} s with {WEARSIM} and {PYTHON}")
    if args.out:
        args.out.write_text(json.dumps({"seconds": round(elapsed), "trials": TRIALS}, indent=1, ensure_ascii=False))


if __name__ == "__main__":
    main()
