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

from . import _wearsim

#: Kim et al. (1986), rolling experiments: k = 6e-7 … 1.5e-3 (paper §4.3, Fig. 6c).
KIM_RANGE = (6e-7, 1.5e-3)

_MARKERS = "o^sDvP*X"

#: Particles in the fit window of a point, summed over its surface pairs, below which its fitted
#: rates rest on too few events to be judged: drawn hollow (the rule of the paper's findings).
RESOLVED_PARTICLES = _wearsim.RESOLVED_PARTICLES


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError('wearsim.plot needs matplotlib: pip install "wearsim[examples]"') from e
    return plt


def _unit(tidy: pd.DataFrame, quantity: str) -> str:
    """The unit of a column or quantity: the table's own (``attrs["units"]``, from
    ``results.units.json``, as :func:`wearsim.study.collect` attaches it), else the library's rule for
    the table's unit system (a table read with ``pandas.read_csv``)."""
    known = tidy.attrs.get("units", {})
    if quantity in known:
        return str(known[quantity])
    system = str(tidy["units"].iloc[0]) if "units" in tidy.columns and len(tidy) else "reduced"
    return _wearsim.unit_of(system, quantity)


def _units(tidy: pd.DataFrame) -> Dict[str, str]:
    """The units that figure labels name, by the quantity that carries each."""
    return {
        "area": _unit(tidy, "wear_rate"),
        "length": _unit(tidy, "surface.length"),
        "volume": _unit(tidy, "volume"),
        "stress": _unit(tidy, "material.shear_strength"),
        "energy": _unit(tidy, "fracture_energy"),
        "pressure": _unit(tidy, "nominal_pressure"),
    }


def _columns(table: pd.DataFrame) -> Dict[str, List[Any]]:
    return {str(c): table[c].tolist() for c in table.columns}


def _label(column: str, value: Any, row: pd.Series, units: Dict[str, str]) -> str:
    """How a setting that tells curves apart is named in legends, with the paper's symbols."""
    name = column.rsplit(".", 1)[-1]
    if column == "material":
        return str(value)
    if name == "shear_strength":
        return rf"$\tilde{{\tau}}$ = {value:g} {units['stress']}"
    if column == "fracture_energy":
        d = row["critical_diameter_mean"]
        return rf"$\mathcal{{G}}$ = {value:.3g} {units['energy']} ($d^*$ = {d:.3g} {units['length']})"
    if name == "rms_height":
        return rf"$h_\mathrm{{rms}}$ = {value:g} {units['length']}"
    return f"{name} = {value:g}" if isinstance(value, (int, float, np.number)) else f"{name} = {value}"


def curves(tidy: pd.DataFrame) -> List[Tuple[str, pd.DataFrame]]:
    """The curves of a tidy table: (label, per-load DataFrame of the library's aggregated table, with
    the nominal pressure, the surface pairs and the mean, min and max over them of every result
    column, as ``<column>_mean`` …), one per setting and fracture energy. The grouping, the
    statistics and which settings name a curve are the library's (those of
    ``results_aggregated.csv``)."""
    units = _units(tidy)
    aggregated = pd.DataFrame(_wearsim.aggregate(_columns(tidy)))
    _, settings = _wearsim.curves(_columns(tidy))
    named = [c for c in settings if c != "fracture_energy"] + ["fracture_energy"]
    out = []
    for _, group in aggregated.groupby("curve", sort=True):
        first = group.iloc[0]
        label = ", ".join(_label(c, first[c], first, units) for c in named if c in group.columns)
        out.append((label, group.sort_values("nominal_pressure").reset_index(drop=True)))
    return out


def _particles(stats: pd.DataFrame) -> np.ndarray:
    """Per point, the particles in the fit window summed over its surface pairs (the library's
    ``particles_in_fit_total``)."""
    return stats["particles_in_fit_total"].to_numpy()


def _load_figure(
    tidy: pd.DataFrame,
    panels: Sequence[Tuple[str, str, bool]],
    title: str,
    band: Optional[Tuple[float, float, str]] = None,
    by_material: bool = False,
    fitted: bool = False,
) -> Any:
    """Quantities against the nominal pressure, one panel each, as the CLI draws them: means over
    surface pairs with min–max bars (a minimum of zero drawn to the axis), points of fitted rates
    resting on fewer than :data:`RESOLVED_PARTICLES` particles hollow with their counts in the
    legend, settings without wear as markers on the axis."""
    plt = _pyplot()
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    units = _units(tidy)
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels) + 3.5, 5.0), squeeze=False)
    materials = list(dict.fromkeys(tidy["material"]))
    data = curves(tidy)
    material_of = [str(stats["material"].iloc[0]) for _, stats in data]
    styles = []
    for i, material in enumerate(material_of):
        if by_material:
            within = material_of[:i].count(material)
            styles.append((f"C{materials.index(material)}", _MARKERS[within % len(_MARKERS)]))
        else:
            styles.append((f"C{i}", _MARKERS[materials.index(material) % len(_MARKERS)]))
    thin = [fitted & (_particles(stats) < RESOLVED_PARTICLES) for _, stats in data]
    zeros_drawn = False
    for p, (ax, (column, label, log)) in enumerate(zip(axes[0], panels)):
        # Per load, the no-wear markers drawn so far: the next stacks above them.
        stacked: Dict[float, int] = {}
        ax.set_xscale("log")
        if log:
            ax.set_yscale("log")
        shown = band if p == len(panels) - 1 else None
        if shown is not None:
            ax.axhspan(shown[0], shown[1], color="tab:blue", alpha=0.15)
        present = [(i, stats) for i, (_, stats) in enumerate(data) if f"{column}_mean" in stats]
        values = np.concatenate(
            [stats[[f"{column}_{s}" for s in ("mean", "min", "max")]].to_numpy().ravel() for _, stats in present]
            + [np.array(shown[:2] if shown is not None else [])]
        )
        values = values[np.isfinite(values) & ((values > 0) if log else True)]
        if log and len(values):
            bottom, top = values.min() / 1.4, values.max() * 1.4
            ax.set_ylim(bottom, top)
        elif len(values):
            bottom = min(values.min(), 0.0)
            ax.set_ylim(bottom, values.max() + 0.08 * (values.max() - bottom or 1.0))
        for i, stats in present:
            color, marker = styles[i]
            x = stats["nominal_pressure"].to_numpy()
            y = stats[f"{column}_mean"].to_numpy()
            lo, hi = stats[f"{column}_min"].to_numpy(), stats[f"{column}_max"].to_numpy()
            drawn = np.isfinite(y) & ((y > 0) if log else True)
            ax.plot(x[drawn], y[drawn], "-", color=color, lw=2)
            hollow = drawn & thin[i]
            ax.plot(x[drawn & ~hollow], y[drawn & ~hollow], marker, color=color, linestyle="none")
            ax.plot(x[hollow], y[hollow], marker, color=color, markerfacecolor="none", mew=1.5, linestyle="none")
            # Bars from min to max over the surface pairs; a minimum of zero reaches the axis.
            floor = ax.get_ylim()[0]
            lower = np.where(log & (lo <= 0), floor, lo)
            ax.vlines(x[drawn], lower[drawn], hi[drawn], color=color, lw=1)
            # No wear in any surface pair: zero has no place on a log axis, so it sits on the axis.
            none = np.isfinite(hi) & (hi <= 0)
            if log and none.any():
                zeros_drawn = True
                levels = []
                for at in x[none]:
                    levels.append(stacked.get(float(at), 0))
                    stacked[float(at)] = levels[-1] + 1
                ax.plot(
                    x[none],
                    0.045 * np.array(levels, dtype=float),
                    "v",
                    color=color,
                    ms=9,
                    clip_on=False,
                    linestyle="none",
                    transform=ax.get_xaxis_transform(),
                    gid="no-wear",
                )
        ax.set_xlabel(rf"nominal pressure $p_N = F_N/(L_x L_y)$ ({units['pressure']})")
        ax.set_ylabel(label.format(**units))
        ax.grid(True, which="major", color="0.9")
        letter = f"({chr(ord('a') + p)})" if len(panels) > 1 else ""
        ax.set_title(" ".join(t for t in (letter, title if p == 0 else "") if t), loc="left", fontsize=10)
    handles: List[Any] = []
    for i, (name, stats) in enumerate(data):
        color, marker = styles[i]
        # A point without any particle has no wear: it is the marker on the axis, not a hollow one.
        counts = _particles(stats)[thin[i] & (_particles(stats) > 0)]
        note = f" — hollow: {', '.join(f'{n:g}' for n in counts)} particles" if len(counts) else ""
        handles.append(Line2D([], [], color=color, marker=marker, lw=2, label=f"{name}{note}"))
    if any(t.any() for t in thin):
        handles.append(
            Line2D(
                [],
                [],
                color="0.35",
                marker="o",
                markerfacecolor="none",
                linestyle="none",
                label=f"hollow: < {RESOLVED_PARTICLES:g} particles in the fit window (summed over surface pairs)",
            )
        )
    if zeros_drawn:
        handles.append(
            Line2D(
                [],
                [],
                color="0.35",
                marker="v",
                linestyle="none",
                label="on the axis (stacked per load): no wear in any surface pair",
            )
        )
    if band is not None:
        handles.append(Patch(color="tab:blue", alpha=0.15, label=band[2]))
    fig.legend(
        handles=handles,
        loc="center right",
        fontsize=8,
        frameon=False,
        title="mean over surface pairs; bars: min–max",
        title_fontsize=8,
    )
    fig.tight_layout(rect=(0, 0, 0.72, 1))
    return fig


def static_model(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 2: the static model, mean over every offset of the sliding runs."""
    return _load_figure(
        tidy,
        [
            ("static_wear_rate_mean", r"static wear rate $W_\mathrm{{static}}/\omega$ ({area})", True),
            ("static_wear_coefficient_mean", r"static wear coefficient $k_\mathrm{{static}}$", False),
        ],
        "static model, mean over every offset",
    )


def sliding_wear(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 4a–b: the sliding model's W and k against load."""
    return _load_figure(
        tidy,
        [
            ("wear_rate", "sliding wear rate $W = dV/ds$ ({area})", True),
            ("wear_coefficient", "wear coefficient $k = W p_m / F_N$", True),
        ],
        "sliding model",
        fitted=True,
    )


def particle_rate(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 5: particles emitted per sliding distance."""
    return _load_figure(
        tidy,
        [("particle_rate", "particle rate $dN^*_+/ds$ (1/{length})", True)],
        "particle rate",
        fitted=True,
    )


def kim_comparison(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 6c: k per material against Kim et al.'s rolling experiments."""
    band = (KIM_RANGE[0], KIM_RANGE[1], "Kim et al. 1986, rolling experiments")
    return _load_figure(
        tidy, [("wear_coefficient", "wear coefficient $k$", True)], "k per material", band, True, fitted=True
    )


def junction_counts(tidy: pd.DataFrame) -> Any:
    """Paper appendix C: junctions N and critical junctions N* (means after running-in)."""
    return _load_figure(
        tidy,
        [
            ("junctions_mean", "junctions $N$", True),
            ("critical_junctions_mean", "junctions ≥ $d^*$, $N^*$", True),
        ],
        "numbers of junctions",
    )


def constant_critical_diameter(tidy: pd.DataFrame, tolerance: float = 0.15) -> List[Any]:
    """Paper Figs. 4c/5c: W, k and dN*₊/ds for settings whose d* agree within ``tolerance`` and differ in
    τ̃ or 𝒢 (the library's grouping); one figure per such group (none when the study has no two)."""
    figures = []
    curve_of_row, _ = _wearsim.curves(_columns(tidy))
    materials = [
        (
            float(s["critical_diameter_mean"].iloc[0]),
            float(s["material.shear_strength"].iloc[0]),
            float(s["fracture_energy"].iloc[0]),
        )
        for _, s in curves(tidy)
    ]
    for group in _wearsim.equal_critical_diameter(materials, tolerance):
        rows = tidy[np.isin(curve_of_row, group)]
        d_star = materials[group[0]][0]
        figures.append(
            _load_figure(
                rows,
                [
                    ("wear_rate", "$W$ ({area})", True),
                    ("wear_coefficient", "$k = W p_m / F_N$", True),
                    ("particle_rate", "$dN^*_+/ds$ (1/{length})", True),
                ],
                f"nearly equal d* ≈ {d_star:.3g}",
                fitted=True,
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
    ax.set(
        xscale="log",
        yscale="log",
        xlabel=f"wear rate $W$ ({units['area']})",
        ylabel=rf"Eq. 5: $\omega\, d^{{*3}}\, dN^*_+/ds$ ({units['area']})",
    )
    fig.legend(loc="center right", fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0, 0.62, 1))
    return fig


def contact_severity(tidy: pd.DataFrame) -> Any:
    """Paper appendix F: W = α S_cⁿ with S_c = p_N √h_rms / K_Ic, the library's least-squares fit in
    log–log with its R², over all materials and per material (when there are several)."""
    plt = _pyplot()
    units = _units(tidy)
    # S_c = p_N √h_rms / K_Ic is a column of the library's table (empty on measured surfaces).
    rows = tidy[(tidy["wear_rate"] > 0) & tidy["contact_severity"].notna()]
    s_c, w = rows["contact_severity"], rows["wear_rate"]
    fig, ax = plt.subplots(figsize=(8.5, 5.0))
    materials = list(dict.fromkeys(rows["material"]))
    grid = np.geomspace(s_c.min(), s_c.max(), 50) if len(rows) else np.array([])
    for i, material in enumerate(materials):
        mine = rows["material"] == material
        ax.scatter(s_c[mine], w[mine], color=f"C{i}", marker=_MARKERS[i % 8], label=material)
        fit = _wearsim.power_law_fit(s_c[mine].tolist(), w[mine].tolist()) if len(materials) > 1 else None
        if fit is not None:
            alpha, n, _ = fit
            ax.plot(grid, alpha * grid**n, "-", color=f"C{i}", lw=1, label=f"{material}: α = {alpha:.3g}, n = {n:.2f}")
    fit = _wearsim.power_law_fit(s_c.tolist(), w.tolist())
    if fit is not None:
        alpha, n, r2 = fit
        r2_text = "undefined" if r2 is None else f"{r2:.3f}"
        ax.plot(
            grid,
            alpha * grid**n,
            "k--",
            lw=1,
            label=f"all materials: α = {alpha:.3g} {units['area']}, n = {n:.3f}, R² = {r2_text}",
        )
    ax.set(
        xscale="log",
        yscale="log",
        xlabel=r"contact severity $S_c = p_N \sqrt{h_\mathrm{rms}} / K_\mathrm{Ic}$",
        ylabel=f"wear rate $W$ ({units['area']})",
    )
    ax.set_title(r"$W = \alpha S_c^n$, least-squares fit in log–log", loc="left", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _one_load(series: pd.DataFrame, load: Optional[float]) -> pd.DataFrame:
    loads = series["load"].unique()
    load = loads[-1] if load is None else load
    return series[np.isclose(series["load"], load, rtol=1e-12, atol=0)]


Results = Union[pd.DataFrame, Sequence[Dict[str, Any]]]


def _result_of(results: Results, load: float, fracture_energy: Optional[float] = None) -> Optional[pd.Series]:
    """The library's results (a row of ``summary["results"]`` or of the tidy table) of one load and,
    when given, one fracture energy; None when ``results`` holds none."""
    table = pd.DataFrame(results) if not isinstance(results, pd.DataFrame) else results
    mine = np.isclose(table["load"].astype(float), load, rtol=1e-12, atol=0)
    if fracture_energy is not None:
        mine &= np.isclose(table["fracture_energy"].astype(float), fracture_energy, rtol=1e-12, atol=0)
    rows = table[mine]
    return None if rows.empty else rows.iloc[0]


def _defined(value: Any) -> bool:
    return value is not None and not pd.isna(value)


def wear_volume(
    series: pd.DataFrame,
    *,
    running_in: Optional[float] = None,
    load: Optional[float] = None,
    length_unit: str = "L",
    results: Optional[Results] = None,
) -> Any:
    """Paper Fig. 3: V(s) of one load (default: the last) per fracture energy, with the line
    V ≈ W s + b fitted over the fit window, drawn in the curve's colour. The line and the window are
    the library's: ``wear_rate``, ``wear_volume_intercept`` and ``fit_window_start`` of ``results``
    (``summary["results"]`` of :func:`wearsim.slide`, or the job's rows of the tidy table). Without
    ``results``, pass ``running_in`` (where the fit window starts, a sliding distance in the series'
    length unit): the library's least-squares line is then fitted to the series' points from there."""
    plt = _pyplot()
    rows = _one_load(series, load)
    if running_in is None:
        first = None if results is None else _result_of(results, float(rows["load"].iloc[0]))
        if first is None or not _defined(first.get("fit_window_start")):
            raise ValueError(
                "invalid `running_in`: pass where the fit window starts (a sliding distance), or `results` of this "
                "load holding `fit_window_start` (a run of this version of wearsim)"
            )
        running_in = float(first["fit_window_start"])
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    ax.axvspan(0, running_in, color="0.85", label="running-in (not fitted)")
    for i, (g, group) in enumerate(rows.groupby("fracture_energy", sort=False)):
        ax.plot(group["s"], group["volume"], color=f"C{i}", lw=2, label=rf"V, $\mathcal{{G}}$ = {g:.3g}")
        line: Optional[Tuple[float, float]] = None
        if results is not None:
            r = _result_of(results, float(group["load"].iloc[0]), float(group["fracture_energy"].iloc[0]))
            if r is not None and _defined(r["wear_rate"]) and _defined(r["wear_volume_intercept"]):
                line = (float(r["wear_rate"]), float(r["wear_volume_intercept"]))
        else:
            fit = group[group["s"] >= running_in - 1e-12]
            fitted = _wearsim.line_fit(fit["s"].tolist(), fit["volume"].tolist())
            line = None if fitted is None else (fitted[0], fitted[1])
        if line is not None:
            slope, intercept = line
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


def memory(
    series: pd.DataFrame,
    *,
    load: Optional[float] = None,
    length_unit: str = "L",
    results: Optional[Results] = None,
) -> Any:
    """The memory of the initial contact (paper §3): junctions descending from s = 0, N₀(s), with its
    exponential fit N₀(0) e^(−s/ℓ). The fit is the library's: ``memory_decay_length`` and
    ``memory_fit_initial_junctions`` of ``results`` (``summary["results"]`` of :func:`wearsim.slide`,
    or the job's rows of the tidy table); without ``results`` the library's least-squares line is
    fitted to ln N₀ over the steps where N₀ > 0."""
    plt = _pyplot()
    rows = _one_load(series, load).drop_duplicates("s")
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    ax.plot(rows["s"], rows["initial_junctions"], lw=2, label="N₀(s)")
    curve: Optional[Tuple[float, float]] = None
    if results is not None:
        r = _result_of(results, float(rows["load"].iloc[0])) if len(rows) else None
        if r is not None and _defined(r["memory_decay_length"]) and _defined(r["memory_fit_initial_junctions"]):
            curve = (float(r["memory_decay_length"]), float(r["memory_fit_initial_junctions"]))
    else:
        live = rows[rows["initial_junctions"] > 0]
        fitted = _wearsim.line_fit(live["s"].tolist(), np.log(live["initial_junctions"]).tolist())
        if fitted is not None and fitted[0] < 0:
            curve = (-1 / fitted[0], float(np.exp(fitted[1])))
    if curve is not None:
        decay_length, initial = curve
        ax.plot(rows["s"], initial * np.exp(-rows["s"] / decay_length), "--", label=f"fit: ℓ = {decay_length:.3g}")
    ax.set(yscale="log", xlabel=f"sliding distance s ({length_unit})", ylabel="N₀")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def study_figures(
    out: Union[str, os.PathLike], folder: Optional[Union[str, os.PathLike]] = None, job: Optional[int] = None
) -> List[Path]:
    """Draws every figure of a finished study folder ``out`` as PNG into ``folder`` (default:
    ``out/figures-python``); the series figures show ``job`` (default: the one that formed the most
    particles after running-in, the lowest index among equals). Returns the files written."""
    from . import study

    plt = _pyplot()
    out = Path(out)
    folder = Path(folder) if folder is not None else out / "figures-python"
    folder.mkdir(parents=True, exist_ok=True)
    tidy, _ = study.collect(out)
    if job is None:
        job = _wearsim.series_job(tidy["job"].astype(int).tolist(), tidy["particles_in_fit"].astype(int).tolist())
        if job is None:
            raise ValueError(f"invalid `out`: {out} holds no job results")
    unit = _unit(tidy, "surface.length")
    series = study.job_series(out, job)
    results = tidy[tidy["job"] == job]
    figures: Dict[str, Any] = {
        "fig2_static_model": static_model(tidy),
        "fig3_wear_volume": wear_volume(series, length_unit=unit, results=results),
        "fig4_sliding_wear": sliding_wear(tidy),
        "fig5_particle_rate": particle_rate(tidy),
        "fig6_kim_comparison": kim_comparison(tidy),
        "appB_particle_counts": particle_counts(series, length_unit=unit),
        "appB_eq5_against_w": equation_5(tidy),
        "appC_junction_counts": junction_counts(tidy),
        "appF_contact_severity": contact_severity(tidy),
        "memory_of_initial_contact": memory(series, length_unit=unit, results=results),
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
