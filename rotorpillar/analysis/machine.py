"""The machine's own checks on the headline ROM: balance grade, steady vibration, modal mass.

At the running speed Omega (where a quasi-static run-up settles with the
scene's drive), on the ROM `analyze` reports (the chain's pillar modes with
the rotor on its shaft):

- the unbalance as a balance quality grade G = e Omega beside the grade the
  machine type asks (``rotor.balance_grade``; ISO 21940-11);
- the steady unbalance response at Omega (``RotorStructure.steady_state``,
  the Bode curve's value at that speed): the shaft's orbit relative to the
  pillar's top (its bearing housing) against API 617's peak-to-peak limit,
  and the top's r.m.s. velocity in the rotor's plane against ISO 20816-3's
  zones (its group from the drive's power at Omega, its support from the
  lowest coupled mode against Omega);
- the effective modal masses along X (the rotor's plane, the only direction
  the planar model moves the pillar in): the coupled modes of the ROM
  (pillar, gondola and rotor), and how many pillar modes carry 90 % of the
  machine's mass as EN 1998-1 4.3.3.3.1 asks of a modal analysis for forces.
  The headline ROM keeps its band's modes; the ROM for forces (the
  transients' section forces) keeps as many more as the 90 % take.  When
  every computed mode carries less, that is warned of (``warnings``, and on
  stderr by the command).

rotorpillar.reduced.vibration_limits and .participation hold the formulas.
"""

from __future__ import annotations

import numpy as np

from ..records import Record
from ..reduced.participation import (
    EC8_MASS_FRACTION,
    EffectiveMassTable,
    effective_mass_table,
    mode_effective_masses,
    modes_for_fraction,
    pillar_mass_fractions,
)
from ..reduced.pillar_modes import PillarModes
from ..reduced.rotor_models import RotorStructure
from ..reduced.tower import tower_mass
from ..reduced.vibration_limits import (
    BalanceQuality,
    HousingVibration,
    ShaftVibration,
    balance_quality,
    housing_vibration,
    shaft_vibration,
)
from ..scene import Scene


class ForceRomModes(Record):
    """How many pillar modes a ROM for forces needs: 90 % of the machine's mass (EN 1998-1);
    the transients' section forces keep them (``internal_forces.mass`` of each modal run)."""

    required: float
    """the share of the mass the modes must carry, 0.90 (EN 1998-1 4.3.3.3.1(3)) (-)"""
    total_mass: float
    """the mass the base carries along X: tube, gondola and rotor (kg)"""
    cumulative: tuple[float, ...]
    """the share the ROM carries with its first k = 1, 2, ... pillar modes, the rotor
    (a coordinate of its own) always whole (-)"""
    modes_kept: int
    """the pillar modes of the headline ROM (-)"""
    fraction_kept: float
    """the share they carry (-)"""
    modes_needed: int | None
    """the fewest pillar modes that carry the required share (None: the modes available do not)"""
    modes_available: int
    """the pillar modes the chain computed (-)"""
    modes_for_forces: int
    """the pillar modes the ROM for forces keeps (the transients' section forces,
    rotorpillar.transients.forces): the headline's, or more to carry the required share,
    or all when they do not (-)"""
    fraction_for_forces: float
    """the share they carry (-)"""


class MachineChecks(Record):
    """analyze.json's ``machine`` block: the checks a machine on a pillar is signed off on."""

    running_speed: float | None
    """Omega, where a quasi-static run-up settles (rad/s); None: no stable speed"""
    balance: BalanceQuality | None
    """the unbalance as a balance grade (ISO 21940-11)"""
    shaft: ShaftVibration | None
    """the steady shaft orbit at Omega against API 617"""
    housing: HousingVibration | None
    """the top's steady r.m.s. velocity at Omega against ISO 20816-3"""
    coupled_modes: EffectiveMassTable
    """the ROM's coupled X modes (pillar, gondola and rotor) and their effective masses"""
    force_rom: ForceRomModes
    """the pillar modes a ROM for forces needs"""
    model: str
    """the ROM the numbers come from, in words"""
    warnings: tuple[str, ...]
    """what the checks warn of (the ROM for forces below 90 % of the mass with every mode computed)"""


def steady_orbit(model: RotorStructure, omega: float) -> tuple[complex, complex, complex]:
    """(tip X, shaft d_x, shaft d_y) complex amplitudes at constant ``omega`` (m): the
    unbalance response of ``rotorpillar.reduced.bode`` at that speed; d = rotor centre
    less the tip less e (cos theta, sin theta), so d_y = Re((Y + i e) e^{i theta})."""
    Z, Y = model.steady_state(omega)
    e = model.eccentricity
    return complex(model.tip @ Z), complex(model.shaft @ Z - e), complex(Y + 1j * e)


def coupled_effective_masses(model: RotorStructure) -> tuple[np.ndarray, np.ndarray]:
    """(omega, effective mass) of the ROM's undamped coupled X modes (rad/s, kg); the
    base acceleration's load is -base_acceleration (L_j on mode j, m_C on the rotor)."""
    omega, shapes = model.undamped_modes_x()
    return omega, mode_effective_masses(model.mass, shapes, -np.asarray(model.base_acceleration))


def machine_mass(scene: Scene) -> float:
    """What the base carries along X: the tube (the integral of its mass per length: a
    uniform tube's section times its height, a tower's cans each), the gondola and the
    rotor (kg).  Not a 1D beam's r^T M r (``PillarModes.total_mass`` there), which
    leaves out the clamped node's share, the mass no mode moves (1.6 % on 40 elements)."""
    p = scene.pillar
    return tower_mass(p) + scene.gondola.mass + scene.rotor.mass


def force_rom_modes(candidates: PillarModes, rotor_mass: float, kept: int, total: float) -> ForceRomModes:
    """The share of ``total`` (kg) along X each count of pillar modes carries, the rotor whole."""
    cum = pillar_mass_fractions(candidates.participation, candidates.modal_mass, rotor_mass, total)
    needed = modes_for_fraction(cum, EC8_MASS_FRACTION)
    k_forces = min(max(int(kept), needed or candidates.count), candidates.count)
    return ForceRomModes(
        EC8_MASS_FRACTION,
        float(total),
        tuple(map(float, cum)),
        int(kept),
        float(cum[kept - 1]),
        needed,
        candidates.count,
        k_forces,
        float(cum[k_forces - 1]),
    )


def _mass_warning(f: ForceRomModes, source: str) -> list[str]:
    if f.fraction_for_forces >= f.required:
        return []
    return [
        f"the ROM for forces keeps all {f.modes_for_forces} pillar modes ({source}); they carry "
        f"{100 * f.fraction_for_forces:.1f} % of the machine's mass along X, below the "
        f"{100 * f.required:.0f} % EN 1998-1 4.3.3.3.1 asks of a modal analysis for forces: its base "
        "shear misses the rest; compute more (modal.n_modes)"
    ]


def machine_checks(
    scene: Scene, model: RotorStructure, candidates: PillarModes, running_speed: float | None
) -> MachineChecks:
    """The machine's checks on ``model`` (the headline ROM) at ``running_speed`` (rad/s)."""
    pm = model.pillar_modes
    if pm is None:
        raise ValueError("the machine checks read the modal ROM: it has no pillar modes")
    omega, me = coupled_effective_masses(model)
    total = machine_mass(scene)
    coupled = effective_mass_table(
        "X",
        omega,
        me,
        total,
        f"the ROM's coupled modes ({pm.count} pillar modes of {pm.source} and the rotor on its "
        "shaft) against the tube's, the gondola's and the rotor's mass",
    )
    force = force_rom_modes(candidates, model.rotor_mass, pm.count, total)
    balance = shaft = housing = None
    if running_speed is not None and running_speed > 0:
        w = float(running_speed)
        balance = balance_quality(scene.rotor.eccentricity, w, scene.rotor.balance_grade)
        tip, dx, dy = steady_orbit(model, w)
        shaft = shaft_vibration(w, dx, dy)
        d = scene.drive
        power = (d.torque_at_zero - d.slope * w) * w
        housing = housing_vibration(w, abs(tip), power, float(omega[0]))
    return MachineChecks(
        None if running_speed is None else float(running_speed),
        balance,
        shaft,
        housing,
        coupled,
        force,
        f"the headline ROM: {pm.count} pillar modes of {pm.source}, the rotor on its shaft",
        tuple(_mass_warning(force, pm.source)),
    )


def machine_text(m: MachineChecks | None) -> list[str]:
    """The lines `rotorpillar analyze` prints for the machine's checks."""
    if m is None:
        return []
    lines = [f"Machine checks ({m.model})"]
    b, s, h = m.balance, m.shaft, m.housing
    if b is None or s is None or h is None:
        lines.append("  balance and vibration: not assessed (no stable running speed with this drive)")
    else:
        lines += [
            f"  balance: G = e Omega = {b.grade:.4g} mm/s ({b.grade_class or 'beyond G 4000'}) at "
            f"{b.running_speed:.4g} rad/s; required G {b.required:g} (e_per = "
            f"{b.permissible_eccentricity * 1e6:.4g} um), {b.clause}",
            f"  shaft orbit at {s.speed_rpm:.4g} rpm: {s.peak_to_peak * 1e6:.4g} um peak-to-peak (X "
            f"{s.peak_to_peak_x * 1e6:.4g}, Y {s.peak_to_peak_y * 1e6:.4g}); limit "
            f"{s.limit * 1e6:.4g} um ({s.clause})",
            f"  top's velocity: {h.velocity_rms:.4g} mm/s r.m.s. in the rotor's plane, zone "
            f"{h.zone or '-'}; B/C boundary {h.limit if h.limit is not None else '-'} mm/s ({h.clause}; "
            f"power {h.power / 1e3:.4g} kW, lowest mode {h.first_frequency:.4g} rad/s)",
        ]
    f = m.force_rom
    lines.append(
        f"  effective mass along X: the headline ROM's {f.modes_kept} pillar mode(s) carry "
        f"{100 * f.fraction_kept:.1f} % of {f.total_mass:.5g} kg; the ROM for forces keeps "
        f"{f.modes_for_forces}: {100 * f.fraction_for_forces:.1f} % ("
        + (
            f"{f.modes_needed} carry {100 * f.required:.0f} %"
            if f.modes_needed is not None
            else f"the {f.modes_available} computed do not reach {100 * f.required:.0f} %"
        )
        + ", EN 1998-1 4.3.3.3.1)"
    )
    for r in m.coupled_modes.rows:
        lines.append(
            f"    mode {r.mode}: {r.omega:9.4g} rad/s  {r.effective_mass:10.5g} kg  {100 * r.fraction:5.1f} %  "
            f"cumulative {100 * r.cumulative:5.1f} %"
        )
    lines += [f"  warning: {w}" for w in m.warnings]
    return lines
