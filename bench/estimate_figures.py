"""Fig. 4a (W per unit nominal area against p_N) and Fig. 5 (dN*₊/ds per unit area) of the static
estimate beside sliding results, from the `results_aggregated.csv` of finished, collected studies:
each study one set of curves (one per fracture energy G), its label given on the command line, bars the 95 %
interval of the mean over surface pairs. Needs pandas and matplotlib.

    python bench/estimate_figures.py --out DIR "LABEL=STUDY_DIR" ["LABEL=STUDY_DIR" …]

(the last "=" of each argument separates the label from the folder)
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

MARKERS = ["o", "s", "^", "D", "v", "P"]
STYLES = ["-", "--", ":", "-."]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("studies", nargs="+", help="LABEL=STUDY_DIR")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    panels = [
        ("wear_rate", "W/(Lx·Ly) (reduced units: the W of a box L × L)", "fig4a"),
        ("particle_rate", "dN*₊/ds/(Lx·Ly) (1/L³)", "fig5"),
    ]
    for column, ylabel, name in panels:
        fig, ax = plt.subplots(figsize=(7.5, 5))
        for k, spec in enumerate(args.studies):
            label, folder = spec.rsplit("=", 1)
            table = pd.read_csv(Path(folder) / "results_aggregated.csv")
            area = table["surface.length"] * table["surface.length_y"].fillna(table["surface.length"])
            for e, (energy, rows) in enumerate(table.groupby("fracture_energy")):
                rows = rows.sort_values("nominal_pressure")
                a = area[rows.index]
                mean = rows[f"{column}_mean"] / a
                low = (rows[f"{column}_mean"] - rows[f"{column}_ci_low"]).clip(lower=0) / a
                high = (rows[f"{column}_ci_high"] - rows[f"{column}_mean"]).clip(lower=0) / a
                ax.errorbar(
                    rows["nominal_pressure"],
                    mean,
                    yerr=[low.fillna(0), high.fillna(0)],
                    marker=MARKERS[e % len(MARKERS)],
                    linestyle=STYLES[k % len(STYLES)],
                    color=f"C{e}",
                    capsize=3,
                    label=f"{label}, G = {energy:.2g} E L",
                )
        ax.set_xlabel("nominal pressure p_N = F_N/(Lx·Ly) (E)")
        ax.set_ylabel(ylabel)
        ax.set_yscale("log")
        ax.set_title(
            f"{name}: static estimate beside sliding runs (bars: 95 % interval over surface pairs)", fontsize=9
        )
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(args.out / f"{name}_estimate.png", dpi=120)
        print("wrote", args.out / f"{name}_estimate.png")


if __name__ == "__main__":
    main()
