"""The pillar's closed forms and the tip reduction the reduced model uses.

The paper's Eq. 1 with Timoshenko's correction, its Eq. 2 reductions (lumped, continuous
limit, Rayleigh) of the bare tube, and which tip mass and stiffness a scene's
reduced model takes (stated, Eq. 2, or the 3D model's, handed in by the
caller: this package never builds the 3D model itself).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..provenance import Record
from ..scene import Pillar, Scene, SceneError
from .beam_fe import BaseSprings
from .pillar import (
    cantilever_root,
    cowper_shear_coefficient,
    omega_euler_bernoulli,
    omega_timoshenko,
    rayleigh_reduction,
    section_of,
    tip_mass_continuous,
    tip_mass_lumped,
)
from .tower import rayleigh_ritz, section_at, tower_mass

LUMPINGS = (1, 2, 3, 5, 10, 20, 50, 100)


class Lumping(Record):
    """The paper's Eq. 2 with the tube lumped into ``n`` equal masses."""

    n: int
    tip_mass: float
    """m_r (kg)"""
    tip_stiffness: float
    """c1 = m_r omega_col1**2 (N/m)"""


class RayleighEstimate(Record):
    """Rayleigh's quotient on a static deflection shape."""

    shape: str
    """"uniform_load" or "tip_load\""""
    tip_mass: float
    """(kg)"""
    tip_stiffness: float
    """(N/m)"""
    omega: float
    """(rad/s)"""
    omega_error: float
    """omega / omega_col1 - 1 (-)"""


class RitzEstimate(Record):
    """The bare tube's bending modes by Rayleigh-Ritz (rotorpillar.reduced.tower.rayleigh_ritz)."""

    omega: tuple[float, ...]
    """the first three, each an upper bound of the Euler-Bernoulli beam's (rad/s)"""
    terms: int
    """assumed shapes: the uniform cantilever's modes (-)"""
    tip_mass: float
    """Eq. 2 on the first Ritz mode (kg)"""
    tip_stiffness: float
    """m_r omega_1**2 (N/m)"""
    on_foundation: bool
    """with the foundation's springs (else clamped)"""


class PillarClosedForms(Record, omit_defaults=True):
    """The bare tube: its section, Eq. 1, Timoshenko's correction, Eq. 2's reductions."""

    area: float
    """steel cross-section (m**2)"""
    second_moment: float
    """I (m**4)"""
    mass_per_length: float
    """(kg/m)"""
    mass: float
    """the tube's mass (kg)"""
    wall_thickness: float
    """(m)"""
    diameter_to_thickness: float
    """D0 / t (-)"""
    slenderness: float
    """height over the radius of gyration (-)"""
    omega_col1: float
    """Eq. 1, Euler-Bernoulli (rad/s)"""
    frequency_col1_hz: float
    """(Hz)"""
    cantilever_root: float
    """beta_1 L of the clamped-free beam (-)"""
    omega_euler_bernoulli: tuple[float, ...]
    """the first three bending modes, Euler-Bernoulli (rad/s)"""
    shear_coefficient: float
    """Cowper's kappa (-)"""
    omega_col1_timoshenko: float
    """(rad/s)"""
    timoshenko_correction: float
    """omega_col1_timoshenko / omega_col1 - 1 (-)"""
    tip_mass_lumped: tuple[Lumping, ...]
    tip_mass_limit: float
    """Eq. 2's continuous limit m_r (kg)"""
    tip_stiffness_limit: float
    """m_r omega_col1**2 (N/m)"""
    rayleigh: tuple[RayleighEstimate, ...]
    rayleigh_ritz: RitzEstimate | None = None
    """the bending modes by Rayleigh-Ritz (upper bounds), in Eq. 1's place for a tapered or
    stepped tower or on a flexible foundation; None (left out) for the uniform tube on a
    clamp, where the closed forms hold"""
    statement: str | None = None
    """what the numbers above are where the closed forms do not hold; None where they do"""

    @property
    def uniform(self) -> bool:
        """A uniform tube clamped at its base: the paper's closed forms hold."""
        return self.statement is None


class TipReductionUsed(Record):
    """The tip mass and stiffness the reduced model uses, and where each came from."""

    source: str
    """[reduction] source: "auto", "stated", "closed_form" or "fem3d\""""
    tip_mass: float
    """m_r (kg)"""
    tip_mass_source: str
    tip_mass_computed: float
    """(kg)"""
    tip_stiffness: float
    """c1 (N/m)"""
    tip_stiffness_source: str
    tip_stiffness_computed: float
    """(N/m)"""
    computed_source: str
    """"closed_form" or "fem3d\""""


#: Timoshenko beam elements of the tower's reference where no closed form holds
#: (error ~1e-5 of omega_1 at h**2 from 200 elements)
TOWER_TIMOSHENKO_ELEMENTS = 200


def _ritz(pillar: Pillar, base: BaseSprings | None) -> RitzEstimate:
    r = rayleigh_ritz(pillar, base=base)
    return RitzEstimate(tuple(map(float, r.omega[:3])), r.terms, r.tip_mass, r.tip_stiffness, base is not None)


def pillar_closed_forms(pillar: Pillar, base: BaseSprings | None = None) -> PillarClosedForms:
    """The paper's Eq. 1 (with Timoshenko's correction) and 2 (the reductions) on the bare
    tube of ``[pillar]``, with the Rayleigh-Ritz modes beside them.

    Eq. 1 is a uniform tube's on a clamp.  For a tapered or stepped tower,
    or on a flexible foundation (``base``), Rayleigh-Ritz takes its place
    (omega_col1, the first three, Eq. 2 on the first Ritz mode), the
    Timoshenko value is the beam's (rotorpillar.reduced.beam_fe, 200
    elements), the section numbers are the base's, and the uniform tube's
    lumping and static shapes are left out (``statement`` says so).
    """
    p = pillar
    if not p.is_uniform or base is not None:
        return _tower_closed_forms(p, base)
    sec = section_of(p)
    I, A, m_rho = sec.second_moment, sec.area, sec.mass_per_length
    mass = m_rho * p.height
    w1 = omega_euler_bernoulli(p.youngs_modulus, I, m_rho, p.height)
    kappa = cowper_shear_coefficient(sec.outer_diameter, sec.inner_diameter, p.poisson_ratio)
    w_timo = omega_timoshenko(p.youngs_modulus, p.poisson_ratio, kappa, p.density, A, I, p.height)
    lumped = tuple(Lumping(n, tip_mass_lumped(mass, n), tip_mass_lumped(mass, n) * w1**2) for n in LUMPINGS)
    m_inf = tip_mass_continuous(mass)
    rayleigh = []
    for shape in ("uniform_load", "tip_load"):
        r = rayleigh_reduction(mass, p.youngs_modulus, I, p.height, shape)
        rayleigh.append(RayleighEstimate(shape, r.tip_mass, r.tip_stiffness, r.omega, r.omega / w1 - 1))
    return PillarClosedForms(
        area=A,
        second_moment=I,
        mass_per_length=m_rho,
        mass=mass,
        wall_thickness=sec.wall_thickness,
        diameter_to_thickness=sec.outer_diameter / sec.wall_thickness,
        slenderness=p.height / sec.radius_of_gyration,
        omega_col1=w1,
        frequency_col1_hz=w1 / (2 * math.pi),
        cantilever_root=cantilever_root(1),
        omega_euler_bernoulli=tuple(omega_euler_bernoulli(p.youngs_modulus, I, m_rho, p.height, k) for k in (1, 2, 3)),
        shear_coefficient=kappa,
        omega_col1_timoshenko=w_timo,
        timoshenko_correction=w_timo / w1 - 1,
        tip_mass_lumped=lumped,
        tip_mass_limit=m_inf,
        tip_stiffness_limit=m_inf * w1**2,
        rayleigh=tuple(rayleigh),
    )


def _tower_closed_forms(p: Pillar, base: BaseSprings | None) -> PillarClosedForms:
    from .beam_fe import beam_modes
    from .pillar_modes import beam_line

    sec = section_at(p, 0.0)
    ritz = _ritz(p, base)
    w1 = ritz.omega[0]
    n = max(TOWER_TIMOSHENKO_ELEMENTS, len(p.segments()))
    w_timo = float(beam_modes(beam_line(p, n), n, "timoshenko", 1, base=base).omega[0])
    where = []
    if not p.is_uniform:
        cans = len(p.segments())
        where.append("a tapered tube (one can)" if cans == 1 else f"a tower of {cans} cans, tapered or stepped")
    if base is not None:
        where.append("on the foundation's springs")
    statement = (
        f"Eq. 1 and Eq. 2's closed forms hold for a uniform tube on a clamp, not for this pillar "
        f"({' and '.join(where)}): omega_col1 and the first three are Rayleigh-Ritz's upper bounds "
        f"({ritz.terms} cantilever modes as shapes), the tip mass is Eq. 2 on the first Ritz mode, "
        f"the Timoshenko value the {n}-element beam's, the section numbers the base's"
    )
    return PillarClosedForms(
        area=sec.area,
        second_moment=sec.second_moment,
        mass_per_length=sec.mass_per_length,
        mass=tower_mass(p),
        wall_thickness=sec.wall_thickness,
        diameter_to_thickness=sec.outer_diameter / sec.wall_thickness,
        slenderness=p.height / sec.radius_of_gyration,
        omega_col1=w1,
        frequency_col1_hz=w1 / (2 * math.pi),
        cantilever_root=cantilever_root(1),
        omega_euler_bernoulli=ritz.omega,
        shear_coefficient=cowper_shear_coefficient(sec.outer_diameter, sec.inner_diameter, p.poisson_ratio),
        omega_col1_timoshenko=w_timo,
        timoshenko_correction=w_timo / w1 - 1,
        tip_mass_lumped=(),
        tip_mass_limit=ritz.tip_mass,
        tip_stiffness_limit=ritz.tip_stiffness,
        rayleigh=(),
        rayleigh_ritz=ritz,
        statement=statement,
    )


def resolve_reduction(
    scene: Scene, closed: PillarClosedForms, fem3d_reduction: Callable[[Scene], tuple[float, float]] | None = None
) -> TipReductionUsed:
    """The tip mass and stiffness the reduced model uses, and where each came from.

    ``fem3d_reduction`` is a callable scene -> (m_reduced, tip_stiffness), used
    when the scene's source is "fem3d".
    """
    red = scene.reduction
    computed = {"tip_mass": closed.tip_mass_limit, "tip_stiffness": closed.tip_stiffness_limit}
    source = "closed_form"
    if red.source == "fem3d":
        if fem3d_reduction is None:
            raise SceneError(
                'reduction.source = "fem3d" needs the 3D model (rotorpillar.fem3d), which is not available here'
            )
        m, c = fem3d_reduction(scene)
        computed, source = {"tip_mass": m, "tip_stiffness": c}, "fem3d"
    used: dict[str, tuple[float, str]] = {}
    for key in ("tip_mass", "tip_stiffness"):
        stated = getattr(red, key)
        if stated is not None and red.source in ("auto", "stated"):
            used[key] = (stated, "stated")
        elif red.source == "stated":
            raise SceneError(f'reduction.{key}: required when reduction.source = "stated"')
        else:
            used[key] = (computed[key], source)
    return TipReductionUsed(
        source=red.source,
        tip_mass=used["tip_mass"][0],
        tip_mass_source=used["tip_mass"][1],
        tip_mass_computed=computed["tip_mass"],
        tip_stiffness=used["tip_stiffness"][0],
        tip_stiffness_source=used["tip_stiffness"][1],
        tip_stiffness_computed=computed["tip_stiffness"],
        computed_source=source,
    )
