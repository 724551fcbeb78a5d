"""ddc2d-converge: how far a model's results are from the converged ones
(docs/error-estimates.md). In the repository also scripts/converge.py.

    ddc2d-converge MODEL.nml [--levels N] [--refine elements,increment,steps]
                   [--tolerance T] [-o DIR] [--exe DDC2D] [--threads T]
                   [--slurm [sbatch options...]] [--collect]

Runs the model at its own resolution and refined N - 1 times (default 3 levels; each
level halves every element, the growth increment and element length, and the load steps,
the time steps of a path with a time axis too), prints the table of the quantities with
their observed order, extrapolated value, error estimate and verdict, and writes the
levels, STUDY.json and convergence.png into DIR (default <model stem>_converge/ in the
current folder).

--slurm writes the levels and submits them as a Slurm job array (other options go to
sbatch as #SBATCH lines, as with submit-sweep) and prints the job id; once it has
finished, the same command with --collect instead gathers the results.

Exit status: 0 the study is done (whatever its verdicts), 1 a level's run failed, 2 bad
arguments, a model that cannot be refined or one that ddc2d refuses (its message printed).
"""

import argparse
import shlex
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

from ..files import write_text_atomically
from ..run import RunError
from ..submit_sweep import find_exe, sbatch_lines
from . import namelist
from .report import FIGURE_FILE, draw_figure, table
from .study import STUDY_FILE, collect, default_out_dir, run_levels, write_levels, write_study


def parse_refine(text):
    return tuple(part.strip() for part in text.split(",") if part.strip())


def array_script(exe, namelists, out_dir, job_name, sbatch_options):
    """The sbatch script running level $SLURM_ARRAY_TASK_ID of the study."""
    stem = namelists[0].name.removesuffix("_level0.nml")
    level = shlex.quote(str(out_dir / stem)) + '_level"$SLURM_ARRAY_TASK_ID"'
    log = out_dir / "logs" / f"{stem}_%A_%a.out"
    extra = sbatch_lines(sbatch_options)
    return f"""#!/bin/bash
#SBATCH --job-name={job_name}
#SBATCH --array=0-{len(namelists) - 1}
#SBATCH --output={log}
{extra}# Written by ddc2d-converge: level $SLURM_ARRAY_TASK_ID of the study of {stem}.
set -u
threads="${{SLURM_CPUS_PER_TASK:-1}}"
export OMP_NUM_THREADS="$threads" OPENBLAS_NUM_THREADS="$threads" MKL_NUM_THREADS="$threads"
exec {shlex.quote(str(exe))} {level}.nml -o {level}.h5
"""


def submit(exe, namelists, out_dir, sbatch_options):
    """Write and submit the array; returns the job id (raises RuntimeError)."""
    (out_dir / "logs").mkdir(parents=True, exist_ok=True)
    script = out_dir / "levels.sbatch"
    write_text_atomically(script, array_script(exe, namelists, out_dir, "converge",
                                               sbatch_options))
    done = subprocess.run(["sbatch", "--parsable", str(script)], capture_output=True,
                          text=True)
    if done.returncode != 0:
        raise RuntimeError(f"sbatch failed (exit status {done.returncode}): "
                           f"{done.stderr.strip()}")
    return done.stdout.strip().split(";")[0]


def parser():
    # No abbreviations: options it does not know go to sbatch whole.
    p = argparse.ArgumentParser(prog="ddc2d-converge", allow_abbrev=False,
                                description=__doc__.split("\n\n")[0])
    p.add_argument("model", type=Path, help="the namelist model")
    p.add_argument("--levels", type=int, default=3, help="levels, the model's own "
                   "included (default 3, at least 3)")
    p.add_argument("--refine", type=parse_refine, default=namelist.REFINEMENTS,
                   help="what to refine, among elements,increment,steps (default all)")
    p.add_argument("--tolerance", type=float, default=0.01,
                   help="relative error estimate below which a quantity is converged "
                   "(default 0.01)")
    p.add_argument("-o", "--output-dir", type=Path, default=None, metavar="DIR")
    p.add_argument("--exe", default=None, help="the ddc2d program (default: as ddc2d.run "
                   "finds it)")
    p.add_argument("--threads", type=int, default=None, help="OpenMP and BLAS threads")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--slurm", action="store_true",
                      help="submit the levels as a Slurm array; options left over go to "
                      "sbatch")
    mode.add_argument("--collect", action="store_true",
                      help="gather the levels' results of an earlier --slurm")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    p = parser()
    args, sbatch_options = p.parse_known_args(argv)
    if sbatch_options and not args.slurm:
        p.error(f"unrecognized arguments: {' '.join(sbatch_options)}")
    if not args.model.is_file():
        p.error(f"no such model file: {args.model}")
    if not args.tolerance > 0.0:
        p.error("--tolerance must be above 0")
    out_dir = args.output_dir or default_out_dir(args.model)
    try:
        namelists, used = write_levels(args.model, args.levels, args.refine, out_dir)
    except (namelist.RefineError, ValueError) as exc:
        print(f"ddc2d-converge: {args.model}: {exc}", file=sys.stderr)
        return 2
    if args.slurm:
        try:
            job = submit(find_exe(args.exe), namelists, out_dir.resolve(), sbatch_options)
        except RuntimeError as exc:
            print(f"ddc2d-converge: {exc}", file=sys.stderr)
            return 1
        print(job)  # alone on stdout, as submit-sweep prints it, for scripts
        print(f"submitted the {len(namelists)} levels as job {job}; when it has finished: "
              f"ddc2d-converge {args.model} --levels {args.levels} -o {out_dir} --collect",
              file=sys.stderr)
        return 0
    outputs = [path.with_suffix(".h5") for path in namelists]
    try:
        if args.collect:
            missing = [str(path) for path in outputs if not path.is_file()]
            if missing:
                raise RunError(f"no result yet: {', '.join(missing)}", 1)
        else:
            run_levels(namelists, args.exe, args.threads, echo=print)
    except (RunError, FileNotFoundError) as exc:
        print(f"ddc2d-converge: {exc}", file=sys.stderr)
        return 2 if getattr(exc, "exit_code", None) == 2 else 1  # 2: ddc2d refused the model
    study = collect(args.model, outputs, used, args.tolerance)
    write_study(study, out_dir)
    draw_figure(study, out_dir)
    print(table(study))
    print(f"wrote {out_dir / STUDY_FILE} and {out_dir / FIGURE_FILE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
