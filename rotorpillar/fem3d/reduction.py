"""The paper's Eq. 2 done on the 3D model's first bending mode.

Equal kinetic energy of the pillar in its first mode and of one mass at its
tip moving like the tip:  m_r = (integral of rho u.u dV) / u_tip**2, the
generalised mass of the mode normalised to unit mean tip displacement;
then c1 = m_r omega_1**2 (the spring that keeps omega_1).  Beside it, the
paper's own form: the deflection line w(z) (mean u_x of each section)
sampled along the height, m_r = sum m_i w_i**2 / w_tip**2 with the
section's mass per length, which leaves out the rotary inertia of the
sections and the motion of the wall within them.

>>> z = np.linspace(0, 1, 2001)
>>> from rotorpillar.reduced.pillar import cantilever_mode
>>> w = cantilever_mode(z)
>>> round(beam_line_tip_mass(z, w / w[-1], 1.0), 4)   # m_col / 4 for a unit beam
0.25
>>> z = np.linspace(0, 1, 21) ** 2                       # graded, 10 quadratic elements
>>> round(beam_line_tip_mass(z, cantilever_mode(z), 1.0, degree=2), 4)
0.25
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import trapezoid  # np.trapz is gone in NumPy 2

from ..errors import ComputationError


def beam_line_tip_mass(z: np.ndarray, w: np.ndarray, mass_per_length, degree: int = 1) -> float:
    """Eq. 2 on a sampled deflection line: int m_rho w**2 dz / w_tip**2 (kg).

    ``mass_per_length``: m_rho (kg/m), or a function of z giving it along a tower.
    ``degree`` 2: the samples are the nodes of quadratic elements (end,
    middle, end, ...) and w**2 is integrated exactly on each element's
    quadratic interpolant (3-point Gauss); degree 1: trapezoids.
    """
    if callable(mass_per_length):
        return _varying_tip_mass(np.asarray(z, dtype=float), np.asarray(w, dtype=float), mass_per_length, degree)
    z, w = np.asarray(z, dtype=float), np.asarray(w, dtype=float)
    if degree == 2 and len(z) % 2 == 1 and len(z) >= 3:
        z0, zm, z1 = z[:-1:2], z[1::2], z[2::2]
        w0, wm, w1 = w[:-1:2], w[1::2], w[2::2]
        total = 0.0
        for g, c in zip((-np.sqrt(0.6), 0.0, np.sqrt(0.6)), (5 / 9, 8 / 9, 5 / 9)):
            zg = (z0 + z1) / 2 + g * (z1 - z0) / 2
            # Lagrange interpolation through (z0, zm, z1) at zg
            l0 = (zg - zm) * (zg - z1) / ((z0 - zm) * (z0 - z1))
            lm = (zg - z0) * (zg - z1) / ((zm - z0) * (zm - z1))
            l1 = (zg - z0) * (zg - zm) / ((z1 - z0) * (z1 - zm))
            wg = l0 * w0 + lm * wm + l1 * w1
            total += np.sum(c * wg**2 * (z1 - z0) / 2)
    else:
        total = trapezoid(w**2, z)
    return float(mass_per_length * total / w[-1] ** 2)


def _varying_tip_mass(z: np.ndarray, w: np.ndarray, m_of, degree: int) -> float:
    """``beam_line_tip_mass`` with m_rho(z): the same rules, m_rho at the rule's points."""
    if degree == 2 and len(z) % 2 == 1 and len(z) >= 3:
        z0, zm, z1 = z[:-1:2], z[1::2], z[2::2]
        w0, wm, w1 = w[:-1:2], w[1::2], w[2::2]
        total = 0.0
        for g, c in zip((-np.sqrt(0.6), 0.0, np.sqrt(0.6)), (5 / 9, 8 / 9, 5 / 9)):
            zg = (z0 + z1) / 2 + g * (z1 - z0) / 2
            l0 = (zg - zm) * (zg - z1) / ((z0 - zm) * (z0 - z1))
            lm = (zg - z0) * (zg - z1) / ((zm - z0) * (zm - z1))
            l1 = (zg - z0) * (zg - zm) / ((z1 - z0) * (z1 - zm))
            wg = l0 * w0 + lm * wm + l1 * w1
            total += float(np.sum(c * m_of(zg) * wg**2 * (z1 - z0) / 2))
    else:
        total = float(trapezoid(m_of(z) * w**2, z))
    return float(total / w[-1] ** 2)


@dataclass(frozen=True)
class TipReduction:
    """The pillar reduced to its tip from the 3D first bending mode."""

    m_reduced: float
    """m_r by kinetic energy of the 3D mode (kg)"""
    tip_stiffness: float
    """c1 = m_r omega**2 (N/m)"""
    omega_bending: float
    """omega of the first bending mode (rad/s)"""
    m_reduced_beam_line: float
    """m_r by Eq. 2 on the sampled deflection line (kg)"""
    mode_index: int
    """index of the mode used in the result's list"""


def tip_reduction(result, pillar) -> TipReduction:
    """Eq. 2 on the 3D model: tip mass and stiffness from a bare tube's first bending_x mode."""
    from ..reduced.pillar import section_of
    from ..reduced.tower import sections_along

    i = result.index("bending_x", n_axial=0)
    if i is None:
        # a mesh too coarse to carry the section (4 x 2: its bending pair is told apart from
        # ovalling by the section's shape, which four elements around barely have)
        raise ComputationError(
            f"no first bending mode in x among the computed modes ({', '.join(result.kind)}): "
            "refine the mesh (mesh.elements_around, mesh.elements_along) or ask more modes (modal.n_modes)"
        )
    if result.normalisation[i] != "unit_tip":
        raise ComputationError("the first bending mode is not normalised to its tip")
    omega = float(result.omega[i])
    m_r = float(result.modal_mass[i])
    m_line = float("nan")
    if result.beam_line is not None and i in result.beam_line:
        z, w = result.beam_line[i]
        m_rho = (
            section_of(pillar).mass_per_length
            if pillar.is_uniform
            else (lambda zz: sections_along(pillar, zz).mass_per_length)
        )
        m_line = beam_line_tip_mass(z, w, m_rho, result.degree)
    return TipReduction(m_r, m_r * omega**2, omega, m_line, i)
