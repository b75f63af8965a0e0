# %% [markdown]
# # Your own material from handbook values
#
# The model of Brink, Frérot & Molinari (J. Mech. Phys. Solids 147 (2021) 104238) needs four
# material numbers: Young's modulus E, Poisson's ratio ν, the junction shear strength τ̃ and the
# fracture energy 𝒢 (paper §2, eq. 1). Handbooks give E, ν, a hardness and a surface energy; this
# tutorial turns them into a wearsim `Material` in SI units and runs one contact and a short slide.
#
# Run it as a script (`python examples/tutorials/01_handbook_material.py`) or open it as a notebook
# (`jupytext --to notebook 01_handbook_material.py`). Small grid: seconds.

# %%
import numpy as np
import wearsim

# %% [markdown]
# ## Handbook values (an alumina, order-of-magnitude values)
#
# - E = 370 GPa, ν = 0.22 (elastic constants);
# - Vickers hardness H_V ≈ 15 GPa, taken as the flow pressure p_m of the saturated contact, so
#   τ̃ = p_m / (3√3) (paper §2.2: p_m = 3√3 τ̃);
# - surface energy γ ≈ 1 J/m²; the fracture energy of a junction creates two surfaces: 𝒢 = 2γ.
#   A range of 𝒢 shows how sensitive the result is to this least certain number.

# %%
youngs_modulus = 370e9  # Pa
poisson_ratio = 0.22  # 1
hardness = 15e9  # Pa, taken as p_m
surface_energy = 1.0  # J/m²
shear_strength = hardness / (3 * np.sqrt(3))  # Pa, τ̃
material = wearsim.Material(
    youngs_modulus=youngs_modulus,
    poisson_ratio=poisson_ratio,
    shear_strength=shear_strength,
    fracture_energies=[2 * surface_energy, 4 * surface_energy],  # J/m²
)
print(f"τ̃ = {material.shear_strength / 1e9:.2f} GPa, p_m = {material.flow_pressure / 1e9:.2f} GPa")
for g, d in zip(material.fracture_energies, material.critical_diameters):
    print(f"𝒢 = {g:.1f} J/m²: critical junction diameter d* = {d * 1e6:.3f} µm (eq. 1)")

# %% [markdown]
# ## A surface pair in metres
#
# A box of side L = 2 µm on 64² pixels (Δx = L/64 ≈ 31 nm), H = 0.7, wavelengths from
# λ_l = 8 Δx to λ_u = L/4, RMS height 20 nm. d* must span at least 4 pixels for junctions of the
# critical size to be resolved (wearsim warns otherwise): d*/Δx is printed.

# %%
n, length = 64, 2e-6  # pixels, m
pixel = length / n  # m
top, bottom = wearsim.generate_pair(
    n, length=length, hurst=0.7, lambda_lower=8 * pixel, lambda_upper=length / 4, rms_height=20e-9, seed=1
)
print(f"Δx = {pixel * 1e9:.0f} nm; d*/Δx = {np.round(np.array(material.critical_diameters) / pixel, 1)}")

# %% [markdown]
# ## One contact and its junctions
#
# A load F_N in newtons: the mean pressure F_N / L² must stay below p_m. `contact_area` is a
# fraction of the box area Lx·Ly (1); junction areas are in m², diameters in m.

# %%
load = 0.1 * material.flow_pressure * length**2  # N: mean pressure 10 % of p_m
heights = wearsim.composite_heights(top, bottom)
contact = wearsim.solve_contact(
    heights,
    load,
    length=length,
    effective_modulus=material.effective_modulus(),
    flow_pressure=material.flow_pressure,
)
junctions = wearsim.label_junctions(contact.contact, pixel_size=pixel)
static = wearsim.static_wear(junctions, material.critical_diameters[0])
print(f"F_N = {load * 1e3:.3f} mN: contact area {contact.contact_area:.4f} of Lx·Ly, {junctions.count} junctions")
print(
    f"largest junction diameter {junctions.diameters.max() * 1e6:.3f} µm; static k = {static['wear_coefficient']:.3g}"
)

# %% [markdown]
# ## A short slide
#
# `distance` and `running_in` are fractions of Lx (1); the wear rate W is a volume per sliding
# distance (m³/m = m²) and k = W p̃ / F_N is dimensionless (paper eq. 5).
# On 64² pixels only a handful of particles form, and wearsim warns that W rests on few events:
# for numbers to report, refine the grid (the paper uses 4096²) and slide further.

# %%
series, summary = wearsim.slide(top, bottom, material, [load], length=length, distance=0.5, running_in=0.25)
for r in summary["results"]:
    print(f"𝒢 = {r['fracture_energy']:.1f} J/m²: W = {r['wear_rate']:.3e} m², k = {r['wear_coefficient']:.3e}")
assert np.isfinite(series["volume"]).all()
