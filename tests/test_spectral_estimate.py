"""The response-spectrum estimate (rotorpillar.reduced.spectral) against closed forms.

References:
- a two-storey shear frame (equal masses m, equal storey stiffnesses k) has
  omega**2 = (k/m)(3 -+ sqrt 5)/2 and the shapes (1, phi), (1, -1/phi) with
  phi = (1 + sqrt 5)/2 (Chopra, *Dynamics of Structures*, 4th ed., Example 10.5
  in other numbers; the characteristic equation is two lines of algebra);
  Rayleigh damping C = a M + b K keeps the modes and gives
  zeta_i = a / (2 omega_i) + b omega_i / 2 exactly;
- the top's participation p_i = (top . u_i)(u_i . M 1)/(u_i . M u_i) from
  those shapes, SRSS by hand.
The spectrum is a closed-form function of (T, zeta), so nothing but the modes
is computed by the code under test.  Tolerance 1e-10: a 2 x 2 symmetric
eigenproblem in double precision.

On the rotor-pillar ROM, the estimate's modes are the coupled modes the
report's tables show (quasi_normal: the same undamped eigenproblem), at the
same damping (the modal damping's diagonal), to round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorpillar.reduced.spectral import spectral_terms, srss

#: double-precision round-off on a 2 x 2 eigenproblem (-)
ROUND_OFF = 1e-10
PHI = (1 + math.sqrt(5)) / 2


def spectrum(T: float, zeta: float) -> float:
    """A smooth made-up displacement spectrum (m): rising with the period, falling with damping."""
    return 0.02 * T / math.sqrt(zeta / 0.05)


def test_a_shear_frame_against_its_closed_form():
    m, k, a, b = 2.0e3, 8.0e5, 0.3, 2.0e-3
    M = m * np.eye(2)
    K = k * np.array([[2.0, -1.0], [-1.0, 1.0]])
    C = a * M + b * K
    top = np.array([0.0, 1.0])
    terms = spectral_terms(M, K, C, -M @ np.ones(2), top, spectrum)

    omega = [math.sqrt(k / m * (3 - math.sqrt(5)) / 2), math.sqrt(k / m * (3 + math.sqrt(5)) / 2)]
    shapes = [np.array([1.0, PHI]), np.array([1.0, -1 / PHI])]
    p = [float(top @ u) * float(u @ M @ np.ones(2)) / float(u @ M @ u) for u in shapes]
    zeta = [a / (2 * w) + b * w / 2 for w in omega]
    peaks = [abs(p[i]) * spectrum(2 * math.pi / omega[i], zeta[i]) for i in range(2)]

    assert [t.omega for t in terms] == pytest.approx(omega, rel=ROUND_OFF)
    assert [t.damping_ratio for t in terms] == pytest.approx(zeta, rel=ROUND_OFF)
    assert [t.participation for t in terms] == pytest.approx(p, rel=ROUND_OFF)
    assert sum(t.participation for t in terms) == pytest.approx(1.0, rel=ROUND_OFF)  # top . r, r = (1, 1)
    assert [t.contribution for t in terms] == pytest.approx(peaks, rel=ROUND_OFF)
    assert srss(terms) == pytest.approx(math.hypot(*peaks), rel=ROUND_OFF)


def test_one_oscillator_peaks_at_its_spectral_displacement():
    m, k, zeta = 3.0, 12.0, 0.07
    c = 2 * zeta * math.sqrt(k * m)
    (t,) = spectral_terms(np.array([[m]]), np.array([[k]]), np.array([[c]]), np.array([-m]), np.ones(1), spectrum)
    assert t.damping_ratio == pytest.approx(zeta, rel=ROUND_OFF)
    assert srss([t]) == pytest.approx(spectrum(2 * math.pi / 2.0, zeta), rel=ROUND_OFF)


@pytest.fixture(scope="module")
def rom():
    from rotorpillar.reduced.models import build_model, scene_motion
    from rotorpillar.scene.files import load_scene

    scene = load_scene("paper", ["excitation.kind=record", "excitation.record=elcentro", "modal_model.source=beam"])
    model, _ = build_model(scene, "modal", 150.0)
    return model, scene_motion(scene)


def test_the_rom_estimate_takes_the_coupled_modes_at_their_damping(rom):
    """The modes of the estimate are the X modes of quasi_normal (the tables' coupled modes),
    the rotor's mode among them; their damping is quasi_normal's two_n / (2 omega)."""
    from rotorpillar.transients.cases import spectral_estimate

    model, motion = rom
    est = spectral_estimate(model, motion)
    coupled = [r for r in model.quasi_normal() if r.direction == "X"]
    assert len(est.modes) == model.nx == len(coupled)
    assert [2 * math.pi / m.period for m in est.modes] == pytest.approx([r.omega for r in coupled], rel=ROUND_OFF)
    assert [m.damping_ratio for m in est.modes] == pytest.approx(
        [r.two_n / (2 * r.omega) for r in coupled], rel=ROUND_OFF
    )
    # the pillar's own modes, the rotor apart, are the uncoupled estimate: Gamma_j S_d(T_j, zeta_j)
    from rotorpillar.reduced.excitation import response_spectrum

    pm = model.pillar_modes
    alone = []
    for j in range(pm.count):
        zeta = model.damping[j, j] / (2 * pm.modal_mass[j] * pm.omega[j])
        sd = response_spectrum(motion, [2 * math.pi / pm.omega[j]], damping=zeta).s_d[0]
        alone.append(abs(pm.participation[j] / pm.modal_mass[j]) * sd)
    assert est.pillar_modes_only == pytest.approx(math.sqrt(sum(x * x for x in alone)), rel=ROUND_OFF)
