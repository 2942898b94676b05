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
PETSc here is real, so the complex system is solved in its real 2 x 2
block form,

    [[A_r, -A_i], [A_i, A_r]] [U_r; U_i] = [F_r; F_i],

A_r = K - Omega**2 M - Re(h) P, A_i = Omega C - Im(h) P, one MUMPS
numerical LU per speed on one symbolic analysis.  Out: the tip (the plate's U_x) and the shaft deflection in X,
x_r - U_x - e = (h / c2)(U_x + e), as complex amplitudes.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np


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
    """unknowns of the real block system (2 x the model's)"""
    seconds_per_speed: float
    """wall time of one speed: assembly, factorisation, solve (s)"""


def shaft_pull(shaft_stiffness: float, rotor_mass: float, shaft_damping: float, omega: float) -> complex:
    """h = c2 (c2 - k_r) / k_r, k_r = c2 - m Omega**2 + i Omega b2 (N/m): the condensed rotor's pull."""
    kr = shaft_stiffness - rotor_mass * omega**2 + 1j * omega * shaft_damping
    return shaft_stiffness * (shaft_stiffness - kr) / kr


def harmonic_response(model, rotor, tip_damping: float, speeds) -> HarmonicResponse:
    """The steady response of an AssembledPillar with the rigid top (collective).

    The block matrices [[K, 0], [0, K]] and [[M, 0], [0, M]] are converted
    once (with explicit zeros where the plate's coupling terms go), so every
    speed has the same sparsity: MUMPS analyses it once and refactorises
    numerically per speed (0.6 of a fresh LU here).
    """
    from petsc4py import PETSc

    if model.extra_dofs == 0:
        raise ValueError("the harmonic response hangs the rotor on the rigid top plate")
    N = model.tube_dofs
    rows = (N, N + 2)
    c2, b2, m, e = rotor.shaft_stiffness, rotor.shaft_damping, rotor.mass, rotor.eccentricity
    speeds = np.asarray(speeds, dtype=float)
    tip, shaft = np.empty(len(speeds), complex), np.empty(len(speeds), complex)
    K, M = model.K, model.M
    lo, hi = K.getOwnershipRange()
    n_local = K.getLocalSize()[0]
    start = time.perf_counter()
    Z = PETSc.Mat().createAIJ(K.getSizes(), nnz=(1, 0), comm=model.comm)
    Z.setUp()
    for r in rows:
        if lo <= r < hi:
            Z.setValue(r, r, 0.0)
    Z.assemble()
    BK = PETSc.Mat().createNest([[K, Z], [Z, K]], comm=model.comm).convert("aij")
    BM = PETSc.Mat().createNest([[M, None], [None, M]], comm=model.comm).convert("aij")
    A = BK.copy()
    # the nest's converted layout: per rank, its real rows then its imaginary rows
    base = A.getOwnershipRange()[0]
    real = lambda r: base + (r - lo)
    imag = lambda r: base + n_local + (r - lo)
    ksp = PETSc.KSP().create(model.comm)
    ksp.setOperators(A)
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    b, x = A.createVecLeft(), A.createVecRight()
    add = PETSc.InsertMode.ADD_VALUES
    for i, w in enumerate(speeds):
        h = shaft_pull(c2, m, b2, w)
        BK.copy(A, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        A.axpy(-(w**2), BM, structure=PETSc.Mat.Structure.SUBSET_NONZERO_PATTERN)
        a_imag = {N: w * tip_damping - h.imag, N + 2: -h.imag}
        force = {N: h * e, N + 2: h * -1j * e}
        b.set(0.0)
        for r in rows:
            if lo <= r < hi:
                A.setValue(real(r), real(r), -h.real, addv=add)
                A.setValue(imag(r), imag(r), -h.real, addv=add)
                A.setValue(real(r), imag(r), -a_imag[r], addv=add)
                A.setValue(imag(r), real(r), a_imag[r], addv=add)
                b.setValue(real(r), force[r].real)
                b.setValue(imag(r), force[r].imag)
        A.assemble()
        b.assemble()
        ksp.solve(b, x)
        arr = x.getArray(readonly=True)
        ux = np.zeros(2)
        if lo <= N < hi:
            ux[:] = arr[N - lo], arr[n_local + N - lo]
        if model.comm.size > 1:
            ux = model.comm.allreduce(ux)
        tip[i] = complex(ux[0], ux[1])
        shaft[i] = h / c2 * (tip[i] + e)
    for obj in (ksp, x, b, A, BM, BK, Z):
        obj.destroy()
    per = (time.perf_counter() - start) / max(len(speeds), 1)
    return HarmonicResponse(speeds, tip, shaft, 2 * model.size, per)


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
