"""Reference elastic interaction energies of sheared disc junctions, computed with tamaas.

Uses tamaas's periodic elastic half-space (``surface_2d`` model, Neumann solve) to compute the
elastic energy stored when a uniform tangential traction q_x = 1 acts on one disc junction and on
pairs of disc junctions, on a 256 x 256 periodic grid of side 256 (pixel size 1), E = 1, nu = 0.3.

Conventions (checked below):
  * Array index ``[i, j]``: the first axis ``i`` is x, the second ``j`` is y. The x component of
    traction/displacement is ``[..., 0]``; its Fourier kernel is (1 - nu kx^2 / k^2) / (G k) with
    kx the wavenumber along the first axis, so "along x" separations are along the first axis.
  * tamaas drops the zero Fourier mode: the displacement has zero mean over the box.

Quantities:
  * disc centred at (x0, y0): pixels {(i, j) : (i - x0)^2 + (j - y0)^2 < 64};
  * E(S) = 0.5 * sum_{k in S} q_x(k) u_x(k) dA with dA = 1;
  * E1 = E(disc at (128, 128));
  * R(s) = E(A u B) / (2 E1) for discs A, B at centre distance s, separated along x (the shear
    direction) or along y.
  * kernel check: a single-pixel traction solved by tamaas versus numpy ifft2 of
    qhat * (1 - nu kx^2 / k^2) / (G k), k = 2 pi m / L, zero mode set to 0.

Writes ``interaction_energy_reference.json`` next to this script (or to the path given as the first
argument). Rerun with:

    python3.11 -m venv venv && venv/bin/pip install tamaas numpy
    venv/bin/python interaction_energy_reference.py [output.json]

From the repository root, to refresh the file used by the Rust tests:

    venv/bin/python bench/interaction_energy_reference.py crates/wearsim/tests/data/interaction_energy_reference.json
"""

import json
import pathlib
import sys

import numpy as np
import tamaas as tm

N = 256
LENGTH = 256.0
YOUNGS = 1.0
POISSON = 0.3
RADIUS_SQUARED = 64
CENTRE = 128
SEPARATIONS = [16, 17, 18, 20, 24, 32, 40, 48, 64, 80]
SHEAR_MODULUS = YOUNGS / (2.0 * (1.0 + POISSON))
PIXEL_AREA = (LENGTH / N) ** 2


def make_model():
    """Periodic elastic half-space model with the reference material."""
    model = tm.ModelFactory.createModel(tm.model_type.surface_2d, [LENGTH, LENGTH], [N, N])
    model.E = YOUNGS
    model.nu = POISSON
    return model


def solve_ux(model, qx):
    """Displacement u_x for a tangential traction field q_x (x = component 0), other components zero."""
    model.traction[...] = 0.0
    model.traction[..., 0] = qx
    model.solveNeumann()
    return np.array(model.displacement[..., 0], copy=True)


def disc_mask(x0, y0):
    """Pixels (i, j) with (i - x0)^2 + (j - y0)^2 < RADIUS_SQUARED (i along x, first axis)."""
    i, j = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    return (i - x0) ** 2 + (j - y0) ** 2 < RADIUS_SQUARED


def energy(model, mask):
    """Elastic energy 0.5 * sum q_x u_x dA with q_x = 1 on the mask."""
    qx = mask.astype(float)
    ux = solve_ux(model, qx)
    return 0.5 * float(np.sum(qx * ux)) * PIXEL_AREA, ux


def numpy_kernel_ux(qx):
    """u_x from ifft2(qhat * (1 - nu kx^2 / k^2) / (G k)), kx along the first axis, zero mode removed."""
    k1 = 2.0 * np.pi * np.fft.fftfreq(N, d=LENGTH / N)
    kx, ky = np.meshgrid(k1, k1, indexing="ij")
    k = np.hypot(kx, ky)
    kernel = np.zeros_like(k)
    nz = k > 0
    kernel[nz] = (1.0 - POISSON * kx[nz] ** 2 / k[nz] ** 2) / (SHEAR_MODULUS * k[nz])
    return np.fft.ifft2(np.fft.fft2(qx) * kernel).real


def kernel_check(model):
    """Compare tamaas with the numpy kernel for a single-pixel x traction at the centre."""
    qx = np.zeros((N, N))
    qx[CENTRE, CENTRE] = 1.0
    ux = solve_ux(model, qx)
    ref = numpy_kernel_ux(qx)
    max_rel = float(np.max(np.abs(ux - ref)) / np.max(np.abs(ref)))
    # Axis-convention check: the same kernel with kx taken along the second axis must NOT match.
    swapped_rel = float(np.max(np.abs(ux - numpy_kernel_ux_swapped(qx))) / np.max(np.abs(ref)))
    return max_rel, swapped_rel, ux


def numpy_kernel_ux_swapped(qx):
    """Same as numpy_kernel_ux but with kx along the second axis (wrong convention, for contrast)."""
    return numpy_kernel_ux(qx.T).T


def pair_ratios(model, e1, axis):
    """R(s) for two discs separated by s along the given axis (0 = x, 1 = y)."""
    rows, pixels = [], {}
    for s in SEPARATIONS:
        a = [CENTRE, CENTRE]
        a[axis] -= s // 2
        b = list(a)
        b[axis] += s
        mask_a, mask_b = disc_mask(*a), disc_mask(*b)
        shared = int(np.sum(mask_a & mask_b))
        if shared:
            raise RuntimeError(f"discs overlap at s={s}: {shared} shared pixels")
        e_pair, _ = energy(model, mask_a | mask_b)
        rows.append([s, e_pair / (2.0 * e1)])
        pixels[s] = int(np.sum(mask_a | mask_b))
    return rows, pixels


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).with_suffix(".json")
    model = make_model()

    max_rel, swapped_rel, point_ux = kernel_check(model)
    # Point-load decay is stronger along y than along x for u_x (Cerruti); confirms axis 0 is x.
    axis_ok = point_ux[CENTRE + 4, CENTRE] > point_ux[CENTRE, CENTRE + 4]

    mask = disc_mask(CENTRE, CENTRE)
    n_pixels = int(mask.sum())
    e1, ux = energy(model, mask)
    radius = float(np.sqrt(RADIUS_SQUARED))
    radius_eq = float(np.sqrt(n_pixels * PIXEL_AREA / np.pi))
    continuum_mean = 4.0 * (2.0 - POISSON) / (3.0 * np.pi * SHEAR_MODULUS)  # times q a, q = 1

    along_x, pixels_x = pair_ratios(model, e1, axis=0)
    along_y, pixels_y = pair_ratios(model, e1, axis=1)

    result = {
        "tamaas_version": tm.__version__,
        "grid": N,
        "length": LENGTH,
        "youngs_modulus": YOUNGS,
        "poisson_ratio": POISSON,
        "disc": {"radius_squared_strict": RADIUS_SQUARED, "pixels": n_pixels},
        "single_energy": e1,
        "along_x": along_x,
        "along_y": along_y,
        "mean_displacement": float(ux.mean()),
        "kernel_check_max_rel_diff": max_rel,
        "diagnostics": {
            "axis_convention": "array index [i, j]: i (first axis) is x, traction/displacement component 0 is x",
            "zero_mode": "tamaas removes the zero Fourier mode: mean u_x over the box is zero",
            "kernel_check_swapped_axes_max_rel_diff": swapped_rel,
            "point_load_ux_larger_along_first_axis": bool(axis_ok),
            "single_disc_centre_ux": float(ux[CENTRE, CENTRE]),
            "single_disc_mean_ux_under_disc": float(ux[mask].mean()),
            "continuum_mean_ux_radius_8": continuum_mean * radius,
            "continuum_mean_ux_equal_area_radius": continuum_mean * radius_eq,
            "equal_area_radius": radius_eq,
            "pair_pixels_along_x": {str(s): p for s, p in pixels_x.items()},
            "pair_pixels_along_y": {str(s): p for s, p in pixels_y.items()},
        },
    }
    out.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
