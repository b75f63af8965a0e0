"""`wearsim slide --save-fields`: the per-step fields file opens in xarray with its coordinates and
units, and its maps are those of `wearsim contact` at the same offset and of the run's series."""

import json
import subprocess

import numpy as np
import pandas as pd
import pytest

xr = pytest.importorskip("xarray")

RUN = """
units = "reduced"
[surface]
grid = [64, 48]
length = 1.0
hurst = 0.7
lambda_lower = 0.125
lambda_upper = 0.5
rms_height = 0.01
seed = 3
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.010
fracture_energies = [0.25e-6]
[sliding]
loads = [2e-3, 4e-3]
distance = 0.5
running_in = 0.25
step_running_in = 4
step = 1
"""


@pytest.fixture(scope="module")
def run(tmp_path_factory, wearsim_bin):
    d = tmp_path_factory.mktemp("fields")
    (d / "run.toml").write_text(RUN)
    subprocess.run(
        [wearsim_bin, "--quiet", "slide", d / "run.toml", "--out", d / "slide", "--save-fields", "--fields-every", "3"],
        check=True,
        capture_output=True,
    )
    return d


def test_the_fields_open_in_xarray_with_coordinates_and_units(run):
    ds = xr.open_zarr(run / "slide" / "fields.zarr")
    assert dict(ds.sizes) == {"load": 2, "s": 7, "x": 64, "y": 48}
    for name in ["pressure", "contact", "junctions"]:
        assert ds[name].dims == ("load", "s", "x", "y")
    assert ds.contact.dtype == bool and ds.junctions.dtype == np.uint32
    np.testing.assert_array_equal(ds["load"].values, [2e-3, 4e-3])
    # Every third step of the schedule: 0, 4, …, 16 px of running-in, then one pixel per step.
    schedule = pd.read_csv(run / "slide" / "series.csv").query("load == 2e-3")["s"].to_numpy()
    np.testing.assert_allclose(ds.s.values, schedule[::3])
    np.testing.assert_array_equal(ds.offset.values, np.rint(ds.s.values * 64).astype(int))
    np.testing.assert_allclose(ds.x.values, np.arange(64) / 64)
    assert ds.pressure.attrs["units"] == "E" and ds.s.attrs["units"] == "L" and ds["load"].attrs["units"] == "E L²"
    assert ds.attrs["units"] == "reduced" and ds.attrs["provenance"]["software"].startswith("wearsim")


def test_the_fields_are_the_contact_solutions_of_the_run(run, wearsim_bin):
    ds = xr.open_zarr(run / "slide" / "fields.zarr")
    series = pd.read_csv(run / "slide" / "series.csv")
    pm = 3 * np.sqrt(3) * 0.010
    for load_index, load in enumerate([2e-3, 4e-3]):
        for step in [0, 5]:
            offset = int(ds.offset.values[step])
            out = run / f"contact-{load_index}-{offset}"
            subprocess.run(
                [
                    wearsim_bin,
                    "contact",
                    run / "run.toml",
                    "--load",
                    str(load),
                    "--offset-px",
                    str(offset),
                    "--out",
                    out,
                ],
                check=True,
                capture_output=True,
            )
            p_contact = np.load(out / "pressure.npy")
            p_fields = ds.pressure.isel(load=load_index, s=step).values
            contact = ds.contact.isel(load=load_index, s=step).values
            assert p_fields.shape == p_contact.shape == (64, 48)
            # The run's solves stop once the contact map is settled (residual ≤ 1e-5), `contact`'s at
            # the tolerance (1e-8): pressures within 1e-3 p_m (measured: 1.1e-4 p_m at most here).
            assert np.abs(p_fields - p_contact).max() < 1e-3 * pm
            if step == 0:
                # Both start cold at s = 0: the same contact map, pixel for pixel.
                np.testing.assert_array_equal(contact, p_contact > 0)
            else:
                # The run warm-starts from the previous step.
                assert np.count_nonzero(contact != (p_contact > 0)) <= 2
            np.testing.assert_array_equal(contact, p_fields > 0)
            labels = ds.junctions.isel(load=load_index, s=step).values
            np.testing.assert_array_equal(labels > 0, contact)
            row = series[(series["load"] == load) & np.isclose(series["s"], ds.s.values[step])].iloc[0]
            assert len(np.unique(labels[labels > 0])) == row["junctions"]
            summary = json.loads((out / "summary.json").read_text())
            assert summary["surfaces"]["grid"] == [64, 48]


def test_the_fields_convert_to_cf_netcdf_that_another_reader_opens(run, wearsim_bin, tmp_path):
    netCDF4 = pytest.importorskip("netCDF4")
    pytest.importorskip("h5netcdf")
    import sys

    from wearsim.fields import to_netcdf

    store = run / "slide" / "fields.zarr"
    zarr_ds = xr.open_zarr(store)
    # Written by h5netcdf (Python API), read by the netCDF-C library (what MATLAB and ParaView use).
    path = to_netcdf(store, tmp_path / "fields.nc")
    with netCDF4.Dataset(path) as nc:
        assert nc.data_model == "NETCDF4" and nc.Conventions == "CF-1.8"
        assert "Brink" in nc.references and json.loads(nc.provenance)["software"].startswith("wearsim")
        assert nc.dimensions["x"].size == 64 and nc.dimensions["y"].size == 48
        assert nc["pressure"].dimensions == ("load", "s", "x", "y")
        assert nc["pressure"].units == "E" and nc["pressure"].long_name == "contact pressure"
        assert nc["x"].units == "L" and nc["x"].axis == "X" and nc["y"].axis == "Y"
        assert nc["load"].units == "E L^2"
        np.testing.assert_array_equal(nc["pressure"][:], zarr_ds.pressure.values)
        np.testing.assert_array_equal(nc["contact"][:], zarr_ds.contact.values.astype(np.int8))
        assert list(nc["contact"].flag_values) == [0, 1]
        np.testing.assert_array_equal(nc["junctions"][:], zarr_ds.junctions.values)
        np.testing.assert_allclose(nc["x"][:], np.arange(64) / 64)
    # xarray through the other engine decodes the same dataset.
    back = xr.open_dataset(path, engine="netcdf4")
    np.testing.assert_array_equal(back.offset.values, zarr_ds.offset.values)
    assert back.pressure.attrs["units"] == "E"
    back.close()
    # The CLI counterpart runs the same conversion in the given interpreter.
    out = tmp_path / "cli.nc"
    subprocess.run(
        [wearsim_bin, "fields", "to-netcdf", store, out, "--python", sys.executable], check=True, capture_output=True
    )
    with netCDF4.Dataset(out) as nc:
        np.testing.assert_array_equal(nc["pressure"][:], zarr_ds.pressure.values)
    # Not a store: a one-line error, no file.
    bad = subprocess.run(
        [wearsim_bin, "fields", "to-netcdf", tmp_path, tmp_path / "x.nc"], capture_output=True, text=True
    )
    assert bad.returncode != 0 and "not a fields store" in bad.stderr and not (tmp_path / "x.nc").exists()
    # An interpreter without the package: the error says what to install.
    missing = subprocess.run(
        [wearsim_bin, "fields", "to-netcdf", store, tmp_path / "y.nc", "--python", "false"],
        capture_output=True,
        text=True,
    )
    assert missing.returncode != 0 and 'pip install "wearsim[fields]"' in missing.stderr


def test_the_conversion_finishes_when_its_output_pipes_are_closed(run, wearsim_bin, tmp_path):
    # `wearsim fields to-netcdf … | head -0`: the printing ends, not the conversion or its status.
    pytest.importorskip("h5netcdf")
    import sys

    store = run / "slide" / "fields.zarr"
    for name, command in [
        ("module.nc", [sys.executable, "-m", "wearsim.fields", "to-netcdf"]),
        ("cli.nc", [wearsim_bin, "fields", "to-netcdf", "--python", sys.executable]),
    ]:
        out = tmp_path / name
        child = subprocess.Popen([*command, store, out], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        child.stdout.close()
        child.stderr.close()
        assert child.wait(timeout=300) == 0, name
        assert out.is_file(), name


def test_the_conversion_never_writes_over_a_file_it_did_not_make(run, wearsim_bin, tmp_path):
    import os
    import sys

    pytest.importorskip("h5netcdf")
    from wearsim.fields import to_netcdf

    store = run / "slide" / "fields.zarr"
    summary = run / "slide" / "summary.json"
    before = summary.read_bytes()
    # Another command's output, under two spellings: refused without --overwrite, left whole.
    for target in (summary, run / "slide" / "." / "summary.json"):
        with pytest.raises(FileExistsError, match="overwrite"):
            to_netcdf(store, target)
        cli = subprocess.run(
            [wearsim_bin, "fields", "to-netcdf", store, target, "--python", sys.executable],
            capture_output=True,
            text=True,
        )
        assert cli.returncode != 0 and "--overwrite" in cli.stderr, cli.stderr
    assert summary.read_bytes() == before
    with pytest.raises(ValueError, match="inside the fields store"):
        to_netcdf(store, store / "pressure" / "x.nc", overwrite=True)
    # Its own output is replaced; the file gets the umask's permissions, not 0600.
    out = tmp_path / "fields.nc"
    old = os.umask(0o022)
    try:
        to_netcdf(store, out)
        to_netcdf(store, out)
    finally:
        os.umask(old)
    assert out.stat().st_mode & 0o777 == 0o644
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_the_fields_extra_installs_every_module_the_conversion_imports(root, wearsim_bin):
    import re
    import tomllib

    extra = tomllib.loads((root / "pyproject.toml").read_text())["project"]["optional-dependencies"]["fields"]
    names = {re.split(r"[<>=\[ ]", r)[0].lower() for r in extra}
    # What `wearsim fields to-netcdf` checks before it runs the conversion.
    source = (root / "crates" / "wearsim-cli" / "src" / "commands" / "fields.rs").read_text()
    probe = re.search(r'"wearsim\.fields",\s*&\[([^\]]*)\]', source).group(1)
    needed = {m.strip().strip('"') for m in probe.split(",") if m.strip()}
    assert {"xarray", "h5netcdf"} <= needed, needed
    assert needed <= names, needed - names
