"""The quantities a user reports, gathered from one ddc2d result (ddc2d.reader's dict).

Keys name the quantity, the fracture and the tip or point: `peak_slip/fault`,
`k2/fault/end`, `grown_length/flaw/begin`, `front_half_length/fault`, `sxx/above/3`.
Each value is a Quantity: the
number and, for quantities that move in steps of the discretization, their quantum (one
element length, one growth increment, one load step); None for smooth ones.

Sign conventions are the result file's (docs/output-reference.md#sign-conventions):
slip is the shear DD `ds`, opening `-dn` (positive where a fracture opens); a peak is the
value of largest magnitude, a mean the length-weighted mean over the fracture.

K at a tip that grew is fixed by where its last increment ended: it moves in steps of
what that increment changed, and is quantised by that change (tip_quantities).
"""

import math
from dataclasses import dataclass

import numpy as np

from ..reader import STATE_CODES

#: The end of a fracture a tip is at (the /growth `end` coding: 0 begin, 1 end).
TIP_ENDS = ("begin", "end")
#: Field components reported at &points and &line observation points.
FIELD_COMPONENTS = ("ux", "uy", "sxx", "syy", "sxy")


#: What a relative error of a direction is measured against [degree]: an angle from +x has
#: no size of its own (91 and -89 degrees are equally well resolved).
DIRECTION_SCALE = 180.0


@dataclass(frozen=True)
class Quantity:
    """One value of a level; `quantum` is the step it moves in (None: smooth), `scale`
    what its relative error is measured against (None: its own size)."""

    value: float
    quantum: float | None = None
    scale: float | None = None


def _peak(values):
    # + 0.0: a peak of -0.0 is reported as 0
    return float(values[np.argmax(np.abs(values))]) + 0.0 if values.size else 0.0


def _lengths(elements):
    return np.hypot(elements["x_end"] - elements["x_begin"],
                    elements["y_end"] - elements["y_begin"])


def fracture_quantities(result):
    """Peak and mean slip and opening, slipping and open lengths of every fracture."""
    elements, out = result["elements"], {}
    lengths = _lengths(elements)
    for fracture in result["fractures"]:
        part = slice(fracture["first"] - 1, fracture["last"])
        name, length, state = fracture["label"], lengths[part], elements["state"][part]
        quantum = float(np.max(length))
        for label, values in (("slip", elements["ds"][part]),
                              ("opening", -elements["dn"][part])):
            out[f"peak_{label}/{name}"] = Quantity(_peak(values))
            out[f"mean_{label}/{name}"] = Quantity(float(np.sum(values * length)
                                                         / np.sum(length)))
        for label, code in (("slipping_length", "slip"), ("open_length", "open")):
            value = float(np.sum(length[state == STATE_CODES[code]]))
            out[f"{label}/{name}"] = Quantity(value, quantum)
    return out


def tip_name(result, fracture_id, x, y):
    """`fracture/begin` or `fracture/end` of the tip at (x, y): the end of the fracture's
    polyline it lies nearer to (a one-element fracture has both tips on one element)."""
    fracture, e = result["fractures"][int(fracture_id) - 1], result["elements"]
    first, last = fracture["first"] - 1, fracture["last"] - 1
    to_begin = math.dist((x, y), (e["x_begin"][first], e["y_begin"][first]))
    to_end = math.dist((x, y), (e["x_end"][last], e["y_end"][last]))
    return f"{fracture['label']}/{'begin' if to_begin < to_end else 'end'}"


def last_increment_change(result, fracture_id, end, k1, k2):
    """How far (K_I, K_II) of a tip moved over the tip's last increment: from its /growth
    record of the last step in which it grew (K before that increment) to its next record
    (K after it, where growth stopped), or to the final (k1, k2) where there is none; None
    when the tip never grew or the change is zero."""
    growth = result["growth"]
    mine = np.flatnonzero((growth["fracture_id"] == fracture_id) & (growth["end"] == end))
    grew = mine[growth["length"][mine] > 0.0]
    if not grew.size:
        return None
    before, after = grew[-1], mine[mine > grew[-1]]
    if after.size:
        k1, k2 = growth["k1"][after[0]], growth["k2"][after[0]]
    return float(math.hypot(k1 - growth["k1"][before], k2 - growth["k2"][before])) or None


def tip_quantities(result):
    """K_I and K_II of every tip, quantised at a tip that grew (last_increment_change); with
    growth, each tip's final direction (degrees from +x: its tip element, from the
    element's other end towards the tip)."""
    tips, elements, out = result["tips"], result["elements"], {}
    for index in range(tips["x"].size):
        name = tip_name(result, tips["fracture_id"][index], tips["x"][index],
                        tips["y"][index])
        k1, k2 = float(tips["k1"][index]), float(tips["k2"][index])
        quantum = None
        if result["growth"] is not None:
            quantum = last_increment_change(result, tips["fracture_id"][index],
                                            TIP_ENDS.index(name.rsplit("/", 1)[1]), k1, k2)
        out[f"k1/{name}"] = Quantity(k1, quantum)
        out[f"k2/{name}"] = Quantity(k2, quantum)
        if result["growth"] is not None:
            element = int(tips["element"][index]) - 1
            ends = [(elements["x_begin"][element], elements["y_begin"][element]),
                    (elements["x_end"][element], elements["y_end"][element])]
            tip = np.array([tips["x"][index], tips["y"][index]])
            far = max(ends, key=lambda p: math.dist(p, tip))
            angle = math.degrees(math.atan2(tip[1] - far[1], tip[0] - far[0]))
            out[f"final_direction/{name}"] = Quantity(angle, scale=DIRECTION_SCALE)
    return out


def growth_quantities(result):
    """Grown length of every tip that may grow, quantum the increment (the /growth
    attribute; each record's own length where the increment was left to its default)."""
    growth, out = result["growth"], {}
    if growth is None:
        return out
    for fracture_id, end in sorted(set(zip(growth["fracture_id"].tolist(),
                                           growth["end"].tolist()))):
        mine = (growth["fracture_id"] == fracture_id) & (growth["end"] == end)
        lengths = growth["length"][mine]
        label = result["fractures"][int(fracture_id) - 1]["label"]
        quantum = float(growth["attrs"].get("increment", 0.0) or 0.0)
        if not quantum > 0.0:
            quantum = float(np.max(lengths)) if lengths.size else 0.0
        out[f"grown_length/{label}/{TIP_ENDS[int(end)]}"] = Quantity(
            float(np.sum(lengths)), quantum or None)
    return out


def _load_axis(history):
    """The name and values of the load that varies along the path (the first that does,
    in ddc2d's order); the time where none does and the path has a time axis (an
    injection at constant stress); None else."""
    for name, values in history["loads"].items():
        values = np.asarray(values, dtype=float)
        if values.size and np.ptp(values) > 0.0:
            return name, values
    if "time" in history:
        return "time", np.asarray(history["time"], dtype=float)
    return None


def _at_step(load, step):
    """The load at `step` (0-based) and the load step that reached it."""
    values = load[1]
    quantum = abs(values[step] - values[step - 1]) if step > 0 else abs(values[1] - values[0])
    return Quantity(float(values[step]), float(quantum))


def load_path_quantities(result):
    """Along a load path, the load at which each fracture first slips, first opens and
    first slips or opens whole (every element it has: the failure load), and the load at
    which growth starts; keys carry the load's name (`first_slip_load/fault`, the load in
    the entry `load`). Events that do not happen are left out."""
    history, out, loads = result["history"], {}, {}
    if history is None or (load := _load_axis(history)) is None:
        return out, loads
    state = history["state"]
    for fracture in result["fractures"]:
        part = state[:, fracture["first"] - 1:fracture["last"]]
        made = part >= 0  # -1: an element not made yet (growth along the path)
        slip, opened = part == STATE_CODES["slip"], part == STATE_CODES["open"]
        events = {"first_slip_load": np.any(slip, axis=1),
                  "first_open_load": np.any(opened, axis=1),
                  "whole_failure_load": np.all((slip | opened) | ~made, axis=1)}
        for label, happened in events.items():
            steps = np.flatnonzero(happened)
            if steps.size:
                key = f"{label}/{fracture['label']}"
                out[key], loads[key] = _at_step(load, int(steps[0])), load[0]
    growth = result["growth"]
    if growth is not None and "load_step" in growth:
        grew = growth["load_step"][growth["length"] > 0.0]
        if grew.size:
            out["growth_start_load"] = _at_step(load, int(np.min(grew)) - 1)
            loads["growth_start_load"] = load[0]
    return out, loads


def _front_quantum(lengths, arc, front, outward):
    """The step a front at arc length `front` moves in: the longer of the element it ends
    (the outermost that slips) and the next one outward (`outward` +1 towards the
    fracture's end, -1 towards its first vertex), which it would take next."""
    ends = np.concatenate([[0.0], arc])
    k = int(np.argmin(np.abs(ends - front)))  # the front is the element end ends[k]
    inner = k - 1 if outward > 0 else k  # the element whose outer end it is
    pair = [j for j in (inner, inner + outward) if 0 <= j < lengths.size]
    return float(np.max(lengths[pair]))


def injection_quantities(result):
    """With fluid sources, at the path's last step: the slipping patch of every fracture
    that has one, its half-length (half the distance between its fronts) and where it
    begins and ends along the fracture (/history front_begin, front_end: the outer ends of
    the outermost elements that slip or open), quantised: the fronts move by whole
    elements, the quantum of each the longer of its element and the next one outward (of
    the half-length the larger of the two fronts'); the fracture's seismic moment (smooth,
    where it has one) and the injected volume (smooth)."""
    history, out = result["history"], {}
    if history is None or "front_begin" not in history:
        return out
    all_lengths = _lengths(result["elements"])
    for index, fracture in enumerate(result["fractures"]):
        name = fracture["label"]
        begin, end = (float(history[key][-1, index]) for key in ("front_begin", "front_end"))
        if math.isfinite(begin):
            lengths = all_lengths[fracture["first"] - 1:fracture["last"]]
            arc = np.cumsum(lengths)
            quanta = (_front_quantum(lengths, arc, begin, -1),
                      _front_quantum(lengths, arc, end, +1))
            out[f"front_half_length/{name}"] = Quantity(0.5 * (end - begin), max(quanta))
            out[f"front_begin/{name}"] = Quantity(begin, quanta[0])
            out[f"front_end/{name}"] = Quantity(end, quanta[1])
        moment = float(history["moment"][-1, index])
        if moment != 0.0:
            out[f"moment/{name}"] = Quantity(moment)
    out["injected_volume"] = Quantity(float(history["injected_volume"][-1]))
    return out


def field_quantities(result):
    """Displacements and stresses at every point of the &points and &line sets (points on
    an element, NaN, are left out)."""
    out = {}
    for name, field in result["fields"].items():
        if field["kind"] not in ("points", "line"):
            continue
        for component in FIELD_COMPONENTS:
            for index, value in enumerate(np.ravel(field[component]), start=1):
                if math.isfinite(value):
                    out[f"{component}/{name}/{index}"] = Quantity(float(value))
    return out


def gather(result):
    """Every quantity of a result (key -> Quantity) and, for loads, the name of the load
    (key -> e.g. 'sxy')."""
    path, loads = load_path_quantities(result)
    quantities = {**fracture_quantities(result), **tip_quantities(result),
                  **growth_quantities(result), **path, **injection_quantities(result),
                  **field_quantities(result)}
    return quantities, loads
