"""What a mode of the tube is, read from its shape (numpy only).

The wall displacement is written in cylindrical components (u_r, u_theta,
u_z) and each ring of nodes (one height z, one radius r) is Fourier
analysed around the circumference.  The share of the mode's (z-weighted)
squared displacement in each circumferential harmonic n names it:

=============  ==================================================================
kind           shape
=============  ==================================================================
bending_x      n = 1, the sections translate in x (the paper's X, the rotor plane)
bending_y      n = 1, the sections translate in y (normal to the rotor plane)
ovalling       n >= 2: shell mode of the wall, ``n_circumferential`` = n waves
               around (n = 2 proper ovalling, n >= 3 lobed)
torsion        n = 0, u_theta dominant: the sections turn about the tube axis
axial          n = 0, u_z dominant: the tube stretches along its axis
breathing      n = 0, u_r dominant: the wall swells uniformly
other          no harmonic holds half of the mode (a mixed or unresolved shape)
=============  ==================================================================

``n_axial`` counts the sign changes of the mode's profile along the height
(base excluded): 0 for the first cantilever bending mode, 1 for the second,
and for shell modes the number of nodal circles between base and top.

Degenerate pairs (equal frequencies by the tube's symmetry: the two bending
directions, the cos/sin phases of a shell mode) come out of the eigensolver
as arbitrary combinations; :func:`align_pair` rotates them, M-orthonormality
kept, into the x/y (or cos/sin) pair.

>>> xyz, u = bending_example()
>>> describe_mode(xyz, u).kind, describe_mode(xyz, u).n_axial
('bending_x', 0)
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

#: Highest circumferential harmonic analysed.
N_MAX = 12
#: A harmonic holding less than this share of the mode leaves it "other".
DOMINANT_SHARE = 0.5
#: Profile values below this fraction of the maximum count as zero when the
#: sign changes along the height are counted.
PROFILE_ZERO = 2e-2
KINDS = ("bending_x", "bending_y", "ovalling", "torsion", "axial", "breathing", "other")


@dataclass(frozen=True)
class Rings:
    """The nodes of the tube grouped into rings (one z, one r), with weights."""

    r: np.ndarray
    theta: np.ndarray
    z: np.ndarray
    ring: np.ndarray
    """ring index of each node"""
    ring_z: np.ndarray
    """height of each ring (m)"""
    ring_weight: np.ndarray
    """weight of one node of each ring: the length its ring stands for over its nodes (m)"""
    levels: np.ndarray
    """the distinct heights, ascending (m)"""
    level_of_ring: np.ndarray
    """level index of each ring"""
    top: np.ndarray
    """mask of the nodes on the top section"""

    # Computed once per mesh, not once per mode: a modal run describes and aligns dozens
    # of modes on the same rings (the paper's loaded tube: 172 calls, 2.7 s of 3.9 s were
    # these two).  cached_property writes the instance's __dict__, which a frozen
    # dataclass allows.
    @functools.cached_property
    def phases(self) -> np.ndarray:
        """e^{-i n theta} at every node for n = 0 .. N_MAX, shape (nodes, N_MAX + 1)."""
        return np.exp(-1j * np.outer(self.theta, np.arange(N_MAX + 1)))

    @functools.cached_property
    def members(self):
        """The sparse (rings, nodes) matrix that sums a nodal quantity over each ring."""
        from scipy.sparse import csr_matrix

        n = len(self.ring)
        return csr_matrix((np.ones(n), (self.ring, np.arange(n))), shape=(self.ring_z.size, n))


def rings_of(xyz: np.ndarray, height: float | None = None) -> Rings:
    """Group tube nodes by (z, r); weight each ring by the length it stands for."""
    x, y, z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    r, theta = np.hypot(x, y), np.arctan2(y, x)
    H = float(z.max()) if height is None else height
    scale = max(H, float(r.max()))
    key = np.round(np.stack([z, r], axis=1) / (1e-7 * scale)).astype(np.int64)
    uniq, ring = np.unique(key, axis=0, return_inverse=True)
    ring = ring.ravel()
    ring_z = uniq[:, 0] * 1e-7 * scale
    levels, level_of_ring = np.unique(uniq[:, 0], return_inverse=True)
    level_of_ring = level_of_ring.ravel()
    levels = levels * 1e-7 * scale
    # Trapezoid weights along z: a graded mesh must not over-weight the base.
    dz = np.diff(levels)
    wz = np.zeros(len(levels))
    wz[:-1] += dz / 2
    wz[1:] += dz / 2
    if len(levels) == 1:
        wz[:] = 1.0
    count = np.bincount(ring)
    radial_count = np.bincount(level_of_ring)  # rings per level
    ring_weight = wz[level_of_ring] / radial_count[level_of_ring] / count
    top = np.isclose(z, levels[-1], atol=1e-7 * scale)
    return Rings(r, theta, z, ring, ring_z, ring_weight, levels, level_of_ring, top)


def cylindrical(rings: Rings, u: np.ndarray) -> np.ndarray:
    """(u_r, u_theta, u_z) at every node, shape (n, 3)."""
    c, s = np.cos(rings.theta), np.sin(rings.theta)
    return np.stack([c * u[:, 0] + s * u[:, 1], -s * u[:, 0] + c * u[:, 1], u[:, 2]], axis=1)


def ring_harmonics(rings: Rings, ucyl: np.ndarray, n_max: int = N_MAX) -> np.ndarray:
    """Complex coefficients c[ring, n, component] = sum over the ring of u e^{-i n theta}."""
    if n_max <= N_MAX:
        phase = rings.phases[:, : n_max + 1]
    else:
        phase = np.exp(-1j * np.outer(rings.theta, np.arange(n_max + 1)))
    terms = (phase[:, :, None] * ucyl[:, None, :]).reshape(len(ucyl), -1)
    return (rings.members @ terms).reshape(rings.ring_z.size, n_max + 1, 3)


def harmonic_shares(rings: Rings, ucyl: np.ndarray, n_max: int = N_MAX) -> np.ndarray:
    """share[n, component]: the weighted squared displacement in harmonic n (sums to <= 1).

    Parseval on K equally spaced nodes: sum u**2 = (|c_0|**2 + 2 sum_n |c_n|**2) / K.
    """
    c = ring_harmonics(rings, ucyl, n_max)
    count = np.bincount(rings.ring).astype(float)
    factor = np.where(np.arange(n_max + 1) == 0, 1.0, 2.0)
    e = np.abs(c) ** 2 * (rings.ring_weight / count)[:, None, None] * factor[None, :, None]
    total = np.sum(rings.ring_weight[rings.ring] * np.sum(ucyl**2, axis=1))
    return e.sum(axis=0) / total if total > 0 else np.zeros((n_max + 1, 3))


def _sign_changes(profile: np.ndarray) -> int:
    p = np.asarray(profile, dtype=float)
    big = np.abs(p) > PROFILE_ZERO * np.max(np.abs(p)) if p.size and np.max(np.abs(p)) > 0 else []
    s = np.sign(p[big]) if len(big) else np.array([])
    return int(np.count_nonzero(s[1:] != s[:-1])) if s.size > 1 else 0


def level_mean(rings: Rings, values: np.ndarray) -> np.ndarray:
    """Mean of a nodal quantity over each height level (ascending z)."""
    level = rings.level_of_ring[rings.ring]
    return np.bincount(level, weights=values, minlength=rings.levels.size) / np.bincount(
        level, minlength=rings.levels.size
    )


@dataclass(frozen=True)
class ModeDescription:
    """What a mode is (see the module docstring for the kinds)."""

    kind: str
    n_circumferential: int | None
    n_axial: int | None
    share: float
    """share of the mode in its dominant harmonic (-)"""
    tip: tuple
    """mean (u_x, u_y) of the top section"""
    max_abs: float
    """max |u| over the nodes"""


def describe_mode(
    xyz: np.ndarray | None, u: np.ndarray, rings: Rings | None = None, n_max: int = N_MAX
) -> ModeDescription:
    """Kind, circumferential and axial wave numbers of one mode shape u (n, 3).

    ``xyz`` (n, 3) the nodes, or None with their ``rings``; ``n_max``: the highest
    circumferential harmonic analysed."""
    if rings is None:
        if xyz is None:
            raise ValueError("describe_mode: give the nodes xyz or their rings")
        rings = rings_of(xyz)
    ucyl = cylindrical(rings, u)
    shares = harmonic_shares(rings, ucyl, n_max)
    per_n = shares.sum(axis=1)
    n = int(np.argmax(per_n))
    tip = (float(np.mean(u[rings.top, 0])), float(np.mean(u[rings.top, 1])))
    max_abs = float(np.max(np.linalg.norm(u, axis=1)))
    if per_n[n] < DOMINANT_SHARE:
        return ModeDescription("other", None, None, float(per_n[n]), tip, max_abs)
    if n == 1:
        ux, uy = level_mean(rings, u[:, 0]), level_mean(rings, u[:, 1])
        along_x = np.sum(ux**2) >= np.sum(uy**2)
        kind = "bending_x" if along_x else "bending_y"
        return ModeDescription(kind, 1, _sign_changes(ux if along_x else uy), float(per_n[n]), tip, max_abs)
    if n == 0:
        comp = int(np.argmax(shares[0]))
        kind = ("breathing", "torsion", "axial")[comp]
        return ModeDescription(kind, 0, _sign_changes(level_mean(rings, ucyl[:, comp])), float(per_n[n]), tip, max_abs)
    c = ring_harmonics(rings, ucyl, n)[:, n, 0]  # u_r coefficient per ring
    k = int(np.argmax(np.abs(c)))
    along = np.real(c * np.exp(-1j * np.angle(c[k])))  # in phase with the largest ring
    level = rings.level_of_ring
    profile = np.bincount(level, weights=along, minlength=rings.levels.size) / np.bincount(
        level, minlength=rings.levels.size
    )
    return ModeDescription("ovalling", n, _sign_changes(profile), float(per_n[n]), tip, max_abs)


def pair_coefficients(rings: Rings, u1: np.ndarray, u2: np.ndarray, n: int) -> np.ndarray:
    """The 2x2 rotation taking a degenerate pair (u1, u2) to its aligned pair.

    n = 1: the first of the new pair moves the top section along x only, the
    second along y.  n >= 2: the first has u_r ~ cos(n theta), the second
    ~ sin(n theta), at the ring where the pair moves most.  Returns R with
    [v1, v2] = [u1, u2] @ R (an orthogonal matrix, so M-orthonormality holds).
    """
    if n == 1:
        a = np.array([np.mean(u1[rings.top, 0]), np.mean(u2[rings.top, 0])])
        b = np.array([np.mean(u1[rings.top, 1]), np.mean(u2[rings.top, 1])])
    else:
        c1 = ring_harmonics(rings, cylindrical(rings, u1), n)[:, n, 0]
        c2 = ring_harmonics(rings, cylindrical(rings, u2), n)[:, n, 0]
        k = int(np.argmax(np.abs(c1) ** 2 + np.abs(c2) ** 2))
        a = np.array([c1[k].real, c2[k].real])
        b = np.array([-c1[k].imag, -c2[k].imag])
    # v1 = (b2 u1 - b1 u2)/|b| has no y (sin) part; v2 = (b1 u1 + b2 u2)/|b|.
    nb = np.hypot(*b)
    if nb < 1e-14 * max(np.hypot(*a), 1e-300):
        return np.eye(2)
    R = np.array([[b[1], b[0]], [-b[0], b[1]]]) / nb
    v1a = a @ R[:, 0]
    if v1a < 0:
        R[:, 0] *= -1
    return R


def bending_example(n_around: int = 16, n_levels: int = 11, height: float = 10.0):
    """Nodes of a thin tube and its first cantilever bending shape in x (a doctest factory)."""
    th = 2 * np.pi * np.arange(n_around) / n_around
    z = np.linspace(0, height, n_levels)
    T, Z = np.meshgrid(th, z)
    xyz = np.stack([np.cos(T).ravel(), np.sin(T).ravel(), Z.ravel()], axis=1)
    w = (Z.ravel() / height) ** 2
    u = np.stack([w, 0 * w, -2 * np.cos(T).ravel() * Z.ravel() / height**2 * 0.1], axis=1)
    return xyz, u
