"""The machine's sections: the pillar, the gondola, the rotor and its shaft, the steel,
the tip reduction, the drive and the load (frozen dataclasses, SI units and the allowed
range in each field; rotorpillar.scene.sections re-exports them)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from .fields import param
from .tower import Can, Segment, segments_of_cans

# --------------------------------------------------------------------------
# Sections.  Defaults exist only where a scene may reasonably leave a key out
# (numerical settings); physical data must be stated.


@dataclass(frozen=True, kw_only=True)
class Pillar:
    """The steel tube: a cantilever on its foundation (clamped at its base by default).

    Either a uniform tube (``height``, ``outer_diameter``, ``inner_diameter``)
    or a stack of cans from the base up (``[[pillar.cans]]``, rotorpillar.scene.tower:
    a linear taper is one can); ``height`` is then the cans' sum and may be left out.

    The ranges of this section and of [gondola], [rotor], [shaft], [drive]
    and [load] span the machines the tool is for (a fan on a 0.1 m post to a
    100,000 t machine on a 1 km tower, rubber to diamond): far past any real
    design, yet short of where the formulas overflow (1e300).
    """

    height: float = param("Height H (m); with cans, their sum (may be left out)", None, ge=0.1, le=1000, optional=True)
    outer_diameter: float | None = param(
        "Outer diameter D0 (m) of the uniform tube", None, ge=0.01, le=100, optional=True
    )
    inner_diameter: float | None = param(
        "Inner diameter D1 (m) of the uniform tube, < outer_diameter, the wall at least D0/1000",
        None,
        ge=0,
        le=100,
        optional=True,
    )
    youngs_modulus: float = param("Young's modulus E (Pa)", ge=1e6, le=1e13)
    poisson_ratio: float = param("Poisson's ratio (-); the 3D elements lock as it nears 0.5", ge=-0.9, le=0.49)
    density: float = param("Density rho (kg/m**3)", ge=1, le=1e5)
    damping: float = param("Damping b1 at the tip (N*s/m)", ge=0, le=1e12)
    damping_ratio: float = param(
        "Structural damping ratio zeta of every pillar mode of the spatial model (bending in both "
        "planes, torsion, axial, ovalling), on top of the tip dashpot b1 (-); default 0.0019 = the "
        "logarithmic decrement 0.012 / (2 pi) that EN 1991-1-4 Annex F Table F.2 gives for an unlined "
        "welded steel stack; the planar ROM and the paper's Eq. 4 leave it out, as today",
        0.012 / (2 * math.pi),
        ge=0,
        le=0.5,
    )
    cans: tuple[Can, ...] = param(
        "The tower's cans from the base up ([[pillar.cans]]), instead of the uniform tube's diameters",
        (),
        ge=0,
        le=1000,
        table=Can,
    )

    def __post_init__(self) -> None:
        # the cans' sum stands for a height left out, so every model reads one height
        if self.height is None and self.cans:
            object.__setattr__(self, "height", float(sum(c.height for c in self.cans)))

    def segments(self) -> tuple[Segment, ...]:
        """The tube as segments from the base up (rotorpillar.scene.tower): one for the uniform tube."""
        if self.cans:
            return segments_of_cans(self.cans)
        assert self.outer_diameter is not None and self.inner_diameter is not None  # validation's
        return (
            Segment(
                0.0, self.height, self.outer_diameter, self.outer_diameter, self.inner_diameter, self.inner_diameter
            ),
        )

    def json_fields(self) -> dict[str, Any]:
        """What a model of the pillar depends on, for a cache key: today's keys, and the
        cans when there are any (so a uniform tube's keys are those it always had)."""
        keys = ("height", "outer_diameter", "inner_diameter", "youngs_modulus", "poisson_ratio", "density")
        out = {k: getattr(self, k) for k in keys}
        if self.cans:
            out["cans"] = [dataclasses.asdict(c) for c in self.cans]
        return out

    @property
    def is_uniform(self) -> bool:
        """One cylinder from base to top: the closed forms of a uniform tube (Eq. 1) hold."""
        s = self.segments()
        return all(x.is_cylinder for x in s) and len({(x.outer_bottom, x.inner_bottom) for x in s}) == 1


@dataclass(frozen=True)
class Gondola:
    """The stator housing on top of the pillar, moving with its tip."""

    mass: float = param("Mass m* (kg)", ge=1e-9, le=1e8)
    roll_inertia: float = param(
        "Moment of inertia about its own centre, about the horizontal axis along the spin axis "
        "(roll: the rotor's plane's rotation) (kg*m**2); the paper neglects it",
        0.0,
        ge=0,
        le=1e10,
    )
    pitch_inertia: float = param(
        "Moment of inertia about its own centre, about the horizontal axis in the rotor's plane (pitch) "
        "(kg*m**2); the paper neglects it",
        0.0,
        ge=0,
        le=1e10,
    )
    yaw_inertia: float = param(
        "Moment of inertia about its own centre, about the vertical (yaw: the pillar's torsion) "
        "(kg*m**2); the paper neglects it",
        0.0,
        ge=0,
        le=1e10,
    )
    height: float = param(
        "Height of its centre above the pillar's top (m); 0 = at the top, as the paper has it", 0.0, ge=0, le=1000
    )


@dataclass(frozen=True)
class Rotor:
    """The rotor on its elastic shaft."""

    mass: float = param("Mass m_C (kg)", ge=1e-3, le=1e8)
    inertia: float = param("Polar mass moment of inertia J_C (kg*m**2)", ge=1e-6, le=1e10)
    eccentricity: float = param("Eccentricity e of the mass centre (m)", ge=0, le=1)
    diametral_inertia: float | None = param(
        "Moment of inertia I_d about a diameter through its centre (kg*m**2); unset = J_C / 2, a thin disc's",
        None,
        ge=1e-6,
        le=1e10,
        optional=True,
    )
    height: float = param(
        "Height of its centre (and of the shaft's bearing point) above the pillar's top (m); 0 = at the "
        "top, as the paper has it",
        0.0,
        ge=0,
        le=1000,
    )
    couple_unbalance: float = param(
        "Couple unbalance U_c (kg*m**2): the product of inertia that tilts the principal axis off the "
        "spin axis, a moment U_c Omega**2 turning with the rotor about the lateral axes; 0 = none",
        0.0,
        ge=0,
        le=1e6,
    )
    clearance: float | None = param(
        "Shaft deflection allowed before the rotor touches its stator: the air gap or seal "
        "clearance (m); unset = the clearance check is not assessed",
        None,
        ge=1e-6,
        le=1,
        optional=True,
    )
    balance_grade: float = param(
        "Balance quality grade G = e Omega required of the machine type (mm/s), the capacity of "
        "the balance check (ISO 21940-11 Table 1: 2.5 for gas and steam turbines, turbo-generators "
        "and compressors, 6.3 for pumps, fans and general machinery)",
        2.5,
        ge=0.1,
        le=4000,
    )
    blades: int = param(
        "Blades (-): the blade-passing order (blades x the rotor speed, 3P on a three-bladed "
        "turbine) forces the tower beside 1P; 0 = none",
        0,
        ge=0,
        le=100,
    )
    order_margin: float = param(
        "Separation the tower's modes keep from each excitation order, 1P and the blade-passing "
        "one, as a fraction of the order's frequency (-); soft-stiff: the first mode above 1P and "
        "below the blade-passing frequency by this much",
        0.10,
        ge=0,
        le=0.9,
    )


@dataclass(frozen=True)
class Shaft:
    """Shaft and bearings, the same in X and Y (c2 = c3, b2 = b3)."""

    stiffness: float = param("Stiffness c2 = c3 (N/m)", ge=1, le=1e14)
    damping: float = param("Damping b2 = b3 (N*s/m)", ge=0, le=1e12)
    axial_stiffness: float | None = param(
        "Stiffness along the spin axis between the rotor and the gondola (N/m); unset = c2",
        None,
        ge=1,
        le=1e14,
        optional=True,
    )
    tilt_stiffness: float | None = param(
        "Stiffness against the rotor's tilt (pitch and yaw) relative to the gondola (N*m/rad); unset = "
        "rigid: the rotor tilts with the gondola (the paper models no tilt)",
        None,
        ge=1,
        le=1e14,
        optional=True,
    )
    tilt_damping: float = param(
        "Damping of the rotor's tilt relative to the gondola (N*m*s/rad); used with tilt_stiffness",
        0.0,
        ge=0,
        le=1e12,
    )
    force_limit: float | None = param(
        "Force the shaft and its bearings may carry (N), against the peak of the shaft's force "
        "on the rotor; unset = the force check is not assessed",
        None,
        ge=1,
        le=1e12,
        optional=True,
    )


FABRICATION_CLASSES = ("A", "B", "C")


@dataclass(frozen=True)
class Material:
    """The tube's steel as the checks need it (its stiffness and density are in [pillar])."""

    yield_strength: float = param(
        "Characteristic yield strength f_yk (Pa); S355 by default, the usual grade of welded steel towers (EN 10025-2)",
        355e6,
        ge=1e6,
        le=1e10,
    )
    fabrication_class: str = param(
        "Fabrication tolerance quality class of the thin-walled tube for shell buckling "
        "(EN 1993-1-6 Table 8.1: A excellent, B high, C normal; Q = 40, 25, 16 in D.1.2.2). "
        "Default C: the lowest class, whose tolerances any fabricator must meet, so an "
        "unstated class never overstates the buckling resistance",
        "C",
        choices=FABRICATION_CLASSES,
    )


REDUCTION_SOURCES = ("auto", "stated", "closed_form", "fem3d")


@dataclass(frozen=True)
class Reduction:
    """The pillar reduced to one mass and one spring at its tip (the paper's Eq. 2).

    Stated values are used as given; absent ones are computed, by
    ``source``: "closed_form" (the continuous first Euler-Bernoulli mode),
    "fem3d" (the first bending mode of the 3D model) or "auto" (= stated
    where given, else closed_form).
    """

    tip_mass: float | None = param("Reduced tip mass m_r (kg)", None, ge=1e-3, le=1e8, optional=True)
    tip_stiffness: float | None = param("Tip stiffness c1 (N/m)", None, ge=1, le=1e14, optional=True)
    source: str = param("Where absent values come from", "auto", choices=REDUCTION_SOURCES)


@dataclass(frozen=True)
class Drive:
    """Motor characteristic Md(Omega) = torque_at_zero - slope*Omega (the paper's Eq. 22)."""

    torque_at_zero: float = param("Stall torque M0 (N*m)", ge=0, le=1e9)
    slope: float = param("Slope of the characteristic (N*m*s/rad)", ge=0, le=1e9)


@dataclass(frozen=True)
class Load:
    """Resistance of the driven machine, Mc(Omega) = coefficient*Omega**2 (the paper's Eq. 22)."""

    coefficient: float = param("Quadratic load coefficient k (N*m*s**2/rad**2)", ge=0, le=1e9)
