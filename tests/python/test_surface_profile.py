"""The surface displacement profile of ddc2d-plot (docs/theory/earth.md#a-free-surface): a &line
on y = 0 of a half-plane model is drawn as ux, uy against x; lines elsewhere, and full-plane
models, are not."""

import subprocess
import sys

import numpy as np

from conftest import PLOT_SCRIPT, REPO_ROOT, ddc2d_exe
from ddc2d.plot import data as plot_data
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import index_of_extreme, load_result

MODEL = REPO_ROOT / "input" / "buried_dipping_fault_slip.nml"


def solve(tmp_path, text, name):
    model = tmp_path / f"{name}.nml"
    model.write_text(text)
    out = tmp_path / f"{name}.h5"
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return out


def test_surface_line_of_a_half_plane_is_plotted(tmp_path):
    text = MODEL.read_text() + ("&line name = 'borehole', x_begin = 500, y_begin = -100, "
                                "x_end = 500, y_end = -3000, points = 30 /\n")
    out = solve(tmp_path, text, "buried")
    result = load_result(out)
    assert plot_data.surface_lines(result) == ["surface"]
    fig = plot_figures.plot_surface(result, "surface")
    (uy_line,) = [line for line in fig.axes[0].get_lines() if line.get_gid() == "uy"]
    x, uy = uy_line.get_data()
    plot_figures.plt.close(fig)
    field = result["fields"]["surface"]
    # The line runs along +x, so the figure draws the stored values in their order: exact.
    assert np.array_equal(x, field["x"])
    assert np.array_equal(uy, field["uy"])
    # Reverse slip lifts the hanging wall: the peak uplift is positive, behind the fault
    # (the first of peaks equal within the tie rule; index_of_extreme skips NaN).
    assert np.nanmax(uy) > 0.3 and -2000.0 < x[index_of_extreme(uy)] < 0.0
    done = subprocess.run([sys.executable, str(PLOT_SCRIPT), str(out), "-o", str(tmp_path)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    # The line named 'surface' gives buried_surface.png (no doubled name); the borehole
    # is no surface line: it gets the figure of an observation line instead.
    assert (tmp_path / "buried_surface.png").is_file()
    assert not list(tmp_path.glob("*_surface_*"))
    assert (tmp_path / "buried_line_borehole.png").is_file()


def test_no_surface_profile_in_a_full_plane(tmp_path):
    text = MODEL.read_text().replace("domain = 'half_plane'", "domain = 'full_plane'")
    out = solve(tmp_path, text, "full")
    assert plot_data.surface_lines(load_result(out)) == []
