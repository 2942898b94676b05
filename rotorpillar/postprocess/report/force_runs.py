"""The runs the forces section shows: each run's ``internal_forces``
(``transients.forces.InternalForcesSummary``) read with its run's record, the
case it names, and its NPZ histories."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...transients.forces import InternalForcesSummary
from ..run_arrays import read_npz
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
    duration: float | None = None
    """the run's length (s)"""
    initial_speed: float | None = None
    """the rotor's speed it starts from (rad/s); None: the case's own start (a run-up's rest)"""

    @property
    def window(self) -> str:
        """What the run covers, in words."""
        length = "?" if self.duration is None else f"{self.duration:.4g} s"
        start = "the case's start" if self.initial_speed is None else f"{self.initial_speed:.4g} rad/s"
        return f"{length} from {start}"

    def same_window(self, other: ForcesRun) -> bool:
        """Both runs cover the same stretch of the case: the same length from the same speed
        (to 1e-9 relative: compare hands every model the same numbers)."""
        close = lambda a, b: a is b or (a is not None and b is not None and abs(a - b) <= 1e-9 * max(abs(a), abs(b)))
        return close(self.duration, other.duration) and close(self.initial_speed, other.initial_speed)


@dataclass(frozen=True)
class ForcePair:
    """The ROM's run beside a full order's, for the section's differences."""

    rom: ForcesRun
    reference: ForcesRun
    same_window: bool
    """True: over the same window (like against like); False: the closest there is"""


def forces_run(label: str, file: str, run) -> ForcesRun:
    """A ``ForcesRun`` of a run record (``transients.model_run.RunRecord``) with internal forces."""
    return ForcesRun(label, file, run.internal_forces, run.duration, getattr(run, "initial_speed", None))


def forces_runs(build: Build) -> list[ForcesRun]:
    """Every run with internal forces, each read through its record;
    ``verdict.summary.model_runs`` picks the file of each case and model (the newest of
    simulate's and compare's)."""
    from ...verdict.summary import model_runs

    return [forces_run(rf.label, rf.file, rf.run) for rf in model_runs(build.out) if rf.run.internal_forces is not None]


def every_forces_run(build: Build) -> list[ForcesRun]:
    """Every run with internal forces, simulate's and compare's both, newest last."""
    from ...verdict.summary import every_run

    return [
        forces_run(rf.label, rf.file, rf.run)
        for _, rf in sorted(every_run(build.out), key=lambda x: x[0])
        if rf.run.internal_forces is not None
    ]


def like_pairs(runs: list[ForcesRun]) -> list[ForcePair]:
    """Per case, the full order (3D, else the 1D beam) beside the ROM's run over the same
    window: ``compare`` runs the ROM over the 3D run's window, ``simulate`` the whole case, and
    only the former measures the ROM's error.  Where no ROM run covers the full order's
    window, the one from the same command (else the last) is paired, ``same_window`` False.
    ``runs``: newest last (the later of two alike wins)."""
    out = []
    for case in sorted({r.case for r in runs}):
        here = [r for r in runs if r.case == case]
        refs = [r for r in here if r.forces.model == "fem3d"] or [r for r in here if r.forces.model == "beam"]
        roms = [r for r in here if r.forces.model == "modal"]
        if not refs or not roms:
            continue
        ref = refs[-1]
        command = lambda r: r.file.split("_", 1)[0]
        alike = [r for r in roms if r.same_window(ref)]
        pick = sorted(alike or roms, key=lambda r: command(r) == command(ref))[-1]
        out.append(ForcePair(pick, ref, bool(alike)))
    return out


def history(build: Build, run: ForcesRun, key: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(t, ``key``) of a run's NPZ beside its JSON, or None."""
    try:
        a = read_npz(build.out / run.file.replace(".json", ".npz"))
    except ValueError:  # a damaged file: the section draws without this run
        return None
    y = a.series(key) if a is not None else None
    return None if a is None or a.t is None or y is None else (a.t, y)
