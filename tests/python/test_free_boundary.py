"""The gap and displacement of a contact solution, and the free-boundary half-space checked against
ContactMechanics' free-boundary solver (FreeFFTElasticHalfSpace, Hockney's method) on the same map."""

import numpy as np
import pytest
import wearsim

E_STAR = 1.0 / (1.0 - 0.3**2)


def rough_map(n, seed=5):
    """A rough, non-periodic map: a paraboloid with self-affine roughness on it."""
    top, bottom = wearsim.generate_pair(
        n, length=1.0, hurst=0.7, lambda_lower=8 / n, lambda_upper=0.25, rms_height=2e-3, seed=seed
    )
    x = (np.arange(n) - n / 2 + 0.5) / n
    return top - (x[:, None] ** 2 + x[None, :] ** 2) / 2.0


@pytest.mark.parametrize("boundary", ["periodic", "free"])
def test_the_gap_meets_the_optimality_conditions(boundary):
    h = rough_map(64)
    pm = 3 * np.sqrt(3) * 0.01
    r = wearsim.solve_contact(h, 2e-3, effective_modulus=E_STAR, flow_pressure=pm, boundary=boundary)
    p, g = r.pressure, r.gap
    assert r.displacement.shape == g.shape == (64, 64)
    np.testing.assert_allclose(
        r.displacement, wearsim.ContactSolver(64, 1.0, E_STAR, boundary=boundary).displacement(p)
    )
    np.testing.assert_allclose(g, r.displacement - h + h.max() - r.approach, atol=1e-14)
    bound = 1.0001 * r.tolerance * h.std()
    free, plastic = (p > 0) & (p < pm), p >= pm
    assert plastic.any() and free.any()
    assert np.abs(g[free]).max() <= bound
    assert g[p == 0].min() >= -bound
    assert g[plastic].max() <= bound
    assert g[plastic].min() < -100 * bound  # plastic pixels do interpenetrate


def test_a_sliding_offset_is_refused_on_a_free_boundary_and_bad_names_too():
    with pytest.raises(ValueError, match="boundary"):
        wearsim.ContactSolver(32, 1.0, E_STAR, boundary="open")
    assert wearsim.ContactSolver(32, 1.0, E_STAR, boundary="free").boundary == "free"


def test_free_boundary_contact_agrees_with_contact_mechanics():
    cm = pytest.importorskip("ContactMechanics")
    st = pytest.importorskip("SurfaceTopography")
    n, force = 64, 4e-3
    h = rough_map(n)
    ours = wearsim.solve_contact(h, force, effective_modulus=E_STAR, boundary="free", tolerance=1e-10)
    substrate = cm.FreeFFTElasticHalfSpace((n, n), E_STAR, (1.0, 1.0))
    system = cm.make_system(substrate=substrate, surface=st.Topography(h, (1.0, 1.0)))
    result = system.minimize_proxy(external_force=force, pentol=1e-10 * h.std())
    assert result.success, result.message
    theirs = np.asarray(system.force)[:n, :n] / (1.0 / n) ** 2
    ours_contact, theirs_contact = ours.pressure > 0, theirs > 0
    assert ours_contact.sum() > 100
    differ = np.count_nonzero(ours_contact != theirs_contact)
    assert differ <= 5, f"{differ} of {ours_contact.sum()} contact pixels differ"
    np.testing.assert_allclose(theirs.sum(), ours.pressure.sum(), rtol=1e-8)
    assert np.abs(theirs - ours.pressure).max() < 1e-3 * ours.pressure.max()


def test_the_device_is_the_cpu_and_a_gpu_this_build_lacks_is_refused_with_the_fix():
    assert wearsim.ContactSolver(32, 1.0, E_STAR).device == "cpu"
    with pytest.raises(ValueError, match='"cpu"'):
        wearsim.ContactSolver(32, 1.0, E_STAR, device="cuda")
    with pytest.raises(ValueError, match="device"):
        wearsim.ContactSolver(32, 1.0, E_STAR, device="gpu")
