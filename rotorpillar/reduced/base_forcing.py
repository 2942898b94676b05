"""How the ground's motion enters the rotor-pillar equations: as published, and as it must.

The paper's Eq. 4 forces the tip q1 by c0 q5 + b0 q5' and the rotor centre
q2 by c2 q5 + b2 q5' (q5 the ground's X displacement, coordinates absolute):
as if the shaft, not only the pillar, were anchored to the ground.  The
consistent forcing of the same energies (the pillar spring c1 and damper b1
are the only members that reach the ground) is c1 q5 + b1 q5' on q1 and
nothing on q2, the same as the inertial forcing -M r a_g in coordinates
relative to the ground.  Under a slow (static) ground displacement u the
whole machine must move with the ground, q1 = q2 = u; the published
forcing instead gives q1 = (c1 + 2 c2)/c1 u, a gain the consistent forcing
does not have.
"""

from __future__ import annotations

from ..provenance import Record

#: Above this ratio of the published static gain over the consistent one (1),
#: the paper model's earthquake is flagged: the published forcing then
#: inflates the response by more than the scatter of a ground-motion record.
AMPLIFICATION_LIMIT = 1.10


def published_static_gain(tip_stiffness: float, shaft_stiffness: float) -> float:
    """Static tip gain q1/q5 of Eq. 4's published base forcing: (c1 + 2 c2)/c1 (-).

    >>> published_static_gain(9.6e6, 0.4e6)
    1.0833333333333333
    >>> published_static_gain(9.6e6, 5e6)
    2.0416666666666665
    """
    return (tip_stiffness + 2 * shaft_stiffness) / tip_stiffness


class ForcingTerms(Record, omit_defaults=True):
    """Eq. 4's base forcing on q1 and q2, in words with this scene's numbers
    (stiffness N/m on q5, damping N*s/m on q5')."""

    q1: str
    """the forcing on the tip q1"""
    q2: str
    """the forcing on the rotor centre q2"""
    relative_coordinates: str | None = None
    """the same forcing in coordinates relative to the ground (absent for the published one)"""


class BaseForcingFinding(Record):
    """Eq. 4's published base forcing against the consistent one, for a scene."""

    published: ForcingTerms
    """c0 q5 + b0 q5' on q1, c2 q5 + b2 q5' on q2"""
    consistent: ForcingTerms
    """c1 q5 + b1 q5' on q1, nothing on q2"""
    static_gain_published: float
    """static tip gain q1/q5 of the published forcing, (c1 + 2 c2)/c1 (-)"""
    static_gain_consistent: float
    """static tip gain of the consistent forcing: 1 (-)"""
    amplification: float
    """the published gain over the consistent one (-)"""
    amplifies: bool
    """the amplification passes ``limit``"""
    limit: float
    """AMPLIFICATION_LIMIT (-)"""


def base_forcing_finding(
    tip_stiffness: float, shaft_stiffness: float, pillar_damping: float, shaft_damping: float
) -> BaseForcingFinding:
    """The published and the consistent base forcing of Eq. 4 for a scene, and the gain."""
    c1, c2, b1, b2 = tip_stiffness, shaft_stiffness, pillar_damping, shaft_damping
    gain = published_static_gain(c1, c2)
    return BaseForcingFinding(
        published=ForcingTerms(
            q1=f"c0 q5 + b0 q5' = {c1 + c2:.4g} q5 + {b1 + b2:.4g} q5'",
            q2=f"c2 q5 + b2 q5' = {c2:.4g} q5 + {b2:.4g} q5'",
        ),
        consistent=ForcingTerms(
            q1=f"c1 q5 + b1 q5' = {c1:.4g} q5 + {b1:.4g} q5'",
            q2="0",
            relative_coordinates="-M r a_g (m_A a_g on q1, m_C a_g on q2)",
        ),
        static_gain_published=gain,
        static_gain_consistent=1.0,
        amplification=gain,
        amplifies=gain > AMPLIFICATION_LIMIT,
        limit=AMPLIFICATION_LIMIT,
    )


def published_forcing_warning(tip_stiffness: float, shaft_stiffness: float) -> str | None:
    """One line when the published forcing amplifies the ground by more than
    AMPLIFICATION_LIMIT over the consistent one, else None.

    >>> published_forcing_warning(9.6e6, 0.4e6) is None
    True
    """
    gain = published_static_gain(tip_stiffness, shaft_stiffness)
    if gain <= AMPLIFICATION_LIMIT:
        return None
    return (
        f"Eq. 4's published base forcing (c0 q5 on q1, c2 q5 on q2) amplifies the ground "
        f"{gain:.3g}x statically ((c1 + 2 c2)/c1 with c1 = {tip_stiffness:.4g}, c2 = "
        f"{shaft_stiffness:.4g} N/m), over {AMPLIFICATION_LIMIT:g}x: this response is inflated; "
        f"the modal model (-M r a_g) is the consistent one"
    )
