"""`rotorpillar study`: a design study over a product of scene keys, on Dask.

``rotorpillar study [SCENE] --case runup|rundown|earthquake --vary
KEY=START:STOP:N [--vary KEY=v1,v2,...]... [--model paper|modal]
[--scheduler ADDRESS] [--workers N] [--out DIR]``.  Writes into
``out/<scene>/``: ``study.json`` (this command's record: the axes, every
run, the boundary, the executor, the batches and the speed), ``study.csv``
(one row a run), the charts ``study_capture_map.png`` (run-ups over two
axes), ``study_final.png`` (one axis) or ``study_ida.png`` (earthquakes),
and the batches under ``study/`` (a rerun computes only those missing).
The study itself is :func:`rotorpillar.studies.design_study`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene
    from ..studies.result import StudyResult

from ..scene import STUDY_CASES, STUDY_MODELS
from . import Done, progress


def add_arguments(p) -> None:
    p.add_argument("--case", choices=STUDY_CASES, default="runup", help="which transient each run is (default: runup)")
    p.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="KEY=START:STOP:N|KEY=v1,v2,...",
        help="an axis: N values from START to STOP, or a list (repeatable; the study "
        "runs their product), e.g. --vary drive.torque_at_zero=560:700:15",
    )
    p.add_argument(
        "--model",
        choices=STUDY_MODELS,
        default=None,
        help="the paper's Eq. 4 as published, the pillar by its modes, or the 1D beam "
        "at full order (default: the scene's simulate.model)",
    )
    p.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="run on this Dask scheduler (tcp://HOST:PORT) instead of a local cluster",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="local cluster: N worker processes (default: one per core)",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def study_command(scene: Scene, args, timings):
    from ..executor import Executor, probe_scheduler
    from . import out_dir

    Executor(args.workers, args.scheduler)  # bad --workers / --scheduler: refused now
    if args.scheduler:
        probe_scheduler(args.scheduler)  # before the study's modes and batches
    from ..postprocess.study_charts import study_charts
    from ..studies import design_study

    which = args.model or scene.simulate.model
    with timings("study"):
        res = design_study(
            scene,
            args.case,
            which,
            args.vary,
            out_dir=out_dir(scene, args),
            workers=args.workers,
            scheduler=args.scheduler,
            show_progress=not args.no_progress,
            charts=study_charts,
            log=progress,
        )
    timings["cluster_start"] = res.performance.cluster_start_seconds
    timings["compute_wall"] = res.performance.compute_wall_seconds
    return Done(res, _summary(res))


def _summary(r: StudyResult) -> str:
    p, b, ex = r.performance, r.batches, r.executor
    axes = " x ".join(f"{a.key} ({len(a.values)})" for a in r.axes)
    lines = [
        f"rotorpillar study {r.scene_name}: {r.case}, {r.model} model, {len(r.runs)} runs over {axes}",
        f"  batches: {b.total} ({b.cached} on disk, {b.computed} computed); "
        f"executor: {ex.kind}" + (f" at {ex.scheduler}, {ex.workers} workers" if ex.scheduler else ""),
        f"  {p.runs_computed} runs computed in {p.compute_wall_seconds:.2f} s"
        + (f" ({p.runs_per_second:.1f} runs/s)" if p.runs_per_second else "")
        + f"; wall {p.wall_seconds:.1f} s",
    ]
    if r.case != "earthquake":
        passed = sum(bool(x.passed) for x in r.runs)
        lines.append(f"  passed {passed} of {len(r.runs)}; captured {len(r.runs) - passed}")
    else:
        lines.append(
            f"  peak tip {max(r.values('peak_tip')):.4g} m, peak shaft deflection "
            f"{max(r.values('peak_shaft_deflection')):.4g} m (largest over the runs)"
        )
    found = r.boundary.found if r.boundary is not None else None
    other_key = getattr(r.boundary.predicted, "other_key", None) if r.boundary is not None else None
    for row in found or ():
        x = "" if row.other is None else f"{other_key} = {row.other:g}: "
        lo, hi = row.captured_max, row.passed_min
        lines.append(
            f"  {x}captured up to {'-' if lo is None else format(lo, '.1f')}, passes from "
            f"{'-' if hi is None else format(hi, '.1f')} N*m"
        )
    for f in r.figures:
        lines.append(f"  chart: {f.file}")
    if r.files is not None:
        lines.append(f"  table: {r.files.csv}")
    return "\n".join(lines)
