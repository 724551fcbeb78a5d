"""ddc2d from Python: read results, build and run models, plot (docs/python.md).

    import ddc2d
    result = ddc2d.open_result("out.h5")        # arrays, units, input echo, provenance
    result.to_xarray("map")                     # an observation set as an xarray Dataset
    model = ddc2d.Model(youngs_modulus=50000, poissons_ratio=0.25)
    result = ddc2d.run(model, output="run.h5")  # or ddc2d.run("input.nml")

The command-line tools (ddc2d-plot, collect-sweep, ...) are modules of this package;
the figures of ddc2d-plot are in ddc2d.plot.
"""

from .model import Model
from .reader import ResultError
from .result import Result, open_result
from .run import RunError, run

__version__ = "0.1.0"  # project(VERSION) of CMakeLists.txt: the test package_metadata
__all__ = ["Model", "Result", "ResultError", "RunError", "__version__", "open_result", "run"]
