"""Fluid-driven growth (docs/fluid-driven-fractures.md#hydraulic-fractures): &growth with
&fluid grows the fractures by one element per tip and step, the time it takes solved for
(K_I of the growing tips reaches the apparent toughness of the front's velocity), the front
located by the tip asymptote.

A KGD fracture in the toughness regime (K_m >= 4) against its closed form: half-length,
net pressure and opening at the source converge to it as the wings gain elements; K_I is
the apparent toughness at every step; the volume is conserved. A KGD fracture in the
viscosity regime (K_m <= 0.1) against Adachi & Detournay's solution. A hydraulic fracture
that reaches a fault stops on it and the fluid enters the fault. &growth criterion = 'work'
is refused.
"""

import math
import re
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import PLOT_SCRIPT, ddc2d_exe, kgd_viscosity_solution, solve_text

E, NU = 30000.0, 0.25
E_PRIME = E / (1.0 - NU**2)
# Far into the toughness regime (K_m = 23), where the closed form (zero viscosity) holds.
TOUGHNESS, RATE, VISCOSITY = 1.0, 1.0e-4, 1.0e-14



def kgd_text(half_length, elements, residual_aperture, viscosity, toughness):
    """A KGD fracture of `elements` from the well at its middle, 60 growth steps."""
    return f"""\
&model youngs_modulus = {E}, poissons_ratio = {NU} /
&remote_stress sxx = -1.0, syy = -1.0 /
&fracture name = 'crack', x = {-half_length}, {half_length}, y = 0.0, 0.0,
          elements = {elements}, mu = 0.6, residual_aperture = {residual_aperture} /
&fluid viscosity = {viscosity}, compressibility = 1.0e-4 /
&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, rate = {RATE} /
&load_path time = 0.0, 100.0, steps = 1 /
&growth steps = 60, toughness = {toughness} /
&solver k_method = 'tip_element' /
"""


KGD = kgd_text(0.1, 8, 1.0e-6, VISCOSITY, TOUGHNESS)


def run(args, cwd):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=900)


def toughness_solution(t):
    """KGD, toughness-dominated: half-length, net pressure, opening at the source."""
    length = (E_PRIME * RATE * t / (2.0 * math.sqrt(math.pi) * TOUGHNESS))**(2.0 / 3.0)
    pressure = TOUGHNESS / math.sqrt(math.pi * length)
    return length, pressure, 4.0 * pressure * length / E_PRIME


def apparent_toughness(toughness, viscosity, velocity, half_length):
    """K_I of a tip element (K = E' w / (4 sqrt(h))) whose opening lies on w^3 = w_k^3 + w_m^3,
    the toughness and viscosity asymptotes, at r = pi h / 2 (docs/theory)."""
    beta_m = 2.0**(1.0 / 3.0) * 3.0**(5.0 / 6.0)
    r = 0.5 * math.pi * half_length
    viscous = beta_m * (12.0 * viscosity * velocity / E_PRIME)**(1.0 / 3.0) * r**(2.0 / 3.0)
    k_viscous = E_PRIME * viscous / (4.0 * math.sqrt(half_length))
    return (toughness**3 + k_viscous**3)**(1.0 / 3.0)


def step_velocities(time, half_length):
    """The fronts move by one element (2 h) per step; not at the first."""
    return np.concatenate([[0.0], 2.0 * half_length / np.diff(time)])


def kgd_errors(path, initial_half_length):
    """Per step: elements per wing and the relative errors of the half-length (to the
    front), the net pressure and the opening at the source."""
    rows = []
    with h5py.File(path) as f:
        history = f["history"]
        elements = f["elements"]
        middle = np.argsort(np.abs(0.5 * (elements["x_begin"][()] + elements["x_end"][()])))[:2]
        for k, t in enumerate(history["time"][()]):
            length, pressure, opening = toughness_solution(t)
            front = initial_half_length + history["grown_length"][k]
            rows.append((history["element_count"][k] // 2,
                         front.mean() / length - 1.0,
                         (history["pressure"][k][middle].mean() - 1.0) / pressure - 1.0,
                         -history["dn"][k][middle].mean() / opening - 1.0))
    return np.array(rows)


@pytest.fixture(scope="module")
def kgd(tmp_path_factory):
    return solve_text(tmp_path_factory.mktemp("kgd"), "kgd", KGD)


def test_kgd_in_the_toughness_regime(kgd):
    # The dimensionless toughness K_m = K' (1 / (E'^3 12 eta Q0))^(1/4): toughness regime.
    k_prime = 4.0 * math.sqrt(2.0 / math.pi) * TOUGHNESS
    assert k_prime * (1.0 / (E_PRIME**3 * 12.0 * VISCOSITY * RATE))**0.25 >= 4.0
    errors = kgd_errors(kgd, 0.1)
    wings, length, pressure, opening = errors.T
    assert wings[0] == 4 and np.all(np.diff(wings) == 1)
    # Within 2.1, 6.3 and 2.8 % at 4 elements per wing; 0.55, 1.5 and 0.75 % at 20; all
    # shrinking as the wings gain elements (first order).
    assert abs(length[0]) < 0.021 and abs(pressure[0]) < 0.065 and abs(opening[0]) < 0.028
    at20 = np.flatnonzero(wings == 20)[0]
    assert abs(length[at20]) < 0.0055 and abs(pressure[at20]) < 0.0155
    assert abs(opening[at20]) < 0.0075
    for error in (length, pressure, opening):
        assert np.all(np.diff(np.abs(error)) < 1e-9)
    assert abs(length[-1]) < 0.0035 and abs(pressure[-1]) < 0.01 and abs(opening[-1]) < 0.0045


def test_kgd_steps(kgd):
    with h5py.File(kgd) as f:
        history = f["history"]
        time = history["time"][()]
        assert np.all(np.diff(time) > 0.0)
        # Every step: K_I of both tips is the apparent toughness, the fronts symmetric.
        expected = [apparent_toughness(TOUGHNESS, VISCOSITY, v, 0.0125)
                    for v in step_velocities(time, 0.0125)]
        assert expected[-1] > TOUGHNESS
        assert history["k1"][()] == pytest.approx(np.repeat(np.array(expected)[:, None], 2,
                                                            axis=1), rel=2e-6)
        grown = history["grown_length"][()]
        assert grown[:, 0] == pytest.approx(grown[:, 1], rel=1e-9)
        # One element per step; the front's place in the tip element moves with K_I within
        # its tolerance (1e-6 of the toughness).
        assert np.diff(grown[:, 0]) == pytest.approx(np.full(len(time) - 1, 0.025), abs=1e-7)
        assert list(history["tip_end"][()]) == [0, 1]
        # Rows of elements made later hold the fill values before.
        state = history["state"][()]
        assert np.all((state[0] == -1) == np.isnan(history["aperture"][0]))
        assert np.count_nonzero(state[0] >= 0) == 8
        # The volume injected is stored.
        injected = history["injected_volume"][()]
        assert injected == pytest.approx(RATE * time, rel=1e-12)
        assert np.max(np.abs(injected - history["stored_volume"][()]) / injected) < 1e-8


VISCOUS_TOUGHNESS, WATER = 1.0e-3, 1.0e-9

VISCOUS_KGD = kgd_text(0.125, 20, 1.0e-7, WATER, VISCOUS_TOUGHNESS)


def test_kgd_in_the_viscosity_regime(tmp_path):
    k_prime = 4.0 * math.sqrt(2.0 / math.pi) * VISCOUS_TOUGHNESS
    assert k_prime * (1.0 / (E_PRIME**3 * 12.0 * WATER * RATE))**0.25 <= 0.1
    path = solve_text(tmp_path, "viscous", VISCOUS_KGD)
    with h5py.File(path) as f:
        history = f["history"]
        elements = f["elements"]
        middle = np.argsort(np.abs(0.5 * (elements["x_begin"][()] + elements["x_end"][()])))[:2]
        time = history["time"][()]
        wings = history["element_count"][()] // 2
        length, opening = kgd_viscosity_solution(time, E_PRIME, WATER, RATE)
        length_error = (0.125 + history["grown_length"][()].mean(axis=1)) / length - 1.0
        opening_error = -history["dn"][()][:, middle].mean(axis=1) / opening - 1.0
        # K_I at every step is the apparent toughness of the front's velocity, which the
        # viscosity makes many times the rock's toughness. The closed crack's tips open at
        # once past the toughness: the first step ends there.
        expected = [apparent_toughness(VISCOUS_TOUGHNESS, WATER, v, 0.00625)
                    for v in step_velocities(time, 0.00625)]
        assert min(expected[1:]) > 50.0 * VISCOUS_TOUGHNESS
        k1 = history["k1"][()]
        assert np.all(k1[0] > VISCOUS_TOUGHNESS)
        assert k1[1:] == pytest.approx(np.repeat(np.array(expected[1:])[:, None], 2, axis=1),
                                       rel=2e-6)
        injected = history["injected_volume"][()]
        assert np.max(np.abs(injected - history["stored_volume"][()]) / injected) < 1e-8
    # The crack starts longer than the solution's (it forgets its start as it grows):
    # 1.9 and -2.1 % at 20 elements per wing, 1.45 and -1.50 % at 70, both shrinking.
    settled = wings >= 20
    assert np.max(np.abs(length_error[settled])) <= 0.03
    assert np.max(np.abs(opening_error[settled])) <= 0.05
    assert np.all(np.diff(np.abs(length_error[1:])) < 1e-9)
    assert np.all(np.diff(np.abs(opening_error)) < 1e-9)
    assert abs(length_error[-1]) < 0.015 and abs(opening_error[-1]) < 0.016
    # The figure draws the viscosity solution's half-length and opening (dotted).
    import matplotlib.pyplot as plt

    from ddc2d.plot import figures
    from ddc2d.reader import load_result

    figure = figures.plot_hydraulic_fracture(load_result(path))
    lines = {line.get_gid(): line for ax in figure.axes for line in ax.get_lines()}
    for key, error in (("half_length", length_error), ("opening", opening_error)):
        drawn = lines[f"{key}:crack"].get_ydata()
        assert drawn / lines[f"viscosity_{key}:crack"].get_ydata() - 1.0 == pytest.approx(
            error, rel=1e-9, abs=1e-12)
    plt.close(figure)


def test_the_figure_against_the_closed_forms(kgd, tmp_path):
    import matplotlib.pyplot as plt

    from ddc2d.plot import figures
    from ddc2d.reader import load_result

    figure = figures.plot_hydraulic_fracture(load_result(kgd))
    lines = {line.get_gid(): line for ax in figure.axes for line in ax.get_lines()}
    errors = kgd_errors(kgd, 0.1)
    time = lines["half_length:crack"].get_xdata()
    for column, key in enumerate(("half_length", "net_pressure", "opening"), start=1):
        drawn = lines[f"{key}:crack"].get_ydata()
        closed = lines[f"toughness_{key}:crack"].get_ydata()
        # The points are the run's, the dashed line the toughness solution.
        assert drawn / closed - 1.0 == pytest.approx(errors[:, column], abs=1e-12)
    length, _, _ = toughness_solution(time[-1])
    assert lines["toughness_half_length:crack"].get_ydata()[-1] == pytest.approx(length)
    # The viscosity solution of this fluid lies far above: the toughness regime.
    assert np.all(lines["viscosity_half_length:crack"].get_ydata()
                  > lines["toughness_half_length:crack"].get_ydata())
    plt.close(figure)
    done = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(kgd), "-o", str(tmp_path)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "kgd_hydraulic_fracture.png").is_file()


FAULT = """\
&model youngs_modulus = 30000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -1.0, syy = -3.0, sxy = 0.5 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 40, mu = 0.6,
          residual_aperture = 1.0e-5 /
&fracture name = 'hydrofracture', x = 0.0, 0.0, y = 0.15, 0.35, elements = 8, mu = 0.6,
          residual_aperture = 1.0e-6 /
&fluid viscosity = 1.0e-9, compressibility = 1.0e-3 /
&injection name = 'well', fracture = 'hydrofracture', x = 0.0, y = 0.25, rate = 1.0e-4 /
&load_path time = 0.0, 100.0, steps = 1 /
&growth steps = 8, toughness = 1.0, fractures = 'hydrofracture' /
&solver k_method = 'tip_element' /
"""


def test_a_hydraulic_fracture_that_reaches_a_fault_feeds_it(tmp_path):
    path = solve_text(tmp_path, "fault", FAULT)
    with h5py.File(path) as f:
        history = f["history"]
        elements = f["elements"]
        # Its lower end reaches the fault in step 6 and stops on it; the upper one grows on.
        grown = history["grown_length"][()]
        assert list(history["element_count"][()]) == [48, 50, 52, 54, 56, 58, 60, 61, 62]
        assert grown[6:, 0] == pytest.approx(0.15, abs=1e-12)
        assert np.all(np.diff(grown[:, 1]) > 0.0)
        hydro = elements["fracture_id"][()] == 2
        assert np.min(elements["y_begin"][()][hydro]) == pytest.approx(0.0, abs=1e-12)
        # The fluid entered the fault: before the link it held none, after it every cell.
        fault = elements["fracture_id"][()] == 1
        pressure = history["pressure"][()]
        assert np.all(pressure[5][fault] == 0.0)
        assert np.all(pressure[-1][fault] > 0.0)
        injected = history["injected_volume"][()]
        assert np.max(np.abs(injected - history["stored_volume"][()]) / injected) < 1e-8


# A hydraulic fracture at 30 degrees to a fault (the gallery's stresses scaled down).
NARROW_JUNCTION = """\
&model youngs_modulus = 30000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -2.875, syy = -1.625, sxy = 1.0826 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 40, mu = {mu}, sf = 0.02,
          residual_aperture = 1.0e-5 /
&fracture name = 'hydrofracture', x = -0.1732, 0.0, y = 0.2, 0.1, elements = 8, mu = 0.6,
          residual_aperture = 1.0e-5 /
&fluid viscosity = 1.0e-9, compressibility = 1.0e-3 /
&injection name = 'well', fracture = 'hydrofracture', x = -0.0866, y = 0.15, rate = 1.0e-4 /
&load_path time = 0.0, 100.0, steps = 1 /
&growth steps = 12, toughness = 1.0, fractures = 'hydrofracture' /
&solver k_method = 'tip_element' /
"""


def test_a_hydraulic_fracture_links_to_a_fault_at_a_narrow_angle(tmp_path):
    # A strong fault (mu = 5): the lower tip ends on it at step 8 and stops, the fluid
    # enters the fault and raises its pressure past its normal stress (1.625 MPa), and the
    # fault's elements near the junction slip; the upper tip grows on. The coupled solve's
    # Jacobian takes the slipping elements' response in (without it the step of the link
    # does not converge).
    path = solve_text(tmp_path, "strong", NARROW_JUNCTION.format(mu=5.0))
    with h5py.File(path) as f:
        history = f["history"]
        elements = f["elements"]
        assert list(history["element_count"][()]) == [48, 50, 52, 54, 56, 58, 60, 62, 64, 65,
                                                      66, 67, 68]
        hydro = elements["fracture_id"][()] == 2
        assert np.min(elements["y_end"][()][hydro]) == pytest.approx(0.0, abs=1e-12)
        fault = elements["fracture_id"][()] == 1
        pressure = history["pressure"][()]
        assert np.all(np.abs(pressure[:5][:, fault]) < 1e-9)
        assert np.all(np.nanmax(pressure[8:][:, fault], axis=1) > 1.625)
        state = history["state"][()]
        assert np.count_nonzero(state[-1][fault] == 2) >= 5
        injected = history["injected_volume"][()]
        assert np.max(np.abs(injected - history["stored_volume"][()]) / injected) < 1e-8


def test_a_run_that_fails_keeps_the_steps_it_made(tmp_path):
    # A fault of mu = 0.7 slips widely once the fluid enters it; a step after the link does
    # not converge (the slip front moving through the step): exit 6, the steps before it
    # kept in a file that says so.
    (tmp_path / "junction.nml").write_text(NARROW_JUNCTION.format(mu=0.7))
    done = run(["junction.nml"], tmp_path)
    assert done.returncode == 6, done.stdout + done.stderr
    found = re.search(r"fluid-driven growth, step (\d+): .*the run stopped there: the result "
                      r"holds the (\d+) step\(s\) before it", done.stderr)
    assert found, done.stderr
    failed, kept = int(found.group(1)), int(found.group(2))
    assert kept == failed >= 1
    with h5py.File(tmp_path / "junction.h5") as f:
        assert f.attrs["complete"] == 1
        assert "the run stopped there" in f.attrs["stopped"].decode()
        history = f["history"]
        time = history["time"][()]
        assert len(time) == kept and np.all(np.diff(time) > 0.0)
        # The final geometry is the last step's: its elements, every one made by then.
        elements = f["elements"]
        assert history["element_count"][-1] == len(elements["x_begin"])
        assert np.all(history["state"][-1] >= 0)
        injected = history["injected_volume"][()]
        assert np.max(np.abs(injected - history["stored_volume"][()]) / injected) < 1e-8


def test_the_work_criterion_is_refused(tmp_path):
    (tmp_path / "bad.nml").write_text(KGD.replace("toughness = 1.0 /",
                                                  "toughness = 1.0, criterion = 'work' /"))
    done = run(["bad.nml"], tmp_path)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "coupled flow does not combine with &growth criterion = 'work'" in done.stderr
    assert not (tmp_path / "bad.h5").exists()
