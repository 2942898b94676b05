"""The 3D full-order transient (rotorpillar.fem3d.full_order), on a coarse tube.

References and tolerances:

- static limit: a ground acceleration ramped smoothly (half cosine over 2 s,
  about 8 periods of the first mode) to a constant a0 and held; the
  plate's final X equals the static solution K u = -(M r + m_C e_x) a0,
  solved here directly with the tube's own K (an independent path: no
  Newmark, no condensation).  Tolerance 2e-3: the residual oscillation of
  the ramp, damped by b1 and b2.
- the modal ROM on the same tube's 3D modes (transients.cases.build_model with
  modal_model.source = fem3d), same Newmark step, same start: truncation and
  the ROM's participation factors are the only differences.  On a coarse
  mesh (16 x 6 cells) the ROM's participation uses the exact annulus's mass
  per length while the meshed tube is 0.3 % lighter, and the error sits at
  0.4 % whatever the number of modes; on this module's 8 x 6 tube 0.49 %;
  tolerance 1 %.
- the tube: 8 x 6 cells, not 16 x 6 (issue 30: 1881 unknowns, not 3753, each
  step's solve half the CPU: a 2000-step run 2.1 -> 1.0 s; the module's CPU
  13.8 -> 8.2 s, best of 2).  Every check below was measured on both; where a number moved
  both are given.
- energy balance: Newmark's energy identity is exact for the linear part;
  the unbalance coupling leaves an O(h**2) residual, measured ~1e-5 of the
  work scale; tolerance 1e-4.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rotorpillar import records
from rotorpillar.fem3d.rotor_top import Affine, RotorOnTop, drive_torque, rotor_start, solve_spin
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import GroundMotion
from rotorpillar.scene import load_scene

COARSE = ["mesh.elements_around=8", "mesh.elements_along=6", "mesh.degree=2"]


def test_solve_spin_without_coupling_is_newmark_on_the_drive():
    """No shaft torque: J alpha = M0 - s W - k W|W|, and the step's
    trapezoidal relations hold at the solution."""
    rot = RotorOnTop(1600.0, 100.0, 0.0, 4e5, 1.1e4)
    zero = Affine(0.0, 0.0, 0.0)
    h, th, W, al = 1e-3, 0.4, 50.0, 2.0
    th1, W1, al1, it = solve_spin(rot, h, th, W, al, zero, zero, 5100.0, 12.0, 0.5)
    assert rot.inertia * al1 == pytest.approx(drive_torque(5100.0, 12.0, 0.5, W1), rel=1e-10)
    assert W1 == pytest.approx(W + h / 2 * (al + al1), rel=1e-12)
    assert th1 == pytest.approx(th + h / 2 * (W + W1), rel=1e-12)
    assert it <= 3


pytestmark_3d = pytest.mark.skipif(__import__("importlib").util.find_spec("dolfinx") is None, reason="needs dolfinx")


def ramp_motion(a0: float, ramp: float, end: float, dt: float = 1e-3) -> GroundMotion:
    """a_g rising as a half cosine to a0 over ``ramp``, then held (no baseline correction)."""
    t = np.arange(0.0, end + dt / 2, dt)
    a = np.where(t < ramp, 0.5 * a0 * (1 - np.cos(math.pi * t / ramp)), a0)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
    d = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * dt)])
    return GroundMotion("record", 0.0, 0.0, 0.0, float(t[-1]), dt, d, v, a, name="ramp")


def _plate_x_under(m, f) -> float:
    """The plate's U_x of K u = f, by a direct solve with the tube's own K (no Newmark, no
    condensation)."""
    from petsc4py import PETSc

    ksp = PETSc.KSP().create(m.comm)
    ksp.setOperators(m.K)
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    u = m.K.createVecRight()
    ksp.solve(f, u)
    return float(u.getValue(m.tube_dofs))


def static_tip(scene, a0: float) -> float:
    """U_x of K u = -(M r + m_C e_x) a0, by a direct solve."""
    from petsc4py import PETSc

    from rotorpillar.fem3d import assemble_pillar

    m = assemble_pillar(scene, top=True)
    f = m.M.createVecLeft()
    m.M.mult(m.influence(0), f)
    f.setValue(m.tube_dofs, scene.rotor.mass, addv=PETSc.InsertMode.ADD_VALUES)
    f.assemble()
    f.scale(-a0)
    return _plate_x_under(m, f)


@pytest.fixture(scope="module")
def static_run():
    from rotorpillar.fem3d.full_order import simulate_fem3d

    scene = load_scene("paper", COARSE)
    a0 = 0.5
    # held 3 s after the ramp, not 7 (issue 30: 1,000 steps, not 1,800; 2.0 -> 1.0 s of CPU):
    # over the last second the plate's X within 1.5e-5 of the direct solve at most, 4.6e-8 on
    # the mean, the shaft 1.6e-6 (9 s: 1.4e-8, 1.0e-8, 3e-10), far inside the bounds below
    # (16 x 6; on 8 x 6: 1.5e-5, 7.8e-8, 1.6e-6)
    motion = ramp_motion(a0, 2.0, 5.0)
    r = simulate_fem3d(
        scene,
        "earthquake",
        motion=motion,
        drive=DriveSchedule.constant(0.0, 0.0, 0.0),
        duration=5.0,
        time_step=5e-3,
        samples=101,
        initial_speed=0.0,
        initial_angle=0.0,
        prescribed_speed=True,
    )
    return scene, a0, r


@pytest.mark.slow  # the 3D full-order transient
@pytestmark_3d
def test_static_limit(static_run):
    scene, a0, r = static_run
    ref = static_tip(scene, a0)
    last = r.t >= r.t[-1] - 1.0
    assert ref < 0
    assert np.mean(r.tip_x[last]) == pytest.approx(ref, rel=2e-3)
    assert np.max(np.abs(r.tip_x[last] - ref)) < 5e-3 * abs(ref)
    # the shaft carries the rotor's inertia: c2 (x_r - U_x - e) = -m_C a0
    assert r.shaft_x[-1] == pytest.approx(-scene.rotor.mass * a0 / scene.shaft.stiffness, rel=5e-3)
    assert r.integrator.factorisations == 1
    assert r.energy_balance.relative_error < 1e-8  # linear: Newmark's identity is exact
    assert np.allclose(r.tip_x_absolute, r.tip_x + r.ground_x)


@pytest.mark.slow  # the 3D full-order transient
@pytestmark_3d
def test_result_json_round_trip(static_run):
    from rotorpillar.fem3d.full_order_result import Fem3dTransient

    r = static_run[2]
    back = records.convert(json.loads(json.dumps(records.to_builtins(r))), Fem3dTransient)
    assert json.dumps(records.to_builtins(back)) == json.dumps(records.to_builtins(r))
    assert isinstance(back.t, np.ndarray) and np.array_equal(back.work, r.work)
    doc = records.to_builtins(r)  # the fields the reduced runs report, plus dofs and wall time
    assert set(doc) >= {"max_abs", "omega_final", "energy_balance", "integrator", "dofs", "wall_seconds"}


def rom_start(rom, scene, theta0: float, W0: float):
    """The ROM's (q0, v0) matching the 3D start: structure at rest, rotor in its whirl."""
    from rotorpillar.fem3d.rotor_top import RotorOnTop, rotor_start

    x, y, vx, vy = rotor_start(RotorOnTop.from_scene(scene), theta0, W0)
    q0, v0 = np.zeros(rom.n), np.zeros(rom.n)
    q0[rom.rotor_x], q0[rom.nx], q0[-1] = x, y, theta0
    v0[rom.rotor_x], v0[rom.nx], v0[-1] = vx, vy, W0
    return q0, v0


# El Centro's strong motion (4 s from 1 s), the rotor spinning at 89 rad/s from 0.3 rad
ELCENTRO_4S = dict(duration=4.0, time_step=2e-3, samples=401, initial_speed=89.0, initial_angle=0.3)


@pytest.fixture(scope="module")
def spin_locked():
    """The 3D run on El Centro with the spin held: the 3D side of the spin-locked comparison
    with the ROM and the x-only run of the three components, computed once for both (issue 30).
    The scene's modal_model.source (fem3d: the ROM's modes) does not enter the 3D run."""
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.reduced.excitation import load_record

    scene = load_scene("paper", COARSE + ["modal_model.source=fem3d"])
    motion = load_record("elcentro", start=1.0)
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    r = simulate_fem3d(scene, "earthquake", motion=motion, drive=drive, prescribed_speed=True, **ELCENTRO_4S)
    return scene, motion, drive, r


def compare_with_rom(case, motion, drive, duration, W0, theta0, prescribed, h=2e-3, dt_out=0.01, run=None):
    """The 3D run (``run`` when given: the very case, already run) and the ROM's."""
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.reduced.integration import Settings, simulate
    from rotorpillar.reduced.models import build_model

    scene = load_scene("paper", COARSE + ["modal_model.source=fem3d"])
    samples = int(round(duration / dt_out)) + 1
    r = run or simulate_fem3d(
        scene,
        case,
        motion=motion,
        drive=drive,
        duration=duration,
        time_step=h,
        samples=samples,
        initial_speed=W0,
        initial_angle=theta0,
        prescribed_speed=prescribed,
    )
    from rotorpillar.fem3d.pillar_modes import candidate_pillar_modes

    rom, _ = build_model(scene, "modal", modes=3, pillar_modes=candidate_pillar_modes(scene))
    q0, v0 = rom_start(rom, scene, theta0, W0)
    R = simulate(
        rom,
        drive,
        motion,
        duration,
        q0,
        v0,
        settings=Settings("newmark", time_step=h, samples=samples),
        prescribed_speed=prescribed,
        speed_scale=max(W0, 1.0),
    )
    assert np.allclose(R.t, r.t)
    return scene, r, R


@pytest.mark.slow
@pytestmark_3d
@pytest.mark.parametrize("prescribed", [True, False], ids=["spin_locked", "free_spin"])
def test_earthquake_against_rom_on_the_3d_modes(prescribed, request):
    from rotorpillar.reduced.excitation import load_record

    motion = load_record("elcentro", start=1.0)
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    run = request.getfixturevalue("spin_locked")[3] if prescribed else None  # the same case, run once
    # 4 s of El Centro from 1 s, its strong motion (as the gondola test below): the largest
    # difference and both peaks are at 3.59 s, so the history error (4.4e-3 both ways), the
    # peaks (1.4e-3 and 6.9e-4) and the speed's difference are the 7-s run's to the digit;
    # the energy balance measured 6.0e-5 spin locked, 9.2e-6 free (3.3e-5 and 9.1e-6 over 7 s)
    # (16 x 6; on 8 x 6: the history error 4.9e-3 both ways, the peaks 7.2e-4 and 6.2e-5, the
    # energy balance 6.0e-5 and 9.2e-6)
    scene, r, R = compare_with_rom("earthquake", motion, drive, 4.0, 89.0, 0.3, prescribed, run=run)
    err = np.max(np.abs(R.tip() - r.tip_x)) / np.max(np.abs(r.tip_x))
    assert err < 1e-2
    assert r.max_abs["tip_x"] == pytest.approx(float(np.max(np.abs(R.tip()))), rel=1e-2)
    assert np.max(np.abs(R.Omega - r.Omega)) < 1e-3
    assert r.energy_balance.relative_error < 1e-4
    assert r.ok and r.integrator.factorisations == 1


@pytest.mark.slow
@pytestmark_3d
def test_runup_against_rom_and_energy():
    from rotorpillar.reduced.excitation import no_motion

    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    scene, r, R = compare_with_rom("runup", no_motion(), drive, 3.0, 0.0, 0.0, False)
    assert np.max(np.abs(R.Omega - r.Omega)) < 1e-3 * np.max(r.Omega)
    err = np.max(np.abs(R.tip() - r.tip_x)) / np.max(np.abs(r.tip_x))
    assert err < 2e-2
    assert r.energy_balance.relative_error < 1e-4
    assert r.energy_balance.work_drive_minus_load > 0


@pytest.mark.slow
@pytestmark_3d
def test_gondola_damping_law_and_structural_ratio_against_the_spatial_rom(spin_locked):
    """The spatial side (issue 26): the 3D full order with b2 relative to the gondola and a
    structural ratio on every loaded-tube mode (low rank, Woodbury in the step) against the
    spatial ROM restricted to the rotor's plane with the same damping
    (rotorpillar.reduced.spatial_model, planes "planar", damping_law "gondola"), on this
    mesh's own 3D modes (SpatialPillarModes: participations from the 3D model's own mass
    matrix, so none of the 0.4 % above), same Newmark step, same start: truncation is the
    only difference, measured 5e-5 on El Centro's tip (16 x 6 and 8 x 6); tolerance 1 %.  zeta = 0.02, ten times
    the scene's default, so that a damping left out would show (it moves the peak tip by 6.7 %).
    4 s of El Centro from 1 s, its strong motion: both runs peak inside it (3.35 and 3.59 s),
    and 7 s gave the same error and the same 6.7 % at 1.4 times the time; the energy balance
    measured 6.5e-5 (3.3e-5 over 7 s).  The run with the paper's law (b2 to the ground, no
    structural ratio) is the spin-locked fixture's: the very case (its modal_model.source
    does not enter the 3D run; the two computed apart gave the same histories to the bit),
    2.3 s of CPU not spent twice (issue 30)."""
    from rotorpillar.fem3d import modal_analysis
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.fem3d.spatial_modes import spatial_modes_from_fem3d
    from rotorpillar.reduced.excitation import load_record
    from rotorpillar.reduced.integration import Settings, simulate
    from rotorpillar.reduced.spatial_model import spatial_model
    from rotorpillar.reduced.spatial_modes import BENDING_IN_PLANE

    zeta, h, duration, W0, theta0 = 0.02, 2e-3, 4.0, 89.0, 0.3
    scene = load_scene("paper", COARSE)
    motion = load_record("elcentro", start=1.0)
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    samples = int(round(duration / 0.01)) + 1
    kw = dict(motion=motion, drive=drive, duration=duration, time_step=h, samples=samples)
    kw.update(initial_speed=W0, initial_angle=theta0, prescribed_speed=True)
    r = simulate_fem3d(scene, "earthquake", damping_law="gondola", damping_ratio=zeta, **kw)
    plain = spin_locked[3]  # damping_law "ground", damping_ratio 0: simulate_fem3d's defaults
    modes = spatial_modes_from_fem3d(modal_analysis(scene, top=True, n_modes=12), zeta)
    rom = spatial_model(
        modes.select(modes.of_kind(BENDING_IN_PLANE)[:3]),
        scene.rotor,
        scene.shaft,
        scene.pillar.damping,
        damping_law="gondola",
        planes="planar",
        drive_reaction=False,
    )
    x, y, vx, vy = rotor_start(RotorOnTop.from_scene(scene), theta0, W0)
    q0, v0 = np.zeros(rom.n), np.zeros(rom.n)
    ix, iz = rom.coordinates.index("rotor_x"), rom.coordinates.index("rotor_vertical")
    q0[ix], q0[iz], q0[-1] = x, y, theta0
    v0[ix], v0[iz], v0[-1] = vx, vy, W0
    R = simulate(
        rom,
        drive,
        motion,
        duration,
        q0,
        v0,
        settings=Settings("newmark", time_step=h, samples=samples),
        prescribed_speed=True,
        speed_scale=W0,
    )
    assert np.allclose(R.t, r.t)
    err = np.max(np.abs(R.tip() - r.tip_x)) / np.max(np.abs(r.tip_x))
    assert err < 1e-2
    assert abs(plain.max_abs["tip_x"] / r.max_abs["tip_x"] - 1) > 5e-2  # the damping shows
    assert r.ok and r.energy_balance.relative_error < 1e-4
    assert "relative to the plate" in r.model.damping_law


@pytest.mark.slow
@pytestmark_3d
def test_three_components_superpose(spin_locked):
    """The ground along x and along the spin axis at once: the tube is symmetric, so the
    in-plane response is the x-only run's (1e-7 of its peak: the factorisation's round-off
    couples the symmetric directions, measured 5e-9 on 16 x 6, 1.0e-8 on 8 x 6, and the x-only
    run's tip_y 7.9e-9 of its tip_x; the rotor's spin and its unbalance are in
    the x-z plane, which the y motion does not enter), and the y
    component moves the top along the spin axis; the energy balance holds with the base
    work of both components (1e-4: the unbalance coupling's O(h**2)).  The x-only run is the
    spin-locked comparison's (the rotor from 0.3 rad; the plane argument holds at any angle)."""
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.reduced.ground3d import spatial_ground_motion

    scene, first, drive, a = spin_locked
    both = spatial_ground_motion([first, first], [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])
    b = simulate_fem3d(scene, "earthquake", motion=both, drive=drive, prescribed_speed=True, **ELCENTRO_4S)
    assert np.max(np.abs(a.tip_x - b.tip_x)) < 1e-7 * np.max(np.abs(a.tip_x))
    assert a.max_abs["tip_y"] < 1e-7 * a.max_abs["tip_x"]  # x alone: nothing along the spin axis
    assert b.max_abs["tip_y"] > 0.1 * b.max_abs["tip_x"]  # the second component moves it
    assert b.ok and b.energy_balance.relative_error < 1e-4


def _moment_tip(scene, moment: float) -> float:
    """The plate's U_x of K u = ``moment`` on its Theta_y, by a direct solve (no Newmark)."""
    from rotorpillar.fem3d import assemble_pillar

    m = assemble_pillar(scene, top=True)
    f = m.K.createVecLeft()
    f.set(0.0)
    f.setValue(m.tube_dofs + 4, moment)
    f.assemble()
    return _plate_x_under(m, f)


@pytest.mark.slow
@pytestmark_3d
def test_the_motors_reaction_on_the_top():
    """The motor's reaction on the plate (issue 27: nrel5mw's run-up set the spatial ROM, which
    carries it, against a 3D run without it: a 4780 % history error).

    A start at speed starts on the static deflection under Md = M0 - s W0: with no ground motion
    and no unbalance the tip starts at the direct solve's U_x (K u = Md on Theta_y, the test's own
    solve: 1e-8, round-off) and stays there (1e-6 of it over 1 s: the start is consistent, nothing
    rings); the direct solve against the cantilever's closed form M H**2 / (2 E I) within this
    8 x 6 mesh's bending error (measured -0.58 %, -0.69 % on 16 x 6: 3 %).  Without the reaction nothing moves the
    top.  A run-up from rest, M0 ramped over 2 s against a slope that holds the speed near 50
    rad/s: the tip follows the reaction's static deflection under Md(t) = M0(t) - s W(t) from the
    run's own speed (the moment follows the spin solve), within 6 % of its peak over the run
    (measured 4.2 %: the ramp's corners ring the first mode, which b1 damps slowly) and 2 % at
    the end (measured 0.4 %); its energy balance holds (1e-4 as the others)."""
    from rotorpillar.fem3d.full_order import simulate_fem3d

    scene = load_scene("paper", COARSE + ["rotor.eccentricity=0", "rotor.inertia=1e5"])
    M0, s = 5e6, 1e5  # N*m: a top rolled ~8 cm; N*m*s: a free speed of 50 rad/s
    kw = dict(motion=ramp_motion(0.0, 1.0, 1.0), duration=1.0, time_step=5e-3, samples=201, initial_speed=30.0)
    kw.update(prescribed_speed=True)  # the speed held: Md constant
    Md0 = M0 - s * 30.0
    r = simulate_fem3d(scene, "earthquake", drive=DriveSchedule.constant(M0, s, 0.0), drive_reaction=True, **kw)
    unit = _moment_tip(scene, 1.0)  # m per N*m
    p = scene.pillar
    EI = p.youngs_modulus * math.pi / 64 * (p.outer_diameter**4 - p.inner_diameter**4)
    assert unit == pytest.approx(p.height**2 / (2 * EI), rel=3e-2)
    # two direct solves of one system agree to its round-off, which the machine's kernels set:
    # measured 1e-10 on one machine and 2.4e-9 on an AVX-512 one (K's diagonal spans 14 decades;
    # 1.5e-9 on the 8 x 6 tube there)
    assert r.tip_x[0] == pytest.approx(unit * Md0, rel=1e-8)
    assert np.max(np.abs(r.tip_x - unit * Md0)) < 1e-6 * abs(unit * Md0)
    assert "reaction" in r.model.forcing and "static deflection" in r.model.start
    plain = simulate_fem3d(scene, "earthquake", drive=DriveSchedule.constant(M0, s, 0.0), **kw)
    assert np.max(np.abs(plain.tip_x)) < 1e-9 * abs(unit * Md0)
    up = simulate_fem3d(
        scene,
        "runup",
        drive=DriveSchedule.ramp(M0, s, 0.0, 2.0),
        duration=4.0,
        time_step=5e-3,
        samples=401,
        drive_reaction=True,
    )
    quasi_static = unit * (np.minimum(up.t / 2.0, 1.0) * M0 - s * up.Omega)
    assert np.max(np.abs(up.tip_x - quasi_static)) < 6e-2 * np.max(np.abs(quasi_static))
    assert up.tip_x[-1] == pytest.approx(quasi_static[-1], rel=2e-2)
    assert up.ok and up.energy_balance.relative_error < 1e-4
