"""Pillar modes (the modal model's input) against cantilever closed forms.

References:
- Euler-Bernoulli cantilever, Eq. 1: omega_k = (beta_k H)**2 sqrt(EI/(m H**4));
  the 40-element Hermite model converges as (k h)**4: 1e-6 k**2 for k = 1..3;
- its first mode scaled to a unit tip deflection has the modal mass m_col/4
  (Eq. 2 in the continuous limit, as reduced.pillar states): 1e-5;
- effective modal masses of a uniform cantilever, 61.3 %, 18.8 %, 6.5 % of
  its mass (the classical values for the first three modes): 1e-3; over every mode of the
  discrete model they sum to the mass off the clamped node: 1e-10;
- with a tip mass M_t the frequency equation is
  1 + cos b cosh b + (M_t/m_col) b (cos b sinh b - sin b cosh b) = 0
  (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1): 1e-6;
- Timoshenko against Euler-Bernoulli: the first frequency of the bare tube drops by the
  shear and rotary-inertia correction of reduced.pillar's closed form (Timoshenko's
  clamped-free frequency equation with Cowper's kappa): 2e-5, the 200 linear Timoshenko
  elements' h**2 error ((pi/200)**2/12 ~ 2e-5; the Hermite beam's h**4 error is nil here).
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorpillar.reduced.pillar import omega_euler_bernoulli, section_of
from rotorpillar.reduced.pillar_modes import beam_pillar_modes
from rotorpillar.reduced.reduction import pillar_closed_forms
from rotorpillar.scene import load_scene, override


@pytest.fixture(scope="module")
def bare():
    return override(load_scene("paper"), ["gondola.mass=1e-9"])


def test_bare_cantilever_frequencies_and_tip_mass(bare):
    p = bare.pillar
    sec = section_of(p)
    pm = beam_pillar_modes(bare.pillar, bare.gondola.mass, 3, "euler", 40)
    for k in (1, 2, 3):
        w = omega_euler_bernoulli(p.youngs_modulus, sec.second_moment, sec.mass_per_length, p.height, k)
        assert pm.omega[k - 1] == pytest.approx(w, rel=1e-6 * k**2)
    m_col = sec.mass_per_length * p.height
    assert pm.modal_mass[0] == pytest.approx(m_col / 4, rel=1e-5)


def test_effective_masses(bare):
    pm = beam_pillar_modes(bare.pillar, bare.gondola.mass, 3, "euler", 40)
    sec = section_of(bare.pillar)
    m_col = sec.mass_per_length * bare.pillar.height
    eff = pm.participation**2 / pm.modal_mass / m_col
    assert eff == pytest.approx([0.6131, 0.1883, 0.0647], abs=1e-3)
    # what the base moves is the mass off the clamped node: r^T M r of the free dofs
    assert pm.total_mass == pytest.approx(m_col * (1 - 0.5 / 40), rel=1e-2)
    full = beam_pillar_modes(bare.pillar, bare.gondola.mass, 200, "euler", 20)  # every mode of the discrete model
    assert full.effective_mass_fraction() == pytest.approx(1.0, abs=1e-10)


def test_first_frequency_with_the_gondola():
    scene = load_scene("paper")
    p = scene.pillar
    sec = section_of(p)
    m_col = sec.mass_per_length * p.height
    ratio = scene.gondola.mass / m_col
    f = lambda b: 1 + math.cos(b) * math.cosh(b) + ratio * b * (math.cos(b) * math.sinh(b) - math.sin(b) * math.cosh(b))
    b1 = brentq(f, 0.5, 1.875104)
    w1 = b1**2 * math.sqrt(p.youngs_modulus * sec.second_moment / (sec.mass_per_length * p.height**4))
    pm = beam_pillar_modes(scene.pillar, scene.gondola.mass, 1, "euler", 40)
    assert pm.omega[0] == pytest.approx(w1, rel=1e-6)


def test_simpson_on_quadratic_element_levels_is_exact_for_quadratics():
    from rotorpillar.fem3d.pillar_modes import integrate_levels

    ends = np.array([0.0, 0.3, 1.0, 2.5, 4.0])  # graded elements
    z = np.sort(np.r_[ends, 0.5 * (ends[:-1] + ends[1:])])
    f = 3 * z**2 - z + 2
    assert integrate_levels(z, f) == pytest.approx(4.0**3 - 8.0 + 8.0, rel=1e-13)


@pytest.mark.slow
def test_modes_of_the_3d_model_agree_with_the_timoshenko_beam():
    """The 3D tube's X bending modes with the gondola on a rigid top plate
    against the 1D Timoshenko beam with the gondola as a tip mass: the same
    structure in two theories.  The plate's rotary inertia and the wall's
    flexibility separate them by ~1-2 % in the second mode: 3 %."""
    pytest.importorskip("dolfinx")
    from rotorpillar.fem3d.pillar_modes import fem3d_pillar_modes

    scene = override(load_scene("paper"), ["modal_model.source=fem3d"])
    pm = fem3d_pillar_modes(scene, 2)
    beam = beam_pillar_modes(scene.pillar, scene.gondola.mass, 2, "timoshenko", 40)
    assert pm.omega == pytest.approx(beam.omega, rel=0.03)
    assert pm.modal_mass == pytest.approx(beam.modal_mass, rel=0.03)
    assert pm.participation == pytest.approx(beam.participation, rel=0.03)
    assert pm.shapes[-1] == pytest.approx([1.0, 1.0])
    # the candidates the simulate command passes to the reduced package
    from rotorpillar.fem3d.pillar_modes import candidate_pillar_modes
    from rotorpillar.reduced.models import build_model

    model, info = build_model(scene, "modal", modes=2, pillar_modes=candidate_pillar_modes(scene))
    assert list(model.pillar_modes.omega) == list(pm.omega) and info.modes == 2


def test_modal_model_on_3d_modes_needs_them_passed_in():
    """The reduced package never runs the 3D model: asked for fem3d modes
    without them, it names the key."""
    from rotorpillar.errors import InputError
    from rotorpillar.reduced.models import build_model

    scene = override(load_scene("paper"), ["modal_model.source=fem3d"])
    with pytest.raises(InputError, match="modal_model.source"):
        build_model(scene, "modal", modes=2)


@pytest.mark.parametrize("overrides", [[], ["pillar.height=8", "pillar.inner_diameter=1.8"]])
def test_each_beam_theory_gives_its_own_frequencies(overrides):
    """The two theories differ by the closed form's shear correction: the beam's
    properties carry Cowper's kappa, the Euler-Bernoulli element ignores it (a squat,
    thick tube: a correction of several per cent)."""
    p = load_scene("paper", overrides).pillar
    euler, timo = (beam_pillar_modes(p, 0.0, 1, theory, 200).omega[0] for theory in ("euler", "timoshenko"))
    closed = pillar_closed_forms(p)
    # 1e-7: the 200-element eigenproblem's round-off (K's condition grows as n**4)
    assert euler == pytest.approx(closed.omega_col1, rel=1e-7)
    assert timo / euler - 1 == pytest.approx(closed.timoshenko_correction, abs=2e-5)
    assert closed.timoshenko_correction < -1e-2  # one this test can see: 1.6 % on the paper's tube
