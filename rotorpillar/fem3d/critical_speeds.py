"""The 3D model's critical speeds: where s = i Omega solves the undamped gyroscopic system.

With s = i Omega, (K - Omega**2 M + i Omega (Omega G)) v = 0, that is

    K v = Omega**2 (M - i G) v,

a Hermitian pencil (G real and skew: M - i G is Hermitian; K is positive
definite, the tube clamped and every rotor dof on a spring), the spatial
ROM's (rotorpillar.reduced.spatial_linear).  Solved as (M - i G) v = nu K v,
nu = 1 / Omega**2, in real arithmetic by its real form

    [[M, G], [-G, M]] [a; b] = nu [[K, 0], [0, K]] [a; b],    v = a + i b,

symmetric with a positive definite right-hand matrix: SLEPc's Krylov-Schur
for a GHEP, the largest nu (the lowest speeds) first, B^-1 by one MUMPS
Cholesky of the block K.  Every eigenvalue of the complex pencil appears
twice in the real form ((a, b) and (-b, a) are v and i v); each cluster of
equal nu gives back half as many complex vectors.  nu <= 0 is a mode the 1x
line never meets (the forward tilt of a disc with J_C > I_d).  Exact for the
undamped model; the damped peaks of the unbalance response lie near them.

Each critical speed takes its whirl from the rotor's orbit
(rotorpillar.fem3d.campbell_tracking), the label of the Campbell branch
whose frequency is nearest Omega there, and what excites it, the spatial
ROM's measure: the cosine, in K's inner product, between the mode and the
static unbalance's rotating load c2 e (d_x - i d_z) (the shaft stretched by
the eccentricity, on the rotor and, opposite, on the gondola), or the
couple unbalance's moment (1, -i) on the spin axis' (pitch, yaw), above
``EXCITATION_TOLERANCE``.
"""

from __future__ import annotations

import numpy as np

from ..errors import ComputationError
from ..reduced.campbell import CampbellBranch, CriticalSpeed
from ..reduced.spatial_linear import EXCITATION_TOLERANCE
from . import campbell_tracking as tr
from .rotor_spatial import shaft_links, tilt_rows

#: nu closer than this (relative) form one cluster: the two copies of each eigenvalue of the
#: complex pencil, and nearly degenerate ones (campbell_tracking.CLUSTER), untangled by kind,
#: each then given its Rayleigh quotient
SAME_NU = 1e-4


def _block(A, B, C, D, comm):
    from petsc4py import PETSc

    return PETSc.Mat().createNest([[A, B], [C, D]], comm=comm).convert("aij")


def undamped_pencil(system, top: float, tol: float = 1e-10, ops=None) -> tuple[np.ndarray, np.ndarray]:
    """(Omega ascending up to ``top`` (rad/s), V (n_local, k) complex): the critical speeds and
    their modes (module text), each degenerate cluster untangled into its kinds
    (campbell_tracking.untangle); collective."""
    from petsc4py import PETSc
    from slepc4py import SLEPc

    from .campbell_branches import BranchTracker

    tracker = BranchTracker(system, system.model.comm, ops)
    rows, gram = tracker.rows, tracker.gram

    comm = system.model.comm
    pcomm = system.K.getComm()
    minus_g = system.G.copy()
    minus_g.scale(-1.0)
    A = _block(system.M, system.G, minus_g, system.M, pcomm)
    B = _block(system.K, None, None, system.K, pcomm)
    minus_g.destroy()
    n_local = system.K.getLocalSize()[0]
    nu_min = 1.0 / top**2
    n = 16
    try:
        while True:
            eps = SLEPc.EPS().create(pcomm)
            try:
                eps.setOperators(A, B)
                eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
                eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
                eps.setDimensions(n)
                eps.setWhichEigenpairs(SLEPc.EPS.Which.LARGEST_REAL)
                eps.setTolerances(tol, 1000)
                # no purification (one more solve a vector: 0.75 s of 3.1 on paper): it
                # cleans the null space of a singular B from the vectors, and B = diag(K, K)
                # is positive definite here (module text)
                eps.setPurify(False)
                st = eps.getST()
                st.setType(SLEPc.ST.Type.SHIFT)
                ksp = st.getKSP()
                ksp.setType("preonly")
                ksp.getPC().setType("cholesky")
                ksp.getPC().setFactorSolverType("mumps")
                eps.solve()
                nconv = eps.getConverged()
                nu, W = [], []
                x = B.createVecRight()
                for i in range(nconv):
                    nu.append(eps.getEigenpair(i, x).real)
                    W.append(x.getArray().copy())
                x.destroy()
            except PETSc.Error as exc:
                raise ComputationError(f"SLEPc failed on the critical speeds' pencil (error code {exc.ierr})") from None
            finally:
                eps.destroy()
            nu_arr = np.asarray(nu)
            if len(nu_arr) < n:
                raise ComputationError(f"the critical speeds' pencil: SLEPc converged {len(nu_arr)} of {n}")
            if np.min(nu_arr) < nu_min or n >= 2 * system.size:
                break
            n *= 2
    finally:
        A.destroy()
        B.destroy()
    order = np.argsort(-nu_arr)
    nu_arr = nu_arr[order]
    Wm = np.column_stack(W)[:, order]
    # the block layout of a converted nest: this rank's real rows, then its imaginary rows
    V = Wm[:n_local] + 1j * Wm[n_local:]
    keep = nu_arr >= nu_min
    nu_arr, V = nu_arr[keep], V[:, keep]
    speeds, vecs = [], []
    i = 0
    while i < len(nu_arr):
        j = i + 1
        while j < len(nu_arr) and abs(nu_arr[j] - nu_arr[i]) <= SAME_NU * abs(nu_arr[i]):
            j += 1
        Q = _complex_basis(V[:, i:j], comm, (j - i + 1) // 2)
        if Q.shape[1] > 1:
            Q = tr.untangle(Q, list(range(Q.shape[1])), rows, gram)
            m, c0, k = tracker.quadratic_forms(0.0, Q)
            g = tracker.quadratic_forms(1.0, Q)[1] - c0
            nus = np.real(m - 1j * g) / np.real(k)  # q^H (M - i G) q / q^H K q
        else:
            nus = nu_arr[i : i + 1]
        for q, nu in zip(Q.T, nus):
            speeds.append(1.0 / np.sqrt(nu))
            vecs.append(q)
        i = j
    order = np.argsort(speeds)
    V_out = np.column_stack(vecs)[:, order] if vecs else np.zeros((n_local, 0), complex)
    return np.asarray(speeds)[order], V_out


def _complex_basis(V: np.ndarray, comm, k: int) -> np.ndarray:
    """k orthonormal complex vectors spanning the columns of V (its rank is k: v and i v)."""
    G = V.conj().T @ V
    if comm.size > 1:
        G = comm.allreduce(G)
    d, U = np.linalg.eigh((G + G.conj().T) / 2)
    top = np.argsort(-d)[:k]
    return V @ (U[:, top] / np.sqrt(np.maximum(d[top], 1e-300)))


def critical_speeds(
    system, top: float, speeds: np.ndarray, branches: list[CampbellBranch], factor, ops=None
) -> list[CriticalSpeed]:
    """The critical speeds up to ``top`` (rad/s) with their whirl, exciter and branch (module
    text); ``factor`` the factors of system.K (rotorpillar.fem3d.quadratic_eigen.stiffness_factor)."""
    from .campbell_branches import BranchTracker

    top = min(top, float(speeds[-1]))
    tracker = BranchTracker(system, system.model.comm, ops)
    W, V = undamped_pencil(system, top, ops=tracker.ops)
    R = tracker.rows(V)
    energy = tracker.energies(V)
    kinds = tracker.kinds(V, R, list(range(V.shape[1])), energy)
    loads = _loads(system)
    cos = _excitation(system, V, loads, factor)
    out = []
    for j, w in enumerate(W):
        whirl = tracker.whirl(R[:, j], energy[j])
        cs, cc = cos[0][j], cos[1][j]
        by = (
            "static unbalance"
            if cs > EXCITATION_TOLERANCE
            else "couple unbalance"
            if cc > EXCITATION_TOLERANCE
            else "neither"
        )
        label = kinds[j]
        if branches:
            same = [b for b in branches if b.kind == kinds[j]] or branches
            label = min(same, key=lambda b: _distance(b, speeds, w)).label
        out.append(
            CriticalSpeed(
                speed=float(w),
                label=label,
                whirl=whirl,
                excited_by=by,
                method="undamped gyroscopic pencil K v = Omega**2 (M - i G) v (3D)",
            )
        )
    return out


def _distance(branch: CampbellBranch, speeds: np.ndarray, w: float) -> float:
    f = np.asarray(branch.frequency, float)
    ok = np.isfinite(f)
    if not np.any(ok) or w < speeds[ok][0] or w > speeds[ok][-1]:
        return np.inf
    return abs(float(np.interp(w, speeds[ok], f[ok])) - w)


def _loads(system) -> list[np.ndarray]:
    """The static and the couple unbalance's loads on the plate's and the rotor's rows
    (complex, per unit e and U_c)."""
    rotor = system.rotor
    D = shaft_links(rotor.height, rotor.tilts)
    static = rotor.lateral_stiffness * (D[0] - 1j * D[1])
    couple = np.zeros(6 + rotor.dofs, complex)
    pitch, yaw = tilt_rows(rotor)
    couple[pitch], couple[yaw] = 1.0, -1j
    return [static, couple]


def _excitation(system, V: np.ndarray, loads: list[np.ndarray], factor) -> list[np.ndarray]:
    """Per load, per mode: |v^H f| / (sqrt(f^H K^-1 f) sqrt(v^H K v)) (-)."""
    comm = system.model.comm
    K = system.K
    lo, hi = K.getOwnershipRange()
    first = system.plate
    nr = 6 + system.rotor.dofs
    mine = lo <= first < hi
    x, y = K.createVecRight(), K.createVecLeft()
    vKv = np.zeros(V.shape[1])
    for c in range(V.shape[1]):
        for part in (V[:, c].real, V[:, c].imag):
            x.setArray(np.ascontiguousarray(part))
            K.mult(x, y)
            vKv[c] += x.dot(y)
    out = []
    for f in loads:
        fKf = 0.0
        for part in (f.real, f.imag):
            x.set(0.0)
            if mine:
                x.getArray()[first - lo : first - lo + nr] = part
            factor.solve(x, y)
            yr = np.zeros(nr)
            if mine:
                yr = y.getArray(readonly=True)[first - lo : first - lo + nr].copy()
            if comm.size > 1:
                yr = comm.allreduce(yr)
            fKf += float(part @ yr)
        rows = np.zeros((nr, V.shape[1]), complex)
        if mine:
            rows = V[first - lo : first - lo + nr]
        if comm.size > 1:
            rows = comm.allreduce(rows)
        vf = np.abs(rows.conj().T @ f)
        norm = np.sqrt(max(fKf, 0.0)) * np.sqrt(np.maximum(vKv, 0.0))
        out.append(np.where(norm > 0, vf / np.maximum(norm, 1e-300), 0.0))
    for v in (x, y):
        v.destroy()
    return out
