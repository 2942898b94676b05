"""Capacities of the tube and the checks of a demand against them.

Shell buckling of the tube under meridional compression and bending, by
EN 1993-1-6:2007 (Eurocode 3, part 1-6, strength and stability of shell
structures), Annex D.1.2 with the buckling curve of 8.5.2:

- length parameter            omega = l / sqrt(r t)                          D.1.2.1
- the factor C_x by length:   short (omega <= 1.7): 1.36 - 1.83/omega + 2.07/omega**2,
                              medium (1.7 < omega <= 0.5 r/t): 1,
                              long (omega > 0.5 r/t): C_x,N = 1 + 0.2/C_xb (1 - 2 omega t/r),
                              at least 0.6; under global bending the long cylinder's
                              C_x = C_x,N s_N/s + s_M/s (s_N, s_M the meridional stresses
                              from the axial force and from bending, s their sum)   D.1.2.1
- critical stress             sigma_x,Rcr = 0.605 E C_x t / r                 D.1.2.1
- imperfection amplitude      Delta w_k = sqrt(r t) / Q, Q of the fabrication
                              quality class: A 40, B 25, C 16                D.1.2.2
- elastic imperfection factor alpha_x = 0.62 / (1 + 1.91 (Delta w_k / t)**1.44)  D.1.2.2
- lambda_x0 = 0.20, beta = 0.60, eta = 1.0                                   D.1.2.2
- relative slenderness        lambda_x = sqrt(f_yk / sigma_x,Rcr)            8.5.2
- plastic limit slenderness   lambda_p = sqrt(alpha / (1 - beta))            8.5.2
- buckling reduction chi      1 (lambda <= lambda_0);
                              1 - beta ((lambda - lambda_0)/(lambda_p - lambda_0))**eta
                              (lambda_0 < lambda < lambda_p); alpha / lambda**2 beyond  8.5.2
- sigma_x,Rk = chi f_yk, sigma_x,Rd = sigma_x,Rk / gamma_M1, gamma_M1 = 1.1
  (the recommended value, 8.5.2(2))

r is the wall's mid-surface radius, t the wall, l the length between the
boundaries (the pillar's height).  A cantilever's free top is none of the
boundary cases the code tabulates for C_xb (6 for both ends clamped, 3 for
clamped-pinned, 1 for both pinned): C_xb = 1 is taken, the lowest, so the
long cylinder's C_x,N is not overstated.

The demands the checks compare (transient peaks) are unfactored: the
partial factors on the actions are the designer's to apply.

>>> b = meridional_buckling(2.1e11, 0.99, 0.02, 20.0, 355e6, "C", axial_share=0.1)
>>> round(b.cx, 3), round(b.alpha, 4), round(b.chi, 4), round(b.design_stress / 1e6, 1)
(0.96, 0.3911, 0.8634, 278.6)
"""

from __future__ import annotations

import math

from ..provenance import Record

#: the fabrication quality classes of EN 1993-1-6 (D.1.2.2): Q, meridional compression
QUALITY_PARAMETER = {"A": 40.0, "B": 25.0, "C": 16.0}
QUALITY_CLASSES = tuple(QUALITY_PARAMETER)
#: EN 1993-1-6 8.5.2(2): the recommended partial factor for shell buckling
GAMMA_M1 = 1.1
#: EN 1993-1-1 6.1(1): the recommended partial factor for cross-section resistance (yield)
GAMMA_M0 = 1.0
#: D.1.2.2 (3): the meridional buckling curve's squash limit, plastic range and interaction exponent
LAMBDA_X0, BETA_X, ETA_X = 0.20, 0.60, 1.0
#: the boundary parameter C_xb taken for a cantilever's free top (the lowest tabulated)
CXB_CANTILEVER = 1.0


def length_parameter(length: float, radius: float, thickness: float) -> float:
    """EN 1993-1-6 D.1.2.1: omega = l / sqrt(r t) (-)."""
    return length / math.sqrt(radius * thickness)


def cx_factor(
    omega: float, radius: float, thickness: float, cxb: float = CXB_CANTILEVER, axial_share: float = 1.0
) -> float:
    """EN 1993-1-6 D.1.2.1: C_x of a short, medium or long cylinder (-).

    ``axial_share`` = s_N / (s_N + s_M): the share of the meridional stress
    that comes from the axial force (1: uniform compression); it matters
    only for a long cylinder, where global bending raises C_x toward 1.
    """
    if omega <= 1.7:
        return 1.36 - 1.83 / omega + 2.07 / omega**2
    if omega <= 0.5 * radius / thickness:
        return 1.0
    cxn = max(1.0 + 0.2 / cxb * (1.0 - 2.0 * omega * thickness / radius), 0.6)
    share = min(max(axial_share, 0.0), 1.0)
    return cxn * share + (1.0 - share)


def critical_meridional_stress(youngs_modulus: float, radius: float, thickness: float, cx: float = 1.0) -> float:
    """EN 1993-1-6 D.1.2.1: sigma_x,Rcr = 0.605 E C_x t / r (Pa), the classical
    critical stress of a cylinder under axial compression (nu = 0.3) times C_x."""
    return 0.605 * youngs_modulus * cx * thickness / radius


def imperfection_reduction(radius: float, thickness: float, quality_class: str) -> float:
    """EN 1993-1-6 D.1.2.2: alpha_x = 0.62 / (1 + 1.91 (Delta w_k / t)**1.44),
    Delta w_k = sqrt(r t) / Q (-)."""
    q = QUALITY_PARAMETER[quality_class]
    dwk = math.sqrt(radius * thickness) / q
    return 0.62 / (1.0 + 1.91 * (dwk / thickness) ** 1.44)  # type: ignore[no-any-return]  # float ** float is Any in typeshed (a negative base gives a complex)


def buckling_reduction(
    slenderness: float, alpha: float, lambda0: float = LAMBDA_X0, beta: float = BETA_X, eta: float = ETA_X
) -> float:
    """EN 1993-1-6 8.5.2: chi from the relative slenderness (-)."""
    lam_p = math.sqrt(alpha / (1.0 - beta))
    if slenderness <= lambda0:
        return 1.0
    if slenderness < lam_p:
        return 1.0 - beta * ((slenderness - lambda0) / (lam_p - lambda0)) ** eta  # type: ignore[no-any-return]  # as above
    return alpha / slenderness**2


class MeridionalBuckling(Record):
    """The tube's design buckling stress under meridional compression and bending."""

    quality_class: str
    """fabrication quality class, "A", "B" or "C" (EN 1993-1-6 Table 8.1)"""
    radius: float
    """r, the mid-surface radius (m)"""
    thickness: float
    """t (m)"""
    length: float
    """l (m)"""
    omega: float
    """length parameter l / sqrt(r t) (-)"""
    length_class: str
    """"short", "medium" or "long" (D.1.2.1)"""
    cx: float
    """C_x (-)"""
    critical_stress: float
    """sigma_x,Rcr (Pa)"""
    alpha: float
    """alpha_x (-)"""
    slenderness: float
    """lambda_x (-)"""
    plastic_slenderness: float
    """lambda_p (-)"""
    chi: float
    """chi_x (-)"""
    characteristic_stress: float
    """sigma_x,Rk = chi f_yk (Pa)"""
    design_stress: float
    """sigma_x,Rd = sigma_x,Rk / gamma_M1 (Pa)"""
    gamma_m1: float
    """gamma_M1 (-)"""
    yield_strength: float
    """f_yk (Pa)"""
    clause: str
    """where the method is: "EN 1993-1-6:2007 Annex D.1.2, 8.5.2\""""


def meridional_buckling(
    youngs_modulus: float,
    radius: float,
    thickness: float,
    length: float,
    yield_strength: float,
    quality_class: str,
    axial_share: float = 1.0,
    cxb: float = CXB_CANTILEVER,
    gamma_m1: float = GAMMA_M1,
) -> MeridionalBuckling:
    """EN 1993-1-6 D.1.2, 8.5.2: the design meridional buckling stress of the tube (Pa).

    ``axial_share`` as in ``cx_factor``: s_N / (s_N + s_M) of the demand
    checked (bending-dominated demands raise a long cylinder's C_x).
    """
    if quality_class not in QUALITY_PARAMETER:
        raise ValueError(f"quality class must be one of {', '.join(QUALITY_CLASSES)}")
    om = length_parameter(length, radius, thickness)
    kind = "short" if om <= 1.7 else "medium" if om <= 0.5 * radius / thickness else "long"
    cx = cx_factor(om, radius, thickness, cxb, axial_share)
    s_cr = critical_meridional_stress(youngs_modulus, radius, thickness, cx)
    alpha = imperfection_reduction(radius, thickness, quality_class)
    lam = math.sqrt(yield_strength / s_cr)
    chi = buckling_reduction(lam, alpha)
    rk = chi * yield_strength
    return MeridionalBuckling(
        quality_class,
        radius,
        thickness,
        length,
        om,
        kind,
        cx,
        s_cr,
        alpha,
        lam,
        math.sqrt(alpha / (1.0 - BETA_X)),
        chi,
        rk,
        rk / gamma_m1,
        gamma_m1,
        yield_strength,
        "EN 1993-1-6:2007 Annex D.1.2, 8.5.2",
    )


# --------------------------------------------------------------------------
# Checks


PASS, FAIL, NOT_ASSESSED = "pass", "fail", "not assessed"


class Check(Record):
    """One demand against one capacity."""

    name: str
    """what is checked, e.g. "base stress vs yield\""""
    quantity: str
    """the demand's name, e.g. "base_stress\""""
    unit: str
    """of demand and capacity, e.g. "Pa\""""
    demand: float | None
    """the largest value the model gave in the case (None: not computed)"""
    capacity: float | None
    """what is allowed (None: not stated, so not assessed)"""
    utilisation: float | None
    """demand / capacity (-)"""
    status: str
    """"pass", "fail" or "not assessed\""""
    model: str | None
    """the model the demand came from, e.g. "modal" (ROM) or "fem3d\""""
    case: str | None
    """the case, e.g. "earthquake\""""
    source: str
    """where demand and capacity come from, in words"""


def check(
    name: str,
    quantity: str,
    unit: str,
    demand: float | None,
    capacity: float | None,
    model: str | None,
    case: str | None,
    source: str,
) -> Check:
    """A check: passes when demand <= capacity; not assessed without a capacity or a demand.

    >>> check("x", "q", "m", 2.0, 4.0, "modal", "runup", "").status
    'pass'
    >>> check("x", "q", "m", 2.0, None, "modal", "runup", "").status
    'not assessed'
    """
    if demand is None or capacity is None or not (math.isfinite(demand) and capacity > 0):
        return Check(name, quantity, unit, demand, capacity, None, NOT_ASSESSED, model, case, source)
    u = demand / capacity
    return Check(
        name, quantity, unit, float(demand), float(capacity), float(u), PASS if u <= 1.0 else FAIL, model, case, source
    )
