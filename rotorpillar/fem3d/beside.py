"""A modal analysis in a second process, beside the caller's own work.

The chain (rotorpillar.chain.modes) solves two configurations of one mesh:
the loaded tube (the ROM's modes) and the bare tube (8 modes, for the
paper's Eq. 2).  The two solves are independent.  In `rotorpillar run`'s
modal stage nothing else runs, so the machine's second core idles while
they run one after the other (paper, 128 x 20: the loaded tube ~20 s, the
bare one ~9 s).  Here the bare tube is solved by ``python -m
rotorpillar.fem3d.beside`` while the caller solves the loaded one.

The result comes back pickled: a :class:`ModalResult` holds numpy arrays and
plain values, no PETSc or dolfinx object.  It goes into this process's cache
(:func:`rotorpillar.fem3d.remember`) as if it had been solved here, so the
callers after it read it as before.  The second process is a fresh
interpreter (about 1 s of imports): it has its own MPI, its own PETSc and
its own memory, and the same code on the same input gives the same numbers.

Only a serial process on a machine with two or more cores starts one
(:func:`start`), and only for a result not already in its cache: under
mpirun the ranks already share the cores.  Where the second process fails,
the solve is done here instead: the same result, only later.
"""

from __future__ import annotations

import os
import pickle
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from ..scene import Scene
from .modal import ModalResult

MODULE = "rotorpillar.fem3d.beside"
"""What ``python -m`` runs: one solve, from a pickled request to a pickled result."""


def cores() -> int:
    """The cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


class Beside:
    """One :func:`rotorpillar.fem3d.modal_analysis` running in a second process.

    Use it as a context manager: leaving the block early (an error, Ctrl-C)
    ends the process and removes its folder."""

    def __init__(self, scene: Scene, *, top: bool, n_modes: int, mesh) -> None:
        self.request = (scene, top, n_modes, mesh)
        self.folder = Path(tempfile.mkdtemp(prefix="rotorpillar-beside-"))
        with open(self.folder / "request.pickle", "wb") as f:
            pickle.dump(self.request, f)
        # an MPI launcher's variables would make the child try to join the parent's job
        env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "PMI_"))}
        with open(self.folder / "stderr.txt", "wb") as err:  # said in one line if it fails
            self.proc: subprocess.Popen | None = subprocess.Popen(
                [sys.executable, "-m", MODULE, str(self.folder)], env=env, stdout=subprocess.DEVNULL, stderr=err
            )

    def result(self) -> ModalResult:
        """The result: the second process's when it succeeded, else solved here now."""
        from . import modal_analysis, remember

        scene, top, n_modes, mesh = self.request
        code = self.proc.wait() if self.proc is not None else None
        if code == 0:
            with open(self.folder / "result.pickle", "rb") as f:
                remember(scene, top, n_modes, mesh, pickle.load(f))
        else:
            err = self.folder / "stderr.txt"
            lines = err.read_text(errors="replace").strip().splitlines() if err.is_file() else []
            why = lines[-1] if lines else "no message"
            print(f"fem3d: the second process's solve failed (exit {code}: {why}); solving here", file=sys.stderr)
        self.close()
        return modal_analysis(scene, top=top, n_modes=n_modes, mesh=mesh)

    def close(self) -> None:
        """End the process if it still runs; remove its folder."""
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        self.proc = None
        shutil.rmtree(self.folder, ignore_errors=True)

    def __enter__(self) -> Beside:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def start(scene: Scene, *, top: bool, n_modes: int, mesh, comm=None) -> Beside | None:
    """A :class:`Beside` solving these arguments where it pays: one serial process on two
    or more cores, the result not already in this process's cache; else None (the
    caller solves it itself)."""
    from mpi4py import MPI

    from . import in_cache

    if MPI.COMM_WORLD.size > 1 or (comm is not None and comm.size > 1) or cores() < 2:
        return None
    if in_cache(scene, top, n_modes, mesh):
        return None
    return Beside(scene, top=top, n_modes=n_modes, mesh=mesh)


def solve(folder: Path) -> None:
    """The second process's work: the request in ``folder``, its result written beside it."""
    from . import modal_analysis

    with open(folder / "request.pickle", "rb") as f:
        scene, top, n_modes, mesh = pickle.load(f)
    result = modal_analysis(scene, top=top, n_modes=n_modes, mesh=mesh)
    partial = folder / "result.pickle.part"
    with open(partial, "wb") as f:
        pickle.dump(result, f, protocol=pickle.HIGHEST_PROTOCOL)
    partial.replace(folder / "result.pickle")  # whole or absent


if __name__ == "__main__":
    solve(Path(sys.argv[1]))
