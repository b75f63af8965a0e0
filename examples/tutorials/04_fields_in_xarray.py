# %% [markdown]
# # Reading the fields of a sliding run in xarray
#
# `wearsim slide --save-fields` keeps the pressure, contact and junction maps of every step (or every
# k-th step) in a Zarr store beside `series.csv`; xarray opens it lazily, with coordinates and units.
# Needs `pip install "wearsim[fields]"` (xarray, zarr) and the `wearsim` command on the PATH (or its
# path in the environment variable WEARSIM_BIN).

# %%
import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

work = Path(tempfile.mkdtemp())
wearsim_bin = os.environ.get("WEARSIM_BIN", "wearsim")

# %% [markdown]
# ## A small sliding run, fields saved every second step
#
# Reduced units: pressures in E, lengths in L, loads in E·L²; `distance` and `running_in` are
# fractions of Lx.

# %%
(work / "run.toml").write_text(
    """
units = "reduced"
[surface]
grid = 64
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
loads = [2e-3]
distance = 0.5
running_in = 0.25
"""
)
subprocess.run(
    [
        wearsim_bin,
        "--quiet",
        "slide",
        work / "run.toml",
        "--out",
        work / "slide",
        "--save-fields",
        "--fields-every",
        "2",
    ],
    check=True,
)

# %% [markdown]
# ## The dataset
#
# Dimensions (load, s, x, y): `s` is the sliding distance in L, `x` and `y` pixel positions in L.
# `pressure` is in E (at most p_m), `contact` a boolean map, `junctions` the label of each contact
# pixel's junction (0 outside contact).

# %%
ds = xr.open_zarr(work / "slide" / "fields.zarr")
print(ds)
print({name: ds[name].attrs.get("units") for name in ["pressure", "s", "x", "load"]})

# %% [markdown]
# ## Quantities from the maps
#
# The contact area fraction of the box area Lx·Ly (1) at every saved step, the largest pressure
# (E), and the number of junctions.

# %%
area_fraction = ds.contact.mean(dim=("x", "y"))
labels = ds.junctions.sel(load=2e-3).values  # (s, x, y)
junction_count = [len(np.unique(step[step > 0])) for step in labels]
print(area_fraction.sel(load=2e-3).to_pandas().rename("contact area / (Lx·Ly)").head())
print(f"max pressure {float(ds.pressure.max()):.4f} E; junctions per saved step: {junction_count[:5]}")
assert np.all((area_fraction > 0) & (area_fraction < 1))
