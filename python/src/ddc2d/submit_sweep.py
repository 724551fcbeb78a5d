"""Submit a ddc2d parameter sweep to Slurm as a job array.

    submit-sweep SWEEP.nml [--max-parallel K] [--cpus-per-task C] [--exe PATH]
                 [--output-dir DIR] [--dry-run] [sbatch options...]

Asks ``ddc2d SWEEP.nml --list`` for the number of tasks N, writes the array script
``DIR/<stem>.sbatch`` (array 0..N-1, at most K tasks at once, C cores per task) and submits
it with ``sbatch --parsable``; prints the job id. Every other option is for sbatch (e.g.
``--partition=long --time=00:10:00`` or ``-t 10``) and is written into the script as an
``#SBATCH`` line, so that the script of a --dry-run is complete and can be submitted later
with a plain ``sbatch DIR/<stem>.sbatch``. Task K writes ``DIR/<stem>_task<K>.h5`` (the id
zero-padded); its Slurm log goes to ``DIR/logs/<stem>_<job>_<K>.out``.

Each task runs with OMP_NUM_THREADS and OPENBLAS_NUM_THREADS both set to the task's
cores (SLURM_CPUS_PER_TASK): ddc2d never runs OpenMP loops and BLAS calls at the same time,
so the two do not multiply and the task uses exactly its cores.

Restarting is safe: a task whose complete output exists is skipped, so after a partial
array (cancelled, failed or timed-out tasks) submitting the same sweep again only runs the
missing tasks. --dry-run writes the script and prints its path without submitting.

A task is one whole run: ddc2d writes its result when it ends, and sweep tasks cannot be
resumed. A single long model (growth, a loading history) that would outlast the time limit
is run in parts chained with Slurm dependencies instead, each part resuming from the result
of the one before (``ddc2d MODEL.nml --resume OUT.h5``; the parts differ only in ``&growth
steps`` or in the legs added to ``&load_path``):

    jid=$(sbatch --parsable -t 04:00:00 --wrap "ddc2d part1.nml -o run.h5")
    sbatch -t 04:00:00 --dependency=afterok:$jid --wrap "ddc2d part2.nml --resume run.h5 -o run.h5"
"""

import argparse
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from .files import write_text_atomically
from .paths import built_executable


def find_exe(given):
    """The ddc2d executable: --exe, else ddc2d on PATH, else a build of the working tree."""
    if given:
        return Path(given).resolve()
    on_path = shutil.which("ddc2d")
    if on_path:
        return Path(on_path).resolve()
    exe = built_executable()
    if exe is None:
        sys.exit("submit-sweep: no ddc2d found: give --exe PATH")
    return exe


def count_tasks(exe, sweep):
    """N from the first line of `ddc2d SWEEP --list`; exits with ddc2d's status on error."""
    done = subprocess.run([str(exe), str(sweep), "--list"], capture_output=True, text=True)
    if done.returncode != 0:
        sys.stderr.write(done.stderr)
        sys.exit(done.returncode)
    first = done.stdout.splitlines()[0] if done.stdout else ""
    match = re.fullmatch(r"tasks: (\d+)", first.strip())
    if not match:
        sys.exit(f"submit-sweep: unexpected first line from {exe} --list: {first!r}")
    return int(match.group(1))


def sbatch_lines(options):
    """``#SBATCH`` lines of extra sbatch options: each option with the values that follow
    it (``--time 10`` as well as ``--time=10``), one line per option, in the given order."""
    groups = []
    for token in options:
        if token.startswith("-") or not groups:
            groups.append([token])
        else:
            groups[-1].append(token)
    return "".join("#SBATCH " + " ".join(shlex.quote(t) for t in group) + "\n"
                   for group in groups)


def array_script(exe, sweep, tasks, output_dir, max_parallel, cpus_per_task, job_name,
                 sbatch_options=()):
    """Text of the sbatch array script; sbatch_options become #SBATCH lines."""
    stem = sweep.stem
    array = f"0-{tasks - 1}" + (f"%{max_parallel}" if max_parallel else "")
    base = output_dir / f"{stem}.h5"
    log = output_dir / "logs" / f"{stem}_%A_%a.out"
    command = " ".join(shlex.quote(str(part)) for part in (exe, sweep, "-o", base))
    extra = sbatch_lines(sbatch_options)
    return f"""#!/bin/bash
#SBATCH --job-name={job_name}
#SBATCH --array={array}
#SBATCH --cpus-per-task={cpus_per_task}
#SBATCH --output={log}
{extra}# Written by scripts/submit-sweep: task $SLURM_ARRAY_TASK_ID of the {tasks}-task sweep
# {sweep}. A task whose complete output exists is skipped, so resubmitting is safe.
set -u
# OpenMP loops and BLAS calls never overlap in ddc2d: both get the task's cores.
threads="${{SLURM_CPUS_PER_TASK:-1}}"
export OMP_NUM_THREADS="$threads"
export OPENBLAS_NUM_THREADS="$threads"
export MKL_NUM_THREADS="$threads"
exec {command} --task "$SLURM_ARRAY_TASK_ID"
"""


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Submit a ddc2d parameter sweep to Slurm as a job array; other "
        "options are passed to sbatch.")
    parser.add_argument("sweep", help="namelist file with a &sweep group")
    parser.add_argument("--max-parallel", type=int, metavar="K",
                        help="run at most K tasks at once (array ...%%K)")
    parser.add_argument("--cpus-per-task", type=int, default=1, metavar="C",
                        help="cores per task (default 1); sets the thread counts")
    parser.add_argument("--exe", help="ddc2d executable (default: ddc2d on PATH or a "
                        "build of this repository)")
    parser.add_argument("--output-dir", metavar="DIR",
                        help="folder of the outputs (default: ./<stem>_sweep)")
    parser.add_argument("--job-name", help="Slurm job name (default: the sweep's stem)")
    parser.add_argument("--dry-run", action="store_true",
                        help="write the script and print its path; do not submit")
    args, sbatch_options = parser.parse_known_args(argv)

    sweep = Path(args.sweep).resolve()
    if not sweep.is_file():
        parser.error(f"no such sweep file: {args.sweep}")
    if args.max_parallel is not None and args.max_parallel < 1:
        parser.error("--max-parallel must be at least 1")
    if args.cpus_per_task < 1:
        parser.error("--cpus-per-task must be at least 1")
    exe = find_exe(args.exe)
    tasks = count_tasks(exe, sweep)
    output_dir = Path(args.output_dir or f"{sweep.stem}_sweep").resolve()
    (output_dir / "logs").mkdir(parents=True, exist_ok=True)
    script = output_dir / f"{sweep.stem}.sbatch"
    write_text_atomically(script, array_script(exe, sweep, tasks, output_dir,
                                               args.max_parallel, args.cpus_per_task,
                                               args.job_name or sweep.stem, sbatch_options))
    script.chmod(0o755)
    if args.dry_run:
        print(script)
        return 0
    done = subprocess.run(["sbatch", "--parsable", str(script)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.stderr.write(done.stderr)
        sys.exit(f"submit-sweep: sbatch failed (exit status {done.returncode})")
    job_id = done.stdout.strip().split(";")[0]
    print(job_id)
    return 0


if __name__ == "__main__":
    sys.exit(main())
