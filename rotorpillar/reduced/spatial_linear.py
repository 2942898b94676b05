"""The spatial model at constant speed: damped modes, whirl, the Campbell diagram, critical speeds.

At a constant spin speed Omega the linearised spatial model
(rotorpillar.reduced.spatial_model) is

    M Z'' + (C + Omega G) Z' + K_f Z = f(t),     K_f = K + c2 (d_x d_x^T + d_v d_v^T),

whose damped modes are the eigenvalues s = -zeta w + i w sqrt(1 - zeta**2) of
the first-order form; each mode's frequency is Im(s) (rad/s), its log decrement
delta = -2 pi Re(s) / Im(s).  Its whirl is the way the rotor's orbit in the
plane normal to the spin axis (x, z) turns, the rotor centre's and its axis's
(the axis's tip moves by (a_z, -a_x)) together, each weighted by its inertia:
forward with the spin (from x towards z), backward against it, "none" where
the orbit is a line (``spatial_model.whirl_ratio`` within WHIRL_TOLERANCE of 0).

**Tracking** (the Campbell diagram): from one speed to the next each mode is
matched to the one whose mode shape is closest (the modal assurance criterion in
the mass's inner product, one-to-one by the Hungarian assignment, with the
frequency change as a tie-break).  Modes that share a frequency (the two
bending planes of a round tube with equal gondola inertias) have no shape of
their own inside their common eigenspace: there the basis is turned so each
vector lies in one kind of coordinate, before the labels are read.

**Critical speeds**: where the 1x line crosses a mode, s = i Omega in the
undamped gyroscopic system, K_f v = Omega**2 (M - i G) v: a Hermitian pencil
(M - i G is Hermitian, K_f positive definite), solved as (M - i G) v = nu K_f v
with nu = 1 / Omega**2; nu <= 0 is a mode the 1x line never meets (the forward
tilt of a disc, J_C > I_d).  Exact for the undamped model; the damped peaks of
the unbalance response lie near them (rotorpillar.reduced.spatial_response).

>>> from rotorpillar.reduced.spatial_model import tilt_example
>>> c = critical_speeds(tilt_example())  # the tilt's backward whirl at sqrt(k_t / (I_d + J_C))
>>> (round(c[0].speed, 4), c[0].whirl, c[0].excited_by), round(c[1].speed, 4)
((11.547, 'backward', 'neither'), 15.8114)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eig, eigh
from scipy.optimize import linear_sum_assignment

from .campbell import CampbellBranch, CampbellDiagram, CriticalSpeed, log_decrement
from .spatial_model import SpatialStructure

Matrix = NDArray[np.float64]
#: |whirl ratio| below this: the orbit is a line (-): an ellipse flatter than 1 : 2000, or
#: the round-off of two modes a few 1e-7 apart whose shapes the eigensolver mixes
WHIRL_TOLERANCE = 1e-3
#: a modal force below this share of the largest possible: the unbalance does not excite the mode (-)
EXCITATION_TOLERANCE = 1e-6


@dataclass(frozen=True, eq=False)
class DampedModes:
    """The damped modes at one speed, ascending in frequency."""

    speed: float
    """Omega (rad/s)"""
    eigenvalues: NDArray[np.complex128]
    """(nz,) s with Im(s) >= 0 (rad/s)"""
    shapes: NDArray[np.complex128]
    """(nz, nz) the Z part of each mode (columns)"""

    @property
    def frequency(self) -> NDArray[np.float64]:
        """Im(s) (rad/s)"""
        out: NDArray[np.float64] = self.eigenvalues.imag
        return out

    @property
    def damping_ratio(self) -> NDArray[np.float64]:
        """-Re(s) / |s| (-)"""
        s = self.eigenvalues
        out: NDArray[np.float64] = np.where(np.abs(s) > 0, -s.real / np.maximum(np.abs(s), 1e-300), 1.0)
        return out


def damped_modes(m: SpatialStructure, speed: float) -> DampedModes:
    """The model's nz damped modes at ``speed`` (rad/s): the eigenvalues of the first-order
    form with Im(s) > 0, an overdamped pair's two real roots each counted (frequency 0)."""
    nz = m.nz
    Minv = np.linalg.inv(m.mass)
    A = np.block(
        [
            [np.zeros((nz, nz)), np.eye(nz)],
            [-Minv @ m.stiffness_full(), -Minv @ (m.damping + speed * m.gyroscopic)],
        ]
    )
    lam, vec = eig(A)
    scale = max(float(np.max(np.abs(lam))), 1e-300)
    upper = np.flatnonzero(lam.imag > 1e-9 * scale)
    real = np.flatnonzero(np.abs(lam.imag) <= 1e-9 * scale)
    keep = np.r_[upper, real[np.argsort(-lam.real[real])]][:nz]
    lam, vec = lam[keep], vec[:nz, keep]
    order = np.lexsort((np.abs(lam), lam.imag))
    return DampedModes(float(speed), lam[order], vec[:, order])


def _kind_codes(m: SpatialStructure) -> tuple[NDArray[np.float64], list[str]]:
    """A number per coordinate naming its kind, and the kinds' words."""
    kinds: list[str] = []
    code = np.zeros(m.nz)
    for i, name in enumerate(m.coordinates):
        if name.startswith("eta"):
            word = m.modes.kind[int(name[3:]) - 1]
        elif name in ("rotor_x", "rotor_vertical"):
            word = "rotor on its shaft"
        elif name == "rotor_axial":
            word = "rotor along the spin axis"
        else:
            word = "rotor tilt"
        if word not in kinds:
            kinds.append(word)
        code[i] = kinds.index(word) + 1
    return code, kinds


def whirl_operator(m: SpatialStructure) -> NDArray[np.complex128]:
    """S, Hermitian: v^H S v = m_C Im(conj(x) z) + I_d Im(conj(a_z) (-a_x)), the orbit's turn
    about the spin axis (negative: forward, from x towards z)."""
    o = m.outputs
    pairs = ((o["rotor_x"], o["rotor_z"], m.rotor_mass), (o["rotor_yaw"], -o["rotor_pitch"], m.diametral_inertia))
    S = np.zeros((m.nz, m.nz), dtype=complex)
    for a, b, w in pairs:
        S += w * (np.outer(a, b) - np.outer(b, a)) / 2j
    return S


def _untangle(
    shapes: NDArray[np.complex128], values: NDArray[np.float64], code: NDArray[np.float64], S: NDArray[np.complex128]
) -> NDArray[np.complex128]:
    """Inside each group of (nearly) equal ``values``, turn the basis so each vector lies in
    one kind of coordinate and, within a kind, whirls one way (see the module text)."""
    out = shapes.copy()
    scale = max(float(np.max(np.abs(S))), 1e-300)
    op = np.diag(code) + 1e-3 * S / scale
    i = 0
    n = len(values)
    while i < n:
        j = i + 1
        while j < n and abs(values[j] - values[i]) <= 1e-7 * max(abs(values[i]), 1e-12):
            j += 1
        if j - i > 1:
            Q, _ = np.linalg.qr(out[:, i:j])
            _, R = np.linalg.eigh(Q.conj().T @ op @ Q)
            out[:, i:j] = Q @ R
        i = j
    return out


def _mac(A: NDArray[np.complex128], B: NDArray[np.complex128], M: Matrix) -> Matrix:
    """|a^H M b|**2 / (a^H M a b^H M b) for every column pair (-)."""
    num = np.abs(A.conj().T @ M @ B) ** 2
    na = np.real(np.einsum("ij,ik,kj->j", A.conj(), M, A))
    nb = np.real(np.einsum("ij,ik,kj->j", B.conj(), M, B))
    out: Matrix = num / np.maximum(np.outer(na, nb), 1e-300)
    return out


def mode_whirl(m: SpatialStructure, v: NDArray[np.complex128]) -> tuple[float, str]:
    """(ratio, word) of a mode shape's whirl: the rotor centre's orbit in (x, z) and its
    axis's (a_z, -a_x), weighted by m_C and I_d (``whirl_ratio`` generalised)."""
    x, z = m.output("rotor_x", v), m.output("rotor_z", v)
    ax, az = m.output("rotor_pitch", v), m.output("rotor_yaw", v)
    h = float(np.real(v.conj() @ whirl_operator(m) @ v))
    norm = m.rotor_mass * (abs(x) ** 2 + abs(z) ** 2) + m.diametral_inertia * (abs(ax) ** 2 + abs(az) ** 2)
    energy = float(np.real(v.conj() @ m.mass @ v))
    if norm <= 1e-12 * energy:
        return 0.0, "none"
    ratio = float(-2 * h / norm)
    if abs(ratio) < WHIRL_TOLERANCE:
        return ratio, "none"
    return ratio, "forward" if ratio > 0 else "backward"


def mode_kind(m: SpatialStructure, v: NDArray[np.complex128]) -> str:
    """The kind of coordinate that carries most of the mode's kinetic energy."""
    code, kinds = _kind_codes(m)
    share = np.real(np.conj(v) * (m.mass @ v))
    best = max(range(len(kinds)), key=lambda i: float(np.sum(share[code == i + 1])))
    return kinds[best]


def campbell(m: SpatialStructure, speeds: NDArray[np.float64], running_speed: float | None = None) -> CampbellDiagram:
    """The Campbell diagram of the model over ``speeds`` (rad/s, ascending; see the module text)."""
    speeds = np.asarray(speeds, dtype=float)
    if len(speeds) < 2 or np.any(np.diff(speeds) <= 0) or speeds[0] < 0:
        raise ValueError("speeds must be ascending, >= 0, at least two")
    code, _ = _kind_codes(m)
    S = whirl_operator(m)
    nz = m.nz
    freq = np.zeros((len(speeds), nz))
    zeta = np.zeros((len(speeds), nz))
    ratio = np.zeros((len(speeds), nz))
    prev = None
    first = None
    for k, w in enumerate(speeds):
        dm = damped_modes(m, w)
        shapes = _untangle(dm.shapes, dm.frequency, code, S)
        f, z = dm.frequency, dm.damping_ratio
        if prev is not None:
            cost = (
                1.0
                - _mac(prev, shapes, m.mass)
                + 1e-3 * np.abs(freq[k - 1][:, None] - f[None, :]) / max(float(np.max(f)), 1e-300)
            )
            _, col = linear_sum_assignment(cost)
            shapes, f, z = shapes[:, col], f[col], z[col]
        else:
            first = shapes
        freq[k], zeta[k] = f, z
        ratio[k] = [mode_whirl(m, shapes[:, j])[0] for j in range(nz)]
        prev = shapes
    assert first is not None
    kinds = [mode_kind(m, first[:, j]) for j in range(nz)]
    counts: dict[str, int] = {}
    branches = []
    for j in range(nz):
        counts[kinds[j]] = counts.get(kinds[j], 0) + 1
        whirl = tuple("none" if abs(r) < WHIRL_TOLERANCE else ("forward" if r > 0 else "backward") for r in ratio[:, j])
        label = f"{kinds[j]} {counts[kinds[j]]}"
        turning = {w for w in whirl[1:] if w != "none"}
        if len(turning) == 1:
            label += " " + turning.pop()
        branches.append(CampbellBranch(label, kinds[j], freq[:, j], whirl, log_decrement(zeta[:, j]), zeta[:, j]))
    crit = critical_speeds(m, branches, speeds)
    notes = (
        "frequencies: the damped natural frequencies Im(s) of the linearised model at each constant speed",
        "tracking: modal assurance criterion in the mass's inner product between neighbouring speeds",
        "critical speeds: the undamped gyroscopic pencil K v = Omega**2 (M - i G) v (s = i Omega)",
    )
    return CampbellDiagram(
        model="modal",
        speeds=speeds,
        modes=tuple(branches),
        critical_speeds=tuple(c for c in crit if c.speed <= speeds[-1]),
        running_speed=running_speed,
        description=f"{m.name} reduced model: " + "; ".join(m.notes),
        notes=notes,
    )


def critical_speed_modes(m: SpatialStructure) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """(Omega, v): every speed where s = i Omega solves the undamped model, ascending."""
    nu, V = eigh(m.mass - 1j * m.gyroscopic, m.stiffness_full())
    V = _untangle(V, nu, _kind_codes(m)[0], whirl_operator(m))
    keep = nu > 0
    W = 1.0 / np.sqrt(nu[keep])
    order = np.argsort(W)
    return W[order], V[:, keep][:, order]


def excitation(m: SpatialStructure, v: NDArray[np.complex128]) -> tuple[float, float]:
    """How much the static and the couple unbalance's rotating loads drive mode v: the
    cosine, in the stiffness's inner product, between the load and the mode (0 ... 1)."""
    Kf = m.stiffness_full()
    Kinv = np.linalg.inv(Kf)
    dx, dv = m.shaft
    out = []
    for f in (m.shaft_stiffness * (dx - 1j * dv), m.couple[0] - 1j * m.couple[1]):
        nf = math.sqrt(max(float(np.real(f.conj() @ Kinv @ f)), 0.0))
        nv = math.sqrt(max(float(np.real(v.conj() @ Kf @ v)), 0.0))
        out.append(0.0 if nf == 0 or nv == 0 else float(abs(v.conj() @ f)) / (nf * nv))
    return out[0], out[1]


def critical_speeds(
    m: SpatialStructure, branches: list[CampbellBranch] | None = None, speeds: NDArray[np.float64] | None = None
) -> list[CriticalSpeed]:
    """The critical speeds with their whirl, what excites them, and the Campbell branch
    they belong to (the branch nearest the crossing, where one is given)."""
    W, V = critical_speed_modes(m)
    out = []
    for w, v in zip(W, V.T):
        _, whirl = mode_whirl(m, v)
        cs, cc = excitation(m, v)
        by = (
            "static unbalance"
            if cs > EXCITATION_TOLERANCE
            else "couple unbalance"
            if cc > EXCITATION_TOLERANCE
            else "neither"
        )
        label = mode_kind(m, v)
        if branches and speeds is not None and speeds[0] <= w <= speeds[-1]:
            same = [b for b in branches if b.kind == label] or branches
            near = min(same, key=lambda b: abs(float(np.interp(w, speeds, b.frequency)) - w))
            label = near.label
        out.append(
            CriticalSpeed(
                float(w),
                label,
                whirl,
                by,
                method="undamped gyroscopic pencil K v = Omega**2 (M - i G) v",
            )
        )
    return out
