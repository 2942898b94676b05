"""Effective modal masses: how much of the structure's mass each mode carries to the base.

For a structure of mass matrix M whose base moves along a direction with
influence vector r (the displacement of every coordinate for a unit rigid
base displacement), mode u_i has

- participation     L_i = u_i^T M r                    (kg)
- modal mass        m_i = u_i^T M u_i                  (kg)
- effective mass    M_i = L_i**2 / m_i                 (kg), independent of u_i's scaling,

and the effective masses of all modes sum to r^T M r, the mass the base
carries in that direction.  The base shear of a mode under a spectral
acceleration S_a is M_i S_a: a set of modes whose effective masses sum to a
fraction f of the total misses the rest of the base shear.

EN 1998-1:2004 4.3.3.3.1(3) asks the modal response spectrum analysis to
take either enough modes that their effective masses sum to at least 90 %
of the total mass, or every mode with an effective mass above 5 % of it.

A uniform cantilever's first mode carries 4 sigma_1**2 / (beta_1 L)**2 =
0.613 of its mass (sigma_1 = 0.7341, beta_1 L = 1.8751; Blevins, *Formulas
for natural frequency and mode shape*, Table 8-1).

>>> import numpy as np
>>> round(float(effective_masses(np.array([3.0]), np.array([9.0]))[0]), 3)
1.0
>>> t = effective_mass_table("X", np.array([10.0, 60.0]), np.array([61.3, 18.8]), 100.0)
>>> [round(r.cumulative, 3) for r in t.rows], t.modes_needed
([0.613, 0.801], None)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..provenance import Record

#: EN 1998-1 4.3.3.3.1(3): the share of the total mass the modes taken must carry (-)
EC8_MASS_FRACTION = 0.90
#: ... or every mode whose effective mass exceeds this share of it (-)
EC8_MODE_FLOOR = 0.05


def effective_masses(participation: ArrayLike, modal_mass: ArrayLike) -> NDArray[np.float64]:
    """M_i = L_i**2 / m_i (kg) per mode."""
    L, m = np.asarray(participation, dtype=float), np.asarray(modal_mass, dtype=float)
    out: NDArray[np.float64] = L**2 / m
    return out


def mode_effective_masses(mass: ArrayLike, shapes: ArrayLike, load: ArrayLike) -> NDArray[np.float64]:
    """M_i = (u_i . p)**2 / (u_i^T M u_i) (kg) for the columns u_i of ``shapes``, where
    p = M r is the base acceleration's load per m/s**2 (``load``, kg) in the same coordinates."""
    M, U, p = (np.asarray(a, dtype=float) for a in (mass, shapes, load))
    return effective_masses(U.T @ p, np.einsum("ji,jk,ki->i", U, M, U))


class EffectiveMassRow(Record):
    """One mode's share of the mass the base carries."""

    mode: int
    """the mode's number, 1 the lowest (-)"""
    omega: float
    """its natural angular frequency (rad/s)"""
    effective_mass: float
    """L**2 / m (kg)"""
    fraction: float
    """its share of the total mass (-)"""
    cumulative: float
    """the share of this mode and every lower one (-)"""


class EffectiveMassTable(Record):
    """The modes' effective masses along one direction and what EN 1998-1 asks of them."""

    direction: str
    """the base's direction of motion, e.g. "X" (in the rotor's plane)"""
    total_mass: float
    """the mass the base carries along it (kg)"""
    rows: tuple[EffectiveMassRow, ...]
    """per mode, ascending"""
    modes_needed: int | None
    """the fewest lowest modes that carry 90 % of the mass (None: these modes do not)"""
    modes_above_floor: int
    """how many modes carry more than 5 % each (-)"""
    note: str
    """what the modes and the total are, in words"""


def modes_for_fraction(cumulative: ArrayLike, target: float = EC8_MASS_FRACTION) -> int | None:
    """The fewest lowest modes whose cumulative fraction reaches ``target`` (None: never)."""
    c = np.asarray(cumulative, dtype=float)
    hit = np.nonzero(c >= target * (1 - 1e-12))[0]
    return int(hit[0]) + 1 if hit.size else None


def pillar_mass_fractions(
    participation: ArrayLike, modal_mass: ArrayLike, rotor_mass: float, total_mass: float
) -> NDArray[np.float64]:
    """The share of ``total_mass`` (kg) a modal ROM carries with its first k = 1, 2, ...
    pillar modes (``participation`` L_j and ``modal_mass`` m_j, kg), the rotor (a
    coordinate of its own, ``rotor_mass``, kg) always whole (-)."""
    out: NDArray[np.float64] = (np.cumsum(effective_masses(participation, modal_mass)) + rotor_mass) / total_mass
    return out


class ForceModes(Record):
    """How many pillar modes a ROM for forces keeps, and why (EN 1998-1 4.3.3.3.1(3))."""

    direction: str
    """the base's direction of motion the shares are taken along, e.g. "X" (the rotor's plane)"""
    required: float
    """the share of the mass the kept modes must carry, 0.90 (-)"""
    total_mass: float
    """the mass the base carries along it: tube, gondola and rotor (kg)"""
    modes: int
    """the pillar modes the forces superpose (-)"""
    fraction: float
    """the share of ``total_mass`` they carry, the rotor whole (-)"""
    cumulative: tuple[float, ...]
    """the share with the first k = 1, 2, ... candidate modes (-)"""
    modes_in_run: int
    """the pillar modes of the case's run (its band rule, the headline's) (-)"""
    modes_for_mass: int | None
    """the fewest that carry ``required`` (None: all the candidates do not)"""
    modes_for_moment: int
    """the fewest with the base moment within the truncation tolerance over the band (-)"""
    modes_available: int
    """the candidate modes there are (-)"""
    reason: str
    """why ``modes``, in words"""


def force_modes(
    cumulative: ArrayLike,
    modes_in_run: int,
    modes_for_moment: int,
    total_mass: float,
    direction: str = "X",
    required: float = EC8_MASS_FRACTION,
) -> ForceModes:
    """The pillar modes a ROM for forces keeps: the most of the run's, the base moment's
    need and the fewest carrying ``required`` of the mass (``cumulative`` per count), at
    most every candidate; ``reason`` says which governed and whether the mass was reached."""
    c = np.asarray(cumulative, dtype=float)
    n = len(c)
    k_mass = modes_for_fraction(c, required)
    needs = {"the case's run": modes_in_run, "the base moment": modes_for_moment, "the mass": k_mass or n}
    k = min(max(needs.values()), n)
    governs = " and ".join(name for name, v in needs.items() if min(v, n) == k)
    share = f"{100 * c[k - 1]:.1f} % of {total_mass:.5g} kg along {direction}"
    if k_mass is None:
        reason = (
            f"all {n} candidate modes; they carry {share}, below the {100 * required:.0f} % "
            "EN 1998-1 4.3.3.3.1 asks of a modal analysis for forces: the base shear misses the rest "
            "(more candidate modes: modal.n_modes for the 3D ones, modal_model.elements for the beam's)"
        )
    else:
        reason = (
            f"{k} modes, set by {governs} (the case's run keeps {modes_in_run}, the base moment needs "
            f"{modes_for_moment}, {k_mass} carry the {100 * required:.0f} % EN 1998-1 4.3.3.3.1 asks): "
            f"they carry {share}"
        )
    return ForceModes(
        direction,
        float(required),
        float(total_mass),
        int(k),
        float(c[k - 1]),
        tuple(map(float, c)),
        int(modes_in_run),
        k_mass,
        int(modes_for_moment),
        n,
        reason,
    )


def effective_mass_table(
    direction: str, omega: ArrayLike, effective_mass: ArrayLike, total_mass: float, note: str = ""
) -> EffectiveMassTable:
    """The participation table of modes at ``omega`` (rad/s) with their effective masses (kg)."""
    w, me = np.asarray(omega, dtype=float), np.asarray(effective_mass, dtype=float)
    frac = me / total_mass
    cum = np.cumsum(frac)
    rows = tuple(
        EffectiveMassRow(i + 1, float(w[i]), float(me[i]), float(frac[i]), float(cum[i])) for i in range(len(w))
    )
    return EffectiveMassTable(
        direction,
        float(total_mass),
        rows,
        modes_for_fraction(cum),
        int(np.sum(frac > EC8_MODE_FLOOR)),
        note,
    )
