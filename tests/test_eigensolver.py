"""The block Lanczos eigen-solve gives the modes SLEPc's Krylov-Schur gives.

Both stop when every wanted pair has a relative residual of the
shift-inverted problem below tol = 1e-10; for a symmetric pencil the
eigenvalue error is bounded by that residual (and is in fact of its
square), so the two agree far inside the 1e-8 relative demanded of the
modes written to modal.json.  Independently of either solver's own
estimate: each vector's Rayleigh quotient x^T K x / x^T M x is its
eigenvalue to 1e-9 (quadratic in the vector's error), the vectors are
M-orthonormal to 1e-10 (Gram-Schmidt twice), and each lies in the span of
Krylov-Schur's vectors of the same eigenvalue to 1e-8 (squared norm of
its M-projection; the angle is of the order of the residual).
Cases: the bare tube (clamped: sigma = 0), the tube with its rigid top plate
(massless rows tied statically to the plate), and a free-free tube (six
rigid-body modes; a negative shift).  Degenerate pairs must come out twice.
"""

import numpy as np
import pytest

from rotorpillar.fem3d import assemble_pillar
from rotorpillar.fem3d.eigensolver import solve_gep_shift_invert
from rotorpillar.fem3d.model import assemble_model
from rotorpillar.scene import Mesh, load_scene, override

# every test here solves a 3D model: the slow tier (tests/conftest.py)
pytestmark = pytest.mark.slow

MESH = Mesh(elements_around=16, elements_along=6)


def check_same_modes(K, M, n, sigma=0.0):
    ref = solve_gep_shift_invert(K, M, n, sigma=sigma, method="krylovschur")
    blk = solve_gep_shift_invert(K, M, n, sigma=sigma, method="block", block=4)
    assert blk.method == "block" and blk.solves > 0
    scale = max(np.max(np.abs(ref.eigenvalues)), 1e-300)
    assert np.allclose(blk.eigenvalues, ref.eigenvalues, rtol=1e-8, atol=1e-8 * scale)
    assert np.max(blk.errors) <= 1e-10
    X = np.stack([x.getArray() for x in blk.vectors], axis=1)
    Xr = np.stack([x.getArray() for x in ref.vectors], axis=1)
    y, z = K.createVecLeft(), K.createVecLeft()
    MX = np.empty_like(X)
    for j, x in enumerate(blk.vectors):
        M.mult(x, z)
        MX[:, j] = z.getArray()
        K.mult(x, y)
        rayleigh = x.dot(y) / x.dot(z)
        assert rayleigh == pytest.approx(blk.eigenvalues[j], rel=1e-9, abs=1e-9 * scale)
    assert np.allclose(X.T @ MX, np.eye(n), atol=1e-10)
    # the same vectors: each block vector lies in the span of Krylov-Schur's vectors
    # of its eigenvalue (a degenerate pair: any basis of the pair's plane)
    P = Xr.T @ MX
    for j in range(n):
        near = np.abs(ref.eigenvalues - blk.eigenvalues[j]) <= 1e-6 * scale
        assert np.sum(P[near, j] ** 2) == pytest.approx(1.0, abs=1e-8)
    for sol in (ref, blk):
        for x in sol.vectors:
            x.destroy()
    return blk.eigenvalues


@pytest.mark.parametrize("top", [False, True])
def test_block_lanczos_gives_krylov_schurs_modes(top):
    # equal roll and pitch inertias of the gondola: the bending pair exactly degenerate
    s = override(load_scene("paper"), ["gondola.roll_inertia=850"])
    model = assemble_pillar(s, top=top, mesh=MESH)
    lam = check_same_modes(model.K, model.M, 9)
    # the first bending pair (x and y) is found twice
    assert lam[1] == pytest.approx(lam[0], rel=1e-7)
    model.K.destroy()
    model.M.destroy()


def test_block_lanczos_free_free_with_negative_shift():
    s = override(load_scene("paper"), ["pillar.height=2.0"])
    mesh = Mesh(elements_around=24, elements_along=3)
    model = assemble_model(s.pillar, mesh, clamped=False)
    K, M = model.K, model.M
    first = solve_gep_shift_invert(K, M, 8, sigma=-1.0, method="krylovschur").eigenvalues[-1]
    lam = check_same_modes(K, M, 10, sigma=-(0.5**2) * first)
    assert np.all(np.abs(lam[:6]) <= 1e-6 * lam[6])  # the rigid-body modes
    K.destroy()
    M.destroy()


def test_mass_matrix_read_in_place_equals_petsc4pys_copy():
    """The block method reads M's CSR arrays in place (ctypes) and drops its zeros:
    the same matrix, entry for entry, as petsc4py's getValuesCSR with scipy's
    eliminate_zeros (exact: no arithmetic, only selection)."""
    import scipy.sparse as sp

    from rotorpillar.fem3d.block_lanczos import _petsc_csr, seq_csr, without_zeros

    model = assemble_pillar(load_scene("paper"), top=True, mesh=MESH)
    ai, aj, av = model.M.getValuesCSR()
    ref = sp.csr_matrix((av, aj, ai), shape=model.M.getSize())
    ref.eliminate_zeros()
    for A in (_petsc_csr(model.M), seq_csr(model.M)):
        assert A.nnz == ref.nnz < len(av) and (A != ref).nnz == 0
    # rows without entries (not in an assembled matrix) take the other path
    rng = np.random.default_rng(5)
    D = rng.standard_normal((40, 30)) * (rng.random((40, 30)) < 0.2)
    D[5:9] = 0.0
    B = sp.csr_matrix(D)  # rows 5..8 empty
    B.data[::3] = 0.0  # explicit zeros kept in the pattern
    assert np.any(np.diff(B.indptr) == 0)
    C = without_zeros(B.indptr, B.indices, B.data, B.shape)
    B.eliminate_zeros()
    assert (C != B).nnz == 0 and C.nnz == B.nnz
    model.K.destroy()
    model.M.destroy()


def test_band_modes_are_the_lowest_of_a_fixed_count_and_pass_the_band():
    """modal.n_modes = 0: the modes are the lowest ones of a fixed-count solve
    (the same eigenpairs: frequencies to the solver's tolerance, 1e-8 relative
    on a 1e-8 residual), every mode below the band's edge is there, and the
    last one lies beyond it."""
    from rotorpillar.fem3d import BAND_MODES, modal_analysis
    from rotorpillar.reduced.band import excitation_band

    scene = override(load_scene("paper"), ["mesh.elements_around=16", "mesh.elements_along=6"])
    assert scene.modal.n_modes == 0
    edge = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    band = modal_analysis(scene, top=False, use_cache=False)
    fixed = modal_analysis(scene, top=False, n_modes=2 * BAND_MODES + 8, use_cache=False)
    k = len(band.omega)
    assert k >= BAND_MODES and band.omega[-1] > edge
    assert np.allclose(band.omega, fixed.omega[:k], rtol=1e-8)
    assert np.sum(np.asarray(fixed.omega) < edge) <= k
