"""The figures of ddc2d-plot as a reader sees them: nothing cut off at the canvas's edges
whatever the grid's aspect, growth tips that hide each other named in the legend, integer
step ticks, Coulomb receivers of a cross-section named reverse / normal, titles that say
what the quantity is, and element states read from the file's coding."""

import io

import h5py
import numpy as np
import pytest

from conftest import NEAR_ELEMENT_CODING, solve_text, write_result
from ddc2d.plot import data as plot_data
from ddc2d.plot import figures as plot_figures
from ddc2d.reader import load_result


def with_grid(path, x_range, y_range, shape=(15, 13), half_plane=False, grown=False):
    """The synthetic result (conftest) with its grid replaced by one over x_range, y_range
    (shape (ny, nx)); for half_plane the root attribute domain says so (y up, y <= 0);
    grown: fracture B's elements were created by growth steps 1 to 3 (the maps then have
    a second colour bar, below the map)."""
    write_result(path)
    x, y = np.meshgrid(np.linspace(*x_range, shape[1]), np.linspace(*y_range, shape[0]))
    with h5py.File(path, "r+") as f:
        if grown:
            f["elements"].create_dataset("created_step",
                                         data=np.array([0, 0, 0, 0, 1, 2, 3], dtype=np.int32))
        grid = f["fields/grid1"]
        grid.attrs["nx"], grid.attrs["ny"] = np.int32(shape[1]), np.int32(shape[0])
        values = {"x": x, "y": y, "ux": 1e-3 * x, "uy": -2e-3 * y, "sxx": -10.0 + 0.1 * x * y,
                  "syy": -5.0 - 0.2 * y, "sxy": 0.5 * np.sin(x),
                  "near_element": np.zeros(shape, dtype=np.int32)}
        for key, value in values.items():
            coding = grid[key].attrs.get("coding")
            del grid[key]
            grid.create_dataset(key, data=value)
            if coding is not None:
                grid[key].attrs["coding"] = coding
        if half_plane:
            f.attrs["domain"] = np.bytes_(b"half_plane")
    return path


def assert_inside_the_canvas(fig):
    """Save the figure, then: its tight bounding box (every text and artist drawn) lies
    within the canvas."""
    fig.savefig(io.BytesIO(), format="png", dpi=60)
    box = fig.get_tightbbox(fig.canvas.get_renderer())
    canvas = fig.bbox_inches
    assert box.x0 >= canvas.x0 and box.y0 >= canvas.y0, (box, canvas)
    assert box.x1 <= canvas.x1 and box.y1 <= canvas.y1, (box, canvas)


GRIDS = {
    "tall": {"x_range": (0.0, 6.0), "y_range": (-7.0, 0.0)},  # 6 x 7 m, minus signs on y
    "wide": {"x_range": (-50.0, 50.0), "y_range": (-2.0, 2.0)},
    "section": {"x_range": (-150.0, 150.0), "y_range": (-500.0, 0.0), "half_plane": True},
}


@pytest.mark.parametrize("grown", [False, True])
@pytest.mark.parametrize("grid", sorted(GRIDS))
@pytest.mark.parametrize("quantity", ["max_shear", "syy", "coulomb", "induced_mean",
                                      "displacement"])
def test_maps_fit_the_canvas_whatever_the_aspect(tmp_path, grid, quantity, grown):
    result = load_result(with_grid(tmp_path / f"{grid}.h5", **GRIDS[grid], grown=grown))
    receiver = plot_data.Receiver(plot_data.Background.of_result(result), 30.0,
                                  cross_section=plot_data.is_cross_section(result))
    fig = plot_figures.plot_map(result, "grid1", quantity, receiver=receiver)
    try:
        assert_inside_the_canvas(fig)
        assert fig.axes[0].get_ylabel() == "y [km]"
    finally:
        plot_figures.plt.close(fig)


def test_the_other_figures_fit_the_canvas(result_file):
    result = load_result(result_file)
    figures = [plot_figures.plot_profile(result, *pair)
               for pair in plot_data.fracture_profiles(result)]
    figures += [plot_figures.plot_overview(result),
                plot_figures.plot_observation_line(result, "line1")]
    try:
        for fig in figures:
            assert_inside_the_canvas(fig)
    finally:
        for fig in figures:
            plot_figures.plt.close(fig)


def test_a_long_title_goes_on_a_line_of_its_own():
    result = {"title": "Surface-breaking thrust fault with friction and pore pressure"}
    text = "fracture 'thrust' (elements 1-240)"
    assert plot_data.heading(result, text) == f"{result['title']}\n{text}"
    assert plot_data.heading({"title": "short"}, text) == f"short: {text}"


# ------------------------------------------------------------------ titles


def test_max_shear_is_not_titled_tension_positive(result_file):
    result = load_result(result_file)
    for quantity, signed in (("max_shear", False), ("sxx", True), ("induced_syy", True),
                             ("displacement", False)):
        title = plot_data.map_title(result, "grid1", quantity)
        assert ("(tension positive)" in title) == signed, title
    fig = plot_figures.plot_map(result, "grid1", "max_shear")
    try:
        assert "tension positive" not in fig.axes[0].get_title()
        assert fig.axes[1].get_ylabel() == "max. shear stress [MPa]"  # the colour bar
    finally:
        plot_figures.plt.close(fig)


@pytest.mark.parametrize("angle, sense, words", [
    (30.0, "right", "reverse"), (30.0, "left", "normal"), (150.0, "right", "normal"),
    (-30.0, "left", "reverse"), (0.0, "right", "the upper side to +x"),
    (90.0, "right", "the +x side down"),
])
def test_a_coulomb_map_of_a_section_names_reverse_or_normal(tmp_path, angle, sense, words):
    """In a half-plane (x horizontal, y up) tau > 0 on a plane rising to +x moves its
    upper side (the hanging wall) up-dip: reverse; the names follow slip_sense's."""
    result = load_result(with_grid(tmp_path / "section.h5", **GRIDS["section"]))
    background = plot_data.Background.of_result(result)
    receiver = plot_data.Receiver(background, angle, 0.6, sense, cross_section=True)
    fig = plot_figures.plot_map(result, "grid1", "coulomb", receiver=receiver)
    try:
        title = fig.axes[0].get_title()
        assert f"receiver {angle:g} deg from +x, {words}, mu = 0.6" in title
        assert "lateral" not in title
    finally:
        plot_figures.plt.close(fig)
    # The same sense asked for by its name: --sense reverse / normal.
    if words in ("reverse", "normal"):
        named = plot_data.Receiver(background, angle, 0.6, words, cross_section=True)
        assert named.sense == sense
    with pytest.raises(ValueError, match="has no sense 'reverse'"):
        plot_data.Receiver(background, angle, 0.6, "reverse", cross_section=False)


def test_a_map_view_receiver_stays_lateral(result_file):
    result = load_result(result_file)
    receiver = plot_data.Receiver(plot_data.Background.of_result(result), 30.0, 0.6, "left")
    assert "left-lateral" in plot_data.map_title(result, "grid1", "coulomb", receiver)


# ------------------------------------------------------------------ codings


def test_states_are_named_by_the_files_coding(result_file):
    """A file whose state coding numbers the states otherwise is drawn by its own names:
    the markers follow the coding, not numbers known to the script."""
    with h5py.File(result_file, "r+") as f:
        f["elements/state"].attrs["coding"] = np.bytes_(b"0 open, 1 slip, 2 stick, 3 free")
    result = load_result(result_file)
    assert plot_data.state_names(result) == {0: "open", 1: "slip", 2: "stick", 3: "free"}
    fracture, profile = plot_data.fracture_profiles(result)[0]  # states 1 2 3 2
    fig = plot_figures.plot_profile(result, fracture, profile)
    try:
        markers = {line.get_label(): line.get_xdata().size for line in fig.axes[0].get_lines()
                   if not line.get_label().startswith("_")}
        assert markers == {"slip": 1, "stick": 2, "free": 1}
    finally:
        plot_figures.plt.close(fig)


def test_points_on_an_element_follow_the_near_element_coding(result_file):
    with h5py.File(result_file, "r+") as f:
        f["fields/grid1/near_element"].attrs["coding"] = np.bytes_(b"0 clear, 1 on an element")
    field = load_result(result_file)["fields"]["grid1"]
    flagged = np.asarray(field["near_element"]) == 1  # the conftest's 'near' point
    _, _, sxx = plot_data.grid_quantity(field, "sxx")
    assert np.all(np.ma.getmaskarray(sxx)[flagged])


# ------------------------------------------------------------------ growth

# A crack alone under remote shear: its two tips are point-symmetric, so their K_eq curves
# are the same.
SYMMETRIC_WINGS = """\
&model title = 'wings', youngs_modulus = 50000, poissons_ratio = 0.25 /
&remote_stress sxy = 10 /
&fracture name = 'crack', x = -1, 1, y = 0, 0, elements = 20, condition = 'traction' /
&growth steps = 2, toughness = 10 /
"""


@pytest.fixture(scope="module")
def symmetric_growth(tmp_path_factory):
    return load_result(solve_text(tmp_path_factory.mktemp("symmetric"), "wings",
                                  SYMMETRIC_WINGS))


def test_tips_with_equal_curves_are_named_together(symmetric_growth):
    series = plot_data.growth_series(symmetric_growth)
    assert [tip["label"] for tip in series] == ["crack begin", "crack end"]
    curves = plot_data.growth_curves(series)
    assert [curve["label"] for curve in curves] == ["crack begin = end (symmetric)"]
    fig = plot_figures.plot_growth(symmetric_growth)
    try:
        k_axes = fig.axes[1]
        labels = [text.get_text() for text in k_axes.get_legend().get_texts()]
        assert labels[0] == "crack begin = end (symmetric)"
        assert "crack begin" not in labels and "crack end" not in labels
        # Two steps: the step axis has integer ticks only.
        ticks = [t for t in k_axes.get_xticks() if k_axes.get_xlim()[0] <= t
                 <= k_axes.get_xlim()[1]]
        assert ticks and all(float(t).is_integer() for t in ticks), ticks
        assert_inside_the_canvas(fig)
    finally:
        plot_figures.plt.close(fig)


def test_tips_with_different_curves_keep_their_own_lines():
    steps = np.array([1, 2])
    series = [{"label": "a begin", "fracture_id": 1, "step": steps, "position": steps,
               "ratio": np.array([1.2, 1.1]), "reason": np.zeros(2)},
              {"label": "a end", "fracture_id": 1, "step": steps, "position": steps,
               "ratio": np.array([1.2, 1.1 * (1 + 1e-6)]), "reason": np.zeros(2)},
              {"label": "b end", "fracture_id": 2, "step": steps, "position": steps,
               "ratio": np.array([1.2, 1.1 * (1 + 1e-12)]), "reason": np.zeros(2)},
              # equal K_eq, but this tip linked where 'a begin' grew: a curve of its own
              {"label": "b begin", "fracture_id": 2, "step": steps, "position": steps,
               "ratio": np.array([1.2, 1.1]), "reason": np.array([0, 5])}]
    labels = [curve["label"] for curve in plot_data.growth_curves(series)]
    assert labels == ["a begin = b end (equal K_eq)", "a end", "b begin"]


# The reasons as ddc2d codes them, with a code this version of the plots does not know:
# the figure names it from the coding all the same.
REASON_CODING = ("0 grew, 1 subcritical, 2 intersection, 3 surface, 4 corrector failed (grew "
                 "at mts_angle), 5 linked (ends on another fracture), 6 closed (the kink "
                 "closes, K_I = 0), 7 waiting (critical, not the most critical), 8 enclosing "
                 "(a second link would enclose a block)")


def with_growth(path, half_plane=False, load_path=False):
    """The synthetic result (conftest, fracture A from (-1, 0) to (1, 0), B from (0, 1) to
    (0.3, 2.4)) as a growth run of two steps: both tips of A grow in step 1 with equal K_eq;
    in step 2, still equal, A's begin stops at an intersection, its end links (A ends at
    (1, 0)); B's begin stops in step 2 by reason 8. load_path: the steps were taken at load
    steps 2 and 4 of a path of syy -10, -20, -30, -40 (one leg)."""
    write_result(path)
    with h5py.File(path, "r+") as f:
        f["elements"].create_dataset("created_step",
                                     data=np.array([0, 0, 0, 0, 1, 2, 2], dtype=np.int32))
        records = {"step": [1, 1, 1, 2, 2, 2], "fracture_id": [1, 1, 2, 1, 1, 2],
                   "end": [0, 1, 0, 0, 1, 0], "k_eq": [3.0, 3.0, 2.5, 2.0, 2.0, 1.5],
                   "reason": [0, 0, 0, 2, 5, 8]}
        growth = f.create_group("growth")
        for key in ("x", "y", "k1", "k2", "mts_angle", "angle", "k2_after", "length"):
            growth.create_dataset(key, data=np.zeros(6))
        growth.create_dataset("corrections", data=np.zeros(6, dtype=np.int32))
        for key, value in records.items():
            growth.create_dataset(key, data=np.array(value, dtype=float if key == "k_eq"
                                                     else np.int32))
        growth["reason"].attrs["coding"] = np.bytes_(REASON_CODING.encode())
        growth["end"].attrs["coding"] = np.bytes_(b"0 begin, 1 end")
        for key, value in {"toughness": 1.0, "steps_taken": np.int32(2),
                           "end_reason": np.bytes_(b"arrested"),
                           "reason_coding": np.bytes_(REASON_CODING.encode())}.items():
            growth.attrs[key] = value
        if load_path:
            growth.create_dataset("load_step", data=np.array([2, 2, 2, 4, 4, 4],
                                                             dtype=np.int32))
            history = f.create_group("history")
            history.create_dataset("syy", data=np.array([-10.0, -20.0, -30.0, -40.0]))
            for key in ("ds", "dn"):
                history.create_dataset(key, data=np.zeros((4, 7)))
            history.create_dataset("state", data=np.ones((4, 7), dtype=np.int32))
            history.create_dataset("leg_steps", data=np.array([3], dtype=np.int32))
        if half_plane:
            f.attrs["domain"] = np.bytes_(b"half_plane")
    return path


def lines_by_gid(ax):
    return {line.get_gid(): line for line in ax.get_lines() if line.get_gid()}


def test_which_tip_linked_and_which_stopped_is_drawn(tmp_path):
    result = load_result(with_growth(tmp_path / "grown.h5"))
    fig = plot_figures.plot_growth(result)
    try:
        ax_map, ax_k = fig.axes[0], fig.axes[1]
        # A's tips: equal K_eq, but one linked and one stopped: a curve each.
        curves = [gid for gid in lines_by_gid(ax_k) if gid.startswith("k_eq:")]
        assert curves == ["k_eq:fault A begin", "k_eq:fault A end", "k_eq:B begin"]
        ends = {text.get_gid(): text.get_text() for text in ax_k.texts}
        assert ends == {"end_reason:fault A begin": "fault A begin: intersection",
                        "end_reason:fault A end": "fault A end: linked",
                        "end_reason:B begin": "B begin: enclosing"}
        # The two texts at one curve end are stacked, not drawn over each other.
        offsets = sorted(text.xyann[1] for text in ax_k.texts if "fault A" in text.get_gid())
        assert offsets[1] - offsets[0] == plot_figures.END_TEXT_STEP
        # Reason 8 is in the legend; a reason the marker table does not know (a newer
        # file's) would be there by its coding's name, with the marker of the unknown.
        legend = [text.get_text() for text in ax_k.get_legend().get_texts()]
        assert "stopped: enclosing" in legend and "stopped: linked" in legend
        assert plot_figures._reason_style("melted") == (plot_figures.OTHER_REASON_MARKER,
                                                        "melted")
        # The link point: the end of fracture A, (1, 0).
        link = lines_by_gid(ax_map)["link_points"]
        np.testing.assert_array_equal(np.column_stack([link.get_xdata(), link.get_ydata()]),
                                      [[1.0, 0.0]])
        assert "surface" not in lines_by_gid(ax_map)  # a full plane has none
        assert ax_k.get_xlabel() == "growth step"
    finally:
        plot_figures.plt.close(fig)


def test_the_half_plane_growth_panel_draws_the_surface(tmp_path):
    result = load_result(with_growth(tmp_path / "section.h5", half_plane=True))
    fig = plot_figures.plot_growth(result)
    try:
        ax_map = fig.axes[0]
        surface = lines_by_gid(ax_map)["surface"]
        np.testing.assert_array_equal(surface.get_ydata(), [0.0, 0.0])
        low, high = ax_map.get_ylim()
        assert low < 0.0 < high  # in view, though every element lies above it here
    finally:
        plot_figures.plt.close(fig)


def test_growth_along_a_load_path_is_drawn_against_the_load(tmp_path):
    result = load_result(with_growth(tmp_path / "path.h5", load_path=True))
    fig = plot_figures.plot_growth(result)
    try:
        ax_k = fig.axes[1]
        assert ax_k.get_xlabel() == "syy [MPa] at the load step"
        line = lines_by_gid(ax_k)["k_eq:fault A begin"]
        # growth steps 1 and 2 at load steps 2 and 4: syy -20 and -40, the values stored
        np.testing.assert_array_equal(line.get_xdata(), [-20.0, -40.0])
        np.testing.assert_array_equal(line.get_ydata(), [3.0, 2.0])
    finally:
        plot_figures.plt.close(fig)


def test_map_points_near_a_grown_element_are_veiled(tmp_path):
    path = with_grid(tmp_path / "near.h5", (-1.0, 1.0), (0.0, 3.0), shape=(7, 5), grown=True)
    with h5py.File(path, "r+") as f:  # grid x -1, -0.5, .., 1; y 0, 0.5, .., 3
        near = np.ones((7, 5), dtype=np.int32)  # every point flagged near
        near[0, 0] = 0
        del f["fields/grid1/near_element"]
        f["fields/grid1"].create_dataset("near_element", data=near)
        f["fields/grid1/near_element"].attrs["coding"] = np.bytes_(
            NEAR_ELEMENT_CODING.encode())
    result = load_result(path)
    # Grown: B's elements, centres (0.15, 1.2), (0.3, 1.65), (0.3, 2.15), each 0.5 long.
    centres = np.array([[0.15, 1.2], [0.3, 1.65], [0.3, 2.15]])
    field = result["fields"]["grid1"]
    x, y = plot_data.as_grid(field, "x"), plot_data.as_grid(field, "y")
    within = np.min(np.hypot(x[..., None] - centres[:, 0], y[..., None] - centres[:, 1]),
                    axis=-1) <= 0.5
    expected = within & (near == 1)
    assert 0 < np.count_nonzero(expected) < near.size  # some points, not all
    np.testing.assert_array_equal(plot_data.near_grown(field, result["elements"]), expected)
    fig = plot_figures.plot_map(result, "grid1", "max_shear")
    try:
        (veil,) = [c for c in fig.axes[0].collections if c.get_gid() == "near_grown"]
        np.testing.assert_array_equal(~np.ma.getmaskarray(veil.get_array()).ravel(),
                                      expected.ravel())
    finally:
        plot_figures.plt.close(fig)
    # Without grown elements nothing is veiled: the maps of other models are unchanged.
    result["elements"].pop("created_step")
    assert not np.any(plot_data.near_grown(field, result["elements"]))


def test_the_growth_legend_covers_no_element_of_a_tall_section(tmp_path):
    """A joint-like section (a tall, narrow map): the input fracture across the middle, the
    grown one down to the lower left corner of the view. The legend of the map (surface,
    elements) lies over none of them."""
    path = with_growth(tmp_path / "tall.h5", half_plane=True)
    ends = {"x_begin": [0.4, 0.2, 0.0, -0.2, -0.4, -0.45, -0.5],
            "y_begin": [-1.0, -1.1, -1.2, -1.3, -1.4, -1.9, -2.4],
            "x_end": [0.2, 0.0, -0.2, -0.4, -0.45, -0.5, -0.5],
            "y_end": [-1.1, -1.2, -1.3, -1.4, -1.9, -2.4, -2.9]}
    with h5py.File(path, "r+") as f:
        for key, values in ends.items():
            f["elements"][key][...] = values
    result = load_result(path)
    fig = plot_figures.plot_growth(result)
    try:
        fig.savefig(io.BytesIO(), format="png", dpi=60)
        renderer = fig.canvas.get_renderer()
        ax_map = fig.axes[0]
        legends = [legend for legend in (ax_map.get_legend(), *fig.legends) if legend]
        assert [text.get_text() for legend in legends for text in legend.get_texts()] == \
            ["elements", "grown elements", "linked here", "surface y = 0"]
        t = np.linspace(0.0, 1.0, 11)[:, None]
        e = result["elements"]
        points = np.concatenate([(1 - t) * np.column_stack([e["x_begin"], e["y_begin"]])[k]
                                 + t * np.column_stack([e["x_end"], e["y_end"]])[k]
                                 for k in range(e["x_begin"].size)])
        on_canvas = ax_map.transData.transform(points)
        for legend in legends:
            box = legend.get_window_extent(renderer)
            covered = [tuple(p) for p, c in zip(points, on_canvas) if box.contains(*c)]
            assert not covered, f"the legend covers elements at {covered}"
        assert_inside_the_canvas(fig)
    finally:
        plot_figures.plt.close(fig)


# A path that rises, falls past zero and comes back: sxy 0 -> 6 (4 steps), 6 -> -6
# (6 steps), -6 -> 0 (3 steps); the middle rows of its legs are 2 -> 3, 7 -> 8, 11 -> 12.
REVERSING_LEGS = [4, 6, 3]
REVERSING_SXY = np.concatenate([np.linspace(0.0, 6.0, 5), np.linspace(6.0, -6.0, 7)[1:],
                                np.linspace(-6.0, 0.0, 4)[1:]])
LEG_MIDDLES = [(2, 3), (7, 8), (11, 12)]


def reversing_history(**per_step):
    """A result (reader's dict) of a loading history along REVERSING_SXY with the given
    arrays of one row per step."""
    rows = REVERSING_SXY.size
    history = {"loads": {"sxy": REVERSING_SXY}, "leg_steps": np.array(REVERSING_LEGS),
               "ds": np.zeros((rows, 2)), **per_step}
    return {"history": history, "title": "reversing", "stress_unit": "MPa",
            "length_unit": "m", "fractures": [{"name": "wing", "label": "wing"}]}


def direction_arrows(ax):
    """(tail, head) of every leg arrow of an axes, as ((x, y), (x, y))."""
    return [(tuple(a.xyann), tuple(a.xy)) for a in ax.texts if a.get_gid() == "direction"]


def expected_arrows(x, y):
    return [((x[a], y[a]), (x[b], y[b])) for a, b in LEG_MIDDLES]


def test_strengths_along_a_reversing_path_show_the_sense_of_each_leg():
    rows = REVERSING_SXY.size
    mu = np.column_stack([np.linspace(0.6, 0.4, rows), np.full(rows, 0.6)])
    sf = np.column_stack([np.linspace(5.0, 1.0, rows), np.full(rows, 5.0)])
    result = reversing_history(mu_in_force=mu, sf_in_force=sf,
                               tensile_strength_in_force=np.zeros((rows, 2)))
    fig = plot_figures.plot_history_strengths(result, [0])
    try:
        ax_mu, ax_strength = fig.axes
        assert direction_arrows(ax_mu) == expected_arrows(REVERSING_SXY, mu[:, 0])
        assert direction_arrows(ax_strength) == [
            *expected_arrows(REVERSING_SXY, sf[:, 0]),
            *expected_arrows(REVERSING_SXY, np.zeros(rows))]
        # Down the falling leg: the arrow points to the lower load.
        tail, head = direction_arrows(ax_mu)[1]
        assert head[0] < tail[0]
    finally:
        plot_figures.plt.close(fig)


def test_growth_under_loading_and_unloading_shows_the_sense_of_each_leg():
    rows = REVERSING_SXY.size
    grown = np.minimum(np.arange(rows), 6).astype(float)[:, None] * 0.1  # then stays
    result = reversing_history(grown_length=grown, tip_fracture_id=np.array([1]),
                               tip_end=np.array([1]))
    fig = plot_figures.plot_growth_history(result)
    try:
        assert direction_arrows(fig.axes[0]) == expected_arrows(REVERSING_SXY, grown[:, 0])
    finally:
        plot_figures.plt.close(fig)
