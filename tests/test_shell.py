"""The shell model of the tube's mid-surface, and the closed forms that check it.

Sources and tolerances:

- Sanders' shell theory with shear-diaphragm ends has exact trigonometric
  modes (Leissa, Vibration of Shells, NASA SP-288, 1973, ch. 2).  Its n = 1
  modes are beam bending: for a long tube (L/R = 2000) they reach the
  Euler-Bernoulli beam, (m pi/L)**2 sqrt(E I/(rho A)) with the thin-wall
  I = pi R**3 t, A = 2 pi R t, to 1e-4 (shear and rotary inertia lower it
  by (m pi r/L)**2 (1 + E/(kappa G))/2 with r**2 = R**2/2: 4e-6 here, but
  already 4e-4 at L/R = 200).  Its n = 2 mode of a very long tube is the plane-strain
  ring (Soedel, Vibrations of Shells and Plates, 2004, sec. 5.3), to 1e-4.
- The FE shell (Naghdi, with transverse shear) against Sanders (Kirchhoff,
  no transverse shear) on the simply supported tube, 32 x 40 cells: the
  converged FE differs from Sanders by 3e-4 (n = 2) and -5e-4 (n = 3) - the
  difference between first-order shell theories at t/R = 0.02 (transverse
  shear alone lowers n = 2 by about 2e-4) - and the mesh adds < 2e-4: 1e-3.
- Cantilever bending against Timoshenko's beam (Cowper's kappa, the exact
  tube section): Sanders and Timoshenko already differ by 1.7e-3 for the
  simply supported m = 1 mode, whose half-wave (20 m) is far shorter than the
  cantilever's; 1e-3 here.
- A rigid rotation about a diameter strains nothing: the bending strain's
  grad(u) grad(n) term cancels the director's turning with the curved
  surface; without it (the flat-facet formula) the twist integrates to
  pi L / (2 R) exactly.  Ours must fall with refinement (geometric
  interpolation error, ~h**8 measured) below 1e-6 of that.
- The shell's eigen-solve is fem3d's one wrapper: its two methods (block
  Lanczos, SLEPc's Krylov-Schur) stop on a relative residual of 1e-10, so
  the frequencies they find agree to far better than 1e-8 (the eigenvalue's
  error is of the residual's order or below; omega halves it).
- Observed order of the Q2 shell's frequencies: 4 in theory (2k for
  degree k = 2); band [3, 5] on meshes 8..24 around.
"""

import math

import numpy as np
import pytest

from rotorpillar.converge import richardson
from rotorpillar.reduced.cylinder import ring_frequency, sanders_frequency
from rotorpillar.reduced.pillar import cowper_shear_coefficient, omega_timoshenko, tube_section

E, NU, RHO, R, T, H = 2.1e11, 0.3, 8.1e3, 0.99, 0.02, 20.0


def test_sanders_n1_is_the_euler_bernoulli_beam_for_a_long_tube():
    L = 2000.0
    I, A = math.pi * R**3 * T, 2 * math.pi * R * T
    for m in (1, 2):
        beam = (m * math.pi / L) ** 2 * math.sqrt(E * I / (RHO * A))
        assert sanders_frequency(m, 1, E, NU, RHO, R, T, L) == pytest.approx(beam, rel=1e-4)


def test_sanders_n2_of_a_very_long_tube_is_the_ring():
    assert sanders_frequency(1, 2, E, NU, RHO, R, T, 2e4) == pytest.approx(
        ring_frequency(2, E, NU, RHO, R, T), rel=1e-4
    )


def _shell(na, nz, ends="clamped-free", n_modes=12, method=None):
    from rotorpillar.fem3d.naghdi import ShellDiscretisation, ShellSection, shell_modal_analysis

    return shell_modal_analysis(
        ShellSection(E, NU, RHO, T), R, H, ShellDiscretisation(na, nz), n_modes=n_modes, ends=ends, method=method
    )


def _first(res, kind, n=None):
    for w, k, nn in zip(res.omega, res.kind, res.n_circumferential):
        if k.startswith(kind) and (n is None or nn == n):
            return w
    raise AssertionError(f"no {kind} mode (n={n}) in {list(zip(res.omega, res.kind))}")


@pytest.mark.slow  # shell models solved
def test_simply_supported_shell_matches_sanders():
    res = _shell(32, 40, ends="simply-supported", n_modes=12)
    # the axial rigid translation comes first (free axial motion), at ~0
    assert res.omega[0] < 1e-2 and res.kind[0] == "axial"
    for n in (1, 2, 3):
        assert _first(res, "bending" if n == 1 else "ovalling", n) == pytest.approx(
            sanders_frequency(1, n, E, NU, RHO, R, T, H), rel=1e-3
        )


@pytest.mark.slow  # shell models solved
def test_cantilever_bending_is_timoshenkos_beam():
    res = _shell(16, 20, n_modes=4)
    sec = tube_section(2.0, 1.96, RHO)
    kappa = cowper_shear_coefficient(2.0, 1.96, NU)
    timo = omega_timoshenko(E, NU, kappa, RHO, sec.area, sec.second_moment, H)
    assert res.kind[:2] == ["bending_x", "bending_y"] or set(res.kind[:2]) == {"bending_x", "bending_y"}
    assert res.omega[0] == pytest.approx(timo, rel=1e-3)
    assert res.omega[1] == pytest.approx(res.omega[0], rel=1e-8)  # the x-y pair


@pytest.mark.slow  # shell models solved
def test_shell_frequencies_agree_between_the_eigensolvers_methods():
    block, ks = (_shell(12, 15, n_modes=8, method=m) for m in ("block", "krylovschur"))
    assert block.omega == pytest.approx(ks.omega, rel=1e-8)
    # the pairs' members may swap (a degenerate pair's basis is arbitrary); the kinds may not
    assert sorted(block.kind) == sorted(ks.kind)


def test_rigid_rotation_has_no_bending_strain():
    import ufl
    from dolfinx import fem

    from rotorpillar.fem3d import naghdi as sh
    from rotorpillar.fem3d.naghdi import mid_surface_mesh
    from rotorpillar.mesh.midsurface import MidSurface

    facet = math.pi * H / (2 * R)
    ours = []
    for na in (8, 16):
        msh, _, _ = mid_surface_mesh(MidSurface(R, H, na, 10))
        cell = msh.ufl_cell()
        V = fem.FunctionSpace(
            msh,
            ufl.MixedElement(
                [ufl.VectorElement("Lagrange", cell, 2, dim=3), ufl.VectorElement("Lagrange", cell, 2, dim=2)]
            ),
        )
        w = fem.Function(V)
        # rotation about x: u = e_x cross x, director turn e_x cross n = sin(theta) e_z
        w.sub(0).interpolate(lambda x: np.vstack([0 * x[0], -x[2], x[1]]))
        w.sub(1).interpolate(lambda x: np.vstack([0 * x[0], x[1] / np.hypot(x[0], x[1])]))
        u, b = ufl.split(w)
        e1, e2, n = sh.cylinder_frame(ufl.SpatialCoordinate(msh))
        P = sh.tangent_projector(e1, e2)
        beta = b[0] * e1 + b[1] * e2
        dx = ufl.dx(metadata={"quadrature_degree": 4})
        sq = lambda k, dx=dx: fem.assemble_scalar(fem.form(ufl.inner(k, k) * dx))
        ours.append(sq(sh.bending_strain(u, beta, P, n)))
        assert sq(ufl.sym(P.T * ufl.grad(beta) * P)) == pytest.approx(facet, rel=1e-3)
        assert sq(sh.membrane_strain(u, P)) < 1e-3 and sq(sh.shear_strain(u, beta, P, n)) < 1e-3
    assert ours[1] < ours[0] and ours[1] < 1e-6 * facet


@pytest.mark.slow  # shell models solved
def test_q2_shell_converges_at_fourth_order():
    runs = [_shell(na, int(1.25 * na)) for na in (8, 12, 16, 24)]
    h = [1 / 12, 1 / 16, 1 / 24]
    for kind in ("bending", "ovalling"):
        f = [_first(r, kind) for r in runs[1:]]
        p = richardson(h, f, 4.0).order
        assert p is not None and 3.0 <= p <= 5.0, (kind, f, p)
