"""Speed of wearsim's contact solver against tamaas and ContactMechanics, on the same surfaces, in one run.

Paper roughness (λ_l = 16 px, λ_u = min(256 px, N/2), h_rms = 0.005 L, H = 0.7), τ̃ = 0.010 E,
F_N = 1e-3 E L², E = 1, ν = 0.3. wearsim runs through its CLI (`wearsim contact`, its own timer);
tamaas `KatoSaturated` (tolerance 1e-10) and ContactMechanics' bounded constrained CG (hardness = p_m)
solve the saturated problem, tamaas `PolonskyKeerRey` the elastic one. Matched accuracy is checked on
the outputs: the contact maps of all solvers are compared pixel by pixel and printed.

    python bench/reference.py --sizes 256 512 [--kato-max 256]
"""

import argparse
import json
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
WEARSIM = ROOT / "target" / "release" / "wearsim"

RUN = """
[surface]
grid = {n}
length = 1.0
hurst = 0.7
lambda_lower = {lam_l}
lambda_upper = {lam_u}
rms_height = 0.005
seed = 1
[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = {tau}
fracture_energies = [0.5e-6]
"""


def wearsim_solve(tmp, n, tau):
    run = tmp / f"run{n}_{tau}.toml"
    run.write_text(RUN.format(n=n, lam_l=16 / n, lam_u=min(256, n // 2) / n, tau=tau))
    surfaces, out = tmp / f"surfaces{n}_{tau}", tmp / f"contact{n}_{tau}"
    subprocess.run([str(WEARSIM), "surface", str(run), "--out", str(surfaces)], check=True, capture_output=True)
    subprocess.run(
        [str(WEARSIM), "contact", str(run), "--load", "1e-3", "--out", str(out)], check=True, capture_output=True
    )
    s = json.loads((out / "summary.json").read_text())
    h = np.load(surfaces / "top.npy") + np.load(surfaces / "bottom.npy")
    return h, np.load(out / "pressure.npy"), s


def tamaas_solve(h, n, pm):
    import tamaas as tm

    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, 0.3
    if pm is None:
        solver = tm.PolonskyKeerRey(model, h, 1e-12)
    else:
        solver = tm.KatoSaturated(model, h, 1e-10, pm)
    t = time.perf_counter()
    solver.solve(1e-3)
    return time.perf_counter() - t, np.array(model.traction).reshape(n, n)


def contactmechanics_solve(h, n, pm):
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization.ConstrainedConjugateGradients import constrained_conjugate_gradients
    from SurfaceTopography import Topography

    e_star = 1.0 / (1 - 0.3**2)
    substrate = PeriodicFFTElasticHalfSpace((n, n), e_star, (1.0, 1.0))
    topography = Topography(h, (1.0, 1.0))
    area = 1.0 / n**2
    t = time.perf_counter()
    res = constrained_conjugate_gradients(
        substrate, topography, hardness=pm * area, external_force=1e-3, pentol=1e-10 * h.std(), maxiter=100000
    )
    elapsed = time.perf_counter() - t
    return elapsed, np.asarray(res.jac).reshape(n, n) / area, res.nit


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512])
    ap.add_argument("--kato-max", type=int, default=256, help="largest N for tamaas KatoSaturated (slow)")
    args = ap.parse_args()
    pm = 3 * np.sqrt(3) * 0.010
    print(f"{'N':>5} {'solver':<34} {'seconds':>9} {'iters':>7} {'map≠':>6} {'ratio':>9}")
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for n in args.sizes:
            h, p_ws, s = wearsim_solve(tmp, n, 0.010)
            t_ws = s["seconds"]
            print(f"{n:>5} {'wearsim saturated':<34} {t_ws:>9.3f} {s['iterations']:>7} {0:>6} {1.0:>9.1f}")
            try:
                t, p = contactmechanics_solve(h, n, pm)[:2]
                nit = "?"
                diff = np.count_nonzero((p > 0) != (p_ws > 0))
                print(f"{n:>5} {'ContactMechanics CCG + hardness':<34} {t:>9.3f} {nit:>7} {diff:>6} {t / t_ws:>9.1f}")
            except Exception as e:  # noqa: BLE001 - report and go on
                print(f"{n:>5} ContactMechanics unavailable: {e}")
            if n <= args.kato_max:
                try:
                    t, p = tamaas_solve(h, n, pm)
                    diff = np.count_nonzero((p > 0) != (p_ws > 0))
                    print(f"{n:>5} {'tamaas KatoSaturated 1e-10':<34} {t:>9.3f} {'':>7} {diff:>6} {t / t_ws:>9.1f}")
                except Exception as e:  # noqa: BLE001
                    print(f"{n:>5} tamaas unavailable: {e}")
            # Elastic: wearsim with a flow pressure far above any contact pressure.
            h, p_el, s_el = wearsim_solve(tmp, n, 100.0)
            print(f"{n:>5} {'wearsim elastic':<34} {s_el['seconds']:>9.3f} {s_el['iterations']:>7} {0:>6} {1.0:>9.1f}")
            try:
                t, p = tamaas_solve(h, n, None)
                diff = np.count_nonzero((p > 0) != (p_el > 0))
                name = "tamaas PolonskyKeerRey 1e-12"
                print(f"{n:>5} {name:<34} {t:>9.3f} {'':>7} {diff:>6} {t / s_el['seconds']:>9.1f}")
            except Exception as e:  # noqa: BLE001
                print(f"{n:>5} tamaas unavailable: {e}")


if __name__ == "__main__":
    main()
