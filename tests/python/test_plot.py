"""Tests of scripts/ddc2d-plot on small synthetic result files (see conftest.py)."""

import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import GRID_NAN_POINT, GRID_NEAR_POINT, LENGTH_UNIT, PLOT_SCRIPT, STRESS_UNIT

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run_plot(*args):
    """Run the plot script as a user would, with this Python (the venv's)."""
    return subprocess.run([sys.executable, str(PLOT_SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def figure_files(folder):
    return sorted(p.name for p in folder.iterdir() if p.is_file() and p.suffix != ".h5")


# ------------------------------------------------------------------ files written


def test_writes_profile_per_fracture_and_map_per_grid(result_file, tmp_path):
    out = tmp_path / "figures"  # does not exist yet: the script creates it
    proc = run_plot(result_file, "-o", out)
    assert proc.returncode == 0, proc.stderr
    expected = ["synthetic_map_grid1_max_shear.png", "synthetic_profile_B.png",
                "synthetic_profile_fault_A.png"]
    assert figure_files(out) == expected  # no map for the 'line' field
    for name in expected:
        assert (out / name).read_bytes()[:8] == PNG_MAGIC
        assert (out / name).stat().st_size > 5000
    printed = sorted(line.rsplit("/", 1)[-1] for line in proc.stdout.split())
    assert printed == expected
    assert proc.stderr == ""


@pytest.mark.parametrize("quantity", ["sxx", "syy", "sxy", "mean", "max_shear",
                                      "displacement"])
def test_every_quantity_names_its_map(plot_module, result_file, tmp_path, quantity):
    out = tmp_path / quantity
    assert plot_module.main([str(result_file), "-o", str(out), "--quantity", quantity]) == 0
    assert (out / f"synthetic_map_grid1_{quantity}.png").is_file()


def test_svg_format(result_file, tmp_path):
    proc = run_plot(result_file, "-o", tmp_path / "svg", "--format", "svg")
    assert proc.returncode == 0, proc.stderr
    names = figure_files(tmp_path / "svg")
    assert names == ["synthetic_map_grid1_max_shear.svg", "synthetic_profile_B.svg",
                     "synthetic_profile_fault_A.svg"]
    for name in names:
        assert "<svg" in (tmp_path / "svg" / name).read_text()[:2000]


def test_pdf_format(plot_module, result_file, tmp_path):
    assert plot_module.main([str(result_file), "-o", str(tmp_path / "pdf"),
                             "--format", "pdf"]) == 0
    pdf = tmp_path / "pdf" / "synthetic_profile_fault_A.pdf"
    assert pdf.read_bytes()[:5] == b"%PDF-"


def test_file_without_fields_still_plots_profiles(result_file_without_fields, tmp_path):
    proc = run_plot(result_file_without_fields, "-o", tmp_path / "out")
    assert proc.returncode == 0, proc.stderr
    assert figure_files(tmp_path / "out") == ["nofields_profile_B.png",
                                              "nofields_profile_fault_A.png"]


# ------------------------------------------------------------------ bad input


def test_missing_file_exits_2_with_message(tmp_path):
    missing = tmp_path / "no_such_result.h5"
    proc = run_plot(missing, "-o", tmp_path / "out")
    assert proc.returncode == 2
    assert "no_such_result.h5" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "out").exists()


def test_corrupt_file_exits_2_with_message(tmp_path):
    corrupt = tmp_path / "corrupt.h5"
    corrupt.write_bytes(np.random.default_rng(7).integers(0, 256, 4096, dtype=np.uint8)
                        .tobytes())
    proc = run_plot(corrupt, "-o", tmp_path / "out")
    assert proc.returncode == 2
    assert "corrupt.h5" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def test_file_without_elements_exits_2(tmp_path):
    from conftest import write_result

    path = write_result(tmp_path / "noelements.h5", with_elements=False)
    proc = run_plot(path, "-o", tmp_path / "out")
    assert proc.returncode == 2
    assert "/elements" in proc.stderr and "noelements.h5" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_bad_clim_is_a_usage_error(result_file, tmp_path):
    proc = run_plot(result_file, "-o", tmp_path / "out", "--clim", "5", "1")
    assert proc.returncode == 2
    assert "--clim" in proc.stderr


# ------------------------------------------------------------------ data preparation


def test_load_result_decodes_fortran_strings(plot_module, result_file):
    result = plot_module.load_result(result_file)
    assert result["length_unit"] == LENGTH_UNIT
    assert result["stress_unit"] == STRESS_UNIT
    assert result["title"] == "synthetic test"
    assert [f["name"] for f in result["fractures"]] == ["fault A", "B"]
    assert [(f["first"], f["last"]) for f in result["fractures"]] == [(1, 4), (5, 7)]
    assert result["fields"]["grid1"]["kind"] == "grid"
    assert plot_module.grid_fields(result) == ["grid1"]


def test_profile_data_equal_hdf5_values(plot_module, result_file):
    with h5py.File(result_file, "r") as f:
        ds = f["elements/ds"][()]
        dn = f["elements/dn"][()]
        state = f["elements/state"][()]
    profiles = plot_module.fracture_profiles(plot_module.load_result(result_file))
    assert len(profiles) == 2
    (frac_a, prof_a), (frac_b, prof_b) = profiles
    np.testing.assert_array_equal(prof_a["slip"], -ds[0:4])
    np.testing.assert_array_equal(prof_a["opening"], -dn[0:4])
    np.testing.assert_array_equal(prof_a["state"], state[0:4])
    np.testing.assert_array_equal(prof_b["slip"], -ds[4:7])
    np.testing.assert_array_equal(prof_b["opening"], -dn[4:7])
    np.testing.assert_array_equal(prof_b["state"], state[4:7])
    # Elements are 0.5 long on both fractures: midpoints at 0.25, 0.75, ...
    np.testing.assert_allclose(prof_a["distance"], [0.25, 0.75, 1.25, 1.75], rtol=1e-14)
    np.testing.assert_allclose(prof_b["distance"], [0.25, 0.75, 1.25], rtol=1e-14)


def test_profile_figure_shows_the_profile_data(plot_module, result_file):
    result = plot_module.load_result(result_file)
    fracture, profile = plot_module.fracture_profiles(result)[0]
    fig = plot_module.plot_profile(result, fracture, profile)
    try:
        ax_slip, ax_open = fig.axes[:2]
        for ax, key in ((ax_slip, "slip"), (ax_open, "opening")):
            (line,) = [ln for ln in ax.get_lines() if ln.get_gid() == key]
            np.testing.assert_array_equal(line.get_xdata(), profile["distance"])
            np.testing.assert_array_equal(line.get_ydata(), profile[key])
            assert f"[{LENGTH_UNIT}]" in ax.get_ylabel()
        # One marker series per state present, in the legend (A: stick, slip, open).
        legend = [t.get_text() for t in ax_slip.get_legend().get_texts()]
        assert legend == ["stick", "slip", "open"]
        (open_markers,) = [ln for ln in ax_slip.get_lines() if ln.get_label() == "open"]
        np.testing.assert_array_equal(open_markers.get_xdata(), [1.25])
        (slip_markers,) = [ln for ln in ax_open.get_lines() if ln.get_label() == "slip"]
        np.testing.assert_array_equal(slip_markers.get_xdata(), [0.75, 1.75])
        np.testing.assert_array_equal(slip_markers.get_ydata(), [0.0, 0.0])
    finally:
        plot_module.plt.close(fig)
    fracture, profile = plot_module.fracture_profiles(result)[1]
    fig = plot_module.plot_profile(result, fracture, profile)
    try:
        legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert legend == ["free", "stick", "open"]  # B: free, open, stick elements
    finally:
        plot_module.plt.close(fig)


def test_grid_quantity_shape_values_and_mask(plot_module, result_file):
    result = plot_module.load_result(result_file)
    field = result["fields"]["grid1"]
    x, y, sxx = plot_module.grid_quantity(field, "sxx")
    assert x.shape == y.shape == sxx.shape == (4, 5)
    np.testing.assert_allclose(x[0], np.linspace(-2.0, 2.0, 5))
    np.testing.assert_allclose(y[:, 0], np.linspace(-1.5, 1.5, 4))
    expected_mask = np.zeros((4, 5), dtype=bool)
    expected_mask[GRID_NAN_POINT] = True
    np.testing.assert_array_equal(np.ma.getmaskarray(sxx), expected_mask)
    assert not np.ma.getmaskarray(sxx)[GRID_NEAR_POINT]  # flag 1 is kept
    np.testing.assert_allclose(sxx.compressed(), (-10.0 + x + 2.0 * y)[~expected_mask])

    _, _, shear = plot_module.grid_quantity(field, "max_shear")
    syy, sxy = -5.0 - x * y, 0.5 * x - y
    expected = np.sqrt((0.5 * ((-10.0 + x + 2.0 * y) - syy)) ** 2 + sxy ** 2)
    np.testing.assert_allclose(shear.compressed(), expected[~expected_mask], rtol=1e-14)
    _, _, mean = plot_module.grid_quantity(field, "mean")
    np.testing.assert_allclose(mean.compressed(),
                               (0.5 * (-10.0 + x + 2.0 * y + syy))[~expected_mask])
    _, _, disp = plot_module.grid_quantity(field, "displacement")
    np.testing.assert_allclose(disp.compressed(),
                               np.hypot(1e-3 * x, -2e-3 * y)[~expected_mask])


def test_masked_point_flagged_even_if_finite(plot_module, result_file):
    field = plot_module.load_result(result_file)["fields"]["grid1"]
    field["sxx"] = np.nan_to_num(field["sxx"], nan=123.0)
    _, _, sxx = plot_module.grid_quantity(field, "sxx")
    assert np.ma.getmaskarray(sxx)[GRID_NAN_POINT]
    assert sxx.count() == 19


def test_map_uses_clim_and_draws_every_element(plot_module, result_file):
    result = plot_module.load_result(result_file)
    fig = plot_module.plot_map(result, "grid1", "sxx", clim=(-4.0, 2.0))
    try:
        ax = fig.axes[0]
        mesh = ax.collections[0]
        assert mesh.get_clim() == (-4.0, 2.0)
        (elements,) = [c for c in ax.collections if c.get_gid() == "elements"]
        segments = elements.get_segments()
        assert len(segments) == 7
        np.testing.assert_allclose(segments[5], [[0.3, 1.4], [0.3, 1.9]])
        assert f"[{STRESS_UNIT}]" in fig.axes[1].get_ylabel()
    finally:
        plot_module.plt.close(fig)


def test_default_clim_is_symmetric_for_signed_quantities(plot_module, result_file):
    field = plot_module.load_result(result_file)["fields"]["grid1"]
    _, _, sxy = plot_module.grid_quantity(field, "sxy")
    assert sxy.min() < 0.0 < sxy.max()
    low, high = plot_module.default_clim(sxy, "sxy")
    assert low == -high and high > 0.0
    _, _, shear = plot_module.grid_quantity(field, "max_shear")
    low, high = plot_module.default_clim(shear, "max_shear")
    assert shear.min() <= low < high <= shear.max()


def test_default_clim_follows_one_signed_data(plot_module):
    # A compressive tectonic sxx never crosses zero: the limits keep to the data.
    values = plot_module.np.ma.masked_array(-150.0 + plot_module.np.linspace(0.0, 10.0, 101))
    low, high = plot_module.default_clim(values, "sxx")
    assert -150.0 <= low < high <= -140.0
