"""What the excitation side's functions return: the ground motion's sizes and its spectrum.

``GroundMotion.sizes()`` (rotorpillar.reduced.excitation) states how big a motion is;
its keys depend on the motion's kind, so each kind has its own record
(``NoMotionSizes``, ``PulseSizes``, ``RecordSizes``; ``ExcitationSizes`` is any of
them) and ``excitation_sizes_from_json`` reads one back by its ``kind``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..provenance import JsonRecord


@dataclass(frozen=True)
class NoMotionSizes(JsonRecord):
    """No ground motion."""

    kind: str = "none"
    """"none\""""


@dataclass(frozen=True)
class PulseSizes(JsonRecord):
    """The sizes of the paper's harmonic pulse q5 = A (cos(omega t) - 1) on its window."""

    kind: str
    """"pulse\""""
    law: str
    """the pulse's law, in words"""
    amplitude: float
    """A (m)"""
    frequency: float
    """omega (rad/s)"""
    start: float
    """start of the window (s)"""
    end: float
    """end of the window (s)"""
    displacement_step_at_start: float
    """the ground's jump at the window's start, A (cos(omega start) - 1) (m)"""
    peak_displacement: float
    """largest |q5| (m)"""
    peak_velocity: float
    """A omega (m/s)"""
    peak_acceleration: float
    """A omega**2 (m/s**2)"""
    peak_acceleration_g: float
    """the peak acceleration in standard gravities (g)"""
    inertial_final_displacement: float
    """the ground displacement at the window's end whose second derivative is the
    applied acceleration (what the modal model's ground does) (m)"""
    realistic: bool
    """False: the pulse is no realistic earthquake"""
    statement: str
    """why, in words"""


@dataclass(frozen=True)
class RecordSizes(JsonRecord):
    """The sizes of an accelerogram on its uniform grid."""

    kind: str
    """"record\""""
    name: str
    """the record's name (a built-in's, or the file's stem)"""
    source: str
    """where it comes from"""
    time_step: float
    """uniform sampling step (s)"""
    start: float
    """time of the first sample (s)"""
    end: float
    """time of the last sample (s)"""
    samples: int
    """samples on the uniform grid (-)"""
    peak_acceleration: float
    """PGA (m/s**2)"""
    peak_acceleration_g: float
    """PGA in standard gravities (g)"""
    peak_velocity: float
    """PGV (m/s)"""
    peak_displacement: float
    """PGD (m)"""
    band: float
    """angular frequency below which 99 % of the record's Fourier energy lies (rad/s)"""
    realistic: bool
    """the sizes lie within those of recorded earthquakes"""
    statement: str | None = field(default=None, metadata={"omit_if_none": True})
    """why the record is not realistic (absent when it is)"""


#: The sizes of any ground motion (its ``kind`` says which).
ExcitationSizes = NoMotionSizes | PulseSizes | RecordSizes

_BY_KIND: dict[str, type[NoMotionSizes] | type[PulseSizes] | type[RecordSizes]] = {
    "none": NoMotionSizes,
    "pulse": PulseSizes,
    "record": RecordSizes,
}


def excitation_sizes_from_json(doc: dict[str, Any]) -> ExcitationSizes:
    """The sizes record of ``doc`` (as ``to_json`` wrote it), chosen by its ``kind``."""
    kind = doc["kind"]
    if kind not in _BY_KIND:
        raise ValueError(f"excitation.kind = {kind!r}: must be one of {', '.join(_BY_KIND)}")
    sizes: ExcitationSizes = _BY_KIND[kind].from_json(doc)
    return sizes


@dataclass(frozen=True, eq=False)
class SpectralOrdinates(JsonRecord):
    """Response-spectrum ordinates of a ground motion at given periods (eqsig)."""

    periods: NDArray[np.float64]
    """the oscillators' periods (s)"""
    damping: float
    """their damping ratio (-)"""
    s_a: NDArray[np.float64]
    """pseudo-acceleration at each period (m/s**2)"""
    s_d: NDArray[np.float64]
    """relative displacement at each period (m)"""

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> SpectralOrdinates:
        return cls(
            periods=np.asarray(doc["periods"], dtype=float),
            damping=float(doc["damping"]),
            s_a=np.asarray(doc["s_a"], dtype=float),
            s_d=np.asarray(doc["s_d"], dtype=float),
        )
