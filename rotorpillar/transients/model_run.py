"""One model of one transient case, run the same way for `simulate` and `compare`.

``run_model(scene, case, model)`` -> ``ModelRun``: its record (the JSON fields
of ``simulate_<case>_<model>.json``: a ``ReducedRun``, one of ``PaperRun``,
``ModalRun``, ``BeamRun``, the case's ``CaseSummary`` and what the model adds;
or the 3D full order's ``Fem3dRun``; ``RunRecord`` is any of them, told apart
by their ``model``), the fields every model reports (``model``, ``case``, ``ok``, ``warnings``, ``max_abs`` with
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
rotorpillar.chain.PillarModel from rotorpillar.transients.run_plan) and
its costs measured warm: what a run compiles (numba's kernels, FFCx's forms)
is compiled by a short warm-up before the timed run, and its time recorded
apart as ``compile_seconds``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import time
from dataclasses import dataclass, field

import msgspec
import numpy as np

from ..chain import ChainModes
from ..chain.record import PillarModel, Uncertain
from ..errors import InputError
from ..fem3d.full_order_result import Fem3dDescription, Fem3dStats
from ..records import Figure, Record, replace, tag
from ..reduced.models import BeamModelInfo, ModelInfo, PaperModelInfo
from ..reduced.rotor_models import StructureDescription
from ..reduced.spatial_rotor import PlanesChoice
from ..reduced.system import DampedMode, Resonance
from ..scene import MODELS, with_values
from .case_summary import CaseSummary, RunOutcome
from .forces import InternalForcesSummary
from .run_plan import BeamFullOrder, Fem3dPlan, fem3d_plan, reduced_pillar_model, solid_pillar_model, with_duration


class RunFiles(Record):
    """The series written beside a run's JSON (paths)."""

    npz: str
    """every series and the scalars tip_x_frame, model, case"""
    csv: str
    """the plain columns (rotorpillar.transients.files.CSV_COLUMNS)"""


class ModelFiles(Record):
    """The names of a model's own files (``simulate_<case>_<model>.*``), which the generic
    ``simulate_<case>.*`` copy."""

    npz: str
    csv: str
    json: str
    figures: tuple[str, ...]


class ReducedRun(CaseSummary, kw_only=True, omit_defaults=True, tag_field="model"):
    """paper, modal or beam on one case (SI: m, rad/s, s): the case's summary, then the run."""

    case: str
    warnings: tuple[str, ...]
    """what makes the answer doubtful, in words (also on the commands' stderr)"""
    pillar_model: PillarModel
    """the pillar model the run used"""
    uncertainty: dict[str, Uncertain] | None
    """modal: peak_tip_relative (m), peak_shaft_deflection (m), omega_final (rad/s) with
    their error bars; None for the other models"""
    dofs: int
    """unknowns of the model (-)"""
    wall_seconds: float
    """the run's wall time, warm (s)"""
    compile_seconds: float
    """the warm-up's wall time: what the run compiled (s)"""
    model_description: StructureDescription
    """the model's matrices and coordinates (RotorStructure.describe)"""
    model_info: ModelInfo | None
    """how the model was built: the reduction (paper), the modes chosen (modal), the
    elements (beam)"""
    resonances: tuple[Resonance, ...]
    """the model's quasi-normal resonances (Eq. 7)"""
    damped_frequencies: tuple[DampedMode, ...]
    """damped natural frequencies (rad/s) and damping ratios (-) of the linear structure"""
    tip_x_frame: str
    """the frame of ``tip_x``: "absolute" or "relative_to_ground\""""
    max_abs_sampled: tuple[str, ...]
    """the ``max_abs`` keys read from the decimated output, not from every step"""
    initial_speed: float | None = None
    """the speed the run starts at, where the case sets one (rad/s)"""
    excitation_in_model: str | None = None
    """earthquake: how the model applies the ground motion, in words"""
    planes: PlanesChoice | None = None
    """modal: the model that ran, "planar" (the rotor's plane, the tip-scaled ROM) or "spatial"
    (rotorpillar.reduced.spatial_model: both planes, torsion, the motor's reaction on the gondola),
    modal_model.planes as the scene asks it, and why"""
    full_order: BeamFullOrder | None = None
    """beam: its discretisation and step"""
    internal_forces: InternalForcesSummary | None
    """section forces, base reactions, the shaft's demand (None: paper's Eq. 4 has no sections)"""
    files: RunFiles | None = None
    """the series written beside the JSON"""
    figures: tuple[Figure, ...] = ()
    """the run's charts"""
    model_files: ModelFiles | None = None
    """the model's own files"""

    @property
    def model(self) -> str:
        """ "paper", "modal" or "beam\""""
        return tag(self)


class PaperRun(ReducedRun, tag="paper"):
    """The paper's Eq. 4 on one case."""


class ModalRun(ReducedRun, tag="modal"):
    """The ROM (the pillar by its modes) on one case."""


class BeamRun(ReducedRun, tag="beam"):
    """The 1D beam at full order on one case."""


#: the reduced runs' records by model
REDUCED_RUNS: dict[str, type[ReducedRun]] = {"paper": PaperRun, "modal": ModalRun, "beam": BeamRun}


class Fem3dRun(RunOutcome, kw_only=True, omit_defaults=True, tag_field="model", tag="fem3d"):
    """The 3D full order on one case (SI: m, rad/s, s)."""

    case: str
    integrator: Fem3dStats
    """the scheme, its step, steps, solves and wall times"""
    warnings: tuple[str, ...]
    captured_at_source: str
    """where the resonances come from (the chain's ROM), and whether the speed settled"""
    pillar_model: PillarModel
    """the 3D mesh as a pillar model, its source and error the reference's"""
    dofs: int
    """unknowns of the 3D model (-)"""
    wall_seconds: float
    """the run's wall time, warm (s)"""
    compile_seconds: float
    """the warm-up's wall time: FFCx's forms (s)"""
    model_description: Fem3dDescription
    """what was run: mesh, top, damping law, frame, forcing, start (fem3d.full_order)"""
    resonances: tuple[Resonance, ...]
    """the chain's ROM's quasi-normal resonances (Eq. 7)"""
    damped_frequencies: tuple[DampedMode, ...]
    """the ROM's damped natural frequencies (rad/s) and damping ratios (-)"""
    tip_x_frame: str
    """"relative_to_ground\""""
    full_order: Fem3dPlan
    """the mesh, duration and step, and why"""
    initial_speed: float | None
    """the speed the run starts at (rad/s), None: from rest"""
    excitation_in_model: str | None = None
    """earthquake: how the 3D model applies the ground motion, in words"""
    internal_forces: InternalForcesSummary | None
    """section resultants, base reactions, the shaft's demand and the von Mises peaks"""
    files: RunFiles | None = None
    figures: tuple[Figure, ...] = ()
    model_files: ModelFiles | None = None

    @property
    def model(self) -> str:
        return "fem3d"


#: one model's run, as ``ModelRun.record`` holds it (tagged by ``model``)
RunRecord = PaperRun | ModalRun | BeamRun | Fem3dRun


@dataclass(frozen=True, eq=False)
class ModelRun:
    """A model's run of a case: its JSON fields, its series, and what its charts need."""

    case: str
    model: str
    record: ReducedRun | Fem3dRun
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


def spatial_modes_for(which: str, chain: ChainModes | None):
    """The chain's modes in every direction for the modal model (None: the beam's or not modal)."""
    return chain.spatial if which == "modal" and chain is not None else None


def warm_up(scene: Scene, case: str, which: str, integrator, modes, motion, pillar_modes, spatial_modes=None) -> float:
    """Compile what the run will (numba's kernels, per integrator and case) on a run of a
    few milliseconds of the same case; its wall time (s), kept apart from the run's."""
    from .cases import run_case

    key = "simulate.earthquake_duration" if case == "earthquake" else "simulate.duration"
    length = motion.start + 1e-2 if case == "earthquake" else 1e-2  # s: 10 ms of the run
    short = with_values(scene, {"simulate.threshold": False, key: length})
    if case == "sweep":
        return 0.0  # a sweep's schedule has no short form; its kernels are dp5's
    start = time.perf_counter()
    try:
        run_case(
            short,
            case,
            which,
            integrator,
            modes,
            truncation=False,
            motion=motion,
            pillar_modes=pillar_modes,
            spatial_modes=spatial_modes,
        )
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
    spatial_modes = spatial_modes_for(which, chain)
    compile_seconds = warm_up(scene, case, which, integrator, modes, motion, pillar_modes, spatial_modes)
    start = time.perf_counter()
    res = run_case(
        scene,
        case,
        which,
        integrator,
        modes,
        truncation=False,
        motion=motion,
        pillar_modes=pillar_modes,
        spatial_modes=spatial_modes,
    )
    wall = time.perf_counter() - start
    bars = None
    spatial = res.planes is not None and res.planes.planes == "spatial"
    if spatial:
        from .cases import with_spatial_truncation

        res = with_spatial_truncation(scene, res, motion, integrator, spatial_modes, progress)
    elif which == "modal":
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
    ma: dict[str, float | None] = dict(res.summary.max_abs)
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
            time_step=run.stats.time_step,
            note=(
                f"the 1D {info.theory} beam with every degree of freedom ({info.elements} "
                f"elements, {info.element_source}), the case's full duration; implicit fixed "
                "step that resolves the fastest forcing within 2e-3 (full_order.time_step, 0 = "
                "that; integrator.step_rule): the beam's stiff shear modes are damped by the "
                "scheme, not resolved"
            ),
        )
    record = REDUCED_RUNS[which](
        **msgspec.structs.asdict(replace(res.summary, max_abs=ma)),
        case=case,
        warnings=tuple(_warnings(case, m, res) + planar_transient_warnings(scene, case, which, res.planes)),
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
        planes=res.planes,
        full_order=full_order,
        internal_forces=None,  # the forces, below
    )
    model_run = ModelRun(case, which, record, data, m.quasi_normal(), res)
    from .forces import with_reduced_forces

    return with_reduced_forces(scene, model_run, res, integrator, pillar_modes, motion, progress)


def planar_transient_warnings(scene: Scene, case: str, model: str, planes: PlanesChoice | None = None) -> list[str]:
    """What a transient of ``model`` leaves out of what the scene asks (``planes``: the modal
    model's, as rotorpillar.reduced.spatial_scene.transient_planes resolved it).  The spatial ROM
    runs every ground component and the motor's reaction; the planar models (paper, beam, the
    planar ROM) and the 3D full order of simulate apply the record's first component in the
    rotor's plane; a sweep runs the planar ROM whatever modal_model.planes says."""
    out = []
    x = scene.excitation
    spatial = planes is not None and planes.planes == "spatial"
    if case == "earthquake" and x.components > 1 and not spatial:
        out.append(
            f"excitation.components = {x.components}: this run applies the first component alone, "
            f"in the rotor's plane{' (excitation.angle ignored)' if x.angle else ''}; "
            f"`rotorpillar compare --case earthquake --components {x.components}` runs all of them on "
            "the spatial ROM and the 3D full order"
            + ("" if model != "modal" else '; modal_model.planes = "spatial" (or "auto") runs them on the spatial ROM')
        )
    if model == "modal" and scene.modal_model.planes == "spatial" and not spatial:
        out.append(
            f'modal_model.planes = "spatial": the {case} runs the planar ROM (the rotor\'s plane): '
            + (planes.reason if planes is not None else "its analysis is the planar averaging's")
        )
    if spatial:
        out.append(
            "the spatial ROM's run: no error bars (uncertainty) and no section forces along the pillar "
            'yet (the planar ROM\'s have them: modal_model.planes = "planar"); compare --case earthquake '
            "--components gives the spatial base reactions"
        )
    return out


def _warnings(case: str, model, res) -> list[str]:
    """The paper model's earthquake: the published base forcing's amplification;
    any earthquake: a record whose sizes no recorded earthquake has (the commands print
    them on stderr)."""
    out = []
    from ..reduced.excitation import RecordSizes

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
    spatial = _like_the_rom(scene, case, scene.modal_model.band_factor * top, ref, chain)
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
    fem3d_motion = motion
    if spatial and case == "earthquake":
        from .cases import spatial_motion

        fem3d_motion = spatial_motion(scene, case, motion)  # every component, as the spatial ROM's
    try:
        r = simulate_fem3d(
            scene,
            case,
            motion=fem3d_motion,
            duration=plan.duration,
            time_step=plan.time_step,
            mesh=mesh,
            samples=scene.simulate.samples,
            initial_speed=initial,
            progress=progress,
            observer=observer,
            # like against like: where the ROM's transient runs on the spatial model, the 3D run
            # takes its b2 on the motion relative to the gondola, its structural ratio and the
            # motor's reaction on the top (nrel5mw's run-up set a ROM with the reaction against
            # a 3D run without it: a 4780 % history error that was the model's, not the ROM's)
            damping_law="gondola" if spatial else "ground",
            damping_ratio=scene.pillar.damping_ratio if spatial else 0.0,
            drive_reaction=spatial,
        )
        recovered = observer.finish()
    finally:
        observer.close()
    plan = replace(plan, time_step=r.integrator.time_step)
    drive_free = _free_speed(scene)
    state = capture_state(ref, r.t, r.Omega, drive_free)
    captured, settled = state.captured_at, state.speed_state != "escaping"
    ma: dict[str, float | None] = dict(r.max_abs)
    ma["tip_x_relative"] = ma["tip_x"]
    integ = r.integrator
    if not integ.wall_seconds:  # the step loop times its integration apart
        integ = replace(integ, wall_seconds=integ.integration_seconds)
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
    description = r.model
    if case == "earthquake":
        description = replace(
            description,
            initial_speed_source="the operating speed of the chain's ROM (the fastest stable stationary speed)",
        )
    record = Fem3dRun(
        case=case,
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
        warnings=() if spatial else tuple(planar_transient_warnings(scene, case, "fem3d")),
        captured_at_source="the chain's ROM: its resonances"
        + ("" if settled else "; the run ended before the speed settled, so no capture is claimed"),
        pillar_model=solid_pillar_model(mesh, r.dofs, plan.reference, plan.note),
        compile_seconds=compile_seconds,
        model_description=description,
        resonances=tuple(ref.quasi_normal()),
        damped_frequencies=tuple(ref.damped_frequencies()),
        tip_x_frame="relative_to_ground",
        full_order=plan,
        initial_speed=description.initial_speed,
        excitation=motion.sizes() if case == "earthquake" else None,
        excitation_in_model=description.forcing if case == "earthquake" else None,
        internal_forces=None,  # the forces, below
    )
    return with_fem3d_forces(
        scene,
        ModelRun(case, "fem3d", record, data, ref.quasi_normal(), None),
        recovered,
        observer.heights,
        observer.base_motion,
    )


def _like_the_rom(scene: Scene, case: str, band_top: float, planar, chain: ChainModes) -> bool:
    """Whether the modal model's transient of ``case`` runs on the spatial ROM
    (rotorpillar.reduced.spatial_scene.transient_model on the chain's modes, as run_case
    resolves it): the 3D run then carries what the spatial ROM does."""
    from ..reduced.spatial_scene import transient_model

    return transient_model(scene, case, band_top, planar, chain.spatial)[0].planes == "spatial"


def _free_speed(scene: Scene) -> float:
    from ..reduced.drive import DriveSchedule

    d, L = scene.drive, scene.load
    return DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
