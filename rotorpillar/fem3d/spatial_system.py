"""The 3D tube with the gondola on its rigid top and the rotor on its shaft, in PETSc.

M x'' + (C + Omega G) x' + K x = f over the unknowns of the loaded tube
(rotorpillar.fem3d.model, the rigid top: the tube's dofs, then the plate's
6) followed by the rotor's 5 (rotorpillar.fem3d.rotor_spatial: in-plane,
along the spin axis, vertical, pitch, yaw; 3 when it tilts with the
gondola), all owned by the last rank as the plate's are.

- K: the tube's and the shaft's (lateral c2, axial, tilt; between the rotor
  and the gondola's point at the rotor's height);
- M: the tube's, the bodies' 6 x 6 block on the plate, the rotor's
  diag(m_C, m_C, m_C, I_d, I_d) (I_d on the plate's pitch and yaw when it
  tilts with the gondola);
- C = C_sparse + C_modal: C_sparse the paper's b1 as a dashpot on the
  plate's two horizontal translations (the tube is axisymmetric: the tip
  damper acts in both directions), and the shaft's b2 and tilt damping
  (relative to the gondola, or b2 to the ground: ``damping_law``);
  C_modal = sum_j 2 zeta omega_j (M phi_j)(M phi_j)^T over the loaded
  tube's modes phi_j (M-orthonormal, the rotor not on it) below
  ``damped_up_to``: ``pillar.damping_ratio`` on every mode of the pillar,
  torsion and ovalling included.  This is the ROM's damping exactly: the
  ROM is these modes with zeta on each, so the Galerkin projection of this
  C on them is the ROM's diag(2 zeta omega_j m_j) plus the same b1 and
  shaft terms.  Rayleigh damping alpha M + beta K would give zeta only at
  two frequencies (across the band's 25-160 rad/s it is off by +40 % between
  them); a modal C is the one that is "the same".  It is of rank k and kept
  as the dense (n, k) W = M Phi, never as a matrix: applied as W (d * W^T x);
- G: the gyroscopic matrix, J_C [[0, 1], [-1, 0]] on the rotor's (pitch,
  yaw), or the plate's.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .model import RIGID_DOFS, AssembledPillar
from .rotor_spatial import SpatialRotor, rotor_blocks, tilt_rows


@dataclass
class RotorPillarSystem:
    """The assembled system (see the module text); the PETSc matrices are the caller's to destroy
    (``destroy``)."""

    model: AssembledPillar
    """the loaded tube (its K and M are not owned here)"""
    rotor: SpatialRotor
    K: Any
    """stiffness (PETSc Mat, N/m)"""
    M: Any
    """mass (PETSc Mat, kg)"""
    C: Any
    """the sparse damping: b1 on the plate, the shaft's (PETSc Mat, N*s/m)"""
    G: Any
    """the gyroscopic matrix per unit speed (PETSc Mat, kg*m**2)"""
    W: np.ndarray
    """(n_local, k) this rank's rows of M phi_j of the damped pillar modes (kg per unit)"""
    d: np.ndarray
    """(k,) 2 zeta omega_j of those modes, phi_j M-orthonormal (1/s)"""
    pillar_omega: np.ndarray
    """(k,) their angular frequencies (rad/s)"""
    damping_law: str
    """"gondola" or "ground": what b2 acts against"""
    tip_damping: float = 0.0
    """b1 on the plate's two horizontal translations (N*s/m)"""

    @property
    def plate(self) -> int:
        """global row of the plate's first dof"""
        return self.model.tube_dofs

    @property
    def size(self) -> int:
        return self.model.size + self.rotor.dofs

    @property
    def tilt_rows(self) -> tuple[int, int]:
        """global rows of the spin axis' pitch and yaw (the rotor's, or the plate's)"""
        return tuple(self.plate + i for i in tilt_rows(self.rotor))  # type: ignore[return-value]

    def modal_damping(self, x, y, scale: float = 1.0) -> None:
        """y += scale C_modal x (PETSc Vecs; collective)."""
        if not len(self.d):
            return
        xa = x.getArray(readonly=True)
        c = self.W.T @ xa
        if self.model.comm.size > 1:
            c = self.model.comm.allreduce(c)
        ya = y.getArray()
        ya += self.W @ (scale * self.d * c)

    def damping_mult(self, speed: float, x, y) -> None:
        """y = (C + speed G) x (collective)."""
        self.C.mult(x, y)
        if speed:
            self.G.multAdd(x, y, y) if speed == 1.0 else _mult_add_scaled(self.G, speed, x, y)
        self.modal_damping(x, y)

    def destroy(self) -> None:
        for A in (self.K, self.M, self.C, self.G):
            A.destroy()


def _mult_add_scaled(A, a: float, x, y) -> None:
    t = y.duplicate()
    A.mult(x, t)
    y.axpy(a, t)
    t.destroy()


def _extended(A, block: np.ndarray | None, at: int, extra: int):
    """A PETSc AIJ of A's size + ``extra`` rows and columns (owned by the last rank), with the
    dense ``block`` added at global rows and columns at, at + 1, ... (owned by the last rank).
    A None for A: a zero matrix of that size with an explicit zero diagonal (so that a later
    shift keeps its pattern)."""
    from petsc4py import PETSc
    from scipy.sparse import coo_matrix, csr_matrix, vstack

    comm = A.getComm().tompi4py()
    last = comm.rank == comm.size - 1
    lo, hi = A.getOwnershipRange()
    n = A.getSize()[0] + extra
    rows = hi - lo + (extra if last else 0)
    ia, ja, va = A.getValuesCSR()
    local = csr_matrix((va, ja, np.r_[ia, np.full(rows - (hi - lo), ia[-1])]), shape=(rows, n))
    if block is not None and last:
        # The block's rows summed as coordinates, not with scipy's `+`: that drops every sum that
        # is exactly 0, and an explicit 0 that T^T K T stores where T^T M T stores round-off
        # (2.5e-11 at one plate row on an AVX-512 machine) would leave M with a place K lacks:
        # K - w^2 M on K's places fails.  The rows above the block are stacked as they are.
        i, j = np.nonzero(block)
        first = at - lo
        c = local[first:].tocoo()
        tail = coo_matrix(
            (np.r_[c.data, block[i, j]], (np.r_[c.row, i], np.r_[c.col, at + j])), shape=(rows - first, n)
        ).tocsr()
        local = vstack([local[:first], tail], format="csr")
    local.sort_indices()
    B = PETSc.Mat().createAIJ(
        ((rows, n), (rows, n)),
        csr=(local.indptr.astype(PETSc.IntType), local.indices.astype(PETSc.IntType), local.data),
        comm=A.getComm(),
    )
    B.assemble()
    return B


def _zero_like(A):
    """A zero AIJ with A's layout and an explicit zero diagonal."""
    from petsc4py import PETSc

    lo, hi = A.getOwnershipRange()
    rows = hi - lo
    ia = np.arange(rows + 1, dtype=PETSc.IntType)
    B = PETSc.Mat().createAIJ(
        (A.getSizes()[0], A.getSizes()[1]),
        csr=(ia, (lo + np.arange(rows)).astype(PETSc.IntType), np.zeros(rows)),
        comm=A.getComm(),
    )
    B.assemble()
    return B


def assemble_system(
    model: AssembledPillar,
    rotor: SpatialRotor,
    *,
    tip_damping: float,
    damping_ratio: float = 0.0,
    damped_up_to: float = 0.0,
    damping_law: str = "gondola",
    tol: float = 1e-8,
) -> RotorPillarSystem:
    """The system of the module text on a loaded tube with the rigid top (collective).

    ``tip_damping`` b1 (N*s/m) on the plate's U_x and U_y; ``damping_ratio`` zeta (-) on every
    mode of the loaded tube below ``damped_up_to`` (rad/s; they are solved here, with one more
    to know the last is past it).
    """
    if model.extra_dofs != RIGID_DOFS:
        raise ValueError("the rotor hangs on the rigid top plate (modal.top_model = 'rigid')")
    at, n = model.tube_dofs, rotor.dofs  # the plate's and the rotor's dofs follow the tube's
    Kr, Cr, Mr, Gr = rotor_blocks(rotor, damping_law)
    Cr[0, 0] += tip_damping
    Cr[1, 1] += tip_damping
    K = _extended(model.K, Kr, at, n)
    M = _extended(model.M, Mr, at, n)
    zero = _zero_like(model.K)
    C = _extended(zero, Cr, at, n)
    G = _extended(zero, Gr, at, n)
    zero.destroy()
    W, d, w = _modal_damping(model, damping_ratio, damped_up_to, tol, n)
    return RotorPillarSystem(model, rotor, K, M, C, G, W, d, w, damping_law, float(tip_damping))


def _modal_damping(model: AssembledPillar, zeta: float, up_to: float, tol: float, extra: int):
    """(W, d, omega) of C_modal (module text): the loaded tube's modes below ``up_to``,
    16 first, doubled until one passes it.  Sixteen, not eight: the solve's cost is
    its factorisation, and 16 modes cost what 8 do (paper, 24k DOFs: 0.72 s against
    0.68 s of CPU), while 8 fall short of twice the band's top on paper."""
    from .eigensolver import solve_gep_shift_invert

    comm = model.comm
    last = comm.rank == comm.size - 1
    n_local = model.K.getLocalSize()[0] + (extra if last else 0)
    if zeta <= 0 or up_to <= 0:
        return np.zeros((n_local, 0)), np.zeros(0), np.zeros(0)
    k = 16
    while True:
        sol = solve_gep_shift_invert(model.K, model.M, k, tol=tol)
        omega = np.sqrt(np.maximum(sol.eigenvalues, 0.0))
        if omega[-1] > up_to or k >= 256:
            break
        for x in sol.vectors:
            x.destroy()
        k *= 2
    keep = np.flatnonzero(omega <= up_to)
    W = np.zeros((n_local, len(keep)))
    y = model.M.createVecLeft()
    for c, i in enumerate(keep):
        model.M.mult(sol.vectors[i], y)
        W[: model.K.getLocalSize()[0], c] = y.getArray(readonly=True)
    y.destroy()
    for x in sol.vectors:
        x.destroy()
    return W, 2 * zeta * omega[keep], omega[keep]
