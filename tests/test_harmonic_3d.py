"""The 3D harmonic response (rotorpillar.fem3d.harmonic.harmonic_response) against the
complex system it solves, assembled and solved here directly.

The module reduces (K - Omega**2 M + i Omega C - h (P_x + P_z)) U = h (e P_x - i e P_z) 1
to the plate's two rows by Woodbury's identity over one real LDL^T of K - Omega**2 M.
The reference builds the whole complex matrix from K and M (scipy) and solves it with a
sparse LU: another factorisation of another matrix, so agreement is the reduction's
exactness, not a repeat of its arithmetic.  Tolerance 1e-6 relative: both are direct
solves of one badly scaled system (K's diagonal spans 14 decades, the Dirichlet rows' 1
to the rigid plate's 1.5e14 N/m) whose condition grows near a mode (one speed is 2 %
below the first bending mode).  Measured on this mesh: 3e-9 to 1e-7 between this
module and the reference, and 5e-9 to 4e-8 between the real 2 x 2 block LU the module
used before and the reference: round-off of the same size.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorpillar.scene import load_scene, override


def _complex_reference(model, rotor, tip_damping, w):
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    from rotorpillar.fem3d.harmonic import shaft_pull

    def csr(mat):
        indptr, indices, data = mat.getValuesCSR()
        return sp.csr_matrix((data, indices, indptr), shape=mat.getSize())

    K, M = csr(model.K), csr(model.M)
    N = model.tube_dofs
    h = shaft_pull(rotor.shaft_stiffness, rotor.mass, rotor.shaft_damping, w)
    D = np.zeros(K.shape[0], complex)
    D[N] = -h + 1j * w * tip_damping
    D[N + 2] = -h
    A = (K - w**2 * M).astype(complex) + sp.diags(D)
    b = np.zeros(K.shape[0], complex)
    b[N], b[N + 2] = h * rotor.eccentricity, -1j * h * rotor.eccentricity
    U = spla.spsolve(A.tocsc(), b)
    tip = U[N]
    return tip, h / rotor.shaft_stiffness * (tip + rotor.eccentricity)


@pytest.mark.slow
def test_the_plates_two_rows_are_the_whole_complex_system():
    from rotorpillar.fem3d import assemble_pillar, modal_analysis
    from rotorpillar.fem3d.harmonic import harmonic_response
    from rotorpillar.fem3d.rotor_top import RotorOnTop

    s = override(load_scene("paper"), ["mesh.elements_around=8", "mesh.elements_along=6"])
    first = modal_analysis(s, top=True, n_modes=4).omega[0]
    speeds = np.array([5.0, 0.98 * first, 15.1, 40.0, 95.0])
    model = assemble_pillar(s, top=True)
    rotor = RotorOnTop.from_scene(s)
    try:
        got = harmonic_response(model, rotor, s.pillar.damping, speeds)
        ref = [_complex_reference(model, rotor, s.pillar.damping, w) for w in speeds]
    finally:
        model.K.destroy()
        model.M.destroy()
    tip = np.array([r[0] for r in ref])
    shaft = np.array([r[1] for r in ref])
    assert np.allclose(got.tip, tip, rtol=1e-6, atol=0.0)
    assert np.allclose(got.shaft, shaft, rtol=1e-6, atol=0.0)
    assert got.dofs == model.size


def _petsc(a):
    from petsc4py import PETSc

    a = a.tocsr()
    out = PETSc.Mat().createAIJ(a.shape, csr=(a.indptr.astype(PETSc.IntType), a.indices.astype(PETSc.IntType), a.data))
    out.assemble()
    return out


def test_the_shifted_matrix_is_the_axpys_bit_for_bit():
    """shifted_in_place (a scaled copy of M on K's pattern, then K added) against what it
    replaced: K copied, then M added times -omega**2 on its own pattern (entry by entry).
    The response depends on these values only, so equal bits keep every response the same.
    A random K (a superset pattern, as the tube's: its stiffness couples what the mass does
    not) and M with values of 14 decades, at speeds from 0 to past the modes."""
    import scipy.sparse as sp
    from petsc4py import PETSc

    from rotorpillar.fem3d.harmonic import mass_on_pattern, shifted_in_place

    rng = np.random.default_rng(3)
    n = 60
    k = sp.random(n, n, density=0.15, random_state=rng) * 1e12
    k = k + k.T + sp.identity(n) * 1e13
    m_pattern = sp.random(n, n, density=0.05, random_state=rng)
    m = (m_pattern + m_pattern.T + sp.identity(n)) * 1e-2
    k = k + m * 1e-3  # M's pattern inside K's (scipy drops the zeros of 0 * m)
    K, M = _petsc(k), _petsc(m)
    A, MK = K.duplicate(copy=False), mass_on_pattern(K, M)
    B = K.duplicate(copy=False)
    for omega in (0.0, 1.7, 312.5, 4.4e4):
        K.copy(B, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        B.axpy(-(omega**2), M, structure=PETSc.Mat.Structure.SUBSET_NONZERO_PATTERN)
        shifted_in_place(A, K, MK, omega)
        a, b = A.getValuesCSR(), B.getValuesCSR()
        assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
        assert np.array_equal(a[2], b[2]), omega
