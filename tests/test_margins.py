"""Separation margins per API 684 (rotorpillar.reduced.margins), worked numbers.

- zeta = 0.05: AF = 1 / (2 * 0.05) = 10; SM below = 17 (1 - 1/8.5) = 15.000 %,
  above = 10 + 15 = 25.000 %;
- zeta = 0.02: AF = 25; SM below = 17 (1 - 1/23.5) = 16.2766 %, above 26.2766 %;
- zeta = 0.2: AF = 2.5, the edge: SM = 17 (1 - 1/1) = 0 (continuous there);
- zeta = 0.25: AF = 2 < 2.5: none required;
- undamped: AF infinite: 17 % and 27 %.
A running speed of 89.7 rad/s against a mode at 85.8 rad/s (the paper's
ovalling pair, undamped): actual (89.7 - 85.8) / 89.7 = 4.348 % < 17 %: fail;
against 27.13 rad/s with zeta 0.0779 (AF 6.418): required 17 (1 - 1/4.918)
= 13.543 %, actual 69.75 %: pass.  Exact to round-off: 1e-9 (the hand
values to their printed digits: 1e-4).
"""

import math

import pytest

from rotorpillar.reduced import margins as m


def test_worked_margins():
    assert m.amplification_factor(0.05) == pytest.approx(10.0)
    assert m.required_margin(10.0, below=True) == pytest.approx(0.15, rel=1e-9)
    assert m.required_margin(10.0, below=False) == pytest.approx(0.25, rel=1e-9)
    assert m.required_margin(25.0, below=True) == pytest.approx(0.162766, rel=1e-5)
    assert m.required_margin(25.0, below=False) == pytest.approx(0.262766, rel=1e-5)
    assert m.required_margin(2.5, below=True) == pytest.approx(0.0, abs=1e-12)
    assert m.required_margin(m.amplification_factor(0.25), below=False) == 0.0
    assert m.amplification_factor(0.0) == math.inf
    assert m.required_margin(math.inf, below=True) == pytest.approx(0.17)
    assert m.required_margin(math.inf, below=False) == pytest.approx(0.27)


def test_rows_pass_and_fail():
    ovalling = m.ModeEntry(85.8, 0.0, "ovalling n=2", "fem3d")
    row = m.separation(89.7, ovalling)
    assert (row.position, row.status, row.amplification_factor) == ("below", "fail", None)
    assert row.actual == pytest.approx(0.04348, rel=1e-3)
    bending = m.ModeEntry(27.13, 0.0779, "coupled X 2", "modal")
    row = m.separation(89.7, bending)
    assert row.required == pytest.approx(0.17 * (1 - 1 / (1 / (2 * 0.0779) - 1.5)), rel=1e-9)
    assert row.required == pytest.approx(0.13543, rel=1e-4)
    assert row.status == "pass"
    table = m.separation_table([89.7], [ovalling, bending, m.ModeEntry(400.0, 0.0, "x", "fem3d")], band_top=200.0)
    assert len(table) == 2


def test_af_from_the_response_peak():
    """API 684 as API 684 does it (issue 26): the AF read off the unbalance response's peak; a
    mode the response shows no peak at needs no margin, undamped or not, and the row says so;
    with a peak, the margins are the formulas' of that AF, measured from the peak's speed."""
    ovalling = m.ModeEntry(105.3, 0.0, "ovalling n=2", "fem3d")
    row = m.separation_from_response(89.7, ovalling, None, None, "")
    assert (row.required, row.status, row.amplification_factor) == (0.0, "pass", None)
    assert "no peak" in row.af_source and row.peak_speed is None
    assert row.actual == pytest.approx((105.3 - 89.7) / 89.7, rel=1e-12)
    bending = m.ModeEntry(27.13, 0.0779, "bending in the rotor's plane", "modal")
    row = m.separation_from_response(89.7, bending, 3.95, 26.9, "tip_x")
    assert row.required == pytest.approx(m.required_margin(3.95, below=True), rel=1e-12)
    assert row.actual == pytest.approx((89.7 - 26.9) / 89.7, rel=1e-12)
    assert row.peak_speed == 26.9 and "half-power" in row.af_source
    low = m.separation_from_response(89.7, bending, 2.0, 80.0, "tip_x")  # AF < 2.5: critically damped
    assert low.required == 0.0 and low.status == "pass"
