# %% [markdown]
# # Your own measured surface: a profilometer's text export
#
# Profilometers (optical or stylus) export a height map as text: x y z columns with units in a header.
# wearsim reads such a file, levels it, tells how far it is from periodic, and fits the self-affine
# parameters (H, λ_l, λ_u, h_rms) that the paper's model assumes (Brink, Frérot & Molinari 2021, §4.1).
#
# So that this tutorial runs anywhere, it first writes such an export itself (a synthetic map with a
# tilt, as an instrument would record it); replace `export` with your own file.

# %%
import tempfile
from pathlib import Path

import numpy as np
import wearsim

work = Path(tempfile.mkdtemp())

# %% [markdown]
# ## The export: x, y in µm, z in nm, one point a line, 128 × 128 points at 0.5 µm pitch
#
# The synthetic map has H = 0.8 and power from λ = 1 µm (two pixels) to 32 µm (half the side).

# %%
n, pitch_um = 128, 0.5
truth = wearsim.generate_surface(
    n, length=n * pitch_um, hurst=0.8, lambda_lower=2 * pitch_um, lambda_upper=n * pitch_um / 2, rms_height=0.02, seed=7
)  # µm
x, y = np.meshgrid(np.arange(n) * pitch_um, np.arange(n) * pitch_um, indexing="ij")
z_nm = (truth + 0.002 * x + 0.001 * y) * 1e3  # a tilted stage, heights in nm
export = work / "profilometer.txt"
with export.open("w") as f:
    f.write("# Profilometer export\n# X [um]\tY [um]\tZ [nm]\n")
    for xi, yi, zi in zip(x.ravel(), y.ravel(), z_nm.ravel()):
        f.write(f"{xi:.3f}\t{yi:.3f}\t{zi:.4f}\n")
print(export.read_text().splitlines()[:4])

# %% [markdown]
# ## Reading it in metres
#
# `lateral_unit` converts x and y, `height_unit` converts z; the result is in metres. The side Lx
# comes from the coordinates (span plus one pitch). `detrend="plane"` removes the tilt.

# %%
heights, length = wearsim.read_surface(export, lateral_unit="um", height_unit="nm", detrend="plane")
print(f"{heights.shape[0]}×{heights.shape[1]} pixels, Lx = {length * 1e6:.1f} µm")
stats = wearsim.surface_statistics(heights, length)
print(f"h_rms = {stats['rms_height'] * 1e9:.1f} nm, RMS slope = {stats['rms_slope']:.3f} (1)")

# %% [markdown]
# ## Periodic or not?
#
# The contact solver is periodic. `periodicity` gives the RMS jump across the border along x and y,
# each divided by the RMS step between neighbouring pixels inside (1: periodic; above 3, a ridge).

# %%
jump_x, jump_y = wearsim.periodicity(heights)
print(f"border jump / inner step: {jump_x:.1f} along x, {jump_y:.1f} along y")
# This synthetic map is periodic once levelled (about 1); a real measurement usually is not.

# %% [markdown]
# ## Two ways on
#
# 1. Taper the borders to the mean (`taper`, a fraction of each side) and use the measured map.
# 2. Fit its self-affine parameters and generate periodic surfaces with the same statistics (the
#    paper's setting). λ_l and λ_u are in metres (the fit's `length` unit), h_rms in metres: the
#    fitted band's (`map_rms_height` is the whole map's), which the generated band then carries.

# %%
tapered = wearsim.preprocess_surface(heights, detrend="plane", taper=0.1)
print(f"tapered: border jump / inner step {wearsim.periodicity(tapered)[0]:.1f} along x")
fit = wearsim.fit_surface(heights, length)
print(
    f"fit: H = {fit['hurst']:.2f}, λ_l = {fit['lambda_lower'] * 1e6:.2f} µm, λ_u = {fit['lambda_upper'] * 1e6:.2f} µm, "
    f"h_rms = {fit['rms_height'] * 1e9:.1f} nm (r² = {fit['r2']:.3f})"
)
top, bottom = wearsim.generate_pair(
    heights.shape[0],
    length=length,
    hurst=fit["hurst"],
    lambda_lower=fit["lambda_lower"],
    lambda_upper=fit["lambda_upper"],
    rms_height=fit["rms_height"],
    seed=1,
)
print(f"generated pair: h_rms = {top.std() * 1e9:.1f} nm (the fitted value, by construction)")
assert np.isclose(top.std(), fit["rms_height"], rtol=1e-9)
print(f"self-affine: {fit['self_affine']} {'; '.join(fit['reasons'])}")

# %% [markdown]
# 3. Where the spectrum is not self-affine (a lay, a peak: `fit["self_affine"]` is false and
#    `fit["reasons"]` says why, with a warning), generate periodic pairs that carry the map's
#    measured 2D spectrum as it is: the surfaces of a run file's `source = "spectrum"`.

# %%
top, bottom = wearsim.spectrum_pair(heights, length, grid=heights.shape, seed=1)
print(f"spectrum pair: h_rms = {top.std() * 1e9:.1f} nm")
