"""Cross-check of wearsim's contact solver against tamaas (PyPI) on the same rough surface pair.

wearsim is run through its CLI (`wearsim surface`, `wearsim contact`); tamaas solves the same
composite surface with `PolonskyKeerRey` (elastic) and `KatoSaturated` (saturated pressure).
Skipped, visibly, only where tamaas cannot be imported.
"""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

tm = pytest.importorskip("tamaas", reason="tamaas not installed: pip install tamaas")
from tamaas_helpers import tamaas_model  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
WEARSIM = os.environ.get("WEARSIM_BIN", str(ROOT / "target" / "release" / "wearsim"))

RUN = """
[surface]
grid = {n}
length = 1.0
hurst = 0.7
lambda_lower = {lam}
lambda_upper = 0.25
rms_height = 0.005
seed = 4
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = {tau}
fracture_energies = [0.5e-6]
[contact]
tolerance = 1e-10
"""


def run_wearsim(tmp_path, n, tau, load):
    run = tmp_path / "run.toml"
    run.write_text(RUN.format(n=n, lam=8.0 / n, tau=tau))
    surfaces, out = tmp_path / "surfaces", tmp_path / "contact"
    subprocess.run([WEARSIM, "surface", str(run), "--out", str(surfaces)], check=True, capture_output=True)
    subprocess.run(
        [WEARSIM, "contact", str(run), "--load", str(load), "--out", str(out)], check=True, capture_output=True
    )
    h = np.load(surfaces / "top.npy") + np.load(surfaces / "bottom.npy")
    summary = json.loads((out / "summary.json").read_text())
    return h, np.load(out / "pressure.npy"), np.load(out / "contact.npy"), summary


@pytest.mark.parametrize("n", [64, 128])
def test_elastic_pressure_matches_polonsky_keer_rey(tmp_path, n):
    # A flow pressure far above any contact pressure makes the wearsim solve purely elastic.
    h, p, contact, summary = run_wearsim(tmp_path, n, tau=10.0, load=1e-3)
    assert summary["plastic_pixels"] == 0
    model = tamaas_model(n)
    solver = tm.PolonskyKeerRey(model, h, 1e-12)
    solver.solve(1e-3)
    p_tm = np.array(model.traction).reshape(n, n)
    scale = p.max()
    assert np.abs(p - p_tm).max() < 1e-5 * scale
    assert np.count_nonzero((p > 0) != (p_tm > 0)) <= 2


@pytest.mark.parametrize("n", [64, 128])
def test_saturated_pressure_matches_kato_saturated(tmp_path, n):
    tau = 0.01
    pm = 3 * np.sqrt(3) * tau
    h, p, contact, summary = run_wearsim(tmp_path, n, tau=tau, load=1e-3)
    assert summary["plastic_pixels"] > 0
    model = tamaas_model(n)
    solver = tm.KatoSaturated(model, h, 1e-10, pm)
    solver.solve(1e-3)
    p_tm = np.array(model.traction).reshape(n, n)
    assert abs(p_tm.mean() - 1e-3) < 1e-8
    # Same contact map up to a few pixels, pressures equal to the solvers' tolerance.
    assert np.count_nonzero((p > 0) != (p_tm > 1e-12 * pm)) <= 3
    assert np.abs(p - p_tm).max() < 1e-5 * pm
