"""Flow coupled to opening (docs/fluid-driven-fractures.md): &fluid switches the sources'
pressure from diffusion on fixed fractures to lubrication flow in the hydraulic aperture
w_res + max(opening, 0), solved with the contact run at every step.

Checked against closed forms: a crack filled by a fluid of negligible viscosity holds a
uniform pressure whose volume is that of a pressurized crack (the error falls as 1/n with
the elements); a closed fault is a linear diffusion of diffusivity w_res^2 / (12 eta c)
(backward Euler: the error falls as the time step); Carter's leak-off of a crack open from
the start. Every step conserves the volume (injected = stored + leaked off). A closed
frictional fault whose pressure exceeds its normal stress opens and conducts, the opening
front inside the slipping patch and moving out with it. Bad input gets one message.
"""

import math
import subprocess

import h5py
import numpy as np
import pytest

import ddc2d
from conftest import ddc2d_exe, solve_text

E, NU = 30000.0, 0.25
E_PRIME = E / (1.0 - NU**2)


def run(args, cwd):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=900)


def crack(elements, leak_off=0.0):
    """A 2 m crack under 1 MPa of confinement, a rate of 1e-4 m^2/s into its middle, a
    fluid of negligible viscosity (the pressure uniform along it)."""
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress sxx = -1.0, syy = -1.0 /
&fracture name = 'crack', x = -1.0, 1.0, y = 0.0, 0.0, elements = {elements}, mu = 0.6,
          residual_aperture = 1.0e-5 /
&fluid viscosity = 1.0e-12, compressibility = 1.0e-4, leak_off_coefficient = {leak_off} /
&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, rate = 1.0e-4 /
&load_path time = 0.0, 10.0, steps = 10 /
&solver k_method = 'tip_element' /
"""


def uniform_pressure(volume, confinement=1.0, half_length=1.0, compressibility=1.0e-4,
                     residual=1.0e-5):
    """The pressure p of a crack holding `volume` of fluid: the pressurized crack's volume
    2 pi (p - s) l^2 / E' at density 1 + c p, plus the residual aperture's compression."""
    def excess(p):
        opening = 2.0 * math.pi * (p - confinement) * half_length**2 / E_PRIME
        return opening * (1.0 + compressibility * p) + \
            2.0 * half_length * residual * compressibility * p - volume
    low, high = confinement, confinement + 1.0e4
    for _ in range(200):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if excess(middle) < 0.0 else (low, middle)
    return 0.5 * (low + high)


def assert_volume_conserved(history):
    injected = history["injected_volume"][1:]
    stored = history["stored_volume"][1:]
    leaked = history["leaked_volume"][1:]
    assert np.all(injected > 0.0)
    assert np.max(np.abs(injected - stored - leaked) / injected) <= 1e-8


@pytest.fixture(scope="module")
def cracks(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cracks")
    return {n: solve_text(folder, f"crack{n}", crack(n)) for n in (20, 40, 80)}


def test_a_crack_holds_the_pressure_of_its_volume(cracks):
    errors = {}
    for n, path in cracks.items():
        with h5py.File(path) as f:
            history = f["history"]
            assert history["time"][()] == pytest.approx(np.arange(11.0), abs=1e-12)
            assert_volume_conserved(history)
            assert np.max(history["flow_residual"][()]) <= 1e-6
            # A rate source lets in exactly its rate times the time.
            assert history["injected_volume"][()] == pytest.approx(1e-4 * np.arange(11.0),
                                                                   rel=1e-12, abs=1e-20)
            errors[n] = []
            for k in (2, 5, 10):
                pressure = history["pressure"][k]
                exact = uniform_pressure(history["injected_volume"][k])
                # Negligible viscosity: the pressure is uniform along the crack (the
                # viscous drop of the flux that fills it is 1.4e-4 of the net pressure).
                assert np.ptp(pressure) <= 1e-3 * (exact - 1.0)
                assert np.all(history["state"][k] == 3)
                errors[n].append((pressure.mean() - 1.0) / (exact - 1.0) - 1.0)
    # Constant elements hold too little volume near the tips: the net pressure is low by
    # about 1/n, halving with each doubling.
    for k in range(3):
        assert -0.05 < errors[20][k] < errors[40][k] < errors[80][k] < 0.0
        assert errors[20][k] / errors[40][k] == pytest.approx(2.0, abs=0.1)
        assert errors[40][k] / errors[80][k] == pytest.approx(2.0, abs=0.1)
    assert abs(errors[80][2]) < 0.013


def test_carter_leak_off_of_a_crack_open_from_the_start(tmp_path):
    path = solve_text(tmp_path, "leaky", crack(40, leak_off=1.0e-6))
    with h5py.File(path) as f:
        history = f["history"]
        assert_volume_conserved(history)
        time = history["time"][()]
        assert np.all(history["state"][1:] == 3)
        # 2 C_L / sqrt(t) per unit length on the 2 m open from the first step's start:
        # 2 C_L 2 m 2 sqrt(t).
        assert history["leaked_volume"][()] == pytest.approx(
            2.0 * 1.0e-6 * 2.0 * 2.0 * np.sqrt(time), rel=1e-12, abs=1e-20)
        efficiency = history["fluid_efficiency"][1:]
        assert np.all(efficiency < 1.0)
        assert efficiency == pytest.approx(history["stored_volume"][1:]
                                           / history["injected_volume"][1:], rel=1e-12)


def closed_fault(steps):
    """A fault held closed (normal stress 10, overpressure 1): linear diffusion."""
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


def test_a_closed_fault_diffuses_the_pressure(tmp_path):
    # T = w^3 / (12 eta), S = w c: alpha = w^2 / (12 eta c) = 8.33 m^2/s; at t = 1 s the
    # diffusion length sqrt(4 alpha t) is 5.8 m, 58 elements.
    alpha = 1.0e-10 / (12.0e-9 * 1.0e-3)
    worst = {}
    for steps in (10, 20, 40):
        path = solve_text(tmp_path, f"closed{steps}", closed_fault(steps))
        with h5py.File(path) as f:
            history = f["history"]
            elements = f["elements"]
            x = 0.5 * (elements["x_begin"][()] + elements["x_end"][()])
            assert_volume_conserved(history)
            assert np.all(history["state"][()] == 1)
            assert np.all(history["aperture"][()] == pytest.approx(1.0e-5, rel=1e-14))
            exact = np.array([math.erfc(abs(s) / math.sqrt(4.0 * alpha)) for s in x])
            worst[steps] = np.max(np.abs(history["pressure"][-1] - exact))
    # Backward Euler: first order in the time step.
    assert worst[10] / worst[20] == pytest.approx(2.0, abs=0.15)
    assert worst[20] / worst[40] == pytest.approx(2.0, abs=0.15)
    assert worst[40] < 4e-3


OPENING_FAULT = """\
&model youngs_modulus = 30000.0, poissons_ratio = 0.25 /
&remote_stress syy = -10.0, sxy = 3.0 /
&fracture name = 'fault', x = -10.0, 10.0, y = 0.0, 0.0, elements = 201, mu = 0.6,
          residual_aperture = 1.0e-5 /
&fluid viscosity = 1.0e-9, compressibility = 1.0e-3 /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = 12.0 /
&load_path time = 0.0, 0.5, steps = 10 /
&solver k_method = 'tip_element' /
"""


def test_a_fault_opens_where_the_pressure_exceeds_its_normal_stress(tmp_path):
    path = solve_text(tmp_path, "opening", OPENING_FAULT)
    with h5py.File(path) as f:
        history = f["history"]
        elements = f["elements"]
        x = 0.5 * (elements["x_begin"][()] + elements["x_end"][()])
        assert_volume_conserved(history)
        state = history["state"][()]
        aperture = history["aperture"][()]
        pressure = history["pressure"][()]
        opened, slipped = [], []
        for k in range(1, 11):
            open_x = x[state[k] == 3]
            slip_x = x[state[k] >= 2]
            # One patch each, about the source; the open one inside the slipping one.
            assert np.ptp(np.diff(np.flatnonzero(state[k] == 3))) == 0
            assert open_x.min() == pytest.approx(-open_x.max(), abs=1e-9)
            assert slip_x.min() < open_x.min() and open_x.max() < slip_x.max()
            opened.append(open_x.max())
            slipped.append(slip_x.max())
            # The open faces carry the fluid's pressure alone, and conduct through their
            # opening; the closed ones through the residual aperture.
            total = history["normal_traction"][k] + pressure[k]
            assert np.max(np.abs(total[state[k] == 3])) < 1e-9 * 10.0
            assert np.all(aperture[k][state[k] == 3] > 1.0e-5)
            assert aperture[k][state[k] != 3] == pytest.approx(1.0e-5, rel=1e-14)
        # Both fronts move out together.
        assert np.all(np.diff(opened) > 0.0) and np.all(np.diff(slipped) > 0.0)
        assert opened[-1] > 2.0 and slipped[-1] > opened[-1] + 2.0
        # The flux runs away from the source on both sides.
        flux = history["flux"][-1]
        assert np.all(flux[x < -0.2][state[-1][x < -0.2] == 3] < 0.0)
        assert np.all(flux[x > 0.2][state[-1][x > 0.2] == 3] > 0.0)


def test_output_and_python(cracks):
    path = cracks[20]
    with h5py.File(path) as f:
        injection = f["injection"]
        assert injection.attrs["viscosity"] == pytest.approx(1.0e-12)
        assert injection.attrs["compressibility"] == pytest.approx(1.0e-4)
        assert f["elements/residual_aperture"][()] == pytest.approx(np.full(20, 1.0e-5))
        history = f["history"]
        assert history["aperture"].attrs["units"].decode().strip() == "m"
        assert history["flux"].attrs["units"].decode().strip() == "m^2/s"
        assert history["stored_volume"].attrs["units"].decode().strip() == "m^2"
        assert history["flow_iterations"][0] == 0
    result = ddc2d.open_result(path)
    data = result.to_xarray("history")
    assert data["aperture"].dims == ("step", "element")
    assert data["fluid_efficiency"].dims == ("step",)
    assert float(data["fluid_efficiency"][-1]) == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("change, message", [
    (("&fluid viscosity = 1.0e-12, compressibility = 1.0e-4, leak_off_coefficient = 0.0 /",
      "&fluid compressibility = 1.0e-4 /"), "viscosity is required"),
    (("compressibility = 1.0e-4,", "compressibility = 0.0,"), "compressibility = 0"),
    (("residual_aperture = 1.0e-5 /",
      "residual_aperture = 1.0e-5, diffusivity = 1.0, transmissivity = 1.0 /"),
     "with &fluid the flow follows from the aperture"),
    (("residual_aperture = 1.0e-5 /", "/"), "does not conduct"),
    (("&load_path time = 0.0, 10.0, steps = 10 /",
      ("&load_path time = 0.0, 10.0, steps = 10 /\n&growth steps = 3, toughness = 1.0, "
       "increment = 0.1 /")), "coupled flow does not combine with &growth increment"),
    (("&solver k_method = 'tip_element' /",
      "&growth steps = 3, toughness = 1.0 /\n&solver k_method = 'higher_order' /"),
     "coupled flow does not combine with &growth and &solver k_method = 'higher_order'"),
    (("&fluid viscosity = 1.0e-12, compressibility = 1.0e-4, leak_off_coefficient = 0.0 /",
      ""), "residual_aperture is for flow coupled to the opening"),
])
def test_bad_input(tmp_path, change, message):
    text = crack(20).replace(*change)
    assert text != crack(20)
    (tmp_path / "bad.nml").write_text(text)
    done = run(["bad.nml"], tmp_path)
    assert done.returncode == 2, done.stdout + done.stderr
    assert message in done.stderr
    assert not (tmp_path / "bad.h5").exists()
