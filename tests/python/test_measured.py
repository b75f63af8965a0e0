"""Measured surfaces from Python: a non-periodic, rectangular ASCII height map in µm read by
SurfaceTopography (so any of its instrument formats) runs through wearsim with its units converted
and its tilt removed, and gives what `wearsim slide` gives on the same files; wearsim's own reader
and the PSD fit work on arrays."""

import subprocess
import warnings

import numpy as np
import pandas as pd
import pytest
import wearsim

st = pytest.importorskip("SurfaceTopography")

DX_UM = 0.5  # pixel size, µm
NX, NY = 64, 48

RUN = f"""
units = "si"
[surface]
top = "top.txt"
bottom = "bottom.txt"
length = [{NX * DX_UM * 1e-6}, {NY * DX_UM * 1e-6}]
height_unit = "um"
detrend = "plane"
[material]
youngs_modulus = 392e9
poisson_ratio = 0.16
shear_strength = 4.8e9
fracture_energies = [45.0]
[sliding]
loads = [0.3, 0.6]
"""


@pytest.fixture(scope="module")
def measured(tmp_path_factory):
    """Two profilometer-style exports: a self-affine surface cut out of a larger periodic one (so not
    periodic), tilted and offset, heights in µm, one line per scan along x, under a header line."""
    d = tmp_path_factory.mktemp("measured")
    for name, seed in [("top", 1), ("bottom", 2)]:
        big = wearsim.generate_surface(
            (96, 64), length=96 * DX_UM, lambda_lower=4 * DX_UM, lambda_upper=16 * DX_UM, rms_height=1.0, seed=seed
        )
        h = big[:NX, :NY] + 0.02 * DX_UM * np.arange(NX)[:, None] + 3.0
        np.savetxt(d / f"{name}.txt", h.T, fmt="%.9f", header="heights in um")
    (d / "run.toml").write_text(RUN)
    return d


def topography(path):
    return st.read_topography(str(path), unit="µm", physical_sizes=(NX * DX_UM, NY * DX_UM))


def test_surface_topography_and_the_cli_give_the_same_run(measured, wearsim_bin):
    subprocess.run(
        [wearsim_bin, "--quiet", "slide", measured / "run.toml", "--out", measured / "cli"],
        check=True,
        capture_output=True,
    )
    cli = pd.read_csv(measured / "cli" / "series.csv")
    top, bottom = (topography(measured / f"{n}.txt") for n in ["top", "bottom"])
    assert top.heights().shape == (NX, NY) and not top.is_periodic
    # The topography's µm become metres; the plane goes.
    levelled = [wearsim.preprocess_surface(t, detrend="plane") for t in (top, bottom)]
    assert abs(levelled[0].mean()) < 1e-12 and 0.3e-6 < levelled[0].std() < 2e-6
    material = wearsim.Material(392e9, 0.16, 4.8e9, [45.0])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        series, summary = wearsim.slide(levelled[0], levelled[1], material, [0.3, 0.6], length=NX * DX_UM * 1e-6)
    assert any("not periodic" in str(w.message) for w in caught), [str(w.message) for w in caught]
    pd.testing.assert_frame_equal(series[cli.columns].reset_index(drop=True), cli, check_dtype=False)
    assert summary["inputs"]["surfaces"]["grid"] == [NX, NY]
    # A topography straight into slide: converted to metres with its physical size.
    raw, _ = wearsim.slide(top, bottom, material, [0.6], distance=0.25, running_in=0.125)
    as_metres, _ = wearsim.slide(
        top.heights() * 1e-6,
        bottom.heights() * 1e-6,
        material,
        [0.6],
        length=NX * DX_UM * 1e-6,
        distance=0.25,
        running_in=0.125,
    )
    pd.testing.assert_frame_equal(raw, as_metres)


def test_wearsims_reader_agrees_with_surface_topography(measured):
    with pytest.warns(UserWarning, match="not periodic"):
        heights, length = wearsim.read_surface(
            measured / "top.txt", length=(NX * DX_UM * 1e-6, NY * DX_UM * 1e-6), height_unit="um"
        )
    t = topography(measured / "top.txt")
    # A map whose mean height exceeds its roughness loses its mean (the contact does not depend on
    # it): the same heights up to that constant.
    desired = t.heights() * 1e-6
    np.testing.assert_allclose(
        heights - heights.mean(), desired - desired.mean(), rtol=0, atol=1e-12 * np.abs(desired).max()
    )
    assert length == pytest.approx(NX * DX_UM * 1e-6)
    jump_x, jump_y = wearsim.periodicity(heights)
    assert jump_x > 3  # the tilt and the cut
    assert (
        wearsim.periodicity(wearsim.generate_surface(64, lambda_lower=1 / 16, lambda_upper=1 / 4, rms_height=1))[0] < 3
    )


def test_the_psd_fit_of_a_topography_gives_a_block_that_generates_similar_surfaces():
    h = wearsim.generate_surface(
        (256, 128), length=128.0, hurst=0.8, lambda_lower=2.0, lambda_upper=32.0, rms_height=1.5, seed=4
    )
    t = st.Topography(h, physical_sizes=(128.0, 64.0), unit="µm", periodic=True)
    fit = wearsim.fit_surface(t)
    assert fit["hurst"] == pytest.approx(0.8, abs=0.05)
    assert 2e-6 / 1.2 < fit["lambda_lower"] < 2e-6 * 1.2
    assert 32e-6 / 1.2 < fit["lambda_upper"] < 32e-6 * 1.2
    assert fit["rms_height"] == pytest.approx(1.5e-6, rel=0.02)


@pytest.mark.parametrize("generation", ["random-phase", "filtered-noise"])
def test_the_psd_fit_leaves_out_the_floor_beyond_the_cut_off_of_a_levelled_generated_surface(generation):
    # Beyond λ_l a generated surface holds round-off, and levelling it adds leakage far under the band.
    h = wearsim.generate_surface(
        512, hurst=0.8, lambda_lower=1 / 64, lambda_upper=1 / 4, rms_height=0.01, seed=3, generation=generation
    )
    fit = wearsim.fit_surface(wearsim.preprocess_surface(h, detrend="plane"), 1.0)
    assert fit["hurst"] == pytest.approx(0.8, abs=0.05)
    assert 1 / 64 / 1.25 < fit["lambda_lower"] < 1 / 64 * 1.25
    assert 1 / 4 / 1.25 < fit["lambda_upper"] < 1 / 4 * 1.25
    # The result says which band was fitted and what was left out.
    q_first, q_last = fit["fitted_q"]
    assert 2 * np.pi * 4 <= q_first < q_last <= 2 * np.pi * 64
    assert fit["shells_shorter"] > 200 and fit["floor"] < 1e-6


def test_a_psd_without_a_power_law_band_is_an_error():
    white = np.random.default_rng(1).normal(size=(64, 64))
    with pytest.raises(ValueError, match="H cannot be fitted"):
        wearsim.fit_surface(white, 1.0)


def test_read_surface_takes_csv_as_spreadsheets_write_it(tmp_path):
    rng = np.random.default_rng(3)
    h = rng.normal(scale=1e-3, size=(32, 20))
    # Lines are scans along x: the file holds the transpose of the map.
    lines = [[f"{v:.6f}" for v in row] for row in h.T]
    plain = tmp_path / "plain.csv"
    plain.write_text("\n".join(",".join(r) for r in lines) + "\n")
    expected, _ = wearsim.read_surface(plain, length=1.0)
    np.testing.assert_allclose(expected, np.round(h, 6))
    # Excel's "CSV UTF-8" (a byte-order mark) and a European export (decimal commas, semicolons).
    bom = tmp_path / "bom.csv"
    bom.write_text("\ufeff" + "\n".join(",".join(r) for r in lines) + "\n", encoding="utf-8")
    semi = tmp_path / "semi.csv"
    semi.write_text("\n".join(";".join(v.replace(".", ",") for v in r) for r in lines) + "\r\n")
    for path in (bom, semi):
        heights, _ = wearsim.read_surface(path, length=1.0)
        np.testing.assert_array_equal(heights, expected)
    spaces = tmp_path / "spaces.txt"
    spaces.write_text("\n".join(" ".join(v.replace(".", ",") for v in r) for r in lines) + "\n")
    with pytest.raises(OSError, match="decimal commas"):
        wearsim.read_surface(spaces, length=1.0)
