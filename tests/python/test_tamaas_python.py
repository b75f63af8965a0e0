"""The tamaas cross-checks from Python: the contact solver (`wearsim.ContactSolver`) against tamaas
`KatoSaturated` and `PolonskyKeerRey`, and `wearsim.label_junctions` against tamaas `FloodFill`, on
the same arrays. Skipped, visibly, only where tamaas cannot be imported."""

import numpy as np
import pytest
import wearsim

tm = pytest.importorskip("tamaas", reason="tamaas not installed: pip install tamaas")
from tamaas_helpers import same_partition, tamaas_labels, tamaas_model  # noqa: E402


@pytest.mark.parametrize("n", [64, 128])
def test_contact_against_tamaas(n):
    top, bottom = wearsim.generate_pair(n, seed=11, lambda_lower=8 / n, lambda_upper=0.25, rms_height=0.005)
    h = wearsim.composite_heights(top, bottom)
    material = wearsim.Material(1.0, 0.3, 0.01)
    pm = material.flow_pressure
    solver = wearsim.ContactSolver(n, 1.0, material.effective_modulus(), tolerance=1e-10)

    saturated = solver.solve(h, 1e-3, flow_pressure=pm)
    model = tamaas_model(n)
    tm.KatoSaturated(model, h, 1e-10, pm).solve(1e-3)
    p_tm = np.array(model.traction).reshape(n, n)
    assert saturated.plastic_pixels > 0
    assert np.count_nonzero(saturated.contact != (p_tm > 1e-12 * pm)) <= 3
    assert np.abs(saturated.pressure - p_tm).max() < 1e-5 * pm

    elastic = solver.solve(h, 1e-3)
    model = tamaas_model(n)
    tm.PolonskyKeerRey(model, h, 1e-12).solve(1e-3)
    p_tm = np.array(model.traction).reshape(n, n)
    assert np.abs(elastic.pressure - p_tm).max() < 1e-5 * elastic.pressure.max()
    assert np.count_nonzero(elastic.contact != (p_tm > 0)) <= 2


@pytest.mark.parametrize("connectivity", [4, 8])
def test_junctions_of_a_contact_solution_against_floodfill(connectivity):
    n = 128
    top, bottom = wearsim.generate_pair(n, seed=5, lambda_lower=8 / n, lambda_upper=0.25, rms_height=0.005)
    material = wearsim.Material(1.0, 0.3, 0.01)
    contact = wearsim.solve_contact(
        wearsim.composite_heights(top, bottom, 17),
        2e-3,
        effective_modulus=material.effective_modulus(),
        flow_pressure=material.flow_pressure,
    ).contact
    ours = wearsim.label_junctions(contact, connectivity=connectivity)
    theirs = tamaas_labels(contact, connectivity == 8)
    assert ours.count == theirs.max() + 1 > 5
    assert same_partition(ours.labels, theirs)
    assert sorted(ours.pixels.tolist()) == sorted(np.bincount(theirs[theirs >= 0]).tolist())


@pytest.mark.parametrize("shape", [(128, 64), (64, 128)])
def test_rectangular_contact_and_junctions_against_tamaas(shape):
    nx, ny = shape
    length_y = ny / nx
    top, bottom = wearsim.generate_pair(shape, seed=3, lambda_lower=8 / nx, lambda_upper=0.25, rms_height=0.005)
    assert top.shape == shape
    h = wearsim.composite_heights(top, bottom, 9)
    material = wearsim.Material(1.0, 0.3, 0.01)
    pm = material.flow_pressure
    solver = wearsim.ContactSolver(shape, 1.0, material.effective_modulus(), tolerance=1e-10)
    assert solver.shape == shape
    # F_N = p̄ Lx Ly: tamaas takes the mean pressure.
    ours = solver.solve(h, 1e-3 * length_y, flow_pressure=pm)
    assert ours.mean_pressure == pytest.approx(1e-3)
    model = tamaas_model(nx, ny, length_y)
    kato = tm.KatoSaturated(model, h, 1e-10, pm)
    kato.max_iter = 20_000  # its default of 1,000 stops short of 1e-10 here
    kato.solve(1e-3)
    p_tm = np.array(model.traction).reshape(shape)
    assert ours.plastic_pixels > 0
    assert np.count_nonzero(ours.contact != (p_tm > 1e-12 * pm)) <= 3
    assert np.abs(ours.pressure - p_tm).max() < 1e-5 * pm
    theirs = tamaas_labels(ours.contact, False)
    junctions = wearsim.label_junctions(ours.contact)
    assert junctions.count == theirs.max() + 1 > 5
    assert same_partition(junctions.labels, theirs)
