"""Records of the 3D von Mises recovery (rotorpillar.fem3d.stress); numpy-free, no dolfinx."""

from __future__ import annotations

from ..records import Record


class StressPeak(Record):
    """A peak of the von Mises field: its value, where and when."""

    value: float
    """von Mises stress (Pa)"""
    position: tuple[float, float, float]
    """(x, y, z) of the node (m)"""
    time: float
    """(s)"""
    nominal: float
    """the section's nominal stress at that height and instant, |M| c / I + N / A (Pa)"""
    ratio: float
    """value / nominal (-)"""


class VonMisesSummary(Record):
    """What the von Mises recovery found over the frames and the peak instants."""

    peak: StressPeak
    """the largest anywhere"""
    clamp: StressPeak
    """the largest within the clamp's boundary layer (z <= clamp_zone); ratio: the stress concentration"""
    away_from_clamp: StressPeak
    """the largest above the clamp's boundary layer; ratio: against the beam's nominal stress"""
    clamp_zone: float
    """height of the clamp's boundary layer l_b (m)"""
    instants: int
    """states evaluated: the frames and the peak instants of base moment and shear (-)"""
    gravity: str
    """how self-weight enters"""
    space: str
    """the continuous space the stress was projected on"""
