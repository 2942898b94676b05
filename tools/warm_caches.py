"""Pay at set-up the one-off compilation a fresh machine's first `make run` would pay.

``make run`` (``rotorpillar run paper``) compiles, on first use:

- numba: the reduced model's kernels (``@njit(cache=True)`` in
  ``rotorpillar/reduced/{dp5,fixed_step,rhs}.py``), 29 signatures of 21
  functions, for the argument types the comparisons, the two ``simulate``
  stages and the integrator study pass;
- FFCx: the forms of the 3D solid (P1 and P2, hexahedra and tetrahedra) and
  of the shell (Q2 quadrilaterals, P2 triangles) with the paper's material:
  6 elements and 12 forms, for the convergence ladder, the modal stage and the
  3D comparison (these last two use the P2 hexahedra's).

(Found by running ``rotorpillar run paper`` with empty ``NUMBA_CACHE_DIR``
and ``XDG_CACHE_HOME`` and listing what appeared.)  This script runs the
same code on small inputs: those stages of :data:`rotorpillar.commands.run.RUN_STAGES`
in this process with short durations (argument types, not sizes, pick a
kernel's signature), and one coarse run of each finite-element family of the
convergence ladder through :func:`rotorpillar.converge.compute.compute_fe`
(a form's code depends on the cell, the degree and the material, not on the
mesh's size).  The compiled code lands in numba's cache (``~/.cache/rotorpillar/numba/<hash of the kernel sources>``:
rotorpillar.reduced.rhs; or ``NUMBA_CACHE_DIR``) and dolfinx's
(``~/.cache/fenics``, or ``XDG_CACHE_HOME``), where the main job finds it.

Idempotent: the stamp ``.venv/.warm-caches.json`` records a key (the
versions of Python, numba, llvmlite, FFCx, UFL, basix and dolfinx; numba's own staleness stamp --
modification time and size -- of each kernel file; a hash of the files that
define the forms and of the paper scene; ``NUMBA_CACHE_DIR`` and
``XDG_CACHE_HOME``) and the cache files the warm-up
used.  With the same key and every file present, nothing runs.  Otherwise
the caches answer what they already hold and only the rest is compiled.

``python tools/warm_caches.py [--force]``; prints one line per cache.
"""

from __future__ import annotations

import argparse
import contextlib
import hashlib
import io
import json
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
STAMP = ROOT / ".venv" / ".warm-caches.json"
SCENE = "paper"

#: The main job's stages that compile numba kernels, and what shortens each
#: without changing the argument types (a stage's own arguments come first:
#: argparse keeps the last ``--models``).  The 3D comparison's forms are the
#: modal stage's and the ladder's P2 hexahedra, warmed below.
SHORT_STAGES = {
    "compare --case earthquake": ["--models", "modal", "--set", "simulate.earthquake_duration=6"],
    "compare --case runup": ["--set", "simulate.duration=2", "--set", "full_order.runup_duration=2"],
    "simulate --case runup": ["--set", "simulate.duration=2"],
    "simulate --case earthquake": ["--set", "simulate.earthquake_duration=6"],
    "integrators": ["--quick", "--duration", "1"],
}
#: The coarsest mesh of each finite-element family: enough to build its forms.
SMALL_SOLID = {"elements_around": 8, "elements_along": 2, "elements_through": 1}
SMALL_SHELL = {"elements_around": 8, "elements_along": 4}
#: Where the forms and the elements come from (their code is in the hash of the key).
FORM_SOURCES = (
    "rotorpillar/fem3d",
    "rotorpillar/mesh",
    "rotorpillar/scenes/paper.toml",
    "rotorpillar/scene/sections.py",
)


def kernel_files() -> list[Path]:
    """The package's files with cached numba kernels."""
    return sorted(p for p in (ROOT / "rotorpillar").rglob("*.py") if "cache=True" in p.read_text(encoding="utf-8"))


def key() -> str:
    """What the caches' validity depends on (see the module docstring)."""
    import os
    import platform
    from importlib.metadata import version

    h = hashlib.sha256()
    h.update(platform.python_version().encode())
    for dist in ("numba", "llvmlite", "fenics-ffcx", "fenics-ufl", "fenics-basix", "fenics-dolfinx"):
        h.update(f" {dist} {version(dist)}".encode())
    for var in ("NUMBA_CACHE_DIR", "XDG_CACHE_HOME"):  # where the caches are
        h.update(f"{var}={os.environ.get(var, '')}\n".encode())
    for p in kernel_files():
        st = p.stat()
        h.update(f"{p.relative_to(ROOT)} {st.st_mtime_ns} {st.st_size}\n".encode())
    for src in FORM_SOURCES:
        path = ROOT / src
        for p in sorted(path.rglob("*.py")) if path.is_dir() else [path]:
            h.update(f"{p.relative_to(ROOT)}\n".encode() + p.read_bytes())
    return h.hexdigest()


def _dispatchers() -> Iterator[tuple[Path, Any]]:
    """(kernel file, dispatcher) of every cached kernel."""
    import importlib

    from numba.core.registry import CPUDispatcher

    for p in kernel_files():
        mod = importlib.import_module(".".join(p.relative_to(ROOT).with_suffix("").parts))
        for obj in vars(mod).values():
            if isinstance(obj, CPUDispatcher):
                yield p, obj


def warm_kernels(out: Path) -> tuple[int, int, list[Path]]:
    """Run the short stages; (signatures compiled, loaded from the cache, index files)."""
    from rotorpillar.cli import main
    from rotorpillar.commands.run import RUN_STAGES

    stages = [(st.command, st.arguments) for st in RUN_STAGES if st.command in SHORT_STAGES]
    missing = set(SHORT_STAGES) - {c for c, _ in stages}
    if missing:
        raise SystemExit(f"warm_caches: the main job has no stage {sorted(missing)}: update SHORT_STAGES")
    for command, own in stages:
        argv = [*command.split(), *own, SCENE, "--out", str(out), *SHORT_STAGES[command]]
        sink = io.StringIO()
        with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
            status = main(argv)
        if status != 0:
            raise SystemExit(f"warm_caches: rotorpillar {' '.join(argv)} exited {status}:\n" + sink.getvalue()[-2000:])
    compiled = loaded = 0
    index: set[Path] = set()
    for path, d in _dispatchers():
        compiled += len(d.stats.cache_misses)  # signatures, not calls
        loaded += len(set(d.stats.cache_hits) - set(d.stats.cache_misses))
        # numba's index files, one a function: <module>.<function>-<line>.py311.nbi
        index.update(Path(d.stats.cache_path).glob(f"{path.stem}.*.nbi"))
    return compiled, loaded, sorted(index)


def cached_signatures(index: list[Path]) -> int:
    """Signatures on disk: one ``<index stem>.<n>.nbc`` file each."""
    return sum(len(list(p.parent.glob(f"{p.stem}.*.nbc"))) for p in index)


@contextlib.contextmanager
def _recording_ffcx_modules() -> Iterator[list[Path]]:
    """The shared libraries FFCx compiles or loads while inside (dolfinx calls these)."""
    import ffcx.codegeneration.jit as jit

    seen: list[Path] = []
    originals = {name: getattr(jit, name) for name in ("compile_forms", "compile_elements")}

    def recording(original: Any) -> Any:
        def call(*args: Any, **kwargs: Any) -> Any:
            result = original(*args, **kwargs)
            module = result[1]
            if getattr(module, "__file__", None):
                seen.append(Path(module.__file__))
            return result

        return call

    for name, original in originals.items():
        setattr(jit, name, recording(original))
    try:
        yield seen
    finally:
        for name, original in originals.items():
            setattr(jit, name, original)


def warm_forms() -> tuple[list[str], list[Path]]:
    """One coarse run of each finite-element family; (families, the FFCx libraries used)."""
    from dataclasses import replace

    from rotorpillar import load_scene
    from rotorpillar.converge.compute import compute_fe
    from rotorpillar.converge.ladder import FAMILIES, ladder

    scene = load_scene(SCENE)
    firsts: dict[str, Any] = {}
    for case in ladder(scene):
        fam = FAMILIES[case.family]
        if fam.model in ("shell", "solid") and not fam.sweep and case.family not in firsts:
            small = SMALL_SHELL if fam.model == "shell" else SMALL_SOLID
            firsts[case.family] = replace(case, params=tuple(sorted({**case.settings, **small}.items())))
    with _recording_ffcx_modules() as seen:
        for case in firsts.values():
            compute_fe(case, scene)
        _warm_linear_view(scene)
    return sorted(firsts), sorted(set(seen))


def _warm_linear_view(scene: Any) -> None:
    """The linear hexahedra of the 3D transients' XDMF series (rotorpillar.fem3d.xdmf_view):
    their coordinate element is compiled once, here, not in a stage's timed run."""
    from dolfinx import fem

    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.xdmf_view import linear_view
    from rotorpillar.scene.sections import Mesh

    model = assemble_pillar(scene, top=True, mesh=Mesh(elements_around=8, elements_along=2))
    linear_view(fem.Function(model.V), fem.Function(fem.FunctionSpace(model.mesh, ("Lagrange", 2))))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--force", action="store_true", help="run even when the stamp is current")
    args = parser.parse_args(argv)
    want = key()
    if STAMP.exists() and not args.force:
        stamp = json.loads(STAMP.read_text())
        if stamp.get("key") == want and all(Path(f).exists() for f in stamp.get("files", [])):
            return 0
    sys.path.insert(0, str(ROOT))
    from rotorpillar.cli import quiet_third_party_logs

    quiet_third_party_logs()  # the compiler's command lines stay off the console
    print(
        "setup: warming the compiled code of the first run (numba kernels, FFCx forms; once, about a minute)",
        flush=True,
    )
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="rotorpillar-warm-") as tmp:
        compiled, loaded, index = warm_kernels(Path(tmp))
    t1 = time.perf_counter()
    families, libraries = warm_forms()
    t2 = time.perf_counter()
    print(
        f"setup: numba: {cached_signatures(index)} signatures of {len(index)} kernels in the "
        f"cache; {compiled} compiled now, {loaded} loaded ({t1 - t0:.0f} s)"
    )
    print(f"setup: FFCx: {len(libraries)} elements and forms of {', '.join(families)} ({t2 - t1:.0f} s)")
    files = [str(p) for p in [*index, *libraries]]
    STAMP.write_text(json.dumps({"key": want, "files": files}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
