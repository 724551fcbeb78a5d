"""The documentation's runnable command blocks run as written.

A fenced ```bash block in README.md or docs/**/*.md whose line before is exactly
`<!-- runnable -->` is a promise to the reader that the commands work when pasted into a
shell in the repository root with ddc2d on PATH. Each such block runs here, one pytest case
per block (id FILE:LINE, the line of its ```bash fence):

- with `bash -euo pipefail`, so that every command of the block has to succeed;
- in a scratch copy of the repository under tmp_path (input/, scripts/, tests/data,
  tests/reference; build/venv linked in, so that scripts/ that rerun themselves with the
  venv's Python find it), so that no block writes into the checkout;
- with the directory of the executable under test ($DDC2D_EXE, else build/debug: see
  conftest.ddc2d_exe) first on PATH;
- within 60 s per block and 300 s for all blocks together.

A marker that is not followed by a ```bash block fails, and so does documentation without
any runnable block (this file cannot pass by finding nothing).
"""

import os
import shutil
import signal
import subprocess
import time
from pathlib import Path

import pytest

from conftest import REPO_ROOT, ddc2d_exe

MARKER = "<!-- runnable -->"
BLOCK_SECONDS = 60.0
TOTAL_SECONDS = 300.0
# What a block may use, copied into the scratch repository (relative to the root).
COPIED = ("input", "scripts", "tests/data", "tests/reference")
VENV = Path("build") / "venv"
OUTPUT_SHOWN = 6000  # characters of a failed block's output in the message


def doc_files():
    """README.md and every Markdown file under docs/, in a fixed order."""
    return [REPO_ROOT / "README.md"] + sorted((REPO_ROOT / "docs").rglob("*.md"))


def scan(path):
    """The runnable blocks of one Markdown file and its misplaced markers.

    Returns (blocks, problems): blocks is a list of (line, text) with the 1-based line of
    the ```bash fence and the block's text; problems a list of 'FILE:LINE: why' strings. A
    marker line inside a fenced block (an example of the convention) does not count.
    """
    name = path.relative_to(REPO_ROOT).as_posix()
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks, problems = [], []
    fence = None  # the opening fence's backticks while inside a fenced block
    i = 0
    while i < len(lines):
        stripped = lines[i].strip()
        if fence is not None:
            if stripped.startswith(fence) and stripped.strip("`") == "":
                fence = None
            i += 1
            continue
        if stripped.startswith("```"):
            fence = "`" * (len(stripped) - len(stripped.lstrip("`")))
            i += 1
            continue
        if stripped != MARKER:
            i += 1
            continue
        opening = lines[i + 1] if i + 1 < len(lines) else ""
        if opening.rstrip() != "```bash":
            problems.append(f"{name}:{i + 1}: {MARKER} not directly followed by a ```bash "
                            f"line (next line: {opening!r})")
            i += 1
            continue
        body = []
        j = i + 2
        while j < len(lines) and lines[j].rstrip() != "```":
            body.append(lines[j])
            j += 1
        if j == len(lines):
            problems.append(f"{name}:{i + 2}: runnable ```bash block never closed")
            break
        if not any(line.strip() and not line.lstrip().startswith("#") for line in body):
            problems.append(f"{name}:{i + 2}: runnable ```bash block without a command")
        else:
            blocks.append((i + 2, "\n".join(body) + "\n"))
        i = j + 1
    return blocks, problems


def collect():
    blocks, problems = [], []
    for path in doc_files():
        found, wrong = scan(path)
        name = path.relative_to(REPO_ROOT).as_posix()
        blocks += [(f"{name}:{line}", text) for line, text in found]
        problems += wrong
    return blocks, problems


BLOCKS, PROBLEMS = collect()
_spent = [0.0]  # seconds the blocks of this session have taken


def scratch_repository(root):
    """A copy of what the blocks use under `root`, with build/venv linked in."""
    for part in COPIED:
        source = REPO_ROOT / part
        if source.is_dir():
            shutil.copytree(source, root / part, symlinks=True)
    venv = REPO_ROOT / VENV
    if venv.is_dir():
        (root / VENV).parent.mkdir(parents=True, exist_ok=True)
        (root / VENV).symlink_to(venv, target_is_directory=True)
    return root


def run_block(script, cwd, env, timeout):
    """Run `script` with bash -euo pipefail; returns (status, output, seconds). Status is
    None when the block ran past `timeout` (its whole process group is killed then)."""
    start = time.monotonic()
    with subprocess.Popen(["bash", "-euo", "pipefail", str(script)], cwd=cwd, env=env,
                          stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True,
                          start_new_session=True) as process:
        try:
            output, _ = process.communicate(timeout=timeout)
            status = process.returncode
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            output, _ = process.communicate()
            status = None
    return status, output, time.monotonic() - start


def test_there_are_runnable_blocks():
    assert BLOCKS, f"no {MARKER} ```bash block in README.md or docs/**/*.md"


def test_every_marker_opens_a_bash_block():
    assert not PROBLEMS, "\n".join(PROBLEMS)


@pytest.mark.parametrize("where,text", BLOCKS, ids=[where for where, _ in BLOCKS])
def test_runnable_block(where, text, tmp_path):
    left = TOTAL_SECONDS - _spent[0]
    if left <= 0:
        pytest.fail(f"{where}: not run, the runnable blocks took their {TOTAL_SECONDS:.0f} s "
                    f"in all already")
    timeout = min(BLOCK_SECONDS, left)
    repo = scratch_repository(tmp_path / "repo")
    script = tmp_path / "block.sh"
    script.write_text(text)
    env = dict(os.environ)
    env["PATH"] = f"{ddc2d_exe().parent}{os.pathsep}{env.get('PATH', '')}"
    env["MPLBACKEND"] = "Agg"
    status, output, seconds = run_block(script, repo, env, timeout)
    _spent[0] += seconds
    if len(output) > OUTPUT_SHOWN:
        output = f"[... {len(output) - OUTPUT_SHOWN} characters]\n" + output[-OUTPUT_SHOWN:]
    outcome = (f"ran past {timeout:.0f} s" if status is None
               else f"exit status {status} after {seconds:.1f} s")
    assert status == 0, (f"{where}: the runnable block failed ({outcome}).\n"
                         f"--- block (bash -euo pipefail, in a copy of the repository) ---\n"
                         f"{text}--- output ---\n{output}")
