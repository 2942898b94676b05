"""Pillar closed forms (Eq. 1-2) against independent references.

Sources and tolerances:
- cantilever roots: Blevins, Formulas for Natural Frequency and Mode Shape
  (1979), Table 8-1: 1.87510407, 4.69409113, 7.85475744; we solve to 1e-14,
  so 1e-8 checks the eight printed digits.
- Eq. 1 against a 1D Hermite finite-element model (another method), whose
  error must fall as h**4 (fitted slope within [3.5, 4.5], the textbook
  rate with room for the pre-asymptotic first points).
- Eq. 2 against its own limit: the lumped tip mass tends to m_col/4 with
  error O(1/n) (slope within [-1.1, -0.9]).
- Timoshenko transfer-matrix root against a 1D Timoshenko FE model refined
  to h**2 convergence (Richardson from two meshes, agreement 1e-6), and its
  slender limit: Euler-Bernoulli within the O((r/H)**2) shear correction.
- Rayleigh quotients bound omega_col1 from above (a theorem), the uniform
  load shape within 0.5 % (Rayleigh's classical accuracy, 0.4 % here).
"""

import math

import numpy as np
import pytest
from scipy.integrate import trapezoid  # np.trapz is gone in NumPy 2

from rotorpillar.reduced.beam_fe import BeamProperties, beam_modes
from rotorpillar.reduced.pillar import (
    cantilever_mode,
    cantilever_root,
    cowper_shear_coefficient,
    omega_euler_bernoulli,
    omega_timoshenko,
    rayleigh_reduction,
    tip_mass_continuous,
    tip_mass_lumped,
    tube_section,
)

E, NU, RHO, H = 2.1e11, 0.3, 8.1e3, 20.0
SEC = tube_section(2.0, 1.96, RHO)


def props(kappa=None, sec=SEC, H=H):
    kappa = kappa or cowper_shear_coefficient(sec.outer_diameter, sec.inner_diameter, NU)
    return BeamProperties(E, NU, kappa, RHO, sec.area, sec.second_moment, H)


@pytest.mark.parametrize("k, blevins", [(1, 1.87510407), (2, 4.69409113), (3, 7.85475744)])
def test_cantilever_roots_match_blevins(k, blevins):
    assert cantilever_root(k) == pytest.approx(blevins, abs=1e-8)


def test_mode_shape_normalisation_and_boundary_conditions():
    xi = np.linspace(0, 1, 20001)
    for k in (1, 2, 3):
        u = cantilever_mode(xi, k)
        assert trapezoid(u**2, xi) == pytest.approx(1.0, rel=1e-6)
        assert abs(u[-1]) == pytest.approx(2.0, rel=1e-9)
        assert u[0] == pytest.approx(0.0, abs=1e-12)
        # clamped: zero slope at the base, so u(h) ~ u''(0) h^2 / 2 = beta^2 h^2
        h = xi[1]
        assert abs(u[1]) < 1.01 * cantilever_root(k) ** 2 * h**2


def test_paper_tube_section():
    # the paper quotes I ~ 0.061 m^4 (Sec. 2.1); closed form pi/64 (D0^4 - D1^4)
    assert SEC.second_moment == pytest.approx(math.pi / 64 * (2**4 - 1.96**4), rel=1e-15)
    assert SEC.second_moment == pytest.approx(0.061, rel=2e-3)


def test_omega_col1_against_beam_fe_with_h4_convergence():
    w = omega_euler_bernoulli(E, SEC.second_moment, SEC.mass_per_length, H)
    ns = np.array([2, 4, 8, 16])
    err = np.array([beam_modes(props(), n, "euler", 1).omega[0] / w - 1 for n in ns])
    assert np.all(err > 0)  # consistent mass FE bounds from above
    slope = np.polyfit(np.log(ns), np.log(err), 1)[0]
    assert -4.5 < slope < -3.5
    assert err[-1] < 2e-7


def test_tip_mass_tends_to_quarter_of_the_pillar_as_O_of_1_over_n():
    m = 1000.0
    assert tip_mass_continuous(m) == 250.0
    assert tip_mass_lumped(m, 1) == pytest.approx(m)  # one mass at the tip
    ns = np.array([10, 20, 40, 80, 160])
    err = np.array([tip_mass_lumped(m, n) - 250.0 for n in ns])
    assert np.all(np.diff(err) < 0) and np.all(err > 0)
    slope = np.polyfit(np.log(ns), np.log(err), 1)[0]
    assert -1.1 < slope < -0.9


def test_rayleigh_bounds_omega_from_above():
    w = omega_euler_bernoulli(E, SEC.second_moment, SEC.mass_per_length, H)
    mass = SEC.mass_per_length * H
    uni = rayleigh_reduction(mass, E, SEC.second_moment, H, "uniform_load")
    tip = rayleigh_reduction(mass, E, SEC.second_moment, H, "tip_load")
    assert uni.omega > w and tip.omega > w
    assert uni.omega / w - 1 < 5e-3
    # textbook values: 33/140 of the beam mass and 3 EI/H^3 for a tip load
    assert tip.tip_mass == pytest.approx(33 / 140 * mass, rel=1e-12)
    assert tip.tip_stiffness == pytest.approx(3 * E * SEC.second_moment / H**3, rel=1e-12)


def test_cowper_shear_coefficient_limits():
    # Cowper (1966): solid circle 6(1+nu)/(7+6nu); thin tube 2(1+nu)/(4+3nu)
    assert cowper_shear_coefficient(1.0, 0.0, NU) == pytest.approx(6 * 1.3 / (7 + 1.8))
    assert cowper_shear_coefficient(1.0, 0.9999, NU) == pytest.approx(2 * 1.3 / (4 + 0.9), rel=1e-6)


def test_timoshenko_root_against_timoshenko_fe():
    kappa = cowper_shear_coefficient(2.0, 1.96, NU)
    exact = omega_timoshenko(E, NU, kappa, RHO, SEC.area, SEC.second_moment, H)
    w256 = beam_modes(props(kappa), 256, "timoshenko", 1).omega[0]
    w512 = beam_modes(props(kappa), 512, "timoshenko", 1).omega[0]
    richardson = (4 * w512 - w256) / 3  # h**2 convergence
    assert richardson == pytest.approx(exact, rel=1e-6)
    eb = omega_euler_bernoulli(E, SEC.second_moment, SEC.mass_per_length, H)
    assert exact < eb


def test_timoshenko_tends_to_euler_bernoulli_for_slender_beams():
    sec = tube_section(0.2, 0.1, RHO)
    kappa = cowper_shear_coefficient(0.2, 0.1, NU)
    for length in (5.0, 20.0):
        eb = omega_euler_bernoulli(E, sec.second_moment, sec.mass_per_length, length)
        ti = omega_timoshenko(E, NU, kappa, RHO, sec.area, sec.second_moment, length)
        r_over_h2 = sec.second_moment / sec.area / length**2
        # first-order theory (simply supported analogue): 1 - w_T/w_EB ~
        # (beta H)^2 / 2 (1 + E/(kappa G)) (r/H)^2 ~ 9.4 (r/H)^2 here; 20 leaves
        # room for the cantilever's other end condition, and 0 < keeps the sign
        assert 0 < 1 - ti / eb < 20 * r_over_h2


@pytest.mark.parametrize("lambda_h", [150.0, 400.0])
def test_timoshenko_past_the_transfer_matrix_against_timoshenko_fe(lambda_h):
    """Past lambda H = SLENDER the root is scaled from the same section's (its shear
    correction ~ 1/H**2), not solved (the determinant cancels to noise; a 1 km tower
    raised an internal error).  The reference is the Timoshenko FE (another method),
    Richardson-extrapolated over three mesh pairs (128/256, 256/512, 512/1024).  So slender
    a beam's correction (1.2e-4 at 150, 1.7e-5 at 400) is near the FE's round-off (its
    Euler-Bernoulli frequency at 512 elements is off the closed form by 2e-6 to 4e-6 here,
    where the discretisation error is ~1e-12): the three pairs scatter by 0.1 % at 150 and
    by 1.5 % at 400 (measured), and that scatter is the reference's own uncertainty.  The
    closed form's correction must lie within the pairs' range, widened by 0.1 % of it for
    the last digits; a wrong scaling (e.g. 1/H instead of 1/H**2: a factor 2.7 at 400) is
    far outside.  Further out (lambda H = 3000) the pairs disagree by a factor 20: no
    reference there."""
    kappa = cowper_shear_coefficient(2.0, 1.96, NU)
    G = E / (2 * (1 + NU))
    length = lambda_h / math.sqrt(kappa * G * SEC.area / (E * SEC.second_moment))
    exact = omega_timoshenko(E, NU, kappa, RHO, SEC.area, SEC.second_moment, length)
    p = BeamProperties(E, NU, kappa, RHO, SEC.area, SEC.second_moment, length)
    eb = omega_euler_bernoulli(E, SEC.second_moment, SEC.mass_per_length, length)
    w = {n: beam_modes(p, n, "timoshenko", 1).omega[0] for n in (128, 256, 512, 1024)}
    corrections = [((4 * w[b] - w[a]) / 3) / eb - 1 for a, b in ((128, 256), (256, 512), (512, 1024))]
    lo, hi = min(corrections), max(corrections)
    slack = 1e-3 * abs(hi + lo) / 2
    assert lo - slack <= exact / eb - 1 <= hi + slack, (exact / eb - 1, corrections)


def test_the_remembered_timoshenko_frequency_is_the_computed_one():
    """``omega_timoshenko`` is remembered per arguments (each model build asks it; a study's
    predicted boundary builds one per point of its curve): the remembered value is the
    computation's, bitwise, for the paper tube's first two modes and a slender tube (the
    branch that calls itself on a shorter one)."""
    import math

    from rotorpillar.reduced.pillar import omega_timoshenko

    A, I = math.pi / 4 * (2.0**2 - 1.96**2), math.pi / 64 * (2.0**4 - 1.96**4)
    for args in (
        (210e9, 0.3, 0.53, 8100.0, A, I, 20.0, 1),
        (210e9, 0.3, 0.53, 8100.0, A, I, 20.0, 2),
        (210e9, 0.3, 0.53, 8100.0, A, I, 2000.0, 1),
    ):
        fresh = omega_timoshenko.__wrapped__(*args)
        assert omega_timoshenko(*args) == fresh and omega_timoshenko(*args) == fresh
