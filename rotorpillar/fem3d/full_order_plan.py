"""What a 3D full-order run will do, decided before any meshing: its case, its step, its cost.

- ``case_setup``: the case's ground motion, drive, duration and start speed,
  as the reduced models run it;
- ``step_rule``: the step the band asks (rotorpillar.reduced.accuracy.full_order_step:
  the fastest forcing resolved by the scheme within 2e-3, no coarser than a
  record's sampling; the modes far above the band damped by the scheme);
- ``estimate`` / ``check_budget``: steps and wall time from the scene alone
  (the mesh's DOFs are estimated, not built), refused above
  ``simulate.max_steps`` or ``simulate.max_seconds`` with the keys to change;
- ``accuracy_failures``: the finished run's step against what it had to resolve.
"""

from __future__ import annotations

import math

from ..errors import InputError
from ..records import Record
from ..reduced.accuracy import (
    AccuracyCheck,
    StepRule,
    check_step,
    forcing_frequencies,
    full_order_parameters,
    full_order_step,
)
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import GroundMotion, no_motion
from ..scene import Scene

CASES_3D = ("earthquake", "runup")
SCHEMES_3D = ("newmark", "hht", "generalized_alpha")


def case_setup(
    scene: Scene,
    case: str,
    motion: GroundMotion | None,
    drive: DriveSchedule | None,
    duration: float | None,
    initial_speed: float | None,
):
    """(motion, drive, duration, initial speed, notes) of a case, as the reduced models run it."""
    if case not in CASES_3D:
        raise InputError(f"case {case!r}: the 3D full-order model runs {', '.join(CASES_3D)}")
    d, L, sim = scene.drive, scene.load, scene.simulate
    notes = {}
    if case == "earthquake":
        if motion is None:
            from ..reduced.models import scene_motion

            motion = scene_motion(scene)
        drive = drive or DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
        duration = duration or sim.earthquake_duration or motion.end + 5.0
        if initial_speed is None:
            initial_speed = beam_operating_speed(scene, drive, motion)
            notes["initial_speed_source"] = (
                "the operating speed of the modal model on the 1D beam's modes (the fastest stable stationary speed)"
            )
    else:
        motion = motion or no_motion()
        drive = drive or DriveSchedule.ramp(d.torque_at_zero, d.slope, L.coefficient, sim.runup_ramp)
        duration = duration or sim.duration
        initial_speed = initial_speed or 0.0
    if not (math.isfinite(duration) and duration > 0):
        raise InputError(f"duration = {duration!r}: must be finite and > 0 (s)")
    return motion, drive, float(duration), float(initial_speed), notes


def beam_operating_speed(scene: Scene, drive: DriveSchedule, motion: GroundMotion) -> float:
    """The operating speed from the modal model on the 1D beam's modes (cheap, no dolfinx):
    far from the resonances it differs from the 3D one by the beams' frequency error only."""
    from ..reduced.models import build_model
    from ..reduced.stationary import operating_speed
    from ..scene import with_values

    beam = with_values(scene, {"modal_model.source": "beam"})
    top = scene.modal_model.band_factor * max(drive.free_speed(), motion.band())
    model, _ = build_model(beam, "modal", top)
    return operating_speed(model, drive.torque_at_zero[-1], drive.slope[-1], drive.load_coefficient)


def scheme_parameters(method: str, rho_inf: float) -> dict:
    """The 3D run's generalized-alpha parameters (reduced.accuracy.full_order_parameters)."""
    if method not in SCHEMES_3D:
        raise InputError(f"full_order.integrator = {method!r}: must be one of {', '.join(SCHEMES_3D)}")
    return full_order_parameters(method, rho_inf)


def top_speed(drive: DriveSchedule, speed: float) -> float:
    """The fastest the rotor runs (rad/s): the start, or the drive's free speed at any knot."""
    frees = [drive.free_speed(t) for t in drive.times] + [drive.free_speed()]
    return max([abs(speed)] + [w for w in frees if math.isfinite(w)])


def step_rule(
    scene: Scene, drive: DriveSchedule, motion: GroundMotion, speed: float, time_step: float | None = None
) -> StepRule:
    """The 3D run's step and why: ``time_step``, else ``simulate.time_step`` or
    ``full_order.time_step`` when set, else the band's rule (module text)."""
    fo = scene.full_order
    forcing = forcing_frequencies(scene.rotor.eccentricity, top_speed(drive, speed), motion)
    if not forcing:  # nothing forces the structure: the spin's pace
        forcing = {"rotor_speed": top_speed(drive, speed)}
    stated, by = 0.0, ""
    for value, key in (
        (time_step, "time_step"),
        (scene.simulate.time_step, "simulate.time_step"),
        (fo.time_step, "full_order.time_step"),
    ):
        if value:
            stated, by = float(value), key
            break
    if by == "time_step":  # the caller's: name the key it came from
        by = next(
            (
                k
                for v, k in ((fo.time_step, "full_order.time_step"), (scene.simulate.time_step, "simulate.time_step"))
                if v == stated
            ),
            "the caller's time_step",
        )
    return full_order_step(
        fo.integrator,
        scheme_parameters(fo.integrator, fo.rho_inf),
        forcing,
        scene.modal_model.band_factor,
        motion.time_step if motion.kind == "record" else None,
        stated,
        by,
    )


# --------------------------------------------------------------------------
# Cost, before any work

#: Seconds per step, a + b * dofs**1.5: Python's share of a step, and MUMPS's
#: forward-backward solve and one matrix product, which grow about as
#: dofs**1.5 on the tube's meshes.  Fitted to the CPU time measured on the
#: 2-core machine: 1.3 ms a step on 3,033 dofs (8 x 10), 8 ms on 11,817
#: (16 x 20).  An estimate, stated as one (the machine's load multiplies it).
SECONDS_PER_STEP = (3.0e-4, 6.0e-9)
#: The wall time before the first step (meshing, assembly, factorisation) as a share of
#: the estimate of a `modal` run on the same mesh (rotorpillar.mesh.tube.MODAL_SECONDS:
#: two meshings and assemblies, and the eigen-solves).  Measured on the 2-core machine
#: shared with two `modal` runs: 4096 x 2 elements (368,649 dofs), 31 s before the first
#: step (14 s assembly, 7 s factorisation), 0.21 of modal's estimate there (145 s).  Its
#: 59 steps took 5.0 s each against SECONDS_PER_STEP's 1.35 s: the load, and the estimate
#: of a step is low this far above the meshes it was fitted on.
SETUP_SHARE = 0.2


class RunEstimate(Record):
    """A 3D run's size before it starts."""

    steps: float
    """integration steps (-)"""
    time_step: float
    """(s)"""
    duration: float
    """(s)"""
    dofs: int
    """estimated unknowns of the mesh (-)"""
    seconds: float
    """estimated wall time of the integration (s)"""
    setup_seconds: float = 0.0
    """estimated wall time before the first step: meshing, assembly, factorisation (s)"""


def estimate(scene: Scene, duration: float, rule: StepRule, mesh=None) -> RunEstimate:
    """Steps and wall time of a run of ``duration`` at the rule's step on ``mesh``
    (default ``scene.mesh``), from the scene alone."""
    from ..mesh import tube_params

    mesh = scene.mesh if mesh is None else mesh
    p = tube_params(scene.pillar, mesh)
    dofs = p.estimated_dofs + 9
    steps = duration / rule.time_step if rule.time_step > 0 else math.inf
    a, b = SECONDS_PER_STEP
    return RunEstimate(
        float(steps),
        rule.time_step,
        float(duration),
        int(dofs),
        float(steps * (a + b * dofs**1.5)),
        SETUP_SHARE * p.estimated_seconds,
    )


def check_budget(scene: Scene, case: str, est: RunEstimate) -> None:
    """Refuse (InputError, one line naming the keys) a run above ``simulate.max_steps``
    or estimated above ``simulate.max_seconds``."""
    limit = scene.simulate.max_steps
    length = "full_order.earthquake_duration" if case == "earthquake" else "full_order.runup_duration"
    own = "simulate.earthquake_duration" if case == "earthquake" else "simulate.duration"
    if math.isfinite(est.steps) and est.steps <= limit:
        total, budget = est.seconds + est.setup_seconds, scene.simulate.max_seconds
        if total <= budget:
            return
        raise InputError(
            f"the 3D {case} of {est.duration:.4g} s on ~{est.dofs:,} dofs would take about "
            f"{duration_text(total)} (an estimate: ~{duration_text(est.setup_seconds)} meshing and "
            f"factorising, {est.steps:.3g} steps of {est.time_step:.3g} s), more than "
            f"simulate.max_seconds = {budget:.3g} s: use fewer elements (full_order.elements_around, "
            f"full_order.elements_along), shorten {length} or {own}, or raise simulate.max_seconds"
        )
    raise InputError(
        f"the 3D {case} of {est.duration:.4g} s at a step of {est.time_step:.3g} s would take about "
        f"{est.steps:.3g} steps (~{duration_text(est.seconds)} on ~{est.dofs:,} dofs), more than "
        f"simulate.max_steps = {limit:.3g}: raise full_order.time_step (0 = the band's step), "
        f"shorten {length} or {own}, or raise simulate.max_steps"
    )


def duration_text(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "forever"
    for unit, size in (("days", 86400), ("h", 3600), ("min", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


def accuracy(scene: Scene, h: float, duration: float, top: float, motion: GroundMotion) -> AccuracyCheck:
    """The step ``h`` a run took against what it had to resolve: the unbalance's
    rotation at the fastest speed it reached, ``top``, and the ground motion's band
    (rotorpillar.reduced.accuracy.check_step)."""
    fo = scene.full_order
    window = (motion.start, motion.end) if motion.kind != "none" else None
    return check_step(
        fo.integrator,
        scheme_parameters(fo.integrator, fo.rho_inf),
        h,
        forcing_frequencies(scene.rotor.eccentricity, top, motion),
        duration,
        window=window,
    )
