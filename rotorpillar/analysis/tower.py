"""A tower's findings in `analyze`: its first frequencies on a clamp and on its foundation,
the published ones beside ours, and why they differ.

For a pillar of cans, on a flexible foundation, or a scene that states a
``[reference]``: the first bending frequency of

- the beam (Timoshenko, rotorpillar.reduced.beam_fe, 200 elements: its
  discretisation error ~1e-5), the rotor-nacelle assembly a rigid mass on
  top (gondola and rotor), clamped and on the scene's foundation;
- Rayleigh-Ritz (Euler-Bernoulli, an upper bound), the same two ways;
- the headline ROM's first coupled mode in the rotor's plane (X), on the
  chain's model (the rotor on its shaft: its own stiffness counts).

The shift the foundation causes is the clamped beam's frequency against
the beam on the foundation's springs.  The published values (the scene's
``[reference]``) stand beside the ROM's and the clamped beam's, with the
scene's own words for why they differ.

The tool's pillar is symmetric and its rotor-nacelle assembly a point mass
on the axis: fore-aft (Y) and side-side (X) are one frequency here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..provenance import JsonRecord
from ..reduced.foundation import FoundationStiffness, foundation_stiffness
from ..reduced.pillar_modes import beam_pillar_modes
from ..reduced.tower import rayleigh_ritz, tower_mass
from ..scene import Scene

#: the beam's elements for the tower's findings (Timoshenko: error ~ h**2 ~ 1e-5 of omega_1)
BEAM_ELEMENTS = 200


@dataclass(frozen=True)
class FirstFrequency(JsonRecord):
    """One model's first bending frequency, clamped and on the scene's foundation."""

    model: str
    """what it is, in words"""
    clamped: float
    """on a rigid base (Hz)"""
    on_foundation: float | None
    """on the scene's foundation's springs (Hz); None: the scene's foundation is a clamp"""

    @property
    def shift(self) -> float | None:
        """on_foundation / clamped - 1 (-)"""
        return None if self.on_foundation is None else self.on_foundation / self.clamped - 1


@dataclass(frozen=True)
class PublishedRow(JsonRecord):
    """A published frequency beside ours."""

    quantity: str
    """e.g. "first fore-aft tower frequency\""""
    published: float
    """(Hz)"""
    computed: float
    """ours, on the same (clamped) base as the published model's (Hz)"""
    model: str
    """ours: which model"""
    difference: float
    """computed / published - 1 (-)"""


@dataclass(frozen=True)
class TowerFindings(JsonRecord):
    """`analyze`'s block on a tower: frequencies, foundation, published numbers."""

    cans: int
    """segments of the pillar from the base up (1: a uniform tube or one taper) (-)"""
    tower_mass: float
    """the tube's mass (kg)"""
    top_mass: float
    """what the beam carries rigidly on top here: gondola and rotor (kg)"""
    frequencies: tuple[FirstFrequency, ...]
    """the beam's and Rayleigh-Ritz's first bending frequency, clamped and on the foundation"""
    rom_first: float
    """the headline ROM's first coupled mode in the rotor's plane, on the chain's model (Hz)"""
    foundation: FoundationStiffness | None = field(default=None, metadata={"omit_if_none": True})
    """the foundation's springs (None: a clamp)"""
    foundation_shift: float | None = field(default=None, metadata={"omit_if_none": True})
    """the beam's first frequency on the foundation over clamped, less 1 (-)"""
    published: tuple[PublishedRow, ...] = ()
    """the scene's [reference] beside ours"""
    source: str = ""
    """the published numbers' source"""
    note: str = ""
    """why ours and the published differ (the scene's [reference] note)"""
    symmetry: str = ""
    """what the tool's model of the tower cannot tell apart"""


def tower_findings(scene: Scene, rom_first_omega: float, rom_model: str) -> TowerFindings | None:
    """The tower's findings (see the module text); None for the paper's kind of scene
    (a uniform tube on a clamp, no published numbers of its own)."""
    p, f, ref = scene.pillar, scene.foundation, scene.reference
    if p.is_uniform and f.kind == "clamped" and not ref.stated:
        return None
    springs = foundation_stiffness(f)
    base = None if springs is None else springs.base_springs()
    top = scene.gondola.mass + scene.rotor.mass
    hz = 1 / (2 * math.pi)

    def beam(b):
        return float(beam_pillar_modes(p, top, 1, "timoshenko", BEAM_ELEMENTS, 0.0, b).omega[0]) * hz

    def ritz(b):
        return float(rayleigh_ritz(p, top_mass=top, base=b).omega[0]) * hz

    beam_clamped = beam(None)
    rows = (
        FirstFrequency(
            f"beam, Timoshenko, {BEAM_ELEMENTS} elements, gondola and rotor a rigid mass on top",
            beam_clamped,
            None if base is None else beam(base),
        ),
        FirstFrequency(
            "Rayleigh-Ritz, Euler-Bernoulli (an upper bound), gondola and rotor a rigid mass on top",
            ritz(None),
            None if base is None else ritz(base),
        ),
    )
    rom = rom_first_omega * hz
    published = []
    for quantity, value in (
        ("first fore-aft tower frequency", ref.first_fore_aft_frequency),
        ("first side-side tower frequency", ref.first_side_side_frequency),
    ):
        if value is not None:
            if base is None:
                published.append(PublishedRow(quantity, value, rom, f"the headline ROM ({rom_model})", rom / value - 1))
            published.append(
                PublishedRow(quantity, value, beam_clamped, rows[0].model + ", clamped", beam_clamped / value - 1)
            )
    return TowerFindings(
        cans=len(p.segments()),
        tower_mass=tower_mass(p),
        top_mass=top,
        frequencies=rows,
        rom_first=rom,
        foundation=springs,
        foundation_shift=rows[0].shift,
        published=tuple(published),
        source=ref.source,
        note=ref.note,
        symmetry="the tube is axisymmetric and the gondola and rotor sit on its axis: fore-aft (Y) and "
        "side-side (X) bending have one frequency here; the published ones differ through the "
        "assembly's offsets and inertias and the flexible blades",
    )
