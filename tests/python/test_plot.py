"""Tests of scripts/ddc2d-plot on small synthetic result files (see conftest.py) and on a
small model solved by ddc2d."""

import csv
import subprocess
import sys

import h5py
import numpy as np
import pytest

from conftest import (
    GRID_NAN_POINT,
    GRID_NEAR_POINT,
    LENGTH_UNIT,
    PLOT_SCRIPT,
    REPO_ROOT,
    STRESS_UNIT,
    ddc2d_exe,
    write_result,
)
from ddc2d.plot import data as plot_data
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import STATE_CODES, load_result

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
    figures = ["synthetic_line_line1.png", "synthetic_map_grid1_max_shear.png",
               "synthetic_profile_B.png", "synthetic_profile_fault_A.png",
               "synthetic_profiles.png"]
    tables = ["synthetic_tips.csv", "synthetic_tips.txt"]
    assert figure_files(out) == sorted(figures + tables)  # a line figure, no map, for 'line1'
    for name in figures:
        assert (out / name).read_bytes()[:8] == PNG_MAGIC
        assert (out / name).stat().st_size > 5000
    # stdout: the tips table (as in _tips.txt), then the files written, one per line
    table = (out / "synthetic_tips.txt").read_text()
    assert proc.stdout.startswith(table)
    printed = sorted(line.rsplit("/", 1)[-1] for line in proc.stdout[len(table):].split())
    assert printed == sorted(figures + tables)
    assert proc.stderr == ""


@pytest.mark.parametrize("quantity", ["sxx", "syy", "sxy", "mean", "max_shear", "coulomb",
                                      "displacement"])
def test_every_quantity_names_its_map(plot_module, result_file, tmp_path, quantity):
    out = tmp_path / quantity
    assert plot_module.main([str(result_file), "-o", str(out), "--quantity", quantity]) == 0
    assert (out / f"synthetic_map_grid1_{quantity}.png").is_file()


def test_svg_format(result_file, tmp_path):
    proc = run_plot(result_file, "-o", tmp_path / "svg", "--format", "svg")
    assert proc.returncode == 0, proc.stderr
    names = [n for n in figure_files(tmp_path / "svg") if n.endswith(".svg")]
    assert names == ["synthetic_line_line1.svg", "synthetic_map_grid1_max_shear.svg",
                     "synthetic_profile_B.svg", "synthetic_profile_fault_A.svg",
                     "synthetic_profiles.svg"]
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
                                              "nofields_profile_fault_A.png",
                                              "nofields_profiles.png", "nofields_tips.csv",
                                              "nofields_tips.txt"]


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


def test_load_result_decodes_fortran_strings(result_file):
    result = load_result(result_file)
    assert result["length_unit"] == LENGTH_UNIT
    assert result["stress_unit"] == STRESS_UNIT
    assert result["title"] == "synthetic test"
    assert [f["name"] for f in result["fractures"]] == ["fault A", "B"]
    assert [(f["first"], f["last"]) for f in result["fractures"]] == [(1, 4), (5, 7)]
    assert result["fields"]["grid1"]["kind"] == "grid"
    assert plot_data.grid_fields(result) == ["grid1"]


def test_profile_data_equal_hdf5_values(result_file):
    # The profiles are the stored values (negated, which is exact): compared bit for bit.
    with h5py.File(result_file, "r") as f:
        ds = f["elements/ds"][()]
        dn = f["elements/dn"][()]
        state = f["elements/state"][()]
    profiles = plot_data.fracture_profiles(load_result(result_file))
    assert len(profiles) == 2
    (_, prof_a), (_, prof_b) = profiles
    np.testing.assert_array_equal(prof_a["slip"], -ds[0:4])
    np.testing.assert_array_equal(prof_a["opening"], -dn[0:4])
    np.testing.assert_array_equal(prof_a["state"], state[0:4])
    np.testing.assert_array_equal(prof_b["slip"], -ds[4:7])
    np.testing.assert_array_equal(prof_b["opening"], -dn[4:7])
    np.testing.assert_array_equal(prof_b["state"], state[4:7])
    # Elements are 0.5 long on both fractures: midpoints at 0.25, 0.75, ...
    np.testing.assert_allclose(prof_a["distance"], [0.25, 0.75, 1.25, 1.75], rtol=1e-14)
    np.testing.assert_allclose(prof_b["distance"], [0.25, 0.75, 1.25], rtol=1e-14)


def test_profile_figure_shows_the_profile_data(result_file):
    result = load_result(result_file)
    fracture, profile = plot_data.fracture_profiles(result)[0]
    fig = plot_figures.plot_profile(result, fracture, profile)
    try:
        ax_slip, ax_open = fig.axes[:2]
        # Lines and markers draw the profile's values themselves, and the element lengths
        # (0.5) and midpoints are exact in binary: compared bit for bit.
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
        plot_figures.plt.close(fig)
    fracture, profile = plot_data.fracture_profiles(result)[1]
    fig = plot_figures.plot_profile(result, fracture, profile)
    try:
        legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert legend == ["free", "stick", "open"]  # B: free, open, stick elements
    finally:
        plot_figures.plt.close(fig)


def test_grid_quantity_shape_values_and_mask(result_file):
    result = load_result(result_file)
    field = result["fields"]["grid1"]
    x, y, sxx = plot_data.grid_quantity(field, "sxx")
    assert x.shape == y.shape == sxx.shape == (4, 5)
    np.testing.assert_allclose(x[0], np.linspace(-2.0, 2.0, 5))
    np.testing.assert_allclose(y[:, 0], np.linspace(-1.5, 1.5, 4))
    expected_mask = np.zeros((4, 5), dtype=bool)
    expected_mask[GRID_NAN_POINT] = True
    np.testing.assert_array_equal(np.ma.getmaskarray(sxx), expected_mask)
    assert not np.ma.getmaskarray(sxx)[GRID_NEAR_POINT]  # flag 1 is kept
    np.testing.assert_allclose(sxx.compressed(), (-10.0 + x + 2.0 * y)[~expected_mask])

    _, _, shear = plot_data.grid_quantity(field, "max_shear")
    syy, sxy = -5.0 - x * y, 0.5 * x - y
    expected = np.sqrt((0.5 * ((-10.0 + x + 2.0 * y) - syy)) ** 2 + sxy ** 2)
    np.testing.assert_allclose(shear.compressed(), expected[~expected_mask], rtol=1e-14)
    _, _, mean = plot_data.grid_quantity(field, "mean")
    np.testing.assert_allclose(mean.compressed(),
                               (0.5 * (-10.0 + x + 2.0 * y + syy))[~expected_mask])
    _, _, disp = plot_data.grid_quantity(field, "displacement")
    np.testing.assert_allclose(disp.compressed(),
                               np.hypot(1e-3 * x, -2e-3 * y)[~expected_mask])


def test_masked_point_flagged_even_if_finite(result_file):
    field = load_result(result_file)["fields"]["grid1"]
    field["sxx"] = np.nan_to_num(field["sxx"], nan=123.0)
    _, _, sxx = plot_data.grid_quantity(field, "sxx")
    assert np.ma.getmaskarray(sxx)[GRID_NAN_POINT]
    assert sxx.count() == 19


def test_map_uses_clim_and_draws_every_element(result_file):
    result = load_result(result_file)
    fig = plot_figures.plot_map(result, "grid1", "sxx", clim=(-4.0, 2.0))
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
        plot_figures.plt.close(fig)


def test_default_clim_is_symmetric_for_signed_quantities(result_file):
    field = load_result(result_file)["fields"]["grid1"]
    _, _, sxy = plot_data.grid_quantity(field, "sxy")
    assert sxy.min() < 0.0 < sxy.max()
    low, high = plot_data.default_clim(sxy, "sxy")
    assert low == -high and high > 0.0  # centre 0: (0 - top, 0 + top), exact negatives
    _, _, shear = plot_data.grid_quantity(field, "max_shear")
    low, high = plot_data.default_clim(shear, "max_shear")
    assert shear.min() <= low < high <= shear.max()


def test_default_clim_follows_one_signed_data():
    # A compressive tectonic sxx never crosses zero: the limits keep to the data.
    values = np.ma.masked_array(-150.0 + np.linspace(0.0, 10.0, 101))
    low, high = plot_data.default_clim(values, "sxx")
    assert -150.0 <= low < high <= -140.0


# ------------------------------------------------------------------ Coulomb stress change

REMOTE = np.array([-143.75, -81.25, 54.13])  # the synthetic file's remote_stress


def hand_coulomb(sxx, syy, sxy, angle_deg, mu, sense):
    """dCFS by rotating the stress-change tensor: tau = t . dS . n, sigma_n = n . dS . n."""
    a = np.radians(angle_deg)
    t = np.array([np.cos(a), np.sin(a)])
    n = np.array([-np.sin(a), np.cos(a)])
    out = np.empty(np.shape(sxx))
    for index in np.ndindex(out.shape):
        change = np.array([[sxx[index], sxy[index]], [sxy[index], syy[index]]]) \
            - np.array([[REMOTE[0], REMOTE[2]], [REMOTE[2], REMOTE[1]]])
        out[index] = sense * (t @ change @ n) + mu * (n @ change @ n)
    return out


def test_coulomb_matches_hand_computation(result_file):
    result = load_result(result_file)
    np.testing.assert_array_equal(result["remote_stress"], REMOTE)  # as written: exact
    field = result["fields"]["grid1"]
    receiver = plot_data.Receiver(result["remote_stress"], 30.0, 0.4, "right")
    x, y, cfs = plot_data.grid_quantity(field, "coulomb", receiver)
    sxx, syy, sxy = -10.0 + x + 2.0 * y, -5.0 - x * y, 0.5 * x - y
    expected = hand_coulomb(sxx, syy, sxy, 30.0, 0.4, 1.0)
    keep = ~np.ma.getmaskarray(cfs)
    assert keep.sum() == 19
    np.testing.assert_allclose(cfs[keep], expected[keep], rtol=1e-12, atol=1e-12)
    # Point (x, y) = (-2, -1.5): sxx = -15, syy = -8, sxy = 0.5; by hand on paper:
    # d_tau = (73.25 - 128.75) sin30 cos30 - 53.63 cos60 = -50.8472050,
    # d_sigma_n = 128.75 / 4 + 73.25 * 3 / 4 + 2 * 53.63 sin30 cos30 = 133.5699424.
    assert cfs[0, 0] == pytest.approx(-50.8472050 + 0.4 * 133.5699424, abs=1e-6)
    left = plot_data.Receiver(result["remote_stress"], 30.0, 0.4, "left")
    _, _, cfs_left = plot_data.grid_quantity(field, "coulomb", left)
    np.testing.assert_allclose(cfs_left[keep], hand_coulomb(sxx, syy, sxy, 30.0, 0.4, -1.0)
                               [keep], rtol=1e-12, atol=1e-12)


def test_remote_stress_gives_no_coulomb_change():
    receiver = plot_data.Receiver(REMOTE, 17.0, 0.6, "right")
    assert plot_data.coulomb_stress_change(*REMOTE, receiver) == pytest.approx(0.0,
                                                                                 abs=1e-12)


def test_receiver_auto_sense_follows_the_remote_shear():
    # On a plane along x the remote shear is sxy = 54.13 > 0: right-lateral. On the
    # conjugate plane at -60 degrees it is -54.13: left-lateral.
    assert plot_data.Receiver(REMOTE, 0.0).sense == "right"
    assert plot_data.Receiver(REMOTE, -60.0).sense == "left"
    tau, sigma_n = plot_data.resolved_traction(*REMOTE, -60.0)
    assert tau == pytest.approx(-54.13, abs=1e-2)
    assert sigma_n == pytest.approx(-81.25, abs=1e-2)


def test_coulomb_map_from_the_command_line(plot_module, result_file, tmp_path):
    args = [str(result_file), "-o", str(tmp_path), "--quantity", "coulomb", "--receiver",
            "30", "--friction", "0.4", "--sense", "right", "--clim", "-5", "5"]
    assert plot_module.main(args) == 0
    assert (tmp_path / "synthetic_map_grid1_coulomb.png").is_file()
    result = load_result(result_file)
    receiver = plot_data.Receiver(result["remote_stress"], 30.0, 0.4, "right")
    fig = plot_figures.plot_map(result, "grid1", "coulomb", (-5.0, 5.0), receiver)
    try:
        ax = fig.axes[0]
        mesh = ax.collections[0]
        x, y = result["fields"]["grid1"]["x"], result["fields"]["grid1"]["y"]
        expected = hand_coulomb(-10.0 + x + 2.0 * y, -5.0 - x * y, 0.5 * x - y, 30.0, 0.4,
                                1.0)
        plotted = np.ma.masked_invalid(np.ma.filled(mesh.get_array(), np.nan)).reshape(4, 5)
        keep = ~np.ma.getmaskarray(plotted)
        np.testing.assert_allclose(plotted[keep], expected[keep], rtol=1e-12, atol=1e-12)
        assert "receiver 30 deg from +x, right-lateral, mu = 0.4" in ax.get_title()
    finally:
        plot_figures.plt.close(fig)


def test_coulomb_without_remote_stress_exits_2(result_file, tmp_path):
    with h5py.File(result_file, "a") as f:
        del f.attrs["remote_stress"]
    proc = run_plot(result_file, "-o", tmp_path / "out", "--quantity", "coulomb")
    assert proc.returncode == 2
    assert "remote_stress" in proc.stderr and "Traceback" not in proc.stderr
    assert run_plot(result_file, "-o", tmp_path / "out").returncode == 0  # other maps do


def test_quantity_lists(plot_module, result_file, tmp_path):
    assert plot_module.main([str(result_file), "-o", str(tmp_path / "two"),
                             "--quantity", "sxx,mean"]) == 0
    assert [p.name for p in sorted((tmp_path / "two").glob("*_map_*"))] == [
        "synthetic_map_grid1_mean.png", "synthetic_map_grid1_sxx.png"]
    assert plot_module.main([str(result_file), "-o", str(tmp_path / "all"),
                             "--quantity", "all", "--format", "svg"]) == 0
    assert len(list((tmp_path / "all").glob("*_map_*.svg"))) == 11
    proc = run_plot(result_file, "-o", tmp_path / "bad", "--quantity", "sxx,tau")
    assert proc.returncode == 2 and "tau" in proc.stderr


def test_default_clim_centres_signed_maps_on_the_remote_value(result_file):
    result = load_result(result_file)
    assert plot_data.remote_value(result, "mean") == pytest.approx(-112.5)
    assert plot_data.remote_value(result, "sxy") == pytest.approx(54.13)
    assert plot_data.remote_value(result, "coulomb") == 0.0
    values = np.ma.masked_array(-112.5 + np.linspace(-3.0, 1.0, 101))
    low, high = plot_data.default_clim(values, "mean", centre=-112.5)
    assert low + high == pytest.approx(-225.0) and high > -112.5


# ------------------------------------------------------ background stress varying with depth

GRADIENT = (0.01325, 0.0265, 0.0)  # lithostatic: dsxx_dy, dsyy_dy, dsxy_dy [MPa/m]


def write_background_only(path, remote=(0.0, 0.0, 0.0), gradient=GRADIENT,
                          pore=(0.0, -0.00981)):
    """The synthetic file with a grid whose total stress is the background alone,
    remote + gradient * y, as around a fault that does not slip."""
    write_result(path)
    with h5py.File(path, "a") as f:
        f.attrs["remote_stress"] = np.array(remote)
        f.attrs["remote_stress_gradient"] = np.array(gradient)
        f.attrs["pore_fluid"] = np.array(pore)
        grid = f["fields/grid1"]
        y = grid["y"][...]
        for key, r, g in zip(("sxx", "syy", "sxy"), remote, gradient):
            grid[key][...] = r + g * y
    return path


def test_changes_are_taken_from_the_background_with_its_gradient(tmp_path):
    # Without fractures acting, the Coulomb stress change and the induced stresses are
    # zero everywhere, however the background grows with depth (gravity); only taking the
    # changes from the uniform remote stress gave lithostatic bands here.
    result = load_result(write_background_only(tmp_path / "litho.h5"))
    assert result["remote_stress_gradient"] == GRADIENT
    assert result["pore_fluid"] == (0.0, -0.00981)
    field = result["fields"]["grid1"]
    background = plot_data.Background.of_result(result)
    receiver = plot_data.Receiver(background, 60.0, 0.6, "right")
    _, y, cfs = plot_data.grid_quantity(field, "coulomb", receiver)
    scale = np.max(np.abs(np.asarray(GRADIENT)[:, None, None] * y))
    assert np.ma.count(cfs) == 19
    assert np.ma.max(np.abs(cfs)) <= 1e-12 * scale
    for quantity in plot_data.INDUCED:
        _, _, induced = plot_data.grid_quantity(field, quantity, background=background)
        assert np.ma.max(np.abs(induced)) <= 1e-12 * scale, quantity


def test_induced_stress_is_total_minus_background(result_file):
    result = load_result(result_file)
    with h5py.File(result_file, "a") as f:
        f.attrs["remote_stress_gradient"] = np.array(GRADIENT)
    result = load_result(result_file)
    field = result["fields"]["grid1"]
    x, y, induced = plot_data.grid_quantity(field, "induced_syy",
                                              background=plot_data.Background.of_result(result))
    expected = (-5.0 - x * y) - (REMOTE[1] + GRADIENT[1] * y)
    keep = ~np.ma.getmaskarray(induced)
    np.testing.assert_allclose(induced[keep], expected[keep], rtol=1e-12, atol=1e-12)
    _, _, mean = plot_data.grid_quantity(field, "induced_mean",
                                           background=plot_data.Background.of_result(result))
    expected = 0.5 * ((-10.0 + x + 2.0 * y) + (-5.0 - x * y)) \
        - 0.5 * (REMOTE[0] + REMOTE[1] + (GRADIENT[0] + GRADIENT[1]) * y)
    np.testing.assert_allclose(mean[keep], expected[keep], rtol=1e-12, atol=1e-12)


def test_auto_sense_from_the_background_at_the_grid_depth():
    # Gravity alone (no uniform part): on a plane at 60 degrees the background drives
    # normal, that is left-lateral, slip below the surface; a zero stress at y = 0 would
    # say 'right'.
    background = plot_data.Background((0.0, 0.0, 0.0), GRADIENT)
    assert plot_data.Receiver(background, 60.0, 0.6, "auto", reference_y=-1500.0).sense \
        == "left"
    assert plot_data.Receiver(background, 60.0, 0.6, "auto", reference_y=0.0).sense \
        == "right"  # zero shear at the surface: the tie rule's right-lateral
    receiver = plot_data.Receiver(background, 60.0, 0.6, "auto", reference_y=-1500.0)
    assert "(auto: the sense at y = -1500)" in receiver.describe()
    field = {"y": np.array([[-3000.0, -3000.0], [-10.0, -10.0]])}
    assert plot_data.grid_reference_y(field) == pytest.approx(-1505.0)


def test_total_stress_map_with_a_gradient_has_no_white_centre(tmp_path):
    result = load_result(write_background_only(tmp_path / "litho.h5",
                                                           remote=(-2.0, 0.0, 0.0)))
    assert plot_data.remote_value(result, "syy") is None
    assert plot_data.remote_value(result, "mean") is None
    assert plot_data.remote_value(result, "sxy") == 0.0  # dsxy_dy = 0: uniform
    assert plot_data.remote_value(result, "induced_syy") == 0.0
    fig = plot_figures.plot_map(result, "grid1", "syy")
    try:
        mesh = fig.axes[0].collections[0]
        assert mesh.get_cmap().name == "viridis"
        assert "for the change see induced_syy" in fig.axes[0].get_title()
    finally:
        plot_figures.plt.close(fig)
    fig = plot_figures.plot_map(result, "grid1", "induced_syy")
    try:
        assert fig.axes[0].collections[0].get_cmap().name == "RdBu_r"
        title = fig.axes[0].get_title()
        assert "change from the remote stress + gradient * y" in title
        assert "pore pressure given, unchanged: drained" in title
    finally:
        plot_figures.plt.close(fig)


def test_coulomb_map_of_a_normal_fault_under_gravity_shows_the_fault(plot_module, tmp_path):
    # A model through ddc2d and the command line: a half-plane normal fault
    # under gravity with hydrostatic pore fluid, receivers parallel to it (60 degrees).
    # Far from the fault the change vanishes (it was -25 .. -45 MPa of lithostatic bands),
    # beside the slipping fault it is a stress shadow, below its tip a positive lobe.
    (tmp_path / "normal.nml").write_text("""\
&model youngs_modulus = 30000, poissons_ratio = 0.25, domain = 'half_plane' /
&remote_stress dsyy_dy = 0.0265, dsxx_dy = 0.01325 /
&pore_fluid dp_dy = -0.00981 /
&fracture name = 'fault', x = 0, -1154.7, y = 0, -2000, elements = 100, mu = 0.6 /
&grid name = 'section', xmin = -3000, xmax = 2000, nx = 11, ymin = -3000, ymax = -100,
      ny = 30 /
""")
    done = subprocess.run([str(ddc2d_exe()), "normal.nml"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert plot_module.main([str(tmp_path / "normal.h5"), "-o", str(tmp_path), "--quantity",
                             "coulomb", "--receiver", "60"]) == 0
    result = load_result(tmp_path / "normal.h5")
    field = result["fields"]["section"]
    receiver = plot_data.Receiver(plot_data.Background.of_result(result), 60.0, 0.6,
                                    "auto", plot_data.grid_reference_y(field))
    assert receiver.sense == "left"  # normal slip on a plane dipping 60 degrees to -x
    x, y, cfs = plot_data.grid_quantity(field, "coulomb", receiver)
    far = (x == 2000.0) & (y <= -2500.0)  # measured 0.16 .. 0.18 MPa
    assert np.all(np.abs(cfs[far]) < 0.5), cfs[far]
    beside = (x == -500.0) & (np.abs(y + 1000.0) < 60.0)  # beside the middle: -1.49
    assert np.all(cfs[beside] < -0.5), cfs[beside]
    below = (x == -1500.0) & (y <= -2150.0) & (y >= -2650.0)  # below the tip: 0.98 .. 1.31
    assert np.all(cfs[below] > 0.5), cfs[below]


# ------------------------------------------------------------------ vectors, overview, tips


def test_displacement_map_draws_the_displacement_vectors(result_file):
    result = load_result(result_file)
    fig = plot_figures.plot_map(result, "grid1", "displacement")
    try:
        (quiver,) = [c for c in fig.axes[0].collections if c.get_gid() == "vectors"]
        field = result["fields"]["grid1"]
        keep = np.isfinite(field["ux"])  # 5 x 4 grid: every point, step 1, but the NaN
        assert plot_data.quiver_step(5, 4) == 1
        # The arrows are the stored values themselves: exact.
        np.testing.assert_array_equal(quiver.U, field["ux"][keep])
        np.testing.assert_array_equal(quiver.V, field["uy"][keep])
        np.testing.assert_array_equal(quiver.X, field["x"][keep])
    finally:
        plot_figures.plt.close(fig)
    assert plot_data.quiver_step(101, 76) == 5  # at most 24 arrows on a side


def test_overview_profile_shows_every_fracture(result_file):
    result = load_result(result_file)
    elements = result["elements"]
    # The elements span 2 in x (A: -1..1) and 2.4 in y (B: 0..2.4): the model's longer
    # extent is y, but each fracture is drawn along its own: A along x, B along y.
    assert plot_data.overview_axis(elements) == "y"
    assert plot_data.overview_axis(elements, 1, 4) == "x"
    assert plot_data.overview_axis(elements, 5, 7) == "y"
    fig = plot_figures.plot_overview(result)
    try:
        for row, key in ((0, "slip"), (1, "opening")):
            lines = {ln.get_gid(): ln for ln in fig.axes[row].get_lines() if ln.get_gid()}
            for label, sl, axis in (("fault_A", slice(0, 4), "x"), ("B", slice(4, 7), "y")):
                line = lines[f"{key}:{label}"]
                np.testing.assert_allclose(line.get_xdata(), elements[f"{axis}_mid"][sl],
                                           rtol=1e-14)
                data = -elements["ds" if key == "slip" else "dn"][sl]
                np.testing.assert_array_equal(line.get_ydata(), data)  # stored values
        legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
        assert legend == ["fault A (against x)", "B (against y)", "stick", "slip", "open",
                          "free"]
        assert fig.axes[1].get_xlabel() == ("x or y of element midpoint, each fracture along "
                                            f"its longer extent [{LENGTH_UNIT}]")
        assert fig.axes[0].get_title(loc="left") == "slip > 0: right-lateral"  # map view
    finally:
        plot_figures.plt.close(fig)


def test_a_vertical_fracture_is_drawn_along_y_in_the_overview(tmp_path):
    # A fault along x and a vertical fracture at x = 0: the fracture no longer collapses
    # onto x = 0 but runs along its own y.
    (tmp_path / "t.nml").write_text("""\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -10, syy = -20, sxy = 5 /
&fracture name = 'fault', x = -3, 3, y = -2, -2, elements = 12, mu = 0.6 /
&fracture name = 'dyke', x = 0, 0, y = -1, 1, elements = 8, condition = 'traction',
          bc_n = -30 /
""")
    done = subprocess.run([str(ddc2d_exe()), "t.nml"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    result = load_result(tmp_path / "t.h5")
    fig = plot_figures.plot_overview(result)
    try:
        lines = {ln.get_gid(): ln for ln in fig.axes[0].get_lines() if ln.get_gid()}
        np.testing.assert_allclose(lines["slip:dyke"].get_xdata(),
                                   result["elements"]["y_mid"][12:], rtol=1e-14)
        assert np.ptp(lines["slip:dyke"].get_xdata()) > 1.5
        np.testing.assert_allclose(lines["slip:fault"].get_xdata(),
                                   result["elements"]["x_mid"][:12], rtol=1e-14)
    finally:
        plot_figures.plt.close(fig)


def test_tips_table_files(result_file, tmp_path):
    proc = run_plot(result_file, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    with open(tmp_path / "synthetic_tips.csv", newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["tip", "fracture", "element", f"x [{LENGTH_UNIT}]",
                       f"y [{LENGTH_UNIT}]", f"K_I [{STRESS_UNIT} {LENGTH_UNIT}^0.5]",
                       f"K_II [{STRESS_UNIT} {LENGTH_UNIT}^0.5]"]
    assert [r[:3] for r in rows[1:]] == [["1", "fault A", "1"], ["2", "fault A", "4"],
                                        ["3", "B", "5"], ["4", "B", "7"]]
    numbers = np.array([[float(v) for v in r[3:]] for r in rows[1:]])
    # The CSV writes repr(): the stored numbers come back bit for bit.
    np.testing.assert_array_equal(numbers, [[-1.0, 0.0, 0.0, 1.2], [1.0, 0.0, 0.0, 1.1],
                                            [0.0, 1.0, 0.1, -0.2], [0.3, 2.4, 0.0, 0.3]])
    text = (tmp_path / "synthetic_tips.txt").read_text().splitlines()
    assert text[0] == "crack tips of synthetic.h5: stress intensity factors"
    assert text[1].split() == ["tip", "fracture", "element", "x", f"[{LENGTH_UNIT}]", "y",
                               f"[{LENGTH_UNIT}]", "K_I", f"[{STRESS_UNIT}",
                               f"{LENGTH_UNIT}^0.5]", "K_II", f"[{STRESS_UNIT}",
                               f"{LENGTH_UNIT}^0.5]"]
    assert text[2].split() == ["1", "fault", "A", "1", "-1", "0", "0", "1.2"]
    assert text[4].split() == ["3", "B", "5", "0", "1", "0.1", "-0.2"]
    assert len(text) == 6


def test_tips_table_without_tips(result_file, tmp_path):
    with h5py.File(result_file, "a") as f:
        del f["tips"]
    result = load_result(result_file)
    assert plot_data.tips_csv(result).splitlines()[1:] == []
    assert "no crack tips" in plot_data.tips_text(result)


# ------------------------------------------------------------------ a model solved by ddc2d

SOLVED_MODEL = """\
! A pressurized crack beside a frictional fault, small enough for a Debug build.
&model title = 'small solved model', youngs_modulus = 50000.0, poissons_ratio = 0.25,
       length_unit = 'm', stress_unit = 'MPa' /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 30, mu = 0.6, sf = 1.0 /
&fracture name = 'crack', x = -0.2, 0.2, y = 0.5, 0.3, elements = 10, mu = 0.6,
          pressure = 70.0 /
&grid name = 'area', xmin = -1.5, xmax = 1.5, nx = 16, ymin = -1.0, ymax = 1.0, ny = 11 /
"""


def test_plots_a_model_solved_by_ddc2d(tmp_path):
    model = tmp_path / "solved.nml"
    model.write_text(SOLVED_MODEL)
    done = subprocess.run([str(ddc2d_exe()), str(model), "-o", str(tmp_path / "solved.h5")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    proc = run_plot(tmp_path / "solved.h5", "-o", tmp_path / "fig", "--quantity",
                    "coulomb,displacement")
    assert proc.returncode == 0, proc.stderr
    assert figure_files(tmp_path / "fig") == [
        "solved_map_area_coulomb.png", "solved_map_area_displacement.png",
        "solved_profile_crack.png", "solved_profile_fault.png", "solved_profiles.png",
        "solved_tips.csv", "solved_tips.txt"]
    result = load_result(tmp_path / "solved.h5")
    with h5py.File(tmp_path / "solved.h5", "r") as f:
        ds, dn, state = f["elements/ds"][()], f["elements/dn"][()], f["elements/state"][()]
        k2 = f["tips/k2"][()]
    (fault, fault_profile), (crack, crack_profile) = plot_data.fracture_profiles(result)
    assert (fault["first"], fault["last"], crack["first"], crack["last"]) == (1, 30, 31, 40)
    fig = plot_figures.plot_profile(result, crack, crack_profile)
    # Figures, profiles and the tips CSV (repr) hold the stored values: compared exactly.
    try:
        (line,) = [ln for ln in fig.axes[1].get_lines() if ln.get_gid() == "opening"]
        np.testing.assert_array_equal(line.get_ydata(), -dn[30:40])
    finally:
        plot_figures.plt.close(fig)
    np.testing.assert_array_equal(fault_profile["slip"], -ds[:30])
    np.testing.assert_array_equal(fault_profile["state"], state[:30])
    assert np.all(crack_profile["state"] == STATE_CODES["open"])  # 70 MPa > 50 MPa: open
    with open(tmp_path / "fig" / "solved_tips.csv", newline="") as handle:
        rows = list(csv.reader(handle))[1:]
    assert [r[1] for r in rows] == ["fault", "fault", "crack", "crack"]
    np.testing.assert_array_equal([float(r[6]) for r in rows], k2)


# ------------------------------------------------ observation lines and points, file names

LINES_MODEL = """\
&model youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -10, syy = -20, sxy = 5 /
&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 20, condition = 'traction',
          bc_n = -30 /
&grid name = 'map', xmin = -2, xmax = 2, nx = 5, ymin = -1, ymax = 1, ny = 4 /
&line name = 'across', x_begin = 0, y_begin = -1, x_end = 0, y_end = 1, points = 9 /
&line name = 'along', x_begin = -0.5, y_begin = 0, x_end = 0.5, y_end = 0, points = 3 /
&points name = 'wells', file = 'wells.csv' /
"""


def test_figures_of_observation_lines_and_points(tmp_path):
    # A full-plane model's &line and &points get figures of ux, uy, sxx, syy, sxy against
    # the distance along them; a point on the crack is a gap; a line that lies on the crack
    # (every point NaN) gets a warning instead of an empty figure. The grid named 'map' is
    # <stem>_map_<quantity>, not <stem>_map_map_<quantity>.
    (tmp_path / "wells.csv").write_text("x,y\n2,0.5\n2,1.5\n-1,1.5\n")
    (tmp_path / "lines.nml").write_text(LINES_MODEL)
    done = subprocess.run([str(ddc2d_exe()), "lines.nml"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    proc = run_plot(tmp_path / "lines.h5", "-o", tmp_path / "out")
    assert proc.returncode == 0, proc.stderr
    assert figure_files(tmp_path / "out") == [
        "lines_line_across.png", "lines_map_max_shear.png", "lines_points_wells.png",
        "lines_profile_crack.png", "lines_tips.csv", "lines_tips.txt"]
    assert proc.stderr == ("ddc2d-plot: warning: every point of line 'along' lies on an "
                           "element (NaN): no figure\n")
    result = load_result(tmp_path / "lines.h5")
    for name, distance in (("across", np.linspace(0.0, 2.0, 9)),
                           ("wells", np.array([0.0, 1.0, 4.0]))):
        field = result["fields"][name]
        fig = plot_figures.plot_observation_line(result, name)
        try:
            lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines()
                     if ln.get_gid()}
            assert sorted(lines) == ["sxx", "sxy", "syy", "ux", "uy"]
            for key, line in lines.items():
                np.testing.assert_allclose(line.get_xdata(), distance, rtol=1e-14,
                                           atol=1e-14)
                # The stored values themselves (NaN where the point is on the crack).
                np.testing.assert_array_equal(line.get_ydata(), field[key])
            assert fig.axes[2].get_ylabel() == rf"$\sigma_{{xx}}$ [{'MPa'}]"
        finally:
            plot_figures.plt.close(fig)
    # The middle point of 'across' is on the crack: NaN, said in the title.
    assert np.isnan(result["fields"]["across"]["sxx"][4])
    fig = plot_figures.plot_observation_line(result, "across")
    try:
        assert "1 on an element (NaN: gaps)" in fig.texts[0].get_text()
    finally:
        plot_figures.plt.close(fig)


def test_figure_names_leave_out_a_name_that_repeats_the_kind(tmp_path):
    used = set()
    base = plot_data.figure_base
    assert base(tmp_path, "m", "map", "map", used, "sxx").name == "m_map_sxx"
    assert base(tmp_path, "m", "map", "grid 2", used, "sxx").name == "m_map_grid_2_sxx"
    assert base(tmp_path, "m", "profile", "profile", used).name == "m_profile"
    assert base(tmp_path, "m", "surface", "surface", used).name == "m_surface"
    # A grid 'induced' mapped as sxx would take the name of grid 'map' mapped as
    # induced_sxx: the second one gets a number, nothing is overwritten.
    assert base(tmp_path, "m", "map", "map", used, "induced_sxx").name == "m_map_induced_sxx"
    assert base(tmp_path, "m", "map", "induced", used, "sxx").name == "m_map_induced_sxx_2"
    assert len(used) == 6


# ------------------------------------------------------------ opening panel and slip sense


def test_no_opening_panel_without_opening(result_file, tmp_path):
    result = load_result(result_file)
    assert plot_data.has_dd(result, "dn")  # elements 3 and 6 are open
    fracture, profile = plot_data.fracture_profiles(result)[0]
    fig = plot_figures.plot_profile(result, fracture, profile)
    assert len(fig.axes) == 2
    plot_figures.plt.close(fig)
    with h5py.File(result_file, "a") as f:
        f["elements/dn"][...] = 0.0
        f["elements/state"][...] = np.where(f["elements/state"][...] == 3, 2,
                                            f["elements/state"][...])
    result = load_result(result_file)
    assert not plot_data.has_dd(result, "dn")
    for fig in (plot_figures.plot_profile(result, fracture, profile),
                plot_figures.plot_overview(result)):
        try:
            assert len(fig.axes) == 1
            assert fig.axes[0].get_ylabel().startswith("slip")
        finally:
            plot_figures.plt.close(fig)


def test_no_slip_panel_for_round_off_slip(result_file):
    # A crack opened symmetrically has slip of round-off size (1e-17 of its opening, of
    # either sign by CPU): no slip panel, as without opening no opening panel.
    with h5py.File(result_file, "a") as f:
        f["elements/ds"][...] = 1e-20 * np.array([1, -3, 2, 0, -1, 4, -2])
        f["elements/state"][...] = 3
    result = load_result(result_file)
    assert not plot_data.has_dd(result, "ds") and plot_data.has_dd(result, "dn")
    fracture, profile = plot_data.fracture_profiles(result)[0]
    fig = plot_figures.plot_profile(result, fracture, profile)
    try:
        assert len(fig.axes) == 1
        assert fig.axes[0].get_ylabel().startswith("opening")
        assert "no element slips" in fig.texts[0].get_text()
    finally:
        plot_figures.plt.close(fig)


def sense_of(plot_module, begin, end, domain="half_plane"):
    result = {"attrs": {"domain": domain}, "remote_stress_gradient": (0.0, 0.0, 0.0),
              "pore_fluid": (0.0, 0.0),
              "elements": {"x_begin": np.array([begin[0]]), "y_begin": np.array([begin[1]]),
                           "x_end": np.array([end[0]]), "y_end": np.array([end[1]])}}
    return plot_data.slip_sense(result, {"first": 1, "last": 1})


def test_what_positive_slip_means(plot_module):
    reverse = "slip > 0: reverse (hanging wall up), < 0: normal"
    normal = "slip > 0: normal (hanging wall down), < 0: reverse"
    # A fault dipping to -x drawn from its outcrop down (the thrust example: Ds < 0 is
    # reverse), and the same fault drawn upward: the meaning does not depend on it.
    assert sense_of(plot_module, (0, 0), (-1154.7, -2000)) == reverse
    assert sense_of(plot_module, (-1154.7, -2000), (0, 0)) == reverse
    assert sense_of(plot_module, (0, 0), (1154.7, -2000)) == normal
    assert sense_of(plot_module, (0, -100), (0, -900)) == "slip > 0: the +x side moves down"
    assert sense_of(plot_module, (0, -900), (0, -100)) == "slip > 0: the +x side moves down"
    assert sense_of(plot_module, (-5, -9), (5, -9)) == "slip > 0: the upper side moves to +x"
    assert sense_of(plot_module, (0, 0), (1, 1), domain="full_plane") == \
        "slip > 0: right-lateral"


def polyline_sense(points, created=None, domain="half_plane"):
    """slip_sense of one fracture on the polyline `points` (an element per segment),
    created_step `created` per element when given."""
    x, y = np.array(points, dtype=float).T
    elements = {"x_begin": x[:-1], "y_begin": y[:-1], "x_end": x[1:], "y_end": y[1:]}
    if created is not None:
        elements["created_step"] = np.array(created)
    result = {"attrs": {"domain": domain}, "remote_stress_gradient": (0.0, 0.0, 0.0),
              "pore_fluid": (0.0, 0.0), "elements": elements}
    return plot_data.slip_sense(result, {"first": 1, "last": x.size - 1})


def test_positive_slip_is_named_only_where_it_holds():
    reverse = "slip > 0: reverse (hanging wall up), < 0: normal"
    # A kinked fault whose segments all dip to +x rising: reverse on each, said as before.
    assert polyline_sense([(0, -10), (5, -5), (6, 0)]) == reverse
    # A fault dipping to +x (reverse), grown at both ends into segments that dip the other
    # way (normal) and a vertical one: the sense is said for the input's elements only.
    assert polyline_sense([(-1, -9), (0, -10), (5, -5), (5, -4)], created=[1, 0, 2]) == \
        reverse + " (the input fracture; the grown elements vary)"
    # A curved input fault that changes its dip: no sense for the whole fracture.
    varies = ("slip > 0: the positive face moves along the element direction (the sense "
              "varies)")
    assert polyline_sense([(-1, -9), (0, -10), (5, -5)]) == varies
    assert polyline_sense([(-1, -9), (0, -10), (5, -5)], created=[0, 0]) == varies
    # In a map view right-lateral holds on every element, curved or not.
    assert polyline_sense([(-1, -9), (0, -10), (5, -5)], domain="full_plane") == \
        "slip > 0: right-lateral"


def test_the_profile_says_what_positive_slip_means(tmp_path):
    # The thrust example's geometry: its profile says reverse, and it slips reverse.
    (tmp_path / "thrust.nml").write_text((REPO_ROOT / "input" / "thrust_fault_surface.nml")
                                         .read_text().replace("elements = 240",
                                                              "elements = 40"))
    done = subprocess.run([str(ddc2d_exe()), "thrust.nml"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    result = load_result(tmp_path / "thrust.h5")
    fracture, profile = plot_data.fracture_profiles(result)[0]
    fig = plot_figures.plot_profile(result, fracture, profile)
    try:
        assert fig.axes[0].get_title(loc="left") == \
            "slip > 0: reverse (hanging wall up), < 0: normal"
    finally:
        plot_figures.plt.close(fig)
    assert np.median(profile["slip"]) > 0.0
