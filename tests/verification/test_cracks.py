"""Cracks in the full plane against closed forms (docs/verification.md): the Griffith crack
in mode I, mode II and inclined (docs/theory/kernels.md#checks-against-closed-forms), the
circular-arc crack (Sih, Paris & Erdogan 1962), and a fault whose stress drop varies linearly
along it (Burgmann, Pollard & Martel 1994). Each quantity is solved on three meshes, each
twice as fine as the one before; the row is the finest's, with the observed order of the
three (ddc2d.richardson)."""

import math

import numpy as np
import pytest
from closed_forms import arc_crack_k

import ddc2d
from ddc2d.richardson import extrapolate

E, NU = 50000.0, 0.25
G = E / (2 * (1 + NU))
#: Element counts of the three levels of the straight cracks; the row is the last's.
LEVELS = (100, 200, 400)
TIPS_BY = "Tada, Paris & Irwin (2000)"


def straight_crack(n, angle=0.0, **remote):
    """A traction-free crack of half-length 1 through the origin at `angle` degrees from
    +x, n elements, under the remote stress `remote`."""
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    model = ddc2d.Model(youngs_modulus=E, poissons_ratio=NU, title="griffith")
    model.remote_stress(**remote)
    model.fracture([-c, c], [-s, s], elements=n, condition="traction", name="crack")
    return model


def solve_levels(solve, build, levels=LEVELS):
    return [solve(build(n), f"level{n}") for n in levels]


def peak_dd(result, name):
    """Largest |DD| `name` ('ds' or 'dn') and the distance of its element from the centre."""
    values = np.abs(result.elements[name])
    k = int(np.argmax(values))
    return values[k], math.hypot(result.elements["x_mid"][k], result.elements["y_mid"][k])


def mesh_text(levels, what="elements on the crack"):
    return f"{levels[-1]} {what} (levels {', '.join(map(str, levels))})"


@pytest.mark.parametrize("mode", ["I", "II"])
def test_griffith_crack(mode, solve, record):
    p = 10.0
    remote = {"syy": p} if mode == "I" else {"sxy": p}
    dd, k_name = ("dn", "k1") if mode == "I" else ("ds", "k2")
    results = solve_levels(solve, lambda n: straight_crack(n, **remote))
    # The peak DD against the exact elliptical profile at the peak element's centre.
    peaks = [peak_dd(r, dd) for r in results]
    exact = [2 * (1 - NU) * p / G * math.sqrt(1 - x**2) for _, x in peaks]
    ratios = [value / e for (value, _), e in zip(peaks, exact, strict=True)]
    order = extrapolate(ratios).order
    label = "opening" if mode == "I" else "slip"
    load = "tension" if mode == "I" else "shear"
    row = record(id=f"griffith-mode-{mode.lower()}-{label}",
                 benchmark=f"Griffith crack, mode {mode} (remote {load})",
                 reference="D(x) = 2 (1 - nu) s sqrt(a^2 - x^2) / G (Griffith 1921; Crouch & "
                           "Starfield 1983)",
                 quantity=f"peak {label} / exact at that element", value=ratios[-1],
                 reference_value=1.0, tolerance=2e-3, mesh=mesh_text(LEVELS), order=order)
    assert row["passed"], row
    # K at both tips: |K| against s sqrt(pi a) (K_II's sign follows the tip; see
    # docs/output-reference.md#sign-conventions).
    ks = [float(np.mean(np.abs(r.tips[k_name]))) for r in results]
    spread = np.ptp(np.abs(results[-1].tips[k_name]))
    assert spread < 1e-9 * ks[-1], "the two tips of a symmetric crack differ"
    row = record(id=f"griffith-mode-{mode.lower()}-k", benchmark=f"Griffith crack, mode {mode}",
                 reference=f"K = s sqrt(pi a) ({TIPS_BY})",
                 quantity=f"K_{mode} at the tips [MPa m^1/2]", value=ks[-1],
                 reference_value=p * math.sqrt(math.pi), tolerance=1e-4,
                 mesh=mesh_text(LEVELS), order=extrapolate(ks).order)
    assert row["passed"], row


def test_inclined_crack(solve, record):
    """A crack at 30 degrees from +x under a uniaxial tension syy: the resolved normal
    stress s cos^2(30) and shear s sin(30) cos(30)."""
    p, angle = 10.0, 30.0
    results = solve_levels(solve, lambda n: straight_crack(n, angle=angle, syy=p))
    b = math.radians(angle)
    for name, exact in (("k1", p * math.cos(b) ** 2), ("k2", p * math.sin(b) * math.cos(b))):
        ks = [float(np.mean(np.abs(r.tips[name]))) for r in results]
        mode = "I" if name == "k1" else "II"
        row = record(id=f"griffith-inclined-{name}",
                     benchmark="Griffith crack at 30 degrees to a uniaxial tension",
                     reference=f"K_I = s cos^2 b sqrt(pi a), K_II = s sin b cos b sqrt(pi a) "
                               f"({TIPS_BY})",
                     quantity=f"K_{mode} at the tips [MPa m^1/2]", value=ks[-1],
                     reference_value=exact * math.sqrt(math.pi), tolerance=1e-4,
                     mesh=mesh_text(LEVELS), order=extrapolate(ks).order)
        assert row["passed"], row


#: Chords on the 90-degree arc: K by the higher-order re-solve is within 1e-5 from 25 on
#: and its error falls as 1/N^3 (docs/theory/tips.md#k-from-a-higher-order-re-solve).
ARC_LEVELS = (25, 50, 100)


def arc_crack(n, half_angle, p):
    """A traction-free circular arc of radius 1 and half-angle `half_angle` [rad],
    symmetric about +y, as n chords with their ends on the arc, under equal biaxial
    tension p."""
    theta = np.linspace(-half_angle, half_angle, n + 1)
    model = ddc2d.Model(youngs_modulus=E, poissons_ratio=NU, title="arc crack")
    model.remote_stress(sxx=p, syy=p)
    model.fracture(np.sin(theta), np.cos(theta), elements=1, condition="traction",
                   name="arc")
    return model


def test_circular_arc_crack(solve, record):
    p, alpha = 10.0, math.pi / 4
    results = solve_levels(solve, lambda n: arc_crack(n, alpha, p), ARC_LEVELS)
    for name, exact in zip(("k1", "k2"), arc_crack_k(alpha, tension=p)):
        ks = [float(np.mean(np.abs(r.tips[name]))) for r in results]
        mode = "I" if name == "k1" else "II"
        row = record(id=f"arc-crack-{name}",
                     benchmark="Circular-arc crack (90-degree arc) under equal biaxial tension",
                     reference="K_I + i K_II = s sqrt(pi R sin a) (cos(a/2) + i sin(a/2)) / "
                               "(1 + sin^2(a/2)) (Sih, Paris & Erdogan 1962)",
                     quantity=f"K_{mode} at the tips [MPa m^1/2]", value=ks[-1],
                     reference_value=exact, tolerance=1e-4,
                     mesh=mesh_text(ARC_LEVELS, "chords on the arc"),
                     order=extrapolate(ks).order)
        assert row["passed"], row


def test_fault_under_linear_stress_drop(solve, record):
    """A vertical frictional fault from y = -3000 to -1000 m (half-length a = 1000) under
    sxy = 20 MPa and sxx = 0.01 y MPa: the stress drop 20 - 0.6 |sxx| falls linearly from
    14 MPa at the top to 2 MPa at the bottom, A = 8 MPa at the centre, B = 0.006 MPa/m,
    and every element slips. D(s) = 2 (1 - nu) / G sqrt(a^2 - s^2) (A + B s / 2),
    K_II(+-a) = sqrt(pi a) (A +- B a / 2)."""
    a, big_a, big_b = 1000.0, 8.0, 0.006

    def build(n):
        model = ddc2d.Model(youngs_modulus=E, poissons_ratio=NU, title="linear drop",
                            length_unit="m")
        model.remote_stress(sxy=20.0, dsxx_dy=0.01)
        model.fracture([0.0, 0.0], [-3000.0, -1000.0], elements=n, condition="contact",
                       mu=0.6, sf=0.0, name="fault")
        return model

    results = solve_levels(solve, build)
    assert np.all(results[-1].elements["state"] == 2), "every element slips"
    reference = "Burgmann, Pollard & Martel (1994); Pollard & Segall (1987)"
    for label, top in (("top", True), ("bottom", False)):
        ks = []
        for r in results:
            k = int(np.argmax(r.tips["y"])) if top else int(np.argmin(r.tips["y"]))
            ks.append(abs(float(r.tips["k2"][k])))
        exact = math.sqrt(math.pi * a) * (big_a + (1 if top else -1) * big_b * a / 2)
        row = record(id=f"linear-drop-k2-{label}",
                     benchmark="Frictional fault under a stress drop linear along it",
                     reference=f"K_II(+-a) = sqrt(pi a) (A +- B a / 2) ({reference})",
                     quantity=f"K_II at the {label} tip [MPa m^1/2]", value=ks[-1],
                     reference_value=exact, tolerance=1e-4, mesh=mesh_text(LEVELS),
                     order=extrapolate(ks).order)
        assert row["passed"], row
    # The peak slip against the continuum's, found on a fine grid of s.
    s = np.linspace(-a, a, 200001)
    exact_peak = float(np.max(2 * (1 - NU) / G * np.sqrt(a**2 - s**2)
                              * (big_a + big_b * s / 2)))
    peaks = [float(np.max(np.abs(r.elements["ds"]))) for r in results]
    row = record(id="linear-drop-peak-slip",
                 benchmark="Frictional fault under a stress drop linear along it",
                 reference=f"D(s) = 2 (1 - nu) / G sqrt(a^2 - s^2) (A + B s / 2) ({reference})",
                 quantity="peak slip [m]", value=peaks[-1], reference_value=exact_peak,
                 tolerance=2e-3, mesh=mesh_text(LEVELS), order=extrapolate(peaks).order)
    assert row["passed"], row
