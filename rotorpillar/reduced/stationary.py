"""Stationary speeds of a rotor-structure model and what the theory predicts.

The exact linear torque balance M0 - s W - k W**2 + <shaft torque>(W) = 0
(``stationary_exact``, ``exact_folds``) beside the averaging theory of the
paper's Eq. 19-23 (``averaging_prediction``), and the motor torque
needed to run up through the first resonance that can capture the rotor,
predicted and simulated (``passing_torque``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from ..errors import InputError
from . import averaging as av
from .batch import Batch, simulate_batch
from .drive import DriveSchedule
from .rotor_models import RotorStructure


def stationary_exact(
    model: RotorStructure, M0: float, slope: float, load: float, top: float | None = None, n: int = 3000
) -> list[dict[str, Any]]:
    """Stationary speeds of the exact linear torque balance
    M0 - s W - k W**2 + <shaft torque>(W) = 0 and their stability."""
    free = DriveSchedule.constant(M0, slope, load).free_speed()
    res = model.quasi_normal()
    top = top or 1.2 * max(free, max(r.omega for r in res))
    grid = av.stationary_speed_grid(res, top, n)

    def g(W: float) -> float:
        return M0 - slope * W - load * W * abs(W) + float(model.steady_torque(W))

    # the grid at once: steady_torque solves its speeds in one stacked solve (chunks bound
    # the memory of a many-DOF model); speed by speed it was ~0.5 s per call
    vals = np.concatenate(
        [
            M0 - slope * w - load * w * np.abs(w) + model.steady_torque(w)
            for w in np.array_split(grid, 1 + len(grid) // 500)
        ]
    )
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
        raise InputError(f"no stable stationary speed for M0 = {M0:g} N*m: the motor cannot drive this machine")
    return float(max(stable))


def averaging_prediction(model: RotorStructure, M0: float, slope: float, load: float) -> dict[str, Any]:
    """What the paper's Eq. 19-23 predict for this drive on this model's quasi-normal modes."""
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(M0, slope, load), res)
    return {
        "stationary": [vars(s) for s in d.stationary],
        "jumps": [vars(j) for j in d.jumps],
        "runup_speed": d.runup_speed,
        "rundown_speed": d.rundown_speed,
        "captured_index": d.captured_index,
        "captured_resonance": None
        if d.captured_index is None
        else next(r.omega for r in res if r.index == d.captured_index),
        "captured_at": None if d.captured_index is None else d.runup_speed,
        "resonances": [
            {
                "index": r.index,
                "direction": r.direction,
                "omega": r.omega,
                "nu": r.nu,
                "a_max": float(av.amplitude(r.omega, r)),
                "dL_max": float(av.resistance_increment(r.omega, r)),
            }
            for r in res
        ],
    }


def exact_folds(model: RotorStructure, slope: float, load: float, top: float) -> list[dict[str, Any]]:
    """Local maxima (A, run-up) and minima (D, run-down) of the exact linear
    F(W) = k W**2 + s W - <shaft torque>(W): the torques where quasi-static
    runs jump."""
    W = av.stationary_speed_grid(model.quasi_normal(), top, 4000)
    F = load * W**2 + slope * W - model.steady_torque(W)
    dF = np.diff(F)
    out = []
    for i in np.nonzero(np.sign(dF[:-1]) != np.sign(dF[1:]))[0]:
        out.append({"kind": "A" if dF[i] > 0 else "D", "omega": float(W[i + 1]), "torque_at_zero": float(F[i + 1])})
    return out


def predicted_passing_torque(
    model: RotorStructure, torque_at_zero: float, slope: float, load: float
) -> tuple[av.Jump | None, dict[str, Any] | None]:
    """(jump, exact): the first run-up fold of Eq. 19-23 (the lowest A
    fold; None when there is none) and the exact linear torque's A fold next to
    it (``exact_folds`` entry, or None).  ``torque_at_zero`` sets only the top
    of the speed grid (the motor's free speed)."""
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(torque_at_zero, slope, load), res)
    ups = sorted((j for j in d.jumps if j.direction == "up"), key=lambda j: j.torque_at_zero)
    if not ups:
        return None, None
    j = ups[0]
    exact = [
        f
        for f in exact_folds(model, slope, load, 1.5 * j.omega_to)
        if f["kind"] == "A" and abs(f["omega"] - j.omega_from) < 0.2 * j.omega_from
    ]
    return j, (exact[0] if exact else None)


def passing_torque(
    model: RotorStructure, drive: DriveSchedule, duration: float, rtol: float, span: float = 0.2, points: int = 41
) -> dict[str, Any]:
    """The motor torque M0 needed to run up through the first resonance that
    can capture the rotor: predicted (the A fold of Eq. 19-23, and of the
    exact linear torque) and simulated (run-ups from rest for M0 around the
    prediction, refined once: the smallest M0 that passes within ``duration``)."""
    s, k = drive.slope[-1], drive.load_coefficient
    res = model.quasi_normal()
    j, fold = predicted_passing_torque(model, max(drive.torque_at_zero), s, k)
    if j is None:
        return {
            "predicted": None,
            "statement": "The analysis finds no fold for this motor slope and load: a run-up "
            "passes every resonance with any torque that reaches it; nothing to test.",
        }
    r = next(r for r in res if r.index == j.resonance)
    exact = [fold] if fold else []
    M_pred = j.torque_at_zero
    threshold = 0.5 * (j.omega_from + j.omega_to)
    M_scene = float(max(drive.torque_at_zero))

    def runs(M: ArrayLike) -> tuple[Batch, NDArray[np.float64], NDArray[np.bool_]]:
        b = simulate_batch(model, drive, duration, torque_scale=np.asarray(M) / M_scene, rtol=rtol, samples=401)
        final = b.Omega[:, -20:].mean(axis=1)
        return b, final, final > threshold

    grid = M_pred * np.linspace(1 - span, 1 + span, points)
    b1, final1, passed1 = runs(grid)
    wall = b1.wall_seconds
    out: dict[str, Any] = {
        "resonance": {"index": r.index, "direction": r.direction, "omega": r.omega, "nu": r.nu},
        "predicted": M_pred,
        "predicted_jump": vars(j),
        "predicted_exact_linear": exact[0]["torque_at_zero"] if exact else None,
        "duration": duration,
        "pass_threshold_speed": threshold,
        "grid": grid,
        "grid_final_speed": final1,
        "grid_passed": passed1,
    }
    if passed1.all() or not passed1.any():
        out["simulated"] = None
        out["statement"] = (
            "every run "
            + ("passed" if passed1.all() else "was captured")
            + f" for M0 within +-{100 * span:g} % of the prediction"
        )
    else:
        i = int(np.argmax(passed1))
        if not passed1[i:].all():
            out["non_monotonic"] = True
        fine = np.linspace(grid[i - 1], grid[i], 21)
        b2, final2, passed2 = runs(fine)
        wall += b2.wall_seconds
        i2 = int(np.argmax(passed2)) if passed2.any() else len(fine) - 1
        lo, hi = fine[max(i2 - 1, 0)], fine[i2]
        out.update(
            {
                "simulated": 0.5 * (lo + hi),
                "simulated_bracket": [lo, hi],
                "rel_error_predicted": M_pred / (0.5 * (lo + hi)) - 1,
                "rel_error_exact_linear": (exact[0]["torque_at_zero"] / (0.5 * (lo + hi)) - 1) if exact else None,
            }
        )
        out["statement"] = (
            f"Run-up through resonance {r.index} ({r.omega:.2f} rad/s): the analysis "
            f"(Eq. 19-23) says M0 >= {M_pred:.1f} N*m passes; simulated run-ups "
            f"from rest over {duration:g} s pass from {0.5 * (lo + hi):.1f} N*m "
            f"({100 * out['rel_error_predicted']:+.1f} %)."
        )
    # two runs just below and above the prediction, for the charts
    below, above = 0.95 * M_pred, 1.05 * M_pred
    b3, final3, passed3 = runs([below, above])
    wall += b3.wall_seconds
    out["bracket_runs"] = [
        {"torque_at_zero": float(M), "final_speed": float(f), "passed": bool(p)}
        for M, f, p in zip((below, above), final3, passed3)
    ]
    out["bracket_series"] = {"t": b3.t, "Omega": b3.Omega, "tip_peak": b3.tip_peak}
    out["runs"] = int(len(grid) + (21 if out.get("simulated") else 0) + 2)
    out["batch_wall_seconds"] = wall
    return out
