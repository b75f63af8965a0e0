"""Studies from Python: local runs equal `wearsim study run` + `collect`; a run on a Dask
LocalCluster with two worker processes equals the local run; resume after a partial run."""

import subprocess

import numpy as np
import pandas as pd
import pytest
import wearsim

STUDY = """
[surface]
grid = 64
lambda_lower = 0.125
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2]
[[materials]]
name = "soft"
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = [0.008, 0.012]
fracture_energies = [0.5e-6, 1e-6]
[sliding]
loads = [5e-4, 1e-3]
distance = 0.25
running_in = 0.125
"""


@pytest.fixture()
def study_file(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(STUDY)
    return path


def test_local_run_equals_the_cli(tmp_path, study_file, wearsim_bin):
    study = wearsim.study.load(study_file)
    assert len(study) == 8
    jobs = study.jobs()
    assert list(jobs["surface.seed"].unique()) == [1, 2] and set(jobs["load"]) == {5e-4, 1e-3}
    calls = []
    tidy = wearsim.study.run(study, out=tmp_path / "py", progress=lambda d, t: calls.append((d, t)))
    assert calls[-1] == (8, 8)
    cli = tmp_path / "cli"
    subprocess.run([wearsim_bin, "study", "run", str(study_file), "--out", str(cli)], check=True, capture_output=True)
    subprocess.run([wearsim_bin, "study", "collect", str(cli)], check=True, capture_output=True)
    assert (tmp_path / "py" / "results.csv").read_text() == (cli / "results.csv").read_text()
    pd.testing.assert_frame_equal(tidy, wearsim.study.collect(cli)[0])
    assert tidy.attrs["units"]["wear_rate"] == "L²" and tidy.attrs["units"]["load"] == "E L²"
    assert tidy.attrs["provenance"]["numpy"] == np.__version__
    assert tidy.attrs["provenance"]["pandas"] == pd.__version__
    assert tidy.attrs["provenance"]["wearsim"] == wearsim.__version__
    assert len(tidy) == 16
    tidy2, aggregated = wearsim.study.collect(tmp_path / "py")
    pd.testing.assert_frame_equal(tidy2, tidy)
    assert (aggregated["surface_pairs"] == 2).all() and len(aggregated) == 8


def test_resume_skips_finished_jobs_and_mixes_with_the_cli(tmp_path, study_file, wearsim_bin):
    out = tmp_path / "out"
    # Half the jobs from Python, the rest from the CLI on the same folder, then collect from Python.
    assert wearsim.study.run(study_file, out=out, shard=(1, 2)).empty
    done = sorted(p.name for p in (out / "jobs").iterdir())
    assert len(done) == 4
    mtimes = {p.name: p.stat().st_mtime_ns for p in (out / "jobs").iterdir()}
    result = subprocess.run(
        [wearsim_bin, "study", "run", str(study_file), "--out", str(out)], check=True, capture_output=True, text=True
    )
    assert "computed 4 jobs, skipped 4" in result.stdout + result.stderr
    assert all((out / "jobs" / name).stat().st_mtime_ns == t for name, t in mtimes.items())
    tidy = wearsim.study.run(study_file, out=out)
    assert len(tidy) == 16
    # A folder of another study is refused with the library's message.
    (tmp_path / "other.toml").write_text(STUDY.replace("0.012", "0.011"))
    with pytest.raises(ValueError, match="different study"):
        wearsim.study.run(tmp_path / "other.toml", out=out)


def test_dask_local_cluster_equals_the_local_run(tmp_path, study_file):
    distributed = pytest.importorskip("dask.distributed", reason="dask not installed: pip install 'dask[distributed]'")
    local = wearsim.study.run(study_file, out=tmp_path / "local")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            assert len(client.scheduler_info()["workers"]) == 2
            # Resume under Dask too: two jobs done beforehand are not resubmitted.
            wearsim.study.run(study_file, out=tmp_path / "dask", shard=(1, 4))
            before = {p.name: p.stat().st_mtime_ns for p in (tmp_path / "dask" / "jobs").iterdir()}
            assert len(before) == 2
            with distributed.get_task_stream(client) as stream:
                tidy = wearsim.study.run(study_file, client, out=tmp_path / "dask", threads=1)
    tasks = [t for t in stream.data if t["key"].startswith("wearsim-")]
    pd.testing.assert_frame_equal(tidy, local)
    assert (tmp_path / "dask" / "results.csv").read_text() == (tmp_path / "local" / "results.csv").read_text()
    assert all((tmp_path / "dask" / "jobs" / n).stat().st_mtime_ns == t for n, t in before.items())
    # Six pending jobs, each a Dask task, spread over both worker processes.
    assert len(tasks) == 6 and len({t["worker"] for t in tasks}) == 2


def _drawn_numbers(fig):
    """The (x, y) each series of a matplotlib figure drawn by `wearsim.plot.draw` plots, by its gid
    "series-<panel>-<index>"."""
    drawn = {}
    for p, ax in enumerate(fig.axes[: len(fig.axes)]):
        for line in ax.lines:
            gid = line.get_gid()
            if gid and gid.startswith(f"series-{p}-"):
                drawn[gid] = (np.asarray(line.get_xdata(), dtype=float), np.asarray(line.get_ydata(), dtype=float))
    return drawn


def test_figures_from_python_and_job_series(tmp_path, study_file, wearsim_bin):
    pytest.importorskip("matplotlib", reason="matplotlib not installed")
    import matplotlib
    import matplotlib.pyplot as plt

    matplotlib.use("Agg")
    out = tmp_path / "out"
    tidy = wearsim.study.run(study_file, out=out)
    series = wearsim.study.job_series(out, 3)
    assert set(series["fracture_energy"]) == {0.5e-6, 1e-6}
    assert (series["n_shrunk"] == series["n_formed"] - series["n_critical"]).all()
    assert series["initial_junctions"].iloc[0] == series["junctions"].iloc[0]
    written = wearsim.plot.study_figures(out)
    python = out / "figures-python"
    # The CLI and Python draw the same figures, from one registry, under the same names, each with
    # the same numbers as CSV beside it.
    subprocess.run([wearsim_bin, "study", "plot", str(out)], check=True, capture_output=True)
    cli = out / "figures"
    stems = {p.stem for p in cli.glob("*.png")}
    assert stems == {p.stem for p in written if p.suffix == ".png"}
    assert {"fig2_static_model", "fig3_wear_volume", "appC_junctions", "memory_of_initial_contact"} <= stems
    # Every entry of the registry draws, but the wear-regime map, which needs a particle-rule axis.
    registry = {name for name, _ in wearsim.plot.FIGURES}
    assert registry - {"wear-regime"} == {f["entry"] for f in wearsim.plot.study_figure_data(out)}
    for stem in stems:
        assert (cli / f"{stem}.csv").read_text() == (python / f"{stem}.csv").read_text(), stem
        assert (python / f"{stem}.png").stat().st_size > 1000
    # What matplotlib plots is the CSV's numbers: every series, point by point.
    for data in wearsim.plot.study_figure_data(out):
        # Read exactly: the CSV holds each number in its shortest round-trip form (pandas 3 reads
        # it so by default and deprecates asking; older pandas only when asked).
        exact = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}
        table = pd.read_csv(cli / f"{data['name']}.csv", **exact)
        points = table[table["kind"] == "point"]
        fig = wearsim.plot.draw(data)
        drawn = _drawn_numbers(fig)
        plt.close(fig)
        for p, panel in enumerate(data["panels"]):
            for i, s in enumerate(panel["series"]):
                mine = points[(points["panel"] == p) & (points["series"] == s["label"])]
                x, y = mine["x"].to_numpy(dtype=float), mine["y"].to_numpy(dtype=float)
                if s["style"] == "means" and panel["y"]["log"]:
                    keep = np.isfinite(y) & (y > 0)
                    x, y = x[keep], y[keep]
                got = drawn[f"series-{p}-{i}"]
                np.testing.assert_array_equal(got[0], x, err_msg=f"{data['name']}: {s['label']}")
                np.testing.assert_array_equal(got[1], y, err_msg=f"{data['name']}: {s['label']}")
    labels = [label for label, _ in wearsim.plot.curves(tidy)]
    assert len(labels) == 4 and all("τ̃ = " in label and "𝒢 = " in label for label in labels)
    # One findings document: the library's, byte for byte the same from both front ends.
    assert (python / "findings.md").read_bytes() == (cli / "findings.md").read_bytes()
    assert (python / "findings.md").read_text(encoding="utf-8").count("| ") > 10
    rows, markdown = wearsim.study.findings(tidy)
    assert markdown == (cli / "findings.md").read_text(encoding="utf-8")
    assert "archard-like" in set(rows["key"]) and "95 % confidence interval" in markdown
    # Every unit's numbers, the same from both front ends, one row per unit the findings count.
    assert (python / "findings_units.csv").read_bytes() == (cli / "findings_units.csv").read_bytes()
    units = wearsim.study.findings_units(tidy)
    counted = rows["counts"].map(sum).sum()
    listed = units["same_data_as"].fillna("").astype(str) != ""
    assert len(units[(units["outcome"] != "shown") & ~listed]) == counted
    assert set(units["finding"]) <= set(rows["key"])
    # A verdict the Holm adjustment would change says which, in its own column and in words; a
    # verdict another run-in rule would change is rule-dependent, with the three verdicts.
    for _, row in rows.iterrows():
        if isinstance(row["verdict_under_holm"], str):
            assert row["verdict_under_holm"] != row["verdict"] and row["verdict_under_holm"] in row["kind"], row["key"]
        if isinstance(row["verdicts_by_rule"], dict):
            assert row["verdict"] == "rule-dependent", row["key"]
            assert all(v in row["kind"] for v in row["verdicts_by_rule"].values()), row["key"]


def test_job_series_is_the_librarys_series_of_the_job_file(tmp_path, study_file):
    import json

    out = tmp_path / "out"
    wearsim.study.run(study_file, out=out)
    series = wearsim.study.job_series(out, 3)
    # The columns of a sliding run's series, in the library's order; those job files do not keep empty.
    assert list(series.columns) == list(wearsim.wear.SERIES_COLUMNS)
    assert series[["static_wear_rate", "iterations", "residual"]].isna().all().all()
    job = json.loads((out / "jobs" / "job-000003.json").read_text())
    expected = [
        (job["load"], w["fracture_energy"], st["s"], st["junctions"], st["n_critical"][e], st["n_formed"][e],
         st["volume"][e], st["initial_junctions"], st["static_wear_coefficient"][e], st["wrapping_junctions"])
        for e, w in enumerate(job["results"])
        for st in job["steps"]
    ]  # fmt: skip
    columns = ["load", "fracture_energy", "s", "junctions", "n_critical", "n_formed", "volume",
               "initial_junctions", "static_wear_coefficient", "wrapping_junctions"]  # fmt: skip
    assert list(series[columns].itertuples(index=False, name=None)) == expected
    assert (series["n_shrunk"] == series["n_formed"] - series["n_critical"]).all()
    with pytest.raises(OSError, match="job-000099.json"):
        wearsim.study.job_series(out, 99)


def test_series_figures_draw_the_librarys_fits(tmp_path):
    pytest.importorskip("matplotlib", reason="matplotlib not installed")
    import matplotlib

    matplotlib.use("Agg")
    top, bottom = wearsim.generate_pair(64, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005, seed=1)
    material = wearsim.Material(youngs_modulus=1.0, poisson_ratio=0.3, shear_strength=0.008, fracture_energies=[0.5e-6])
    with pytest.warns(wearsim.ResolutionWarning):  # a small, coarse run: under-resolved d*, not run in
        series, summary = wearsim.slide(top, bottom, material, [1e-3], distance=0.25, running_in=0.125)
    r = summary["results"][0]
    # The fit window starts at the first step at or past running-in (8 of 64 px here).
    assert r["fit_window_start"] == 0.125
    fig = wearsim.plot.wear_volume(series, results=summary["results"])
    line = [ln for ln in fig.axes[0].get_lines() if ln.get_linestyle() == "--"]
    assert r["wear_rate"] is not None and r["wear_volume_intercept"] is not None
    s, v = line[0].get_data()
    assert np.allclose(v, r["wear_volume_intercept"] + r["wear_rate"] * np.asarray(s), rtol=1e-12)
    # Without the results there is no library fit to draw: the figure asks for them.
    with pytest.raises(ValueError, match="results"):
        wearsim.plot.wear_volume(series)
    fig = wearsim.plot.memory(series, results=summary["results"])
    curve = [ln for ln in fig.axes[0].get_lines() if ln.get_linestyle() == "--"]
    assert r["memory_decay_length"] is not None and r["memory_fit_initial_junctions"] is not None
    s, n0 = curve[0].get_data()
    expected = r["memory_fit_initial_junctions"] * np.exp(-np.asarray(s) / r["memory_decay_length"])
    assert np.allclose(n0, expected, rtol=1e-12)
    with pytest.raises(ValueError, match="results"):
        wearsim.plot.memory(series)
