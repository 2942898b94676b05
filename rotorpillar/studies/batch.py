"""One batch of a study's runs, as a worker computes it.

Runs that share a compiled model, drive schedule, ground motion and initial
state go to ONE call of the compiled batch loop
(``rotorpillar.reduced.batch.simulate_batch``), which takes per run only
what its signature takes: the motor's M0 (as a scale on the schedule), its
slope s, the load k, the eccentricity e and the shaft stiffness c2 (none of
them enters the model's matrices: the shaft acts through c2 and e in the
right-hand side).  So for a run-up these five keys vary inside a batch loop
(``PER_RUN``) and every other key makes its own group (its own model).  A
run-down and an earthquake start from the steady state at the operating
speed, which depends on all of them: there every run is its own group.

``run_batch(spec)`` is what the executor sends to a worker (a ``BatchSpec``); it
returns a ``BatchResult``: one ``StudyRun`` a run.
Each run condenses as ``simulate`` condenses a case
(rotorpillar.transients.case_summary): the final speed and its mean over the last
5 %, the resonance it settled at (``capture``), the peak tip displacement
relative to the ground (from every step where the model's frame is the
ground's; sampled otherwise) and the peak shaft deflection
|(d.z - e cos theta, y - e sin theta)| (sampled on the output grid).  A
run-up starts from rest, where the shaft is deflected by e (the mass centre
on the axis); that start decays as exp(-b2 t / (2 m_C)), so a run-up's peak
shaft deflection is taken from ``settle_time`` on, when it is below 1 % of e.
"""

from __future__ import annotations

import math
import os
import socket
import time
from typing import Any

import numpy as np

from ..records import Record, replace
from ..reduced.band import forcing_top
from ..reduced.batch import shaft_deflection, simulate_batch
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import NoMotionSizes, no_motion
from ..reduced.models import build_model, scene_motion
from ..reduced.pillar_modes import PillarModes
from ..reduced.stationary import operating_speed
from ..scene import Scene, scene_from_dict
from ..transients.case_summary import capture_state, ground_displacement
from .axes import Param, run_scene
from .modes import mode_key
from .result import StudyRun


class PlannedRun(Record):
    """A run of a batch before it runs: its place in the study and its scene keys."""

    index: int
    """position in the product of the axes"""
    params: dict[str, Param]
    """{scene key: value} of this run"""


class BatchSpec(Record, omit_defaults=True):
    """One batch as the executor sends it to a worker (and as its cache key hashes it)."""

    scene: dict[str, Any]
    """the study's scene (``Scene.to_dict()``)"""
    case: str
    model: str
    implied: dict[str, Param]
    """scene keys the axes imply"""
    runs: tuple[PlannedRun, ...]
    pillar_modes: dict[str, PillarModes] | None = None
    """the ROM's pillar modes by ``studies.modes.mode_key`` (None: not the ROM)"""


class BatchResult(Record):
    """One batch computed (a cache entry of the study)."""

    runs: tuple[StudyRun, ...]
    """one a run, by index"""
    groups: int
    """batch-loop calls (-)"""
    wall_seconds: float
    """the batch's wall time on its worker (s)"""
    worker: str
    """host:pid of the worker"""


#: scene key -> simulate_batch keyword, per case: what the batch loop takes per run
PER_RUN = {
    "runup": {
        "drive.torque_at_zero": "torque_scale",
        "drive.slope": "slope",
        "load.coefficient": "load",
        "rotor.eccentricity": "eccentricity",
        "shaft.stiffness": "shaft_stiffness",
    },
    "rundown": {},
    "earthquake": {},
}
#: output spacing of the sampled quantities (s): run-ups and run-downs, earthquakes
SAMPLE_SPACING = {"runup": 0.02, "rundown": 0.02, "earthquake": 0.005}
MIN_SAMPLES, MAX_SAMPLES = 2001, 40001


def group_key(params: dict[str, Param], case: str) -> tuple:
    """What runs must share to go to one batch loop: the values of the other keys."""
    per = PER_RUN[case]
    return tuple((k, v) for k, v in params.items() if k not in per)


def samples_for(case: str, t_end: float) -> int:
    return int(min(MAX_SAMPLES, max(MIN_SAMPLES, t_end / SAMPLE_SPACING[case] + 1)))


def settle_time(scene: Scene, t_end: float) -> float:
    """When the start's shaft deflection e has decayed to 1 %: ln(100) 2 m_C / b2,
    at most half the run (s)."""
    b2, m = scene.shaft.damping, scene.rotor.mass
    return min(0.5 * t_end, np.log(100.0) * 2 * m / b2) if b2 > 0 else 0.5 * t_end


def _tail_mean(t, W) -> float:
    """Mean speed over the last 5 % of the run (as simulate's summary)."""
    tail = t >= t[-1] - max(0.05 * (t[-1] - t[0]), 1e-9)
    return float(np.mean(W[tail]))


def _spatial_runs(scene: Scene, case: str, runs: list[PlannedRun], pillar_modes=None) -> list[StudyRun] | None:
    """The group's runs on the spatial ROM, one at a time as ``simulate`` runs them
    (rotorpillar.transients.cases.run_case), where the scene's ``modal_model.planes`` resolves
    to spatial for this case (a ground motion in several components or at an angle to the
    rotor's plane, the drive's reaction, or the scene's own choice); None where it resolves to
    planar, and the batch loop runs them.  The batch loop integrates the planar ROM alone: on
    it, ``excitation.angle`` or a second component would change nothing, and a study over them
    would report the same peak at every value."""
    from ..transients.cases import case_model, run_case

    m = case_model(scene, case, "modal", pillar_modes=pillar_modes)
    if m.planes is None or m.planes.planes != "spatial":
        return None
    out = []
    for p in runs:
        own = run_scene(scene, {k: v for k, v in p.params.items() if k in PER_RUN[case]})
        res = run_case(own, case, "modal", truncation=False, pillar_modes=pillar_modes)
        run, sm = res.run, res.summary
        size, _ = shaft_deflection(run.q, res.model.shaft, res.model.eccentricity)
        since = run.t >= (settle_time(own, float(run.t[-1])) if case == "runup" else 0.0)
        sizes = scene_motion(own).sizes() if case == "earthquake" else None
        out.append(
            StudyRun(
                index=p.index,
                params=p.params,
                ok=bool(sm.ok),
                final_speed=float(sm.omega_final),
                final_speed_mean=float(sm.omega_final_mean),
                captured_at=sm.captured_at,
                speed_state=sm.speed_state,
                passed=None if case == "earthquake" else sm.speed_state not in ("captured", "escaping"),
                peak_tip=float(sm.max_abs["tip_x"] or 0.0),
                peak_shaft_deflection=float(np.max(size[since])),
                free_speed=float(run.drive.free_speed() if run.drive is not None else math.nan),
                nfev=int(sm.integrator.nfev),
                pga=None
                if sizes is None
                else (0.0 if isinstance(sizes, NoMotionSizes) else float(sizes.peak_acceleration)),
                initial_speed=res.initial_speed,
            )
        )
    return out


def _run_group(scene: Scene, case: str, which: str, runs: list[PlannedRun], pillar_modes=None) -> list[StudyRun]:
    if which == "modal":
        spatial = _spatial_runs(scene, case, runs, pillar_modes)
        if spatial is not None:
            return spatial
    sim, d, L, r, sh = scene.simulate, scene.drive, scene.load, scene.rotor, scene.shaft
    per: dict[str, list[float]] = {"M0": [], "s": [], "k": [], "e": [], "c2": []}
    for p in runs:
        per["M0"].append(float(p.params.get("drive.torque_at_zero", d.torque_at_zero)))
        per["s"].append(float(p.params.get("drive.slope", d.slope)))
        per["k"].append(float(p.params.get("load.coefficient", L.coefficient)))
        per["e"].append(float(p.params.get("rotor.eccentricity", r.eccentricity)))
        per["c2"].append(float(p.params.get("shaft.stiffness", sh.stiffness)))
    M0 = np.array(per["M0"])
    M_ref = float(M0.max()) if M0.max() > 0 else 1.0
    # the model (its modal band: the group's fastest motor) with the largest e
    # (the batch loop's tolerances take the largest e as simulate would)
    top_scene = replace(scene, drive=replace(d, torque_at_zero=M_ref))
    motion = scene_motion(scene) if case == "earthquake" else no_motion()
    top = scene.modal_model.band_factor * forcing_top(top_scene.drive, top_scene.load, top_scene.sweep, case, motion)
    model, info = build_model(top_scene, which, top, pillar_modes=pillar_modes)
    kw: dict[str, Any] = dict(
        torque_scale=M0 / M_ref,
        slope=per["s"],
        load=per["k"],
        eccentricity=per["e"],
        shaft_stiffness=per["c2"],
        rtol=sim.rtol,
    )
    extra: dict[str, float] = {}
    if case == "runup":
        drive = DriveSchedule.ramp(M_ref, d.slope, L.coefficient, sim.runup_ramp)
        t_end = sim.duration
        # one thread: the study's parallelism is its Dask workers, one per core
        b = simulate_batch(model, drive, t_end, samples=samples_for(case, t_end), threads=1, **kw)
        frees = [DriveSchedule.ramp(m, s, k, sim.runup_ramp).free_speed() for m, s, k in zip(M0, per["s"], per["k"])]
        extra = {"shaft_from": float(settle_time(scene, t_end))}
    else:
        assert len(runs) == 1, "a run-down or an earthquake run is its own group"
        Wop = operating_speed(model, d.torque_at_zero, d.slope, L.coefficient)
        q0, v0 = model.steady_initial_state(Wop)
        if case == "rundown":
            after = (0.0, 0.0) if sim.rundown_motor == "off" else (sim.rundown_torque_at_zero, d.slope)
            drive = DriveSchedule.switched(d.torque_at_zero, d.slope, L.coefficient, 0.0, *after)
            t_end = sim.duration
            frees = [drive.free_speed() if sim.rundown_motor == "weaker" else 0.0]
        else:
            drive = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
            t_end = sim.earthquake_duration or motion.end + 5.0
            frees = [drive.free_speed()]
            sizes = motion.sizes()
            extra = {"pga": 0.0 if isinstance(sizes, NoMotionSizes) else float(sizes.peak_acceleration)}
        b = simulate_batch(
            model,
            drive,
            t_end,
            q0=q0,
            v0=v0,
            motion=motion,
            speed_scale=Wop,
            samples=samples_for(case, t_end),
            torque_scale=[1.0],
            rtol=sim.rtol,
            threads=1,
        )
        extra["initial_speed"] = float(Wop)
    since = b.t >= extra.pop("shaft_from", 0.0)
    shaft = b.shaft_deflection
    assert shaft is not None, "the batch loop records the shaft's deflection"
    out = []
    for i, p in enumerate(runs):
        mr = replace(model, eccentricity=per["e"][i], shaft_stiffness=per["c2"][i])
        mean = _tail_mean(b.t, b.Omega[i])
        state = capture_state(mr, b.t, b.Omega[i], frees[i])
        captured = state.captured_at
        if case == "earthquake" and model.frame == "absolute":
            tip = float(np.max(np.abs(b.tip[i] - ground_displacement(model, motion, b.t))))
        else:
            tip = float(np.max(b.tip_peak[i]))
        out.append(
            StudyRun(
                index=p.index,
                params=p.params,
                ok=bool(b.ok[i]),
                final_speed=float(b.Omega[i, -1]),
                final_speed_mean=mean,
                captured_at=captured,
                speed_state=state.speed_state,
                passed=None if case == "earthquake" else state.speed_state not in ("captured", "escaping"),
                peak_tip=tip,
                peak_shaft_deflection=float(np.max(shaft[i, since])),
                free_speed=float(frees[i]),
                nfev=int(b.nfev[i]),
                pga=extra.get("pga"),
                initial_speed=extra.get("initial_speed"),
            )
        )
    return out


def warm_kernels() -> None:
    """Load the compiled batch loop in this process (numba's disk cache): one
    tiny run, so that a worker's first batch is timed like the others."""
    from ..scene import load_scene

    model, _ = build_model(load_scene("sommerfeld"), "paper")
    simulate_batch(model, DriveSchedule.constant(600.0, 2.0, 0.5), 0.1)


def run_batch(spec: BatchSpec) -> BatchResult:
    """Compute one batch: its runs grouped by what they must share (``group_key``), each
    group in one call of the batch loop; the ROM's pillar modes from the spec."""
    start = time.perf_counter()
    doc = dict(spec.scene)
    base = scene_from_dict(doc, name=doc.pop("name"))
    groups: dict[tuple, list[PlannedRun]] = {}
    for p in spec.runs:
        key = group_key(p.params, spec.case)
        if not PER_RUN[spec.case]:
            key = key + (("_index", p.index),)
        groups.setdefault(key, []).append(p)
    results: list[StudyRun] = []
    for key, runs in groups.items():
        group_params = {k: v for k, v in key if k != "_index"}
        scene = run_scene(base, group_params, spec.implied)
        modes = None if spec.pillar_modes is None else spec.pillar_modes[mode_key(base, scene)]
        results += _run_group(scene, spec.case, spec.model, runs, modes)
    return BatchResult(
        runs=tuple(sorted(results, key=lambda r: r.index)),
        groups=len(groups),
        wall_seconds=time.perf_counter() - start,
        worker=f"{socket.gethostname()}:{os.getpid()}",
    )
