"""The SCEC SEAS benchmark BP3-QD for ddc2d: its model as a namelist (bp3_namelist), and the
benchmark's ASCII files written from a ddc2d earthquake-cycle result (write_seas).

    ddc2d-seas RESULT.h5 -o DIR [--problem 'SEAS Benchmark BP3-QD'] [--modeler NAME]

The result's /cycle (docs/output-reference.md#cycle) becomes the benchmark's files
(docs/earthquake-cycles.md#the-seas-files):

* ``fltst_dpXXX``: time series at the on-fault stations (down-dip distances XXX / 10 km:
  0, 2.5, 5, 7.5, 10, 12.5, 15, 17.5, 20, 25, 30, 35 km), each at the recorded element
  nearest to it: ``t slip slip_rate shear_stress normal_stress state`` (slip rate and state
  as log10);
* ``srfst_fnXXX``: time series at the observation points on the free surface (y = 0), named
  by their distance from the fault trace in km (``-32`` ... ``+32``; ``+00`` and ``-00``
  the two sides of the trace): ``t disp_1 disp_2 vel_1 vel_2`` (``disp_2`` positive
  downward);
* ``slip.dat``, ``shear_stress.dat``, ``normal_stress.dat``: the profiles of the recorded
  elements, a first row ``0 0 x_d...`` then ``t log10(max V) values...`` per row.

ddc2d keeps its own signs in /cycle (tension positive, slip ds = us(-) - us(+)); the files
are in the benchmark's: shear and normal stress compression positive (shear_stress = -t_s,
normal_stress = -t_n), slip = ds (thrust positive for a fault dipping toward +x), in m, s
and MPa (the result's unit labels m, km, mm; Pa, kPa, MPa, GPa; s, min, h, day, yr are
converted, others refused).

Exit status: 0 success; 2 bad usage or a file that is not a cycle result; 3 a file could
not be written.
"""

import argparse
import datetime
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from . import __version__
from .files import write_text_atomically
from .reader import ResultError, load_result

PROGRAM = "ddc2d-seas"
EXIT_OK = 0
EXIT_BAD_INPUT = 2
EXIT_IO_FAILURE = 3

#: BP3-QD's values (docs/earthquake-cycles.md#bp3-qd), SI units: density, shear wave speed,
#: Poisson's ratio, effective normal stress [MPa], a0, a_max, b0, L [m], V0 [m/s], f0, the
#: plate rate [m/s], H, h, W_f [m].
BP3 = {"rho": 2670.0, "cs": 3464.0, "nu": 0.25, "sigma": 50.0, "a0": 0.010, "amax": 0.025,
       "b": 0.015, "dc": 0.008, "v0": 1.0e-6, "f0": 0.6, "vp": 1.0e-9, "H": 15.0e3,
       "h": 3.0e3, "Wf": 40.0e3}
#: A year [s] (365.25 days, as the benchmark's output counts it).
YEAR = 365.25 * 86400.0
#: Surface stations of BP3-QD: x [m] from the fault trace, the two sides of it at +-1 m.
SURFACE_STATIONS_M = (-32.0e3, -16.0e3, -8.0e3, 1.0, -1.0, 8.0e3, 16.0e3, 32.0e3)
#: Down-dip distances of the on-fault stations of BP3-QD [km].
FAULT_STATIONS_KM = (0.0, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0, 17.5, 20.0, 25.0, 30.0, 35.0)
#: A point within this distance of the surface y = 0 [m] is a surface station.
SURFACE_TOLERANCE_M = 1.0e-6
#: Factors to the benchmark's units, by unit label.
LENGTH_TO_M = {"m": 1.0, "km": 1.0e3, "mm": 1.0e-3}
STRESS_TO_MPA = {"Pa": 1.0e-6, "kPa": 1.0e-3, "MPa": 1.0, "GPa": 1.0e3}
TIME_TO_S = {"s": 1.0, "min": 60.0, "h": 3600.0, "day": 86400.0, "yr": 365.25 * 86400.0}


def bp3_namelist(dip: float = 60.0, thrust: bool = True, cell: float = 25.0,
                 years: float = 1500.0, scale: float = 1.0, matrix: str = "dense",
                 tolerance: float = 1.0e-7, points_file: str = "",
                 dc_scale: float | None = None) -> str:
    """The namelist of BP3-QD (docs/earthquake-cycles.md#bp3-qd): a planar fault from the
    surface, dipping at `dip` degrees toward +x, of cells `cell` m down to W_f, its a(x_d)
    per element, and the initial shear traction and state of the benchmark; thrust
    (V_p > 0) or normal (V_p < 0). `scale` shrinks every length of the fault (H, h, W_f, L)
    and so the time between events: a small model of the same kind for the tests; L is
    scaled by `dc_scale` instead when given.
    Units m, MPa, s; outputs as the benchmark asks (0.1 yr apart between events, 0.1 s in
    them, every 500 m along the fault); the surface stations from `points_file` (a CSV of
    x, y) when given."""
    p = BP3
    g = p["rho"] * p["cs"] ** 2 / 1.0e6
    vp = p["vp"] if thrust else -p["vp"]
    eta = g / (2.0 * p["cs"])
    dc = p["dc"] * (scale if dc_scale is None else dc_scale)
    tau = (p["sigma"] * p["amax"] * np.arcsinh(abs(vp) / (2.0 * p["v0"]) * np.exp(
        (p["f0"] + p["b"] * np.log(p["v0"] / abs(vp))) / p["amax"])) + eta * abs(vp))
    corners = [0.0, p["H"] * scale, (p["H"] + p["h"]) * scale, p["Wf"] * scale]
    count = round(corners[-1] / cell)
    middle = (np.arange(count) + 0.5) * corners[-1] / count
    a = np.interp(middle, corners, [p["a0"], p["a0"], p["amax"], p["amax"]])
    # A polyline segment per run of equal a (the transition: one per element)
    vertices: list[float] = [0.0]
    counts: list[int] = []
    values: list[float] = []
    for k in range(count):
        if values and a[k] == values[-1]:
            counts[-1] += 1
        else:
            counts.append(1)
            values.append(float(a[k]))
            vertices.append(0.0)
        vertices[-1] = (k + 1) * corners[-1] / count
    cos, sin = np.cos(np.radians(dip)), np.sin(np.radians(dip))

    def listed(numbers: Sequence[float]) -> str:
        """The numbers, six to a line (no negative zero)."""
        texts = [f"{v + 0.0:.12g}" for v in numbers]
        return ",\n    ".join(", ".join(texts[k:k + 6]) for k in range(0, len(texts), 6))

    points = f"&points name = 'surface', file = '{points_file}' /\n" if points_file else ""
    return (
        f"&model title = 'BP3-QD {'thrust' if thrust else 'normal'} {dip:g}', "
        f"youngs_modulus = {2.0 * g * (1.0 + p['nu']):.12g}, poissons_ratio = {p['nu']:g},\n"
        "  domain = 'half_plane', length_unit = 'm', stress_unit = 'MPa', time_unit = 's' /\n"
        f"&fracture name = 'fault', condition = 'rate_state',\n"
        f"  x = {listed([v * cos for v in vertices])},\n"
        f"  y = {listed([-v * sin for v in vertices])},\n"
        f"  elements = {listed(counts)},\n"
        f"  a = {listed(values)},\n"
        f"  b = {p['b']:g}, dc = {dc:.12g}, f0 = {p['f0']:g}, v0 = {p['v0']:g}, "
        f"v_init = {vp:g}, sigma0 = {p['sigma']:g}, tau0 = {-np.sign(vp) * tau:.12g} /\n"
        f"{points}"
        f"&cycle end_time = {years * YEAR:.12g}, tolerance = {tolerance:g}, "
        f"shear_wave_speed = {p['cs']:g}, plate_rate = {vp:g},\n"
        f"  output_interval = {0.1 * YEAR:.12g}, event_output_interval = 0.1, "
        f"profile_spacing = {500.0 * scale:.12g} /\n"
        f"&solver matrix = '{matrix}' /\n")


def unit_factor(label: str, table: dict[str, float], what: str) -> float:
    """The factor from a unit label to the benchmark's unit (ValueError for another)."""
    if label not in table:
        raise ValueError(f"cannot convert the {what} unit '{label}' (known: "
                         f"{', '.join(table)})")
    return table[label]


def surface_name(x_m: float) -> str:
    """The benchmark's name of a surface station at x [m] from the trace: 'srfst_fn+08';
    the sign tells the two sides of the trace apart (+00, -00)."""
    km = round(abs(x_m) / 1.0e3)
    return f"srfst_fn{'-' if x_m < 0 else '+'}{km:02d}"


def header(problem: str, modeler: str, element_size: float, rows: int,
           lines: Sequence[str]) -> str:
    """The common file header, then `lines` (each without '# ')."""
    common = ["This is the file header:", f"problem={problem}", "code=ddc2d",
              f"version={__version__}", f"modeler={modeler}",
              f"date={datetime.date.today():%Y/%m/%d}", f"element_size={element_size:g} m",
              f"num_time_steps={rows}"]
    return "".join(f"# {line}\n" for line in common + list(lines))


def rows_text(columns: Sequence[np.ndarray]) -> str:
    """One line per row: the time in %21.13E, the other columns in %14.6E."""
    table = np.column_stack(columns) + 0.0  # no negative zero
    formats = "%21.13E " + " ".join(["%14.6E"] * (table.shape[1] - 1))
    return "".join(formats % tuple(row) + "\n" for row in table)


def seas_files(result_path: str | Path, problem: str = "SEAS Benchmark BP3-QD",
               modeler: str = "") -> dict[str, str]:
    """The benchmark's files of a cycle result: file name -> text (ResultError for a file
    that is not one, ValueError for units that cannot be converted)."""
    result = load_result(result_path)
    cycle = result["cycle"]
    if cycle is None:
        raise ResultError(f"'{result_path}' has no /cycle: not an earthquake-cycle result")
    length = unit_factor(result["length_unit"], LENGTH_TO_M, "length")
    stress = unit_factor(result["stress_unit"], STRESS_TO_MPA, "stress")
    time = unit_factor(cycle["attrs"].get("time_unit", "s"), TIME_TO_S, "time")
    elements = result["elements"]
    t = cycle["time"] * time
    rows = t.size
    log_max_rate = np.log10(np.maximum(cycle["max_slip_rate"] * length / time,
                                       np.finfo(float).tiny))
    distance_m = cycle["distance"] * length
    size = float(np.median(2.0 * elements["half_length"][cycle["profile"] - 1])) * length
    files = {}
    for km in FAULT_STATIONS_KM:
        j = int(np.argmin(np.abs(distance_m - km * 1.0e3)))
        lines = [f"location=on fault, {km:g} km down-dip distance",
                 "Column #1 = Time (s)", "Column #2 = Slip (m)",
                 "Column #3 = Slip rate (log10 m/s)", "Column #4 = Shear stress (MPa)",
                 "Column #5 = Normal stress (MPa)", "Column #6 = State (log10 s)",
                 "The line below lists the names of the data fields"]
        rate = np.abs(cycle["slip_rate"][:, j]) * length / time
        text = header(problem, modeler, size, rows, lines)
        text += "t slip slip_rate shear_stress normal_stress state\n"
        text += "# Here is the time-series data.\n"
        text += rows_text([t, cycle["slip"][:, j] * length,
                           np.log10(np.maximum(rate, np.finfo(float).tiny)),
                           -cycle["shear_traction"][:, j] * stress,
                           -cycle["normal_traction"][:, j] * stress,
                           cycle["state"][:, j] + np.log10(time)])
        files[f"fltst_dp{round(km * 10):03d}"] = text
    for p, (x, y) in enumerate(zip(cycle["point_x"] * length, cycle["point_y"] * length)):
        if abs(y) > SURFACE_TOLERANCE_M:
            continue
        lines = [f"location=on surface, {x / 1.0e3:+g} km off fault",
                 "Column #1 = Time (s)", "Column #2 = Displacement 1 (m)",
                 "Column #3 = Displacement 2 (m)", "Column #4 = Velocity 1 (m/s)",
                 "Column #5 = Velocity 2 (m/s)",
                 "The line below lists the names of the data fields"]
        text = header(problem, modeler, size, rows, lines)
        text += "t disp_1 disp_2 vel_1 vel_2\n# Here is the time-series data.\n"
        # disp_2 is positive downward: -uy
        text += rows_text([t, cycle["ux"][:, p] * length, -cycle["uy"][:, p] * length,
                           cycle["vx"][:, p] * length / time,
                           -cycle["vy"][:, p] * length / time])
        files[surface_name(x)] = text
    profiles = (("slip", "Slip (m)", cycle["slip"] * length),
                ("shear_stress", "Shear stress (MPa)", -cycle["shear_traction"] * stress),
                ("normal_stress", "Normal stress (MPa)", -cycle["normal_traction"] * stress))
    for name, description, values in profiles:
        lines = ["Row #1 = Distance down dip (m) with two zeros first",
                 "Column #1 = Time (s)", "Column #2 = Max slip rate (log10 m/s)",
                 f"Columns #3-{distance_m.size + 2} = {description}",
                 "The line below lists the names of the data fields"]
        text = header(problem, modeler, size, rows, lines)
        text += f"xd\nt max_slip_rate {name}\n# Here are the data\n"
        text += " ".join(f"{v:14.6E}" for v in np.concatenate(([0.0, 0.0], distance_m)))
        text += "\n" + rows_text([t, log_max_rate, values])
        files[f"{name}.dat"] = text
    return files


def write_seas(result_path: str | Path, out_dir: str | Path,
               problem: str = "SEAS Benchmark BP3-QD", modeler: str = "") -> list[Path]:
    """Write the benchmark's files of a cycle result into out_dir (created if missing);
    returns their paths (ResultError, ValueError as seas_files; OSError when one cannot be
    written)."""
    files = seas_files(result_path, problem, modeler)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, text in files.items():
        write_text_atomically(out / name, text)
        written.append(out / name)
    return written


def parse_arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog=PROGRAM,
        description="Write the SCEC SEAS benchmark's ASCII files (fltst_dpXXX, srfst_fnXXX, "
        "slip.dat, shear_stress.dat, normal_stress.dat) of a ddc2d earthquake-cycle result.",
        epilog="Exit status: 0 success, 2 bad usage or a file that is not a cycle result, "
        "3 a file could not be written.")
    parser.add_argument("result", metavar="RESULT.h5", help="ddc2d result file of a &cycle run")
    parser.add_argument("-o", "--output-dir", metavar="DIR", default=".",
                        help="folder for the files (created if missing; default: .)")
    parser.add_argument("--problem", default="SEAS Benchmark BP3-QD",
                        help="the header's problem (default: SEAS Benchmark BP3-QD)")
    parser.add_argument("--modeler", default="", help="the header's modeler")
    return parser.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = parse_arguments(argv)
    try:
        written = write_seas(args.result, args.output_dir, args.problem, args.modeler)
    except (ResultError, ValueError) as exc:
        print(f"{PROGRAM}: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except OSError as exc:
        print(f"{PROGRAM}: error: cannot write to '{args.output_dir}': {exc}", file=sys.stderr)
        return EXIT_IO_FAILURE
    for path in written:
        print(path)
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
