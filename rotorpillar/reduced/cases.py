"""The transient cases of a scene: run-up, run-down, quasi-static sweep, earthquake.

Each case builds the model the scene asks for (the paper's Eq. 4 with the
scene's tip reduction, or the modal model with k pillar modes), the drive
schedule and the ground motion, integrates, and condenses the run into a
JSON-ready summary beside the averaging theory's predictions:

- ``omega_final``, ``max_abs`` per coordinate (from every step, not the
  decimated output), ``jumps`` [{direction, omega_from, omega_to, ...}],
  ``captured_at`` (the resonance's omega, or None), the energy balance and
  the integrator's statistics;
- the modal model's truncation estimate: the same case with k + 1 modes.

Capture: a run settles at a resonance when its final speed lies inside
that resonance's peak (|Omega - omega_i| <= max(3 n_i, 0.03 omega_i)) while
the motor alone, without any resonance, would settle more than 2 % away
(Md = Mc).  Jumps of a quasi-static sweep: between consecutive M0 bins the
speed moves more than ``JUMP_FACTOR`` times what the motor and load alone
would allow, dM0 / (s + 2 k Omega); consecutive flagged bins make one jump.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import brentq

from ..errors import InputError
from ..scene import CASES
from . import averaging as av
from .drive import DriveSchedule
from .excitation import GroundMotion, load_record, no_motion, paper_pulse, response_spectrum
from .pillar_modes import PillarModes, beam_pillar_modes, modes_in_band
from .rotor_models import RotorStructure, modal_model, paper_model
from .reduction import pillar_closed_forms, resolve_reduction
from .system import reduced_system
from .transient import Settings, Transient, simulate, simulate_batch

JUMP_FACTOR = 5.0
CAPTURE_WIDTH = 3.0          # in n_i = nu_i omega_i
CAPTURE_MIN_WIDTH = 0.03     # relative
MAX_CANDIDATE_MODES = 12


# --------------------------------------------------------------------------
# Models of a scene


def paper_system(scene):
    """The paper's ReducedSystem with the scene's tip reduction (stated or Eq. 2)."""
    red = resolve_reduction(scene, pillar_closed_forms(scene))
    return reduced_system(scene, red["tip_mass"], red["tip_stiffness"]), red


def scene_pillar_modes(scene, count: int) -> PillarModes:
    """The first ``count`` pillar modes from the scene's [modal_model] source."""
    m = scene.modal_model
    if m.source == "beam":
        return beam_pillar_modes(scene, count, m.theory, m.elements, m.gondola_inertia)
    import importlib.util
    if importlib.util.find_spec("dolfinx") is None:
        raise InputError('modal_model.source = "fem3d" needs the 3D model (dolfinx), which is not '
                         'installed here; use modal_model.source = "beam"')
    from .fem3d_modes import fem3d_pillar_modes
    return fem3d_pillar_modes(scene, count)


def _fem3d_bending_count(scene) -> int:
    """How many X bending modes the scene's 3D analysis will find (at most 12)."""
    from ..fem3d import modal_analysis
    n = sum(1 for k in modal_analysis(scene, top=True).kind if k == "bending_x")
    return max(1, min(n, MAX_CANDIDATE_MODES))


def build_model(scene, which: str, band_top: float | None = None, modes: int | None = None):
    """(model, info) for "paper" or "modal"; the modal model keeps ``modes``
    modes, or those below ``band_top`` (rad/s)."""
    if which == "paper":
        s, red = paper_system(scene)
        return paper_model(s), {"reduction": red}
    if which != "modal":
        raise InputError(f"model {which!r}: must be paper or modal")
    candidates = scene_pillar_modes(scene, MAX_CANDIDATE_MODES if scene.modal_model.source == "beam"
                                    else _fem3d_bending_count(scene))
    k = modes or scene.modal_model.modes or modes_in_band(candidates.omega, band_top or 0.0)
    k = min(k, candidates.count)
    pm = candidates.truncate(k)
    r, sh = scene.rotor, scene.shaft
    model = modal_model(pm, r.mass, r.inertia, r.eccentricity, sh.stiffness, sh.damping,
                        scene.pillar.damping)
    info = {"modes": k, "band_top": band_top, "candidate_omega": list(map(float, candidates.omega)),
            "mode_choice": ("stated (modal_model.modes)" if (modes or scene.modal_model.modes) else
                            f"the pillar modes below {band_top:.4g} rad/s = band_factor x the highest "
                            "forcing frequency")}
    return model, info


def scene_motion(scene) -> GroundMotion:
    x = scene.excitation
    if x.kind == "paper":
        return paper_pulse(x.amplitude, x.frequency, x.start, x.duration)
    return load_record(x.record, x.record_units, x.record_scale, x.start)


# --------------------------------------------------------------------------
# Stationary speeds


def stationary_exact(model: RotorStructure, M0: float, slope: float, load: float,
                     top: float | None = None, n: int = 3000) -> list[dict]:
    """Stationary speeds of the exact linear torque balance
    M0 - s W - k W**2 + <shaft torque>(W) = 0 and their stability."""
    free = DriveSchedule.constant(M0, slope, load).free_speed()
    res = model.quasi_normal()
    top = top or 1.2 * max(free, max(r.omega for r in res))
    grid = av.speed_grid(res, top, n)
    g = lambda W: M0 - slope * W - load * W * abs(W) + float(model.steady_torque(W))
    vals = np.array([g(w) for w in grid])
    out = []
    for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
        w = brentq(g, grid[i], grid[i + 1], xtol=1e-12 * grid[i + 1])
        h = 1e-6 * w
        out.append({"omega": w, "stable": bool(g(w + h) - g(w - h) < 0)})
    return out


def operating_speed(model: RotorStructure, M0: float, slope: float, load: float) -> float:
    """The fastest stationary speed: where the machine runs in service (rad/s)."""
    st = stationary_exact(model, M0, slope, load)
    stable = [s["omega"] for s in st if s["stable"]]
    if not stable:
        raise InputError(f"no stable stationary speed for M0 = {M0:g} N*m: the motor cannot "
                         "drive this machine")
    return max(stable)


def averaging_prediction(model: RotorStructure, M0: float, slope: float, load: float) -> dict:
    """What Eq. 19-23 predict for this drive on this model's quasi-normal modes."""
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(M0, slope, load), res)
    return {"stationary": [vars(s) for s in d.stationary], "jumps": [vars(j) for j in d.jumps],
            "runup_speed": d.runup_speed, "rundown_speed": d.rundown_speed,
            "captured_at": None if d.captured_at is None else
            next(r.omega for r in res if r.index == d.captured_at),
            "resonances": [{"index": r.index, "direction": r.direction, "omega": r.omega, "nu": r.nu,
                            "a_max": float(av.amplitude(r.omega, r)),
                            "dL_max": float(av.resistance_increment(r.omega, r))} for r in res]}


# --------------------------------------------------------------------------
# Reading a run


def capture(model: RotorStructure, omega_final: float, drive_free_speed: float) -> float | None:
    """omega_i of the resonance the run settled at, or None."""
    if not math.isfinite(drive_free_speed) or abs(drive_free_speed - omega_final) <= 0.02 * drive_free_speed:
        return None
    best = None
    for r in model.quasi_normal():
        width = max(CAPTURE_WIDTH * r.n, CAPTURE_MIN_WIDTH * r.omega)
        if abs(omega_final - r.omega) <= width and (best is None or
                                                     abs(omega_final - r.omega) < abs(omega_final - best)):
            best = r.omega
    return best


def passages(run: Transient) -> list[dict]:
    """When the speed first crosses each resonance, and the largest tip
    amplitude within +-10 % of it."""
    out = []
    W = run.Omega
    tip_peak = run.peak[:, -1]
    for r in run.model.quasi_normal():
        idx = np.nonzero((W[:-1] - r.omega) * (W[1:] - r.omega) <= 0)[0]
        near = np.abs(W - r.omega) <= 0.1 * r.omega
        entry = {"index": r.index, "direction": r.direction, "omega": r.omega,
                 "crossed": bool(idx.size), "time": float(run.t[idx[0]]) if idx.size else None,
                 "peak_tip_near": float(tip_peak[near].max()) if near.any() else None,
                 "peak_rotor_y_near": float(run.peak[near, run.model.nx].max()) if near.any() else None}
        out.append(entry)
    return out


def max_abs(run: Transient) -> dict:
    """Largest |value| over the run, from the integrator's per-step peaks (m)."""
    m = run.model
    pk = np.nanmax(run.peak, axis=0)
    out = {"tip_x": float(pk[-1]), "rotor_x": float(pk[m.rotor_x]), "rotor_y": float(pk[m.nx])}
    for i, name in enumerate(m.coordinates):
        out[name] = float(pk[i])
    shaft = run.q[:, :m.nx] @ m.shaft - m.eccentricity * np.cos(run.q[:, -1])
    out["shaft_deflection_x_sampled"] = float(np.nanmax(np.abs(shaft)))
    return out


def ground_displacement(model: RotorStructure, motion: GroundMotion, t) -> np.ndarray:
    """The ground displacement each model applies: q5 as written (paper), the
    double integral of the applied acceleration (modal)."""
    if model.frame == "absolute":
        return motion.evaluate(t)[0]
    return motion.inertial_displacement(t)


def decimate(run: Transient, max_samples: int) -> Transient:
    """Every k-th output so that at most ``max_samples`` remain (the last kept);
    the interval peaks are merged, so no peak is lost."""
    n = len(run.t)
    if n <= max_samples:
        return run
    k = int(math.ceil((n - 1) / (max_samples - 1)))
    idx = np.arange(0, n, k)
    if idx[-1] != n - 1:
        idx = np.r_[idx, n - 1]
    starts = np.r_[0, idx[:-1] + 1]
    peak = np.maximum.reduceat(run.peak, starts, axis=0)
    peak[0] = run.peak[0]
    return replace(run, t=run.t[idx], q=run.q[idx], v=run.v[idx], work=run.work[idx], peak=peak)


def series(run: Transient, max_samples: int | None = None) -> dict:
    """The arrays written to the NPZ/CSV (contract with the animations)."""
    if max_samples:
        run = decimate(run, max_samples)
    m = run.model
    motion = run.motion or no_motion()
    ground = ground_displacement(m, motion, run.t)
    tip = run.tip()
    out = {"t": run.t, "Omega": run.Omega, "theta": run.q[:, -1], "tip_x": tip,
           "rotor_x": run.q[:, m.rotor_x], "rotor_y": run.q[:, m.nx], "ground_x": ground,
           "ground_acceleration": motion.evaluate(run.t)[2],
           "q": run.q, "v": run.v, "peak": run.peak, "work": run.work}
    if run.drive is not None:
        out["M0"] = run.drive.at(run.t)[0]
        out["drive_torque"] = run.drive.torque(run.t, run.Omega)
    T, P = m.energy(run.q, run.v)
    out["energy"] = T + P
    if m.frame == "relative_to_ground":
        out["tip_x_absolute"] = tip + ground
        out["rotor_x_absolute"] = out["rotor_x"] + ground
        out["modal_coordinates"] = run.q[:, :m.pillar_modes.count]
        if m.pillar_modes.shapes is not None:
            out["mode_heights"] = m.pillar_modes.heights
            out["mode_shapes"] = m.pillar_modes.shapes
            out["mode_omega"] = np.asarray(m.pillar_modes.omega)
    return out


def run_summary(run: Transient, drive_free_speed: float) -> dict:
    tail = run.t >= run.t[-1] - max(0.05 * (run.t[-1] - run.t[0]), 1e-9)
    om_final = float(run.Omega[-1])
    om_mean = float(np.mean(run.Omega[tail]))
    return {
        "ok": run.ok,
        "duration": float(run.t[-1] - run.t[0]),
        "omega_final": om_final,
        "omega_final_mean": om_mean,
        "max_abs": max_abs(run),
        "captured_at": capture(run.model, om_mean, drive_free_speed),
        "passages": passages(run),
        "energy_balance": run.energy_balance(),
        "integrator": dict(run.stats),
    }


# --------------------------------------------------------------------------
# Sweep


def sweep_bins(run: Transient, drive: DriveSchedule, phase: tuple[float, float], bins: int,
               direction: str) -> dict:
    """Stationary speed and amplitudes per M0 bin over one ramp of a sweep."""
    m = run.model
    t0, t1 = phase
    sel = (run.t >= t0) & (run.t <= t1)
    M0 = drive.at(run.t[sel])[0]
    lo, hi = float(min(M0.min(), M0.max())), float(max(M0.min(), M0.max()))
    edges = np.linspace(lo, hi, bins + 1)
    idx = np.clip(np.digitize(M0, edges) - 1, 0, bins - 1)
    W = run.Omega[sel]
    tt = run.t[sel]
    tip, ry, rx = run.peak[sel, -1], run.peak[sel, m.nx], run.peak[sel, m.rotor_x]
    cols = {k: np.full(bins, np.nan) for k in ("M0", "omega", "tip_x", "rotor_y", "rotor_x",
                                                "M0_inertia_corrected")}
    for b in range(bins):
        s = idx == b
        if not s.any():
            continue
        cols["M0"][b] = 0.5 * (edges[b] + edges[b + 1])
        cols["omega"][b] = W[s].mean()
        # the rotor's inertia: M0 - J dOmega/dt is what the stationary balance sees
        acc = np.polyfit(tt[s], W[s], 1)[0] if s.sum() > 2 else 0.0
        cols["M0_inertia_corrected"][b] = cols["M0"][b] - m.rotor_inertia * acc
        cols["tip_x"][b], cols["rotor_y"][b], cols["rotor_x"][b] = tip[s].max(), ry[s].max(), rx[s].max()
    keep = np.isfinite(cols["M0"])
    cols = {k: v[keep] for k, v in cols.items()}
    if direction == "down":
        cols = {k: v[::-1] for k, v in cols.items()}
    cols["direction"] = direction
    return cols


def detect_jumps(cols: dict, slope: float, load: float) -> tuple[list[dict], float]:
    """Jumps along one ramp's bins; also the largest speed step over what the
    motor and load alone allow (1 on a smooth curve).  Marks the bins inside
    a jump in cols["in_jump"] (not stationary: left out of the amplitude
    comparison)."""
    M0, W = cols["M0"], cols["omega"]
    sign = 1.0 if cols["direction"] == "up" else -1.0
    dM = np.abs(np.diff(M0))
    dW = sign * np.diff(W)
    expected = dM / (slope + 2 * load * np.abs(W[:-1]))
    ratio = dW / np.maximum(expected, 1e-300)
    flagged = ratio > JUMP_FACTOR
    in_jump = np.zeros(len(W), dtype=bool)
    in_jump[:-1] |= flagged
    in_jump[1:] |= flagged
    cols["in_jump"] = in_jump
    jumps = []
    i = 0
    while i < len(flagged):
        if not flagged[i]:
            i += 1
            continue
        j = i
        while j + 1 < len(flagged) and flagged[j + 1]:
            j += 1
        w_from, w_to = float(W[i]), float(W[j + 1])
        if abs(w_to - w_from) > 0.01 * abs(w_from):
            jumps.append({"direction": cols["direction"], "omega_from": w_from, "omega_to": w_to,
                          "torque_at_zero": float(0.5 * (M0[i] + M0[i + 1])),
                          "bins": int(j - i + 1)})
        i = j + 1
    return jumps, float(np.max(ratio)) if len(ratio) else 0.0


def compare_amplitudes(model: RotorStructure, cols: dict) -> list[dict]:
    """Numeric stationary amplitudes of the sweep against Eq. 19 and the exact
    linear steady state, near each resonance the sweep crosses."""
    out = []
    W = cols["omega"]
    res = model.quasi_normal()
    for r in res:
        key = "tip_x" if r.direction == "X" else "rotor_y"
        # where resonance i dominates: within 2 n_i, and nearer to omega_i than
        # to any other resonance of the same direction; stationary bins only
        gap = min((abs(q.omega - r.omega) for q in res if q.direction == r.direction and q is not r),
                  default=math.inf)
        near = (np.abs(W - r.omega) <= min(2 * r.n, 0.5 * gap)) & ~cols.get("in_jump", np.zeros(len(W), bool))
        if near.sum() < 2:
            continue
        num = cols[key][near]
        eq19 = av.amplitude(W[near], r)
        exact = model.steady_amplitudes(W[near])[key]
        k = int(np.argmax(num))
        out.append({"index": r.index, "direction": r.direction, "omega": r.omega, "coordinate": key,
                    "sweep": cols["direction"], "bins": int(near.sum()),
                    "numeric_peak": float(num[k]), "omega_at_numeric_peak": float(W[near][k]),
                    "eq19_at_that_speed": float(eq19[k]), "exact_at_that_speed": float(exact[k]),
                    "eq19_a_max": float(av.amplitude(r.omega, r)),
                    "rel_error_eq19": float(np.max(np.abs(eq19 / num - 1))),
                    "rel_error_exact": float(np.max(np.abs(exact / num - 1))),
                    "rel_error_eq19_median": float(np.median(np.abs(eq19 / num - 1))),
                    "rel_error_exact_median": float(np.median(np.abs(exact / num - 1))),
                    "rel_error_eq19_at_peak": float(eq19[k] / num[k] - 1),
                    "rel_error_exact_at_peak": float(exact[k] / num[k] - 1)})
    return out


def match_jumps(numeric: list[dict], predicted: list[dict]) -> list[dict]:
    """Each predicted jump beside the nearest numeric one of the same direction."""
    rows = []
    for p in predicted:
        cands = [j for j in numeric if j["direction"] == p["direction"]]
        if not cands:
            rows.append({"predicted": p, "numeric": None})
            continue
        j = min(cands, key=lambda j: abs(j["omega_from"] - p["omega_from"]))
        rows.append({"predicted": p, "numeric": j,
                     "rel_error_omega_from": j["omega_from"] / p["omega_from"] - 1,
                     "rel_error_omega_to": j["omega_to"] / p["omega_to"] - 1,
                     "rel_error_torque": j["torque_at_zero"] / p["torque_at_zero"] - 1})
    return rows


# --------------------------------------------------------------------------
# Cases


@dataclass
class CaseResult:
    case: str
    model: RotorStructure
    run: Transient
    summary: dict
    extra: dict = field(default_factory=dict)


def settings_of(scene, integrator: str | None = None) -> Settings:
    s = scene.simulate
    return Settings(method=integrator or s.integrator, rtol=s.rtol, time_step=s.time_step,
                    samples=s.samples)


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
             motion: GroundMotion | None = None) -> CaseResult:
    """Run one case of the scene; for the modal model also with k + 1 modes.
    ``motion`` (earthquake) defaults to the scene's [excitation]."""
    if case not in CASES:
        raise InputError(f"case {case!r}: must be one of {', '.join(CASES)}")
    which = which or scene.simulate.model
    if case != "earthquake":
        motion = no_motion()
    elif motion is None:
        motion = scene_motion(scene)
    top = scene.modal_model.band_factor * forcing_top(scene, case, motion)
    model, info = build_model(scene, which, top, modes)
    result = _run_on(scene, case, model, motion, integrator)
    result.extra["model_info"] = info
    if which == "modal" and truncation:
        k = model.pillar_modes.count
        if progress:
            progress(f"truncation check: the same case with {k + 1} modes")
        model2, _ = build_model(scene, "modal", modes=k + 1)
        if model2.pillar_modes.count == k:
            result.summary["truncation"] = {
                "modes": k, "modes_check": None,
                "statement": f"no truncation estimate: the mode source ({model.pillar_modes.source}) "
                             f"offers only {k} X bending modes (for fem3d: raise modal.n_modes)"}
        else:
            r2 = _run_on(scene, case, model2, motion, integrator)
            result.summary["truncation"] = truncation_estimate(result, r2)
    return result


def truncation_estimate(a: CaseResult, b: CaseResult) -> dict:
    """How much the (k+1)-th mode changes the answers: the truncation error estimate."""
    ma, mb = a.summary["max_abs"], b.summary["max_abs"]
    tip_b = np.interp(a.run.t, b.run.t, b.run.tip())
    scale = max(np.max(np.abs(tip_b)), 1e-300)
    out = {"modes": a.model.pillar_modes.count, "modes_check": b.model.pillar_modes.count,
           "omega_added": float(b.model.pillar_modes.omega[-1]),
           "effective_mass_fraction": a.model.pillar_modes.effective_mass_fraction(),
           "effective_mass_fraction_check": b.model.pillar_modes.effective_mass_fraction(),
           "omega_final_rel_diff": b.summary["omega_final"] / a.summary["omega_final"] - 1
           if a.summary["omega_final"] else None,
           "tip_series_max_rel_diff": float(np.max(np.abs(a.run.tip() - tip_b)) / scale)}
    for key in ("tip_x", "rotor_x", "rotor_y"):
        out[f"{key}_max_rel_diff"] = mb[key] / ma[key] - 1 if ma[key] > 0 else None
    return out


def _run_on(scene, case: str, model: RotorStructure, motion: GroundMotion,
            integrator: str | None) -> CaseResult:
    d, L, sim = scene.drive, scene.load, scene.simulate
    st = settings_of(scene, integrator)
    M0, s, k = d.torque_at_zero, d.slope, L.coefficient
    pred = averaging_prediction(model, M0, s, k)
    extra = {}
    if case == "runup":
        drive = DriveSchedule.ramp(M0, s, k, sim.runup_ramp)
        run = simulate(model, drive, motion, sim.duration, settings=st)
        free = drive.free_speed()
        extra["passing_torque"] = passing_torque(model, drive, sim.duration, st.rtol)
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
        extra["excitation"] = motion.sizes()
        extra["excitation_in_model"] = (
            "Eq. 4 as published: c0 q5 + b0 q5' on q1, c2 q5 + b2 q5' on q2 (absolute coordinates)"
            if model.frame == "absolute" else
            "relative to the ground, forced by -M r a_g (a_g = q5'' inside the window; the "
            "displacement step of the written q5 carries no finite acceleration and is not applied)")
    else:
        w = scene.sweep
        drive = DriveSchedule.sweep(s, k, w.torque_low, w.torque_high, w.rate, w.settle)
        t_end = drive.times[-1]
        run = simulate(model, drive, motion, t_end, settings=replace(st, samples=max(st.samples, 40 * w.bins)),
                       speed_scale=drive.free_speed(drive.times[2]))
        free = drive.free_speed()
        extra.update(_sweep_analysis(scene, model, run, drive))
        if extra["numeric_jumps"]:
            extra["rate_convergence"] = rate_convergence(scene, model, st, extra["numeric_jumps"],
                                                         extra["predicted_jumps"])
    summary = run_summary(run, free)
    summary["prediction"] = pred
    if case == "sweep":
        summary["jumps"] = extra["numeric_jumps"]
        summary["captured_at"] = extra["captured_at"]
    else:
        summary["jumps"] = []
    if case == "runup":
        summary["passing_torque"] = extra["passing_torque"]
    if case == "sweep":
        for key in ("predicted_jumps", "jump_comparison", "largest_speed_step_ratio", "amplitudes",
                    "rate_check", "no_jump_reason", "rate_convergence"):
            summary[key] = extra.get(key)
    if case == "earthquake":
        summary["excitation"] = extra["excitation"]
        if motion.kind == "record":
            summary["response_spectrum_check"] = spectrum_check(model, motion, run)
    return CaseResult(case, model, run, summary, extra)


def exact_folds(model: RotorStructure, slope: float, load: float, top: float) -> list[dict]:
    """Local maxima (A, run-up) and minima (D, run-down) of the exact linear
    F(W) = k W**2 + s W - <shaft torque>(W): the torques where quasi-static
    runs jump."""
    W = av.speed_grid(model.quasi_normal(), top, 4000)
    F = load * W**2 + slope * W - model.steady_torque(W)
    dF = np.diff(F)
    out = []
    for i in np.nonzero(np.sign(dF[:-1]) != np.sign(dF[1:]))[0]:
        out.append({"kind": "A" if dF[i] > 0 else "D", "omega": float(W[i + 1]),
                    "torque_at_zero": float(F[i + 1])})
    return out


def passing_torque(model: RotorStructure, drive: DriveSchedule, duration: float, rtol: float,
                   span: float = 0.2, points: int = 41) -> dict:
    """The motor torque M0 needed to run up through the first resonance that
    can capture the rotor: predicted (the A fold of Eq. 19-23, and of the
    exact linear torque) and simulated (run-ups from rest for M0 around the
    prediction, refined once: the smallest M0 that passes within ``duration``)."""
    s, k = drive.slope[-1], drive.load_coefficient
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(max(drive.torque_at_zero), s, k), res)
    ups = sorted((j for j in d.jumps if j.direction == "up"), key=lambda j: j.torque_at_zero)
    if not ups:
        return {"predicted": None,
                "statement": "The analysis finds no fold for this motor slope and load: a run-up "
                             "passes every resonance with any torque that reaches it; nothing to test."}
    j = ups[0]
    r = next(r for r in res if r.index == j.resonance)
    exact = [f for f in exact_folds(model, s, k, 1.5 * j.omega_to) if f["kind"] == "A"
             and abs(f["omega"] - j.omega_from) < 0.2 * j.omega_from]
    M_pred = j.torque_at_zero
    threshold = 0.5 * (j.omega_from + j.omega_to)
    M_scene = float(max(drive.torque_at_zero))

    def runs(M):
        b = simulate_batch(model, drive, duration, torque_scale=np.asarray(M) / M_scene, rtol=rtol,
                           samples=401)
        final = b.Omega[:, -20:].mean(axis=1)
        return b, final, final > threshold

    grid = M_pred * np.linspace(1 - span, 1 + span, points)
    b1, final1, passed1 = runs(grid)
    wall = b1.wall_seconds
    out = {"resonance": {"index": r.index, "direction": r.direction, "omega": r.omega, "nu": r.nu},
           "predicted": M_pred, "predicted_jump": vars(j),
           "predicted_exact_linear": exact[0]["torque_at_zero"] if exact else None,
           "duration": duration, "pass_threshold_speed": threshold,
           "grid": grid, "grid_final_speed": final1, "grid_passed": passed1}
    if passed1.all() or not passed1.any():
        out["simulated"] = None
        out["statement"] = ("every run " + ("passed" if passed1.all() else "was captured") +
                            f" for M0 within +-{100 * span:g} % of the prediction")
    else:
        i = int(np.argmax(passed1))
        if not passed1[i:].all():
            out["non_monotonic"] = True
        fine = np.linspace(grid[i - 1], grid[i], 21)
        b2, final2, passed2 = runs(fine)
        wall += b2.wall_seconds
        i2 = int(np.argmax(passed2)) if passed2.any() else len(fine) - 1
        lo, hi = fine[max(i2 - 1, 0)], fine[i2]
        out.update({"simulated": 0.5 * (lo + hi), "simulated_bracket": [lo, hi],
                    "rel_error_predicted": M_pred / (0.5 * (lo + hi)) - 1,
                    "rel_error_exact_linear": (exact[0]["torque_at_zero"] / (0.5 * (lo + hi)) - 1)
                    if exact else None})
        out["statement"] = (f"Run-up through resonance {r.index} ({r.omega:.2f} rad/s): the analysis "
                            f"(Eq. 19-23) says M0 >= {M_pred:.1f} N*m passes; simulated run-ups "
                            f"from rest over {duration:g} s pass from {0.5 * (lo + hi):.1f} N*m "
                            f"({100 * out['rel_error_predicted']:+.1f} %).")
    # two runs just below and above the prediction, for the charts
    below, above = 0.95 * M_pred, 1.05 * M_pred
    b3, final3, passed3 = runs([below, above])
    wall += b3.wall_seconds
    out["bracket_runs"] = [{"torque_at_zero": float(M), "final_speed": float(f), "passed": bool(p)}
                           for M, f, p in zip((below, above), final3, passed3)]
    out["bracket_series"] = {"t": b3.t, "Omega": b3.Omega, "tip_peak": b3.tip_peak}
    out["runs"] = int(len(grid) + (21 if out.get("simulated") else 0) + 2)
    out["batch_wall_seconds"] = wall
    return out


def _sweep_analysis(scene, model, run, drive) -> dict:
    w = scene.sweep
    t = drive.times
    up = sweep_bins(run, drive, (t[1], t[2]), w.bins, "up")
    down = sweep_bins(run, drive, (t[3], t[4]), w.bins, "down")
    s, k = scene.drive.slope, scene.load.coefficient
    j_up, r_up = detect_jumps(up, s, k)
    j_down, r_down = detect_jumps(down, s, k)
    res = model.quasi_normal()
    # the analysis' folds: for this drive slope and load, M0 free
    pred = av.analyse_drive(av.Characteristic(w.torque_high, s, k), res)
    predicted = [vars(j) for j in pred.jumps if w.torque_low <= j.torque_at_zero <= w.torque_high]
    numeric = j_up + j_down
    captured = None
    if j_up:
        below = [r.omega for r in res if r.omega <= j_up[0]["omega_from"] * (1 + 0.03)]
        captured = max(below) if below else None
    rate_check = []
    for r in res:
        if not (w.torque_low <= float(r.omega * (s + k * r.omega)) <= w.torque_high):
            continue
        acc = w.rate / (s + 2 * k * r.omega)
        rate_check.append({"index": r.index, "omega": r.omega, "n": r.n,
                           "speed_rate": acc, "ratio": acc / r.n**2,
                           "quasi_static": bool(acc / r.n**2 < 0.1)})
    if numeric:
        reason = None
    elif predicted:
        reason = "the analysis predicts jumps the sweep did not find (see predicted_jumps)"
    else:
        worst = max((av.resistance_increment(r.omega, r) / (k * r.omega**2) for r in res if k > 0),
                    default=0.0)
        reason = (f"No jumps: the speed rose and fell smoothly with M0 (largest step {max(r_up, r_down):.2f}x "
                  f"what the motor and load alone allow; a jump needs > {JUMP_FACTOR:g}x), as the "
                  f"analysis predicts: no fold of Md = L in [{w.torque_low:g}, {w.torque_high:g}] N*m; "
                  f"the resonances draw at most {100 * worst:.2g} % of Mc at their own speed.")
    W_curve = av.speed_grid(res, 1.05 * max(np.nanmax(up["omega"]), np.nanmax(down["omega"])), 1500)
    curves = {"omega": W_curve,
              "F_averaging": av.total_resistance(W_curve, k, res) + s * W_curve,
              "F_exact": k * W_curve**2 + s * W_curve - model.steady_torque(W_curve),
              "exact": model.steady_amplitudes(W_curve),
              "eq19": {f"{r.direction}{r.index}": av.amplitude(W_curve, r) for r in res}}
    return {"up": up, "down": down, "numeric_jumps": numeric, "predicted_jumps": predicted,
            "jump_comparison": match_jumps(numeric, predicted),
            "largest_speed_step_ratio": {"up": r_up, "down": r_down},
            "amplitudes": compare_amplitudes(model, up) + compare_amplitudes(model, down),
            "rate_check": rate_check, "captured_at": captured, "no_jump_reason": reason,
            "curves": curves}


def rate_convergence(scene, model: RotorStructure, st: Settings, jumps: list[dict],
                     predicted: list[dict], factors=(1.0, 0.5, 0.25)) -> dict:
    """The sweep's jumps at rates r, r/2, r/4, and their limit at zero rate.

    A slow passage past a fold is delayed by a power of the rate (about 2/3
    for a saddle-node); with three rates halving, the exponent p follows from
    the differences d1, d2 and the limit is M(r/4) - d2 / (2**p - 1).
    """
    w = scene.sweep
    s, k = scene.drive.slope, scene.load.coefficient
    rows = []
    found = {1.0: jumps}
    for f in factors:
        if f == 1.0:
            continue
        drive = DriveSchedule.sweep(s, k, w.torque_low, w.torque_high, w.rate * f, w.settle)
        run = simulate(model, drive, no_motion(), drive.times[-1],
                       settings=replace(st, samples=max(st.samples, int(40 * w.bins / f))),
                       speed_scale=drive.free_speed(drive.times[2]))
        t = drive.times
        bins = int(w.bins / f)
        j_up = detect_jumps(sweep_bins(run, drive, (t[1], t[2]), bins, "up"), s, k)[0]
        j_dn = detect_jumps(sweep_bins(run, drive, (t[3], t[4]), bins, "down"), s, k)[0]
        found[f] = j_up + j_dn
    for idx, j in enumerate(jumps):
        same = [j]
        for f in factors[1:]:
            c = [x for x in found[f] if x["direction"] == j["direction"]]
            same.append(min(c, key=lambda x: abs(x["omega_from"] - j["omega_from"])) if c else None)
        row = {"direction": j["direction"], "rates": [w.rate * f for f in factors],
               "torque_at_zero": [None if x is None else x["torque_at_zero"] for x in same],
               "omega_from": [None if x is None else x["omega_from"] for x in same],
               "omega_to": [None if x is None else x["omega_to"] for x in same]}
        for key in ("torque_at_zero", "omega_from", "omega_to"):
            v = row[key]
            lim, p = None, None
            if None not in v and len(v) == 3:
                d1, d2 = v[0] - v[1], v[1] - v[2]
                if d1 * d2 > 0 and abs(d2) < abs(d1):
                    p = math.log2(d1 / d2)
                    lim = v[2] - d2 / (2**p - 1)
            row[f"{key}_limit"] = lim
            row[f"{key}_exponent"] = p
        pred = [q for q in predicted if q["direction"] == j["direction"]]
        if pred and row["torque_at_zero_limit"] is not None:
            q = min(pred, key=lambda q: abs(q["omega_from"] - j["omega_from"]))
            row["predicted_torque_at_zero"] = q["torque_at_zero"]
            row["rel_error_limit_vs_predicted"] = row["torque_at_zero_limit"] / q["torque_at_zero"] - 1
        rows.append(row)
    return {"rows": rows, "note": "jump torques at decreasing sweep rates, extrapolated to a "
                                  "quasi-static sweep (rate -> 0) with a fitted power of the rate"}


def spectrum_check(model: RotorStructure, motion: GroundMotion, run: Transient) -> dict:
    """The tip's largest relative displacement beside the response-spectrum
    estimate of the first pillar mode alone (modal model: Gamma_1 S_d(T_1), 5 %)."""
    if model.pillar_modes is None:
        return {"note": "needs the modal model"}
    pm = model.pillar_modes
    zeta = float(model.damping[0, 0] / (2 * pm.modal_mass[0] * pm.omega[0]))
    T1 = 2 * math.pi / float(pm.omega[0])
    rs = response_spectrum(motion, [T1], damping=zeta)
    gamma = float(pm.participation[0] / pm.modal_mass[0])
    est = abs(gamma) * float(rs["s_d"][0])
    num = float(np.max(np.abs(run.tip()[run.t >= motion.start])))
    return {"period": T1, "damping_ratio": zeta, "participation_factor": gamma,
            "s_d": float(rs["s_d"][0]), "tip_estimate": est, "tip_numeric": num,
            "ratio": num / est if est > 0 else None,
            "note": "first mode alone, rotor as a separate mass: an estimate, not a bound"}
