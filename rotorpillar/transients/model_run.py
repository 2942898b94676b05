"""One model of one transient case, run the same way for `simulate` and `compare`.

``run_model(scene, case, model)`` -> ``ModelRun``: the JSON fields every
model reports (``model``, ``case``, ``ok``, ``warnings``, ``max_abs`` with
``tip_x_relative`` and ``tip_x_absolute``, ``omega_final``, ``captured_at``,
``energy_balance``, ``integrator``, ``dofs``, ``wall_seconds``, and for the
full-order models ``full_order``) and the series of the NPZ/CSV (``t``,
``Omega``, ``tip_x_relative``, ``tip_x_absolute``, ``ground_x``,
``ground_acceleration``, ``rotor_x``, ``rotor_y``, ``shaft_deflection_x``
beside the existing columns).

- paper, modal, beam: rotorpillar.transients.cases.run_case (the beam is the
  full-order 1D beam, integrated by [full_order] beam_integrator at the
  forcing's step); the modal model (the ROM) takes its pillar modes from the
  chain (rotorpillar.chain: the model the convergence study chose, or the
  scene's own), which the caller resolves once and hands in;
- fem3d: rotorpillar.fem3d.full_order.simulate_fem3d on the mesh and over the
  duration [full_order] states (rotorpillar.transients.run_plan.fem3d_plan);
  its ``captured_at`` and resonances come from the chain's ROM (the 3D run has
  no quasi-normal data of its own; the capture width, 3 % at least, is far
  wider than the ROM's frequency error).

Every result names the pillar model it ran on (``pillar_model``, a
rotorpillar.chain.PillarModel from rotorpillar.transients.pillar_models) and
its costs measured warm: what a run compiles (numba's kernels, FFCx's forms)
is compiled by a short warm-up before the timed run, and its time recorded
apart as ``compile_seconds``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..chain import ChainModes
from ..errors import InputError
from ..reduced.models import BeamModelInfo, PaperModelInfo
from ..scene import MODELS, override
from .pillar_models import reduced_pillar_model, solid_pillar_model
from .run_plan import fem3d_plan, with_duration
from .run_records import BeamFullOrder, Fem3dRun, ReducedRun, RunRecord


@dataclass(frozen=True, eq=False)
class ModelRun:
    """A model's run of a case: its JSON fields, its series, and what its charts need."""

    case: str
    model: str
    record: RunRecord
    """the run's record: the JSON fields of simulate_<case>_<model>.json (less files and
    provenance)"""
    data: dict
    """the series (arrays) of the NPZ/CSV"""
    resonances: list = field(default_factory=list)
    """rotorpillar.reduced.system.Resonance records (charts)"""
    case_result: object = None
    """the reduced models' CaseResult (the run-up's brackets, the sweep's curves), else None"""


def run_model(
    scene: Scene,
    case: str,
    model: str,
    integrator: str | None = None,
    modes: int | None = None,
    progress=None,
    motion=None,
    duration: float | None = None,
    chain: ChainModes | None = None,
    field_dir=None,
    field_stem: str | None = None,
    study_dir=None,
) -> ModelRun:
    """Run ``model`` (one of scene.MODELS) on ``case``; ``duration`` shortens the run
    (compare: one window for every model); ``chain`` the chain's pillar model and
    modes (rotorpillar.chain.resolve; None: the scene's own, no study); ``field_dir``:
    where the 3D model writes its stress field's XDMF time series (None: not written),
    named ``field_stem`` (default ``simulate_<case>_fem3d``); ``study_dir``: where the
    convergence study lies (fem3d's reference mesh, ``fem3d_plan``).  Bad input raises
    InputError before any work."""
    if model not in MODELS:
        raise InputError(f"model {model!r}: must be one of {', '.join(MODELS)}")
    if case == "earthquake" and motion is None:
        from ..reduced.models import scene_motion

        motion = scene_motion(scene)
    if model in ("modal", "fem3d"):
        if chain is None:
            from ..chain import resolve

            chain = resolve(scene, None, motion=motion, progress=progress)
        if model == "fem3d":
            return _run_fem3d(
                scene,
                case,
                motion,
                duration,
                progress,
                chain,
                field_dir,
                field_stem or f"simulate_{case}_fem3d",
                study_dir,
            )
    if duration is not None:
        scene = with_duration(scene, case, duration)
    from .cases import quiet_divergence

    with quiet_divergence():  # a diverging run: its checks say so (not_finite, stability)
        return _run_reduced(scene, case, model, integrator, modes, progress, motion, chain)


# --------------------------------------------------------------------------
# paper, modal, beam


def pillar_modes_for(which: str, chain: ChainModes | None):
    """The chain's candidate pillar modes for the modal model, else None."""
    return chain.modes if which == "modal" and chain is not None else None


def warm_up(scene: Scene, case: str, which: str, integrator, modes, motion, pillar_modes) -> float:
    """Compile what the run will (numba's kernels, per integrator and case) on a run of a
    few milliseconds of the same case; its wall time (s), kept apart from the run's."""
    from .cases import run_case

    short = override(
        scene,
        [
            "simulate.threshold=false",
            f"simulate.{'earthquake_duration' if case == 'earthquake' else 'duration'}"
            f"={(motion.start + 1e-2) if case == 'earthquake' else 1e-2!r}",
        ],
    )
    if case == "sweep":
        return 0.0  # a sweep's schedule has no short form; its kernels are dp5's
    start = time.perf_counter()
    try:
        run_case(short, case, which, integrator, modes, truncation=False, motion=motion, pillar_modes=pillar_modes)
    except InputError:
        pass  # the real run refuses it the same way, with its own message
    return time.perf_counter() - start


def _run_reduced(scene: Scene, case, which, integrator, modes, progress, motion, chain) -> ModelRun:
    from ..reduced.excitation import no_motion
    from .case_summary import ground_displacement, series
    from .cases import run_case, with_truncation

    pillar_modes = pillar_modes_for(which, chain)
    if which == "beam" and progress:
        from ..fem3d.full_order_plan import duration_text
        from .cases import beam_estimate

        est = beam_estimate(scene, case, motion or no_motion(), integrator)
        if est is not None:
            progress(
                f"beam full order: {est[0]:.3g} steps of {est[4]:.3g} s on {est[2]} dofs, about "
                f"{duration_text(est[1])} (estimate; full_order.beam_elements sets the dofs)"
            )
    compile_seconds = warm_up(scene, case, which, integrator, modes, motion, pillar_modes)
    start = time.perf_counter()
    res = run_case(scene, case, which, integrator, modes, truncation=False, motion=motion, pillar_modes=pillar_modes)
    wall = time.perf_counter() - start
    bars = None
    if which == "modal":
        res = with_truncation(scene, res, res.run.motion, integrator, pillar_modes, progress)
        if case != "sweep":
            from .uncertainty import uncertainty

            bars = uncertainty(scene, case, integrator, motion, chain, res, progress)
    m, run = res.model, res.run
    data = series(run, scene.simulate.samples)
    ground = data["ground_x"]
    if m.frame == "absolute":
        data["tip_x_absolute"] = data["tip_x"]
        data["tip_x_relative"] = data["tip_x"] - ground
    else:
        data["tip_x_relative"] = data["tip_x"]
    data["shaft_deflection_x"] = data["q"][:, : m.nx] @ m.shaft - m.eccentricity * np.cos(data["theta"])
    ma = dict(res.summary.max_abs)
    full_tip, full_ground = run.tip(), ground_displacement(m, run.motion or no_motion(), run.t)
    if m.frame == "absolute":
        ma["tip_x_absolute"] = ma["tip_x"]
        ma["tip_x_relative"] = float(np.max(np.abs(full_tip - full_ground)))
    else:
        ma["tip_x_relative"] = ma["tip_x"]
        ma["tip_x_absolute"] = float(np.max(np.abs(full_tip + full_ground)))
    ma["shaft_deflection_x"] = ma["shaft_deflection_x_sampled"]
    info = res.model_info
    full_order = None
    if which == "beam":
        assert isinstance(info, BeamModelInfo)  # build_model's for "beam"
        full_order = BeamFullOrder(
            elements=info.elements,
            theory=info.theory,
            duration=res.summary.duration,
            time_step=run.stats.get("time_step"),
            note=(
                f"the 1D {info.theory} beam with every degree of freedom ({info.elements} "
                f"elements, {info.element_source}), the case's full duration; implicit fixed "
                "step that resolves the fastest forcing within 2e-3 (full_order.time_step, 0 = "
                "that; integrator.step_rule): the beam's stiff shear modes are damped by the "
                "scheme, not resolved"
            ),
        )
    record = ReducedRun(
        case=case,
        model=which,
        summary=replace(res.summary, max_abs=ma),
        warnings=tuple(_warnings(case, m, res)),
        pillar_model=reduced_pillar_model(which, chain, info),
        uncertainty=bars,
        dofs=int(m.n),
        wall_seconds=wall,
        compile_seconds=compile_seconds,
        model_description=m.describe(),
        model_info=info,
        resonances=tuple(m.quasi_normal()),
        damped_frequencies=tuple(m.damped_frequencies()),
        tip_x_frame=m.frame,
        max_abs_sampled=("tip_x_relative" if m.frame == "absolute" else "tip_x_absolute", "shaft_deflection_x"),
        initial_speed=res.initial_speed,
        excitation_in_model=res.excitation_in_model,
        full_order=full_order,
    )
    model_run = ModelRun(case, which, record, data, m.quasi_normal(), res)
    from .forces import with_reduced_forces

    return with_reduced_forces(scene, model_run, res, integrator, pillar_modes, motion, progress)


def _warnings(case: str, model, res) -> list[str]:
    """The paper model's earthquake: the published base forcing's amplification;
    any earthquake: a record whose sizes no recorded earthquake has (the commands print
    them on stderr)."""
    out = []
    from ..reduced.excitation_records import RecordSizes

    quake = res.excitation  # the ground motion's sizes, for the earthquake only
    if case == "earthquake" and isinstance(quake, RecordSizes) and not quake.realistic:
        out.append(quake.statement or "the record is not a realistic earthquake")
    if case == "earthquake" and model.name == "paper":
        from ..reduced.base_forcing import published_forcing_warning

        assert isinstance(res.model_info, PaperModelInfo)  # build_model's for "paper"
        c1 = res.model_info.reduction.tip_stiffness
        w = published_forcing_warning(c1, model.shaft_stiffness)
        if w:
            out.append(w)
    return out


# --------------------------------------------------------------------------
# fem3d


def fem3d_warm_up(scene: Scene, mesh) -> float:
    """Compile the 3D forms of ``mesh``'s cell type and degree (FFCx; once per machine, then
    read from its disk cache) on a mesh of a few cells, before the timed run (s)."""
    from dataclasses import replace as dc_replace

    from ..fem3d import assemble_pillar

    tiny = dc_replace(mesh, elements_around=8, elements_along=1, elements_through=1)
    start = time.perf_counter()
    model = assemble_pillar(scene, top=True, mesh=tiny)
    model.K.destroy()
    model.M.destroy()
    return time.perf_counter() - start


def _run_fem3d(
    scene: Scene,
    case,
    motion,
    duration,
    progress,
    chain: ChainModes,
    field_dir=None,
    field_stem: str = "",
    study_dir=None,
) -> ModelRun:
    from ..fem3d.full_order import simulate_fem3d
    from ..reduced.band import forcing_top
    from ..reduced.models import build_model
    from ..reduced.stationary import operating_speed
    from .case_summary import capture_state

    plan = fem3d_plan(scene, case, motion, duration, study_dir)
    mesh = plan.mesh
    steps_hint = f"{mesh.elements_around} x {mesh.elements_along} elements, {plan.duration:g} s"
    top = forcing_top(scene.drive, scene.load, scene.sweep, case, motion)
    ref, _ = build_model(scene, "modal", scene.modal_model.band_factor * top, pillar_modes=chain.modes)
    initial = None
    if case == "earthquake":
        d, L = scene.drive, scene.load
        initial = operating_speed(ref, d.torque_at_zero, d.slope, L.coefficient)
    compile_seconds = fem3d_warm_up(scene, mesh)
    if progress:
        progress(f"3D full order: {case} on {steps_hint}")
    if case == "runup":
        initial = scene.simulate.runup_initial_speed or None
    from .forces import stress_observer, with_fem3d_forces

    observer = stress_observer(scene, plan.duration, field_dir, field_stem)
    try:
        r = simulate_fem3d(
            scene,
            case,
            motion=motion,
            duration=plan.duration,
            time_step=plan.time_step,
            mesh=mesh,
            samples=scene.simulate.samples,
            initial_speed=initial,
            progress=progress,
            observer=observer,
        )
        recovered = observer.finish()
    finally:
        observer.close()
    plan = replace(plan, time_step=r.integrator["time_step"])
    drive_free = _free_speed(scene)
    state = capture_state(ref, r.t, r.Omega, drive_free)
    captured, settled = state.captured_at, state.speed_state != "escaping"
    ma = dict(r.max_abs)
    ma["tip_x_relative"] = ma["tip_x"]
    integ = dict(r.integrator)
    integ.setdefault("wall_seconds", integ.get("integration_seconds"))
    ground = r.ground_x
    data = {
        "t": r.t,
        "Omega": r.Omega,
        "theta": r.theta,
        "tip_x": r.tip_x,
        "tip_x_relative": r.tip_x,
        "tip_x_absolute": r.tip_x_absolute,
        "ground_x": ground,
        "ground_acceleration": r.ground_acceleration,
        "rotor_x": r.rotor_x,
        "rotor_y": r.rotor_y,
        "rotor_x_absolute": r.rotor_x + ground,
        "shaft_deflection_x": r.shaft_x,
        "shaft_deflection_y": r.shaft_y,
        "plate_z": r.plate_z,
        "drive_torque": r.drive_torque,
        "energy": r.energy,
        "work": r.work,
        "peak": np.abs(r.tip_x)[:, None],
    }
    if case == "earthquake":
        r.model["initial_speed_source"] = "the operating speed of the chain's ROM (the fastest stable stationary speed)"
    record = Fem3dRun(
        case=case,
        model="fem3d",
        ok=r.ok,
        duration=float(r.t[-1] - r.t[0]),
        omega_final=r.omega_final,
        omega_final_mean=r.omega_final_mean,
        max_abs=ma,
        energy_balance=r.energy_balance,
        integrator=integ,
        dofs=r.dofs,
        wall_seconds=r.wall_seconds,
        failed_checks=tuple(r.failed_checks) if r.failed_checks else None,
        captured_at=captured,
        captured_resonance=state.captured_resonance,
        captured_index=state.captured_index,
        speed_state=state.speed_state,
        warnings=(),
        captured_at_source="the chain's ROM: its resonances"
        + ("" if settled else "; the run ended before the speed settled, so no capture is claimed"),
        pillar_model=solid_pillar_model(mesh, r.dofs, plan.reference, plan.note),
        compile_seconds=compile_seconds,
        model_description=r.model,
        model_info={"dofs": r.dofs, "mesh": dict(vars(mesh))},
        resonances=tuple(ref.quasi_normal()),
        damped_frequencies=tuple(ref.damped_frequencies()),
        tip_x_frame="relative_to_ground",
        full_order=plan,
        initial_speed=r.model.get("initial_speed"),
        excitation=motion.sizes() if case == "earthquake" else None,
        excitation_in_model=r.model.get("forcing") if case == "earthquake" else None,
    )
    return with_fem3d_forces(
        scene, ModelRun(case, "fem3d", record, data, ref.quasi_normal(), None), recovered, observer.heights
    )


def _free_speed(scene: Scene) -> float:
    from ..reduced.drive import DriveSchedule

    d, L = scene.drive, scene.load
    return DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
