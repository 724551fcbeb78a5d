"""ddc2d.reader (python/src/ddc2d/reader.py), the reader every tool and test shares: strings,
codings, the groups of a result file, and what is not a ddc2d result."""

import subprocess

import h5py
import numpy as np
import pytest

from conftest import ddc2d_exe, solve_text, write_result
from ddc2d import reader, twodd2nml

# ------------------------------------------------------------------ strings


@pytest.mark.parametrize("value", [
    b"slip  ", b"slip\x00\x00", np.bytes_(b"slip   "), "slip ", np.array(b"slip  "),
    np.array([b"slip  "]), np.array(["slip"], dtype=object),
])
def test_decode_strips_fortran_padding(value):
    assert reader.decode(value) == "slip"


def test_decode_joins_several_strings():
    assert reader.decode(np.array([b"a  ", b"bc "], dtype="S3")) == "a bc"


def test_strings_read_back_from_hdf5_as_ddc2d_writes_them(tmp_path):
    with h5py.File(tmp_path / "s.h5", "w") as f:
        f.attrs["title"] = np.bytes_(b"two words    ")
        f.attrs["count"] = np.int32(3)
        f.create_dataset("names", data=np.array([b"fault A ", b"B       "], dtype="S8"))
    with h5py.File(tmp_path / "s.h5", "r") as f:
        assert reader.attr_text(f.attrs, "title") == "two words"
        assert reader.attr_text(f.attrs, "absent", "none") == "none"
        assert reader.attr_int(f.attrs, "count", 0) == 3
        assert reader.attr_int(f.attrs, "absent", -1) == -1
        assert reader.decoded_attrs(f.attrs) == {"title": "two words", "count": 3}
        assert [reader.decode(v) for v in f["names"][()]] == ["fault A", "B"]


# ------------------------------------------------------------------ codings


def test_codings_are_inverse_pairs():
    assert reader.STATE_NAMES == {0: "free", 1: "stick", 2: "slip", 3: "open"}
    assert reader.CONDITION_NAMES == {1: "traction", 2: "displacement", 3: "mixed_us_sn",
                                        4: "mixed_ss_un", 5: "contact", 6: "prescribed_dd",
                                        7: "rate_state"}
    for names, codes in ((reader.STATE_NAMES, reader.STATE_CODES),
                         (reader.CONDITION_NAMES, reader.CONDITION_CODES)):
        assert {code: name for name, code in codes.items()} == names


def test_twodd2nml_kode_is_the_condition_code():
    # twodd2nml keeps its own table (it runs without numpy and h5py): the same names.
    kodes = twodd2nml.CONDITIONS
    assert kodes == {code: reader.CONDITION_NAMES[code] for code in (1, 2, 3, 4)}


def test_parse_coding_takes_the_first_word_after_each_code():
    text = b"0 free (TWODD-style condition), 1 stick, 2 slip, 3 open"
    assert reader.parse_coding(text) == reader.STATE_NAMES


MIXED_MODEL = """\
&model youngs_modulus = 50000.0, poissons_ratio = 0.25 /
&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /
&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = 6, mu = 0.6, sf = 1.0 /
&fracture name = 'crack', x = -0.2, 0.2, y = 0.5, 0.5, elements = 4,
          condition = 'traction', bc_n = 10.0 /
&grid name = 'map', xmin = -1, xmax = 1, nx = 3, ymin = 0.2, ymax = 0.8, ny = 2 /
"""


@pytest.fixture(scope="module")
def solved_file(tmp_path_factory):
    """A small model solved by ddc2d: a contact fault and a traction crack."""
    return solve_text(tmp_path_factory.mktemp("solved"), "mixed", MIXED_MODEL)


def test_codings_match_what_ddc2d_writes(solved_file):
    with h5py.File(solved_file, "r") as f:
        state = f["elements/state"]
        condition = f["elements/condition"]
        assert reader.parse_coding(state.attrs["coding"]) == reader.STATE_NAMES
        # A model without rate-and-state elements is written as before they existed.
        assert reader.parse_coding(condition.attrs["coding"]) == {
            code: name for code, name in reader.CONDITION_NAMES.items() if name != "rate_state"}
        codes = reader.CONDITION_CODES
        assert list(condition[()]) == [codes["contact"]] * 6 + [codes["traction"]] * 4
        assert list(state[6:]) == [reader.STATE_CODES["free"]] * 4


# ------------------------------------------------------------------ reading a result


def test_load_result_of_a_solved_model(solved_file):
    result = reader.load_result(solved_file)
    assert result["complete"] is True
    assert (result["length_unit"], result["stress_unit"]) == ("m", "MPa")
    assert [(f["name"], f["first"], f["last"]) for f in result["fractures"]] == [
        ("fault", 1, 6), ("crack", 7, 10)]
    assert result["remote_stress"] == (-143.75, -81.25, 54.13)  # the input, copied
    assert result["fields"]["map"]["kind"] == "grid"
    assert result["fields"]["map"]["x"].shape == (2, 3)
    assert result["tips"]["k_unit"] == "MPa m^0.5"
    assert result["tips"]["x"].size == 4
    assert result["history"] is None
    with h5py.File(solved_file, "r") as f:
        assert reader.units_of(f["elements/ds"]) == "m"
        assert reader.is_complete(f.attrs)
        assert reader.read_sweep(f) is None
        solver = reader.read_solver(f)
        assert set(solver["seconds"]) == set(reader.SOLVER_PHASES)
        assert solver["attrs"]["method"] == "lemke"


def test_sweep_task_group(tmp_path):
    model = tmp_path / "sweep.nml"
    model.write_text(MIXED_MODEL + "&sweep parameters = 'mu', 'sxy', values_1 = 0.2, 0.6, "
                     "values_2 = 40, 50 /\n")
    done = subprocess.run([str(ddc2d_exe()), str(model), "--task", "3", "-o",
                           str(tmp_path / "s.h5")], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "s_task0003.h5", "r") as f:
        # The swept values are the input's decimals, stored unchanged: exact.
        assert reader.read_sweep(f) == {"task": 3, "tasks": 4,
                                          "parameters": {"mu": 0.6, "sxy": 50.0}}


def test_is_complete_reads_the_flag_written_last(tmp_path):
    path = write_result(tmp_path / "r.h5")
    with h5py.File(path, "a") as f:
        assert reader.is_complete(f.attrs)
        f.attrs["complete"] = np.int32(0)
        assert not reader.is_complete(f.attrs)
        del f.attrs["complete"]
        assert not reader.is_complete(f.attrs)
        assert reader.is_complete(f.attrs, when_missing=True)
    assert reader.load_result(path)["complete"] is True  # plots files without the flag


# ------------------------------------------------------------------ what is not a result


def test_missing_file_and_folder(tmp_path):
    with pytest.raises(reader.ResultError, match="no such file"):
        reader.load_result(tmp_path / "absent.h5")
    with pytest.raises(reader.ResultError, match="it is a folder"):
        reader.load_result(tmp_path)


def test_text_file_is_not_hdf5(tmp_path):
    (tmp_path / "notes.h5").write_text("not an HDF5 file\n")
    with pytest.raises(reader.ResultError, match="not a readable HDF5 file"):
        reader.load_result(tmp_path / "notes.h5")


def test_hdf5_file_of_another_program_is_refused(tmp_path):
    with h5py.File(tmp_path / "other.h5", "w") as f:
        f.create_dataset("data", data=np.arange(3.0))
    with pytest.raises(reader.ResultError, match="has no /elements group: not a ddc2d"):
        reader.load_result(tmp_path / "other.h5")
    with h5py.File(tmp_path / "other.h5", "a") as f:
        f.create_group("elements").create_dataset("ds", data=np.zeros(2))
    with pytest.raises(reader.ResultError, match="lacks /elements/x_begin"):
        reader.load_result(tmp_path / "other.h5")


def test_elements_of_different_lengths_are_refused(tmp_path):
    path = write_result(tmp_path / "r.h5")
    with h5py.File(path, "a") as f:
        del f["elements/dn"]
        f["elements"].create_dataset("dn", data=np.zeros(3))
    with pytest.raises(reader.ResultError, match="/elements/dn has 3 values"):
        reader.load_result(path)


# ------------------------------------------------------------------ the tie rule


@pytest.mark.parametrize("kind, values, expected", [
    ("max", [1.0, 3.0, 3.0, 1.0], 1),  # symmetric: an exact tie
    ("min", [3.0, 1.0, 2.0, 1.0, 3.0], 1),
    ("max", [-2.0, -1.0, -1.0], 1),  # negative extremes
    ("min", [0.0, 5.0, 0.0], 0),  # a zero extreme ties with exact zeros only
    ("max", [0.0, 0.0], 0),
])
def test_exact_ties_give_the_lowest_index(kind, values, expected):
    assert reader.index_of_extreme(values, kind) == expected


@pytest.mark.parametrize("kind, sign", [("max", 1.0), ("min", -1.0)])
def test_near_ties_within_1e_9_give_the_lowest_index(kind, sign):
    # The later value is the extreme by a relative 1e-10 (or 5e-10): still a tie.
    for relative in (1e-10, 5e-10):
        values = sign * np.array([1.0, 3.0, 3.0 * (1.0 + relative), 1.0])
        assert reader.index_of_extreme(values, kind) == 1, relative
    # Beyond the tolerance (a relative 2e-9) the later value is the extreme.
    values = sign * np.array([1.0, 3.0, 3.0 * (1.0 + 2e-9), 1.0])
    assert reader.index_of_extreme(values, kind) == 2


def test_rtol_is_a_parameter():
    values = [1.0, 1.0 + 1e-6]
    assert reader.index_of_extreme(values) == 1
    assert reader.index_of_extreme(values, rtol=1e-5) == 0
    assert reader.index_of_extreme(values, rtol=0.0) == 1
    assert reader.index_of_extreme([2.0, 2.0], rtol=0.0) == 0


def test_nan_is_ignored_and_infinity_ties_only_with_itself():
    assert reader.index_of_extreme([np.nan, 2.0, 2.0]) == 1
    assert reader.index_of_extreme([np.nan, 2.0, np.nan, 1.0], "min") == 3
    assert reader.index_of_extreme([1e300, np.inf, np.inf]) == 1
    assert reader.index_of_extreme([-np.inf, -1e300], "min") == 0
    with pytest.raises(ValueError, match="no value that is not NaN"):
        reader.index_of_extreme([np.nan, np.nan])
    with pytest.raises(ValueError, match="no value that is not NaN"):
        reader.index_of_extreme([])
    with pytest.raises(ValueError, match="kind"):
        reader.index_of_extreme([1.0], "largest")


def test_two_dimensional_values_give_the_flat_index():
    grid = np.array([[1.0, 4.0], [4.0, 1.0]])
    assert reader.index_of_extreme(grid) == 1
    assert np.unravel_index(reader.index_of_extreme(grid, "min"), grid.shape) == (0, 0)


def test_is_tie():
    assert reader.is_tie(3.0, 3.0)
    assert reader.is_tie(3.0, 3.0 * (1.0 + 1e-10))
    assert not reader.is_tie(3.0, 3.0 * (1.0 + 2e-9))
    assert reader.is_tie(0.0, 0.0) and not reader.is_tie(0.0, 1e-300)
    assert reader.is_tie(1e-12, 0.0, scale=100.0)  # zero relative to the data's scale
    assert not reader.is_tie(1e-6, 0.0, scale=100.0)
