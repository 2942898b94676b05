"""Closed forms of the pillar as a cantilever beam, and its reduction to the tip.

The tube is a uniform cantilever of height H, clamped at the base (x = 0) and
free at the top (x = H).  Euler-Bernoulli theory gives the paper's Eq. 1;
Timoshenko theory adds shear and rotary inertia, which matter a little for a
thin tube (shear coefficient of Cowper, 1966).  The reduction to one tip mass
and one spring is the paper's Eq. 2: equal kinetic energy in the first mode.

All quantities SI: m, kg, Pa, rad/s.

>>> p = tube_section(2.0, 1.96, 8.1e3)
>>> round(p.second_moment, 4), round(p.mass_per_length, 1)
(0.061, 1007.7)
>>> round(cantilever_root(1), 6)
1.875104
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache, lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import expm
from scipy.optimize import brentq

from ..scene import Pillar

#: Euler-Bernoulli cantilever: the first mode's modal mass over its tip value
#: squared, per unit beam mass, is exactly 1/4 (the paper's Eq. 2 in the limit n -> inf).
CONTINUOUS_TIP_MASS_RATIO = 0.25


@dataclass(frozen=True)
class TubeSection:
    """Cross-section of a circular tube."""

    outer_diameter: float
    """D0 (m)"""
    inner_diameter: float
    """D1 (m)"""
    density: float
    """rho (kg/m**3)"""

    @property
    def area(self) -> float:
        """A (m**2)"""
        return math.pi / 4 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> float:
        """I about a diameter (m**4)"""
        return math.pi / 64 * (self.outer_diameter**4 - self.inner_diameter**4)

    @property
    def mass_per_length(self) -> float:
        """m_rho = rho A (kg/m)"""
        return self.density * self.area

    @property
    def radius_of_gyration(self) -> float:
        """sqrt(I/A) (m)"""
        return math.sqrt(self.second_moment / self.area)

    @property
    def wall_thickness(self) -> float:
        """t (m)"""
        return (self.outer_diameter - self.inner_diameter) / 2


def tube_section(outer_diameter: float, inner_diameter: float, density: float) -> TubeSection:
    return TubeSection(outer_diameter, inner_diameter, density)


def section_of(pillar: Pillar) -> TubeSection:
    """The tube section of a scene's uniform ``[pillar]``; a tower of cans has one per height
    (rotorpillar.reduced.tower.section_at)."""
    if pillar.cans or pillar.outer_diameter is None or pillar.inner_diameter is None:
        if pillar.is_uniform:
            s = pillar.segments()[0]
            return TubeSection(s.outer_bottom, s.inner_bottom, pillar.density)
        raise ValueError("a tower of cans has a section per height: use rotorpillar.reduced.tower.section_at")
    return TubeSection(pillar.outer_diameter, pillar.inner_diameter, pillar.density)


# --------------------------------------------------------------------------
# Euler-Bernoulli cantilever


@cache
def cantilever_root(k: int) -> float:
    """k-th root beta_k*L of 1 + cos(x) cosh(x) = 0 (clamped-free beam).

    Written as cos(x) + 1/cosh(x) = 0 to keep it well scaled for large x.
    """
    if k < 1:
        raise ValueError("mode number k must be >= 1")
    guess = (2 * k - 1) * math.pi / 2
    lo, hi = (1.5, 2.5) if k == 1 else (guess - 0.3, guess + 0.3)
    return float(brentq(lambda x: math.cos(x) + 1.0 / math.cosh(x), lo, hi, xtol=1e-15))


def omega_euler_bernoulli(E: float, I: float, mass_per_length: float, H: float, k: int = 1) -> float:
    """Eq. 1: natural angular frequency of the k-th cantilever mode (rad/s)::

    omega_k = (beta_k H)**2 * sqrt(E I / (m_rho H**4))
    """
    return cantilever_root(k) ** 2 * math.sqrt(E * I / (mass_per_length * H**4))


def cantilever_mode(xi: ArrayLike, k: int = 1) -> NDArray[np.float64]:
    """Shape of the k-th Euler-Bernoulli cantilever mode at xi = x/H in [0, 1].

    Normalised so that the integral of its square over [0, 1] is 1; the tip
    value is then +-2 for every k.
    """
    b = cantilever_root(k)
    xi = np.asarray(xi, dtype=float)
    # The bounded form: cosh - sinh = exp(-x) keeps it accurate for large k.
    sigma = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    x = b * xi
    shape: NDArray[np.float64] = (np.cosh(x) - sigma * np.sinh(x)) - np.cos(x) + sigma * np.sin(x)
    return shape


def _hyperbolic_parts(xi: ArrayLike, k: int) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """(cosh x - sigma sinh x, sinh x - sigma cosh x, beta_k) at x = beta_k xi, without cancellation.

    sigma = 1 + delta with delta ~ 2 exp(-beta) (cos beta - sin beta): the two
    hyperbolic terms stay of order one where cosh x and sinh x reach 1e13 (k ~ 10).
    """
    b = cantilever_root(k)
    x = b * np.asarray(xi, dtype=float)
    delta = (math.exp(-b) + math.cos(b) - math.sin(b)) / (math.sinh(b) + math.sin(b))
    e = np.exp(-x)
    ch_minus_sh = e  # cosh x - sinh x
    sh_minus_ch = -e
    return ch_minus_sh - delta * np.sinh(x), sh_minus_ch - delta * np.cosh(x), b


def cantilever_mode_stable(xi: ArrayLike, k: int = 1) -> NDArray[np.float64]:
    """``cantilever_mode`` without the cancellation of cosh and sinh at large k (same shape)."""
    c, _, b = _hyperbolic_parts(xi, k)
    x = b * np.asarray(xi, dtype=float)
    sigma = 1 + (math.exp(-b) + math.cos(b) - math.sin(b)) / (math.sinh(b) + math.sin(b))
    out: NDArray[np.float64] = c - np.cos(x) + sigma * np.sin(x)
    return out


def cantilever_slope(xi: ArrayLike, k: int = 1) -> NDArray[np.float64]:
    """d/dxi of ``cantilever_mode`` (the same normalisation)."""
    _, s, b = _hyperbolic_parts(xi, k)
    x = b * np.asarray(xi, dtype=float)
    sigma = 1 + (math.exp(-b) + math.cos(b) - math.sin(b)) / (math.sinh(b) + math.sin(b))
    out: NDArray[np.float64] = b * (s + np.sin(x) + sigma * np.cos(x))
    return out


def cantilever_curvature(xi: ArrayLike, k: int = 1) -> NDArray[np.float64]:
    """d**2/dxi**2 of ``cantilever_mode`` (the same normalisation)."""
    c, _, b = _hyperbolic_parts(xi, k)
    x = b * np.asarray(xi, dtype=float)
    sigma = 1 + (math.exp(-b) + math.cos(b) - math.sin(b)) / (math.sinh(b) + math.sin(b))
    out: NDArray[np.float64] = b**2 * (c + np.cos(x) - sigma * np.sin(x))
    return out


# --------------------------------------------------------------------------
# Reduction to the tip, the paper's Eq. 2


def tip_mass_lumped(mass: float, n: int) -> float:
    """Eq. 2: the pillar lumped into n equal masses m_col/n at x_i = i H/n.

    m_r = sum_i m_i u_i1**2 / u_11**2 with u the first cantilever mode.  The top
    node carries a whole segment, as the paper's m_i = m_col/n reads, so m_r
    falls towards the continuous limit ``mass/4`` as n grows, as O(1/n).
    """
    if n < 1:
        raise ValueError("n must be >= 1")
    xi = np.arange(1, n + 1) / n
    u = cantilever_mode(xi)
    return float(mass / n * np.sum(u**2) / u[-1] ** 2)


def tip_mass_continuous(mass: float) -> float:
    """The paper's Eq. 2 on the continuous first mode: exactly m_col/4 (kg)."""
    return CONTINUOUS_TIP_MASS_RATIO * mass


_GAUSS: tuple[NDArray[np.float64], NDArray[np.float64]] = np.polynomial.legendre.leggauss(12)  # type: ignore[no-untyped-call]  # numpy's polynomial stubs leave leggauss untyped; exact for polynomials up to degree 23


def _integrate01(f: Callable[[NDArray[np.float64]], NDArray[np.float64]]) -> float:
    x, w = _GAUSS
    xi = 0.5 * (x + 1.0)
    return float(0.5 * np.sum(w * f(xi)))


@dataclass(frozen=True)
class RayleighReduction:
    """A tip-referred mass and stiffness from an assumed shape psi(xi), psi(1) = 1."""

    shape: str
    tip_mass: float
    """m = m_col * int psi**2 dxi (kg)"""
    tip_stiffness: float
    """k = E I / H**3 * int psi''**2 dxi (N/m)"""

    @property
    def omega(self) -> float:
        """Rayleigh's quotient, an upper bound of omega_col1 (rad/s)"""
        return math.sqrt(self.tip_stiffness / self.tip_mass)


# Static deflection shapes of a cantilever, normalised to 1 at the tip, and
# their second derivatives (in xi).
_Shape = Callable[[NDArray[np.float64]], NDArray[np.float64]]
_SHAPES: dict[str, tuple[_Shape, _Shape]] = {
    # Under its own weight (uniform load): Rayleigh's classical choice.
    "uniform_load": (lambda s: (s**4 - 4 * s**3 + 6 * s**2) / 3, lambda s: 4 * (1 - s) ** 2),
    # Under a tip load: the textbook 33/140 of the beam mass.
    "tip_load": (lambda s: (3 * s**2 - s**3) / 2, lambda s: 3 * (1 - s)),
}


def rayleigh_reduction(mass: float, E: float, I: float, H: float, shape: str = "uniform_load") -> RayleighReduction:
    """Tip mass and stiffness from a static deflection shape (Rayleigh)."""
    psi, psi2 = _SHAPES[shape]
    m = mass * _integrate01(lambda s: psi(s) ** 2)
    k = E * I / H**3 * _integrate01(lambda s: psi2(s) ** 2)
    return RayleighReduction(shape, m, k)


# --------------------------------------------------------------------------
# Timoshenko cantilever


def cowper_shear_coefficient(outer_diameter: float, inner_diameter: float, nu: float) -> float:
    """Shear coefficient kappa of a hollow circular section (Cowper, 1966).

    kappa = 6 (1+nu)(1+m**2)**2 / ((7+6nu)(1+m**2)**2 + (20+12nu) m**2), m = D1/D0;
    0.53 for a thin steel tube, 0.89 for a solid bar.
    """
    m = inner_diameter / outer_diameter
    a = (1 + m**2) ** 2
    return 6 * (1 + nu) * a / ((7 + 6 * nu) * a + (20 + 12 * nu) * m**2)


def _timoshenko_determinant(
    omega: float,
    E: float,
    G: float,
    kappa: float,
    rho: float,
    A: float,
    I: float,
    H: float,
    rotary_inertia: bool = True,
) -> float:
    """Boundary determinant of the clamped-free Timoshenko beam at omega.

    State y = [w, w', psi, psi'] obeys y' = S y with
        w''   = psi' - rho omega**2 / (kappa G) w
        psi'' = -(kappa G A / (E I)) (w' - psi) - (rho omega**2 / E) psi;
    clamped base: w = psi = 0; free top: psi' = 0 (moment) and w' - psi = 0 (shear).
    """
    rI = rho * omega**2 / E if rotary_inertia else 0.0
    S = np.array(
        [
            [0.0, 1.0, 0.0, 0.0],
            [-rho * omega**2 / (kappa * G), 0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0, 1.0],
            [0.0, -kappa * G * A / (E * I), kappa * G * A / (E * I) - rI, 0.0],
        ]
    )
    T = expm(S * H)
    # columns of T acting on the free unknowns w'(0), psi'(0)
    return float(T[3, 1] * (T[1, 3] - T[2, 3]) - T[3, 3] * (T[1, 1] - T[2, 1]))


#: lambda H beyond which the Timoshenko frequency is scaled, not solved (omega_timoshenko)
SLENDER = 100.0


@lru_cache(maxsize=512)
def omega_timoshenko(
    E: float, nu: float, kappa: float, rho: float, A: float, I: float, H: float, k: int = 1, rotary_inertia: bool = True
) -> float:
    """k-th natural angular frequency of a clamped-free Timoshenko beam (rad/s).

    Found as the k-th sign change of the boundary determinant below the
    Euler-Bernoulli value (shear and rotary inertia only lower it), then
    refined by Brent's method.

    Remembered per arguments (a pure function of them: the same float again): each
    build of a model asks it (``reduction.pillar_closed_forms``), ~9 ms a call (400
    determinants and Brent's refinement), and a study builds one per point on the same
    pillar (a design study's predicted boundary: ~130 calls, 1.2 s of its 4 s).
    """
    G = E / (2 * (1 + nu))
    m_rho = rho * A
    # The transfer matrix grows as exp(lambda H), lambda = sqrt(kappa G A/(E I)):
    # past lambda H ~ 150 its boundary determinant loses the first mode's
    # correction to cancellation (a tube of D/t = 100: (w/w_EB - 1)(lambda H)**2
    # is -2.797 at 80 and 120, -2.55 at 250, -3.20 at 299).  The shear and
    # rotary-inertia correction scales, to first order, as 1/H**2 for a given
    # section (both enter as (r/H)**2): past SLENDER it is the correction of the
    # same section at lambda H = SLENDER, times (H_SLENDER / H)**2; what that
    # leaves out changes the constant by 5e-4 from 80 to 120: below 2e-7 of omega.
    lam = math.sqrt(kappa * G * A / (E * I))
    if lam * H > SLENDER:
        short = SLENDER / lam
        w_short = omega_timoshenko(E, nu, kappa, rho, A, I, short * (1 - 1e-12), k, rotary_inertia)
        correction = w_short / omega_euler_bernoulli(E, I, m_rho, short, k) - 1
        return omega_euler_bernoulli(E, I, m_rho, H, k) * (1 + correction * (short / H) ** 2)
    w_eb = omega_euler_bernoulli(E, I, m_rho, H, k)

    def det(w: float) -> float:
        return _timoshenko_determinant(w, E, G, kappa, rho, A, I, H, rotary_inertia)

    grid = np.linspace(1e-6 * w_eb, w_eb * 1.000001, 400 * k)
    vals = np.array([det(w) for w in grid])
    changes = np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0]
    if len(changes) < k:
        raise RuntimeError("Timoshenko root not bracketed below the Euler-Bernoulli value")
    i = changes[k - 1]
    return float(brentq(det, grid[i], grid[i + 1], xtol=1e-12 * w_eb))
