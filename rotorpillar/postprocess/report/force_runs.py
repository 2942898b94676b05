"""The runs the forces section shows: each run's ``internal_forces``
(``transients.forces.InternalForcesSummary``) read with its run's record, the
case it names, and its NPZ histories."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...transients.forces import InternalForcesSummary
from .state import Build


@dataclass(frozen=True)
class ForcesRun:
    """One run with internal forces, as the section shows it."""

    case: str
    """the case as a reader names it (``verdict.summary.case_name``: "earthquake (elcentro)")"""
    file: str
    """its JSON's name in the output directory"""
    forces: InternalForcesSummary
    """its ``internal_forces``"""


def forces_runs(build: Build) -> list[ForcesRun]:
    """Every run with internal forces, each read through its record;
    ``verdict.summary.model_runs`` picks the file of each case and model (the newest of
    simulate's and compare's)."""
    from ...verdict.summary import model_runs

    return [
        ForcesRun(rf.label, rf.file, rf.run.internal_forces)
        for rf in model_runs(build.out)
        if rf.run.internal_forces is not None
    ]


def history(build: Build, run: ForcesRun, key: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(t, ``key``) of a run's NPZ beside its JSON, or None."""
    path = build.out / run.file.replace(".json", ".npz")
    try:
        with np.load(path) as z:
            return np.asarray(z["t"]), np.asarray(z[key])
    except (OSError, KeyError, ValueError):
        return None
