"""Fracture growth end to end (docs/fracture-growth.md#output): ddc2d on a &growth model prints
a line per step and a table per tip, writes /growth and /elements/created_step, and
scripts/ddc2d-plot draws the grown elements and K_eq / toughness from exactly those values."""

import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import PLOT_SCRIPT, ddc2d_exe
from ddc2d.plot import data as plot_data
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import GROWTH_DATASETS, load_result

# A crack under remote shear grows wings from both tips (the toughness is below its K_eq
# all along); a second fracture, a strong fault that sticks and may not grow, is left alone.
SHEAR_MODEL = """\
&model title = 'wings', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxy = 10 /
&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 20, condition = 'traction' /
&fracture name = 'fault', x = -1, 1, y = -3, -3, elements = 10, mu = 0.6, sf = 100 /
&growth steps = 3, toughness = 10, fractures = 'crack' /
&grid name = 'map', xmin = -2, xmax = 2, nx = 9, ymin = -2, ymax = 2, ny = 9 /
"""


def solve(tmp_path, text=SHEAR_MODEL):
    model = tmp_path / "wings.nml"
    model.write_text(text)
    return subprocess.run([str(ddc2d_exe()), str(model), "-o", str(tmp_path / "wings.h5")],
                          capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def grown(tmp_path_factory):
    """The shear model solved once: (folder, completed process)."""
    folder = tmp_path_factory.mktemp("growth")
    done = solve(folder)
    assert done.returncode == 0, done.stdout + done.stderr
    return folder, done


def test_growth_layout(grown):
    folder, _ = grown
    with h5py.File(folder / "wings.h5", "r") as f:
        g = f["growth"]
        # Two tips (the crack's; the fault may not grow), three steps: six records.
        for key in GROWTH_DATASETS:
            assert g[key].shape == (6,), key
        assert list(g["step"][()]) == [1, 1, 2, 2, 3, 3]
        assert list(g["fracture_id"][()]) == [1] * 6
        assert list(g["end"][()]) == [0, 1] * 3
        assert list(g["reason"][()]) == [0] * 6
        assert g.attrs["end_reason"] == b"step_limit"
        assert g.attrs["steps_taken"] == 3
        assert g.attrs["fractures"] == b"crack"
        assert g.attrs["toughness"] == 10.0
        assert b"2 intersection" in g.attrs["reason_coding"]
        assert g["k_eq"].attrs["units"] == b"MPa m^0.5"
        assert g["angle"].attrs["units"] == b"degree"
        # Pure mode II at the input's tips: MTS angle -70.53 degrees where K_II > 0.
        np.testing.assert_allclose(g["mts_angle"][:2], -70.528779, atol=0.1)
        assert np.all(g["k2"][:2] > 0.0)
        created = f["elements/created_step"][()]
        # 20 + 3 steps x 2 tips x 2 elements on the crack, then the fault's 10.
        assert list(created) == [3, 3, 2, 2, 1, 1] + [0] * 20 + [1, 1, 2, 2, 3, 3] + [0] * 10
        assert list(f["fractures/first_element"][()]) == [1, 33]
        assert list(f["fractures/last_element"][()]) == [32, 42]
        # /tips describe the final geometry: the crack's new tips are the grown ones.
        x_end = f["elements/x_end"][()]
        assert f["tips/x"][1] == x_end[31]


def test_progress_lines_and_tip_table(grown):
    _, done = grown
    lines = done.stdout.splitlines()
    steps = [line for line in lines if line.startswith("growth step ")]
    assert [line.split(":")[0] for line in steps] == [f"growth step {k}" for k in (1, 2, 3)]
    assert all("2 tip(s) grew, largest K_eq" in line for line in steps)
    assert "growth: 3 step(s) with growth; ended: step_limit" in done.stdout
    table = lines[lines.index("growth: 3 step(s) with growth; ended: step_limit") + 1:]
    assert table[0].split()[:3] == ["fracture", "tip", "steps"]
    for row, end in zip(table[1:3], ("begin", "end")):
        words = row.split()
        assert words[:3] == ["crack", end, "3"]
        assert float(words[3]) == pytest.approx(0.6, rel=1e-12)  # 3 increments of 0.2
        assert "step limit" in row


def test_growth_figure_draws_the_records(grown):
    folder, _ = grown
    proc = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(folder / "wings.h5"), "-o",
                           str(folder / "fig"), "--quantity", "sxy"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert (folder / "fig" / "wings_growth.png").read_bytes()[:4] == b"\x89PNG"
    assert (folder / "fig" / "wings_map_sxy.png").is_file()
    result = load_result(folder / "wings.h5")
    series = plot_data.growth_series(result)
    assert [tip["label"] for tip in series] == ["crack begin", "crack end"]
    with h5py.File(folder / "wings.h5", "r") as f:
        k_eq = f["growth/k_eq"][()]
        created = f["elements/created_step"][()]
    # K_eq / toughness: the stored values divided by the stored toughness (10).
    np.testing.assert_allclose(series[1]["ratio"], k_eq[1::2] / 10.0, rtol=1e-15)
    assert list(series[0]["step"]) == [1, 2, 3]
    fig = plot_figures.plot_growth(result)
    try:
        geometry, k_axes = fig.axes[:2]
        grown_elements = [c for c in geometry.collections if c.get_gid() == "grown_elements"]
        assert len(grown_elements) == 1
        # One segment per grown element, coloured by its step.
        np.testing.assert_array_equal(grown_elements[0].get_array(), created[created > 0])
        lines = {line.get_gid(): line for line in k_axes.get_lines() if line.get_gid()}
        np.testing.assert_array_equal(lines["k_eq:crack end"].get_ydata(), k_eq[1::2] / 10.0)
    finally:
        plot_figures.plt.close(fig)
    fig = plot_figures.plot_map(result, "map", "sxy")
    try:
        gids = [c.get_gid() for c in fig.axes[0].collections]
        assert "grown_elements" in gids and "elements" in gids
    finally:
        plot_figures.plt.close(fig)


def test_result_without_growth_has_no_growth_figure(tmp_path):
    done = solve(tmp_path, SHEAR_MODEL.replace("&growth", "! &growth"))
    assert done.returncode == 0, done.stderr
    assert "growth step" not in done.stdout
    with h5py.File(tmp_path / "wings.h5", "r") as f:
        assert "growth" not in f
        assert "created_step" not in f["elements"]
    assert load_result(tmp_path / "wings.h5")["growth"] is None
    proc = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(tmp_path / "wings.h5"), "-o",
                           str(tmp_path / "fig")], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert not list((tmp_path / "fig").glob("*_growth.*"))


# A fault that barely slides (principal stresses -100 and -40 MPa, sigma_1 25 degrees from it,
# mu 0.5, sf 0.5, p0 6 MPa: K_II 0.22) with a toughness of 0.2: both tips are critical
# (K_eq 0.25), but under the confinement even the shortest kink (1/64 of an element) closes
# (K_I = 0 on the new tip), so neither tip grows and the run arrests
# (docs/theory/growth.md#closed-kinks).
CLOSED_MODEL = """\
&model title = 'closed', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -89.2836, syy = -50.7164, sxy = 22.9813 /
&pore_fluid p0 = 6.0 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 40, condition = 'contact',
          mu = 0.5, sf = 0.5 /
&growth steps = 30, toughness = 0.2, increment = 0.1 /
"""


def test_closed_tips_in_table_and_figure(tmp_path):
    done = solve(tmp_path, CLOSED_MODEL)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "ended: arrested" in done.stdout
    rows = [line for line in done.stdout.splitlines() if line.startswith("  fault ")]
    assert len(rows) == 2
    assert all("closed: the kink closes (K_I = 0)" in row for row in rows)
    with h5py.File(tmp_path / "wings.h5", "r") as f:
        coding = f["growth"].attrs["reason_coding"].decode()
        reason = f["growth/reason"][()]
    assert "5 linked" in coding and "6 closed" in coding and "7 waiting" in coding
    assert list(reason[-2:]) == [6, 6]
    result = load_result(tmp_path / "wings.h5")
    fig = plot_figures.plot_growth(result)
    try:
        k_axes = fig.axes[1]
        legend = [text.get_text() for text in k_axes.get_legend().get_texts()]
        assert plot_figures.GROWTH_MARKERS["closed"][1] in legend
        closed = [line for line in k_axes.get_lines()
                  if line.get_label() == plot_figures.GROWTH_MARKERS["closed"][1]]
        assert [line.get_marker() for line in closed] == [plot_figures.GROWTH_MARKERS["closed"][0]]
    finally:
        plot_figures.plt.close(fig)


# A crack under syy grows straight towards a fault across its path (which may not grow):
# in step 3 its end tip would cross the fault at one of its vertices and links there.
LINK_MODEL = """\
&model title = 'link', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress syy = 10 /
&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 40, condition = 'traction' /
&fracture name = 'fault', x = 1.25, 1.25, y = -0.5, 0.5, elements = 20,
          condition = 'traction' /
&growth steps = 4, toughness = 5, fractures = 'crack' /
"""


def test_linked_tip_in_table_and_figure(tmp_path):
    done = solve(tmp_path, LINK_MODEL)
    assert done.returncode == 0, done.stdout + done.stderr
    rows = [line.split() for line in done.stdout.splitlines() if line.startswith("  crack ")]
    linked = [row for row in rows if row[1] == "end"]
    assert len(linked) == 1
    # Two increments of 0.1 and the 0.05 link; the table names the fracture it ends on.
    assert linked[0][2] == "3" and float(linked[0][3]) == pytest.approx(0.25, rel=1e-9)
    assert " ".join(linked[0][5:]) == "linked: ends on fracture fault"
    with h5py.File(tmp_path / "wings.h5", "r") as f:
        reason = f["growth/reason"][()]
        end = f["growth/end"][()]
    assert list(reason[end == 1]) == [0, 0, 5]
    result = load_result(tmp_path / "wings.h5")
    fig = plot_figures.plot_growth(result)
    try:
        k_axes = fig.axes[1]
        text = plot_figures.GROWTH_MARKERS["linked"][1]
        assert text in [t.get_text() for t in k_axes.get_legend().get_texts()]
        markers = [line.get_marker() for line in k_axes.get_lines()
                   if line.get_label() == "_reason" and line.get_marker() == "P"]
        assert plot_figures.GROWTH_MARKERS["linked"][0] == "P" and len(markers) == 1
    finally:
        plot_figures.plt.close(fig)
