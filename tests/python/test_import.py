"""`wearsim surface import` / `wearsim.measured.import_topography`: instrument files (written here by
SurfaceTopography's own writers, NetCDF and ISO 25178 .x3p) turned into the maps of a run's two bodies:
the map itself, and the counter-body's own map or the map rotated by 180° about its centre."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

st = pytest.importorskip("SurfaceTopography")

import wearsim  # noqa: E402
from wearsim import measured  # noqa: E402
from wearsim.measured import import_topography  # noqa: E402

Topography = st.Topography


def self_affine(nx=64, ny=64, seed=3):
    """A periodic self-affine map, 0.5 µm pixels, heights ~0.1 (in the unit of the file)."""
    g = wearsim.generate_surface(
        (nx, ny), length=0.5 * nx, hurst=0.8, lambda_lower=2.0, lambda_upper=16.0, rms_height=0.1, seed=seed
    )
    return g


def no_temporary_folders(folder):
    return not [p for p in folder.iterdir() if p.name.endswith(".tmp")]


def correlation(bottom, top, offset):
    """The correlation coefficient of the bottom body's heights and the top's slid by ``offset``
    pixels along x, the two terms of the run's composite surface ``bottom + roll(top, offset)``."""
    return np.corrcoef(bottom.ravel(), np.roll(top, offset, axis=0).ravel())[0, 1]


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
        "bottom_map",
        "bodies",
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


def test_surface_fit_of_a_resampled_import_takes_the_native_pixels_from_its_import_json(tmp_path, wearsim_bin):
    # A measurement with pixels of 0.5 µm along x and 1 µm along y (every other row of a self-affine
    # surface), resampled onto 0.5 µm: `surface fit DIR/heights.npy` reads the native pixels in
    # DIR/import.json and fits the measured wavevectors only, as fit_surface with measured_pixel does.
    g = wearsim.generate_surface(
        256, length=128.0, hurst=0.8, lambda_lower=2.0, lambda_upper=16.0, rms_height=0.1, seed=3
    )
    Topography(g[:, ::2], (128.0, 128.0), unit="um").to_netcdf(tmp_path / "rect.nc")
    import_topography(tmp_path / "rect.nc", tmp_path / "out", resample=True)
    lx = json.loads((tmp_path / "out" / "import.json").read_text())["length"][0]
    cli = ["surface", "fit", tmp_path / "out" / "heights.npy", "--length", repr(lx), "--out", tmp_path / "fit"]
    done = subprocess.run([wearsim_bin, *cli], check=True, capture_output=True, text=True)
    assert "resampled onto finer pixels" in done.stderr and "import.json" in done.stderr
    record = json.loads((tmp_path / "fit" / "fit.json").read_text())
    assert "import.json" in record["measured_pixel_from"]
    assert record["fit"]["measured_pixel"] == pytest.approx([0.5e-6, 1e-6], rel=1e-9)
    h = np.load(tmp_path / "out" / "heights.npy")
    fit = wearsim.fit_surface(h, lx, measured_pixel=(0.5e-6, 1e-6))
    assert fit["hurst"] == pytest.approx(record["fit"]["hurst"], abs=1e-12)
    assert fit["rms_height"] == pytest.approx(record["fit"]["rms_height"], rel=1e-12)


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
    assert sorted(p.name for p in mine.iterdir()) == ["bottom.npy", "heights.npy", "import.json"]
    assert no_temporary_folders(tmp_path)
    # Nor one that is or holds the second map.
    Topography(self_affine(seed=4), (32.0, 32.0), unit="um").to_netcdf(tmp_path / "other.nc")
    with pytest.raises(ValueError, match="instrument file"):
        import_topography(tmp_path / "scan.nc", tmp_path / "other.nc", bottom=tmp_path / "other.nc", overwrite=True)
    assert (tmp_path / "other.nc").is_file()


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
    # The block's bottom body is the rotated map, as written.
    assert f'bottom = "{out}/bottom.npy"' in done.stdout and "rotated by 180° about its centre" in done.stdout
    bottom = np.load(tmp_path / "surfaces" / "bottom.npy")
    assert np.array_equal(bottom, np.load(out / "bottom.npy"))
    assert np.array_equal(bottom, np.load(out / "heights.npy")[::-1, ::-1])
    # A damaged instrument file: one line of error, nothing written.
    (tmp_path / "bad.x3p").write_bytes(b"PK\x03\x04 not a zip")
    bad = subprocess.run(
        [wearsim_bin, "surface", "import", tmp_path / "bad.x3p", "--out", tmp_path / "bad", "--python", sys.executable],
        capture_output=True,
        text=True,
    )
    assert bad.returncode != 0 and "Traceback" not in bad.stderr and not (tmp_path / "bad").exists()


def test_a_file_without_size_is_refused_with_the_way_to_give_it(tmp_path):
    # A text matrix or a .npy array: wearsim reads it without an import, given its side.
    (tmp_path / "plain.txt").write_text("1 2 3 4\n5 6 7 8\n9 10 11 12\n13 14 15 16\n")
    np.save(tmp_path / "plain.npy", self_affine())
    # A CSV matrix, which no reader of SurfaceTopography opens (its XYZ reader wants columns).
    np.savetxt(tmp_path / "plain.csv", self_affine(), delimiter=",")
    for plain in ("plain.txt", "plain.npy", "plain.csv"):
        with pytest.raises(ValueError, match=r"states no physical size, which wearsim reads without an import") as e:
            import_topography(tmp_path / plain, tmp_path / "out")
        assert "wearsim surface fit FILE --length L" in str(e.value) and "physical_sizes" not in str(e.value)
        assert not (tmp_path / "out").exists()


def test_without_a_second_map_the_bottom_body_is_the_map_rotated_by_180_degrees(tmp_path):
    g = self_affine()
    Topography(np.vstack([g, g[:1]]), (32.5, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    lines = []
    record = import_topography(tmp_path / "scan.nc", tmp_path / "out", say=lines.append)
    top, bottom = np.load(tmp_path / "out" / "heights.npy"), np.load(tmp_path / "out" / "bottom.npy")
    assert bottom.dtype == np.float64 and bottom.shape == top.shape == (64, 64)
    # h_b[i, j] = h[Nx−1−i, Ny−1−j], exactly: the measured heights rearranged, their sign kept.
    assert np.array_equal(bottom, top[::-1, ::-1])
    assert np.array_equal(np.sort(bottom, axis=None), np.sort(top, axis=None))
    # The 2D power spectrum (and so the lay direction) is the map's own: |ĥ_b(q)| = |ĥ(q)|.
    np.testing.assert_allclose(np.abs(np.fft.fft2(bottom)), np.abs(np.fft.fft2(top)), atol=1e-12 * np.abs(top).sum())
    # The composite surface is bottom + roll(top, s) along x. The same map for both bodies is perfectly
    # correlated at s = 0; the rotated copy no more at any s than two independent maps of this size are.
    assert correlation(top, top, 0) == pytest.approx(1.0)
    rotated = max(abs(correlation(bottom, top, s)) for s in range(64))
    h4 = wearsim.preprocess_surface(self_affine(seed=4))
    independent = max(abs(correlation(h4, top, s)) for s in range(64))
    assert rotated < 0.5 and independent < 0.5, (rotated, independent)
    # The block names both files; import.json and the printed lines say which rule made the bottom body.
    block = record["surface_toml"]
    assert f'top = "{tmp_path}/out/heights.npy"' in block
    assert f'bottom = "{tmp_path}/out/bottom.npy"  # the map rotated by 180° about its centre' in block
    on_disk = json.loads((tmp_path / "out" / "import.json").read_text())
    assert on_disk["bottom_map"] is None
    bodies = on_disk["bodies"]
    assert bodies["top"]["file"] == "heights.npy" and bodies["bottom"]["file"] == "bottom.npy"
    assert bodies["bottom"]["rule"] == "rotated-180"
    assert bodies["bottom"]["made_from"].startswith("the map rotated by 180° about its centre")
    scan = str((tmp_path / "scan.nc").resolve())
    assert bodies["bottom"]["source"] == bodies["top"]["source"] == on_disk["source"] == scan
    assert bodies["bottom"]["rms_height_m"] == pytest.approx(on_disk["rms_height_m"])
    text = "\n".join(lines)
    assert "bottom body: the map rotated by 180° about its centre" in text and "--bottom FILE2" in text
    assert "bottom.npy (bottom body)" in text


def test_a_second_map_is_imported_with_the_same_options_as_the_bottom_body(tmp_path):
    g, g4 = self_affine(), self_affine(seed=4)
    Topography(np.vstack([g, g[:1]]), (32.5, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    # The counter-body in nm (the same 0.5 µm pixels), tilted, with three unmeasured pixels.
    tilt = 5.0 * np.arange(64)[:, None]
    holes = np.ma.masked_array(g4 * 1e3 + tilt, mask=np.zeros((64, 64), bool))
    holes.mask[10:13, 20] = True
    Topography(holes, (32000.0, 32000.0), unit="nm").to_x3p(tmp_path / "other.x3p")
    # The options apply to both maps: the second's undefined pixels are refused without --fill.
    with pytest.raises(ValueError, match=r"other\.x3p: 3 of its 4096 pixels are undefined.*--fill harmonic"):
        import_topography(tmp_path / "scan.nc", tmp_path / "out", bottom=tmp_path / "other.x3p")
    assert not (tmp_path / "out").exists() and no_temporary_folders(tmp_path)
    lines = []
    record = import_topography(
        tmp_path / "scan.nc", tmp_path / "out", bottom=tmp_path / "other.x3p", fill="harmonic", say=lines.append
    )
    top, bottom = np.load(tmp_path / "out" / "heights.npy"), np.load(tmp_path / "out" / "bottom.npy")
    assert top.shape == bottom.shape == (64, 64)
    np.testing.assert_allclose(top, wearsim.preprocess_surface(g * 1e-6), atol=1e-12 * np.abs(top).max())
    # In metres, levelled, filled; away from the holes the counter-body's own heights.
    assert np.isfinite(bottom).all() and abs(np.polyfit(np.arange(64), bottom.mean(axis=1), 1)[0]) < 1e-12
    kept = ~holes.mask
    expected = wearsim.preprocess_surface(g4 * 1e-6)
    np.testing.assert_allclose(bottom[kept] - bottom[kept].mean(), expected[kept] - expected[kept].mean(), atol=2e-9)
    scan, other = str((tmp_path / "scan.nc").resolve()), str((tmp_path / "other.x3p").resolve())
    assert record["bottom_map"]["source"] == other
    assert record["bottom_map"]["format"] == "x3p" and record["bottom_map"]["undefined_pixels"] == 3
    assert record["bottom_map"]["fill"] == "harmonic"
    assert record["bottom_map"]["heights_grid"] == record["heights_grid"] == [64, 64]
    assert record["source"] == scan and record["cropped"] == {"from": [65, 64], "to": [64, 64]}
    bodies = json.loads((tmp_path / "out" / "import.json").read_text())["bodies"]
    assert bodies["bottom"]["rule"] == "second-map" and bodies["bottom"]["source"] == other
    assert bodies["bottom"]["made_from"] == f"the second map {other}"
    assert f'bottom = "{tmp_path}/out/bottom.npy"  # the second map "other.x3p"' in record["surface_toml"]
    text = "\n".join(lines)
    assert "top: read" in text and "bottom: read" in text and "bottom: filled 3 undefined pixels" in text
    assert f"bottom body: the second map {other}" in text
    # Without levelling, the second map's heights as they are, in metres (µm and nm, the same pixels).
    Topography(g4 * 1e3 + tilt, (32000.0, 32000.0), unit="nm").to_netcdf(tmp_path / "whole.nc")
    record = import_topography(tmp_path / "scan.nc", tmp_path / "raw", bottom=tmp_path / "whole.nc", detrend="none")
    np.testing.assert_allclose(np.load(tmp_path / "raw" / "bottom.npy"), (g4 * 1e3 + tilt) * 1e-9, rtol=1e-12)
    assert record["bottom_map"]["unit"] == "nm" and record["bottom_map"]["metres_per_unit"] == pytest.approx(1e-9)
    assert record["bottom_map"]["detrend"] == "none"


def test_a_second_map_on_another_grid_or_pixel_size_is_refused_naming_both(tmp_path):
    Topography(self_affine(), (32.0, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    Topography(self_affine(64, 48, seed=4), (32.0, 24.0), unit="um").to_netcdf(tmp_path / "narrow.nc")
    Topography(self_affine(seed=4), (64.0, 64.0), unit="um").to_netcdf(tmp_path / "coarse.nc")
    # An earlier import's folder stays as it was.
    import_topography(tmp_path / "scan.nc", tmp_path / "out")
    before = {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()}
    with pytest.raises(ValueError) as refused:
        import_topography(tmp_path / "scan.nc", tmp_path / "out", bottom=tmp_path / "narrow.nc")
    message = str(refused.value)
    assert "scan.nc gives 64×64 pixels of 5e-07 m" in message, message
    assert "narrow.nc (--bottom) gives 64×48 pixels of 5e-07 m" in message, message
    assert "crop both to 64×48 pixels" in message and "resample" not in message, message
    with pytest.raises(ValueError) as refused:
        import_topography(tmp_path / "scan.nc", tmp_path / "out", bottom=tmp_path / "coarse.nc")
    message = str(refused.value)
    assert "64×64 pixels of 5e-07 m" in message and "64×64 pixels of 1e-06 m" in message, message
    assert "resample one map onto the other's pixel size" in message and "crop" not in message, message
    # The same file twice, however spelt, would be the same map for both bodies.
    (tmp_path / "sub").mkdir()
    with pytest.raises(ValueError, match=r"perfectly correlated at offset 0.*rotated by 180°"):
        import_topography(tmp_path / "scan.nc", tmp_path / "out", bottom=tmp_path / "sub" / ".." / "scan.nc")
    with pytest.raises(FileNotFoundError, match="none.nc: no such file"):
        import_topography(tmp_path / "scan.nc", tmp_path / "out", bottom=tmp_path / "none.nc")
    assert {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()} == before
    assert no_temporary_folders(tmp_path)


def test_a_stop_while_the_bodies_are_written_leaves_the_earlier_folder(tmp_path, monkeypatch, capsys):
    Topography(self_affine(), (32.0, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    Topography(self_affine(seed=4), (32.0, 32.0), unit="um").to_netcdf(tmp_path / "other.nc")
    import_topography(tmp_path / "scan.nc", tmp_path / "out")
    before = {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()}
    save = np.save

    def stopped_at_the_bottom_body(path, array, *args, **kwargs):
        if str(path).endswith("bottom.npy"):
            raise KeyboardInterrupt  # what a stop signal raises (wearsim.measured's handler)
        return save(path, array, *args, **kwargs)

    monkeypatch.setattr(measured, "_stop_on_signals", lambda: None)
    monkeypatch.setattr(np, "save", stopped_at_the_bottom_body)
    argv = [str(tmp_path / "scan.nc"), str(tmp_path / "out"), "--bottom", str(tmp_path / "other.nc")]
    assert measured.main(argv) == 130
    assert "stopped by a signal; nothing was written" in capsys.readouterr().err
    assert {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir()} == before
    assert no_temporary_folders(tmp_path)
    monkeypatch.setattr(np, "save", save)
    assert measured.main(argv) == 0
    assert json.loads((tmp_path / "out" / "import.json").read_text())["bodies"]["bottom"]["rule"] == "second-map"


DI = Path(__file__).resolve().parents[2] / "examples" / "measured" / "di-3.di"


@pytest.mark.parametrize("pixels", [(1.0, 2.0), (1.0, 1.5), (1.0, 2.1875), (2.0, 1.0)])
def test_round_pixel_ratios_of_a_non_periodic_map_resample(tmp_path, pixels):
    # Pixels of 1 × 2 µm put a sample at (n − 1)·2e-6 m, which divided by 2e-6 exceeds n − 1 by one
    # unit in the last place: SurfaceTopography's linear interpolation refused it.
    px, py = pixels
    for nx, ny in ((52, 49), (34, 49), (70, 82)):
        x, y = np.arange(nx)[:, None] * px, np.arange(ny)[None, :] * py
        heights = 0.01 * x + 0.03 * y
        Topography(heights, (nx * px * 1e-6, ny * py * 1e-6), unit="m", periodic=False).to_x3p(tmp_path / "r.x3p")
        record = import_topography(tmp_path / "r.x3p", tmp_path / "out", resample=True, detrend="none")
        a = np.load(tmp_path / "out" / "heights.npy")
        p = min(px, py)
        assert record["resampled"]["pixel_size"] == pytest.approx(p * 1e-6)
        xs, ys = np.arange(a.shape[0])[:, None] * p, np.arange(a.shape[1])[None, :] * p
        np.testing.assert_allclose(a, 0.01 * xs + 0.03 * ys, rtol=1e-9, atol=1e-12)


def test_a_map_with_no_measured_pixel_is_refused_and_a_mostly_filled_one_warned_about(tmp_path):
    h = np.ma.masked_array(self_affine(), mask=np.ones((64, 64), bool))
    Topography(h, (32.0, 32.0), unit="nm").to_x3p(tmp_path / "none.x3p")
    with pytest.raises(ValueError, match=r"none of its 4096 pixels is measured"):
        import_topography(tmp_path / "none.x3p", tmp_path / "out", fill="harmonic")
    assert not (tmp_path / "out").exists()
    # Half of the map undefined: filled on request, with a warning giving the share, in import.json too.
    h.mask[:] = False
    h.mask[:, :32] = True
    Topography(h, (32.0, 32.0), unit="nm").to_x3p(tmp_path / "half.x3p")
    lines = []
    with pytest.warns(UserWarning, match=r"50 % of the map \(2048 of 4096 pixels\) was not measured"):
        record = import_topography(tmp_path / "half.x3p", tmp_path / "out", fill="harmonic", say=lines.append)
    assert record["undefined_share"] == pytest.approx(0.5) and len(record["warnings"]) == 1
    assert any(line.startswith("warning: ") and "invented" in line for line in lines)
    assert json.loads((tmp_path / "out" / "import.json").read_text())["undefined_share"] == pytest.approx(0.5)
    # A few filled pixels: no warning, the share recorded.
    h.mask[:] = False
    h.mask[3, 4] = True
    Topography(h, (32.0, 32.0), unit="nm").to_x3p(tmp_path / "one.x3p")
    record = import_topography(tmp_path / "one.x3p", tmp_path / "few", fill="harmonic")
    assert record["warnings"] == [] and record["undefined_share"] == pytest.approx(1 / 4096)


def test_maps_under_sixteen_pixels_a_side_are_refused_at_import(tmp_path):
    for shape in ((2, 2), (2, 64), (64, 14)):
        Topography(np.random.default_rng(0).normal(size=shape), shape, unit="um").to_netcdf(tmp_path / "s.nc")
        with pytest.raises(ValueError, match=r"at least 16 pixels a side"):
            import_topography(tmp_path / "s.nc", tmp_path / "out")
        assert not (tmp_path / "out").exists()
    # 16 × 16 (15 × 17 cropped to 14 × 16 would not be) imports.
    Topography(np.random.default_rng(0).normal(size=(16, 17)), (16, 17), unit="um").to_netcdf(tmp_path / "s.nc")
    assert import_topography(tmp_path / "s.nc", tmp_path / "out")["heights_grid"] == [16, 16]


def test_a_channel_that_is_not_heights_is_named_with_the_height_channels(tmp_path):
    with pytest.raises(ValueError) as e:
        import_topography(DI, tmp_path / "out", channel=2)
    text = str(e.value)
    assert "channel 2 ('Phase')" in text and "is not a height channel" in text, text
    assert "0 ('ZSensor'), 3 ('Height')" in text and "('nm', None)" not in text, text
    assert not (tmp_path / "out").exists()
    record = import_topography(DI, tmp_path / "out", channel=3)
    assert record["channel_name"] == "Height"


def test_a_damaged_or_unknown_file_is_said_in_one_line_before_every_readers_answer(tmp_path, capsys):
    data = DI.read_bytes()
    (tmp_path / "cut.di").write_bytes(data[: len(data) // 3])
    with pytest.raises(ValueError) as e:
        import_topography(tmp_path / "cut.di", tmp_path / "out")
    lines = str(e.value).splitlines()
    assert "looks damaged" in lines[0] and "DIReader" in lines[0] and "not large enough" in lines[0], lines[0]
    assert lines[1] == "every reader's answer:" and any("tried XYZReader" in line for line in lines[2:])
    # An empty file, and random bytes that only the elevation-tile reader takes: refused, with no
    # advice to give them a physical size.
    (tmp_path / "empty.dat").write_bytes(b"")
    with pytest.raises(ValueError, match=r"is empty \(0 bytes\)"):
        import_topography(tmp_path / "empty.dat", tmp_path / "out")
    (tmp_path / "noise.bin").write_bytes(np.random.default_rng(0).bytes(2 * 64 * 64))
    with pytest.raises(ValueError, match=r"only its reader of SRTM elevation tiles") as e:
        import_topography(tmp_path / "noise.bin", tmp_path / "out")
    assert "physical_sizes" not in str(e.value)
    assert not (tmp_path / "out").exists()
    # From the command line (`python -m wearsim.measured`, what `wearsim surface import` runs): the
    # first line of the error leads.
    assert measured.main([str(tmp_path / "cut.di"), str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "looks damaged" in err.splitlines()[0], err


def test_an_out_below_a_file_is_refused_in_words(tmp_path):
    Topography(self_affine(), (32.0, 32.0), unit="um").to_netcdf(tmp_path / "scan.nc")
    (tmp_path / "file.txt").write_text("keep")
    with pytest.raises(ValueError, match=r"file.txt, which is a file, not a folder"):
        import_topography(tmp_path / "scan.nc", tmp_path / "file.txt" / "sub")
    assert (tmp_path / "file.txt").read_text() == "keep"


def test_the_package_imports_its_measured_and_fields_modules(tmp_path):
    done = subprocess.run(
        [sys.executable, "-c", "import wearsim; print(wearsim.measured.import_topography, wearsim.fields)"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr


def test_the_contact_solver_takes_a_topography(tmp_path):
    g = self_affine()
    t = Topography(g, (32.0, 32.0), unit="um")
    h, lx = wearsim.heights_and_length(t)
    e_star, load = 1e11, 1e-3 * 1e11 * lx * lx
    direct = wearsim.solve_contact(h, load, effective_modulus=e_star, length=lx)
    via = wearsim.solve_contact(t, load, effective_modulus=e_star)
    np.testing.assert_array_equal(via.pressure, direct.pressure)
    solver = wearsim.ContactSolver(64, lx, e_star)
    np.testing.assert_array_equal(solver.solve(t, load).pressure, direct.pressure)
    with pytest.raises(ValueError, match="the solver's length"):
        wearsim.ContactSolver(64, 32.0, e_star).solve(t, load)
    np.testing.assert_array_equal(wearsim.composite_heights(t, t, 3), wearsim.composite_heights(h, h, 3))
