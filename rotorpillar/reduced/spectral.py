"""The response-spectrum estimate of one output of a linear structure on a moving base.

A structure in coordinates z relative to the ground,

    M z'' + C z' + K z = b a_g,

with b the force per unit ground acceleration (b = -M r for an influence
vector r), has undamped modes K u_i = omega_i**2 M u_i.  Projected on mode i
(modal mass m_i = u_i^T M u_i) and with the modal damping's diagonal only,
zeta_i = u_i^T C u_i / (2 m_i omega_i) (the classical-damping approximation),
the modal coordinate obeys q_i'' + 2 zeta_i omega_i q_i' + omega_i**2 q_i =
(u_i . b / m_i) a_g.  The single-degree oscillator of the response spectrum,
x'' + 2 zeta omega x' + omega**2 x = -a_g, peaks at S_d(T, zeta), so an output
y = o . z (the tip's displacement) has in mode i the peak

    |p_i| S_d(T_i, zeta_i),   p_i = -(o . u_i)(u_i . b) / m_i,

p_i the output's participation: independent of how u_i is scaled; for
b = -M r the p_i of all the modes sum to o . r (the modal expansion of r).
The modes' peaks are combined by SRSS (Rosenblueth's
square root of the sum of the squares; Chopra, *Dynamics of Structures*,
4th ed., section 13.7): an estimate, not a bound.

These are the modes of the whole linear structure: for the rotor-pillar
model the coupled rotor-pillar modes (the rotor on its shaft included), not
the pillar's own.

>>> import numpy as np
>>> t = spectral_terms(np.eye(1), np.array([[4.0]]), np.array([[0.4]]), -np.ones(1), np.ones(1), lambda T, z: 0.01)
>>> round(t[0].omega, 6), round(t[0].damping_ratio, 6), round(t[0].participation, 6), srss(t)
(2.0, 0.1, 1.0, 0.01)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh


@dataclass(frozen=True)
class SpectralTerm:
    """One mode's part in the estimate (SI units)."""

    omega: float
    """undamped natural frequency omega_i (rad/s)"""
    damping_ratio: float
    """zeta_i = u_i^T C u_i / (2 m_i omega_i) (-)"""
    participation: float
    """p_i: the output's participation in mode i for a ground acceleration (-)"""
    s_d: float
    """the spectral displacement S_d(T_i, zeta_i) (m)"""

    @property
    def period(self) -> float:
        """T_i = 2 pi / omega_i (s)"""
        return 2 * math.pi / self.omega

    @property
    def contribution(self) -> float:
        """|p_i| S_d(T_i, zeta_i): the output's peak in mode i (m)"""
        return abs(self.participation) * self.s_d


def spectral_terms(
    mass: NDArray[np.float64],
    stiffness: NDArray[np.float64],
    damping: NDArray[np.float64],
    force_per_acceleration: NDArray[np.float64],
    output: NDArray[np.float64],
    spectral_displacement: Callable[[float, float], float],
) -> list[SpectralTerm]:
    """Each mode's part in the peak of ``output . z`` (see the module text), in ascending
    frequency; ``spectral_displacement(T, zeta)`` gives the record's S_d (m).  Modes of zero
    frequency (a free coordinate) carry no spectral peak and are left out."""
    M, K, C = (np.asarray(a, dtype=float) for a in (mass, stiffness, damping))
    b, o = np.asarray(force_per_acceleration, dtype=float), np.asarray(output, dtype=float)
    lam, U = eigh(K, M)
    out = []
    for i in range(len(lam)):
        if lam[i] <= 0:
            continue
        u = U[:, i]
        w = math.sqrt(lam[i])
        m = float(u @ M @ u)
        zeta = float(u @ C @ u) / (2 * m * w)
        p = -float(o @ u) * float(u @ b) / m
        out.append(SpectralTerm(w, zeta, p, float(spectral_displacement(2 * math.pi / w, zeta))))
    return out


def srss(terms: list[SpectralTerm]) -> float:
    """The square root of the sum of the modes' peaks squared (m)."""
    return math.sqrt(sum(t.contribution**2 for t in terms))
