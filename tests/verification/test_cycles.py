"""Earthquake cycles against an independent integration (docs/verification.md;
docs/theory/cycles.md): one rate-and-state element in the full plane under back-slip is a
spring-slider, integrated by scipy (tests/spring_slider.py). The long runs (BP3-QD against
the community) are the section "Earthquake cycles" of docs/verification.md."""

from spring_slider import SLIDER, spring_slider

END = 5.0e8


def test_spring_slider_event_time(solve, tmp_path, record):
    """The second event's start (the largest slip rate reaching 1e-3 m/s) at tolerance 1e-7,
    aging law: within 1e-7 relative of scipy's DOP853 at rtol 1e-12 (measured 4e-9; one
    element: no mesh)."""
    path = tmp_path / "slider.nml"
    path.write_text(SLIDER.format(end=END, law="aging"))
    result = solve(path, "slider")
    events, _ = spring_slider("aging", END)
    starts = result.cycle["event_start"]
    assert starts.size == events.size == 2
    row = record(id="spring-slider-event-time",
                 benchmark="One rate-and-state element on its self-stiffness, back-slip "
                 "(aging law, tolerance 1e-7)",
                 reference="the spring-slider integrated by scipy (DOP853, rtol 1e-12)",
                 quantity="start of the second event [s]", value=float(starts[1]),
                 reference_value=float(events[1]), tolerance=1e-7, mesh="1 element")
    assert row["passed"], row
