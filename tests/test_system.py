"""The reduced system's modes and quasi-normal coefficients (Eq. 5-7).

Reference: a numerical generalized eigen-solve (scipy.linalg.eigh) of the 2x2
pencil (K, M) of Eq. 4, and the projections u^T M u, u^T F, u^T C u done by
matrix algebra.  Both are exact up to round-off, so 1e-10 relative.
"""

import numpy as np
import pytest
from scipy.linalg import eigh

from rotorpillar.reduced.system import ReducedSystem, linear_modes, omega_pair, paper_example

CASES = [
    paper_example(),
    paper_example(5e6, 25e3),
    ReducedSystem(3.0e3, 7.0e2, 5.0, 0.01, 2.0e6, 8.0e5, 1e3, 2e2),
    ReducedSystem(1.0e5, 10.0, 1.0, 1e-3, 1.0e9, 1.0e3, 0.0, 0.0),
]  # widely split scales


@pytest.mark.parametrize("s", CASES)
def test_eq5_against_numerical_eigensolve(s):
    lam = eigh(s.stiffness_matrix(), s.mass_matrix(), eigvals_only=True)
    assert np.array(omega_pair(s)) == pytest.approx(np.sqrt(lam), rel=1e-10)


@pytest.mark.parametrize("s", CASES)
def test_modal_vectors_and_projections(s):
    K, M, C = s.stiffness_matrix(), s.mass_matrix(), s.damping_matrix()
    c2e = s.shaft_stiffness * s.eccentricity
    F = np.array([-c2e, c2e])  # Eq. 4 right-hand side over cos(q4)
    for r in linear_modes(s).resonances[:2]:
        u = np.array(r.shape)
        assert u[0] == 1.0
        resid = (K - r.omega**2 * M) @ u
        assert np.linalg.norm(resid) <= 1e-9 * np.linalg.norm(K @ u)
        I = u @ M @ u
        assert r.modal_mass == pytest.approx(I, rel=1e-12)
        assert r.forcing == pytest.approx(u @ F / I, rel=1e-12)
        assert r.coupling == pytest.approx(u @ F, rel=1e-12)
        assert r.two_n == pytest.approx(u @ C @ u / I, rel=1e-12, abs=1e-15)


def test_y_resonance_is_the_shaft_alone():
    s = paper_example()
    r3 = linear_modes(s).resonances[2]
    assert r3.omega == pytest.approx(np.sqrt(s.shaft_stiffness / s.rotor_mass))
    # the paper prints omega3 = 15.8 for c2 = 0.4e6, m_C = 1.6e3 (Sec. 2.5)
    assert r3.omega == pytest.approx(15.8, rel=2e-3)
