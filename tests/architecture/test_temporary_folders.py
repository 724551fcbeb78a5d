"""tests/temporary_folders.py fails when a test leaves something in its temporary folder,
and only then (CTest architecture_checks)."""

import temporary_folders


def test_empty_folders_pass_and_are_removed(tmp_path, capsys):
    root = tmp_path / "tmp"
    assert temporary_folders.main(["", "create", str(root), "crack", "python_cli"]) == 0
    assert sorted(p.name for p in root.iterdir()) == ["crack", "python_cli"]
    (root / "python_cli" / "pytest-of-someone").mkdir()  # pytest's root, emptied by pytest
    assert temporary_folders.main(["", "check", str(root)]) == 0
    assert not root.exists()
    assert "every test removed what it wrote" in capsys.readouterr().out


def test_what_a_test_left_fails_and_is_named(tmp_path, capsys):
    root = tmp_path / "tmp"
    temporary_folders.main(["", "create", str(root), "crack", "python_cli", "sweep"])
    (root / "sweep" / "ddc2d_test_sweep_a.nml").write_text("&model /")
    (root / "python_cli" / "pytest-of-someone" / "pytest-0").mkdir(parents=True)
    assert temporary_folders.main(["", "check", str(root)]) == 1
    out = capsys.readouterr().out
    assert "sweep left in its temporary folder" in out and "ddc2d_test_sweep_a.nml" in out
    assert "python_cli left in" in out and "pytest-of-someone/pytest-0" in out
    assert "crack" not in out
    assert sorted(p.name for p in root.iterdir()) == ["python_cli", "sweep"]  # kept to look


def test_a_missing_root_fails(tmp_path):
    assert temporary_folders.main(["", "check", str(tmp_path / "none")]) == 1


def test_a_fresh_create_clears_what_was_left(tmp_path):
    root = tmp_path / "tmp"
    temporary_folders.main(["", "create", str(root), "sweep"])
    (root / "sweep" / "left.h5").write_text("")
    temporary_folders.main(["", "create", str(root), "sweep"])
    assert not any((root / "sweep").iterdir())
