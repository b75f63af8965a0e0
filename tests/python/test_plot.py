"""The figures of `wearsim.plot` on a small hand-made tidy table: the library's curves, labels,
statistics with their 95 % intervals, units and power-law fit; rates per unit nominal area; points
resting on few particles drawn hollow with their counts in the legend; settings without wear drawn on
the axis; interval bars whose lower end is at or below zero reaching the axis."""

import numpy as np
import pandas as pd
import pytest
import wearsim
from wearsim import _wearsim

matplotlib = pytest.importorskip("matplotlib", reason="matplotlib not installed")
matplotlib.use("Agg")

# Two settings (τ̃ = 0.008 and 0.012) at two nominal pressures, two surface pairs each.
P1, P2 = 2.5e-4, 1e-3


def _tidy() -> pd.DataFrame:
    rows = []
    job = 0
    for tau, per_load in [
        # τ̃ = 0.008: no wear in either pair at the lower load, resolved at the higher one.
        (0.008, {P1: [(0.0, 0), (0.0, 0)], P2: [(3e-4, 15), (5e-4, 25)]}),
        # τ̃ = 0.012: 5 + 6 = 11 particles at the lower load (hollow); one pair without wear at the higher.
        (0.012, {P1: [(1e-4, 5), (2e-4, 6)], P2: [(0.0, 12), (4e-4, 30)]}),
    ]:
        for p, pairs in per_load.items():
            for seed, (w, n) in enumerate(pairs, start=1):
                rows.append(
                    {
                        "job": job,
                        "material": "m",
                        "units": "reduced",
                        "surface.seed": seed,
                        "surface.length": 0.5,
                        "material.shear_strength": tau,
                        "load": p * 0.0156,
                        "nominal_pressure": p,
                        "fracture_energy": 5e-7,
                        "critical_diameter": 0.01 if tau == 0.008 else 0.005,
                        "wear_rate": w,
                        "wear_coefficient": w * 10,
                        "particles_in_fit": n,
                        "warnings": "",
                    }
                )
                job += 1
    return pd.DataFrame(rows)


def _legend_texts(fig):
    return [t.get_text() for legend in fig.legends for t in legend.get_texts()]


def test_curves_come_from_the_library():
    tidy = _tidy()
    data = wearsim.plot.curves(tidy)
    # One curve per τ̃ (the seed and the load do not name one), its statistics over the two pairs.
    assert len(data) == 2
    assert all("τ̃ = " in label and "𝒢 = " in label and "seed" not in label for label, _ in data)
    _, stats = data[1]
    assert list(stats["nominal_pressure"]) == [P1, P2]
    assert list(stats["surface_pairs"]) == [2, 2]
    assert stats["wear_rate_min"].iloc[1] == 0.0 and stats["wear_rate_max"].iloc[1] == 4e-4
    assert np.isclose(stats["wear_rate_mean"].iloc[0], 1.5e-4)
    # The 95 % interval of the mean of 1e-4 and 2e-4: 1.5e-4 ± t(1) · sd/√2 with t(1) = 12.706 and
    # sd = 7.07e-5 (known spread), the library's numbers in both languages.
    half = 12.7062047 * np.std([1e-4, 2e-4], ddof=1) / np.sqrt(2)
    assert np.isclose(stats["wear_rate_ci_high"].iloc[0], 1.5e-4 + half, rtol=1e-7)
    assert np.isclose(stats["wear_rate_ci_low"].iloc[0], 1.5e-4 - half, rtol=1e-7)
    assert "Student t" in stats["interval_method"].iloc[0]
    # One value per quantity: the figure draws the curves' means (per unit nominal area), and
    # results_aggregated.csv holds the same table (the library's StudyTable::means).
    assert list(stats["fit_window_pairs"]) == [2, 2]
    drawn = wearsim.plot.figure_data(tidy, ["fig4"])[0]["panels"][0]["series"]
    for (label, curve), series in zip(data, drawn):
        assert series["label"] == label
        means = curve["wear_rate_mean"] * (1 / 0.5**2)  # the box is 0.5 × 0.5
        assert [p["y"] for p in series["points"]] == list(means[curve["wear_rate_mean"].notna()])
    # Units: the library's rule for the table's unit system, on the figures' axes.
    assert _wearsim.unit_of("si", "nominal_pressure") == "Pa"
    fig = wearsim.plot.figure_data(tidy, ["fig4"])[0]
    assert fig["panels"][0]["x"]["label"].endswith("(E)") and fig["name"] == "fig4_sliding_wear"


def test_intervals_of_the_library_on_data_of_a_known_spread():
    # Five values of mean 10 and sample standard deviation 2: 10 ± t(4) · 2/√5, t(4) = 2.7764451.
    a = 2 * np.sqrt(2)
    mean, low, high, n = _wearsim.mean_interval([10 - a, 10, 10, 10, 10 + a])
    assert n == 5 and np.isclose(mean, 10) and np.isclose(high - 10, 2.7764451 * 2 / np.sqrt(5), rtol=1e-7)
    assert np.isclose(10 - low, high - 10)
    assert _wearsim.mean_interval([1.0]) is None
    # 15 particles: exact Poisson [8.395, 24.74].
    count, low, high = _wearsim.poisson_interval(15)
    assert count == 15 and np.isclose(low, 8.3954, atol=1e-3) and np.isclose(high, 24.7402, atol=1e-3)
    assert _wearsim.INTERVAL_LEVEL == 0.95


def test_rates_are_drawn_per_unit_area():
    import matplotlib.pyplot as plt

    fig = wearsim.plot.sliding_wear(_tidy())
    ax = fig.axes[0]
    assert "per unit nominal area" in ax.get_ylabel()
    # The τ̃ = 0.012 curve at the lower load: mean 1.5e-4 over a box of 0.5 × 0.5.
    means = [line for line in ax.lines if line.get_linestyle() == "-" and len(line.get_xdata()) == 2]
    assert any(np.isclose(line.get_ydata()[0], 1.5e-4 / 0.25) for line in means)
    plt.close(fig)


def test_power_law_fit_of_the_library():
    alpha, n, r2 = _wearsim.power_law_fit([1.0, 2.0, 4.0], [1.0, 2.0, 2.0])
    assert np.isclose(n, 0.5) and np.isclose(r2, 0.75) and np.isclose(alpha, 2 ** (1 / 6))
    assert _wearsim.power_law_fit([1.0, 2.0], [1.0, 0.0]) is None


def test_few_particles_hollow_and_no_wear_on_the_axis():
    import matplotlib.pyplot as plt

    fig = wearsim.plot.sliding_wear(_tidy())
    ax = fig.axes[0]
    # The τ̃ = 0.012 point at the lower load rests on 11 particles: a hollow marker, its count in the legend.
    hollow = [line for line in ax.lines if line.get_markerfacecolor() == "none" and len(line.get_xdata())]
    assert [list(line.get_xdata()) for line in hollow] == [[P1]]
    texts = _legend_texts(fig)
    assert any("τ̃ = 0.012" in t and "hollow: 11 particles" in t for t in texts), texts
    assert any(t.startswith("hollow: < 20 particles") for t in texts)
    # τ̃ = 0.008 wears nothing at the lower load: a marker on the axis (y = 0 in axes coordinates).
    at_axis = [line for line in ax.lines if line.get_gid() == "no-wear"]
    assert len(at_axis) == 1 and list(at_axis[0].get_xdata()) == [P1] and list(at_axis[0].get_ydata()) == [0.0]
    assert any("no wear" in t for t in texts)
    # The τ̃ = 0.012 bar at the higher load (pairs 0 and 4e-4) has an interval reaching below zero:
    # it reaches the axis bottom.
    bottom = ax.get_ylim()[0]
    lows = [seg[0][1] for c in ax.collections for seg in c.get_segments()]
    assert any(np.isclose(low, bottom) for low in lows), (lows, bottom)
    # No panel letters (the paper's letters name rows of settings, not quantities); the bars are named.
    assert ax.get_title(loc="left").startswith("sliding model") and fig.axes[1].get_title(loc="left") == ""
    assert any("95 % confidence interval" in legend.get_title().get_text() for legend in fig.legends)
    plt.close(fig)


def test_settings_without_wear_at_one_load_stack_their_markers():
    import matplotlib.pyplot as plt

    tidy = _tidy()
    # A third setting (τ̃ = 0.010) that wears nothing at the lower load either: its marker sits above
    # τ̃ = 0.008's, not on it.
    extra = tidy[tidy["material.shear_strength"] == 0.008].copy()
    extra["material.shear_strength"] = 0.010
    extra["job"] += 100
    fig = wearsim.plot.sliding_wear(pd.concat([tidy, extra], ignore_index=True))
    at_axis = [line for line in fig.axes[0].lines if line.get_gid() == "no-wear"]
    assert [list(line.get_xdata()) for line in at_axis] == [[P1], [P1]]
    heights = sorted(float(line.get_ydata()[0]) for line in at_axis)
    assert heights[0] == 0.0 and heights[1] > 0.0
    assert at_axis[0].get_color() != at_axis[1].get_color()
    plt.close(fig)


def test_unfitted_figures_draw_no_hollow_markers():
    import matplotlib.pyplot as plt

    tidy = _tidy()
    tidy["junctions_mean"] = 10.0
    tidy["critical_junctions_mean"] = 2.0
    fig = wearsim.plot.junction_counts(tidy)
    assert not any(line.get_markerfacecolor() == "none" and len(line.get_xdata()) for line in fig.axes[0].lines)
    assert not any("hollow" in t for t in _legend_texts(fig))
    plt.close(fig)


def test_a_table_of_estimates_alone_judges_no_finding_and_says_why():
    tidy = _tidy()
    tidy["sliding.model"] = "estimate"
    rows, markdown = wearsim.study.findings(tidy)
    assert rows.empty and {"key", "verdict", "counts"} <= set(rows.columns)
    assert "holds no run of the sliding model" in markdown
    # Appendix F has nothing to fit there either, and says so.
    with pytest.raises(ValueError, match="nothing to fit"):
        wearsim.plot.contact_severity(tidy)


def test_settings_of_equal_critical_diameter_by_the_library():
    import matplotlib.pyplot as plt

    tidy = _tidy()
    # d* 0.01 and 0.005: nothing to compare; both 0.01 (τ̃ differs): one figure of both curves.
    assert wearsim.plot.constant_critical_diameter(tidy) == []
    tidy["critical_diameter"] = 0.01
    figures = wearsim.plot.constant_critical_diameter(tidy)
    assert len(figures) == 1
    assert sum("τ̃" in t for t in _legend_texts(figures[0])) == 2
    assert _wearsim.equal_critical_diameter([(0.01, 0.008, 1e-6), (0.0114, 0.012, 1e-6)], 0.15) == [[0, 1]]
    plt.close(figures[0])


def test_the_wear_regime_map_pairs_each_rule_with_the_papers():
    """The map, beyond the paper: a study without a particle-rule axis has none (a clear error); with
    one, each rule's W over the paper's rule's on the same pairs, where it departs in the legend, and
    a load in the breakdown regime ringed."""
    import matplotlib.pyplot as plt

    tidy = _tidy()
    with pytest.raises(ValueError, match="particle_rule"):
        wearsim.plot.wear_regime(tidy)
    tidy["particle_rate"] = tidy["particles_in_fit"] * 10.0
    tidy["breakdown_measures"] = 0
    paper = tidy.assign(**{"sliding.particle_rule": ""})
    other = tidy.assign(
        **{"sliding.particle_rule": "interacting(reach=1, particle=members)", "wear_rate": tidy["wear_rate"] * 1.5}
    )
    paper.loc[paper["nominal_pressure"] == P2, "breakdown_measures"] = 1
    both = pd.concat([paper, other], ignore_index=True)
    both["job"] = range(len(both))
    fig = wearsim.plot.wear_regime(both)
    texts = _legend_texts(fig)
    assert sum("departs" in t for t in texts) == 2, texts
    assert any(t.startswith("ringed") for t in texts), texts
    ratio = wearsim.plot.figure_data(both, ["wear-regime"])[0]["panels"][2]
    ys = {round(p["y"], 12) for s in ratio["series"] for p in s["points"]}
    assert ys == {1.5}, ys
    plt.close(fig)


def test_particle_counts_draws_three_curves_per_fracture_energy():
    """Appendix B on one run's series, the library's figure: N*₊ solid and thick, N* dashed, N*₋
    thin, one colour per 𝒢, at the load asked for, each curve the series' own numbers; without the
    results each curve is named by its 𝒢, with them by its d*."""
    top, bottom = wearsim.generate_pair(64, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005, seed=1)
    material = wearsim.Material(
        youngs_modulus=1.0, poisson_ratio=0.3, shear_strength=0.008, fracture_energies=[2.5e-7, 5e-7]
    )
    with pytest.warns(wearsim.ResolutionWarning):  # a small, coarse run
        series, summary = wearsim.slide(top, bottom, material, [1e-3, 2e-3], distance=0.25, running_in=0.125)
    fig = wearsim.plot.particle_counts(series, load=1e-3)
    lines = [line for line in fig.axes[0].lines if str(line.get_gid()).startswith("series-")]
    assert [(line.get_linestyle(), line.get_linewidth()) for line in lines] == [
        ("-", 2.0),
        ("--", 2.0),
        ("-", 1.0),
    ] * 2
    assert len({line.get_color() for line in lines[:3]}) == 1 and lines[0].get_color() != lines[3].get_color()
    for i, g in enumerate((2.5e-7, 5e-7)):
        mine = series[(series["load"] == 1e-3) & (series["fracture_energy"] == g)]
        for line, column in zip(lines[3 * i : 3 * i + 3], ("n_formed", "n_critical", "n_shrunk")):
            np.testing.assert_array_equal(line.get_xdata(), mine["s"])
            np.testing.assert_array_equal(line.get_ydata(), mine[column])
    labels = [t.get_text() for t in fig.legends[0].get_texts()] if fig.legends else []
    labels += [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    assert labels[0] == r"N*₊ (particles formed), $\mathcal{G}$ = 2.5×10⁻⁷ E L", labels
    matplotlib.pyplot.close(fig)
    named = wearsim.plot.particle_counts(series, results=summary["results"], load=1e-3)
    labels = [t.get_text() for ax in named.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
    labels += [t.get_text() for legend in named.legends for t in legend.get_texts()]
    assert any("d* = " in label for label in labels), labels
    matplotlib.pyplot.close(named)
    with pytest.raises(ValueError, match="no load 0.005"):
        wearsim.plot.particle_counts(series, load=5e-3)
    with pytest.raises(ValueError, match="length_unit"):
        wearsim.plot.particle_counts(series, length_unit="µm")
