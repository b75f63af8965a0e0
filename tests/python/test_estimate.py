"""The static estimate from Python: ``wearsim.estimate`` and ``RunFile.estimate`` equal ``wearsim
estimate``'s results and summary, marked as an estimate."""

import json
import subprocess

import pandas as pd
import pytest
import wearsim

RUN = """units = "reduced"
[surface]
grid = 128
length = 0.03125
hurst = 0.7
lambda_lower = 0.00390625
lambda_upper = 0.0078125
rms_height = 0.005
seed = 2
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.010
fracture_energies = [0.25e-6, 0.5e-6]
[sliding]
loads = [1.5e-6, 2.4e-6]
"""


def test_estimate_equals_the_cli_and_is_marked(tmp_path, wearsim_bin):
    run = tmp_path / "run.toml"
    run.write_text(RUN)
    out = tmp_path / "out"
    subprocess.run([wearsim_bin, "estimate", str(run), "--out", str(out), "--quiet"], check=True, capture_output=True)
    results, summary = wearsim.estimate(run)
    assert summary["model"] == "estimate"
    assert "not a sliding run" in summary["notice"]
    cli = pd.read_csv(out / "results.csv")
    assert list(results.columns) == list(cli.columns)
    pd.testing.assert_frame_equal(results.reset_index(drop=True), cli, check_dtype=False, rtol=1e-12)
    cli_summary = json.loads((out / "summary.json").read_text())
    assert summary["calibration"] == cli_summary["calibration"]
    assert summary["static_maps"] == cli_summary["static_maps"]
    # The same through a RunFile, with a fixed number of maps.
    fixed, s = wearsim.load_run(run).estimate(samples=5)
    assert s["static_maps"] == 5
    defined = fixed.dropna(subset=["wear_rate"])
    assert (defined.wear_rate_low < defined.wear_rate).all()
    assert (defined.wear_rate < defined.wear_rate_high).all()


def test_bad_counts_are_named_not_overflow_errors(tmp_path):
    run = tmp_path / "run.toml"
    run.write_text(RUN)
    for samples in (-1, 0, 17, 2.5, "4"):
        with pytest.raises(ValueError, match="invalid `samples`"):
            wearsim.estimate(run, samples=samples)
    with pytest.raises(ValueError, match="invalid `threads`"):
        wearsim.estimate(run, threads=-1)
    with pytest.raises(ValueError, match="invalid `threads`"):
        wearsim.load_run(run).slide(threads=-2)
