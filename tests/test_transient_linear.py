"""Linear subsystems of the transient models against closed forms.

References (all exact for the linear equations integrated here):
- free decay of a viscously damped oscillator,
  x = x0 e^{-zeta w t} (cos w_d t + zeta/sqrt(1 - zeta**2) sin w_d t);
- free decay of the paper's X system (Eq. 4, two masses, its printed
  damping) by the matrix exponential of its state matrix (scipy.linalg.expm);
- steady forced amplitude of the rotor on its shaft in Y at a prescribed
  speed, c2 e / sqrt((c2 - m W**2)**2 + (b2 W)**2), and of the X system by
  Cramer's rule on the 2x2 dynamic stiffness, written out here;
- the modal model with one mode of mass m_A and stiffness c1 and Eq. 4 with
  b1 on q1 are the same equations: their runs must coincide.

Tolerances: the compiled Dormand-Prince at rtol 1e-10 reaches ~1e-9 of the
amplitude on these smooth problems: 1e-7 relative.  Steady amplitudes are
read after e^-25 of the slowest transient by a least-squares fit of
cos/sin at the forcing frequency: 1e-6 relative.  The fixed-step schemes are
second order: their error on the free decay must fall as h**2 (fitted slope
in [1.8, 2.2]).
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.linalg import expm

from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import no_motion
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.pillar_modes import PillarModes
from rotorpillar.reduced.rotor_models import modal_model, paper_model
from rotorpillar.reduced.system import paper_example

IDLE = DriveSchedule.constant(0.0, 0.0, 0.0)
TIGHT = Settings("dp5", rtol=1e-10, samples=2001)


def sdof_model(m=7000.0, k=5e6, c=2e4):
    """A single pillar mode with nothing on top (shaft and rotor decoupled)."""
    modes = PillarModes(np.array([math.sqrt(k / m)]), np.array([m]), np.array([m]), m, "test")
    return modal_model(
        modes,
        rotor_mass=1.0,
        rotor_inertia=1.0,
        eccentricity=0.0,
        shaft_stiffness=0.0,
        shaft_damping=0.0,
        tip_damping=c,
    )


def harmonic_fit(t, x, W):
    A = np.column_stack([np.cos(W * t), np.sin(W * t)])
    return float(np.hypot(*np.linalg.lstsq(A, x, rcond=None)[0]))


def test_free_decay_of_a_pillar_mode():
    m, k, c = 7000.0, 5e6, 2e4
    model = sdof_model(m, k, c)
    x0 = 0.01
    q0 = np.zeros(model.n)
    q0[0] = x0
    run = simulate(model, IDLE, no_motion(), 3.0, q0, settings=TIGHT, speed_scale=1.0)
    w = math.sqrt(k / m)
    z = c / (2 * math.sqrt(k * m))
    wd = w * math.sqrt(1 - z * z)
    exact = x0 * np.exp(-z * w * run.t) * (np.cos(wd * run.t) + z / math.sqrt(1 - z * z) * np.sin(wd * run.t))
    assert np.max(np.abs(run.tip() - exact)) < 1e-7 * x0


def test_free_decay_of_the_paper_x_system_against_the_matrix_exponential():
    s = paper_example(5e6, 25e3)
    model = dataclasses.replace(paper_model(s), eccentricity=0.0)  # equilibrium at z = 0
    q0 = np.zeros(model.n)
    q0[:2] = [0.002, -0.001]
    v0 = np.zeros(model.n)
    v0[1] = 0.05
    run = simulate(model, IDLE, no_motion(), 2.0, q0, v0, settings=TIGHT, speed_scale=1.0)
    M, K, C = s.mass_matrix(), s.stiffness_matrix(), s.damping_matrix()
    Mi = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ K, -Mi @ C]])
    y0 = np.r_[q0[:2], v0[:2]]
    exact = np.array([expm(A * t) @ y0 for t in run.t])
    assert np.max(np.abs(run.q[:, :2] - exact[:, :2])) < 1e-7 * 0.002


@pytest.mark.parametrize("W", [10.0, 15.8, 30.0])
def test_steady_amplitude_of_the_rotor_on_its_shaft(W):
    s = paper_example()
    model = paper_model(s)
    m, c2, b2, e = s.rotor_mass, s.shaft_stiffness, s.shaft_damping, s.eccentricity
    settle = 25 / (b2 / (2 * m))
    q0, v0 = np.zeros(model.n), np.zeros(model.n)
    v0[-1] = W
    run = simulate(model, IDLE, no_motion(), settle + 2.0, q0, v0, settings=TIGHT, prescribed_speed=True, speed_scale=W)
    tail = run.t >= settle
    amp = harmonic_fit(run.t[tail], run.q[tail, model.nx], W)
    exact = c2 * e / math.hypot(c2 - m * W * W, b2 * W)
    assert amp == pytest.approx(exact, rel=1e-6)


@pytest.mark.parametrize("W", [15.36, 22.0, 29.1])
def test_steady_amplitudes_of_the_x_system_by_cramer(W):
    s = paper_example()
    model = paper_model(s)
    mA, mC, c0, c2, b0, b2, e = (
        s.tip_mass,
        s.rotor_mass,
        s.c0,
        s.shaft_stiffness,
        s.b0,
        s.shaft_damping,
        s.eccentricity,
    )
    # [[c0 - mA W^2 + i W b0, -c2], [-c2, c2 - mC W^2 + i W b2]] Q = c2 e (-1, 1)
    a11, a12, a22 = c0 - mA * W**2 + 1j * W * b0, -c2, c2 - mC * W**2 + 1j * W * b2
    det = a11 * a22 - a12 * a12
    f1, f2 = -c2 * e, c2 * e
    Q1 = (f1 * a22 - a12 * f2) / det
    Q2 = (a11 * f2 - a12 * f1) / det
    settle = 25 / min(r.n for r in model.quasi_normal())
    q0, v0 = np.zeros(model.n), np.zeros(model.n)
    v0[-1] = W
    run = simulate(model, IDLE, no_motion(), settle + 2.0, q0, v0, settings=TIGHT, prescribed_speed=True, speed_scale=W)
    tail = run.t >= settle
    assert harmonic_fit(run.t[tail], run.q[tail, 0], W) == pytest.approx(abs(Q1), rel=1e-6)
    assert harmonic_fit(run.t[tail], run.q[tail, 1], W) == pytest.approx(abs(Q2), rel=1e-6)
    # and the model's own steady-state solve agrees with Cramer
    Z, _ = model.steady_state(W)
    assert abs(Z[0]) == pytest.approx(abs(Q1), rel=1e-12)


def test_modal_model_with_one_mode_is_eq4_with_b1_on_q1():
    s = paper_example(5e6, 25e3)
    eq4 = dataclasses.replace(paper_model(s), damping=np.diag([s.pillar_damping, s.shaft_damping]))
    modes = PillarModes(
        np.array([math.sqrt(s.pillar_stiffness / s.tip_mass)]),
        np.array([s.tip_mass]),
        np.array([s.tip_mass]),
        s.tip_mass,
        "one mode",
    )
    modal = modal_model(
        modes, s.rotor_mass, s.rotor_inertia, s.eccentricity, s.shaft_stiffness, s.shaft_damping, s.pillar_damping
    )
    for m in (eq4, modal):
        assert np.allclose(m.stiffness_full(), s.stiffness_matrix())
    drive = DriveSchedule.constant(5100.0, 12.0, 0.5)
    a = simulate(eq4, drive, no_motion(), 8.0, settings=Settings(rtol=1e-10, samples=801))
    b = simulate(modal, drive, no_motion(), 8.0, settings=Settings(rtol=1e-10, samples=801))
    assert np.max(np.abs(a.q - b.q)[:, :3]) < 1e-12 + 1e-8 * np.max(np.abs(a.q[:, :3]))
    assert a.Omega[-1] == pytest.approx(b.Omega[-1], rel=1e-10)


@pytest.mark.parametrize("method", ["newmark", "hht", "generalized_alpha", "central_difference"])
def test_fixed_step_schemes_converge_at_second_order(method):
    m, k, c = 7000.0, 5e6, 2e4
    model = sdof_model(m, k, c)
    q0 = np.zeros(model.n)
    q0[0] = 0.01
    w = math.sqrt(k / m)
    z = c / (2 * math.sqrt(k * m))
    wd = w * math.sqrt(1 - z * z)
    T = 2.0
    errs, hs = [], []
    for steps_per_output in (8, 16, 32, 64):
        h = T / (200 * steps_per_output)
        run = simulate(
            model, IDLE, no_motion(), T, q0, settings=Settings(method, time_step=h, samples=201), speed_scale=1.0
        )
        exact = 0.01 * np.exp(-z * w * run.t) * (np.cos(wd * run.t) + z / math.sqrt(1 - z * z) * np.sin(wd * run.t))
        errs.append(np.max(np.abs(run.tip() - exact)))
        hs.append(h)
    slope = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert 1.8 <= slope <= 2.2
