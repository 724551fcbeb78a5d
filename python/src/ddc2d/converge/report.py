"""The table and the figure of a convergence study (ddc2d.converge.study's dict)."""

from pathlib import Path

#: The figure of the study in the output folder.
FIGURE_FILE = "convergence.png"
#: Field quantities (at &points and &line points) are many: the figure leaves them out.
FIELD_PREFIXES = ("ux/", "uy/", "sxx/", "syy/", "sxy/")


def _number(value, digits=6):
    return "-" if value is None else f"{value:.{digits}g}"


def table(study):
    """The study as text: one row per quantity, values coarse to fine, observed order,
    extrapolated value, error estimate of level 0 and verdict (quantum for quantised)."""
    lengths = ", ".join(_number(h, 4) for h in study["element_length"])
    lines = [(f"{study['model']}: {study['levels']} levels ({', '.join(study['refined'])} "
              f"refined; element length {lengths}), tolerance {study['tolerance']:g}")]
    header = ["quantity", *(f"level {k}" for k in range(study["levels"])), "order",
              "extrapolated", "error (level 0)", "verdict"]
    rows = [header]
    for key, entry in study["quantities"].items():
        name = key + (f" [{entry['load']}]" if "load" in entry else "")
        verdict = entry["verdict"]
        if "quantum" in entry:
            verdict += f" (quantum {_number(entry['quantum'][-1], 4)})"
        rows.append([name, *(_number(v) for v in entry["values"]),
                     _number(entry["order"], 3), _number(entry["extrapolated"], 8),
                     _number(entry["error_estimate"], 3), verdict])
    widths = [max(len(row[c]) for row in rows) for c in range(len(header))]
    for row in rows:
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip())
    return "\n".join(lines)


def _errors(entry):
    """Relative distance of every level from the limit (the extrapolated value, else the
    finest level for a quantised quantity); None when there is none to draw."""
    values = entry["values"]
    if any(v is None for v in values):
        return None
    limit = entry["extrapolated"] if "quantum" not in entry else values[-1]
    if limit is None:
        return None
    scale = max(abs(limit), max(abs(v) for v in values))
    errors = [abs(v - limit) / scale if scale > 0 else 0.0 for v in values]
    return errors if any(e > 0.0 for e in errors) else None


def draw_figure(study, out_dir):
    """convergence.png in out_dir: the relative error of every quantity (fields apart)
    against the element length, log-log, with slopes 1 and 2; returns its path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 6), constrained_layout=True)
    lengths = study["element_length"]
    drawn = 0
    for key, entry in study["quantities"].items():
        errors = _errors(entry)
        if key.startswith(FIELD_PREFIXES) or errors is None:
            continue
        points = [(h, e) for h, e in zip(lengths, errors) if e > 0.0]
        style = "--" if "quantum" in entry else "-"
        ax.loglog(*zip(*points), style, marker="o", label=f"{key} ({entry['verdict']})")
        drawn += 1
    if drawn:
        tops = [line.get_ydata()[0] for line in ax.get_lines()]
        top = max(tops)
        for order, dash in ((1, ":"), (2, "-.")):
            ax.loglog(lengths, [top * (h / lengths[0]) ** order for h in lengths], dash,
                      color="0.5", label=f"slope {order}")
    ax.set_xlabel("element length")
    ax.set_ylabel("relative distance from the limit (extrapolated; quantised: finest)")
    ax.set_title(f"{Path(study['model']).name}: convergence")
    ax.grid(True, which="both", linewidth=0.3)
    if drawn:
        ax.legend(fontsize="x-small", loc="best")
    path = Path(out_dir) / FIGURE_FILE
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def verdict_counts(study):
    """How many quantities got each verdict."""
    counts = {}
    for entry in study["quantities"].values():
        counts[entry["verdict"]] = counts.get(entry["verdict"], 0) + 1
    return counts

