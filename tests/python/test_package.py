"""The ddc2d Python package's own interface (docs/python.md): a model built in Python and
run by ddc2d.run, the Result of ddc2d.open_result with its units, input echo and
provenance, to_xarray, RunError on bad input, and where the executable is found."""

import math
import os

import numpy as np
import pytest

import ddc2d
from conftest import REPO_ROOT, ddc2d_exe
from ddc2d.model import namelist_value
from ddc2d.paths import find_executable

#: The pressurized crack of input/pressurized_crack.nml: half-length a [m], pressure p [MPa].
HALF_LENGTH, PRESSURE = 1.0, 10.0
#: K_I of 200 constant-DD elements against the closed form p sqrt(pi a) (measured 0.07 %
#: below it; the bound leaves room for other BLAS kernels, not for a wrong unit or factor).
K_RTOL = 5e-3


def pressurized_crack(elements=200):
    """input/pressurized_crack.nml built in Python, with a smaller grid and a point set."""
    model = ddc2d.Model(youngs_modulus=50000.0, poissons_ratio=0.25, title="Pressurized crack",
                        length_unit="m", stress_unit="MPa")
    model.remote_stress(sxx=0.0, syy=0.0, sxy=0.0)
    model.fracture([-HALF_LENGTH, HALF_LENGTH], [0.0, 0.0], elements=elements,
                   condition="traction", bc_s=0.0, bc_n=-PRESSURE, name="crack")
    model.grid(xmin=-2.0, xmax=2.0, nx=11, ymin=-1.5, ymax=1.5, ny=7, name="map")
    model.line(0.0, 0.05, 0.0, 3.0, 6, name="above_centre")
    model.points([0.5, 1.5, -0.25], [0.5, -0.5, 2.0], name="wells")
    return model


@pytest.fixture(scope="module")
def crack(tmp_path_factory):
    folder = tmp_path_factory.mktemp("crack")
    return ddc2d.run(pressurized_crack(), output=folder / "crack.h5", executable=ddc2d_exe())


def test_pressurized_crack_k1_against_the_closed_form(crack):
    closed_form = PRESSURE * math.sqrt(math.pi * HALF_LENGTH)
    assert crack.tips["k1"].size == 2
    np.testing.assert_allclose(crack.tips["k1"], closed_form, rtol=K_RTOL)
    np.testing.assert_allclose(crack.tips["k2"], 0.0, atol=1e-6 * closed_form)
    assert crack.unit("tips/k1") == "MPa m^0.5"
    assert crack.unit("/elements/ds") == "m" and crack.unit("elements/absent") == ""


def test_result_holds_the_input_echo_and_the_provenance(crack, tmp_path):
    written = (crack.path.parent / "crack.nml").read_text()
    assert crack.input_text.strip() == written.strip()
    assert crack.provenance["program"] == "ddc2d"
    assert crack.provenance["youngs_modulus"] == pytest.approx(50000.0)
    assert crack.title == "Pressurized crack" and crack.complete
    assert crack.elements["ds"].size == 200 and crack.fractures[0]["name"] == "crack"
    assert crack["length_unit"] == "m"  # the reader's dict, for ddc2d.plot
    assert "200 elements, 2 tips" in repr(crack)


def test_the_builders_namelist_runs_as_the_example_file(crack, tmp_path):
    """The namelist the builder writes is the model of input/pressurized_crack.nml: the
    same elements and the same opening, run from the file."""
    from_file = ddc2d.run(REPO_ROOT / "input" / "pressurized_crack.nml",
                          output=tmp_path / "file.h5", executable=ddc2d_exe())
    for key in ("x_begin", "y_begin", "x_end", "y_end"):
        np.testing.assert_allclose(crack.elements[key], from_file.elements[key], atol=1e-12)
    scale = np.max(np.abs(from_file.elements["dn"]))
    np.testing.assert_allclose(crack.elements["dn"], from_file.elements["dn"],
                               rtol=0, atol=1e-9 * scale)


def test_grid_to_xarray_has_the_grid_lines_as_coordinates(crack):
    grid = crack.to_xarray("map")
    assert grid["sxx"].dims == ("y", "x") and grid["sxx"].shape == (7, 11)
    np.testing.assert_allclose(grid["x"], np.linspace(-2.0, 2.0, 11), atol=1e-12)
    np.testing.assert_allclose(grid["y"], np.linspace(-1.5, 1.5, 7), atol=1e-12)
    assert grid["syy"].attrs["units"] == "MPa" and grid["ux"].attrs["units"] == "m"
    # A value picked by coordinates is the file's value at that row and column.
    row, column = 5, 8
    picked = grid["syy"].sel(x=grid["x"][column], y=grid["y"][row])
    assert float(picked) == crack.fields["map"]["syy"][row, column]


def test_line_and_points_to_xarray_run_along_a_point_index(crack):
    line = crack.to_xarray("above_centre")
    assert line["uy"].dims == ("point",) and line.sizes["point"] == 6
    np.testing.assert_allclose(line["y"], np.linspace(0.05, 3.0, 6), atol=1e-12)
    wells = crack.to_xarray("wells")
    np.testing.assert_allclose(wells["x"], [0.5, 1.5, -0.25], atol=1e-12)
    assert list(wells["point"].values) == [1, 2, 3]
    everything = crack.to_xarray()
    assert sorted(everything) == ["above_centre", "map", "wells"]
    with pytest.raises(KeyError, match="no observation set 'nowhere'"):
        crack.to_xarray("nowhere")
    with pytest.raises(KeyError, match="no loading history"):
        crack.to_xarray("history")


def test_history_to_xarray_is_steps_by_elements(tmp_path):
    model = ddc2d.Model(youngs_modulus=50000.0, poissons_ratio=0.25)
    model.remote_stress(sxx=-143.75, syy=-81.25, sxy=0.0)
    model.fracture([-1.0, 1.0], [0.0, 0.0], elements=10, mu=0.6, sf=1.0, name="fault")
    model.load_path(steps=[4, 2], sxy=[0.0, 54.13, 0.0])
    result = ddc2d.run(model, output=tmp_path / "path.h5", executable=ddc2d_exe())
    history = result.to_xarray("history")
    assert history["ds"].dims == ("step", "element") and history["ds"].shape == (7, 10)
    assert list(history["element"].values) == list(range(1, 11))
    np.testing.assert_allclose(history["sxy"], [0, 13.5325, 27.065, 40.5975, 54.13, 27.065, 0],
                               atol=1e-9)
    assert history["ds"].attrs["units"] == "m"
    assert history["k2"].dims == ("step", "tip")
    # Slip at the peak load: every element slips (the fault's strength is 49.75 MPa).
    assert np.all(np.abs(history["ds"].sel(step=5)) > 0)


def test_bad_model_raises_run_error_with_the_programs_message(tmp_path):
    model = ddc2d.Model(youngs_modulus=-1.0, poissons_ratio=0.25)
    model.fracture([0.0, 1.0], [0.0, 0.0], elements=4, mu=0.6)
    with pytest.raises(ddc2d.RunError) as caught:
        ddc2d.run(model, output=tmp_path / "bad.h5", executable=ddc2d_exe())
    assert caught.value.exit_code == 2
    assert str(caught.value).startswith("ddc2d: error: ")
    assert "youngs_modulus = -1.00000 must be positive" in str(caught.value)
    assert not (tmp_path / "bad.h5").exists()


def test_missing_result_raises_result_error(tmp_path):
    with pytest.raises(ddc2d.ResultError, match="no such file"):
        ddc2d.open_result(tmp_path / "absent.h5")


def test_namelist_values():
    assert namelist_value("it's") == "'it''s'"
    assert namelist_value(True) == ".true."
    assert namelist_value([1, 2.5, np.float64(0.1)]) == "1, 2.5, 0.1"
    assert namelist_value(np.array([1.0, -2.0])) == "1.0, -2.0"
    with pytest.raises(ValueError, match="finite"):
        namelist_value(float("nan"))
    with pytest.raises(TypeError):
        namelist_value({"a": 1})


def test_points_are_written_beside_the_namelist(tmp_path):
    path = pressurized_crack().write(tmp_path / "crack.nml")
    assert "&points name = 'wells', file = 'crack_wells.csv' /" in path.read_text()
    assert (tmp_path / "crack_wells.csv").read_text() == "x,y\n0.5,0.5\n1.5,-0.5\n-0.25,2.0\n"


def test_a_single_group_given_twice_is_replaced():
    model = ddc2d.Model(youngs_modulus=1.0, poissons_ratio=0.0)
    model.remote_stress(sxx=-1.0).remote_stress(syy=-2.0)
    assert model.namelist().count("&remote_stress") == 1
    assert "syy = -2.0" in model.namelist()


def test_the_executable_given_then_environment_then_path(tmp_path, monkeypatch):
    on_path = tmp_path / "bin" / "ddc2d"
    on_path.parent.mkdir()
    on_path.write_text("#!/bin/sh\n")
    on_path.chmod(0o755)
    monkeypatch.setenv("PATH", str(on_path.parent))
    monkeypatch.setenv("DDC2D_EXE", str(tmp_path / "from_environment"))
    assert find_executable(tmp_path / "given") == tmp_path / "given"
    assert find_executable() == tmp_path / "from_environment"
    monkeypatch.delenv("DDC2D_EXE")
    assert find_executable() == on_path


def test_no_executable_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.setenv("DDC2D_EXE", str(tmp_path / "nowhere" / "ddc2d"))
    with pytest.raises(FileNotFoundError, match="no ddc2d executable at .*nowhere"):
        ddc2d.run(pressurized_crack(), output=tmp_path / "x.h5")
    assert os.listdir(tmp_path) == []
