"""Fluid injection into a fault against closed forms (docs/verification.md;
docs/theory/injection.md): the pressure a held source makes along a fault, the self-similar
slip front of a planar fault under a constant overpressure at one point (Bhattacharya &
Viesca 2019) for five stress-injection parameters T, its slip profiles in the critically
stressed and marginally pressurized limits, and the jump of a slip-weakening patch
(Garagash & Germanovich 2012).

The fault lies along x under s0' = 10 (syy = -10), friction 0.6, no cohesion, with alpha = 1
and T_h = 1; the overpressure dp = 5 is held at x = 0 from t = 0 and the front is compared at
t = 0.5, 0.75 and 1 (sqrt(4 alpha t) = 2 at the end). The mesh is fine (200 elements per
final half-length a) within 1.25 a of the source and has 20 elements per sqrt(4 alpha t) at
t = 0.25 outside, out to where the pressure stays below 1e-6 of dp."""

import math

import numpy as np
import pytest

from ddc2d.injection import (
    critical_slip_profile,
    front_factor,
    injection_parameter,
    marginal_slip_profile,
    overpressure_profile,
)

E, NU, F, S0, DP = 30000.0, 0.25, 0.6, 10.0, 5.0
G = E / (2 * (1 + NU))
MU_PRIME = G / (2 * (1 - NU))
TIMES = (0.5, 0.75, 1.0)
VIESCA = "Bhattacharya & Viesca (2019); Viesca (2021)"


def fault_model(parameter, per_front=200, friction_drop=None):
    """The fault with tau0 from T (text of a namelist), and its inner element length."""
    tau0 = F * S0 - parameter * F * DP
    reach = front_factor(parameter) * 2.0
    inner = 1.25 * reach
    end = max(8.0, 1.3 * inner)
    fine = 2 * math.ceil(inner / (reach / per_front)) + 1
    coarse = math.ceil((end - inner) / max(0.05, 2 * inner / fine))
    laws = ""
    if friction_drop is not None:
        laws = f", mu_dynamic = {friction_drop[0]}, slip_weakening_distance = {friction_drop[1]}"
    text = f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress syy = {-S0}, sxy = {tau0} /
&fracture name = 'fault', x = {-end}, {-inner}, {inner}, {end}, y = 0, 0, 0, 0,
          elements = {coarse}, {fine}, {coarse}, mu = {F}, sf = 0.0,
          diffusivity = 1.0, transmissivity = 1.0{laws} /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = {DP} /
&load_path time = 0.0, 0.25, 1.0, steps = 1, 3 /
&solver k_method = 'tip_element', lcp_method = 'newton' /
"""
    return text, 2 * inner / fine


def solve_text(solve, tmp_path, text, name):
    path = tmp_path / f"{name}.nml"
    path.write_text(text)
    return solve(path, name)


def fronts(result):
    """Half the distance between the outer ends of the outermost slipping elements, at
    each step."""
    history = result.history
    return 0.5 * (history["front_end"][:, 0] - history["front_begin"][:, 0])


@pytest.mark.parametrize("parameter, tolerance", [(0.1, 0.01), (0.3, 0.01), (0.5, 0.01),
                                                  (0.7, 0.01), (0.9, 0.02)])
def test_the_front_is_self_similar(solve, record, tmp_path, parameter, tolerance):
    text, element = fault_model(parameter)
    result = solve_text(solve, tmp_path, text, f"front{parameter}")
    time = result.history["time"]
    steps = [int(np.argmin(np.abs(time - t))) for t in TIMES]
    assert time[steps] == pytest.approx(TIMES, abs=1e-12)
    ratios = fronts(result)[steps] / np.sqrt(4.0 * time[steps])
    lam = front_factor(parameter)
    row = record(id=f"injection-front-{parameter}", benchmark="Slip front of a fault under "
                 f"an overpressure held at one point, T = {parameter} ({VIESCA})",
                 reference="a = lambda(T) sqrt(4 alpha t), T = (2/pi) int erfc(lambda cos z) "
                 "dz", quantity="a / sqrt(4 alpha t) at t = 1 (a: half the slipping length)",
                 value=float(ratios[-1]), reference_value=lam, tolerance=tolerance,
                 mesh=f"{round(lam * 2 / element)} elements over a at t = 1 (graded fault), "
                 "steps of 0.25 in t",
                 order=None)
    assert row["passed"], row
    # Self-similar: the same at every compared time, within the tolerance.
    assert np.max(np.abs(ratios / lam - 1.0)) <= tolerance, ratios / lam
    assert np.ptp(ratios) / lam <= tolerance
    assert injection_parameter(F, S0, F * S0 - parameter * F * DP, DP) == pytest.approx(
        parameter, rel=1e-12)
    if parameter == 0.9:
        check_profile(result, record, steps[-1], parameter, "marginal")


def check_profile(result, record, step, parameter, limit):
    """The slip profile at the step against a limit's closed form on |x / a| < 0.9."""
    lam = front_factor(parameter)
    time = result.history["time"][step]
    a = lam * math.sqrt(4.0 * time)
    x = result.elements["x_mid"]
    inside = np.abs(x / a) < 0.9
    if limit == "critical":
        inside &= np.abs(x / a) >= 0.2
    scale = math.sqrt(4.0 * time) * F * DP / MU_PRIME
    slip = np.abs(result.history["ds"][step]) / scale
    if limit == "marginal":
        exact = marginal_slip_profile(x / a, lam)
    else:
        exact = critical_slip_profile(x / a)
    gap = float(np.max(np.abs(slip[inside] - exact[inside])) / np.max(exact[inside]))
    row = record(id=f"injection-profile-{limit}", benchmark="Slip profile of a fault under "
                 f"an overpressure held at one point, T = {parameter} ({VIESCA})",
                 reference=("marginally pressurized limit (T -> 1)" if limit == "marginal"
                            else "critically stressed limit (T -> 0)"),
                 quantity="largest difference of slip / (sqrt(4 alpha t) f dp / mu') on "
                 f"{'0.2 <= ' if limit == 'critical' else ''}|x/a| < 0.9, over the largest "
                 "slip there", value=gap,
                 reference_value=0.0, tolerance=0.02, mesh=f"{np.count_nonzero(inside)} "
                 "elements on |x/a| < 0.9", order=None, tolerance_kind="absolute")
    assert row["passed"], row


def test_critically_stressed_profile(solve, record, tmp_path):
    """T = 0.02: the T -> 0 limit is singular at the source (log) and approached as T
    shrinks (0.2 <= |x/a| < 0.9: 7.9 % at T = 0.05, 1.3 % at T = 0.02), so the row compares
    T = 0.02 there."""
    text, _ = fault_model(0.02)
    result = solve_text(solve, tmp_path, text, "critical")
    check_profile(result, record, len(result.history["time"]) - 1, 0.02, "critical")


def test_the_pressure_of_a_held_source(solve, record, tmp_path):
    """A fault that does not slip (no shear stress): the pressure along it is dp erfc(|x| /
    sqrt(4 alpha t)), here at 20 elements per sqrt(4 alpha t) = 1 (t = 0.25)."""
    text = f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress syy = {-S0} /
&fracture name = 'fault', x = -4.0, 4.0, y = 0.0, 0.0, elements = 161, mu = {F},
          diffusivity = 1.0, transmissivity = 1.0 /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = {DP} /
&load_path time = 0.0, 0.25, steps = 1 /
&solver k_method = 'tip_element' /
"""
    result = solve_text(solve, tmp_path, text, "pressure")
    x = result.elements["x_mid"]
    gap = float(np.max(np.abs(result.history["pressure"][-1]
                              - overpressure_profile(x, 0.25, 1.0, DP))) / DP)
    row = record(id="injection-pressure-erfc", benchmark="Pressure along a fault from an "
                 "overpressure held at one point", reference="dp erfc(|s| / sqrt(4 alpha t))",
                 quantity="largest difference over dp", value=gap, reference_value=0.0,
                 tolerance=1e-3, mesh="20 elements per sqrt(4 alpha t)", order=None,
                 tolerance_kind="absolute")
    assert row["passed"], row
    # No shear stress: nothing slips; where the pressure exceeds s0' an element would open.
    assert np.all(result.elements["state"] == 1)


def test_a_weakening_patch_jumps(solve, record, tmp_path):
    """Linear slip weakening f_p = 0.6 to f_r = 0.36, tau0 / (f_p s0') = 0.55, dp / s0' = 0.5
    (T = 0.9 with the peak friction): the patch grows stably, jumps near sqrt(4 alpha t) /
    a_w = 4.9 from about 1.1 a_w to about 3.9 a_w, and goes on growing (Garagash &
    Germanovich 2012); a_w = G d_c / ((1 - nu) (f_p - f_r) s0') = 1 here, 10 elements per
    a_w."""
    d_c = 1.0 * (1 - NU) * (0.6 - 0.36) * S0 / G
    text = f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress syy = -10.0, sxy = 3.3 /
&fracture name = 'fault', x = -24.0, -5.0, 5.0, 24.0, y = 0.0, 0.0, 0.0, 0.0,
          elements = 19, 101, 19, mu = 0.6, sf = 0.0, mu_dynamic = 0.36,
          slip_weakening_distance = {d_c}, diffusivity = 1.0, transmissivity = 1.0 /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = 5.0 /
&load_path time = 0.0, 4.0, 9.0, steps = 8, 25 /
&solver k_method = 'tip_element', lcp_method = 'newton' /
"""
    result = solve_text(solve, tmp_path, text, "weakening")
    half = fronts(result)
    diffusion = np.sqrt(4.0 * result.history["time"])
    growth = np.diff(half)
    jump = int(np.argmax(growth)) + 1
    # One jump: the rest grows by at most a few elements a step.
    assert growth[jump - 1] > 2.0 and np.all(np.delete(growth, jump - 1) <= 0.25)
    row = record(id="injection-weakening-jump", benchmark="A slip-weakening patch under an "
                 "overpressure held at one point (Garagash & Germanovich 2012)",
                 reference="the jump at sqrt(4 alpha t) / a_w = 4.9", quantity="sqrt(4 alpha "
                 "t) / a_w of the step the patch jumps in", value=float(diffusion[jump]),
                 reference_value=4.9, tolerance=0.02, mesh="10 elements per a_w, steps of "
                 "0.08 a_w in sqrt(4 alpha t)", order=None)
    assert row["passed"], row
    assert half[jump - 1] == pytest.approx(1.1, abs=0.2)
    assert half[jump] == pytest.approx(3.9, abs=0.2)
