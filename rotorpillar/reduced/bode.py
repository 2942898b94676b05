"""Steady unbalance response against speed (the Bode chart) of a rotor-structure model.

At a constant speed Omega (theta = Omega t) the unbalance c2 e drives the
linear structure harmonically; every coordinate is z = Re(Z e^{i theta})
(``RotorStructure.steady_state``).  Per speed: the amplitude |Z| and the
phase lag -arg(Z) (degrees, 0 ... 360) behind the unbalance's direction,
for the tip (X, relative to the ground) and the shaft deflection in X
(d.Z - e: rotor centre - tip - e cos theta).  The averaging theory's
amplitude of resonance i (Eq. 19, rotorpillar.reduced.averaging.amplitude)
is the first-order expansion of the tip's curve about omega_i.

>>> from rotorpillar.reduced.system import paper_example
>>> from rotorpillar.reduced.rotor_models import paper_model
>>> b = unbalance_response(paper_model(paper_example()), np.array([10.0, 100.0]))
>>> [round(a * 1e3, 4) for a in b.tip_amplitude]
[0.0711, 0.0075]
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..provenance import Record
from . import averaging as av
from .rotor_models import RotorStructure
from .system import Resonance


def phase_lag(Z: ArrayLike) -> NDArray[np.float64]:
    """-arg(Z) in degrees, wrapped to [0, 360): how far the response lags the unbalance."""
    lag: NDArray[np.float64] = np.mod(-np.degrees(np.angle(np.asarray(Z))), 360.0)
    return lag


class BodeCurve(Record):
    """Steady unbalance response of one model against speed."""

    model: str
    """"modal" (the ROM), "fem3d" (3D harmonic response), "paper\""""
    speeds: tuple[float, ...]
    """Omega (rad/s)"""
    tip_amplitude: tuple[float, ...]
    """|tip X| relative to the ground (m)"""
    tip_phase: tuple[float, ...]
    """tip's lag behind the unbalance (deg)"""
    shaft_amplitude: tuple[float, ...]
    """|shaft deflection X| (m)"""
    shaft_phase: tuple[float, ...]
    """shaft deflection's lag behind the unbalance (deg)"""
    peaks: tuple[tuple[float, float], ...]
    """(speed rad/s, tip amplitude m) at each local maximum of the tip's curve"""


def local_peaks(speeds: ArrayLike, amplitude: ArrayLike) -> tuple[tuple[float, float], ...]:
    """(speed, amplitude) at each interior local maximum, refined by a parabola through three points."""
    W, a = np.asarray(speeds, dtype=float), np.asarray(amplitude, dtype=float)
    out = []
    for i in range(1, len(W) - 1):
        if a[i] >= a[i - 1] and a[i] > a[i + 1]:
            x, y = W[i - 1 : i + 2], a[i - 1 : i + 2]
            c = np.polyfit(x - x[1], y, 2)
            if c[0] < 0:
                s = -c[1] / (2 * c[0])
                if abs(s) <= max(x[2] - x[1], x[1] - x[0]):
                    out.append((float(x[1] + s), float(np.polyval(c, s))))
                    continue
            out.append((float(W[i]), float(a[i])))
    return tuple(out)


def curve(model: str, speeds: ArrayLike, tip: NDArray[np.complex128], shaft: NDArray[np.complex128]) -> BodeCurve:
    """A BodeCurve from complex amplitudes of the tip and of the shaft deflection."""
    speeds = np.asarray(speeds, dtype=float)
    ta, sa = np.abs(tip), np.abs(shaft)
    return BodeCurve(
        model,
        tuple(map(float, speeds)),
        tuple(map(float, ta)),
        tuple(map(float, phase_lag(tip))),
        tuple(map(float, sa)),
        tuple(map(float, phase_lag(shaft))),
        local_peaks(speeds, ta),
    )


def unbalance_response(model: RotorStructure, speeds: ArrayLike) -> BodeCurve:
    """The model's steady unbalance response at each speed (rad/s)."""
    speeds = np.asarray(speeds, dtype=float)
    tip, shaft = np.empty(len(speeds), complex), np.empty(len(speeds), complex)
    for i, w in enumerate(speeds):
        Z, _ = model.steady_state(float(w))
        tip[i] = model.tip @ Z
        shaft[i] = model.shaft @ Z - model.eccentricity
    return curve(model.name, speeds, tip, shaft)


def speed_grid(resonances: Iterable[Resonance], top: float, n: int = 600, dense: int = 80) -> NDArray[np.float64]:
    """Speeds from 0 (excluded) to ``top``: uniform, plus ``dense`` points within
    +-5 half-power widths of each resonance below ``top`` (rad/s)."""
    grid = [np.linspace(top / n, top, n)]
    for r in resonances:
        if 0 < r.omega < top:
            width = max(5 * r.nu * r.omega, 0.01 * r.omega)
            grid.append(np.linspace(max(r.omega - width, top / n), min(r.omega + width, top), dense))
    speeds: NDArray[np.float64] = np.unique(np.concatenate(grid))
    return speeds


class AveragingCurve(Record):
    """Eq. 19's amplitude of one resonance, over the speeds near it."""

    index: int
    """the resonance's index (the quasi-normal mode)"""
    direction: str
    """"X" or "Y\""""
    omega: float
    """omega_i (rad/s)"""
    nu: float
    """relative damping nu_i = n_i / omega_i (-)"""
    speeds: tuple[float, ...]
    """Omega (rad/s), within +-30 % of omega_i"""
    amplitude: tuple[float, ...]
    """a_i (Eq. 19) (m): for an X resonance, the tip's amplitude (u_tip = 1)"""


def averaging_curves(model: RotorStructure, top: float, width: float = 0.3, n: int = 200) -> tuple[AveragingCurve, ...]:
    """Eq. 19 near each X resonance below ``top`` (rad/s), over +-``width`` of omega_i."""
    out = []
    for r in model.quasi_normal():
        if r.direction != "X" or not (0 < r.omega < top):
            continue
        W = np.linspace((1 - width) * r.omega, min((1 + width) * r.omega, top), n)
        out.append(
            AveragingCurve(
                r.index,
                r.direction,
                float(r.omega),
                float(r.nu),
                tuple(map(float, W)),
                tuple(map(float, np.asarray(av.amplitude(W, r)))),
            )
        )
    return tuple(out)


def peak_near(curve_: BodeCurve, omega: float, width: float = 0.2) -> tuple[float, float] | None:
    """The curve's highest local peak within +-``width`` of ``omega`` (speed, amplitude), or None."""
    near = [p for p in curve_.peaks if abs(p[0] - omega) <= width * omega]
    return max(near, key=lambda p: p[1]) if near else None
