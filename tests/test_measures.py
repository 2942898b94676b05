"""Errors that measure the model (rotorpillar.transients.compare).

References: closed forms and an inequality that holds for any two signals.
- The running peak is a max over a window, so |env(x) - env(y)| <= max |x - y|
  over the window, and both errors share the reference's peak as their scale:
  the envelope error never exceeds the history error (random signals).
- A whirl that lags by phi has history error 2 sin(phi / 2) against itself
  (closed form) and an envelope error of zero once the window holds a period;
  the lead is the envelope when the rotor angles drift by 0.1 rad or more,
  the history otherwise.
"""

import math

import numpy as np
import pytest

from rotorpillar.transients.compare import PHASE_LOCKED, compare_series, running_peak


def test_envelope_error_never_exceeds_history_error():
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 20.0, 4001)
    for _ in range(20):
        x_ref = np.cumsum(rng.normal(size=t.size)) * 1e-3
        x = x_ref + rng.normal(scale=2e-3, size=t.size)
        m = compare_series(t, x, t, x_ref, window=rng.uniform(0.1, 3.0))
        assert m.envelope_error <= m.history_error + 1e-15


@pytest.mark.parametrize("phi", [0.05, 0.3, 1.0])
def test_a_lagging_whirl_reads_as_phase_not_amplitude(phi):
    t = np.linspace(0.0, 30.0, 30001)
    w = 2.0 * math.pi
    m = compare_series(t, np.cos(w * t - phi), t, np.cos(w * t), window=1.0, theta=w * t - phi, theta_ref=w * t)
    assert m.history_error == pytest.approx(2 * math.sin(phi / 2), rel=1e-3)  # sampling: 1e-3
    assert m.envelope_error < 1e-3
    assert m.angle_drift == pytest.approx(phi)
    assert m.lead == ("envelope" if phi >= PHASE_LOCKED else "history")


def test_running_peak_of_a_sine_is_its_amplitude_inside():
    t = np.linspace(0.0, 10.0, 10001)
    env = running_peak(t, 3.0 * np.sin(2 * math.pi * t), 1.0)
    inner = (t > 0.5) & (t < 9.5)
    assert np.allclose(env[inner], 3.0, rtol=1e-4)
