"""The figures of ``wearsim study plot`` on matplotlib. The figures and every number they plot are the
library's (one registry, :data:`FIGURES`, shared with the CLI): :func:`figure_data` gives them as data
from a tidy table (:func:`wearsim.study.collect`, or ``pandas.read_csv("results.csv")``),
:func:`study_figure_data` from a study folder, and :func:`draw` draws one with matplotlib, for users
who restyle. :func:`study_figures` writes every figure of a study as PNG with its numbers as CSV
beside it, under the names the CLI uses.

Figures (Brink, Frérot & Molinari 2021): :func:`static_model` (Fig. 2), :func:`sliding_wear`
(Fig. 4a–b), :func:`constant_critical_diameter` (Figs. 4c/5c), :func:`particle_rate` (Fig. 5),
:func:`kim_comparison` (Fig. 6), :func:`equation_5` (Fig. B.9b), :func:`junction_counts` and
:func:`critical_junction_counts` (appendix C), :func:`contact_severity` (appendix F) and, beyond the
paper, :func:`wear_regime` (the particle rules against load), each from a tidy table;
:func:`memory_of_setting` (the memory of the initial contact, §3) from a study folder; and for the
series of one run of :func:`wearsim.slide`, :func:`wear_volume` (Fig. 3), :func:`particle_counts`
(appendix B) and :func:`memory`.

Curves are settings (material and every input that varies, but the surface pair) and fracture
energies, labelled by the library; points are means over surface pairs, bars the 95 % confidence
interval of the mean (Student t over the pairs). Wear and particle rates are drawn per unit nominal
area (W/(Lx·Ly): in reduced units the W of a box L × L, the paper's). Needs matplotlib
(``pip install "wearsim[examples]"``).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

from . import _wearsim

#: The registry of figures: (name, what it shows), as ``wearsim study plot --figures`` takes them.
FIGURES: List[Tuple[str, str]] = [tuple(f) for f in _wearsim.FIGURES]  # type: ignore[misc]

#: Kim et al. (1986), rolling experiments: k = 6e-7 … 1.5e-3 (paper §4.2, Fig. 6c); drawn only for
#: studies of Kim's ceramics.
KIM_RANGE = tuple(_wearsim.KIM_EXPERIMENTAL_K)

#: What the points and bars of the figures against load are (the legend's title): on a log axis
#: the interval is drawn in log space, mean ×/÷ e^(t·se/mean), positive and symmetric about the mean.
BARS = (
    "mean over surface pairs; bars: 95 % confidence interval of the mean (Student t); on a log axis drawn in "
    "log space: mean ×/÷ e^(t·se/mean)"
)

#: Particles in the fit window of a point, summed over its surface pairs, below which its fitted
#: rates rest on too few events to be judged: drawn hollow (the rule of the paper's findings).
RESOLVED_PARTICLES = _wearsim.RESOLVED_PARTICLES

#: The palette of the CLI's figures (Okabe & Ito, colour-blind safe), then greys; the library's
#: colours index it.
PALETTE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#969696"]
_NEUTRAL = {"grey": "#787878", "black": "#000000", "light": "#c8c8c8", "band": "#56B4E9"}
_MARKERS = "o^sDx"


def _pyplot() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError('wearsim.plot needs matplotlib: pip install "wearsim[examples]"') from e
    return plt


def _columns(table: pd.DataFrame) -> Dict[str, List[Any]]:
    return {str(c): table[c].tolist() for c in table.columns}


def curves(tidy: pd.DataFrame) -> List[Tuple[str, pd.DataFrame]]:
    """The curves of a tidy table: (label, per-load DataFrame of the library's aggregated table, with
    the nominal pressure, the surface pairs and the statistics over them of every result column:
    ``<column>_mean``, ``_min``, ``_max``, ``_ci_low``, ``_ci_high``; the fit window's results over
    the ``fit_window_pairs`` run in, all where none is), one per setting and fracture energy. The
    grouping, the statistics and the labels are the library's: the same numbers as
    ``results_aggregated.csv`` and the figures of ``wearsim study plot``."""
    columns = _columns(tidy)
    aggregated = pd.DataFrame(_wearsim.aggregate(columns))
    labels = _wearsim.curve_labels(columns)
    out = []
    for _, group in aggregated.groupby("curve", sort=True):
        index = int(group["curve"].iloc[0])
        out.append((labels[index], group.sort_values("nominal_pressure").reset_index(drop=True)))
    return out


def per_area_label(label: str, tidy: pd.DataFrame, quantity: str = "wear_rate") -> str:
    """The axis label of the rate ``quantity`` divided by the nominal area, as the library's figures
    write it: in SI a wear depth per sliding distance (m/m), or particles per m slid per m²."""
    si = "units" in tidy.columns and len(tidy) and str(tidy["units"].iloc[0]) == "si"
    if not si:
        return f"{label} / (Lx·Ly) (per unit nominal area, = a box L × L (the paper's))"
    if quantity == "particle_rate":
        return f"{label} / (Lx·Ly) (per unit nominal area, particles per m slid per m², 1/m³)"
    return f"{label} / (Lx·Ly) (per unit nominal area: wear depth per sliding distance, m/m)"


def _shown(label: str) -> str:
    """A library label as matplotlib draws it: the script 𝒢, which its default font lacks, in mathtext."""
    return label.replace("𝒢", r"$\mathcal{G}$")


def figure_data(tidy: pd.DataFrame, names: Optional[Sequence[str]] = None) -> List[Dict[str, Any]]:
    """The library's figures of a tidy table (all, or the registry entries ``names``), as dicts:
    ``entry``, ``name`` (the file name the CLI writes), ``title``, ``panels`` (each with axes ``x``
    and ``y`` — label, log, fallback —, shaded ``x_band``/``y_band``, ``diagonal``, and ``series`` of
    ``points`` x, y, low, high, hollow, no_wear, breakdown), ``legend``, ``legend_title``, ``note`` (why a figure
    has nothing to draw), ``report`` (what ``wearsim study plot`` prints of it: the appendix F fits) and
    ``csv`` (its numbers). The series figures need job files:
    :func:`study_figure_data`."""
    return list(_wearsim.table_figures(_columns(tidy), None if names is None else list(names)))


def study_figure_data(
    out: Union[str, os.PathLike], job: Optional[int] = None, names: Optional[Sequence[str]] = None
) -> List[Dict[str, Any]]:
    """:func:`figure_data` of a finished study folder, the series figures included (of ``job``;
    default: the one that formed the most particles after running-in): what ``wearsim study plot``
    draws."""
    return list(_wearsim.study_figures(Path(out), job, None if names is None else list(names)))


def _color(c: Any) -> str:
    if isinstance(c, dict):
        return PALETTE[int(c["palette"]) % len(PALETTE)]
    return _NEUTRAL[str(c)]


def _values(points: List[Dict[str, Any]], key: str) -> np.ndarray:
    return np.array([np.nan if p[key] is None else p[key] for p in points], dtype=float)


def _limits(panel: Dict[str, Any], axis: str) -> Optional[Tuple[float, float]]:
    """An axis' range as the CLI spans it: the data's values (and interval ends, and a shaded range;
    fitted and reference lines are drawn over them, not spanned) with some room; None without
    values."""
    points = [p for s in panel["series"] if not s["reference"] for p in s["points"]]
    keys: Tuple[str, ...] = ("x",) if axis == "x" else ("y", "low", "high")
    if panel["diagonal"]:
        keys = ("x", "y", "low", "high")
    values = np.concatenate([_values(points, k) for k in keys] + [np.array([], dtype=float)])
    band = panel.get("y_band") if axis == "y" else None
    if band is not None:
        values = np.append(values, [band["low"], band["high"]])
    log = panel[axis]["log"]
    values = values[np.isfinite(values) & ((values > 0) if log else True)]
    if not len(values):
        return None
    lo, hi = float(values.min()), float(values.max())
    if log:
        if hi <= lo:
            lo, hi = lo / 2, hi * 2
        return lo / 1.4, hi * 1.4
    lo = min(lo, 0.0)
    return lo, hi + 0.08 * ((hi - lo) or abs(hi) or 1.0)


def _draw_means(ax: Any, s: Dict[str, Any], log: bool, stacked: Dict[float, int], gid: str) -> None:
    """Means over surface pairs: a line, markers (hollow on few particles, ringed in the breakdown regime
    of the paper's appendix C), the 95 % interval as bars (a lower end at or below zero reaches the axis
    on a log axis), and settings without wear on the axis, stacked per load."""
    color, marker = _color(s["color"]), _MARKERS[s["marker"] % len(_MARKERS)]
    x, y = _values(s["points"], "x"), _values(s["points"], "y")
    lo, hi = _values(s["points"], "low"), _values(s["points"], "high")
    hollow = np.array([p["hollow"] for p in s["points"]], dtype=bool)
    none = np.array([p["no_wear"] for p in s["points"]], dtype=bool)
    drawn = np.isfinite(y) & ((y > 0) if log else True)
    ax.plot(x[drawn], y[drawn], "-", color=color, lw=2, gid=gid)
    ax.plot(x[drawn & ~hollow], y[drawn & ~hollow], marker, color=color, linestyle="none")
    ax.plot(
        x[drawn & hollow], y[drawn & hollow], marker, color=color, markerfacecolor="none", mew=1.5, linestyle="none"
    )
    # A load in the paper's breakdown regime (appendix C) in at least one surface pair: ringed.
    ringed = drawn & np.array([p.get("breakdown", False) for p in s["points"]], dtype=bool)
    ax.plot(x[ringed], y[ringed], "o", color=_color("grey"), ms=14, markerfacecolor="none", mew=1.5, linestyle="none")
    floor = ax.get_ylim()[0]
    lower = np.where(log & (lo <= 0), floor, lo)
    bar = drawn & np.isfinite(lo) & np.isfinite(hi)
    ax.vlines(x[bar], lower[bar], hi[bar], color=color, lw=1)
    if log and none.any():
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


def _draw_panel(ax: Any, panel: Dict[str, Any], p: int) -> None:
    for axis in ("x", "y"):
        if panel[axis]["log"]:
            getattr(ax, f"set_{axis}scale")("log")
        limits = _limits(panel, axis) or tuple(panel[axis]["fallback"])
        getattr(ax, f"set_{axis}lim")(*limits)
    if panel.get("y_band") is not None:
        ax.axhspan(panel["y_band"]["low"], panel["y_band"]["high"], color=_color(panel["y_band"]["color"]), alpha=0.25)
    if panel.get("x_band") is not None:
        ax.axvspan(panel["x_band"]["low"], panel["x_band"]["high"], color=_color(panel["x_band"]["color"]), alpha=0.35)
    if panel["diagonal"]:
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        lo, hi = min(x0, y0), max(x1, y1)
        ax.plot([lo, hi], [lo, hi], "--", color=_color("grey"), lw=1)
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
    stacked: Dict[float, int] = {}
    for i, s in enumerate(panel["series"]):
        # Each series' line or markers carry `gid` "series-<panel>-<index>": its numbers, the CSV's.
        gid = f"series-{p}-{i}"
        style = s["style"]
        if style == "means":
            _draw_means(ax, s, panel["y"]["log"], stacked, gid)
            continue
        x, y = _values(s["points"], "x"), _values(s["points"], "y")
        color = _color(s["color"])
        if style == "markers":
            ax.plot(x, y, _MARKERS[s["marker"] % len(_MARKERS)], color=color, linestyle="none", gid=gid)
        else:
            line = style["line"]
            ax.plot(x, y, "--" if line["dashed"] else "-", color=color, lw=line["width"], gid=gid)
    ax.set_xlabel(_shown(panel["x"]["label"]))
    ax.set_ylabel(_shown(panel["y"]["label"]))
    ax.grid(True, which="major", color="0.9")


def _handle(entry: Dict[str, Any]) -> Any:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    color, label = _color(entry["color"]), _shown(entry["label"])
    marker = _MARKERS[entry["marker"] % len(_MARKERS)]
    swatch = entry["swatch"]
    if swatch == "band":
        return Patch(color=color, alpha=0.3, label=label)
    if swatch == "marker":
        return Line2D([], [], color=color, marker=marker, linestyle="none", label=label)
    if swatch == "line_marker":
        return Line2D([], [], color=color, marker=marker, lw=2, label=label)
    if swatch == "hollow":
        return Line2D([], [], color=color, marker=marker, markerfacecolor="none", linestyle="none", label=label)
    if swatch == "ring":
        return Line2D([], [], color=color, marker="o", ms=12, markerfacecolor="none", linestyle="none", label=label)
    if swatch == "at_axis":
        return Line2D([], [], color=color, marker="v", linestyle="none", label=label)
    dashed = isinstance(swatch, dict) and swatch["line"]["dashed"]
    return Line2D([], [], color=color, linestyle="--" if dashed else "-", lw=2, label=label)


def draw(figure: Dict[str, Any]) -> Any:
    """Draws one of the library's figures (:func:`figure_data`, :func:`study_figure_data`) with
    matplotlib, as ``wearsim study plot`` draws it: one axes per panel, the legend in a column on the
    right. Returns the ``matplotlib.figure.Figure``."""
    plt = _pyplot()
    n = len(figure["panels"])
    if figure["note"] is not None:
        fig = plt.figure(figsize=(9.5, 5.0))
        fig.text(0.04, 0.5, _shown(figure["note"]), wrap=True, fontsize=10)
        return fig
    fig, axes = plt.subplots(1, n, figsize=(6.5 * n + 3.5, 5.0), squeeze=False)
    for p, (ax, panel) in enumerate(zip(axes[0], figure["panels"])):
        _draw_panel(ax, panel, p)
        # No panel letters: the paper's letters name its rows of settings (Figs. 2, 4, 5), not quantities.
        ax.set_title(_shown(figure["title"]) if p == 0 else "", loc="left", fontsize=10)
    handles = [_handle(e) for e in figure["legend"]]
    # One clause per line, as the CLI draws it.
    title = _shown(figure["legend_title"]).replace("; ", "\n")
    fig.tight_layout(rect=(0, 0, 0.72, 1))
    # The legend in its own column right of the panels, never over the data (a figure saved with
    # ``bbox_inches="tight"`` widens to hold it).
    fig.legend(
        handles=handles,
        loc="center left",
        bbox_to_anchor=(0.72, 0.5),
        fontsize=8,
        frameon=False,
        title=title,
        title_fontsize=8,
        alignment="left",
    )
    return fig


def _one(tidy: pd.DataFrame, entry: str, name: Optional[str] = None) -> Any:
    figures = [f for f in figure_data(tidy, [entry]) if name is None or f["name"] == name]
    return draw(figures[0])


def static_model(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 2: the static model, mean over every offset of the sliding runs."""
    return _one(tidy, "fig2")


def sliding_wear(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 4a–b: the sliding model's W and k against load."""
    return _one(tidy, "fig4")


def particle_rate(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 5: particles emitted per sliding distance."""
    return _one(tidy, "fig5")


def kim_comparison(tidy: pd.DataFrame) -> Any:
    """Paper Fig. 6c: k per material against Kim et al.'s rolling experiments; the experimental band
    only for a study of Kim's ceramics (the properties of the paper's Table 1)."""
    return _one(tidy, "fig6")


def junction_counts(tidy: pd.DataFrame) -> Any:
    """Paper appendix C: junctions N (mean after running-in)."""
    return _one(tidy, "appC", "appC_junctions")


def critical_junction_counts(tidy: pd.DataFrame) -> Any:
    """Paper appendix C: critical junctions N* (junctions ≥ d*, mean after running-in)."""
    return _one(tidy, "appC", "appC_critical_junctions")


def constant_critical_diameter(tidy: pd.DataFrame) -> List[Any]:
    """Paper Figs. 4c/5c: W, k and dN*₊/ds for settings whose d* agree within 15 % and differ in τ̃
    or 𝒢 (the library's grouping); one figure per such group (none when the study has no two)."""
    return [draw(f) for f in figure_data(tidy, ["fig4c"]) if f["note"] is None]


def wear_regime(tidy: pd.DataFrame) -> Any:
    """The wear-regime map, beyond the paper: W/F_N, the mean particle diameter over d* and W of each
    particle rule over the paper's rule against p_N, with the load where a rule of interacting
    junctions departs from the paper's (its paired ratio's 95 % interval over surface pairs excludes 1)
    and the loads in the breakdown regime of the paper's appendix C ringed. Needs a study with
    ``particle_rule`` as an axis holding ``"overlap"`` and another rule (``studies/wear-regime.toml``);
    raises ``ValueError`` otherwise."""
    figures = [f for f in figure_data(tidy, ["wear-regime"]) if f["note"] is None]
    if not figures:
        raise ValueError(
            'the wear-regime map needs a study with `particle_rule` as an axis that holds "overlap" and another '
            "rule, such as studies/wear-regime.toml"
        )
    return draw(figures[0])


def equation_5(tidy: pd.DataFrame) -> Any:
    """Paper Fig. B.9b: Eq. 5 (ω d*³ dN*₊/ds) against the summed W, means over surface pairs; beside
    it Eq. 5 / W against load, the mean over the run-in pairs with its 95 % interval, over the range
    [0.6, 1] of appendix B's "slightly underestimates"."""
    return _one(tidy, "appB-eq5")


def contact_severity(tidy: pd.DataFrame) -> Any:
    """Paper appendix F: W = α S_cⁿ with S_c = p_N √h_rms / K_Ic, the library's least-squares fits in
    log–log per material and over all materials; Kim et al.'s fit to their experiments and the
    paper's to its simulations only beside Kim's ceramics. Raises ValueError with fewer than two
    rows with W > 0 on generated surfaces."""
    figure = figure_data(tidy, ["appF"])[0]
    if figure["note"] is not None:
        raise ValueError(f"invalid `tidy`: {figure['note']}")
    return draw(figure)


Results = Union[pd.DataFrame, Sequence[Dict[str, Any]]]


def _run_figure(
    entry: str,
    runs: Sequence[Tuple[str, pd.DataFrame, Optional[Results]]],
    load: Optional[float],
    length_unit: str,
) -> Any:
    """Draws the library's figure ``entry`` of one run's series (or several runs', the memory figure):
    the figure and its numbers are the library's, as a study's series figures are. The library checks
    the arguments: a series missing a column, results missing where the figure draws their fits, a
    load the series does not have, a ``length_unit`` other than "L" or "m" are a ``ValueError``."""
    tables = [
        (label, _columns(series), None if results is None else _columns(pd.DataFrame(results)))
        for label, series, results in runs
    ]
    return draw(_wearsim.run_figure(entry, tables, load, length_unit))


def wear_volume(
    series: pd.DataFrame,
    *,
    results: Optional[Results] = None,
    load: Optional[float] = None,
    length_unit: str = "L",
) -> Any:
    """Paper Fig. 3: V(s) of one load (default: the last) per fracture energy, with the line
    V ≈ W s + b fitted over the fit window, drawn in the curve's colour, and the running-in shaded.
    The figure is the library's (the study figure ``fig3_wear_volume`` of one run): the line and the
    window are ``wear_rate``, ``wear_volume_intercept`` and ``fit_window_start`` of ``results``
    (``summary["results"]`` of :func:`wearsim.slide`, or the job's rows of the tidy table), which
    are required: the figure draws the library's fit, never one of its own. ``length_unit``: "L"
    (reduced units) or "m" (SI)."""
    return _run_figure("fig3", [("V(s)", series, results)], load, length_unit)


def particle_counts(
    series: pd.DataFrame,
    *,
    results: Optional[Results] = None,
    load: Optional[float] = None,
    length_unit: str = "L",
) -> Any:
    """Paper appendix B: N*₊ (solid), N* (dashed) and N*₋ = N*₊ − N* (thin) against s, of one load
    (default: the last) per fracture energy: the library's figure (the study figure
    ``appB_particle_counts`` of one run). With ``results`` each curve is named by its d*, without
    by its fracture energy."""
    return _run_figure("appB", [("N*", series, results)], load, length_unit)


def memory(
    series: Union[pd.DataFrame, Sequence[Tuple[str, pd.DataFrame, Results]]],
    *,
    results: Optional[Results] = None,
    load: Optional[float] = None,
    length_unit: str = "L",
) -> Any:
    """The memory of the initial contact (paper §3): junctions descending from s = 0, N₀(s), with its
    exponential fit N₀(0) e^(−s/ℓ) (ln N₀ against s weighted by N₀). The fit is the library's:
    ``memory_decay_length`` and ``memory_fit_initial_junctions`` of ``results``
    (``summary["results"]`` of :func:`wearsim.slide`, or the job's rows of the tidy table), which
    are required. ``series`` may instead be a list of (label, series, results), one per surface
    pair of a setting: each pair is drawn with its fit,
    and the mean ℓ with its 95 % interval over the pairs heads the legend. The figure is the
    library's (the study figure ``memory_of_initial_contact``; :func:`memory_of_setting` draws it
    from a study folder)."""
    runs: Sequence[Tuple[str, pd.DataFrame, Optional[Results]]] = (
        [("N₀(s)", series, results)] if isinstance(series, pd.DataFrame) else series
    )
    return _run_figure("memory", runs, load, length_unit)


def memory_of_setting(out: Union[str, os.PathLike], job: int) -> Any:
    """The memory of the initial contact (paper §3) of every surface pair of the setting of study job
    ``job`` (the jobs that differ from it in the surface pair alone), each with the library's fit, from
    the study folder ``out``: the CLI's ``memory_of_initial_contact``."""
    return draw(study_figure_data(out, job, ["memory"])[0])


def study_figures(
    out: Union[str, os.PathLike], folder: Optional[Union[str, os.PathLike]] = None, job: Optional[int] = None
) -> List[Path]:
    """Draws every figure of the registry for a finished study folder ``out`` as PNG into ``folder``
    (default: ``out/figures-python``), each with its numbers as CSV beside it, under the names
    ``wearsim study plot`` writes, and the paper's findings judged on it (``findings.md``); the series
    figures show ``job`` (default: the one that formed the most particles after running-in, the
    lowest index among equals), the memory figure every surface pair of its setting. Returns the
    files written."""
    from . import study

    plt = _pyplot()
    out = Path(out)
    folder = Path(folder) if folder is not None else out / "figures-python"
    folder.mkdir(parents=True, exist_ok=True)
    tidy, _ = study.collect(out)
    _, markdown = study.findings(tidy)
    (folder / "findings.md").write_text(markdown, encoding="utf-8", newline="\n")
    (folder / "findings_units.csv").write_text(study.findings_units_csv(tidy), encoding="utf-8", newline="\n")
    written = [folder / "findings.md", folder / "findings_units.csv"]
    for data in study_figure_data(out, job):
        fig = draw(data)
        path = folder / f"{data['name']}.png"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        (folder / f"{data['name']}.csv").write_text(data["csv"], encoding="utf-8", newline="\n")
        written += [path, folder / f"{data['name']}.csv"]
    return written
