"""Run the ddc2d program from Python: ``ddc2d.run(input, output=..., executable=...)``.

The program is the one given, else $DDC2D_EXE, else ``ddc2d`` on PATH, else one installed
beside this package (the bin/ of this Python environment's prefix, then of $DDC2D_ROOT),
else a build of the working tree (ddc2d.paths.find_executable). A failed run raises
RunError with the program's error lines and its exit status (docs/troubleshooting.md: 1 no
solution, 2 bad input or usage, 3 an output problem, 4 an internal error).
"""

import os
import subprocess
from collections.abc import Sequence
from pathlib import Path

from .model import Model
from .paths import find_executable, not_found_message
from .reader import FilePath
from .result import Result, open_result

#: Output of a run of a Model when none is given: in the current folder.
DEFAULT_MODEL_OUTPUT = "model.h5"


class RunError(Exception):
    """A run of ddc2d that failed: the message is the program's error line(s);
    ``exit_code`` its exit status, ``stdout`` and ``stderr`` all it printed."""

    def __init__(self, message: str, exit_code: int, stdout: str = "", stderr: str = ""
                 ) -> None:
        super().__init__(message)
        self.exit_code = exit_code
        self.stdout = stdout
        self.stderr = stderr


def run(input: FilePath | Model, output: FilePath | None = None,
        executable: FilePath | None = None, threads: int | None = None,
        options: Sequence[object] = (), timeout: float | None = None) -> Result:
    """Solve `input`, a namelist file or a ddc2d.Model, and return its ddc2d.Result.

    output: the result file (default: for a file, its name with .h5 in the current
    folder, as the program does; for a Model, model.h5 there); a Model is written beside
    it as <output stem>.nml. executable: the ddc2d program (see the module). threads:
    OpenMP and BLAS threads (default: as the environment says). options: more command-line
    options (e.g. ['--res', 'tables.txt']). timeout: seconds (subprocess.TimeoutExpired).
    Raises RunError when the program fails, FileNotFoundError when there is none."""
    exe = find_executable(executable)
    if exe is None or not exe.is_file():
        raise FileNotFoundError(not_found_message(exe))
    if isinstance(input, Model):
        output = Path(output or DEFAULT_MODEL_OUTPUT).resolve()
        namelist = input.write(output.with_suffix(".nml"))
    else:
        namelist = Path(input)
        output = Path(output or Path(namelist.name).with_suffix(".h5")).resolve()
    env = dict(os.environ)
    if threads is not None:
        env["OMP_NUM_THREADS"] = env["OPENBLAS_NUM_THREADS"] = str(threads)
    done = subprocess.run([str(exe), str(namelist), "-o", str(output), *map(str, options)],
                          capture_output=True, text=True, env=env, timeout=timeout)
    if done.returncode != 0:
        lines = (done.stderr.strip() or done.stdout.strip()
                 or f"ddc2d ended with exit status {done.returncode}")
        raise RunError(lines, done.returncode, done.stdout, done.stderr)
    return open_result(output)
