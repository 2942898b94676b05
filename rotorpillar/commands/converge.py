"""`rotorpillar converge`: the ladder of pillar models, refined, and the model a scene needs.

Writes ``convergence.json`` (every run, the reference values, observed
orders, Pareto fronts, failures and the chosen model), the two charts
``convergence_dofs.png`` and ``convergence_time.png``, and the usual
``converge.json`` record.  Runs are cached under ``<out>/cache/`` (or
``--cache DIR``): a second call, or one after an interruption, computes only
what is missing.  The study itself is :func:`rotorpillar.converge.study`;
this module holds its arguments and its summary.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..converge.result import ConvergenceStudy
    from ..scene import Scene

from pathlib import Path

from ..converge.refinement import LadderRefinement
from ..converge.result import ModelSelection, ReferenceValue, StudyCounts
from ..errors import InputError
from ..records import Record
from . import Done, progress


def add_arguments(p) -> None:
    p.add_argument("--cache", type=Path, default=None, metavar="DIR", help="run cache directory (default: <out>/cache)")
    p.add_argument(
        "--tolerance",
        type=float,
        default=None,
        metavar="TOL",
        help="relative frequency tolerance of the chosen model (default: the scene's converge.tolerance)",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument(
        "--full-ladder",
        action="store_true",
        help="run every rung of every family (default: each refined only as far as the choice needs)",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="runs at once, on a Dask LocalCluster (default: one per core; 1 = serially in this process)",
    )


def add_modal_arguments(p) -> None:
    """`rotorpillar modal --tolerance TOL`: run the model the study picks for TOL."""
    p.add_argument(
        "--tolerance",
        type=float,
        default=None,
        metavar="TOL",
        help="pick the cheapest 3D mesh that meets this relative frequency "
        "tolerance over the scene's band, from the convergence study "
        "(run, or loaded from its cache: see `rotorpillar converge`)",
    )
    p.add_argument(
        "--cache", type=Path, default=None, metavar="DIR", help="the study's run cache (default: <out>/cache)"
    )


def _summary(st: ConvergenceStudy) -> str:
    """The study in words: counts, references, orders, band, front, choice and failures."""
    ref, sel, n = st.reference, st.selection, st.study
    lines = [
        f"rotorpillar converge {st.scene_name}: {n.runs} runs "
        f"({n.cached} cached, {n.computed} computed, "
        f"{n.failed} failed) in {n.wall_time or 0.0:.0f} s",
        "",
        "Reference values (Richardson on the finest three runs):",
    ]
    for q, r in ref.items():
        p = "n/a" if r.order is None else f"{r.order:.2f}"
        lines.append(
            f"  first {q:9s} {r.value:10.4f} rad/s +- {r.error_estimate:.1e} "
            f"({st.families[r.family].label}; observed order {p}, "
            f"theory {r.order_theory:g})"
        )
        if r.check is not None:
            c = r.check
            lines.append(
                f"    check: from the three runs before, {c.value:.4f} +- "
                f"{c.error_estimate:.1e}; the finer run gives {c.finer_value:.4f} "
                f"({'within' if c.within_estimate else 'OUTSIDE'} the estimate)"
            )
    lines += ["", "Observed orders per family (theory in brackets):"]
    for fam, qs in st.extrapolations.items():
        parts = [
            f"{q} {('n/a' if e.order is None else format(e.order, '.2f'))} [{e.order_theory:g}] -> {e.value:.4f}"
            for q, e in qs.items()
        ]
        lines.append(f"  {st.families[fam].label:34s} " + "; ".join(parts))
    b = sel.band
    lines += [
        "",
        f"Band: up to {b.omega_max:.1f} rad/s = {b.margin:g} x "
        f"max(drive free speed {b.free_speed:.1f}, earthquake "
        f"{b.earthquake_frequency:.2f}) rad/s; needs: {', '.join(sel.needed)}",
        "Pareto front (band error vs wall time): " + ", ".join(st.pareto.wall_time.band),
    ]
    lines += [
        "",
        f"Chosen at tolerance {sel.tolerance:g}: " + (sel.chosen.label if sel.chosen else "none"),
        "  " + sel.reason,
    ]
    rf = st.refinement
    if rf is not None and not rf.full:
        lines += ["", f"Refined: {rf.runs} of the ladder's {rf.ladder_runs} runs, in {rf.rounds} rounds:"]
        lines += [f"  {st.families[f.family].label:34s} {f.runs}/{f.rungs}: {f.stop} ({f.why})" for f in rf.families]
    if st.failures:
        lines += ["", "Where methods fail:"] + [f"  - {f}" for f in st.failures]
    if st.charts is not None:
        lines += ["", "charts: " + ", ".join(st.charts.values()), f"study: {st.json_file}"]
    return "\n".join(lines)


def _under_mpi() -> bool:
    import os

    return any(int(os.environ.get(k, "1")) > 1 for k in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE"))


def preflight(scene: Scene, args) -> None:
    """What `converge` refuses before any work (`run` calls it for its stage too): MPI,
    --workers, --tolerance, and runs (not in the cache) this process's memory cannot hold."""
    from ..executor import check_workers, default_workers
    from . import out_dir

    if _under_mpi():
        raise InputError(
            "rotorpillar converge runs its runs as subprocesses (--workers at once): start it without mpirun"
        )
    check_workers(args.workers)
    from ..converge.ladder import study_cases
    from ..converge.runner import check_study_memory, todo_cases
    from ..converge.study import check_tolerance

    check_tolerance(scene.converge.tolerance if args.tolerance is None else args.tolerance)
    cache = out_dir(scene, args) / "cache" if args.cache is None else args.cache
    check_study_memory(
        todo_cases(study_cases(scene), scene, cache), default_workers() if args.workers is None else args.workers
    )


def converge_command(scene: Scene, args, timings):
    from . import out_dir

    preflight(scene, args)
    from ..converge import study
    from ..executor import default_workers
    from ..postprocess.convergence_charts import convergence_charts

    workers = default_workers() if args.workers is None else args.workers
    st = study(
        scene,
        out_dir=out_dir(scene, args),
        cache_dir=args.cache,
        tolerance=args.tolerance,
        show_progress=not args.no_progress,
        charts=convergence_charts,
        timings=timings,
        log=progress,
        workers=workers,
        full=getattr(args, "full_ladder", False),
    )
    result = ConvergeRun(
        convergence_json=st.json_file,
        charts=st.charts or {},
        tolerance=st.tolerance,
        reference=st.reference,
        selection=st.selection,
        failures=st.failures,
        study=st.study,
        refinement=st.refinement,
    )
    return Done(result, _summary(st))


class ConvergeRun(Record):
    """converge.json: where the study was written and its headline (the whole study is
    convergence.json's ``ConvergenceStudy``)."""

    convergence_json: str | None
    """the convergence.json written"""
    charts: dict[str, str]
    """chart name -> path"""
    tolerance: float
    """relative frequency tolerance of the choice (-)"""
    reference: dict[str, ReferenceValue]
    """per quantity: Richardson on the finest runs of the best family"""
    selection: ModelSelection
    """the model chosen for the scene's band"""
    failures: tuple[str, ...]
    """where methods fail, one sentence each"""
    study: StudyCounts
    """the runs and their time"""
    refinement: LadderRefinement | None
    """how far each family was refined, and why no further"""
