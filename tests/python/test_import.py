"""`wearsim surface import` / `wearsim.measured.import_topography`: instrument files (written here by
SurfaceTopography's own writers, NetCDF and ISO 25178 .x3p) turned into the map a run file reads."""

import json
import subprocess
import sys

import numpy as np
import pytest

st = pytest.importorskip("SurfaceTopography")

import wearsim  # noqa: E402
from wearsim.measured import import_topography  # noqa: E402

Topography = st.Topography


def self_affine(nx=64, ny=64):
    """A periodic self-affine map, 0.5 µm pixels, heights ~0.1 (in the unit of the file)."""
    g = wearsim.generate_surface(
        (nx, ny), length=0.5 * nx, hurst=0.8, lambda_lower=2.0, lambda_upper=16.0, rms_height=0.1, seed=3
    )
    return g


def test_units_become_metres_odd_sides_are_cropped_and_the_tilt_is_removed(tmp_path):
    g = self_affine()
    # One row more (odd side along x) and a tilt; in µm.
    h = np.vstack([g, g[:1]]) + 0.01 * np.arange(65)[:, None] + 0.002 * np.arange(64)[None, :]
    Topography(h, (32.5, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    lines = []
    record = import_topography(tmp_path / "scan.nc", tmp_path / "out", say=lines.append)
    a = np.load(tmp_path / "out" / "heights.npy")
    assert a.dtype == np.float64 and a.shape == (64, 64)
    # Same orientation as SurfaceTopography's heights() (i along x), in metres, tilt gone.
    np.testing.assert_allclose(a, wearsim.preprocess_surface(g * 1e-6), atol=1e-12 * np.abs(a).max())
    assert record["metres_per_unit"] == pytest.approx(1e-6)
    assert record["length"] == pytest.approx([32e-6, 32e-6])
    assert record["cropped"] == {"from": [65, 64], "to": [64, 64]}
    assert record["detrend"] == "plane"
    text = "\n".join(lines)
    assert "cropped" in text and "detrend plane" in text and "metres" in text and "[surface]" in text
    on_disk = json.loads((tmp_path / "out" / "import.json").read_text())
    for key in (
        "source",
        "format",
        "reader",
        "channel",
        "channel_name",
        "grid",
        "physical_sizes",
        "unit",
        "pixel_size",
        "metres_per_unit",
        "undefined_pixels",
        "fill",
        "resampled",
        "cropped",
        "detrend",
        "length",
        "surface_toml",
    ):
        assert key in on_disk, key
    assert on_disk["grid"] == [65, 64] and on_disk["physical_sizes"] == [32.5, 32.0] and on_disk["unit"] == "µm"
    assert on_disk["pixel_size"] == pytest.approx([0.5, 0.5]) and on_disk["undefined_pixels"] == 0
    assert "length = 3.2e-05" in on_disk["surface_toml"] and 'units = "si"' in on_disk["surface_toml"]
    # Without levelling the heights are the file's, in metres.
    record = import_topography(tmp_path / "scan.nc", tmp_path / "raw", detrend="none")
    np.testing.assert_allclose(np.load(tmp_path / "raw" / "heights.npy"), h[:64] * 1e-6, rtol=1e-12)


def test_undefined_pixels_are_refused_with_their_count_and_filled_on_request(tmp_path):
    h = np.ma.masked_array(self_affine(), mask=np.zeros((64, 64), bool))
    h.mask[10:13, 20] = True
    Topography(h, (32.0, 32.0), unit="nm").to_x3p(tmp_path / "holes.x3p")
    with pytest.raises(ValueError, match=r"3 of its 4096 pixels are undefined.*--fill harmonic"):
        import_topography(tmp_path / "holes.x3p", tmp_path / "out")
    assert not (tmp_path / "out").exists()
    record = import_topography(tmp_path / "holes.x3p", tmp_path / "out", fill="harmonic")
    a = np.load(tmp_path / "out" / "heights.npy")
    assert np.isfinite(a).all() and record["undefined_pixels"] == 3 and record["fill"] == "harmonic"
    with pytest.raises(ValueError, match="fill"):
        import_topography(tmp_path / "holes.x3p", tmp_path / "other", fill="kriging")


def test_non_square_pixels_are_refused_and_resampled_on_request(tmp_path):
    # A plane, so that linear interpolation is exact: 40 pixels of 0.5 µm along x, 30 of 0.8 along y.
    x, y = np.arange(40)[:, None] * 0.5, np.arange(30)[None, :] * 0.8
    Topography(0.01 * x + 0.03 * y, (20.0, 24.0), unit="um").to_netcdf(tmp_path / "rect.nc")
    with pytest.raises(ValueError, match=r"not square, 0.5 µm along x and 0.8 µm along y.*--resample"):
        import_topography(tmp_path / "rect.nc", tmp_path / "out")
    assert not (tmp_path / "out").exists()
    record = import_topography(tmp_path / "rect.nc", tmp_path / "out", resample=True, detrend="none")
    a = np.load(tmp_path / "out" / "heights.npy")
    # Square 0.5 µm pixels; x kept whole; y within the measured span (the last sample at 23.2 µm).
    assert record["resampled"]["grid"] == [40, 47] and record["resampled"]["pixel_size"] == pytest.approx(0.5)
    assert a.shape == (40, 46) and record["cropped"] == {"from": [40, 47], "to": [40, 46]}
    assert record["length"] == pytest.approx([20e-6, 23e-6])
    xs, ys = np.arange(40)[:, None] * 0.5, np.arange(46)[None, :] * 0.5
    np.testing.assert_allclose(a, (0.01 * xs + 0.03 * ys) * 1e-6, atol=1e-15)


def test_the_output_folder_is_never_one_it_did_not_write_nor_the_input(tmp_path):
    Topography(self_affine(), (32.0, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("keep")
    with pytest.raises(FileExistsError, match="--overwrite"):
        import_topography(tmp_path / "scan.nc", mine)
    assert (mine / "notes.txt").read_text() == "keep"
    (tmp_path / "afile").write_text("keep")
    with pytest.raises(FileExistsError):
        import_topography(tmp_path / "scan.nc", tmp_path / "afile")
    for holder in (tmp_path, tmp_path / "scan.nc", tmp_path / "sub" / ".."):
        with pytest.raises(ValueError, match="instrument file"):
            import_topography(tmp_path / "scan.nc", holder, overwrite=True)
    assert (tmp_path / "scan.nc").is_file()
    # Its own folder is replaced; a foreign one with overwrite; nothing temporary is left.
    import_topography(tmp_path / "scan.nc", tmp_path / "out")
    import_topography(tmp_path / "scan.nc", tmp_path / "out", detrend="mean")
    assert json.loads((tmp_path / "out" / "import.json").read_text())["detrend"] == "mean"
    import_topography(tmp_path / "scan.nc", mine, overwrite=True)
    assert sorted(p.name for p in mine.iterdir()) == ["heights.npy", "import.json"]
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


def test_the_cli_imports_and_the_map_reads_in_surface_fit_and_a_run_file(tmp_path, wearsim_bin):
    g = self_affine()
    Topography(np.vstack([g, g[:1]]), (32.5, 32.0), unit="um").to_x3p(tmp_path / "scan.x3p")
    out = tmp_path / "imported"
    done = subprocess.run(
        [wearsim_bin, "surface", "import", tmp_path / "scan.x3p", "--out", out, "--python", sys.executable],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert "cropped" in done.stdout and f'top = "{out}/heights.npy"' in done.stdout
    record = json.loads((out / "import.json").read_text())
    lx = record["length"][0]
    assert record["format"] == "x3p" and record["reader"] == "X3PReader"
    fit = subprocess.run(
        [wearsim_bin, "surface", "fit", out / "heights.npy", "--length", repr(lx)], capture_output=True, text=True
    )
    assert fit.returncode == 0, fit.stderr
    assert "hurst" in fit.stdout
    run = tmp_path / "run.toml"
    run.write_text(
        record["surface_toml"]
        + "[material]\nyoungs_modulus = 3e11\npoisson_ratio = 0.25\nshear_strength = 3e9\n"
        + "fracture_energies = [10.0]\n[sliding]\nloads = [1e-6]\n"
    )
    surfaces = subprocess.run(
        [wearsim_bin, "surface", run, "--out", tmp_path / "surfaces"], capture_output=True, text=True
    )
    assert surfaces.returncode == 0, surfaces.stderr
    assert np.array_equal(np.load(tmp_path / "surfaces" / "top.npy"), np.load(out / "heights.npy"))
    # A damaged instrument file: one line of error, nothing written.
    (tmp_path / "bad.x3p").write_bytes(b"PK\x03\x04 not a zip")
    bad = subprocess.run(
        [wearsim_bin, "surface", "import", tmp_path / "bad.x3p", "--out", tmp_path / "bad", "--python", sys.executable],
        capture_output=True,
        text=True,
    )
    assert bad.returncode != 0 and "Traceback" not in bad.stderr and not (tmp_path / "bad").exists()


def test_a_file_without_size_is_refused_with_the_way_to_give_it(tmp_path):
    (tmp_path / "plain.txt").write_text("1 2 3 4\n5 6 7 8\n9 10 11 12\n13 14 15 16\n")
    with pytest.raises(ValueError, match=r"no physical size.*read_topography\(path, physical_sizes"):
        import_topography(tmp_path / "plain.txt", tmp_path / "out")
    assert not (tmp_path / "out").exists()
