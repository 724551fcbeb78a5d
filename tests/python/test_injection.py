"""Fluid injection into a fault (docs/injection.md): the input's checks of &injection, the
time axis and the hydraulic properties, and a fault whose slipping patch grows with the
pressure that diffuses from a source held at its middle: the front at the self-similar
solution's position within one element (the measure's quantum), the history's datasets.
"""

import math
import subprocess

import h5py
import numpy as np
import pytest

from conftest import ddc2d_exe
from ddc2d.injection import front_factor, injection_parameter

#: A straight fault of 201 elements (h = 0.04) under s0 = 10, tau0 = 4.5, f = 0.6, an
#: overpressure of 5 held at its middle: T = 0.5.
FAULT = """\
&model youngs_modulus = 30000.0, poissons_ratio = 0.25, time_unit = 'h' /
&remote_stress syy = -10.0, sxy = 4.5 /
&fracture name = 'fault', x = -4.0, 4.0, y = 0.0, 0.0, elements = 201, mu = 0.6, sf = 0.0,
          diffusivity = 1.0, transmissivity = 1.0 /
&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = 5.0 /
&load_path time = 0.0, 0.4, steps = 4 /
&solver k_method = 'tip_element' /
"""


def run(args, cwd):
    return subprocess.run([str(ddc2d_exe()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=600)


def test_the_front_follows_the_self_similar_solution(tmp_path):
    (tmp_path / "fault.nml").write_text(FAULT)
    done = run(["fault.nml"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "t = 0.1 h" in done.stdout.replace("0.100000", "0.1")
    lam = front_factor(injection_parameter(0.6, 10.0, 4.5, 5.0))
    assert lam == pytest.approx(0.791607, abs=1e-6)
    with h5py.File(tmp_path / "fault.h5") as f:
        assert f.attrs["time_unit"].decode().strip() == "h"
        history = f["history"]
        time = history["time"][()]
        assert time == pytest.approx([0.0, 0.1, 0.2, 0.3, 0.4], abs=1e-15)
        assert history["time"].attrs["units"].decode().strip() == "h"
        front_begin = history["front_begin"][:, 0]
        front_end = history["front_end"][:, 0]
        element = 8.0 / 201
        for k in range(1, len(time)):
            half = 0.5 * (front_end[k] - front_begin[k])
            # The measure takes whole elements: within one of the exact front.
            assert abs(half - lam * math.sqrt(4.0 * time[k])) <= element
            # Symmetric about the source, along the fault from its first vertex at x = -4.
            assert 0.5 * (front_end[k] + front_begin[k]) == pytest.approx(4.0, abs=1e-12)
        # At the start the source's element alone holds the pressure; the patch and the
        # moment grow after.
        assert history["slipping_length"][0, 0] == pytest.approx(element, rel=1e-12)
        assert np.all(np.diff(history["slipping_length"][:, 0]) > 0.0)
        assert np.all(np.diff(history["moment"][:, 0]) > 0.0)
        # The pressure a held source makes: erfc, and the volume it let in stored.
        pressure = history["pressure"][()]
        x = f["elements/x_mid"][()]
        exact = 5.0 * np.array([math.erfc(abs(s) / math.sqrt(4.0 * 0.4)) for s in x])
        assert np.max(np.abs(pressure[-1] - exact)) <= 0.05 * 5.0
        stored = np.sum(pressure[-1] * 8.0 / 201)
        assert history["injected_volume"][-1] == pytest.approx(stored, rel=1e-9)
        assert f["injection/overpressure"][0] == 5.0 and np.isnan(f["injection/rate"][0])


def test_a_path_of_times_alone(tmp_path):
    text = FAULT.replace("&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, "
                         "overpressure = 5.0 /\n", "")
    (tmp_path / "times.nml").write_text(text)
    done = run(["times.nml"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    with h5py.File(tmp_path / "times.h5") as f:
        assert f["history/time"][()] == pytest.approx([0.0, 0.1, 0.2, 0.3, 0.4])
        assert "pressure" not in f["history"] and "injection" not in f
        # Nothing changes along the path: every step is the first.
        assert np.all(f["history/ds"][()] == f["history/ds"][0])


@pytest.mark.parametrize("old, new, words", [
    ("x = 0.0, y = 0.0, overpressure", "x = 0.0, y = 0.5, overpressure",
     ["&injection 1 'well'", "is not on fracture 'fault'"]),
    ("overpressure = 5.0", "overpressure = 5.0, rate = 1.0", ["give either overpressure"]),
    ("overpressure = 5.0", "", ["give either overpressure"]),
    ("fracture = 'fault'", "fracture = 'other'", ["fracture = 'other' names no &fracture"]),
    ("diffusivity = 1.0, transmissivity = 1.0", "", ["does not conduct", "diffusivity"]),
    ("diffusivity = 1.0", "diffusivity = 0.0", ["&fracture 1 'fault'", "diffusivity"]),
    ("diffusivity = 1.0, ", "", ["give both diffusivity and transmissivity"]),
    ("&load_path time = 0.0, 0.4, steps = 4 /", "&load_path p0 = 0.0, 0.0, steps = 4 /",
     ["a source needs a time axis"]),
    ("overpressure = 5.0", "overpressure = 5.0, start = -1.0",
     ["start = -1", "before the first time"]),
    ("overpressure = 5.0", "overpressure = 5.0, start = 0.2, stop = 0.1",
     ["stop = 0.1", "is not after the start"]),
    ("time = 0.0, 0.4", "time = 0.4, 0.4", ["time(2) = 0.4", "times must increase"]),
    ("time = 0.0, 0.4", "time = 0.0, 0.2, 0.4", ["time has 3 values", "one per vertex"]),
])
def test_bad_injection_input_exits_2_without_output(tmp_path, old, new, words):
    assert old in FAULT
    (tmp_path / "bad.nml").write_text(FAULT.replace(old, new))
    done = run(["bad.nml"], tmp_path)
    assert done.returncode == 2, done.stdout + done.stderr
    assert done.stderr.count("ddc2d: error:") == 1
    for word in words:
        assert word in done.stderr, done.stderr
    assert not list(tmp_path.glob("*.h5"))


GROWING = """\
&model youngs_modulus = 30000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -20.0, syy = -10.0 /
&fracture name = 'crack', x = -0.5, 0.5, y = 0.0, 0.0, elements = 21, mu = 0.6, sf = 0.0,
          diffusivity = 1.0, transmissivity = 1.0 /
&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, overpressure = 15.0 /
&load_path time = 0.0, 0.2, steps = 4 /
&growth toughness = 3.0, increment = 0.05, steps = 4 /
"""


def test_a_crack_the_pressure_opens_grows(tmp_path):
    """A closed crack (s_yy = -10) with a source of 15 at its middle: the crack opens as the
    pressure spreads and grows at its ends; the new elements conduct and start at the
    pressure of the tip they grew from."""
    (tmp_path / "grow.nml").write_text(GROWING)
    done = run(["grow.nml"], tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "load step 5 of 5 (t = 0.2" in done.stdout
    with h5py.File(tmp_path / "grow.h5") as f:
        history = f["history"]
        count = history["element_count"][()]
        assert count[0] == 21 and count[-1] == 21 + 2 * 4
        pressure = history["pressure"][()]
        assert pressure.shape == (5, count[-1])
        # Rows follow the geometry: the grown elements have none before they were made.
        created = f["elements/created_step"][()]
        assert np.all(np.isnan(pressure[0, created > 0]))
        # They grew in the last load step: each has its old tip element's pressure then.
        x = f["elements/x_mid"][()]
        old = np.flatnonzero(created == 0)
        tips = old[[np.argmin(x[old]), np.argmax(x[old])]]
        assert pressure[-1, tips[0]] == pytest.approx(pressure[-1, tips[1]], rel=1e-12)
        assert 10.0 < pressure[-1, tips[0]] < 15.0
        assert pressure[-1, created > 0] == pytest.approx(pressure[-1, tips[0]], rel=1e-12)
        assert np.all(f["elements/diffusivity"][()] == 1.0)
        assert np.all(np.diff(history["injected_volume"][()]) > 0.0)


def test_a_growth_run_with_sources_is_not_resumed(tmp_path):
    (tmp_path / "grow.nml").write_text(GROWING)
    assert run(["grow.nml"], tmp_path).returncode == 0
    done = run(["grow.nml", "--resume", "grow.h5", "-o", "again.h5"], tmp_path)
    assert done.returncode == 2, done.stdout + done.stderr
    assert "cannot be resumed" in done.stderr
