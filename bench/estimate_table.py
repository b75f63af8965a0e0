"""The held-out table of docs/estimate.md from the `comparison.csv` files of `wearsim estimate-check`:
one row per setting (job × 𝒢) with at least MIN particles in the sliding run's fit window, the
estimate beside the sliding run for W, k and dN*₊/ds, whether the 95 % interval covers the sliding
W, then per set and over all sets the median and worst |estimate/sliding − 1| and the coverage.
Standard library only.

    python bench/estimate_table.py MIN LABEL=DIR/comparison.csv [LABEL=…]
"""

import csv
import statistics
import sys


def num(x: str) -> float:
    return float(x) if x not in ("", None) else float("nan")


def covered(r):
    """yes / no / no interval (outside the calibrated domain), as `estimate-check` scores it."""
    if r.get("scored") == "withheld":
        return "no interval"
    return "yes" if r["wear_rate_covered"] == "true" else "**no**"


def main() -> None:
    least = int(sys.argv[1])
    every = []
    print(
        "| set | job | seed | τ̃ (E) | p_N (E) | d* (px) | particles | W sliding | W estimate [95 %] | k sliding "
        "| k estimate | dN*₊/ds sliding | estimate | W error | covered |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    sets = []
    for arg in sys.argv[2:]:
        label, path = arg.split("=", 1)
        rows = [r for r in csv.DictReader(open(path)) if int(r["particles_in_fit"]) >= least and r["sliding_wear_rate"]]
        sets.append((label, rows))
        for r in rows:
            err = num(r["wear_rate_error"])
            print(
                f"| {label} | {r['job']} | {r['surface.seed'] or 'file'} | {num(r['material.shear_strength']):.3f} "
                f"| {num(r['nominal_pressure']):.2e} | {num(r['critical_diameter_pixels']):.1f} "
                f"| {r['particles_in_fit']} "
                f"| {num(r['sliding_wear_rate']):.3e} | {num(r['wear_rate']):.3e} [{num(r['wear_rate_low']):.2e}, "
                f"{num(r['wear_rate_high']):.2e}] | {num(r['sliding_wear_coefficient']):.3f} "
                f"| {num(r['wear_coefficient']):.3f} "
                f"| {num(r['sliding_particle_rate']):.1f} | {num(r['particle_rate']):.1f} | {100 * err:+.0f} % "
                f"| {covered(r)} |"
            )
        every.extend(rows)
    print()
    print(
        "| set | settings | W, k: median \\|error\\| | worst | dN*₊/ds: median | worst "
        "| interval covers W | covers dN*₊/ds |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for label, rows in sets + [("all held-out", every)]:
        if not rows:
            print(f"| {label} | 0 | – | – | – | – | – | – |")
            continue
        w = [abs(num(r["wear_rate_error"])) for r in rows]
        p = [abs(num(r["particle_rate_error"])) for r in rows]
        cw = sum(r["wear_rate_covered"] == "true" for r in rows)
        cp = sum(r["particle_rate_covered"] == "true" for r in rows)
        # Settings without an interval (outside the calibrated domain) are not in the denominator.
        n = sum(r["wear_rate_covered"] in ("true", "false") for r in rows)
        withheld = len(rows) - n
        note = f" ({withheld} without interval)" if withheld else ""
        print(
            f"| {label} | {len(rows)} | {100 * statistics.median(w):.1f} % | {100 * max(w):.0f} % "
            f"| {100 * statistics.median(p):.1f} % | {100 * max(p):.0f} % | {cw}/{n}{note} | {cp}/{n} |"
        )


if __name__ == "__main__":
    main()
