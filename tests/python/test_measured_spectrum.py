"""The PSD fit's verdict on whether a spectrum is self-affine, as `wearsim surface fit` gives it, and
periodic pairs that carry a measured map's 2D spectrum, as a run file's `source = "spectrum"`
makes them."""

import json
import subprocess
import warnings

import numpy as np
import pytest
import wearsim
from fake_topography import FakeTopography

N = 128


def stretched(n=N, stretch=4.0, hurst=0.7, seed=0):
    """A periodic map whose self-affine spectrum is stretched ``stretch`` times along y: its
    features are that much longer along y than along x (a lay), C(qx, qy) ∝ |(qx, stretch qy)|^−2(1+H)."""
    rng = np.random.default_rng(seed)
    m = np.fft.fftfreq(n) * n
    q = np.hypot(m[:, None], stretch * m[None, :])
    amplitude = np.where(q >= 4, np.maximum(q, 1) ** -(1 + hurst), 0.0)
    h = np.fft.ifft2(amplitude * np.exp(2j * np.pi * rng.random((n, n)))).real
    return h / h.std() * 0.01


def self_affine(seed=1):
    return wearsim.generate_surface(256, lambda_lower=4 / 256, lambda_upper=0.25, rms_height=0.01, seed=seed)


def cli_fit(wearsim_bin, tmp_path, heights, name):
    np.save(tmp_path / f"{name}.npy", heights)
    out = tmp_path / f"{name}-fit"
    cli = ["surface", "fit", tmp_path / f"{name}.npy", "--length", "1", "--out", out]
    subprocess.run([wearsim_bin, "--quiet", *cli], check=True, capture_output=True)
    return json.loads((out / "fit.json").read_text())


def python_fit_of_cli(cli):
    """What fit_surface returns for a map, from the fit.json of `wearsim surface fit` on it: the
    fit's fields and, beside them, the spectrum, notes and verdict."""
    return {**cli["fit"], **{k: cli[k] for k in ("spectrum", "notes", "self_affine", "reasons", "rms_slope")}}


def test_an_anisotropic_spectrum_is_not_self_affine_and_warns_pointing_to_spectrum_pairs(tmp_path, wearsim_bin):
    h = stretched()
    with pytest.warns(UserWarning, match=r"not self-affine \(anisotropic.*spectrum_pair.*source = \"spectrum\""):
        fit = wearsim.fit_surface(h, 1.0)
    assert fit["self_affine"] is False
    assert any("anisotropic" in r for r in fit["reasons"]), fit["reasons"]
    assert fit["anisotropy"] > 2
    # What `wearsim surface fit` writes for the same map, every field and the verdict.
    cli = cli_fit(wearsim_bin, tmp_path, h, "lay")
    assert cli["self_affine"] is False
    assert fit == python_fit_of_cli(cli)


def test_a_generated_self_affine_surface_passes_the_verdict_without_a_warning(tmp_path, wearsim_bin):
    h = self_affine()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit = wearsim.fit_surface(h, 1.0)
    assert fit["self_affine"] is True and fit["reasons"] == []
    assert fit["window"] == "none"
    assert fit == python_fit_of_cli(cli_fit(wearsim_bin, tmp_path, h, "self-affine"))


def test_a_map_that_is_not_periodic_is_fitted_under_a_hann_window_as_the_cli_does(tmp_path, wearsim_bin):
    # A piece cut out of a periodic surface: its borders jump.
    h = wearsim.generate_surface(256, lambda_lower=4 / 256, lambda_upper=0.25, rms_height=0.01, seed=2)[:128, :128]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = wearsim.fit_surface(h, 1.0)
    assert fit["window"] == "hann"
    assert fit == python_fit_of_cli(cli_fit(wearsim_bin, tmp_path, h, "cut"))


SPECTRUM_RUN = """
[surface]
source = "spectrum"
map = "map.npy"
map_length = 1.0
grid = {grid}
length = {length}
seed = {seed}
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]
"""


def cli_pair(wearsim_bin, tmp_path, h, grid, length, seed, name):
    np.save(tmp_path / "map.npy", h)
    run = tmp_path / f"{name}.toml"
    run.write_text(SPECTRUM_RUN.format(grid=grid, length=length, seed=seed))
    out = tmp_path / name
    subprocess.run([wearsim_bin, "--quiet", "surface", run, "--out", out], check=True, capture_output=True)
    return np.load(out / "top.npy"), np.load(out / "bottom.npy")


@pytest.mark.parametrize("periodic", [True, False])
def test_spectrum_pairs_are_the_run_files_surfaces_bit_for_bit(tmp_path, wearsim_bin, periodic):
    # A periodic map takes no window, a piece cut out of one a Hann window: both as the run file.
    h = stretched(seed=3) if periodic else stretched(n=2 * N, seed=3)[:N, :N]
    top, bottom = wearsim.spectrum_pair(h, 1.0, grid=64, box_length=1.0, seed=7)
    cli_top, cli_bottom = cli_pair(wearsim_bin, tmp_path, h, 64, 1.0, 7, "run")
    assert top.shape == bottom.shape == (64, 64)
    np.testing.assert_array_equal(top, cli_top)
    np.testing.assert_array_equal(bottom, cli_bottom)
    assert not np.array_equal(top, bottom)
    # Another seed, other surfaces (the same spectrum).
    other_top, _ = wearsim.spectrum_pair(h, 1.0, grid=64, box_length=1.0, seed=8)
    assert not np.array_equal(top, other_top)
    # The window can be named; the automatic choice is the one the map needs.
    named, _ = wearsim.spectrum_pair(h, 1.0, grid=64, box_length=1.0, seed=7, window="none" if periodic else "hann")
    np.testing.assert_array_equal(top, named)


def test_spectrum_pairs_say_what_a_larger_box_or_a_smaller_pixel_leaves_out(tmp_path, wearsim_bin):
    h = stretched(seed=4)
    with pytest.warns(UserWarning) as caught:
        top, bottom = wearsim.spectrum_pair(h, 1.0, grid=512, box_length=2.0, seed=1)
    text = " | ".join(str(w.message) for w in caught)
    assert "larger than the map" in text and "pixel" in text and "smaller than the map's" in text, text
    cli_top, cli_bottom = cli_pair(wearsim_bin, tmp_path, h, 512, 2.0, 1, "larger")
    np.testing.assert_array_equal(top, cli_top)
    np.testing.assert_array_equal(bottom, cli_bottom)
    # The map's own box and pixel leave nothing out.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wearsim.spectrum_pair(h, 1.0, grid=N, seed=1)


def test_spectrum_pairs_check_the_map_as_every_heights_entry_does():
    h = stretched(seed=5)
    holes = np.ma.masked_array(h, mask=np.zeros(h.shape, bool))
    holes.mask[3, 4] = True
    with pytest.raises(ValueError, match=r"invalid `map`: 1 masked \(undefined\).*interpolate_undefined_data"):
        wearsim.spectrum_pair(holes, 1.0, grid=64, seed=1)
    nan = h.copy()
    nan[1, 2] = np.nan
    with pytest.raises(ValueError, match=r"invalid `map`: 1 NaN or infinite"):
        wearsim.spectrum_pair(nan, 1.0, grid=64, seed=1)
    with pytest.raises(ValueError, match="window"):
        wearsim.spectrum_pair(h, 1.0, grid=64, seed=1, window="tukey")
    with pytest.raises(ValueError, match="seed"):
        wearsim.spectrum_pair(h, 1.0, grid=64, seed=-1)


def test_spectrum_pairs_of_a_topography_are_in_metres_box_and_heights_alike():
    h = stretched(seed=6)
    t = FakeTopography(h * 1e6, (100.0, 100.0), unit="um")
    top, bottom = wearsim.spectrum_pair(t, grid=64, seed=2)
    expected = wearsim.spectrum_pair(h, 1e-4, grid=64, box_length=1e-4, seed=2)
    np.testing.assert_allclose(top, expected[0], rtol=1e-9, atol=1e-9 * np.abs(expected[0]).max())
    np.testing.assert_allclose(bottom, expected[1], rtol=1e-9, atol=1e-9 * np.abs(expected[1]).max())
    wide = FakeTopography(h * 1e6, (N * 0.128, N * 0.315), unit="um")
    with pytest.raises(ValueError, match=r"invalid `map`: the topography's pixels are not square"):
        wearsim.spectrum_pair(wide, grid=64, seed=2)
