# %% [markdown]
# # A study on a Slurm cluster with dask-jobqueue
#
# A study file lists parameters; wearsim expands it into jobs (surface pair × material × load) and
# runs each as a Dask task (Brink, Frérot & Molinari 2021, §4). On a Slurm cluster, dask-jobqueue
# submits Dask workers as batch jobs. This tutorial writes the Slurm job script that would be
# submitted, without submitting it, then runs the same study on a local cluster so that it runs
# anywhere. On your cluster, replace the `LocalCluster` by the `SLURMCluster` and call `scale`.
#
# Needs `pip install "wearsim[slurm]"` (dask-jobqueue) for the job script.

# %%
import tempfile
from pathlib import Path

import wearsim
from dask.distributed import Client, LocalCluster

work = Path(tempfile.mkdtemp())

# %% [markdown]
# ## The study file
#
# Reduced units (E = 1, L = 1): loads in E·L², fracture energies in E·L, lengths in L; `distance`
# and `running_in` are fractions of Lx. 2 seeds × 2 loads = 4 jobs on a 64² grid.

# %%
study_file = work / "study.toml"
study_file.write_text(
    """
[surface]
grid = 64
lambda_lower = 0.125
lambda_upper = 0.25
rms_height = 0.005
seed = [1, 2]

[material]
youngs_modulus = 1.0
poisson_ratio = 0.3
shear_strength = 0.01
fracture_energies = [0.5e-6]

[sliding]
loads = [1e-3, 2e-3]
distance = 0.5
running_in = 0.25
"""
)
study = wearsim.study.load(study_file)
print(f"{len(study)} jobs, hash {study.hash}")

# %% [markdown]
# ## The Slurm job script (written, not submitted)
#
# One Dask worker per Slurm job, 16 cores each; wearsim's jobs use every core of their worker
# (`threads=16` below). `job_script()` only formats the script; nothing reaches Slurm until `scale`.

# %%
try:
    from dask_jobqueue import SLURMCluster
except ImportError:
    print("dask-jobqueue is not installed: pip install 'wearsim[slurm]'")
else:
    slurm = SLURMCluster(
        cores=16,
        processes=1,
        memory="32GB",
        walltime="04:00:00",
        scheduler_options={"port": 0, "dashboard_address": None},
    )
    script = work / "dask-worker.sbatch"
    script.write_text(slurm.job_script())
    slurm.close()
    print(script.read_text())
    # On the cluster's login node:
    #   cluster = SLURMCluster(cores=16, processes=1, memory="32GB", walltime="04:00:00")
    #   cluster.scale(jobs=20)
    #   table = wearsim.study.run(study, client=Client(cluster), out="study-out", threads=16)

# %% [markdown]
# ## The same study on a local cluster
#
# The result folder is that of `wearsim study run`: rerunning skips finished jobs. `wear_rate` W is
# in L² (volume L³ per sliding distance L), `wear_coefficient` k = W p̃ / F_N is dimensionless.

# %%
# Workers as threads of this process (processes=False), so that this script also runs as a plain
# script; Slurm workers are separate processes on other nodes.
with (
    LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster,
    Client(cluster) as client,
):
    table = wearsim.study.run(study, client, out=work / "study-out", threads=1)
print(table[["surface.seed", "load", "wear_rate", "wear_coefficient"]].to_string(index=False))
print("units:", {c: table.attrs["units"][c] for c in ["load", "wear_rate"]})
assert len(table) == 4
