"""The figures of ``wearsim study plot`` on matplotlib, from the tidy table of a study
(:func:`wearsim.study.collect`, or ``pandas.read_csv("results.csv")``) and from the series of one
sliding run (:func:`wearsim.slide`, or :func:`wearsim.study.job_series`). Each function returns a
``matplotlib.figure.Figure``; :func:`study_figures` draws them all into a folder.

Figures (Brink, Frérot & Molinari 2021): :func:`static_model` (Fig. 2), :func:`wear_volume` (Fig. 3),
:func:`sliding_wear` (Fig. 4a–b), :func:`constant_critical_diameter` (Figs. 4c/5c),
:func:`particle_rate` (Fig. 5), :func:`kim_comparison` (Fig. 6), :func:`particle_counts` (appendix
B), :func:`equation_5` (Fig. B.9b), :func:`junction_counts` (appendix C), :func:`contact_severity`
(appendix F), :func:`memory` (the memory of the initial contact, §3).

Curves are settings (material and every input that varies, but the surface pair) and fracture
energies; points are means over surface pairs, bars their min–max. Needs matplotlib
(``pip install "wearsim[examples]"``).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

#: Kim et al. (1986), rolling experiments: k = 6e-7 … 1.5e-3 (paper §4.3, Fig. 6c).
KIM_RANGE = (6e-7, 1.5e-3)

# Neither a study axis nor a result: the job, the seed, the load and the nominal pressure (along a
# curve), the fracture energy (labelled apart) and the warnings.
_NOT_SETTINGS = {"job", "surface.seed", "load", "nominal_pressure", "fracture_energy", "warnings"}
_MARKERS = "o^sDvP*X"


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError('wearsim.plot needs matplotlib: pip install "wearsim[examples]"') from e
    return plt


def _units(tidy: pd.DataFrame) -> Dict[str, str]:
    si = "units" in tidy.columns and (tidy["units"] == "si").any()
    if si:
        return {"load": "N", "length": "m", "area": "m²", "volume": "m³", "energy": "J/m²", "stress": "Pa"}
    return {"load": "E L²", "length": "L", "area": "L²", "volume": "L³", "energy": "E L", "stress": "E"}


def _result_columns(tidy: pd.DataFrame) -> List[str]:
    first_result = (
        list(tidy.columns).index("critical_diameter") if "critical_diameter" in tidy.columns else len(tidy.columns)
    )
    return list(tidy.columns[first_result:])


def _varying(tidy: pd.DataFrame) -> List[str]:
    """Input columns that take more than one value (the study's axes), the seed aside."""
    results = set(_result_columns(tidy))
    return [
        c
        for c in tidy.columns
        if c not in results and c not in _NOT_SETTINGS and tidy[c].astype(str).nunique(dropna=False) > 1
    ]


def curves(tidy: pd.DataFrame) -> List[Tuple[str, pd.DataFrame]]:
    """The curves of a tidy table: (label, per-load DataFrame with the mean, min and max over surface
    pairs of every result column, as ``<column>_mean`` …), one per setting and fracture energy."""
    units = _units(tidy)
    keys = _varying(tidy) + ["fracture_energy"]
    out = []
    for values, group in tidy.groupby(keys, sort=False, dropna=False):
        chosen: Tuple[Any, ...] = tuple(values) if isinstance(values, tuple) else (values,)
        parts = []
        for k, v in zip(keys, chosen):
            name = k.rsplit(".", 1)[-1]
            if k == "material":
                parts.append(str(v))
            elif name == "shear_strength":
                parts.append(rf"$\tilde{{\tau}}$ = {v:g} {units['stress']}")
            elif k == "fracture_energy":
                d = group["critical_diameter"].iloc[0]
                parts.append(rf"$\mathcal{{G}}$ = {v:.3g} {units['energy']} (d* = {d:.3g} {units['length']})")
            else:
                parts.append(f"{name} = {v:g}" if isinstance(v, (int, float, np.number)) else f"{name} = {v}")
        numeric = group.select_dtypes("number")
        by_pressure = numeric.drop(columns=["nominal_pressure"], errors="ignore").groupby(group["nominal_pressure"])
        stats = by_pressure.agg(["mean", "min", "max"])
        stats.columns = ["_".join(map(str, pair)) for pair in stats.columns.to_flat_index()]
        out.append((", ".join(parts), stats.reset_index()))
    return out


def _load_figure(
    tidy: pd.DataFrame,
    panels: Sequence[Tuple[str, str, bool]],
    title: str,
    band: Optional[Tuple[float, float, str]] = None,
    by_material: bool = False,
) -> Any:
    plt = _pyplot()
    units = _units(tidy)
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels) + 3.5, 5.0), squeeze=False)
    materials = list(dict.fromkeys(tidy["material"]))
    data = curves(tidy)
    for p, (ax, (column, label, log)) in enumerate(zip(axes[0], panels)):
        if band is not None and p == len(panels) - 1:
            ax.axhspan(band[0], band[1], color="tab:blue", alpha=0.15, label=band[2])
        for i, (name, stats) in enumerate(data):
            if f"{column}_mean" not in stats:
                continue
            m = materials.index(name.split(",")[0]) if by_material and name.split(",")[0] in materials else 0
            color = f"C{m if by_material else i}"
            y = stats[f"{column}_mean"]
            err = [y - stats[f"{column}_min"], stats[f"{column}_max"] - y]
            ax.errorbar(
                stats["nominal_pressure"],
                y,
                yerr=err,
                color=color,
                marker=_MARKERS[m % len(_MARKERS)],
                capsize=2,
                label=name,
            )
        ax.set_xscale("log")
        if log:
            ax.set_yscale("log")
        ax.set_xlabel(f"nominal pressure p_N = F_N/(Lx·Ly) ({units['stress']})")
        ax.set_ylabel(label.format(**units))
        ax.grid(True, which="major", color="0.9")
    axes[0][0].set_title(title, loc="left", fontsize=10)
    handles, labels = axes[0][-1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0, 0.72, 1))
    return fig


def static_model(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 2: the static model, mean over every offset of the sliding runs."""
    return _load_figure(
        tidy,
        [
            ("static_wear_rate_mean", "static wear rate W_static/ω ({area})", True),
            ("static_wear_coefficient_mean", "static wear coefficient k_static", False),
        ],
        "static model, mean over every offset",
    )


def sliding_wear(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 4a–b: the sliding model's W and k against load."""
    return _load_figure(
        tidy,
        [
            ("wear_rate", "sliding wear rate W = dV/ds ({area})", True),
            ("wear_coefficient", "wear coefficient k = W p_m / F_N", True),
        ],
        "sliding model",
    )


def particle_rate(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 5: particles emitted per sliding distance."""
    return _load_figure(tidy, [("particle_rate", "particle rate dN*₊/ds (1/{length})", True)], "particle rate")


def kim_comparison(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 6c: k per material against Kim et al.'s rolling experiments."""
    band = (KIM_RANGE[0], KIM_RANGE[1], "Kim et al. 1986, rolling experiments")
    return _load_figure(tidy, [("wear_coefficient", "wear coefficient k", True)], "k per material", band, True)


def junction_counts(tidy: pd.DataFrame) -> Any:
    """Paper appendix C: junctions N and critical junctions N* (means after running-in)."""
    return _load_figure(
        tidy,
        [
            ("junctions_mean", "junctions N", True),
            ("critical_junctions_mean", "junctions ≥ d*, N*", True),
        ],
        "numbers of junctions",
    )


def constant_critical_diameter(tidy: pd.DataFrame, tolerance: float = 0.15) -> List[Any]:
    """Paper Figs. 4c/5c: W, k and dN*₊/ds for settings whose d* agree within ``tolerance``; one
    figure per such group (none when the study has no two)."""
    figures = []
    diameters = sorted(tidy["critical_diameter"].unique())
    groups: List[List[float]] = []
    for d in diameters:
        if groups and d <= (1 + tolerance) * groups[-1][0]:
            groups[-1].append(d)
        else:
            groups.append([d])
    for group in groups:
        rows = tidy[tidy["critical_diameter"].isin(group)]
        if rows[["material.shear_strength", "fracture_energy"]].drop_duplicates().shape[0] < 2:
            continue
        figures.append(
            _load_figure(
                rows,
                [
                    ("wear_rate", "W ({area})", True),
                    ("wear_coefficient", "k", True),
                    ("particle_rate", "dN*₊/ds (1/{length})", True),
                ],
                f"nearly equal d* ≈ {group[0]:.3g}",
            )
        )
    return figures


def equation_5(tidy: pd.DataFrame) -> Any:
    """Paper Fig. B.9b: Eq. 5 (ω d*³ dN*₊/ds) against the summed W, means over surface pairs."""
    plt = _pyplot()
    units = _units(tidy)
    fig, ax = plt.subplots(figsize=(8.5, 5.0))
    values = []
    for i, (name, stats) in enumerate(curves(tidy)):
        w, e = stats["wear_rate_mean"], stats["wear_rate_estimate_mean"]
        keep = (w > 0) & (e > 0)
        ax.scatter(w[keep], e[keep], color=f"C{i}", label=name)
        values += list(w[keep]) + list(e[keep])
    if values:
        lo, hi = min(values) / 1.5, max(values) * 1.5
        ax.plot([lo, hi], [lo, hi], "k--", lw=1, label="Eq. 5 = W")
    ax.set(xscale="log", yscale="log", xlabel=f"wear rate W ({units['area']})", ylabel="Eq. 5: ω d*³ dN*₊/ds")
    fig.legend(loc="center right", fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0, 0.62, 1))
    return fig


def contact_severity(tidy: pd.DataFrame) -> Any:
    """Paper appendix F: W = α S_cⁿ with S_c = p_N √h_rms / K_Ic, fitted in log–log, with R²."""
    plt = _pyplot()
    units = _units(tidy)
    # S_c = p_N √h_rms / K_Ic is a column of the library's table (empty on measured surfaces).
    rows = tidy[(tidy["wear_rate"] > 0) & tidy["contact_severity"].notna()]
    s_c = rows["contact_severity"]
    fig, ax = plt.subplots(figsize=(8.5, 5.0))
    for i, material in enumerate(dict.fromkeys(rows["material"])):
        mine = rows["material"] == material
        ax.scatter(s_c[mine], rows["wear_rate"][mine], color=f"C{i}", marker=_MARKERS[i % 8], label=material)
    if len(rows) >= 2:
        x, y = np.log(s_c.to_numpy()), np.log(rows["wear_rate"].to_numpy())
        n, ln_alpha = np.polyfit(x, y, 1)
        r2 = 1 - np.sum((y - (n * x + ln_alpha)) ** 2) / np.sum((y - y.mean()) ** 2)
        grid = np.geomspace(s_c.min(), s_c.max(), 50)
        ax.plot(
            grid,
            np.exp(ln_alpha) * grid**n,
            "k--",
            lw=1,
            label=f"fit: α = {np.exp(ln_alpha):.3g}, n = {n:.3f}, R² = {r2:.3f}",
        )
    ax.set(xscale="log", yscale="log", xlabel="S_c = p_N √h_rms / K_Ic", ylabel=f"W ({units['area']})")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _one_load(series: pd.DataFrame, load: Optional[float]) -> pd.DataFrame:
    loads = series["load"].unique()
    load = loads[-1] if load is None else load
    return series[np.isclose(series["load"], load, rtol=1e-12, atol=0)]


def wear_volume(
    series: pd.DataFrame, *, running_in: float, load: Optional[float] = None, length_unit: str = "L"
) -> Any:
    """Paper Fig. 3: V(s) of one load (default: the last) per fracture energy, with the line fitted
    after ``running_in`` (a sliding distance, in the series' length unit), drawn in the curve's colour."""
    plt = _pyplot()
    rows = _one_load(series, load)
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    ax.axvspan(0, running_in, color="0.85", label="running-in (not fitted)")
    for i, (g, group) in enumerate(rows.groupby("fracture_energy", sort=False)):
        ax.plot(group["s"], group["volume"], color=f"C{i}", lw=2, label=rf"V, $\mathcal{{G}}$ = {g:.3g}")
        fit = group[group["s"] >= running_in - 1e-12]
        if len(fit) >= 2:
            slope, intercept = np.polyfit(fit["s"], fit["volume"], 1)
            s = np.array([0, group["s"].max()])
            ax.plot(s, intercept + slope * s, "--", color=f"C{i}", lw=1, label=f"fit: W = {slope:.3g}")
    ax.set(xlabel=f"sliding distance s ({length_unit})", ylabel=f"wear volume V ({length_unit}³)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def particle_counts(series: pd.DataFrame, *, load: Optional[float] = None, length_unit: str = "L") -> Any:
    """Paper appendix B: N*₊ (solid), N* (dashed) and N*₋ = N*₊ − N* (thin) against s."""
    plt = _pyplot()
    rows = _one_load(series, load)
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    for i, (g, group) in enumerate(rows.groupby("fracture_energy", sort=False)):
        ax.plot(group["s"], group["n_formed"], color=f"C{i}", lw=2, label=rf"N*₊, $\mathcal{{G}}$ = {g:.3g}")
        ax.plot(group["s"], group["n_critical"], "--", color=f"C{i}", lw=2, label=rf"N*, $\mathcal{{G}}$ = {g:.3g}")
        ax.plot(group["s"], group["n_shrunk"], color=f"C{i}", lw=0.8, label=rf"N*₋, $\mathcal{{G}}$ = {g:.3g}")
    ax.set(xlabel=f"sliding distance s ({length_unit})", ylabel="number of junctions")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def memory(series: pd.DataFrame, *, load: Optional[float] = None, length_unit: str = "L") -> Any:
    """The memory of the initial contact (paper §3): junctions descending from s = 0, N₀(s), with its
    exponential fit."""
    plt = _pyplot()
    rows = _one_load(series, load).drop_duplicates("s")
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    ax.plot(rows["s"], rows["initial_junctions"], lw=2, label="N₀(s)")
    live = rows[rows["initial_junctions"] > 0]
    if len(live) >= 2:
        slope, intercept = np.polyfit(live["s"], np.log(live["initial_junctions"]), 1)
        if slope < 0:
            ax.plot(rows["s"], np.exp(intercept + slope * rows["s"]), "--", label=f"fit: ℓ = {-1 / slope:.3g}")
    ax.set(yscale="log", xlabel=f"sliding distance s ({length_unit})", ylabel="N₀")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def study_figures(
    out: Union[str, os.PathLike], folder: Optional[Union[str, os.PathLike]] = None, job: Optional[int] = None
) -> List[Path]:
    """Draws every figure of a finished study folder ``out`` as PNG into ``folder`` (default:
    ``out/figures-python``); the series figures show ``job`` (default: the one that formed the most
    particles after running-in). Returns the files written."""
    from . import study

    plt = _pyplot()
    out = Path(out)
    folder = Path(folder) if folder is not None else out / "figures-python"
    folder.mkdir(parents=True, exist_ok=True)
    tidy, _ = study.collect(out)
    if job is None:
        job = int(tidy["job"].to_numpy()[tidy["particles_in_fit"].to_numpy().argmax()])
    row = tidy[tidy["job"] == job].iloc[0]
    running_in = row["sliding.running_in"] * row["surface.length"]
    unit = _units(tidy)["length"]
    series = study.job_series(out, job)
    figures: Dict[str, Any] = {
        "fig2_static_model": static_model(tidy),
        "fig3_wear_volume": wear_volume(series, running_in=running_in, length_unit=unit),
        "fig4_sliding_wear": sliding_wear(tidy),
        "fig5_particle_rate": particle_rate(tidy),
        "fig6_kim_comparison": kim_comparison(tidy),
        "appB_particle_counts": particle_counts(series, length_unit=unit),
        "appB_eq5_against_w": equation_5(tidy),
        "appC_junction_counts": junction_counts(tidy),
        "appF_contact_severity": contact_severity(tidy),
        "memory_of_initial_contact": memory(series, length_unit=unit),
    }
    for i, fig in enumerate(constant_critical_diameter(tidy)):
        figures[f"fig4c_constant_d_star_{i + 1}"] = fig
    written = []
    for name, fig in figures.items():
        path = folder / f"{name}.png"
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written
