"""The base reactions of the spatial model: two shears, the axial force, two moments, the torque,
and the base stress from the resultant moment, at each instant.

By modal superposition (the mode displacement method, as the planar ROM's
rotorpillar.reduced.internal_forces): each resultant at the base is
sum_j eta_j(t) R_j(0), R_j the mode's section resultant per unit modal
coordinate (SpatialPillarModes: shear_x, shear_y, axial_force, moment_x,
moment_y, torque; what the part above exerts on the part below, about the
section's centre).  A moment and a shear weight the higher modes' curvature,
so they need more modes than the tip (internal_forces.force_truncation
counts them for the planar model).

The axial force is **compression positive**, as internal_forces writes it:
the weight of the pillar, the gondola and the rotor under g, minus the
modes' axial force, minus the rotor's vertical pull on the gondola
c2 (d_v.Z - e sin theta) (the shaft stretched upward unloads the tube; the
pillar's axial modes lie far above any band, so it reaches the base
unchanged).  The base stress is the extreme fibre's, compression positive,
from the resultant of the two moments:

    sigma = sqrt(M_x**2 + M_y**2) c / I + N / A.

>>> from rotorpillar.scene import load_scene
>>> from rotorpillar.reduced.spatial_beam import beam_spatial_modes
>>> from rotorpillar.reduced.spatial_model import spatial_model
>>> s = load_scene("paper")
>>> m = spatial_model(beam_spatial_modes(s.pillar, s.gondola, 2), s.rotor, s.shaft, s.pillar.damping)
>>> r = base_reactions(m, np.zeros(1), np.zeros((1, m.n)), s.pillar, s.gondola.mass)
>>> round(float(r.axial_force[0]) / 9.80665)  # pillar 20154 + gondola 2300 + rotor 1600 kg
24054
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..provenance import Record
from ..scene import Pillar
from .internal_forces import STANDARD_GRAVITY
from .spatial_model import SpatialStructure
from .spatial_modes import Array
from .tower import section_at, tower_mass


class BaseReactions(Record, eq=False):
    """The pillar's base reactions over a run (what the pillar exerts on its foundation's top)."""

    t: Array
    """(n,) times (s)"""
    shear_x: Array
    """(n,) shear force in the rotor's plane (N)"""
    shear_y: Array
    """(n,) shear force along the spin axis (N)"""
    axial_force: Array
    """(n,) axial force, compression positive, the weights included (N)"""
    moment_x: Array
    """(n,) moment about x (bending along the spin axis) (N*m)"""
    moment_y: Array
    """(n,) moment about y (bending in the rotor's plane) (N*m)"""
    torque: Array
    """(n,) moment about the vertical (torsion) (N*m)"""
    moment: Array
    """(n,) the resultant bending moment sqrt(M_x**2 + M_y**2) (N*m)"""
    stress: Array
    """(n,) the extreme fibre's meridional stress from it and the axial force, compression positive (Pa)"""
    modes: int
    """the pillar modes superposed (-)"""


def base_reactions(
    m: SpatialStructure,
    t: NDArray[np.float64],
    q: NDArray[np.float64],
    pillar: Pillar,
    gondola_mass: float,
    g: float = STANDARD_GRAVITY,
) -> BaseReactions:
    """The base reactions at the states q (n, model.n) of a run of ``m`` (see the module text)."""
    pm = m.modes
    names = ("shear_x", "shear_y", "axial_force", "moment_x", "moment_y", "torque")
    missing = [n for n in names if getattr(pm, n) is None]
    if missing:
        raise ValueError(f"{pm.source}: the modes carry no {', '.join(missing)}: no base reactions")
    k = pm.count
    eta = np.asarray(q)[:, :k]
    base = {n: eta @ np.asarray(getattr(pm, n))[0] for n in names}
    Z, theta = np.asarray(q)[:, : m.nz], np.asarray(q)[:, m.nz]
    pull = m.shaft_stiffness * (Z @ m.shaft[1] - m.eccentricity * np.sin(theta))
    p = pillar
    sec = section_at(p, 0.0)  # the base's section (a tower's varies along it)
    area, second, outer = sec.area, sec.second_moment, sec.outer_diameter
    weight = g * (tower_mass(p) + gondola_mass + m.rotor_mass)
    axial = weight - base["axial_force"] - pull
    moment = np.hypot(base["moment_x"], base["moment_y"])
    return BaseReactions(
        t=np.asarray(t, dtype=float),
        shear_x=base["shear_x"],
        shear_y=base["shear_y"],
        axial_force=axial,
        moment_x=base["moment_x"],
        moment_y=base["moment_y"],
        torque=base["torque"],
        moment=moment,
        stress=moment * (outer / 2) / second + axial / area,
        modes=k,
    )
