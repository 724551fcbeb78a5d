"""Flow coupled to opening (docs/fluid-driven-fractures.md) against closed forms.

- A 2 m crack under 1 MPa of confinement filled at 1e-4 m^2/s by a fluid of negligible
  viscosity: the pressure is uniform and the crack's volume that of a pressurized crack,
  2 pi (p - s) l^2 / E' (with the fluid's compression and the residual aperture's). The
  row is the net pressure at 10 s; constant elements hold too little volume near the
  tips, so it converges at order 1 in the elements.
- A fault held closed (normal stress 10 MPa) with an overpressure of 1 MPa held at its
  middle: linear diffusion of diffusivity w_res^2 / (12 eta c), the pressure
  dp erfc(|s| / sqrt(4 alpha t)); the row is the pressure 1 m from the source at 1 s,
  of order 1 in the time step (backward Euler).
- A KGD fracture in the toughness regime (K_m = 7.2) grown by its fluid over two decades in
  time: half-length (to the front the toughness asymptote locates), net pressure and
  opening at the source against the closed form, within 1e-2 over the last decade (46
  elements per wing at its start) and 3e-2 before it.
"""

import math

import numpy as np

from ddc2d.richardson import extrapolate

E, NU = 30000.0, 0.25
E_PRIME = E / (1.0 - NU**2)


def crack_text(elements):
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress sxx = -1.0, syy = -1.0 /
&fracture name = 'crack', x = -1.0, 1.0, y = 0.0, 0.0, elements = {elements}, mu = 0.6,
          residual_aperture = 1.0e-5 /
&fluid viscosity = 1.0e-12, compressibility = 1.0e-4 /
&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, rate = 1.0e-4 /
&load_path time = 0.0, 10.0, steps = 10 /
&solver k_method = 'tip_element' /
"""


def uniform_pressure(volume):
    """p with 2 pi (p - 1) / E' (1 + c p) + 2 w_res c p = volume (l = 1 m)."""
    low, high = 1.0, 1.0e4
    for _ in range(200):
        p = 0.5 * (low + high)
        excess = 2.0 * math.pi * (p - 1.0) / E_PRIME * (1.0 + 1.0e-4 * p) + \
            2.0e-5 * 1.0e-4 * p - volume
        low, high = (p, high) if excess < 0.0 else (low, p)
    return 0.5 * (low + high)


def test_crack_of_inviscid_fluid(solve, record, tmp_path):
    levels = (40, 80, 160)
    values = []
    for n in levels:
        model = tmp_path / f"crack{n}.nml"
        model.write_text(crack_text(n))
        history = solve(model, f"crack{n}").history
        values.append(float(history["pressure"][-1].mean()) - 1.0)
    exact = uniform_pressure(1.0e-3) - 1.0
    order = extrapolate(values).order
    row = record(id="fluid-crack-uniform-pressure",
                 benchmark="2 m crack under 1 MPa filled at 1e-4 m^2/s by a fluid of "
                 "negligible viscosity (1e-12 MPa s), 10 s",
                 reference="pressurized crack: V = 2 pi (p - s) l^2 / E' at the fluid's "
                 "density", quantity="net pressure p - s at 10 s [MPa]", value=values[-1],
                 reference_value=exact, tolerance=1e-2,
                 mesh=f"{levels[-1]} elements (levels {', '.join(map(str, levels))})",
                 order=order)
    assert row["passed"], row
    assert 0.9 < order < 1.1, values


def fault_text(steps):
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress syy = -10.0, sxy = 2.0 /
&fracture name = 'fault', x = -20.0, 20.0, y = 0.0, 0.0, elements = 401, mu = 0.6,
          residual_aperture = 1.0e-5 /
&fluid viscosity = 1.0e-9, compressibility = 1.0e-3 /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = 1.0 /
&load_path time = 0.0, 1.0, steps = {steps} /
&solver k_method = 'tip_element' /
"""


def test_closed_fault_diffusion(solve, record, tmp_path):
    alpha = 1.0e-10 / (12.0e-9 * 1.0e-3)
    levels = (10, 20, 40)
    values = []
    for steps in levels:
        model = tmp_path / f"fault{steps}.nml"
        model.write_text(fault_text(steps))
        result = solve(model, f"fault{steps}")
        # Element 211 has its midpoint at x = 1.0 (401 elements of 0.0998 m).
        x = 0.5 * (result.elements["x_begin"][210] + result.elements["x_end"][210])
        values.append(float(result.history["pressure"][-1][210]))
    exact = math.erfc(abs(x) / math.sqrt(4.0 * alpha))
    order = extrapolate(values).order
    row = record(id="fluid-closed-fault-diffusion",
                 benchmark="fault held closed (10 MPa), residual aperture 10 um, water "
                 "(1e-9 MPa s, c = 1e-3 / MPa), 1 MPa held at its middle",
                 reference="linear diffusion, alpha = w^2 / (12 eta c): dp erfc(|s| / "
                 "sqrt(4 alpha t))", quantity=f"pressure at s = {x:.3f} m, t = 1 s [MPa]",
                 value=values[-1], reference_value=exact, tolerance=5e-3,
                 tolerance_kind="absolute",
                 mesh=f"401 elements, {levels[-1]} time steps (levels "
                      f"{', '.join(map(str, levels))})", order=order)
    assert row["passed"], row
    assert 0.85 < order < 1.15, values


KGD_TOUGHNESS, KGD_RATE = 1.0, 1.0e-4


def kgd_text():
    """A KGD fracture in the toughness regime (K_m = 7.2): 0.25 m with 10 elements per wing
    at the start, one more per wing and step, 205 steps (two decades in time)."""
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress sxx = -1.0, syy = -1.0 /
&fracture name = 'crack', x = -0.125, 0.125, y = 0.0, 0.0, elements = 20, mu = 0.6,
          residual_aperture = 1.0e-6 /
&fluid viscosity = 1.0e-12, compressibility = 1.0e-4 /
&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, rate = {KGD_RATE} /
&load_path time = 0.0, 100.0, steps = 1 /
&growth steps = 205, toughness = {KGD_TOUGHNESS} /
&solver k_method = 'tip_element' /
"""


def test_kgd_toughness_regime(solve, record, tmp_path):
    model = tmp_path / "kgd.nml"
    model.write_text(kgd_text())
    result = solve(model, "kgd")
    history = result.history
    time = history["time"]
    x = 0.5 * (result.elements["x_begin"] + result.elements["x_end"])
    source = np.argsort(np.abs(x))[:2]
    length = 0.125 + history["grown_length"].mean(axis=1)
    closed = (E_PRIME * KGD_RATE * time / (2.0 * math.sqrt(math.pi) * KGD_TOUGHNESS))**(2 / 3)
    pressure = KGD_TOUGHNESS / np.sqrt(math.pi * closed)
    opening = 4.0 * pressure * closed / E_PRIME
    errors = {"half-length": (length, closed, "half-length l to the front [m]"),
              "net-pressure": (history["pressure"][:, source].mean(axis=1) - 1.0, pressure,
                               "net pressure at the source [MPa]"),
              "opening": (-history["dn"][:, source].mean(axis=1), opening,
                          "opening at the source [m]")}
    # Two decades in time; the last one starts with 46 elements per wing.
    assert time[-1] / time[0] > 90.0
    last_decade = time >= time[-1] / 10.0
    assert history["element_count"][last_decade][0] // 2 >= 20
    rows = []
    for name, (value, reference, quantity) in errors.items():
        relative = np.abs(value / reference - 1.0)
        assert np.max(relative[last_decade]) <= 0.01, (name, relative)
        assert np.max(relative) <= 0.03, (name, relative)
        rows.append(record(
            id=f"fluid-kgd-toughness-{name}",
            benchmark="KGD fracture, toughness regime (K_m = 7.2): E' = 32000 MPa, K_Ic = 1 "
            "MPa m^1/2, Q0 = 1e-4 m^2/s, two decades in time",
            reference="l = (E' Q0 t / (2 sqrt(pi) K_Ic))^(2/3), p = K_Ic / sqrt(pi l), "
            "w0 = 4 p l / E'", quantity=f"{quantity} at t = {time[-1]:.3f} s",
            value=float(value[-1]), reference_value=float(reference[-1]), tolerance=1e-2,
            mesh=f"{history['element_count'][-1] // 2} elements per wing at the end (10 at "
                 "the start, one more per step; worst of the last decade within the "
                 "tolerance too, of the first within 3e-2)"))
    assert all(row["passed"] for row in rows), rows


WATER, VISCOUS_TOUGHNESS = 1.0e-9, 1.0e-3


def viscous_kgd_text(elements, steps):
    """A KGD fracture in the viscosity regime (water, K_Ic = 1e-3 MPa m^1/2: K_m = 0.0013):
    0.25 m with `elements`, one more per wing and step."""
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress sxx = -1.0, syy = -1.0 /
&fracture name = 'crack', x = -0.125, 0.125, y = 0.0, 0.0, elements = {elements}, mu = 0.6,
          residual_aperture = 1.0e-7 /
&fluid viscosity = {WATER}, compressibility = 1.0e-4 /
&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, rate = {KGD_RATE} /
&load_path time = 0.0, 100.0, steps = 1 /
&growth steps = {steps}, toughness = {VISCOUS_TOUGHNESS} /
&solver k_method = 'tip_element' /
"""


def viscosity_solution(t):
    """KGD, viscosity-dominated, zero toughness (Adachi & Detournay 2002): half-length
    0.61524 (E' Q0^3 t^4 / mu')^(1/6), opening at the source gamma (A0 + A1 + 4 B) eps L with
    their series' gamma = 0.6152, A0 = 3^(1/2), A1 = -0.156, B = 0.0663."""
    mu_prime = 12.0 * WATER
    length = 0.61524 * (E_PRIME * KGD_RATE**3 * t**4 / mu_prime)**(1.0 / 6.0)
    omega0 = 0.6152 * (math.sqrt(3.0) - 0.156 + 4.0 * 0.0663)
    return length, omega0 * (mu_prime * KGD_RATE**3 * t**2 / E_PRIME)**(1.0 / 6.0)


def viscous_errors(result):
    """Per step: time, elements per wing, errors of the half-length and of the opening at
    the source."""
    history = result.history
    time = history["time"]
    x = 0.5 * (result.elements["x_begin"] + result.elements["x_end"])
    source = np.argsort(np.abs(x))[:2]
    length, opening = viscosity_solution(time)
    return (time, history["element_count"] // 2,
            (0.125 + history["grown_length"].mean(axis=1)) / length - 1.0,
            -history["dn"][:, source].mean(axis=1) / opening - 1.0)


def test_kgd_viscosity_regime(solve, record, tmp_path):
    k_prime = 4.0 * math.sqrt(2.0 / math.pi) * VISCOUS_TOUGHNESS
    assert k_prime * (1.0 / (E_PRIME**3 * 12.0 * WATER * KGD_RATE))**0.25 <= 0.1
    runs = {}
    for elements, steps in ((10, 32), (20, 205), (40, 124)):
        model = tmp_path / f"viscous{elements}.nml"
        model.write_text(viscous_kgd_text(elements, steps))
        runs[elements] = viscous_errors(solve(model, f"viscous{elements}"))
    time, wings, length_error, opening_error = runs[20]
    # Two decades in time; the last one starts with 66 elements per wing.
    assert time[-1] / time[0] > 100.0
    last_decade = time >= time[-1] / 10.0
    assert wings[last_decade][0] >= 20
    # The mesh: the errors at t = 1.25 s shrink as the start's elements double.
    at = [np.interp(1.25, runs[n][0], np.abs(runs[n][k])) for n in (10, 20, 40) for k in (2, 3)]
    assert at[0] > at[2] > at[4] and at[1] > at[3] > at[5], at
    rows = []
    for name, error, reference, tolerance, quantity in (
            ("half-length", length_error, viscosity_solution(time)[0], 3e-2,
             "half-length l to the front [m]"),
            ("opening", opening_error, viscosity_solution(time)[1], 5e-2,
             "opening at the source [m]")):
        assert np.max(np.abs(error[last_decade])) <= tolerance, (name, error)
        rows.append(record(
            id=f"fluid-kgd-viscosity-{name}",
            benchmark="KGD fracture, viscosity regime (K_m = 0.0013): E' = 32000 MPa, water "
            "(1e-9 MPa s), K_Ic = 1e-3 MPa m^1/2, Q0 = 1e-4 m^2/s, two decades in time",
            reference="Adachi & Detournay (2002): l = 0.61524 (E' Q0^3 t^4 / (12 eta))^(1/6), "
            "w0 = 1.133 (12 eta Q0^3 t^2 / E')^(1/6)", quantity=f"{quantity} at t = "
            f"{time[-1]:.3f} s", value=float((1.0 + error[-1]) * reference[-1]),
            reference_value=float(reference[-1]), tolerance=tolerance,
            mesh=f"{wings[-1]} elements per wing at the end (10 at the start, one more per "
                 "step; worst of the last decade within the tolerance; at t = 1.25 s "
                 f"{100 * at[0 if name == 'half-length' else 1]:.2f} / "
                 f"{100 * at[2 if name == 'half-length' else 3]:.2f} / "
                 f"{100 * at[4 if name == 'half-length' else 5]:.2f} % with 5 / 10 / 20 "
                 "elements per wing at the start)"))
    assert all(row["passed"] for row in rows), rows
