"""Internal forces of the pillar (rotorpillar.reduced.internal_forces, beam_fe.section_forces).

References and tolerances:
- statics: a tip load P on a cantilever gives V = P and M = P (H - z) at
  every section, by equilibrium, whatever the discretisation.  The element
  end forces K_e u_e carry it exactly: 1e-9 (round-off of a 40-element
  solve, condition ~1e8).
- the modal superposition of the section resultants with every mode of the
  discrete beam is the beam itself in other coordinates: the same numbers
  to round-off (1e-7 relative to the peak: 80 modes of a stiff model).
- the truncation check's reference (every mode available plus the static
  share of the others) against the beam's full-order harmonic solution
  over the band: the static share is exact at 0 Hz and the residual modes
  respond quasi-statically (omega / omega_13 < 0.05 over the band), so
  within 0.1 % of the peak.
- the mode counts on the paper's pillar: the tip needs fewer modes than the
  base moment, and the base shear, which carries the mass of the modes left
  out, more than the 12 available.
- a cubic Hermite interpolant through samples and slopes finds the peak of
  a sine to O(h**4): at 8 samples per period, placed to straddle the crests,
  within 0.2 % (measured 0.13 %) where the samples alone miss 7.6 %; at 4,
  within 2 % (1.5 %) where they miss 29 %.
"""

import math

import numpy as np
import pytest

from rotorpillar.reduced import internal_forces as f
from rotorpillar.reduced.beam_fe import THEORIES, assemble, section_forces
from rotorpillar.reduced.pillar import section_of
from rotorpillar.reduced.pillar_modes import beam_pillar_modes, beam_properties
from rotorpillar.scene import load_scene


@pytest.fixture(scope="module")
def scene():
    return load_scene("paper")


@pytest.mark.parametrize("theory", THEORIES)
def test_static_tip_load_gives_PL_and_constant_shear(scene, theory):
    bp = beam_properties(scene.pillar)
    n, P = 40, 1.0e4
    K, _ = assemble(bp, n, theory, scene.gondola.mass)
    load = np.zeros(K.shape[0])
    load[-2] = P
    u = np.r_[0.0, 0.0, np.linalg.solve(K, load)]
    V, M = section_forces(bp, n, theory, u)
    z = np.linspace(0, bp.length, n + 1)
    assert V == pytest.approx(np.full(n + 1, P), rel=1e-9)
    assert M == pytest.approx(P * (bp.length - z), rel=1e-9, abs=1e-9 * P * bp.length)
    assert M[0] == pytest.approx(P * bp.length, rel=1e-9)


@pytest.mark.parametrize("theory", THEORIES)
def test_all_modes_superposed_are_the_beam(scene, theory):
    """Harmonic tip force at 60 rad/s: modal superposition of the modes' resultants
    with every mode against the element end forces of the full-order solution."""
    n = 20
    pm = beam_pillar_modes(scene.pillar, scene.gondola.mass, 2 * n, theory, n)
    bp = beam_properties(scene.pillar)
    K, M = assemble(bp, n, theory, scene.gondola.mass)
    w = 60.0
    load = np.zeros(K.shape[0])
    load[-2] = 1.0
    u = np.r_[0.0, 0.0, np.linalg.solve(K - w**2 * M, load)]
    V, Mz = section_forces(bp, n, theory, u)
    eta = 1.0 / (pm.modal_stiffness - w**2 * pm.modal_mass)  # tip-scaled modes: f_j = 1
    assert f.superpose(eta[None], pm.moment_shapes)[0] == pytest.approx(Mz, rel=1e-7, abs=1e-7 * np.max(np.abs(Mz)))
    assert f.superpose(eta[None], pm.shear_shapes)[0] == pytest.approx(V, rel=1e-7, abs=1e-7 * np.max(np.abs(V)))
    assert np.sum(eta) == pytest.approx(u[-2], rel=1e-8)


def test_truncation_reference_is_the_full_order_beam(scene):
    """The truncation check's reference base moment against the beam's own harmonic solution."""
    n, theory = 40, "timoshenko"
    pm = beam_pillar_modes(scene.pillar, scene.gondola.mass, 12, theory, n)
    bp = beam_properties(scene.pillar)
    sec = section_of(scene.pillar)
    K, M = assemble(bp, n, theory, scene.gondola.mass)
    C = np.zeros_like(K)
    C[-2, -2] = scene.pillar.damping
    r = np.zeros(K.shape[0])
    r[0::2] = 1.0
    band = 186.0
    statics = f.cantilever_tip_statics(
        bp.youngs_modulus,
        bp.second_moment,
        bp.shear_coefficient * bp.shear_modulus * bp.area,
        bp.length,
        sec.mass_per_length,
        scene.gondola.mass,
    )
    trunc = f.force_truncation(
        pm, band, f.tip_dashpot(12, scene.pillar.damping), bp.length, sec.mass_per_length, scene.gondola.mass, statics
    )
    # the full-order beam: base moment under a unit tip force and a unit base acceleration
    omega = np.linspace(0, band, 300)

    def base_moment(u):
        return section_forces(bp, n, theory, np.r_[0.0, 0.0, u])[1][0]

    for name, load, fj in (("tip", np.eye(K.shape[0])[-2], np.ones(12)), ("base", -(M @ r), -pm.participation)):
        ref = []
        for w in omega:
            u = np.linalg.solve(K - w**2 * M + 1j * w * C, load.astype(complex))
            ref.append(base_moment(u.real) + 1j * base_moment(u.imag))
        ref = np.array(ref)
        # every mode available plus the static share of the rest: the check's reference
        D = (
            np.diag(pm.modal_stiffness)[None]
            - (omega**2)[:, None, None] * np.diag(pm.modal_mass)[None]
            + 1j * omega[:, None, None] * f.tip_dashpot(12, scene.pillar.damping)[None]
        )
        eta = np.linalg.solve(D, np.broadcast_to(fj.astype(complex), (len(omega), 12))[..., None])[..., 0]
        exact = f.static_resultants(np.array([0.0]), bp.length, sec.mass_per_length, scene.gondola.mass)[name][1][0]
        modal = eta @ pm.moment_shapes[0] + exact - np.sum(fj * pm.moment_shapes[0] / pm.modal_stiffness)
        assert np.max(np.abs(modal - ref)) <= 1e-3 * np.max(np.abs(ref))
    assert trunc.rows[-1].base_moment < 1e-3


def test_moments_and_shears_need_more_modes_than_the_tip(scene):
    pm = beam_pillar_modes(scene.pillar, scene.gondola.mass, 12, "timoshenko", 40)
    bp = beam_properties(scene.pillar)
    sec = section_of(scene.pillar)
    statics = f.cantilever_tip_statics(
        bp.youngs_modulus,
        bp.second_moment,
        bp.shear_coefficient * bp.shear_modulus * bp.area,
        bp.length,
        sec.mass_per_length,
        scene.gondola.mass,
    )
    trunc = f.force_truncation(
        pm, 186.0, f.tip_dashpot(12, scene.pillar.damping), bp.length, sec.mass_per_length, scene.gondola.mass, statics
    )
    assert trunc.modes_needed_tip < trunc.modes_needed_base_moment
    # the base shear carries the missing modes' mass: more than 12 modes for 1 %
    assert trunc.modes_needed_base_shear is None and trunc.rows[-1].base_shear > 1e-2
    assert trunc.modes_for_forces == trunc.modes_needed_base_moment
    for a, b in zip(trunc.rows, trunc.rows[1:]):  # errors fall as modes are added (to round-off)
        assert b.base_moment <= a.base_moment * 1.5 + 1e-6


def test_axial_force_and_extreme_fibre_stress_worked_numbers():
    """Paper's tube: A = pi/4 (2**2 - 1.96**2) = 0.124407 m**2, I = 0.0609712 m**4,
    m_rho = 8100 A = 1007.70 kg/m; N(0) = g (1007.70 * 20 + 2300 + 1600)
    = 9.80665 * 24054.0 = 235,889 N; with M = 1 MN m at the base,
    sigma = 1e6 * 1.0 / 0.0609712 + 235889 / 0.124407 = 16.4012 + 1.8961 = 18.297 MPa."""
    sec = section_of(load_scene("paper").pillar)
    N0 = f.axial_force(0.0, sec.mass_per_length, 20.0, 2300.0 + 1600.0)
    assert float(N0) == pytest.approx(235889, rel=1e-5)
    assert float(f.extreme_fibre_stress(-1e6, N0, sec)) == pytest.approx(18.297e6, rel=1e-4)


def test_hermite_peak_finds_the_sine_between_samples():
    w = 2 * math.pi
    for n, tol in ((8, 2e-3), (4, 2e-2)):
        t = (np.arange(n + 1) + 0.5) / n  # the crests fall between samples
        peak, when = f.hermite_peak(t, np.sin(w * t), w * np.cos(w * t))
        assert np.max(np.abs(np.sin(w * t))) < 1 - 0.07
        assert peak == pytest.approx(1.0, rel=tol)
        assert abs(math.sin(w * when)) == pytest.approx(1.0, rel=tol)
