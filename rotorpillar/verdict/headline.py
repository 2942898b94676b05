"""What summary.json's parts share: a headline number, and the tube's shell buckling
resistance at its base (EN 1993-1-6, rotorpillar.reduced.capacity.meridional_buckling).

Apart from ``verdict.summary`` so that its parts (``verdict.earthquake3d``) use them
without importing the module that collects them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..records import Record
from ..reduced.capacity import MeridionalBuckling, meridional_buckling
from ..reduced.tower import base_section

if TYPE_CHECKING:
    from ..scene import Scene


class Headline(Record, omit_defaults=True):
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
    error: float | None = None
    """its error bar, in ``unit`` (rotorpillar.chain.Uncertain's error), where one was made"""


def base_buckling(scene: Scene, axial_share: float = 1.0) -> MeridionalBuckling:
    """The design meridional buckling stress of the tube's base section (Pa in its fields):
    the wall's mid-surface radius and thickness there, the pillar's height as the length;
    ``axial_share`` = s_N / (s_N + s_M) of the demand checked (EN 1993-1-6's C_x)."""
    p, mat = scene.pillar, scene.material
    sec = base_section(p)
    r = (sec.outer_diameter + sec.inner_diameter) / 4
    return meridional_buckling(
        p.youngs_modulus, r, sec.wall_thickness, p.height, mat.yield_strength, mat.fabrication_class, axial_share
    )
