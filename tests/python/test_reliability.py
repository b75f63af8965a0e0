"""Reliability from Python: a failing study job raises the kind of its cause once the others are
saved; under-resolved or undefined results warn; absurd thread counts are capped; odd material
names survive the tables."""

import warnings

import pytest
import wearsim

STUDY = """
[surface]
grid = 64
lambda_lower = 0.125
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2]
[[materials]]
name = "steel, \\"hard\\""
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]
[contact]
max_iterations = {max_iterations}
[sliding]
loads = [5e-4, 1e-3]
distance = 0.25
running_in = 0.125
"""


def test_a_study_job_that_does_not_converge_raises_not_converged_after_the_others_finish(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(STUDY.format(max_iterations="[1, 20000]"))
    out = tmp_path / "out"
    with pytest.raises(wearsim.NotConvergedError, match="4 of 8 jobs failed"):
        wearsim.study.run(path, out=out)
    assert len(list((out / "jobs").glob("job-*.json"))) == 4


def test_odd_material_names_keep_the_tables_whole(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(STUDY.format(max_iterations="20000"))
    tidy = wearsim.study.run(path, out=tmp_path / "out")
    assert len(tidy) == 4 and (tidy["material"] == 'steel, "hard"').all()
    _, aggregated = wearsim.study.collect(tmp_path / "out")
    assert (aggregated["surface_pairs"] == 2).all()


def test_undefined_and_under_resolved_results_warn():
    top, bottom = wearsim.generate_pair(64, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005, seed=1)
    # d* far beyond the box: no particle forms after running-in.
    material = wearsim.Material(1.0, 0.3, 0.01, [1e-2])
    with pytest.warns(wearsim.ResolutionWarning, match="no particle formed"):
        series, summary = wearsim.slide(top, bottom, material, [5e-4])
    result = summary["results"][0]
    assert result["wear_rate"] == 0.0 and result["wear_rate_r2"] is None
    assert any("no particle formed" in w for w in summary["warnings"])


def test_absurd_thread_counts_are_capped_and_zero_is_refused():
    top, bottom = wearsim.generate_pair(64, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005, seed=1)
    material = wearsim.Material(1.0, 0.3, 0.01, [0.5e-6])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        wearsim.slide(top, bottom, material, [1e-3], threads=3000)
    assert any("four per core" in str(w.message) for w in caught)
    with pytest.raises(ValueError, match="threads"):
        wearsim.slide(top, bottom, material, [1e-3], threads=0)


def test_materials_run_files_and_solvers_pickle_and_deep_copy(tmp_path):
    import copy
    import pickle

    import numpy as np

    material = wearsim.Material(1.0, 0.3, 0.01, [0.25e-6, 1e-6], 2.5)
    path = tmp_path / "run.toml"
    path.write_text(
        "[surface]\ngrid = 64\nlambda_lower = 0.125\nlambda_upper = 0.25\nrms_height = 0.005\nseed = 1\n"
        "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-6]\n"
    )
    run = wearsim.RunFile(path)
    solver = wearsim.ContactSolver(64, 1.0, 1.0, tolerance=1e-9)
    top, bottom = wearsim.generate_pair(64, lambda_lower=0.125, lambda_upper=0.25, rms_height=0.005, seed=1)
    expected = solver.solve(top - bottom, 1e-3).pressure
    for clone in (pickle.loads(pickle.dumps(material)), copy.deepcopy(material), copy.copy(material)):
        assert repr(clone) == repr(material) and clone.critical_diameters == material.critical_diameters
    for clone in (pickle.loads(pickle.dumps(run)), copy.deepcopy(run)):
        assert clone.material.critical_diameters == run.material.critical_diameters
    for clone in (pickle.loads(pickle.dumps(solver)), copy.deepcopy(solver)):
        assert clone.shape == (64, 64) and clone.tolerance == 1e-9
        np.testing.assert_array_equal(clone.solve(top - bottom, 1e-3).pressure, expected)


def test_one_solver_used_from_several_threads_solves_one_call_at_a_time():
    from concurrent.futures import ThreadPoolExecutor

    import numpy as np

    solver = wearsim.ContactSolver(128, 1.0, 1.0)
    top, bottom = wearsim.generate_pair(128, lambda_lower=0.0625, lambda_upper=0.25, rms_height=0.005, seed=2)
    loads = [5e-4, 1e-3, 2e-3, 4e-3] * 2
    alone = [solver.solve(top - bottom, f).pressure for f in loads]
    with ThreadPoolExecutor(4) as pool:
        together = list(pool.map(lambda f: solver.solve(top - bottom, f).pressure, loads))
    for a, b in zip(alone, together):
        np.testing.assert_array_equal(a, b)


def test_grid_sizes_and_pixel_sizes_out_of_range_are_refused_in_words():
    import numpy as np

    for grid in (-4, (64, -2), 0):
        with pytest.raises(ValueError, match="`grid`") as e:
            wearsim.ContactSolver(grid, 1.0, 1.0)
        assert "convert" not in str(e.value)
    contact = np.zeros((16, 16), dtype=bool)
    contact[3:6, 3:6] = True
    for size in (float("inf"), float("nan"), 0.0, -1.0):
        with pytest.raises(ValueError, match="`pixel_size`"):
            wearsim.label_junctions(contact, pixel_size=size)


MEMORY_SCRIPT = """
import sys
import numpy as np
import wearsim

rng = np.random.default_rng(1)
top, bottom = (1e-3 * rng.standard_normal((2048, 2048)) for _ in range(2))
material = wearsim.Material(1.0, 0.3, 0.01, [1e-6])
for name, run in [
    ("slide", lambda: wearsim.slide(top, bottom, material, [1e-3], length=1.0, distance=0.002, running_in=0.001,
                                    step_running_in=1, step=1)),
    ("RunFile.slide", lambda: wearsim.RunFile(sys.argv[1]).slide()),
]:
    try:
        run()
        print(name, "ran")
    except Exception as e:
        print(name, type(e).__name__, str(e).replace("\\n", " "))
"""


def test_slide_refuses_a_run_too_large_for_the_memory_with_the_clis_message(tmp_path, wearsim_bin):
    # Slurm's --mem=100M: a 2048² sliding run needs about 430 MiB, its surface pair alone about 140
    # MiB. The library's sliding run checks the memory for every front end before the surfaces are
    # made, so Python refuses it (arrays or a run file) in the CLI's words, not as the pair's.
    import os
    import subprocess
    import sys

    run = tmp_path / "run.toml"
    run.write_text(
        "[surface]\ngrid = 2048\nlambda_lower = 0.0078125\nlambda_upper = 0.25\nrms_height = 0.005\n"
        "[material]\nyoungs_modulus = 1.0\npoisson_ratio = 0.3\nshear_strength = 0.01\nfracture_energies = [1e-6]\n"
        "[sliding]\nloads = [1e-3]\ndistance = 0.1\nrunning_in = 0.05\n"
    )
    env = {**os.environ, "SLURM_MEM_PER_NODE": "100"}
    cli = subprocess.run(
        [wearsim_bin, "slide", str(run), "--out", str(tmp_path / "o")], env=env, capture_output=True, text=True
    )
    assert cli.returncode == 1, cli.stderr
    (line,) = [text for text in cli.stderr.splitlines() if text.startswith("error:") and "needs about" in text]
    message = line[line.index("a sliding run on 2048×2048 pixels") :]
    assert "SLURM_MEM_PER_NODE" in message
    py = subprocess.run(
        [sys.executable, "-c", MEMORY_SCRIPT, str(run)], env=env, capture_output=True, text=True, timeout=120
    )
    assert py.returncode == 0, py.stderr
    lines = py.stdout.splitlines()
    assert [text.split(" ")[0] for text in lines] == ["slide", "RunFile.slide"], py.stdout
    for text in lines:
        assert "ran" != text.split(" ")[1], py.stdout
        assert text.endswith(message), f"{text}\n{message}"
    assert not (tmp_path / "o").exists()
