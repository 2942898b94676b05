"""The Campbell diagram's records: each mode's frequency, whirl and log decrement against speed.

campbell.json (`rotorpillar campbell`) is a ``CampbellDiagram``: per model
("modal", the spatial reduced model; "fem3d", the 3D model's), the speeds,
one ``CampbellBranch`` per mode tracked across them, and the critical
speeds, where the 1x line (the unbalance's frequency, Omega) crosses a
branch (``CriticalSpeed``).  The field names are issue 26's: ``modes``
(each ``label``, ``kind``, ``frequency[]``, ``whirl[]``,
``log_decrement[]``) and ``critical_speeds`` (each ``speed``, ``label``,
``whirl``, ``excited_by``).

Whirl: the direction the rotor centre's (or, for a mode that hardly moves
the rotor, the top's) orbit turns in the plane normal to the spin axis
(in the rotor's plane x, vertical z): "forward" with the spin, "backward"
against it, "none" where the orbit is a line (a mode that moves only one
direction, or none of the plane).

Computed by rotorpillar.reduced.campbell_analysis (the modal model) and
rotorpillar.fem3d (the 3D model); drawn by rotorpillar.postprocess.

>>> d = campbell_example()
>>> d.modes[0].label, d.critical_speeds[0].excited_by
('bending 1 backward', 'neither')
"""

from __future__ import annotations

import numpy as np

from ..provenance import Record
from .spatial_modes import Array

#: Whirl directions.
WHIRLS = ("forward", "backward", "none")
#: What excites a critical speed: the 1x unbalance force, the 1x unbalance moment, or neither.
EXCITERS = ("static unbalance", "couple unbalance", "neither")
#: The models a Campbell diagram is computed on.
CAMPBELL_MODELS = ("modal", "fem3d")


class CampbellBranch(Record, eq=False):
    """One mode tracked across the speeds."""

    label: str
    """its name, e.g. "bending 1 forward", "torsion 1", "ovalling n=2" """
    kind: str
    """what moves, in words (rotorpillar.reduced.spatial_modes.KINDS, or "rotor on its shaft",
    "rotor tilt")"""
    frequency: Array
    """(n,) damped natural frequency at each speed (rad/s)"""
    whirl: tuple[str, ...]
    """(n,) "forward", "backward" or "none" at each speed"""
    log_decrement: Array
    """(n,) logarithmic decrement delta = 2 pi zeta / sqrt(1 - zeta**2) at each speed (-)"""
    damping_ratio: Array | None = None
    """(n,) zeta = -Re(s) / |s| at each speed (-)"""


class CriticalSpeed(Record):
    """A speed where the 1x line crosses a branch: Omega = the branch's frequency."""

    speed: float
    """Omega at the crossing (rad/s)"""
    label: str
    """the branch crossed"""
    whirl: str
    """its whirl at the crossing"""
    excited_by: str
    """"static unbalance" (the branch's mode takes work from the rotating force m_C e
    Omega**2: a forward whirl of the rotor or the top in the plane normal to the spin axis),
    "couple unbalance" (from the rotating moment only) or "neither" (a backward or planar-
    less mode the unbalance does not drive)"""
    amplification_factor: float | None = None
    """AF of the unbalance response's peak there (API 684: Omega / half-power bandwidth) (-);
    None where the response shows no peak"""
    method: str = ""
    """how the crossing was found, in words"""


class CampbellDiagram(Record, eq=False):
    """campbell.json: the modes' frequencies against speed and the critical speeds."""

    model: str
    """"modal" (the spatial reduced model) or "fem3d" (the 3D model)"""
    speeds: Array
    """(n,) rotor speeds Omega (rad/s)"""
    modes: tuple[CampbellBranch, ...]
    """one branch per mode, ascending at the first speed"""
    critical_speeds: tuple[CriticalSpeed, ...]
    """where Omega equals a branch's frequency, ascending"""
    running_speed: float | None
    """the running speed the API 684 bands are drawn around (rad/s); None when the drive has none"""
    description: str = ""
    """the model, in words"""
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    fem3d: CampbellDiagram | None = None
    """the 3D model's diagram beside this one (``rotorpillar campbell --model both``, the run's
    campbell stage); None otherwise"""
    differences: tuple[CriticalSpeedDifference, ...] = ()
    """each of this diagram's critical speeds against the 3D one's nearest of the same exciter
    (with ``fem3d`` only)"""


class CriticalSpeedDifference(Record):
    """One critical speed of the ROM against the 3D model's nearest one excited the same way."""

    label: str
    """the ROM's branch"""
    excited_by: str
    """what excites both (CriticalSpeed.excited_by)"""
    modal: float
    """the ROM's critical speed (rad/s)"""
    fem3d: float | None
    """the 3D model's nearest critical speed of the same exciter (rad/s); None: it has none"""
    fem3d_label: str | None
    """its branch"""
    relative: float | None
    """(modal - fem3d) / fem3d (-)"""


def critical_speed_differences(modal: CampbellDiagram, fem3d: CampbellDiagram) -> tuple[CriticalSpeedDifference, ...]:
    """Each of ``modal``'s critical speeds against ``fem3d``'s nearest one with the same
    ``excited_by`` (the labels differ between the models: the 3D names a branch's whirl).

    >>> d = campbell_example()
    >>> [round(x.relative, 3) for x in critical_speed_differences(d, d)]
    [0.0, 0.0]
    """
    out = []
    for c in modal.critical_speeds:
        same = [r for r in fem3d.critical_speeds if r.excited_by == c.excited_by]
        near = min(same, key=lambda r: abs(r.speed - c.speed), default=None)
        out.append(
            CriticalSpeedDifference(
                c.label,
                c.excited_by,
                c.speed,
                None if near is None else near.speed,
                None if near is None else near.label,
                None if near is None else (c.speed - near.speed) / near.speed,
            )
        )
    return tuple(out)


def first_critical(d: CampbellDiagram, whirl: str) -> CriticalSpeed | None:
    """The lowest critical speed whirling ``whirl`` ("forward", "backward"), or None.

    >>> first_critical(campbell_example(), "forward").speed.__round__(2)
    31.58
    """
    return min((c for c in d.critical_speeds if c.whirl == whirl), key=lambda c: c.speed, default=None)


def log_decrement(damping_ratio: Array) -> Array:
    """delta = 2 pi zeta / sqrt(1 - zeta**2) (-); infinite at and past critical damping.

    >>> float(log_decrement(np.array([0.0019]))[0]).__round__(4)
    0.0119
    """
    z = np.asarray(damping_ratio, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out: Array = np.where(z < 1, 2 * np.pi * z / np.sqrt(np.maximum(1 - z * z, 0.0)), np.inf)
    return out


def campbell_example() -> CampbellDiagram:
    """A made-up two-branch diagram (for doctests and the chart's test)."""
    speeds = np.linspace(0.0, 100.0, 5)
    zeta = np.full(5, 0.01)
    return CampbellDiagram(
        model="modal",
        speeds=speeds,
        modes=(
            CampbellBranch("bending 1 backward", "bending", 30 - 0.05 * speeds, ("backward",) * 5, log_decrement(zeta)),
            CampbellBranch("bending 1 forward", "bending", 30 + 0.05 * speeds, ("forward",) * 5, log_decrement(zeta)),
        ),
        critical_speeds=(
            CriticalSpeed(30 / 1.05, "bending 1 backward", "backward", "neither"),
            CriticalSpeed(30 / 0.95, "bending 1 forward", "forward", "static unbalance"),
        ),
        running_speed=80.0,
    )
