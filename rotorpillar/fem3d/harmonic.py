"""Steady unbalance response of the 3D tube with the rotor at its top (the 3D Bode curve).

At a constant speed Omega, theta = Omega t, every displacement is
Re(U e^{i theta}).  The rotor centre, on its shaft c2 at the rigid top
plate and damped by b2 against the ground (as in rotorpillar.fem3d.full_order),
has the dynamic stiffness k_r = c2 - m_C Omega**2 + i Omega b2; condensed
onto the plate it leaves the shaft's pull h (U_p + E) on the plate's row,
h = c2 (c2 - k_r) / k_r, with E = e along X (the unbalance e cos theta) and
-i e along the tube's axis (e sin theta).  The structure:

    (K - Omega**2 M + i Omega C - h (P_x + P_z)) U = h (e P_x - i e P_z) 1

with C the pillar's dashpot b1 on the plate's X and P the plate's rows.
The damping and the rotor's pull act on the plate's two rows only: with
A0 = K - Omega**2 M (real, symmetric) and E the plate's rows (X and the
tube's axis), the system is (A0 + E S E^T) U = E f, S = diag(-h + i Omega b1,
-h), f = h e (1, -i).  So the plate's u = E^T U solves the 2 x 2 complex
system (I + G S) u = G f with G = E^T A0^-1 E: per speed one real LDL^T of
A0 (MUMPS; one symbolic analysis for all speeds) and two solves, exact to
round-off (Woodbury's identity; the spatial response,
:func:`spatial_response`, does the same with more rows).  It replaced the
real 2 x 2 block form [[A_r, -A_i], [A_i, A_r]] and its LU of twice the
size: 85 speeds on the paper's [full_order] mesh took ~11 s that way.
Out: the tip (the plate's U_x) and the shaft deflection in X,
x_r - U_x - e = (h / c2)(U_x + e), as complex amplitudes.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..scene import Scene


@dataclass(frozen=True)
class HarmonicResponse:
    """Complex amplitudes of the 3D model's steady unbalance response."""

    speeds: np.ndarray
    """Omega (rad/s)"""
    tip: np.ndarray
    """plate U_x (m), complex"""
    shaft: np.ndarray
    """shaft deflection in X (m), complex"""
    dofs: int
    """unknowns of the real symmetric system factorised at each speed (the model's)"""
    seconds_per_speed: float
    """wall time of one speed: the matrix, its factorisation, two solves (s)"""


def mass_on_pattern(K, M):
    """M on K's nonzero pattern (zeros where M has none; M's lies inside K's), for
    :func:`shifted_in_place`."""
    from petsc4py import PETSc

    out = K.duplicate(copy=False)
    out.axpy(1.0, M, structure=PETSc.Mat.Structure.SUBSET_NONZERO_PATTERN)
    return out


def shifted_in_place(A, K, MK, omega: float) -> None:
    """A = K - omega**2 M on K's pattern (MK: ``mass_on_pattern``), the values the axpy of M on
    its own pattern (SUBSET_NONZERO_PATTERN) gave, bit for bit: that one goes entry by entry
    through MatSetValues, K + (-omega**2 M) rounded twice (25 ms a speed on the 16 x 10 tube's
    850,000 nonzeros); here the scaled copy of MK, then K added by an axpy on equal patterns
    (PETSc's BLAS axpy: a fused multiply-add by 1.0 is the same single rounding of the sum),
    ~2 ms.  A K - omega**2 MK axpy would fuse the product into the sum: 1e-10 apart."""
    from petsc4py import PETSc

    same = PETSc.Mat.Structure.SAME_NONZERO_PATTERN
    MK.copy(A, structure=same)
    A.scale(-(omega**2))
    A.axpy(1.0, K, structure=same)


def shaft_pull(shaft_stiffness: float, rotor_mass: float, shaft_damping: float, omega: float) -> complex:
    """h = c2 (c2 - k_r) / k_r, k_r = c2 - m Omega**2 + i Omega b2 (N/m): the condensed rotor's pull."""
    kr = shaft_stiffness - rotor_mass * omega**2 + 1j * omega * shaft_damping
    return shaft_stiffness * (shaft_stiffness - kr) / kr


def harmonic_response(model, rotor, tip_damping: float, speeds) -> HarmonicResponse:
    """The steady response of an AssembledPillar with the rigid top (collective): per speed
    one real LDL^T of K - Omega**2 M on one symbolic analysis, and the plate's 2 x 2 complex
    system (module text).  An undamped mode of the tube with its plate exactly at a speed
    (K - Omega**2 M singular) is a ComputationError naming the speed."""
    from petsc4py import PETSc

    from ..errors import ComputationError
    from .block_lanczos import shifted_cholesky

    if model.extra_dofs == 0:
        raise ValueError("the harmonic response hangs the rotor on the rigid top plate")
    N = model.tube_dofs
    rows = (N, N + 2)
    c2, b2, m, e = rotor.shaft_stiffness, rotor.shaft_damping, rotor.mass, rotor.eccentricity
    speeds = np.asarray(speeds, dtype=float)
    tip, shaft = np.empty(len(speeds), complex), np.empty(len(speeds), complex)
    K, M = model.K, model.M
    lo, hi = K.getOwnershipRange()
    start = time.perf_counter()
    # K - Omega**2 M in place, on K's pattern (M's lies inside it: the same space and mesh)
    ksp, A = shifted_cholesky(K, M, sigma=1.0)
    E = K.createVecRight(), K.createVecRight()
    Y = K.createVecRight(), K.createVecRight()
    for vec, r in zip(E, rows):
        vec.set(0.0)
        if lo <= r < hi:
            vec.setValue(r, 1.0)
        vec.assemble()
    MK = mass_on_pattern(K, M)
    try:
        for i, w in enumerate(speeds):
            shifted_in_place(A, K, MK, w)
            ksp.setOperators(A)  # new values, the same pattern: a numerical factorisation only
            try:
                for y, x in zip(Y, E):
                    ksp.solve(x, y)
            except PETSc.Error as exc:
                raise ComputationError(
                    f"the 3D harmonic response at {w:.6g} rad/s: K - Omega**2 M is singular there "
                    f"(an undamped mode of the tube with its plate; error code {exc.ierr})"
                ) from None
            G = np.zeros((2, 2))  # G[j, k] = (A0^-1 E_k) at row j
            for k, y in enumerate(Y):
                arr = y.getArray(readonly=True)
                for j, r in enumerate(rows):
                    if lo <= r < hi:
                        G[j, k] = arr[r - lo]
            if model.comm.size > 1:
                G = model.comm.allreduce(G)
            h = shaft_pull(c2, m, b2, w)
            S = np.diag([-h + 1j * w * tip_damping, -h])
            f = np.array([h * e, -1j * h * e])
            u = np.linalg.solve(np.eye(2) + G @ S, G @ f)
            tip[i] = u[0]
            shaft[i] = h / c2 * (tip[i] + e)
    finally:
        for obj in (ksp, A, MK, *E, *Y):
            if obj is not None:
                obj.destroy()
    per = (time.perf_counter() - start) / max(len(speeds), 1)
    return HarmonicResponse(speeds, tip, shaft, model.size, per)


def harmonic_speeds(resonances, top: float, n: int = 40, dense: int = 15) -> np.ndarray:
    """The 3D curve's speeds (fewer than the ROM's: one LU each): uniform up to
    ``top`` plus ``dense`` within +-5 % of each resonance below it (rad/s)."""
    grid = [np.linspace(top / n, top, n)]
    for w in resonances:
        if 0 < w < top:
            grid.append(np.linspace(0.95 * w, min(1.05 * w, top), dense))
    return np.unique(np.concatenate(grid))


def relative_error(a, b) -> float:
    """max |a - b| / max |b| (-)."""
    b = np.asarray(b)
    return float(np.max(np.abs(np.asarray(a) - b)) / max(np.max(np.abs(b)), 1e-300))


# --------------------------------------------------------------------------
# The spatial model's unbalance response (issue 26): both lateral directions,
# static and couple unbalance, on rotorpillar.fem3d.spatial_system.

#: the unbalance cases: the shaft stretched by the eccentricity, c2 e (cos, sin) (the paper's
#: form: the rotor's coordinates are its mass centre's), the rotating moment U_c Omega**2 about
#: its lateral axes, or both at once (the spatial ROM's rotorpillar.reduced.spatial_response)
UNBALANCE_CASES = ("static", "couple", "both")


@dataclass(frozen=True)
class SpatialResponse:
    """Complex amplitudes x(t) = Re(X e^{i Omega t}) of the rotor-pillar system's steady
    response to one unbalance case, at the top plate and the rotor."""

    case: str
    """"static" or "couple\""""
    speeds: np.ndarray
    """Omega (rad/s)"""
    top: np.ndarray
    """(n, 6) the plate's (u_x, u_y, u_z, theta_x, theta_y, theta_z) (m, rad)"""
    rotor: np.ndarray
    """(n, 5 or 3) the rotor's (x, y, z[, pitch, yaw]) (m, rad)"""
    shaft: np.ndarray
    """(n, 2) the shaft's deflection across the spin axis, in-plane and vertical: the rotor
    centre less the gondola's point at the rotor's height less e (cos, sin) (m)"""
    dofs: int
    """unknowns of the system (-)"""
    seconds_per_speed: float
    """wall time of one speed: the factorisation and the solves (s)"""


def spatial_response(system, speeds, case: str = "static") -> SpatialResponse:
    """The steady unbalance response of a RotorPillarSystem (collective).

    (K - Omega**2 M + i Omega (C + Omega G)) X = F with F = c2 e (d_x - i d_z) ("static":
    the shaft's in-plane and vertical links d stretched by the eccentricity, pulling the rotor
    and, opposite, the gondola's point) or U_c Omega**2 (1, -i) on the spin axis' (pitch, yaw)
    ("couple"), or their sum ("both"): each turns from +x towards +z with the rotor.  Every damping and
    the gyroscopic term act on few dofs or have a low rank (b1, the shaft and the gyroscopic
    matrix on the plate's and the rotor's 6 + 5 dofs, the modal damping W D W^T of rank k),
    so per speed one real symmetric LDL^T factorisation of A = K - Omega**2 M (MUMPS; one
    symbolic analysis for all speeds) and Woodbury's identity with the (11 + k)-square complex
    capacitance matrix give the exact complex response:
    X = A^-1 F - A^-1 L (I + i Omega S L^T A^-1 L)^-1 i Omega S L^T A^-1 F, L = [E, W],
    S = diag(the 11 x 11 block, D).  Exactly at an undamped mode A is singular: a speed there
    is refused with the mode's name left to the caller (a ComputationError).
    """
    from petsc4py import PETSc

    from ..errors import ComputationError
    from .block_lanczos import modal_solve_failure, shifted_cholesky
    from .rotor_spatial import rotor_blocks, shaft_links

    if case not in UNBALANCE_CASES:
        raise ValueError(f"case must be one of {UNBALANCE_CASES}")
    rotor, comm = system.rotor, system.model.comm
    speeds = np.asarray(speeds, dtype=float)
    first, nr = system.plate, 6 + rotor.dofs
    lo, hi = system.K.getOwnershipRange()
    n_local = hi - lo
    mine = lo <= first < hi  # the plate's and the rotor's rows live on one rank (the last)
    Kr, Cr, Mr, Gr = rotor_blocks(rotor, system.damping_law)
    Cr[0, 0] += _tip_damping(system)
    Cr[1, 1] += _tip_damping(system)
    k = len(system.d)
    E = np.zeros((n_local, nr))
    if mine:
        E[first - lo : first - lo + nr] = np.eye(nr)
    L = np.hstack([E, system.W])
    pitch, yaw = (9, 10) if rotor.tilts else (3, 5)
    D = shaft_links(rotor.height, rotor.tilts)
    static = rotor.lateral_stiffness * rotor.eccentricity * (D[0] - 1j * D[1]) if case != "couple" else 0.0
    couple = np.zeros(nr, complex)
    if case != "static":
        couple[pitch], couple[yaw] = rotor.couple_unbalance, -1j * rotor.couple_unbalance
    top, rot = np.zeros((len(speeds), 6), complex), np.zeros((len(speeds), rotor.dofs), complex)
    A = system.K.copy()
    ksp, _ = shifted_cholesky(A, A, 0.0)
    start = time.perf_counter()
    rhs = np.zeros((n_local, 2 + L.shape[1]))
    rhs[:, 2:] = L
    MK = mass_on_pattern(system.K, system.M)
    try:
        for i, w in enumerate(speeds):
            shifted_in_place(A, system.K, MK, w)
            ksp.setOperators(A)
            try:
                ksp.setUp()
            except PETSc.Error as exc:
                raise modal_solve_failure("MUMPS", exc) from None
            F = static + w * w * couple
            if mine:
                rhs[first - lo : first - lo + nr, 0] = F.real
                rhs[first - lo : first - lo + nr, 1] = F.imag
            Y = _block_solve(ksp, A, rhs)
            Af = Y[:, 0] + 1j * Y[:, 1]
            AL = Y[:, 2:]
            LtAL = L.T @ AL
            LtAf = L.T @ Af
            if comm.size > 1:
                LtAL, LtAf = comm.allreduce(LtAL), comm.allreduce(LtAf)
            S = np.zeros((nr + k, nr + k), complex)
            S[:nr, :nr] = Cr + w * Gr
            S[nr:, nr:] = np.diag(system.d)
            iwS = 1j * w * S
            cap = np.eye(nr + k) + iwS @ LtAL
            try:
                c = np.linalg.solve(cap, iwS @ LtAf)
            except np.linalg.LinAlgError:
                raise ComputationError(f"the unbalance response at {w:.6g} rad/s: an undamped mode there") from None
            X = Af - AL @ c
            r = np.zeros(nr, complex)
            if mine:
                r = X[first - lo : first - lo + nr].copy()
            if comm.size > 1:
                r = comm.allreduce(r)
            top[i], rot[i] = r[:6], r[6:]
    finally:
        ksp.destroy()
        A.destroy()
        MK.destroy()
    per = (time.perf_counter() - start) / max(len(speeds), 1)
    h, e = rotor.height, rotor.eccentricity if case != "couple" else 0.0
    shaft = np.column_stack([rot[:, 0] - top[:, 0] - h * top[:, 4] - e, rot[:, 2] - top[:, 2] + 1j * e])
    return SpatialResponse(case, speeds, top, rot, shaft, system.size, per)


def _tip_damping(system) -> float:
    """b1 as the system carries it: the plate's U_x entry of C less the shaft's there (N*s/m)."""
    return float(system.tip_damping)


def _block_solve(ksp, A, rhs: np.ndarray) -> np.ndarray:
    """A^-1 rhs for a block of right-hand sides with the factors (MatMatSolve)."""
    from petsc4py import PETSc

    F = ksp.getPC().getFactorMatrix()
    n_local, n = A.getLocalSize()[0], A.getSize()[0]
    out = np.empty(rhs.shape, order="F")
    B = PETSc.Mat().createDense(((n_local, n), (None, rhs.shape[1])), array=np.asfortranarray(rhs), comm=A.getComm())
    X = PETSc.Mat().createDense(((n_local, n), (None, rhs.shape[1])), array=out, comm=A.getComm())
    try:
        F.matSolve(B, X)
    finally:
        B.destroy()
        X.destroy()
    return out


def scene_spatial_response(
    scene: Scene, speeds, *, mesh=None, case: str = "both", damping_law: str = "gondola", comm=None
) -> SpatialResponse:
    """The scene's 3D unbalance response (``spatial_response``) on ``mesh`` (a scene Mesh
    section; default ``scene.mesh``): the tube with the gondola on its rigid top, the rotor on
    its shaft, b1 both ways, ``pillar.damping_ratio`` on every loaded-tube mode up to twice the
    highest speed asked, b2 by ``damping_law`` (collective)."""
    from . import assemble_pillar
    from .rotor_spatial import SpatialRotor
    from .spatial_system import assemble_system

    model = assemble_pillar(scene, top=True, mesh=mesh, comm=comm)
    system = assemble_system(
        model,
        SpatialRotor.from_scene(scene),
        tip_damping=scene.pillar.damping,
        damping_ratio=scene.pillar.damping_ratio,
        damped_up_to=2.0 * float(np.max(speeds)),
        damping_law=damping_law,
        tol=scene.modal.tolerance,
    )
    try:
        return spatial_response(system, speeds, case)
    finally:
        system.destroy()
        model.K.destroy()
        model.M.destroy()
