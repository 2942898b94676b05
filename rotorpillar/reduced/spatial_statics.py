"""The drive's reaction on the gondola, statically: what the motor's stall torque does to the pillar.

The motor turns the rotor with Md about the spin axis; the stator, fixed to
the gondola, takes -Md: a moment +Md about y (roll) on the pillar's top,
which bends it in the rotor's plane.  At stall (Omega = 0) Md = M0, the
drive's largest torque.  Statically the rotor on its shaft carries nothing
(its springs have no other support), so the top's response is the pillar's
own under a moment at its top:

    u_top = F_top (0, 0, 0, 0, M0, 0),

F_top the pillar's static flexibility at the top (SpatialPillarModes.
top_compliance: exact for the beam source), else the modal sum
sum_j top_j top_j^T / k_j over the modes given (a truncation: said so).
The base moment is M0 about y (a couple passes down the pillar unchanged), its
bending stress M0 (D0 / 2) / I.  For a uniform cantilever the closed form is
u = M0 H**2 / (2 E I), theta = M0 H / (E I) (pure bending: no shear, the same
for Timoshenko).

>>> from rotorpillar.scene import load_scene
>>> from rotorpillar.reduced.spatial_beam import beam_spatial_modes
>>> s = load_scene("paper")
>>> r = drive_reaction(beam_spatial_modes(s.pillar, s.gondola, 2), s.drive.torque_at_zero, s.pillar)
>>> round(r.tip_displacement / r.closed_form_tip_displacement, 9)
1.0
"""

from __future__ import annotations

import numpy as np

from ..provenance import Record
from ..scene import Pillar
from .spatial_modes import SpatialPillarModes
from .tower import section_at


class DriveReaction(Record):
    """analyze.json's ``drive_reaction``: the motor's stall torque reacting on the gondola."""

    torque: float
    """M0: the drive's stall torque, reacting on the gondola about the spin axis (roll) (N*m)"""
    tip_displacement: float
    """the top's static displacement in the rotor's plane (x) under it (m)"""
    tip_rotation: float
    """the top's static roll, about the spin axis (rad)"""
    base_moment: float
    """the base's bending moment about the spin axis (N*m)"""
    base_stress: float
    """the base's bending stress M (D0 / 2) / I (Pa)"""
    closed_form_tip_displacement: float
    """M0 H**2 / (2 E I) of the uniform cantilever (m)"""
    closed_form_tip_rotation: float
    """M0 H / (E I) (rad)"""
    method: str
    """"the pillar's static flexibility at the top" or "modal sum over k modes" """


def drive_reaction(modes: SpatialPillarModes, torque: float, pillar: Pillar) -> DriveReaction:
    """The static response of the pillar to the motor's reaction ``torque`` (N*m) at its top."""
    load = np.zeros(6)
    load[4] = torque
    if modes.top_compliance is not None:
        u = modes.top_compliance @ load
        method = "the pillar's static flexibility at the top (" + modes.source + ")"
    else:
        u = (modes.top.T / modes.modal_stiffness) @ (modes.top @ load)
        method = f"modal sum over the {modes.count} modes of {modes.source} (truncated: no static correction)"
    p = pillar
    base = section_at(p, 0.0)  # a tower's closed forms: the uniform tube of its base's section
    EI = p.youngs_modulus * base.second_moment
    return DriveReaction(
        torque=float(torque),
        tip_displacement=float(u[0]),
        tip_rotation=float(u[4]),
        base_moment=float(torque),
        base_stress=float(torque * (base.outer_diameter / 2) / base.second_moment),
        closed_form_tip_displacement=float(torque * p.height**2 / (2 * EI)),
        closed_form_tip_rotation=float(torque * p.height / EI),
        method=method,
    )
