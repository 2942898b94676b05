"""Averaging (Bogoliubov-Mitropolski) near the resonances: the paper's Eq. 17-24.

Near resonance i the quasi-normal coordinate x_i = a cos(q4 + xi) with
slowly varying amplitude a, phase xi and speed Omega; the stationary averaged
equations (17)-(18) give, with z = Omega/omega_i and nu_i = n_i/omega_i:

- amplitude (19):          a_i(z)  = |f_i| / (2 omega_i**2 sqrt((1 - z)**2 + nu_i**2))
- extra torque (20):       dL_i(z) = f_i g_i nu_i / (4 omega_i**2 ((1 - z)**2 + nu_i**2))
- total resistance (21):   L(Omega) = Mc(Omega) + sum_i dL_i
- stationary speeds where Md = L, stable where d(Md - L)/dOmega < 0 (23);
- the largest extra torque over the load at the resonance (24).

Two departures from the printed paper, both forced by its own Eq. 17:
Eq. 19 as printed divides by omega_i, not omega_i**2 (its a_i would be a
velocity; (17) gives a = f/(2 omega (Omega - omega ...)) with f an
acceleration); and Eq. 21 prints (1 - z**2) where Eq. 20 has (1 - z)**2.
The torque coupling g_i replaces the paper's f4 = c2 e (see
rotorpillar.reduced.system).  The printed forms stay available for
comparison.

Quasi-static run-up and run-down: with Md = M0 - s Omega and M0 slowly
varied, stationary speeds solve F(Omega) = M0 with F = L + s Omega.  A
run-up follows the lowest root; where F has a local maximum (A) the branch
ends and the speed jumps to B, the next root above; a run-down follows the
highest root down to a local minimum (D) and jumps to C (paper Figs. 3-4).

>>> from rotorpillar.reduced.system import linear_modes, paper_example
>>> r = linear_modes(paper_example(5e6, 25e3)).resonances[0]
>>> round(float(amplitude(r.omega, r)) / (abs(r.forcing) / (2 * r.omega**2 * r.nu)), 12)
1.0
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..provenance import Record

#: A speed or an array of speeds (rad/s), and what the closed forms give for it.
Speeds = float | NDArray[np.float64]


class Resonance(Protocol):
    """What the averaging theory reads of a resonance: reduced.system.Resonance, or the
    record analyze.json holds of it (analysis.results.ResonanceAnalysis)."""

    @property
    def index(self) -> int:
        """i, from 1"""

    @property
    def omega(self) -> float:
        """omega_i (rad/s)"""

    @property
    def forcing(self) -> float:
        """f_i (m/s**2)"""

    @property
    def coupling(self) -> float:
        """g_i (N)"""

    @property
    def two_n(self) -> float:
        """2 n_i (1/s)"""

    @property
    def nu(self) -> float:
        """n_i / omega_i (-)"""

    @property
    def modal_mass(self) -> float:
        """I_i (kg)"""


# --------------------------------------------------------------------------
# Per-resonance closed forms


def amplitude(Omega: Speeds, r: Resonance) -> Speeds:
    """Eq. 19: a_i at speed Omega, with its omega_i**2 restored (m)."""
    z = np.asarray(Omega, dtype=float) / r.omega
    with np.errstate(divide="ignore"):  # undamped (nu = 0): unbounded at z = 1, as it is
        a: Speeds = abs(r.forcing) / (2 * r.omega**2 * np.sqrt((1 - z) ** 2 + r.nu**2))
    return a


def amplitude_as_printed(Omega: Speeds, r: Resonance) -> Speeds:
    """The paper's Eq. 19 exactly as printed: f_i / (2 omega_i sqrt(...)) (m/s, not m)."""
    return amplitude(Omega, r) * r.omega


def amplitude_linear(Omega: Speeds, r: Resonance) -> Speeds:
    """Exact steady amplitude of x'' + 2n x' + omega**2 x = f cos(Omega t) (m).

    The averaging result (Eq. 19) is its first-order expansion about Omega = omega.
    """
    W = np.asarray(Omega, dtype=float)
    with np.errstate(divide="ignore"):  # undamped: unbounded at Omega = omega
        a: Speeds = abs(r.forcing) / np.sqrt((r.omega**2 - W**2) ** 2 + (r.two_n * W) ** 2)
    return a


def resistance_increment(Omega: Speeds, r: Resonance) -> Speeds:
    """Eq. 20: dL_i, the averaged torque drawn by resonance i (N*m)."""
    z = np.asarray(Omega, dtype=float) / r.omega
    if r.nu == 0:  # undamped: a steady regime draws no average torque
        return np.zeros_like(z) if z.ndim else 0.0
    dL: Speeds = r.forcing * r.coupling * r.nu / (4 * r.omega**2 * ((1 - z) ** 2 + r.nu**2))
    return dL


def resistance_increment_slope(Omega: Speeds, r: Resonance) -> Speeds:
    """d(dL_i)/dOmega (N*m*s)."""
    z = np.asarray(Omega, dtype=float) / r.omega
    if r.nu == 0:
        return np.zeros_like(z) if z.ndim else 0.0
    C = r.forcing * r.coupling * r.nu / (4 * r.omega**2)
    D = (1 - z) ** 2 + r.nu**2
    slope: Speeds = 2 * C * (1 - z) / (r.omega * D**2)
    return slope


def resistance_increment_as_printed(Omega: Speeds, r: Resonance, f4: float) -> Speeds:
    """The paper's Eq. 20 with its f4 = c2 e in place of g_i (N*m)."""
    return resistance_increment(Omega, r) * f4 / r.coupling


def resistance_increment_linear(Omega: Speeds, r: Resonance) -> Speeds:
    """Exact averaged torque of the linear mode at constant Omega (N*m).

    Power balance: dL * Omega = I (2n) <x'**2> = I n a**2 Omega**2.
    """
    W = np.asarray(Omega, dtype=float)
    dL: Speeds = r.modal_mass * (r.two_n / 2) * amplitude_linear(W, r) ** 2 * W
    return dL


# --------------------------------------------------------------------------
# Drive and load


@dataclass(frozen=True)
class Characteristic:
    """Eq. 22: motor and machine torques, Md = M0 - s Omega, Mc = k Omega**2."""

    torque_at_zero: float
    """M0 (N*m)"""
    slope: float
    """s (N*m*s)"""
    load_coefficient: float
    """k (N*m*s**2)"""

    def drive(self, Omega: Speeds) -> Speeds:
        Md: Speeds = self.torque_at_zero - self.slope * np.asarray(Omega, dtype=float)
        return Md

    def load(self, Omega: Speeds) -> Speeds:
        Mc: Speeds = self.load_coefficient * np.asarray(Omega, dtype=float) ** 2
        return Mc

    def free_speed(self) -> float:
        """Speed where Md = Mc with no resonance: an upper bound of every
        stationary speed, since dL_i >= 0 (rad/s)."""
        k, s, M0 = self.load_coefficient, self.slope, self.torque_at_zero
        if k > 0:
            return (-s + math.sqrt(s * s + 4 * k * M0)) / (2 * k)
        if s > 0:
            return M0 / s
        return math.inf


def total_resistance(Omega: Speeds, load_coefficient: float, resonances: Iterable[Resonance]) -> Speeds:
    """Eq. 21: L(Omega) = Mc(Omega) + sum_i dL_i(Omega) (N*m)."""
    W = np.asarray(Omega, dtype=float)
    L: Speeds = load_coefficient * W**2 + sum(resistance_increment(W, r) for r in resonances)
    return L


def peak_resistance_ratio(r: Resonance, load_coefficient: float) -> float:
    """Eq. 24: dL_i at its peak (Omega = omega_i) over the load Mc(omega_i) = k omega_i**2 (-).

    Small (the paper's stiff shaft: 0.11) means the resonance cannot hold
    the rotor: no jump.
    """
    return float(resistance_increment(r.omega, r)) / (load_coefficient * r.omega**2)


def stability_margin(Omega: Speeds, slope: float, load_coefficient: float, resonances: Iterable[Resonance]) -> Speeds:
    """d(Md - L)/dOmega = -(s + 2 k Omega + sum_i d(dL_i)/dOmega) (N*m*s): negative where stable."""
    W = np.asarray(Omega, dtype=float)
    margin: Speeds = -(2 * load_coefficient * W + slope + sum(resistance_increment_slope(W, r) for r in resonances))
    return margin


def branch_is_stable(
    Omega: Speeds, slope: float, load_coefficient: float, resonances: Iterable[Resonance]
) -> bool | NDArray[np.bool_]:
    """Eq. 23: is the stationary regime at Omega stable, d[Md - L]/dOmega < 0?

    Omega: speed (rad/s), a number or an array; slope: the motor's s in
    Md = M0 - s Omega (N*m*s); load_coefficient: k in Mc = k Omega**2
    (N*m*s**2); resonances: the Resonance records whose dL_i make up L.
    Returns a bool (numpy bool, or a bool array for an array Omega).
    """
    return stability_margin(Omega, slope, load_coefficient, resonances) < 0


def stationary_speed_grid(resonances: Iterable[Resonance], top: float, n: int = 4000) -> NDArray[np.float64]:
    """Speeds from 0 to ``top``, dense across each resonance peak."""
    parts = [np.linspace(0.0, top, n)]
    for r in resonances:
        parts.append(r.omega * (1 + r.nu * np.linspace(-25, 25, 2001)))
    g = np.unique(np.concatenate(parts))
    speeds: NDArray[np.float64] = g[(g > 0) & (g <= top)]
    return speeds


def _roots(fun: Callable[[Speeds], Speeds], grid: NDArray[np.float64]) -> list[float]:
    vals = np.asarray(fun(grid))
    out: list[float] = []
    for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
        out.append(brentq(fun, grid[i], grid[i + 1], xtol=1e-12 * grid[i + 1]))  # a float: scipy has no stubs
    # the grid's exact zeros, by a mask (the speeds in grid order, as a loop over the pairs
    # gave them, ~1 ms on a grid of 10**4 speeds against ~3 us): a design study's predicted
    # boundary asks it ~500 times (8 x 6 run-ups of sommerfeld: 0.60-0.83 -> 0.36-0.50 s)
    out += [float(w) for w in grid[vals == 0.0]]
    return sorted(out)


# --------------------------------------------------------------------------
# Stationary regimes, stability, jumps


class Stationary(Record):
    """A stationary regime of the averaged equations (Md = L, Eq. 21-23)."""

    omega: float
    """stationary speed Omega (rad/s)"""
    stable: bool
    """d(Md - L)/dOmega < 0 there (the paper's Eq. 23)"""
    margin: float
    """d(Md - L)/dOmega (N*m*s): negative when stable"""


class Jump(Record):
    """Where a quasi-static run-up or run-down leaves its branch, and where it lands."""

    direction: str
    """"up" (A -> B, quasi-static run-up) or "down" (D -> C, run-down)"""
    omega_from: float
    """the speed the branch ends at: the fold A or D (rad/s)"""
    omega_to: float
    """the speed it jumps to: B or C (rad/s)"""
    torque_at_zero: float
    """M0 at which the jump happens (N*m)"""
    resonance: int
    """index of the nearest resonance"""


@dataclass(frozen=True)
class DriveAnalysis:
    stationary: list[Stationary]
    jumps: list[Jump]
    runup_speed: float | None
    """where a quasi-static run-up to this M0 settles: the lowest root (rad/s)"""
    rundown_speed: float | None
    """where a quasi-static run-down to this M0 settles: the highest root (rad/s)"""
    captured_index: int | None = None
    """the resonance (index) below which the run-up settles while a faster
    stable regime exists: Sommerfeld capture"""
    grid_top: float = field(default=0.0)


def analyse_drive(ch: Characteristic, resonances: Sequence[Resonance], top: float | None = None) -> DriveAnalysis:
    """Stationary speeds for this drive, their stability, and the jumps of a
    quasi-static run-up and run-down of M0 with the drive's slope."""
    omegas = [r.omega for r in resonances]
    free = ch.free_speed()
    if top is None:
        top = max(3 * max(omegas), 1.05 * free if math.isfinite(free) else 10 * max(omegas))
    grid = stationary_speed_grid(resonances, top)
    k, s = ch.load_coefficient, ch.slope

    def F(W: Speeds) -> Speeds:  # M0 on the branch
        return total_resistance(W, k, resonances) + s * W

    def dF(W: Speeds) -> Speeds:
        return -stability_margin(W, s, k, resonances)

    def nearest(W: float) -> int:
        return min(resonances, key=lambda r: abs(r.omega - W)).index

    roots = _roots(lambda W: F(W) - ch.torque_at_zero, grid)
    stationary = [
        Stationary(w, bool(branch_is_stable(w, s, k, resonances)), float(stability_margin(w, s, k, resonances)))
        for w in roots
    ]

    folds = _roots(dF, grid)
    jumps: list[Jump] = []
    for w in folds:
        level = float(F(w))
        curv = float(dF(w * (1 + 1e-6)) - dF(w * (1 - 1e-6)))

        def g(W: Speeds, level: float = level) -> Speeds:
            return F(W) - level

        if curv < 0:  # local maximum of F: end of the lower branch, A -> B
            above = [x for x in _roots(g, grid[grid > w * (1 + 1e-9)]) if x > w * (1 + 1e-7)]
            if above:
                jumps.append(Jump("up", w, above[0], level, nearest(w)))
        else:  # local minimum: end of the upper branch, D -> C
            below = [x for x in _roots(g, grid[grid < w * (1 - 1e-9)]) if x < w * (1 - 1e-7)]
            if below:
                jumps.append(Jump("down", w, below[-1], level, nearest(w)))

    runup = roots[0] if roots else None
    rundown = roots[-1] if roots else None
    captured = None
    if runup is not None and rundown is not None and rundown - runup > 1e-9 * rundown:
        faster = [r for r in resonances if r.omega > runup]
        captured = min(faster, key=lambda r: r.omega).index if faster else None
    return DriveAnalysis(stationary, jumps, runup, rundown, captured, top)


def critical_slope(load_coefficient: float, r: Resonance, top: float) -> float:
    """The largest drive slope s for which resonance i, alone, has a fold:
    max over Omega of -(2 k Omega + d(dL_i)/dOmega) (N*m*s).  Negative when
    no falling motor characteristic can cause a jump there."""
    grid = stationary_speed_grid([r], top)
    return float(np.max(-(2 * load_coefficient * grid + resistance_increment_slope(grid, r))))


def critical_eccentricity_factor(ch: Characteristic, r: Resonance, top: float) -> float:
    """The factor on the eccentricity beyond which resonance i, alone, has a
    fold with this drive's slope (dL grows as e**2)."""
    grid = stationary_speed_grid([r], top)
    slope = np.asarray(resistance_increment_slope(grid, r))
    falling = slope < 0
    if not np.any(falling):
        return math.inf
    need = (2 * ch.load_coefficient * grid[falling] + ch.slope) / (-slope[falling])
    return float(math.sqrt(np.min(need)))
