"""summary.json's machine checks: balance grade, vibration at speed, modal mass, foundation loads.

Read from what the stages wrote (``verdict.summary`` collects them):

- analyze.json's ``machine_checks`` block (rotorpillar.analysis.machine, on the
  headline ROM at the running speed): the balance grade against
  ``rotor.balance_grade`` (ISO 21940-11), the shaft's steady peak-to-peak
  against API 617, the top's r.m.s. velocity against ISO 20816-3's B/C
  boundary, and the share of the machine's mass the ROM for forces' modes
  carry against EN 1998-1's 90 % (demand = the share required, capacity =
  the share there is, as the separation margins read);
- each modal run's section forces: the share their modes carry (the
  transients' force ROM may keep more modes than the run: its
  ``internal_forces.modes``, the share its ``internal_forces.mass``);
- modal.json's loaded-tube modes (3D): the effective masses along x, y, z;
- each run's ``internal_forces.design``: the foundation's design reactions
  (no capacity: they are the foundation designer's loads, not a check).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..analysis.machine import MachineChecks
    from ..fem3d.modal_summary import ModalSummary
    from ..scene import Scene

import numpy as np

from ..records import Record
from ..reduced.capacity import Check, check
from ..reduced.participation import EffectiveMassTable, effective_mass_table
from ..reduced.reactions import DesignReactions
from ..reduced.tower import tower_mass

MASS_CHECK = "effective modal mass (EN 1998-1)"


class FoundationLoads(Record):
    """One run's design reactions at the pillar's base (rotorpillar.reduced.reactions)."""

    model: str
    """the model, e.g. "modal" (ROM), "beam", "fem3d\""""
    case: str
    """the case as a reader names it, e.g. "earthquake (elcentro)\""""
    source: str
    """the file and field"""
    reactions: DesignReactions


def machine_check_rows(m: MachineChecks) -> list[Check]:
    """The checks of analyze.json's ``machine_checks`` block."""
    out = []
    speed = None if m.running_speed is None else f"running at {m.running_speed:.4g} rad/s"
    b, s, h = m.balance, m.shaft, m.housing
    out.append(
        check(
            "balance grade (ISO 21940-11)",
            "balance_grade",
            "mm/s",
            None if b is None else b.grade,
            None if b is None else b.required,
            "modal",
            speed,
            "analyze.json: machine_checks.balance; G = e Omega (rotor.eccentricity at the running speed) "
            "against rotor.balance_grade"
            + ("" if b is None else f" ({b.grade_class or 'beyond G 4000'} against G {b.required:g}; {b.clause})"),
        )
    )
    out.append(
        check(
            "shaft vibration (API 617)",
            "shaft_peak_to_peak",
            "m",
            None if s is None else s.peak_to_peak,
            None if s is None else s.limit,
            "modal",
            speed,
            "analyze.json: machine_checks.shaft; the steady unbalance response's shaft orbit relative to the "
            "pillar's top, peak-to-peak along its major axis"
            + ("" if s is None else f", at {s.speed_rpm:.4g} rpm; {s.clause}"),
        )
    )
    out.append(
        check(
            "housing vibration (ISO 20816-3)",
            "housing_velocity_rms",
            "mm/s",
            None if h is None else h.velocity_rms,
            None if h is None else h.limit,
            "modal",
            speed,
            "analyze.json: machine_checks.housing; the pillar top's steady r.m.s. velocity in the rotor's plane "
            "against the zone B/C boundary" + ("" if h is None else f" (zone {h.zone or '-'}; {h.clause})"),
        )
    )
    f = m.force_rom
    out.append(
        check(
            MASS_CHECK,
            "effective_mass_fraction",
            "-",
            f.required,
            f.fraction_for_forces,
            "modal",
            "analyze: the ROM for forces",
            f"analyze.json: machine_checks.force_rom; {f.modes_for_forces} pillar mode(s) and the rotor carry "
            f"{100 * f.fraction_for_forces:.1f} % of {f.total_mass:.5g} kg along X (the headline ROM's "
            f"{f.modes_kept}: {100 * f.fraction_kept:.1f} %); demand = the share EN 1998-1 4.3.3.3.1 "
            "requires, capacity = the share there is; "
            + (f"{f.modes_needed} mode(s) reach it" if f.modes_needed else "the modes computed do not reach it"),
        )
    )
    return out


def run_mass_rows(m: MachineChecks, runs: list) -> list[Check]:
    """The share of the mass each modal run's section forces keep (their modes); ``runs``:
    ``verdict.summary.RunFile``s (not imported here: summary imports this module)."""
    out = []
    f = m.force_rom
    for rf in runs:
        forces = rf.run.internal_forces
        if rf.run.model != "modal" or forces is None or forces.modes is None:
            continue
        own = forces.mass
        k = min(forces.modes, len(f.cumulative))
        out.append(
            check(
                MASS_CHECK,
                "effective_mass_fraction",
                "-",
                f.required,
                f.cumulative[k - 1] if own is None else own.fraction,
                "modal",
                rf.label,
                f"{rf.file}: internal_forces.modes = {forces.modes}, their share of the mass from "
                + ("analyze.json's machine_checks.force_rom" if own is None else f"internal_forces.mass ({own.reason})")
                + "; demand = the share required, capacity = the share kept",
            )
        )
    return out


def foundation_loads(runs: list) -> list[FoundationLoads]:
    """Each run's design reactions, where its transient computed them (``runs`` as above)."""
    return [
        FoundationLoads(rf.run.model, rf.label, f"{rf.file}: internal_forces.design", rf.run.internal_forces.design)
        for rf in runs
        if rf.run.internal_forces is not None and rf.run.internal_forces.design is not None
    ]


def tube_effective_masses(scene: Scene, modal: ModalSummary) -> tuple[EffectiveMassTable, ...]:
    """The loaded tube's 3D modes (modal.json) along x, y and z: its own and its top's mass."""
    rows = [r for r in modal.modes_with_top if r.effective_mass is not None]
    if not rows:
        return ()
    p = scene.pillar
    total = tower_mass(p) + modal.top.mass  # a tower's cans integrated, a uniform tube's rho A H
    omega = np.array([r.omega for r in rows])
    me = np.array([r.effective_mass for r in rows], dtype=float)
    note = (
        f"the loaded tube's {len(rows)} 3D modes (modal.json, up to {omega.max():.4g} rad/s) against "
        f"the tube's and its top's ({modal.top.carries}) mass; the rotor is not on this model"
    )
    return tuple(effective_mass_table(d, omega, me[:, i], total, note) for i, d in enumerate("xyz"))
