"""The table tool of the verification suite (ddc2d.verification, ddc2d-verification-table;
docs/verification.md): rows made and written, the page written below its marker, and the
check that fails on every kind of difference and not on digits beyond the table's."""

import json
import subprocess
import sys

import pytest

from conftest import SCRIPTS
from ddc2d import verification

HEAD = "# Verification\n\nText above the table.\n\n" + verification.TABLE_MARKER + "\n"


def sample_rows():
    return [verification.make_row(id="a-k", benchmark="crack | one", reference="K = s",
                                  quantity="K", value=1.004, reference_value=1.0,
                                  tolerance=1e-2, mesh="100 elements", order=0.99),
            verification.make_row(id="b-angle", benchmark="wing", reference="70.53",
                                  quantity="angle", value=70.6, reference_value=70.53,
                                  tolerance=0.1, tolerance_kind="absolute", mesh="80")]


def test_make_row_scores_the_error():
    good, angle = sample_rows()
    assert good["error"] == pytest.approx(4e-3) and good["passed"]
    assert angle["error"] == pytest.approx(0.07) and angle["passed"]
    bad = verification.make_row(id="c", benchmark="b", reference="r", quantity="q", value=1.2,
                                reference_value=1.0, tolerance=0.1, mesh="m")
    assert not bad["passed"]
    with pytest.raises(ValueError, match="tolerance_kind"):
        verification.make_row(id="c", benchmark="b", reference="r", quantity="q", value=1.0,
                              reference_value=1.0, tolerance=0.1, mesh="m",
                              tolerance_kind="percent")


def write_page(tmp_path, rows):
    folder = tmp_path / "rows"
    for row in rows:
        verification.write_row(row, folder)
    page = tmp_path / "verification.md"
    page.write_text(HEAD + "old table\n")
    assert verification.main([str(folder), "-o", str(page)]) == 0
    return folder, page


def test_page_keeps_its_text_and_checks_clean(tmp_path):
    rows = sample_rows()
    folder, page = write_page(tmp_path, rows)
    text = page.read_text()
    assert text.startswith(HEAD) and "old table" not in text
    assert "crack \\| one" in text  # a | in a cell does not split it
    assert verification.load_rows(folder) == sorted(rows, key=lambda r: r["id"])
    assert verification.differences(text, rows) == []
    assert verification.main([str(folder), "-o", str(page), "--check"]) == 0


def changed(rows, index, **values):
    rows = [dict(r) for r in rows]
    rows[index].update(values)
    return rows


@pytest.mark.parametrize(("change", "expected"), [
    ({"value": 1.006}, "ddc2d 1.004"),
    ({"reference_value": 1.01}, "reference value"),
    ({"error": 6e-3}, "error"),
    ({"order": 1.5}, "observed order"),
    ({"order": None}, "observed order"),
    ({"passed": False}, "the table says pass"),
])
def test_check_finds_each_difference(tmp_path, change, expected):
    rows = sample_rows()
    _, page = write_page(tmp_path, rows)
    found = verification.differences(page.read_text(), changed(rows, 0, **change))
    assert len(found) == 1 and expected in found[0], found


def test_check_finds_missing_and_extra_rows(tmp_path):
    rows = sample_rows()
    _, page = write_page(tmp_path, rows)
    text = page.read_text()
    assert verification.differences(text, rows[:1]) == [
        "b-angle: in the table, but no test wrote this row"]
    extra = verification.make_row(id="c-new", benchmark="b", reference="r", quantity="q",
                                  value=1.0, reference_value=1.0, tolerance=0.1, mesh="m")
    assert verification.differences(text, [*rows, extra]) == [
        "c-new: a row the table does not have"]


def test_check_ignores_digits_below_the_table(tmp_path):
    """Another CPU's last digits: the value 1e-7 relative away, an error of round-off."""
    rows = sample_rows()
    _, page = write_page(tmp_path, rows)
    near = changed(rows, 0, value=1.004 * (1 + 1e-7), error=4e-3 * (1 + 1e-7))
    near = changed(near, 1, error=0.07 + 1e-9)
    assert verification.differences(page.read_text(), near) == []


def test_command_exit_statuses(tmp_path):
    rows = sample_rows()
    folder, page = write_page(tmp_path, rows)
    verification.write_row(changed(rows, 0, passed=False)[0], folder)
    done = subprocess.run([sys.executable, str(SCRIPTS / "verification-table"), str(folder),
                           "-o", str(page), "--check"], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 1
    assert "a-k: the table says pass" in done.stderr
    assert "regenerate the table with ddc2d-verification-table" in done.stderr
    (folder / "broken.json").write_text(json.dumps({"id": "x"}))
    done = subprocess.run([sys.executable, str(SCRIPTS / "verification-table"), str(folder),
                           "-o", str(page)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "not a verification row" in done.stderr
    empty = tmp_path / "none"
    empty.mkdir()
    assert verification.main([str(empty), "-o", str(page)]) == 2
    (folder / "broken.json").unlink()
    unmarked = tmp_path / "plain.md"
    unmarked.write_text("# no marker\n")
    assert verification.main([str(folder), "-o", str(unmarked)]) == 2
    assert unmarked.read_text() == "# no marker\n"
