"""The schemes' accuracy at a step, and the full orders' step rule (rotorpillar.reduced.accuracy,
rotorpillar.fem3d.rotor_top.Step), against closed forms and the schemes' textbook statements.

Sources: Chung & Hulbert (1993), J. Appl. Mech. 60:371 (generalized-alpha:
second order when gamma = 1/2 - alpha_m + alpha_f, spectral radius rho_inf at
infinite frequency); Hilber, Hughes & Taylor (1977) (HHT-alpha); Hughes, *The
Finite Element Method* (2000) ch. 9 (Newmark's average acceleration:
omega_bar h = 2 atan(omega h / 2); central difference: cos(omega_bar h) =
1 - (omega h)**2 / 2); Hairer & Wanner, *Solving ODEs II* IV.2 (DOPRI5's
stability polynomial 1 + z + ... + z**5/120 + z**6/600).

- the 3D integrator's scalar step (Step: the rotor centre, the plate's
  dashpot) and its spin equation (solve_spin) converge at second order on
  closed forms (a forced damped oscillator from rest; a rotor spun up by a
  linear drive): the fitted log-log slope of the error over h = T/200 ...
  T/1600 lies in [1.85, 2.15] (second order: 2; the band covers the
  pre-asymptotic drift of the coarsest step, measured < 0.05);
- far above its reach (omega h = 1e4) the scalar step shrinks a free
  oscillation by the stated rho_inf per step (1e-2: the spectral radius
  approaches rho_inf as (omega h)**(-2/3), 2e-3 here) and by exactly the
  amplification's spectral radius there (1e-6);
- the accuracy module's period error and amplitude loss equal the closed
  forms (1e-12) and what the compiled kernels do on an oscillator (the
  principal root fitted to 300 steps: 1e-6, round-off of the fit);
- the full orders' step does not depend on the shaft's stiffness (the old
  rule resolved sqrt(c2 / m_C)), and resolves the fastest forcing within 2e-3.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorpillar.fem3d.rotor_top import Affine, RotorOnTop, Step, solve_spin
from rotorpillar.reduced.accuracy import (
    FULL_ORDER_ERROR,
    full_order_parameters,
    scheme_error,
    stability_function,
    steps_per_period_needed,
)

SCHEMES = [
    ("newmark", 1.0),
    ("hht", 0.8),
    ("generalized_alpha", 0.8),
    ("generalized_alpha", 0.5),
    ("generalized_alpha", 0.0),
]


def slope(hs, errors) -> float:
    return float(np.polyfit(np.log(hs), np.log(errors), 1)[0])


def oscillator_exact(t, m, c, k, F0, W):
    """m x'' + c x' + k x = F0 cos(W t) from rest, closed form."""
    wn = math.sqrt(k / m)
    z = c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - z * z)
    X = F0 / complex(k - m * W * W, c * W)  # steady state X e^{i W t}
    x0p, v0p = X.real, -W * X.imag  # its value and rate at t = 0
    A = -x0p  # the homogeneous part cancels them
    B = (z * wn * A - v0p) / wd
    return np.exp(-z * wn * t) * (A * np.cos(wd * t) + B * np.sin(wd * t)) + (X * np.exp(1j * W * t)).real


def step_oscillator(step: Step, n: int, m, c, k, F0, W) -> float:
    """x(n h) by the scalar step the 3D run uses for its rotor centre (history + new-time force)."""
    x = v = 0.0
    a = F0 / m
    kk = step.mass_coefficient * m + step.damping_coefficient * c + step.new_weight * k
    for i in range(n):
        t0, t1 = i * step.h, (i + 1) * step.h
        old = -k * x + F0 * math.cos(W * t0)
        x1 = (step.history(m, c, x, v, a, old) + step.new_weight * F0 * math.cos(W * t1)) / kk
        v, a = step.update(x1, *step.predict(x, v, a))
        x = x1
    return x


@pytest.mark.parametrize("method, rho", SCHEMES)
def test_scalar_step_is_second_order_on_a_forced_damped_oscillator(method, rho):
    m, c, k, F0, W, T = 2.0, 0.6, 200.0, 3.0, 7.0, 2.0
    p = full_order_parameters(method, rho)
    hs, errs = [], []
    for n in (200, 400, 800, 1600):
        h = T / n
        x = step_oscillator(Step(h, **p), n, m, c, k, F0, W)
        errs.append(abs(x - oscillator_exact(T, m, c, k, F0, W)))
        hs.append(h)
    assert 1.85 <= slope(hs, errs) <= 2.15


@pytest.mark.parametrize("method, rho", SCHEMES)
def test_spin_equation_is_second_order_on_a_linear_drive(method, rho):
    """J theta'' = M0 - s Omega: Omega = (M0/s)(1 - exp(-s t/J)), theta its integral."""
    J, M0, s, T = 100.0, 5100.0, 12.0, 5.0
    rot = RotorOnTop(1600.0, J, 0.0, 4e5, 1.1e4)
    zero = Affine(0.0, 0.0, 0.0)
    p = full_order_parameters(method, rho)
    exact = (M0 / s) * (T - J / s * (1 - math.exp(-s * T / J)))
    hs, errs = [], []
    for n in (200, 400, 800, 1600):
        h = T / n
        st = Step(h, **p)
        th, W, al, tau = 0.0, 0.0, M0 / J, M0
        for _ in range(n):
            th, W, al, _it = solve_spin(rot, h, th, W, al, zero, zero, M0, s, 0.0, step=st, old_torque=tau)
            tau = M0 - s * W
        hs.append(h)
        errs.append(abs(th - exact))
    assert 1.85 <= slope(hs, errs) <= 2.15


@pytest.mark.parametrize("rho", [0.8, 0.5, 0.0])
def test_far_above_the_band_the_step_shrinks_a_mode_by_rho_inf(rho):
    """The scalar step's own one-step map (applied to the unit states) has the
    amplification's eigenvalues, whose radius is rho_inf far above the band; a
    free oscillation there is gone in a few dozen steps (Newmark would keep it)."""
    p = full_order_parameters("generalized_alpha", rho)
    w, h = 1e4, 1.0  # omega h = 1e4: far above any band
    st = Step(h, **p)
    m, k = 1.0, w * w
    kk = st.mass_coefficient * m + st.new_weight * k

    def one(x, v, a):
        x1 = st.history(m, 0.0, x, v, a, -k * x) / kk
        return (x1, *st.update(x1, *st.predict(x, v, a)))

    scale = np.diag([1.0, h, h * h])  # the state as (x, h v, h**2 a)
    A = np.column_stack([scale @ np.array(one(*(np.linalg.inv(scale) @ e))) for e in np.eye(3)])
    radius = max(abs(np.linalg.eigvals(A)))
    assert radius == pytest.approx(scheme_error("generalized_alpha", w * h, **p).spectral_radius, rel=1e-8)
    assert radius == pytest.approx(rho, abs=1e-2)
    state = (1.0, 0.0, -k)
    for _ in range(200):
        state = one(*state)
    assert abs(state[0]) < (rho + 0.05) ** 100


def test_period_errors_are_the_closed_forms():
    for Om in (0.1, 0.6, 1.5):
        nm = scheme_error("newmark", Om)
        assert nm.period_error == pytest.approx(Om / (2 * math.atan(Om / 2)) - 1, rel=1e-12)
        assert abs(nm.amplitude_loss) < 1e-12
        cd = scheme_error("central_difference", Om)
        assert cd.period_error == pytest.approx(Om / math.acos(1 - Om * Om / 2) - 1, rel=1e-10)
    assert scheme_error("newmark", 0.05).period_error == pytest.approx(0.05**2 / 12, rel=1e-3)
    z = 0.3 + 0.7j
    assert stability_function("dp5", z) == pytest.approx(
        sum(z**k / math.factorial(k) for k in range(6)) + z**6 / 600, rel=1e-13
    )
    # Newmark's 10 % limit in closed form: Om / (2 atan(Om / 2)) = 1.1
    from scipy.optimize import brentq

    Om = brentq(lambda x: x / (2 * math.atan(x / 2)) - 1.1, 0.1, 3.0)
    assert steps_per_period_needed("newmark", 0.1) == pytest.approx(2 * math.pi / Om, rel=1e-8)
    assert not scheme_error("central_difference", 2.1).stable


@pytest.mark.parametrize("method, rho", [("newmark", 1.0), ("generalized_alpha", 0.8), ("hht", 0.6)])
def test_the_kernels_do_what_the_accuracy_module_says(method, rho):
    """An undamped oscillator at 12 steps per period, 50 periods, by the compiled kernel:
    its period (phase of the last cycles) and its amplitude decay are the predicted ones."""
    from test_integrators import IDLE, oscillator, start

    from rotorpillar.reduced.excitation import no_motion
    from rotorpillar.reduced.integration import Settings, simulate

    w, spp, periods = 30.0, 12, 50
    h = 2 * math.pi / w / spp
    n = spp * periods
    model = oscillator(w)
    st = Settings(method, time_step=h, samples=n + 1, rho_inf=rho, hht_alpha=(rho - 1) / (rho + 1))
    run = simulate(model, IDLE, no_motion(), n * h, start(model), settings=st, speed_scale=1.0)
    err = scheme_error(method, w * h, **full_order_parameters(method, rho))
    # once the spurious root has died, x_n = A r**n cos(n theta + phi) exactly, so
    # x_{n+1} = 2 r cos(theta) x_n - r**2 x_{n-1}: r and theta by least squares
    x = run.q[len(run.q) // 2 :, 0]
    (p1, q1), *_ = np.linalg.lstsq(np.column_stack([x[1:-1], x[:-2]]), x[2:], rcond=None)
    r = math.sqrt(-q1)
    theta = math.acos(p1 / (2 * r))
    assert w * h / theta - 1 == pytest.approx(err.period_error, rel=1e-6)
    assert 1 - r**spp == pytest.approx(err.amplitude_loss, rel=1e-6, abs=1e-12)


def test_the_full_orders_step_ignores_the_stiff_shaft():
    from rotorpillar.fem3d.full_order_plan import case_setup, step_rule
    from rotorpillar.reduced.models import scene_motion
    from rotorpillar.scene import load_scene
    from rotorpillar.transients.cases import full_order_step_rule

    rec = ["excitation.kind=record"]
    soft, stiff = load_scene("paper", rec), load_scene("paper", rec + ["shaft.stiffness=1e10"])
    motion = scene_motion(soft)
    beam = [full_order_step_rule(s, "earthquake", motion, "generalized_alpha") for s in (soft, stiff)]
    assert beam[0].time_step == beam[1].time_step
    rules = []
    for s in (soft, stiff):
        mo, drive, _, speed, _ = case_setup(s, "earthquake", motion, None, 15.0, 80.0)
        rules.append(step_rule(s, drive, mo, speed))
    assert rules[0].time_step == rules[1].time_step == beam[0].time_step
    r = rules[0]
    # the unbalance's rotation at the drive's free speed is the fastest forcing here
    assert r.forcing_top == pytest.approx(max(r.forcing.values()))
    assert r.at_forcing_top.worst == pytest.approx(FULL_ORDER_ERROR, rel=1e-6)
    assert r.time_step <= motion.time_step
