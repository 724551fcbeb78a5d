"""Two bonded half-planes against their exact limits (docs/verification.md;
docs/theory/bimaterial.md): equal materials are the full plane, a vanishing upper material
is the half-plane, tractions and displacements are continuous across the interface, a crack
ending on the interface opens with the exponent of Zak & Williams (1963), and a crack far
from the interface is the full plane's Griffith crack."""

import math

import numpy as np

import ddc2d

E, NU = 1.0, 0.25
#: Material of the cross-interface checks: a lower and an upper one
LOWER, UPPER = (40000.0, 0.2), (10000.0, 0.3)


def two_materials(lower, upper, interface_y=0.0, title="two materials"):
    """A bimaterial model (lower, upper: Young's modulus and Poisson's ratio)."""
    model = ddc2d.Model(None, None, domain="bimaterial", interface_y=interface_y, title=title)
    model.material("lower", *lower)
    model.material("upper", *upper)
    return model


def largest_gap(a, b):
    """Largest |a - b| over the largest |b|, finite entries."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    keep = np.isfinite(b)
    return float(np.max(np.abs(a[keep] - b[keep])) / np.max(np.abs(b[keep])))


def result_gaps(result, reference, field):
    """The largest gap of each DD, K and quantity of the field `field`, over the largest
    value of each."""
    gaps = [largest_gap(result.elements[k], reference.elements[k]) for k in ("ds", "dn")]
    gaps += [largest_gap(result.tips[k], reference.tips[k]) for k in ("k1", "k2")]
    return gaps + [largest_gap(result.fields[field][q], reference.fields[field][q])
                   for q in ("ux", "uy", "sxx", "syy", "sxy")]


def with_cracks(model):
    """A crack across the interface y = 0 (a vertex on it), an inclined one below and one
    above it, pressurized, with field points on both sides."""
    model.remote_stress(sxx=-1.0, syy=-1.5, sxy=0.5)
    model.fracture([0.0, 0.0, 0.0], [-0.8, 0.0, 0.6], elements=[16, 12], condition="traction",
                   bc_s=0.0, bc_n=-2.0, name="across")
    model.fracture([1.0, 2.0], [-1.5, -0.7], elements=10, condition="traction", bc_s=0.5,
                   bc_n=-1.0, name="below")
    model.fracture([-2.0, -1.0], [0.4, 1.1], elements=10, condition="traction", bc_s=0.0,
                   bc_n=-1.0, name="above")
    model.grid(-3.0, 3.0, 13, -2.0, 2.0, 9, name="map")
    return model


def test_equal_materials_are_the_full_plane(solve, record):
    """Both materials equal: DDs, K and fields of the full plane within 1e-12 of the
    largest value of each (a crack crosses the interface at a vertex: both kernels' sides
    serve)."""
    full = solve(with_cracks(ddc2d.Model(youngs_modulus=E, poissons_ratio=NU)), "full")
    two = solve(with_cracks(two_materials((E, NU), (E, NU))), "equal")
    gaps = result_gaps(two, full, "map")
    assert max(gaps) <= 1e-12, gaps
    row = record(id="bimaterial-equal-full-plane",
                 benchmark="Two bonded half-planes of equal materials (three pressurized "
                 "cracks, one across the interface)",
                 quantity="peak opening [m] (every DD, K and field within 1e-12 of the "
                 "largest of its kind)",
                 reference="the full plane (the same model, domain = 'full_plane')",
                 value=float(np.max(-two.elements["dn"])),
                 reference_value=float(np.max(-full.elements["dn"])), tolerance=1e-12,
                 mesh="48 elements (exact for any mesh)")
    assert row["passed"], row


def test_soft_upper_material_is_the_half_plane(solve, record):
    """An upper material 1e-12 times as stiff: the half-plane's DDs, K and fields (body
    below y = 0) within 1e-9 of the largest value of each."""

    def build(model):
        model.remote_stress(sxx=-2.0, dsxx_dy=0.5, dsyy_dy=1.0)
        model.fracture([-1.0, 0.2, 1.0], [-2.0, -1.0, -0.5], elements=[12, 8],
                       condition="traction", bc_s=0.3, bc_n=-3.0, name="crack")
        model.line(-3.0, -0.01, 3.0, -0.01, 31, name="below_surface")
        return model

    half = solve(build(ddc2d.Model(youngs_modulus=E, poissons_ratio=NU,
                                   domain="half_plane")), "half")
    two = solve(build(two_materials((E, NU), (1e-12 * E, 0.3))), "soft")
    gaps = result_gaps(two, half, "below_surface")
    assert max(gaps) <= 1e-9, gaps
    row = record(id="bimaterial-soft-upper-half-plane",
                 benchmark="Two bonded half-planes, the upper 1e-12 times as stiff (a kinked "
                 "crack below the interface, stress with depth)",
                 quantity="K_I at the upper tip [MPa m^1/2] (every DD, K and field within "
                 "1e-9 of the largest of its kind)",
                 reference="the half-plane below a free surface (domain = 'half_plane')",
                 value=float(two.tips["k1"][-1]), reference_value=float(half.tips["k1"][-1]),
                 tolerance=1e-9, mesh="20 elements (exact for any mesh)")
    assert row["passed"], row


def test_continuity_across_the_interface(solve, record):
    """Field points on the interface y = 0.3 (the lower side) and one rounding step above
    it (the upper side), for cracks in both materials of a 4:1 contrast: syy, sxy, ux, uy
    agree within 1e-12 of their largest value."""
    model = two_materials(LOWER, UPPER, interface_y=0.3)
    model.remote_stress(sxx=-3.0, syy=-5.0, sxy=1.0)
    model.fracture([-1.0, 1.0], [-0.5, 0.1], elements=20, condition="traction", bc_s=0.0,
                   bc_n=-2.0, name="below")
    model.fracture([0.5, 1.5], [0.6, 1.4], elements=20, condition="traction", bc_s=0.4,
                   bc_n=-1.0, name="above")
    x = np.linspace(-3.0, 3.0, 41)
    above = float(np.nextafter(0.3, 1.0))
    model.points(np.concatenate([x, x]), [0.3] * x.size + [above] * x.size, name="interface")
    field = solve(model, "continuity").fields["interface"]
    gaps = []
    for q in ("ux", "uy", "syy", "sxy"):
        values = np.asarray(field[q])
        gaps.append(largest_gap(values[x.size:], values[:x.size]))
    assert max(gaps) <= 1e-12, gaps
    sxx = np.asarray(field["sxx"])
    assert largest_gap(sxx[x.size:], sxx[:x.size]) > 1e-3, "sxx jumps"
    syy = np.asarray(field["syy"])
    k = int(np.argmax(np.abs(syy[:x.size])))
    row = record(id="bimaterial-interface-continuity",
                 benchmark="Two bonded half-planes (E 40000 and 10000 MPa), cracks in both",
                 quantity="syy just above the interface where it peaks [MPa] (ux, uy, syy, "
                 "sxy at 41 points within 1e-12 of the largest of each)",
                 reference="perfect bonding: syy on the interface (just below)",
                 value=float(syy[x.size + k]), reference_value=float(syy[k]),
                 tolerance=1e-12, mesh="40 elements (exact for any mesh)")
    assert row["passed"], row


def zak_williams_opening_exponent(cracked, ahead):
    """1 - lambda: the exponent of the opening behind a crack tip on the interface, normal
    to it (Zak & Williams 1963, in He & Hutchinson's (1989) form; Dundurs' alpha and beta
    of the material ahead against the cracked one); materials as (E, nu)."""

    def shear_and_kappa(material):
        e, nu = material
        return e / (2 * (1 + nu)), 3 - 4 * nu

    g1, k1 = shear_and_kappa(ahead)
    g2, k2 = shear_and_kappa(cracked)
    d = g1 * (k2 + 1) + g2 * (k1 + 1)
    alpha, beta = (g1 * (k2 + 1) - g2 * (k1 + 1)) / d, (g1 * (k2 - 1) - g2 * (k1 - 1)) / d

    def residual(lam):
        return (math.cos(lam * math.pi) - 2 * (beta - alpha) / (1 + beta) * (1 - lam) ** 2
                - (alpha + beta**2) / (1 - beta**2))

    low, high = 1e-6, 1 - 1e-6
    for _ in range(100):
        middle = 0.5 * (low + high)
        low, high = (low, middle) if residual(low) * residual(middle) <= 0 else (middle, high)
    return 1 - 0.5 * (low + high)


def graded_opening_exponent(solve, cracked, ahead, q, n):
    """The exponent of the opening fitted over 1e-6 < r < 1e-4 behind the tip of a crack
    from y = -1 up to the interface y = 0, graded towards the tip by q in n elements."""
    length = (1 - q) / (1 - q**n)
    y = np.zeros(n + 1)
    for k in range(n, 0, -1):  # summed from the tip, where the elements are smallest
        y[k - 1] = y[k] - length * q ** (k - 1)
    model = two_materials(cracked, ahead, title=f"crack ending on the interface, q = {q}")
    model.fracture(np.zeros(n + 1), y, elements=[1] * n, condition="traction", bc_s=0.0,
                   bc_n=-1.0, name="crack")
    model.solver(k_method="tip_element")
    result = solve(model, f"zw_{q}")
    r = -0.5 * (result.elements["y_begin"] + result.elements["y_end"])
    opening = -result.elements["dn"]
    window = (r > 1e-6) & (r < 1e-4)
    return float(np.polyfit(np.log(r[window]), np.log(opening[window]), 1)[0])


def test_crack_ending_on_the_interface(solve, record):
    """A pressurized crack in a stiff material (E = 10) with its tip on a softer one (E =
    1): the opening goes as r^(1 - lambda); the fits on meshes graded by 0.9 and 0.95 are low
    by a multiple of 1 - q (constant elements), extrapolated to q = 1."""
    cracked, ahead = (10.0, 0.25), (1.0, 0.3)
    fits = [graded_opening_exponent(solve, cracked, ahead, q, n)
            for q, n in ((0.9, 220), (0.95, 440))]
    row = record(id="bimaterial-zak-williams",
                 benchmark="Pressurized crack normal to the interface, its tip on it, in the "
                 "stiffer material (E 10 against 1)",
                 quantity="exponent of the opening behind the tip, fits at grading 0.9 and "
                 f"0.95 ({fits[0]:.4f}, {fits[1]:.4f}) extrapolated to 1",
                 reference="1 - lambda, cos(lambda pi) = 2 (b - a)/(1 + b) (1 - lambda)^2 + "
                 "(a + b^2)/(1 - b^2) (Zak & Williams 1963; He & Hutchinson 1989)",
                 value=2 * fits[1] - fits[0],
                 reference_value=zak_williams_opening_exponent(cracked, ahead),
                 tolerance=0.02, mesh="220 and 440 elements graded to the tip")
    assert row["passed"], row


def test_far_crack_is_the_griffith_crack(solve, record):
    """A pressurized crack of half-length 1 at 40 half-lengths below an interface with a
    material 5 times as stiff: K_I = p sqrt(pi a) of the full plane (the interface's
    effect falls as 1 / d^2)."""
    p, a = 1.0, 1.0
    ks = []
    for depth in (20.0, 40.0):
        model = two_materials((E, NU), (5 * E, 0.3), title=f"crack at depth {depth}")
        model.fracture([-a, a], [-depth, -depth], elements=20, condition="traction",
                       bc_s=0.0, bc_n=-p, name="crack")
        ks.append(float(solve(model, f"far{depth:g}").tips["k1"][0]))
    exact = p * math.sqrt(math.pi * a)
    assert abs(ks[1] - exact) < abs(ks[0] - exact), "closer farther from the interface"
    row = record(id="bimaterial-far-crack-k1",
                 benchmark="Pressurized crack 40 half-lengths below a 5 times stiffer "
                 "material",
                 quantity="K_I at the tips [MPa m^1/2]",
                 reference="K_I = p sqrt(pi a) (Griffith crack in a full plane)",
                 value=ks[1], reference_value=exact, tolerance=1e-3,
                 mesh="20 elements on the crack")
    assert row["passed"], row
