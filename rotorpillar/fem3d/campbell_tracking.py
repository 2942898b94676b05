"""Following a mode from speed to speed, its whirl and where the 1x line crosses it (numpy only).

- ``align_degenerate``: a cluster of equal eigenvalues (the tube's cos/sin
  shell pairs, the two bending planes where nothing on the top tells them
  apart: equal to ~1e-5) comes out of the eigen-solver as an arbitrary
  basis of its space; it is replaced by the projections of the previous
  speed's vectors onto that space, orthonormalised in their order, so each
  member keeps its identity before the modal assurance criterion (MAC)
  compares them and before the whirl is read from it;
- ``assign``: the previous speed's branches to this speed's modes, the
  assignment of largest total MAC (|u^H v|**2 of unit vectors; scipy's
  linear_sum_assignment), a pair kept only above ``MIN_MAC``;
- ``whirl``: from the rotor's motion in the plane normal to the spin axis:
  its centre's orbit (in-plane x, vertical z) and its spin axis' (-phi_z,
  phi_x), weighted by m_C and I_d: the sign of the whirl's angular momentum
  about the spin axis, forward when it turns as the unbalance does (from +x
  towards +z, rotorpillar.fem3d.rotor_spatial.whirl_direction); "none" when
  the orbit is a line, the ratio 2 |turn| / size below ``WHIRL_TOLERANCE``
  (1 for a circle; the spatial ROM's rotorpillar.reduced.spatial_linear, the
  same rule), or when the rotor hardly moves (``ROTOR_SHARE`` of the mode's
  x^H M x);
- ``crossings``: where Omega equals a branch's frequency, the root of
  f(Omega) - Omega by linear interpolation between two speeds of the
  diagram (the branch tracked, damped: Im(s)).

>>> speeds = np.array([0.0, 10.0, 20.0, 30.0])
>>> crossings(speeds, np.array([15.0, 15.0, 15.0, 15.0]))
[(15.0, 2)]
>>> whirl(np.array([1.0, -1j]), np.zeros(2), 1.0, 0.0)
'forward'
"""

from __future__ import annotations

import numpy as np

#: below this MAC a branch is not followed to a mode (it left the band; the mode is new)
MIN_MAC = 0.3
#: 2 |turn| / size below which an orbit is a line: an ellipse flatter than 1 : 2000 (the
#: spatial ROM's rotorpillar.reduced.spatial_linear.WHIRL_TOLERANCE)
WHIRL_TOLERANCE = 1e-3
#: the rotor's whirl measure below this share of the mode's x^H M x: the rotor does not move
ROTOR_SHARE = 1e-12
#: relative distance of two eigenvalues of one (nearly) degenerate cluster: the two bending
#: planes with the gondola's different roll and pitch inertias are ~1e-5 apart, within the
#: eigenvectors' accuracy (the residual over the gap), so they are told apart by their kinds
#: and each gets back its own eigenvalue by its Rayleigh quotient
CLUSTER = 1e-4


def clusters(s: np.ndarray, tol: float = CLUSTER) -> list[list[int]]:
    """Groups of indices of (nearly) equal eigenvalues, each of two or more.

    >>> clusters(np.array([1.0, 1.0 + 1e-6, 2.0]))
    [[0, 1]]
    """
    out, i = [], 0
    order = np.argsort(np.abs(s))
    while i < len(order):
        j = i + 1
        while j < len(order) and abs(s[order[j]] - s[order[i]]) <= tol * abs(s[order[i]]):
            j += 1
        if j - i > 1:
            out.append([int(k) for k in order[i:j]])
        i = j
    return out


def align_degenerate(prev: np.ndarray, new: np.ndarray, members: list[int], gram) -> np.ndarray:
    """The cluster's columns of ``new`` replaced by the previous vectors' projections onto their
    span, orthonormalised in the order of the previous vectors nearest the span (module text).

    ``gram(A, B)`` = A^H B summed over the ranks."""
    V = new[:, members]
    # an orthonormal basis of the cluster's span
    G = gram(V, V)
    d, U = np.linalg.eigh((G + G.conj().T) / 2)
    Qc = V @ (U / np.sqrt(np.maximum(d, 1e-300)))
    P = gram(Qc, prev)  # coefficients of each previous vector in the span
    nearest = np.argsort(-np.sum(np.abs(P) ** 2, axis=0))[: len(members)]
    C = P[:, nearest]
    # Gram-Schmidt on the projections (their span is the cluster's)
    Qr, _ = np.linalg.qr(C)
    out = new.copy()
    out[:, members] = Qc @ Qr
    return out


def untangle(X: np.ndarray, members: list[int], rows, gram) -> np.ndarray:
    """The cluster's columns of ``X`` turned, within their span, so each lies as much as it can
    in one of the plate's and the rotor's dofs: where no previous speed tells them apart (the
    first speed; the critical speeds' pencil), a degenerate cluster's arbitrary basis is made
    the one of its kinds (the rotor in-plane against the rotor along the spin axis, bending in
    one plane against the other), as the spatial ROM's ``_untangle`` does on its coordinates.

    ``rows(V)`` = the plate's and the rotor's rows of V on every rank; ``gram(A, B)`` = A^H B
    summed over the ranks."""
    V = X[:, members]
    G = gram(V, V)
    d, U = np.linalg.eigh((G + G.conj().T) / 2)
    Q = V @ (U / np.sqrt(np.maximum(d, 1e-300)))
    R = rows(Q)
    code = np.arange(1.0, R.shape[0] + 1.0)  # a distinct weight per plate and rotor dof
    op = R.conj().T @ (code[:, None] * R)
    _, T = np.linalg.eigh((op + op.conj().T) / 2)
    out = X.copy()
    out[:, members] = Q @ T
    return out


def assign(mac: np.ndarray) -> list[tuple[int, int]]:
    """(branch, mode) pairs of largest total MAC, each above MIN_MAC."""
    from scipy.optimize import linear_sum_assignment

    if mac.size == 0:
        return []
    rows, cols = linear_sum_assignment(-mac)
    return [(int(r), int(c)) for r, c in zip(rows, cols) if mac[r, c] >= MIN_MAC]


def orbit_turn(x: complex, z: complex) -> tuple[float, float]:
    """(turn, size) of the orbit (Re(x e^{iwt}), Re(z e^{iwt})): turn = -Im(conj(x) z) > 0
    from +x towards +z; size = |x|**2 + |z|**2."""
    return -float(np.imag(np.conj(x) * z)), float(abs(x) ** 2 + abs(z) ** 2)


def whirl(centre: np.ndarray, axis: np.ndarray, mass: float, inertia: float, energy: float | None = None) -> str:
    """The whirl, "forward", "backward" or "none", of a body's motion in the plane normal to
    the spin axis: ``centre`` (x, z) and ``axis`` (-phi_z, phi_x) complex amplitudes, weighted
    by ``mass`` and ``inertia``; ``energy`` the mode's x^H M x (module text)."""
    t1, s1 = orbit_turn(*centre)
    t2, s2 = orbit_turn(*axis)
    turn, size = mass * t1 + inertia * t2, mass * s1 + inertia * s2
    if size <= 0 or (energy is not None and size <= ROTOR_SHARE * energy):
        return "none"
    if 2 * abs(turn) < WHIRL_TOLERANCE * size:
        return "none"
    return "forward" if turn > 0 else "backward"


def crossings(speeds: np.ndarray, frequency: np.ndarray) -> list[tuple[float, int]]:
    """(speed, index of the speed at or after it) where frequency - speed changes sign,
    linearly interpolated (NaN gaps skipped)."""
    f = np.asarray(frequency, float) - np.asarray(speeds, float)
    out = []
    for i in range(len(f) - 1):
        a, b = f[i], f[i + 1]
        if not (np.isfinite(a) and np.isfinite(b)):
            continue
        if a == 0.0:
            out.append((float(speeds[i]), i))
        elif a * b < 0:
            t = a / (a - b)
            out.append((float(speeds[i] + t * (speeds[i + 1] - speeds[i])), i + 1))
    if len(f) and f[-1] == 0.0:
        out.append((float(speeds[-1]), len(f) - 1))
    return out
