"""The tower's shape and its footing: the cans of a tapered or stepped tube, the foundation.

A pillar is either today's uniform tube (``[pillar]`` ``height``,
``outer_diameter``, ``inner_diameter``) or a stack of cans from the base up
(``[[pillar.cans]]``), each a conical steel shell whose outer diameter and
wall vary linearly from its bottom to its top: a linear taper is one can, a
stepped tube several cylindrical ones.  Either way :func:`segments` gives
the tube as :class:`Segment` s, the one description every model reads
(section properties: rotorpillar.reduced.tower; meshes: rotorpillar.mesh).

The ``[foundation]`` is the ground the tube stands on: clamped (rigid, the
default), springs at the tube's base, or a circular footing on soil whose
springs come from Gazetas' formulas (rotorpillar.reduced.foundation).

>>> c = Can(height=10.0, outer_diameter_bottom=4.0, outer_diameter_top=3.0, wall_thickness=0.03)
>>> s = segments_of_cans((c,))[0]
>>> s.outer_diameter(5.0), round(s.inner_diameter(5.0), 3)
(3.5, 3.44)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .fields import SceneError, param


@dataclass(frozen=True)
class Can:
    """One can of the tower: a conical steel shell, its outer diameter and wall linear in height."""

    height: float = param("Height of the can (m)", gt=0, le=1000)
    outer_diameter_bottom: float = param("Outer diameter at the can's bottom (m)", gt=0, le=100)
    outer_diameter_top: float = param("Outer diameter at the can's top (m)", gt=0, le=100)
    wall_thickness: float = param(
        "Wall thickness t (m), at the can's bottom and all along unless wall_thickness_top is given; "
        "< the outer radius at both ends",
        gt=0,
        le=50,
    )
    wall_thickness_top: float | None = param(
        "Wall thickness at the can's top (m) when the wall tapers linearly from wall_thickness "
        "at its bottom (a published tower's distributed properties often do); unset = wall_thickness",
        None,
        gt=0,
        le=50,
        optional=True,
    )

    @property
    def thickness_top(self) -> float:
        """The wall at the can's top (m)."""
        return self.wall_thickness if self.wall_thickness_top is None else self.wall_thickness_top


@dataclass(frozen=True)
class Segment:
    """A stretch of the tube between two heights, its diameters linear in height between them."""

    bottom: float
    """z of its lower end (m)"""
    top: float
    """z of its upper end (m)"""
    outer_bottom: float
    """outer diameter at ``bottom`` (m)"""
    outer_top: float
    """outer diameter at ``top`` (m)"""
    inner_bottom: float
    """inner diameter at ``bottom`` (m)"""
    inner_top: float
    """inner diameter at ``top`` (m)"""

    @property
    def length(self) -> float:
        """(m)"""
        return self.top - self.bottom

    @property
    def is_cylinder(self) -> bool:
        """Constant diameters along it."""
        return self.outer_bottom == self.outer_top and self.inner_bottom == self.inner_top

    def _along(self, z: ArrayLike, bottom: float, top: float) -> NDArray[np.float64]:
        if bottom == top:
            return np.full(np.shape(z), bottom, dtype=float)
        s = (np.asarray(z, dtype=float) - self.bottom) / self.length
        out: NDArray[np.float64] = bottom + s * (top - bottom)
        return out

    def outer_diameter(self, z: ArrayLike) -> Any:
        """D0(z) (m): linear between the ends (a float for a float z)."""
        d = self._along(z, self.outer_bottom, self.outer_top)
        return float(d) if np.ndim(d) == 0 else d

    def inner_diameter(self, z: ArrayLike) -> Any:
        """D1(z) (m)"""
        d = self._along(z, self.inner_bottom, self.inner_top)
        return float(d) if np.ndim(d) == 0 else d

    def slope(self) -> float:
        """d(mid-surface radius)/dz = (dD0/dz + dD1/dz) / 4 (-): the cone's half-angle tangent, negative when it narrows."""
        return ((self.outer_top - self.outer_bottom) + (self.inner_top - self.inner_bottom)) / (4 * self.length)


def segments_of_cans(cans: Sequence[Can]) -> tuple[Segment, ...]:
    """The cans stacked from the base (z = 0) up."""
    out, z = [], 0.0
    for c in cans:
        out.append(
            Segment(
                z,
                z + c.height,
                c.outer_diameter_bottom,
                c.outer_diameter_top,
                c.outer_diameter_bottom - 2 * c.wall_thickness,
                c.outer_diameter_top - 2 * c.thickness_top,
            )
        )
        z += c.height
    return tuple(out)


def segment_index(segs: Sequence[Segment], z: ArrayLike, side: str = "above") -> NDArray[np.int64]:
    """Which segment holds each height z: at a joint, the one ``side`` ("above" or
    "below") of it; the ends belong to the first and the last."""
    joints = np.array([s.top for s in segs[:-1]])
    zs = np.asarray(z, dtype=float)
    idx: NDArray[np.int64] = np.searchsorted(joints, zs, side="right" if side == "above" else "left").astype(np.int64)
    return idx


#: the uniform tube's keys that set its modes
PILLAR_MODEL_KEYS = ("height", "outer_diameter", "inner_diameter", "youngs_modulus", "poisson_ratio", "density")


def pillar_key(pillar: Any) -> Any:
    """What a model of the pillar depends on, for a cache key (``Pillar.json_fields``)."""
    return pillar.json_fields()


def foundation_key(foundation: Foundation) -> Any:
    """The foundation's part of a cache key (``Foundation.json_fields``)."""
    return foundation.json_fields()


def check_cans(cans: Sequence[Can], key: str = "pillar.cans") -> None:
    """Each can a tube (its wall thinner than its outer radius at both ends), SceneError naming the can."""
    for i, c in enumerate(cans):
        for name, t, d in (
            ("wall_thickness", c.wall_thickness, c.outer_diameter_bottom),
            ("wall_thickness_top", c.thickness_top, c.outer_diameter_top),
        ):
            if t >= d / 2:
                end = "bottom" if name == "wall_thickness" else "top"
                raise SceneError(
                    f"{key}[{i}].{name} = {t:g} is out of range: must be > 0 and < the can's outer radius "
                    f"at its {end}, outer_diameter_{end} / 2 = {d / 2:g} (m)"
                )


# --------------------------------------------------------------------------
# The foundation

FOUNDATION_KINDS = ("clamped", "springs", "footing")
SPRING_KEYS = ("horizontal_stiffness", "rocking_stiffness", "vertical_stiffness", "torsional_stiffness")
FOOTING_KEYS = ("soil_shear_modulus", "soil_poisson_ratio", "radius", "embedment")


@dataclass(frozen=True)
class Foundation:
    """The ground under the tube's base: clamped, springs, or a circular footing on soil.

    The springs act at the tube's base (z = 0) against the ground, which the
    earthquake moves: horizontal (each horizontal direction), rocking (about
    each horizontal axis), vertical, torsional (about the tube's axis) and the
    horizontal-rocking coupling (a base force per unit base rotation, the
    rotation positive when it moves the tube's upper part the way the
    horizontal displacement goes).  ``kind = "footing"`` computes them from
    the soil and the footing (Gazetas 1991; rotorpillar.reduced.foundation).
    """

    kind: str = param(
        "clamped (the base held rigidly), springs (stated stiffnesses) or footing (a rigid circular "
        "footing on an elastic half-space, its stiffnesses by Gazetas' formulas)",
        "clamped",
        choices=FOUNDATION_KINDS,
    )
    horizontal_stiffness: float | None = param(
        "springs: horizontal stiffness K_H at the base, each direction (N/m)", None, ge=1, le=1e16, optional=True
    )
    rocking_stiffness: float | None = param(
        "springs: rocking stiffness K_R about each horizontal axis (N*m/rad)", None, ge=1, le=1e18, optional=True
    )
    vertical_stiffness: float | None = param(
        "springs: vertical stiffness K_V (N/m); unset = rigid vertically", None, ge=1, le=1e16, optional=True
    )
    torsional_stiffness: float | None = param(
        "springs: torsional stiffness K_T about the tube's axis (N*m/rad); unset = rigid in torsion",
        None,
        ge=1,
        le=1e18,
        optional=True,
    )
    coupling_stiffness: float = param(
        "springs: horizontal-rocking coupling K_HR (N/rad), either sign, K_HR**2 < K_H K_R",
        0.0,
        ge=-1e17,
        le=1e17,
    )
    soil_shear_modulus: float | None = param(
        "footing: the soil's small-strain shear modulus G (Pa)", None, ge=1e3, le=1e11, optional=True
    )
    soil_poisson_ratio: float | None = param(
        "footing: the soil's Poisson's ratio (-)", None, ge=0, le=0.5, optional=True
    )
    radius: float | None = param("footing: radius R of the circular footing (m)", None, ge=0.01, le=1000, optional=True)
    embedment: float = param(
        "footing: depth D of the footing's base below the ground, its sidewall in contact over "
        "the whole depth (m); 0 = on the surface",
        0.0,
        ge=0,
        le=1000,
    )
    rotation_limit: float | None = param(
        "Serviceability limit of the foundation's rotation (rad), against the peak base rotation; unset = not assessed",
        None,
        ge=1e-9,
        le=1,
        optional=True,
    )

    def json_fields(self) -> dict[str, Any]:
        """The foundation's part of a cache key: nothing for a clamp (so keys made before
        foundations existed stay valid), its springs' keys otherwise."""
        if self.kind == "clamped":
            return {}
        return {"foundation": {k: v for k, v in asdict(self).items() if k != "rotation_limit"}}


def check_foundation(f: Foundation) -> None:
    """The keys that belong to the foundation's kind, and only those (SceneError)."""
    defaults = {x.name: x.default for x in fields(Foundation)}
    given = {k for k in (*SPRING_KEYS, "coupling_stiffness") if getattr(f, k) != defaults[k]}
    given_footing = {k for k in FOOTING_KEYS if getattr(f, k) != defaults[k]}
    if f.kind != "springs" and given:
        raise SceneError(f"foundation.{sorted(given)[0]}: only with foundation.kind = 'springs' (kind is {f.kind!r})")
    if f.kind != "footing" and given_footing:
        raise SceneError(
            f"foundation.{sorted(given_footing)[0]}: only with foundation.kind = 'footing' (kind is {f.kind!r})"
        )
    if f.kind == "springs":
        for k in ("horizontal_stiffness", "rocking_stiffness"):
            if getattr(f, k) is None:
                raise SceneError(f"foundation.{k}: required with kind = 'springs' (> 0)")
        assert f.horizontal_stiffness is not None and f.rocking_stiffness is not None
        if f.coupling_stiffness**2 >= f.horizontal_stiffness * f.rocking_stiffness:
            bound = (f.horizontal_stiffness * f.rocking_stiffness) ** 0.5
            raise SceneError(
                f"foundation.coupling_stiffness = {f.coupling_stiffness:g} is out of range: must be > "
                f"{-bound:g} and < {bound:g}, sqrt(K_H K_R), for the springs to store energy (N/rad)"
            )
    if f.kind == "footing":
        for k in ("soil_shear_modulus", "soil_poisson_ratio", "radius"):
            if getattr(f, k) is None:
                raise SceneError(f"foundation.{k}: required with kind = 'footing'")


@dataclass(frozen=True)
class Reference:
    """Published numbers of the machine the scene describes, set beside ours (`analyze`, the report)."""

    source: str = param("Where the numbers are published (a citation, with its table)", "")
    first_fore_aft_frequency: float | None = param(
        "The published first fore-aft (along the rotor's axis, Y) tower frequency (Hz)",
        None,
        ge=1e-4,
        le=1e4,
        optional=True,
    )
    first_side_side_frequency: float | None = param(
        "The published first side-side (in the rotor's plane, X) tower frequency (Hz)",
        None,
        ge=1e-4,
        le=1e4,
        optional=True,
    )
    note: str = param("What the published model has that ours has not, or the reverse: why they differ", "")

    @property
    def stated(self) -> bool:
        return (
            bool(self.source) or self.first_fore_aft_frequency is not None or self.first_side_side_frequency is not None
        )
