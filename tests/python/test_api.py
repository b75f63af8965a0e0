"""The Python API (`import wearsim`): round trips against the CLI, physics checks, errors raised as
Python exceptions with the library's messages, GIL release and Ctrl-C."""

import inspect
import json
import re
import signal
import subprocess
import sys
import textwrap
import threading
import time
import warnings

import numpy as np
import pandas as pd
import pytest
import wearsim

RUN = """
units = "reduced"
[surface]
grid = 64
length = 1.0
hurst = 0.7
lambda_lower = 0.125
lambda_upper = 0.25
rms_height = 0.005
seed = 7
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.25e-6, 1e-6]
[contact]
tolerance = 1e-8
[sliding]
loads = [5e-4, 1e-3]
distance = 0.5
running_in = 0.25
"""

SURFACE = dict(lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005)


@pytest.fixture()
def run_file(tmp_path):
    path = tmp_path / "run.toml"
    path.write_text(RUN)
    return path


def test_surfaces_equal_the_cli_pair(tmp_path, run_file, wearsim_bin):
    subprocess.run(
        [wearsim_bin, "surface", str(run_file), "--out", str(tmp_path / "s")], check=True, capture_output=True
    )
    top, bottom = wearsim.generate_pair(64, seed=7, **SURFACE)
    np.testing.assert_array_equal(top, np.load(tmp_path / "s" / "top.npy"))
    np.testing.assert_array_equal(bottom, np.load(tmp_path / "s" / "bottom.npy"))
    stats = wearsim.surface_statistics(top)
    assert abs(stats["rms_height"] - 0.005) < 1e-15
    assert stats["grid"] == 64 and stats["pixel_size"] == 1 / 64
    q, c = wearsim.radial_psd(top)
    assert q.shape == c.shape and np.all(q > 0)
    # Composite height: bottom + roll(top, offset) along x.
    np.testing.assert_array_equal(wearsim.composite_heights(top, bottom, 5), bottom + np.roll(top, 5, axis=0))
    run_top, run_bottom = wearsim.load_run(run_file).surfaces()
    np.testing.assert_array_equal(run_top, top)
    np.testing.assert_array_equal(run_bottom, bottom)


def test_material_derived_quantities():
    m = wearsim.Material(1.0, 0.3, 0.01, [0.5e-6])
    assert m.flow_pressure == pytest.approx(3 * np.sqrt(3) * 0.01, rel=1e-15)
    mu = 1.0 / (2 * 1.3)
    assert m.critical_diameters[0] == pytest.approx(3 * 0.5e-6 * 2 * mu / 0.01**2, rel=1e-14)
    assert m.effective_modulus() == pytest.approx(1 / (1 - 0.09))
    assert m.effective_modulus("composite") == pytest.approx(0.5 / (1 - 0.09))


def test_contact_solve_balance_warm_start_and_cli(tmp_path, run_file, wearsim_bin):
    top, bottom = wearsim.generate_pair(64, seed=7, **SURFACE)
    m = wearsim.Material(1.0, 0.3, 0.01)
    solver = wearsim.ContactSolver(64, 1.0, m.effective_modulus())
    h = wearsim.composite_heights(top, bottom, 0)
    cold = solver.solve(h, 1e-3, flow_pressure=m.flow_pressure)
    assert cold.pressure.mean() == pytest.approx(1e-3, rel=1e-12)
    assert cold.pressure.max() <= m.flow_pressure and cold.pressure.min() >= 0.0
    assert cold.residual <= cold.tolerance and cold.plastic_pixels > 0
    assert cold.contact_pixels == np.count_nonzero(cold.contact)
    # Same solution as `wearsim contact` on the run file.
    out = tmp_path / "c"
    subprocess.run(
        [wearsim_bin, "contact", str(run_file), "--load", "1e-3", "--out", str(out)], check=True, capture_output=True
    )
    np.testing.assert_array_equal(cold.pressure, np.load(out / "pressure.npy"))
    summary = json.loads((out / "summary.json").read_text())
    assert summary["iterations"] == cold.iterations
    # Warm start from the converged field: nothing to do.
    warm = solver.solve(h, 1e-3, flow_pressure=m.flow_pressure, initial_pressure=cold.pressure)
    assert warm.iterations <= 1
    np.testing.assert_allclose(warm.pressure, cold.pressure, atol=1e-12)
    # Elastic: the displacement matches the heights (up to the rigid-body shift) inside the contact.
    elastic = solver.solve(h, 1e-3)
    u = solver.displacement(elastic.pressure)
    gap = u - h
    inside = elastic.contact
    assert np.ptp(gap[inside]) < 1e-6 * h.std()


def test_junctions_and_static_model():
    contact = np.zeros((16, 16), dtype=bool)
    contact[0, 0] = contact[15, 0] = True  # one junction across the periodic boundary
    contact[5:8, 5:8] = True  # 9 pixels
    j = wearsim.label_junctions(contact, pixel_size=0.5)
    assert j.count == 2
    assert sorted(j.pixels.tolist()) == [2, 9]
    assert j.labels[0, 0] == j.labels[15, 0] != j.labels[6, 6]
    assert (j.labels == -1).sum() == 256 - 11
    np.testing.assert_allclose(j.areas, j.pixels * 0.25)
    table = j.table()
    assert list(table.columns) == ["pixels", "area", "diameter", "volume", "wraps_x", "wraps_y"]
    assert not j.wrapping.any()
    # d* between the two junction diameters: only the 9-pixel junction counts.
    d_star = 0.5 * (j.diameters.min() + j.diameters.max())
    w = wearsim.static_wear(j, d_star)
    assert w["wear_coefficient"] == pytest.approx(9 / 11)
    assert w["wear_rate_over_omega"] == pytest.approx(9 / 11 * 11 * 0.25)
    # A pressure field is a contact map too.
    assert wearsim.label_junctions(contact * 2.5).count == 2


def test_a_junction_around_the_periodic_box_is_flagged_and_warned_about():
    # Full contact: one junction that closes on itself both ways; it is no particle (d = 1.128 L).
    with pytest.warns(RuntimeWarning, match="wrap the periodic box"):
        full = wearsim.label_junctions(np.ones((64, 64), bool))
    assert full.count == 1 and full.wraps.tolist() == [[True, True]]
    # A band along y (a full row) wraps along y only; beside it an ordinary junction.
    band = np.zeros((16, 12), bool)
    band[3, :] = True
    band[8:10, 4:6] = True
    with pytest.warns(RuntimeWarning, match=r"junction\(s\) \[0\]"):
        j = wearsim.label_junctions(band)
    assert j.wraps.tolist() == [[False, True], [False, False]]
    assert j.table()["wraps_y"].tolist() == [True, False]
    # A row with a gap spans the box without closing: an ordinary junction, no warning.
    band[3, 7] = False
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert not wearsim.label_junctions(band).wrapping.any()


def test_a_contact_map_with_undefined_pixels_is_refused_as_the_cli_refuses_it(tmp_path, wearsim_bin):
    pressure = np.zeros((8, 8))
    pressure[2:4, 2:4] = 1.0
    pressure[6, 5] = np.nan
    with pytest.raises(ValueError, match=r"NaN at \(6, 5\)"):
        wearsim.label_junctions(pressure)
    np.save(tmp_path / "map.npy", pressure)
    cli = subprocess.run(
        [wearsim_bin, "junctions", str(tmp_path / "map.npy"), "--out", str(tmp_path / "j")], capture_output=True
    )
    assert cli.returncode != 0 and b"NaN at (6, 5)" in cli.stderr
    # A masked pixel is as undefined; a mask with nothing masked is an ordinary map.
    masked = np.ma.masked_invalid(pressure)
    with pytest.raises(ValueError, match="1 masked pixel"):
        wearsim.label_junctions(masked)
    assert wearsim.label_junctions(np.ma.masked_array(pressure[:6], mask=False)).count == 1


def test_slide_equals_the_cli(tmp_path, run_file, wearsim_bin):
    out = tmp_path / "slide"
    subprocess.run([wearsim_bin, "slide", str(run_file), "--out", str(out)], check=True, capture_output=True)
    cli_series = pd.read_csv(out / "series.csv")
    cli_summary = json.loads((out / "summary.json").read_text())
    run = wearsim.load_run(run_file)
    series, summary = run.slide()
    assert list(series.columns) == wearsim.wear.SERIES_COLUMNS
    for column in cli_series.columns:
        np.testing.assert_allclose(series[column].to_numpy(), cli_series[column].to_numpy(), rtol=1e-6, err_msg=column)

    def key(r):
        return (r["load"], r["fracture_energy"])

    for a, b in zip(sorted(summary["results"], key=key), sorted(cli_summary["results"], key=key)):
        # Undefined results (None: N*'s growth at the lowest load, …) are undefined in both.
        undefined = {k for k, v in b.items() if v is None}
        assert {k for k, v in a.items() if v is None} == undefined
        defined = {k: v for k, v in a.items() if k not in undefined}
        assert defined == pytest.approx({k: v for k, v in b.items() if k not in undefined}, rel=1e-12, nan_ok=True)
    assert summary["inputs"] == cli_summary["inputs"]
    # The array API on the same surfaces and material gives the same series and results.
    top, bottom = run.surfaces()
    arrays_series, arrays_summary = wearsim.slide(top, bottom, run.material, run.loads)
    pd.testing.assert_frame_equal(arrays_series, series)
    assert arrays_summary["results"] == summary["results"]
    # The thread count changes nothing.
    one_thread, _ = wearsim.slide(top, bottom, run.material, run.loads, threads=1)
    pd.testing.assert_frame_equal(one_thread, series)
    # Bookkeeping invariants: V and N*₊ never decrease within a load and fracture energy.
    for _, g in series.groupby(["load", "fracture_energy"]):
        assert np.all(np.diff(g["volume"]) >= 0) and np.all(np.diff(g["n_formed"]) >= 0)
        assert np.all(g["n_shrunk"] == g["n_formed"] - g["n_critical"])


def test_slide_defaults_are_the_library_constants(tmp_path):
    # The Python signatures name the library's constants ...
    schedule = {
        "connectivity": wearsim.DEFAULT_CONNECTIVITY,
        "distance": wearsim.DEFAULT_DISTANCE,
        "running_in": wearsim.DEFAULT_RUNNING_IN,
        "step_running_in": wearsim.DEFAULT_STEP_RUNNING_IN,
        "step": wearsim.DEFAULT_STEP,
    }
    parameters = inspect.signature(wearsim.slide).parameters
    for name, constant in schedule.items():
        assert parameters[name].default == constant, name
    assert inspect.signature(wearsim.label_junctions).parameters["connectivity"].default == wearsim.DEFAULT_CONNECTIVITY
    # ... which are the paper's schedule (§3) and 4-connected junctions ...
    assert schedule == {"connectivity": 4, "distance": 0.5, "running_in": 0.25, "step_running_in": 4, "step": 1}
    # ... and what a run file that leaves them out gets.
    path = tmp_path / "defaults.toml"
    path.write_text(
        "[surface]\ngrid = 32\nlambda_lower = 0.125\nlambda_upper = 0.5\nrms_height = 0.01\n"
        "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n"
        "fracture_energies = [0.25e-6]\n[sliding]\nloads = [2e-3]\n"
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", wearsim.ResolutionWarning)
        _, summary = wearsim.load_run(path).slide()
    inputs = summary["inputs"]
    assert inputs["contact"]["connectivity"] == wearsim.DEFAULT_CONNECTIVITY
    # The particle rule and the device are the library's defaults, and recorded.
    assert parameters["particle_rule"].default == wearsim.DEFAULT_PARTICLE_RULE == wearsim.wear.PARTICLE_RULES[0]
    assert inputs["sliding"]["particle_rule"] == wearsim.DEFAULT_PARTICLE_RULE
    assert inputs["contact"]["device"] == parameters["device"].default == "cpu"
    assert {k: inputs["sliding"][k] for k in schedule if k != "connectivity"} == {
        k: v for k, v in schedule.items() if k != "connectivity"
    }


def test_a_particle_rule_takes_its_parameters_from_a_mapping_a_string_or_a_run_file(tmp_path):
    pair = wearsim.generate_pair(32, lambda_lower=0.125, lambda_upper=0.5, rms_height=0.01, seed=3)
    material = wearsim.Material(1.0, 0.3, 0.01, [0.25e-6])
    recorded = "interacting(reach=2, particle=hull)"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", wearsim.ResolutionWarning)
        by_mapping = wearsim.slide(*pair, material, [2e-3], particle_rule={"name": "interacting", "reach": 2})
        by_name = wearsim.slide(*pair, material, [2e-3], particle_rule="interacting(reach=2)")
        path = tmp_path / "interacting.toml"
        path.write_text(
            "[surface]\ngrid = 32\nlambda_lower = 0.125\nlambda_upper = 0.5\nrms_height = 0.01\nseed = 3\n"
            "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\n"
            "fracture_energies = [0.25e-6]\n[sliding]\nloads = [2e-3]\n"
            '[sliding.particle_rule]\nname = "interacting"\nreach = 2\n'
        )
        run = wearsim.load_run(path)
    assert by_mapping[1]["inputs"]["sliding"]["particle_rule"] == recorded == run.particle_rule
    assert by_name[1]["inputs"]["sliding"]["particle_rule"] == recorded
    assert by_mapping[0].equals(by_name[0])
    assert "interacting" in wearsim.wear.PARTICLE_RULES
    with pytest.raises(ValueError, match=re.escape("sliding.particle_rule.reach")):
        wearsim.slide(*pair, material, [2e-3], particle_rule={"name": "interacting", "reach": -1})
    with pytest.raises(ValueError, match="neither a rule's name nor a mapping"):
        wearsim.slide(*pair, material, [2e-3], particle_rule={"reach": 2})


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: wearsim.Material(-1.0, 0.3, 0.01), "invalid `youngs_modulus`"),
        (lambda: wearsim.Material(1.0, 0.6, 0.01), "invalid `poisson_ratio`"),
        (lambda: wearsim.ContactSolver(63, 1.0, 1.0), "invalid `grid`"),
        (
            lambda: wearsim.generate_surface(64, lambda_lower=0.01, lambda_upper=0.25, rms_height=0.005),
            "invalid `lambda_lower`",
        ),
        (lambda: wearsim.solve_contact(np.zeros((32, 15)), 1e-3, effective_modulus=1.0), "(along y)"),
        (
            lambda: wearsim.slide(
                np.zeros((32, 16)), np.zeros((32, 32)), wearsim.Material(1, 0.3, 0.01, [1e-6]), [1e-3]
            ),
            "shape 32×32 differs from the top's 32×16",
        ),
        (
            lambda: wearsim.solve_contact(np.zeros((32, 32)), 0.1, effective_modulus=1.0, flow_pressure=0.05),
            "load cannot be carried",
        ),
        (lambda: wearsim.label_junctions(np.ones((8, 8)), connectivity=6), "invalid `connectivity`"),
        (lambda: wearsim.surface_statistics(np.full((16, 16), np.nan)), "NaN"),
        (
            lambda: wearsim.slide(np.zeros((32, 32)), np.zeros((32, 32)), wearsim.Material(1, 0.3, 0.01), [1e-3]),
            "fracture_energies",
        ),
        (
            lambda: wearsim.slide(np.zeros((32, 32)), np.zeros((32, 32)), wearsim.Material(1, 0.3, 0.01, [1e-6]), []),
            "invalid `loads`",
        ),
        (
            lambda: wearsim.slide(
                np.zeros((32, 32)), np.zeros((32, 32)), wearsim.Material(1, 0.3, 0.01, [1e-6]), [1e-3], device="gpu"
            ),
            "invalid `device`",
        ),
        (
            lambda: wearsim.slide(
                np.zeros((32, 32)),
                np.zeros((32, 32)),
                wearsim.Material(1, 0.3, 0.01, [1e-6]),
                [1e-3],
                particle_rule="sometimes",
            ),
            "invalid `particle_rule`",
        ),
    ],
)
def test_bad_input_raises_value_error_naming_the_field(call, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        call()


def test_arguments_of_the_wrong_kind_name_the_argument_and_the_fix():
    spectrum = dict(lambda_lower=0.0625, lambda_upper=0.25, rms_height=0.005)
    # A float grid was a multi-line enum extraction failure; a negative seed an OverflowError.
    for grid in (64.0, "64", (64, 32, 16), 0, True):
        with pytest.raises(ValueError, match=r"invalid `grid`: .* \(e\.g\. 64\)"):
            wearsim.generate_pair(grid, **spectrum)
    for seed in (-1, 2**64, 1.5):
        with pytest.raises(ValueError, match=r"invalid `seed`: .*from 0 to 2\*\*64 - 1"):
            wearsim.generate_surface(64, seed=seed, **spectrum)
        with pytest.raises(ValueError, match="invalid `seed`"):
            wearsim.generate_pair(64, seed=seed, **spectrum)
    # A scalar where a list is needed: named, with the list to give.
    top, bottom = wearsim.generate_pair(32, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005)
    with pytest.raises(TypeError, match=r"invalid `loads`: 0\.001 is one value.*\[0\.001\]"):
        wearsim.slide(top, bottom, wearsim.Material(1, 0.3, 0.01, [1e-6]), 1e-3)
    largest = wearsim.generate_surface((32, 16), seed=2**64 - 1, lambda_lower=0.125, lambda_upper=0.25, rms_height=5e-3)
    assert largest.shape == (32, 16)


def test_errors_of_files_and_convergence(tmp_path):
    with pytest.raises(OSError, match="missing.toml"):
        wearsim.load_run(tmp_path / "missing.toml")
    (tmp_path / "typo.toml").write_text(RUN.replace("hurst", "hurts"))
    with pytest.raises(ValueError, match="hurts"):
        wearsim.load_run(tmp_path / "typo.toml")
    top, bottom = wearsim.generate_pair(64, seed=1, **SURFACE)
    with pytest.raises(wearsim.NotConvergedError, match="did not converge"):
        wearsim.solve_contact(top + bottom, 1e-3, effective_modulus=1.0, max_iterations=1, tolerance=1e-14)
    assert issubclass(wearsim.NotConvergedError, wearsim.WearsimError)


def test_progress_callback_and_its_exceptions():
    top, bottom = wearsim.generate_pair(128, seed=3, lambda_lower=16 / 128, lambda_upper=0.25, rms_height=0.005)
    m = wearsim.Material(1.0, 0.3, 0.01, [1e-6])
    calls = []
    series, _ = wearsim.slide(top, bottom, m, [5e-4, 1e-3], progress=lambda done, total: calls.append((done, total)))
    steps = len(series)
    assert calls and calls[-1] == (steps, steps)
    assert all(a[0] < b[0] for a, b in zip(calls, calls[1:])) and all(t == steps for _, t in calls)

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop(f"stopped at {done}/{total}")

    with pytest.raises(Stop, match="stopped at"):
        wearsim.slide(top, bottom, m, [5e-4, 1e-3, 2e-3], distance=1.0, running_in=0.5, progress=stop)
    with pytest.raises(ValueError, match="invalid `progress`"):
        wearsim.slide(top, bottom, m, [1e-3], progress="yes")


def test_long_calls_release_the_gil():
    top, bottom = wearsim.generate_pair(256, seed=3, lambda_lower=16 / 256, lambda_upper=0.25, rms_height=0.005)
    m = wearsim.Material(1.0, 0.3, 0.01, [1e-6])
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    wearsim.slide(top, bottom, m, [1e-3], distance=0.05, running_in=0.02)
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    during = [t for t in ticks if start <= t <= start + elapsed]
    # The Python thread kept running during the slide (it would get no tick if the GIL were held).
    assert elapsed > 0.05 and len(during) >= 0.3 * elapsed / 0.005


def test_ctrl_c_interrupts_a_slide(tmp_path):
    script = tmp_path / "long.py"
    script.write_text(
        textwrap.dedent(
            """
            import signal, sys, wearsim
            # Ctrl-C raises KeyboardInterrupt, as in a Python started from a terminal, even when this
            # test runs in a background job (which inherits SIGINT as ignored, so Python leaves it so).
            signal.signal(signal.SIGINT, signal.default_int_handler)
            top, bottom = wearsim.generate_pair(256, seed=3, lambda_lower=16 / 256, lambda_upper=0.25, rms_height=0.005)
            m = wearsim.Material(1.0, 0.3, 0.01, [1e-6])
            print("sliding", flush=True)
            try:
                wearsim.slide(top, bottom, m, [1e-4, 2e-4, 5e-4, 1e-3], distance=1.0, running_in=0.5)
            except KeyboardInterrupt:
                print("interrupted", flush=True)
                sys.exit(3)
            print("finished", flush=True)
            """
        )
    )
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "sliding"
    time.sleep(1.0)
    sent = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    assert proc.returncode == 3, out
    assert "interrupted" in out
    # It stops within a solver iteration or two, not at the end of the run (minutes).
    assert time.perf_counter() - sent < 5.0
