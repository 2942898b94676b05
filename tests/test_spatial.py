"""The spatial reduced model (issue 26) against independent references.

- **Tilt pair of a rigid rotor on a rigid support**: I_d a'' -/+ J Omega (rotated) + k a = 0
  gives, with p = a_x + i a_z, I_d w**2 - J Omega w - k = 0: the forward whirl at
  J Omega / (2 I_d) + sqrt((J Omega / (2 I_d))**2 + k / I_d), the backward at
  sqrt(...) - J Omega / (2 I_d) (the issue's -J Omega/(2 Id) +- sqrt(...), by magnitude),
  and the backward synchronous critical speed sqrt(k / (I_d + J)) (no forward one
  when J > I_d).  The support is a 1e12 N/m axial spring that moves no rotation, so
  the tilt is exactly decoupled: the eigensolver's round-off only, 1e-9.
- **Pillar's first torsion with a top inertia**: a uniform bar, clamped, a disc
  J_top at its end: lambda tan(lambda) = J_pillar / J_top, omega = (lambda / H)
  sqrt(G J_t / (rho I_p)) (Blevins, Formulas for Natural Frequency and Mode Shape,
  Table 8-1; Saint-Venant torsion of a round tube, J_t = I_p).  Linear elements
  with a consistent mass converge as h**2 (a fitted slope within 1.9 ... 2.1);
  at 160 elements the error is ~(lambda / 160)**2 / 12 < 1e-5.
- **Static tip displacement under a tip moment**: M H**2 / (2 E I) and M H / (E I)
  of a cantilever; pure bending has no shear, so both element families are exact at
  the nodes: 1e-9.
- **The planar restriction is today's ROM**: restricted to the rotor's plane, b2 to
  the ground, no structural ratio and no motor reaction, the spatial model packs the
  very arrays of rotorpillar.reduced.rotor_models.modal_model, and its run-up and El
  Centro runs are the same numbers (compared at 1e-12 of their scale: the same
  arithmetic); the spatial beam's planar modes are the planar beam's (1e-9: two
  assemblies of the same element matrices).
- **Gyroscopic sign by a transient**: a moment step M about x (pitch) on the spinning
  rotor moves its axis towards +x (dH/dt = M with H = J Omega (a_z, -1, -a_x)): after
  time T, J Omega a_z + I_d a_x' = M T - k int(a_x) (the angular-momentum balance about
  x), checked at 1e-4 of M T (the integrator's rtol 1e-10 on the states).
- **Base reactions by equilibrium**: with every mode of a 6-element beam (the mode
  displacement method is then exact), static loads at the top (a moment M about y, a
  force F along y, a torque T) give the base M_y = M, V_y = F, M_x = -F H, torsion T,
  and the axial force the weights: the round-off of the modal sums, 1e-8.
- **Half-power AF**: the rotor on its shaft on a rigid support, damping ratio zeta,
  forced by c2 e (a constant force: the mass-centre form): r_peak = sqrt(1 - 2 zeta**2)
  and r_{1,2}**2 = 1 - 2 zeta**2 -+ 2 zeta sqrt(1 - zeta**2) exactly, so
  AF = r_peak / (r_2 - r_1); the root-finder's 1e-10, checked at 1e-7.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorpillar.reduced.beam_sections import tube_sections
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import load_record, no_motion
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.pillar_modes import beam_pillar_modes
from rotorpillar.reduced.rotor_models import modal_model
from rotorpillar.reduced.spatial_beam import beam_spatial_modes
from rotorpillar.reduced.spatial_forces import base_reactions
from rotorpillar.reduced.spatial_linear import critical_speeds, damped_modes, mode_kind, mode_whirl
from rotorpillar.reduced.spatial_model import spatial_model, tilt_example
from rotorpillar.reduced.spatial_modes import BENDING_IN_PLANE, TORSION
from rotorpillar.reduced.spatial_response import unbalance_response
from rotorpillar.reduced.spatial_statics import drive_reaction
from rotorpillar.scene import Gondola, load_scene


def tilt_reference(J, Id, k, W):
    a = J * W / (2 * Id)
    root = math.sqrt(a * a + k / Id)
    return a + root, root - a


@pytest.mark.parametrize("W", [0.0, 30.0, 100.0, 400.0])
def test_tilt_pair_on_a_rigid_support(W):
    k = 2e4
    m = tilt_example(tilt_stiffness=k)
    dm = damped_modes(m, W)
    tilt = [(f, mode_whirl(m, v)[1]) for f, v in zip(dm.frequency, dm.shapes.T) if mode_kind(m, v) == "rotor tilt"]
    forward, backward = tilt_reference(m.rotor_inertia, m.diametral_inertia, k, W)
    got = sorted(f for f, _ in tilt)
    assert got == pytest.approx(sorted([forward, backward]), rel=1e-9)
    if W > 0:
        whirl = dict((round(f, 6), w) for f, w in tilt)
        assert whirl[round(forward, 6)] == "forward" and whirl[round(backward, 6)] == "backward"


def test_tilt_critical_speed_is_backward_only_for_a_disc():
    m = tilt_example(tilt_stiffness=2e4)
    tilt = [c for c in critical_speeds(m) if c.label == "rotor tilt"]
    assert len(tilt) == 1  # J_C = 100 > I_d = 50: the forward tilt never meets the 1x line
    assert tilt[0].speed == pytest.approx(math.sqrt(2e4 / (50.0 + 100.0)), rel=1e-9)
    assert (tilt[0].whirl, tilt[0].excited_by) == ("backward", "neither")


def torsion_reference(pillar, J_top):
    s = tube_sections(pillar, 1)
    J_pillar = s.polar_mass_inertia
    lam = brentq(lambda x: x * math.tan(x) - J_pillar / J_top, 1e-9, math.pi / 2 - 1e-12)
    c = math.sqrt(s.shear_modulus[0] * s.torsion_constant[0] / (s.density[0] * s.polar_moment[0]))
    return lam / pillar.height * c


def test_first_torsion_with_a_top_inertia():
    p = load_scene("paper").pillar
    g = Gondola(mass=2.3e3, yaw_inertia=850.0)
    ref = torsion_reference(p, g.yaw_inertia)
    errors = []
    for n in (20, 40, 80, 160):
        m = beam_spatial_modes(p, g, 1, "timoshenko", n)
        w = float(m.omega[m.of_kind(TORSION)[0]])
        errors.append(abs(w / ref - 1))
    slope = np.polyfit(np.log([20, 40, 80, 160]), np.log(errors), 1)[0]
    assert -2.1 < slope < -1.9
    assert errors[-1] < 1e-5


def test_static_tip_displacement_under_a_tip_moment():
    s = load_scene("paper")
    for theory in ("euler", "timoshenko"):
        r = drive_reaction(beam_spatial_modes(s.pillar, s.gondola, 2, theory, 10), 5100.0, s.pillar)
        EI = s.pillar.youngs_modulus * math.pi / 64 * (s.pillar.outer_diameter**4 - s.pillar.inner_diameter**4)
        assert r.tip_displacement == pytest.approx(5100.0 * s.pillar.height**2 / (2 * EI), rel=1e-9)
        assert r.tip_rotation == pytest.approx(5100.0 * s.pillar.height / EI, rel=1e-9)
        assert r.base_moment == 5100.0


def _planar_pair(scene):
    g = dataclasses.replace(scene.gondola, roll_inertia=0.0, pitch_inertia=0.0, yaw_inertia=0.0)
    sm = beam_spatial_modes(scene.pillar, g, 6, "timoshenko", 40)
    r, sh = scene.rotor, scene.shaft
    old = modal_model(
        sm.planar().truncate(3), r.mass, r.inertia, r.eccentricity, sh.stiffness, sh.damping, scene.pillar.damping
    )
    inplane = sm.select(sm.of_kind(BENDING_IN_PLANE)[:3])
    new = spatial_model(
        inplane,
        r,
        sh,
        scene.pillar.damping,
        damping_ratio=0.0,
        damping_law="ground",
        planes="planar",
        drive_reaction=False,
    )
    return sm, old, new


def test_planar_modes_are_the_planar_beams():
    s = load_scene("paper")
    sm, _, _ = _planar_pair(s)
    today = beam_pillar_modes(s.pillar, s.gondola.mass, 6, "timoshenko", 40)
    mine = sm.planar().truncate(6)
    for a, b in (
        (mine.omega, today.omega),
        (mine.modal_mass, today.modal_mass),
        (mine.participation, today.participation),
    ):
        np.testing.assert_allclose(a, b, rtol=1e-9)


def test_planar_restriction_is_todays_rom():
    s = load_scene("paper")
    _, old, new = _planar_pair(s)
    d = DriveSchedule.constant(s.drive.torque_at_zero, s.drive.slope, s.load.coefficient)
    for a, b in zip(old.pack(d, no_motion()), new.pack(d, no_motion())):
        np.testing.assert_array_equal(a, b)
    # the resonances: today's undamped X modes and the Y oscillator are the restriction's
    w_old = np.sort(np.r_[old.undamped_modes_x()[0], math.sqrt(old.shaft_stiffness / old.rotor_mass)])
    np.testing.assert_allclose(np.sort(new.undamped_modes_x()[0]), w_old, rtol=1e-12)
    runs = [(d, no_motion(), 20.0), (d, load_record("elcentro", start=1.0), 12.0)]
    for drive, motion, t_end in runs:
        a, b = simulate(old, drive, motion, t_end), simulate(new, drive, motion, t_end)
        assert a.ok and b.ok
        scale = np.max(np.abs(a.q), axis=0) + 1e-300
        assert np.max(np.abs(a.q - b.q) / scale) < 1e-12


def test_moment_step_tilts_the_spin_axis_towards_the_moment():
    k, Mx, W, T = 1.0, 100.0, 200.0, 0.5
    m = tilt_example(tilt_stiffness=k)
    i_pitch = m.coordinates.index("rotor_pitch")
    step = np.zeros(m.nz)
    step[i_pitch] = 1.0  # the reaction channel carries M0 = Mx onto the rotor's pitch
    m = dataclasses.replace(m, reaction=step, eccentricity=0.0)
    q0, v0 = np.zeros(m.n), np.zeros(m.n)
    v0[-1] = W
    run = simulate(
        m,
        DriveSchedule.constant(Mx, 0.0, 0.0),
        no_motion(),
        T,
        q0,
        v0,
        settings=Settings("dp5", rtol=1e-10, samples=2001),
        prescribed_speed=True,
    )
    assert run.ok
    ax, az = run.q[:, i_pitch], run.q[:, m.coordinates.index("rotor_yaw")]
    vx = run.v[-1, i_pitch]
    assert az[-1] > 0 and abs(az[-1]) > 10 * np.max(np.abs(ax))  # the axis moves towards +x
    Hx = m.rotor_inertia * W * az[-1] + m.diametral_inertia * vx
    impulse = Mx * T - k * float(np.sum((ax[1:] + ax[:-1]) * np.diff(run.t)) / 2)
    assert Hx == pytest.approx(impulse, rel=1e-4)


def test_half_power_af_of_a_single_mode():
    zeta = 0.01
    m0 = tilt_example()
    c = 2 * zeta * math.sqrt(m0.shaft_stiffness * m0.rotor_mass)
    rotor = dataclasses.replace(load_scene("paper").rotor, height=0.0)
    shaft = dataclasses.replace(load_scene("paper").shaft, damping=c, tilt_stiffness=2e4)
    m = spatial_model(m0.modes, rotor, shaft, 0.0, damping_ratio=0.0)
    wn = math.sqrt(shaft.stiffness / rotor.mass)
    r = unbalance_response(m, np.linspace(0.5 * wn, 1.5 * wn, 201))
    peaks = [p for p in r.curve("rotor_x").peaks if abs(p.speed / wn - 1) < 0.1]
    assert len(peaks) == 1
    r_peak = math.sqrt(1 - 2 * zeta**2)
    u1, u2 = (1 - 2 * zeta**2 + s * 2 * zeta * math.sqrt(1 - zeta**2) for s in (-1, 1))
    assert peaks[0].speed == pytest.approx(r_peak * wn, rel=1e-7)
    assert peaks[0].amplification_factor == pytest.approx(r_peak / (math.sqrt(u2) - math.sqrt(u1)), rel=1e-7)


def test_base_reactions_by_equilibrium():
    s = load_scene("paper")
    modes = beam_spatial_modes(s.pillar, s.gondola, 100, "timoshenko", 6)  # every mode of each line
    m = spatial_model(modes, s.rotor, s.shaft, 0.0)
    pm = m.modes
    M, F, T, H = 5100.0, 2e3, 700.0, s.pillar.height
    load = np.array([0.0, F, 0.0, 0.0, M, T])
    q = np.zeros((1, m.n))
    q[0, : pm.count] = (pm.top @ load) / pm.modal_stiffness  # the static modal coordinates
    r = base_reactions(m, np.zeros(1), q, s.pillar, s.gondola.mass)
    assert float(r.moment_y[0]) == pytest.approx(M, rel=1e-8)
    assert float(r.shear_y[0]) == pytest.approx(F, rel=1e-8)
    assert float(r.moment_x[0]) == pytest.approx(-F * H, rel=1e-8)
    assert float(r.torque[0]) == pytest.approx(T, rel=1e-8)
    assert abs(float(r.shear_x[0])) < 1e-8 * F
    weight = 9.80665 * (s.pillar.density * math.pi / 4 * (2.0**2 - 1.96**2) * H + s.gondola.mass + s.rotor.mass)
    assert float(r.axial_force[0]) == pytest.approx(weight, rel=1e-12)
    assert float(r.moment[0]) == pytest.approx(math.hypot(M, F * H), rel=1e-8)


def test_one_speeds_amplitude_is_steady_states_at_that_speed():
    """The peak refinement's amplitude at one speed (spatial_response._amplitude_at_one_speed,
    the speed-free parts built once: steady_solver) is steady_states' at that one speed, to
    the last bit: the same operations in the same order, the same LAPACK solve.  (Against a
    stack of speeds the output's product may differ in the last bit: BLAS sums a
    matrix-vector product of several rows in another order.)  Both against the equations
    written out here, (K + c2 (d_x d_x^T + d_v d_v^T) - w^2 M + i w (C + w G)) Z =
    c2 e (d_x - i d_v) + U_c w^2 (c_pitch - i c_yaw), solved by numpy directly: round-off of
    a 7 x 7 complex solve (1e-12 relative; measured below 1e-14)."""
    from rotorpillar.reduced.spatial_response import (
        PEAK_CURVES,
        _amplitude_at_one_speed,
        output_amplitude,
        steady_states,
    )
    from rotorpillar.reduced.spatial_scene import scene_spatial_model

    m = scene_spatial_model(load_scene("paper"), 180.0)
    speeds = [3.7, 14.9, 27.17, 108.8, 157.0]
    for name in PEAK_CURVES:
        amp = _amplitude_at_one_speed(m, name)
        one_at_a_time = [float(abs(output_amplitude(m, name, steady_states(m, [w]))[0])) for w in speeds]
        assert [amp(w) for w in speeds] == one_at_a_time, name
    dx, dv = m.shaft
    K = m.stiffness + m.shaft_stiffness * (np.outer(dx, dx) + np.outer(dv, dv))
    for w in speeds:
        A = K - w**2 * m.mass + 1j * w * (m.damping + w * m.gyroscopic)
        f = m.shaft_stiffness * m.eccentricity * (dx - 1j * dv) + m.couple_unbalance * w**2 * (
            m.couple[0] - 1j * m.couple[1]
        )
        Z = np.linalg.solve(A, f)
        assert np.allclose(steady_states(m, [w])[0], Z, rtol=1e-12, atol=1e-12 * np.max(np.abs(Z)))
