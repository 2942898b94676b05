"""What an animation's frames show, apart from drawing them: the pillar's
motion, the frames' times and the scales.

The pillar's elastic displacement is the superposition of its 3D mode
shapes, u(x, t) = sum_k q_k(t) phi_k(x), with phi_k the first bending modes
of ``modes_top.vtu`` (unit tip: q_k is the tip displacement of mode k, m).
A run of the paper's model has no modal coordinates: then the tube is
deformed by its tip displacement (tip_x - ground_x) times the first bending
mode, and without a VTU by the Euler-Bernoulli cantilever shape
(``pillar_motion``).  ``frame_times`` samples the run uniformly or
time-warped into the passage through resonance; ``exaggeration`` is the
elastic deflection's factor; ``rotor_orbit`` the rotor's centre about the
pillar top.  No plotting library: rotorpillar.postprocess.animation draws
and writes the frames.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .geometry import ModeSet, bending_columns
from .modeshapes import BEAM_TARGET, nice_factor
from .readers import Simulation

MAX_FRAMES = 180


@dataclass(frozen=True)
class PillarMotion:
    """What moves the tube: coefficients times shapes, plus the ground."""

    t: np.ndarray
    """times (s), n_t"""
    coefficients: np.ndarray
    """n_t x k: q_k(t), the tip displacement of each shape (m)"""
    shapes: list
    """k arrays n_points x 3, unit tip"""
    ground_x: np.ndarray
    """n_t ground displacement along the paper's X (m)"""
    source: str
    """how the coefficients were obtained, for the screen and the report"""


def pillar_motion(sim: Simulation, modeset: ModeSet) -> PillarMotion:
    """Match a simulation's modal coordinates to the mode shapes of ``modeset``.

    ``modal_coordinates`` column k goes with the k-th bending mode in the
    paper's X (no run's JSON names its modes otherwise); without them, the elastic tip displacement tip_x - ground_x drives the
    first such mode.
    """
    t = sim.arrays.t
    if t is None:
        raise ValueError(f"simulate_{sim.case}.npz has no t")
    n = len(t)
    ground = sim.arrays.ground_x
    ground = np.zeros(n) if ground is None else ground
    q = sim.arrays.modal_coordinates
    if q is not None:
        q = q.reshape(n, -1)
        cols = bending_columns(modeset.modes, q.shape[1])
        if len(cols) == q.shape[1]:
            return PillarMotion(
                t,
                q,
                [modeset.shape(i) for i in cols],
                ground,
                f"modal coordinates x {q.shape[1]} bending mode(s) of the 3D model",
            )
    tip = sim.arrays.tip_x
    if tip is None:
        raise ValueError(f"simulate_{sim.case}.npz has neither modal_coordinates nor tip_x")
    cols = bending_columns(modeset.modes, 1)
    i = cols[0] if cols else 0
    what = (
        "tip_x x first bending mode of the 3D model"
        if modeset.source.endswith(".vtu")
        else "tip_x x Euler-Bernoulli cantilever shape (no 3D mode shapes)"
    )
    return PillarMotion(t, (tip - ground)[:, None], [modeset.shape(i)], ground, what)


def frame_times(t: np.ndarray, max_frames: int = MAX_FRAMES, focus=None, share: float = 0.7) -> np.ndarray:
    """Frame times over the run, at most ``max_frames`` and at most one per
    stored sample: uniform, or with ``focus`` = (t0, t1) time-warped, a
    ``share`` of the frames spread over that window (the passage through
    resonance) and the rest over the time outside it.

    >>> frame_times(np.linspace(0, 10, 1001), 5)
    array([ 0. ,  2.5,  5. ,  7.5, 10. ])
    >>> len(frame_times(np.linspace(0, 1, 3), 100))
    3
    >>> f = frame_times(np.linspace(0, 80, 20001), 100, focus=(0.2, 1.2))
    >>> len(f), int(np.sum((f >= 0.2) & (f <= 1.2)))
    (100, 70)
    """
    n = int(max(2, min(max_frames, len(t))))
    t0, t1 = float(t[0]), float(t[-1])
    if focus is None or not (t0 <= focus[0] < focus[1] <= t1) or n < 10:
        return np.linspace(t0, t1, n)
    a, b = float(focus[0]), float(focus[1])
    inside = int(round(share * n))
    rest = n - inside
    before = int(round(rest * (a - t0) / ((a - t0) + (t1 - b)))) if (a - t0) + (t1 - b) > 0 else 0
    after = rest - before
    parts = [
        np.linspace(t0, a, before, endpoint=False) if before else np.zeros(0),
        np.linspace(a, b, inside),
        np.linspace(b, t1, after + 1)[1:] if after else np.zeros(0),
    ]
    return np.concatenate(parts)


def interpolate(t: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Linear interpolation of each column of ``values`` (n_t or n_t x k) at ``at``."""
    values = np.asarray(values, dtype=float)
    if values.ndim == 1:
        return np.interp(at, t, values)
    return np.column_stack([np.interp(at, t, values[:, j]) for j in range(values.shape[1])])


def elastic_field(coefficients: np.ndarray, shapes: list) -> np.ndarray:
    """sum_k q_k phi_k at one instant (n_points x 3)."""
    out = np.zeros_like(shapes[0])
    for c, s in zip(coefficients, shapes):
        out += c * s
    return out


def exaggeration(motion: PillarMotion, height: float) -> float:
    """The factor bringing the largest elastic displacement of the run to a
    tenth of the height (as the mode-shape pictures), rounded to 1-2-5."""
    peak = np.array([np.abs(s).max() for s in motion.shapes])
    amplitude = float(np.max(np.abs(motion.coefficients) @ peak))
    return nice_factor(BEAM_TARGET * height / amplitude) if amplitude > 0 else 1.0


def rotor_orbit(sim: Simulation):
    """Rotor centre relative to the pillar top (m), or None."""
    a = sim.arrays
    rx, ry, tip = a.rotor_x, a.rotor_y, a.tip_x
    if rx is None or ry is None:
        return None
    return (rx - (tip if tip is not None else 0.0)), ry
