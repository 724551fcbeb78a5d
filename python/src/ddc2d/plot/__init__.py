"""The figures of ddc2d-plot, for use from Python (a Result of ddc2d.open_result or
ddc2d.run goes where they take a `result`):

    import ddc2d
    from ddc2d.plot import fracture_profiles, plot_map, plot_profile
    result = ddc2d.open_result("out.h5")
    fracture, profile = fracture_profiles(result)[0]
    plot_profile(result, fracture, profile).savefig("slip.png")
    plot_map(result, "map", "max_shear").savefig("map.png")

ddc2d.plot.data prepares what every figure shows (no matplotlib; ddc2d.plot.injection
those of a fluid injection), ddc2d.plot.figures draws it, and ddc2d.plot.cli is the
command ddc2d-plot.
"""

from .data import QUANTITIES, Receiver, fracture_profiles, grid_fields, grid_quantity
from .figures import (
    plot_cycle_events,
    plot_cycle_rate,
    plot_cycle_slip,
    plot_fronts,
    plot_growth,
    plot_growth_history,
    plot_history,
    plot_hydraulic_fracture,
    plot_injection,
    plot_map,
    plot_moment,
    plot_observation_line,
    plot_overview,
    plot_profile,
    plot_surface,
    save_figure,
)

__all__ = ["QUANTITIES", "Receiver", "fracture_profiles", "grid_fields", "grid_quantity",
           "plot_cycle_events", "plot_cycle_rate", "plot_cycle_slip",
           "plot_fronts", "plot_growth", "plot_growth_history", "plot_history",
           "plot_hydraulic_fracture", "plot_injection", "plot_map", "plot_moment",
           "plot_observation_line", "plot_overview", "plot_profile", "plot_surface",
           "save_figure"]
