"""The 3D side of the spatial model (issue 26) against closed forms, the 1D beam and itself.

Sources and tolerances
----------------------
1. The gondola as a rigid body on the rigid top (fem3d.model.TopBody): the
   free-free tube's 6 x 6 rigid-body mass matrix about the base's centre,
   R^T M R over the six rigid motions, against the closed form of a thin
   annulus (its mass rho A H, centre H/2, inertia m ((Ro**2 + Ri**2)/4 +
   H**2/3) about a base diameter, m (Ro**2 + Ri**2)/2 about the axis) plus
   the gondola (its mass at H + h, its own inertias, the parallel-axis
   terms).  1e-6: quadratic arcs with 64 cells around miss the annulus'
   area by O((2 pi / 64)**4) ~ 2e-7 (tests/test_fem3d.py measures 1e-6 on
   r^T M r); the gondola's part is exact.
2. Torsion with a top inertia: Saint-Venant torsion of a circular tube has
   no warping, so the clamped tube with a disc J_top on its free end is the
   shaft of lambda tan(lambda) = J_pillar / J_top, omega = lambda sqrt(G /
   rho) / H, J_pillar = rho I_p H.  tests/test_fem3d.py holds the bare
   tube's torsion to 1e-4 (the mesh's sine along the height); 2e-4 here
   (a quadratic mesh of 10 graded layers, the end disc included).
3. The SpatialPillarModes of the 3D model against the 1D sources: the first
   bending mode in each plane against the Timoshenko beam with the gondola
   as tip mass and rotary inertia (roll for the rotor's plane, pitch across
   it) within 0.3 % (docs/fem3d.md: the default mesh's +0.16 % and
   Timoshenko's 0.013 % from the converged 3D value); the planes' split from
   the gondola's different roll and pitch inertias within 10 % of the
   beam's (both are the same rotary-inertia term; the 3D tube adds the
   wall's own rotary inertia, equal in both planes); the second bending
   mode within 1.5 % (the default mesh's +0.85 % on it, plus Timoshenko's
   own ~0.3 % there); the axial mode against the bar with a tip mass,
   lambda tan(lambda) = rho A H / m_top, within 0.3 % (Poisson's lateral
   inertia, (nu k r)**2 / 2 ~ 1e-3 at lambda = 1.4 and r = 0.7 m, lowers it).
   The participation of each bending mode against the beam's within 0.5 %.
4. Ovalling modes leave the rigid top: their plate components are below
   1e-7 of their largest wall displacement and their participations below
   1e-7 of the first bending mode's (an n = 2 shape is orthogonal to the n = 0
   and n = 1 motions of the plate on the symmetric mesh; what is left is the
   eigen-solve's residual, 1e-8).
5. The gyroscopic sign: dL/dt = M with L = -J_C Omega e_y (the unbalance
   turns from +x to +z): a step moment about x precesses the spin axis'
   far end (-y) towards +x, phi_z' -> M_x J_C Omega / ((J_C Omega)**2 +
   c**2) with a tilt dashpot c, checked by integrating the rotor's tilt
   equations from rest (scipy's DOP853 at 1e-10; 1e-6: the nutation has
   decayed by e**-15 over the window averaged).
6. The tilt pair on a stiff support (E = 1e13 Pa, a tube of negligible
   mass): backward and forward whirl at -+J_C Omega / (2 I_d) + sqrt((J_C
   Omega / (2 I_d))**2 + k_t / I_d) within 1e-4 (the support's rotational
   compliance k_t / (E I / H) ~ 3e-6); the higher one forward.
7. The block Arnoldi and SLEPc's PEP TOAR give the same eigenvalues within
   1e-7 relative (both converge the residual to 1e-8).
8. The spatial ROM's Campbell diagram (rotorpillar.reduced.spatial_linear, on
   the same mesh's 3D modes below the band) against the 3D model's: see the
   test's docstring for the measured differences and the tolerances.
"""

import math

import numpy as np
import pytest

from rotorpillar.errors import InputError
from rotorpillar.fem3d.model import TopBody
from rotorpillar.fem3d.rotor_spatial import SpatialRotor, rotor_blocks, tilt_whirl_frequencies
from rotorpillar.reduced.pillar import section_of
from rotorpillar.scene import Mesh, load_scene, override

SMALL = Mesh(elements_around=16, elements_along=10)


def test_gyroscopic_sign_by_a_transient():
    """A moment about x precesses the spin axis about z at M_x / (J_C Omega) (source 5)."""
    from scipy.integrate import solve_ivp

    c = 500.0  # tilt damping: the nutation (J_C Omega / I_d = 600 rad/s) decays at c / (2 I_d) = 5 /s
    rotor = SpatialRotor(1600.0, 100.0, 50.0, 0.0, 0.0, 0.0, 4e5, 0.0, 4e5, 1.0, c)
    K, C, M, G = rotor_blocks(rotor)
    i = [9, 10]  # the rotor's pitch and yaw (their springs to the gondola left out: a free gyro)
    Mt, Ct, Gt = M[np.ix_(i, i)], C[np.ix_(i, i)], G[np.ix_(i, i)]
    speed, moment = 300.0, 10.0

    def rhs(t, rate):  # the tilt rates under a step moment about x from rest
        return np.linalg.solve(Mt, np.array([moment, 0.0]) - (Ct + speed * Gt) @ rate)

    sol = solve_ivp(rhs, (0.0, 4.0), np.zeros(2), method="DOP853", rtol=1e-10, atol=1e-14, dense_output=True)
    yaw_rate = sol.sol(np.linspace(3.0, 4.0, 401))[1]
    # the steady precession with the dashpot: J_C Omega phi_z' + c phi_x' = M_x, c phi_z' = J_C Omega phi_x'
    h = rotor.polar_inertia * speed
    assert np.mean(yaw_rate) == pytest.approx(moment * h / (h * h + c * c), rel=1e-6)
    assert np.mean(yaw_rate) > 0  # the far end of the spin axis (-y) tips towards +x


def test_tilt_whirl_closed_form_is_backward_then_forward():
    """The closed form's roots in order, forward above backward, meeting at rest."""
    rotor = SpatialRotor(1600.0, 100.0, 50.0, 0.0, 0.0, 0.0, 4e5, 0.0, 4e5, 1e5, 0.0)
    b0, f0 = tilt_whirl_frequencies(rotor, 0.0)
    b, f = tilt_whirl_frequencies(rotor, 50.0)
    assert b0 == f0 == pytest.approx(math.sqrt(1e5 / 50.0))
    assert b < b0 < f and b * f == pytest.approx(1e5 / 50.0)


def test_top_body_mass_block_is_a_rigid_body():
    """The block's kinetic energy is the body's for any rigid motion of the plate."""
    body = TopBody(2300.0, 850.0, 830.0, 600.0, height=1.2)
    q = np.array([0.3, -0.2, 0.1, 0.05, -0.04, 0.07])
    centre = q[:3] + np.cross(q[3:], [0.0, 0.0, body.height])
    energy = body.mass * centre @ centre + np.array([850.0, 830.0, 600.0]) @ q[3:] ** 2
    assert q @ body.mass_block() @ q == pytest.approx(energy, rel=1e-14)


def test_campbell_estimate_refuses_a_run_too_long():
    from rotorpillar.fem3d.campbell import check_budget, estimate

    s = load_scene("paper")
    est = estimate(s, 151)
    assert est.dofs > 24000 and est.seconds > 0
    with pytest.raises(InputError, match="fewer speeds"):
        check_budget(est, max_seconds=1.0)


@pytest.mark.slow
def test_free_free_rigid_body_inertia_with_the_gondola():
    from rotorpillar.fem3d.model import assemble_model

    p = load_scene("paper").pillar
    mesh = Mesh(elements_around=64, elements_along=2)
    body = TopBody(2300.0, pitch_inertia=850.0, roll_inertia=830.0, yaw_inertia=600.0, height=1.2)
    model = assemble_model(
        p, mesh, top_model="rigid", top_mass=body.mass, top_bodies=(body,), clamped=False, isolated=False
    )
    # the six rigid motions about the base's centre, in the model's unknowns
    xyz = model.owned_node_coordinates()
    n = model.size
    R = np.zeros((n, 6))
    for a in range(3):
        R[a : model.tube_dofs : 3, a] = 1.0
        R[model.tube_dofs + a, a] = 1.0
    for a in range(3):
        w = np.zeros(3)
        w[a] = 1.0
        R[: model.tube_dofs, 3 + a] = np.cross(w, xyz).ravel()
        R[model.tube_dofs : model.tube_dofs + 3, 3 + a] = np.cross(w, [0.0, 0.0, p.height])
        R[model.tube_dofs + 3 + a, 3 + a] = 1.0
    x, y = model.M.createVecRight(), model.M.createVecLeft()
    got = np.zeros((6, 6))
    for j in range(6):
        x.setArray(R[:, j])
        model.M.mult(x, y)
        got[:, j] = R.T @ y.getArray()
    ro, ri, H = p.outer_diameter / 2, p.inner_diameter / 2, p.height
    m = section_of(p).mass_per_length * H
    expected = np.zeros((6, 6))

    def point(mass, zc, inertia):
        B = np.zeros((6, 6))
        B[:3, :3] = mass * np.eye(3)
        B[0, 4] = B[4, 0] = mass * zc
        B[1, 3] = B[3, 1] = -mass * zc
        B[3, 3], B[4, 4], B[5, 5] = inertia[0] + mass * zc**2, inertia[1] + mass * zc**2, inertia[2]
        return B

    diameter = m * (ro**2 + ri**2) / 4 + m * H**2 / 12  # about its own centre
    expected += point(m, H / 2, (diameter, diameter, m * (ro**2 + ri**2) / 2))
    expected += point(body.mass, H + body.height, (850.0, 830.0, 600.0))
    scale = np.sqrt(np.outer(np.diag(expected), np.diag(expected)))
    assert np.max(np.abs(got - expected) / scale) < 1e-6


@pytest.mark.slow
def test_torsion_with_a_top_inertia():
    from scipy.optimize import brentq

    from rotorpillar.fem3d import modal_analysis

    s = load_scene("paper")
    p = s.pillar
    ro, ri = p.outer_diameter / 2, p.inner_diameter / 2
    J_pillar = p.density * math.pi * (ro**4 - ri**4) / 2 * p.height
    s = override(s, [f"gondola.yaw_inertia={J_pillar}"])  # lambda tan(lambda) = 1: lambda = 0.86
    r = modal_analysis(s, top=True, n_modes=12, mesh=SMALL)
    lam = brentq(lambda x: x * math.tan(x) - J_pillar / J_pillar, 1e-6, math.pi / 2 - 1e-9)
    G = p.youngs_modulus / (2 * (1 + p.poisson_ratio))
    assert r.first("torsion") == pytest.approx(lam * math.sqrt(G / p.density) / p.height, rel=2e-4)


@pytest.fixture(scope="module")
def spatial_paper():
    from rotorpillar.fem3d import modal_analysis
    from rotorpillar.fem3d.spatial_modes import spatial_modes_from_fem3d

    s = load_scene("paper")
    r = modal_analysis(s, top=True, n_modes=20, mesh=Mesh(elements_around=32, elements_along=10))
    return s, r, spatial_modes_from_fem3d(r, s.pillar.damping_ratio)


@pytest.mark.slow
def test_spatial_modes_against_the_beam(spatial_paper):
    from scipy.optimize import brentq

    from rotorpillar.reduced.pillar_modes import beam_pillar_modes
    from rotorpillar.reduced.spatial_modes import AXIAL, BENDING_ACROSS, BENDING_IN_PLANE

    s, _, sm = spatial_paper
    g, p = s.gondola, s.pillar
    in_plane = beam_pillar_modes(p, g.mass, 2, "timoshenko", 40, g.roll_inertia)
    across = beam_pillar_modes(p, g.mass, 2, "timoshenko", 40, g.pitch_inertia)
    x, y = sm.of_kind(BENDING_IN_PLANE), sm.of_kind(BENDING_ACROSS)
    assert sm.omega[x[0]] == pytest.approx(in_plane.omega[0], rel=3e-3)
    assert sm.omega[y[0]] == pytest.approx(across.omega[0], rel=3e-3)
    assert sm.omega[x[1]] == pytest.approx(in_plane.omega[1], rel=1.5e-2)
    assert sm.omega[y[1]] == pytest.approx(across.omega[1], rel=1.5e-2)
    # the gondola's roll inertia on the rotor's plane, its pitch inertia across it
    split_3d = sm.omega[x[0]] - sm.omega[y[0]]
    split_beam = in_plane.omega[0] - across.omega[0]
    assert split_3d == pytest.approx(split_beam, rel=0.1)
    # unit top translation: the participation is the beam's tip-scaled one
    assert sm.top[x[0], 0] == pytest.approx(1.0) and sm.top[y[0], 1] == pytest.approx(1.0)
    assert sm.participation[x[0], 0] == pytest.approx(in_plane.participation[0], rel=5e-3)
    assert sm.participation[y[0], 1] == pytest.approx(across.participation[0], rel=5e-3)
    # the axial bar with the gondola at its end
    m_bar = section_of(p).mass_per_length * p.height
    lam = brentq(lambda t: t * math.tan(t) - m_bar / g.mass, 1e-6, math.pi / 2 - 1e-9)
    axial = sm.omega[sm.of_kind(AXIAL)[0]]
    assert axial == pytest.approx(lam * math.sqrt(p.youngs_modulus / p.density) / p.height, rel=3e-3)
    assert sm.has_resultants and sm.damping_ratio[0] == s.pillar.damping_ratio


@pytest.mark.slow
def test_ovalling_modes_leave_the_rigid_top(spatial_paper):
    _, r, sm = spatial_paper
    oval = sm.of_kind("ovalling")
    assert len(oval) >= 2
    first_bending = np.max(np.abs(sm.participation[0]))
    for j in oval:
        # unit max |u| = 1 m: the plate's components in m and rad per m of the wall
        assert np.max(np.abs(sm.top[j])) < 1e-7
        assert np.max(np.abs(sm.participation[j])) < 1e-7 * first_bending


@pytest.mark.slow
def test_tilt_pair_on_a_stiff_support_whirls_as_the_closed_form():
    from rotorpillar.fem3d.campbell import ROTOR_TILT, campbell_fem3d

    s = override(
        load_scene("paper"),
        [
            "pillar.youngs_modulus=1e13",
            "pillar.density=1",
            "shaft.tilt_stiffness=1e5",
            "rotor.diametral_inertia=50",
            "pillar.damping_ratio=0",
        ],
    )
    speeds = np.linspace(0.0, 50.0, 11)
    d = campbell_fem3d(s, speeds, band_top=150.0, mesh=Mesh(elements_around=8, elements_along=4))
    tilt = [b for b in d.modes if b.kind == ROTOR_TILT]
    assert len(tilt) == 2
    rotor = SpatialRotor.from_scene(s)
    closed = np.array([tilt_whirl_frequencies(rotor, w) for w in speeds])
    low, high = sorted(tilt, key=lambda b: b.frequency[-1])
    assert np.allclose(low.frequency, closed[:, 0], rtol=1e-4)
    assert np.allclose(high.frequency, closed[:, 1], rtol=1e-4)
    assert set(low.whirl[1:]) == {"backward"} and set(high.whirl[1:]) == {"forward"}


@pytest.mark.slow
def test_block_arnoldi_and_slepc_toar_agree():
    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.quadratic_eigen import solve_quadratic, solve_quadratic_toar, stiffness_factor
    from rotorpillar.fem3d.spatial_system import assemble_system

    s = override(load_scene("paper"), ["shaft.tilt_stiffness=1e5"])
    model = assemble_pillar(s, top=True, mesh=SMALL)
    system = assemble_system(
        model, SpatialRotor.from_scene(s), tip_damping=3e4, damping_ratio=0.002, damped_up_to=300.0
    )
    ksp, factor = stiffness_factor(system.K)
    try:
        a = solve_quadratic(system, 80.0, 170.0, factor)
        b = solve_quadratic_toar(system, 80.0, 170.0, n_wanted=8)
    finally:
        ksp.destroy()
        system.destroy()
    assert len(a.s) == len(b.s) >= 8
    assert np.max(np.abs(np.sort_complex(a.s) - np.sort_complex(b.s)) / np.abs(a.s)) < 1e-7
    assert a.backward_error.max() < 1e-10 and b.backward_error.max() < 1e-8


@pytest.mark.slow
def test_the_roms_campbell_diagram_is_the_3d_models_within_the_band():
    """Source 8: the spatial ROM on this mesh's 3D modes below the band against the 3D model
    with the rotor on its top, the same damping (b1 both ways, zeta on every mode, b2
    relative to the gondola): the ROM leaves out the modes above the band, whose static
    flexibility at the top it misses; measured 5e-4 on the frequencies (the rotor on its
    shaft and the first bending pair), 3e-3 on the log decrements; tolerances 2e-3 and 2e-2.
    The critical speeds' AFs, each read off the unbalance response's peak by the same rule
    (rotorpillar.reduced.spatial_response.peak_near), the ROM's refined on its model, the 3D
    one's interpolated between ~50 sampled speeds: measured 1.8 % apart; tolerance 4 %.

    On an 8 x 10 tube, not SMALL's 16 x 10 (issue 30: the 3D side's CPU 8.0 -> 3.3 s, its 250
    factorisations of K - Omega**2 M at the five criticals' sampled speeds): the comparison is
    of two models on one mesh, and the same five criticals come out with the same differences
    (16 x 10 against 8 x 10: frequencies 5.6e-4 both, log decrements 2.65e-3 both, critical
    speeds 5.2e-4 both, AFs 2.2 % and 1.8 % at most).  The known oddity stays visible: the 3D
    AF at the rotor's 15.81 rad/s critical reads 45.5 on 12 x 10, 16 x 8, 12 x 8 and 16 x 6 (the
    ROM 3.15 on all), 3.10 here and 3.08 on 16 x 10."""
    from rotorpillar.fem3d import modal_analysis
    from rotorpillar.fem3d.campbell import campbell_fem3d
    from rotorpillar.fem3d.spatial_modes import spatial_modes_from_fem3d
    from rotorpillar.reduced.spatial_scene import scene_campbell

    s = load_scene("paper")
    speeds = np.linspace(0.0, 135.0, 7)
    mesh = Mesh(elements_around=8, elements_along=10)
    r = modal_analysis(s, top=True, n_modes=24, mesh=mesh)
    rom = scene_campbell(s, speeds, 135.0, None, spatial_modes_from_fem3d(r, s.pillar.damping_ratio))
    fem = campbell_fem3d(s, speeds, band_top=135.0, mesh=mesh, with_af=True)

    def in_band(d):
        return {
            b.label.rsplit(" ", 1)[0] if b.label.endswith(("forward", "backward")) else b.label: b
            for b in d.modes
            if np.nanmax(b.frequency) < 135.0
        }

    a, b = in_band(rom), in_band(fem)
    assert set(a) == set(b) and len(a) >= 5
    for label in a:
        assert np.allclose(b[label].frequency, a[label].frequency, rtol=2e-3), label
        assert np.allclose(b[label].log_decrement, a[label].log_decrement, rtol=2e-2), label
        turning = [i for i, w in enumerate(a[label].whirl) if w != "none"]
        assert [b[label].whirl[i] for i in turning] == [a[label].whirl[i] for i in turning], label
    ca = sorted((c.speed, c.excited_by, c.amplification_factor) for c in rom.critical_speeds)
    cb = sorted((c.speed, c.excited_by, c.amplification_factor) for c in fem.critical_speeds)
    assert len(ca) == len(cb)
    assert np.allclose([c[0] for c in cb], [c[0] for c in ca], rtol=2e-3)
    assert [c[1] for c in cb] == [c[1] for c in ca]
    assert all((x[2] is None) == (y[2] is None) for x, y in zip(ca, cb))
    af = [(x[2], y[2]) for x, y in zip(ca, cb) if x[2] is not None]
    assert af and np.allclose([y for _, y in af], [x for x, _ in af], rtol=4e-2)


@pytest.mark.slow
def test_spatial_unbalance_response_against_the_planar_3d_response():
    """Source 9: with the paper's law (b2 to the ground), no structural ratio and the rotor at
    the top, the static unbalance moves only the rotor's plane and the vertical: the spatial
    response (one real LDL^T of K - Omega**2 M and Woodbury's identity on the damping) is the
    planar 3D response (the rotor condensed onto the plate, its two rows solved in closed form;
    rotorpillar.fem3d.harmonic.harmonic_response), 1e-6: two direct solves of one system, whose
    round-off grows with the condition of K - Omega**2 M near a mode (26 rad/s is 2.6 % below
    the first bending mode; measured 4e-8 there, 1e-9 elsewhere)."""
    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.harmonic import harmonic_response, spatial_response
    from rotorpillar.fem3d.rotor_top import RotorOnTop
    from rotorpillar.fem3d.spatial_system import assemble_system

    s = load_scene("paper")
    model = assemble_pillar(s, top=True, mesh=SMALL)
    speeds = np.array([10.0, 15.1, 26.0, 60.0])
    planar = harmonic_response(model, RotorOnTop.from_scene(s), s.pillar.damping, speeds)
    system = assemble_system(model, SpatialRotor.from_scene(s), tip_damping=s.pillar.damping, damping_law="ground")
    try:
        r = spatial_response(system, speeds, "static")
    finally:
        system.destroy()
    assert np.allclose(r.top[:, 0], planar.tip, rtol=1e-6, atol=0.0)
    assert np.allclose(r.shaft[:, 0], planar.shaft, rtol=1e-6, atol=0.0)
    assert np.max(np.abs(r.top[:, 1])) < 1e-8 * np.max(np.abs(r.top[:, 0]))  # nothing along the spin axis


@pytest.mark.slow
def test_the_six_section_resultants_in_statics():
    """Source 10: loads on the rigid top plate, P along x, S along the spin axis (y), Q along
    the axis and a torque T about it: at every element-layer cut, by equilibrium, V_x = P,
    M_y = P (H - z), N = -Q (compression positive), V_y = S, M_x = -S (H - z) (the moment
    about +x of a force along +y above the cut), T; the cuts' functionals read the nodal
    forces of the elements beside the cut, so to round-off: 1e-7 (as tests/test_fem3d_engineering.py
    for the planar three).  The base's peaks as base_reactions_six reads them."""
    from petsc4py import PETSc

    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.sections import section_functionals
    from rotorpillar.fem3d.stress import base_reactions_six

    s = load_scene("paper")
    model = assemble_pillar(s, top=True, mesh=SMALL)
    ksp = PETSc.KSP().create(model.comm)
    ksp.setOperators(model.K)
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    b, x = model.K.createVecLeft(), model.K.createVecRight()
    b.set(0.0)
    P, S, Q, T = 1.0e5, -4.0e4, -3.0e4, 2.0e5
    for i, value in enumerate((P, S, Q, 0.0, 0.0, T)):
        b.setValue(model.tube_dofs + i, value)
    b.assemble()
    ksp.solve(b, x)
    sf = section_functionals(model, s.pillar.youngs_modulus, s.pillar.poisson_ratio, spatial=True)
    R = sf.resultants(x)
    H, z = s.pillar.height, sf.heights
    n = len(z)
    expected = np.column_stack([np.full(n, P), P * (H - z), np.full(n, -Q), np.full(n, S), -S * (H - z), np.full(n, T)])
    scale = np.max(np.abs(expected), axis=0)
    assert np.max(np.abs(R - expected) / scale) < 1e-7
    six = base_reactions_six(np.zeros(1), R[None])
    assert [c.peak for c in six.components] == pytest.approx(list(np.abs(expected[0])), rel=1e-7)
    assert six.overturning_moment == pytest.approx(H * math.hypot(P, S), rel=1e-7)
    for obj in (ksp, b, x, model.K, model.M):
        obj.destroy()


@pytest.mark.slow
def test_spatial_modes_against_the_spatial_beam_source(spatial_paper):
    """Source 3 against the spatial ROM's own beam source (rotorpillar.reduced.spatial_beam:
    Timoshenko bending in both planes with the gondola's inertias, a Saint-Venant torsion bar,
    an axial bar), the first mode of each kind: bending within 0.3 % (as above), torsion within
    2e-4 (no warping: both exact but for their meshes, the 3D one's 1e-4), axial within 0.3 %
    (Poisson's lateral inertia, above); measured +0.17 %, -5e-5, +0.09 %.  The top plate's six
    components of each, per unit top translation (bending, axial) or rotation (torsion),
    within 1e-3: the tip rotation per unit deflection differs by 0.23 % (1.6e-4 rad/m: the
    shear-deformed 3D section against Timoshenko's), the others are zero in both (3D: 1e-10)."""
    from rotorpillar.reduced.spatial_beam import beam_spatial_modes
    from rotorpillar.reduced.spatial_modes import AXIAL, BENDING_ACROSS, BENDING_IN_PLANE, TORSION

    s, _, sm = spatial_paper
    beam = beam_spatial_modes(s.pillar, s.gondola, 4, "timoshenko", 40)
    for kind, rel, comp in (
        (BENDING_IN_PLANE, 3e-3, 0),
        (BENDING_ACROSS, 3e-3, 1),
        (TORSION, 2e-4, 5),
        (AXIAL, 3e-3, 2),
    ):
        a, b = sm.of_kind(kind)[0], beam.of_kind(kind)[0]
        assert sm.omega[a] == pytest.approx(beam.omega[b], rel=rel), kind
        ta, tb = sm.top[a] / sm.top[a, comp], beam.top[b] / beam.top[b, comp]
        assert np.allclose(ta, tb, rtol=0.0, atol=1e-3), kind
