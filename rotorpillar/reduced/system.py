"""The paper's reduced rotor-pillar system: parameters, linear modes (its Eq. 5-7).

Coordinates (the paper's Eq. 4): q1 pillar tip (X), q2 and q3 rotor mass centre
(X and Y), q4 rotor angle.  In X the tip mass m_A = m_r + m* and the rotor
m_C form a two-mass chain (c1 to the ground, c2 between them); in Y the rotor
alone rides on the shaft (c2).  Units SI.

Modal vectors are scaled with u_1i = 1 (Eq. 6), so a modal amplitude is the
pillar-tip amplitude of that mode.  With this scaling, for resonance i:

- modal mass            I_i  = m_A u_1i**2 + m_C u_2i**2
- forcing (Eq. 7)  f_i  = c2 e (u_2i - u_1i) / I_i           (m/s**2)
- torque coupling       g_i  = c2 e (u_2i - u_1i)                 (N)
- damping (Eq. 7)  2n_i = (b0 u_1i**2 + b2 u_2i**2) / I_i     (1/s)
- nu_i = n_i / omega_i.

The third resonance is the rotor alone in Y: I_3 = m_C, f_3 = c2 e / m_C,
g_3 = c2 e, 2n_3 = b2 / m_C.

The paper writes the torque coupling as f4 = c2 e for every resonance.  That
is g_i only for a scaling with u_2i - u_1i = 1; the energy balance of the
rotor (power in = power dissipated in the mode) needs g_i, and the tests
check it against the integrated equations.

>>> s = paper_example()
>>> m = linear_modes(s)
>>> [round(w, 2) for w in m.omega]
[15.36, 29.11, 15.81]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..provenance import Record
from ..scene import Rotor, Shaft


class DampedMode(Record):
    """A damped natural frequency of the linear structure."""

    direction: str
    """"X" (horizontal, in the rotor's plane) or "Y" (vertical)"""
    omega: float
    """undamped natural frequency |lambda| (rad/s)"""
    damped_omega: float
    """rad/s"""
    damping_ratio: float
    """-"""


@dataclass(frozen=True)
class ReducedSystem:
    """Parameters of the paper's Eq. 4."""

    tip_mass: float
    """m_A = m_r + m*: reduced pillar mass and gondola at the tip (kg)"""
    rotor_mass: float
    """m_C (kg)"""
    rotor_inertia: float
    """J_C (kg*m**2)"""
    eccentricity: float
    """e (m)"""
    pillar_stiffness: float
    """c1 (N/m)"""
    shaft_stiffness: float
    """c2 = c3 (N/m)"""
    pillar_damping: float
    """b1 (N*s/m)"""
    shaft_damping: float
    """b2 = b3 (N*s/m)"""

    @property
    def c0(self) -> float:
        return self.pillar_stiffness + self.shaft_stiffness

    @property
    def b0(self) -> float:
        return self.pillar_damping + self.shaft_damping

    def mass_matrix(self) -> NDArray[np.float64]:
        """X-direction mass matrix of (q1, q2)."""
        return np.diag([self.tip_mass, self.rotor_mass])

    def stiffness_matrix(self) -> NDArray[np.float64]:
        """X-direction stiffness matrix of (q1, q2), as the paper's Eq. 4 has it."""
        c0, c2 = self.c0, self.shaft_stiffness
        return np.array([[c0, -c2], [-c2, c2]])

    def damping_matrix(self) -> NDArray[np.float64]:
        """X-direction damping matrix of (q1, q2) as the paper's Eq. 4 prints it:
        b0 on q1, absolute b2 on q2 and no coupling term."""
        return np.diag([self.b0, self.shaft_damping])


def reduced_system(
    rotor: Rotor,
    shaft: Shaft,
    gondola_mass: float,
    pillar_damping: float,
    tip_mass_reduced: float,
    tip_stiffness: float,
) -> ReducedSystem:
    """The paper's system for a rotor on its shaft, a gondola of ``gondola_mass`` (kg) and
    the pillar's tip reduction (m_r in kg, c1 in N/m; b1 = ``pillar_damping``, N*s/m)."""
    return ReducedSystem(
        tip_mass=tip_mass_reduced + gondola_mass,
        rotor_mass=rotor.mass,
        rotor_inertia=rotor.inertia,
        eccentricity=rotor.eccentricity,
        pillar_stiffness=tip_stiffness,
        shaft_stiffness=shaft.stiffness,
        pillar_damping=pillar_damping,
        shaft_damping=shaft.damping,
    )


def paper_example(
    shaft_stiffness: float = 0.4e6, shaft_damping: float = 11e3, pillar_damping: float = 30e3
) -> ReducedSystem:
    """The paper's turbo-generator with its stated reduction (m_r, c1)."""
    return ReducedSystem(9.7e3 + 2.3e3, 1.6e3, 100.0, 0.002, 9.6e6, shaft_stiffness, pillar_damping, shaft_damping)


def omega_pair(s: ReducedSystem) -> tuple[float, float]:
    """Eq. 5: omega_1 < omega_2 in X from the 2x2 frequency determinant.

    det [[c0 - m_A w**2, -c2], [-c2, c2 - m_C w**2]] = 0 is a quadratic in w**2:
    m_A m_C w**4 - (c0 m_C + c2 m_A) w**2 + c0 c2 - c2**2 = 0.
    """
    mA, mC, c0, c2 = s.tip_mass, s.rotor_mass, s.c0, s.shaft_stiffness
    a, b, c = mA * mC, -(c0 * mC + c2 * mA), c0 * c2 - c2**2
    disc = math.sqrt(b * b - 4 * a * c)
    # the two roots computed without cancellation
    big = (-b + disc) / (2 * a)
    small = c / (a * big)
    return math.sqrt(small), math.sqrt(big)


def omega_y(s: ReducedSystem) -> float:
    """Eq. 5 in Y: omega_3 = sqrt(c2 / m_C), the shaft's critical speed."""
    return math.sqrt(s.shaft_stiffness / s.rotor_mass)


class Resonance(Record):
    """Quasi-normal data of one resonance (the paper's Eq. 7)."""

    index: int
    """i, from 1 (-)"""
    direction: str
    """"X" (pillar and rotor) or "Y" (rotor on its shaft)"""
    omega: float
    """omega_i (rad/s)"""
    shape: tuple[float, float]
    """(u_1i, u_2i): tip and rotor amplitude, u_1i = 1 (Eq. 6); (0, 1) in Y"""
    modal_mass: float
    """I_i (kg)"""
    forcing: float
    """f_i: amplitude of the modal forcing per unit modal mass (m/s**2)"""
    coupling: float
    """g_i: torque on the rotor per unit modal amplitude and sin q4 (N)"""
    two_n: float
    """2 n_i: modal damping (1/s)"""

    @property
    def n(self) -> float:
        return self.two_n / 2

    @property
    def nu(self) -> float:
        """nu_i = n_i / omega_i (-)"""
        return self.n / self.omega


@dataclass(frozen=True)
class SystemModes:
    omega: tuple[float, float, float]
    """(omega_1, omega_2, omega_3) (rad/s)"""
    resonances: tuple[Resonance, Resonance, Resonance]


def modal_vector(s: ReducedSystem, omega: float) -> tuple[float, float]:
    """Eq. 6: (u_1i, u_2i) of the X mode at omega, tip-scaled: u_2i/u_1i = c2 / (c2 - m_C omega**2)."""
    return 1.0, s.shaft_stiffness / (s.shaft_stiffness - s.rotor_mass * omega**2)


def linear_modes(s: ReducedSystem) -> SystemModes:
    """Eq. 7: the quasi-normal coefficients (I_i, f_i, g_i, 2 n_i) of the paper's system, on its modes."""
    c2, e = s.shaft_stiffness, s.eccentricity
    res = []
    for i, w in enumerate(omega_pair(s), start=1):
        u1, u2 = modal_vector(s, w)
        I = s.tip_mass * u1**2 + s.rotor_mass * u2**2
        g = c2 * e * (u2 - u1)
        two_n = (s.b0 * u1**2 + s.shaft_damping * u2**2) / I
        res.append(Resonance(i, "X", w, (u1, u2), I, g / I, g, two_n))
    w3 = omega_y(s)
    res.append(
        Resonance(3, "Y", w3, (0.0, 1.0), s.rotor_mass, c2 * e / s.rotor_mass, c2 * e, s.shaft_damping / s.rotor_mass)
    )
    x1, x2, y = res  # two X resonances, one in Y: the shapes SystemModes states
    return SystemModes((x1.omega, x2.omega, y.omega), (x1, x2, y))
