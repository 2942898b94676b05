"""The 3D full order's step operator and its plate rows (rotorpillar.fem3d.full_order).

- ``step_operator``: Keff = wf K + cm M + the plate's rows (its dashpot and the
  rotor centre condensed onto it), factorised once (MUMPS Cholesky: K and M are
  symmetric, the plate's terms positive);
- ``Plate``: reads and adds the plate's rows (U_x, U_y, U_z) on any rank count;
- ``add_shaft_acceleration``: the consistent initial acceleration;
- ``without_zeros``: a matrix without the zeros its pattern stores (the step's product).
"""

from __future__ import annotations

import numpy as np


def step_operator(K, M, plate_rows: dict, wf: float, cm: float, comm):
    """(ksp, Keff, the values added): Keff = wf K + cm M + ``plate_rows[row]`` on each of the
    plate's diagonal rows given (global row: N/m), factorised."""
    from petsc4py import PETSc

    Keff = K.copy()
    Keff.scale(wf)
    Keff.axpy(cm, M, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
    lo, hi = Keff.getOwnershipRange()
    for row, value in plate_rows.items():
        if lo <= row < hi:
            Keff.setValue(row, row, value, addv=PETSc.InsertMode.ADD_VALUES)
    Keff.assemble()
    Keff.setOption(PETSc.Mat.Option.SPD, True)
    ksp = PETSc.KSP().create(comm)
    ksp.setOperators(Keff)
    ksp.setType("preonly")
    ksp.getPC().setType("cholesky")
    ksp.getPC().setFactorSolverType("mumps")
    ksp.setUp()
    return ksp, Keff, tuple(plate_rows.values())


def without_zeros(A):
    """A copy of the assembled AIJ matrix ``A`` holding only its nonzero entries, on
    ``A``'s rows and columns (any rank count).  The consistent mass of a vector space
    couples no two directions, yet its pattern is K's: two thirds of what it stores are
    zeros, which its product reads all the same."""
    from petsc4py import PETSc

    indptr, indices, values = A.getValuesCSR()
    keep = values != 0.0
    kept = np.concatenate(([0], np.cumsum(keep)))[indptr]
    B = PETSc.Mat().createAIJ(
        A.getSizes(),
        csr=(kept.astype(PETSc.IntType), indices[keep].astype(PETSc.IntType), values[keep]),
        comm=A.getComm(),
    )
    B.assemble()
    return B


class Plate:
    """Reads and adds the plate's U_x and U_z rows of a PETSc Vec on any rank count."""

    def __init__(self, vec, rows, comm):
        lo, hi = vec.getOwnershipRange()
        self.local = [(i, r - lo) for i, r in enumerate(rows) if lo <= r < hi]
        self.n, self.comm = len(rows), comm

    def get(self, vec) -> np.ndarray:
        out = np.zeros(self.n)
        if self.local:
            arr = vec.getArray(readonly=True)
            for i, r in self.local:
                out[i] = arr[r]
        if self.comm.size > 1:
            out = self.comm.allreduce(out)
        return out

    def add(self, vec, values) -> None:
        if self.local:
            arr = vec.getArray()
            for i, r in self.local:
                arr[r] += values[i]


def add_shaft_acceleration(M, mask, plate: Plate, a, force) -> None:
    """a += M^-1 (the shaft's force on the plate at the start): the tube's consistent
    initial acceleration.  Without it the first steps carry the whirl's force on the
    plate as an acceleration error, which the trapezoidal velocity update keeps as a
    velocity error of O(h): first order instead of second.  One factorisation of M
    (the massless rows, clamped or placeholders, made the identity)."""
    if not any(force):
        return
    from petsc4py import PETSc

    Mm = M.copy()
    Mm.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)
    ones = mask.duplicate()
    ones.set(1.0)
    ones.axpy(-1.0, mask)
    Mm.setDiagonal(ones, addv=PETSc.InsertMode.ADD_VALUES)
    ksp = PETSc.KSP().create(M.getComm())
    ksp.setOperators(Mm)
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    f, da = M.createVecLeft(), M.createVecLeft()
    f.set(0.0)
    plate.add(f, force)
    ksp.solve(f, da)
    a.axpy(1.0, da)
    for obj in (ksp, Mm, ones, f, da):
        obj.destroy()
