"""The capture boundary of a run-up study: predicted, and as the study found it.

Predicted: the motor torque M0 a run-up needs to pass the first resonance
that can capture it, by the averaging theory (the A fold of the paper's
Eq. 19-23) and by the exact linear torque balance
(``rotorpillar.reduced.stationary.predicted_passing_torque``), as a function
of the study's other axis (e.g. the eccentricity), on a grid finer than the
study's; with, per point, the resonance that fold belongs to (``resonance``)
and the model's resonances (``resonances``: the charts label each piece of
the curve, and tell a run that stopped below a resonance it never reached
from one that passed them all).  Found: per value of the other axis, the largest M0 that was
captured and the smallest that passed.

The boundary applies when one axis is ``drive.torque_at_zero`` (and at most
one other, numeric, axis); with one axis of another key, the threshold of
that key is where the predicted torque crosses the scene's M0.
"""

from __future__ import annotations

import numpy as np

from ..records import Record, replace
from ..reduced.band import forcing_top
from ..reduced.models import build_model
from ..reduced.stationary import predicted_passing_torque
from ..scene import Scene
from .axes import Axis, Param, run_scene

TORQUE = "drive.torque_at_zero"
#: points of the predicted curve along the other axis
CURVE_POINTS = 61


class ResonanceMark(Record):
    """A resonance of the model, as the charts label the boundary's pieces."""

    index: int
    """i, from 1 (-)"""
    direction: str
    """"X" or "Y\""""
    omega: float
    """omega_i (rad/s)"""


class TorqueBoundary(Record, tag_field="kind", tag="torque"):
    """The torque M0 a run-up needs to pass, along the study's other axis (predicted)."""

    torque_key: str
    """the torque's scene key"""
    other_key: str | None
    """the other axis's key (None: the torque is the only axis)"""
    other_values: tuple[float, ...]
    """the other axis's values, on a grid finer than the study's (its unit)"""
    averaging: tuple[float | None, ...]
    """M0 at the A fold of Eq. 19-23 per value (N*m; None: no fold)"""
    exact_linear: tuple[float | None, ...]
    """M0 at the exact linear torque balance's A fold (N*m; None: no fold)"""
    resonance: tuple[int | None, ...]
    """the resonance each fold belongs to (its index)"""
    resonances: tuple[ResonanceMark, ...]
    """the model's resonances"""
    statement: str
    """what the curves are, in words"""


class ThresholdBoundary(Record, tag_field="kind", tag="threshold"):
    """Where the torque needed to pass equals the scene's M0, along the study's one axis."""

    torque_key: str
    """the torque's scene key"""
    other_key: str
    """the axis's key"""
    other_values: tuple[float, ...]
    """its values, on a finer grid (its unit)"""
    averaging: tuple[float | None, ...]
    """M0 needed by Eq. 19-23 per value (N*m)"""
    exact_linear: tuple[float | None, ...]
    """M0 needed by the exact linear torque balance (N*m)"""
    scene_torque: float
    """the scene's M0 (N*m)"""
    threshold_averaging: float | None
    """the axis's value where Eq. 19-23's M0 crosses the scene's (None: no crossing)"""
    threshold_exact_linear: float | None
    """the same for the exact linear balance"""
    statement: str
    """what the threshold is, in words"""


class FoundRow(Record):
    """The boundary as the study found it at one value of the other axis."""

    other: Param | None
    """the other axis's value (None: the torque is the only axis)"""
    captured_max: float | None
    """the largest M0 captured below the smallest that passed (N*m)"""
    passed_min: float | None
    """the smallest M0 that passed (N*m)"""
    monotonic: bool
    """every M0 above ``passed_min`` passed and none above it was captured"""


class StudyBoundary(Record):
    """A run-up study's capture boundary: predicted and found."""

    predicted: TorqueBoundary | ThresholdBoundary | None
    """the theory's (tagged by ``kind``), None where it does not apply"""
    found: tuple[FoundRow, ...] | None
    """per value of the other axis, None where the torque is no axis"""


def _numeric(axis: Axis) -> bool:
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in axis.values)


def _fold(scene: Scene, which: str, M_top: float, modes_of=None) -> tuple:
    """(averaging's and exact linear passing torque, the index of the resonance
    that fold belongs to, the model's resonances)."""
    top_scene = replace(scene, drive=replace(scene.drive, torque_at_zero=M_top))
    top = scene.modal_model.band_factor * forcing_top(top_scene.drive, top_scene.load, top_scene.sweep, "runup", None)
    model, _ = build_model(top_scene, which, top, pillar_modes=modes_of(scene) if modes_of is not None else None)
    d, L = scene.drive, scene.load
    j, exact = predicted_passing_torque(model, M_top, d.slope, L.coefficient)
    res = tuple(ResonanceMark(int(r.index), str(r.direction), float(r.omega)) for r in model.quasi_normal())
    return (
        None if j is None else float(j.torque_at_zero),
        None if exact is None else float(exact.torque_at_zero),
        None if j is None else int(j.resonance),
        res,
    )


def _grid(axis: Axis) -> list:
    from .modes import affects_modes

    if affects_modes(axis.key):
        return sorted(axis.values)  # each value a pillar of its own: its own modes, no finer grid
    values = [float(v) for v in axis.values]  # a numeric axis (``_numeric``)
    lo, hi = min(values), max(values)
    if len(values) == 1 or lo == hi:
        return [lo]
    if all(isinstance(v, int) for v in axis.values):  # an integer key: its integers, a scene each
        return sorted({int(round(x)) for x in np.linspace(lo, hi, CURVE_POINTS)})
    return list(np.linspace(lo, hi, CURVE_POINTS))


def predicted_boundary(
    scene: Scene, case: str, which: str, axes: tuple[Axis, ...], implied: dict, modes_of=None
) -> TorqueBoundary | ThresholdBoundary | None:
    """The predicted passing torque along the other axis (run-ups), or None;
    ``modes_of(scene)``: the ROM's pillar modes for a point's scene."""
    if case != "runup":
        return None
    keys = [a.key for a in axes]
    if TORQUE in keys and len(axes) <= 2:
        torque = next(a for a in axes if a.key == TORQUE)
        M_top = float(max(torque.values))
        other = next((a for a in axes if a.key != TORQUE), None)
        if other is not None and not _numeric(other):
            return None
        xs = _grid(other) if other is not None else [None]
        avg, lin, which_res, res = [], [], [], ()
        for x in xs:
            sc = run_scene(scene, {other.key: x} if other is not None else {}, implied)
            a, e, i, res = _fold(sc, which, M_top, modes_of)
            avg.append(a)
            lin.append(e)
            which_res.append(i)
        return TorqueBoundary(
            torque_key=TORQUE,
            other_key=other.key if other else None,
            other_values=tuple(map(float, xs)) if other is not None else (),
            averaging=tuple(avg),
            exact_linear=tuple(lin),
            resonance=tuple(which_res),
            resonances=res,
            statement="M0 needed to pass the first capturing resonance on run-up: the A fold "
            "of Eq. 19-23 (averaging) and of the exact linear torque balance",
        )
    if len(axes) == 1 and _numeric(axes[0]):
        ax = axes[0]
        xs = _grid(ax)
        M0 = scene.drive.torque_at_zero
        avg, lin = [], []
        for x in xs:
            a, e, _, _ = _fold(run_scene(scene, {ax.key: x}, implied), which, M0, modes_of)
            avg.append(a)
            lin.append(e)
        return ThresholdBoundary(
            torque_key=TORQUE,
            other_key=ax.key,
            other_values=tuple(map(float, xs)),
            averaging=tuple(avg),
            exact_linear=tuple(lin),
            scene_torque=M0,
            threshold_averaging=crossing(xs, avg, M0),
            threshold_exact_linear=crossing(xs, lin, M0),
            statement=f"where the torque needed to pass equals the scene's M0 = {M0:g} N*m",
        )
    return None


def crossing(xs, ys, level) -> float | None:
    """The first x where ys crosses ``level`` (linear interpolation), or None."""
    pts = [(x, y) for x, y in zip(xs, ys) if y is not None]
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if (y0 - level) * (y1 - level) <= 0 and y0 != y1:
            return float(x0 + (level - y0) * (x1 - x0) / (y1 - y0))
    return None


def found_boundary(axes: tuple[Axis, ...], runs) -> tuple[FoundRow, ...] | None:
    """Per value of the other axis: the largest M0 captured and the smallest
    that passed (the study's boundary lies between them)."""
    keys = [a.key for a in axes]
    if TORQUE not in keys or len(axes) > 2:
        return None
    other = next((a.key for a in axes if a.key != TORQUE), None)
    rows: dict = {}
    for r in runs:
        x = r.params.get(other) if other else None
        rows.setdefault(repr(x), (x, []))[1].append((r.params[TORQUE], r.passed))
    out = []
    for x, cells in rows.values():
        cells.sort()
        passed = [m for m, p in cells if p]
        captured = [m for m, p in cells if p is False]
        lo = max((m for m in captured if not passed or m < min(passed)), default=None)
        hi = min(passed) if passed else None
        out.append(
            FoundRow(
                other=x,
                captured_max=lo,
                passed_min=hi,
                monotonic=not passed or all(m >= hi for m in passed) and not any(m > hi for m in captured),
            )
        )
    return tuple(out)
