"""What a taper does to the contact of a measured map slid over itself.

A measured map is not periodic, and the documented way to slide it as one period of a periodic
surface is to taper it: a Tukey window brings the heights to the mean over a fraction of each side.
With top = the map and bottom = the map turned by 180° (a counter-body with the same statistics),
both tapered, the strips along the two borders y = 0 and y = Ly (parallel to the sliding direction x)
are flat in *both* bodies at every offset, so the composite surface is flat there whatever the
offset: a flat band at the mean height, which carries load that the rough interior would carry.

This script solves the elastic–perfectly plastic contact (paper §2) of the pair at offsets spread
over one period, for several taper fractions, and reports per offset the fraction of the border
strip (the bottom's tapered border, all four sides) in contact and the mean pressure there against
the interior's. It writes ``taper_border_contact.csv`` (one row per taper and offset) and
``taper_border_contact.png``.

    python examples/measured/taper_border_contact.py --map HEIGHTS.npy LX PRESSURE [--map ...] --out DIR

HEIGHTS.npy in metres, [x, y], as ``wearsim surface import`` writes it, LX its side in metres,
PRESSURE the nominal pressure F_N/(Lx Ly) in Pa. Material: SI, E = 200 GPa, ν = 0.3, τ̃ = 2 GPa by
default (those of examples/measured/study.toml).
"""

from __future__ import annotations

import argparse
import csv
import math
import os
from pathlib import Path
from typing import Dict, List

import numpy as np
import wearsim


def tukey(n: int, fraction: float) -> np.ndarray:
    """The taper of ``wearsim`` (topography::prepare): cosine ramps over ``fraction`` of the side,
    half at each end."""
    w = np.ones(n)
    ramp = fraction * n / 2.0
    if ramp <= 0.0:
        return w
    i = np.arange(n) + 0.5
    left = i < ramp
    right = i > n - ramp
    w[left] = 0.5 * (1.0 - np.cos(np.pi * i[left] / ramp))
    w[right] = 0.5 * (1.0 - np.cos(np.pi * (n - i[right]) / ramp))
    return w


def tapered(h: np.ndarray, fraction: float) -> np.ndarray:
    mean = h.mean()
    window = np.outer(tukey(h.shape[0], fraction), tukey(h.shape[1], fraction))
    return mean + (h - mean) * window


def border_mask(shape: tuple, width: int) -> np.ndarray:
    """Pixels within ``width`` of any side."""
    nx, ny = shape
    i = np.arange(nx)[:, None]
    j = np.arange(ny)[None, :]
    return (i < width) | (i >= nx - width) | (j < width) | (j >= ny - width)


def contact_rows(
    name: str, h: np.ndarray, length: float, pressure: float, args: argparse.Namespace
) -> List[Dict[str, object]]:
    """One row per taper and offset: the contact of the border strip against the interior's."""
    nx, ny = h.shape
    e_star = args.youngs_modulus / (1.0 - args.poisson_ratio**2)
    flow_pressure = 3.0 * math.sqrt(3.0) * args.shear_strength
    load = pressure * length * length * ny / nx
    solver = wearsim.ContactSolver((nx, ny), length, e_star)
    strip = border_mask(h.shape, max(1, round(args.strip * nx / 2.0)))
    rows: List[Dict[str, object]] = []
    for fraction in args.tapers:
        top = tapered(h, fraction)
        bottom = np.rot90(top, 2).copy()
        previous = None
        for k in range(args.offsets):
            offset = k * nx // args.offsets
            r = solver.solve(
                bottom + np.roll(top, offset, axis=0), load, flow_pressure=flow_pressure, initial_pressure=previous
            )
            previous = r.pressure
            contact = r.pressure > 0.0
            rows.append(
                {
                    "map": name,
                    "nominal_pressure_pa": pressure,
                    "taper": fraction,
                    "offset_px": offset,
                    "contact_area": r.contact_area,
                    "border_contact_fraction": float(contact[strip].mean()),
                    "interior_contact_fraction": float(contact[~strip].mean()),
                    "border_share_of_load": float(r.pressure[strip].sum() / r.pressure.sum()),
                    "border_share_of_area": float(strip.mean()),
                }
            )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--map",
        nargs=3,
        action="append",
        required=True,
        metavar=("HEIGHTS", "LENGTH", "PRESSURE"),
        help="heights.npy (m), its side Lx (m) and the nominal pressure F_N/(Lx Ly) (Pa); repeat for more maps",
    )
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--youngs-modulus", type=float, default=200e9)
    parser.add_argument("--poisson-ratio", type=float, default=0.3)
    parser.add_argument("--shear-strength", type=float, default=2e9, help="τ̃, Pa")
    parser.add_argument("--tapers", type=float, nargs="+", default=[0.0, 0.05, 0.1, 0.2])
    parser.add_argument("--offsets", type=int, default=8, help="offsets over one period")
    parser.add_argument("--strip", type=float, default=0.05, help="border strip compared, fraction of the side")
    args = parser.parse_args()

    rows: List[Dict[str, object]] = []
    maps = []
    for path, length, pressure in args.map:
        name = Path(path).parent.name or Path(path).stem
        h = np.load(path)
        maps.append((name, float(pressure)))
        rows += contact_rows(name, h, float(length), float(pressure), args)
    args.out.mkdir(parents=True, exist_ok=True)
    table = args.out / "taper_border_contact.csv"
    with open(table.with_suffix(".csv.tmp"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    os.replace(table.with_suffix(".csv.tmp"), table)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(maps), figsize=(4.2 * len(maps), 3.6), constrained_layout=True, squeeze=False)
    for ax, (name, pressure) in zip(axes[0], maps):
        for key, style, label in [
            ("border_contact_fraction", "o-", "border strip"),
            ("interior_contact_fraction", "s--", "interior"),
        ]:
            values = [[float(r[key]) for r in rows if r["map"] == name and r["taper"] == t] for t in args.tapers]  # type: ignore[arg-type]
            mean = np.array([np.mean(v) for v in values])
            low = mean - np.array([np.min(v) for v in values])
            high = np.array([np.max(v) for v in values]) - mean
            ax.errorbar(args.tapers, mean, yerr=[low, high], fmt=style, ms=4, capsize=3, label=label)
        ax.set_xlabel("taper (fraction of each side)")
        ax.set_ylabel("fraction in contact")
        ax.set_title(f"{name}, p_N = {pressure / 1e6:g} MPa", fontsize=9)
        ax.set_ylim(bottom=0.0)
        ax.legend(fontsize=8)
    fig.suptitle(
        f"map over itself turned 180°: contact in the border strip ({args.strip:g} of each side) and inside"
        " (mean over offsets; bars: min–max)",
        fontsize=10,
    )
    png = args.out / "taper_border_contact.png"
    fig.savefig(png.with_suffix(".tmp.png"), dpi=120)
    os.replace(png.with_suffix(".tmp.png"), png)
    print(f"wrote {table} and {png}")


if __name__ == "__main__":
    main()
