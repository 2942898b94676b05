"""1D finite-element models of the pillar as a cantilever beam.

Two theories, each with n equal elements along the height:

- Euler-Bernoulli: Hermite cubic elements, consistent mass; frequency error
  falls as h**4.
- Timoshenko: linear elements for deflection w and section rotation psi,
  shear integrated at one point (selective reduced integration, free of shear
  locking), consistent mass with rotary inertia; frequency error falls as h**2.

An optional rigid body at the top (mass, and rotary inertia about the tip)
models the gondola and rotor riding on the pillar.  Units SI.

>>> m = beam_modes(BeamProperties(2.1e11, 0.3, 0.53, 8.1e3, 0.12441, 0.060972, 20.0), 20, "euler")
>>> round(m.omega[0], 2)
31.33
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

THEORIES = ("euler", "timoshenko")


@dataclass(frozen=True)
class BeamProperties:
    """A uniform beam."""

    youngs_modulus: float
    """E (Pa)"""
    poisson_ratio: float
    """nu (-)"""
    shear_coefficient: float
    """kappa (-)"""
    density: float
    """rho (kg/m**3)"""
    area: float
    """A (m**2)"""
    second_moment: float
    """I (m**4)"""
    length: float
    """H (m)"""

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2 * (1 + self.poisson_ratio))


@dataclass(frozen=True)
class BeamModes:
    """Modes of the cantilever, ascending."""

    omega: NDArray[np.float64]
    """natural angular frequencies (rad/s)"""
    x: NDArray[np.float64]
    """node heights (m)"""
    deflection: NDArray[np.float64]
    """(n_nodes, n_modes) lateral deflection, mass-normalised (kg**-0.5)"""
    rotation: NDArray[np.float64]
    """(n_nodes, n_modes) section rotation (rad per sqrt(kg))"""
    dofs: int


def _euler_element(p: BeamProperties, L: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    EI, mA = p.youngs_modulus * p.second_moment, p.density * p.area
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
        mA
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


def _timoshenko_element(p: BeamProperties, L: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    EI = p.youngs_modulus * p.second_moment
    kGA = p.shear_coefficient * p.shear_modulus * p.area
    # dof order (w1, psi1, w2, psi2)
    bend = np.zeros((4, 4))
    bend[np.ix_([1, 3], [1, 3])] = EI / L * np.array([[1, -1], [-1, 1]])
    b = np.array([-1 / L, -0.5, 1 / L, -0.5])  # shear strain at the midpoint
    k = bend + kGA * L * np.outer(b, b)
    lin = L / 6 * np.array([[2, 1], [1, 2]])
    m = np.zeros((4, 4))
    m[np.ix_([0, 2], [0, 2])] = p.density * p.area * lin
    m[np.ix_([1, 3], [1, 3])] = p.density * p.second_moment * lin
    return k, m


def assemble(
    p: BeamProperties, n_elements: int, theory: str, tip_mass: float = 0.0, tip_inertia: float = 0.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Global K and M of the clamped-free beam (base dofs removed)."""
    if theory not in THEORIES:
        raise ValueError(f"theory must be one of {THEORIES}")
    if n_elements < 1:
        raise ValueError("n_elements must be >= 1")
    L = p.length / n_elements
    ke, me = (_euler_element if theory == "euler" else _timoshenko_element)(p, L)
    n = 2 * (n_elements + 1)
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for e in range(n_elements):
        s = slice(2 * e, 2 * e + 4)
        K[s, s] += ke
        M[s, s] += me
    M[-2, -2] += tip_mass
    M[-1, -1] += tip_inertia
    return K[2:, 2:], M[2:, 2:]


def beam_modes(
    p: BeamProperties,
    n_elements: int,
    theory: str = "euler",
    n_modes: int = 4,
    tip_mass: float = 0.0,
    tip_inertia: float = 0.0,
) -> BeamModes:
    """The lowest ``n_modes`` bending modes of the cantilever."""
    K, M = assemble(p, n_elements, theory, tip_mass, tip_inertia)
    k = min(n_modes, K.shape[0])
    # K's condition number grows as n**4: solving M v = mu K v for the largest
    # mu = 1/omega**2 (the inverse iteration's view) keeps the lowest modes
    # accurate on fine meshes, where K v = lam M v loses them to round-off.
    n = K.shape[0]
    mu, vec = eigh(M, K, subset_by_index=[n - k, n - 1])
    lam, vec = 1.0 / mu[::-1], vec[:, ::-1]
    full = np.zeros((K.shape[0] + 2, k))
    full[2:] = vec
    x = np.linspace(0.0, p.length, n_elements + 1)
    # sign convention: positive tip deflection
    full *= np.sign(full[-2])
    return BeamModes(np.sqrt(lam), x, full[0::2], full[1::2], K.shape[0])


def section_forces(
    p: BeamProperties, n_elements: int, theory: str, u: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Shear V(z) and bending moment M(z) at the nodes from the element end forces K_e u_e.

    ``u`` holds (w, psi) per node from the base up, base included: shape
    (2 (n_elements + 1),) or (2 (n_elements + 1), k) for k displacement
    fields.  Returns (V, M), each (n_elements + 1,) or (n_elements + 1, k):
    the force in X (N) and the y-moment about the section's centre (N*m)
    that the part above a section exerts on the part below; a tip load P
    along +X gives V = P and M = P (H - z).  An element's end forces f = K_e
    u_e are what its nodes exert on it, so the element above a node gives
    (V, M) = -(f_w, f_psi) at its lower node and the element below +(f_w,
    f_psi) at its upper node; the two differ by the node's share of the
    inertia, and an inner node takes their mean.  Static loads at the tip
    are carried exactly (each element is in equilibrium under its end forces).

    >>> bp = BeamProperties(2.1e11, 0.3, 0.53, 8.1e3, 0.12441, 0.060972, 20.0)
    >>> K, _ = assemble(bp, 4, "timoshenko")
    >>> f = np.zeros(K.shape[0]); f[-2] = 1e3
    >>> V, M = section_forces(bp, 4, "timoshenko", np.r_[0.0, 0.0, np.linalg.solve(K, f)])
    >>> np.round(V, 6).tolist(), np.round(M, 6).tolist()
    ([1000.0, 1000.0, 1000.0, 1000.0, 1000.0], [20000.0, 15000.0, 10000.0, 5000.0, 0.0])
    """
    if theory not in THEORIES:
        raise ValueError(f"theory must be one of {THEORIES}")
    u = np.asarray(u, dtype=float)
    if u.shape[0] != 2 * (n_elements + 1):
        raise ValueError(f"u must have 2 (n_elements + 1) = {2 * (n_elements + 1)} rows")
    L = p.length / n_elements
    ke, _ = (_euler_element if theory == "euler" else _timoshenko_element)(p, L)
    ue = np.stack([u[2 * e : 2 * e + 4] for e in range(n_elements)])  # (n_el, 4, ...)
    f = np.einsum("ij,ej...->ei...", ke, ue)
    below = np.zeros((n_elements + 1, 2) + u.shape[1:])  # from the element below
    above = np.zeros_like(below)  # from the element above
    below[1:] = f[:, 2:4]
    above[:-1] = -f[:, 0:2]
    mean = 0.5 * (below + above)
    mean[0], mean[-1] = above[0], below[-1]
    return mean[:, 0], mean[:, 1]
