"""The sweep's stationary curve is binned by sums (transients.sweep.binned_statistics):
checked against the per-bin loop it replaced, numpy's mean, max and polyfit bin by bin."""

import numpy as np
import pytest

from rotorpillar.transients.sweep import binned_statistics


def test_binned_statistics_are_the_per_bin_loop():
    """Agreement to 1e-9 relative (the same sums in another order, on deviations about each
    bin's means), on bins with empty, single-sample and two-sample ones (slope 0 there, as
    the loop took it)."""
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0.0, 50.0, 3000))
    w = 3.0 * t + np.sin(t) + rng.normal(0.0, 0.1, t.size)
    peaks = rng.uniform(0.0, 1.0, (3, t.size))
    bins = 400
    idx = np.clip((t / 50.0 * bins).astype(int), 0, bins - 1)
    idx[idx == 7] = 8  # an empty bin
    idx[np.flatnonzero(idx == 20)[1:]] = 21  # a single-sample bin
    idx[np.flatnonzero(idx == 30)[2:]] = 31  # a two-sample bin
    got = binned_statistics(idx, bins, t, w, *peaks)
    for b in range(bins):
        s = idx == b
        if not s.any():
            assert np.isnan(got.omega[b]) and np.isnan(got.tip_x[b])
            continue
        assert got.omega[b] == pytest.approx(w[s].mean(), rel=1e-12)
        slope = np.polyfit(t[s], w[s], 1)[0] if s.sum() > 2 else 0.0
        assert got.acceleration[b] == pytest.approx(slope, rel=1e-9, abs=1e-12)
        for k, name in enumerate(("tip_x", "rotor_y", "rotor_x")):
            assert getattr(got, name)[b] == peaks[k][s].max()
    assert np.isnan(got.omega[7]) and got.acceleration[20] == 0.0 and got.acceleration[30] == 0.0
