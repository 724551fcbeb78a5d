"""One rate-and-state element on a spring, integrated independently of ddc2d (scipy), which
tests/python/test_cycle.py and the verification row compare a single-element cycle run with
(docs/theory/cycles.md#back-slip-loading).

One element of half-length HALF in the full plane under back-slip at V_P is a spring-slider:
tau = TAU0 + k (delta - V_P t) with its own self-stiffness k = G / (pi (1 - nu) HALF).
scipy's DOP853 at rtol 1e-12 integrates slip and psi = ln(V0 theta / L), the slip rate of
each evaluation by brentq to 1e-15 on ln V.
"""

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

E, NU, HALF = 75000.0, 0.25, 500.0
G = E / (2.0 * (1.0 + NU))
A, B, DC, F0, V0, SIGMA, TAU0, VP, CS = 0.01, 0.015, 0.008, 0.6, 1.0e-6, 50.0, -30.0, 1e-9, 3464.0
ETA = G / (2.0 * CS)

#: The namelist of the element (format with end and law)
SLIDER = f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&fracture name = 'slider', x = -{HALF}, {HALF}, y = 0, 0, elements = 1,
  condition = 'rate_state', a = {A}, b = {B}, dc = {DC}, f0 = {F0}, v0 = {V0},
  v_init = {VP}, sigma0 = {SIGMA}, tau0 = {TAU0} /
&cycle end_time = {{end}}, shear_wave_speed = {CS}, plate_rate = {VP}, output_interval = 0,
  state_law = '{{law}}', checkpoint_interval = 0 /
"""


def spring_slider(law, end):
    """Times at which the slip rate reaches 1e-3 (upward) and the dense solution [slip,
    psi] of the spring-slider of SLIDER over [0, end], for the 'aging' or the 'slip' law."""
    k = G / (np.pi * (1.0 - NU) * HALF)

    def rate(drive, psi):
        shift = (F0 + B * psi) / A - np.log(2.0 * V0)

        def balance(x):
            return SIGMA * A * np.arcsinh(np.exp(x + shift)) + ETA * np.exp(x) - drive

        return np.exp(brentq(balance, -200.0, np.log(drive / ETA), xtol=1e-14, rtol=1e-15))

    def rates(t, y):
        v = rate(-(TAU0 + k * (y[0] - VP * t)), y[1])
        if law == "aging":
            return [v, (V0 * np.exp(-y[1]) - v) / DC]
        return [v, -(v / DC) * (y[1] + np.log(v / V0))]

    def seismic(t, y):
        return rate(-(TAU0 + k * (y[0] - VP * t)), y[1]) - 1.0e-3

    seismic.direction = 1
    psi0 = (A * (np.log(2.0 * V0 / VP) + np.log(np.sinh((-TAU0 - ETA * VP) / (A * SIGMA))))
            - F0) / B
    solution = solve_ivp(rates, (0.0, end), [0.0, psi0], method="DOP853", rtol=1e-12,
                         atol=[1e-14, 1e-12], dense_output=True, events=seismic)
    return solution.t_events[0], solution.sol
