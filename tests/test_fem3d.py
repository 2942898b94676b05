"""The 3D tube model against beam theory, ring theory, symmetry and itself.

Sources and tolerances
----------------------
1. Beam theory where it holds: a slender thick tube (H = 20, D0 = 0.5,
   D1 = 0.3 m: D/t = 5, H/r_g = 137).  Timoshenko's first cantilever
   frequency (Cowper's shear coefficient; rotorpillar.reduced.pillar) within
   0.25 %: Timoshenko and Euler-Bernoulli differ by 0.07 % here, the 3D clamp
   (which also stops the Poisson contraction of the base section) stiffens
   by ~0.1 %, the mesh adds < 0.1 % (measured by refinement).  The second
   bending mode against Timoshenko's second root within 0.5 %.  Eq. 2 on the
   3D mode gives m_col/4 within 0.5 % (the beam-theory limit).
2. Ring theory (Rayleigh's inextensional modes; Soedel, *Vibrations of
   Shells and Plates*, 3rd ed., Sec. 4.2 and 13.2): a free-free tube with
   the paper's wall (D/t = 100) and length 2R has lobed modes with
   omega_n**2 = D n**2 (n**2-1)**2 / (rho t R**4 (n**2+1)), D = E t**3 /
   (12 (1-nu**2)).  Within 1 % for n = 2, 3: thin-shell error (t/R)**2 ~
   4e-4, the free edges' anticlastic zones (length ~sqrt(R t), 7 % of the
   tube, where the bending stiffness tends to E t**3/12) lower it by at most
   0.6 %, 96 quadratic cells around add +0.3 % (measured rate h**3.8).
   Torsion of a circular tube is Saint-Venant's without warping: the first
   clamped-free torsion mode is (pi/2) sqrt(G/rho) / H exactly (1e-4: the
   mesh's sine along the height); the k-th bending mode in x has k-1 sign
   changes along the height.
3. Symmetry: the mesh is invariant under a quarter turn, so bending in x and
   y are one degenerate pair (equal to 1e-7, the eigensolver's accuracy on
   a double eigenvalue) and come out aligned with x and y.
4. Refinement: uniform layers L = 5, 10, 20 are nested spaces, so the
   frequency falls monotonically (Rayleigh-Ritz); the differences shrink by
   more than 2 per halving (order >= 1 although the clamp's edge singularity
   caps it; 2.6 observed).
5. Masses on top: the free tube's r^T M r is rho A H (1e-6: quadratic arcs,
   64 around, miss O((2 pi/64)**4) ~ 2e-7 of the annulus) and the rigid top
   and the ring mass each add exactly the top mass (1e-8); the top section of the rigid-top modes moves rigidly
   (1e-9 m per unit tip); the loaded first bending frequency is within
   0.5 % of the tip model c1 / (m_r + m_top) (the Rayleigh quotient of the
   bare mode on the loaded tube; the mode-shape change is second order).
6. phi^T K phi / phi^T M phi = omega**2 to 1e-7 (a degenerate pair, split
   ~1e-8 by round-off, shares the mean of its two Rayleigh quotients).
"""

import math

import numpy as np
import pytest

from rotorpillar.fem3d import assemble_pillar, modal_analysis, tip_reduction
from rotorpillar.fem3d.modal import run_modal
from rotorpillar.fem3d.model import assemble_model
from rotorpillar.reduced.pillar import cowper_shear_coefficient, omega_euler_bernoulli, omega_timoshenko, section_of
from rotorpillar.scene import Mesh, load_scene, override

# every test here solves a 3D model: the slow tier (tests/conftest.py)
pytestmark = pytest.mark.slow

THICK = ["pillar.outer_diameter=0.5", "pillar.inner_diameter=0.3"]


def timoshenko(p, k=1):
    sec = section_of(p)
    kappa = cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    return omega_timoshenko(
        p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area, sec.second_moment, p.height, k
    )


@pytest.fixture(scope="module")
def thick():
    s = override(load_scene("paper"), THICK)
    mesh = Mesh(elements_around=8, elements_along=40, elements_through=2, grading=10.0)
    return s, modal_analysis(s, top=False, n_modes=10, mesh=mesh)


def test_slender_thick_tube_is_a_timoshenko_beam(thick):
    s, r = thick
    p = s.pillar
    w1, w2 = r.first("bending_x", n_axial=0), r.first("bending_x", n_axial=1)
    assert w1 == pytest.approx(timoshenko(p), rel=2.5e-3)
    assert w2 == pytest.approx(timoshenko(p, 2), rel=5e-3)
    sec = section_of(p)
    eb = omega_euler_bernoulli(p.youngs_modulus, sec.second_moment, sec.mass_per_length, p.height)
    assert w1 == pytest.approx(eb, rel=2.5e-3)
    red = tip_reduction(r, p)
    assert red.m_reduced == pytest.approx(sec.mass_per_length * p.height / 4, rel=5e-3)
    assert red.tip_stiffness == pytest.approx(red.m_reduced * w1**2, rel=1e-12)


def test_torsion_and_the_order_of_the_bending_modes(thick):
    s, r = thick
    p = s.pillar
    G = p.youngs_modulus / (2 * (1 + p.poisson_ratio))
    assert r.first("torsion") == pytest.approx(math.pi / 2 * math.sqrt(G / p.density) / p.height, rel=1e-4)
    bx = [i for i, k in enumerate(r.kind) if k == "bending_x"]
    assert [r.n_axial[i] for i in bx] == list(range(len(bx)))  # 1st, 2nd, ... bending
    assert r.n_circumferential[r.index("torsion")] == 0


def test_the_paper_tube_is_not_an_euler_bernoulli_beam():
    """The same comparison fails for the thin paper tube: shear lowers it by 1.6 %."""
    s = load_scene("paper")
    r = modal_analysis(s, top=False, n_modes=2, mesh=Mesh(elements_around=16, elements_along=10))
    p = s.pillar
    sec = section_of(p)
    eb = omega_euler_bernoulli(p.youngs_modulus, sec.second_moment, sec.mass_per_length, p.height)
    assert r.omega[0] / eb - 1 < -0.01
    assert r.omega[0] == pytest.approx(timoshenko(p), rel=3e-3)


def test_degenerate_pairs_and_generalised_quantities(thick):
    _, r = thick
    assert r.kind[:2] == ("bending_x", "bending_y")
    assert r.omega[1] == pytest.approx(r.omega[0], rel=1e-7)
    assert np.allclose(r.tip[0], [1, 0], atol=1e-8) and np.allclose(r.tip[1], [0, 1], atol=1e-8)
    assert r.normalisation[:2] == ("unit_tip", "unit_tip")
    assert np.allclose(r.modal_stiffness / r.modal_mass, r.omega**2, rtol=1e-7)
    assert np.all(np.diff(r.omega) >= -1e-9 * r.omega[1:])


def ring_omega(p, n):
    t = (p.outer_diameter - p.inner_diameter) / 2
    R = (p.outer_diameter + p.inner_diameter) / 4
    D = p.youngs_modulus * t**3 / (12 * (1 - p.poisson_ratio**2))
    return math.sqrt(D * n**2 * (n**2 - 1) ** 2 / (p.density * t * R**4 * (n**2 + 1)))


def test_free_free_thin_tube_has_the_ring_modes():
    s = override(load_scene("paper"), ["pillar.height=2.0"])
    p = s.pillar
    mesh = Mesh(elements_around=96, elements_along=4, elements_through=1)
    model = assemble_model(p, mesh, clamped=False)
    w2 = ring_omega(p, 2)
    # six rigid-body modes at zero: shift below them
    r = run_modal(model, 12, sigma=-((0.5 * w2) ** 2), mesh_section=mesh)
    i2 = r.index("ovalling", n_circumferential=2)
    i3 = r.index("ovalling", n_circumferential=3)
    assert r.omega[i2] == pytest.approx(w2, rel=1e-2)
    assert r.omega[i3] == pytest.approx(ring_omega(p, 3), rel=1e-2)
    assert r.omega[i2 + 1] == pytest.approx(r.omega[i2], rel=1e-7)  # the cos/sin pair
    assert np.all(r.omega[:6] < 1e-3 * w2)  # rigid-body modes


def test_error_falls_under_refinement():
    s = override(load_scene("paper"), THICK)
    w = [
        modal_analysis(
            s, top=False, n_modes=2, mesh=Mesh(elements_around=8, elements_along=L, elements_through=2, grading=1.0)
        ).omega[0]
        for L in (5, 10, 20)
    ]
    assert w[0] > w[1] > w[2]
    assert (w[0] - w[1]) / (w[1] - w[2]) > 2.0


@pytest.mark.parametrize("top_model", ["rigid", "ring_mass"])
def test_the_top_mass_is_all_there(top_model):
    s = override(load_scene("paper"), [f"modal.top_model={top_model}"])
    mesh = Mesh(elements_around=64, elements_along=2)
    p = s.pillar

    def translated_mass(model):
        rx = model.influence(0)
        y = model.M.createVecLeft()
        model.M.mult(rx, y)
        return rx.dot(y)

    tube = section_of(p).mass_per_length * p.height
    assert translated_mass(assemble_model(p, mesh, clamped=False)) == pytest.approx(tube, rel=1e-6)
    # clamped: the base nodes' share is in the Dirichlet rows, the same in both
    bare, loaded = (assemble_pillar(s, top=top, mesh=mesh) for top in (False, True))
    assert translated_mass(loaded) - translated_mass(bare) == pytest.approx(s.gondola.mass, rel=1e-8)
    assert loaded.extra_dofs == (6 if top_model == "rigid" else 0)


def test_rigid_top_moves_rigidly_and_matches_the_tip_model():
    s = load_scene("paper")
    mesh = Mesh(elements_around=32, elements_along=8)
    bare = modal_analysis(s, top=False, n_modes=4, mesh=mesh)
    top = modal_analysis(s, top=True, n_modes=4, mesh=mesh)
    red = tip_reduction(bare, s.pillar)
    i = top.index("bending_x", n_axial=0)
    assert top.omega[i] == pytest.approx(math.sqrt(red.tip_stiffness / (red.m_reduced + s.gondola.mass)), rel=5e-3)
    # unit tip: the modal mass is the pillar's share plus the whole top mass
    assert top.modal_mass[i] - s.gondola.mass == pytest.approx(red.m_reduced, rel=0.05)
    # the top vertices follow the plate: u = U + Theta x (x - (0, 0, H))
    q = top.rigid_top[i]
    on_top = np.isclose(top.points[:, 2], s.pillar.height)
    d = top.points[on_top] - [0, 0, s.pillar.height]
    rigid = q[:3] + np.cross(q[3:], d)
    assert np.abs(top.shapes[i][on_top] - rigid).max() < 1e-9
    assert q[0] == pytest.approx(1.0, rel=1e-9)


def test_tetrahedra_and_linear_elements_run_and_bound_from_above(tmp_path):
    """Conforming elements bound the frequency from above; tetrahedra and
    linear hexahedra lock in a thin wall (stiffer), quadratic hexahedra least.
    Each writes its VTU on its own cells (quadratic: every P2 node), in VTK's
    node order (tests/fixtures.check_tube_vtu)."""
    import fixtures

    from rotorpillar.fem3d.output import write_modes_vtu

    s = load_scene("paper")
    tim = timoshenko(s.pillar)
    w = {}
    vtk_types = {("hexahedron", 2): 29, ("tetrahedron", 2): 24, ("hexahedron", 1): 12}
    for ct, deg, T in (("hexahedron", 2, 1), ("tetrahedron", 2, 1), ("hexahedron", 1, 2)):
        m = Mesh(elements_around=16, elements_along=10, elements_through=T, degree=deg, cell_type=ct)
        r = modal_analysis(s, top=False, n_modes=2, mesh=m)
        assert r.kind[0].startswith("bending") and r.cell_type == ct and r.degree == deg
        w[(ct, deg)] = r.omega[0]
        got = fixtures.check_tube_vtu(
            write_modes_vtu(tmp_path / f"{ct}{deg}.vtu", r),
            s.pillar.height,
            s.pillar.outer_diameter / 2,
            s.pillar.inner_diameter / 2,
            around=16,
            through=T,
        )
        assert got["vtk_type"] == vtk_types[(ct, deg)]
        assert got["points"] == r.dofs // 3  # every node of the space, once
    assert w[("hexahedron", 2)] < w[("tetrahedron", 2)] < w[("hexahedron", 1)]
    assert w[("hexahedron", 2)] == pytest.approx(tim, rel=3e-3)
