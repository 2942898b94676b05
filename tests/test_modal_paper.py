"""The paper's tube on the default mesh: what issue 3's "done" asks.

Sources and tolerances
----------------------
- First bending against Timoshenko's cantilever (Cowper's shear
  coefficient), 0.5 %: the issue's budget for the default mesh.  The
  converged 3D value (30.817 rad/s, docs/fem3d.md) is itself 0.013 % below
  Timoshenko's 30.821, so the budget is the mesh's.
- The n = 2 shell modes: a clamped-free tube this long (L/R = 20) ovalises
  almost like a free ring (Rayleigh's inextensional ring, plane strain; see
  tests/test_fem3d.py), the clamp only adds membrane energy: between the
  ring value and 3 % above it (converged +0.8 %, the default mesh adds
  +0.9 %).  They must lie below the second bending mode and be named
  ovalling with n = 2, in cos/sin pairs.
- The slow test compares the default mesh with a finer one (twice the cells
  around, twice along, graded harder): bending within 0.5 %, the n = 2
  shell mode within 1.5 %.  Measured against that mesh: bending +0.136 %,
  n = 2 +0.806 %; against four times along (the mesh this test used before)
  +0.152 % and +0.807 %: the reference moves by 0.016 % of bending, thirty
  times inside the budget, for 4.7 s of CPU instead of 11.6 s.
"""

import math

import pytest

from rotorpillar.fem3d import modal_analysis
from rotorpillar.reduced.pillar import cowper_shear_coefficient, omega_timoshenko, section_of
from rotorpillar.scene import Mesh, load_scene

# every test here solves the 3D model at the scene's mesh: the slow tier (tests/conftest.py)
pytestmark = pytest.mark.slow


def ring_n2(p):
    t = (p.outer_diameter - p.inner_diameter) / 2
    R = (p.outer_diameter + p.inner_diameter) / 4
    D = p.youngs_modulus * t**3 / (12 * (1 - p.poisson_ratio**2))
    return math.sqrt(D * 4 * 9 / (p.density * t * R**4 * 5))


@pytest.fixture(scope="module")
def paper():
    s = load_scene("paper")
    return s, modal_analysis(s, top=False), modal_analysis(s, top=True)


def test_default_mesh_first_bending_within_half_a_percent(paper):
    s, bare, _ = paper
    p = s.pillar
    sec = section_of(p)
    kappa = cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    w_t = omega_timoshenko(p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area, sec.second_moment, p.height)
    assert bare.kind[:2] == ("bending_x", "bending_y")
    assert bare.omega[0] == pytest.approx(w_t, rel=5e-3)


def test_shell_modes_below_the_second_bending_are_found_and_named(paper):
    s, bare, top = paper
    w2 = bare.first("bending_x", n_axial=1)
    assert w2 is not None
    shells = [i for i, k in enumerate(bare.kind) if k == "ovalling" and bare.omega[i] < w2]
    assert len(shells) >= 2 and len(shells) % 2 == 0
    assert all(bare.n_circumferential[i] == 2 for i in shells)
    ring = ring_n2(s.pillar)
    assert ring < bare.omega[shells[0]] < 1.03 * ring
    assert bare.omega[shells[1]] == pytest.approx(bare.omega[shells[0]], rel=1e-7)
    # the masses on top: bending drops, the rigid top stiffens the ovalling
    assert top.first("bending_x") < bare.first("bending_x")
    assert top.first("ovalling", n_circumferential=2) > bare.omega[shells[0]]


@pytest.mark.slow
def test_default_mesh_against_a_finer_one(paper):
    s, bare, _ = paper
    d = s.mesh
    fine = Mesh(
        elements_around=2 * d.elements_around,
        elements_along=2 * d.elements_along,  # 4x: +0.016 % on bending, 2.5x the CPU
        elements_through=d.elements_through,
        degree=d.degree,
        cell_type=d.cell_type,
        grading=100.0,
    )
    r = modal_analysis(s, top=False, n_modes=4, mesh=fine)
    assert bare.first("bending_x") == pytest.approx(r.first("bending_x"), rel=5e-3)
    assert bare.first("ovalling") == pytest.approx(r.first("ovalling"), rel=1.5e-2)
    assert bare.first("bending_x") > r.first("bending_x")  # conforming: from above
