"""The foundation's springs: stated, or a circular footing on soil by Gazetas' formulas.

A rigid circular footing of radius R on (or embedded a depth D in) a
homogeneous elastic half-space of shear modulus G and Poisson's ratio nu,
static stiffnesses (the frequency factors of the dynamic impedances are
left out: the tower's modes lie far below the footing's, a0 = omega R / V_s
<< 1):

Surface (D = 0), the rigid disk on the half-space, as Gazetas (1991) Table 1
gives it for a circle (the classical solutions: vertical Boussinesq-Sneddon,
horizontal Bycroft 1956, rocking Borowicka, torsion Reissner-Sagoci)::

    K_V = 4 G R / (1 - nu)          K_H = 8 G R / (2 - nu)
    K_R = 8 G R**3 / (3 (1 - nu))   K_T = 16 G R**3 / 3

Embedded, Gazetas (1991) Table 2, for a prismatic footing whose sidewall is
in contact with the soil over a height d (here d = D, the whole depth),
with B = L = R (the circle's circumscribed square), basemat area
A_b = pi R**2, sidewall area A_w = 2 pi R d, chi = A_b / (4 L**2) = pi / 4
and h = D - d / 2 the depth of the sidewall's centroid::

    K_V,emb = K_V [1 + D/(21 B) (1 + 1.3 chi)] [1 + 0.2 (A_w/A_b)**(2/3)]
    K_H,emb = K_H [1 + 0.15 (D/B)**0.5] [1 + 0.52 (h A_w/(B L**2))**0.4]
    K_R,emb = K_R [1 + 1.26 (d/B) (1 + (d/B) (d/D)**-0.2 (B/L)**0.5)]
    K_T,emb = K_T [1 + 1.4 (1 + B/L) (d/B)**0.9]
    K_HR,emb ~ (1/3) d K_H,emb

These refer to the centre of the footing's base, a depth D below the
ground.  The tube stands on the footing's top at the ground (z = 0, a height
D above that point): the rigid footing carries them there (u_base = u_top -
D theta)::

    K_H' = K_H,   K_HR' = K_HR - D K_H,   K_R' = K_R - 2 D K_HR + D**2 K_H

The rocking factor is Gazetas' for rocking about the long axis; for B = L
his two rocking formulas differ by a few per cent at D/R = 0.5, and for the
circle neither is exact: read the footing's springs to that accuracy.  The
footing is massless here: its inertia would lower the tower's frequencies
a little further.

Reference: G. Gazetas, "Formulas and charts for impedances of surface and
embedded foundations", J. Geotech. Eng. 117(9), 1363-1381, 1991.

Sign convention (rotorpillar.reduced.beam_fe.BaseSprings): the base force
is K_H u + K_HR theta and the base moment K_HR u + K_R theta, theta the
base rotation that moves the tube's upper part the way u goes.

>>> s = footing_stiffness(50e6, 0.3, 10.0, 0.0)
>>> round(s.vertical / 1e9, 4), round(s.horizontal / 1e9, 4), round(s.rocking / 1e11, 4)
(2.8571, 2.3529, 1.9048)
"""

from __future__ import annotations

import math

from ..provenance import Record
from ..scene import Foundation
from .beam_fe import BaseSprings

GAZETAS_1991 = (
    'G. Gazetas, "Formulas and charts for impedances of surface and embedded foundations", '
    "J. Geotech. Eng. 117(9), 1363-1381, 1991: Table 1 (surface; the circle's classical values) "
    "and Table 2 (embedment, sidewall in contact over the whole depth)"
)


class FoundationStiffness(Record):
    """The springs under the tube's base, at the base (z = 0)."""

    kind: str
    """"springs" (stated) or "footing" (Gazetas 1991)"""
    horizontal: float
    """K_H, each horizontal direction (N/m)"""
    rocking: float
    """K_R, about each horizontal axis (N*m/rad)"""
    coupling: float
    """K_HR (N/rad)"""
    vertical: float | None
    """K_V (N/m); None = rigid"""
    torsional: float | None
    """K_T (N*m/rad); None = rigid"""
    source: str
    """where the numbers come from, in words"""

    def base_springs(self) -> BaseSprings:
        """The springs in the beam's plane of bending."""
        return BaseSprings(self.horizontal, self.rocking, self.coupling)


def surface_circle(G: float, nu: float, R: float) -> tuple[float, float, float, float]:
    """(K_V, K_H, K_R, K_T) of a rigid disk on the half-space's surface (N/m, N/m, N*m/rad, N*m/rad)."""
    return 4 * G * R / (1 - nu), 8 * G * R / (2 - nu), 8 * G * R**3 / (3 * (1 - nu)), 16 * G * R**3 / 3


def embedment_factors(R: float, D: float) -> tuple[float, float, float, float]:
    """Gazetas (1991) Table 2's factors on (K_V, K_H, K_R, K_T) for a circle embedded D with
    its sidewall in contact over the whole depth (-); all 1 at D = 0."""
    if D <= 0:
        return 1.0, 1.0, 1.0, 1.0
    B = L = R
    d = D
    area_base, area_wall = math.pi * R**2, 2 * math.pi * R * d
    chi = area_base / (4 * L**2)
    h = D - d / 2
    vertical = (1 + D / (21 * B) * (1 + 1.3 * chi)) * (1 + 0.2 * (area_wall / area_base) ** (2 / 3))
    horizontal = (1 + 0.15 * math.sqrt(D / B)) * (1 + 0.52 * (h * area_wall / (B * L**2)) ** 0.4)
    rocking = 1 + 1.26 * (d / B) * (1 + (d / B) * (d / D) ** -0.2 * math.sqrt(B / L))
    torsion = 1 + 1.4 * (1 + B / L) * (d / B) ** 0.9
    return vertical, horizontal, rocking, torsion


def footing_stiffness(G: float, nu: float, R: float, D: float) -> FoundationStiffness:
    """The springs of a circular footing (Gazetas 1991), carried to the ground surface (z = 0)."""
    kv, kh, kr, kt = surface_circle(G, nu, R)
    fv, fh, fr, ft = embedment_factors(R, D)
    kv, kh, kr, kt = kv * fv, kh * fh, kr * fr, kt * ft
    khr = D * kh / 3  # at the base's centre, a depth D below the tube
    return FoundationStiffness(
        "footing",
        kh,
        kr - 2 * D * khr + D**2 * kh,
        khr - D * kh,
        kv,
        kt,
        f"circular footing R = {R:g} m, embedded D = {D:g} m, on soil G = {G:.4g} Pa, nu = {nu:g}: {GAZETAS_1991}; "
        "carried from the base's centre to the ground by the rigid footing",
    )


def foundation_stiffness(f: Foundation) -> FoundationStiffness | None:
    """The springs of a scene's ``[foundation]``; None when it is clamped."""
    if f.kind == "clamped":
        return None
    if f.kind == "footing":
        assert f.soil_shear_modulus is not None and f.soil_poisson_ratio is not None and f.radius is not None
        return footing_stiffness(f.soil_shear_modulus, f.soil_poisson_ratio, f.radius, f.embedment)
    assert f.horizontal_stiffness is not None and f.rocking_stiffness is not None  # validated
    return FoundationStiffness(
        "springs",
        f.horizontal_stiffness,
        f.rocking_stiffness,
        f.coupling_stiffness,
        f.vertical_stiffness,
        f.torsional_stiffness,
        "stated in [foundation]",
    )


def base_springs(f: Foundation) -> BaseSprings | None:
    """The beam's base springs of a scene's ``[foundation]`` (None: clamped)."""
    s = foundation_stiffness(f)
    return None if s is None else s.base_springs()
