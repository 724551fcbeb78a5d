#!/usr/bin/env python3
"""Every test's temporary folder (tests/CMakeLists.txt): CTest runs each test with TMPDIR
set to a folder of its own in the build tree, ROOT/<test name>, so that what a test and
the programs it starts write through the system's temporary folder (tempfile, mktemp,
pytest's tmp_path, the Fortran suites' ddc_test_temporary) lands there, never in /tmp,
where two suites on one machine would meet.

    temporary_folders.py create ROOT NAME...   the fixture's setup: ROOT holds one new,
                                               empty folder per test
    temporary_folders.py check ROOT            its cleanup, after the last test: each
                                               folder must be empty again

check lists what each test left and exits 1 when one left anything; it removes the empty
folders and keeps the others for a look (the next create clears them). An empty
pytest-of-USER folder counts as empty: pytest keeps that root of its numbered session
folders after it removed the session folder of a passing run (pytest.ini).
"""
import shutil
import sys
from pathlib import Path

#: Entries of a test's folder that check shows at most.
SHOWN = 10


def create(root, names):
    """ROOT new, with an empty folder for each name."""
    shutil.rmtree(root, ignore_errors=True)
    for name in names:
        (root / name).mkdir(parents=True)
    return 0


def left_behind(folder):
    """What is left in a test's folder: every entry below it but empty pytest-of-* roots."""
    return sorted(path.relative_to(folder).as_posix() for path in folder.rglob("*")
                  if not (path.parent == folder and path.name.startswith("pytest-of-")
                          and path.is_dir() and not path.is_symlink()
                          and not any(path.iterdir())))


def check(root):
    """Remove the empty folders under ROOT; report the others. 1 when there is one."""
    if not root.is_dir():
        print(f"temporary_folders: {root} is missing: was the setup test left out?")
        return 1
    failed = False
    for folder in sorted(root.iterdir()):
        left = left_behind(folder)
        if not left:
            shutil.rmtree(folder)
            continue
        failed = True
        print(f"{folder.name} left in its temporary folder {folder}:")
        for entry in left[:SHOWN]:
            print(f"    {entry}")
        if len(left) > SHOWN:
            print(f"    ... and {len(left) - SHOWN} more")
    if not failed:
        root.rmdir()
        print(f"temporary_folders: every test removed what it wrote ({root} removed)")
    return 1 if failed else 0


def main(argv):
    if len(argv) >= 3 and argv[1] == "create":
        return create(Path(argv[2]), argv[3:])
    if len(argv) == 3 and argv[1] == "check":
        return check(Path(argv[2]))
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
