"""What ddc2d-plot draws, without drawing it: the data of every figure of a ddc2d result.

Used by ddc2d-plot (ddc2d.plot.cli, the command line), ddc2d.plot.figures (the figures)
and the tests; needs numpy and ddc2d.reader (the one reader of result files), never
matplotlib. Element states, near_element flags and growth codes are taken
from the `coding` attributes the file carries (``reader.coding_of``), not from numbers
written here.

Defaults that pick "the largest" or "the first" follow one tie rule: values within a
relative 1e-9 count as equal, and the lowest index wins (reader.index_of_extreme), so
that the choice does not depend on last-bit rounding (symmetric models, other CPUs).

The background stress is the stress without the fractures: the remote stress plus its
gradient, remote_stress + remote_stress_gradient * y (root attributes). The induced
stresses (induced_sxx, ..., induced_mean) are the total minus the background, what one
usually contours; sxx, syy, sxy and mean are the total stress, drawn with a diverging
colour map whose white is the remote value when the background does not vary over the map,
with a sequential one when it varies with depth (no single value means "unchanged").

The Coulomb stress change on a receiver plane at ANGLE_DEG (counterclockwise from +x) with
friction MU is  dCFS = sense * d(tau) + MU * d(sigma_n),  with the changes taken relative to
the background stress at each point, sigma_n tension positive and tau the shear traction on
the plane, positive when the side the plane normal points to moves along the plane
direction (the normal is the direction rotated by +90 degrees): right-lateral slip in a map
view; in a cross-section (is_cross_section: y is up) reverse slip for a plane dipping to
+x (0 < angle < 90 degrees), normal slip for one dipping to -x. sense = +1 for that sense,
-1 for the other; 'auto' takes the sense that the background stress drives on the receiver
at the grid's middle height (the mean y of its points). dCFS > 0 brings the receiver
closer to failure. Pore fluid: ddc2d's pore pressure p0 + dp_dy * y (root attribute
pore_fluid) is given, not computed: the fractures do not change it (no poroelastic
coupling), so it belongs to the background and cancels in the change (d(p) = 0, a drained
response). For an undrained estimate give an effective friction MU (1 - B) with
Skempton's B as --friction.
"""

import re
from itertools import pairwise
from typing import Any

import numpy as np

from ..reader import (
    STATE_NAMES,
    TIE_RTOL,
    ResultData,
    ResultError,
    code_of,
    coding_of,
    index_of_extreme,
    is_tie,
)

#: The stress components and their mean, as total stress and as induced stress.
STRESSES = ("sxx", "syy", "sxy", "mean")
INDUCED = tuple(f"induced_{name}" for name in STRESSES)
QUANTITIES = ("sxx", "syy", "sxy", "mean", "max_shear", "coulomb", *INDUCED, "displacement")
DEFAULT_QUANTITY = "max_shear"
STRESS_LABELS = {
    "sxx": r"$\sigma_{xx}$",
    "syy": r"$\sigma_{yy}$",
    "sxy": r"$\sigma_{xy}$",
    "mean": r"mean stress $(\sigma_{xx}+\sigma_{yy})/2$",
}
QUANTITY_LABELS = {
    **STRESS_LABELS,
    "max_shear": r"max. shear stress $\sqrt{((\sigma_{xx}-\sigma_{yy})/2)^2+\sigma_{xy}^2}$",
    "coulomb": r"Coulomb stress change $\pm\Delta\tau + \mu\,\Delta\sigma_n$",
    **{f"induced_{name}": "induced " + label for name, label in STRESS_LABELS.items()},
    "displacement": r"displacement magnitude $\sqrt{u_x^2+u_y^2}$",
}
#: The colour-bar labels of the maps: short, to fit beside a map of any aspect (the maps'
#: titles give the QUANTITY_LABELS).
COLORBAR_LABELS = {
    **STRESS_LABELS,
    "mean": "mean stress",
    "max_shear": "max. shear stress",
    "coulomb": "Coulomb stress change",
    **{f"induced_{name}": "induced " + label for name, label in STRESS_LABELS.items()
       if name != "mean"},
    "induced_mean": "induced mean stress",
    "displacement": "displacement magnitude",
}
#: Quantities that change sign (drawn with a diverging colour map centred on the value
#: without fractures, when there is one).
SIGNED_QUANTITIES = (*STRESSES, "coulomb", *INDUCED)
#: Quantities that need the background stress (root attribute remote_stress).
BACKGROUND_QUANTITIES = ("coulomb", *INDUCED)
#: Receiver defaults of the Coulomb stress change: a plane along +x, friction 0.6.
DEFAULT_RECEIVER_ANGLE = 0.0
DEFAULT_FRICTION = 0.6
SENSES = {"right": 1, "left": -1}
#: At most this many displacement vectors along each side of a map.
QUIVER_MAX_ARROWS = 24
#: Percentile of |value| used for the default colour limits (tips are singular).
CLIM_PERCENTILE = 98.0
#: Longest first line of a heading that joins the model's title and the figure's subject
#: (characters: a suptitle of 80 fits an 8-inch figure).
HEADING_WIDTH = 80
#: (axis index, profile key, axis label) of the two profile panels.
PROFILE_PANELS = ((0, "slip", "slip $-D_s$"), (1, "opening", "opening $-D_n$"))
#: The strength panels of a profile (strength_panels): (key, axis label, unit kind, lines),
#: each line (dataset in force, dataset as given, legend text).
STRENGTH_PANELS = (
    ("friction", "friction", None, (("mu_in_force", "mu", r"$\mu$"),)),
    ("strength", "strength", "stress",
     (("sf_in_force", "sf", "cohesion $S_f$"),
      ("tensile_strength_in_force", "tensile_strength", "tensile strength $T$"))),
)
#: (profile key, /elements total and elastic DD, legend text) of the joint panel.
JOINT_PARTS = (("slip", "ds", "ds_elastic", "slip"), ("opening", "dn", "dn_elastic", "opening"))
#: (field key, panel label, unit kind) of the observation line figures.
LINE_PANELS = (("ux", "$u_x$", "length"), ("uy", "$u_y$", "length"),
               ("sxx", r"$\sigma_{xx}$", "stress"), ("syy", r"$\sigma_{yy}$", "stress"),
               ("sxy", r"$\sigma_{xy}$", "stress"))


def unit_label(unit):
    """' [unit]' for axis labels, '' without a unit."""
    return f" [{unit}]" if unit else ""


def heading(result, text):
    """A figure's heading: the model's title (when it has one), then `text`; on a line of
    its own when the two would make a first line longer than HEADING_WIDTH characters."""
    if not result["title"]:
        return text
    joined = f"{result['title']}: {text}"
    if len(joined.split("\n", 1)[0]) > HEADING_WIDTH:
        return f"{result['title']}\n{text}"
    return joined


# --------------------------------------------------------------------------- history


def history_parameter(history):
    """(name, values) of the load quantity with the largest range along the path; of
    ranges equal within the tie rule (reader.index_of_extreme), the first in file order.
    A path with a time axis along which no load changes (an injection at constant stress)
    runs along its time: ('time', the time of each step)."""
    names = list(history["loads"])
    ranges = [np.ptp(history["loads"][k]) for k in names]
    if "time" in history and not any(r > 0.0 for r in ranges):
        return "time", history["time"]
    name = names[index_of_extreme(ranges)]
    return name, history["loads"][name]


def history_unit(result, name):
    """The unit of history quantity `name` (history_parameter): the time unit of 'time';
    else the stress unit, per length unit for a gradient (a name starting with 'd')."""
    if name == "time":
        return result["time_unit"]
    return result["stress_unit"] + ("/" + result["length_unit"] if name.startswith("d")
                                    else "")


def leg_arrows(history):
    """(from, to) row pairs of one arrow per leg of a loading history, at the leg's middle
    row, pointing the way the path runs (its sense on an unloading branch); none for a leg
    whose middle the run did not reach (a growth run may stop inside the path)."""
    rows = history["ds"].shape[0]
    vertices = np.cumsum(np.concatenate([[0], history["leg_steps"]])).astype(int)
    return [((a + b) // 2, (a + b) // 2 + 1) for a, b in pairwise(vertices)
            if b > a and (a + b) // 2 + 1 < rows]


def same_profiles(profiles):
    """For each row of `profiles` (one profile per row), the index of the first earlier row
    equal to it under the tie rule (relative to the largest |value| of all), else None: a
    profile drawn on top of an equal one hides it."""
    profiles = np.asarray(profiles, dtype=float)
    finite = np.abs(profiles[np.isfinite(profiles)])
    scale = float(finite.max()) if finite.size else 0.0
    same = []
    for k, row in enumerate(profiles):
        same.append(next((j for j in range(k) if np.array_equal(
            np.isnan(profiles[j]), np.isnan(row)) and np.all(
            np.abs(np.nan_to_num(profiles[j] - row)) <= TIE_RTOL * scale)), None))
    return same


def along_fractures(result, values):
    """(distance, values) of per-element `values` against the distance along each
    fracture (fracture_profile's, from its begin point), fracture after fracture with a NaN
    between them so that one line does not join them."""
    distance, joined = [], []
    for fracture in result["fractures"]:
        sl = slice(fracture["first"] - 1, fracture["last"])
        if distance:
            distance.append([np.nan])
            joined.append([np.nan])
        distance.append(fracture_profile(result["elements"], fracture["first"],
                                         fracture["last"])["distance"])
        joined.append(np.asarray(values, dtype=float)[sl])
    return np.concatenate(distance), np.concatenate(joined)


def history_choices(history, elements=None, steps=None):
    """0-based element and step indices to plot: the given 1-based ones (checked), or the
    element of largest |slip| over the path and the steps at the path's vertices that the
    run reached, with its last step (a growth run may stop inside the path). Of
    elements whose largest |slip| is equal within the tie rule (the two centre elements of a
    symmetric fault), the lowest numbered (reader.index_of_extreme)."""
    nsteps, count = history["ds"].shape
    if elements is None:
        # nanmax: with growth an element has no slip (NaN) before it was made
        elements = [index_of_extreme(np.nanmax(np.abs(history["ds"]), axis=0)) + 1]
    if steps is None:
        vertices = np.cumsum(np.concatenate([[1], history["leg_steps"]]))
        steps = [int(k) for k in vertices if k < nsteps] + [nsteps]
    for k, limit, what in [(k, count, "element") for k in elements] + \
            [(k, nsteps, "step") for k in steps]:
        if not 1 <= k <= limit:
            raise ResultError(f"{what} {k} is not in 1..{limit}")
    return [k - 1 for k in elements], [k - 1 for k in steps]


def state_names(result):
    """Element state code -> name, from the coding of /elements/state."""
    return coding_of(result, "/elements/state", STATE_NAMES)


def growth_abscissa(result):
    """(axis label, value per /growth record) of the K_eq panel: the load quantity of the
    path (history_parameter) at each record's load step for growth along a load path (a
    load step without growth then takes no room), else the growth step."""
    growth = result["growth"]
    if "load_step" not in growth or result.get("history") is None:
        return "growth step", np.asarray(growth["step"])
    name, load = history_parameter(result["history"])
    label = f"{name}" + unit_label(history_unit(result, name)) + " at the load step"
    return label, np.asarray(load)[np.asarray(growth["load_step"]) - 1]


def growth_series(result):
    """One dict per tip of a growth run, in record order: ``label`` ('<fracture> begin'
    or '... end', the end's name from the coding of /growth/end), ``fracture_id``, ``end``
    and, per record of the tip, ``step``, ``position`` (its abscissa, growth_abscissa),
    ``ratio`` (K_eq / toughness) and ``reason`` (the codes of /growth/reason)."""
    growth = result["growth"]
    position = growth_abscissa(result)[1]
    ends = coding_of(result, "/growth/end")
    toughness = float(growth["attrs"]["toughness"])
    names = {index: f["name"] or f["label"]
             for index, f in enumerate(result["fractures"], start=1)}
    series = []
    keys = list(zip(growth["fracture_id"].tolist(), growth["end"].tolist()))
    for fracture_id, end in dict.fromkeys(keys):
        rows = [i for i, key in enumerate(keys) if key == (fracture_id, end)]
        series.append({
            "label": f"{names.get(fracture_id, fracture_id)} {ends.get(end, end)}",
            "fracture_id": fracture_id, "end": end,
            "step": growth["step"][rows], "position": position[rows],
            "ratio": growth["k_eq"][rows] / toughness,
            "reason": growth["reason"][rows]})
    return series


def trial_curves(result):
    """The trial kinks of a work-criterion growth run (/growth/trials), one dict per tip and
    step in record order: ``label`` ('step <k>, <fracture> <end>'), ``step``, ``record``
    (0-based index of the tip's /growth record), ``angle`` and ``efficiency`` of its solved
    trials sorted by angle (refinement trials among the search's), ``state`` (the codes of
    /growth/trials/trial_state) and ``chosen`` (the applied angle, NaN when the tip did not
    grow). Empty without trials."""
    growth = result["growth"]
    trials = growth.get("trials")
    if trials is None:
        return []
    labels = {record: tip["label"] for tip in growth_series(result)
              for record in _records_of(growth, tip)}
    curves = []
    for record in dict.fromkeys(trials["trial_record"].tolist()):
        rows = np.flatnonzero(trials["trial_record"] == record)
        rows = rows[np.argsort(trials["trial_angle"][rows], kind="stable")]
        index = record - 1
        curves.append({
            "label": f"step {growth['step'][index]}, {labels[index]}",
            "step": int(growth["step"][index]), "record": index,
            "angle": trials["trial_angle"][rows],
            "efficiency": trials["trial_efficiency"][rows],
            "state": trials["trial_state"][rows],
            "chosen": float(growth["angle"][index])})
    return curves


def flaw_trial_curves(result):
    """The trials of the flaws' first cracks (criterion 'work': /growth/initiations/flaw_trials),
    one dict per flaw and check: ``label`` ('step <k>, flaw<p>'), ``angle`` (the crack's
    direction from +x) and ``efficiency`` of its trials sorted by angle (the refinement's among
    the grid's), ``state`` and ``chosen`` (the direction it started in, in [-90, 90), NaN
    when it did not start in that check). Empty without flaw trials."""
    growth = result["growth"]
    trials = growth.get("flaw_trials") if growth is not None else None
    if trials is None:
        return []
    starts = growth["flaw_starts"]
    curves = []
    for step, flaw in dict.fromkeys(zip(trials["step"].tolist(), trials["flaw"].tolist())):
        rows = np.flatnonzero((trials["step"] == step) & (trials["flaw"] == flaw))
        rows = rows[np.argsort(trials["angle"][rows], kind="stable")]
        started = np.flatnonzero((starts["step"] == step) & (starts["flaw"] == flaw))
        curves.append({
            "label": f"step {step}, flaw{flaw}",
            "angle": trials["angle"][rows], "efficiency": trials["efficiency"][rows],
            "state": trials["state"][rows],
            "chosen": (float((starts["angle"][started[0]] + 90.0) % 180.0 - 90.0)
                       if started.size else float("nan"))})
    return curves


def _records_of(growth, tip):
    """0-based indices of the /growth records of one tip of growth_series."""
    return np.flatnonzero((growth["fracture_id"] == tip["fracture_id"])
                          & (growth["end"] == tip["end"])).tolist()


def growth_curves(series):
    """The tips of growth_series grouped by equal K_eq curves (same steps and reasons,
    ratios equal under the tie rule relative to the largest ratio of the run: the wings of
    a symmetric model), so that a tip hidden under another is named; tips whose reasons
    differ (one linked, the other stopped) keep their own curves: one dict per group, in
    the order of its first tip, with ``label`` ('wing begin = end (symmetric)' for the two
    ends of one fracture, 'a end = b begin (equal K_eq)' across fractures, else the tip's
    label), ``tips`` (the members' series) and the first member's ``step``, ``position``,
    ``ratio``, ``reason``."""
    scale = max((float(np.max(np.abs(tip["ratio"]))) for tip in series if tip["ratio"].size),
                default=0.0)
    groups = []
    for tip in series:
        for group in groups:
            first = group["tips"][0]
            if np.array_equal(first["step"], tip["step"]) and np.array_equal(
                    first["reason"], tip["reason"]) and all(
                    is_tie(a, b, scale) for a, b in zip(first["ratio"], tip["ratio"])):
                group["tips"].append(tip)
                break
        else:
            groups.append({"tips": [tip], **{key: tip[key] for key in
                                             ("step", "position", "ratio", "reason")}})
    for group in groups:
        tips = group["tips"]
        if len(tips) == 1:
            group["label"] = tips[0]["label"]
        elif len({tip["fracture_id"] for tip in tips}) == 1:
            name = tips[0]["label"].rsplit(" ", 1)[0]
            ends = " = ".join(tip["label"].rsplit(" ", 1)[-1] for tip in tips)
            group["label"] = f"{name} {ends} (symmetric)"
        else:
            group["label"] = " = ".join(tip["label"] for tip in tips) + " (equal K_eq)"
    return groups


def link_points(result):
    """(n, 2) array of the points where growing tips linked (the coding of /growth/reason
    names it 'linked'; its record is the tip's last): the end of the tip's fracture at
    that end after the link, the point on the other fracture (docs/fracture-growth.md)."""
    growth = result["growth"]
    reasons = coding_of(result, "/growth/reason")
    linked = growth["reason"] == code_of(reasons, "linked") if "linked" in \
        reasons.values() else np.zeros(growth["reason"].size, dtype=bool)
    e = result["elements"]
    points = []
    for fracture_id, end in zip(growth["fracture_id"][linked], growth["end"][linked]):
        fracture = result["fractures"][int(fracture_id) - 1]
        if int(end) == 0:
            k, which = fracture["first"] - 1, "begin"
        else:
            k, which = fracture["last"] - 1, "end"
        points.append((float(e[f"x_{which}"][k]), float(e[f"y_{which}"][k])))
    return np.array(points, dtype=float).reshape(-1, 2)


def element_segments(elements, mask=None):
    """(n, 2, 2) array of element end points (all elements, or those where mask is true)."""
    segments = np.stack([np.column_stack([elements["x_begin"], elements["y_begin"]]),
                         np.column_stack([elements["x_end"], elements["y_end"]])], axis=1)
    return segments if mask is None else segments[mask]


# --------------------------------------------------------------------------- preparing


def element_lengths(elements, first=1, last=None):
    """Lengths of elements first..last (1-based, inclusive) from their end points."""
    sl = slice(first - 1, last)
    return np.hypot(
        elements["x_end"][sl] - elements["x_begin"][sl],
        elements["y_end"][sl] - elements["y_begin"][sl],
    )


def fracture_profile(elements, first, last):
    """Profile data of the elements first..last (1-based, inclusive) of one fracture.

    Returns a dict of 1-D arrays: ``distance`` (at element midpoints, cumulative from the
    begin point of the first element), ``slip`` (= -ds), ``opening`` (= -dn) and
    ``state``.
    """
    sl = slice(first - 1, last)
    lengths = element_lengths(elements, first, last)
    distance = np.cumsum(lengths) - 0.5 * lengths
    return {
        "distance": distance,
        "slip": -np.asarray(elements["ds"][sl], dtype=float),
        "opening": -np.asarray(elements["dn"][sl], dtype=float),
        "state": np.asarray(elements["state"][sl]).astype(int),
    }


def fracture_profiles(result: ResultData) -> list[tuple[dict[str, Any], dict[str, Any]]]:
    """List of (fracture, profile) pairs for every fracture of a loaded result."""
    return [
        (fracture, fracture_profile(result["elements"], fracture["first"], fracture["last"]))
        for fracture in result["fractures"]
    ]


def overview_axis(elements, first=1, last=None):
    """Coordinate of the elements first..last (1-based, inclusive; default all) for the
    all-fractures profile: 'x', or 'y' when they extend further in y than in x (beyond
    the tie rule: equal extents, as of a fault at 45 degrees, give 'x')."""
    sl = slice(first - 1, last)
    xs = np.concatenate([elements["x_begin"][sl], elements["x_end"][sl]])
    ys = np.concatenate([elements["y_begin"][sl], elements["y_end"][sl]])
    if xs.size and index_of_extreme([np.ptp(xs), np.ptp(ys)]) == 1:
        return "y"
    return "x"


def has_dd(result, key):
    """True when some element of the model has a nonzero DD `key` ('ds' or 'dn') under the
    tie rule (|DD| within 1e-9 of the largest |ds| or |dn| of the model counts as 0, as the
    round-off slip of a symmetrically opened crack does), or, for 'dn', when an element is
    open."""
    ds = np.abs(np.asarray(result["elements"]["ds"], dtype=float))
    dn = np.abs(np.asarray(result["elements"]["dn"], dtype=float))
    if ds.size == 0:
        return False
    opened = code_of(state_names(result), "open")
    if key == "dn" and np.any(np.asarray(result["elements"]["state"]) == opened):
        return True
    largest = float(np.max(ds if key == "ds" else dn))
    return not is_tie(largest, 0.0, scale=max(float(np.max(ds)), float(np.max(dn))))


def is_cross_section(result):
    """True when y is the vertical of the model: a half-plane, layers (two bonded
    half-planes), or a stress or pore pressure that changes with y (gravity); otherwise a
    map view."""
    return (result["attrs"].get("domain") in ("half_plane", "bimaterial")
            or any(result["remote_stress_gradient"]) or result["pore_fluid"][1] != 0.0)


def body_outline(result):
    """The vertices (x, y) of a finite body's polygon, None without a body (or for a
    result read before bodies existed)."""
    try:
        body = result["body"]
    except KeyError:
        return None
    if body is None:
        return None
    return body["vertex_x"], body["vertex_y"]


def interface_height(result):
    """The height y of the interface of two bonded half-planes (domain 'bimaterial'), None
    in any other domain."""
    if result["attrs"].get("domain") != "bimaterial":
        return None
    return float(result["attrs"]["interface_y"])


def direction_sense(sx, sy):
    """What positive slip means in a cross-section on an element or fracture of direction
    (sx, sy) (slip_sense)."""
    length = float(np.hypot(sx, sy))
    if is_tie(sx, 0.0, scale=length):
        return "slip > 0: the +x side moves down"
    if is_tie(sy, 0.0, scale=length):
        return "slip > 0: the upper side moves to +x"
    if sx * sy > 0.0:
        return "slip > 0: reverse (hanging wall up), < 0: normal"
    return "slip > 0: normal (hanging wall down), < 0: reverse"


def slip_sense(result, fracture):
    """What positive slip (-Ds > 0: the positive face moves along the element direction
    s) means on a fracture. Map view: right-lateral, whichever way the fracture is drawn
    (on every element of a curved one too). Cross-section (is_cross_section): for a
    dipping fracture reverse (hanging wall up) when s_x s_y > 0, else normal; for a
    vertical one the +x side moving down; for a horizontal one the upper side moving to +x
    (both within the tie rule of the direction's length): direction_sense of the
    end-to-end direction, said only where it holds on every element. Where it does not (a
    grown or curved fracture), the sense of the input's elements when it holds on them,
    said to be theirs, else that the sense varies. Independent of the drawing direction:
    reversing it changes neither Ds nor s_x s_y."""
    if not is_cross_section(result):
        return "slip > 0: right-lateral"
    e = result["elements"]
    sl = slice(fracture["first"] - 1, fracture["last"])
    created = e.get("created_step")
    given = np.ones(e["x_begin"][sl].size, dtype=bool) if created is None else created[sl] == 0
    each = [direction_sense(sx, sy) for sx, sy in zip(e["x_end"][sl] - e["x_begin"][sl],
                                                      e["y_end"][sl] - e["y_begin"][sl])]
    senses = set(each)
    given_senses = {sense for sense, mine in zip(each, given) if mine}
    sx = float(e["x_end"][fracture["last"] - 1] - e["x_begin"][fracture["first"] - 1])
    sy = float(e["y_end"][fracture["last"] - 1] - e["y_begin"][fracture["first"] - 1])
    whole = direction_sense(sx, sy)
    if senses == {whole}:
        return whole
    if len(given_senses) == 1 and not np.all(given):
        return f"{given_senses.pop()} (the input fracture; the grown elements vary)"
    return "slip > 0: the positive face moves along the element direction (the sense varies)"


def tip_rows(result):
    """One dict per crack tip: number, fracture name, element, x, y, k1, k2."""
    tips = result["tips"]
    names = {index: f["name"] or f["label"]
             for index, f in enumerate(result["fractures"], start=1)}
    return [
        {"tip": number, "fracture": names.get(int(fid), str(int(fid))),
         "element": int(element), "x": float(x), "y": float(y), "k1": float(k1),
         "k2": float(k2)}
        for number, (fid, element, x, y, k1, k2) in enumerate(
            zip(tips["fracture_id"], tips["element"], tips["x"], tips["y"], tips["k1"],
                tips["k2"]), start=1)
    ]


def tips_text(result):
    """The tips table as aligned text (what the script prints and writes to _tips.txt)."""
    length = unit_label(result["length_unit"])
    k_unit = unit_label(result["tips"]["k_unit"])
    rows = tip_rows(result)
    width = max([len("fracture")] + [len(row["fracture"]) for row in rows])
    lines = [f"crack tips of {result['path'].name}: stress intensity factors",
             (f"{'tip':>4}  {'fracture':<{width}}  {'element':>7}  {'x' + length:>14}  "
              f"{'y' + length:>14}  {'K_I' + k_unit:>20}  {'K_II' + k_unit:>20}")]
    for row in rows:
        lines.append(f"{row['tip']:>4}  {row['fracture']:<{width}}  {row['element']:>7}  "
                     f"{row['x']:>14.6g}  {row['y']:>14.6g}  {row['k1']:>20.6g}  "
                     f"{row['k2']:>20.6g}")
    if not rows:
        lines.append("(no crack tips: every element end is shared)")
    return "\n".join(lines) + "\n"


def tips_csv(result):
    """The tips table as CSV text, full precision, units in the header."""
    length = unit_label(result["length_unit"])
    k_unit = unit_label(result["tips"]["k_unit"])
    lines = [f"tip,fracture,element,x{length},y{length},K_I{k_unit},K_II{k_unit}"]
    for row in tip_rows(result):
        name = row["fracture"].replace('"', '""')
        lines.append(f"{row['tip']},\"{name}\",{row['element']},{row['x']!r},{row['y']!r},"
                     f"{row['k1']!r},{row['k2']!r}")
    return "\n".join(lines) + "\n"


def grid_fields(result: ResultData) -> list[str]:
    """Names of the fields of kind 'grid', in file order."""
    return [name for name, field in result["fields"].items() if field["kind"] == "grid"]


def surface_lines(result):
    """Names of the fields of kind 'line' lying on the free surface y = 0 of a half-plane
    model, in file order (none in a full-plane model). The points of a &line given at
    y = 0 are exactly 0 (y_begin + t (y_end - y_begin)), hence the exact comparison."""
    if result["attrs"].get("domain") != "half_plane":
        return []
    return [name for name, field in result["fields"].items()
            if field["kind"] == "line" and "y" in field and field["y"].size > 1
            and np.all(field["y"] == 0.0)]


def observation_sets(result):
    """Names of the fields of kind 'line' or 'points' that are not surface lines (those
    have plot_surface), in file order."""
    surface = set(surface_lines(result))
    return [name for name, field in result["fields"].items()
            if field["kind"] in ("line", "points") and name not in surface]


def distance_along(field):
    """Distance of each point from the first, along the points in their order
    [length unit]; a point that is not finite adds nothing."""
    x = np.ravel(np.asarray(field["x"], dtype=float))
    y = np.ravel(np.asarray(field["y"], dtype=float))
    steps = np.hypot(np.diff(x), np.diff(y))
    return np.concatenate([[0.0], np.cumsum(np.where(np.isfinite(steps), steps, 0.0))])


def all_nan(field):
    """True when no point of an observation set has a finite value."""
    return not any(np.any(np.isfinite(np.asarray(field[key], dtype=float)))
                   for key, _, _ in LINE_PANELS)


def figure_base(out_dir, stem, kind, name, used, suffix=""):
    """Path (without extension) of a figure: <stem>_<kind>_<name>[_<suffix>], the name made
    file-safe; the name part is left out when it repeats the kind (a grid named 'map':
    <stem>_map_<quantity>) unless that shorter name is taken. A name already in `used`
    gets _2, _3, ...; used collects the names given."""
    label = re.sub(r"[^A-Za-z0-9_.-]+", "_", name)
    tail = f"_{suffix}" if suffix else ""
    full = f"{stem}_{kind}_{label}{tail}"
    candidates = ([f"{stem}_{kind}{tail}"] if label == kind else []) + [full] + \
        [f"{full}_{k}" for k in range(2, len(used) + 3)]
    base = next(c for c in candidates if c not in used)
    used.add(base)
    return out_dir / base


def as_grid(field, key):
    values = np.asarray(field[key], dtype=float)
    nx, ny = field["nx"], field["ny"]
    if values.ndim == 2:
        return values
    if nx * ny == values.size and nx > 0:
        return values.reshape(ny, nx)
    raise ValueError(f"{key} has shape {values.shape}, expected ({ny}, {nx})")


def resolved_traction(sxx, syy, sxy, angle_deg):
    """Shear and normal traction of a stress on a plane at angle_deg from +x.

    With s = (cos a, sin a) along the plane and n = (-sin a, cos a): returns
    ``(tau, sigma_n) = (s . sigma . n, n . sigma . n)``; tau > 0 drives right-lateral slip
    (the +n side moves along +s), sigma_n is tension positive.
    """
    angle = np.radians(angle_deg)
    c, s = np.cos(angle), np.sin(angle)
    tau = (syy - sxx) * s * c + sxy * (c * c - s * s)
    sigma_n = sxx * s * s + syy * c * c - 2.0 * sxy * s * c
    return tau, sigma_n


class Background:
    """The stress without the fractures at height y: remote + gradient * y (root
    attributes remote_stress and remote_stress_gradient); in two bonded half-planes
    (domain 'bimaterial') above the interface the upper material's (upper_remote)."""

    def __init__(self, remote, gradient=(0.0, 0.0, 0.0), upper=None):
        """upper: (interface_y, remote, gradient) of the upper material of two bonded
        half-planes, None in one material."""
        self.remote = tuple(float(v) for v in remote)
        self.gradient = tuple(float(v) for v in gradient)
        self.upper = upper

    @classmethod
    def of_result(cls, result):
        """The background of a loaded result; None without remote_stress."""
        if result["remote_stress"] is None:
            return None
        upper = None
        if interface_height(result) is not None:
            upper = (interface_height(result), upper_remote(result, result["remote_stress"]),
                     upper_remote(result, result["remote_stress_gradient"]))
        return cls(result["remote_stress"], result["remote_stress_gradient"], upper)

    def stress(self, y=0.0):
        """(sxx, syy, sxy) at height y (scalars or arrays like y)."""
        y = np.asarray(y, dtype=float)
        lower = tuple(r + g * y for r, g in zip(self.remote, self.gradient))
        if self.upper is None:
            return lower
        interface, remote, gradient = self.upper
        return tuple(np.where(y > interface, r + g * y, value)
                     for value, r, g in zip(lower, remote, gradient))

    def varies(self, quantity):
        """True when the background value of a stress quantity changes with y (or across
        the interface of two bonded half-planes)."""
        if self.upper is not None:
            below, above = (stress_quantity(*self.stress(self.upper[0] + d), quantity)
                            for d in (-1.0, 1.0))
            if self.gradient != (0.0, 0.0, 0.0) or float(below) != float(above):
                return True
        g = dict(zip(("sxx", "syy", "sxy"), self.gradient))
        if quantity == "mean":
            return g["sxx"] + g["syy"] != 0.0
        return g.get(quantity, 0.0) != 0.0


def upper_remote(result, lower):
    """The remote stress (or its gradient) of the upper material of two bonded half-planes
    from the lower one's (docs/theory/bimaterial.md#remote-stress): syy and sxy as given,
    sxx such that the plane-strain exx is continuous across the interface."""
    attrs = result["attrs"]
    g_lower, nu_lower = float(attrs["shear_modulus"]), float(attrs["poissons_ratio"])
    nu_upper = float(attrs["upper_poissons_ratio"])
    g_upper = float(attrs["upper_youngs_modulus"]) / (2.0 * (1.0 + nu_upper))
    sxx, syy, sxy = (float(v) for v in lower)
    return ((g_upper / g_lower * ((1 - nu_lower) * sxx - nu_lower * syy) + nu_upper * syy)
            / (1 - nu_upper), syy, sxy)


def stress_quantity(sxx, syy, sxy, name):
    """One of STRESSES from the components."""
    if name == "mean":
        return 0.5 * (sxx + syy)
    return {"sxx": sxx, "syy": syy, "sxy": sxy}[name]


def plane_slip_name(angle_deg, sign, cross_section):
    """What slip of sign `sign` (+1: tau > 0 of resolved_traction, the +n side moving
    along +s) on a plane at angle_deg from +x is called. Map view: right- / left-lateral.
    Cross-section (y up): on a dipping plane reverse when sign * sin(a) cos(a) > 0 (a plane
    rising to +x whose upper side, the hanging wall, moves up-dip), else normal; on a
    horizontal plane (within TIE_RTOL) the upper side moves to +x or -x, on a vertical one
    the +x side moves down or up."""
    if not cross_section:
        return "right-lateral" if sign > 0 else "left-lateral"
    a = np.radians(angle_deg)
    if is_tie(np.sin(a), 0.0, scale=1.0):
        return "the upper side to " + ("+x" if sign > 0 else "-x")
    if is_tie(np.cos(a), 0.0, scale=1.0):
        return "the +x side " + ("down" if sign > 0 else "up")
    return "reverse" if sign * np.sin(a) * np.cos(a) > 0.0 else "normal"


class Receiver:
    """Receiver of the Coulomb stress change: plane angle, friction, slip sense, and the
    background stress the change is taken from."""

    def __init__(self, background, angle_deg=DEFAULT_RECEIVER_ANGLE,
                 friction=DEFAULT_FRICTION, sense="auto", reference_y=0.0,
                 cross_section=False):
        """background: a Background or the remote (sxx, syy, sxy); sense 'right', 'left',
        in a cross-section also 'reverse' or 'normal' on a dipping plane (plane_slip_name),
        or 'auto' (the sense of the background shear traction on the plane at reference_y;
        'right' when it is zero, that is within TIE_RTOL of the largest background
        component there, as on a principal plane). ValueError for a sense the plane cannot
        have. ``sense`` is then 'right' (tau > 0 of resolved_traction) or 'left'."""
        if not isinstance(background, Background):
            background = Background(background)
        self.background = background
        self.angle_deg = float(angle_deg)
        self.friction = float(friction)
        self.reference_y = float(reference_y)
        self.cross_section = bool(cross_section)
        self.auto = sense == "auto"
        if self.auto:
            there = [float(v) for v in background.stress(self.reference_y)]
            tau_there, _ = resolved_traction(*there, self.angle_deg)
            scale = max(abs(v) for v in there)
            sense = "left" if tau_there < -TIE_RTOL * scale else "right"
        elif sense not in SENSES:
            names = {plane_slip_name(self.angle_deg, sign, self.cross_section): name
                     for name, sign in SENSES.items()}
            if sense not in names:
                raise ValueError(f"a receiver at {self.angle_deg:g} deg has no sense '{sense}' "
                                 f"here (it has {', '.join(names)})")
            sense = names[sense]
        self.sense = sense

    def sense_name(self):
        """The receiver's slip sense in words (plane_slip_name): right-/left-lateral in a
        map view, reverse / normal on a dipping plane of a cross-section."""
        return plane_slip_name(self.angle_deg, SENSES[self.sense], self.cross_section)

    def describe(self):
        """One line for figure titles."""
        text = (f"receiver {self.angle_deg:g} deg from +x, {self.sense_name()}, "
                f"mu = {self.friction:g}")
        if self.auto and any(self.background.gradient):
            text += f" (auto: the sense at y = {self.reference_y:g})"
        return text


def coulomb_stress_change(sxx, syy, sxy, receiver, y=0.0):
    """Coulomb stress change sense * d(tau) + mu * d(sigma_n) on the receiver plane.

    The changes are relative to the receiver's background stress at height y (the pore
    pressure is part of it and cancels); sense = +1 for a receiver whose sense is that of
    tau > 0 (right-lateral in a map view; see resolved_traction), -1 for the other.
    """
    bxx, byy, bxy = receiver.background.stress(y)
    d_tau, d_normal = resolved_traction(sxx - bxx, syy - byy, sxy - bxy, receiver.angle_deg)
    return SENSES[receiver.sense] * d_tau + receiver.friction * d_normal


def grid_reference_y(field):
    """Middle height of a grid: the mean y of its finite points (0 without any)."""
    y = np.asarray(field["y"], dtype=float)
    y = y[np.isfinite(y)]
    return float(np.mean(y)) if y.size else 0.0


def on_element_code(field):
    """The near_element code of a field's points on an element (its coding's 'on'; None
    when the file has no coding for it: then only their NaN values mark them)."""
    coding = field.get("codings", {}).get("near_element", {})
    return code_of(coding, "on") if "on" in coding.values() else None


def near_grown(field, elements):
    """Boolean grid (ny, nx) of the points of grid `field` flagged near an element (the
    near_element coding's 'within') that lie within one element length of the centre of an
    element made by growth (/elements/created_step > 0): their accuracy is reduced like
    that of the points near the input's elements, but the grid was not laid out around the
    grown crack, so the map marks them."""
    shape = as_grid(field, "x").shape
    coding = field.get("codings", {}).get("near_element", {})
    created = elements.get("created_step")
    if "within" not in coding.values() or created is None or not np.any(created > 0) \
            or "near_element" not in field:
        return np.zeros(shape, dtype=bool)
    near = np.asarray(field["near_element"]).reshape(shape) == code_of(coding, "within")
    grown = created > 0
    mid_x = 0.5 * (elements["x_begin"] + elements["x_end"])[grown]
    mid_y = 0.5 * (elements["y_begin"] + elements["y_end"])[grown]
    length = element_lengths(elements)[grown]
    x, y = as_grid(field, "x")[..., None], as_grid(field, "y")[..., None]
    close = np.any(np.hypot(x - mid_x, y - mid_y) <= length, axis=-1)
    return near & close


def grid_quantity(field, quantity, receiver=None, background=None):
    """Coordinates and values of a quantity on a grid field.

    Returns ``(x, y, values)``, 2-D arrays shaped (ny, nx); ``values`` is a masked array
    with non-finite values and points flagged on an element (on_element_code) masked.
    'coulomb' needs a Receiver, the induced stresses a Background.
    """
    if quantity not in QUANTITIES:
        raise ValueError(f"unknown quantity '{quantity}'")
    if quantity == "coulomb" and receiver is None:
        raise ValueError("the Coulomb stress change needs a receiver and the remote stress")
    if quantity in INDUCED and background is None:
        raise ValueError(f"{quantity} needs the background (remote) stress")
    x = as_grid(field, "x")
    y = as_grid(field, "y")
    if quantity in STRESSES:
        values = stress_quantity(*(as_grid(field, k) for k in ("sxx", "syy", "sxy")),
                                 quantity)
    elif quantity in INDUCED:
        name = quantity.removeprefix("induced_")
        values = (stress_quantity(*(as_grid(field, k) for k in ("sxx", "syy", "sxy")), name)
                  - stress_quantity(*background.stress(y), name))
    elif quantity == "max_shear":
        values = np.hypot(0.5 * (as_grid(field, "sxx") - as_grid(field, "syy")),
                          as_grid(field, "sxy"))
    elif quantity == "coulomb":
        values = coulomb_stress_change(as_grid(field, "sxx"), as_grid(field, "syy"),
                                       as_grid(field, "sxy"), receiver, y)
    else:
        values = np.hypot(as_grid(field, "ux"), as_grid(field, "uy"))
    mask = ~np.isfinite(values)
    on_element = on_element_code(field)
    if "near_element" in field and on_element is not None:
        mask |= np.asarray(field["near_element"]).reshape(values.shape) == on_element
    return x, y, np.ma.masked_array(values, mask=mask)


def remote_value(result, quantity):
    """The value of a signed quantity without the fractures, the centre of its diverging
    colour map: the remote value of a total stress (0 without remote stress), None when the
    background varies with depth (no single value: the map gets a sequential colour map),
    0 for the changes (coulomb, induced_*)."""
    background = Background.of_result(result)
    if background is None or quantity not in STRESSES:
        return 0.0
    if background.varies(quantity):
        return None
    return float(stress_quantity(*background.stress(0.0), quantity))


def default_clim(values, quantity, centre=0.0):
    """Colour limits from the 2nd and 98th percentiles (fields are singular at tips).

    A signed quantity whose range straddles `centre` (its remote value, see remote_value)
    gets limits symmetric about it, so that the centre of the diverging colour map means
    'as without the fractures'; otherwise (or with centre None: a background that varies)
    the limits follow the data, to keep the contrast.
    Values equal within the tie rule (reader.is_tie) count as equal: a percentile at the
    centre but for rounding (relative to the largest of |low|, |high|, |centre|) does not
    straddle it, and data constant but for rounding get the limits of a constant.
    """
    data = np.ma.compressed(values)
    diverging = quantity in SIGNED_QUANTITIES and centre is not None
    if data.size == 0:
        return (centre - 1.0, centre + 1.0) if diverging else (0.0, 1.0)
    low, high = (float(v) for v in np.percentile(data, [100.0 - CLIM_PERCENTILE,
                                                        CLIM_PERCENTILE]))
    scale = max(abs(low), abs(high), abs(centre or 0.0))
    if diverging and low < centre < high \
            and not is_tie(low, centre, scale) and not is_tie(high, centre, scale):
        top = max(centre - low, high - centre)
        return (centre - top, centre + top)
    if high <= low or is_tie(low, high):
        spread = abs(low) if low != 0.0 else 1.0
        return (low - 0.5 * spread, low + 0.5 * spread)
    return (low, high)


def profile_panels(result):
    """The PROFILE_PANELS a model's profiles show, renumbered from 0: slip when some element
    slips, opening when some element opens (has_dd); slip alone when neither does."""
    keys = [key for _, key, _ in PROFILE_PANELS
            if has_dd(result, "ds" if key == "slip" else "dn")] or ["slip"]
    return tuple((row, key, label) for row, (key, label) in
                 enumerate((key, label) for _, key, label in PROFILE_PANELS if key in keys))


def map_title(result, name, quantity, receiver=None):
    """The title of the map of `quantity` on grid `name`: the quantity, 'tension positive'
    for a signed stress (not for max_shear, never negative, nor for the Coulomb change,
    whose sign is its own), what a change is taken from, the receiver of a Coulomb map
    (Receiver.describe), and what the white of a total stress map is."""
    text = f"grid '{name}': {quantity}"
    if QUANTITY_LABELS[quantity] != COLORBAR_LABELS[quantity]:
        text += f", {QUANTITY_LABELS[quantity]}"
    centre = remote_value(result, quantity)
    if quantity in BACKGROUND_QUANTITIES:
        text += (" (tension positive)" if quantity in INDUCED else "") + \
            f"\n{background_text(result)}"
        if quantity == "coulomb":
            text += f"\n{receiver.describe()}"
    elif quantity in STRESSES:
        text += " (tension positive)"
        if centre is None:
            text += (f"\nthe remote stress varies with depth: for the change see "
                     f"induced_{quantity}")
        elif centre != 0.0:
            text += f"\nwhite: the remote value {centre:g}"
    return heading(result, text)


def background_text(result):
    """What the changes are taken from, for the titles of the change maps."""
    text = "change from the remote stress"
    if any(result["remote_stress_gradient"]):
        text += " + gradient * y"
    if any(result["pore_fluid"]):
        text += " (pore pressure given, unchanged: drained)"
    return text


def map_figure_size(x, y, width=8.0):
    """Figure size (inches) fitting the grid's aspect ratio, plus room for the colour bar
    and the titles; the height is kept between 3.5 and 10 inches."""
    span_x, span_y = np.ptp(x), np.ptp(y)
    aspect = span_y / span_x if span_x > 0.0 and span_y > 0.0 else 1.0
    return (width, float(np.clip((width - 1.8) * aspect + 1.6, 3.5, 10.0)))


def quiver_step(nx, ny):
    """Stride through the grid so that at most QUIVER_MAX_ARROWS arrows fit on a side."""
    return max(1, -(-max(nx, ny) // QUIVER_MAX_ARROWS))


def _fracture_values(result, fracture, key):
    """/elements `key` over the elements of one fracture, as floats."""
    return np.asarray(result["elements"][key][fracture["first"] - 1:fracture["last"]],
                      dtype=float)


def strength_panels(result, fracture):
    """The strength panels of a fracture's profile, drawn below its DDs: (key, axis label,
    unit kind, lines), each line (legend text, values in force, values as given) over the
    fracture's elements (STRENGTH_PANELS). Friction when it weakens with slip (mu_dynamic
    below mu on some element: weakened and intact slipping elements then differ);
    cohesion and tensile strength when it has a tensile strength or a residual cohesion
    below sf; a strength 0 throughout (as given and in force) has no line. None (an empty
    tuple) for Coulomb's law, elastic joints alone, or a file without the strengths in
    force."""
    elements = result["elements"]
    needed = ("mu_in_force", "sf_in_force", "tensile_strength_in_force", "mu", "sf",
              "tensile_strength", "mu_dynamic", "sf_residual")
    if not all(key in elements for key in needed):
        return ()

    def values(key):
        return _fracture_values(result, fracture, key)

    shown = {"friction": bool(np.any(values("mu_dynamic") < values("mu"))),
             "strength": bool(np.any(values("tensile_strength") > 0.0)
                              or np.any(values("sf_residual") < values("sf")))}
    panels = []
    for key, label, unit, lines in STRENGTH_PANELS:
        # A strength that is 0 throughout, given and in force, is left out.
        drawn = tuple((text, values(force), values(given)) for force, given, text in lines
                      if np.any(values(force) != 0.0) or np.any(values(given) != 0.0))
        if shown[key] and drawn:
            panels.append((key, label, unit, drawn))
    return tuple(panels)


def joint_parts(result, fracture, keys):
    """The elastic and plastic parts of the DDs `keys` ('slip', 'opening': the profile
    panels shown) of a fracture of elastic joints (a finite shear_stiffness or
    normal_stiffness): (legend text, values) pairs, elastic = -ds_elastic (-dn_elastic),
    plastic = the total less the elastic part; empty when the fracture has no joint or the
    file no elastic DDs."""
    elements = result["elements"]
    if not all(key in elements for key in ("ds_elastic", "dn_elastic", "shear_stiffness",
                                           "normal_stiffness")):
        return ()
    finite = (np.isfinite(_fracture_values(result, fracture, "shear_stiffness"))
              | np.isfinite(_fracture_values(result, fracture, "normal_stiffness")))
    if not np.any(finite):
        return ()
    lines = []
    for key, total, elastic, text in JOINT_PARTS:
        if key in keys:
            part = -_fracture_values(result, fracture, elastic)
            lines += [(f"elastic {text}", part),
                      (f"plastic {text}", -_fracture_values(result, fracture, total) - part)]
    return tuple(lines)


# --------------------------------------------------------------------------- cycles

#: Seconds per unit of the time labels a cycle's times convert from (others: unconverted).
TIME_SECONDS = {"s": 1.0, "min": 60.0, "h": 3600.0, "day": 86400.0, "yr": 365.25 * 86400.0}
#: A year [s] (365.25 days), the unit of the cycle figures' times.
YEAR_SECONDS = 365.25 * 86400.0
#: Interval of the cumulative slip lines between events [yr] and during them [s].
SLIP_LINES_BETWEEN, SLIP_LINES_DURING = 5.0, 1.0


def cycle_years(cycle, times):
    """Times of a cycle run in years (their unit when it is none of TIME_SECONDS) and the
    unit's name."""
    unit = cycle["attrs"].get("time_unit", "s")
    if unit not in TIME_SECONDS:
        return np.asarray(times, dtype=float), unit
    return np.asarray(times, dtype=float) * TIME_SECONDS[unit] / YEAR_SECONDS, "yr"


def cycle_slip_lines(result):
    """The cumulative slip profiles to draw (docs/plotting.md#earthquake-cycles): the rows
    every SLIP_LINES_BETWEEN years between events and every SLIP_LINES_DURING seconds
    during them (the largest slip rate at least seismic_threshold), as (distance along the
    fault, slip at each, whether seismic), in time order."""
    cycle = result["cycle"]
    unit = cycle["attrs"].get("time_unit", "s")
    seconds = cycle["time"] * TIME_SECONDS.get(unit, 1.0)
    seismic = cycle["max_slip_rate"] >= cycle["attrs"]["seismic_threshold"]
    lines = []
    last = {True: -np.inf, False: -np.inf}
    for k in range(seconds.size):
        step = SLIP_LINES_DURING if seismic[k] else SLIP_LINES_BETWEEN * YEAR_SECONDS
        if seconds[k] - last[bool(seismic[k])] >= step:
            last[bool(seismic[k])] = seconds[k]
            lines.append((cycle["distance"], cycle["slip"][k], bool(seismic[k])))
    return lines


def cycle_catalogue(result):
    """The events of a cycle run as a dict: start, end [yr or the time unit], interval to
    the next start, largest slip, moment per unit length and the hypocentre's distance
    along the fault (that of the recorded element nearest it); the unit of the times."""
    cycle = result["cycle"]
    start, unit = cycle_years(cycle, cycle["event_start"])
    end, _ = cycle_years(cycle, cycle["event_end"])
    # The distance of the element, interpolated between the recorded elements around it
    along = np.interp(cycle["event_element"], cycle["profile"], cycle["distance"])
    return {"start": start, "end": end, "interval": np.diff(start),
            "max_slip": cycle["event_max_slip"], "moment": cycle["event_moment"],
            "hypocentre": along, "unit": unit}
