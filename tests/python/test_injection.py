"""Fluid injection into a fault (docs/injection.md): the input's checks of &injection, the
time axis and the hydraulic properties, and a fault whose slipping patch grows with the
pressure that diffuses from a source held at its middle: the front at the self-similar
solution's position within one element (the measure's quantum), the history's datasets;
what users look at of it: the figures of ddc2d-plot (fronts with the closed form where it
applies, profiles, moment) and the history as an xarray Dataset along time.
"""

import copy
import math
import subprocess
import sys

import h5py
import matplotlib.pyplot as plt
import numpy as np
import pytest

import ddc2d
from conftest import PLOT_SCRIPT, ddc2d_exe
from ddc2d.injection import front_factor, injection_parameter, overpressure_profile
from ddc2d.plot import figures as plot_figures
from ddc2d.plot import injection as plot_injection
from ddc2d.reader import load_result

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


@pytest.fixture(scope="module")
def fault(tmp_path_factory):
    """FAULT solved once: (the finished ddc2d run, the result file)."""
    folder = tmp_path_factory.mktemp("fault")
    (folder / "fault.nml").write_text(FAULT)
    done = run(["fault.nml"], folder)
    assert done.returncode == 0, done.stdout + done.stderr
    return done, folder / "fault.h5"


def test_the_front_follows_the_self_similar_solution(fault):
    done, path = fault
    assert "t = 0.1 h" in done.stdout.replace("0.100000", "0.1")
    lam = front_factor(injection_parameter(0.6, 10.0, 4.5, 5.0))
    assert lam == pytest.approx(0.791607, abs=1e-6)
    with h5py.File(path) as f:
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


# ------------------------------------------------------------------ what users look at


def plot_cli(*args):
    return subprocess.run([sys.executable, str(PLOT_SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=300)


def line(fig, gid):
    """The one line of a figure with this gid."""
    found = [ln for ax in fig.axes for ln in ax.get_lines() if ln.get_gid() == gid]
    assert len(found) == 1, (gid, [ln.get_gid() for ax in fig.axes for ln in ax.get_lines()])
    return found[0]


def test_ddc2d_plot_writes_the_injection_figures(fault, tmp_path):
    done = plot_cli(fault[1], "-o", tmp_path, "--dpi", 40, "--injection-times", "0.16,0.4")
    assert done.returncode == 0, done.stderr
    for name in ("front", "injection", "moment", "history"):
        assert (tmp_path / f"fault_{name}.png").stat().st_size > 2000
    bad = plot_cli(fault[1], "-o", tmp_path, "--injection-times", "0.5")
    assert bad.returncode == 2 and "time 0.5 is not in the path's times 0 to 0.4" in bad.stderr


def test_the_front_figure_has_the_fronts_from_the_source_and_the_closed_form(fault):
    result = load_result(fault[1])
    history = result["history"]
    fig = plot_figures.plot_fronts(result)
    end, begin = line(fig, "front_end:fault"), line(fig, "front_begin:fault")
    np.testing.assert_array_equal(end.get_xdata(), np.sqrt(history["time"]))
    # Measured from the source at x = 0, 4 from the fault's first vertex.
    np.testing.assert_allclose(end.get_ydata(), history["front_end"][:, 0] - 4.0, atol=1e-12)
    np.testing.assert_allclose(begin.get_ydata(), history["front_begin"][:, 0] - 4.0,
                               atol=1e-12)
    closed = [ln for ax in fig.axes for ln in ax.get_lines() if ln.get_gid() == "closed_form"]
    reach = 0.791607 * np.sqrt(4.0 * history["time"])  # lambda(0.5) of the issue
    np.testing.assert_allclose(sorted(ln.get_ydata()[-1] for ln in closed),
                               [-reach[-1], reach[-1]], rtol=1e-6)
    assert "T = 0.5, lambda(T) = 0.7916" in fig._suptitle.get_text()
    plt.close(fig)


def test_the_profiles_and_the_moment_are_the_historys(fault):
    result = load_result(fault[1])
    history = result["history"]
    steps = plot_injection.profile_steps(result)
    # 4 times evenly in sqrt(t): 0.025, 0.1, 0.225, 0.4 -> the steps after t = 0 nearest.
    assert steps == [1, 2, 4]
    assert plot_injection.profile_steps(result, [0.16, 0.0, 0.4]) == [0, 2, 4]
    fig = plot_figures.plot_injection(result, steps)
    np.testing.assert_array_equal(line(fig, "pressure:fault:step_3").get_ydata(),
                                  history["pressure"][2])
    np.testing.assert_array_equal(line(fig, "slip:fault:step_5").get_ydata(),
                                  -history["ds"][4])
    # The closed form's erfc, against the pressure the run diffused (as the test above).
    x = result["elements"]["x_mid"]
    exact = line(fig, "closed_form:step_5").get_ydata()
    np.testing.assert_allclose(exact, overpressure_profile(x, 0.4, 1.0, 5.0), atol=1e-12)
    assert np.max(np.abs(history["pressure"][4] - exact)) <= 0.05 * 5.0
    plt.close(fig)
    fig = plot_figures.plot_moment(result)
    moment = line(fig, "moment:fault")
    np.testing.assert_array_equal(moment.get_xdata(), history["injected_volume"])
    np.testing.assert_array_equal(moment.get_ydata(), history["moment"][:, 0])
    assert fig.axes[0].get_ylabel() == "seismic moment per unit length [MPa m^2]"
    plt.close(fig)


def _two_sources(r):
    r["injection"] = {k: (v * 2 if isinstance(v, list) else np.r_[v, v])
                      for k, v in r["injection"].items()}


def _rate(r):
    r["injection"]["rate"][0], r["injection"]["overpressure"][0] = 1.0, np.nan


def _set(where, key, index, value):
    def change(r):
        r[where][key] = np.array(r[where][key], dtype=float)
        r[where][key][index] = value
    return change


@pytest.mark.parametrize("change, why", [
    (_two_sources, "2 sources"),
    (_rate, "a rate source"),
    (_set("injection", "stop", 0, 0.2), "the source is shut in"),
    (lambda r: r["attrs"].update(domain="half_plane"), "a half-plane"),
    (lambda r: r.update(remote_stress_gradient=(0.0, 0.01, 0.0)), "changes with depth"),
    (_set("elements", "mu", 7, 0.7), "the friction varies along the fault"),
    (_set("elements", "sf", 3, 1.0), "a cohesion"),
    (_set("elements", "mu_dynamic", 3, 0.5), "mu_dynamic"),
    (_set("elements", "diffusivity", 0, 2.0), "the diffusivity varies along the fault"),
    (lambda r: r["elements"].pop("transmissivity"), "no transmissivity in the file"),
    (lambda r: r.update(remote_stress=(0.0, -10.0, 7.0)), "T = -0.3333"),
    (lambda r: r.update(remote_stress=(0.0, -10.0, 0.0)), "T = 2 (a front grows for 0 < T < 1)"),
    (_set("injection", "overpressure", 0, 12.0),
     "the overpressure 12 is not between 0 and the effective normal stress 10"),
])
def test_the_closed_form_applies_to_its_own_model_only(fault, change, why):
    result = load_result(fault[1])
    form, reason = plot_injection.closed_form_front(result)
    assert reason == "" and form["parameter"] == pytest.approx(0.5, abs=1e-12)
    assert form["factor"] == pytest.approx(0.791607, abs=1e-6)
    assert form["origin"] == pytest.approx(4.0, abs=1e-12) and form["start"] == 0.0
    changed = copy.deepcopy(result)
    change(changed)
    form, reason = plot_injection.closed_form_front(changed)
    assert form is None and why in reason, reason


def test_history_to_xarray_runs_along_time(fault):
    history = ddc2d.open_result(fault[1]).to_xarray("history")
    np.testing.assert_allclose(history["time"], [0.0, 0.1, 0.2, 0.3, 0.4], atol=1e-15)
    assert history["time"].dims == ("step",) and history["time"].attrs["units"] == "h"
    assert history["pressure"].dims == ("step", "element")
    assert history["pressure"].attrs["units"] == "MPa"
    assert history["injected_volume"].dims == ("step",)
    for key in ("slipping_length", "front_begin", "front_end", "moment"):
        assert history[key].dims == ("step", "fracture")
    assert list(history["fracture_name"].values) == ["fault"]
    assert history["moment"].attrs["units"] == "MPa m^2"
    by_time = history.swap_dims(step="time")
    with h5py.File(fault[1]) as f:
        np.testing.assert_array_equal(by_time["pressure"].sel(time=f["history/time"][2]),
                                      f["history/pressure"][2])
        np.testing.assert_array_equal(by_time["front_end"].sel(fracture=1),
                                      f["history/front_end"][:, 0])


def test_the_model_builder_writes_an_injection(fault, tmp_path):
    model = ddc2d.Model(youngs_modulus=30000.0, poissons_ratio=0.25, time_unit="h")
    model.remote_stress(syy=-10.0, sxy=4.5)
    model.fracture([-4.0, 4.0], [0.0, 0.0], elements=201, mu=0.6, sf=0.0, name="fault",
                   diffusivity=1.0, transmissivity=1.0)
    model.injection("fault", 0.0, 0.0, name="well", overpressure=5.0)
    model.load_path(steps=4, time=[0.0, 0.4])
    model.solver(k_method="tip_element")
    assert "&injection name = 'well', fracture = 'fault', x = 0.0, y = 0.0, overpressure = " \
        "5.0 /" in model.namelist()
    built = ddc2d.run(model, output=tmp_path / "built.h5", executable=ddc2d_exe())
    with h5py.File(fault[1]) as f:
        for key in ("front_begin", "front_end", "injected_volume"):
            np.testing.assert_allclose(built.history[key], f["history"][key][()], rtol=1e-12)
    assert built.injection["name"] == ["well"] and built.time_unit == "h"
