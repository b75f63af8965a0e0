"""Measured maps as they come from instruments (through SurfaceTopography or as arrays): undefined
pixels, non-square pixels and units never pass silently into a wearsim function, and the PSD fit
levels a map first, as `wearsim surface fit` does."""

import json
import subprocess
import warnings

import numpy as np
import pytest
import wearsim
from fake_topography import FakeTopography

N = 64
MATERIAL = wearsim.Material(1.0, 0.3, 0.01, [1e-6])


def surface(seed=1, rms=0.005):
    return wearsim.generate_surface(N, lambda_lower=4 / N, lambda_upper=0.25, rms_height=rms, seed=seed)


def with_holes(h, count=5):
    """``h`` with ``count`` undefined pixels: masked, with instrument garbage (a spike) underneath."""
    mask = np.zeros(h.shape, bool)
    mask.flat[np.linspace(0, h.size - 1, count).astype(int)] = True
    return np.ma.masked_array(np.where(mask, 1e3, h), mask=mask)


# Every Python entry that takes heights, called on `h` (an array or a topography).
ENTRIES = {
    "surface_statistics": lambda h: wearsim.surface_statistics(h),
    "radial_psd": lambda h: wearsim.radial_psd(h),
    "preprocess_surface": lambda h: wearsim.preprocess_surface(h),
    "periodicity": lambda h: wearsim.periodicity(h),
    "fit_surface": lambda h: wearsim.fit_surface(h),
    "heights_and_length": lambda h: wearsim.heights_and_length(h),
    "slide": lambda h: wearsim.slide(h, surface(2), MATERIAL, [1e-3], distance=0.05, running_in=0.02),
}
ARRAY_ENTRIES = {
    **ENTRIES,
    "solve_contact": lambda h: wearsim.solve_contact(h, 1e-3, effective_modulus=1.0),
    "ContactSolver.solve": lambda h: wearsim.ContactSolver(N, 1.0, 1.0).solve(h, 1e-3),
}


@pytest.mark.parametrize("entry", ARRAY_ENTRIES)
def test_a_masked_array_is_refused_not_read_under_its_mask(entry):
    with pytest.raises(ValueError, match=r"5 masked \(undefined\) of its 4096 pixels.*interpolate_undefined_data"):
        ARRAY_ENTRIES[entry](with_holes(surface()))


@pytest.mark.parametrize("entry", ENTRIES)
def test_a_topography_with_undefined_data_is_refused(entry):
    t = FakeTopography(with_holes(surface() * 1e6, count=3), (64.0, 64.0), unit="um")
    with pytest.raises(ValueError, match=r"3 masked \(undefined\) of its 4096 pixels.*crop"):
        ENTRIES[entry](t)


def test_non_finite_heights_are_counted():
    h = surface()
    h[3, 4], h[10, 11] = np.nan, np.inf
    with pytest.raises(ValueError, match=r"invalid `heights`: 2 NaN or infinite of its 4096 pixels"):
        wearsim.surface_statistics(h)


def test_a_masked_array_with_nothing_masked_is_taken():
    h = surface()
    np.testing.assert_array_equal(wearsim.preprocess_surface(np.ma.masked_array(h)), wearsim.preprocess_surface(h))


@pytest.mark.parametrize("entry", ENTRIES)
def test_a_topography_with_non_square_pixels_is_refused(entry):
    # An .x3p map with 0.128 × 0.315 µm pixels.
    t = FakeTopography(surface() * 1e6, (N * 0.128, N * 0.315), unit="um")
    with pytest.raises(ValueError, match=r"not square: 0\.128 um along x .* 0\.315 um along y.*resample"):
        ENTRIES[entry](t)


def test_a_topography_comes_back_in_metres_heights_and_side_alike():
    h = surface() * 1e3
    t = FakeTopography(h, (0.1, 0.1), unit="mm")
    # The side in the file's unit alongside converted heights is the mismatch that gave full contact.
    with pytest.raises(ValueError, match=r"`length`.*0\.1 is the topography's side in its unit \(mm\).*metres"):
        wearsim.fit_surface(t, 0.1)
    heights, length = wearsim.heights_and_length(t)
    np.testing.assert_allclose(heights, h * 1e-3)
    assert length == pytest.approx(1e-4)
    # A length in metres overrides the size.
    assert wearsim.heights_and_length(t, 2e-4)[1] == 2e-4


def test_the_two_topographies_of_a_slide_share_one_box():
    top = FakeTopography(surface(1), (64.0, 64.0), unit="um")
    bottom = FakeTopography(surface(2), (64.0, 64.0), unit="nm")
    with pytest.raises(ValueError, match=r"invalid `bottom`: its side along x is 6\.4e-08 but the top's is 6\.4e-05"):
        wearsim.slide(top, bottom, MATERIAL, [1e-3], distance=0.05, running_in=0.02)


def test_fit_surface_levels_the_map_first_as_the_cli_does(tmp_path, wearsim_bin):
    h = wearsim.generate_surface(
        128, hurst=0.8, lambda_lower=1 / 32, lambda_upper=1 / 4, rms_height=0.01, seed=5, generation="filtered-noise"
    )
    tilted = h + 0.5 * np.linspace(-1, 1, 128)[:, None] + 0.2 * np.linspace(-1, 1, 128)[None, :]
    fit = wearsim.fit_surface(tilted, 1.0)
    assert fit["rms_height"] == pytest.approx(0.01, rel=0.1)
    assert fit["hurst"] == pytest.approx(0.8, abs=0.1)
    # The same numbers as `wearsim surface fit` with its default levelling.
    np.save(tmp_path / "tilted.npy", tilted)
    cli = ["surface", "fit", tmp_path / "tilted.npy", "--length", "1", "--out", tmp_path / "fit"]
    subprocess.run([wearsim_bin, "--quiet", *cli], check=True, capture_output=True)
    cli = json.loads((tmp_path / "fit" / "fit.json").read_text())
    assert fit == {**cli["fit"], **{k: cli[k] for k in ("spectrum", "notes", "self_affine", "reasons", "rms_slope")}}
    # Without levelling, the tilt is the "roughness".
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            raw = wearsim.fit_surface(tilted, 1.0, detrend="none")
            assert raw["map_rms_height"] > 10 * fit["map_rms_height"]
        except ValueError as e:
            assert "H cannot be fitted" in str(e)
    with pytest.raises(ValueError, match="detrend"):
        wearsim.fit_surface(tilted, 1.0, detrend="tilt")


def test_fit_surface_gives_the_rms_height_of_the_band_and_reports_the_whole_maps():
    # A self-affine band (h_rms 0.01 between 1/64 and 1/8) and a cosine of the box's wavelength that
    # holds 56 % of the variance: the block's h_rms is the band's (paper §4.1), not the whole map's.
    band = wearsim.generate_surface(512, hurst=0.7, lambda_lower=1 / 64, lambda_upper=1 / 8, rms_height=0.01, seed=2)
    outside = 1e-4 * 0.56 / 0.44
    wavy = band + np.sqrt(2 * outside) * np.cos(2 * np.pi * np.arange(512) / 512)[:, None]
    fit = wearsim.fit_surface(wavy, 1.0, detrend="none")
    assert fit["rms_height"] == pytest.approx(0.01, rel=0.03)
    assert fit["spectrum"]["rms_height"] == fit["rms_height"]
    assert fit["map_rms_height"] == pytest.approx(np.sqrt(1e-4 + outside), rel=1e-6)
    assert fit["out_of_band_share"] == pytest.approx(0.56, abs=0.02)
    assert fit["measured_pixel"] is None
    assert any("56 % of the map's variance lies outside" in n for n in fit["notes"])
    alone = wearsim.fit_surface(band, 1.0, detrend="none")
    assert alone["rms_height"] == pytest.approx(alone["map_rms_height"], rel=0.01)
    assert alone["out_of_band_share"] < 0.01
    assert not any("outside the self-affine band" in n for n in alone["notes"])


def test_fit_surface_of_a_resampled_map_takes_its_native_pixel():
    # Every other row of a surface whose power law runs to the pixel scale, each repeated: pixels
    # measured twice as long along y. Given the native pixel, the fit takes the measured wavevectors
    # (|q_y| ≤ π/Δy) only and recovers the original's H; fitted on all, H is off.
    n = 256
    original = wearsim.generate_surface(n, hurst=0.7, lambda_lower=2 / n, lambda_upper=0.25, rms_height=0.01, seed=1)
    resampled = np.repeat(original[:, ::2], 2, axis=1)
    h0 = wearsim.fit_surface(original, 1.0, detrend="none")["hurst"]
    native = wearsim.fit_surface(resampled, 1.0, detrend="none", measured_pixel=(1 / n, 2 / n))
    assert native["measured_pixel"] == pytest.approx([1 / n, 2 / n])
    assert native["hurst"] == pytest.approx(h0, abs=0.05)
    assert abs(wearsim.fit_surface(resampled, 1.0, detrend="none")["hurst"] - h0) > 0.08
    # One value is both axes: the map's own pixel changes nothing.
    same = wearsim.fit_surface(original, 1.0, detrend="none", measured_pixel=1 / n)
    assert same["hurst"] == h0 and same["measured_pixel"] is None
    for bad in [(1 / n, 2 / n, 3 / n), 0.5 / n]:
        with pytest.raises(ValueError, match="measured_pixel"):
            wearsim.fit_surface(resampled, 1.0, measured_pixel=bad)


def test_a_poor_power_law_fit_warns_as_the_cli_does(monkeypatch):
    fit = wearsim.fit_surface(surface(), 1.0)
    monkeypatch.setattr(wearsim.surface._wearsim, "fit_surface", lambda h, lx, native=None: {**fit, "r2": 0.5})
    with pytest.warns(UserWarning, match=r"R² < 0\.9"):
        wearsim.fit_surface(surface(), 1.0)


def test_surface_topography_maps_with_undefined_or_non_square_pixels():
    st = pytest.importorskip("SurfaceTopography")
    h = surface() * 1e6
    holes = with_holes(h, count=4)
    t = st.Topography(holes, (64.0, 64.0), unit="um")
    assert t.has_undefined_data
    with pytest.raises(ValueError, match=r"4 masked \(undefined\)"):
        wearsim.fit_surface(t)
    with pytest.raises(ValueError, match=r"4 masked \(undefined\)"):
        wearsim.slide(t, t, MATERIAL, [1e-3], distance=0.05, running_in=0.02)
    # The fix the message names works: the spikes under the mask are gone.
    filled, length = wearsim.heights_and_length(t.interpolate_undefined_data())
    assert length == pytest.approx(64e-6) and np.abs(filled).max() < 2 * np.abs(h).max() * 1e-6
    wide = st.Topography(h, (N * 0.128, N * 0.315), unit="um")
    with pytest.raises(ValueError, match=r"not square: 0\.128 um along x"):
        wearsim.surface_statistics(wide)
    square = st.Topography(h, (N * 0.128, N * 0.128), unit="um")
    assert wearsim.surface_statistics(square)["length"] == pytest.approx(N * 0.128e-6)
