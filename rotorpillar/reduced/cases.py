"""The transient cases of a scene: run-up, run-down, quasi-static sweep, earthquake.

Each case builds the model the scene asks for (rotorpillar.reduced.models:
the paper's equation 4 with the scene's tip reduction, or the modal model
with k pillar modes), the drive schedule and the ground motion, integrates,
and condenses the run into a ``CaseSummary`` (rotorpillar.reduced.summaries)
beside the averaging theory's predictions (rotorpillar.reduced.stationary);
the modal model adds its truncation estimate: the same case with k + 1 modes.

The 3D model's pillar modes (``modal_model.source = "fem3d"``) come in as
``pillar_modes``: the caller computes them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError
from ..scene import CASES
from .drive import DriveSchedule
from .excitation import GroundMotion, no_motion, response_spectrum
from .models import build_model, scene_motion
from .pillar_modes import PillarModes
from .rotor_models import RotorStructure
from .stationary import averaging_prediction, operating_speed, passing_torque
from .summaries import CaseSummary, SweepFindings, run_summary
from .sweep import rate_convergence, sweep_analysis
from .transient import Settings, Transient, simulate


@dataclass(frozen=True)
class CaseResult:
    """One case run on one model: the run, its summary, and what the charts need."""
    case: str
    model: RotorStructure
    run: Transient
    summary: CaseSummary
    extra: dict = field(default_factory=dict)
    """model_info, initial_speed, excitation_in_model, and the sweep's bins and curves"""


#: full-order runs' automatic step: this many steps per period of the fastest forcing
FULL_ORDER_STEPS_PER_PERIOD = 40


def settings_of(scene, integrator: str | None = None) -> Settings:
    """The scene's [simulate] integration settings, ``integrator`` replacing its method."""
    s = scene.simulate
    return Settings(method=integrator or s.integrator, rtol=s.rtol, time_step=s.time_step,
                    samples=s.samples, max_steps=s.max_steps)


def forcing_time_step(scene, fastest: float, motion: GroundMotion) -> float:
    """A full-order run's automatic step (s): FULL_ORDER_STEPS_PER_PERIOD steps per
    period of the fastest of ``fastest`` (the rotor, the ground motion's band) and
    the shaft's Y mode, no coarser than a record's sampling.  The structure's own
    stiff modes (a beam's shear modes, the tube's) are left to the implicit scheme."""
    fast = max(fastest, math.sqrt(scene.shaft.stiffness / scene.rotor.mass), motion.band(), 1e-3)
    h = 2 * math.pi / fast / FULL_ORDER_STEPS_PER_PERIOD
    return min(h, motion.time_step) if motion.kind == "record" else h


def full_order_settings(scene, case: str, motion: GroundMotion, integrator: str | None = None) -> Settings:
    """The beam's settings: [full_order] beam_integrator (or ``integrator``) and
    time_step, else forcing_time_step."""
    fo = scene.full_order
    st = settings_of(scene, integrator or fo.beam_integrator)
    return replace(st, time_step=fo.time_step or forcing_time_step(scene, forcing_top(scene, case, motion),
                                                                   motion))


def forcing_top(scene, case: str, motion: GroundMotion | None) -> float:
    """The highest forcing frequency of a case (rad/s): the fastest rotor speed
    it reaches, and the ground motion's band."""
    d, L = scene.drive, scene.load
    fast = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
    if case == "sweep":
        fast = max(fast, DriveSchedule.constant(scene.sweep.torque_high, d.slope, L.coefficient).free_speed())
    if case == "earthquake" and motion is not None:
        fast = max(fast, motion.band())
    return fast


def run_case(scene, case: str, which: str | None = None, integrator: str | None = None,
             modes: int | None = None, truncation: bool = True, progress=None,
             motion: GroundMotion | None = None, pillar_modes: PillarModes | None = None) -> CaseResult:
    """Run one case of the scene; for the modal model also with k + 1 modes.
    ``motion`` (earthquake) defaults to the scene's [excitation];
    ``pillar_modes``: the modal model's candidate modes (needed when
    ``modal_model.source = "fem3d"``, see ``models.build_model``)."""
    if case not in CASES:
        raise InputError(f"case {case!r}: must be one of {', '.join(CASES)}")
    which = which or scene.simulate.model
    if case != "earthquake":
        motion = no_motion()
    elif motion is None:
        motion = scene_motion(scene)
    top = scene.modal_model.band_factor * forcing_top(scene, case, motion)
    model, info = build_model(scene, which, top, modes, pillar_modes)
    settings = full_order_settings(scene, case, motion, integrator) if which == "beam" else None
    result = _run_on(scene, case, model, motion, integrator, {"model_info": info}, settings)
    if which == "modal" and truncation:
        result = with_truncation(scene, result, motion, integrator, pillar_modes, progress)
    return result


def with_truncation(scene, result: CaseResult, motion: GroundMotion, integrator: str | None = None,
                    pillar_modes: PillarModes | None = None, progress=None) -> CaseResult:
    """A modal model's result with its truncation estimate: the same case with k + 1 modes."""
    model = result.model
    k = model.pillar_modes.count
    if progress:
        progress(f"truncation check: the same case with {k + 1} modes")
    model2, _ = build_model(scene, "modal", modes=k + 1, pillar_modes=pillar_modes)
    if model2.pillar_modes.count == k:
        trunc = {"modes": k, "modes_check": None,
                 "statement": f"no truncation estimate: the mode source ({model.pillar_modes.source}) "
                              f"offers only {k} X bending modes (for fem3d: raise modal.n_modes)"}
    else:
        trunc = truncation_estimate(result, _run_on(scene, result.case, model2, motion, integrator))
    return replace(result, summary=replace(result.summary, truncation=trunc))


def truncation_estimate(a: CaseResult, b: CaseResult) -> dict:
    """How much the (k+1)-th mode changes the answers: the truncation error estimate."""
    ma, mb = a.summary.max_abs, b.summary.max_abs
    tip_b = np.interp(a.run.t, b.run.t, b.run.tip())
    scale = max(np.max(np.abs(tip_b)), 1e-300)
    out = {"modes": a.model.pillar_modes.count, "modes_check": b.model.pillar_modes.count,
           "omega_added": float(b.model.pillar_modes.omega[-1]),
           "effective_mass_fraction": a.model.pillar_modes.effective_mass_fraction(),
           "effective_mass_fraction_check": b.model.pillar_modes.effective_mass_fraction(),
           "omega_final_rel_diff": b.summary.omega_final / a.summary.omega_final - 1
           if a.summary.omega_final else None,
           "tip_series_max_rel_diff": float(np.max(np.abs(a.run.tip() - tip_b)) / scale)}
    for key in ("tip_x", "rotor_x", "rotor_y"):
        out[f"{key}_max_rel_diff"] = mb[key] / ma[key] - 1 if ma[key] > 0 else None
    return out


def _run_on(scene, case: str, model: RotorStructure, motion: GroundMotion,
            integrator: str | None, extra: dict | None = None, settings: Settings | None = None) -> CaseResult:
    d, L, sim = scene.drive, scene.load, scene.simulate
    st = settings or settings_of(scene, integrator)
    M0, s, k = d.torque_at_zero, d.slope, L.coefficient
    pred = averaging_prediction(model, M0, s, k)
    extra = dict(extra or {})
    sections = {}
    if case == "runup":
        drive = DriveSchedule.ramp(M0, s, k, sim.runup_ramp)
        if sim.runup_initial_speed > 0:
            q0, v0 = model.held_whirl_state(sim.runup_initial_speed)
            run = simulate(model, drive, motion, sim.duration, q0, v0, settings=st,
                           speed_scale=sim.runup_initial_speed)
            extra["initial_speed"] = sim.runup_initial_speed
        else:
            run = simulate(model, drive, motion, sim.duration, settings=st)
        free = drive.free_speed()
        if sim.threshold:
            sections["passing_torque"] = passing_torque(model, drive, sim.duration, st.rtol)
    elif case == "rundown":
        Wop = operating_speed(model, M0, s, k)
        q0, v0 = model.steady_initial_state(Wop)
        after = (0.0, 0.0) if sim.rundown_motor == "off" else (sim.rundown_torque_at_zero, s)
        drive = DriveSchedule.switched(M0, s, k, 0.0, *after)
        run = simulate(model, drive, motion, sim.duration, q0, v0, settings=st, speed_scale=Wop)
        free = drive.free_speed() if sim.rundown_motor == "weaker" else 0.0
        extra["initial_speed"] = Wop
        pred = averaging_prediction(model, after[0], after[1], k)
    elif case == "earthquake":
        Wop = operating_speed(model, M0, s, k)
        q0, v0 = model.steady_initial_state(Wop)
        drive = DriveSchedule.constant(M0, s, k)
        t_end = sim.earthquake_duration or motion.end + 5.0
        if t_end <= motion.start:
            raise InputError(f"simulate.earthquake_duration = {t_end:g} s ends before the ground "
                             f"motion starts ({motion.start:g} s)")
        run = simulate(model, drive, motion, t_end, q0, v0, settings=st, speed_scale=Wop)
        free = drive.free_speed()
        extra["initial_speed"] = Wop
        extra["excitation"] = sections["excitation"] = motion.sizes()
        extra["excitation_in_model"] = (
            "Eq. 4 as published: c0 q5 + b0 q5' on q1, c2 q5 + b2 q5' on q2 (absolute coordinates)"
            if model.frame == "absolute" else
            "relative to the ground, forced by -M r a_g (a_g = q5'' inside the window; the "
            "displacement step of the written q5 carries no finite acceleration and is not applied)")
        if motion.kind == "record":
            sections["response_spectrum_check"] = spectrum_check(model, motion, run)
    else:
        w = scene.sweep
        drive = DriveSchedule.sweep(s, k, w.torque_low, w.torque_high, w.rate, w.settle)
        t_end = drive.times[-1]
        run = simulate(model, drive, motion, t_end, settings=replace(st, samples=max(st.samples, 40 * w.bins)),
                       speed_scale=drive.free_speed(drive.times[2]))
        free = drive.free_speed()
        extra.update(sweep_analysis(scene, model, run, drive))
        if extra["numeric_jumps"]:
            extra["rate_convergence"] = rate_convergence(scene, model, st, extra["numeric_jumps"],
                                                         extra["predicted_jumps"])
        sections["jumps"] = extra["numeric_jumps"]
        for key in ("captured_at", "captured_resonance", "captured_index"):
            sections[key] = extra[key]
        sections["sweep"] = SweepFindings(**{key: extra.get(key) for key in (
            "predicted_jumps", "jump_comparison", "largest_speed_step_ratio", "amplitudes",
            "rate_check", "no_jump_reason", "rate_convergence")})
    return CaseResult(case, model, run, run_summary(run, free, pred, **sections), extra)


def spectral_estimate(model: RotorStructure, motion: GroundMotion) -> dict:
    """The response-spectrum estimate of the tip's largest displacement relative to the
    ground: per pillar mode j, Gamma_j S_d(T_j, zeta_j) (zeta_j of the mode's diagonal
    damping), combined by SRSS (the modes are well separated).  Modal model only."""
    pm = model.pillar_modes
    T = 2 * math.pi / np.asarray(pm.omega, dtype=float)
    zeta = [float(model.damping[j, j] / (2 * pm.modal_mass[j] * pm.omega[j])) for j in range(pm.count)]
    rows = []
    for j in range(pm.count):
        sd = float(response_spectrum(motion, [T[j]], damping=zeta[j])["s_d"][0])
        gamma = float(pm.participation[j] / pm.modal_mass[j])
        rows.append({"mode": j + 1, "period": float(T[j]), "damping_ratio": zeta[j],
                     "participation_factor": gamma, "s_d": sd, "contribution": abs(gamma) * sd})
    return {"modes": rows, "srss_tip_estimate": math.sqrt(sum(r["contribution"] ** 2 for r in rows))}


def spectrum_check(model: RotorStructure, motion: GroundMotion, run: Transient) -> dict:
    """The tip's largest relative displacement beside the response-spectrum
    estimate of the first pillar mode alone (modal model: Gamma_1 S_d(T_1), 5 %),
    and of all the modes kept (SRSS, ``spectral_estimate``)."""
    if model.pillar_modes is None:
        return {"note": "needs the modal model"}
    est_all = spectral_estimate(model, motion)
    first = est_all["modes"][0]
    T1, zeta, gamma, sd = first["period"], first["damping_ratio"], first["participation_factor"], first["s_d"]
    est = first["contribution"]
    num = float(np.max(np.abs(run.tip()[run.t >= motion.start])))
    return {"period": T1, "damping_ratio": zeta, "participation_factor": gamma,
            "s_d": sd, "tip_estimate": est, "tip_numeric": num,
            "ratio": num / est if est > 0 else None,
            "srss_tip_estimate": est_all["srss_tip_estimate"], "modes": est_all["modes"],
            "note": "first mode alone, rotor as a separate mass: an estimate, not a bound; "
                    "srss_tip_estimate: every mode kept"}
