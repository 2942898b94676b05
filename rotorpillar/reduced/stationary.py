"""Stationary speeds of a rotor-structure model and what the theory predicts.

The exact linear torque balance M0 - s W - k W**2 + <shaft torque>(W) = 0
(``stationary_exact``, ``exact_folds``) beside the averaging theory of the
paper's Eq. 19-23 (``averaging_prediction``), and the motor torque
needed to run up through the first resonance that can capture the rotor,
predicted and simulated (``passing_torque``).

Each returns its records (``StationarySpeed``, ``Fold``, ``AveragingPrediction``,
``PassingTorqueStudy`` or ``NoPassingFold``: a ``PassingTorque``), which ``simulate_<case>.json`` writes as
its ``prediction`` and ``passing_torque``.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from ..errors import InputError
from ..provenance import Record
from . import averaging as av
from .batch import Batch, simulate_batch
from .drive import DriveSchedule
from .rotor_models import RotorStructure, model_digest


class StationarySpeed(Record):
    """A stationary speed of the exact linear torque balance (``stationary_exact``)."""

    omega: float
    """the speed (rad/s)"""
    stable: bool
    """the balance falls through it (its slope in W is negative): a disturbed run returns"""


class Fold(Record):
    """A fold of the exact linear F(W) = k W**2 + s W - <shaft torque>(W) (``exact_folds``)."""

    kind: str
    """"A" (a local maximum: a run-up's branch ends) or "D" (a local minimum: a run-down's)"""
    omega: float
    """where the fold lies (rad/s)"""
    torque_at_zero: float
    """F there: the motor's M0 at which a quasi-static run jumps (N*m)"""


class ResonancePeak(Record):
    """One resonance and the averaging's response at its peak (Eq. 19-20 at Omega = omega_i)."""

    index: int
    """i, from 1 (-)"""
    direction: str
    """"X" (pillar and rotor) or "Y" (rotor on its shaft)"""
    omega: float
    """omega_i (rad/s)"""
    nu: float
    """n_i / omega_i (-)"""
    a_max: float | None
    """Eq. 19 at Omega = omega_i (m); None (JSON null) where unbounded: an undamped resonance"""
    dL_max: float
    """Eq. 20 at Omega = omega_i (N*m)"""


class AveragingPrediction(Record):
    """What the paper's Eq. 19-23 predict for one drive on a model (``averaging_prediction``):
    the ``prediction`` of ``simulate_<case>.json``."""

    stationary: tuple[av.Stationary, ...]
    """the stationary speeds of the averaged torque balance, ascending"""
    jumps: tuple[av.Jump, ...]
    """the jumps of a quasi-static run-up and run-down of M0 with the drive's slope"""
    runup_speed: float | None
    """where a quasi-static run-up settles: the lowest stationary speed (rad/s), or None"""
    rundown_speed: float | None
    """where a quasi-static run-down settles: the highest (rad/s), or None"""
    captured_index: int | None
    """the resonance (index) that holds a run-up below a faster stable regime (-), or None"""
    captured_resonance: float | None
    """that resonance's omega_i (rad/s), or None"""
    captured_at: float | None
    """the speed the run-up settles at when captured: ``runup_speed`` (rad/s), or None"""
    resonances: tuple[ResonancePeak, ...]
    """every resonance of the model with its peak amplitude and torque"""


class PassingResonance(Record):
    """The resonance whose fold sets the passing torque."""

    index: int
    """i, from 1 (-)"""
    direction: str
    """"X" (pillar and rotor) or "Y" (rotor on its shaft)"""
    omega: float
    """omega_i (rad/s)"""
    nu: float
    """n_i / omega_i (-)"""


class BracketRun(Record):
    """A simulated run-up from rest just below or above the predicted passing torque."""

    torque_at_zero: float
    """its motor's M0 (N*m)"""
    final_speed: float
    """mean speed over its last 20 outputs (rad/s)"""
    passed: bool
    """the final speed lies above the pass threshold (the predicted jump's midpoint)"""


class BracketSeries(Record):
    """The two bracket runs' histories, for the run-up chart: rows in ``bracket_runs``' order."""

    t: tuple[float, ...]
    """output times (s)"""
    Omega: tuple[tuple[float, ...], ...]
    """(2, n_t) rotor speed (rad/s)"""
    tip_peak: tuple[tuple[float, ...], ...]
    """(2, n_t) largest |tip X| per output interval (m)"""


class NoPassingFold(Record, kw_only=True, tag_field="kind", tag="no_fold"):
    """The passing-torque study when the analysis finds no run-up fold: nothing to test."""

    predicted: None = None
    """no passing torque: null in the JSON"""
    statement: str
    """why, in words"""


class PassingTorqueStudy(Record, kw_only=True, omit_defaults=True, tag_field="kind", tag="passing"):
    """The motor torque M0 needed to run up through the first resonance that can capture
    the rotor, predicted and simulated (``passing_torque``): ``passing_torque`` of
    ``simulate_runup.json``."""

    resonance: PassingResonance
    """the resonance the run-up must pass"""
    predicted: float
    """M0 at the A fold of Eq. 19-23 (N*m)"""
    predicted_jump: av.Jump
    """that fold's jump"""
    predicted_exact_linear: float | None
    """M0 at the exact linear torque's A fold next to it (N*m), or None"""
    duration: float
    """length of each simulated run-up (s)"""
    pass_threshold_speed: float
    """a run passed when its final speed lies above this: the jump's midpoint (rad/s)"""
    grid: tuple[float, ...]
    """M0 of the first batch of run-ups, around the prediction (N*m)"""
    grid_final_speed: tuple[float, ...]
    """their final speeds (rad/s)"""
    grid_passed: tuple[bool, ...]
    """whether each passed"""
    non_monotonic: bool | None = None
    """True when a run above the first that passed was captured (absent otherwise)"""
    simulated: float | None
    """the smallest M0 that passes, refined between two grid points (N*m); None when every
    run passed or none did"""
    simulated_bracket: tuple[float, float] | None = None
    """the refined M0 captured and passed around it (N*m) (absent without ``simulated``)"""
    rel_error_predicted: float | None = None
    """predicted / simulated - 1 (-) (absent without ``simulated``)"""
    rel_error_exact_linear: float | None = None
    """predicted_exact_linear / simulated - 1 (-), None without the exact fold (absent
    without ``simulated``)"""
    statement: str
    """the outcome in words"""
    bracket_runs: tuple[BracketRun, ...]
    """run-ups at 0.95 and 1.05 times the prediction"""
    bracket_series: BracketSeries
    """their histories"""
    runs: int
    """run-ups simulated in all (-)"""
    batch_wall_seconds: float
    """wall time of the batches (s)"""


#: The passing-torque study, or why there is none (tagged by ``kind``).
PassingTorque = PassingTorqueStudy | NoPassingFold


#: stationary_exact's latest answers, by the model's pickle and the drive: an earthquake or a
#: run-down run asks for its operating speed three times on equal models (the preflight, the
#: kernels' warm-up, the run), each time ~10**4 steady solves (2-3 s on the paper's spatial
#: ROM); a model equal in every field pickles to the same bytes, any other to other bytes.
_MEMO: OrderedDict[str, tuple[StationarySpeed, ...]] = OrderedDict()
MEMO_SIZE = 8
"""Answers kept (a run asks on one or two models; each answer is a few speeds)."""


def _memo_key(model: RotorStructure, *args: float | None) -> str | None:
    """The model's digest (rotor_models.model_digest) and the arguments; None where the model
    does not pickle (it is then solved every time)."""
    digest = model_digest(model)
    return None if digest is None else f"{digest} {args!r}"


def stationary_exact(
    model: RotorStructure, M0: float, slope: float, load: float, top: float | None = None, n: int = 3000
) -> list[StationarySpeed]:
    """Stationary speeds of the exact linear torque balance
    M0 - s W - k W**2 + <shaft torque>(W) = 0 and their stability (an answer for an equal
    model and drive is given again, not solved again: ``_MEMO``)."""
    key = _memo_key(model, M0, slope, load, top, n)
    if key is not None and key in _MEMO:
        _MEMO.move_to_end(key)
        return list(_MEMO[key])
    out = _stationary_exact(model, M0, slope, load, top, n)
    if key is not None:
        _MEMO[key] = tuple(out)
        while len(_MEMO) > MEMO_SIZE:
            _MEMO.popitem(last=False)
    return out


def _stationary_exact(
    model: RotorStructure, M0: float, slope: float, load: float, top: float | None, n: int
) -> list[StationarySpeed]:
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
        out.append(StationarySpeed(float(w), bool(g(w + h) - g(w - h) < 0)))
    return out


def operating_speed(model: RotorStructure, M0: float, slope: float, load: float) -> float:
    """The fastest stationary speed: where the machine runs in service (rad/s)."""
    st = stationary_exact(model, M0, slope, load)
    stable = [s.omega for s in st if s.stable]
    if not stable:
        raise InputError(f"no stable stationary speed for M0 = {M0:g} N*m: the motor cannot drive this machine")
    return float(max(stable))


def averaging_prediction(model: RotorStructure, M0: float, slope: float, load: float) -> AveragingPrediction:
    """What the paper's Eq. 19-23 predict for this drive on this model's quasi-normal modes."""
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(M0, slope, load), res)
    peaks = []
    for r in res:
        a_max = float(av.amplitude(r.omega, r))
        peaks.append(
            ResonancePeak(
                index=r.index,
                direction=r.direction,
                omega=r.omega,
                nu=r.nu,
                a_max=a_max if np.isfinite(a_max) else None,  # what the JSON has always held: null
                dL_max=float(av.resistance_increment(r.omega, r)),
            )
        )
    return AveragingPrediction(
        stationary=tuple(d.stationary),
        jumps=tuple(d.jumps),
        runup_speed=d.runup_speed,
        rundown_speed=d.rundown_speed,
        captured_index=d.captured_index,
        captured_resonance=None
        if d.captured_index is None
        else next(r.omega for r in res if r.index == d.captured_index),
        captured_at=None if d.captured_index is None else d.runup_speed,
        resonances=tuple(peaks),
    )


def exact_folds(model: RotorStructure, slope: float, load: float, top: float) -> list[Fold]:
    """Local maxima (A, run-up) and minima (D, run-down) of the exact linear
    F(W) = k W**2 + s W - <shaft torque>(W): the torques where quasi-static
    runs jump."""
    W = av.stationary_speed_grid(model.quasi_normal(), top, 4000)
    F = load * W**2 + slope * W - model.steady_torque(W)
    dF = np.diff(F)
    out = []
    for i in np.nonzero(np.sign(dF[:-1]) != np.sign(dF[1:]))[0]:
        out.append(Fold("A" if dF[i] > 0 else "D", float(W[i + 1]), float(F[i + 1])))
    return out


def predicted_passing_torque(
    model: RotorStructure, torque_at_zero: float, slope: float, load: float
) -> tuple[av.Jump | None, Fold | None]:
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
        if f.kind == "A" and abs(f.omega - j.omega_from) < 0.2 * j.omega_from
    ]
    return j, (exact[0] if exact else None)


def passing_torque(
    model: RotorStructure, drive: DriveSchedule, duration: float, rtol: float, span: float = 0.2, points: int = 41
) -> PassingTorqueStudy | NoPassingFold:
    """The motor torque M0 needed to run up through the first resonance that
    can capture the rotor: predicted (the A fold of Eq. 19-23, and of the
    exact linear torque) and simulated (run-ups from rest for M0 around the
    prediction, refined once: the smallest M0 that passes within ``duration``)."""
    s, k = drive.slope[-1], drive.load_coefficient
    res = model.quasi_normal()
    j, fold = predicted_passing_torque(model, max(drive.torque_at_zero), s, k)
    if j is None:
        return NoPassingFold(
            statement="The analysis finds no fold for this motor slope and load: a run-up "
            "passes every resonance with any torque that reaches it; nothing to test."
        )
    r = next(r for r in res if r.index == j.resonance)
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
    non_monotonic: bool | None = None
    simulated: float | None = None
    bracket: tuple[float, float] | None = None
    rel_pred: float | None = None
    rel_exact: float | None = None
    if passed1.all() or not passed1.any():
        statement = (
            "every run "
            + ("passed" if passed1.all() else "was captured")
            + f" for M0 within +-{100 * span:g} % of the prediction"
        )
    else:
        i = int(np.argmax(passed1))
        if not passed1[i:].all():
            non_monotonic = True
        fine = np.linspace(grid[i - 1], grid[i], 21)
        b2, final2, passed2 = runs(fine)
        wall += b2.wall_seconds
        i2 = int(np.argmax(passed2)) if passed2.any() else len(fine) - 1
        lo, hi = fine[max(i2 - 1, 0)], fine[i2]
        simulated = float(0.5 * (lo + hi))
        bracket = (float(lo), float(hi))
        rel_pred = float(M_pred / (0.5 * (lo + hi)) - 1)
        rel_exact = None if fold is None else float(fold.torque_at_zero / (0.5 * (lo + hi)) - 1)
        statement = (
            f"Run-up through resonance {r.index} ({r.omega:.2f} rad/s): the analysis "
            f"(Eq. 19-23) says M0 >= {M_pred:.1f} N*m passes; simulated run-ups "
            f"from rest over {duration:g} s pass from {0.5 * (lo + hi):.1f} N*m "
            f"({100 * rel_pred:+.1f} %)."
        )
    # two runs just below and above the prediction, for the charts
    below, above = 0.95 * M_pred, 1.05 * M_pred
    b3, final3, passed3 = runs([below, above])
    wall += b3.wall_seconds
    return PassingTorqueStudy(
        resonance=PassingResonance(r.index, r.direction, r.omega, r.nu),
        predicted=M_pred,
        predicted_jump=j,
        predicted_exact_linear=None if fold is None else fold.torque_at_zero,
        duration=duration,
        pass_threshold_speed=threshold,
        grid=tuple(grid.tolist()),
        grid_final_speed=tuple(final1.tolist()),
        grid_passed=tuple(passed1.tolist()),
        non_monotonic=non_monotonic,
        simulated=simulated,
        simulated_bracket=bracket,
        rel_error_predicted=rel_pred,
        rel_error_exact_linear=rel_exact,
        statement=statement,
        bracket_runs=tuple(BracketRun(float(M), float(f), bool(p)) for M, f, p in zip((below, above), final3, passed3)),
        bracket_series=BracketSeries(
            t=tuple(b3.t.tolist()),
            Omega=tuple(map(tuple, b3.Omega.tolist())),
            tip_peak=tuple(map(tuple, b3.tip_peak.tolist())),
        ),
        runs=int(len(grid) + (21 if simulated else 0) + 2),
        batch_wall_seconds=wall,
    )
