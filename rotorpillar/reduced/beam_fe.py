"""1D finite-element models of the pillar as a cantilever beam.

Two theories, each with n elements along the height (equal for a uniform
beam; for a tower of cans, a node on every joint: rotorpillar.reduced.tower),
each element's section integrated along it (Gauss-Legendre, exact for a
cone's sections):

- Euler-Bernoulli: Hermite cubic elements, consistent mass; frequency error
  falls as h**4.
- Timoshenko: linear elements for deflection w and section rotation psi,
  shear integrated at one point (selective reduced integration, free of shear
  locking), consistent mass with rotary inertia; frequency error falls as h**2.

An optional rigid body at the top (mass, and rotary inertia about the tip)
models the gondola and rotor riding on the pillar; the base is clamped or
stands on springs (``BaseSprings``: horizontal, rocking and their coupling).
Units SI.

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


@dataclass(frozen=True, eq=False)
class BeamLine:
    """A beam cut into elements: node positions and each element's section at its Gauss points.

    The uniform beam's (``BeamProperties.line``) and a tapered or stepped
    tower's (rotorpillar.reduced.tower.tower_line) are the same to the element
    code, which integrates each element's matrices by Gauss-Legendre
    quadrature (``GAUSS_POINTS``: exact for a cone's polynomial sections).
    """

    nodes: NDArray[np.float64]
    """(n + 1,) node positions from the base up (m)"""
    youngs_modulus: float
    """E (Pa)"""
    shear_modulus: float
    """G (Pa)"""
    density: float
    """rho (kg/m**3)"""
    area: NDArray[np.float64]
    """(n, q) A at each element's Gauss points (m**2)"""
    second_moment: NDArray[np.float64]
    """(n, q) I at each element's Gauss points (m**4)"""
    shear_coefficient: NDArray[np.float64]
    """(n, q) kappa at each element's Gauss points (-)"""

    @property
    def n_elements(self) -> int:
        return len(self.nodes) - 1

    @property
    def lengths(self) -> NDArray[np.float64]:
        """(n,) element lengths (m)"""
        return np.diff(self.nodes)

    @property
    def length(self) -> float:
        """H (m)"""
        return float(self.nodes[-1] - self.nodes[0])


#: Gauss-Legendre points and weights on [0, 1] of every element's integrals: 5 points
#: integrate degree 9 exactly (rho A N N of a Hermite element on a cone is degree 8).
_XG, _WG = np.polynomial.legendre.leggauss(5)  # type: ignore[no-untyped-call]  # numpy's polynomial stubs leave leggauss untyped
GAUSS_POINTS: NDArray[np.float64] = 0.5 * (np.asarray(_XG) + 1.0)
GAUSS_WEIGHTS: NDArray[np.float64] = 0.5 * np.asarray(_WG)


def uniform_line(p: BeamProperties, n_elements: int) -> BeamLine:
    """The uniform beam ``p`` cut into ``n_elements`` equal elements."""
    if n_elements < 1:
        raise ValueError("n_elements must be >= 1")
    shape = (n_elements, len(GAUSS_POINTS))
    return BeamLine(
        np.linspace(0.0, p.length, n_elements + 1),
        p.youngs_modulus,
        p.shear_modulus,
        p.density,
        np.full(shape, p.area),
        np.full(shape, p.second_moment),
        np.full(shape, p.shear_coefficient),
    )


def _line(p: BeamProperties | BeamLine, n_elements: int) -> BeamLine:
    if isinstance(p, BeamLine):
        if p.n_elements != n_elements:
            raise ValueError(f"the beam line has {p.n_elements} elements, not {n_elements}")
        return p
    return uniform_line(p, n_elements)


def _euler_elements(b: BeamLine) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(n, 4, 4) Hermite element matrices, dofs (w1, w1', w2, w2'): k = int EI N'' N''^T, m = int rho A N N^T."""
    L = b.lengths[:, None]
    s = GAUSS_POINTS[None, :]
    N = np.stack(
        np.broadcast_arrays(1 - 3 * s**2 + 2 * s**3, L * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3, L * (s**3 - s**2))
    )
    B = np.stack(np.broadcast_arrays((-6 + 12 * s) / L**2, (-4 + 6 * s) / L, (6 - 12 * s) / L**2, (-2 + 6 * s) / L))
    wL = GAUSS_WEIGHTS[None, :] * L
    EI = b.youngs_modulus * b.second_moment
    k = np.einsum("eq,ieq,jeq->eij", wL * EI, B, B)
    m = np.einsum("eq,ieq,jeq->eij", wL * b.density * b.area, N, N)
    return k, m


def _timoshenko_elements(b: BeamLine) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(n, 4, 4) linear Timoshenko element matrices, dofs (w1, psi1, w2, psi2).

    Bending and inertia integrated exactly; shear at one point, the element's
    midpoint, with the element's mean kappa G A (selective reduced integration,
    free of shear locking)."""
    n = b.n_elements
    L = b.lengths
    EI = b.youngs_modulus * (b.second_moment @ GAUSS_WEIGHTS)
    kGA = b.shear_modulus * ((b.shear_coefficient * b.area) @ GAUSS_WEIGHTS)
    k = np.zeros((n, 4, 4))
    k[:, 1, 1] = k[:, 3, 3] = EI / L
    k[:, 1, 3] = k[:, 3, 1] = -EI / L
    bs = np.stack([-1 / L, np.full(n, -0.5), 1 / L, np.full(n, -0.5)], axis=1)  # shear strain at the midpoint
    k += (kGA * L)[:, None, None] * bs[:, :, None] * bs[:, None, :]
    s = GAUSS_POINTS
    lin = np.stack([1 - s, s])  # (2, q)
    wL = GAUSS_WEIGHTS[None, :] * L[:, None]
    mw = np.einsum("eq,iq,jq->eij", wL * b.density * b.area, lin, lin)
    mr = np.einsum("eq,iq,jq->eij", wL * b.density * b.second_moment, lin, lin)
    m = np.zeros((n, 4, 4))
    m[:, 0::2, 0::2] = mw
    m[:, 1::2, 1::2] = mr
    return k, m


def element_matrices(b: BeamLine, theory: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(n, 4, 4) stiffness and mass of every element of ``b`` in ``theory``."""
    if theory not in THEORIES:
        raise ValueError(f"theory must be one of {THEORIES}")
    return (_euler_elements if theory == "euler" else _timoshenko_elements)(b)


@dataclass(frozen=True)
class BaseSprings:
    """The beam's base on springs against the ground, in the plane of bending."""

    horizontal: float
    """K_H, base force per unit base displacement (N/m)"""
    rocking: float
    """K_R, base moment per unit base rotation (N*m/rad)"""
    coupling: float = 0.0
    """K_HR, base force per unit base rotation and moment per unit displacement (N/rad)"""

    def matrix(self) -> NDArray[np.float64]:
        """[[K_H, K_HR], [K_HR, K_R]] on (w, psi) of the base node."""
        return np.array([[self.horizontal, self.coupling], [self.coupling, self.rocking]])


def first_free_dof(base: BaseSprings | None) -> int:
    """Index of the first unknown among the node dofs (w, psi per node from the base):
    2 for the clamped base (its dofs removed), 0 on springs."""
    return 2 if base is None else 0


def assemble(
    p: BeamProperties | BeamLine,
    n_elements: int,
    theory: str,
    tip_mass: float = 0.0,
    tip_inertia: float = 0.0,
    base: BaseSprings | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Global K and M of the beam: clamped at its base (base dofs removed) or, with
    ``base``, on springs (every node's dofs kept, the springs on the base node's)."""
    if n_elements < 1:
        raise ValueError("n_elements must be >= 1")
    ke, me = element_matrices(_line(p, n_elements), theory)
    n = 2 * (n_elements + 1)
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for e in range(n_elements):
        s = slice(2 * e, 2 * e + 4)
        K[s, s] += ke[e]
        M[s, s] += me[e]
    M[-2, -2] += tip_mass
    M[-1, -1] += tip_inertia
    if base is not None:
        K[:2, :2] += base.matrix()
    f = first_free_dof(base)
    return K[f:, f:], M[f:, f:]


def beam_modes(
    p: BeamProperties | BeamLine,
    n_elements: int,
    theory: str = "euler",
    n_modes: int = 4,
    tip_mass: float = 0.0,
    tip_inertia: float = 0.0,
    base: BaseSprings | None = None,
) -> BeamModes:
    """The lowest ``n_modes`` bending modes of the cantilever (on ``base`` springs if given)."""
    K, M = assemble(p, n_elements, theory, tip_mass, tip_inertia, base)
    k = min(n_modes, K.shape[0])
    # K's condition number grows as n**4: solving M v = mu K v for the largest
    # mu = 1/omega**2 (the inverse iteration's view) keeps the lowest modes
    # accurate on fine meshes, where K v = lam M v loses them to round-off.
    n = K.shape[0]
    mu, vec = eigh(M, K, subset_by_index=[n - k, n - 1])
    lam, vec = 1.0 / mu[::-1], vec[:, ::-1]
    f = first_free_dof(base)
    full = np.zeros((K.shape[0] + f, k))
    full[f:] = vec
    x = _line(p, n_elements).nodes
    # sign convention: positive tip deflection
    full *= np.sign(full[-2])
    return BeamModes(np.sqrt(lam), x, full[0::2], full[1::2], K.shape[0])


def section_forces(
    p: BeamProperties | BeamLine, n_elements: int, theory: str, u: NDArray[np.float64]
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
    >>> (np.round(V, 6) + 0.0).tolist(), (np.round(M, 6) + 0.0).tolist()  # + 0.0: no -0.0
    ([1000.0, 1000.0, 1000.0, 1000.0, 1000.0], [20000.0, 15000.0, 10000.0, 5000.0, 0.0])
    """
    u = np.asarray(u, dtype=float)
    if u.shape[0] != 2 * (n_elements + 1):
        raise ValueError(f"u must have 2 (n_elements + 1) = {2 * (n_elements + 1)} rows")
    ke, _ = element_matrices(_line(p, n_elements), theory)
    ue = np.stack([u[2 * e : 2 * e + 4] for e in range(n_elements)])  # (n_el, 4, ...)
    f = np.einsum("eij,ej...->ei...", ke, ue)
    below = np.zeros((n_elements + 1, 2) + u.shape[1:])  # from the element below
    above = np.zeros_like(below)  # from the element above
    below[1:] = f[:, 2:4]
    above[:-1] = -f[:, 0:2]
    mean = 0.5 * (below + above)
    mean[0], mean[-1] = above[0], below[-1]
    return mean[:, 0], mean[:, 1]
