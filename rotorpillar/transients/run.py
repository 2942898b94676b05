"""One model of one transient case, run the same way for `simulate` and `compare`.

``run_model(scene, case, model)`` -> ``ModelRun``: the JSON fields every
model reports (``model``, ``case``, ``ok``, ``warnings``, ``max_abs`` with
``tip_x_relative`` and ``tip_x_absolute``, ``omega_final``, ``captured_at``,
``energy_balance``, ``integrator``, ``dofs``, ``wall_seconds``, and for the
full-order models ``full_order``) and the series of the NPZ/CSV (``t``,
``Omega``, ``tip_x_relative``, ``tip_x_absolute``, ``ground_x``,
``ground_acceleration``, ``rotor_x``, ``rotor_y``, ``shaft_deflection_x``
beside the existing columns).

- paper, modal, beam: rotorpillar.reduced.cases.run_case (the beam is the
  full-order 1D beam, integrated by [full_order] beam_integrator at the
  forcing's step);
- fem3d: rotorpillar.fem3d.transient.simulate_fem3d on the mesh and over the
  duration [full_order] states (``fem3d_plan``); its ``captured_at`` and
  resonances come from the modal model on the 1D beam's modes (the 3D run
  has no quasi-normal data of its own; the capture width, 3 % at least, is
  far wider than the beam's frequency error).
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError
from ..scene import MODELS, override


@dataclass(frozen=True, eq=False)
class ModelRun:
    """A model's run of a case: its JSON fields, its series, and what its charts need."""
    case: str
    model: str
    result: dict
    """the JSON fields of simulate_<case>_<model>.json (less files and provenance)"""
    data: dict
    """the series (arrays) of the NPZ/CSV"""
    resonances: list = field(default_factory=list)
    """rotorpillar.reduced.system.Resonance records (charts)"""
    case_result: object = None
    """the reduced models' CaseResult (the run-up's brackets, the sweep's curves), else None"""


def own_duration(scene, case: str, motion=None) -> float:
    """The length of a case's run as the reduced models run it (s)."""
    sim = scene.simulate
    if case == "earthquake":
        from ..reduced.models import scene_motion
        return sim.earthquake_duration or (motion or scene_motion(scene)).end + 5.0
    if case in ("runup", "rundown"):
        return sim.duration
    raise InputError(f"case {case!r}: a common duration is defined for runup, rundown and earthquake")


def with_duration(scene, case: str, duration: float):
    """The scene with the case's run length set to ``duration`` (s)."""
    key = "earthquake_duration" if case == "earthquake" else "duration"
    return override(scene, [f"simulate.{key}={float(duration)!r}"])


def fem3d_plan(scene, case: str, motion=None, duration: float | None = None) -> dict:
    """The 3D run's mesh, duration and step from [full_order], and what was coarsened or
    shortened, and why (the ``full_order`` block of the JSON)."""
    from ..fem3d.transient import CASES_3D
    if case not in CASES_3D:
        raise InputError(f"--model fem3d: case {case!r} is not available; the 3D full order runs "
                         f"{', '.join(CASES_3D)}")
    fo, m = scene.full_order, scene.mesh
    mesh = replace(m, elements_around=fo.elements_around or m.elements_around,
                   elements_along=fo.elements_along or m.elements_along)
    own = own_duration(scene, case, motion)
    stated = fo.earthquake_duration if case == "earthquake" else fo.runup_duration
    length = min(own, stated or own, duration or own)
    notes = []
    if (mesh.elements_around, mesh.elements_along) != (m.elements_around, m.elements_along):
        notes.append(f"mesh coarsened from the scene's {m.elements_around} x {m.elements_along} to "
                     f"{mesh.elements_around} x {mesh.elements_along} elements (around x along; "
                     "full_order.elements_around/along)")
    if length < own:
        notes.append(f"run shortened from the case's {own:g} s to {length:g} s "
                     f"(full_order.{'earthquake' if case == 'earthquake' else 'runup'}_duration)")
    why = ("the 3D run costs its steps (40 per period of the fastest forcing) times one solve; the "
           "scene's [full_order] section keeps it to tens of seconds (its docstring and "
           "docs/transients.md give the measured cost and the agreement with the ROM)")
    return {"mesh": dict(vars(mesh)), "duration": float(length), "case_duration": float(own),
            "time_step": fo.time_step or None,
            "note": ("; ".join(notes) + f": {why}") if notes else "the scene's mesh and duration, unchanged",
            "_mesh": mesh}


def run_model(scene, case: str, model: str, integrator: str | None = None, modes: int | None = None,
              progress=None, motion=None, duration: float | None = None) -> ModelRun:
    """Run ``model`` (one of scene.MODELS) on ``case``; ``duration`` shortens the run
    (compare: one window for every model).  Bad input raises InputError before any work."""
    if model not in MODELS:
        raise InputError(f"model {model!r}: must be one of {', '.join(MODELS)}")
    if case == "earthquake" and motion is None:
        from ..reduced.models import scene_motion
        motion = scene_motion(scene)
    if model == "fem3d":
        return _run_fem3d(scene, case, motion, duration, progress)
    if duration is not None:
        scene = with_duration(scene, case, duration)
    return _run_reduced(scene, case, model, integrator, modes, progress, motion)


# --------------------------------------------------------------------------
# paper, modal, beam


def pillar_modes_for(scene, which: str):
    """The 3D candidate pillar modes when the modal model takes its modes from fem3d, else None."""
    if which != "modal" or scene.modal_model.source != "fem3d":
        return None
    from ..fem3d.pillar_modes import candidate_pillar_modes
    return candidate_pillar_modes(scene)


def _run_reduced(scene, case, which, integrator, modes, progress, motion) -> ModelRun:
    from ..reduced.cases import run_case, with_truncation
    from ..reduced.excitation import no_motion
    from ..reduced.summaries import ground_displacement, series
    pillar_modes = pillar_modes_for(scene, which)
    start = time.perf_counter()
    res = run_case(scene, case, which, integrator, modes, truncation=False, motion=motion,
                   pillar_modes=pillar_modes)
    wall = time.perf_counter() - start
    if which == "modal":
        res = with_truncation(scene, res, res.run.motion, integrator, pillar_modes, progress)
    m, run = res.model, res.run
    data = series(run, scene.simulate.samples)
    summary = res.summary.to_json()
    ground = data["ground_x"]
    if m.frame == "absolute":
        data["tip_x_absolute"] = data["tip_x"]
        data["tip_x_relative"] = data["tip_x"] - ground
    else:
        data["tip_x_relative"] = data["tip_x"]
    data["shaft_deflection_x"] = data["q"][:, :m.nx] @ m.shaft - m.eccentricity * np.cos(data["theta"])
    ma = dict(summary["max_abs"])
    full_tip, full_ground = run.tip(), ground_displacement(m, run.motion or no_motion(), run.t)
    if m.frame == "absolute":
        ma["tip_x_absolute"] = ma["tip_x"]
        ma["tip_x_relative"] = float(np.max(np.abs(full_tip - full_ground)))
    else:
        ma["tip_x_relative"] = ma["tip_x"]
        ma["tip_x_absolute"] = float(np.max(np.abs(full_tip + full_ground)))
    ma["shaft_deflection_x"] = ma["shaft_deflection_x_sampled"]
    summary["max_abs"] = ma
    result = {"case": case, "model": which, **summary, "warnings": _warnings(case, m, res),
              "dofs": int(m.n), "wall_seconds": wall,
              "model_description": m.describe(), "model_info": res.extra.get("model_info"),
              "resonances": [vars(r) for r in m.quasi_normal()],
              "damped_frequencies": m.damped_frequencies(), "tip_x_frame": m.frame,
              "max_abs_sampled": ["tip_x_relative" if m.frame == "absolute" else "tip_x_absolute",
                                  "shaft_deflection_x"]}
    for key in ("initial_speed", "excitation_in_model"):
        if key in res.extra:
            result[key] = res.extra[key]
    if which == "beam":
        info = res.extra["model_info"]
        result["full_order"] = {
            "elements": info["elements"], "theory": info["theory"], "duration": summary["duration"],
            "time_step": run.stats.get("time_step"),
            "note": (f"the 1D {info['theory']} beam with every degree of freedom ({info['elements']} "
                     f"elements, {info['element_source']}), the case's full duration; implicit fixed "
                     "step that resolves the fastest forcing within 2e-3 (full_order.time_step, 0 = "
                     "that; integrator.step_rule): the beam's stiff shear modes are damped by the "
                     "scheme, not resolved")}
    return ModelRun(case, which, result, data, m.quasi_normal(), res)


def _warnings(case: str, model, res) -> list[str]:
    """The paper model's earthquake: the published base forcing's amplification;
    any earthquake: a record whose sizes no recorded earthquake has."""
    out = []
    quake = res.extra.get("excitation") or {}
    if case == "earthquake" and quake.get("kind") == "record" and not quake.get("realistic", True):
        out.append(quake.get("statement", "the record is not a realistic earthquake"))
    if case == "earthquake" and model.name == "paper":
        from ..reduced.base_forcing import published_forcing_warning
        c1 = res.extra["model_info"]["reduction"]["tip_stiffness"]
        w = published_forcing_warning(c1, model.shaft_stiffness)
        if w:
            out.append(w)
    for w in out:
        print(f"[rotorpillar] warning: {w}", file=sys.stderr, flush=True)
    return out


# --------------------------------------------------------------------------
# fem3d


def _run_fem3d(scene, case, motion, duration, progress) -> ModelRun:
    from ..fem3d.transient import simulate_fem3d
    from ..reduced.models import build_model
    from ..reduced.cases import forcing_top
    from ..reduced.summaries import capture_state
    plan = fem3d_plan(scene, case, motion, duration)
    mesh = plan.pop("_mesh")
    steps_hint = f"{mesh.elements_around} x {mesh.elements_along} elements, {plan['duration']:g} s"
    if progress:
        progress(f"3D full order: {case} on {steps_hint}")
    r = simulate_fem3d(scene, case, motion=motion, duration=plan["duration"],
                       time_step=plan["time_step"], mesh=mesh, samples=scene.simulate.samples,
                       progress=progress)
    plan["time_step"] = r.integrator["time_step"]
    beam = override(scene, ["modal_model.source=beam"])
    ref, _ = build_model(beam, "modal", scene.modal_model.band_factor * forcing_top(scene, case, motion))
    drive_free = _free_speed(scene)
    state = capture_state(ref, r.t, r.Omega, drive_free)
    captured, settled = state["captured_at"], state["speed_state"] != "escaping"
    ma = dict(r.max_abs)
    ma["tip_x_relative"] = ma["tip_x"]
    integ = dict(r.integrator)
    integ.setdefault("wall_seconds", integ.get("integration_seconds"))
    ground = r.ground_x
    data = {"t": r.t, "Omega": r.Omega, "theta": r.theta, "tip_x": r.tip_x, "tip_x_relative": r.tip_x,
            "tip_x_absolute": r.tip_x_absolute, "ground_x": ground,
            "ground_acceleration": r.ground_acceleration, "rotor_x": r.rotor_x, "rotor_y": r.rotor_y,
            "rotor_x_absolute": r.rotor_x + ground, "shaft_deflection_x": r.shaft_x,
            "shaft_deflection_y": r.shaft_y, "plate_z": r.plate_z, "drive_torque": r.drive_torque,
            "energy": r.energy, "work": r.work, "peak": np.abs(r.tip_x)[:, None]}
    result = {"case": case, "model": "fem3d", **r.summary(), "max_abs": ma, "integrator": integ,
              "captured_at": captured, "captured_resonance": state["captured_resonance"],
              "speed_state": state["speed_state"], "warnings": [],
              "captured_at_source": "the modal model on the 1D beam's modes: its resonances"
                                    + ("" if settled else "; the run ended before the speed settled, "
                                                          "so no capture is claimed"),
              "model_description": r.model, "model_info": {"dofs": r.dofs, "mesh": plan["mesh"]},
              "resonances": [vars(x) for x in ref.quasi_normal()],
              "damped_frequencies": ref.damped_frequencies(), "tip_x_frame": "relative_to_ground",
              "full_order": plan, "initial_speed": r.model.get("initial_speed")}
    result.pop("model", None)
    result["model"] = "fem3d"
    if case == "earthquake":
        result["excitation"] = motion.sizes()
        result["excitation_in_model"] = r.model.get("forcing")
    return ModelRun(case, "fem3d", result, data, ref.quasi_normal(), None)


def _free_speed(scene) -> float:
    from ..reduced.drive import DriveSchedule
    d, L = scene.drive, scene.load
    return DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
