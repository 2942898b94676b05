"""The band of frequencies a scene excites, which its models must resolve."""

from __future__ import annotations

from collections.abc import Sequence

from ..provenance import Record
from ..scene import Converge, Drive, Load, Sweep
from .averaging import Characteristic
from .drive import DriveSchedule
from .excitation import GroundMotion


class ExcitationBand(Record):
    """The frequencies the scene excites, and the band a model must resolve
    (``excitation_band``)."""

    free_speed: float
    """the drive's free speed (rad/s)"""
    earthquake_frequency: float
    """the ground motion's highest frequency, converge.earthquake_frequency (rad/s)"""
    margin: float
    """converge.margin (-)"""
    omega_max: float
    """the band's top: margin x the larger (rad/s)"""
    driver: str
    """which sets it: "drive free speed" or "earthquake" """


def excitation_band(drive: Drive, load: Load, converge: Converge) -> ExcitationBand:
    """The frequencies the scene excites, and the band a model must resolve.

    The rotor runs at most at the drive's free speed (Md = Mc, no resonance
    drag: every stationary speed lies below it); the ground motion reaches
    ``converge.earthquake_frequency``.  The band is the larger times
    ``converge.margin``.
    """
    ch = Characteristic(drive.torque_at_zero, drive.slope, load.coefficient)
    free = ch.free_speed()
    cv = converge
    top = max(free, cv.earthquake_frequency)
    return ExcitationBand(
        free_speed=free,
        earthquake_frequency=cv.earthquake_frequency,
        margin=cv.margin,
        omega_max=cv.margin * top,
        driver="drive free speed" if free >= cv.earthquake_frequency else "earthquake",
    )


def forcing_top(drive: Drive, load: Load, sweep: Sweep, case: str, motion: GroundMotion | None) -> float:
    """The highest forcing frequency of a case (rad/s): the fastest rotor speed
    it reaches (the sweep's top torque for "sweep"), and the ground motion's band."""
    d, L = drive, load
    fast = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
    if case == "sweep":
        fast = max(fast, DriveSchedule.constant(sweep.torque_high, d.slope, L.coefficient).free_speed())
    if case == "earthquake" and motion is not None:
        fast = max(fast, motion.band())
    return fast


def cut_count(omega: Sequence[float], edge: float, first: int = 8) -> int:
    """How many of the ascending angular frequencies ``omega`` (rad/s) `modal` keeps for a
    band whose edge is ``edge`` (rad/s): ``first``, doubled while the last one kept lies at
    or below the edge (at most all of them).

    >>> cut_count([10.0] * 8 + [20.0] * 8 + [200.0] * 16, 100.0)
    32
    >>> cut_count([10.0] * 8 + [200.0] * 8, 100.0), cut_count([10.0] * 4, 100.0)
    (16, 4)
    """
    n = first
    while n < len(omega) and omega[n - 1] <= edge:
        n *= 2
    return min(n, len(omega))


def cut_stands(listed: Sequence[float], edge: float, first: int = 8) -> bool:
    """Whether ``listed`` (rad/s, ascending), the lowest modes of a solve cut at some
    band's edge, is also that solve's cut at ``edge``: the doubling stops at its end,
    and its last mode lies past the edge (else the cut would reach past the list).

    >>> cut_stands([10.0] * 8 + [200.0] * 8, 100.0), cut_stands([10.0] * 8 + [200.0] * 8, 5.0)
    (True, False)
    """
    return cut_count(listed, edge, first) >= len(listed) and (not listed or listed[-1] > edge)
