"""The transient cases of a scene: run-up, run-down, quasi-static sweep, earthquake.

Each case builds the model the scene asks for (rotorpillar.reduced.models:
the paper's Eq. 4 with the scene's tip reduction, or the modal model
with k pillar modes), the drive schedule and the ground motion, integrates,
and condenses the run into a ``CaseSummary`` (rotorpillar.transients.case_summary)
beside the averaging theory's predictions (rotorpillar.reduced.stationary);
the modal model adds its truncation estimate: the same case with k + 1 modes.

The 3D model's pillar modes (``modal_model.source = "fem3d"``) come in as
``pillar_modes``: the caller computes them.

Where ``modal_model.planes`` resolves to "spatial" for a run-up, run-down or
earthquake (rotorpillar.reduced.spatial_scene.transient_model: "auto" also
weighs the drive's reaction), the modal model's case runs on the spatial ROM
(``spatial_modes``: the chain's modes in every direction) with the motor's
reaction on the gondola and every ground component; its truncation estimate
adds the next bending mode in the rotor's plane (``with_spatial_truncation``).
"""

from __future__ import annotations

import contextlib
import math
import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from ..errors import InputError
from ..records import Record, replace
from ..reduced.accuracy import FULL_ORDER_SCHEMES, StepRule, forcing_frequencies, full_order_parameters, full_order_step
from ..reduced.band import forcing_top
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import ExcitationSizes, GroundMotion, no_motion, response_spectrum
from ..reduced.integration import Settings, Transient, check_simulation, simulate
from ..reduced.models import ModelInfo, build_model, scene_motion
from ..reduced.pillar_modes import PillarModes
from ..reduced.rotor_models import RotorStructure
from ..reduced.spatial_modes import SpatialPillarModes
from ..reduced.spatial_rotor import PlanesChoice, SpatialRotor
from ..reduced.spatial_scene import transient_model
from ..reduced.spectral import spectral_terms, srss
from ..reduced.stationary import AveragingPrediction, averaging_prediction, operating_speed, passing_torque
from ..scene import CASES, Scene
from .case_summary import (
    CaseSummary,
    NoSpectrumCheck,
    NoTruncationEstimate,
    SpectralEstimate,
    SpectralMode,
    SpectrumCheck,
    TruncationEstimate,
    run_summary,
)
from .sweep import SweepAnalysis, SweepFindings, rate_convergence, sweep_analysis


@dataclass(frozen=True)
class CaseResult:
    """One case run on one model: the run, its summary, and what the charts need."""

    case: str
    model: RotorStructure
    run: Transient
    summary: CaseSummary
    model_info: ModelInfo | None = None
    """how the model was built (build_model); None for a model handed in"""
    initial_speed: float | None = None
    """the speed the run starts at, where the case sets one (rad/s)"""
    excitation: ExcitationSizes | None = None
    """earthquake: the ground motion's sizes (GroundMotion.sizes)"""
    excitation_in_model: str | None = None
    """earthquake: how the model applies the ground motion, in words"""
    sweep: SweepAnalysis | None = None
    """sweep: the chart's bins and curves"""
    planes: PlanesChoice | None = None
    """the modal model: modal_model.planes resolved for this case, and why (None: other models)"""


def settings_of(scene: Scene, integrator: str | None = None) -> Settings:
    """The scene's [simulate] integration settings, ``integrator`` replacing its method."""
    s = scene.simulate
    return Settings(
        method=integrator or s.integrator, rtol=s.rtol, time_step=s.time_step, samples=s.samples, max_steps=s.max_steps
    )


def full_order_step_rule(
    scene: Scene, case: str, motion: GroundMotion, method: str, model: RotorStructure | None = None
) -> StepRule:
    """The beam's step and why (rotorpillar.reduced.accuracy.full_order_step): the
    longest that resolves the fastest forcing (the unbalance's rotation at the
    rotor's top speed, the ground motion's band) within 2e-3, no coarser than a
    record's sampling, or ``full_order.time_step``; not the stiffest part's (the
    shaft, the beam's shear modes): the implicit schemes damp those (rho_inf).
    Central difference (explicit) stays below 0.9 of its stability limit on ``model``."""
    fo = scene.full_order
    forcing = forcing_frequencies(
        scene.rotor.eccentricity, forcing_top(scene.drive, scene.load, scene.sweep, case, None), motion
    )
    if not forcing:  # nothing forces the structure: the spin's pace
        forcing = {"rotor_speed": forcing_top(scene.drive, scene.load, scene.sweep, case, None)}
    rule = full_order_step(
        method,
        full_order_parameters(method, fo.rho_inf),
        forcing,
        scene.modal_model.band_factor,
        motion.time_step if motion.kind == "record" else None,
        fo.time_step,
    )
    if method == "central_difference" and model is not None and not fo.time_step:
        limit = 0.9 * 2.0 / model.stiffest_frequency()
        if limit < rule.time_step:
            rule = replace(
                rule,
                time_step=limit,
                rule=rule.rule + "; below 0.9 of central difference's "
                f"stability limit 2 / omega_max ({model.stiffest_frequency():.4g} rad/s)",
            )
    return rule


def full_order_settings(
    scene: Scene, case: str, motion: GroundMotion, integrator: str | None = None, model: RotorStructure | None = None
) -> tuple[Settings, StepRule | None]:
    """The beam's settings: [full_order] beam_integrator (or ``integrator``), rho_inf
    and the step of ``full_order_step_rule``; and that rule (None for an adaptive
    ``integrator``: it chooses its own steps)."""
    fo = scene.full_order
    st = settings_of(scene, integrator or fo.beam_integrator)
    if st.method not in FULL_ORDER_SCHEMES:
        return st, None
    st = replace(st, rho_inf=fo.rho_inf, hht_alpha=max(-1 / 3, (fo.rho_inf - 1) / (fo.rho_inf + 1)))
    rule = full_order_step_rule(scene, case, motion, st.method, model)
    return replace(st, time_step=rule.time_step), rule


def case_duration(scene: Scene, case: str, motion: GroundMotion) -> float:
    """The length of a case's run as ``_run_on`` runs it (s)."""
    sim = scene.simulate
    if case == "earthquake":
        return sim.earthquake_duration or motion.end + 5.0
    if case == "sweep":
        d, L, w = scene.drive, scene.load, scene.sweep
        return DriveSchedule.sweep(d.slope, L.coefficient, w.torque_low, w.torque_high, w.rate, w.settle).times[-1]
    return sim.duration


#: The beam's seconds per step and dof**3: Newton on its dense n x n Jacobian, an LU
#: factorisation per iteration, about three a step.  Measured on the 2-core machine,
#: 0.3 s of run-up: 15 ms a step on 163 dofs, 160 ms on 323 (n**3.4 between them; the
#: machine loaded 7-fold); an estimate, stated as one.
BEAM_SECONDS_PER_STEP_DOF3 = 4e-9


def beam_estimate(scene: Scene, case: str, motion: GroundMotion, integrator: str | None = None):
    """(steps, seconds, dofs, duration, step) of the beam's run of ``case``, from the scene
    alone (before the beam is built); None for an adaptive integrator (simulate's own)."""
    fo = scene.full_order
    method = integrator or fo.beam_integrator
    if method not in FULL_ORDER_SCHEMES:
        return None
    duration = case_duration(scene, case, motion)
    h = full_order_step_rule(scene, case, motion, method).time_step
    steps = duration / h
    n = 2 * (fo.beam_elements or scene.modal_model.elements) + 3
    return steps, steps * BEAM_SECONDS_PER_STEP_DOF3 * n**3, n, duration, h


def check_full_order_budget(scene: Scene, case: str, motion: GroundMotion, integrator: str | None = None) -> None:
    """Refuse (InputError naming the keys) a beam run estimated above ``simulate.max_steps``,
    before the beam is built: steps = the case's duration over the rule's step."""
    est = beam_estimate(scene, case, motion, integrator)
    if est is None:  # adaptive: simulate's own estimate
        return
    steps, seconds, n, duration, h = est
    if math.isfinite(steps) and steps <= scene.simulate.max_steps:
        return
    length = (
        "simulate.earthquake_duration"
        if case == "earthquake"
        else "sweep.rate"
        if case == "sweep"
        else "simulate.duration"
    )
    raise InputError(
        f"the beam's {case} of {duration:.4g} s at a step of {h:.3g} s would take about {steps:.3g} "
        f"steps (~{seconds:.3g} s on {n} dofs), more than simulate.max_steps = "
        f"{scene.simulate.max_steps:.3g}: raise full_order.time_step (0 = the band's step), shorten "
        f"{length}, or raise simulate.max_steps"
    )


@contextlib.contextmanager
def quiet_divergence() -> Iterator[None]:
    """numpy's floating-point warnings off for a run's own arithmetic.

    A run past its stability limit overflows on its way to infinity (the model's
    forces, the drive's torque, the summary's maxima of an all-NaN tail); its checks
    say so in the result, where a user reads it (not_finite, stability,
    energy_balance: ``ok: false``, exit 4).  The warnings would only repeat them,
    as tracebacks' lines on stderr.  An overflow that reaches the result is a
    non-finite value, which not_finite fails on."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"), warnings.catch_warnings():
        for text in ("All-NaN slice encountered", "Mean of empty slice", "invalid value encountered"):
            warnings.filterwarnings("ignore", message=text, category=RuntimeWarning)
        yield


def run_case(
    scene: Scene,
    case: str,
    which: str | None = None,
    integrator: str | None = None,
    modes: int | None = None,
    truncation: bool = True,
    progress=None,
    motion: GroundMotion | None = None,
    pillar_modes: PillarModes | None = None,
    spatial_modes: SpatialPillarModes | None = None,
) -> CaseResult:
    """Run one case of the scene; for the modal model also with k + 1 modes.
    ``motion`` (earthquake) defaults to the scene's [excitation];
    ``pillar_modes``: the modal model's candidate modes (needed when
    ``modal_model.source = "fem3d"``, see ``models.build_model``);
    ``spatial_modes``: the chain's modes in every direction (None: the beam's), for a
    modal model whose ``modal_model.planes`` resolves to "spatial"
    (rotorpillar.reduced.spatial_scene.transient_model): the case then runs on the
    spatial ROM, the motor's reaction on the gondola and every ground component acting."""
    m = case_model(scene, case, which, integrator, modes, motion, pillar_modes, spatial_modes)
    result = _run_on(scene, case, m.model, m.motion, integrator, m.info, m.settings)
    if m.planes is not None:
        result = replace(result, planes=m.planes)
    if m.rule is not None:
        rule = m.rule
        result = replace(
            result,
            run=replace(result.run, stats=replace(result.run.stats, step_rule=rule)),
            summary=replace(result.summary, integrator=replace(result.summary.integrator, step_rule=rule)),
        )
    if m.which == "modal" and truncation:
        if isinstance(result.model, SpatialRotor):
            result = with_spatial_truncation(scene, result, m.motion, integrator, spatial_modes, progress)
        else:
            result = with_truncation(scene, result, m.motion, integrator, pillar_modes, progress)
    return result


class CaseModel(Record):
    """The model a case runs on and the ground motion it takes, built as ``run_case`` builds them."""

    which: str
    """the model asked for: paper, modal or beam"""
    model: RotorStructure
    """the model (the spatial ROM, duck-typed, where modal_model.planes resolves to spatial)"""
    motion: GroundMotion
    """the ground motion: none but for the earthquake; the spatial ROM's takes every component"""
    info: ModelInfo | None
    """how the model was built (build_model)"""
    planes: PlanesChoice | None
    """the modal model: modal_model.planes resolved for this case, and why (None: other models)"""
    settings: Settings | None
    """the beam's integration settings, from its step rule (None: the scene's [simulate])"""
    rule: StepRule | None
    """the beam's step rule (None: other models)"""


def case_model(
    scene: Scene,
    case: str,
    which: str | None = None,
    integrator: str | None = None,
    modes: int | None = None,
    motion: GroundMotion | None = None,
    pillar_modes: PillarModes | None = None,
    spatial_modes: SpatialPillarModes | None = None,
) -> CaseModel:
    """The model of ``case`` and its ground motion (the arguments as ``run_case`` takes them);
    a beam over its step budget is refused before it is built."""
    if case not in CASES:
        raise InputError(f"case {case!r}: must be one of {', '.join(CASES)}")
    which = which or scene.simulate.model
    if case != "earthquake":
        motion = no_motion()
    elif motion is None:
        motion = scene_motion(scene)
    if which == "beam":  # before the beam is built
        check_full_order_budget(scene, case, motion, integrator)
    top = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, case, motion)
    model, info = build_model(scene, which, top, modes, pillar_modes)
    planes = None
    if which == "modal":
        planes, spatial = transient_model(scene, case, top, model, spatial_modes)
        if spatial is not None:
            # duck-typed: SpatialRotor offers the RotorStructure interface the case and its summary read
            model = cast(RotorStructure, spatial)
            motion = spatial_motion(scene, case, motion)
    settings, rule = full_order_settings(scene, case, motion, integrator, model) if which == "beam" else (None, None)
    return CaseModel(which, model, motion, info, planes, settings, rule)


class CaseStart(Record):
    """A case's first integration, as ``simulate`` takes it (rotorpillar.reduced.integration),
    and the averaging theory's prediction, made before it."""

    drive: DriveSchedule
    """the motor's torque schedule"""
    t_end: float
    """the run's end (s); it starts at 0"""
    q0: np.ndarray | None
    """the start's displacements (m, rad); None: at rest"""
    v0: np.ndarray | None
    """the start's velocities (m/s, rad/s); None: at rest"""
    speed_scale: float | None
    """the speed the run integrates at (rad/s); None: simulate's own, from the drive"""
    settings: Settings
    """the integration settings of the run"""
    initial_speed: float | None
    """the speed the run starts at, where the case sets one (rad/s)"""
    prediction: AveragingPrediction
    """the paper's Eq. 19-23 for the scene's drive on the model"""


def case_start(scene: Scene, case: str, model: RotorStructure, motion: GroundMotion, settings: Settings) -> CaseStart:
    """Where ``case`` starts on ``model`` and how long it runs (see the module text); an
    earthquake run that ends before the ground moves is refused (InputError)."""
    d, L, sim = scene.drive, scene.load, scene.simulate
    M0, s, k = d.torque_at_zero, d.slope, L.coefficient
    pred = averaging_prediction(model, M0, s, k)
    if case == "runup":
        drive = DriveSchedule.ramp(M0, s, k, sim.runup_ramp)
        if sim.runup_initial_speed > 0:
            W0 = sim.runup_initial_speed
            return CaseStart(drive, sim.duration, *model.held_whirl_state(W0), W0, settings, W0, pred)
        return CaseStart(drive, sim.duration, None, None, None, settings, None, pred)
    if case in ("rundown", "earthquake"):
        Wop = operating_speed(model, M0, s, k)
        q0, v0 = on_reaction(model, *model.steady_initial_state(Wop), M0 - s * Wop)
        if case == "rundown":
            drive = DriveSchedule.switched(M0, s, k, 0.0, *_rundown_motor(scene))
            return CaseStart(drive, sim.duration, q0, v0, Wop, settings, Wop, pred)
        t_end = sim.earthquake_duration or motion.end + 5.0
        if t_end <= motion.start:
            raise InputError(
                f"simulate.earthquake_duration = {t_end:g} s ends before the ground motion starts ({motion.start:g} s)"
            )
        return CaseStart(DriveSchedule.constant(M0, s, k), t_end, q0, v0, Wop, settings, Wop, pred)
    w = scene.sweep
    drive = DriveSchedule.sweep(s, k, w.torque_low, w.torque_high, w.rate, w.settle)
    sweep_settings = replace(settings, samples=max(settings.samples, 40 * w.bins))
    return CaseStart(drive, drive.times[-1], None, None, drive.free_speed(drive.times[2]), sweep_settings, None, pred)


def _rundown_motor(scene: Scene) -> tuple[float, float]:
    """The motor of a run-down after the switch: (M0 (N*m), slope (N*m*s)); off: (0, 0)."""
    sim = scene.simulate
    return (0.0, 0.0) if sim.rundown_motor == "off" else (sim.rundown_torque_at_zero, scene.drive.slope)


def check_case(
    scene: Scene,
    case: str,
    which: str | None = None,
    integrator: str | None = None,
    modes: int | None = None,
    motion: GroundMotion | None = None,
) -> None:
    """Refuse (InputError, one line) a run of ``case`` that ``run_case`` (without its
    truncation check) would refuse, doing only the work before its first integration:
    the model built (a beam over its budget refused first), the start found, and
    ``simulate``'s own checks (rotorpillar.reduced.integration.check_simulation).
    Nothing is integrated; a command calls it before any work."""
    m = case_model(scene, case, which, integrator, modes, motion)
    with quiet_divergence():
        start = case_start(scene, case, m.model, m.motion, m.settings or settings_of(scene, integrator))
        check_simulation(
            m.model, start.drive, m.motion, start.t_end, start.v0, start.settings, speed_scale=start.speed_scale
        )


def spatial_motion(scene: Scene, case: str, motion: GroundMotion):
    """The ground motion the spatial ROM takes: the scene's components and angle
    (rotorpillar.reduced.ground3d.scene_spatial_motion) where they leave the rotor's plane,
    else ``motion`` as it is (one component in the plane)."""
    x = scene.excitation
    if case == "earthquake" and (x.components > 1 or math.sin(math.radians(x.angle)) != 0):
        from ..reduced.ground3d import scene_spatial_motion

        return scene_spatial_motion(x)
    return motion


def with_spatial_truncation(
    scene: Scene,
    result: CaseResult,
    motion: GroundMotion | None,
    integrator: str | None = None,
    spatial_modes: SpatialPillarModes | None = None,
    progress=None,
) -> CaseResult:
    """A spatial ROM's result with its truncation estimate: the same case with the next bending
    mode in the rotor's plane above the band added (the planar ROM's k + 1 likewise adds its
    next mode; the modes out of the plane above the band, torsion and axial first, leave the
    tip in the rotor's plane unchanged but through the rotor's coupling)."""
    from ..reduced.spatial_modes import BENDING_IN_PLANE
    from ..reduced.spatial_scene import scene_spatial_model, scene_spatial_modes

    m = result.model
    assert isinstance(m, SpatialRotor)  # a spatial ROM's result
    kept = m.structure.modes
    k = kept.count
    every = scene_spatial_modes(scene, spatial_modes)
    after = [int(j) for j in every.of_kind(BENDING_IN_PLANE) if j >= k]
    trunc: TruncationEstimate | NoTruncationEstimate
    if not after:
        trunc = NoTruncationEstimate(
            modes=k,
            modes_check=None,
            statement=f"no truncation estimate: the mode source ({every.source}) offers no bending mode in the "
            f"rotor's plane above the {k} kept (for fem3d: raise modal.n_modes)",
        )
        return replace(result, summary=replace(result.summary, truncation=trunc))
    if progress:
        progress(f"truncation check: the same case with the next bending mode ({every.omega[after[0]]:.4g} rad/s)")
    more = every.select(list(range(k)) + after[:1])
    m2 = SpatialRotor.of(scene_spatial_model(scene, math.inf, more), m.planes)
    b = _run_on(
        scene,
        result.case,
        cast(RotorStructure, m2),
        spatial_motion(scene, result.case, motion or no_motion()),
        integrator,
    )
    a = result
    ma, mb = a.summary.max_abs, b.summary.max_abs
    tip_b = np.interp(a.run.t, b.run.t, b.run.tip())
    scale = max(np.max(np.abs(tip_b)), 1e-300)

    def rel(key: str) -> float | None:
        x, y = ma.get(key), mb.get(key)
        return y / x - 1 if x and y is not None and x > 0 else None

    trunc = TruncationEstimate(
        modes=k,
        modes_check=k + 1,
        omega_added=float(every.omega[after[0]]),
        effective_mass_fraction=kept.effective_mass_fraction(0),
        effective_mass_fraction_check=more.effective_mass_fraction(0),
        omega_final_rel_diff=b.summary.omega_final / a.summary.omega_final - 1 if a.summary.omega_final else None,
        tip_series_max_rel_diff=float(np.max(np.abs(a.run.tip() - tip_b)) / scale),
        tip_x_max_rel_diff=rel("tip_x"),
        rotor_x_max_rel_diff=rel("rotor_x"),
        rotor_y_max_rel_diff=rel("rotor_y"),
    )
    return replace(result, summary=replace(result.summary, truncation=trunc))


def with_truncation(
    scene: Scene,
    result: CaseResult,
    motion: GroundMotion | None,
    integrator: str | None = None,
    pillar_modes: PillarModes | None = None,
    progress=None,
) -> CaseResult:
    """A modal model's result with its truncation estimate: the same case with k + 1 modes."""
    model = result.model
    assert model.pillar_modes is not None  # a modal model's result
    k = model.pillar_modes.count
    if progress:
        progress(f"truncation check: the same case with {k + 1} modes")
    model2, _ = build_model(scene, "modal", modes=k + 1, pillar_modes=pillar_modes)
    assert model2.pillar_modes is not None
    trunc: TruncationEstimate | NoTruncationEstimate
    if model2.pillar_modes.count == k:
        trunc = NoTruncationEstimate(
            modes=k,
            modes_check=None,
            statement=f"no truncation estimate: the mode source ({model.pillar_modes.source}) "
            f"offers only {k} X bending modes (for fem3d: raise modal.n_modes)",
        )
    else:
        trunc = truncation_estimate(result, _run_on(scene, result.case, model2, motion or no_motion(), integrator))
    return replace(result, summary=replace(result.summary, truncation=trunc))


def truncation_estimate(a: CaseResult, b: CaseResult) -> TruncationEstimate:
    """How much the (k+1)-th mode changes the answers: the truncation error estimate."""
    ma, mb = a.summary.max_abs, b.summary.max_abs
    tip_b = np.interp(a.run.t, b.run.t, b.run.tip())
    scale = max(np.max(np.abs(tip_b)), 1e-300)
    pa, pb = a.model.pillar_modes, b.model.pillar_modes
    assert pa is not None and pb is not None  # modal models' results

    def rel(key: str) -> float | None:
        x, y = ma.get(key), mb.get(key)
        return y / x - 1 if x and y is not None and x > 0 else None

    return TruncationEstimate(
        modes=pa.count,
        modes_check=pb.count,
        omega_added=float(pb.omega[-1]),
        effective_mass_fraction=pa.effective_mass_fraction(),
        effective_mass_fraction_check=pb.effective_mass_fraction(),
        omega_final_rel_diff=b.summary.omega_final / a.summary.omega_final - 1 if a.summary.omega_final else None,
        tip_series_max_rel_diff=float(np.max(np.abs(a.run.tip() - tip_b)) / scale),
        tip_x_max_rel_diff=rel("tip_x"),
        rotor_x_max_rel_diff=rel("rotor_x"),
        rotor_y_max_rel_diff=rel("rotor_y"),
    )


def _run_on(
    scene: Scene,
    case: str,
    model: RotorStructure,
    motion: GroundMotion,
    integrator: str | None,
    model_info: ModelInfo | None = None,
    settings: Settings | None = None,
) -> CaseResult:
    """One case on one model, run and summarised; a diverging run's warnings are left to
    its checks (``quiet_divergence``)."""
    with quiet_divergence():
        return _run_and_summarise(scene, case, model, motion, integrator, model_info, settings)


def _run_and_summarise(
    scene: Scene,
    case: str,
    model: RotorStructure,
    motion: GroundMotion,
    integrator: str | None,
    model_info: ModelInfo | None = None,
    settings: Settings | None = None,
) -> CaseResult:
    sim = scene.simulate
    st = settings or settings_of(scene, integrator)
    s, k = scene.drive.slope, scene.load.coefficient
    start = case_start(scene, case, model, motion, st)
    drive, pred, initial_speed = start.drive, start.prediction, start.initial_speed
    run = simulate(
        model, drive, motion, start.t_end, start.q0, start.v0, settings=start.settings, speed_scale=start.speed_scale
    )
    sections: dict[str, Any] = {}
    excitation, excitation_in_model, sweep = None, None, None
    if case == "runup":
        free = drive.free_speed()
        if sim.threshold:
            sections["passing_torque"] = passing_torque(model, drive, sim.duration, st.rtol)
    elif case == "rundown":
        free = drive.free_speed() if sim.rundown_motor == "weaker" else 0.0
        pred = averaging_prediction(model, *_rundown_motor(scene), k)
    elif case == "earthquake":
        free = drive.free_speed()
        excitation = sections["excitation"] = motion.sizes()
        excitation_in_model = (
            "Eq. 4 as published: c0 q5 + b0 q5' on q1, c2 q5 + b2 q5' on q2 (absolute coordinates)"
            if model.frame == "absolute"
            else "relative to the ground, forced by -M r a_g (a_g = q5'' inside the window; the "
            "displacement step of the written q5 carries no finite acceleration and is not applied)"
        )
        if isinstance(model, SpatialRotor):
            excitation_in_model, run = spatial_excitation(model, motion, run)
            sections["response_spectrum_check"] = NoSpectrumCheck(
                "the spatial ROM: the response-spectrum estimate is the planar ROM's (one component, its modes)"
            )
        elif motion.kind == "record":
            sections["response_spectrum_check"] = spectrum_check(model, motion, run)
    else:
        w = scene.sweep
        free = drive.free_speed()
        sw = sweep_analysis(w, s, k, model, run, drive)
        sweep = sw
        rates = None
        if sw.numeric_jumps:
            rates = rate_convergence(w, s, k, model, st, sw.numeric_jumps, sw.predicted_jumps)
        sections["jumps"] = sw.numeric_jumps
        sections["captured_at"] = sw.captured_at
        sections["captured_resonance"] = sw.captured_resonance
        sections["captured_index"] = sw.captured_index
        sections["sweep"] = SweepFindings(
            predicted_jumps=sw.predicted_jumps,
            jump_comparison=sw.jump_comparison,
            largest_speed_step_ratio=sw.largest_speed_step_ratio,
            amplitudes=sw.amplitudes,
            rate_check=sw.rate_check,
            no_jump_reason=sw.no_jump_reason,
            rate_convergence=rates,
        )
    summary = run_summary(run, free, pred, **sections)
    return CaseResult(case, model, run, summary, model_info, initial_speed, excitation, excitation_in_model, sweep)


def on_reaction(model, q0: np.ndarray, v0: np.ndarray, torque: float) -> tuple[np.ndarray, np.ndarray]:
    """A start at speed on the spatial ROM starts on the static deflection under the motor's
    ``torque`` (N*m) reacting on the gondola (SpatialRotor.reaction_deflection); the planar
    models' start as it is."""
    if isinstance(model, SpatialRotor):
        return q0 + model.reaction_deflection(torque), v0
    return q0, v0


def spatial_excitation(model: SpatialRotor, motion, run: Transient) -> tuple[str, Transient]:
    """How the spatial ROM applies the ground motion, in words, and the run as its summary reads
    it: a multi-component motion's series (``ground_x``) are its first component's.  The words
    name the motor's reaction on the gondola only where ``model`` carries it (a model built with
    ``drive_reaction=False`` has a zero reaction vector)."""
    from ..reduced.ground3d import SpatialGroundMotion

    reaction = (
        "the motor's reaction on the gondola acting"
        if np.any(model.structure.reaction)
        else "no motor reaction on the gondola (the model leaves it off)"
    )
    words = f"the spatial ROM, relative to the ground, forced by -M r a_g in each direction; {reaction}"
    if isinstance(motion, SpatialGroundMotion):
        names = ", ".join(f"{n} along {tuple(round(c, 6) for c in d)}" for n, d in zip(motion.names, motion.directions))
        words += (
            f"; {motion.count} components ({names}; x in the rotor's plane, y along the spin axis, z "
            "vertical); ground_x and ground_acceleration are the ground's motion in the rotor's plane"
        )
        run = replace(run, motion=in_rotor_plane(motion))
    return words, run


def in_rotor_plane(motion) -> GroundMotion:
    """A SpatialGroundMotion's motion in the rotor's plane (x) as one GroundMotion: each
    component times its direction's x (the components share one grid, or one pulse)."""
    first = motion.components[0]
    dx = [float(d[0]) for d in motion.directions]
    if first.kind == "pulse" and motion.count == 1:
        return replace(first, amplitude=first.amplitude * dx[0])
    if first.kind != "record" or any(len(c.acceleration) != len(first.acceleration) for c in motion.components):
        raise ValueError("the ground's components must be records on one grid")

    def x_of(field: str) -> np.ndarray:
        return sum((w * getattr(c, field) for w, c in zip(dx, motion.components)), np.zeros(len(first.acceleration)))

    return replace(
        first,
        displacement=x_of("displacement"),
        velocity=x_of("velocity"),
        acceleration=x_of("acceleration"),
        name=f"{first.name}: the {motion.count} components in the rotor's plane",
    )


def spectral_estimate(model: RotorStructure, motion: GroundMotion) -> SpectralEstimate:
    """The response-spectrum estimate of the tip's largest displacement relative to the
    ground over the coupled rotor-pillar modes in X (rotorpillar.reduced.spectral: the
    modes of M, Ks + c2 d d^T, each at its own damping ratio, SRSS), and the same over the
    pillar's own modes with the rotor apart (Ks, the rotor's row and column dropped): how
    much the coupling moves the estimate.  Modal model only (relative to the ground)."""
    assert model.pillar_modes is not None and model.frame == "relative_to_ground"  # modal model only

    def s_d(period: float, zeta: float) -> float:
        return float(response_spectrum(motion, [period], damping=zeta).s_d[0])

    b, tip = model.base_acceleration, model.tip
    coupled = spectral_terms(model.mass, model.stiffness_full(), model.damping, b, tip, s_d)
    keep = [i for i in range(model.nx) if i != model.rotor_x]
    part = np.ix_(keep, keep)
    alone = spectral_terms(model.mass[part], model.stiffness[part], model.damping[part], b[keep], tip[keep], s_d)
    rows = tuple(
        SpectralMode(
            mode=j,
            period=t.period,
            damping_ratio=t.damping_ratio,
            participation_factor=t.participation,
            s_d=t.s_d,
            contribution=t.contribution,
        )
        for j, t in enumerate(coupled, start=1)
    )
    return SpectralEstimate(rows, srss(coupled), srss(alone))


def spectrum_check(model: RotorStructure, motion: GroundMotion, run: Transient) -> SpectrumCheck | NoSpectrumCheck:
    """The tip's largest relative displacement beside the response-spectrum estimate over
    the coupled modes (``spectral_estimate``): the mode of the largest contribution alone,
    and every mode (SRSS); the ratio is against the SRSS."""
    if model.pillar_modes is None or model.frame != "relative_to_ground":
        return NoSpectrumCheck("needs the modal model")
    est = spectral_estimate(model, motion)
    top = max(est.modes, key=lambda m: m.contribution)
    num = float(np.max(np.abs(run.tip()[run.t >= motion.start])))
    total = est.srss_tip_estimate
    return SpectrumCheck(
        period=top.period,
        damping_ratio=top.damping_ratio,
        participation_factor=top.participation_factor,
        s_d=top.s_d,
        tip_estimate=top.contribution,
        tip_numeric=num,
        ratio=num / total if total > 0 else None,
        srss_tip_estimate=total,
        modes=est.modes,
        note=(
            "the coupled rotor-pillar modes in X, each at its own damping ratio; period .. tip_estimate: "
            "the mode of the largest contribution alone; srss_tip_estimate: every mode, SRSS (an estimate, "
            f"not a bound); over the pillar's own modes, the rotor apart, the SRSS would read "
            f"{est.pillar_modes_only:.4g} m"
        ),
    )
