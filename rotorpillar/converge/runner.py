"""Running the ladder: the run cache, the subprocess worker, time and memory.

Each run is cached on disk under a hash of everything it depends on (model,
mesh, degree, cell type, geometry, material and the source of the model's
code), written atomically: an interrupted study resumes where it stopped and
computes nothing twice.  The finite-element runs run in a separate process
that serves run after run (rotorpillar.converge.service: ``python -m
rotorpillar.converge --serve``, :func:`run_one` per run), whose resident
high-water mark, reset before each run, is the run's peak memory; the
pure-Python models run in-process and report tracemalloc's peak.
"""

from __future__ import annotations

import functools
import resource
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import msgspec

from .. import records
from ..cache import DiskCache, cache_key, source_hash
from ..provenance import write_json
from ..scene.tower import Foundation, foundation_key, pillar_key
from .compute import compute_fe, compute_in_process
from .ladder import FAMILIES, N_MODES, QUANTITIES, Case, estimated_dofs, estimated_seconds, resolved_only
from .result import ERROR_KINDS, CaseFile, ConvergenceRun, RunResult

if TYPE_CHECKING:
    from ..scene import Scene


SHELL_MODEL, SHELL_MESH = "fem3d.naghdi", "mesh.midsurface"
"""The shell model's modules (the solid model is every other module of fem3d and mesh)."""
SHELL_SOLVER = ("fem3d.eigensolver", "fem3d.block_lanczos", "fem3d.identify")
"""The modules the shell model shares with the solid one (its solve and its mode names)."""

SOLID_CONSUMERS = ("modal_summary", "pillar_modes", "full_order", "full_order_result", "output")
"""fem3d modules that use the 3D modes but do not compute them."""

CACHE_VERSION = 4  # 3: an Entry of a ConvergenceRun record (msgspec); 4: a study on more than one
# worker before the executor gave each map call its own task keys may have cached a run under
# another rung's key (the round before's result): every such run is computed again
"""Bump to invalidate every cached run (the layout of a cached result changed)."""


@functools.cache
def _code(model: str) -> str:
    """The hash of the source files a model's results depend on, once a process: the
    package's code does not change while it runs, and the tornado's nine studies asked
    for the runs' keys 1,659 times (1.4 s of listing and hashing the same files)."""
    return source_hash(_source_files(model))


def _source_files(model: str) -> list[Path]:
    """The source files a model's results depend on (their hash is in the cache key)."""
    root = Path(__file__).parent.parent
    tower = [root / "reduced" / "tower.py", root / "reduced" / "foundation.py", root / "scene" / "tower.py"]
    if model == "closed_form":
        return [root / "reduced" / "pillar.py", root / "reduced" / "cylinder.py", *tower]
    if model == "beam":
        return [root / "reduced" / "beam_fe.py", root / "reduced" / "pillar.py", *tower]
    shell = [root / (m.replace(".", "/") + ".py") for m in (SHELL_MODEL, SHELL_MESH)]
    if model == "shell":
        return shell + [root / (m.replace(".", "/") + ".py") for m in SHELL_SOLVER]
    # the solid model: every module of fem3d and mesh but the shell's and those
    # that only use the modes (a change there leaves the cached frequencies valid)
    files = sorted((root / "fem3d").glob("*.py")) + sorted((root / "mesh").glob("*.py"))
    after = {root / "fem3d" / f"{m}.py" for m in SOLID_CONSUMERS}
    return [f for f in files if f not in shell and f not in after]


def case_key(case: Case, pillar, tolerance: float | None = None, foundation: Foundation | None = None) -> str:
    """Hash of everything a run's result depends on (``tolerance``: the 3D
    eigen-solve's, ``modal.tolerance``; the other models have their own)."""
    fam = FAMILIES[case.family]
    args = {
        "model": fam.model,
        "params": case.settings,
        "n_modes": N_MODES if fam.model in ("shell", "solid") else None,
        "tolerance": tolerance if fam.model == "solid" else None,
        "pillar": pillar_key(pillar),
        **foundation_key(foundation or Foundation()),
    }
    return cache_key(args, version=CACHE_VERSION, code=_code(fam.model))


def _run_in_process(case: Case, pillar, foundation: Foundation | None = None) -> RunResult:
    # time without tracemalloc (it slows Python code), then measure memory
    t0 = time.perf_counter()
    out = compute_in_process(case, pillar, foundation)
    wall = time.perf_counter() - t0
    tracemalloc.start()
    try:
        compute_in_process(case, pillar, foundation)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return msgspec.structs.replace(
        out, wall_time=wall, peak_memory=peak, memory_method="tracemalloc (Python heap peak)", timings={"total": wall}
    )


class ModelUnavailable(RuntimeError):
    """The model cannot run here (e.g. the 3D model is not installed)."""


UNAVAILABLE_EXIT = 3
"""Exit code of a worker whose model cannot be imported."""


def _jit_files() -> int:
    """How many files FFCx's disk cache holds (it grows when a form is compiled)."""
    from ..fem3d.dolfinx_import import import_dolfinx

    import_dolfinx()
    from dolfinx.jit import get_parameters

    root = Path(get_parameters()["cache_dir"])
    return sum(1 for _ in root.rglob("*")) if root.exists() else 0


def import_models() -> int:
    """Import what the models import lazily, so that every run is timed in the
    same state (imports excluded); returns their resident memory (bytes), the
    baseline a run adds to."""
    import importlib

    for name in (
        "gmsh",
        "ufl",
        "basix",
        "dolfinx",
        "dolfinx.fem.petsc",
        "dolfinx.io.gmshio",
        "petsc4py.PETSc",
        "slepc4py.SLEPc",
        "mpi4py.MPI",
    ):
        importlib.import_module(name)
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def run_one(case_file: str, out_file: str, baseline: int, *, per_run_peak: bool) -> None:
    """Run one FE case in this process, write its result JSON to ``out_file``.

    ``per_run_peak``: the process serves run after run (rotorpillar.converge.service):
    its memory high-water mark was reset for this run, and nothing is reused
    from a run before.  Else the process is fresh: its ru_maxrss is the run's.
    """
    from ..scene import scene_from_dict
    from .service import peak_memory, reset_peak_memory, resident_memory

    job = records.read(case_file, CaseFile)
    case = Case(job.family, job.level, tuple(job.params))
    scene_doc = dict(job.scene)
    scene = scene_from_dict(scene_doc, name=scene_doc.pop("name"))
    import importlib

    if FAMILIES[case.family].model == "solid":
        try:
            from ..fem3d import modal_analysis  # noqa: F401
        except ImportError as exc:
            raise ModelUnavailable(f"3D model unavailable: {exc}") from None
        importlib.import_module("rotorpillar.mesh")
    else:
        importlib.import_module(f"rotorpillar.{SHELL_MESH}")
    importlib.import_module(f"rotorpillar.{SHELL_MODEL}")
    start = 0
    if per_run_peak:
        start = resident_memory() or 0
        reset_peak_memory()
    jit_before = _jit_files()
    t0 = time.perf_counter()
    # Gmsh in this process: it is already the study's child (a crash in Gmsh ends it, and
    # the study records the run as failed); a meshing child would cost its interpreter's
    # start and imports (0.4-2 s) on every 3D run
    out = compute_fe(case, scene, fresh=per_run_peak, isolated=False)
    total = time.perf_counter() - t0
    compiled = _jit_files() > jit_before
    if compiled:
        # FFCx compiled forms in this run (once per machine and form): time it
        # again warm, as every later run of the family will be
        first = total
        if per_run_peak:
            # the warm run's own memory too: the first run's result is dropped and the
            # high-water mark starts again.  The file count is a heuristic that another
            # process compiling into the same cache also trips (seen in the test suite:
            # the served peak then held both runs, 19 % above a fresh process's)
            del out
            start = resident_memory() or 0
            reset_peak_memory()
        t0 = time.perf_counter()
        out = compute_fe(case, scene, fresh=True, isolated=False)
        total = time.perf_counter() - t0
        out = msgspec.structs.replace(out, first_run_with_compilation=first)
    # the model's whole time: mesh, forms, assembly, solve and naming the modes
    if per_run_peak:
        peak, method = (
            baseline + max((peak_memory() or start) - start, 0),
            (
                "baseline_memory (the imports) + the run's growth of the serving process's resident "
                "set (VmHWM reset before the run, over the resident set at its start)"
            ),
        )
    else:
        peak, method = (
            resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
            "ru_maxrss of a fresh subprocess (includes ~baseline_memory of imports)",
        )
    out = msgspec.structs.replace(
        out, wall_time=total, peak_memory=peak, baseline_memory=baseline, memory_method=method
    )
    write_json(out_file, out)


def serve(stdin=sys.stdin, replies=None) -> int:
    """The serving process's loop (rotorpillar.converge.service): each run it is sent, by ``run_one``.

    The replies go to the process's original stdout; file descriptor 1 then
    points at stderr, so that whatever a library prints (Python or C) lands
    in the log, never in the middle of the protocol."""
    import gc
    import os

    from .service import RETAINED_LIMIT, ServiceJob, ServiceReply, reset_peak_memory, resident_memory

    if replies is None:
        sys.stdout.flush()
        replies = os.fdopen(os.dup(1), "w")
        os.dup2(2, 1)
    baseline = import_models()
    imported = resident_memory() or 0
    # What the imports made lives as long as the process: kept out of the collections that
    # resident_memory runs before and after every run (each scanned ~70k objects, 15-30 ms;
    # ~10 s of CPU over the test suite's served runs), the resident set they measure the same
    gc.freeze()
    reusable = reset_peak_memory()
    for line in stdin:
        if not line.strip():
            continue
        job = records.decode(line, ServiceJob)
        status, error = "ok", None
        try:
            run_one(job.case, job.out, baseline, per_run_peak=reusable)
        except ModelUnavailable as exc:
            status, error = "unavailable", str(exc)
        except Exception as exc:  # the parent records the run as failed and goes on
            status, error = "error", f"{type(exc).__name__}: {exc}"
        last = not reusable or (resident_memory() or 0) - imported > RETAINED_LIMIT
        replies.write(records.encode(ServiceReply(status=status, error=error, last=last)).decode() + "\n")
        replies.flush()
        if last:
            return 0
    return 0


def worker(case_file: str, out_file: str) -> None:
    """One-shot subprocess entry (``python -m rotorpillar.converge CASE RESULT``)."""
    baseline = import_models()
    try:
        run_one(case_file, out_file, baseline, per_run_peak=False)
    except ModelUnavailable as exc:
        print(exc, file=sys.stderr)
        sys.exit(UNAVAILABLE_EXIT)


def _run_in_service(case: Case, scene: Scene) -> RunResult:
    from .service import service

    with tempfile.TemporaryDirectory(prefix="rotorpillar-converge-") as tmp:
        case_file, out_file = Path(tmp) / "case.json", Path(tmp) / "result.json"
        write_json(case_file, CaseFile(case.family, case.level, tuple(case.params), scene.to_dict()))
        t0 = time.perf_counter()
        reply = service().run(case_file, out_file)
        elapsed = time.perf_counter() - t0
        if reply.status == "unavailable":
            raise ModelUnavailable(reply.error)
        if reply.status != "ok" or not out_file.exists():
            raise RuntimeError(f"{case.label}: worker failed: {reply.error}")
        out = records.read(out_file, RunResult)
    return msgspec.structs.replace(out, process_time=elapsed)


def run_point(case: Case, scene: Scene) -> RunResult:
    """Compute one case (in-process or in the serving process, by model)."""
    if FAMILIES[case.family].model in ("closed_form", "beam"):
        return _run_in_process(case, scene.pillar, scene.foundation)
    return _run_in_service(case, scene)


def run_record(
    case: Case, key: str, result: RunResult | None, status: str = "ok", error: str | None = None
) -> ConvergenceRun:
    """A run of the ladder: its case and what it computed (no errors yet:
    rotorpillar.converge.selection.attach_errors gives them); a run that failed or could
    not run has no ``result`` but its ``status`` and ``error``: why."""
    return ConvergenceRun(
        key=key,
        family=case.family,
        model=FAMILIES[case.family].model,
        label=case.label,
        level=case.level,
        params=case.settings,
        status=status,
        error=error,
        cached=False,
        **(msgspec.structs.asdict(result) if result is not None else {}),
    )


def cache_entry(run: ConvergenceRun) -> ConvergenceRun:
    """The run as its cache file holds it: its case and its result, without what this
    study made of it (its errors against the reference, the alias dropped) and whether
    it came from the cache."""
    errors = {f"{q}_{kind}": None for q in QUANTITIES for kind in ERROR_KINDS}
    return msgspec.structs.replace(run, cached=False, ovalling_alias=None, **errors)  # type: ignore[arg-type]


#: The [converge] key that bounds each finite-element family's finest run.
LIMIT_KEYS = {
    "shell_quad": "shell_max_around",
    "shell_tri": "shell_tri_max_around",
    "solid_hex_p1": "solid_p1_max_around",
    "solid_tet_p1": "solid_p1_max_around",
    "solid_hex_p2": "solid_p2_max_around",
    "solid_hex_p2_around": "solid_p2_max_around",
    "solid_tet_p2": "solid_tet_p2_max_around",
}


def check_study_memory(cases: list[Case], workers: int) -> None:
    """Refuse (InputError, before any run) finite-element runs this process's memory limit
    cannot hold: the largest alone, or the ``workers`` largest at once (the longest run
    first on every worker: the largest start together).  Per run: mesh.tube.BYTES_PER_DOF
    per DOF (one modal solve), shells counted as the solids."""
    from ..mesh.tube import BYTES_PER_DOF
    from ..provenance import check_memory, memory_limit

    fe = sorted(
        ((estimated_dofs(c), c) for c in cases if FAMILIES[c.family].model in ("shell", "solid")), key=lambda t: -t[0]
    )
    if not fe:
        return
    dofs, big = fe[0]
    check_memory(
        BYTES_PER_DOF * dofs,
        f"converge: its largest run, {big.label} ({dofs:,} DOFs),",
        f"lower converge.{LIMIT_KEYS.get(big.family, 'solid_p2_max_around')} or set converge.solid = false",
    )
    at_once = fe[: max(1, workers)]
    need = BYTES_PER_DOF * sum(d for d, _ in at_once)
    budget, fit, total = memory_limit().budget, 0, 0.0
    for d, _ in at_once:
        total += BYTES_PER_DOF * d
        fit += total <= budget
    check_memory(
        need,
        f"converge: {len(at_once)} runs at once on {workers} workers (the largest first: "
        + ", ".join(c.label for _, c in at_once)
        + ")",
        f"use --workers {max(fit, 1)}",
    )


def todo_cases(cases: list[Case], scene: Scene, cache_dir: Path) -> list[Case]:
    """The cases the run cache under ``cache_dir`` does not hold."""
    cache = DiskCache(Path(cache_dir))
    return [
        c
        for c in cases
        if _load_cached(cache, case_key(c, scene.pillar, scene.modal.tolerance, scene.foundation)) is None
    ]


def run_study(
    cases: list[Case],
    scene: Scene,
    cache_dir: Path,
    *,
    runner: Callable[[Case, Scene], RunResult] = run_point,
    progress: bool = True,
    log: Callable[[str], None] | None = None,
    workers: int = 1,
    executor=None,
    close: bool = True,
) -> list[ConvergenceRun]:
    """Every case, each loaded from ``cache_dir`` or computed and cached.

    A run is written to ``cache_dir/<key>.json`` atomically as soon as it
    finishes, so an interruption (KeyboardInterrupt included) loses at most
    the runs under way and leaves no partial file.  A run that fails is
    recorded as failed and not cached (it is tried again next time).

    ``workers`` > 1 (or an ``executor``, rotorpillar.executor.Executor): the
    runs go to a Dask LocalCluster of that many single-threaded workers, the
    longest (by estimate) first; each worker hands the run to its serving process, so
    that many finite-element runs run at once.  The results are the same;
    a run's wall time is its own process's (measured inside it).  ``close``: end this
    process's serving processes when done (False: the next call reuses them).
    """
    from tqdm import tqdm

    cache = DiskCache(Path(cache_dir))
    keys = [case_key(c, scene.pillar, scene.modal.tolerance, scene.foundation) for c in cases]
    runs: list[ConvergenceRun | None] = [None] * len(cases)
    todo = []
    for i, (c, key) in enumerate(zip(cases, keys)):
        cached = _load_cached(cache, key)
        if cached is not None:
            # names follow the code and the case, not the cache (they are not part of the key)
            runs[i] = msgspec.structs.replace(
                resolved_only(c.family, cached),
                label=c.label,
                family=c.family,
                level=c.level,  # a run shared by two families (one key) was cached by either
                model=FAMILIES[c.family].model,
                cached=True,
            )
        else:
            todo.append(i)
    # two families may share a run (one key: the around-only sweep's rung at the scene's
    # cells along is a rung of the along-only family): it is computed once for both
    n_cached = len(cases) - len(todo)
    twins: dict[int, list[int]] = {}
    first: dict[str, int] = {}
    for i in todo:
        if keys[i] in first:
            twins[first[keys[i]]].append(i)
        else:
            first[keys[i]], twins[i] = i, []
    todo = list(twins)
    check_study_memory([cases[i] for i in todo], workers)
    if log:
        log(
            f"converge: {len(cases)} runs, {n_cached} cached, {len(todo)} to compute"
            + (f" on {workers} workers" if (workers > 1 or executor) and todo else "")
        )
    weights = {i: estimated_seconds(cases[i]) for i in todo}
    bar = tqdm(
        total=sum(weights.values()),
        disable=not progress or not todo,
        unit="s~",
        file=sys.stderr,
        bar_format="{l_bar}{bar}| {n:.0f}/{total:.0f} est. s [{elapsed}<{remaining}] {postfix}",
    )
    unavailable = {}

    def finish(i, result=None, exc=None):
        for j in (i, *twins[i]):
            finish_one(j, result, exc)

    def finish_one(i, result=None, exc=None):
        case, key = cases[i], keys[i]
        model = FAMILIES[case.family].model
        if isinstance(exc, ModelUnavailable) or (exc is None and model in unavailable):
            if exc is not None and model not in unavailable:
                unavailable[model] = str(exc)
                if log:
                    log(f"converge: skipping the {model} runs: {exc}")
            runs[i] = run_record(case, key, None, "unavailable", unavailable[model])
        elif isinstance(exc, (RuntimeError, ValueError, ArithmeticError)):
            runs[i] = run_record(case, key, None, "failed", str(exc))
        elif exc is not None:
            raise exc
        else:
            rec = run_record(case, key, result)
            cache.write(key, cache_entry(rec))
            runs[i] = resolved_only(case.family, rec)
        bar.set_postfix_str(case.label)
        bar.update(weights.get(i, 0.0))  # a twin (i not in todo) costs nothing more

    try:
        if todo and (workers > 1 or executor is not None):
            _run_parallel(todo, cases, scene, runner, workers, executor, finish, weights)
        else:
            for i in todo:
                bar.set_postfix_str(cases[i].label)
                if FAMILIES[cases[i].family].model in unavailable:
                    finish(i)
                    continue
                try:
                    result = runner(cases[i], scene)
                except (ModelUnavailable, RuntimeError, ValueError, ArithmeticError) as exc:
                    finish(i, exc=exc)
                else:
                    finish(i, result)
    finally:
        bar.close()
        if close:
            from .service import close_services

            close_services()
    return [r for r in runs if r is not None]  # finish() filled every one


def _guarded(job):
    """A worker's call of the runner: its expected failures come back as values."""
    runner, case, scene = job
    try:
        return runner(case, scene), None
    except (ModelUnavailable, RuntimeError, ValueError, ArithmeticError) as exc:
        return None, exc


def _run_parallel(todo, cases, scene: Scene, runner, workers, executor, finish, weights) -> None:
    from ..executor import Executor

    order = sorted(todo, key=lambda i: -weights[i])  # longest first
    ex = executor or Executor(workers)
    own = executor is None
    if own:
        ex.__enter__()
    try:
        for j, done in ex.map(_guarded, [(runner, cases[i], scene) for i in order]):
            result, exc = done  # type: ignore[misc]  # _guarded's (result, exception)
            finish(order[j], result, exc)
    finally:
        if own:
            ex.__exit__(None, None, None)


def _load_cached(cache: DiskCache, key: str) -> ConvergenceRun | None:
    """The run cached under ``key``; a damaged file or a failed run is no cached run (None:
    recompute it)."""
    return cache.read(key, ConvergenceRun, accept=lambda run: run.status == "ok")
