"""Typed records of harmonic.json (Bode, Campbell, separation margins) and summary.json (the verdict).

Imports only provenance and the numpy-only records of rotorpillar.reduced
they nest, so the report reads them without the models.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..chain.record import PillarModel
from ..provenance import JsonRecord
from ..reduced.bode import AveragingCurve, BodeCurve
from ..reduced.capacity import Check, MeridionalBuckling
from ..reduced.margins import ModeEntry, SeparationRow
from ..reduced.spatial_records import PlanesChoice
from ..reduced.spatial_response import SpatialResponse


@dataclass(frozen=True)
class PeakComparison(JsonRecord):
    """One resonance's Bode peak on the ROM, on the 3D model and by Eq. 19."""

    omega: float
    """the ROM's omega_i (rad/s)"""
    rom_speed: float | None
    """speed of the ROM's tip peak near omega_i (rad/s); None: no peak (heavily damped)"""
    rom_amplitude: float | None
    """its tip amplitude (m)"""
    fem3d_speed: float | None
    """the 3D curve's peak near omega_i (rad/s), or None"""
    fem3d_amplitude: float | None
    """(m)"""
    averaging_amplitude: float
    """Eq. 19 at omega_i: |f_i| / (2 omega_i**2 nu_i) (m)"""
    amplitude_difference: float | None
    """fem3d / ROM - 1 at the peaks (-)"""


@dataclass(frozen=True)
class HarmonicResult(JsonRecord):
    """What `rotorpillar harmonic` found (harmonic.json)."""

    running_speeds: tuple[float, ...]
    """the stable stationary speeds of the ROM with the scene's drive (rad/s)"""
    running_speed_source: str
    band_top: float
    """the band checked: converge.margin x the highest excitation (rad/s)"""
    rom: BodeCurve
    fem3d: BodeCurve | None
    """the 3D model's harmonic response (None when dolfinx is missing)"""
    averaging: tuple[AveragingCurve, ...]
    peaks: tuple[PeakComparison, ...]
    modes: tuple[ModeEntry, ...]
    """the structural modes in the band: the ROM's coupled system and the 3D loaded tube"""
    separation: tuple[SeparationRow, ...]
    """every running speed against every mode (API 684)"""
    rom_model: str
    """the ROM's pillar modes (source, count)"""
    fem3d_model: str
    """the 3D harmonic response's mesh and dofs, or why there is none"""
    rom_seconds_per_speed: float
    """(s)"""
    fem3d_seconds_per_speed: float | None
    """one real-block assembly, LU and solve (s)"""
    notes: tuple[str, ...]
    pillar_model: PillarModel | None = field(default=None, metadata={"omit_if_none": True})
    """the chain's pillar model the ROM's modes come from (rotorpillar.chain)"""
    spatial: SpatialResponse | None = field(default=None, metadata={"omit_if_none": True})
    """the spatial ROM's unbalance response in every direction: Bode curves, their peaks and
    half-power AFs, the orbits of the shaft, the rotor and the top (issue 26)"""
    planes: PlanesChoice | None = field(default=None, metadata={"omit_if_none": True})
    """modal_model.planes resolved, with its reason"""


@dataclass(frozen=True)
class Headline(JsonRecord):
    """A number a reader came for, with the model and the case it came from."""

    key: str
    """e.g. "loaded_first_frequency\""""
    label: str
    """what it is, in words"""
    value: float | None
    unit: str
    model: str | None
    case: str | None
    source: str
    """the file (and field) it was read from"""
    text: str
    """the sentence the report prints"""
    error: float | None = field(default=None, metadata={"omit_if_none": True})
    """its error bar, in ``unit`` (rotorpillar.chain.Uncertain's error), where one was made"""


@dataclass(frozen=True)
class EngineeringSummary(JsonRecord):
    """summary.json: the verdict first, then the numbers a reader came for."""

    scene: str
    verdict: str
    """"pass" (every assessed check passes), "fail" (one fails) or "incomplete" (none assessed)"""
    checks: tuple[Check, ...]
    """per check, its governing model and case (the largest utilisation)"""
    check_details: tuple[Check, ...]
    """every model and case each check was evaluated on"""
    headlines: tuple[Headline, ...]
    buckling: MeridionalBuckling | None
    """the tube's design buckling stress at the governing demand"""
    not_assessed: tuple[str, ...]
    """the checks without a capacity or a demand, and what to state or run"""
    inputs: tuple[str, ...]
    """the files read"""
