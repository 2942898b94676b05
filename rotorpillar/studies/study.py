"""A design study: the product of the axes, run as batches on Dask, cached, resumable.

``design_study(scene, case, model, vary, ...)`` checks the axes (bad input:
InputError before anything is written), plans the batches (runs sorted so
that runs sharing a compiled model sit together, then cut into batches of at
most ``BATCH_RUNS``), loads the batches already on disk, computes the rest on
the executor (``rotorpillar.executor.Executor``: a LocalCluster by default,
or a scheduler's address) with a progress bar over the runs, writes each
finished batch at once (one small JSON under ``<cache>/<key>.json``,
atomically: Ctrl-C leaves the finished batches, a rerun computes only the
missing ones), then writes study.csv, asks ``charts`` for the figures and
returns the ``StudyResult`` (which the command writes as study.json).

A batch's key hashes the resolved scene, the case, the model, its runs'
parameters and the source of the code that computes them, so a changed scene
or code never reuses a stale batch.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from pathlib import Path

from .. import records
from ..cache import DiskCache, cache_key, source_hash
from ..errors import InputError
from ..executor import Executor
from ..provenance import write_text
from ..records import Figure, replace
from ..scene import STUDY_CASES, STUDY_MODELS, Scene
from .axes import Param, check_points, implied_settings, parse_axes, run_scene
from .batch import BatchResult, BatchSpec, PlannedRun, group_key, run_batch
from .boundary import StudyBoundary, found_boundary, predicted_boundary
from .modes import StudyModes
from .result import BatchCounts, ExecutorInfo, StudyFiles, StudyPerformance, StudyResult

#: the most runs in one batch: small enough to spread a study over the
#: workers and to lose little to a Ctrl-C, large enough that the batch loop's
#: speed is not lost to the per-batch overhead (~10 ms against ~60 ms a run)
BATCH_RUNS = 8
CACHE_VERSION = 2  # 2: an Entry of a BatchResult record (msgspec)
CSV_RESULTS = (
    "final_speed",
    "final_speed_mean",
    "captured_at",
    "speed_state",
    "passed",
    "peak_tip",
    "peak_shaft_deflection",
    "free_speed",
    "pga",
    "ok",
    "nfev",
)

Charts = Callable[[StudyResult, Path], list[Figure]]
"""Draws a study's charts: (result, out_dir) -> figures."""


def _source_hash() -> str:
    root = Path(__file__).parent.parent
    return source_hash(sorted((root / "reduced").glob("*.py")) + sorted((root / "studies").glob("*.py")))


def plan(points: list[dict[str, Param]], case: str, batch_runs: int = BATCH_RUNS) -> list[list[PlannedRun]]:
    """The batches: runs sorted by what they must share, cut into near-equal chunks."""
    runs = [PlannedRun(i, p) for i, p in enumerate(points)]
    runs.sort(key=lambda r: (repr(group_key(r.params, case)), r.index))
    if not runs:
        return []
    nb = math.ceil(len(runs) / batch_runs)
    cuts = [round(i * len(runs) / nb) for i in range(nb + 1)]
    return [runs[a:b] for a, b in zip(cuts, cuts[1:])]


def batch_key(spec: BatchSpec, source: str) -> str:
    """The batch's key in the cache: its spec and the code (``source``) that computes it."""
    return cache_key(records.to_builtins(spec), version=CACHE_VERSION, code=source)


def _check_inputs(scene: Scene, case: str, model: str, vary: list[str]):
    if case not in STUDY_CASES:
        raise InputError(f"--case {case!r}: a study runs one of {', '.join(STUDY_CASES)}")
    if model not in STUDY_MODELS:
        raise InputError(f"--model {model!r}: a study runs one of {', '.join(STUDY_MODELS)}")
    if scene.reduction.source == "fem3d" and model == "paper":
        raise InputError(
            'reduction.source = "fem3d": a study runs the reduced models only; '
            "use the stated or closed-form reduction for the paper model"
        )
    axes = parse_axes(vary, scene)
    implied = implied_settings(axes, case, scene)
    points = check_points(scene, axes, implied)
    if case == "earthquake":
        from ..reduced.excitation import BUILTIN_RECORDS
        from ..reduced.models import scene_motion
        from ..transients.run_plan import own_duration

        windows = {
            tuple((k, v) for k, v in p.items() if k.startswith("excitation.") or k == "simulate.earthquake_duration")
            for p in points
        }
        # every record readable before anything runs, each once; the user's files before
        # the built-in records (whose library takes seconds to import): a bad file, at once;
        # and every run long enough to see its ground motion
        for m in sorted(windows, key=lambda m: (any(v in BUILTIN_RECORDS for _, v in m), repr(m))):
            sc = run_scene(scene, dict(m), implied)
            own_duration(sc, "earthquake", scene_motion(sc))
    return axes, implied, points


def design_study(
    scene: Scene,
    case: str,
    model: str,
    vary: list[str],
    *,
    out_dir: Path,
    workers: int | None = None,
    scheduler: str | None = None,
    cache_dir: Path | None = None,
    show_progress: bool = True,
    charts: Charts | None = None,
    log: Callable[[str], None] | None = None,
    executor: Executor | None = None,
    write_csv: bool = True,
) -> StudyResult:
    """Run (or load) every batch of the study and condense it (see the module text).

    ``write_csv``: write study.csv in ``out_dir`` (False: a study inside another command,
    such as `tornado`, which must not overwrite the scene's own study.csv).
    """
    from tqdm import tqdm

    start = time.perf_counter()
    axes, implied, points = _check_inputs(scene, case, model, vary)
    out_dir = Path(out_dir)
    cache_dir = out_dir / "study" if cache_dir is None else Path(cache_dir)
    cache = DiskCache(cache_dir)
    batches = plan(points, case)
    source = _source_hash()
    scene_doc = scene.to_dict()
    modes = StudyModes(scene, out_dir, log) if model == "modal" else None
    specs, keys = [], []
    for b in batches:
        table = None
        if modes is not None:
            scenes = [run_scene(scene, p.params, implied) for p in b]
            for sc in scenes:
                modes(sc)
            table = {modes.key(sc): modes.table[modes.key(sc)] for sc in scenes}
        spec = BatchSpec(scene_doc, case, model, implied, tuple(b), table)
        specs.append(spec)
        keys.append(batch_key(spec, source))
    done: dict[int, BatchResult] = {}
    for i, k in enumerate(keys):
        got = cache.read(k, BatchResult)  # a damaged file is no finished batch: recomputed
        if got is not None:
            done[i] = got
    todo = [i for i in range(len(batches)) if i not in done]
    n_cached = sum(len(batches[i]) for i in done)
    if log:
        log(
            f"study {scene.name}: {case}, {len(points)} runs in {len(batches)} batches "
            f"({len(done)} on disk, {len(todo)} to compute)"
        )
    # before the cluster: the curve builds a scene per point, and its refusal must come first
    predicted = predicted_boundary(scene, case, model, axes, implied, modes)
    info = ExecutorInfo("none (every batch on disk)", None, 0, 0)
    t_cluster = t_compute = compute = 0.0
    if todo:
        t0 = time.perf_counter()
        ex = executor or Executor(workers, scheduler)
        own = executor is None
        if own:
            ex.__enter__()
        try:
            info = ex.describe()
            t_cluster = time.perf_counter() - t0
            if log:
                log(f"study: {info.kind} at {info.scheduler}, {info.workers} workers")
            bar = tqdm(
                total=len(points),
                initial=n_cached,
                disable=not show_progress,
                unit="run",
                file=sys.stderr,
                desc="study",
            )
            t1 = time.perf_counter()
            try:
                for j, res in ex.map(run_batch, [specs[i] for i in todo]):
                    i = todo[j]
                    cache.write(keys[i], res)
                    done[i] = res
                    compute += res.wall_seconds
                    bar.update(len(res.runs))
            finally:
                bar.close()
            t_compute = time.perf_counter() - t1
        finally:
            if own:
                ex.__exit__(None, None, None)
    runs = [replace(r, batch=k) for i, k in enumerate(keys) for r in done[i].runs]
    runs.sort(key=lambda r: r.index)
    found = found_boundary(axes, runs) if case == "runup" else None
    boundary = StudyBoundary(predicted, found) if predicted is not None or found else None
    n_computed = len(points) - n_cached
    result = StudyResult(
        scene_name=scene.name,
        case=case,
        model=model,
        axes=axes,
        implied=implied,
        runs=tuple(runs),
        boundary=boundary,
        executor=info,
        batches=BatchCounts(
            total=len(batches),
            cached=len(done) - len(todo),
            computed=len(todo),
            runs_per_batch_max=BATCH_RUNS,
            groups=sum(d.groups for d in done.values()),
            cache_dir=str(cache_dir),
        ),
        performance=StudyPerformance(
            runs=len(points),
            runs_computed=n_computed,
            cluster_start_seconds=t_cluster,
            compute_wall_seconds=t_compute,
            batch_seconds=compute,
            runs_per_second=n_computed / t_compute if t_compute > 0 else None,
            wall_seconds=0.0,
        ),
    )
    csv = write_text(out_dir / "study.csv", study_csv(result)) if write_csv else None
    figures = charts(result, out_dir) if charts is not None else []
    return replace(
        result,
        figures=tuple(figures),
        performance=replace(result.performance, wall_seconds=time.perf_counter() - start),
        pillar_model=modes.pillar_model if modes is not None else None,
        files=None if csv is None else StudyFiles(csv=str(csv), cache_dir=str(cache_dir)),
    )


def study_csv(result: StudyResult) -> str:
    """One row a run: index, the axes' values, then the results (SI units: rad/s, m, m/s2).

    Plain: the header is the first line (no comment line, which csv.DictReader,
    spreadsheets and pandas would take for the header); the study's
    provenance is in study.json beside it.
    """
    keys = [a.key for a in result.axes]
    cols = ["index", *keys, *CSV_RESULTS]

    def cell(v):
        if v is None:
            return ""
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, float):
            return f"{v:.10g}"
        s = str(v)
        return '"' + s.replace('"', '""') + '"' if ("," in s or '"' in s) else s

    lines = [",".join(cols)]
    for r in result.runs:
        row = [r.index, *(r.params.get(k) for k in keys), *(getattr(r, c) for c in CSV_RESULTS)]
        lines.append(",".join(cell(v) for v in row))
    return "\n".join(lines) + "\n"
