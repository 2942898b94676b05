"""Averaging results (the paper's Eq. 19-20, 23, 24) against integrated equations.

References:
- the quasi-normal equation x'' + 2n x' + omega^2 x = f cos(Omega t),
  integrated at fixed Omega (DOP853, rtol 1e-10) to steady state; its
  amplitude and the averaged torque <g x sin(Omega t)> are measured over the
  last whole periods.  At z = 1 Eq. 19-20 are exact, so they must agree to
  the integration accuracy (1e-5); off resonance they are first-order
  expansions in (1 - z), whose error is bounded by |1 - z| (amplitude) and
  2|1 - z| (torque) plus 1e-5.
- the full linear X-Y system of Eq. 4 at fixed Omega (exact steady state by
  a complex frequency-domain solve): its averaged torque at Omega = omega_i
  minus the other modes' exact tails must equal Eq. 20's term for mode i,
  within the error of dropping Eq. 4's non-proportional modal damping
  coupling (see the test's docstring).  The paper's coupling f4 = c2 e instead of
  g_i misses it by the factor (u_2i - u_1i), which the last test shows.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp, trapezoid

from rotorpillar.reduced import averaging as av
from rotorpillar.reduced.system import linear_modes, paper_example

RESONANCES = linear_modes(paper_example()).resonances + linear_modes(paper_example(5e6, 25e3)).resonances


def integrate_mode(r, Omega, periods_settle=None, periods_measure=20):
    """Steady amplitude and averaged torque of one quasi-normal mode at fixed Omega."""
    T = 2 * np.pi / Omega
    settle = periods_settle or int(np.ceil(12 / (r.n * T)))  # e^-12 of the transient
    t_end = (settle + periods_measure) * T
    rhs = lambda t, y: [y[1], r.forcing * np.cos(Omega * t) - r.two_n * y[1] - r.omega**2 * y[0]]
    t_eval = np.linspace(settle * T, t_end, periods_measure * 200 + 1)
    sol = solve_ivp(rhs, (0, t_end), [0.0, 0.0], method="DOP853", rtol=1e-10, atol=1e-14, t_eval=t_eval)
    x, t = sol.y[0], sol.t
    basis = np.column_stack([np.cos(Omega * t), np.sin(Omega * t)])
    coef = np.linalg.lstsq(basis, x, rcond=None)[0]
    amp = np.hypot(*coef)
    torque = trapezoid(r.coupling * x * np.sin(Omega * t), t) / (t[-1] - t[0])
    return amp, torque


@pytest.mark.parametrize("r", RESONANCES, ids=lambda r: f"w{r.omega:.1f}")
def test_eq19_eq20_exact_at_resonance(r):
    amp, torque = integrate_mode(r, r.omega)
    assert float(av.amplitude(r.omega, r)) == pytest.approx(amp, rel=1e-5)
    assert float(av.resistance_increment(r.omega, r)) == pytest.approx(torque, rel=1e-5)


@pytest.mark.parametrize("z", [0.9, 0.95, 1.05, 1.1])
def test_eq19_eq20_first_order_off_resonance(z):
    r = RESONANCES[0]
    W = z * r.omega
    amp, torque = integrate_mode(r, W)
    # the exact linear forms agree with the integration
    assert float(av.amplitude_linear(W, r)) == pytest.approx(amp, rel=1e-5)
    assert float(av.resistance_increment_linear(W, r)) == pytest.approx(torque, rel=1e-5)
    # the averaging forms are first-order accurate in (1 - z)
    assert abs(float(av.amplitude(W, r)) / amp - 1) <= abs(1 - z) + 1e-5
    assert abs(float(av.resistance_increment(W, r)) / torque - 1) <= 2 * abs(1 - z) + 1e-5


def full_system_torque(s, Omega):
    """Averaged resisting torque of Eq. 4 with q4 = Omega t, exact steady state."""
    K, M, C = s.stiffness_matrix(), s.mass_matrix(), s.damping_matrix()
    c2e = s.shaft_stiffness * s.eccentricity
    # X: forcing c2 e (-1, 1) cos(Omega t) -> complex amplitude Q, q = Re(Q e^{i W t})
    Q = np.linalg.solve(K - Omega**2 * M + 1j * Omega * C, c2e * np.array([-1.0, 1.0]))
    rel = Q[1] - Q[0]
    # <c2 e (q2 - q1) sin(W t)> = c2 e * (-Im(rel)) / 2
    torque_x = c2e * (-rel.imag) / 2
    # Y: m q3'' + b2 q3' + c2 q3 = c2 e sin(W t); torque -c2 e q3 cos(W t) resists
    Y = c2e / (s.shaft_stiffness - Omega**2 * s.rotor_mass + 1j * Omega * s.shaft_damping)
    # q3 = Im(Y e^{iWt}); <q3 cos(Wt)> = Im(Y)/2;  resisting torque = -c2 e <q3 cos>
    torque_y = -c2e * Y.imag / 2
    return torque_x + torque_y


def modal_damping_coupling(s):
    """Largest |c_ij| / sqrt(c_ii c_jj) of Eq. 4's damping in the X modes."""
    U = np.array([r.shape for r in linear_modes(s).resonances[:2]]).T
    Cm = U.T @ s.damping_matrix() @ U
    return abs(Cm[0, 1]) / np.sqrt(Cm[0, 0] * Cm[1, 1])


@pytest.mark.parametrize(
    "scene, index, agrees",
    [
        ("elastic", 1, True),
        ("elastic", 2, True),
        ("elastic", 3, True),
        ("stiff", 1, False),
        ("stiff", 2, True),
        ("stiff", 3, True),
    ],
)
def test_eq20_resonant_term_against_full_equations(scene, index, agrees):
    """Full Eq. 4 torque minus the other modes' exact tails = Eq. 20's term.

    Where the modal damping coupling is weak (0.11, elastic shaft) the
    quasi-normal picture holds to a few per cent: 3 %.  With the stiff shaft
    Eq. 4's non-proportional damping couples the X modes strongly (0.45) and
    at omega_1 the decoupled mode misses the full torque by a quarter: the
    paper's reduction to quasi-normal coordinates stops holding there.
    """
    s = paper_example() if scene == "elastic" else paper_example(5e6, 25e3)
    res = linear_modes(s).resonances
    r = res[index - 1]
    tails = sum(float(av.resistance_increment_linear(r.omega, q)) for q in res if q is not r)
    own = full_system_torque(s, r.omega) - tails
    err = abs(own / float(av.resistance_increment(r.omega, r)) - 1)
    if agrees:
        assert err < 0.03
    else:
        assert modal_damping_coupling(s) > 0.3 and err > 0.1


def test_paper_coupling_f4_misses_the_mode_factor():
    s = paper_example()
    r = linear_modes(s).resonances[0]
    c2e = s.shaft_stiffness * s.eccentricity
    printed = float(av.resistance_increment_as_printed(r.omega, r, c2e))
    ours = float(av.resistance_increment(r.omega, r))
    assert ours / printed == pytest.approx(r.shape[1] - r.shape[0], rel=1e-12)
    assert abs(printed / full_system_torque(s, r.omega) - 1) > 0.5


def strong_case():
    """The paper's elastic scene with a 20x eccentricity: resonances 1 and 3 fold."""
    from rotorpillar.reduced.system import ReducedSystem

    s = paper_example()
    s = ReducedSystem(
        s.tip_mass,
        s.rotor_mass,
        s.rotor_inertia,
        20 * s.eccentricity,
        s.pillar_stiffness,
        s.shaft_stiffness,
        s.pillar_damping,
        s.shaft_damping,
    )
    return linear_modes(s).resonances


def test_jumps_are_folds_of_the_stationary_curve():
    res = strong_case()
    ch = av.Characteristic(500.0, 12.0, 0.5)
    out = av.analyse_drive(ch, res)
    assert out.jumps, "a 20x eccentricity must fold the curve"
    F = lambda W: float(av.total_resistance(W, 0.5, res) + 12.0 * W)
    for j in out.jumps:
        h = 1e-6 * j.omega_from
        dF = (F(j.omega_from + h) - F(j.omega_from - h)) / (2 * h)  # independent derivative
        assert abs(dF) < 1e-4 * 12.0
        assert F(j.omega_to) == pytest.approx(j.torque_at_zero, rel=1e-9)
        if j.direction == "up":
            assert j.omega_to > j.omega_from
        else:
            assert j.omega_to < j.omega_from
    ups = [j for j in out.jumps if j.direction == "up"]
    downs = [j for j in out.jumps if j.direction == "down"]
    assert len(ups) == len(downs)
    # hysteresis: the run-down's fold lies above the run-up's in speed, below in torque
    for u, d in zip(ups, downs):
        assert d.omega_from > u.omega_from and d.torque_at_zero < u.torque_at_zero


def test_stability_alternates_and_quasistatic_branches():
    res = strong_case()
    up = [j for j in av.analyse_drive(av.Characteristic(500.0, 12.0, 0.5), res).jumps if j.direction == "up"][0]
    down = [j for j in av.analyse_drive(av.Characteristic(500.0, 12.0, 0.5), res).jumps if j.direction == "down"][0]
    M0 = 0.5 * (up.torque_at_zero + down.torque_at_zero)  # inside the hysteresis band
    out = av.analyse_drive(av.Characteristic(M0, 12.0, 0.5), res)
    assert [s.stable for s in out.stationary] == [True, False, True]
    assert out.runup_speed < up.omega_from < out.rundown_speed
    assert out.captured_index is not None


def test_branch_is_stable_against_a_numerical_derivative():
    """Eq. 23 by finite differences of Md - L on the strong case's
    stationary speeds: stable exactly where d(Md - L)/dOmega < 0."""
    res = strong_case()
    s, k = 12.0, 0.5
    G = lambda W: float(-s * W - av.total_resistance(W, k, res))  # Md - L without M0
    up = [j for j in av.analyse_drive(av.Characteristic(500.0, s, k), res).jumps if j.direction == "up"][0]
    out = av.analyse_drive(av.Characteristic(up.torque_at_zero * 0.999, s, k), res)
    assert len(out.stationary) == 3
    for st in out.stationary:
        h = 1e-6 * st.omega
        dG = (G(st.omega + h) - G(st.omega - h)) / (2 * h)
        assert bool(av.branch_is_stable(st.omega, s, k, res)) == (dG < 0) == st.stable
        assert av.stability_margin(st.omega, s, k, res) == pytest.approx(dG, rel=1e-5)
    grid = np.array([st.omega for st in out.stationary])
    assert list(av.branch_is_stable(grid, s, k, res)) == [st.stable for st in out.stationary]


def test_peak_resistance_ratio_is_eq20_over_the_load_at_resonance():
    r = linear_modes(paper_example(5e6, 25e3)).resonances[0]
    assert av.peak_resistance_ratio(r, 0.5) == pytest.approx(
        float(av.resistance_increment(r.omega, r)) / (0.5 * r.omega**2), rel=1e-15
    )


def test_critical_eccentricity_is_where_folds_appear():
    base = paper_example()
    from rotorpillar.reduced.system import ReducedSystem

    ch = av.Characteristic(5100.0, 12.0, 0.5)
    r = linear_modes(base).resonances[2]  # the Y resonance, alone
    factor = av.critical_eccentricity_factor(ch, r, 200.0)
    for scale, expect in ((0.97, False), (1.03, True)):
        e = base.eccentricity * factor * scale
        s = ReducedSystem(
            base.tip_mass,
            base.rotor_mass,
            base.rotor_inertia,
            e,
            base.pillar_stiffness,
            base.shaft_stiffness,
            base.pillar_damping,
            base.shaft_damping,
        )
        r2 = linear_modes(s).resonances[2]
        folds = av.analyse_drive(av.Characteristic(2000.0, 12.0, 0.5), [r2], top=200.0).jumps
        assert bool(folds) is expect


def test_roots_finds_sign_changes_and_grid_points_that_are_roots():
    """The stationary regimes' root finder: a root between two grid speeds is bracketed
    (brentq to 1e-12 relative), a root that lies on a grid speed (the function exactly 0
    there, no sign change on either side) is taken from the grid itself; both in order.
    Reference: the roots 1.7, 3 and 4.3 of a cubic, on a grid that holds 3.0 and brackets the others."""
    grid = np.linspace(0.5, 5.0, 10)  # 0.5, 1.0, ..., 5.0 (exact in binary): 3.0 is a grid speed

    def f(W):
        W = np.asarray(W, dtype=float)
        return (W - 1.7) * (W - 3.0) * (W - 4.3)

    roots = av._roots(f, grid)
    assert roots == pytest.approx([1.7, 3.0, 4.3], rel=1e-11)
    assert 3.0 in roots  # the grid point itself, not a bracket's estimate
    assert roots == sorted(roots)


def test_the_roots_exact_zeros_are_the_loops():
    """``averaging._roots`` takes the grid's exact zeros by a mask (it was a loop over the
    (speed, value) pairs): the same list as the loop's code, bitwise, on a grid with sign
    changes, exact zeros (-0.0 one of them) and NaNs (none), whole and cut by a mask as
    ``analyse_drive`` cuts it."""
    from scipy.optimize import brentq

    from rotorpillar.reduced.averaging import _roots

    def loop_roots(fun, grid):  # the code it replaces
        vals = np.asarray(fun(grid))
        out = []
        for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
            out.append(brentq(fun, grid[i], grid[i + 1], xtol=1e-12 * grid[i + 1]))
        out += [float(w) for w, v in zip(grid, vals) if v == 0.0]
        return sorted(out)

    grid = np.linspace(1.0, 100.0, 10_001)

    def fun(w):
        v = np.sin(np.asarray(w) / 7.0)
        v = np.where(np.isin(w, grid[[0, 17, 4000, 10_000]]), 0.0, v)
        v = np.where(np.isin(w, grid[[18]]), -0.0, v)
        return np.where(np.isin(w, grid[[5, 6]]), np.nan, v)

    for g in (grid, grid[grid > 30.0]):
        expected = loop_roots(fun, g)
        assert _roots(fun, g) == expected
    assert set(loop_roots(fun, grid)) >= {float(grid[i]) for i in (0, 17, 18, 4000, 10_000)}
