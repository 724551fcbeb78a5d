"""A convergence study of one model: write its refined levels, run them, gather the
quantities of every level and judge each (ddc2d.converge.verdict).

    study = ddc2d.converge.study("input/paper_fault_slip.nml", levels=3)
    study["quantities"]["k2/fault/end"]["extrapolated"]

`study` runs everything and writes STUDY.json and the figure into the output folder;
`write_levels`, `run_levels` and `collect` are its steps, for runs made elsewhere (Slurm).
"""

import json
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..reader import FilePath, Loaded, load_result
from ..run import run
from . import namelist
from .quantities import gather
from .verdict import RATIO, judge

#: The file of the study in the output folder.
STUDY_FILE = "STUDY.json"
#: Fewest levels: an observed order needs three.
MIN_LEVELS = 3


def default_out_dir(model_path: FilePath) -> Path:
    """`<model stem>_converge/` in the current folder."""
    return Path(f"{Path(model_path).stem}_converge")


def level_stem(model_path: FilePath, level: int) -> str:
    return f"{Path(model_path).stem}_level{level}"


#: The group each refinement needs in the model.
NEEDS = {"elements": "fracture", "increment": "growth", "steps": "load_path"}


def applicable(groups: Iterable[namelist.Group], refine: Iterable[str]) -> tuple[str, ...]:
    """The chosen refinements that apply to the model (increment needs &growth, steps a
    &load_path)."""
    names = {g.name for g in groups}
    return tuple(r for r in refine if NEEDS[r] in names)


def write_levels(model_path: FilePath, levels: int, refine: Sequence[str], out_dir: Path
                 ) -> tuple[list[Path], tuple[str, ...]]:
    """Write the namelist of every level into out_dir; returns their paths and the
    refinements applied. Raises namelist.RefineError (what cannot be refined),
    ValueError (fewer than three levels, an unknown refinement) and OSError."""
    if levels < MIN_LEVELS:
        raise ValueError(f"--levels {levels}: an observed order needs at least "
                         f"{MIN_LEVELS} levels")
    unknown = [r for r in refine if r not in namelist.REFINEMENTS]
    if unknown or not refine:
        raise ValueError(f"--refine {','.join(refine)}: choose among "
                         f"{','.join(namelist.REFINEMENTS)}")
    model_path = Path(model_path)
    text = model_path.read_text()
    groups = namelist.parse(text)
    namelist.check_refinable(groups, tuple(refine))
    used = applicable(groups, refine)
    if not used:
        missing = " or ".join(f"&{NEEDS[r]}" for r in refine)
        raise namelist.RefineError(f"--refine {','.join(refine)}: the model has no {missing}")
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for level in range(levels):
        path = out_dir / f"{level_stem(model_path, level)}.nml"
        path.write_text(namelist.refined_text(text, groups, level, used,
                                              model_path.resolve().parent))
        paths.append(path)
    return paths, used


def run_levels(namelists: Iterable[Path], executable: FilePath | None = None,
               threads: int | None = None, echo: Callable[[str], object] | None = None
               ) -> list[Path]:
    """Run every level (ddc2d.run); returns the result paths. Raises ddc2d.RunError."""
    outputs = []
    for path in namelists:
        if echo:
            echo(f"running {path.name}")
        run(path, output=path.with_suffix(".h5"), executable=executable, threads=threads)
        outputs.append(path.with_suffix(".h5"))
    return outputs


def element_length(result: Loaded) -> float:
    """The median length of the elements the model was given (not those grown)."""
    e = result["elements"]
    lengths = np.hypot(e["x_end"] - e["x_begin"], e["y_end"] - e["y_begin"])
    if "created_step" in e:
        lengths = lengths[e["created_step"] == 0]
    return float(np.median(lengths))


def collect(model_path: FilePath, outputs: Sequence[FilePath], refine: Iterable[str],
            tolerance: float = 0.01) -> dict[str, Any]:
    """The study from the results of the levels, coarse to fine: a dict with the model,
    the levels' element lengths, and `quantities` -> key -> values, order, extrapolated,
    error_estimate, verdict (and quantum, load as they apply)."""
    results = [load_result(path) for path in outputs]
    gathered = [gather(result) for result in results]
    keys = list(dict.fromkeys(k for quantities, _ in gathered for k in quantities))
    loads = {k: v for _, named in gathered for k, v in named.items()}
    entries = {}
    for key in keys:
        levels = [quantities.get(key) for quantities, _ in gathered]
        values = [q.value if q else None for q in levels]
        quantised = all(q is not None and q.quantum is not None for q in levels)
        quanta = [q.quantum for q in levels] if quantised else None
        scale = next((q.scale for q in levels if q), None)
        entry = {"values": values, **judge(values, quanta, tolerance, scale)}
        if key in loads:
            entry["load"] = loads[key]
        entries[key] = entry
    return {"model": str(Path(model_path)), "levels": len(outputs), "ratio": RATIO,
            "refined": list(refine), "tolerance": tolerance,
            "element_length": [element_length(r) for r in results],
            "results": [str(p) for p in outputs], "quantities": entries}


def write_study(study_dict: dict[str, Any], out_dir: FilePath) -> Path:
    """STUDY.json in out_dir; returns its path."""
    path = Path(out_dir) / STUDY_FILE
    path.write_text(json.dumps(study_dict, indent=1) + "\n")
    return path


def study(model_path: FilePath, levels: int = 3, refine: Iterable[str] = namelist.REFINEMENTS,
          tolerance: float = 0.01, out_dir: FilePath | None = None,
          executable: FilePath | None = None, threads: int | None = None, figure: bool = True,
          echo: Callable[[str], object] | None = None) -> dict[str, Any]:
    """Run the convergence study of the namelist model at `model_path` and return it
    (see collect); writes the levels, their results, STUDY.json and (figure=True)
    convergence.png into out_dir (default <model stem>_converge/ in the current folder).
    Raises namelist.RefineError, ValueError, ddc2d.RunError."""
    out_dir = Path(out_dir or default_out_dir(model_path))
    namelists, used = write_levels(model_path, levels, tuple(refine), out_dir)
    outputs = run_levels(namelists, executable, threads, echo)
    result = collect(model_path, outputs, used, tolerance)
    write_study(result, out_dir)
    if figure:
        from .report import draw_figure  # matplotlib only when drawing

        draw_figure(result, out_dir)
    return result
