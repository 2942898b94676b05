"""The runs of the transients' speed-against-accuracy study (transients.pareto): which
models run (``run_specs``), the scene and window they share, each run's cache key, the
reduced runs in-process and the 3D runs on workers (``compute_3d``), warm.

Each run is cached as one JSON under ``out/<scene>/cache/`` (``pareto-<key>.json``)
by the project's one cache (:mod:`rotorpillar.cache`): the key a hash of the scene,
the window, the model, the record's samples and the source of the code, written
atomically: an interrupted study resumes and computes nothing twice; a damaged entry
is a miss, computed again.
"""

from __future__ import annotations

import hashlib
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..cache import DiskCache, cache_key, source_hash
from ..records import Record, replace
from ..scene import Scene

PARETO_RECORD_START = 0.5
"""The record starts this long after the runs (s): the start's own transient is
the same for every model and small beside the record's (the rotor's whirl alone).
Not the earthquake comparison's start (COMPARISONS: 1 s), so the study's 3D run on
the comparison's mesh is not the comparison's 3D run cut at PARETO_DURATION (paper:
134 % apart; 0.18 % shifted by the 0.5 s; with the start aligned still 0.095 % of the
peak, from the step, 5 s / 2972 against 9 s / 5350, and the output's sampling)."""
PARETO_DURATION = 5.0
"""Length of every run (s): 4.5 s of the record, its largest pulses and the tip's peak."""
PARETO_SAMPLES = 2001
"""Points of the common output grid the histories are compared on (2.5 ms apart:
more than 25 per period of the fastest forcing of the embedded scenes)."""
BEAM_ELEMENTS = (2, 4, 8, 16, 32)
"""The beam's implicit step costs ~n**3: 64 elements took 21 s (32: 2.4 s) for 0.05 % less error."""
ROM_EXTRA_MODES = 2


def pareto_along(finest: int) -> tuple[int, ...]:
    """Elements along of the 3D runs (the bending-only family of the ladder): the
    finest (``full_order.pareto_along``, 20: 5, 10, 15, 20) is the reference, so its
    cost bounds the study's; three coarser at 1/4, 1/2 and 3/4 of it give Richardson
    its three finest and the front its cheap end."""
    return tuple(sorted({max(1, round(finest * k / 4)) for k in (1, 2, 3, 4)}))


CACHE_VERSION = 2  # 2: an Entry of a StoredRun record (msgspec)


class ParetoRun(Record):
    """One model's run of the Pareto case (SI)."""

    family: str
    """rom, beam or fem3d"""
    label: str
    params: dict[str, Any]
    """modes (rom), elements (beam), the mesh (fem3d)"""
    dofs: int
    wall_seconds: float
    """warm: building the model and integrating (s)"""
    peak_tip: float
    """largest |tip X relative to the ground| over every step (m)"""
    peak_tip_error: float | None
    """peak_tip / the reference's - 1 (-); the reference: its own estimated error"""
    history_error: float | None
    """max_t |tip - tip_ref| / max_t |tip_ref| on the common grid (-); the reference:
    its own estimated error"""
    ok: bool
    cached: bool
    key: str


class ParetoOutcome(Record):
    """How one model's run of the Pareto case ended: its size, cost and tip (SI)."""

    dofs: int
    """unknowns of the model (-)"""
    wall_seconds: float
    """warm: building the model and integrating (s)"""
    ok: bool
    """the integrator's verdict"""
    peak_tip: float
    """largest |tip X relative to the ground| over every step (m)"""
    tip: tuple[float, ...]
    """tip X relative to the ground on the common grid: PARETO_SAMPLES points over the run (m)"""


class StoredRun(Record, omit_defaults=True):
    """One run as the cache stores it: its encoding is ``pareto-<key>.json``'s document
    (``cached`` is not stored), read back by ``DiskCache.read(key, StoredRun)``."""

    key: str
    """the run's cache key (``run_key``)"""
    family: str
    """rom, beam or fem3d"""
    label: str
    params: dict[str, Any]
    """modes (rom), elements (beam), the mesh (fem3d)"""
    dofs: int
    """unknowns of the model (-)"""
    wall_seconds: float
    """warm: building the model and integrating (s)"""
    ok: bool
    """the integrator's verdict"""
    peak_tip: float
    """largest |tip X relative to the ground| over every step (m)"""
    tip: tuple[float, ...]
    """tip X relative to the ground on the common grid: PARETO_SAMPLES points over the run (m)"""
    cached: bool = False
    """read from the cache rather than computed by this process (a property of this
    process's plan: never written, the cache stores it False)"""

    @classmethod
    def of(cls, key: str, family: str, label: str, params: dict[str, Any], outcome: ParetoOutcome) -> StoredRun:
        """The run ``(family, label, params)`` under ``key`` that ended as ``outcome``, computed here."""
        o = outcome
        return cls(key, family, label, params, o.dofs, o.wall_seconds, o.ok, o.peak_tip, o.tip)


def pareto_scene(scene: Scene, duration: float = PARETO_DURATION):
    """The scene of the Pareto case: the scene's record from PARETO_RECORD_START, ``duration`` long."""
    from ..scene import with_values

    return with_values(
        scene,
        {
            "excitation.kind": "record",
            "excitation.start": PARETO_RECORD_START,
            "simulate.earthquake_duration": duration,
        },
    )


def run_specs(
    rom_modes: int, candidates: int, chosen_mesh, along: tuple[int, ...], beams=BEAM_ELEMENTS
) -> list[tuple[str, str, dict]]:
    """(family, label, params) of every run, cheapest family first."""
    from ..converge.ladder import ALONG_FAMILY_AROUND

    specs = [
        ("rom", f"ROM, {k} mode{'s' if k > 1 else ''}", {"modes": k})
        for k in range(1, min(candidates, rom_modes + ROM_EXTRA_MODES) + 1)
    ]
    specs += [("beam", f"beam, {n} el.", {"elements": n}) for n in beams]
    meshes = [(ALONG_FAMILY_AROUND, n) for n in along]
    if chosen_mesh is not None and (chosen_mesh.elements_around, chosen_mesh.elements_along) not in meshes:
        meshes.append((chosen_mesh.elements_around, chosen_mesh.elements_along))
    base = (
        {}
        if chosen_mesh is None
        else {k: v for k, v in vars(chosen_mesh).items() if k not in ("elements_around", "elements_along")}
    )
    specs += [
        ("fem3d", f"3D, {a}x{n}", {"elements_around": a, "elements_along": n, **base})
        for a, n in sorted(meshes, key=lambda m: m[0] * m[1])
    ]
    return specs


def _source_files(family: str) -> list[Path]:
    """The code a run of ``family`` depends on: reduced/ (and fem3d/, mesh/ for the 3D runs)."""
    root = Path(__file__).parent.parent
    files = sorted((root / "reduced").glob("*.py"))
    if family == "fem3d":
        files += sorted((root / "fem3d").glob("*.py")) + sorted((root / "mesh").glob("*.py"))
    return files


def run_key(family: str, params: dict, scene: Scene, motion, modes_digest: str) -> str:
    """The cache key of a run: the hash of everything it depends on (its arguments, the code)."""
    args = {
        "family": family,
        "params": params,
        "scene": {k: v for k, v in scene.to_dict().items() if k not in ("name", "description")},
        "record": hashlib.sha256(np.asarray(motion.acceleration, float).tobytes()).hexdigest()[:16],
        "samples": PARETO_SAMPLES,
        "modes": modes_digest if family == "rom" else None,
    }
    return cache_key(args, version=CACHE_VERSION, code=source_hash(_source_files(family)))


def run_cache(cache_dir: Path) -> DiskCache:
    """The runs' cache: ``pareto-<key>.json`` files in ``cache_dir``."""
    return DiskCache(Path(cache_dir), prefix="pareto-")


def _grid(duration: float) -> np.ndarray:
    return np.linspace(0.0, duration, PARETO_SAMPLES)


def reduced_run(
    scene: Scene, family: str, params: dict, motion, speed: float, pillar_modes, duration: float
) -> ParetoOutcome:
    from ..reduced.drive import DriveSchedule
    from ..reduced.integration import simulate
    from ..reduced.models import build_model
    from ..scene import with_values
    from .cases import full_order_settings, settings_of

    d, L = scene.drive, scene.load
    drive = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
    t0 = time.perf_counter()
    if family == "rom":
        model, _ = build_model(scene, "modal", modes=params["modes"], pillar_modes=pillar_modes)
        st = settings_of(scene)
    else:
        beam = with_values(scene, {"full_order.beam_elements": params["elements"]})
        model, _ = build_model(beam, "beam")
        st, _ = full_order_settings(beam, "earthquake", motion)
    q0, v0 = model.held_whirl_state(speed)
    run = simulate(model, drive, motion, duration, q0, v0, settings=st, speed_scale=speed)
    wall = time.perf_counter() - t0
    grid = _grid(duration)
    return ParetoOutcome(
        dofs=int(model.n),
        wall_seconds=wall,
        ok=bool(run.ok),
        peak_tip=float(np.nanmax(run.peak[:, -1])),
        tip=tuple(np.interp(grid, run.t, run.tip()).tolist()),
    )


_WARM: dict = {}
"""family -> seconds of this process's warm-up run (once per process)."""


def warm_up_family(family: str, scene: Scene, motion, speed: float, pillar_modes=None) -> float:
    """Run a tiny case of ``family`` once per process (numba kernels, FFCx forms); its seconds."""
    if family in _WARM:
        return 0.0
    t0 = time.perf_counter()
    if family == "fem3d":
        from ..fem3d.full_order import simulate_fem3d

        tiny = replace(scene.mesh, elements_around=4, elements_along=1)
        simulate_fem3d(
            scene, "earthquake", motion=motion, duration=1e-3, time_step=5e-4, mesh=tiny, samples=3, initial_speed=speed
        )
    else:
        reduced_run(scene, family, {"modes": 1, "elements": 2}, motion, speed, pillar_modes, 1e-2)
    _WARM[family] = time.perf_counter() - t0
    return _WARM[family]


def compute_3d(job) -> tuple[ParetoOutcome, float]:
    """One 3D run (a worker's job: picklable arguments); its outcome and this process's
    warm-up seconds (s)."""
    from ..fem3d.full_order import simulate_fem3d

    scene, params, motion, speed, duration = job
    warm = warm_up_family("fem3d", scene, motion, speed)
    mesh = replace(scene.mesh, **params)
    r = simulate_fem3d(
        scene, "earthquake", motion=motion, duration=duration, mesh=mesh, samples=PARETO_SAMPLES, initial_speed=speed
    )
    grid = _grid(duration)
    outcome = ParetoOutcome(
        dofs=int(r.dofs),
        wall_seconds=float(r.wall_seconds),
        ok=bool(r.ok),
        peak_tip=float(r.max_abs["tip_x"]),
        tip=tuple(np.interp(grid, r.t, r.tip_x).tolist()),
    )
    return outcome, warm


def load_run(cache: DiskCache, key: str) -> StoredRun | None:
    """The run cached under ``key`` (``cached``), or None: a missing, damaged or foreign
    entry, one without its verdict (``ok``) or without a field of the run, is no cached
    run (computed again)."""
    run = cache.read(key, StoredRun)
    return None if run is None else replace(run, cached=True)


# --------------------------------------------------------------------------
# The study


def pareto_estimate(scene: Scene, chosen_mesh=None) -> str:
    """The study's 3D runs, estimated from the scene alone before any work, in a line;
    InputError (as a single 3D run is refused: fem3d.full_order_plan) when one of them
    would not fit in memory, would take more than ``simulate.max_steps`` steps or is
    estimated above ``simulate.max_seconds``."""
    from ..converge.ladder import ALONG_FAMILY_AROUND
    from ..errors import InputError
    from ..fem3d.full_order_plan import case_setup, duration_text, estimate, step_rule
    from ..mesh import tube_params
    from ..reduced.models import scene_motion

    sc = pareto_scene(scene)
    motion = scene_motion(sc)
    motion, drive, length, _, _ = case_setup(sc, "earthquake", motion, None, PARETO_DURATION, 0.0)
    rule = step_rule(sc, drive, motion, 0.0)
    meshes = [
        replace(sc.mesh, elements_around=ALONG_FAMILY_AROUND, elements_along=n)
        for n in pareto_along(scene.full_order.pareto_along)
    ]
    if chosen_mesh is not None:
        meshes.append(replace(sc.mesh, **{k: getattr(chosen_mesh, k) for k in ("elements_around", "elements_along")}))
    runs = []
    for mesh in meshes:
        label = f"3D {mesh.elements_around}x{mesh.elements_along}"
        try:
            tube_params(sc.pillar, mesh)  # its memory
        except InputError as exc:
            raise InputError(f"compare --pareto: the run {label} (full_order.pareto_along): {exc}") from None
        est = estimate(sc, length, rule, mesh)
        if est.steps > scene.simulate.max_steps:
            raise InputError(
                f"compare --pareto: the run {label} of {length:g} s at a step of {est.time_step:.3g} s would "
                f"take about {est.steps:.3g} steps (~{duration_text(est.seconds)}), more than simulate.max_steps = "
                f"{scene.simulate.max_steps:.3g}: raise full_order.time_step (0 = the band's step) or "
                "simulate.max_steps"
            )
        seconds = est.seconds + est.setup_seconds
        if not seconds <= sc.simulate.max_seconds:  # the run's own check_budget would refuse it mid-study
            raise InputError(
                f"compare --pareto: the run {label} of {length:g} s on ~{est.dofs:,} dofs would take about "
                f"{duration_text(seconds)} (an estimate), more than simulate.max_seconds = "
                f"{sc.simulate.max_seconds:.3g} s: lower full_order.pareto_along, or raise simulate.max_seconds"
            )
        runs.append((label, est))
    total = sum(e.seconds for _, e in runs)
    return (
        f"speed against accuracy: {len(runs)} 3D runs ({', '.join(label for label, _ in runs)}) of "
        f"{length:g} s, {runs[0][1].steps:.3g} steps each, up to ~{max(e.dofs for _, e in runs):,} dofs: "
        f"about {duration_text(total)} of work, less what the cache holds (estimate; full_order.pareto_along sets the finest)"
    )
