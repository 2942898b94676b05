"""The one eigen-solver wrapper: K x = lambda M x by shift-invert over one MUMPS factorisation.

One symmetric (LDL^T) factorisation of K - sigma M by MUMPS (half the memory
and time of LU; indefinite is fine) serves the whole solve; the n
eigenvalues nearest sigma are returned sorted ascending.  Two methods:

- ``"block"`` (the default up to ``BLOCK_MAX_MODES`` modes): block
  Lanczos on (K - sigma M)^-1 M with full M-reorthogonalisation and no
  restart.  Each step solves with the factors for a block of
  ``BLOCK_SIZE`` right-hand sides at once (MUMPS reads its factors once
  per block: a column costs a fraction of a single solve), then
  Rayleigh-Ritz on the whole basis, until every wanted pair meets the
  tolerance;
- ``"krylovschur"``: SLEPc's Krylov-Schur, one right-hand side per step;
  PETSc options under the prefix ``modal_`` override its settings, e.g.
  ``-modal_eps_ncv 40`` or ``-modal_eps_view`` (setting any ``modal_``
  option chooses it; ``-modal_method block|krylovschur`` chooses
  explicitly).  The block method falls back to it if its basis would grow
  past ``BLOCK_MAX_COLUMNS`` (or ``BLOCK_MAX_BYTES``).

Both stop on the same test: the residual of the shift-inverted problem,
||(K - sigma M)^-1 M x - theta x||_M / |theta| <= tol (SLEPc's relative
error estimate for a GHEP).  docs/fem3d.md has what was measured.  Any
failure is a :class:`~rotorpillar.errors.ComputationError` saying what failed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError, InputError
from .block_lanczos import modal_solve_failure, shifted_cholesky

OPTIONS_PREFIX = "modal_"
METHODS = ("block", "krylovschur")
#: Right-hand sides per block solve; chosen by measurement (docs/fem3d.md).
BLOCK_SIZE = 6
#: Above this many modes, Krylov-Schur (its restarts bound the memory).
BLOCK_MAX_MODES = 64
#: The block basis never grows past this many columns (else Krylov-Schur)...
BLOCK_MAX_COLUMNS = 400
#: ... nor past this many bytes per rank for V and M V (no restart: its memory grows).
BLOCK_MAX_BYTES = 2**30


@dataclass(frozen=True)
class EigenSolution:
    """Eigenpairs of the pencil (K, M), ascending, M-orthonormal vectors."""

    eigenvalues: np.ndarray
    """lambda = omega**2 (rad**2/s**2)"""
    vectors: list
    """PETSc Vecs, one per eigenvalue"""
    iterations: int
    """Krylov-Schur restarts, or block Lanczos steps"""
    errors: np.ndarray
    """error estimates of the eigenpairs (relative, -)"""
    method: str = "krylovschur"
    """the method that produced them (one of METHODS)"""
    solves: int = 0
    """right-hand sides solved with the factors (block method; 0: not counted)"""


def solve_gep_shift_invert(
    K,
    M,
    n_modes: int,
    *,
    sigma: float = 0.0,
    tol: float = 1e-10,
    max_it: int = 500,
    ncv: int | None = None,
    method: str | None = None,
    block: int = BLOCK_SIZE,
) -> EigenSolution:
    """The ``n_modes`` eigenpairs of K x = lambda M x nearest ``sigma`` (rad**2/s**2).

    K must be nonsingular after the shift (a clamped structure with sigma = 0,
    or any structure with sigma < 0).  Rows with K_ii = 1, M_ii = 0 (the
    Dirichlet rows) have lambda = infinity and are never returned.
    ``method``: one of ``METHODS``, None = block up to ``BLOCK_MAX_MODES``
    modes; ``ncv`` and ``max_it`` are Krylov-Schur's, ``block`` the block
    method's right-hand sides per solve.
    """
    if n_modes < 1:
        raise ValueError("n_modes must be >= 1")
    if method is None:
        method = default_method(n_modes)
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}")
    if method == "block":
        from .block_lanczos import block_lanczos

        columns = min(BLOCK_MAX_COLUMNS, BLOCK_MAX_BYTES // (16 * max(K.getLocalSize()[0], 1)))
        sol = block_lanczos(K, M, n_modes, sigma=sigma, tol=tol, block=block, max_columns=columns)
        if sol is not None:
            lam, vecs, steps, err, solves = sol
            return EigenSolution(lam, vecs, steps, err, "block", solves)
    return _krylov_schur(K, M, n_modes, sigma=sigma, tol=tol, max_it=max_it, ncv=ncv)


def default_method(n_modes: int) -> str:
    """``-modal_method`` if given; else Krylov-Schur when any other ``modal_``
    PETSc option is set (they are Krylov-Schur's) or past BLOCK_MAX_MODES; else block."""
    from petsc4py import PETSc

    opts = PETSc.Options().getAll()
    if OPTIONS_PREFIX + "method" in opts:
        method = str(opts[OPTIONS_PREFIX + "method"])
        if method not in METHODS:
            raise InputError(f"-{OPTIONS_PREFIX}method must be one of {', '.join(METHODS)}, not {method!r}")
        return method
    if any(k.startswith(OPTIONS_PREFIX) for k in opts) or n_modes > BLOCK_MAX_MODES:
        return "krylovschur"
    return "block"


def _krylov_schur(K, M, n_modes, *, sigma, tol, max_it, ncv) -> EigenSolution:
    """SLEPc Krylov-Schur, shift-invert, MUMPS LDL^T."""
    from petsc4py import PETSc
    from slepc4py import SLEPc

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
                f"restarts (reason {eps.getConvergedReason()}, tolerance {tol:g})"
            )
        lam, vecs, res = [], [], []
        for i in range(nconv):
            x = K.createVecRight()
            lam.append(eps.getEigenpair(i, x).real)
            res.append(eps.getErrorEstimate(i))
            vecs.append(x)
        iterations = eps.getIterationNumber()
    except PETSc.Error as exc:
        raise modal_solve_failure("PETSc/SLEPc", exc) from None
    finally:
        eps.destroy()
    order = np.argsort(lam)[:n_modes]
    for i in set(range(len(vecs))) - set(order[:n_modes]):
        vecs[i].destroy()
    return EigenSolution(
        np.asarray(lam)[order], [vecs[i] for i in order], iterations, np.asarray(res)[order], "krylovschur"
    )


def factorisation_time(K, M, sigma: float = 0.0) -> float:
    """Seconds of one MUMPS factorisation of K - sigma M, as the modal solve does it."""
    import time

    ksp, A = shifted_cholesky(K, M, sigma)
    try:
        t0 = time.perf_counter()
        ksp.setUp()
        return time.perf_counter() - t0
    finally:
        ksp.destroy()
        if A is not None:
            A.destroy()
