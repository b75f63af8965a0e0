"""wearsim from Python, notebook style: surfaces → contact → junctions → sliding wear → a study on
a Dask cluster, with matplotlib figures.

    pip install ".[examples]"          # from the repository root
    python examples/python/quickstart.py --out out/python-example

Reduced units throughout: E = 1, L = 1 (pressures in E, lengths in L, loads in E·L², fracture
energies in E·L). A grid of 128² keeps it to seconds; the paper's results need 4096².
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only; drop this line in a notebook
import matplotlib.pyplot as plt
import numpy as np
import wearsim

HERE = Path(__file__).resolve().parent


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)

    # %% 1. Two self-affine surfaces: H = 0.7, λ_l = 16 Δx, λ_u = L/4, h_rms = 0.005 L (paper §4.1).
    n = 128
    top, bottom = wearsim.generate_pair(n, hurst=0.7, lambda_lower=16 / n, lambda_upper=0.25, rms_height=0.005, seed=1)
    stats = wearsim.surface_statistics(top)
    print(f"surface: {n}², h_rms = {stats['rms_height']:.4f} L, rms slope = {stats['rms_slope']:.3f}")

    # %% 2. Material: τ̃ = 0.01 E gives p_m = 3√3 τ̃; d* from each fracture energy (eq. 1).
    material = wearsim.Material(
        youngs_modulus=1.0, poisson_ratio=0.3, shear_strength=0.01, fracture_energies=[0.5e-6, 1e-6]
    )
    print(f"flow pressure p_m = {material.flow_pressure:.4f} E, d* = {np.round(material.critical_diameters, 4)} L")

    # %% 3. One saturated contact at F_N = 1e-3 E L², its junctions and the static model.
    heights = wearsim.composite_heights(top, bottom, offset=0)
    contact = wearsim.solve_contact(
        heights, 1e-3, effective_modulus=material.effective_modulus(), flow_pressure=material.flow_pressure
    )
    junctions = wearsim.label_junctions(contact.contact, pixel_size=1 / n)
    static = wearsim.static_wear(junctions, material.critical_diameters[0])
    print(
        f"contact: A/L² = {contact.contact_area:.4f}, {contact.iterations} iterations, "
        f"{junctions.count} junctions, k_static = {static['wear_coefficient']:.3f}"
    )

    # %% 4. The sliding model: V(s) per load and fracture energy, W fitted after running-in.
    loads = [5e-4, 1e-3, 2e-3]
    series, summary = wearsim.slide(top, bottom, material, loads)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.5), sharex=True)
    for ax, (g, d) in zip(axes, zip(material.fracture_energies, material.critical_diameters)):
        for load in loads:
            s = series[(series.load == load) & (series.fracture_energy == g)]
            ax.plot(s.s, s.volume, label=f"$F_N$ = {load:g} $EL^2$")
        ax.axvline(0.25, color="0.6", lw=0.8, ls="--")
        ax.set(
            title=f"$\\mathcal{{G}}$ = {g:g} $EL$ ($d^*$ = {d:.3f} $L$)",
            xlabel="sliding distance $s/L$",
            ylabel="wear volume $V/L^3$",
        )
    axes[0].legend(frameon=False)
    fig.tight_layout()
    fig.savefig(out / "wear_volume.png", dpi=120)
    for r in summary["results"]:
        load, energy = r["load"], r["fracture_energy"]
        print(f"F_N = {load:g}, 𝒢 = {energy:g}: W = {r['wear_rate']:.3e} L², k = {r['wear_coefficient']:.3e}")

    # %% 5. A small study on a Dask cluster (here two local worker processes; on Slurm use
    # dask_jobqueue.SLURMCluster, see wearsim.study). The table equals `wearsim study collect`.
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, Client(cluster) as client:
        table = wearsim.study.run(HERE / "study.toml", client, out=out / "study")
    mean = table.groupby(["material.shear_strength", "load"])["wear_coefficient"].mean().unstack()
    print("mean Archard coefficient k over surface pairs (rows τ̃, columns F_N):")
    print(mean.to_string(float_format=lambda v: f"{v:.3e}"))
    fig, ax = plt.subplots(figsize=(4.5, 3.5))
    for tau, row in mean.iterrows():
        ax.plot(row.index, row.values, "o-", label=f"$\\tilde\\tau$ = {tau:g} $E$")
    ax.set(xscale="log", xlabel="normal load $F_N/(EL^2)$", ylabel="wear coefficient $k$")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(out / "study_wear_coefficient.png", dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("out/python-example"))
    main(parser.parse_args().out)
