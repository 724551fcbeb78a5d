"""Benchmark ddc2d (docs/performance.md#the-benchmark): the command ddc2d-benchmark, in the
repository also scripts/benchmark.py.

    benchmark.py --exe PATH --sizes 250,500,1000
                 --case straight|mixed|history|fields|growth|growth-work|growth-history|
                        injection|kgd
                 --json FILE [--threads T[,T...]] [--lcp-method auto|lemke|newton] [--grid NX]
                 [--steps K] [--compare-lemke] [--lu-exe PATH] [--workdir DIR]
                 [--mpi P [--mpiexec PATH] [--block-size NB]]
                 [--matrix dense|hierarchical [--compare-dense]] [--figure PNG]
    benchmark.py --exe PATH --case bp3 --json FILE [--threads T] [--matrix M] [--years Y]
                 [--cell C] [--tolerance TOL] [--workdir DIR]

For every size N it writes a namelist model with N contact elements, runs ``ddc2d`` on it,
reads the phase times from ``/solver/seconds`` of the HDF5 output (the output phase from
the run summary, as the file is written during that phase), measures the peak resident
memory of the run (``os.wait4``), and times one LAPACK LU (DGETRF) of a 2N x 2N random
matrix with ``ddc2d_lu_benchmark`` (tests/lu_benchmark.f90, linked to the same LAPACK as
ddc2d; by default next to the executable's build: ``<build>/tests/ddc2d_lu_benchmark``).

Cases (CASES: a model builder per case; a new case adds one):
  straight  the paper's fault: (-1, 0)-(1, 0), mu = 0.6, Sf = 1, principal stresses -175 and
            -50 MPa at 30 degrees (every element slips);
  mixed     a kinked fault network (two faults, each with a flat, a 35-degree and a flat
            segment) under fluid pressure on part of it: elements stick, slip and open;
  history   the paper's fault along a loading history of K increments (--steps, default
            100): sxy from 0 to 54.13 MPa (it slips), back to 0 (it sticks) and on to
            -54.13 MPa (it slips back), in legs of about K/3 increments;
  fields    the straight case with a GRID x GRID map (--grid, default 500 for this case;
            0 for history and growth, 100 for the others): the field evaluation, reported
            as ``fields_over_lu``;
  growth    wing cracks off a sliding flaw (docs/theory/growth.md#checks-against-closed-forms):
            a 2 m frictional flaw of N elements at 45 degrees to the compression, each tip
            growing by 20 of its elements per step for K steps (--steps, default 25; toughness
            2 MPa m^1/2, so that it does not arrest before), with the local-symmetry corrector.
            The reference LU is that of the final geometry, LU(2 N_final); the record adds
            ``n_final``, ``growth_steps``, ``solves`` (from the progress lines) and
            ``end_reason``.
  growth-work  the growth case with criterion = 'work' (docs/theory/growth.md#the-work-criterion:
            the seeded search's trial kinks, each solved with contact by updating the kept
            factors, the best refined). Measured against LU(2 N_final)
            and against the growth case's run of the same model (MTS with the corrector),
            run in the same call: the record adds ``mts`` (its seconds, solves, growth steps,
            N_final), ``over_mts`` (total / the MTS run's total; target at most 5) and
            ``solves_per_step``, ``updates_per_step`` (low-rank updates per growth step).
  growth-history  the growth case's flaw along a loading history
            (docs/theory/growth.md#growth-along-a-loading-history): syy rises from -2 to
            -100 MPa in K load steps (--steps, default 20) at sxx = -2 MPa, and at each load
            step the wings grow (20 of the flaw's elements per growth step) until no tip is
            critical. One set of kept factors serves every load step (a new load changes the
            right-hand side, not the matrix). Measured against LU(2 N_final) like the growth
            case; the record adds ``steps`` (load steps) too.
  injection  fluid injection into a fault (docs/injection.md): a 2 m fault of N elements that
            conducts (diffusivity and transmissivity 1e-3), at sxy / syy = 0.45 under mu = 0.6,
            with an overpressure of 5 MPa held at its middle; K steps to 60 s (--steps,
            default 200). One matrix and one set of factors serve every step: a step changes
            the pressures, so the loads, alone. Measured against LU(2 N) like the history case.

  kgd       a KGD hydraulic fracture (docs/fluid-driven-fractures.md#hydraulic-fractures) in
            the toughness regime that ends with N elements after K growth steps (--steps,
            default 100), one element of 0.0125 m per wing and step: every step prepares the
            grown geometry's run and solves for the time at which K_I reaches the toughness,
            each trial a coupled step of flow and contact. Measured against LU(2 N) of the
            final geometry.

The case ``bp3`` is an earthquake-cycle run (docs/earthquake-cycles.md#bp3-qd): the SCEC
SEAS benchmark BP3-QD, thrust at 60 degrees (ddc2d.seas.bp3_namelist; --cell, default 25 m;
--years, default 1500; --tolerance, default 1e-7; --matrix, default hierarchical for this
case), run once. It prints and records the wall time, the run's own seconds, accepted and
rejected steps, products of the elastic operator and the peak memory, the first event and
the last complete cycle of four events (inter-event times from the one of about 63 years,
and the slip at the station 7.5 km down-dip of each event) against the community's numbers
(BP3_COMMUNITY: the FDRA submission, 25 m cells; Erickson et al. 2023), with the relative
differences (the issue's target: within 2 %).

--compare-lemke runs every model a second time with lcp_method = 'lemke' and adds to its
record ``lemke``: Lemke's seconds, peak memory and ratio to the LU, whether the states are
the same, and the largest DD difference relative to the largest DD (of every step for a
history).

Matrices (``--matrix``, default dense; docs/theory/hierarchical.md): every model is run
with &solver matrix set to it. The record adds ``matrix`` and ``compression_ratio`` (the
hierarchical matrix's reals over the dense one's; 1 for dense); ``--compare-dense`` runs
each hierarchical model on the dense matrix too where that fits (else ``None``) and adds
``error_vs_dense``: whether the states are the same and the largest DD difference relative
to the largest DD. Every record holds ``time_exponent``, the exponent of a least-squares
fit of the total time against N over the sizes of the call; ``--figure`` draws total time
and peak memory against N. The reference LU is run only where its matrix (2N)^2 fits in
half of this machine's memory (else its fields are ``None``).

Threads: ``OMP_NUM_THREADS`` and ``OPENBLAS_NUM_THREADS`` are both set to T (default: the
number of CPUs); ddc2d calls BLAS outside its OpenMP regions only, so the two never nest.
``--threads 1,2,4,8,16`` runs every size at each thread count in turn (each with its own
reference LU on as many threads): a table of threads against the time of each phase.

MPI (``--mpi P``, with ``--exe`` the ddc2d of the MPI build): ``mpiexec -n P`` runs the model
on P processes of T threads each (default T: the CPUs divided by P; ``--oversubscribe`` when
P T exceeds the CPUs; Open MPI's variables for running as root are set when root). Each
process is started through this script (``--measure-rank``), which waits for it and records
its own peak resident memory, so that the JSON record holds the peak RSS of every process
(``peak_rss_mb_per_rank``; ``peak_rss_mb`` is the largest) besides ``processes``,
``process_grid`` and ``block_size`` (``--block-size`` sets &solver block_size). The phase
times are the root's. The reference LU runs on P T threads.

The table printed and the JSON records (a list) hold
``{n, case, threads, seconds: {assembly, factorization, lcp, fields, output, total},
lu_reference_seconds, peak_rss_mb}`` and, in addition, the BLAS library and kernel the run
used (``blas``, ``blas_core`` from /solver), the share of the total in no named phase
(``untimed_share``), the memory ddc2d echoed before the solve (``estimated_mb``, from the
Newton method's starting states), the contact method used, any
fallback, Newton iterations, LCP pivots, the Newton method's new factorizations, low-rank
updates and reuses of its factors, element states, the nominal factorization flops and
rates (``factorization_gflops``, ``lu_reference_gflops``), ``total_over_lu``,
``fields_over_lu`` and the wall time of the run; a history adds ``steps`` and
``fallback_steps``, a growth run ``n_final``, ``growth_steps``, ``solves`` and
``end_reason`` (its ``lu_reference_seconds`` is the LU of 2 N_final).
"""

import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

from .reader import SOLVER_PHASES, read_history, read_solver

#: Default grid (GRID x GRID points) of each case
DEFAULT_GRID = {"straight": 100, "mixed": 100, "history": 0, "fields": 500, "growth": 0,
                "growth-work": 0, "growth-history": 0, "injection": 0, "kgd": 0}
#: Default --steps of each case that has steps
DEFAULT_STEPS = {"history": 100, "growth": 25, "growth-work": 25, "growth-history": 20,
                 "injection": 200, "kgd": 100}
#: The growth cases (a record adds the growth summary)
GROWTH_CASES = ("growth", "growth-work", "growth-history")
#: New elements per tip and growth step of the growth case
GROWTH_ELEMENTS = 20
#: BP3-QD thrust 60 (FDRA, 25 m cells; Erickson et al. 2023): the first event's start [yr],
#: the inter-event times of the cycle of four [yr] and the slip of its events at 7.5 km [m]
BP3_COMMUNITY = {"first_event": 177.1, "intervals": (63.3, 87.1, 91.1, 97.5),
                 "slips": (2.33, 2.59, 2.78, 2.97)}


def straight_model(n, grid):
    """The paper's fault with n elements (docs/theory/contact.md#checks-against-closed-forms)."""
    return (
        "&model title = 'benchmark: straight fault', youngs_modulus = 50000.0,\n"
        "       poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /\n"
        "&remote_stress sxx = -143.75, syy = -81.25, sxy = 54.13 /\n"
        f"&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = {n},\n"
        "          condition = 'contact', mu = 0.6, sf = 1.0 /\n" + grid_group(grid))


def split(n, parts):
    """n elements over `parts` segments, as equal as possible (sum is n)."""
    base = [n // parts] * parts
    for k in range(n - sum(base)):
        base[k] += 1
    return base


def mixed_model(n, grid):
    """A kinked fault network: two faults of three segments each (flat, 35 degrees up,
    flat), fluid pressure above the normal compression on the inclined segments, under
    sxx = -5, syy = -20, sxy = 0.5 (the contact suite's kink, doubled and extended)."""
    b = math.radians(35.0)
    counts = split(n, 6)
    faults = []
    for k, (x0, y0) in enumerate(((-1.0, 0.0), (-0.6, -0.9))):
        xs = [x0, x0 + 1.0, x0 + 1.0 + math.cos(b), x0 + 2.0 + math.cos(b)]
        ys = [y0, y0, y0 + math.sin(b), y0 + math.sin(b)]
        c = counts[3 * k:3 * k + 3]
        faults.append(
            f"&fracture name = 'fault_{k + 1}',\n"
            f"          x = {', '.join(f'{v:.12g}' for v in xs)},\n"
            f"          y = {', '.join(f'{v:.12g}' for v in ys)},\n"
            f"          elements = {c[0]}, {c[1]}, {c[2]}, condition = 'contact',\n"
            "          mu = 0.6, 0.6, 0.6, sf = 0.0, 0.0, 0.5,\n"
            "          pressure = 12.0, 17.5, 5.0 /\n")
    return (
        "&model title = 'benchmark: kinked fault network', youngs_modulus = 50000.0,\n"
        "       poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /\n"
        "&remote_stress sxx = -5.0, syy = -20.0, sxy = 0.5 /\n" + "".join(faults)
        + grid_group(grid))


def history_model(n, grid, steps=100):
    """The paper's fault loaded by sxy to 54.13 MPa, unloaded to 0 and loaded the other way
    to -54.13 MPa, in `steps` increments."""
    legs = split(steps, 3)
    return (straight_model(n, grid).replace("sxy = 54.13", "sxy = 0.0")
            + "&load_path sxy = 0.0, 54.13, 0.0, -54.13, "
            f"steps = {legs[0]}, {legs[1]}, {legs[2]} /\n")


def growth_model(n, grid, steps=25):
    """Wing cracks off a sliding flaw (input/wing_cracks_sliding_flaw.nml with n elements):
    each tip grows by GROWTH_ELEMENTS of the flaw's elements per step, `steps` steps."""
    c = math.sqrt(0.5)
    increment = GROWTH_ELEMENTS * 2.0 / n
    return (
        "&model title = 'benchmark: wing cracks off a sliding flaw', youngs_modulus = 50000.0,\n"
        "       poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /\n"
        "&remote_stress sxx = -2.0, syy = -100.0, sxy = 0.0 /\n"
        f"&fracture name = 'flaw', x = {-c:.17g}, {c:.17g}, y = {-c:.17g}, {c:.17g},\n"
        f"          elements = {n}, condition = 'contact', mu = 0.6, sf = 1.0 /\n"
        f"&growth steps = {steps}, toughness = 2.0, new_sf = 0.0,\n"
        f"        increment = {increment:.17g} /\n"
        + grid_group(grid))


def growth_work_model(n, grid, steps=25):
    """The growth case's flaw grown by the work criterion (its default search: the climbs
    from the kinked-crack estimate and straight ahead, every angle_step = 5 degrees)."""
    return growth_model(n, grid, steps).replace("new_sf = 0.0,",
                                                "new_sf = 0.0, criterion = 'work',")


def growth_history_model(n, grid, steps=20):
    """The growth case's flaw with syy rising from -2 to -100 MPa in `steps` load steps;
    the wings grow to arrest at each (at most 100 growth steps per load step)."""
    return (growth_model(n, grid, 100).replace("syy = -100.0", "syy = -2.0")
            + f"&load_path syy = -2.0, -100.0, steps = {steps} /\n")


def injection_model(n, grid, steps=200):
    """A 2 m fault of n elements that conducts, an overpressure of 5 MPa held at its middle
    from time 0 (docs/injection.md), `steps` steps to 60 s: the pressure diffuses about
    0.5 m each way and the slipping patch follows it."""
    return (
        "&model title = 'benchmark: injection into a fault', youngs_modulus = 30000.0,\n"
        "       poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa',\n"
        "       time_unit = 's' /\n"
        "&remote_stress syy = -10.0, sxy = 4.5 /\n"
        f"&fracture name = 'fault', x = -1.0, 1.0, y = 0.0, 0.0, elements = {n},\n"
        "          condition = 'contact', mu = 0.6, sf = 0.0, diffusivity = 1.0e-3,\n"
        "          transmissivity = 1.0e-3 /\n"
        "&injection name = 'well', fracture = 'fault', x = 1.0e-9, y = 0.0,\n"
        "           overpressure = 5.0 /\n"
        f"&load_path time = 0.0, 60.0, steps = {steps} /\n"
        + grid_group(grid))


def kgd_model(n, grid, steps=100):
    """A KGD hydraulic fracture (docs/fluid-driven-fractures.md#hydraulic-fractures) that
    ends with n elements after `steps` growth steps (one element of 0.0125 m per wing and
    step) in the toughness regime: a rate of 1e-4 m^2/s into its middle."""
    start = n - 2 * steps
    if start < 4:
        raise ValueError(f"--case kgd: {n} elements leave {start} at the start of {steps} "
                         "growth steps; give more elements or fewer steps")
    half = 0.5 * 0.0125 * start
    return (
        "&model title = 'benchmark: KGD hydraulic fracture', youngs_modulus = 30000.0,\n"
        "       poissons_ratio = 0.25, length_unit = 'm', stress_unit = 'MPa' /\n"
        "&remote_stress sxx = -1.0, syy = -1.0 /\n"
        f"&fracture name = 'crack', x = {-half!r}, {half!r}, y = 0.0, 0.0, elements = {start},\n"
        "          mu = 0.6, residual_aperture = 1.0e-6 /\n"
        "&fluid viscosity = 1.0e-12, compressibility = 1.0e-4 /\n"
        "&injection name = 'well', fracture = 'crack', x = 0.0, y = 0.0, rate = 1.0e-4 /\n"
        "&load_path time = 0.0, 1.0e4, steps = 1 /\n"
        f"&growth steps = {steps}, toughness = 1.0 /\n"
        + grid_group(grid))


#: The model of each case: n elements, a grid of nx x nx points (0: none), steps.
CASES = {
    "straight": lambda n, grid, steps: straight_model(n, grid),
    "mixed": lambda n, grid, steps: mixed_model(n, grid),
    "history": history_model,
    "fields": lambda n, grid, steps: straight_model(n, grid),
    "growth": growth_model,
    "growth-work": growth_work_model,
    "growth-history": growth_history_model,
    "injection": injection_model,
    "kgd": kgd_model,
}


def grid_group(nx):
    """A nx x nx grid around the faults (none when nx is 0)."""
    if nx <= 0:
        return ""
    return (f"&grid name = 'map', xmin = -2.5, xmax = 2.5, nx = {nx}, "
            f"ymin = -2.0, ymax = 2.0, ny = {nx} /\n")


def solver_group(method, block_size=None, matrix="dense"):
    size = "" if block_size is None else f", block_size = {block_size}"
    return f"&solver lcp_method = '{method}', matrix = '{matrix}'{size} /\n"


def run_measured(command, env):
    """Run a command; return (stdout, wall seconds, peak RSS in MB of that process)."""
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               env=env, text=True)
    stdout = process.stdout.read()
    stderr = process.stderr.read()
    process.stdout.close()
    process.stderr.close()
    # os.wait4 reports the resource usage of this child alone.
    _, status, usage = os.wait4(process.pid, 0)
    process.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - start
    if process.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed with exit status "
                           f"{process.returncode}:\n{stdout}\n{stderr}")
    return stdout, wall, usage.ru_maxrss / 1024.0


def lu_reference(lu_exe, n2, env):
    """Seconds and GFLOP/s of one DGETRF of an n2 x n2 random matrix."""
    out, _, _ = run_measured([str(lu_exe), str(n2)], env)
    match = re.search(r"seconds\s+(\S+)\s+gflops\s+(\S+)", out)
    if not match:
        raise RuntimeError(f"unexpected output of {lu_exe}: {out!r}")
    return float(match.group(1)), float(match.group(2))


RANK_ENVIRONMENT = ("OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID")


def measure_rank(argv):
    """--measure-rank PREFIX -- COMMAND...: run COMMAND (one MPI process), write its peak
    RSS to PREFIX.<rank> as JSON and exit with its status."""
    prefix, separator, *command = argv
    if separator != "--" or not command:
        raise SystemExit("usage: benchmark.py --measure-rank PREFIX -- COMMAND...")
    rank = next((os.environ[v] for v in RANK_ENVIRONMENT if v in os.environ), "0")
    process = subprocess.Popen(command)
    _, status, usage = os.wait4(process.pid, 0)
    Path(f"{prefix}.{rank}").write_text(json.dumps({"rank": int(rank),
                                                    "peak_rss_mb": usage.ru_maxrss / 1024.0}))
    return os.waitstatus_to_exitcode(status)


def mpi_command(mpiexec, processes, threads, prefix):
    """mpiexec -n P with every process started through --measure-rank."""
    command = [mpiexec, "-n", str(processes)]
    if processes * threads > (os.cpu_count() or 1):
        command.insert(1, "--oversubscribe")
    return command + [sys.executable, "-m", "ddc2d.benchmark", "--measure-rank", str(prefix),
                      "--"]


def run_model(exe, text, method, name, workdir, env, launcher=(), block_size=None,
              matrix="dense"):
    """Run one model with a method and matrix (through the MPI launcher when given); return
    (stdout, wall seconds, peak RSS MB, the result file's /solver and /history (None
    without a path), its element states and DDs)."""
    nml = Path(workdir) / f"{name}_{method}_{matrix}.nml"
    h5 = Path(workdir) / f"{name}_{method}_{matrix}.h5"
    nml.write_text(text + solver_group(method, block_size, matrix)
                   + f"&output file = '{h5.name}' /\n")
    stdout, wall, rss = run_measured([*launcher, str(exe), str(nml), "-o", str(h5)], env)
    with h5py.File(h5, "r") as f:
        solver = read_solver(f)
        history = read_history(h5, f, f["elements/ds"].shape[0])
        states = f["elements/state"][()]
        dds = [f["elements/ds"][()], f["elements/dn"][()]]
    h5.unlink()
    if history is not None:
        states = history["state"]
        dds = [history["ds"], history["dn"]]
    return stdout, wall, rss, solver, history, states, dds


#: Units of the sizes ddc2d prints
UNITS = {"kB": 1e3, "MB": 1e6, "GB": 1e9, "TB": 1e12}


def echoed_need_mb(stdout):
    """The memory ddc2d echoed as needed before the solve [MB] (None when not echoed)."""
    match = re.search(r"^  memory: about ([0-9.]+) (kB|MB|GB|TB) needed", stdout, re.MULTILINE)
    return float(match.group(1)) * UNITS[match.group(2)] / 1e6 if match else None


def growth_summary(stdout, label):
    """Steps and solves of a growth run from its progress lines ('growth step 3: ..., 3
    solve(s), ...'; one more solve for the input geometry), its end reason from the
    summary."""
    solves = [int(v) for v in re.findall(r"^growth step \d+: .*?, (\d+) solve\(s\)", stdout,
                                          re.MULTILINE)]
    match = re.search(r"^growth: (\d+) step\(s\) with growth; ended: (\w+)", stdout,
                      re.MULTILINE)
    if not solves or not match:
        raise RuntimeError(f"no growth progress in the output of {label}:\n{stdout}")
    return {"growth_steps": int(match.group(1)), "end_reason": match.group(2),
            "solves": 1 + sum(solves)}


def compare_with_lemke(exe, text, name, workdir, env, lu_seconds, states, dds, launcher=(),
                       block_size=None):
    """Lemke on the same model: its time, memory and ratio to the LU; same states; largest
    DD difference relative to the largest DD."""
    _, _, rss, solver, _, lemke_states, lemke_dds = run_model(
        exe, text, "lemke", name, workdir, env, launcher, block_size)
    scale = max(float(np.max(np.abs(d))) for d in lemke_dds) or 1.0
    total = solver["seconds"]["total"]
    return {"seconds": total, "peak_rss_mb": rss, "total_over_lu": total / lu_seconds,
            "pivots": int(solver["attrs"].get("pivots", 0)),
            "same_states": bool(np.array_equal(states, lemke_states)),
            "max_dd_difference": max(float(np.max(np.abs(a - b)))
                                     for a, b in zip(dds, lemke_dds)) / scale}


def compare_with_mts(exe, n, grid, steps, method, record, workdir, env):
    """The growth case's MTS run of the same model beside a growth-work record: its
    seconds, solves, growth steps and N_final; the work run's time over it, and its solves
    and low-rank updates per growth step."""
    stdout, _, _, solver, _, states, _ = run_model(exe, growth_model(n, grid, steps), method,
                                                   f"growth_{n}_mts", workdir, env)
    mts = growth_summary(stdout, f"growth_{n}_mts")
    match = re.search(r"output\s+([0-9.]+)", stdout)
    seconds = solver["seconds"]["total"]
    if match:
        seconds += float(match.group(1)) - solver["seconds"]["output"]
    steps_taken = max(record["growth_steps"], 1)
    return {"mts": {"seconds": seconds, "solves": mts["solves"],
                    "growth_steps": mts["growth_steps"], "n_final": len(states)},
            "over_mts": record["seconds"]["total"] / seconds if seconds > 0 else None,
            "solves_per_step": record["solves"] / steps_taken,
            "updates_per_step": record["low_rank_updates"] / steps_taken}


def machine_memory_bytes():
    """MemTotal of /proc/meminfo [bytes] (infinite where it cannot be read)."""
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal:"):
                return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return math.inf


def error_vs_dense(exe, text, method, name, workdir, env, states, dds):
    """The same model on the dense matrix: whether the states are the same and the largest
    DD difference relative to the largest DD; None where the dense run does not fit (exit
    status 5)."""
    try:
        _, _, _, _, _, dense_states, dense_dds = run_model(exe, text, method, name, workdir,
                                                           env, matrix="dense")
    except RuntimeError as failure:
        if "exit status 5" in str(failure):
            return None
        raise
    peak = max(float(np.max(np.abs(d))) for d in dense_dds)
    return {"same_states": bool(np.array_equal(states, dense_states)),
            "max_dd_difference": max(float(np.max(np.abs(a - b)))
                                     for a, b in zip(dds, dense_dds)) / peak}


def time_exponent(records):
    """The exponent p of a least-squares fit total seconds ~ c n^p over the records (None
    with fewer than two sizes)."""
    sizes = sorted({r["n"] for r in records})
    if len(sizes) < 2:
        return None
    n = np.log([r["n"] for r in records])
    t = np.log([max(r["seconds"]["total"], 1e-9) for r in records])
    return float(np.polyfit(n, t, 1)[0])


def plot_scaling(records, path):
    """Total time and peak memory against n, log-log, one line per case and matrix."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    for key in sorted({(r["case"], r["matrix"]) for r in records}):
        rows = sorted((r for r in records if (r["case"], r["matrix"]) == key),
                      key=lambda r: r["n"])
        label = f"{key[0]}, {key[1]}"
        left.loglog([r["n"] for r in rows], [r["seconds"]["total"] for r in rows], "o-",
                    label=label)
        right.loglog([r["n"] for r in rows], [r["peak_rss_mb"] / 1e3 for r in rows], "o-",
                     label=label)
    left.set(xlabel="elements N", ylabel="total time [s]")
    right.set(xlabel="elements N", ylabel="peak resident memory [GB]")
    left.legend()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def benchmark_one(exe, lu_exe, n, case, threads, method, grid, workdir, steps=100,
                  compare_lemke=False, processes=0, mpiexec="mpiexec", block_size=None,
                  matrix="dense", compare_dense=False):
    """Run one model of n elements (on `processes` MPI processes when > 0) on the dense or
    the hierarchical matrix; return its JSON record."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads),
               OPENBLAS_NUM_THREADS=str(threads))
    if processes and os.geteuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    text = CASES[case](n, grid, steps)
    name = f"{case}_{n}"
    launcher = []
    prefix = Path(workdir) / f"{name}.rss"
    if processes:
        launcher = mpi_command(mpiexec, processes, threads, prefix)
    stdout, wall, rss, solver, history, states, dds = run_model(
        exe, text, method, name, workdir, env, launcher, block_size, matrix)
    seconds, attrs = solver["seconds"], solver["attrs"]
    # The output phase is timed while the file is written: the file holds its part up to
    # /solver (in its total too); take the whole from the summary.
    match = re.search(r"output\s+([0-9.]+)", stdout)
    if match:
        seconds["total"] += float(match.group(1)) - seconds["output"]
        seconds["output"] = float(match.group(1))
    lu_threads = threads * max(processes, 1)
    # A growth run is measured against the LU of its final geometry.
    n_final = len(states[-1]) if history is not None else len(states)
    # The reference LU only where its matrix fits in half of this machine's memory (a
    # hierarchical run goes far beyond).
    if 8.0 * (2 * n_final) ** 2 <= 0.5 * machine_memory_bytes():
        lu_seconds, lu_gflops = lu_reference(lu_exe, 2 * n_final, dict(
            env, OMP_NUM_THREADS=str(lu_threads), OPENBLAS_NUM_THREADS=str(lu_threads)))
    else:
        lu_seconds, lu_gflops = None, None
    flops = float(attrs.get("factorization_flops", 0.0))
    fact = seconds["factorization"]
    final = states[-1] if history is not None else states
    named = sum(seconds[p] for p in SOLVER_PHASES if p != "total")
    record = {
        "n": n, "case": case, "threads": threads, "seconds": seconds,
        "lu_reference_seconds": lu_seconds, "peak_rss_mb": rss,
        "estimated_mb": echoed_need_mb(stdout),
        "untimed_share": (seconds["total"] - named) / seconds["total"]
        if seconds["total"] > 0 else 0.0,
        "blas": attrs.get("blas", "").strip(), "blas_core": attrs.get("blas_core", "").strip(),
        "lcp_method": method, "method": attrs.get("method", ""),
        "fallback": attrs.get("fallback", ""),
        "newton_iterations": int(attrs.get("newton_iterations", 0)),
        "pivots": int(attrs.get("pivots", 0)),
        "factorizations": int(attrs.get("factorizations", 0)),
        "low_rank_updates": int(attrs.get("low_rank_updates", 0)),
        "factorization_reuses": int(attrs.get("factorization_reuses", 0)),
        "factorization_borderings": int(attrs.get("factorization_borderings", 0)),
        "states": {s: int(np.sum(final == code)) for s, code in (("stick", 1), ("slip", 2),
                                                                 ("open", 3))},
        "factorization_flops": flops,
        "factorization_gflops": flops / fact * 1e-9 if fact > 0 else None,
        "lu_reference_gflops": lu_gflops,
        "total_over_lu": seconds["total"] / lu_seconds if lu_seconds else None,
        "fields_over_lu": seconds["fields"] / lu_seconds if lu_seconds else None,
        "wall_seconds": wall,
        "matrix": attrs.get("matrix", "dense").strip() or "dense",
        "compression_ratio": float(attrs.get("compression_ratio", 1.0)),
    }
    if compare_dense and matrix == "hierarchical":
        record["error_vs_dense"] = error_vs_dense(exe, text, method, name, workdir, env,
                                                  states, dds)
    if processes:
        ranks = sorted((json.loads(f.read_text()) for f in Path(workdir).glob(f"{prefix.name}.*")),
                       key=lambda r: r["rank"])
        if [r["rank"] for r in ranks] != list(range(processes)):
            raise RuntimeError(f"peak RSS of ranks {[r['rank'] for r in ranks]} recorded, "
                               f"expected 0 to {processes - 1}")
        record.update(processes=processes, process_grid=[int(v) for v in attrs["process_grid"]],
                      block_size=int(attrs["block_size"]),
                      peak_rss_mb_per_rank=[r["peak_rss_mb"] for r in ranks],
                      peak_rss_mb=max(r["peak_rss_mb"] for r in ranks))
        for f in Path(workdir).glob(f"{prefix.name}.*"):
            f.unlink()
    if case in GROWTH_CASES:
        record.update(growth_summary(stdout, f"{name}_{method}"), n_final=n_final)
    if case == "growth-work":
        record.update(compare_with_mts(exe, n, grid, steps, method, record, workdir, env))
    if history is not None:
        record["steps"] = int(history["state"].shape[0])
        record["fallback_steps"] = int(sum(1 for f in history.get("fallback", []) if f))
    if compare_lemke:
        record["lemke"] = compare_with_lemke(exe, text, name, workdir, env, lu_seconds,
                                             states, dds, launcher, block_size)
    return record


def bp3_cycle(starts, slips):
    """The last complete cycle of four events: inter-event times from the one nearest
    BP3_COMMUNITY's first (the short one, within 10 %) and the slips of the four events it
    leads to; (None, None) when the record holds no such cycle."""
    intervals = np.diff(starts)
    short = BP3_COMMUNITY["intervals"][0]
    for k in range(len(intervals) - 4, -1, -1):
        if abs(intervals[k] / short - 1.0) < 0.1:
            return [float(v) for v in intervals[k:k + 4]], [float(v) for v in slips[k + 1:k + 5]]
    return None, None


def bp3_benchmark(exe, threads, matrix, years, cell, tolerance, workdir):
    """Run BP3-QD thrust 60 once; its record (docs/earthquake-cycles.md#bp3-qd)."""
    from .seas import YEAR, bp3_namelist
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OPENBLAS_NUM_THREADS=str(threads))
    path = Path(workdir) / "bp3qd_thrust60.nml"
    path.write_text(bp3_namelist(cell=cell, years=years, matrix=matrix, tolerance=tolerance))
    result = path.with_suffix(".h5")
    _, wall, rss = run_measured([str(exe), str(path), "-o", str(result)], env)
    with h5py.File(result, "r") as f:
        cycle = f["cycle"]
        starts = cycle["event_start"][()] / YEAR
        station = int(np.argmin(np.abs(cycle["distance"][()] - 7500.0)))
        slips = cycle["event_slip"][()][:, station] if starts.size else np.zeros(0)
        attrs = dict(cycle.attrs)
        compression = float(f["solver"].attrs.get("compression_ratio", 1.0))
    intervals, cycle_slips = bp3_cycle(starts, slips)
    community = BP3_COMMUNITY
    record = {
        "case": "bp3", "threads": threads, "matrix": matrix, "cell": cell, "years": years,
        "tolerance": tolerance, "wall_seconds": wall, "seconds": float(attrs["seconds"]),
        "steps": int(attrs["steps"]), "rejected_steps": int(attrs["rejected_steps"]),
        "products": int(attrs["products"]), "peak_rss_mb": rss,
        "compression_ratio": compression, "event_starts_yr": [float(v) for v in starts],
        "cycle_intervals_yr": intervals, "cycle_slips_m": cycle_slips,
        "first_event_difference": float(starts[0] / community["first_event"] - 1.0)
        if starts.size else None,
        "interval_differences": None if intervals is None else
        [a / b - 1.0 for a, b in zip(intervals, community["intervals"])],
        "slip_differences": None if cycle_slips is None else
        [a / b - 1.0 for a, b in zip(cycle_slips, community["slips"])],
    }
    return record


def print_bp3(record, out=sys.stdout):
    """The BP3-QD record as text: cost, then the comparison with the community."""
    r = record
    print(f"# ddc2d benchmark, case bp3 (BP3-QD thrust 60), {r['cell']:g} m cells, "
          f"{r['years']:g} years, tolerance {r['tolerance']:g}, matrix {r['matrix']} "
          f"({100 * r['compression_ratio']:.1f} %), {r['threads']} thread(s), "
          f"{time.strftime('%Y-%m-%d')}", file=out)
    print(f"  wall {r['wall_seconds']:.1f} s (run {r['seconds']:.1f} s), {r['steps']} steps "
          f"({r['rejected_steps']} rejected), {r['products']} products, peak "
          f"{r['peak_rss_mb']:.0f} MB", file=out)
    community = BP3_COMMUNITY
    if r["first_event_difference"] is not None:
        print(f"  first event {r['event_starts_yr'][0]:.2f} yr (community "
              f"{community['first_event']}, {100 * r['first_event_difference']:+.2f} %)",
              file=out)
    if r["cycle_intervals_yr"] is None:
        print("  no complete cycle of four events", file=out)
        return
    for name, values, reference, differences, unit in (
            ("inter-event times", r["cycle_intervals_yr"], community["intervals"],
             r["interval_differences"], "yr"),
            ("slips at 7.5 km", r["cycle_slips_m"], community["slips"],
             r["slip_differences"], "m")):
        cells = ", ".join(f"{v:.2f} ({ref}, {100 * d:+.2f} %)"
                          for v, ref, d in zip(values, reference, differences))
        print(f"  {name} [{unit}]: {cells}", file=out)


def optional(value, spec):
    """A table cell: the value formatted, '-' for None."""
    return "-" if value is None else format(value, spec)


def print_table(records, out=sys.stdout):
    """One row per record; with MPI records the processes and each one's peak RSS."""
    mpi = any("processes" in r for r in records)
    head = ("n", "case", *(("P",) if mpi else ()), "thr", "method", "assembly", "factor",
            "lcp", "fields", "output", "total", "untimed", "LU ref", "tot/LU", "fld/LU",
            "fact GF/s", "LU GF/s", "RSS MB", *(("rank RSS MB",) if mpi else ()), "stk/slp/opn",
            "fact/upd/reuse")
    rows = []
    for r in records:
        s = r["seconds"]
        gf = r["factorization_gflops"]
        st = r["states"]
        ranks = "/".join(f"{v:.0f}" for v in r.get("peak_rss_mb_per_rank", []))
        rows.append((str(r["n"]), r["case"], *((str(r.get("processes", 1)),) if mpi else ()),
                     str(r["threads"]), r["method"] + ("*" if r["fallback"] else ""),
                     *(f"{s[p]:.3f}" for p in SOLVER_PHASES),
                     f"{100.0 * r['untimed_share']:.1f}%",
                     optional(r["lu_reference_seconds"], ".3f"),
                     optional(r["total_over_lu"], ".2f"), optional(r["fields_over_lu"], ".2f"),
                     optional(gf, ".1f"), optional(r["lu_reference_gflops"], ".1f"),
                     f"{r['peak_rss_mb']:.0f}",
                     *((ranks or "-",) if mpi else ()),
                     f"{st['stick']}/{st['slip']}/{st['open']}",
                     "/".join(str(r[k]) for k in ("factorizations", "low_rank_updates",
                                                  "factorization_reuses"))))
    widths = [max(len(h), *(len(row[i]) for row in rows)) for i, h in enumerate(head)]
    print(" ".join(h.rjust(w) for h, w in zip(head, widths)), file=out)
    for row in rows:
        print(" ".join(c.rjust(w) for c, w in zip(row, widths)), file=out)
    for r in records:
        if "solves" in r:
            print(f"  n = {r['n']}: {r['growth_steps']} growth steps ({r['end_reason']}), "
                  f"{r['solves']} solves, N_final = {r['n_final']}, LU ref of "
                  f"2 N_final = {2 * r['n_final']}", file=out)
        if "over_mts" in r:
            m = r["mts"]
            print(f"  n = {r['n']}: work {r['seconds']['total']:.3f} s = {r['over_mts']:.2f} x "
                  f"the MTS run ({m['seconds']:.3f} s, {m['solves']} solves, "
                  f"{m['growth_steps']} growth steps, N_final = {m['n_final']}); "
                  f"{r['solves_per_step']:.1f} solves and {r['updates_per_step']:.1f} "
                  "low-rank updates per growth step", file=out)
        if "steps" in r:
            print(f"  n = {r['n']}: {r['steps']} steps, {r['newton_iterations']} Newton "
                  f"iterations, {r['pivots']} Lemke pivots, {r['fallback_steps']} steps fell "
                  "back", file=out)
        if r["fallback"]:
            print(f"* n = {r['n']}: {r['fallback']}", file=out)
        if r.get("matrix") == "hierarchical":
            dense = r.get("error_vs_dense")
            versus = "" if dense is None else (
                f"; against dense: same states {dense['same_states']}, largest DD "
                f"difference {dense['max_dd_difference']:.1e}")
            print(f"  n = {r['n']}: hierarchical matrix, {100 * r['compression_ratio']:.3f} % "
                  f"of the dense one{versus}", file=out)
        if "lemke" in r:
            lk = r["lemke"]
            print(f"  n = {r['n']}: lemke {lk['seconds']:.3f} s ({lk['total_over_lu']:.2f} x "
                  f"LU, {lk['peak_rss_mb']:.0f} MB, {lk['pivots']} pivots); same states: "
                  f"{lk['same_states']}, largest DD difference {lk['max_dd_difference']:.1e}",
                  file=out)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["--measure-rank"]:  # one process of an --mpi run (mpi_command)
        return measure_rank(argv[1:])
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--exe", required=True, type=Path, help="the ddc2d executable")
    parser.add_argument("--sizes", default=None,
                        help="comma-separated numbers of contact elements (not for bp3)")
    parser.add_argument("--case", required=True, choices=sorted([*CASES, "bp3"]))
    parser.add_argument("--json", required=True, type=Path, help="JSON file to write")
    parser.add_argument("--threads", default=None,
                        help="OpenMP and OpenBLAS threads of each process, or a comma-"
                             "separated list of them run in turn (default: all CPUs, "
                             "divided by P with --mpi)")
    parser.add_argument("--lcp-method", default="auto", choices=("auto", "lemke", "newton"))
    parser.add_argument("--grid", type=int, default=None,
                        help="observation grid of GRID x GRID points (0: none; default "
                             "500 for the fields case, 0 for history, else 100)")
    parser.add_argument("--steps", type=int, default=None,
                        help="increments of the history case (default 100), growth steps "
                             "of the growth case (default 25), load steps of the "
                             "growth-history case (default 20)")
    parser.add_argument("--compare-lemke", action="store_true",
                        help="also run every model with lcp_method = 'lemke' and compare")
    parser.add_argument("--lu-exe", type=Path, default=None,
                        help="reference LU program (default: <build>/tests/"
                             "ddc2d_lu_benchmark beside the executable's app/ folder)")
    parser.add_argument("--workdir", type=Path, default=None,
                        help="folder for the models (default: a temporary folder)")
    parser.add_argument("--mpi", type=int, default=0, metavar="P",
                        help="run on P MPI processes (--exe: the MPI build's ddc2d)")
    parser.add_argument("--mpiexec", default="mpiexec", help="MPI launcher (default mpiexec)")
    parser.add_argument("--block-size", type=int, default=None,
                        help="&solver block_size of the distributed matrices (default 64)")
    parser.add_argument("--matrix", default=None, choices=("dense", "hierarchical"),
                        help="&solver matrix (default dense; hierarchical for bp3)")
    parser.add_argument("--years", type=float, default=1500.0,
                        help="bp3: years simulated (default 1500)")
    parser.add_argument("--cell", type=float, default=25.0,
                        help="bp3: cell size [m] (default 25)")
    parser.add_argument("--tolerance", type=float, default=1e-7,
                        help="bp3: &cycle tolerance (default 1e-7)")
    parser.add_argument("--compare-dense", action="store_true",
                        help="with --matrix hierarchical: also run every model on the dense "
                             "matrix where it fits and compare")
    parser.add_argument("--figure", type=Path, default=None,
                        help="also draw total time and peak memory against N (PNG)")
    args = parser.parse_args(argv)
    if args.case == "bp3":
        return main_bp3(args, parser)
    if args.sizes is None:
        parser.error("--sizes is required for this case")
    args.matrix = args.matrix or "dense"

    try:
        sizes = [int(s) for s in args.sizes.split(",") if s.strip()]
    except ValueError:
        parser.error(f"--sizes must be comma-separated integers, not {args.sizes!r}")
    if not sizes or min(sizes) < 6 and args.case == "mixed" or min(sizes) < 1:
        parser.error("--sizes must be positive (at least 6 for the mixed case)")
    if args.mpi < 0 or args.block_size is not None and args.block_size < 1:
        parser.error("--mpi and --block-size must be positive")
    if args.threads is None:
        thread_counts = [max(1, (os.cpu_count() or 1) // max(args.mpi, 1))]
    else:
        try:
            thread_counts = [int(t) for t in args.threads.split(",") if t.strip()]
        except ValueError:
            parser.error(f"--threads must be comma-separated integers, not {args.threads!r}")
    if not thread_counts or min(thread_counts) < 1:
        parser.error("--threads must be at least 1")
    if args.steps is None:
        args.steps = DEFAULT_STEPS.get(args.case, 100)
    if args.steps < 3 and args.case == "history" or args.steps < 1:
        parser.error("--steps must be at least 3 (history) or 1 (growth)")
    if args.grid is None:
        args.grid = DEFAULT_GRID[args.case]
    exe = args.exe.resolve()
    if not exe.is_file():
        parser.error(f"--exe {exe} does not exist")
    lu_exe = args.lu_exe or exe.parent.parent / "tests" / "ddc2d_lu_benchmark"
    if not Path(lu_exe).is_file():
        parser.error(f"reference LU program {lu_exe} not found (build the tests, or give "
                     "--lu-exe)")

    records = []
    with tempfile.TemporaryDirectory() as tmp:
        workdir = args.workdir or Path(tmp)
        workdir.mkdir(parents=True, exist_ok=True)
        for threads in thread_counts:
            for n in sizes:
                records.append(benchmark_one(exe, lu_exe, n, args.case, threads,
                                             args.lcp_method, args.grid, workdir, args.steps,
                                             args.compare_lemke, args.mpi, args.mpiexec,
                                             args.block_size, args.matrix,
                                             args.compare_dense))
    processes = f"{args.mpi} MPI processes of " if args.mpi else ""
    threads = ",".join(map(str, thread_counts))
    cores = sorted({r["blas_core"] for r in records})
    exponent = time_exponent(records)
    for record in records:
        record["time_exponent"] = exponent
    print(f"# ddc2d benchmark, case {args.case}, {processes}{threads} thread(s), "
          f"lcp_method = {args.lcp_method}, matrix = {args.matrix}, grid {args.grid} x "
          f"{args.grid}, BLAS kernel {', '.join(cores) or 'unknown'}, "
          f"{time.strftime('%Y-%m-%d')}")
    print_table(records)
    if exponent is not None:
        print(f"  total time grows as N^{exponent:.2f} over these sizes (least squares)")
    if args.figure:
        plot_scaling(records, args.figure)
    args.json.write_text(json.dumps(records, indent=2) + "\n")
    return 0


def main_bp3(args, parser):
    """--case bp3: one earthquake-cycle run, printed and written as a one-record JSON list."""
    exe = args.exe.resolve()
    if not exe.is_file():
        parser.error(f"--exe {exe} does not exist")
    threads = int(args.threads or 1)
    with tempfile.TemporaryDirectory() as tmp:
        workdir = args.workdir or Path(tmp)
        workdir.mkdir(parents=True, exist_ok=True)
        record = bp3_benchmark(exe, threads, args.matrix or "hierarchical", args.years,
                               args.cell, args.tolerance, workdir)
    print_bp3(record)
    args.json.write_text(json.dumps([record], indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
