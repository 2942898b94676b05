"""1D finite elements on a line of elements with their own sections: bending, torsion, axial.

Each element takes its constants from rotorpillar.reduced.beam_sections
(one row per element), so a tapered or stepped tube changes the arrays,
not this code.  Three kinds of line, clamped at the base:

- bending (dofs (w, psi) per node: the deflection and the section's
  rotation in the plane, psi = dw/dz for Euler-Bernoulli): Hermite cubics
  (``euler``), or linear w and psi with one-point shear (``timoshenko``,
  free of shear locking, rotary inertia rho I in the mass), as
  rotorpillar.reduced.beam_fe;
- torsion (the section's rotation about the axis): linear elements,
  stiffness G J_t / L, consistent mass rho I_p L / 6 [[2, 1], [1, 2]]
  (Saint-Venant torsion, no warping: exact for a round tube);
- axial (the section's displacement along the axis): linear elements,
  E A / L and rho A L / 6 [[2, 1], [1, 2]].

``line_matrices`` assembles K and M with the base dofs removed;
``line_resultants`` gives, at every node, the generalised force the part
above exerts on the part below, from the elements' end forces K_e u_e.

>>> from rotorpillar.scene import load_scene
>>> from rotorpillar.reduced.beam_sections import tube_sections
>>> s = tube_sections(load_scene("paper").pillar, 20)
>>> K, M = line_matrices(s, "torsion")
>>> f = np.zeros(K.shape[0]); f[-1] = 1e3
>>> N = line_resultants(s, "torsion", np.r_[0.0, np.linalg.solve(K, f)])
>>> np.allclose(N, 1e3)
True
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .beam_sections import BeamSections

#: Bending theories, and the kinds of line.
BENDING_THEORIES = ("euler", "timoshenko")
LINES = ("euler", "timoshenko", "torsion", "axial")

Matrix = NDArray[np.float64]


def bending_element(EI: float, kGA: float, rhoA: float, rhoI: float, L: float, theory: str) -> tuple[Matrix, Matrix]:
    """(k, m) of one bending element, dofs (w1, psi1, w2, psi2)."""
    if theory == "euler":
        k = (
            EI
            / L**3
            * np.array(
                [
                    [12, 6 * L, -12, 6 * L],
                    [6 * L, 4 * L**2, -6 * L, 2 * L**2],
                    [-12, -6 * L, 12, -6 * L],
                    [6 * L, 2 * L**2, -6 * L, 4 * L**2],
                ]
            )
        )
        m = (
            rhoA
            * L
            / 420
            * np.array(
                [
                    [156, 22 * L, 54, -13 * L],
                    [22 * L, 4 * L**2, 13 * L, -3 * L**2],
                    [54, 13 * L, 156, -22 * L],
                    [-13 * L, -3 * L**2, -22 * L, 4 * L**2],
                ]
            )
        )
        return k, m
    if theory != "timoshenko":
        raise ValueError(f"theory must be one of {BENDING_THEORIES}")
    k = np.zeros((4, 4))
    k[np.ix_([1, 3], [1, 3])] = EI / L * np.array([[1, -1], [-1, 1]])
    b = np.array([-1 / L, -0.5, 1 / L, -0.5])  # the shear strain w' - psi at the midpoint
    k += kGA * L * np.outer(b, b)
    lin = L / 6 * np.array([[2.0, 1.0], [1.0, 2.0]])
    m = np.zeros((4, 4))
    m[np.ix_([0, 2], [0, 2])] = rhoA * lin
    m[np.ix_([1, 3], [1, 3])] = rhoI * lin
    return k, m


def bar_element(stiffness: float, inertia: float, L: float) -> tuple[Matrix, Matrix]:
    """(k, m) of a linear bar element: stiffness * [[1, -1], [-1, 1]] / L and
    inertia * L / 6 [[2, 1], [1, 2]] (torsion: G J_t and rho I_p; axial: E A and rho A)."""
    return stiffness / L * np.array([[1.0, -1.0], [-1.0, 1.0]]), inertia * L / 6 * np.array([[2.0, 1.0], [1.0, 2.0]])


def dofs_per_node(line: str) -> int:
    if line not in LINES:
        raise ValueError(f"line must be one of {LINES}")
    return 2 if line in BENDING_THEORIES else 1


def element_matrices(s: BeamSections, line: str) -> list[tuple[Matrix, Matrix]]:
    """(k_e, m_e) of every element of the line, from its own section."""
    out = []
    for e in range(s.count):
        L = float(s.length[e])
        if line in BENDING_THEORIES:
            EI = float(s.youngs_modulus[e] * s.second_moment[e])
            kGA = float(s.shear_coefficient[e] * s.shear_modulus[e] * s.area[e])
            out.append(
                bending_element(
                    EI, kGA, float(s.density[e] * s.area[e]), float(s.density[e] * s.second_moment[e]), L, line
                )
            )
        elif line == "torsion":
            out.append(
                bar_element(
                    float(s.shear_modulus[e] * s.torsion_constant[e]), float(s.density[e] * s.polar_moment[e]), L
                )
            )
        elif line == "axial":
            out.append(bar_element(float(s.youngs_modulus[e] * s.area[e]), float(s.density[e] * s.area[e]), L))
        else:
            raise ValueError(f"line must be one of {LINES}")
    return out


def line_matrices(s: BeamSections, line: str) -> tuple[Matrix, Matrix]:
    """Global K and M of the clamped-free line (the base node's dofs removed), the top
    node's dofs last."""
    p = dofs_per_node(line)
    n = p * (s.count + 1)
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for e, (ke, me) in enumerate(element_matrices(s, line)):
        sl = slice(p * e, p * e + 2 * p)
        K[sl, sl] += ke
        M[sl, sl] += me
    return K[p:, p:], M[p:, p:]


def line_resultants(s: BeamSections, line: str, u: NDArray[np.float64]) -> NDArray[np.float64]:
    """At each node (base first), what the part above exerts on the part below.

    ``u`` holds the line's dofs at every node, base included: shape (p (n + 1),)
    or (p (n + 1), k) for k fields.  Returns (n + 1, p) or (n + 1, p, k): for a
    bending line (shear V, moment M) with V = P and M = P (H - z) for a tip load P
    along +w; for torsion the torque, for an axial line the normal force
    (tension positive).  An element's end forces f = K_e u_e are what its nodes
    exert on it: the element above a node gives -f at its lower node, the element
    below +f at its upper node; they differ by the node's inertia, and an inner
    node takes their mean (static tip loads are carried exactly).
    """
    p = dofs_per_node(line)
    u = np.asarray(u, dtype=float)
    if u.shape[0] != p * (s.count + 1):
        raise ValueError(f"u must have {p * (s.count + 1)} rows")
    tail = u.shape[1:]
    below = np.zeros((s.count + 1, p) + tail)
    above = np.zeros_like(below)
    for e, (ke, _) in enumerate(element_matrices(s, line)):
        f = np.tensordot(ke, u[p * e : p * e + 2 * p], axes=(1, 0))
        below[e + 1] = f[p:]
        above[e] = -f[:p]
    mean = 0.5 * (below + above)
    mean[0], mean[-1] = above[0], below[-1]
    return mean
