"""The figures of ``wearsim study plot`` on matplotlib, from the tidy table of a study
(:func:`wearsim.study.collect`, or ``pandas.read_csv("results.csv")``) and from the series of one
sliding run (:func:`wearsim.slide`, or :func:`wearsim.study.job_series`). Each function returns a
``matplotlib.figure.Figure``; :func:`study_figures` draws them all into a folder.

Figures (Brink, Frérot & Molinari 2021): :func:`static_model` (Fig. 2), :func:`wear_volume` (Fig. 3),
:func:`sliding_wear` (Fig. 4a–b), :func:`constant_critical_diameter` (Figs. 4c/5c),
:func:`particle_rate` (Fig. 5), :func:`kim_comparison` (Fig. 6), :func:`particle_counts` (appendix
B), :func:`equation_5` (Fig. B.9b), :func:`junction_counts` (appendix C), :func:`contact_severity`
(appendix F), :func:`memory` and :func:`memory_of_setting` (the memory of the initial contact, §3).

Curves are settings (material and every input that varies, but the surface pair) and fracture
energies, labelled by the library; points are means over surface pairs, bars the 95 % confidence
interval of the mean (Student t over the pairs, the aggregated table's ``_ci_low``/``_ci_high``). Wear
and particle rates are drawn per unit nominal area (W/(Lx·Ly): in reduced units the W of a box L × L,
the paper's). Needs matplotlib (``pip install "wearsim[examples]"``).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

from . import _wearsim

#: Kim et al. (1986), rolling experiments: k = 6e-7 … 1.5e-3 (paper §4.2, Fig. 6c); drawn only for
#: studies of Kim's ceramics.
KIM_RANGE = tuple(_wearsim.KIM_EXPERIMENTAL_K)

#: What the bars of the figures against load are.
BARS = "mean over surface pairs; bars: 95 % confidence interval of the mean (Student t)"

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


def curves(tidy: pd.DataFrame) -> List[Tuple[str, pd.DataFrame]]:
    """The curves of a tidy table: (label, per-load DataFrame of the library's aggregated table, with
    the nominal pressure, the surface pairs and the statistics over them of every result column:
    ``<column>_mean``, ``_min``, ``_max``, ``_ci_low``, ``_ci_high``), one per setting and fracture
    energy. The grouping, the statistics and the labels are the library's (those of
    ``results_aggregated.csv`` and of ``wearsim study plot``)."""
    columns = _columns(tidy)
    aggregated = pd.DataFrame(_wearsim.aggregate(columns))
    labels = _wearsim.curve_labels(columns)
    out = []
    for _, group in aggregated.groupby("curve", sort=True):
        index = int(group["curve"].iloc[0])
        out.append((labels[index], group.sort_values("nominal_pressure").reset_index(drop=True)))
    return out


def _shown(label: str) -> str:
    """A library label as matplotlib draws it: the script 𝒢, which its default font lacks, in mathtext."""
    return label.replace("𝒢", r"$\mathcal{G}$")


def _area(stats: pd.DataFrame) -> np.ndarray:
    """The nominal area Lx·Ly of each row's box (1 for a hand-made table without the box's size)."""
    if "surface.length" not in stats:
        return np.ones(len(stats))
    lx = stats["surface.length"].to_numpy(dtype=float)
    ly = stats["surface.length_y"].to_numpy(dtype=float) if "surface.length_y" in stats else lx
    return lx * np.where(np.isfinite(ly), ly, lx)


def per_area_label(label: str, tidy: pd.DataFrame) -> str:
    """The axis label of a rate divided by the nominal area."""
    si = "units" in tidy.columns and len(tidy) and str(tidy["units"].iloc[0]) == "si"
    unit = "m²/m²" if si else "= a box L × L (the paper's)"
    return f"{label} / (Lx·Ly) (per unit nominal area, {unit})"


def _is_estimate(stats: pd.DataFrame) -> np.ndarray:
    """Per point: the static estimate (``sliding.model = "estimate"``), not a sliding run."""
    if "sliding.model" not in stats:
        return np.zeros(len(stats), dtype=bool)
    return (stats["sliding.model"].astype(str) == "estimate").to_numpy()


def _particles(stats: pd.DataFrame) -> np.ndarray:
    """Per point, the particles in the fit window summed over its surface pairs (the library's
    ``particles_in_fit_total``)."""
    return stats["particles_in_fit_total"].to_numpy()


Panel = Union[Tuple[str, str, bool], Tuple[str, str, bool, bool]]
Style = Tuple[str, str]


def _styles(data: List[Tuple[str, pd.DataFrame]], materials: List[Any], by_material: bool) -> List[Style]:
    """Colour and marker per curve: by curve (marker by material), or by material (marker by its
    curves) for figures of several materials."""
    material_of = [str(stats["material"].iloc[0]) for _, stats in data]
    styles = []
    for i, material in enumerate(material_of):
        if by_material:
            within = material_of[:i].count(material)
            styles.append((f"C{materials.index(material)}", _MARKERS[within % len(_MARKERS)]))
        else:
            styles.append((f"C{i}", _MARKERS[materials.index(material) % len(_MARKERS)]))
    return styles


def _panel(
    ax: Any,
    tidy: pd.DataFrame,
    spec: Panel,
    data: List[Tuple[str, pd.DataFrame]],
    styles: List[Style],
    thin: List[np.ndarray],
    shown: Optional[Tuple[float, float, str]],
) -> bool:
    """Draws one panel of :func:`_load_figure`; returns whether settings without wear were marked on
    the axis."""
    column, label, log = spec[0], spec[1], spec[2]
    per_area = len(spec) > 3 and bool(spec[3])
    units = _units(tidy)
    if per_area:
        label = per_area_label(label, tidy)
    # Per load, the no-wear markers drawn so far: the next stacks above them.
    stacked: Dict[float, int] = {}
    zeros_drawn = False
    ax.set_xscale("log")
    if log:
        ax.set_yscale("log")
    if shown is not None:
        ax.axhspan(shown[0], shown[1], color="tab:blue", alpha=0.15)
    present = [(i, stats) for i, (_, stats) in enumerate(data) if f"{column}_mean" in stats]

    def scaled(stats: pd.DataFrame, statistic: str) -> np.ndarray:
        values = stats[f"{column}_{statistic}"].to_numpy(dtype=float)
        return values / _area(stats) if per_area else values

    values = np.concatenate(
        [np.concatenate([scaled(stats, s) for s in ("mean", "ci_low", "ci_high")]) for _, stats in present]
        + [np.array(shown[:2] if shown is not None else [])]
    )
    values = values[np.isfinite(values) & ((values > 0) if log else True)]
    if log and len(values):
        ax.set_ylim(values.min() / 1.4, values.max() * 1.4)
    elif len(values):
        bottom = min(values.min(), 0.0)
        ax.set_ylim(bottom, values.max() + 0.08 * (values.max() - bottom or 1.0))
    for i, stats in present:
        color, marker = styles[i]
        x = stats["nominal_pressure"].to_numpy()
        y = scaled(stats, "mean")
        lo, hi = scaled(stats, "ci_low"), scaled(stats, "ci_high")
        most = stats[f"{column}_max"].to_numpy(dtype=float)
        drawn = np.isfinite(y) & ((y > 0) if log else True)
        ax.plot(x[drawn], y[drawn], "-", color=color, lw=2)
        hollow = drawn & thin[i]
        ax.plot(x[drawn & ~hollow], y[drawn & ~hollow], marker, color=color, linestyle="none")
        ax.plot(x[hollow], y[hollow], marker, color=color, markerfacecolor="none", mew=1.5, linestyle="none")
        # Bars of the 95 % interval of the mean; a lower end at or below zero reaches the axis.
        floor = ax.get_ylim()[0]
        lower = np.where(log & (lo <= 0), floor, lo)
        bar = drawn & np.isfinite(lo) & np.isfinite(hi)
        ax.vlines(x[bar], lower[bar], hi[bar], color=color, lw=1)
        # No wear in any surface pair: zero has no place on a log axis, so it sits on the axis.
        none = np.isfinite(most) & (most <= 0)
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
    return zeros_drawn


def _handles(
    data: List[Tuple[str, pd.DataFrame]],
    styles: List[Style],
    thin: List[np.ndarray],
    zeros_drawn: bool,
    band: Optional[Tuple[float, float, str]],
) -> List[Any]:
    """The legend of :func:`_load_figure`: each curve with the particle counts of its hollow points,
    then what the hollow points, the markers on the axis and the band are."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles: List[Any] = []
    for i, (name, stats) in enumerate(data):
        color, marker = styles[i]
        # A point without any particle has no wear: it is the marker on the axis, not a hollow one.
        counts = _particles(stats)[thin[i] & (_particles(stats) > 0)]
        note = f" — hollow: {', '.join(f'{n:g}' for n in counts)} particles" if len(counts) else ""
        handles.append(Line2D([], [], color=color, marker=marker, lw=2, label=f"{_shown(name)}{note}"))
    if any(t.any() for t in thin):
        label = f"hollow: < {RESOLVED_PARTICLES:g} particles in the fit window (summed over surface pairs)"
        handles.append(Line2D([], [], color="0.35", linestyle="none", marker="o", markerfacecolor="none", label=label))
    if zeros_drawn:
        label = "on the axis (stacked per load): no wear in any surface pair"
        handles.append(Line2D([], [], color="0.35", linestyle="none", marker="v", label=label))
    if band is not None:
        handles.append(Patch(color="tab:blue", alpha=0.15, label=band[2]))
    return handles


def _load_figure(
    tidy: pd.DataFrame,
    panels: Sequence[Panel],
    title: str,
    band: Optional[Tuple[float, float, str]] = None,
    by_material: bool = False,
    fitted: bool = False,
) -> Any:
    """Quantities against the nominal pressure, one panel each, as the CLI draws them: means over
    surface pairs with their 95 % interval as bars (a lower end at or below zero drawn to the axis),
    points of fitted rates resting on fewer than :data:`RESOLVED_PARTICLES` particles hollow with their
    counts in the legend, settings without wear as markers on the axis. A panel is (column, label,
    log axis) or (column, label, log axis, per unit area)."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels) + 3.5, 5.0), squeeze=False)
    data = curves(tidy)
    styles = _styles(data, list(dict.fromkeys(tidy["material"])), by_material)
    # A curve of the static estimate counts no particle: its points are never drawn hollow.
    thin = [fitted & (_particles(stats) < RESOLVED_PARTICLES) & ~_is_estimate(stats) for _, stats in data]
    zeros_drawn = False
    for p, (ax, spec) in enumerate(zip(axes[0], panels)):
        shown = band if p == len(panels) - 1 else None
        zeros_drawn |= _panel(ax, tidy, spec, data, styles, thin, shown)
        # No panel letters: the paper's letters name its rows of settings (Figs. 2, 4, 5), not quantities.
        ax.set_title(title if p == 0 else "", loc="left", fontsize=10)
    handles = _handles(data, styles, thin, zeros_drawn, band)
    fig.legend(handles=handles, loc="center right", fontsize=8, frameon=False, title=BARS, title_fontsize=8)
    fig.tight_layout(rect=(0, 0, 0.72, 1))
    return fig


def static_model(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 2: the static model, mean over every offset of the sliding runs."""
    return _load_figure(
        tidy,
        [
            ("static_wear_rate_mean", r"$W_\mathrm{{static}}/\omega$", True, True),
            ("static_wear_coefficient_mean", r"static wear coefficient $k_\mathrm{{static}}$", False),
        ],
        r"static model, mean over every offset (the paper's Fig. 2 rows: $\mathcal{G}$ varied, $\tilde{\tau}$ varied)",
    )


def sliding_wear(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 4a–b: the sliding model's W and k against load."""
    return _load_figure(
        tidy,
        [
            ("wear_rate", "sliding wear rate $W = dV/ds$", True, True),
            ("wear_coefficient", "wear coefficient $k = W p_m / F_N$", True),
        ],
        "sliding model (the paper's Fig. 4 rows: W, k)",
        fitted=True,
    )


def particle_rate(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 5: particles emitted per sliding distance."""
    return _load_figure(
        tidy,
        [("particle_rate", "particle rate $dN^*_+/ds$", True, True)],
        "particle rate",
        fitted=True,
    )


def kim_comparison(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 6c: k per material against Kim et al.'s rolling experiments; the experimental band
    only for a study of Kim's ceramics (the properties of the paper's Table 1)."""
    kim = _wearsim.has_kim_materials(_columns(tidy))
    band = (KIM_RANGE[0], KIM_RANGE[1], "Kim et al. 1986, rolling experiments") if kim else None
    title = "k per material" if kim else "k per material (no material of Kim et al.'s Table 1: no experimental band)"
    return _load_figure(tidy, [("wear_coefficient", "wear coefficient $k$", True)], title, band, True, fitted=True)


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
                    ("wear_rate", "$W$", True, True),
                    ("wear_coefficient", "$k = W p_m / F_N$", True),
                    ("particle_rate", "$dN^*_+/ds$", True, True),
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
        ax.scatter(w[keep], e[keep], color=f"C{i}", label=_shown(name))
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
    """Paper appendix F: W = α S_cⁿ with S_c = p_N √h_rms / K_Ic, the library's least-squares fits in
    log–log per material and over all materials (``_wearsim.severity_fits``, as ``wearsim study plot``
    draws them); Kim et al.'s fit to their experiments and the paper's to its simulations only beside
    Kim's ceramics."""
    plt = _pyplot()
    units = _units(tidy)
    materials, everything = _wearsim.severity_fits(_columns(tidy))
    fig, ax = plt.subplots(figsize=(8.5, 5.0))
    s_all = [p[0] for m in materials for p in m["points"]]
    grid = np.geomspace(min(s_all), max(s_all), 50) if s_all else np.array([])
    for i, m in enumerate(materials):
        s_c, w = zip(*m["points"])
        kim = f" (Kim et al.'s {m['kim']})" if m["kim"] else ""
        ax.scatter(s_c, w, color=f"C{i}", marker=_MARKERS[i % 8], label=f"{m['material']}{kim}")
        if m["fit"] is not None:
            alpha, n, _ = m["fit"]
            fitted = f"{m['material']}: α = {alpha:.3g}, n = {n:.2f}"
            ax.plot(grid, alpha * grid**n, "-", color=f"C{i}", lw=1, label=fitted)
    if everything is not None:
        alpha, n, r2 = everything
        r2_text = "undefined" if r2 is None else f"{r2:.3f}"
        ax.plot(
            grid,
            alpha * grid**n,
            "k--",
            lw=1,
            label=f"all materials: α = {alpha:.3g} {units['area']}, n = {n:.3f}, R² = {r2_text}",
        )
    if any(m["kim"] for m in materials) and len(grid):
        for (alpha, n), who in [
            (_wearsim.PAPER_SEVERITY_FIT, "the paper's fit to its simulations"),
            (_wearsim.KIM_SEVERITY_FIT, "Kim et al.'s fit to their experiments"),
        ]:
            ax.plot(grid, alpha * grid**n, ":", color="0.45", lw=1, label=f"{who}: α = {alpha:.3g} m², n = {n}")
    ax.set(
        xscale="log",
        yscale="log",
        xlabel=r"contact severity $S_c = p_N \sqrt{h_\mathrm{rms}} / K_\mathrm{Ic}$",
        ylabel=f"wear rate $W$ ({units['area']})",
    )
    ax.set_title(r"$W = \alpha S_c^n$, least-squares fits in log–log", loc="left", fontsize=10)
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


def _required(results: Optional[Results], what: str) -> Results:
    if results is None:
        raise ValueError(
            f"invalid `results`: pass the library's results of the run ({what}): `summary['results']` of "
            "wearsim.slide, or the job's rows of the tidy table"
        )
    return results


def wear_volume(
    series: pd.DataFrame,
    *,
    results: Optional[Results] = None,
    load: Optional[float] = None,
    length_unit: str = "L",
) -> Any:
    """Paper Fig. 3: V(s) of one load (default: the last) per fracture energy, with the line
    V ≈ W s + b fitted over the fit window, drawn in the curve's colour. The line and the window are
    the library's: ``wear_rate``, ``wear_volume_intercept`` and ``fit_window_start`` of ``results``
    (``summary["results"]`` of :func:`wearsim.slide`, or the job's rows of the tidy table), which
    are required: the figure draws the library's fit, never one of its own."""
    plt = _pyplot()
    results = _required(results, "wear_rate, wear_volume_intercept, fit_window_start")
    rows = _one_load(series, load)
    first = _result_of(results, float(rows["load"].iloc[0]))
    if first is None or not _defined(first.get("fit_window_start")):
        raise ValueError("invalid `results`: none of this load holds `fit_window_start` (a run of this version)")
    running_in = float(first["fit_window_start"])
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    ax.axvspan(0, running_in, color="0.85", label="running-in (not fitted)")
    for i, (g, group) in enumerate(rows.groupby("fracture_energy", sort=False)):
        ax.plot(group["s"], group["volume"], color=f"C{i}", lw=2, label=rf"V, $\mathcal{{G}}$ = {g:.3g}")
        r = _result_of(results, float(group["load"].iloc[0]), float(group["fracture_energy"].iloc[0]))
        if r is not None and _defined(r["wear_rate"]) and _defined(r["wear_volume_intercept"]):
            slope, intercept = float(r["wear_rate"]), float(r["wear_volume_intercept"])
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
    series: Union[pd.DataFrame, Sequence[Tuple[str, pd.DataFrame, Results]]],
    *,
    results: Optional[Results] = None,
    load: Optional[float] = None,
    length_unit: str = "L",
) -> Any:
    """The memory of the initial contact (paper §3): junctions descending from s = 0, N₀(s), with its
    exponential fit N₀(0) e^(−s/ℓ). The fit is the library's: ``memory_decay_length`` and
    ``memory_fit_initial_junctions`` of ``results`` (``summary["results"]`` of :func:`wearsim.slide`,
    or the job's rows of the tidy table), which are required. ``series`` may instead be a list of
    (label, series, results), one per surface pair of a setting (:func:`memory_of_setting`): each
    pair is drawn with its fit, and the mean ℓ with its 95 % interval over the pairs is the title."""
    plt = _pyplot()
    if isinstance(series, pd.DataFrame):
        series = [("N₀(s)", series, _required(results, "memory_decay_length, memory_fit_initial_junctions"))]
    fig, ax = plt.subplots(figsize=(9.5, 5.0))
    lengths = []
    for i, (name, one, res) in enumerate(series):
        rows = _one_load(one, load).drop_duplicates("s")
        label = name
        r = _result_of(res, float(rows["load"].iloc[0])) if len(rows) else None
        if r is not None and _defined(r["memory_decay_length"]) and _defined(r["memory_fit_initial_junctions"]):
            decay_length, initial = float(r["memory_decay_length"]), float(r["memory_fit_initial_junctions"])
            lengths.append(decay_length)
            s = rows["s"].to_numpy()
            fit = initial * np.exp(-s / decay_length)
            keep = fit >= 1.0
            ax.plot(s[keep], fit[keep], "--", color=f"C{i}", lw=1)
            label = f"{name}, fit ℓ = {decay_length:.3g} {length_unit}"
        ax.plot(rows["s"], rows["initial_junctions"], color=f"C{i}", lw=2, label=label)
    interval = _wearsim.mean_interval(lengths)
    if interval is not None:
        mean, low, high, n = interval
        ax.set_title(
            f"mean ℓ = {mean:.3g} [{low:.3g}, {high:.3g}] {length_unit} (95 %, Student t over {n} pairs); dashed: fits",
            loc="left",
            fontsize=9,
        )
    ax.set(yscale="log", xlabel=f"sliding distance s ({length_unit})", ylabel="N₀")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def memory_of_setting(out: Union[str, os.PathLike], job: int) -> Any:
    """:func:`memory` of every surface pair of the setting of study job ``job`` (the jobs that differ
    from it in the surface pair alone), from the study folder ``out``."""
    from . import study

    tidy, _ = study.collect(out)
    curve, _ = _wearsim.curves(_columns(tidy))
    tidy = tidy.assign(_curve=curve)
    mine = tidy[tidy["job"] == job].iloc[0]
    same = tidy[(tidy["_curve"] == mine["_curve"]) & np.isclose(tidy["load"], mine["load"], rtol=1e-12, atol=0)]
    unit = _unit(tidy, "surface.length")
    pairs = []
    for j in dict.fromkeys(same["job"].astype(int)):
        rows = tidy[tidy["job"] == j]
        seed = rows["surface.seed"].iloc[0] if "surface.seed" in rows else j
        pairs.append((f"pair {seed}", study.job_series(out, j), rows))
    return memory(pairs, length_unit=unit)


def study_figures(
    out: Union[str, os.PathLike], folder: Optional[Union[str, os.PathLike]] = None, job: Optional[int] = None
) -> List[Path]:
    """Draws every figure of a finished study folder ``out`` as PNG into ``folder`` (default:
    ``out/figures-python``), and the paper's findings judged on it (``findings.md``); the series
    figures show ``job`` (default: the one that formed the most particles after running-in, the
    lowest index among equals), the memory figure every surface pair of its setting. Returns the
    files written."""
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
        "memory_of_initial_contact": memory_of_setting(out, job),
    }
    for i, fig in enumerate(constant_critical_diameter(tidy)):
        figures[f"fig4c_constant_d_star_{i + 1}"] = fig
    _, markdown = study.findings(tidy)
    (folder / "findings.md").write_text(f"# The paper's findings on this study\n\n{markdown}")
    written = [folder / "findings.md"]
    for name, fig in figures.items():
        path = folder / f"{name}.png"
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written
