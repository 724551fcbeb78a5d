"""ddc2d-converge: the discretization error of a model, by running it refined
(docs/error-estimates.md). `study(model_path, levels=3, ...)` returns the study as a
dict (STUDY.json); the command line is ddc2d.converge.cli."""

from .namelist import REFINEMENTS, RefineError
from .study import collect, study

__all__ = ["REFINEMENTS", "RefineError", "collect", "study"]
