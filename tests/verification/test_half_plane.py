"""The free surface against closed forms (docs/verification.md; docs/theory/earth.md): a
pressurized crack that breaks the surface (the edge crack of Tada, Paris & Irwin 2000) and
the surface displacement of a buried dipping fault with uniform slip (Segall 2010)."""

import math

import numpy as np

import ddc2d
from ddc2d.richardson import extrapolate

E, NU = 50000.0, 0.25
LEVELS = (100, 200, 400)


def test_surface_breaking_crack(solve, record):
    """A vertical crack from (0, 0) to (0, -a) under internal pressure p: one tip, at
    depth a, with K_I = 1.1215 p sqrt(pi a)."""
    p, a = 10.0, 1.0

    def build(n):
        model = ddc2d.Model(youngs_modulus=E, poissons_ratio=NU, domain="half_plane",
                            title="edge crack")
        model.fracture([0.0, 0.0], [0.0, -a], elements=n, condition="traction", bc_n=-p,
                       name="crack")
        return model

    results = [solve(build(n), f"edge{n}") for n in LEVELS]
    for r in results:
        assert r.tips["k1"].size == 1, "the mouth is no tip"
    ks = [float(r.tips["k1"][0]) for r in results]
    row = record(id="edge-crack-k1", benchmark="Pressurized crack breaking a free surface",
                 reference="K_I = 1.1215 p sqrt(pi a) (edge crack; Tada, Paris & Irwin 2000)",
                 quantity="K_I at the buried tip [MPa m^1/2]", value=ks[-1],
                 reference_value=1.1215 * p * math.sqrt(math.pi * a), tolerance=1e-4,
                 mesh=f"{LEVELS[-1]} elements (levels {', '.join(map(str, LEVELS))})",
                 order=extrapolate(ks).order)
    assert row["passed"], row


def segall_semi_infinite(x, depth, dip, slip):
    """Surface displacement (u_x, u_z) of a dip-slip fault of dip `dip` [rad] from the
    depth `depth` down to infinity, uniform slip `slip` (Segall 2010, eq. 3.71; after
    Freund & Barnett 1976); x from the surface trace of the fault's plane, positive in the
    dip direction."""
    zeta = (x - depth / math.tan(dip)) / depth
    step = np.arctan(zeta) - math.pi / 2 * np.sign(x)
    ux = slip / math.pi * (math.cos(dip) * step
                           + (math.sin(dip) - zeta * math.cos(dip)) / (1 + zeta**2))
    uz = -slip / math.pi * (math.sin(dip) * step
                            + (math.cos(dip) + zeta * math.sin(dip)) / (1 + zeta**2))
    return ux, uz


def test_segall_surface_displacement(solve, record):
    """The fault of input/buried_dipping_fault_slip.nml: 40 degrees dip from (0, -2000) down
    to (-3575.2, -5000), reverse slip Ds = -1 m. A finite fault is the top semi-infinite one
    less the bottom one; with the fault drawn down-dip, Segall's slip is Ds. The sum of
    uniform-slip elements is the uniform-slip fault exactly: round-off, whatever the mesh."""
    top, bottom, ds = (0.0, -2000.0), (-3575.2, -5000.0), -1.0
    model = ddc2d.Model(youngs_modulus=30000.0, poissons_ratio=NU, domain="half_plane",
                        length_unit="m", title="Segall")
    model.fracture([top[0], bottom[0]], [top[1], bottom[1]], elements=100,
                   condition="prescribed_dd", bc_s=ds, bc_n=0.0, name="fault")
    # 250 points: none on the fault's trace (x = 2383.5), where u_x steps.
    model.line(-15000.0, 0.0, 10000.0, 0.0, 250, name="surface")
    field = solve(model, "segall").fields["surface"]
    dip = math.atan2(top[1] - bottom[1], top[0] - bottom[0])
    trace = top[0] - top[1] * (top[0] - bottom[0]) / (top[1] - bottom[1])
    along_dip = trace - field["x"]  # the fault dips towards -x
    ux_top, uz_top = segall_semi_infinite(along_dip, -top[1], dip, ds)
    ux_bottom, uz_bottom = segall_semi_infinite(along_dip, -bottom[1], dip, ds)
    ux, uz = -(ux_top - ux_bottom), uz_top - uz_bottom  # u_x back to +x
    scale = float(np.max(np.abs(uz)))
    assert np.max(np.abs(field["ux"] - ux)) < 1e-9 * scale, "u_x along the surface"
    assert np.max(np.abs(field["uy"] - uz)) < 1e-9 * scale, "u_y along the surface"
    k = int(np.argmax(uz))
    row = record(id="segall-surface-uplift", benchmark="Buried dipping fault with uniform "
                 "slip: surface displacement (half-plane)",
                 reference="Segall (2010) eq. 3.71 (Freund & Barnett 1976)",
                 quantity="peak uplift [m] (u_x and u_y at 250 points within 1e-9 of it)",
                 value=float(field["uy"][k]), reference_value=float(uz[k]), tolerance=1e-9,
                 mesh="100 elements (exact for any mesh: uniform slip)")
    assert row["passed"], row
