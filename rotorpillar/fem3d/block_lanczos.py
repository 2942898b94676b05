"""Block Lanczos for K x = lambda M x, shift-invert, over one MUMPS factorisation.

The operator is A = (K - sigma M)^-1 M, self-adjoint in the M inner product;
its largest |theta| give the lambda = sigma + 1/theta nearest sigma.  The
basis V (M-orthonormal) grows by one block per step: W = A V_j by one
MUMPS solve with ``block`` right-hand sides (MatMatSolve: the factors are
read once per block instead of once per column), orthogonalised against the
whole basis twice (classical Gram-Schmidt, twice is enough), then made
M-orthonormal by the eigen-decomposition of its Gram matrix (columns that
are already in the basis are dropped: the space is exhausted there).  After
each step, Rayleigh-Ritz on the basis: T = V^T M A V, whose column blocks
are the orthogonalisation's coefficients (no extra products), and whose
eigenpairs (theta, s) give x = V s with the residual A x - theta x = F s_j:
F is the part of the last block's image outside the basis (its M-Gram
matrix comes with the orthogonalisation), s_j the Ritz vector's entries on
the last block (every earlier block's image lies inside the basis).  No
restart: the basis is a few times the wanted count.

The start is A R for a random R (seeded per MPI rank): inside the range of
A, so the massless rows (Dirichlet rows, the rigid top's statically tied
dofs) are consistent from the first vector on, and the M inner product is
a norm on the whole basis.  Vectors are distributed as the PETSc rows of
K; the small dense products are summed over the communicator.
"""

from __future__ import annotations

import numpy as np

from ..errors import ComputationError

#: A column whose M-norm after orthogonalisation is below this fraction of its
#: norm before carries nothing new (round-off): it is dropped.
DROP = 1e-10


def modal_solve_failure(tool: str, exc) -> ComputationError:
    """The one-line error of a failed modal solve, with the usual cause."""
    return ComputationError(
        f"{tool} failed in the modal solve (error code {exc.ierr}; a MUMPS "
        "factorisation failure is typical of an unclamped or disconnected "
        "model)"
    )


def shifted_cholesky(K, M, sigma: float = 0.0):
    """A MUMPS Cholesky solver of K - sigma M, not yet factorised: (ksp, the shifted
    matrix or None when it is K itself).  ``ksp.setUp()`` factorises; the caller
    destroys both."""
    from petsc4py import PETSc

    A = None
    if sigma != 0.0:  # the factorisation leaves K untouched: no copy at sigma 0
        A = K.copy()
        A.axpy(-sigma, M)
    ksp = PETSc.KSP().create(K.getComm())
    ksp.setOperators(K if A is None else A)
    ksp.setType(PETSc.KSP.Type.PREONLY)
    pc = ksp.getPC()
    pc.setType(PETSc.PC.Type.CHOLESKY)
    pc.setFactorSolverType("mumps")
    return ksp, A


def block_lanczos(
    K,
    M,
    n_modes: int,
    *,
    sigma: float = 0.0,
    tol: float = 1e-10,
    block: int = 8,
    max_columns: int = 400,
    seed: int = 20240607,
):
    """The ``n_modes`` eigenpairs nearest ``sigma``: (eigenvalues ascending, their
    PETSc Vecs, steps, relative residuals, columns solved), or None when the
    basis would pass ``max_columns`` before they converge."""
    from petsc4py import PETSc

    comm = K.getComm().tompi4py()
    block = max(int(block), 2)  # degenerate pairs need two vectors per step
    if max_columns < n_modes + block:
        return None
    ksp, A = shifted_cholesky(K, M, sigma)
    try:
        ksp.setUp()
        op = _Operator(K, M, ksp.getPC().getFactorMatrix(), comm)
        rng = np.random.default_rng([seed, comm.rank])
        W = op.solve(op.mass(rng.standard_normal((op.n_local, block))))
        basis = _Basis(op.n_local, max_columns + block, 6 * n_modes + 2 * block)
        Vn, MVn, _, _ = op.orthonormalise(W, op.mass(W), basis)
        T = np.zeros((0, 0))
        steps = 0
        while True:
            steps += 1
            m0 = basis.m
            basis.append(Vn, MVn)
            V = basis.V
            W = op.solve(MVn)  # A V_j
            # the new block's images against the whole basis: C = V^T M A V_j, a
            # column block of T = V^T M A V (symmetric in the M inner product)
            Vn, MVn, C, G = op.orthonormalise(W, op.mass(W), basis)
            m = basis.m
            T = np.pad(T, ((0, m - m0), (0, m - m0)))
            T[:, m0:] = C
            T[m0:, :] = C.T
            theta, S = np.linalg.eigh(T)
            order = np.argsort(-np.abs(theta))[:n_modes]
            theta, S = theta[order], S[:, order]
            if len(theta) == n_modes:
                # A x - theta x = F s_j for x = V s: F, the part of A V_j outside
                # the basis (Gram G), s_j the Ritz vector's entries on the last block
                Sj = S[m0:, :]
                err = np.sqrt(np.maximum(np.einsum("ik,ij,jk->k", Sj, G, Sj), 0.0)) / np.abs(theta)
                if np.all(err <= tol):
                    break
            if m + block > max_columns:
                return None
            if Vn.shape[1] == 0:
                if len(theta) < n_modes:
                    raise ComputationError(
                        f"block Lanczos: the model has only {len(theta)} finite eigenvalues, {n_modes} asked"
                    )
                return None  # exhausted, not converged
        X = V @ S
        vecs = []
        for k in range(n_modes):
            x = K.createVecRight()
            x.setArray(X[:, k])
            vecs.append(x)
        lam = sigma + 1.0 / theta
        order = np.argsort(lam)
        return lam[order], [vecs[i] for i in order], steps, err[order], op.solves
    except PETSc.Error as exc:
        raise modal_solve_failure("PETSc", exc) from None
    finally:
        ksp.destroy()
        if A is not None:
            A.destroy()


def seq_csr(M):
    """A sequential AIJ matrix as scipy CSR without its explicit zeros (the vector
    mass matrix's uncoupled components: 2/3 of its entries).

    petsc4py's getValuesCSR copies row by row (0.5 s at 150k dofs, with
    scipy's zero elimination about a tenth of the eigen-solve); PETSc's own
    arrays (MatGetRowIJ, MatSeqAIJGetArrayRead, through ctypes) filtered in
    one pass cost a fraction of that.  getValuesCSR stays the fallback.
    """
    try:
        return _petsc_csr(M)
    except (OSError, AttributeError, RuntimeError):
        import scipy.sparse as sp

        ai, aj, av = M.getValuesCSR()
        A = sp.csr_matrix((av, aj, ai), shape=M.getSize())
        A.eliminate_zeros()
        return A


def without_zeros(ia, ja, vals, shape):
    """CSR of (ia, ja, vals) without its zero entries, in new arrays (the inputs may be PETSc's)."""
    import scipy.sparse as sp

    keep = vals != 0.0
    if len(ia) > 1 and np.all(ia[1:] > ia[:-1]):
        # no empty row (an assembled matrix has its diagonal): per-row counts,
        # no array as long as the entries (fresh memory is slow on this VM)
        indptr = np.zeros(len(ia), dtype=ja.dtype)
        indptr[1:] = np.cumsum(np.add.reduceat(keep, ia[:-1], dtype=ja.dtype))
    else:
        before = np.zeros(len(keep) + 1, dtype=ja.dtype)  # kept entries before entry k
        before[1:] = np.cumsum(keep, dtype=ja.dtype)
        indptr = before[ia]
    return sp.csr_matrix((vals[keep], ja[keep], indptr), shape=shape, copy=False)


def _petsc_csr(M):
    """``without_zeros`` of a real SeqAIJ matrix's own arrays, read in place."""
    import ctypes

    from petsc4py import PETSc

    if M.getType() != "seqaij" or PETSc.ScalarType != np.float64:
        raise RuntimeError("not a real sequential AIJ matrix")
    lib = ctypes.CDLL(_petsc_library())
    c_int = {4: ctypes.c_int32, 8: ctypes.c_int64}[np.dtype(PETSc.IntType).itemsize]
    h = ctypes.c_void_p(M.handle)
    n, done = c_int(), c_int()
    ia_p, ja_p = ctypes.POINTER(c_int)(), ctypes.POINTER(c_int)()
    v_p = ctypes.POINTER(ctypes.c_double)()
    if (
        lib.MatGetRowIJ(h, 0, 0, 0, ctypes.byref(n), ctypes.byref(ia_p), ctypes.byref(ja_p), ctypes.byref(done)) != 0
        or not done.value
    ):
        raise RuntimeError("MatGetRowIJ")
    try:
        if lib.MatSeqAIJGetArrayRead(h, ctypes.byref(v_p)) != 0:
            raise RuntimeError("MatSeqAIJGetArrayRead")
        try:
            ia = np.ctypeslib.as_array(ia_p, shape=(n.value + 1,))
            ja = np.ctypeslib.as_array(ja_p, shape=(int(ia[-1]),))
            vals = np.ctypeslib.as_array(v_p, shape=(int(ia[-1]),))
            return without_zeros(ia, ja, vals, M.getSize())
        finally:
            lib.MatSeqAIJRestoreArrayRead(h, ctypes.byref(v_p))
    finally:
        lib.MatRestoreRowIJ(h, 0, 0, 0, ctypes.byref(n), ctypes.byref(ia_p), ctypes.byref(ja_p), ctypes.byref(done))


def _petsc_library() -> str:
    """The PETSc shared library this process has loaded (petsc4py links it)."""
    with open("/proc/self/maps") as maps:
        for line in maps:
            path = line.split()[-1]
            if "/libpetsc" in path and ".so" in path:
                return path
    raise OSError("libpetsc is not among the loaded libraries")


class _Operator:
    """Block products with M, block solves with the factors, reduced dot products."""

    def __init__(self, K, M, factor, comm):
        self.K, self.M, self.F, self.comm = K, M, factor, comm
        self.n_local, self.n = K.getLocalSize()[0], K.getSize()[0]
        self.solves = 0
        # serial: scipy's CSR product (PETSc's MatMatMult with a dense block
        # costs more than the solve)
        self.csr = seq_csr(M) if comm.size == 1 else None

    def _dense(self, X):
        from petsc4py import PETSc

        return PETSc.Mat().createDense(
            ((self.n_local, self.n), (None, X.shape[1])), array=np.asfortranarray(X), comm=self.K.getComm()
        )

    def mass(self, X):
        if self.csr is not None:
            return self.csr @ X
        D = self._dense(X)
        Y = self.M.matMult(D)
        out = Y.getDenseArray().copy(order="F")
        D.destroy()
        Y.destroy()
        return out

    def solve(self, Y):
        out = np.empty(Y.shape, order="F")  # the solution lands here: PETSc wraps it, no copy
        B, X = self._dense(Y), self._dense(out)
        try:
            self.F.matSolve(B, X)
        finally:
            B.destroy()
            X.destroy()
        self.solves += Y.shape[1]
        return out

    def gram(self, X, Y):
        """X^T Y summed over the ranks."""
        return self.comm.allreduce(X.T @ Y)

    def dots(self, X, Y):
        """Column-wise x_k . y_k summed over the ranks."""
        return self.comm.allreduce(np.einsum("ij,ij->j", X, Y))

    def orthonormalise(self, W, MW, basis):
        """W M-orthogonal to the basis (twice) and M-orthonormal, dependent columns
        dropped: (new block, its M-product, V^T M W, M-Gram of the projected W)."""
        before = np.sqrt(np.maximum(self.dots(W, MW), 0.0))
        V, MV = basis.V, basis.MV
        C = np.zeros((V.shape[1], W.shape[1]))
        for _ in range(2):
            if V.shape[1]:
                c = self.gram(MV, W)
                W, MW, C = W - V @ c, MW - MV @ c, C + c
        G = self.gram(W, MW)
        G = (G + G.T) / 2
        d, U = np.linalg.eigh(G)
        keep = d > (DROP * max(float(before.max()), 1e-300)) ** 2
        Q = U[:, keep] / np.sqrt(d[keep])
        return W @ Q, MW @ Q, C, G


class _Basis:
    """The M-orthonormal basis V and M V, in buffers that grow by doubling."""

    def __init__(self, rows: int, limit: int, guess: int):
        self.limit = limit
        cap = min(guess, limit)  # usually enough: no copy
        self._V = np.empty((rows, cap), order="F")  # columns contiguous: appending
        self._MV = np.empty((rows, cap), order="F")  # a block writes one stretch
        self.m = 0

    @property
    def V(self):
        return self._V[:, : self.m]

    @property
    def MV(self):
        return self._MV[:, : self.m]

    def append(self, X, MX):
        k = X.shape[1]
        if self.m + k > self._V.shape[1]:
            cap = min(max(2 * self._V.shape[1], self.m + k), max(self.limit, self.m + k))
            for name in ("_V", "_MV"):
                old = getattr(self, name)
                new = np.empty((old.shape[0], cap), order="F")
                new[:, : self.m] = old[:, : self.m]
                setattr(self, name, new)
        self._V[:, self.m : self.m + k] = X
        self._MV[:, self.m : self.m + k] = MX
        self.m += k
