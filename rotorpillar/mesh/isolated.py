"""Gmsh in a child process: a crash inside Gmsh cannot take the caller down.

``python -m rotorpillar.mesh`` is the worker: the parameters arrive as JSON
on the command line, the arrays leave as npz bytes on stdout.
"""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import asdict
from pathlib import Path

from ..errors import ComputationError, InputError
from .arrays import MeshData, extract_mesh_data
from .tube import TubeMeshParams, build_tube

#: Seconds a meshing child process may take before it is stopped.
MESH_TIMEOUT = 600.0


def _mesh_in_process(p: TubeMeshParams) -> MeshData:
    import gmsh

    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("tube")
        build_tube(gmsh.model, p)
        data = extract_mesh_data(gmsh.model, p)
    except InputError:
        raise
    except Exception as exc:  # Gmsh raises plain Exceptions carrying its log line
        raise ComputationError(f"Gmsh failed to mesh the tube: {exc}") from None
    finally:
        gmsh.finalize()
    expected = p.cells
    if len(data.cells) != expected:
        raise ComputationError(f"Gmsh made {len(data.cells)} cells, expected {expected}")
    return data


def tube_mesh_data(p: TubeMeshParams, *, isolated: bool = True) -> MeshData:
    """Mesh the tube with Gmsh and return its arrays.

    With ``isolated`` (the default) Gmsh runs in a child process (``python -m
    rotorpillar.mesh``), so that a crash inside Gmsh cannot take the caller,
    possibly an MPI rank holding PETSc objects, down with it.
    """
    if not isolated:
        return _mesh_in_process(p)
    try:
        # The parameters go on the command line, not through stdin: writing to
        # the pipe of a child that has already died raises SIGPIPE, which
        # PETSc's signal handler (installed once petsc4py is imported) turns
        # into an abort of the caller.
        proc = subprocess.run(
            worker_command() + [json.dumps(asdict(p))],
            capture_output=True,
            stdin=subprocess.DEVNULL,
            timeout=MESH_TIMEOUT,
        )
    except subprocess.TimeoutExpired:
        raise ComputationError(f"Gmsh did not finish meshing the tube within {MESH_TIMEOUT:g} s") from None
    if proc.returncode != 0:
        err = proc.stderr.decode(errors="replace").strip().splitlines()
        last = err[-1] if err else f"exit code {proc.returncode}"
        if proc.returncode < 0:
            last = f"killed by signal {-proc.returncode} ({last})"
        raise ComputationError(f"Gmsh failed to mesh the tube: {last}")
    return MeshData.from_bytes(proc.stdout)


#: The layout of a kept mesh: bump it when MeshData's npz changes.
KEPT_VERSION = 1


def kept_mesh_path(p: TubeMeshParams) -> Path:
    """Where the tube's arrays for ``p`` are kept in the user's cache (rotorpillar.cache):
    the key is the parameters, Gmsh's version and this package's meshing code."""
    from importlib.metadata import PackageNotFoundError, version

    from ..cache import cache_key, source_hash, user_cache_root

    try:
        gmsh_version = version("gmsh")
    except PackageNotFoundError:  # Debian's python3-gmsh carries no metadata
        gmsh_version = "system"
    here = Path(__file__).resolve().parent
    code = source_hash(sorted(here.glob("*.py")))
    key = cache_key({"params": asdict(p), "gmsh": gmsh_version}, version=KEPT_VERSION, code=code)
    return user_cache_root() / "meshes" / f"{key}.npz"


def cached_tube_mesh_data(p: TubeMeshParams, *, isolated: bool = True) -> MeshData:
    """:func:`tube_mesh_data`, kept on disk (rotorpillar.provenance.kept): every stage of `run`
    and every rerun assembles the same few tubes, and each Gmsh child costs 0.3-0.7 s of CPU
    (paper: eight in the earthquake comparison alone).  Gmsh is deterministic for one version
    and one set of parameters, so a kept mesh is the very arrays a new child would hand back."""
    from ..provenance import kept

    def read(data: bytes) -> MeshData:
        mesh = MeshData.from_bytes(data)
        if len(mesh.cells) != p.cells:
            raise ValueError("another mesh")
        return mesh

    return kept(kept_mesh_path(p), lambda: tube_mesh_data(p, isolated=isolated), MeshData.to_bytes, read)


def worker_command() -> list[str]:
    """The command line of the isolated meshing process."""
    return [sys.executable, "-m", "rotorpillar.mesh"]


def _worker() -> int:
    """Child-process entry: params as JSON in argv[1], MeshData as npz bytes on stdout."""
    params = TubeMeshParams(**json.loads(sys.argv[1]))
    try:
        data = _mesh_in_process(params)
    except (ComputationError, InputError) as exc:
        print(str(exc).removeprefix("Gmsh failed to mesh the tube: "), file=sys.stderr)
        return 1
    sys.stdout.buffer.write(data.to_bytes())
    return 0
