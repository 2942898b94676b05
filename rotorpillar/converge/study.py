"""The convergence study of a scene: run (or load) the ladder, analyse it, write it.

From the runs: reference values by Richardson extrapolation of the finest
runs of the most complete family, each run's error against them, the Pareto
fronts of error against DOFs and against wall time, the failures in words,
and the cheapest model that meets a tolerance over the scene's band.
:func:`study` writes it all to ``convergence.json`` as a
:class:`ConvergenceStudy`; :func:`model_for_modal` picks the 3D mesh
`rotorpillar modal --tolerance` runs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..scene import Scene

import dataclasses
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from ..errors import InputError
from ..provenance import Timings, write_result
from ..records import Record, replace
from .adaptive import run_ladder
from .failures import drop_aliases, failures
from .ladder import FAMILIES, QUANTITIES, study_cases
from .refinement import LadderRefinement
from .result import (
    ConvergenceRun,
    ConvergenceStudy,
    ExcitationBand,
    FamilyExtrapolation,
    FamilyInfo,
    Fronts,
    ModalModelSelection,
    ModelSelection,
    ParetoFronts,
    ReferenceValue,
    RunBrief,
    StudyCounts,
)
from .richardson import family_extrapolations, reference_values
from .runner import check_study_memory, run_study, todo_cases
from .selection import (
    attach_errors,
    band_error,
    brief,
    excitation_band,
    needed_quantities,
    pareto_front,
    reference_uncertainty,
    select_model,
)

Charts = Callable[[ConvergenceStudy, Path], dict]
"""Draws the study's charts into a directory: (the study, out_dir) -> name: path."""


class StudyAnalysis(Record):
    """What the study makes of its runs (the parts of convergence.json after the runs' own)."""

    runs: tuple[ConvergenceRun, ...]
    """the runs, their errors against the reference attached"""
    reference: dict[str, ReferenceValue]
    """per quantity: Richardson on the finest runs of the best family"""
    extrapolations: dict[str, dict[str, FamilyExtrapolation]]
    """per refined family, per quantity: Richardson on its three finest runs"""
    band: ExcitationBand
    selection: ModelSelection
    pareto: ParetoFronts
    failures: tuple[str, ...]
    """where methods fail, one sentence each"""


def analyse(records: Sequence[ConvergenceRun], scene: Scene, tolerance: float) -> StudyAnalysis:
    """Reference values, errors, fronts, failures and the chosen model, from the
    runner's runs (their aliased ovalling modes dropped first)."""
    dealiased = drop_aliases(records)
    extrapolations = family_extrapolations(dealiased)
    references = reference_values(dealiased, extrapolations)
    runs = attach_errors(dealiased, references, extrapolations)
    band = excitation_band(scene.drive, scene.load, scene.converge)
    selection = select_model(runs, references, band, tolerance)
    ref_unc = reference_uncertainty(references)
    ok = [r for r in runs if r.status == "ok"]
    fronts = ParetoFronts(
        dofs=_fronts(ok, "dofs", selection.needed, ref_unc),
        wall_time=_fronts(ok, "wall_time", selection.needed, ref_unc),
    )
    return StudyAnalysis(
        runs=runs,
        reference=references,
        extrapolations=extrapolations,
        band=band,
        selection=selection,
        pareto=fronts,
        failures=tuple(failures(runs, extrapolations, references, tolerance)),
    )


def _fronts(ok: list[ConvergenceRun], cost: str, needed: Sequence[str], ref_unc: dict[str, float]) -> Fronts:
    """The runs on the Pareto front of each error against ``cost`` ("dofs" or "wall_time")."""

    def front(errors: list[float | None]) -> tuple[str, ...]:
        return tuple(ok[i].label for i in pareto_front([getattr(r, cost) for r in ok], errors))

    return Fronts(
        bending=front([r.bending_error for r in ok]),
        ovalling=front([r.ovalling_error for r in ok]),
        band=front([band_error(r, needed, ref_unc) for r in ok]),
    )


def _compute_seconds(r: ConvergenceRun) -> float:
    """The time the study waited for a computed run (s): its serving process's, else its own."""
    seconds = r.process_time if r.process_time is not None else r.wall_time
    return seconds or 0.0


def check_tolerance(tolerance: float) -> None:
    """Refuse (InputError) a relative frequency tolerance outside (0, 1)."""
    if not 0 < tolerance < 1:
        raise InputError(f"--tolerance = {tolerance!r} is out of range: must be > 0 and < 1")


def study(
    scene: Scene,
    *,
    out_dir: Path,
    cache_dir: Path | None = None,
    tolerance: float | None = None,
    show_progress: bool = True,
    charts: Charts | None = None,
    timings=None,
    log: Callable[[str], None] | None = None,
    workers: int = 1,
    full: bool = False,
) -> ConvergenceStudy:
    """Run (or load) the study and analyse it; write convergence.json (and the charts).

    The ladder is refined as far as the choice needs (rotorpillar.converge.adaptive;
    ``full``: every rung).  ``workers`` > 1 runs that many at once
    (rotorpillar.executor: a Dask LocalCluster); ``charts`` draws the charts (the
    caller passes ``rotorpillar.postprocess.convergence_charts.convergence_charts``:
    plotting lives above this package); ``log`` takes the stage lines.
    """
    timings = Timings() if timings is None else timings
    tol = scene.converge.tolerance if tolerance is None else tolerance
    check_tolerance(tol)
    cache_dir = Path(out_dir) / "cache" if cache_dir is None else Path(cache_dir)
    start = time.perf_counter()
    with timings("study"):
        records, refinement = ladder_runs(
            scene, tol, cache_dir, progress=show_progress, log=log, workers=workers, full=full
        )
    with timings("analysis"):
        analysis = analyse(records, scene, tol)
    counts = StudyCounts(
        runs=len(records),
        workers=workers,
        cached=sum(r.cached for r in records),
        computed=sum(not r.cached for r in records),
        failed=sum(r.status == "failed" for r in records),
        unavailable=sum(r.status == "unavailable" for r in records),
        compute_seconds=sum(_compute_seconds(r) for r in records if not r.cached),
    )
    result = ConvergenceStudy(
        scene_name=scene.name,
        scene=scene.to_dict(),
        tolerance=tol,
        cache_dir=str(cache_dir),
        families={
            k: FamilyInfo(
                label=f.label, model=f.model, order_theory=f.order, quantities=tuple(f.quantities), sweep=f.sweep
            )
            for k, f in FAMILIES.items()
        },
        runs=analysis.runs,
        reference=analysis.reference,
        extrapolations=analysis.extrapolations,
        band=analysis.band,
        selection=analysis.selection,
        pareto=analysis.pareto,
        failures=analysis.failures,
        study=counts,
        refinement=refinement,
    )
    if charts is not None:
        with timings("charts"):
            drawn = charts(result, out_dir)
        result = replace(result, charts={k: str(v) for k, v in drawn.items()})
    result = replace(result, study=replace(counts, wall_time=time.perf_counter() - start))
    path = write_result(Path(out_dir) / "convergence.json", result, timings=dict(timings))
    return replace(result, json_file=str(path))


def ladder_runs(
    scene: Scene,
    tolerance: float,
    cache_dir: Path,
    *,
    runner: Callable | None = None,
    progress: bool = False,
    log: Callable[[str], None] | None = None,
    workers: int = 1,
    full: bool = False,
) -> tuple[list[ConvergenceRun], LadderRefinement]:
    """The study's runs, each loaded from ``cache_dir`` or computed, refined round by
    round as far as the choice at ``tolerance`` needs (``full``: every rung); one
    Dask cluster (``workers`` > 1) and the serving processes last the whole study."""
    from contextlib import ExitStack

    from ..executor import Executor
    from .service import close_services

    # refused before any run, as the whole ladder could ask (the refinement is not known yet)
    check_study_memory(todo_cases(study_cases(scene), scene, cache_dir), workers)
    extra = {} if runner is None else {"runner": runner}
    how = "every rung" if full else "each family then refined as far as the choice needs"
    with ExitStack() as stack:
        stack.callback(close_services)
        pool: list[Executor] = []  # started for the first round with a run to compute

        def run_round(cases, k):
            # one line: the first round's (the later ones are few runs each; the study's
            # summary says how many rounds it took)
            say = None if log is None or k else (lambda line: log(f"{line} (the first round; {how})"))
            if workers > 1 and not pool and todo_cases(cases, scene, cache_dir):
                pool.append(stack.enter_context(Executor(workers)))
            return run_study(
                cases,
                scene,
                cache_dir,
                progress=progress,
                log=say,
                workers=workers,
                executor=pool[0] if pool else None,
                close=False,
                **extra,
            )

        return run_ladder(scene, tolerance, run_round, study_cases(scene), full=full)


def _cached_study(scene: Scene, tolerance: float, cache_dir: Path) -> StudyAnalysis:
    """Under MPI: the runs from the cache only (a missing run is an input error)."""

    def runner(case, sc):
        # the ladder's runner contract: a case and the scene it runs on (here: the one to name)
        raise InputError(
            f"modal --tolerance under MPI needs the convergence study cached "
            f"({case.label} is not): run `rotorpillar converge {sc.name}` "
            "serially first"
        )

    records, _ = ladder_runs(scene, tolerance, cache_dir, runner=runner)
    return analyse(records, scene, tolerance)


def model_for_modal(
    scene: Scene,
    tolerance: float,
    out_dir: Path,
    *,
    cache_dir: Path | None = None,
    timings=None,
    charts: Charts | None = None,
    log: Callable[[str], None] | None = None,
    show_progress: bool = False,
) -> tuple[Scene, ModalModelSelection]:
    """The scene with the [mesh] the study picks for ``tolerance``, and why.

    `modal` computes the 3D model, so the choice is among the 3D families;
    the cheapest model of all (a shell, a beam) is reported beside it.
    Serially the study runs what its cache lacks (and writes
    convergence.json, with ``charts`` if given); under MPI it must be cached
    already (`rotorpillar converge` first), since its runs are subprocesses.

    Whether a ladder reaches a tolerance is known only once its runs are
    done (their errors come from Richardson on the runs), so an unmet
    tolerance is a result, not bad input: the most accurate 3D run is taken
    (or, with no error estimate at all, the scene's [mesh]) and the
    selection says ``met: false`` and why; `modal` then exits 4.
    """
    from mpi4py import MPI

    json_file: str | None
    if MPI.COMM_WORLD.size > 1:
        cache = Path(out_dir) / "cache" if cache_dir is None else Path(cache_dir)
        analysis = _cached_study(scene, tolerance, cache)
        runs, reference, band, overall = analysis.runs, analysis.reference, analysis.band, analysis.selection.chosen
        json_file = None
    else:
        st = study(
            scene,
            out_dir=out_dir,
            cache_dir=cache_dir,
            tolerance=tolerance,
            timings=timings,
            charts=charts,
            log=log,
            show_progress=show_progress,
        )
        runs, reference, band, overall, json_file = st.runs, st.reference, st.band, st.chosen, st.json_file
    # the 3D families that resolve every frequency the study measures: modal shows the
    # shell modes too (not the bending-only family)
    solid = [k for k, f in FAMILIES.items() if f.model == "solid" and set(QUANTITIES) <= set(f.quantities)]
    sel = select_model(runs, reference, band, tolerance, families=solid)
    unmet: str | None = None
    chosen = sel.chosen
    if chosen is None:
        chosen, unmet = _closest(runs, reference, band, solid, tolerance, sel.reason)
    if chosen is not None:
        p: dict[str, Any] = chosen.params  # the 3D run's mesh keys, as the scene's [mesh] has them
        mesh = dataclasses.replace(
            scene.mesh,
            elements_around=p["elements_around"],
            elements_along=p["elements_along"],
            elements_through=p["elements_through"],
            degree=p["degree"],
            cell_type=p["cell_type"],
            grading=p["grading"],
        )
        lines = [
            f"Model {'chosen' if unmet is None else 'run'} for tolerance {tolerance:g}: "
            f"{chosen.label} ({chosen.dofs:,} DOFs, {chosen.wall_time:.1f} s for "
            "the bare tube in the study).",
            "Why: " + (sel.reason if unmet is None else unmet),
            "The same mesh carries the top mass (the study's errors are the bare tube's).",
        ]
    else:
        mesh = scene.mesh
        lines = [
            f"No 3D model of the study has an error estimate for tolerance {tolerance:g}: "
            f"the scene's own [mesh] is run, unverified.",
            f"Why: {unmet}",
        ]
    if overall is not None and chosen is not None and overall.label != chosen.label:
        lines.append(
            f"Cheapest of all models at this tolerance: {overall.label} "
            f"({overall.wall_time:.2f} s), not a 3D model: `rotorpillar converge` "
            "has it."
        )
    if json_file:
        lines.append(f"Study: {json_file}")
    selection = ModalModelSelection(
        tolerance=tolerance,
        met=unmet is None,
        chosen=chosen,
        reason=sel.reason if unmet is None else unmet,
        rule=sel.rule,
        band=sel.band,
        needed=sel.needed,
        reference_uncertainty=sel.reference_uncertainty,
        rejected_cheaper=sel.rejected_cheaper,
        overall_cheapest=overall,
        convergence_json=json_file,
        text="\n".join(lines),
    )
    return dataclasses.replace(scene, mesh=mesh), selection


def _closest(
    runs: Sequence[ConvergenceRun],
    reference: dict[str, ReferenceValue],
    band: ExcitationBand,
    families: Sequence[str],
    tolerance: float,
    why_none: str,
) -> tuple[RunBrief | None, str]:
    """Where no 3D run meets the tolerance: the 3D run with the smallest error bound
    over the band (None when no run has one), and the sentence that says so."""
    needed, unc = needed_quantities(reference, band), reference_uncertainty(reference)
    rated = [
        (e, r)
        for r in runs
        if r.status == "ok" and r.family in families and reference
        if (e := band_error(r, needed, unc)) is not None
    ]
    if not rated:
        return None, (f"tolerance {tolerance:g} not met: {why_none}")
    err, best = min(rated, key=lambda t: (t[0], t[1].wall_time or 0.0))
    return brief(best), (
        f"tolerance {tolerance:g} not met: no 3D model of the study reaches it; the most "
        f"accurate, {best.label}, has an error bound of {err:.1e} over the band "
        "(raise converge.solid_p2_max_around, or loosen the tolerance)"
    )
