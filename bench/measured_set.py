"""The committed measured-surface set (evidence/measured): instrument files to crops and study files.

For each instrument file given (SurfaceTopography's MIT-licensed file-format examples,
test/file_format_examples of https://github.com/ContactEngineering/SurfaceTopography):

1. ``wearsim surface import FILE --out TMP`` (adding ``--fill harmonic`` / ``--resample`` where the
   import's refusal names it, as bench/measured_maps.py does), levelled by a plane;
2. the central CROP × CROP pixels of the imported map (the whole map where it is that small), its
   own least-squares plane removed, stored as float32 ``evidence/measured/maps/NAME/heights.npy``
   (array [x, y], metres) with ``map.json``: the instrument file (name, SHA-256, the commit of
   SurfaceTopography it was taken from), the import's record (format, channel, unit, undefined pixels
   filled, resampling, native pixel sizes), the crop and the material and loads below;
3. ``evidence/measured/studies/NAME.toml``: a study on periodic pairs carrying the crop's measured
   spectrum (``source = "spectrum"``), a box of the crop's side on its own pixels, seeds 1 and 2, a
   steel-like material (E = 200 GPa, ν = 0.3, τ̃ = 2 GPa) whose two d* are 8 and 16 pixels, and the
   nominal pressures p_N = 1, 2 and 4 % of E* h'_rms (h'_rms the RMS slope of the composite
   surface, √2 that of the crop; E* h'_rms taken at most 2.5 p_m), one box slid with the second
   half fitted.

The studies are then run into their folders, ``wearsim study run evidence/measured/studies/NAME.toml
--out evidence/measured/NAME`` (docs/estimate.md, "Measured surfaces, committed", gives the commands
and the time). Usage::

    python bench/measured_set.py --wearsim target/ci/wearsim --commit COMMIT \\
        ST/test/file_format_examples/{di-1.di,mi-1.mi,opd-1.opd,plu-1.plu,di-3.di,x3p-2.x3p}
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from measured_maps import POISSON, SHEAR, YOUNGS, import_map  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
SET = ROOT / "evidence" / "measured"
CROP = 256
SEEDS = [1, 2]
PIXELS_OF_D_STAR = (8, 16)
LOAD_FRACTIONS = (0.01, 0.02, 0.04)

STUDY = """# The measured-surface set: {name} ({instrument}), docs/estimate.md "Measured surfaces, committed".
# Written by bench/measured_set.py; the crop and its provenance: ../maps/{name}/map.json.
#
# Periodic pairs carrying the crop's measured 2D PSD (source = "spectrum"), a box of the crop's side
# ({side_um:.4g} µm, {crop}² pixels of {pixel_nm:.4g} nm), seeds 1 and 2; E = 200 GPa, ν = 0.3,
# τ̃ = 2 GPa, 𝒢 = {g1:.4g} and {g2:.4g} J/m² (d* = 8 and 16 pixels); p_N = 1, 2 and 4 % of
# E* h'_rms = {scale_gpa:.4g} GPa ({p_mpa}); one box slid, the second half fitted.
units = "si"

[surface]
source = "spectrum"
map = "../maps/{name}/heights.npy"
map_length = {map_length!r}
grid = {crop}
length = {map_length!r}
seed = {seeds}

[material]
youngs_modulus = {youngs!r}
poisson_ratio = {poisson!r}
shear_strength = {shear!r}
fracture_energies = [{g1!r}, {g2!r}]

[sliding]
loads = [{f1!r}, {f2!r}, {f3!r}]
distance = 1.0
running_in = 0.5
"""

INSTRUMENTS = {
    "di": "Bruker (Digital Instruments) AFM",
    "mi": "Molecular Imaging AFM",
    "opd": "Wyko optical profiler",
    "plu": "Sensofar confocal microscope",
    "sur": "Digital Surf profilometer",
    "x3p": "ISO 25178 (X3P)",
}


def crop(heights: np.ndarray, side: int) -> tuple[np.ndarray, list[int]]:
    """The central side × side pixels (all of a side shorter), their least-squares plane removed."""
    nx, ny = heights.shape
    cx, cy = min(side, nx), min(side, ny)
    i0, j0 = (nx - cx) // 2, (ny - cy) // 2
    h = heights[i0 : i0 + cx, j0 : j0 + cy].astype(np.float64)
    x, y = np.meshgrid(np.arange(cx), np.arange(cy), indexing="ij")
    a = np.stack([np.ones(cx * cy), x.ravel(), y.ravel()], axis=1)
    coef, *_ = np.linalg.lstsq(a, h.ravel(), rcond=None)
    return h - (a @ coef).reshape(cx, cy), [i0, j0]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", type=Path)
    parser.add_argument("--wearsim", required=True)
    parser.add_argument("--commit", required=True, help="the SurfaceTopography commit the files were taken from")
    args = parser.parse_args()
    wearsim = str(Path(args.wearsim).resolve())
    env = dict(os.environ, WEARSIM_PYTHON=os.environ.get("WEARSIM_PYTHON", sys.executable))
    for file in args.files:
        name = file.stem
        with tempfile.TemporaryDirectory() as tmp:
            flags = import_map(wearsim, file.resolve(), Path(tmp) / "map", env)
            imported = json.loads((Path(tmp) / "map" / "import.json").read_text())
            heights = np.load(Path(tmp) / "map" / "heights.npy")
        h, origin = crop(heights, CROP)
        if h.shape != (CROP, CROP):
            raise SystemExit(f"{file}: imported as {heights.shape}, smaller than {CROP}² pixels")
        pixel = imported["pixel_size_m"]
        side = CROP * pixel
        slope = math.sqrt(2.0) * float(np.sqrt(np.mean(np.diff(h, axis=0) ** 2) + np.mean(np.diff(h, axis=1) ** 2)))
        slope /= pixel
        e_star = YOUNGS / (1 - POISSON**2)
        flow = 3 * math.sqrt(3) * SHEAR
        scale = min(e_star * slope, 2.5 * flow)
        loads = [f * scale * side * side for f in LOAD_FRACTIONS]
        mu = YOUNGS / (2 * (1 + POISSON))
        g = [d * pixel * SHEAR**2 / (2 * mu) / 3.0 for d in PIXELS_OF_D_STAR]
        out = SET / "maps" / name
        out.mkdir(parents=True, exist_ok=True)
        np.save(out / "heights.npy", h.astype(np.float32))
        record = {
            "written_by": "bench/measured_set.py",
            "instrument_file": file.name,
            "instrument": INSTRUMENTS.get(file.suffix.lstrip("."), file.suffix),
            "instrument_file_sha256": hashlib.sha256(file.read_bytes()).hexdigest(),
            "taken_from": "test/file_format_examples of https://github.com/ContactEngineering/SurfaceTopography",
            "surface_topography_commit": args.commit,
            "licence": "MIT (SurfaceTopography's LICENSE.md, in ../../SOURCE.md)",
            "import_flags": flags,
            "import": {
                k: imported.get(k)
                for k in (
                    "wearsim",
                    "surface_topography",
                    "format",
                    "reader",
                    "channel",
                    "channel_name",
                    "grid",
                    "physical_sizes",
                    "unit",
                    "pixel_size",
                    "undefined_pixels",
                    "fill",
                    "resampled",
                    "detrend",
                    "heights_grid",
                    "pixel_size_m",
                )
            },
            "crop": {
                "origin": origin,
                "grid": list(h.shape),
                "what": "the central pixels of the imported map, the crop's least-squares plane removed, as float32",
            },
            "length_m": side,
            "rms_height_m": float(h.std()),
            "composite_rms_slope": slope,
            "loads_n": loads,
            "nominal_pressures_pa": [f / side / side for f in loads],
            "fracture_energies_j_per_m2": g,
            "critical_diameter_pixels": list(PIXELS_OF_D_STAR),
        }
        (out / "map.json").write_text(json.dumps(record, indent=2, ensure_ascii=False) + "\n")
        studies = SET / "studies"
        studies.mkdir(parents=True, exist_ok=True)
        text = STUDY.format(
            name=name,
            instrument=record["instrument"],
            side_um=side * 1e6,
            crop=CROP,
            pixel_nm=pixel * 1e9,
            g1=g[0],
            g2=g[1],
            scale_gpa=scale / 1e9,
            p_mpa="/".join(f"{p / 1e6:.3g}" for p in record["nominal_pressures_pa"]) + " MPa",
            map_length=side,
            seeds=SEEDS,
            youngs=YOUNGS,
            poisson=POISSON,
            shear=SHEAR,
            f1=loads[0],
            f2=loads[1],
            f3=loads[2],
        )
        (studies / f"{name}.toml").write_text(text)
        pressures = record["nominal_pressures_pa"]
        print(f"{name}: {' '.join(flags) or 'as is'}, crop at {origin}, h'_rms {slope:.3f}, p_N {pressures} Pa")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
