"""The response spectrum (reduced.excitation.pseudo_spectra) against eqsig, whose
Nigam-Jennings step it keeps and whose time loop it replaces, and against a closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorpillar.reduced.excitation import pseudo_spectra


def _elcentro():
    from rotorpillar.scene import load_scene, override
    from rotorpillar.transients.cases import scene_motion

    scene = override(
        load_scene("paper"), ["excitation.kind=record", "excitation.record=elcentro", "excitation.start=1"]
    )
    motion = scene_motion(scene)
    return motion.acceleration.copy(), motion.time_step


@pytest.mark.parametrize("damping", [0.0, 0.02, 0.05, 0.3])
def test_the_spectrum_is_eqsigs_on_el_centro(damping):
    eqsig = pytest.importorskip("eqsig")
    acc, dt = _elcentro()
    # T = 0 (eqsig's zero row), short periods (T < 6 dt: the record's peak) and periods that
    # make eqsig resample the record (T / 20 < dt), up to 10 s
    periods = np.array([0.0, 0.02, 0.05, 0.1, 0.3, 1.0, 2.5, 10.0])
    sig = eqsig.AccSignal(acc, dt)
    sig.generate_response_spectrum(response_times=periods, xi=damping)
    s_a, s_d = pseudo_spectra(acc, dt, periods, damping)
    # Same step matrices, summed in another order: the recursion's poles lie within
    # omega dt of 1 (6e-3 at 10 s), so round-off grows by about 1/(omega dt)**2 ~ 3e4 over
    # eps; measured 1.2e-11 at most.  1e-9 keeps a margin and still fails on any wrong term.
    np.testing.assert_allclose(s_d, sig.s_d, rtol=1e-9, atol=0.0)
    np.testing.assert_allclose(s_a, sig.s_a, rtol=1e-9, atol=0.0)


def test_a_step_of_ground_acceleration_doubles_the_static_deflection():
    """An undamped oscillator from rest under a sudden constant base acceleration a swings
    between 0 and 2 a / omega**2 (the dynamic load factor of a step is 2)."""
    a, dt, period = 3.0, 0.001, 0.5
    acc = np.full(4001, a)  # 4 s: eight periods, so the first peak (T/2) is inside
    s_a, s_d = pseudo_spectra(acc, dt, np.array([period]), 0.0)
    omega = 2 * math.pi / period
    # the step is exact for a piecewise-linear record; the peak falls between samples at
    # most dt/2 from t = T/2, where the swing's curvature costs (omega dt / 2)**2 / 2 ~ 2e-5
    assert s_d[0] == pytest.approx(2 * a / omega**2, rel=5e-5)
    assert s_a[0] == pytest.approx(omega**2 * s_d[0], rel=1e-12)
