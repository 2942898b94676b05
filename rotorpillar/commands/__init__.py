"""The commands behind the CLI, one module each.

A command is a function ``(scene, args, timings) -> Done``: its ``result`` a
record (rotorpillar.records) written to ``<out>/<command>.json``, its
``summary`` the readable text printed instead of the JSON, its exit status.  The stages of ``rotorpillar
run`` hand results over through the files they write.  Commands stay thin: the physics
lives in the library modules they call.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import os
import sys
from pathlib import Path
from typing import Any, NamedTuple

#: Exit code of a command whose computation ran to its end but failed its own
#: checks (an integrator past its stability limit, an energy balance that does
#: not close, ...): the results are written, marked ``ok: false`` with the
#: reasons.  The CLI's other codes: cli.EXIT_*.
EXIT_CHECKS = 4


class Done(NamedTuple):
    """What a command returns."""

    result: Any
    """its record: the fields of ``<out>/<command>.json`` (the provenance is added beside)"""
    summary: str
    """the readable text printed instead of the JSON"""
    exit_status: int = 0
    """0, or EXIT_CHECKS when the computation failed its own checks (1: report --strict)"""


def out_dir(scene: Scene, args) -> Path:
    """Where a command writes: ``--out DIR``, or ``out/<scene name>/``."""
    return args.out if args.out is not None else Path("out") / scene.name


def is_root_rank() -> bool:
    """Write and print on MPI rank 0 only (mpi4py is imported only by fem3d)."""
    mpi = sys.modules.get("mpi4py.MPI")
    return mpi is None or mpi.COMM_WORLD.rank == 0


def progress(message: str) -> None:
    """A stage line on stderr (stdout may carry --json)."""
    print(f"[rotorpillar] {message}", file=sys.stderr, flush=True)


def launched_ranks() -> int:
    """Ranks of the MPI job this process was started in (1 outside mpirun), from the
    launcher's environment: known before mpi4py is imported."""
    for key in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MPI_LOCALNRANKS"):
        value = os.environ.get(key, "")
        if value.isdigit():
            return int(value)
    return 1


def mpi_progress():
    """``progress`` on rank 0 and silence elsewhere, for a command that runs under
    mpirun (imports mpi4py only when launched on several ranks)."""
    if launched_ranks() <= 1:
        return progress
    from mpi4py import MPI

    return progress if MPI.COMM_WORLD.rank == 0 else (lambda message: None)
