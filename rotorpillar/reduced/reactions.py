"""The foundation's design reactions: the envelopes of the base forces with their simultaneous values.

A foundation (its anchor bolts, its base plate, the pile cap) is designed
for each extreme of the base reactions together with the others at the same
instant, not for every peak at once: the largest |M| with the V and N of
that instant, the largest |V| with its M and N, the largest and smallest N
with theirs.  Sign conventions as ``reduced.internal_forces``: M the
y-moment and V the force along X the pillar exerts on the foundation's
part below the section (the rotor's plane), N the axial force, compression
positive.

The planar models compute neither the shear across the rotor's plane, nor
the moment about X, nor the torsion about the pillar's axis: their rows say
"not computed" (None), never 0.

>>> import numpy as np
>>> t = np.linspace(0.0, 1.0, 5)
>>> r = design_reactions(t, [0, 3, -5, 1, 0], [1, -2, 0, 4, 0], [10, 11, 12, 9, 10])
>>> [(row.governs, row.time, row.moment, row.shear, row.axial) for row in r.rows[:2]]
[('max |M|', 0.5, -5.0, 0.0, 12.0), ('max |V|', 0.75, 1.0, 4.0, 9.0)]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..provenance import Record

#: what the planar models leave out, in words
NOT_COMPUTED = (
    "torsion about the pillar's axis, the shear across the rotor's plane and the moment "
    "about X: not computed by the planar model (the pillar bends in the rotor's plane only)"
)


class ReactionRow(Record):
    """The base reactions at the instant one of them is extreme."""

    governs: str
    """which extreme: "max |M|", "max |V|", "max N" or "min N\""""
    time: float
    """when (s)"""
    moment: float
    """M, the base moment about Y at that instant (N*m)"""
    shear: float
    """V, the base shear along X at that instant (N)"""
    axial: float
    """N, the axial force at that instant, compression positive (N)"""
    torsion: float | None
    """T, the torsion about the axis (N*m); None: not computed"""


class DesignReactions(Record):
    """The envelopes of the base reactions over one run, each with its simultaneous values."""

    rows: tuple[ReactionRow, ...]
    """max |M|, max |V|, max N, min N"""
    moment_envelope: float
    """max_t |M| (N*m)"""
    shear_envelope: float
    """max_t |V| (N)"""
    axial_range: tuple[float, float]
    """(min_t N, max_t N) (N)"""
    torsion_envelope: float | None
    """max_t |T| (N*m); None: not computed"""
    not_computed: str
    """the components the model does not compute"""


def design_reactions(
    t: ArrayLike,
    moment: ArrayLike,
    shear: ArrayLike,
    axial: ArrayLike,
    moment_peak: tuple[float, float] | None = None,
    not_computed: str = NOT_COMPUTED,
) -> DesignReactions:
    """The design reactions of sampled base series (s; N*m, N, N), extremes at the samples;
    ``moment_peak`` = (max |M|, its time) where the run refined it between the samples
    (``internal_forces.hermite_peak``): that row then takes V and N interpolated there,
    so the moment's envelope is the run's one number."""
    ts, M, V, N = (np.asarray(a, dtype=float) for a in (t, moment, shear, axial))

    def row(label: str, i: int) -> ReactionRow:
        return ReactionRow(label, float(ts[i]), float(M[i]), float(V[i]), float(N[i]), None)

    i_m = int(np.argmax(np.abs(M)))
    if moment_peak is None:
        first, m_env = row("max |M|", i_m), float(abs(M[i_m]))
    else:
        m_env, when = float(moment_peak[0]), float(moment_peak[1])

        def at(a: NDArray[np.float64]) -> float:
            return float(np.interp(when, ts, a))

        first = ReactionRow("max |M|", when, float(np.copysign(m_env, at(M))), at(V), at(N), None)
    rows = (
        first,
        row("max |V|", int(np.argmax(np.abs(V)))),
        row("max N", int(np.argmax(N))),
        row("min N", int(np.argmin(N))),
    )
    return DesignReactions(
        rows,
        m_env,
        float(np.max(np.abs(V))),
        (float(N.min()), float(N.max())),
        None,
        not_computed,
    )
