"""Convergence study of fracture growth (docs/theory/growth.md#convergence-with-the-increment):
the wings of a sliding flaw against the increment and the element length. The command
ddc2d-growth-convergence, in the repository also scripts/growth_convergence.py; it writes
into results/ in the current folder unless told otherwise.

    growth_convergence.py [--exe DDC2D] [--work DIR] [--figure PNG] [--csv CSV]
                          [--elements N[,N...]] [--increments D[,D...]]
                          [--k-method auto|higher_order|tip_element] [--quick]

The model: a 2 m flaw at 45 degrees to sigma_1 (sxx = -5, syy = -100), frictional contact
(mu 0.6, sf 0), N elements, &growth toughness 2, new_sf 0, at most 80 steps. For every N
(default 40, 80) and increment (default 0.2, 0.1, 0.05, 0.025) one run with
element_length = min(2/N, increment) (new elements never longer than the flaw's) and K by
--k-method (default 'auto': the calibrated tip element; 'higher_order': the local re-solve
at every trial, docs/theory/tips.md#tips-of-grown-fractures), in DIR (default
results/growth-convergence), one thread; the program is --exe, else the
one ddc2d.run finds (ddc2d.paths.find_executable). From each result: the arrest length of
a wing (sum of its increments), its final direction (last element, degrees from +x;
sigma_1 is at 90), the first applied kink angle, the end reason and the steps.

Writes the table (CSV, default DIR/growth_convergence.csv) and the figure (default
results/growth_convergence.png; the gallery's is docs/gallery/growth_convergence.png):
arrest length, final direction and first kink angle against the increment (one line per
element count; the first angle with the MTS angle 70.53 and the infinitesimal-kink
local-symmetry angle of pure mode II, 77.3), and the wing paths. --quick: N = 40 only.

Exit status: 0 when, for every N, every run arrested and its arrest length is within 10 %
and its final direction within 5 degrees of the finest increment's; 1 otherwise (the table
and the figure are written all the same); 2 bad arguments or a run that failed.
"""

import argparse
import csv
import os
import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from .paths import find_executable
from .reader import load_result

#: The wing flaw of docs/theory/growth.md#convergence-with-the-increment
#: ({n}, {increment}, {element_length}, {steps} filled in).
MODEL = """\
&model title = 'wing n={n} d={increment}', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxx = -5, syy = -100 /
&fracture name = 'flaw', x = -0.70710678, 0.70710678, y = -0.70710678, 0.70710678,
          elements = {n}, condition = 'contact', mu = 0.6, sf = 0 /
&growth steps = {steps}, toughness = 2, new_sf = 0, increment = {increment},
        element_length = {element_length} /
"""
#: Angles of the first kink in pure mode II [degree]: maximum tangential stress, and local
#: symmetry of an infinitesimal kink (Amestoy & Leblond 1992)
MTS_ANGLE = 70.53
PLS_ANGLE = 77.3
#: Arrest length within 10 %, final direction within 5 degrees
#: (docs/theory/growth.md#convergence-with-the-increment)
LENGTH_TOLERANCE = 0.10
DIRECTION_TOLERANCE = 5.0


def parse_list(text, kind):
    try:
        values = [kind(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a list of numbers: {text!r}") from None
    if not values or min(values) <= 0:
        raise argparse.ArgumentTypeError(f"need positive numbers: {text!r}")
    return values


def run_case(exe, work, n, increment, k_method="auto", steps=80, element_length=None):
    """Run one model (K by &solver k_method; at most `steps` growth steps; new elements of
    element_length, default min(2/n, increment)); return its row of the table."""
    if element_length is None:
        element_length = min(2.0 / n, increment)
    stem = (f"wing_n{n}_d{increment:g}" + ("" if k_method == "auto" else f"_{k_method}")
            + ("" if steps == 80 else f"_s{steps}_l{element_length:g}"))
    text = MODEL.format(n=n, increment=increment, element_length=element_length, steps=steps)
    if k_method != "auto":
        text += f"&solver k_method = '{k_method}' /\n"
    (work / f"{stem}.nml").write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    done = subprocess.run([str(exe), f"{stem}.nml", "-o", f"{stem}.h5"], cwd=work, env=env,
                          capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        raise RuntimeError(f"{stem}: ddc2d exit {done.returncode}: {done.stderr.strip()}")
    result = load_result(work / f"{stem}.h5")
    growth, elements = result["growth"], result["elements"]
    end = growth["end"] == 1
    last = int(result["fractures"][0]["last"]) - 1
    direction = np.degrees(np.arctan2(elements["y_end"][last] - elements["y_begin"][last],
                                      elements["x_end"][last] - elements["x_begin"][last]))
    angles = growth["angle"][end]
    first = angles[np.isfinite(angles)]
    path = np.column_stack([elements["x_end"], elements["y_end"]])[
        (elements["created_step"] > 0) & (elements["x_mid"] > 0)]
    return {"elements": n, "increment": increment, "element_length": element_length,
            "k_method": k_method,
            "arrest_length": float(np.sum(growth["length"][end])),
            "final_direction": float(direction),
            "first_angle": float(abs(first[0])) if first.size else float("nan"),
            "end_reason": growth["attrs"]["end_reason"],
            "steps": int(growth["attrs"]["steps_taken"]), "path": path}


def check(rows):
    """Messages for every run that misses the targets against its N's finest increment."""
    problems = []
    for n in sorted({r["elements"] for r in rows}):
        runs = sorted((r for r in rows if r["elements"] == n), key=lambda r: r["increment"])
        finest = runs[0]
        for r in runs:
            name = f"N = {n}, increment {r['increment']:g}"
            if r["end_reason"] != "arrested":
                problems.append(f"{name}: ended {r['end_reason']}")
            if abs(r["arrest_length"] - finest["arrest_length"]) > \
                    LENGTH_TOLERANCE * finest["arrest_length"]:
                problems.append(f"{name}: arrest length {r['arrest_length']:.3f} against "
                                f"{finest['arrest_length']:.3f}")
            if abs(r["final_direction"] - finest["final_direction"]) > DIRECTION_TOLERANCE:
                problems.append(f"{name}: final direction {r['final_direction']:.2f} against "
                                f"{finest['final_direction']:.2f}")
    return problems


def plot(rows, figure):
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), constrained_layout=True)
    (ax_len, ax_dir), (ax_first, ax_path) = axes
    for index, n in enumerate(sorted({r["elements"] for r in rows})):
        runs = sorted((r for r in rows if r["elements"] == n), key=lambda r: r["increment"])
        inc = [r["increment"] for r in runs]
        label = f"{n} elements (L = {2.0 / n:g} m)"
        style = {"color": f"C{index}", "marker": "o", "label": label}
        ax_len.plot(inc, [r["arrest_length"] for r in runs], **style)
        ax_dir.plot(inc, [r["final_direction"] for r in runs], **style)
        ax_first.plot(inc, [r["first_angle"] for r in runs], **style)
        for k, r in enumerate(runs):
            ax_path.plot(r["path"][:, 0], r["path"][:, 1], color=f"C{index}",
                         linewidth=1.0, alpha=0.4 + 0.6 * k / max(1, len(runs) - 1),
                         label=f"{label}" if k == 0 else None)
    ax_first.axhline(MTS_ANGLE, color="0.4", linestyle="--", linewidth=0.8,
                     label="MTS 70.53")
    ax_first.axhline(PLS_ANGLE, color="0.4", linestyle=":", linewidth=0.8,
                     label="local symmetry, infinitesimal kink (77.3)")
    ax_path.plot([-0.70710678, 0.70710678], [-0.70710678, 0.70710678], color="black",
                 linewidth=1.5, label="flaw")
    titles = ("arrest length per wing", "final direction of the wing (sigma_1: 90)",
              "first applied kink angle", "wing paths (darker: finer increment)")
    ylabels = ("length [m]", "degrees from +x", "degrees", "y [m]")
    for ax, title, ylabel in zip(axes.flat, titles, ylabels):
        ax.set_title(title, fontsize="medium")
        ax.set_ylabel(ylabel)
        ax.grid(True, linewidth=0.3)
        ax.legend(fontsize="small", loc="best")
        if ax is not ax_path:
            ax.set_xscale("log")
            ax.set_xlabel("increment [m]")
    ax_path.set_xlabel("x [m]")
    ax_path.set_aspect("equal")
    fig.suptitle("wings of a sliding flaw: convergence with the increment")
    figure.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(figure, dpi=110)
    plt.close(fig)


def main(argv=None):
    # Results go to results/ in the current folder, never over the tracked gallery figure
    # (regenerate that with --figure docs/gallery/growth_convergence.png).
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--exe", type=Path, default=None)
    parser.add_argument("--work", type=Path, default=Path("results/growth-convergence"))
    parser.add_argument("--figure", type=Path, default=Path("results/growth_convergence.png"))
    parser.add_argument("--csv", type=Path, default=None)
    parser.add_argument("--elements", type=lambda t: parse_list(t, int), default=[40, 80])
    parser.add_argument("--increments", type=lambda t: parse_list(t, float),
                        default=[0.2, 0.1, 0.05, 0.025])
    parser.add_argument("--k-method", choices=("auto", "higher_order", "tip_element"),
                        default="auto", help="&solver k_method of every run (default auto: "
                        "the tip element, calibrated, in growth)")
    parser.add_argument("--quick", action="store_true", help="40 elements only")
    args = parser.parse_args(argv)
    args.exe = find_executable(args.exe)
    if args.exe is None or not args.exe.is_file():
        parser.error(f"no executable {args.exe or 'found'} (build it, or give --exe)")
    elements = [40] if args.quick else args.elements
    args.work.mkdir(parents=True, exist_ok=True)
    args.figure.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    try:
        for n in elements:
            for increment in args.increments:
                rows.append(run_case(args.exe.resolve(), args.work, n, increment,
                                     args.k_method))
                r = rows[-1]
                print(f"N {n:4d}  increment {increment:7.4f}  element {r['element_length']:7.4f}"
                      f"  arrest {r['arrest_length']:7.4f} m  direction "
                      f"{r['final_direction']:7.2f}  first angle {r['first_angle']:6.2f}  "
                      f"{r['end_reason']} after {r['steps']} steps", flush=True)
    except (RuntimeError, subprocess.TimeoutExpired) as exc:
        print(f"growth_convergence: {exc}", file=sys.stderr)
        return 2
    table = args.csv or args.work / "growth_convergence.csv"
    with open(table, "w", newline="") as f:
        writer = csv.DictWriter(f, [k for k in rows[0] if k != "path"], extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, args.figure)
    print(f"wrote {table} and {args.figure}")
    problems = check(rows)
    for p in problems:
        print(f"not converged: {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
