"""Shell buckling resistance (EN 1993-1-6) and the checks (rotorpillar.reduced.capacity).

Worked by hand (EN 1993-1-6:2007 D.1.2 and 8.5.2) for the paper's tube:
r = (1.00 + 0.98) / 2 = 0.99 m mid-surface, t = 0.02 m, l = 20 m, E = 2.1e11 Pa,
f_yk = 355e6 Pa (S355), quality class C (Q = 16):

  sqrt(r t)      = sqrt(0.0198)                      = 0.140712 m
  omega          = 20 / 0.140712                     = 142.134   > 0.5 r/t = 24.75: long
  C_x,N          = 1 + 0.2/1 (1 - 2 * 142.134 * 0.02 / 0.99) = 0.05144 -> 0.6 (floor)
  C_x (s_N/s = 0.1) = 0.6 * 0.1 + 0.9                = 0.96
  sigma_x,Rcr    = 0.605 * 2.1e11 * 0.96 * 0.02/0.99 = 2.46400e9 Pa
  lambda_x       = sqrt(355e6 / 2.46400e9)           = 0.379572
  Delta w_k / t  = (0.140712 / 16) / 0.02            = 0.439726;  0.439726**1.44 = 0.306325
  alpha_x        = 0.62 / (1 + 1.91 * 0.306325)     = 0.62 / 1.585081 = 0.391147
  lambda_p       = sqrt(0.391147 / 0.4)              = 0.988872
  chi            = 1 - 0.6 (0.379572 - 0.2)/(0.988872 - 0.2) = 0.863421
  sigma_x,Rk     = 0.863421 * 355e6                  = 306.515e6 Pa
  sigma_x,Rd     = 306.515e6 / 1.1                   = 278.650e6 Pa
The hand values carry 6 digits: 1e-5.

The short cylinder's C_x and the elastic branch of chi are checked against
their formulas at one point each (a different code path), the classes'
order (A the strongest) and the checks' statuses without a capacity.
"""

import math

import pytest

from rotorpillar.reduced import capacity as c


def test_paper_tube_worked_example():
    b = c.meridional_buckling(2.1e11, 0.99, 0.02, 20.0, 355e6, "C", axial_share=0.1)
    assert b.omega == pytest.approx(142.134, rel=1e-5)
    assert b.length_class == "long"
    assert b.cx == pytest.approx(0.96, rel=1e-12)
    assert b.critical_stress == pytest.approx(2.46400e9, rel=1e-5)
    assert b.slenderness == pytest.approx(0.379572, rel=1e-5)
    assert b.alpha == pytest.approx(0.391147, rel=1e-5)
    assert b.plastic_slenderness == pytest.approx(0.988872, rel=1e-5)
    assert b.chi == pytest.approx(0.863421, rel=1e-5)
    assert b.characteristic_stress == pytest.approx(306.515e6, rel=1e-5)
    assert b.design_stress == pytest.approx(278.650e6, rel=1e-5)


def test_length_classes_and_branches():
    # short: omega = 1 -> C_x = 1.36 - 1.83 + 2.07 = 1.60
    assert c.cx_factor(1.0, 1.0, 0.01) == pytest.approx(1.60, rel=1e-12)
    # medium: 1.7 < omega <= 0.5 r/t
    assert c.cx_factor(10.0, 1.0, 0.01) == 1.0
    # long under uniform compression: the floor 0.6 or the formula above it
    assert c.cx_factor(60.0, 1.0, 0.01) == pytest.approx(max(1 + 0.2 * (1 - 2 * 60 * 0.01), 0.6))
    # elastic branch: lambda beyond lambda_p -> chi = alpha / lambda**2
    assert c.buckling_reduction(2.0, 0.3) == pytest.approx(0.3 / 4)
    assert c.buckling_reduction(0.1, 0.3) == 1.0
    # a better fabrication class resists more
    r = [c.meridional_buckling(2.1e11, 2.0, 0.005, 10.0, 355e6, q).design_stress for q in "ABC"]
    assert r[0] > r[1] > r[2]


def test_checks_statuses():
    assert c.check("stress", "s", "Pa", 1.0e8, 3.55e8, "modal", "earthquake", "").utilisation == pytest.approx(
        1e8 / 3.55e8
    )
    assert c.check("stress", "s", "Pa", 4.0e8, 3.55e8, "modal", "earthquake", "").status == c.FAIL
    assert c.check("clearance", "d", "m", 0.02, None, "modal", "earthquake", "").status == c.NOT_ASSESSED
    assert c.check("clearance", "d", "m", None, 0.01, None, None, "").status == c.NOT_ASSESSED
    assert c.check("x", "d", "m", math.nan, 0.01, None, None, "").status == c.NOT_ASSESSED
