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

API 684 reads the AF off the unbalance response: N_c / (N_2 - N_1), the
half-power bandwidth of the response's peak at the critical speed N_c
(``separation_from_response``, the peaks from
rotorpillar.reduced.spatial_response).  A mode that shows no peak in the
response (the unbalance does not drive it: an ovalling mode the rigid top
plate hardly moves, a backward whirl) is, in API 684's terms, critically
damped: no margin is required, and the table says so.  ``separation``
keeps the modal estimate AF = 1 / (2 zeta) for a mode without a response
to read (zeta = 0 gives AF infinite: 17 % below and 27 % above).

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

from ..provenance import Record

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
    af_source: str = ""
    """where the AF comes from: the half-power bandwidth of a response peak (which curve,
    where), 1 / (2 zeta) of the mode, or no peak in the response (no margin required)"""
    peak_speed: float | None = None
    """the speed of the response peak the AF was read from (rad/s); None: no peak"""


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
        "1 / (2 zeta) of the mode's damping ratio",
    )


def separation_from_response(
    running_speed: float, mode: ModeEntry, af: float | None, peak_speed: float | None, where: str
) -> SeparationRow:
    """One running speed against one mode, the AF read off the unbalance response's peak near
    the mode (``af`` at ``peak_speed``, rad/s, on the curve ``where``); ``af`` None: the response
    shows no peak there, so no margin is required (API 684).  The actual margin is measured from
    the peak's speed where there is one, else from the mode's frequency.

    >>> r = separation_from_response(100.0, ModeEntry(105.3, 0.0, "ovalling n=2", "fem3d"), None, None, "")
    >>> r.required, r.status, r.af_source
    (0.0, 'pass', 'no peak in the unbalance response near the mode: no margin required (API 684)')
    """
    at = mode.omega if peak_speed is None else peak_speed
    below = at < running_speed
    req = 0.0 if af is None else required_margin(af, below)
    act = actual_margin(running_speed, at)
    source = (
        "no peak in the unbalance response near the mode: no margin required (API 684)"
        if af is None
        else f"half-power bandwidth of the unbalance response's peak at {peak_speed:.4g} rad/s ({where})"
    )
    return SeparationRow(
        float(running_speed),
        mode,
        None if af is None or math.isinf(af) else float(af),
        "below" if below else "above",
        float(req),
        float(act),
        "pass" if act >= req else "fail",
        source,
        None if peak_speed is None else float(peak_speed),
    )


def separation_table(
    running_speeds: Iterable[float], modes: Iterable[ModeEntry], band_top: float | None = None
) -> tuple[SeparationRow, ...]:
    """Every running speed against every mode (up to ``band_top``, rad/s, when given)."""
    return tuple(separation(w, m) for w in running_speeds for m in modes if band_top is None or m.omega <= band_top)


# --------------------------------------------------------------------------
# Excitation orders: 1P and the blade-passing order (a wind turbine's 3P)

#: what the first tower mode's place among the orders is called (wind-turbine usage)
REGIMES = ("stiff-stiff", "soft-stiff", "soft-soft", "resonant")


class OrderMargin(Record):
    """A tower mode against one excitation order at one running speed."""

    running_speed: float
    """Omega_run (rad/s)"""
    order: int
    """the order: 1 (1P, the unbalance) or the blades' count (the blade passing) (-)"""
    excitation: float
    """order x Omega_run (rad/s)"""
    mode: ModeEntry
    position: str
    """the mode "below" or "above" the excitation"""
    required: float
    """the scene's rotor.order_margin (-)"""
    actual: float
    """|omega_mode - excitation| / excitation (-)"""
    status: str
    """"pass" (actual >= required) or "fail\""""


class ExcitationOrders(Record):
    """The first tower mode against 1P and the blade-passing order, the Campbell diagram's data."""

    orders: tuple[int, ...]
    """the excitation orders (1, and the blades' count when there are blades) (-); on a
    Campbell diagram each is a line omega = order x Omega"""
    margin: float
    """the separation required from each (rotor.order_margin) (-)"""
    first_mode: ModeEntry
    """the first tower mode in the rotor's plane"""
    regime: str
    """where it lies at the highest running speed: "soft-stiff" (above 1P, below the blade
    passing), "stiff-stiff" (above both), "soft-soft" (below 1P), "resonant" (within a margin of one)"""
    rows: tuple[OrderMargin, ...]
    """every running speed against every order"""
    status: str
    """"pass" when every row passes, else "fail\""""


def order_margins(
    running_speeds: Iterable[float], first_mode: ModeEntry, blades: int, margin: float
) -> ExcitationOrders:
    """The first tower mode's separation from 1P and from the blade-passing order.

    >>> m = ModeEntry(2.03, 0.01, "coupled X 1", "modal")
    >>> r = order_margins([1.2671], m, 3, 0.10)
    >>> r.regime, r.status, [round(x.actual, 3) for x in r.rows]
    ('soft-stiff', 'pass', [0.602, 0.466])
    """
    orders = (1,) if blades <= 1 else (1, blades)
    rows = []
    for w in running_speeds:
        for k in orders:
            f = k * w
            act = actual_margin(f, first_mode.omega)
            rows.append(
                OrderMargin(
                    float(w),
                    k,
                    float(f),
                    first_mode,
                    "below" if first_mode.omega < f else "above",
                    float(margin),
                    float(act),
                    "pass" if act >= margin else "fail",
                )
            )
    top = max(running_speeds, default=0.0)
    w1 = first_mode.omega
    if any(r.status == "fail" and r.running_speed == top for r in rows):
        regime = "resonant"
    elif w1 < top:
        regime = "soft-soft"
    elif w1 < orders[-1] * top:
        regime = "soft-stiff"
    else:
        regime = "stiff-stiff"
    return ExcitationOrders(
        orders,
        float(margin),
        first_mode,
        regime,
        tuple(rows),
        "pass" if all(r.status == "pass" for r in rows) else "fail",
    )
