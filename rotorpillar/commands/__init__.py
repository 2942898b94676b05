"""The commands behind the CLI, one module each.

A command is a function ``(scene, args, timings) -> (result, summary)``:
``result`` a JSON-ready dict written to ``<out>/<command>.json``, ``summary``
the readable text printed instead of the JSON.  The stages of ``rotorpillar
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

#: Exit code of a command whose computation ran to its end but failed its own
#: checks (an integrator past its stability limit, an energy balance that does
#: not close, ...): the results are written, marked ``ok: false`` with the
#: reasons.  The CLI's other codes: cli.EXIT_*.
EXIT_CHECKS = 4


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
