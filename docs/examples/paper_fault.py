# %% [markdown]
# # The fault of Ritz, Mutlu & Pollard (2012) from Python
#
# A notebook in cells (`# %%`): open it in Jupyter (with jupytext) or VS Code, or run it
# whole with `build/venv/bin/python docs/examples/paper_fault.py` from any folder; it
# writes its files into the current folder. It builds the paper's fault (the model of
# input/paper_fault_slip.nml), runs ddc2d, plots the slip and a stress map, and sweeps the
# friction coefficient in a loop. See docs/python.md.

# %%
import csv

import matplotlib.pyplot as plt
import numpy as np

import ddc2d
from ddc2d.plot import fracture_profiles, plot_map, plot_profile

# %% [markdown]
# ## The model
#
# A 2 m fault along x in 500 elements, friction 0.6 and cohesion 1 MPa, under principal
# stresses -175 and -50 MPa whose most compressive axis is 30 degrees from the fault:
# resolved on the fault, shear 54.13 MPa and normal stress -81.25 MPa, so the strength
# is 1 + 0.6 x 81.25 = 49.75 MPa and every element slips.

# %%
def paper_fault(mu=0.6, grid=True):
    """The paper's fault with friction `mu`; with a stress map grid when `grid`."""
    model = ddc2d.Model(youngs_modulus=50000.0, poissons_ratio=0.25, length_unit="m",
                        stress_unit="MPa", title=f"Ritz et al. (2012) fault, mu = {mu}")
    model.remote_stress(sxx=-143.75, syy=-81.25, sxy=54.13)
    model.fracture([-1.0, 1.0], [0.0, 0.0], elements=500, condition="contact", mu=mu,
                   sf=1.0, name="fault")
    if grid:
        model.grid(xmin=-2.0, xmax=2.0, nx=81, ymin=-1.5, ymax=1.5, ny=61, name="map")
    return model


result = ddc2d.run(paper_fault(), output="paper_fault.h5")
slip = -result.elements["ds"]
print(f"peak slip {np.max(np.abs(slip)):.4e} {result.unit('elements/ds')} "
      f"(the paper's closed form: 3.285e-4 m), K_II at the tips {result.tips['k2']}")

# %% [markdown]
# ## Slip along the fault and a stress map
#
# The figures of `ddc2d-plot`, from `ddc2d.plot`; the map's data also as an xarray
# Dataset.

# %%
fracture, profile = fracture_profiles(result)[0]
plot_profile(result, fracture, profile).savefig("paper_fault_slip.png", dpi=100)
plot_map(result, "map", "max_shear").savefig("paper_fault_max_shear.png", dpi=100)
plt.close("all")

grid = result.to_xarray("map")
print(grid["sxy"].sel(x=0.0, y=0.5, method="nearest").item(), grid["sxy"].attrs["units"])

# %% [markdown]
# ## Friction sweep
#
# The same fault with friction from 0.3 to 0.7 (no map): above 0.6663 the strength
# exceeds the resolved shear and the fault sticks.

# %%
frictions = [0.3, 0.4, 0.5, 0.6, 0.7]
peak_slips = []
for mu in frictions:
    run = ddc2d.run(paper_fault(mu, grid=False), output=f"paper_fault_mu{mu}.h5")
    peak_slips.append(float(np.max(np.abs(run.elements["ds"]))))
    print(f"mu = {mu}: peak slip {peak_slips[-1]:.4e} m")

with open("paper_fault_friction_sweep.csv", "w", newline="") as table:
    writer = csv.writer(table)
    writer.writerow(["mu", "peak_slip [m]"])
    writer.writerows((mu, repr(peak)) for mu, peak in zip(frictions, peak_slips))

fig, ax = plt.subplots(figsize=(5, 3.5), layout="constrained")
ax.plot(frictions, peak_slips, marker="o")
ax.set_xlabel("friction coefficient mu")
ax.set_ylabel("peak slip [m]")
ax.set_title("Ritz et al. (2012) fault: peak slip against friction", fontsize="medium")
fig.savefig("paper_fault_friction_sweep.png", dpi=100)
plt.close(fig)
