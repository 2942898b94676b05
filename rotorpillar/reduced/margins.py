"""Separation margins between the running speeds and the structure's modes (API 684).

The criterion is the one of API Standard 684 (Tutorial on the API Standard
Paragraphs Covering Rotor Dynamics, 2nd ed., 2005), as API 617 (7th ed.,
2.6.2.10) states it for lateral critical speeds:

- amplification factor of a mode      AF = 1 / (2 zeta)
  (the half-power estimate N_c / (N_2 - N_1) of a lightly damped mode);
- a mode with AF < 2.5 is critically damped: no margin is required;
- otherwise the separation margin required, in % of the running speed,
  below it:  SM = 17 (1 - 1 / (AF - 1.5)),
  above it:  SM = 10 + 17 (1 - 1 / (AF - 1.5));
- the actual margin is |N_mode - N_run| / N_run.

An undamped mode (zeta = 0, as the 3D model leaves the modes its
dashpot does not move: ovalling, torsion, the bending normal to the rotor's
plane) has AF infinite: the full 17 % below and 27 % above apply, the
most a mode can require.  Steel's own damping (zeta ~ 0.2-0.5 %) gives AF >
100 and the same margins to within 0.2 %: leaving it out costs nothing here.

>>> round(required_margin(amplification_factor(0.05), below=True), 4)
0.15
>>> round(required_margin(amplification_factor(0.05), below=False), 4)
0.25
>>> required_margin(amplification_factor(0.25), below=True)
0.0
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from ..records import Record

#: AF below which a mode is critically damped and needs no margin (API 684)
AF_CRITICALLY_DAMPED = 2.5
#: the margins' constants (API 684), as fractions of the running speed
SM_BELOW, SM_ABOVE_EXTRA = 0.17, 0.10


def amplification_factor(damping_ratio: float) -> float:
    """AF = 1 / (2 zeta) (-); infinite for an undamped mode."""
    return math.inf if damping_ratio <= 0 else 1.0 / (2.0 * damping_ratio)


def required_margin(af: float, below: bool) -> float:
    """API 684's separation margin (a fraction of the running speed, -): 0 when
    AF < 2.5, else 0.17 (1 - 1/(AF - 1.5)) for a mode below the running speed and
    0.10 more for one above."""
    if af < AF_CRITICALLY_DAMPED:
        return 0.0
    base = SM_BELOW * (1.0 - (0.0 if math.isinf(af) else 1.0 / (af - 1.5)))
    return base if below else SM_ABOVE_EXTRA + base


def actual_margin(running_speed: float, mode_frequency: float) -> float:
    """|omega_mode - Omega_run| / Omega_run (-)."""
    return abs(mode_frequency - running_speed) / running_speed


class ModeEntry(Record):
    """One structural mode a running speed is checked against."""

    omega: float
    """natural (undamped) angular frequency (rad/s)"""
    damping_ratio: float
    """zeta (-); 0 where the model leaves the mode undamped"""
    kind: str
    """e.g. "coupled X 1" (the ROM), "bending_x", "ovalling n=2", "torsion" (3D)"""
    model: str
    """"modal" (the ROM's coupled system) or "fem3d" (the loaded tube's modes)"""
    note: str = ""
    """where the damping comes from"""


class SeparationRow(Record):
    """A running speed against one mode (API 684)."""

    running_speed: float
    """Omega_run (rad/s)"""
    mode: ModeEntry
    amplification_factor: float | None
    """AF (-); None for an undamped mode (infinite)"""
    position: str
    """"below" or "above" the running speed"""
    required: float
    """required margin, a fraction of the running speed (-)"""
    actual: float
    """actual margin, a fraction of the running speed (-)"""
    status: str
    """"pass" (actual >= required) or "fail\""""


def separation(running_speed: float, mode: ModeEntry) -> SeparationRow:
    """One running speed against one mode."""
    af = amplification_factor(mode.damping_ratio)
    below = mode.omega < running_speed
    req = required_margin(af, below)
    act = actual_margin(running_speed, mode.omega)
    return SeparationRow(
        float(running_speed),
        mode,
        None if math.isinf(af) else float(af),
        "below" if below else "above",
        float(req),
        float(act),
        "pass" if act >= req else "fail",
    )


def separation_table(
    running_speeds: Iterable[float], modes: Iterable[ModeEntry], band_top: float | None = None
) -> tuple[SeparationRow, ...]:
    """Every running speed against every mode (up to ``band_top``, rad/s, when given)."""
    return tuple(separation(w, m) for w in running_speeds for m in modes if band_top is None or m.omega <= band_top)
