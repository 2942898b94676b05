"""The quadratic eigenproblem (M s**2 + (C + Omega G) s + K) x = 0 of the 3D model with its rotor.

Real arithmetic throughout (PETSc is built real here): complex eigenpairs
come as conjugate pairs of a real problem.  K does not depend on the speed
(the gyroscopic term is a damping-like term), so one MUMPS Cholesky
factorisation of K serves every speed: the shift is 0, the eigenvalues
nearest it are the low ones, the band's.

Two methods, the same eigenpairs:

- ``"block"`` (the default): the first companion linearisation, scaled by a
  frequency w0 (lambda = s / w0, z = (x, lambda x)),

      Op (x, y) = (-K^-1 (w0**2 M y + w0 C x), x),   Op z = (1 / lambda) z,

  (Op = A^-1 B for A = [[0, I], [-K, -w0 C]], B = [[I, 0], [0, w0**2 M]]),
  by a block Arnoldi with full reorthogonalisation (classical Gram-Schmidt
  twice) and Rayleigh-Ritz on the whole basis after each block, no restart.
  Each block is one MUMPS solve with many right-hand sides (the factors read
  once per block: a column costs 1/4-1/5 of a single solve,
  rotorpillar.fem3d.block_lanczos).  Across a Campbell diagram's speeds the
  start block is the previous speed's converged eigenvectors (their real
  and imaginary parts) and a few random columns: near-invariant, so one or
  two blocks converge them again;
- ``"toar"``: SLEPc's PEP, TOAR, shift-and-invert at 0 (MUMPS Cholesky of
  K), C + Omega G as a shell matrix (its modal part is of low rank); one
  right-hand side per Krylov step.  Kept as the reference the block method
  is checked against (tests/test_fem3d_campbell.py).

Convergence (both): the Ritz pair's residual in Op, ||Op z - mu z|| / |mu|
<= tol, for every eigenvalue with |s| <= ``radius`` and at least one
beyond it (so that none inside is missed for want of a Krylov direction: a
shift-invert Krylov space finds the eigenvalues nearest the shift first;
the one beyond to sqrt(tol): it has to be there, its value is not used).
The result states each pair's backward error in the quadratic problem
itself, ||P(s) x|| / ((|s|**2 ||M|| + |s| ||C|| + ||K||) ||x||) (the norms
1-norms), computed from the products, independent of the method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError

METHODS = ("block", "toar")
#: columns per block of the first speed (no start from a previous speed)
FIRST_BLOCK = 12
#: random columns added to a previous speed's eigenvectors in the start block
FRESH_COLUMNS = 4
#: converged pairs beyond the radius carried to the next speed's start
SEED_BEYOND = 2
#: the basis never grows past this many columns
MAX_COLUMNS = 400
#: a column whose norm after orthogonalisation is below this share of its norm before is dropped
DROP = 1e-10


@dataclass
class QuadraticModes:
    """Eigenpairs of the quadratic problem at one speed, Im(s) >= 0, ascending |s|."""

    s: np.ndarray
    """(k,) eigenvalues s = -zeta w + i w sqrt(1 - zeta**2) (rad/s), complex"""
    X: np.ndarray
    """(n_local, k) this rank's rows of the right eigenvectors, complex, unit 2-norm over all ranks"""
    backward_error: np.ndarray
    """(k,) ||P(s) x|| / ((|s|**2 ||M|| + |s| ||C|| + ||K||) ||x||) (-)"""
    steps: int
    """blocks (block) or restarts (toar)"""
    solves: int
    """right-hand sides solved with the factors of K"""
    seeds: np.ndarray | None = None
    """(2 n_local, c) real start columns for the next speed (block method)"""


class Products:
    """Block products with M, C + speed G, K and the solves with K's factors (one rank's rows);
    made once per system (the CSR copies, serial), its ``speed`` set per speed."""

    def __init__(self, system, speed: float, factor, comm):
        from .block_lanczos import seq_csr

        self.sys, self.speed, self.F, self.comm = system, speed, factor, comm
        self.n_local, self.n = system.K.getLocalSize()[0], system.K.getSize()[0]
        self.serial = comm.size == 1
        if self.serial:
            self.Mc, self.Cc, self.Gc = seq_csr(system.M), seq_csr(system.C), seq_csr(system.G)
            self.Kc = seq_csr(system.K)
        self.solves = 0

    def _dense(self, X):
        from petsc4py import PETSc

        return PETSc.Mat().createDense(
            ((self.n_local, self.n), (None, X.shape[1])), array=np.asfortranarray(X), comm=self.sys.K.getComm()
        )

    def _petsc(self, A, X):
        D = self._dense(X)
        Y = A.matMult(D)
        out = Y.getDenseArray().copy(order="F")
        D.destroy()
        Y.destroy()
        return out

    def mass(self, X):
        return self.Mc @ X if self.serial else self._petsc(self.sys.M, X)

    def stiffness(self, X):
        return self.Kc @ X if self.serial else self._petsc(self.sys.K, X)

    def damping(self, X):
        """(C_sparse + speed G + C_modal) X"""
        if self.serial:
            out = self.Cc @ X
            if self.speed:
                out += self.speed * (self.Gc @ X)
        else:
            out = self._petsc(self.sys.C, X)
            if self.speed:
                out += self.speed * self._petsc(self.sys.G, X)
        W, d = self.sys.W, self.sys.d
        if len(d):
            c = W.T @ X
            if not self.serial:
                c = self.comm.allreduce(c)
            out += W @ (d[:, None] * c)
        return out

    def solve(self, Y):
        out = np.empty(Y.shape, order="F")
        B, X = self._dense(Y), self._dense(out)
        try:
            self.F.matSolve(B, X)
        finally:
            B.destroy()
            X.destroy()
        self.solves += Y.shape[1]
        return out

    def gram(self, X, Y):
        g = X.T @ Y
        return g if self.serial else self.comm.allreduce(g)

    def _sum_cols(self, A: np.ndarray) -> np.ndarray:
        """Column sums over the rows of every rank."""
        return _sum(self.comm, np.sum(A, axis=0))

    def forms(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(x^H M x, x^H (C + speed G) x, x^H K x) of each complex column, summed over the ranks."""
        Xr, Xi = X.real.copy(order="F"), X.imag.copy(order="F")
        out = []
        for apply in (self.mass, self.damping, self.stiffness):
            AX = apply(Xr) + 1j * apply(Xi)
            out.append(_sum(self.comm, np.sum(np.conj(X) * AX, axis=0)))
        return out[0], out[1], out[2]

    def norms_of_products(self):
        """(||M||, ||C + speed G + C_modal||, ||K||) in the 1-norm (the modal part bounded by
        ||W||_1 d ||W||_inf summed)."""
        from petsc4py import PETSc

        one = PETSc.NormType.NORM_1
        nM, nK = self.sys.M.norm(one), self.sys.K.norm(one)
        nC = self.sys.C.norm(one) + abs(self.speed) * self.sys.G.norm(one)
        W, d = self.sys.W, self.sys.d
        if len(d):
            col = np.abs(W).sum(axis=0)
            row = np.abs(W).max(axis=0)
            if not self.serial:
                col, row = self.comm.allreduce(col), self.comm.allreduce(row, op=_max_op())
            nC += float(np.sum(d * col * row * W.shape[0]))
        return nM, nC, nK


def _max_op():
    from mpi4py import MPI

    return MPI.MAX


def stiffness_factor(K):
    """(ksp, factor): MUMPS Cholesky of K, factorised (the caller destroys the ksp)."""
    from petsc4py import PETSc

    from .block_lanczos import modal_solve_failure, shifted_cholesky

    K.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    ksp, _ = shifted_cholesky(K, K, 0.0)
    try:
        ksp.setUp()
    except PETSc.Error as exc:
        ksp.destroy()
        raise modal_solve_failure("MUMPS", exc) from None
    return ksp, ksp.getPC().getFactorMatrix()


def solve_quadratic(
    system,
    speed: float,
    radius: float,
    factor,
    *,
    scale: float | None = None,
    tol: float = 1e-8,
    seeds: np.ndarray | None = None,
    rng_seed: int = 20261127,
    ops: Products | None = None,
) -> QuadraticModes:
    """The eigenpairs with |s| <= ``radius`` (rad/s) at ``speed`` (rad/s) by the block method
    (module text), with ``factor`` the factors of system.K (``stiffness_factor``); ``seeds``
    the previous speed's ``QuadraticModes.seeds``; ``ops`` the system's Products (made here
    when None)."""
    comm = system.model.comm
    ops = Products(system, speed, factor, comm) if ops is None else ops
    ops.speed, ops.solves = speed, 0
    w0 = float(radius if scale is None else scale)
    n = ops.n_local

    def op(Z):
        X, Y = Z[:n], Z[n:]
        rhs = -(w0 * w0) * ops.mass(Y) - w0 * ops.damping(X)
        return np.vstack([ops.solve(rhs), X])

    rng = np.random.default_rng(rng_seed + comm.rank)
    # the start inside Op's range, so that the massless rows are consistent from the first vector
    # on: random columns through Op; the last speed's Ritz vectors are combinations of Op's images
    if seeds is not None and seeds.shape[1]:
        start = np.hstack([seeds, op(rng.standard_normal((2 * n, FRESH_COLUMNS)))])
    else:
        start = op(rng.standard_normal((2 * n, FIRST_BLOCK)))
    basis = _Basis(2 * n, 8 * start.shape[1])
    Q0, _, _ = _orthonormalise(ops, start, basis.Q)
    basis.append(Q0)
    last = Q0
    H = np.zeros((Q0.shape[1], Q0.shape[1]))
    steps, done = 0, False
    while True:
        steps += 1
        m0, width = basis.m, last.shape[1]
        Qn, h, R = _orthonormalise(ops, op(last), basis.Q)
        m1 = m0 + Qn.shape[1]
        Hn = np.zeros((m1, m1))
        Hn[:m0, :m0] = H
        Hn[:m0, m0 - width : m0] = h
        Hn[m0:, m0 - width : m0] = R
        H = Hn
        mu, Yr = np.linalg.eig(H[:m0, :m0])
        # Op Q y - mu Q y = Qn R y_last: the residual of each Ritz pair (Qn orthonormal)
        res = np.linalg.norm(R @ Yr[m0 - width :, :], axis=0) / np.maximum(np.abs(mu), 1e-300)
        with np.errstate(divide="ignore"):
            s = w0 / mu
        done = _converged(s, res, radius, tol)
        Q = basis.Q[:, :m0]  # the basis of the Ritz vectors (before this step's block)
        basis.append(Qn)
        last = basis.Q[:, m0:]
        if done or Qn.shape[1] == 0 or m1 >= MAX_COLUMNS:
            break
    upper = s.imag >= -1e-12 * np.abs(s)
    if not done:
        raise ComputationError(
            f"the quadratic eigen-solve at {speed:.4g} rad/s did not converge in {m1} columns "
            f"(tolerance {tol:g}); largest residual {float(np.max(res[np.abs(s) <= radius], initial=0.0)):.3g}"
        )
    keep = np.flatnonzero((np.abs(s) <= radius) & upper & (res <= tol))
    order = keep[np.argsort(np.abs(s[keep]))]
    # the next speed starts from these and from the converged pairs just beyond the radius,
    # the first to come in if the speed moves one inside
    beyond = np.flatnonzero((np.abs(s) > radius) & upper & (res <= math.sqrt(tol)))
    beyond = beyond[np.argsort(np.abs(s[beyond]))][:SEED_BEYOND]
    Zs = Q @ Yr[:, np.r_[order, beyond]]
    Z = Zs[:, : len(order)]
    X = Z[:n]
    X = X / np.sqrt(_sum(comm, np.sum(np.abs(X) ** 2, axis=0)))
    seeds_out = np.hstack([Zs.real, Zs.imag])
    seeds_out /= np.maximum(np.sqrt(_sum(comm, np.sum(seeds_out**2, axis=0))), 1e-300)
    be = backward_errors(ops, s[order], X)
    return QuadraticModes(s[order], X, be, steps, ops.solves, seeds_out)


class _Basis:
    """The orthonormal basis in a buffer that grows by doubling (no copy per block)."""

    def __init__(self, rows: int, guess: int):
        self._Q = np.empty((rows, guess), order="F")
        self.m = 0

    @property
    def Q(self):
        return self._Q[:, : self.m]

    def append(self, X):
        k = X.shape[1]
        if self.m + k > self._Q.shape[1]:
            new = np.empty((self._Q.shape[0], max(2 * self._Q.shape[1], self.m + k)), order="F")
            new[:, : self.m] = self._Q[:, : self.m]
            self._Q = new
        self._Q[:, self.m : self.m + k] = X
        self.m += k


def _sum(comm, a):
    return a if comm.size == 1 else comm.allreduce(a)


def _converged(s, res, radius: float, tol: float) -> bool:
    """Every Ritz value with |s| <= radius converged, and one beyond it to sqrt(tol) (it
    only has to be there: an eigenvalue the Krylov space has found past the radius)."""
    inside = np.abs(s) <= radius
    if not np.any(inside):
        return False
    beyond = (~inside) & (res <= math.sqrt(tol))
    return bool(np.all(res[inside] <= tol) and np.any(beyond))


def _orthonormalise(ops, W, Q):
    """(Qn, h, R): W = Q h + Qn R with Qn orthonormal and orthogonal to Q (classical
    Gram-Schmidt twice, then the Gram matrix's eigen-decomposition; dependent columns dropped)."""
    h = np.zeros((Q.shape[1], W.shape[1]))
    before = np.sqrt(np.maximum(np.diag(ops.gram(W, W)), 0.0))
    for _ in range(2):
        if Q.shape[1]:
            c = ops.gram(Q, W)
            W = W - Q @ c
            h += c
    G = ops.gram(W, W)
    G = (G + G.T) / 2
    d, U = np.linalg.eigh(G)
    keep = d > (DROP * max(float(before.max(initial=0.0)), 1e-300)) ** 2
    U, d = U[:, keep], d[keep]
    Qn = W @ (U / np.sqrt(d))
    R = np.sqrt(d)[:, None] * U.T  # W = Qn R
    return Qn, h, R


def backward_errors(ops, s: np.ndarray, X: np.ndarray) -> np.ndarray:
    """||P(s) x|| / ((|s|**2 ||M|| + |s| ||C|| + ||K||) ||x||) per pair (-), 1-norms."""
    if not len(s):
        return np.zeros(0)
    nM, nC, nK = ops.norms_of_products()
    Xr, Xi = X.real.copy(order="F"), X.imag.copy(order="F")
    MX = ops.mass(Xr) + 1j * ops.mass(Xi)
    CX = ops.damping(Xr) + 1j * ops.damping(Xi)
    KX = ops.stiffness(Xr) + 1j * ops.stiffness(Xi)
    R = MX * s**2 + CX * s + KX
    num = _sum(ops.comm, np.sum(np.abs(R), axis=0))
    den = _sum(ops.comm, np.sum(np.abs(X), axis=0))
    return num / ((np.abs(s) ** 2 * nM + np.abs(s) * nC + nK) * np.maximum(den, 1e-300))


def solve_quadratic_toar(
    system, speed: float, radius: float, *, n_wanted: int = 16, tol: float = 1e-8
) -> QuadraticModes:
    """The same eigenpairs by SLEPc's PEP (TOAR, shift-and-invert at 0, real arithmetic): the
    ``n_wanted`` nearest 0 (each of a conjugate pair counts), doubled until one lies past
    ``radius``; those with |s| <= ``radius`` returned (module text)."""
    while True:
        out, beyond = _toar(system, speed, radius, n_wanted, tol)
        if beyond or n_wanted >= system.size // 2:
            return out
        n_wanted *= 2


def _toar(system, speed: float, radius: float, n_wanted: int, tol: float) -> tuple[QuadraticModes, bool]:
    from petsc4py import PETSc
    from slepc4py import SLEPc

    comm = system.model.comm
    beyond = False

    class _Damping:
        def mult(self, A, x, y):
            system.damping_mult(speed, x, y)

    C = PETSc.Mat().createPython(system.K.getSizes(), _Damping(), comm=system.K.getComm())
    C.setUp()
    pep = SLEPc.PEP().create(system.K.getComm())
    try:
        pep.setOperators([system.K, C, system.M])
        pep.setType(SLEPc.PEP.Type.TOAR)
        pep.setProblemType(SLEPc.PEP.ProblemType.GENERAL)
        pep.setDimensions(n_wanted)
        pep.setTarget(0.0)
        pep.setWhichEigenpairs(SLEPc.PEP.Which.TARGET_MAGNITUDE)
        pep.setTolerances(tol, 500)
        st = pep.getST()
        st.setType(SLEPc.ST.Type.SINVERT)
        ksp = st.getKSP()
        ksp.setType("preonly")
        ksp.getPC().setType("cholesky")
        ksp.getPC().setFactorSolverType("mumps")
        system.K.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        pep.solve()
        nconv = pep.getConverged()
        s, X = [], []
        xr, xi = system.K.createVecRight(), system.K.createVecRight()
        for i in range(nconv):
            z = pep.getEigenpair(i, xr, xi)
            beyond = beyond or abs(z) > radius
            if z.imag < 0 or abs(z) > radius:
                continue
            s.append(z)
            X.append(xr.getArray().copy() + 1j * xi.getArray())
        steps = pep.getIterationNumber()
    except PETSc.Error as exc:
        raise ComputationError(f"SLEPc's PEP failed at {speed:.4g} rad/s (error code {exc.ierr})") from None
    finally:
        pep.destroy()
        C.destroy()
    s_arr = np.asarray(s, dtype=complex)
    order = np.argsort(np.abs(s_arr))
    Xa = np.column_stack(X)[:, order] if X else np.zeros((system.K.getLocalSize()[0], 0), complex)
    Xa = Xa / np.sqrt(_sum(comm, np.sum(np.abs(Xa) ** 2, axis=0)))
    ops = Products(system, speed, None, comm)
    return QuadraticModes(s_arr[order], Xa, backward_errors(ops, s_arr[order], Xa), steps, 0), beyond
