"""The worked example of docs/measured-surfaces.md, end to end as a user runs it: a real AFM file
(examples/measured/di-3.di) imported, fitted, turned into periodic surface pairs that carry its
measured spectrum, slid in a study, collected, plotted and estimated, and the taper's border contact
measured (examples/measured/run.sh)."""

import json
import os
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

pytest.importorskip("SurfaceTopography")


def test_the_worked_example_runs_from_the_instrument_file_to_figures(wearsim_bin, root, tmp_path):
    out = tmp_path / "example"
    env = dict(os.environ, WEARSIM=wearsim_bin, WEARSIM_PYTHON=sys.executable, MPLBACKEND="Agg")
    # The example's study on two of its four surface pairs and two of its three loads (a third of
    # its sliding): every step of the example is taken, on fewer jobs.
    study = (root / "examples" / "measured" / "study.toml").read_text()
    assert "seed = [1, 2, 3, 4]" in study and "loads = [0.025, 0.05, 0.1]" in study
    quick = tmp_path / "study.toml"
    quick.write_text(study.replace("seed = [1, 2, 3, 4]", "seed = [1, 2]").replace("[0.025, 0.05, 0.1]", "[0.05, 0.1]"))
    run = subprocess.run(
        ["bash", str(root / "examples" / "measured" / "run.sh"), str(out), str(quick)],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-4000:]

    # 1. The import: the AFM map in metres, its size from the file.
    imported = json.loads((out / "di-3" / "import.json").read_text())
    assert imported["grid"] == [256, 256] and imported["unit"] == "nm"
    assert imported["length"] == pytest.approx([1e-5, 1e-5])
    heights = np.load(out / "di-3" / "heights.npy")
    assert heights.shape == (256, 256) and np.isfinite(heights).all()
    assert 1e-8 < heights.std() < 1e-7  # tens of nanometres, as the file's nm converted to metres

    # 2. The fit, windowed (the map is not periodic), with its verdict.
    fit = json.loads((out / "fit" / "fit.json").read_text())
    assert "self_affine" in fit and "reasons" in fit

    # 3–4. The study: two surface pairs carrying the measured spectrum, every job with a wear rate.
    results = pd.read_csv(out / "study" / "results.csv")
    assert len(results) == 2 * 2 * 2
    assert sorted(results["surface.seed"].unique()) == [1, 2]
    assert (results["surface.source"] == "spectrum").all()
    assert np.isfinite(results["wear_rate"]).all() and (results["wear_rate"] >= 0).all()
    # Particles formed: the example is not a row of zeros.
    assert results["particles_in_fit"].sum() > 100
    figures = {p.name for p in (out / "study" / "figures").iterdir()}
    assert "findings.md" in figures and any(name.startswith("fig4") and name.endswith(".png") for name in figures)
    comparison = pd.read_csv(out / "estimate-check" / "comparison.csv")
    assert len(comparison) == len(results)
    # The estimate says that measured spectra lie outside what its constants were calibrated on.
    check = json.loads((out / "estimate-check" / "summary.json").read_text())
    assert any("measured map's spectrum" in str(w) for w in check["warnings"]), check["warnings"][:3]

    # 5. The taper's border contact, one row per taper and offset.
    taper = pd.read_csv(out / "taper" / "taper_border_contact.csv")
    assert set(taper["taper"]) == {0.0, 0.05, 0.1, 0.2}
    assert (taper["border_contact_fraction"].between(0, 1)).all()
    assert (out / "taper" / "taper_border_contact.png").stat().st_size > 10_000
