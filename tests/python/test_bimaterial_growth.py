"""Fracture growth in two bonded half-planes (docs/theory/bimaterial.md#growth): with equal
materials it is the full plane's growth, and a tip stops before the interface (reason
'interface'), as crossing or deflecting into it needs a rule of its own."""

import subprocess

import h5py
import numpy as np

from conftest import ddc2d_exe, solve_text
from ddc2d.reader import load_result

#: A tilted traction crack in the lower material opened by sxx: both tips grow, the upper
#: one toward the interface y = INTERFACE.
CRACK = """\
&remote_stress sxx = 10.0, syy = -5.0, sxy = 2.0 /
&fracture name = 'crack', x = -0.3, 0.3, y = -1.0, -0.6, elements = 12, condition = 'traction' /
&growth steps = {steps}, toughness = 1.0, increment = 0.1 /
"""
INTERFACE = 0.0


def two_materials(upper_modulus, interface_y=INTERFACE, steps=8):
    return (f"&model domain = 'bimaterial', interface_y = {interface_y} /\n"
            f"&material name = 'upper', youngs_modulus = {upper_modulus}, "
            "poissons_ratio = 0.25 /\n"
            "&material name = 'lower', youngs_modulus = 40000.0, poissons_ratio = 0.25 /\n"
            + CRACK.format(steps=steps))


def largest_gap(a, b):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


def test_equal_materials_grow_as_the_full_plane(tmp_path):
    # The interface far above every path: the same paths, DDs and K as the full plane.
    full = load_result(solve_text(tmp_path, "full", "&model youngs_modulus = 40000.0, "
                                  "poissons_ratio = 0.25 /\n" + CRACK.format(steps=5)))
    equal = load_result(solve_text(tmp_path, "equal", two_materials(40000.0, 5.0, steps=5)))
    assert equal["elements"]["x_begin"].size == full["elements"]["x_begin"].size == 12 + 2 * 5 * 2
    for key in ("x_begin", "y_begin", "x_end", "y_end", "ds", "dn"):
        assert largest_gap(equal["elements"][key], full["elements"][key]) < 1e-12, key
    # K_II is small here (1e-4 of K_I): both against the largest K.
    scale = np.max(np.abs(full["tips"]["k1"]))
    for key in ("k1", "k2"):
        assert np.max(np.abs(equal["tips"][key] - full["tips"][key])) < 1e-12 * scale, key


def test_a_tip_stops_before_the_interface(tmp_path):
    # A soft upper material: the upper tip grows until its next increment would come
    # within half an element length of the interface, and stops there for good; the lower
    # tip grows on to the step limit.
    path = solve_text(tmp_path, "soft", two_materials(10000.0))
    with h5py.File(path, "r") as f:
        reasons = f["growth/reason"][()]
        end = f["growth/end"][()]
        coding = f["growth/reason"].attrs["coding"].decode()
        y = np.concatenate([f["elements/y_begin"][()], f["elements/y_end"][()]])
        step = f["growth/step"][()]
    assert "9 interface" in coding
    stops = np.flatnonzero(reasons == 9)
    assert stops.size == 1, reasons
    stop = stops[0]
    # The stopped tip: no record after its stop; the other tip grew at every step.
    assert not np.any((end == end[stop]) & (step > step[stop]))
    assert np.all(reasons[end != end[stop]] == 0) and step.max() == 8
    # Below the interface, within one increment (0.1) and half an element (0.025) of it.
    assert INTERFACE - 0.1 - 0.025 <= y.max() < INTERFACE - 0.025


def test_a_resumed_run_keeps_the_stopped_tip(tmp_path):
    # Resumed after the stop (step 7 of 8): the tip stays stopped, as in the whole run.
    whole = load_result(solve_text(tmp_path, "whole", two_materials(10000.0)))
    solve_text(tmp_path, "first", two_materials(10000.0, steps=7))
    (tmp_path / "more.nml").write_text(two_materials(10000.0))
    done = subprocess.run([str(ddc2d_exe()), "more.nml", "--resume", "first.h5", "-o",
                           "more.h5"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    more = load_result(tmp_path / "more.h5")
    assert list(more["growth"]["reason"]) == list(whole["growth"]["reason"])
    for key in ("y_end", "ds", "dn"):
        assert largest_gap(more["elements"][key], whole["elements"][key]) < 1e-12, key


def test_the_stop_closes_on_the_interface_as_the_increment_shrinks(tmp_path):
    # The stopped tip lies within one increment and the clearance (half an element) of the
    # interface, so it comes closer as the increment (and its elements) are refined.
    gaps = []
    for increment in (0.1, 0.05, 0.025):
        text = two_materials(10000.0, steps=80).replace(
            "increment = 0.1", f"increment = {increment}, element_length = {increment / 2}")
        with h5py.File(solve_text(tmp_path, f"inc{increment}", text), "r") as f:
            stops = np.flatnonzero(f["growth/reason"][()] == 9)
            assert stops.size == 1
            gap = INTERFACE - f["growth/y"][stops[0]]
        assert increment / 4 <= gap < increment + increment / 4, (increment, gap)
        gaps.append(gap)
    assert gaps[2] < gaps[0], gaps
