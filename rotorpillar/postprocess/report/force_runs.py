"""The runs the forces section shows: each run's ``internal_forces``
(``transients.force_records.InternalForcesSummary``) read with its run's record, the
case it names, and its NPZ histories."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...transients.force_records import InternalForcesSummary
from ..readers import outcome, read_run
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
    """Every run with internal forces, each read through its record (``readers.read_run``:
    a damaged one raises, naming the file); ``verdict.summary.model_runs`` picks the
    file of each case and model (the newest of simulate's and compare's)."""
    from ...verdict.summary import case_name, model_runs

    out = []
    for doc in model_runs(build.out):
        got = read_run(build.out / doc["_file"])
        run = got.record if got is not None else None
        if run is not None and run.internal_forces is not None:
            ex = outcome(run).excitation
            label = case_name(run.case, None if ex is None else ex.to_json())  # verdict reads documents
            out.append(ForcesRun(label, doc["_file"], run.internal_forces))
    return out


def history(build: Build, run: ForcesRun, key: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(t, ``key``) of a run's NPZ beside its JSON, or None."""
    path = build.out / run.file.replace(".json", ".npz")
    try:
        with np.load(path) as z:
            return np.asarray(z["t"]), np.asarray(z[key])
    except (OSError, KeyError, ValueError):
        return None
