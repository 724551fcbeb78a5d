"""The figures of ddc2d-plot, drawn with matplotlib from the data of ddc2d.plot.data.

Every ``plot_*`` function returns a matplotlib Figure laid out so that nothing is cut off
at the canvas's edges whatever the grid's aspect (constrained layout; map sizes from
ddc2d.plot.data.map_figure_size); ``save_figure`` writes one. Used by ddc2d-plot
(ddc2d.plot.cli), which describes the figures in its help, and by the user's own code
(through ddc2d.plot). The backend is matplotlib's choice (inline in Jupyter); ddc2d-plot
picks Agg.
"""

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from ..files import atomic_path
from ..reader import ResultData, coding_of
from . import hydraulic
from .data import (
    COLORBAR_LABELS,
    LINE_PANELS,
    SIGNED_QUANTITIES,
    SLIP_LINES_BETWEEN,
    SLIP_LINES_DURING,
    Background,
    Receiver,
    along_fractures,
    as_grid,
    body_outline,
    cycle_catalogue,
    cycle_slip_lines,
    cycle_years,
    default_clim,
    distance_along,
    element_segments,
    flaw_trial_curves,
    fracture_profile,
    fracture_profiles,
    grid_quantity,
    growth_abscissa,
    growth_curves,
    growth_series,
    heading,
    history_parameter,
    history_unit,
    interface_height,
    is_cross_section,
    joint_parts,
    leg_arrows,
    link_points,
    map_figure_size,
    map_title,
    near_grown,
    overview_axis,
    profile_panels,
    quiver_step,
    remote_value,
    same_profiles,
    slip_sense,
    state_names,
    strength_panels,
    trial_curves,
    unit_label,
)
from .injection import (
    closed_form_front,
    front_series,
    moment_series,
    pressure_profile,
    profile_fractures,
    source_positions,
    start_time,
    time_label,
)

#: Marker of each element state, by its name in the coding of /elements/state.
STATE_STYLES = {
    "free": {"color": "tab:gray", "marker": "s"},
    "stick": {"color": "tab:blue", "marker": "o"},
    "slip": {"color": "tab:red", "marker": "^"},
    "open": {"color": "tab:green", "marker": "D"},
}
#: Marker of a state the styles do not know.
OTHER_STATE_STYLE = {"color": "black", "marker": "x"}
#: Space kept free around the edges of a map figure and between its parts [inch].
MAP_PAD = 0.1
#: The overview's legend names the fractures when there are at most this many.
LEGEND_MAX_FRACTURES = 8
#: Opacity of the white veil over map points near a grown element (near_grown).
NEAR_GROWN_ALPHA = 0.5
#: Line styles of the fractures in the all-fractures profile and of the growth tips.
LINESTYLES = ("-", "--", ":", "-.")

#: Colour map of the growth steps (new elements, /elements/created_step).
GROWTH_CMAP = "plasma"
#: Marker and legend text of each growth reason, by its name in the coding of
#: /growth/reason (an open marker for 'subcritical'); a reason not here gets
#: OTHER_REASON_MARKER and its name from the coding.
GROWTH_MARKERS = {"grew": ("o", "grew"), "subcritical": ("o", "subcritical"),
                  "intersection": ("X", "stopped: intersection"),
                  "surface": ("^", "broke through the surface"),
                  "corrector": ("s", "grew at the MTS angle"),
                  "linked": ("P", "stopped: linked"), "closed": ("v", "closed (K_I = 0)"),
                  "waiting": ("D", "waiting"),
                  "enclosing": ("x", "stopped: enclosing"),
                  "interface": ("h", "stopped: interface")}
OTHER_REASON_MARKER = "*"
#: Vertical distance between the end-reason texts of curves ending at one place [points],
#: and how near (a fraction of the data's span on each axis) such ends count as one place.
END_TEXT_STEP = 9
END_NEAR = 0.03
#: Markers of the history profiles, one per chosen step (equal profiles stay visible).
PROFILE_MARKERS = ("o", "s", "^", "v", "D", "x")


def plot_history(result: ResultData, elements: Sequence[int], steps: Sequence[int]) -> Figure:
    """Hysteresis (slip at elements against the load parameter) and slip profiles at
    steps of a loading history; elements and steps are 0-based. Returns the Figure."""
    history = result["history"]
    name, load = history_parameter(history)
    unit = history_unit(result, name)
    slip = -history["ds"]
    fig, (ax_loop, ax_profile) = plt.subplots(1, 2, figsize=(11, 4.5),
                                              constrained_layout=True)
    labelled: set[str] = set()
    for e in elements:
        ax_loop.plot(load, slip[:, e], color="0.3", linewidth=1.0, gid=f"element_{e + 1}",
                     label=f"element {e + 1}")
        _mark_states(ax_loop, load, slip[:, e], history["state"][:, e], state_names(result),
                     labelled, markersize=4)
        _draw_leg_arrows(ax_loop, history, load, slip[:, e], "0.3")
    ax_loop.set_xlabel(f"{name}" + unit_label(unit))
    ax_loop.set_ylabel("slip $-D_s$" + unit_label(result["length_unit"]))
    ax_loop.legend(fontsize="small", loc="best")
    ax_loop.set_title("slip against the load along the path")
    same = same_profiles(slip[steps])
    for index, k in enumerate(steps):
        distance, values = along_fractures(result, slip[k])
        label = f"step {k + 1}: {name} = {load[k]:g}"
        if same[index] is not None:
            label += f" (same as step {steps[same[index]] + 1})"
        ax_profile.plot(distance, values, linewidth=1.0, gid=f"step_{k + 1}", label=label,
                        linestyle=LINESTYLES[index % len(LINESTYLES)], markersize=3,
                        marker=PROFILE_MARKERS[index % len(PROFILE_MARKERS)])
    several = ", each from its begin point" if len(result["fractures"]) > 1 else ""
    ax_profile.set_xlabel(f"distance along the fracture{several}"
                          + unit_label(result["length_unit"]))
    ax_profile.set_ylabel("slip $-D_s$" + unit_label(result["length_unit"]))
    ax_profile.legend(fontsize="small", loc="best")
    ax_profile.set_title("slip profiles at chosen steps")
    for ax in (ax_loop, ax_profile):
        ax.axhline(0.0, color="0.7", linewidth=0.5)
        ax.grid(True, linewidth=0.3)
    fig.suptitle(heading(result, f"loading history ({slip.shape[0]} steps)"))
    return fig


def plot_fronts(result: ResultData) -> Figure:
    """The slip fronts of a fluid injection (docs/plotting.md#fluid-injection): for every
    fracture whose patch slips or opens, where it begins and ends (/history front_begin,
    front_end) against sqrt(t - t0), t0 the first source's start, measured from the
    fracture's first source (its first vertex without one: front_series); the closed form
    +-lambda sqrt(4 alpha (t - t0)) dotted where it applies (closed_form_front), else the
    heading says why not. Returns the Figure."""
    series = front_series(result)
    form, why = closed_form_front(result)
    t0 = start_time(result)
    root = np.sqrt(np.clip(np.asarray(result["history"]["time"], dtype=float) - t0, 0.0, None))
    fig, axes = plt.subplots(max(1, len(series)), 1, sharex=True, squeeze=False,
                             figsize=(7, 2.4 + 2.4 * max(1, len(series))),
                             constrained_layout=True)
    length = unit_label(result["length_unit"])
    for ax, item in zip(axes[:, 0], series):
        for key, colour, style in (("end", "C0", "-"), ("begin", "C1", "--")):
            ax.plot(root, item[key], color=colour, linestyle=style, marker="o", markersize=3,
                    linewidth=1.0, label=f"front at its {key}", gid=f"front_{key}:{item['name']}")
        if form is not None and form["fracture"] == item["fracture"]:
            reach = form["factor"] * np.sqrt(4.0 * form["diffusivity"]) * root
            for sign, label in ((1.0, r"closed form $\pm\lambda\sqrt{4\alpha t}$"),
                                (-1.0, "_closed form")):
                ax.plot(root, sign * reach, color="black", linestyle=":", linewidth=1.0,
                        label=label, gid="closed_form")
        where = (f"from the source '{item['source']}'" if item["source"] is not None
                 else "from its first vertex")
        ax.set_ylabel(f"along '{item['name']}'\n{where}{length}")
        ax.grid(True, linewidth=0.3)
        ax.legend(fontsize="small", loc="best")
    if not series:
        axes[0, 0].text(0.5, 0.5, "no fracture slips", transform=axes[0, 0].transAxes,
                        ha="center", va="center")
    axes[-1, 0].set_xlabel(time_label(result, t0))
    text = "slip fronts: outer ends of the outermost elements that slip or open"
    if form is not None:
        text += (f"\nclosed form: T = {form['parameter']:.4g}, lambda(T) = "
                 f"{form['factor']:.4g}, alpha = {form['diffusivity']:g}")
    else:
        text += f"\nno closed form: {why}"
    fig.suptitle(heading(result, text))
    return fig


def plot_injection(result: ResultData, steps: Sequence[int]) -> Figure:
    """The pressure change (/history/pressure) and the slip (-Ds) along each fracture the
    pressure reaches or that slips (profile_fractures) at steps (from 0), one column per
    fracture, against the distance from its first vertex; the sources as vertical lines,
    and the closed form's pressure dp erfc(|s - s0| / sqrt(4 alpha (t - t0))) dotted where
    the front's closed form applies (closed_form_front). With coupled flow (&fluid) a third
    row: the hydraulic aperture (/history/aperture). Returns the Figure."""
    history = result["history"]
    fractures = profile_fractures(result, list(steps))
    form, _ = closed_form_front(result)
    sources = list(zip(source_positions(result), result["injection"]["name"]))
    coupled = "aperture" in history
    rows = 3 if coupled else 2
    fig, axes = plt.subplots(rows, len(fractures), sharex="col", squeeze=False,
                             figsize=(1.5 + 4.5 * len(fractures), 3.25 * rows),
                             constrained_layout=True)
    time_unit = result["time_unit"]
    for column, index in enumerate(fractures):
        fracture = result["fractures"][index]
        name = fracture["name"] or fracture["label"]
        part = slice(fracture["first"] - 1, fracture["last"])
        distance = fracture_profile(result["elements"], fracture["first"],
                                    fracture["last"])["distance"]
        ax_pressure, ax_slip = axes[:2, column]
        for i, k in enumerate(steps):
            style = {"color": f"C{i % 10}", "linestyle": LINESTYLES[i % len(LINESTYLES)],
                     "linewidth": 1.0}
            label = f"t = {history['time'][k]:g}" + (f" {time_unit}" if time_unit else "")
            ax_pressure.plot(distance, history["pressure"][k, part], label=label,
                             gid=f"pressure:{name}:step_{k + 1}", **style)
            ax_slip.plot(distance, -history["ds"][k, part], label=label,
                         gid=f"slip:{name}:step_{k + 1}", **style)
            if coupled:
                axes[2, column].plot(distance, history["aperture"][k, part], label=label,
                                     gid=f"aperture:{name}:step_{k + 1}", **style)
            if form is not None and form["fracture"] == index:
                ax_pressure.plot(distance, pressure_profile(result, form, distance, k),
                                 color="black", linestyle=":", linewidth=0.8,
                                 label="closed form" if i == 0 else "_closed form",
                                 gid=f"closed_form:step_{k + 1}")
        for (where, arc), source in sources:
            if where == index:
                for ax in axes[:, column]:
                    ax.axvline(arc, color="0.5", linewidth=0.8, linestyle="-.",
                               label=f"source '{source}'", gid=f"source:{source}")
        ax_pressure.set_title(f"'{name}'", fontsize="medium")
        ax_pressure.set_ylabel("pressure change" + unit_label(result["stress_unit"]))
        ax_slip.set_ylabel("slip $-D_s$" + unit_label(result["length_unit"]))
        if coupled:
            axes[2, column].set_ylabel("hydraulic aperture" + unit_label(result["length_unit"]))
        axes[-1, column].set_xlabel("distance from its first vertex"
                                    + unit_label(result["length_unit"]))
        for ax in axes[:, column]:
            ax.axhline(0.0, color="0.7", linewidth=0.5)
            ax.grid(True, linewidth=0.3)
        ax_pressure.legend(fontsize="small", loc="best")
    fig.suptitle(heading(result, "pressure and slip along the fractures at chosen times"))
    return fig


def plot_hydraulic_fracture(result: ResultData) -> Figure:
    """A hydraulic fracture (fluid-driven growth): the half-length to the fronts, the net
    pressure and the opening at the source of each growing fracture that holds a source
    against time on log-log axes, a point per growth step, with the KGD closed forms of the
    total rate: the toughness-dominated solution (dashed) and the viscosity-dominated
    half-length and opening (dotted). Returns the Figure."""
    series = hydraulic.fracture_series(result)
    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.5), constrained_layout=True)
    time_unit = result["time_unit"]
    length, stress = result["length_unit"], result["stress_unit"]
    quantities = (("half_length", "half-length to the fronts", length),
                  ("net_pressure", "net pressure at the source", stress),
                  ("opening", "opening at the source", length))
    for i, fracture in enumerate(series):
        forms = hydraulic.closed_forms(result, fracture["time"])
        for ax, (key, label, unit) in zip(axes, quantities):
            ax.loglog(fracture["time"], fracture[key], marker="o", markersize=2.5,
                      linewidth=0.0, color=f"C{i % 10}", label=f"'{fracture['name']}'",
                      gid=f"{key}:{fracture['name']}")
            if f"toughness_{key}" in forms:
                ax.loglog(fracture["time"], forms[f"toughness_{key}"], color="black",
                          linestyle="--", linewidth=0.9, label="toughness-dominated",
                          gid=f"toughness_{key}:{fracture['name']}")
            if f"viscosity_{key}" in forms:
                ax.loglog(fracture["time"], forms[f"viscosity_{key}"], color="0.4",
                          linestyle=":", linewidth=0.9, label="viscosity-dominated",
                          gid=f"viscosity_{key}:{fracture['name']}")
            ax.set_ylabel(label + unit_label(unit))
    # The axes span the run's points: a regime's solution far from them (the toughness
    # solution of a fracture in the viscosity regime) leaves the view, not squeezes it.
    for ax, (key, _, _) in zip(axes, quantities):
        if not series:
            continue
        values = np.concatenate([np.asarray(f[key], dtype=float) for f in series])
        values = values[np.isfinite(values) & (values > 0.0)]
        if values.size:
            ax.set_ylim(values.min() / 3.0, values.max() * 3.0)
    for ax in axes:
        ax.set_xlabel("time" + unit_label(time_unit))
        ax.grid(True, which="both", linewidth=0.3)
    axes[0].legend(fontsize="small", loc="best")
    fig.suptitle(heading(result, "hydraulic fracture against the KGD closed forms"))
    return fig


def plot_moment(result: ResultData) -> Figure:
    """The seismic moment of every fracture that slips (/history/moment) against the volume
    the sources let in (/history/injected_volume), both per unit length out of the plane, a
    point per step. Returns the Figure."""
    history = result["history"]
    length, stress = result["length_unit"], result["stress_unit"]
    fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
    series = moment_series(result)
    for i, (index, name) in enumerate(series):
        ax.plot(history["injected_volume"], history["moment"][:, index], marker="o",
                markersize=3, linewidth=1.0, color=f"C{i % 10}",
                linestyle=LINESTYLES[i % len(LINESTYLES)], label=name, gid=f"moment:{name}")
    if series:
        ax.legend(fontsize="small", loc="best", title="fracture")
    else:
        ax.text(0.5, 0.5, "no fracture slips", transform=ax.transAxes, ha="center",
                va="center")
    ax.set_xlabel("injected volume per unit length" + unit_label(f"{length}^2" if length
                                                                 else ""))
    ax.set_ylabel("seismic moment per unit length"
                  + unit_label(f"{stress} {length}^2".strip() if length else stress))
    ax.grid(True, linewidth=0.3)
    fig.suptitle(heading(result, f"moment against injected volume "
                                 f"({history['moment'].shape[0]} steps)"))
    return fig


def _draw_leg_arrows(ax, history, x, y, colour):
    """An arrow on the curve (x, y) of one value per step at the middle of each leg of the
    loading history (leg_arrows), pointing the way the path runs: the sense of a curve
    that goes back over itself when the load reverses (gid 'direction'); none where the
    curve has no value yet (an element growth had not made)."""
    for start, stop in leg_arrows(history):
        if not np.all(np.isfinite([x[start], x[stop], y[start], y[stop]])):
            continue
        ax.annotate("", xy=(x[stop], y[stop]), xytext=(x[start], y[start]),
                    arrowprops={"arrowstyle": "-|>", "color": colour,
                                "mutation_scale": 14}).set_gid("direction")


def plot_history_strengths(result: ResultData, elements: Sequence[int]) -> Figure:
    """The strengths in force at elements (0-based) against the load parameter of a loading
    history that records them (/history mu_in_force, sf_in_force,
    tensile_strength_in_force): the friction, and the cohesion and tensile strength.
    Returns the Figure."""
    history = result["history"]
    name, load = history_parameter(history)
    unit = history_unit(result, name)
    fig, (ax_mu, ax_strength) = plt.subplots(1, 2, figsize=(11, 4.5),
                                             constrained_layout=True)
    for i, e in enumerate(elements):
        colour = f"C{i % 10}"
        ax_mu.plot(load, history["mu_in_force"][:, e], color=colour, marker=".",
                   label=f"element {e + 1}", gid=f"mu_in_force:element_{e + 1}")
        ax_strength.plot(load, history["sf_in_force"][:, e], color=colour, marker=".",
                         label=f"cohesion, element {e + 1}", gid=f"sf_in_force:element_{e + 1}")
        ax_strength.plot(load, history["tensile_strength_in_force"][:, e], color=colour,
                         linestyle="--", label=f"tensile strength, element {e + 1}",
                         gid=f"tensile_strength_in_force:element_{e + 1}")
        for ax, key in ((ax_mu, "mu_in_force"), (ax_strength, "sf_in_force"),
                        (ax_strength, "tensile_strength_in_force")):
            _draw_leg_arrows(ax, history, load, history[key][:, e], colour)
    ax_mu.set_ylabel("friction in force")
    ax_strength.set_ylabel("strength in force" + unit_label(result["stress_unit"]))
    for ax in (ax_mu, ax_strength):
        ax.set_xlabel(f"{name}" + unit_label(unit))
        ax.legend(fontsize="small", loc="best")
        ax.grid(True, linewidth=0.3)
    fig.suptitle(heading(result, f"strengths in force along the path ({load.size} steps)"))
    return fig


def plot_growth_history(result: ResultData) -> Figure:
    """The length each tip has grown against the load parameter of a loading history
    (growth along a load path: docs/theory/growth.md#growth-along-a-loading-history). Returns
    the Figure."""
    history = result["history"]
    name, load = history_parameter(history)
    unit = history_unit(result, name)
    fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
    ends = ("begin", "end")
    for t, (fid, end) in enumerate(zip(history["tip_fracture_id"], history["tip_end"])):
        label = f"{result['fractures'][fid - 1]['name']} {ends[end]}"
        # Equal curves (the wings of a symmetric model) stay visible: one style per tip.
        ax.plot(load, history["grown_length"][:, t], marker="o", markersize=3,
                linewidth=1.2, linestyle=LINESTYLES[t % len(LINESTYLES)], color=f"C{t % 10}",
                label=label, gid=f"grown_length:{label}")
        _draw_leg_arrows(ax, history, load, history["grown_length"][:, t], f"C{t % 10}")
    ax.set_xlabel(f"{name}" + unit_label(unit))
    ax.set_ylabel("grown length" + unit_label(result["length_unit"]))
    ax.legend(fontsize="small", loc="best")
    ax.grid(True, linewidth=0.3)
    ax.set_title("growth along the load path (a point per load step)", fontsize="medium")
    fig.suptitle(heading(result, f"growth under a loading history ({load.size} steps)"))
    return fig


def plot_growth_trials(result: ResultData) -> Figure:
    """The efficiency dW_ext / da of every trial kink against its angle (criterion 'work':
    docs/theory/growth.md#the-work-criterion), one line per tip and step (the refinement's
    trials among the search's), the trials that neither open nor slip as crosses, the applied
    angle as a filled marker and the threshold as a dashed line. Returns the Figure."""
    curves = trial_curves(result)
    fig = _trials_figure(result, curves, "trial angle [degree]", "efficiency dW_ext/da",
                         "trial kinks (x: neither opens nor slips; o: applied)")
    fig.suptitle(heading(result, f"work criterion: {len(curves)} searches"))
    return fig


def plot_flaw_trials(result: ResultData) -> Figure:
    """The efficiency of every trial of a flaw's first crack against the crack's direction
    (criterion 'work' with flaw points: docs/fracture-growth.md#new-fractures-inside-the-rock),
    one line per flaw and check, as plot_growth_trials draws a tip's. Returns the Figure."""
    curves = flaw_trial_curves(result)
    fig = _trials_figure(result, curves, "crack direction from +x [degree]",
                         "efficiency dW_ext/L", "flaws' first cracks "
                         "(x: neither opens nor slips; o: started)")
    fig.suptitle(heading(result, f"work criterion: {len(curves)} flaw searches"))
    return fig


def _trials_figure(result, curves, xlabel, ylabel, title):
    """Efficiency against angle of trial curves (trial_curves, flaw_trial_curves): the
    candidates joined, the stuck trials as crosses, the chosen one filled, the work threshold
    dashed."""
    unit = f"{result['stress_unit']} {result['length_unit']}".strip()
    # Under work_mode = 'opening' only opening trials (state 2) are candidates.
    opening_only = result["growth"]["attrs"].get("work_mode") == "opening"
    fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
    for index, curve in enumerate(curves):
        colour = f"C{index % 10}"
        candidate = np.isin(curve["state"], (2,) if opening_only else (1, 2))
        ax.plot(curve["angle"], np.where(candidate, curve["efficiency"], np.nan), marker=".",
                linewidth=1.0, color=colour, linestyle=LINESTYLES[index % len(LINESTYLES)],
                label=curve["label"], gid=f"efficiency:{curve['label']}")
        stuck = curve["state"] == 0
        if np.any(stuck):
            ax.plot(curve["angle"][stuck], curve["efficiency"][stuck], "x", color=colour,
                    linestyle="none")
        chosen = np.abs(curve["angle"] - curve["chosen"]) <= 1e-9
        if np.any(chosen):
            ax.plot(curve["angle"][chosen], curve["efficiency"][chosen], "o", color=colour,
                    markersize=7, linestyle="none", gid=f"chosen:{curve['label']}")
    ax.axhline(float(result["growth"]["attrs"]["work_threshold"]), color="black",
               linestyle="--", linewidth=0.8, label="work_threshold", gid="work_threshold")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel + unit_label(unit))
    ax.legend(fontsize="small", loc="best")
    ax.grid(True, linewidth=0.3)
    ax.set_title(title, fontsize="medium")
    return fig


def _draw_elements(ax, elements):
    """The elements: the input's in black, those created by growth coloured by their step.
    Returns the collection of the grown elements (for a colour bar), or None."""
    created = elements.get("created_step")
    grown = np.zeros(elements["ds"].size, dtype=bool) if created is None else created > 0
    ax.add_collection(LineCollection(element_segments(elements, ~grown), colors="black",
                                     linewidths=1.5, label="elements", gid="elements"),
                      autolim=False)
    if not np.any(grown):
        return None
    steps = created[grown]
    collection = LineCollection(element_segments(elements, grown), cmap=GROWTH_CMAP,
                                linewidths=2.0, label="grown elements", gid="grown_elements")
    collection.set_array(steps.astype(float))
    collection.set_clim(0.5, steps.max() + 0.5)
    ax.add_collection(collection, autolim=False)
    return collection


def plot_growth(result: ResultData) -> Figure:
    """The grown geometry coloured by step, with the points where tips linked and the
    surface y = 0 of a half-plane (left), and K_eq / toughness of every tip (right) against
    the growth step, or against the load along a load path (growth_abscissa), each curve
    ending with its tip's last reason. Returns the Figure."""
    growth = result["growth"]
    elements = result["elements"]
    fig, (ax_map, ax_k) = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    grown = _draw_elements(ax_map, elements)
    links = link_points(result)
    if links.size:
        ax_map.plot(links[:, 0], links[:, 1], linestyle="none", marker="o", markersize=8,
                    markerfacecolor="none", markeredgecolor="tab:red", markeredgewidth=1.5,
                    label="linked here", gid="link_points")
    points = element_segments(elements).reshape(-1, 2)
    half_plane = result["attrs"].get("domain") == "half_plane"
    if half_plane:  # the surface belongs in the view
        points = np.vstack([points, [[points[0, 0], 0.0]]])
    span = np.ptp(points, axis=0).max() or 1.0
    ax_map.set_xlim(points[:, 0].min() - 0.05 * span, points[:, 0].max() + 0.05 * span)
    ax_map.set_ylim(points[:, 1].min() - 0.05 * span, points[:, 1].max() + 0.05 * span)
    if half_plane:
        ax_map.axhline(0.0, color="saddlebrown", linewidth=1.2, label="surface y = 0",
                       gid="surface")
    if links.size or half_plane:
        # Below the panels, not inside the map: where the map has room depends on the
        # geometry, and 'best' does not see the elements (line collections).
        fig.legend(*ax_map.get_legend_handles_labels(), fontsize="small",
                   loc="outside lower left", ncols=3)
    ax_map.set_aspect("equal")
    if grown is not None:
        bar = fig.colorbar(grown, ax=ax_map, label="growth step", shrink=0.8)
        bar.ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax_map.set_xlabel("x" + unit_label(result["length_unit"]))
    ax_map.set_ylabel("y" + unit_label(result["length_unit"]))
    ax_map.set_title("input (black) and grown elements (colour: step)", fontsize="medium")
    reasons = coding_of(result, "/growth/reason")
    used = set()
    ends = []
    # Tips with equal curves (the wings of a symmetric model) share one line, whose label
    # names them all: drawn apart, one would hide the other.
    for index, curve in enumerate(growth_curves(growth_series(result))):
        colour = f"C{index % 10}"
        ax_k.plot(curve["position"], curve["ratio"], color=colour, linewidth=1.2,
                  linestyle=LINESTYLES[index % len(LINESTYLES)],
                  label=curve["label"], gid=f"k_eq:{curve['label']}")
        for code in np.unique(curve["reason"]):
            name = reasons.get(int(code), str(code))
            chosen = curve["reason"] == code
            used.add(name)
            ax_k.plot(curve["position"][chosen], curve["ratio"][chosen], linestyle="none",
                      marker=_reason_style(name)[0], color=colour, markersize=5,
                      markerfacecolor="none" if name == "subcritical" else colour,
                      label="_reason")
        if curve["reason"].size:
            ends.append((curve, colour))
    _mark_end_reasons(ax_k, ends, reasons)
    for name in sorted(used, key=lambda n: list(reasons.values()).index(n)
                       if n in reasons.values() else len(reasons)):  # the markers, in grey
        marker, text = _reason_style(name)
        ax_k.plot([], [], linestyle="none", marker=marker, color="0.4",
                  markerfacecolor="none" if name == "subcritical" else "0.4", label=text)
    ax_k.axhline(1.0, color="0.4", linewidth=0.8, linestyle="--")
    axis_label, _ = growth_abscissa(result)
    if axis_label == "growth step":
        ax_k.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax_k.set_xlabel(axis_label)
    ax_k.set_ylabel("$K_{eq}$ / toughness")
    ax_k.grid(True, linewidth=0.3)
    ax_k.legend(fontsize="small", loc="best")
    attrs = growth["attrs"]
    ax_k.set_title(f"toughness {float(attrs['toughness']):g}; ended: "
                   f"{attrs.get('end_reason', '?')} after {int(attrs['steps_taken'])} "
                   "step(s) with growth", fontsize="medium")
    fig.suptitle(heading(result, "fracture growth"))
    return fig


def _mark_end_reasons(ax, ends, reasons):
    """Write at the end of each K_eq curve (`ends`: (curve, colour) pairs) its tips' last
    reason (named by the coding `reasons`), so that merged-looking curves tell which tip
    linked and which stopped; texts of curves ending within END_NEAR of the data's span of
    one another are stacked."""
    if not ends:
        return
    points = np.array([(c["position"][-1], c["ratio"][-1]) for c, _ in ends], dtype=float)
    every = np.concatenate([np.column_stack([c["position"], c["ratio"]]) for c, _ in ends])
    span = np.ptp(every, axis=0)
    span[span == 0.0] = 1.0
    for k, (curve, colour) in enumerate(ends):
        near = np.all(np.abs(points[:k] - points[k]) <= END_NEAR * span, axis=1)
        last = int(curve["reason"][-1])
        ax.annotate(f"{curve['label']}: {reasons.get(last, str(last))}", points[k],
                    color=colour, fontsize="x-small", textcoords="offset points",
                    xytext=(4, 4 + END_TEXT_STEP * int(np.count_nonzero(near))),
                    gid=f"end_reason:{curve['label']}")


def _reason_style(name):
    """(marker, legend text) of a growth reason by its name (GROWTH_MARKERS; a reason
    they do not know, as a newer file's, gets OTHER_REASON_MARKER and its name)."""
    return GROWTH_MARKERS.get(name, (OTHER_REASON_MARKER, name))


def plot_surface(result: ResultData, name: str) -> Figure:
    """Figure of the surface displacement profile ux, uy against x; returns the Figure."""
    field = result["fields"][name]
    length_unit = result["length_unit"]
    order = np.argsort(field["x"], kind="stable")
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6), constrained_layout=True)
    for ax, key, label in zip(axes, ("uy", "ux"), ("uplift uy", "horizontal ux")):
        ax.plot(field["x"][order], field[key][order], color="C0", linewidth=1.2, gid=key)
        ax.axhline(0.0, color="0.7", linewidth=0.5)
        ax.set_ylabel(label + unit_label(length_unit))
        ax.grid(True, linewidth=0.3)
    axes[-1].set_xlabel("x along the surface y = 0" + unit_label(length_unit))
    fig.suptitle(heading(result, f"surface displacement '{name}'"))
    return fig


def plot_observation_line(result: ResultData, name: str) -> Figure:
    """Figure of ux, uy, sxx, syy, sxy against the distance along an observation line or
    point list (total stress, tension positive; NaN points are gaps)."""
    field = result["fields"][name]
    distance = distance_along(field)
    units = {"length": result["length_unit"], "stress": result["stress_unit"]}
    marker = "o" if distance.size <= 60 else None
    fig, axes = plt.subplots(len(LINE_PANELS), 1, sharex=True, figsize=(8, 10),
                             constrained_layout=True)
    for ax, (key, label, kind) in zip(axes, LINE_PANELS):
        ax.plot(distance, np.ravel(field[key]), color="C0", linewidth=1.2, marker=marker,
                markersize=3, gid=key)
        ax.axhline(0.0, color="0.7", linewidth=0.5)
        ax.set_ylabel(label + unit_label(units[kind]))
        ax.grid(True, linewidth=0.3)
    x, y = np.ravel(field["x"]), np.ravel(field["y"])
    start = f"from ({x[0]:g}, {y[0]:g})"
    if field["kind"] == "points":
        along = f"distance along the points in file order, {start}"
    else:
        along = f"distance along the line {start} to ({x[-1]:g}, {y[-1]:g})"
    axes[-1].set_xlabel(along + unit_label(result["length_unit"]))
    nan = int(np.count_nonzero(~np.isfinite(np.ravel(field["sxx"]))))
    text = f"{field['kind']} '{name}': {distance.size} points, stress tension positive"
    if nan:
        text += f"\n{nan} on an element (NaN: gaps)"
    fig.suptitle(heading(result, text))
    return fig


def _mark_states(ax, position, values, state, names, labelled, markersize=5):
    """Markers by element state (`names`: code -> name, state_names); a state gets a legend
    label once (`labelled`: the names labelled so far)."""
    for code in sorted(names):
        chosen = state == code
        if np.any(chosen):
            name = names[code]
            label = name if name not in labelled else "_" + name
            labelled.add(name)
            ax.plot(position[chosen], values[chosen], linestyle="none",
                    markersize=markersize, label=label,
                    **STATE_STYLES.get(name, OTHER_STATE_STYLE))
    unknown = ~np.isin(state, list(names))
    if np.any(unknown):
        label = "other state" if "other state" not in labelled else "_other state"
        labelled.add("other state")
        ax.plot(position[unknown], values[unknown], linestyle="none", label=label,
                **OTHER_STATE_STYLE)


def _profile_axes(panels):
    """A figure with one axes per profile panel, stacked, sharing x: (Figure, axes)."""
    fig, axes = plt.subplots(len(panels), 1, sharex=True, squeeze=False,
                             figsize=(8, 3.4 + 2.6 * (len(panels) - 1)),
                             constrained_layout=True)
    return fig, axes[:, 0]


def plot_profile(result: ResultData, fracture: dict[str, Any], profile: dict[str, Any]
                 ) -> Figure:
    """Figure with slip (and opening, see profile_panels) along one fracture, saying what
    positive slip means (slip_sense); returns the Figure."""
    length_unit = result["length_unit"]
    panels = profile_panels(result)
    strengths = strength_panels(result, fracture)
    joints = joint_parts(result, fracture, [key for _, key, _ in panels])
    fig, axes = _profile_axes((*panels, *strengths, *((joints,) if joints else ())))
    for row, key, label in panels:
        ax = axes[row]
        ax.plot(profile["distance"], profile[key], color="0.3", linewidth=1.0,
                label="_profile", gid=key)
        _mark_states(ax, profile["distance"], profile[key], profile["state"],
                     state_names(result), set())
        ax.axhline(0.0, color="0.7", linewidth=0.5)
        ax.set_ylabel(label + unit_label(length_unit))
        ax.grid(True, linewidth=0.3)
    axes[0].legend(title="element state", loc="best", fontsize="small")
    _draw_strengths(axes[len(panels):], profile["distance"], strengths, joints, result)
    if panels[0][1] == "slip":
        axes[0].set_title(slip_sense(result, fracture), fontsize="small", loc="left")
    axes[-1].set_xlabel("distance along fracture" + unit_label(length_unit))
    name = fracture["name"] or fracture["label"]
    text = f"fracture '{name}' (elements {fracture['first']}-{fracture['last']})"
    if len(panels) == 1:
        text += "\nno element " + ("opens" if panels[0][1] == "slip" else "slips")
    fig.suptitle(heading(result, text))
    return fig


def _draw_strengths(axes, distance, strengths, joints, result):
    """The panels below a profile's DDs: each strength panel (strength_panels: a line in
    force and a dashed one as given per strength), then the elastic and plastic parts of a
    joint's DDs (joint_parts); one legend each."""
    for ax, (key, label, unit, lines) in zip(axes, strengths):
        for i, (text, in_force, given) in enumerate(lines):
            ax.plot(distance, in_force, color=f"C{i}", linewidth=1.2, marker=".",
                    label=f"{text} in force", gid=f"{key}:{text} in force")
            ax.plot(distance, given, color=f"C{i}", linewidth=0.8, linestyle="--",
                    label=f"{text} as given", gid=f"{key}:{text} as given")
        ax.set_ylabel(label + (unit_label(result[f"{unit}_unit"]) if unit else ""))
    if joints:
        ax = axes[len(strengths)]
        for i, (text, values) in enumerate(joints):
            ax.plot(distance, values, color=f"C{i}", linewidth=1.0,
                    linestyle=LINESTYLES[i % len(LINESTYLES)], label=text, gid=f"joint:{text}")
        ax.axhline(0.0, color="0.7", linewidth=0.5)
        ax.set_ylabel("joint DDs" + unit_label(result["length_unit"]))
    for ax in axes:
        ax.legend(loc="best", fontsize="small")
        ax.grid(True, linewidth=0.3)


def plot_overview(result: ResultData) -> Figure:
    """Slip (and opening, see profile_panels) of every fracture in one figure, each against
    the x or y coordinate of its element midpoints (overview_axis of the fracture: its
    longer extent); one line style per fracture, markers by state; the legend gives each
    fracture's coordinate and, in a cross-section, what its positive slip means (in a map
    view it is right-lateral on every fracture, said once); of more than
    LEGEND_MAX_FRACTURES fractures (a TWODD deck's contour) only the states."""
    elements = result["elements"]
    panels = profile_panels(result)
    fig, axes = _profile_axes(panels)
    names = state_names(result)
    labelled: set[str] = set()
    used_axes = set()
    for index, (fracture, profile) in enumerate(fracture_profiles(result)):
        sl = slice(fracture["first"] - 1, fracture["last"])
        axis = overview_axis(elements, fracture["first"], fracture["last"])
        used_axes.add(axis)
        position = 0.5 * (elements[f"{axis}_begin"][sl] + elements[f"{axis}_end"][sl])
        style = LINESTYLES[index % len(LINESTYLES)]
        label = f"{fracture['name'] or fracture['label']} (against {axis}"
        label += f"; {slip_sense(result, fracture)})" if is_cross_section(result) else ")"
        if len(result["fractures"]) > LEGEND_MAX_FRACTURES:
            label = "_" + label
        for row, key, _ in panels:
            axes[row].plot(position, profile[key], color="0.25", linewidth=1.0,
                           linestyle=style, label=label, gid=f"{key}:{fracture['label']}")
            _mark_states(axes[row], position, profile[key], profile["state"], names,
                         labelled if row == 0 else set(), markersize=3)
    for row, _, label in panels:
        axes[row].axhline(0.0, color="0.7", linewidth=0.5)
        axes[row].set_ylabel(label + unit_label(result["length_unit"]))
        axes[row].grid(True, linewidth=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    states = [i for i, label in enumerate(labels) if label in labelled]
    order = [i for i in range(len(labels)) if i not in states] + states
    title = "fracture (line), element state (marker)"
    if len(result["fractures"]) > LEGEND_MAX_FRACTURES:
        title = "element state"
    axes[0].legend([handles[i] for i in order], [labels[i] for i in order], loc="best",
                   fontsize="small", title=title)
    if not is_cross_section(result) and panels[0][1] == "slip":
        axes[0].set_title(slip_sense(result, result["fractures"][0]), fontsize="small",
                          loc="left")
    coordinate = " or ".join(sorted(used_axes))
    where = ", each fracture along its longer extent" if len(used_axes) > 1 else ""
    axes[-1].set_xlabel(f"{coordinate} of element midpoint{where}"
                        + unit_label(result["length_unit"]))
    fig.suptitle(heading(result, f"all {len(result['fractures'])} fractures"))
    return fig


def plot_map(result: ResultData, name: str, quantity: str,
             clim: Sequence[float] | None = None, receiver: Receiver | None = None) -> Figure:
    """Map of a quantity on grid field `name` with the elements drawn (and displacement
    vectors for 'displacement'); 'coulomb' needs a Receiver. Returns the Figure."""
    field = result["fields"][name]
    background = Background.of_result(result)
    x, y, values = grid_quantity(field, quantity, receiver, background)
    centre = remote_value(result, quantity)
    vmin, vmax = clim if clim is not None else default_clim(values, quantity, centre)
    diverging = quantity in SIGNED_QUANTITIES and centre is not None
    cmap = "RdBu_r" if diverging else "viridis"
    # The compressed layout sizes the axes at their fixed aspect before placing the labels
    # and colour bars (the constrained one cut them off a map taller than wide).
    fig, ax = plt.subplots(figsize=map_figure_size(x, y), layout="compressed")
    # A ConstrainedLayoutEngine, whose set() takes the pads; the stubs know the base class.
    fig.get_layout_engine().set(w_pad=MAP_PAD, h_pad=MAP_PAD)  # type: ignore[union-attr,call-arg]
    mesh = ax.pcolormesh(x, y, values, shading="nearest", cmap=cmap, vmin=vmin, vmax=vmax)
    xlim, ylim = ax.get_xlim(), ax.get_ylim()  # the grid's extent
    near = near_grown(field, result["elements"])
    if np.any(near):  # veiled in white: reduced accuracy
        ax.pcolormesh(x, y, np.ma.masked_array(np.zeros(near.shape), mask=~near),
                      shading="nearest", cmap="Greys", vmin=0.0, vmax=1.0,
                      alpha=NEAR_GROWN_ALPHA, gid="near_grown")
    grown = _draw_elements(ax, result["elements"])
    outline = body_outline(result)
    if outline is not None:  # the finite body's outline: no rock beyond it
        ax.fill(*outline, fill=False, edgecolor="black", linewidth=1.5, gid="body")
    interface = interface_height(result)
    if interface is not None:
        ax.axhline(interface, color="saddlebrown", linestyle="--", linewidth=1.0,
                   gid="interface")
    if quantity == "displacement":
        _draw_vectors(ax, field, x, y, values)
    ax.set_xlim(xlim)  # the view is the grid; elements beyond it are clipped
    ax.set_ylim(ylim)
    ax.set_aspect("equal")
    unit = result["length_unit"] if quantity == "displacement" else result["stress_unit"]
    fig.colorbar(mesh, ax=ax, extend="both", label=COLORBAR_LABELS[quantity] + unit_label(unit))
    if grown is not None:
        bar = fig.colorbar(grown, ax=ax, location="bottom", shrink=0.6, aspect=40,
                           label="growth step of the grown elements")
        bar.ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("x" + unit_label(result["length_unit"]))
    ax.set_ylabel("y" + unit_label(result["length_unit"]))
    ax.set_title(map_title(result, name, quantity, receiver), fontsize="medium")
    return fig


def _draw_vectors(ax, field, x, y, magnitude):
    """Displacement arrows on every quiver_step-th grid point that is not masked."""
    step = quiver_step(x.shape[1], x.shape[0])
    pick = (slice(None, None, step), slice(None, None, step))
    keep = ~np.ma.getmaskarray(magnitude)[pick]
    ux = as_grid(field, "ux")[pick][keep]
    uy = as_grid(field, "uy")[pick][keep]
    if ux.size:
        ax.quiver(x[pick][keep], y[pick][keep], ux, uy, color="white", edgecolor="black",
                  linewidth=0.3, pivot="middle", gid="vectors")


def save_figure(fig: Figure, base: Path, fmt: str, dpi: float) -> Path:
    """Write `fig` to `base` + '.' + fmt (png, pdf or svg) and close it; returns the path."""
    path = base.with_name(base.name + "." + fmt)
    try:
        with atomic_path(path) as temporary:
            fig.savefig(temporary, format=fmt, dpi=dpi)
    finally:
        plt.close(fig)
    return path


# --------------------------------------------------------------------------- cycles


def plot_cycle_slip(result: ResultData) -> Figure:
    """Cumulative slip along the fault (docs/plotting.md#earthquake-cycles): a line every 5
    years between events (blue) and every second during them (red), against the distance
    along the fault from its first vertex. Returns the Figure."""
    lines = cycle_slip_lines(result)
    fig, ax = plt.subplots(figsize=(7.0, 4.5), constrained_layout=True)
    for seismic in (False, True):
        segments = [np.column_stack((d, s)) for d, s, q in lines if q == seismic]
        if segments:
            ax.add_collection(LineCollection(
                segments, colors="tab:red" if seismic else "tab:blue",
                linewidths=0.6 if seismic else 0.8,
                label=f"every {SLIP_LINES_DURING:g} s in events" if seismic else
                f"every {SLIP_LINES_BETWEEN:g} yr between events"))
    ax.autoscale()
    length = result["length_unit"]
    ax.set_xlabel("distance along the fault" + unit_label(length))
    ax.set_ylabel("slip $D_s$" + unit_label(length))
    ax.legend(fontsize="small", loc="upper left")
    ax.grid(True, linewidth=0.3)
    fig.suptitle(heading(result, "cumulative slip"))
    return fig


def plot_cycle_rate(result: ResultData) -> Figure:
    """The largest slip rate on the faults against time, the seismic threshold dashed.
    Returns the Figure."""
    cycle = result["cycle"]
    years, unit = cycle_years(cycle, cycle["time"])
    rate = f"{result['length_unit']}/{cycle['attrs'].get('time_unit', 's')}"
    fig, ax = plt.subplots(figsize=(7.0, 4.0), constrained_layout=True)
    ax.semilogy(years, np.maximum(cycle["max_slip_rate"], np.finfo(float).tiny),
                linewidth=0.8, gid="max_slip_rate")
    ax.axhline(cycle["attrs"]["seismic_threshold"], color="k", linestyle="--", linewidth=0.6,
               label="seismic threshold")
    ax.set_xlabel(f"time [{unit}]")
    ax.set_ylabel("largest slip rate" + unit_label(rate))
    ax.legend(fontsize="small", loc="lower right")
    ax.grid(True, linewidth=0.3)
    fig.suptitle(heading(result, f"{cycle['event_start'].size} events"))
    return fig


def plot_cycle_events(result: ResultData) -> Figure:
    """The catalogue of a cycle run: each event's largest slip against its start time, and
    the time from each event to the next. Returns the Figure."""
    events = cycle_catalogue(result)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.0, 5.5), sharex=True,
                                      constrained_layout=True)
    top.plot(events["start"], events["max_slip"], "o", gid="max_slip")
    top.set_ylabel("largest slip" + unit_label(result["length_unit"]))
    bottom.plot(events["start"][:-1], events["interval"], "s", color="C1", gid="interval")
    bottom.set_ylabel(f"time to the next event [{events['unit']}]")
    bottom.set_xlabel(f"event start [{events['unit']}]")
    for ax in (top, bottom):
        ax.grid(True, linewidth=0.3)
    fig.suptitle(heading(result, f"catalogue: {events['start'].size} events"))
    return fig
