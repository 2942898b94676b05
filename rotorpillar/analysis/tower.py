"""A tower's findings in `analyze`: its first frequencies on a clamp and on its foundation,
the published ones beside ours, and why they differ.

For a pillar of cans, on a flexible foundation, or a scene that states a
``[reference]``: the first bending frequency of

- the beam (Timoshenko, 200 elements: its discretisation error ~1e-5) in
  each plane (rotorpillar.reduced.spatial_beam), the rotor-nacelle assembly
  one rigid body on top: the gondola and the rotor welded on, their masses
  at their heights above the top, the rotor's diametral inertia and the
  gondola's pitch inertia in fore-aft bending (Y, about x), the gondola's
  roll inertia in side-side bending (X, about the spin axis y: the rotor
  spins freely about that axis, its polar inertia is not dragged along);
  clamped and on the scene's foundation;
- Rayleigh-Ritz (Euler-Bernoulli, an upper bound), the assembly a point
  mass, the same two ways;
- the headline ROM's first coupled mode in the rotor's plane (X), on the
  chain's model (the rotor on its shaft: its own stiffness counts).

The shift the foundation causes is the clamped beam's frequency against
the beam on the foundation's springs.  The published values (the scene's
``[reference]``) stand beside the ROM's and the clamped beam's, with the
scene's own words for why they differ.

The assembly's horizontal offsets (the rotor's overhang, the nacelle's
centre downwind) are not modelled: the tube is axisymmetric and every body
sits on its axis.
"""

from __future__ import annotations

import math

from ..records import Record
from ..reduced.foundation import FoundationStiffness, foundation_stiffness
from ..reduced.spatial_beam import beam_spatial_modes
from ..reduced.spatial_modes import BENDING_ACROSS, BENDING_IN_PLANE
from ..reduced.tower import rayleigh_ritz, tower_mass
from ..scene import Gondola, Scene

#: the beam's elements for the tower's findings (Timoshenko: error ~ h**2 ~ 1e-5 of omega_1)
BEAM_ELEMENTS = 200


class FirstFrequency(Record):
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


class PublishedRow(Record):
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


class TowerFindings(Record):
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
    foundation: FoundationStiffness | None = None
    """the foundation's springs (None: a clamp)"""
    foundation_shift: float | None = None
    """the beam's first frequency on the foundation over clamped, less 1 (-)"""
    published: tuple[PublishedRow, ...] = ()
    """the scene's [reference] beside ours"""
    source: str = ""
    """the published numbers' source"""
    note: str = ""
    """why ours and the published differ (the scene's [reference] note)"""
    symmetry: str = ""
    """what the tool's model of the tower cannot tell apart"""


def rigid_assembly(scene: Scene) -> Gondola:
    """The gondola and the rotor welded into one rigid body on the top: their masses at their
    heights, the pitch inertia (about x, fore-aft bending) the gondola's and the rotor's
    diametral one, the roll inertia (about the spin axis y, side-side) the gondola's alone
    (the rotor spins freely about it), each with the parallel-axis terms to the common centre."""
    g, r = scene.gondola, scene.rotor
    m = g.mass + r.mass
    h = (g.mass * g.height + r.mass * r.height) / m
    shift = g.mass * (g.height - h) ** 2 + r.mass * (r.height - h) ** 2
    diametral = r.diametral_inertia if r.diametral_inertia is not None else r.inertia / 2
    return Gondola(
        mass=m,
        pitch_inertia=g.pitch_inertia + diametral + shift,
        roll_inertia=g.roll_inertia + shift,
        yaw_inertia=g.yaw_inertia + diametral,
        height=h,
    )


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

    body = rigid_assembly(scene)

    def beam(stiffness, kind: str) -> float:
        m = beam_spatial_modes(p, body, 2, "timoshenko", BEAM_ELEMENTS, foundation=stiffness)
        return float(next(w for w, k in zip(m.omega, m.kind) if k == kind)) * hz

    def ritz(b):
        return float(rayleigh_ritz(p, top_mass=top, base=b).omega[0]) * hz

    fa, ss = (beam(None, k) for k in (BENDING_ACROSS, BENDING_IN_PLANE))
    what = f"beam, Timoshenko, {BEAM_ELEMENTS} elements, gondola and rotor one rigid body on top"
    rows = (
        FirstFrequency(f"{what}: fore-aft (Y)", fa, None if base is None else beam(springs, BENDING_ACROSS)),
        FirstFrequency(f"{what}: side-side (X)", ss, None if base is None else beam(springs, BENDING_IN_PLANE)),
        FirstFrequency(
            "Rayleigh-Ritz, Euler-Bernoulli (an upper bound), gondola and rotor a point mass on top",
            ritz(None),
            None if base is None else ritz(base),
        ),
    )
    rom = rom_first_omega * hz
    published = []
    for quantity, value, ours, row in (
        ("first fore-aft tower frequency", ref.first_fore_aft_frequency, fa, rows[0]),
        ("first side-side tower frequency", ref.first_side_side_frequency, ss, rows[1]),
    ):
        if value is not None:
            if base is None and row is rows[1]:
                published.append(PublishedRow(quantity, value, rom, f"the headline ROM ({rom_model})", rom / value - 1))
            published.append(PublishedRow(quantity, value, ours, row.model + ", clamped", ours / value - 1))
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
        symmetry="the tube is axisymmetric and the gondola and rotor sit on its axis (their heights and "
        "rotary inertias counted, their horizontal offsets not): fore-aft and side-side differ here by "
        "the assembly's rotary inertia about each axis only",
    )
