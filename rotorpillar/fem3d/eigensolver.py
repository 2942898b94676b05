"""The one SLEPc wrapper: K x = lambda M x by shift-invert with MUMPS.

Krylov-Schur on (K - sigma M)^-1 M, one symmetric (LDL^T) factorisation of
K - sigma M by MUMPS (half the memory and time of LU; indefinite is fine),
the n eigenvalues nearest sigma, returned sorted ascending.  PETSc
options under the prefix ``modal_`` override the settings, e.g.
``-modal_eps_ncv 40`` or ``-modal_eps_view``.  Any failure is a
:class:`~rotorpillar.errors.ComputationError` saying what failed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError

OPTIONS_PREFIX = "modal_"


@dataclass(frozen=True)
class EigenSolution:
    """Eigenpairs of the pencil (K, M), ascending, M-orthonormal vectors."""
    eigenvalues: np.ndarray
    """lambda = omega**2 (rad**2/s**2)"""
    vectors: list
    """PETSc Vecs, one per eigenvalue"""
    iterations: int
    """Krylov-Schur restarts"""
    errors: np.ndarray
    """SLEPc's error estimates of the eigenpairs (relative, -)"""


def solve_gep_shift_invert(K, M, n_modes: int, *, sigma: float = 0.0, tol: float = 1e-10,
                           max_it: int = 500, ncv: int | None = None) -> EigenSolution:
    """The ``n_modes`` eigenpairs of K x = lambda M x nearest ``sigma`` (rad**2/s**2).

    K must be nonsingular after the shift (a clamped structure with sigma = 0,
    or any structure with sigma < 0).  Rows with K_ii = 1, M_ii = 0 (the
    Dirichlet rows) have lambda = infinity and are never returned.
    """
    from petsc4py import PETSc
    from slepc4py import SLEPc
    if n_modes < 1:
        raise ValueError("n_modes must be >= 1")
    eps = SLEPc.EPS().create(K.getComm())
    try:
        eps.setOptionsPrefix(OPTIONS_PREFIX)
        eps.setOperators(K, M)
        eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
        eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
        eps.setDimensions(n_modes, ncv if ncv is not None else PETSc.DECIDE)
        eps.setTarget(sigma)
        eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
        eps.setTolerances(tol, max_it)
        # No purification: the massless rows (clamped dofs, rigid-top placeholders and
        # rotations) are either decoupled or statically tied to the massive ones, so the
        # Krylov vectors already satisfy them; purifying costs one more solve per mode.
        eps.setPurify(False)
        st = eps.getST()
        st.setType(SLEPc.ST.Type.SINVERT)
        st.setShift(sigma)
        ksp = st.getKSP()
        ksp.setType(PETSc.KSP.Type.PREONLY)
        pc = ksp.getPC()
        pc.setType(PETSc.PC.Type.CHOLESKY)
        pc.setFactorSolverType("mumps")
        eps.setFromOptions()
        eps.solve()
        nconv = eps.getConverged()
        if nconv < n_modes:
            raise ComputationError(
                f"SLEPc converged {nconv} of {n_modes} eigenpairs in {eps.getIterationNumber()} "
                f"restarts (reason {eps.getConvergedReason()}, tolerance {tol:g})")
        lam, vecs, res = [], [], []
        for i in range(nconv):
            x = K.createVecRight()
            lam.append(eps.getEigenpair(i, x).real)
            res.append(eps.getErrorEstimate(i))
            vecs.append(x)
        iterations = eps.getIterationNumber()
    except PETSc.Error as exc:
        raise ComputationError(f"PETSc/SLEPc failed in the modal solve (error code {exc.ierr}; "
                               "a MUMPS factorisation failure is typical of an unclamped or "
                               "disconnected model)") from None
    finally:
        eps.destroy()
    order = np.argsort(lam)[:n_modes]
    return EigenSolution(np.asarray(lam)[order], [vecs[i] for i in order], iterations,
                         np.asarray(res)[order])


def factorisation_time(K, M, sigma: float = 0.0) -> float:
    """Seconds of one MUMPS factorisation of K - sigma M, as the modal solve does it."""
    import time

    from petsc4py import PETSc
    A = K.copy()
    if sigma != 0.0:
        A.axpy(-sigma, M)
    ksp = PETSc.KSP().create(K.getComm())
    try:
        ksp.setOperators(A)
        ksp.setType(PETSc.KSP.Type.PREONLY)
        pc = ksp.getPC()
        pc.setType(PETSc.PC.Type.CHOLESKY)
        pc.setFactorSolverType("mumps")
        t0 = time.perf_counter()
        ksp.setUp()
        return time.perf_counter() - t0
    finally:
        ksp.destroy()
        A.destroy()
