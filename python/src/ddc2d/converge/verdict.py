"""The verdict on one quantity over the refined levels (docs/error-estimates.md).

Smooth quantities: the observed order and Richardson value of the last three levels
(ddc2d.richardson), the error estimate of level 0 (the user's model) its distance from
that value, and the verdict `converged` (estimate within the tolerance, relative to the
extrapolated value), `converging` (differences of one sign that shrink at every
refinement, at an order of at least MIN_ORDER; estimate above the tolerance),
`oscillating` (differences that change sign) or `not converging` (differences that do not
shrink at every refinement, or shrink more slowly than MIN_ORDER). The last two get no
extrapolated value and no estimate, unless every level lies within the tolerance of the
others: `converged` then, the estimate level 0's distance from the finest level.

Quantised quantities (lengths in elements, loads in load steps, grown lengths in
increments): no Richardson value. The change between two levels is counted in quanta of
the finer one; `converged` when the last change is at most one quantum of the coarser
level (the finer level moved it no more than the coarser one can resolve), `converging`
when the change, in quanta, does not grow from level to level (it falls at least as fast
as the quantum: order 1 or better), `not converging` when it grows (the value moves by
more quanta at every refinement, as a result that depends on the mesh does). The error
estimate is level 0's distance from the finest level.
"""

from .. import richardson

CONVERGED, CONVERGING, NOT_CONVERGING = "converged", "converging", "not converging"
OSCILLATING = "oscillating"
#: The lowest observed order that is extrapolated. Below 1/2 the extrapolated value lies
#: further beyond the finest level than the first of the last three levels lies from it
#: (d_2 / (2^p - 1) > d_1 + d_2 exactly when 4^p < 2): a guess, not an estimate.
MIN_ORDER = 0.5
#: The refinement ratio between levels (every length halved).
RATIO = 2.0
#: Relative slack when comparing a change with a quantum (rounding of the quanta).
QUANTUM_SLACK = 1e-9


def judge_smooth(values, tolerance, scale=None):
    """The entry of a smooth quantity: order, extrapolated, error_estimate, verdict; the
    tolerance is relative to `scale`, by default the size of the quantity."""
    fit = richardson.extrapolate(values, RATIO)
    if fit.extrapolated is not None and (fit.order is None or fit.order >= MIN_ORDER):
        estimate = richardson.error_estimate(values[0], fit)
        if fit.order is None:
            verdict = CONVERGED  # it no longer changes
        else:
            if scale is None:
                scale = max(abs(fit.extrapolated), max(abs(v) for v in values))
            verdict = CONVERGED if estimate <= tolerance * scale else CONVERGING
        return {"order": fit.order, "extrapolated": fit.extrapolated,
                "error_estimate": estimate, "verdict": verdict}
    if scale is None:
        scale = max(abs(v) for v in values)
    if max(values) - min(values) <= tolerance * scale:
        # Every level within the tolerance of the others: whatever the differences do,
        # the quantity is resolved; no order to extrapolate with.
        verdict, estimate = CONVERGED, abs(values[0] - values[-1])
    else:
        verdict, estimate = (OSCILLATING if fit.oscillates else NOT_CONVERGING), None
    return {"order": fit.order, "extrapolated": None, "error_estimate": estimate,
            "verdict": verdict}


def judge_quantised(values, quanta):
    """The entry of a quantised quantity: its changes in quanta of the finer level, the
    error estimate (level 0's distance from the finest) and the verdict."""
    changes = [abs(values[k + 1] - values[k]) for k in range(len(values) - 1)]
    in_quanta = [change / quanta[k + 1] for k, change in enumerate(changes)]
    if changes[-1] <= quanta[-2] * (1.0 + QUANTUM_SLACK):
        verdict = CONVERGED
    elif in_quanta[-1] <= in_quanta[-2] * (1.0 + QUANTUM_SLACK):
        verdict = CONVERGING
    else:
        verdict = NOT_CONVERGING
    return {"order": None, "extrapolated": None,
            "error_estimate": abs(values[0] - values[-1]), "verdict": verdict,
            "quantum": list(quanta), "changes_in_quanta": in_quanta}


def judge(values, quanta, tolerance, scale=None):
    """The entry of one quantity from its values per level (None where a level lacks
    it: `not converging`), its quanta (None for a smooth quantity) and the scale of its
    relative error (judge_smooth)."""
    if any(v is None for v in values):
        return {"order": None, "extrapolated": None, "error_estimate": None,
                "verdict": NOT_CONVERGING,
                "note": "missing at some levels: the event or tip comes and goes"}
    if quanta is not None:
        return judge_quantised(values, quanta)
    return judge_smooth(values, tolerance, scale)
