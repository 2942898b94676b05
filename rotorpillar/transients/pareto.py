"""Speed against accuracy for the transients: El Centro on every model of the ladder.

The convergence study charts each pillar model's frequency error against
its cost; this does the same for a transient, where the error is what a
user reads: the peak tip displacement relative to the ground and the tip's
history.  One case, El Centro's first ``PARETO_DURATION - PARETO_RECORD_START``
seconds (its strong pulses and the tip's peak, 2.6 s into the record),
run on

- the ROM with 1 .. k + ``ROM_EXTRA_MODES`` pillar modes (k: the modes the
  comparison's ROM keeps), from the scene's mode source;
- the 1D Timoshenko beam at full order with ``BEAM_ELEMENTS`` elements;
- the 3D tube at full order on the bending-only meshes of the convergence
  ladder (``ALONG_FAMILY_AROUND`` around, :func:`pareto_along` of
  ``full_order.pareto_along`` along) and the
  mesh the comparison's reference runs on;

every model from the same state: the pillar at rest, the rotor in its
steady whirl at the ROM's operating speed.  The errors are against the
finest 3D run, whose own error is estimated by Richardson over the three
finest 3D runs where they converge monotonically at a plausible order, else
by its difference to the next coarser (``ParetoStudy.reference``).

Costs are warm: each process first runs a tiny case of each kind (numba's
kernels, FFCx's forms), outside the timed region, ``compile_seconds``; the
timed region is what the model costs a user: building it (the ROM and the
beam: their modes; 3D: mesh, assembly, factorisation) and integrating.
Each run is cached as one JSON under ``out/<scene>/cache/``
(``pareto-<key>.json``, :func:`.pareto_runs.run_cache`: the project's one
cache, rotorpillar.cache), the key a hash of the scene, the window, the
model, the record's samples and the source of the code, written
atomically: an interrupted study resumes and computes nothing twice.  The
3D runs go to ``workers`` processes (rotorpillar.executor), started before
the caller's own work (``plan_pareto``, ``ParetoRunning``, ``finish``) so that
compare's own models and the study share the machine's cores.
"""

from __future__ import annotations

import hashlib
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..records import Record, replace
from ..scene import Mesh, Scene
from .pareto_runs import (
    BEAM_ELEMENTS,
    PARETO_DURATION,
    PARETO_RECORD_START,
    PARETO_SAMPLES,
    ParetoOutcome,
    ParetoRun,
    StoredRun,
    compute_3d,
    load_run,
    pareto_along,
    pareto_scene,
    reduced_run,
    run_cache,
    run_key,
    run_specs,
    warm_up_family,
)


class ParetoReference(Record, omit_defaults=True):
    """The finest 3D run, every error's reference, and its own error."""

    label: str
    """the run's label (e.g. "3D, 8x20")"""
    peak_tip: float
    """its largest |tip X relative to the ground| (m)"""
    peak_error: float | None
    """its own relative error of the peak (-); None for a single 3D run"""
    history_error: float | None
    """its own relative error of the tip's history (-); None for a single 3D run"""
    method: str
    """how the error was estimated ("richardson", "next_coarser" or "none")"""
    order: float | None
    """the observed order of convergence (-); Richardson only"""
    limit: float | None = None
    """the extrapolated peak (m); Richardson only"""
    note: str = ""
    """how the error was estimated, in words"""


class ParetoCase(Record):
    """The case every model of the study runs."""

    record: str
    """the ground-motion record's name"""
    record_start: float
    """the record starts this long after the runs (s)"""
    duration: float
    """length of every run (s)"""
    initial_speed: float
    """the rotor's speed at the start: the ROM's operating speed (rad/s)"""
    samples: int
    """points of the common grid the tips are compared on (-)"""
    start: str
    """the initial state, in words"""


class ParetoCost(Record):
    """What the study cost (wall times on a shared machine: noisy)."""

    runs: int
    """runs of the study (-)"""
    computed: int
    """of them computed by this call (-)"""
    cached: int
    """of them read from the cache (-)"""
    workers: int
    """worker processes of the 3D runs (-; 0: in the caller's process)"""
    wall_seconds: float
    """what the caller waited for the study: planning, its own runs, waiting for the workers (s)"""
    pool_seconds: float
    """the workers' elapsed time, beside the caller's own work (s)"""
    compute_seconds: float
    """the computed runs' times, summed (s)"""


class TipFronts(Record):
    """Per error measure, the labels on the Pareto front of |error| against wall time,
    cheapest first."""

    peak_tip: tuple[str, ...]
    history: tuple[str, ...]


class ParetoChoice(Record):
    """The comparison's models among the study's runs, and why they sit where they do."""

    rom: str | None
    """the ROM compare runs (its label)"""
    fem3d: str | None
    """the 3D reference compare runs (its label; None without one)"""
    why: str = ""
    """where each stands against the fronts, in words"""


class ParetoStudy(Record):
    """Speed against accuracy on El Centro (``pareto`` in compare_earthquake.json)."""

    case: ParetoCase | None
    """the case every model runs (None until the runs are done: ``analyse_pareto`` alone)"""
    runs: tuple[ParetoRun, ...]
    reference: ParetoReference
    fronts: TipFronts
    """the labels on the Pareto front of each error against wall time"""
    chosen: ParetoChoice
    """the labels of the comparison's models, and why"""
    compile_seconds: dict[str, float]
    """family -> seconds of the warm-up run in this process (numba, FFCx), outside every timing
    (a mapping: the families that ran)"""
    cost: ParetoCost | None
    """what the study cost (None until the runs are done)"""
    chart: str | None = None
    note: str = ""


# --------------------------------------------------------------------------
# The case and its runs


@dataclass(frozen=True, eq=False)
class ParetoPlan:
    """The Pareto case ready to run: its scene, record, start, runs, keys and the cached ones."""

    scene: Scene
    motion: object
    pillar_modes: object
    speed: float
    """the ROM's operating speed: every model starts there (rad/s)"""
    specs: list
    keys: list
    results: dict[int, StoredRun]
    """index into ``specs`` -> its run (the cached ones first; the computed ones added as they end)"""
    rom_modes: int
    chosen_mesh: Mesh | None
    cache_dir: Path
    plan_seconds: float
    duration: float = PARETO_DURATION


def plan_pareto(
    scene: Scene,
    *,
    cache_dir: Path,
    rom_modes: int,
    chosen_mesh=None,
    duration: float = PARETO_DURATION,
    along: tuple[int, ...] | None = None,
    beams=BEAM_ELEMENTS,
    pillar_modes=None,
) -> ParetoPlan:
    """The runs of the Pareto case, those on disk loaded (cheap: no run); ``duration``,
    ``along`` (default: :func:`pareto_along` of the scene's ``full_order.pareto_along``)
    and ``beams`` replace the module's choices (tests: a short, coarse case);
    ``pillar_modes``: the ROM's candidate modes (the chain's; None: resolved for the
    scene without a study)."""
    from ..reduced.models import build_model, candidate_modes, scene_motion
    from ..reduced.stationary import operating_speed

    started = time.perf_counter()
    sc = pareto_scene(scene, duration)
    motion = scene_motion(sc)
    pm = pillar_modes
    if pm is None:
        from ..chain import resolve

        pm = resolve(sc, None, motion=motion).modes
    cands = candidate_modes(sc, pm)
    digest = hashlib.sha256(
        np.concatenate(
            [np.asarray(cands.omega), np.asarray(cands.modal_mass), np.asarray(cands.participation)]
        ).tobytes()
    ).hexdigest()[:16]
    rom, _ = build_model(sc, "modal", modes=rom_modes, pillar_modes=pm)
    d, L = sc.drive, sc.load
    speed = operating_speed(rom, d.torque_at_zero, d.slope, L.coefficient)
    if along is None:
        along = pareto_along(scene.full_order.pareto_along)
    specs = run_specs(rom_modes, cands.count, chosen_mesh, along, beams)
    keys = [run_key(f, p, sc, motion, digest) for f, _, p in specs]
    results = {}
    cache = run_cache(cache_dir)
    for i, key in enumerate(keys):
        stored = load_run(cache, key)
        if stored is not None:
            results[i] = stored
    return ParetoPlan(
        sc,
        motion,
        pm,
        speed,
        specs,
        keys,
        results,
        rom_modes,
        chosen_mesh,
        Path(cache_dir),
        time.perf_counter() - started,
        float(duration),
    )


def _mpi_rank_size() -> tuple[int, int]:
    """(rank, size) when running under MPI (mpi4py imported), else (0, 1)."""
    import sys

    mpi = sys.modules.get("mpi4py.MPI")
    return (0, 1) if mpi is None else (mpi.COMM_WORLD.rank, mpi.COMM_WORLD.size)


class ParetoRunning:
    """The plan's missing 3D runs under way on worker processes (a thread waits for them),
    so that the caller's own work (compare's models) runs meanwhile on the other core."""

    def __init__(self, plan: ParetoPlan, workers: int, progress=None):
        import threading

        self.plan, self.progress = plan, progress
        self.compile: dict[str, float] = {}
        self.todo = [i for i in range(len(plan.specs)) if i not in plan.results]
        self.solid = [i for i in self.todo if plan.specs[i][0] == "fem3d"]
        self.workers = 0
        self.error: BaseException | None = None
        self.thread, self.pool_seconds = None, 0.0
        if progress:
            progress(
                f"speed against accuracy: {len(plan.specs)} runs, "
                f"{len(plan.specs) - len(self.todo)} cached, {len(self.todo)} to compute"
                + (
                    f" ({len(self.solid)} 3D on {min(workers, len(self.solid))} worker process(es))"
                    if self.solid and workers > 0
                    else ""
                )
            )
        if _mpi_rank_size()[1] > 1:
            workers = 0  # under mpirun every rank runs the 3D runs together, here
        if self.solid and workers > 0:
            self.workers = min(workers, len(self.solid))
            self.thread = threading.Thread(target=self._pool, daemon=True)
            self.thread.start()

    def keep(self, i: int, out: ParetoOutcome) -> None:
        plan = self.plan
        fam, label, params = plan.specs[i]
        run = StoredRun.of(plan.keys[i], fam, label, params, out)
        if _mpi_rank_size()[0] == 0:
            run_cache(plan.cache_dir).write(plan.keys[i], run)
        plan.results[i] = run
        if self.progress:
            self.progress(f"speed against accuracy: {label} in {out.wall_seconds:.3g} s")

    def _job(self, i: int):
        p = self.plan
        return (p.scene, p.specs[i][2], p.motion, p.speed, p.duration)

    def _pool(self) -> None:
        import logging

        from ..executor import Executor

        logging.getLogger("distributed").setLevel(logging.ERROR)  # dolfinx leaves INFO on
        order = sorted(
            self.solid,
            key=lambda i: -self.plan.specs[i][2]["elements_around"] * self.plan.specs[i][2]["elements_along"],
        )
        t0 = time.perf_counter()
        try:
            with Executor(self.workers) as ex:
                for j, (out, warm) in ex.map(compute_3d, [self._job(i) for i in order]):
                    self.compile["fem3d"] = self.compile.get("fem3d", 0.0) + warm
                    self.keep(order[j], out)
        except BaseException as exc:  # re-raised in finish(), in the caller's thread
            self.error = exc
        self.pool_seconds = time.perf_counter() - t0

    def finish(self) -> tuple[ParetoStudy, dict]:
        """The reduced runs here, then the 3D runs (here too without workers); the study."""
        plan = self.plan
        t0 = time.perf_counter()
        for i in (i for i in self.todo if plan.specs[i][0] != "fem3d"):
            fam, _, params = plan.specs[i]
            self.compile[fam] = self.compile.get(fam, 0.0) + warm_up_family(
                fam, plan.scene, plan.motion, plan.speed, plan.pillar_modes
            )
            self.keep(
                i, reduced_run(plan.scene, fam, params, plan.motion, plan.speed, plan.pillar_modes, plan.duration)
            )
        if self.thread is not None:
            self.thread.join()
            if self.error is not None:
                raise self.error
        else:
            for i in self.solid:
                out, warm = compute_3d(self._job(i))
                self.compile["fem3d"] = self.compile.get("fem3d", 0.0) + warm
                self.keep(i, out)
        docs = [plan.results[i] for i in range(len(plan.specs))]
        k, mesh = plan.rom_modes, plan.chosen_mesh
        study, series = analyse_pareto(
            docs,
            chosen=ParetoChoice(
                rom=f"ROM, {k} mode{'s' if k > 1 else ''}",
                fem3d=None if mesh is None else f"3D, {mesh.elements_around}x{mesh.elements_along}",
            ),
        )
        case = ParetoCase(
            record=plan.scene.excitation.record,
            record_start=PARETO_RECORD_START,
            duration=plan.duration,
            initial_speed=plan.speed,
            samples=PARETO_SAMPLES,
            start="every model from the pillar at rest, the rotor in its steady whirl at the ROM's operating speed",
        )
        cost = ParetoCost(
            runs=len(plan.specs),
            computed=len(self.todo),
            cached=len(plan.specs) - len(self.todo),
            workers=self.workers,
            wall_seconds=plan.plan_seconds + time.perf_counter() - t0,
            pool_seconds=self.pool_seconds,
            compute_seconds=float(sum(plan.results[i].wall_seconds for i in self.todo)),
        )
        return replace(study, case=case, compile_seconds=dict(self.compile), cost=cost), series


def transient_pareto(
    scene: Scene, *, cache_dir: Path, rom_modes: int, chosen_mesh=None, workers: int = 0, progress=None, **choices
) -> tuple[ParetoStudy, dict]:
    """Run (or load) every run of the Pareto case; (the study, the histories by label).
    ``workers`` > 0: the 3D runs on that many worker processes, else in this one;
    ``choices``: plan_pareto's duration, along, beams."""
    plan = plan_pareto(scene, cache_dir=cache_dir, rom_modes=rom_modes, chosen_mesh=chosen_mesh, **choices)
    return ParetoRunning(plan, workers, progress).finish()


def _reference_error(fine: list[StoredRun], grid_tips: dict) -> ParetoReference:
    """The finest 3D run's own error: Richardson over the three finest where monotone at a
    plausible order, else the difference to the next coarser."""
    from ..converge.richardson import richardson

    ref = fine[-1]
    label, peak = ref.label, ref.peak_tip
    if len(fine) < 2:
        return ParetoReference(
            label, peak, None, None, "none", None, note="a single 3D run: its own error is not estimated"
        )
    prev = fine[-2]
    diff = np.max(np.abs(grid_tips[ref.label] - grid_tips[prev.label])) / max(
        np.max(np.abs(grid_tips[ref.label])), 1e-300
    )
    if len(fine) >= 3:
        last = fine[-3:]
        h = [1.0 / r.params["elements_along"] for r in last]
        rich = richardson(h, [r.peak_tip for r in last], 4.0)
        p = rich.order
        if rich.monotone and p is not None and 0.5 <= p <= 8:
            factor = 1.0 / ((h[1] / h[2]) ** p - 1)
            return ParetoReference(
                label,
                peak,
                peak_error=rich.error_estimate / abs(rich.value),
                history_error=1.25 * factor * float(diff),
                method="richardson",
                order=p,
                limit=rich.value,
                note=f"Richardson over {', '.join(r.label for r in last)} (observed order "
                f"{p:.2f}): Roache's 1.25 |limit - finest| for the peak; the history's "
                "difference to the next coarser times 1.25 / (r**p - 1)",
            )
    return ParetoReference(
        label,
        peak,
        peak_error=abs(ref.peak_tip / prev.peak_tip - 1),
        history_error=float(diff),
        method="next_coarser",
        order=None,
        note=f"the difference to the next coarser run ({prev.label}): the 3D runs do not "
        "converge monotonically at a plausible order, so no extrapolation",
    )


def analyse_pareto(docs: list[StoredRun], chosen: ParetoChoice) -> tuple[ParetoStudy, dict]:
    """Errors against the finest 3D run, its own error, the fronts (the study, the histories)."""
    from ..converge.selection import pareto_front

    tips = {d.label: np.asarray(d.tip, float) for d in docs}
    fine = sorted(
        (d for d in docs if d.family == "fem3d" and d.ok),
        key=lambda d: (d.params["elements_along"], d.params["elements_around"]),
    )
    if not fine:
        raise ValueError("no 3D run finished: no reference")
    ref_err = _reference_error(fine, tips)
    ref = fine[-1]
    x_ref = tips[ref.label]
    scale = max(float(np.max(np.abs(x_ref))), 1e-300)
    runs = []
    for d in docs:
        if d is ref:
            pe, he = ref_err.peak_error, ref_err.history_error
        elif d.ok:
            pe = d.peak_tip / ref.peak_tip - 1 if ref.peak_tip else None
            he = float(np.max(np.abs(tips[d.label] - x_ref)) / scale)
        else:
            pe = he = None
        runs.append(
            ParetoRun(
                family=d.family,
                label=d.label,
                params=d.params,
                dofs=d.dofs,
                wall_seconds=d.wall_seconds,
                peak_tip=d.peak_tip,
                peak_tip_error=pe,
                history_error=he,
                ok=d.ok,
                cached=d.cached,
                key=d.key,
            )
        )
    wall = [r.wall_seconds for r in runs]
    fronts = TipFronts(
        peak_tip=tuple(runs[i].label for i in pareto_front(wall, [r.peak_tip_error for r in runs])),
        history=tuple(runs[i].label for i in pareto_front(wall, [r.history_error for r in runs])),
    )
    by = {r.label: r for r in runs}
    why = []
    for role, label in (("rom", chosen.rom), ("fem3d", chosen.fem3d)):
        r = by.get(label or "")  # no label is empty: None finds nothing
        if r is not None:
            on = [m for m in ("peak_tip", "history") if r.label in getattr(fronts, m)]
            why.append(
                f"{r.label} ({'the ROM compare runs' if role == 'rom' else 'the 3D reference compare runs'}): "
                f"peak {_pct(r.peak_tip_error)}, history {_pct(r.history_error)} in "
                f"{r.wall_seconds:.3g} s, " + (f"on the front of {' and '.join(on)}" if on else "on no front")
            )
    study = ParetoStudy(
        case=None,
        runs=tuple(runs),
        reference=ref_err,
        fronts=fronts,
        chosen=replace(chosen, why="; ".join(why)),
        compile_seconds={},
        cost=None,
        note="errors of the tip relative to the ground against the finest 3D run; "
        "wall times warm, measured on a shared machine (noisy)",
    )
    return study, tips


def _pct(x) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{100 * abs(x):.2g} %"
