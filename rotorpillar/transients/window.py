"""The run-up's window for the full order: through the resonances, not the whole run.

A 3D run-up from rest over the case's duration spends most of its steps far
from any resonance (the paper's rotor passes its resonances in its first
second of 80; the sommerfeld fan needs 12 s to get near its first and is
then held there).  The window starts where the ROM's run-up from rest first
reaches ``START_FRACTION`` of the lowest resonance (X or Y) and ends where
the speed has passed the last resonance the drive passes by
``PASS_FACTOR``, or, when the rotor is captured, ``SETTLE_PERIODS`` periods
of the captured resonance after the tip's peak.  Every model of the
comparison starts at that speed from the same state: the pillar at rest,
the rotor in its steady whirl on it as if held (``simulate.runup_initial_speed``;
the 3D full order's rotorpillar.fem3d.rotor_top.rotor_start, the reduced
models' ``RotorStructure.held_whirl_state``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import math
from functools import partial

import numpy as np

from ..records import Record

START_FRACTION = 0.7
"""Window start: this share of the lowest resonance, where the pillar barely moves
(steady amplification 1 / (1 - 0.49) ~ 2 of the unbalance's static deflection) (-)."""
PASS_FACTOR = 1.5
"""Window end after a passage: the speed at this multiple of the last resonance passed,
past the peak of the ringing it leaves (-)."""
SETTLE_PERIODS = 10
"""Window end after a capture: periods of the captured resonance after the tip's peak."""


class RunupWindow(Record):
    """Where the compared run-up starts and ends, from the ROM's run-up from rest (SI)."""

    initial_speed: float
    """the speed every model starts at (rad/s); 0: from rest (no window)"""
    start: float
    """when the ROM's run-up from rest reaches it (s)"""
    end: float
    """(s)"""
    duration: float
    """end - start: the length every model runs (s)"""
    resonances: tuple[float, ...]
    """the ROM's resonances (X and Y) (rad/s)"""
    passed: tuple[float, ...]
    """those the run-up from rest passes (rad/s)"""
    captured_resonance: float | None
    """the resonance the rotor is held at, or None (rad/s)"""
    peak_time: float
    """when the ROM's tip peaks in its run-up from rest (s)"""
    reason: str


def runup_window(scene: Scene, pillar_modes=None) -> RunupWindow:
    """The window of the scene's run-up (see the module text): one run-up of the
    modal ROM from rest, without the passing-torque batch and the truncation check;
    ``pillar_modes``: the ROM's (the chain's; None: resolved for the scene, no study)."""
    from ..reduced.drive import DriveSchedule
    from ..scene import with_values
    from .case_summary import capture_state
    from .cases import run_case

    sim = scene.simulate
    if pillar_modes is None:
        from ..chain import resolve

        pillar_modes = resolve(scene, None).modes  # no study here: the scene's own model
    # the planar ROM's run-up places the window (its resonances in the rotor's plane are the
    # spatial ROM's to the gondola's inertia): as today, whatever modal_model.planes says
    rest = with_values(
        scene, {"simulate.threshold": False, "simulate.runup_initial_speed": 0.0, "modal_model.planes": "planar"}
    )
    res = run_case(rest, "runup", "modal", truncation=False, pillar_modes=pillar_modes)
    t, W, tip = res.run.t, res.run.Omega, np.abs(res.run.tip())
    qn = sorted(r.omega for r in res.model.quasi_normal())
    d, L = scene.drive, scene.load
    free = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
    state = capture_state(res.model, t, W, free)
    w0 = START_FRACTION * qn[0]
    reached = np.nonzero(W >= w0)[0]
    whole = partial(
        RunupWindow,
        initial_speed=0.0,
        start=0.0,
        end=float(t[-1]),
        duration=float(t[-1]),
        resonances=tuple(qn),
        passed=tuple(w for w in qn if w <= W.max()),
        captured_resonance=state.captured_resonance,
        peak_time=float(t[int(np.argmax(tip))]),
    )
    if reached.size == 0:
        return whole(
            reason=f"the run-up never reaches {START_FRACTION:g} x the lowest "
            f"resonance ({qn[0]:.2f} rad/s): the whole run from rest"
        )
    i0 = int(reached[0])
    t0 = float(t[i0])
    if sim.runup_ramp > t0:
        return whole(
            reason=f"the motor's ramp (simulate.runup_ramp = {sim.runup_ramp:g} s) "
            f"lasts past {t0:.3g} s, where the speed reaches {w0:.3g} rad/s: a window "
            "would start on a partial torque; the whole run from rest"
        )
    after = slice(i0, None)
    i_peak = i0 + int(np.argmax(tip[after]))
    t_peak = float(t[i_peak])
    passed = tuple(w for w in qn if w <= float(W.max()))
    if state.captured_resonance is not None:
        wc = state.captured_resonance
        t_end = t_peak + SETTLE_PERIODS * 2 * math.pi / wc
        why = f"captured at {wc:.2f} rad/s: until {SETTLE_PERIODS} periods of it after the tip's peak at {t_peak:.3g} s"
    elif passed:
        last = max(passed)
        beyond = np.nonzero(W >= PASS_FACTOR * last)[0]
        t_end = max(float(t[beyond[0]]) if beyond.size else float(t[-1]), t_peak)
        why = f"through the last resonance passed ({last:.2f} rad/s) to {PASS_FACTOR:g} x it" + (
            "" if beyond.size else " (not reached: the end of the run)"
        )
    else:
        t_end, why = float(t[-1]), "no resonance passed: to the end of the run"
    t_end = min(t_end, float(t[-1]))
    return RunupWindow(
        initial_speed=float(w0),
        start=t0,
        end=t_end,
        duration=t_end - t0,
        resonances=tuple(qn),
        passed=passed,
        captured_resonance=state.captured_resonance,
        peak_time=t_peak,
        reason=(
            f"from {w0:.3g} rad/s ({START_FRACTION:g} x the lowest resonance {qn[0]:.2f} rad/s, "
            f"reached at {t0:.3g} s from rest) {why}: {t_end - t0:.3g} s of the ROM's run-up, "
            "every model from the same state (pillar at rest, rotor in its steady whirl)"
        ),
    )


def window_scene(scene: Scene, window: RunupWindow) -> Scene:
    """The scene whose run-up is the window's (without the passing-torque batch: it
    answers for a run-up from rest over the whole case, which the window is not)."""
    from ..scene import with_values

    values: dict[str, float | bool] = {"simulate.duration": window.duration, "simulate.threshold": False}
    if window.initial_speed > 0:
        values |= {"simulate.runup_initial_speed": window.initial_speed, "simulate.runup_ramp": 0.0}
    return with_values(scene, values)
