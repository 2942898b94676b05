"""The records of the spatial model's results in analyze.json: which planes, every direction's
resonances, the planar model's error, the drive's reaction (rotorpillar.reduced.spatial_scene
computes them; numpy-free to read)."""

from __future__ import annotations

from ..provenance import Record
from .campbell import CriticalSpeed
from .spatial_statics import DriveReaction


class PlanesChoice(Record):
    """Which directions the modal model keeps, and why."""

    requested: str
    """modal_model.planes: "auto", "planar" or "spatial" """
    planes: str
    """what is used: "planar" (the rotor's plane, today's ROM) or "spatial" """
    reason: str
    """why, in words"""


class SpatialResonance(Record):
    """A damped mode of the spatial model at rest, named."""

    label: str
    """its name: the kind that carries most of its kinetic energy and its rank among them"""
    kind: str
    """that kind (rotorpillar.reduced.spatial_modes.KINDS, "rotor on its shaft", ...)"""
    omega: float
    """damped natural frequency at rest (rad/s)"""
    damping_ratio: float
    """zeta (-)"""
    whirl_at_running_speed: str
    """its whirl at the running speed: forward, backward or none (a line)"""


class PlanarError(Record):
    """What the planar model misses: the spatial model's numbers against it."""

    planar_omega: tuple[float, ...]
    """the planar ROM's coupled resonances in the rotor's plane (rad/s)"""
    spatial_omega: tuple[float, ...]
    """the spatial model's nearest resonances moving the rotor's plane (rad/s)"""
    relative_difference: tuple[float, ...]
    """planar / spatial - 1 per resonance (-)"""
    peak_tip_planar: float
    """the planar model's largest unbalance response of the top in the rotor's plane over the band (m)"""
    peak_tip_spatial: float
    """the spatial model's (m)"""
    peak_tip_difference: float
    """planar / spatial - 1 (-)"""
    note: str


class SpatialAnalysis(Record):
    """analyze.json's ``spatial``: the machine in three dimensions, beside the planar ROM."""

    planes: PlanesChoice
    model: str
    """the spatial model, in words (modes, damping, tilt)"""
    mode_source: str
    """where its pillar modes come from"""
    running_speed: float | None
    """the speed the whirl is read at (rad/s)"""
    resonances: tuple[SpatialResonance, ...]
    """every direction's damped modes at rest, named"""
    critical_speeds: tuple[CriticalSpeed, ...]
    """where the 1x line crosses a mode (the undamped gyroscopic pencil)"""
    planar_error: PlanarError


class ReactionRunup(Record):
    """The run-up from rest on the spatial model, with the motor's reaction on the gondola and without."""

    duration: float
    """(s)"""
    final_speed: float
    """Omega at the end (rad/s)"""
    peak_tip_displacement: float
    """the largest |top in the rotor's plane| with the reaction (m)"""
    peak_tip_displacement_without: float
    """the same without it (m)"""
    peak_reaction_part: float
    """the largest |difference| the reaction makes to the top in the rotor's plane (m)"""
    peak_tip_rotation: float
    """the largest |roll of the top| with the reaction (rad)"""


class DriveReactionAnalysis(Record):
    """analyze.json's ``drive_reaction``: the stall torque on the gondola, statically and in the run-up."""

    torque: float
    """M0, the drive's stall torque (N*m)"""
    tip_displacement: float
    """the top's static displacement in the rotor's plane under it (m)"""
    tip_rotation: float
    """the top's static roll (rad)"""
    base_moment: float
    """the base's moment about the spin axis (N*m)"""
    statics: DriveReaction
    runup: ReactionRunup | None
    """the run-up's transient with the reaction acting; None when the drive never starts, or
    when the model's stiffest mode would make it too long a run for analyze (``runup_skipped``)"""
    runup_skipped: str | None = None
    """why there is no run-up although the drive starts (None: it ran, or nothing to run)"""
