"""Reading a transient run: what it reached, where it settled, and its series.

- ``max_abs`` per coordinate (from every step, not the decimated output);
- ``capture``: a run settles at a resonance when its final speed lies inside
  that resonance's peak (|Omega - omega_i| <= max(3 n_i, 0.03 omega_i)) while
  the motor alone, without any resonance, would settle more than 2 % away
  (Md = Mc);
- ``passages``: when the speed first crosses each resonance;
- ``series``: the arrays written to the NPZ/CSV;
- ``RunOutcome``: what every model's run reached; ``CaseSummary``: a case on a
  reduced model, what ``simulate_<case>.json`` carries about it;
- the checks a case's summary carries beside its numbers, built by
  rotorpillar.transients.cases: ``truncation``, the modal model's answers against
  the same case with one more pillar mode (``TruncationEstimate``, or why there is
  none: ``NoTruncationEstimate``); ``response_spectrum_check``, an earthquake on a
  record, the tip's largest displacement relative to the ground beside the
  response-spectrum estimate (``SpectrumCheck``, or ``NoSpectrumCheck``), each
  pair a union tagged by ``kind``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from dataclasses import replace as replace_run
from typing import Any

import numpy as np

from ..records import Record, replace
from ..reduced.accuracy import AccuracyCheck, check_step, forcing_frequencies
from ..reduced.batch import shaft_deflection
from ..reduced.excitation import ExcitationSizes, GroundMotion, no_motion
from ..reduced.integration import EnergyBalance, IntegratorStats, Transient
from ..reduced.rotor_models import RotorStructure
from ..reduced.stationary import AveragingPrediction, PassingTorque
from .sweep import NumericJump, SweepFindings


class SpectralMode(Record):
    """One coupled rotor-pillar mode's part in the response-spectrum estimate of the tip
    (rotorpillar.reduced.spectral)."""

    mode: int
    """its number, from 1 (-)"""
    period: float
    """T_j = 2 pi / omega_j, omega_j its undamped natural frequency (s)"""
    damping_ratio: float
    """its own damping ratio zeta_j = u_j^T C u_j / (2 m_j omega_j) (-)"""
    participation_factor: float
    """the tip's participation p_j = -(tip . u_j)(u_j . b) / m_j for a base acceleration,
    independent of the shape's scale (-)"""
    s_d: float
    """the record's spectral displacement at its period and damping (m)"""
    contribution: float
    """|p_j| S_d(T_j, zeta_j): the tip's peak in this mode (m)"""


class TruncationEstimate(Record, tag_field="kind", tag="estimate"):
    """How much the (k+1)-th pillar mode changes a modal run's answers: the
    truncation error estimate (relative differences: the run with k + 1 modes
    over the run with k, minus 1)."""

    modes: int
    """k: the pillar modes of the run (-)"""
    modes_check: int
    """k + 1: the pillar modes of the check (-)"""
    omega_added: float
    """circular frequency of the mode the check adds (rad/s)"""
    effective_mass_fraction: float
    """share of the base-excited mass the k modes carry (-)"""
    effective_mass_fraction_check: float
    """the same for the k + 1 modes (-)"""
    omega_final_rel_diff: float | None
    """of the final speed (-); None when the run ends at rest"""
    tip_series_max_rel_diff: float
    """max_t |tip_k - tip_k+1| over max_t |tip_k+1| (-)"""
    tip_x_max_rel_diff: float | None
    """of the largest |tip X| (-); None when the run's is zero"""
    rotor_x_max_rel_diff: float | None
    """of the largest |rotor X| (-); None when the run's is zero"""
    rotor_y_max_rel_diff: float | None
    """of the largest |rotor Y| (-); None when the run's is zero"""


class NoTruncationEstimate(Record, tag_field="kind", tag="unavailable"):
    """A modal run without its truncation estimate: the mode source offers no more modes."""

    modes: int
    """the pillar modes of the run (-)"""
    modes_check: None
    """no check run (always None)"""
    statement: str
    """why, in words"""


#: The truncation estimate, or why there is none.
Truncation = TruncationEstimate | NoTruncationEstimate


class SpectralEstimate(Record):
    """The response-spectrum estimate of the tip's largest displacement relative to the
    ground: per coupled rotor-pillar mode j, |p_j| S_d(T_j, zeta_j), combined by SRSS."""

    modes: tuple[SpectralMode, ...]
    """each coupled mode's part, in ascending frequency"""
    srss_tip_estimate: float
    """the square root of the sum of the contributions' squares (m)"""
    pillar_modes_only: float
    """the same SRSS over the pillar's own modes, the rotor apart (m): what the estimate
    would read without the rotor's coupling"""


class SpectrumCheck(Record, tag_field="kind", tag="check"):
    """The tip's largest displacement relative to the ground beside the response-spectrum
    estimate over the coupled rotor-pillar modes: the mode of the largest contribution alone
    (|p_k| S_d(T_k, zeta_k)), and every mode (SRSS)."""

    period: float
    """T_k: the period of the mode of the largest contribution (s)"""
    damping_ratio: float
    """zeta_k: its own damping ratio (-)"""
    participation_factor: float
    """p_k: the tip's participation in it for a base acceleration (-)"""
    s_d: float
    """the record's spectral displacement at T_k, zeta_k (m)"""
    tip_estimate: float
    """|p_k| S_d(T_k, zeta_k): that mode alone (m)"""
    tip_numeric: float
    """the run's largest |tip X| relative to the ground after the motion starts (m)"""
    ratio: float | None
    """tip_numeric / srss_tip_estimate (-); None when the estimate is zero"""
    srss_tip_estimate: float
    """every coupled mode, SRSS (m)"""
    modes: tuple[SpectralMode, ...]
    """each coupled mode's part"""
    note: str
    """what the estimate is, in words"""


class NoSpectrumCheck(Record, tag_field="kind", tag="unavailable"):
    """No response-spectrum check: the model has no pillar modes."""

    note: str
    """why, in words"""


#: The response-spectrum check, or why there is none.
SpectrumCheckResult = SpectrumCheck | NoSpectrumCheck


CAPTURE_WIDTH = 3.0  # in n_i = nu_i omega_i
CAPTURE_MIN_WIDTH = 0.03  # relative


def capture(model: RotorStructure, omega_final: float, drive_free_speed: float):
    """The resonance (a ``Resonance`` record) the run settled at, or None."""
    if not math.isfinite(drive_free_speed) or abs(drive_free_speed - omega_final) <= 0.02 * drive_free_speed:
        return None
    best = None
    for r in model.quasi_normal():
        width = max(CAPTURE_WIDTH * r.n, CAPTURE_MIN_WIDTH * r.omega)
        if abs(omega_final - r.omega) <= width and (
            best is None or abs(omega_final - r.omega) < abs(omega_final - best.omega)
        ):
            best = r
    return best


#: A run whose speed still rose by more than this share over its last 5 % is
#: escaping its resonance, not captured (the sommerfeld scene at M0 = 630 N*m
#: rises 2 % over its last 4 s, a captured run less than 1e-4).
ESCAPE_RISE = 0.005
TAIL = 0.05


@dataclass(frozen=True)
class CaptureState:
    """Where a run's speed ended (``capture_state``)."""

    captured_at: float | None
    """the speed the rotor settled at below a resonance (rad/s), or None"""
    captured_resonance: float | None
    """that resonance's omega_i (rad/s), or None"""
    captured_index: int | None
    """its index among the model's resonances (-), or None"""
    speed_state: str
    """"captured", "escaping", "accelerating" or "at_speed" (see capture_state)"""


def capture_state(model: RotorStructure, t, Omega, drive_free_speed: float) -> CaptureState:
    """Where a run's speed ended: captured below a resonance, escaping it, or at speed.

    ``captured_at``: the speed the rotor settled at below the resonance (the
    mean over the last 5 % of the run, rad/s), or None; ``captured_resonance``:
    that resonance's omega_i (rad/s), or None; ``captured_index``: its index
    among the model's resonances, or None; ``speed_state``: "captured",
    "escaping" (near a resonance but still accelerating at the end: the run
    is too short to tell, and the rotor is not stuck), "accelerating" (still
    rising, no resonance near) or "at_speed".
    """
    t, Omega = np.asarray(t, dtype=float), np.asarray(Omega, dtype=float)
    tail = t >= t[-1] - max(TAIL * (t[-1] - t[0]), 1e-9)
    mean = float(np.mean(Omega[tail]))
    rise = float(Omega[-1] - Omega[tail][0])
    rising = rise > ESCAPE_RISE * max(abs(mean), 1e-9)
    resonance = capture(model, mean, drive_free_speed)
    if resonance is not None and not rising:
        return CaptureState(mean, resonance.omega, resonance.index, "captured")
    state = ("escaping" if resonance is not None else "accelerating") if rising else "at_speed"
    return CaptureState(None, None, None, state)


class Passage(Record):
    """When a run's speed first crosses one resonance, and the peaks near it."""

    index: int
    """the resonance's index among the model's (-)"""
    direction: str
    """"X" (pillar and rotor) or "Y" (rotor on its shaft)"""
    omega: float
    """omega_i (rad/s)"""
    crossed: bool
    """the speed crossed omega_i"""
    time: float | None
    """when it first did (s), or None"""
    peak_tip_near: float | None
    """largest tip amplitude while the speed was within 10 % of omega_i (m), or None"""
    peak_rotor_y_near: float | None
    """largest |rotor Y| there (m), or None"""


def passages(run: Transient) -> tuple[Passage, ...]:
    """When the speed first crosses each resonance, and the largest tip
    amplitude within +-10 % of it."""
    out = []
    W = run.Omega
    tip_peak = run.peak[:, -1]
    for r in run.model.quasi_normal():
        idx = np.nonzero((W[:-1] - r.omega) * (W[1:] - r.omega) <= 0)[0]
        near = np.abs(W - r.omega) <= 0.1 * r.omega
        out.append(
            Passage(
                index=r.index,
                direction=r.direction,
                omega=r.omega,
                crossed=bool(idx.size),
                time=float(run.t[idx[0]]) if idx.size else None,
                peak_tip_near=float(tip_peak[near].max()) if near.any() else None,
                peak_rotor_y_near=float(run.peak[near, run.model.nx].max()) if near.any() else None,
            )
        )
    return tuple(out)


def max_abs(run: Transient) -> dict[str, float | None]:
    """Largest |value| over the run, from the integrator's per-step peaks (m); a mapping by
    coordinate name, not a record: its keys are the model's coordinates (the JSON's max_abs)."""
    m = run.model
    pk = np.nanmax(run.peak, axis=0)
    out: dict[str, float | None] = {"tip_x": float(pk[-1]), "rotor_x": float(pk[m.rotor_x]), "rotor_y": float(pk[m.nx])}
    if not m.notes.get("full_order"):  # a full-order model's nodes: not worth a key each
        for i, name in enumerate(m.coordinates):
            out[name] = float(pk[i])
    shaft_x = shaft_deflection(run.q, m.shaft, m.eccentricity)[1]
    out["shaft_deflection_x_sampled"] = float(np.nanmax(np.abs(shaft_x)))
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
    return replace_run(run, t=run.t[idx], q=run.q[idx], v=run.v[idx], work=run.work[idx], peak=peak)


def series(run: Transient, max_samples: int | None = None) -> dict[str, np.ndarray]:
    """The arrays written to the NPZ/CSV (contract with the animations); a mapping by column
    name, not a record: the columns present depend on the model (drive, frame, modes)."""
    if max_samples:
        run = decimate(run, max_samples)
    m = run.model
    motion = run.motion or no_motion()
    ground = ground_displacement(m, motion, run.t)
    tip = run.tip()
    out = {
        "t": run.t,
        "Omega": run.Omega,
        "theta": run.q[:, -1],
        "tip_x": tip,
        "rotor_x": run.q[:, m.rotor_x],
        "rotor_y": run.q[:, m.nx],
        "ground_x": ground,
        "ground_acceleration": motion.evaluate(run.t)[2],
        "q": run.q,
        "v": run.v,
        "peak": run.peak,
        "work": run.work,
    }
    if run.drive is not None:
        out["M0"] = run.drive.at(run.t)[0]
        out["drive_torque"] = run.drive.torque(run.t, run.Omega)
    T, P = m.energy(run.q, run.v)
    out["energy"] = T + P
    if m.frame == "relative_to_ground":
        out["tip_x_absolute"] = tip + ground
        out["rotor_x_absolute"] = out["rotor_x"] + ground
    if m.pillar_modes is not None:
        out["modal_coordinates"] = run.q[:, : m.pillar_modes.count]
        if m.pillar_modes.shapes is not None and m.pillar_modes.heights is not None:
            out["mode_heights"] = m.pillar_modes.heights
            out["mode_shapes"] = m.pillar_modes.shapes
            out["mode_omega"] = np.asarray(m.pillar_modes.omega)
    return out


# --------------------------------------------------------------------------
# The summary of a case


class RunOutcome(Record, kw_only=True, omit_defaults=True):
    """What every model's run of a case reached (``simulate_<case>.json``; SI units)."""

    ok: bool
    """the run passed its own checks (``run_checks``)"""
    failed_checks: tuple[str, ...] | None = None
    """why ``ok`` is false, one named line each (absent when no check failed)"""
    duration: float
    """length of the run (s)"""
    omega_final: float
    """rotor speed at the end (rad/s)"""
    omega_final_mean: float
    """mean speed over the last 5 % of the run (rad/s)"""
    max_abs: dict[str, float | None]
    """largest |value| per coordinate (m), and the forces' (N, N m, Pa); a mapping by
    name: its keys are the model's coordinates"""
    captured_at: float | None
    """the speed the rotor settled at below a resonance (rad/s), or None"""
    captured_resonance: float | None
    """omega_i of the resonance that holds the rotor (rad/s), or None"""
    captured_index: int | None
    """that resonance's index among the model's resonances (-), or None"""
    speed_state: str
    """"captured", "escaping", "accelerating" or "at_speed" (see capture_state)"""
    energy_balance: EnergyBalance
    """the run's energy against the work done (J)"""
    integrator: IntegratorStats
    """what the integrator did"""
    excitation: ExcitationSizes | None = None
    """earthquake: the ground motion's sizes"""


class CaseSummary(RunOutcome, kw_only=True, omit_defaults=True):
    """A case on a reduced model condensed (paper, modal, beam): the outcome, the passages,
    the theory's prediction and the case's own checks."""

    passages: tuple[Passage, ...]
    """when the speed first crossed each resonance"""
    prediction: AveragingPrediction
    """what the averaging theory predicts for the drive"""
    jumps: tuple[NumericJump, ...]
    """the sweep's numeric jumps (empty for the other cases)"""
    passing_torque: PassingTorque | None = None
    """run-up: the torque needed to pass the first capturing resonance"""
    sweep: SweepFindings | None = None
    """sweep: the jumps and amplitudes against the averaging theory"""
    response_spectrum_check: SpectrumCheckResult | None = None
    """earthquake on a record: the tip against the response-spectrum estimate"""
    truncation: Truncation | None = None
    """modal model: the same case with one mode more"""


#: A run whose energy balance misses by more than this share of the energy
#: exchanged is no solution of its equations (dp5 at rtol 1e-7 closes to ~1e-6,
#: Newmark at 40 steps per period to ~1e-3; an unstable scheme to ~1).
ENERGY_CHECK = 0.05
#: The speed may pass the drive's free speed only by what the structure gives
#: back (a few per mille in the embedded scenes); more is an integration error.
SPEED_CHECK = 0.02


def accuracy_check(run: Transient) -> AccuracyCheck:
    """The run's step against what it had to resolve (rotorpillar.reduced.accuracy):
    the unbalance's rotation at the fastest speed the run reached and the ground
    motion's band, and the run's and the ground motion's durations.  Fixed-step
    schemes: their step; adaptive ones: the steps they took against the periods
    they went through at each moment's fastest frequency, and their rtol."""
    st, m = run.stats, run.model
    method = st.method
    motion = run.motion or no_motion()
    W = np.abs(np.asarray(run.Omega, dtype=float))
    finite = W[np.isfinite(W)]
    top = float(finite.max()) if len(finite) else 0.0
    if motion.kind == "none" and not run.prescribed_speed and run.drive is not None:
        # a diverged run's speed says nothing of what it had to resolve: with the ground
        # still the rotor cannot outrun its drive (run_checks flags it when it does)
        reach = max(
            [abs(float(run.Omega[0])), run.drive.free_speed()] + [run.drive.free_speed(ti) for ti in run.drive.times]
        )
        if math.isfinite(reach) and reach > 0:
            top = min(top, reach)
    W = np.where(np.isfinite(W), np.minimum(W, top), top)
    freq = forcing_frequencies(m.eccentricity, top, motion)
    t = np.asarray(run.t, dtype=float)
    duration = float(t[-1] - t[0])
    window = None
    if motion.kind != "none":
        window = (motion.start - t[0], motion.end - t[0])
    h = st.time_step
    if h:
        scheme = st.scheme if isinstance(st.scheme, dict) else {}
        return check_step(method, dict(scheme), float(h), freq, duration, window=window)
    # adaptive: the periods gone through at each moment's fastest frequency
    fast = W if m.eccentricity > 0 else np.zeros_like(t)
    if "ground_motion_band" in freq:
        on = (t >= motion.start) & (t < motion.end)
        fast = np.where(on, np.maximum(fast, freq["ground_motion_band"]), fast)
    periods = float(np.sum(0.5 * (fast[1:] + fast[:-1]) * np.diff(t)) / (2 * math.pi))
    steps = st.steps
    mean = duration / steps if steps else 0.0
    return check_step(
        method,
        {},
        mean,
        freq,
        duration,
        adaptive=True,
        periods=periods,
        steps=steps,
        window=window,
        rtol=st.rtol,
    )


def run_checks(run: Transient, drive_free_speed: float, accuracy: AccuracyCheck | None = None) -> list[str]:
    """The run's own checks, one named line each ("name: why") for every one that
    fails (empty: all hold).

    The integrator finished, took steps, kept every value finite, stayed
    within its stability limit, took a step fit for what it had to resolve
    (``accuracy_check``), closed the energy balance, and the rotor did not
    outrun its drive.
    """
    failed = []
    status = run.stats.status
    if status != "ok":
        failed.append(f"integrator_stopped: {status}")
    if run.stats.steps == 0:
        failed.append("no_steps: the integrator took no step (tolerance or step below what it can resolve)")
    if not (np.all(np.isfinite(run.q)) and np.all(np.isfinite(run.v))):
        failed.append("not_finite: the solution holds non-finite values")
    h = run.stats.time_step
    if run.stats.method == "central_difference" and h:
        w_max = run.model.stiffest_frequency()
        if h * w_max > 2.0:
            failed.append(
                f"stability: central difference past its stability limit: h omega_max = "
                f"{h * w_max:.3g} > 2 (h = {h:g} s)"
            )
    failed += (accuracy or accuracy_check(run)).failed
    e = run.energy_balance().relative_error
    if not np.isfinite(e) or e > ENERGY_CHECK:
        failed.append(
            f"energy_balance: the energy balance misses by {100 * e:.3g} % of the energy "
            f"exchanged (limit {100 * ENERGY_CHECK:g} %)"
        )
    w = float(np.max(np.abs(run.Omega))) if len(run.Omega) else 0.0
    # the fastest the drive can hold at any of its knots, or the start, if faster
    drive = run.drive
    top = max(
        [drive_free_speed, abs(float(run.Omega[0]))]
        + ([] if drive is None else [drive.free_speed(t) for t in drive.times])
    )
    # a moving ground feeds the rotor through the structure: no bound from the drive alone
    still = run.motion is None or run.motion.kind == "none"
    if still and np.isfinite(top) and top > 0 and not run.prescribed_speed and w > (1 + SPEED_CHECK) * top:
        failed.append(f"speed: the rotor reached {w:.4g} rad/s, above the drive's free speed {top:.4g} rad/s")
    return failed


def run_summary(run: Transient, drive_free_speed: float, prediction: AveragingPrediction, **sections) -> CaseSummary:
    """The summary of ``run``; ``sections`` override or add fields (jumps,
    captured_at, passing_torque, sweep, ...)."""
    tail = run.t >= run.t[-1] - max(0.05 * (run.t[-1] - run.t[0]), 1e-9)
    om_mean = float(np.mean(run.Omega[tail]))
    acc = accuracy_check(run)
    failed = run_checks(run, drive_free_speed, acc)
    state = capture_state(run.model, run.t, run.Omega, drive_free_speed)
    base: dict[str, Any] = dict(
        ok=not failed,
        failed_checks=tuple(failed) or None,
        duration=float(run.t[-1] - run.t[0]),
        omega_final=float(run.Omega[-1]),
        omega_final_mean=om_mean,
        max_abs=max_abs(run),
        captured_at=state.captured_at,
        captured_resonance=state.captured_resonance,
        captured_index=state.captured_index,
        speed_state=state.speed_state,
        passages=passages(run),
        energy_balance=run.energy_balance(),
        integrator=replace(run.stats, accuracy=acc),
        prediction=prediction,
        jumps=(),
    )
    base.update(sections)
    return CaseSummary(**base)
