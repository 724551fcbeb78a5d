"""Plot a ddc2d result file (HDF5).

    ddc2d-plot RESULT.h5 [-o DIR] [--format png|pdf|svg] [--quantity Q[,Q...]]
               [--clim MIN MAX] [--receiver ANGLE_DEG] [--friction MU]
               [--sense auto|right|left|reverse|normal] [--dpi DPI]
               [--history-elements K[,K...]] [--history-steps K[,K...]]
               [--injection-times T[,T...]]

Q is one of sxx, syy, sxy, mean, max_shear, coulomb, induced_sxx, induced_syy,
induced_sxy, induced_mean, displacement, or 'all'.
Writes, into DIR (default: the current folder, created if missing):

* ``<stem>_profile_<fracture>.<fmt>`` for every fracture: slip (-Ds) and opening (-Dn)
  against the distance along the fracture (measured from the begin point of its first
  element, plotted at element midpoints), each element marked by its state
  (free / stick / slip / open); a panel only for a DD that some element of the model has
  (profile_panels: no opening panel when nothing opens, no slip panel when nothing slips);
  the figure says what positive slip means (slip_sense);
* ``<stem>_profiles.<fmt>`` when there is more than one fracture: the profiles of all
  fractures in one figure, each against the x coordinate of its element midpoints, or y
  when that fracture extends further in y than in x (the legend says which);
* ``<stem>_map_<grid>_<quantity>.<fmt>`` for every field of kind 'grid' and every quantity
  asked for: a map of the quantity with all elements drawn over it (with displacement
  vectors for 'displacement'); points flagged as on an element (near_element == 2) or not
  finite are left blank;
* ``<stem>_surface_<line>.<fmt>`` for every field of kind 'line' lying on the free surface
  y = 0 of a half-plane model (root attribute domain = 'half_plane'): the surface
  displacement profile, ux and uy against x (points on an element end, NaN, are gaps);
* ``<stem>_line_<line>.<fmt>`` and ``<stem>_points_<set>.<fmt>`` for every other field of
  kind 'line' or 'points' (TWODD observation lines too): ux, uy, sxx, syy, sxy against the
  distance along the line from its first point (for a point list: along the points in file
  order); points on an element (NaN) are gaps, and a set whose every point is NaN gets a
  warning instead of a figure;

The name part of a file is left out when it repeats the kind (a grid named 'map' gives
``<stem>_map_<quantity>``, not ``<stem>_map_map_<quantity>``) unless that name is taken.
* ``<stem>_tips.csv`` and ``<stem>_tips.txt``: the crack tips with K_I and K_II (the text
  table is also printed);
* ``<stem>_history.<fmt>`` for a loading history (/history;
  docs/plotting.md#loading-histories): the hysteresis, slip (-Ds) at chosen elements
  (1-based; default: the element of largest slip over the path) against the load parameter
  (the path quantity with the largest range), steps joined in path order and marked by
  state, an arrow per leg showing the way the path runs; and the slip profiles (against
  the distance along each fracture; a profile equal to an earlier one says so) at chosen
  steps (1-based; default: the path's vertices);
  (a path with a time axis along which no load changes runs along its time);
* ``<stem>_front.<fmt>``, ``<stem>_injection.<fmt>`` and ``<stem>_moment.<fmt>`` for a
  result with fluid sources (/injection; docs/plotting.md#fluid-injection): the slip
  fronts of every fracture that slips against sqrt(t - t0), measured from the fracture's
  source (from its first vertex without one), with the self-similar closed form where it
  applies (ddc2d.plot.injection.closed_form_front says when, and the heading why not); the
  pressure change and the slip along every fracture the pressure reaches or that slips at
  chosen times (the step nearest each; default: 4 times evenly spaced in sqrt(t - t0));
  the seismic moment of every fracture that slips against the injected volume;
* ``<stem>_history_strengths.<fmt>`` for a loading history that records the strengths in
  force (a law beyond Coulomb's): the friction, cohesion and tensile strength in force at
  the same elements against the load parameter;
* ``<stem>_growth.<fmt>`` for a fracture growth run (/growth; docs/plotting.md#growth): the grown
  geometry, the input's elements in black and every new element coloured by the step that
  created it (/elements/created_step), link points and a half-plane's surface, and K_eq /
  toughness against the step (along a load path: against the load) for every tip (one line
  per tip, markers by what the tip did in that step, its last reason at the line's end;
  growth goes on while a tip's ratio is at least 1; tips with equal curves and reasons, as
  the wings of a symmetric model, share a line labelled 'begin = end (symmetric)'). The
  maps draw the grown elements in the same colours and veil the points near them.
* ``<stem>_growth_trials.<fmt>`` for growth by the work criterion (/growth/trials;
  docs/plotting.md#growth): the efficiency of every trial kink against its angle, a line per
  tip and step, the applied angle marked and the threshold dashed.
* ``<stem>_flaw_trials.<fmt>`` for flaw points under the work criterion
  (/growth/initiations/flaw_trials; docs/plotting.md#growth): the efficiency of every trial
  of a flaw's first crack against its direction, a line per flaw and check, the direction it
  started in marked and the threshold dashed.
* ``<stem>_growth_history.<fmt>`` for growth along a load path (/history/grown_length;
  docs/plotting.md#growth): the length each tip has grown against the load parameter, a point
  per load step.
* ``<stem>_cycle_slip.<fmt>``, ``<stem>_cycle_rate.<fmt>`` and ``<stem>_cycle_events.<fmt>``
  for an earthquake-cycle run (/cycle; docs/plotting.md#earthquake-cycles): the cumulative
  slip along the fault every 5 years between events and every second during them, the
  largest slip rate against time, and the catalogue (each event's largest slip, the time to
  the next).

The maps' quantities, the background stress and the Coulomb stress change (receiver plane,
friction, slip sense: right- / left-lateral in a map view, reverse / normal in a
cross-section) are described in ddc2d.plot.data, which prepares every figure's data
without matplotlib (ddc2d.plot.figures draws them); ddc2d.plot gives both for reuse.
Element states and the other integer codes are read from the `coding` attributes of the
file.

Prints the tips table, then the path of every file written, one per line. Exit status:
0 success; 2 bad usage or an input file that is missing, unreadable or not a ddc2d result;
3 a figure or table could not be written.
"""

import argparse
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np

from ..files import write_text_atomically
from ..reader import Loaded, ResultError, load_result
from . import figures
from .data import (
    BACKGROUND_QUANTITIES,
    CLIM_PERCENTILE,
    DEFAULT_FRICTION,
    DEFAULT_QUANTITY,
    DEFAULT_RECEIVER_ANGLE,
    QUANTITIES,
    Background,
    Receiver,
    all_nan,
    figure_base,
    fracture_profiles,
    grid_fields,
    grid_quantity,
    grid_reference_y,
    history_choices,
    is_cross_section,
    observation_sets,
    surface_lines,
    tips_csv,
    tips_text,
)
from .hydraulic import fracture_series as hydraulic_series
from .hydraulic import is_hydraulic_fracture
from .injection import has_injection, profile_steps

PROGRAM = "ddc2d-plot"
EXIT_OK = 0
EXIT_BAD_INPUT = 2
EXIT_IO_FAILURE = 3
#: Slip senses of a Coulomb receiver (--sense).
SENSE_CHOICES = ("auto", "right", "left", "reverse", "normal")
#: The names of the figures (and tables) of the whole result, after <stem>_: a fracture,
#: grid or line whose name would give one of them gets a longer name (figure_base).
FIXED_NAMES = ("profiles", "history", "tips", "growth", "growth_history", "growth_trials",
               "flaw_trials", "history_strengths", "front", "injection", "moment", "cycle_slip",
               "cycle_rate", "cycle_events", "hydraulic_fracture")


@dataclass
class Chosen:
    """What the figures of a result draw at: the history's elements and steps (0-based;
    None without a history) and the steps of the injection profiles (None without fluid
    sources)."""

    history: tuple[list[int], list[int]] | None = None
    injection: list[int] | None = None


# --------------------------------------------------------------------------- command line


def _quantity_list(text: str) -> list[str]:
    """argparse type of --quantity: comma-separated names, or 'all'."""
    names = [name.strip() for name in text.split(",") if name.strip()]
    if names == ["all"]:
        return list(QUANTITIES)
    unknown = [name for name in names if name not in QUANTITIES]
    if unknown or not names:
        raise argparse.ArgumentTypeError(
            f"unknown quantity '{','.join(unknown) or text}' (choose from "
            f"{', '.join(QUANTITIES)}, or all)")
    return list(dict.fromkeys(names))


def _index_list(text: str) -> list[int]:
    try:
        return [int(item) for item in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a list of integers") from None


def _time_list(text: str) -> list[float]:
    try:
        times = [float(item) for item in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a list of times") from None
    if not all(np.isfinite(times)):
        raise argparse.ArgumentTypeError(f"'{text}': the times must be finite")
    return times


def parse_arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Plot slip/opening profiles and field maps of a ddc2d result file and "
        "tabulate the stress intensity factors of its crack tips.",
        epilog="Exit status: 0 success, 2 bad usage or unreadable / non-ddc2d input file, "
        "3 a figure or table could not be written.",
    )
    parser.add_argument("result", metavar="RESULT.h5", help="ddc2d result file (HDF5)")
    parser.add_argument("-o", "--output-dir", metavar="DIR", default=".",
                        help="folder for the figures (created if missing; default: .)")
    parser.add_argument("--format", choices=("png", "pdf", "svg"), default="png",
                        help="figure format (default: png)")
    parser.add_argument("--quantity", type=_quantity_list, default=[DEFAULT_QUANTITY],
                        metavar="Q[,Q...]",
                        help=f"quantities mapped on grids: {', '.join(QUANTITIES)} or all "
                        f"(default: {DEFAULT_QUANTITY})")
    parser.add_argument("--clim", nargs=2, type=float, metavar=("MIN", "MAX"),
                        help="colour limits of the maps (default: the 2nd and "
                        f"{CLIM_PERCENTILE:g}th percentiles, symmetric about 0 for the "
                        "signed quantities when they change sign)")
    parser.add_argument("--receiver", type=float, default=DEFAULT_RECEIVER_ANGLE,
                        metavar="ANGLE_DEG",
                        help="coulomb: angle of the receiver plane, degrees counterclockwise "
                        f"from +x (default: {DEFAULT_RECEIVER_ANGLE:g})")
    parser.add_argument("--friction", type=float, default=DEFAULT_FRICTION, metavar="MU",
                        help=f"coulomb: friction of the receiver (default: {DEFAULT_FRICTION:g})")
    parser.add_argument("--sense", choices=SENSE_CHOICES, default="auto",
                        help="coulomb: slip sense of the receiver, right / left (-lateral), or "
                        "in a cross-section (half-plane, or stress varying with y) reverse / "
                        "normal on a dipping plane; auto = the sense the remote stress "
                        "drives on it (default: auto)")
    parser.add_argument("--dpi", type=int, default=150, help="resolution of PNG figures")
    parser.add_argument("--history-elements", type=_index_list, metavar="K[,K...]",
                        help="loading history: elements (1-based) whose slip is drawn against "
                        "the load (default: the one of largest slip; of slips equal within a "
                        "relative 1e-9, the lowest numbered)")
    parser.add_argument("--history-steps", type=_index_list, metavar="K[,K...]",
                        help="loading history: steps (1-based) whose slip profiles are drawn "
                        "(default: the path's vertices)")
    parser.add_argument("--injection-times", type=_time_list, metavar="T[,T...]",
                        help="fluid injection: times (in the model's time unit) whose "
                        "pressure and slip profiles are drawn, each at the step nearest to "
                        "it (default: 4 times evenly spaced in sqrt(t - t0))")
    args = parser.parse_args(argv)
    if args.clim is not None and not (np.all(np.isfinite(args.clim))
                                      and args.clim[0] < args.clim[1]):
        parser.error("--clim needs finite MIN < MAX")
    if not (np.isfinite(args.receiver) and np.isfinite(args.friction)
            and args.friction >= 0.0):
        parser.error("--receiver needs a finite angle and --friction a finite MU >= 0")
    if args.dpi < 1:
        parser.error("--dpi needs a positive integer")
    return args


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    matplotlib.use("Agg")  # files only, no window
    args = parse_arguments(argv)
    try:
        result, receivers, chosen = _read(args)
    except ResultError as exc:
        print(f"{PROGRAM}: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if not result["complete"]:
        print(f"{PROGRAM}: warning: '{args.result}' is not marked complete", file=sys.stderr)
    out_dir = Path(args.output_dir)
    table = tips_text(result)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
        written = _write_all(result, receivers, chosen, args, out_dir)
    except OSError as exc:
        print(f"{PROGRAM}: error: cannot write figures to '{out_dir}': {exc}",
              file=sys.stderr)
        return EXIT_IO_FAILURE
    print(table, end="")
    for path in written:
        print(path)
    if not result["fractures"] and not grid_fields(result):
        print(f"{PROGRAM}: warning: '{args.result}' has no fractures and no grids",
              file=sys.stderr)
    return EXIT_OK


def _read(args: argparse.Namespace) -> tuple[Loaded, dict[str, Receiver | None], Chosen]:
    """The loaded result, the Receiver of each grid (None without a Coulomb map) and the
    steps and elements chosen (Chosen); every map's data is computed once here, so that a
    file that cannot be drawn fails before anything is written (ResultError)."""
    result = load_result(args.result)
    receivers = {name: _receiver(result, args, result["fields"][name])
                 for name in grid_fields(result)}
    chosen = Chosen()
    if result["history"] is not None:
        chosen.history = history_choices(result["history"], args.history_elements,
                                         args.history_steps)
    if has_injection(result):
        chosen.injection = profile_steps(result, args.injection_times)
    elif args.injection_times is not None:
        raise ResultError(f"'{args.result}' has no fluid sources: --injection-times "
                          "needs a result with &injection")
    for name in grid_fields(result):
        try:
            for quantity in args.quantity:
                grid_quantity(result["fields"][name], quantity, receivers[name],
                              Background.of_result(result))
        except (KeyError, ValueError) as exc:
            raise ResultError(f"cannot read '{args.result}': grid field {name}: {exc}") \
                from exc
    return result, receivers, chosen


def _figures(result, receivers, chosen, args, out_dir, stem):
    """(Figure maker, path without extension) of every figure of the result, in the order
    they are written; a maker is called only when its figure is written."""
    used = {f"{stem}_{name}" for name in FIXED_NAMES}
    for fracture, profile in fracture_profiles(result):
        yield (lambda f=fracture, p=profile: figures.plot_profile(result, f, p),
               figure_base(out_dir, stem, "profile", fracture["label"], used))
    if len(result["fractures"]) > 1:
        yield (lambda: figures.plot_overview(result)), out_dir / f"{stem}_profiles"
    for name in grid_fields(result):
        for quantity in args.quantity:
            yield (lambda n=name, q=quantity: figures.plot_map(result, n, q, args.clim,
                                                               receivers[n]),
                   figure_base(out_dir, stem, "map", name, used, quantity))
    for name in surface_lines(result):
        yield (lambda n=name: figures.plot_surface(result, n),
               figure_base(out_dir, stem, "surface", name, used))
    for name in observation_sets(result):
        field = result["fields"][name]
        if all_nan(field):
            print(f"{PROGRAM}: warning: every point of {field['kind']} '{name}' lies on "
                  "an element (NaN): no figure", file=sys.stderr)
            continue
        yield (lambda n=name: figures.plot_observation_line(result, n),
               figure_base(out_dir, stem, field["kind"], name, used))
    if chosen.history is not None:
        yield ((lambda: figures.plot_history(result, *chosen.history)),
               out_dir / f"{stem}_history")
        if "mu_in_force" in result["history"]:
            yield ((lambda: figures.plot_history_strengths(result, chosen.history[0])),
                   out_dir / f"{stem}_history_strengths")
    if chosen.injection is not None:
        yield (lambda: figures.plot_fronts(result)), out_dir / f"{stem}_front"
        yield ((lambda: figures.plot_injection(result, chosen.injection)),
               out_dir / f"{stem}_injection")
        yield (lambda: figures.plot_moment(result)), out_dir / f"{stem}_moment"
    if result["growth"] is not None:
        yield (lambda: figures.plot_growth(result)), out_dir / f"{stem}_growth"
        if "trials" in result["growth"]:
            yield ((lambda: figures.plot_growth_trials(result)),
                   out_dir / f"{stem}_growth_trials")
        if "flaw_trials" in result["growth"]:
            yield ((lambda: figures.plot_flaw_trials(result)), out_dir / f"{stem}_flaw_trials")
    if result["history"] is not None and "grown_length" in result["history"]:
        yield (lambda: figures.plot_growth_history(result)), out_dir / f"{stem}_growth_history"
    if is_hydraulic_fracture(result) and hydraulic_series(result):
        yield ((lambda: figures.plot_hydraulic_fracture(result)),
               out_dir / f"{stem}_hydraulic_fracture")
    if result["cycle"] is not None:
        yield (lambda: figures.plot_cycle_slip(result)), out_dir / f"{stem}_cycle_slip"
        yield (lambda: figures.plot_cycle_rate(result)), out_dir / f"{stem}_cycle_rate"
        yield (lambda: figures.plot_cycle_events(result)), out_dir / f"{stem}_cycle_events"


def _write_all(result: Loaded, receivers: dict[str, Receiver | None], chosen: Chosen,
               args: argparse.Namespace, out_dir: Path) -> list[Path]:
    """Write every figure and the tips tables; returns the paths written (OSError when
    one cannot be written)."""
    stem = Path(args.result).stem
    written = [figures.save_figure(make(), base, args.format, args.dpi)
               for make, base in _figures(result, receivers, chosen, args, out_dir, stem)]
    for suffix, text in ((".csv", tips_csv(result)), (".txt", tips_text(result))):
        path = out_dir / f"{stem}_tips{suffix}"
        write_text_atomically(path, text)
        written.append(path)
    return written


def _receiver(result: Loaded, args: argparse.Namespace, field: dict[str, Any]
              ) -> Receiver | None:
    """The Receiver of the Coulomb map of a grid field, or None when no map is of
    'coulomb'; a change map without remote_stress in the file, or a sense the receiver
    cannot have, is an error (ResultError)."""
    wanted = [q for q in args.quantity if q in BACKGROUND_QUANTITIES]
    if wanted and result["remote_stress"] is None:
        raise ResultError(f"'{args.result}' has no root attribute remote_stress: "
                          f"cannot compute {', '.join(wanted)}")
    if "coulomb" not in args.quantity:
        return None
    try:
        return Receiver(Background.of_result(result), args.receiver, args.friction,
                        args.sense, grid_reference_y(field), is_cross_section(result))
    except ValueError as exc:
        raise ResultError(f"--sense {args.sense}: {exc}") from None


if __name__ == "__main__":
    sys.exit(main())
