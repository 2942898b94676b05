"""The 3D full-order run's record: ``Fem3dTransient``, its energy balance and checks.

``transient_result`` turns what the step loop (rotorpillar.fem3d.full_order)
sampled into the record: the ground's displacement, E(t) - E(0) against the
work done, and the ``failed_checks`` (integrator stopped, energy balance
missed, the step's accuracy).  No dolfinx here: the record reads back from
JSON without the solver.
"""

from __future__ import annotations

import msgspec
import numpy as np

from ..records import Array, Record
from ..reduced.integration import EnergyBalance, IntegratorStats
from ..scene import Mesh
from .full_order_plan import RunEstimate

WORK_COLUMNS = ("drive_minus_load", "shaft_on_structure", "dissipated", "base")
#: the share of the energy exchanged the balance may miss (as transients.case_summary.ENERGY_CHECK)
ENERGY_CHECK = 0.05


class Fem3dStats(IntegratorStats, kw_only=True, omit_defaults=True):
    """What the 3D step loop did (the ``integrator`` of a fem3d run)."""

    factorisations: int
    """factorisations of the step operator (-)"""
    solves: int
    """linear solves (-)"""
    newton_max: int
    """the most Newton iterations of the rotor's scalar step in one step (-)"""
    factorisation_seconds: float
    """(s)"""
    integration_seconds: float
    """the step loop (s)"""
    seconds_per_step: float
    """(s)"""
    output_stride: int
    """steps between outputs (-)"""
    estimate: RunEstimate | None = None
    """the run's size as estimated before it started"""
    assembly_seconds: float | None = None
    """assembling the 3D model (s)"""


class Fem3dDescription(Record, omit_defaults=True):
    """What a 3D full-order run ran: its mesh, top, damping, frame, forcing and start."""

    mesh: Mesh
    """the [mesh] section"""
    top: str
    damping_law: str
    frame: str
    """the frame of the tube's displacements: "relative_to_ground\""""
    forcing: str
    """how the ground motion enters, in words"""
    start: str
    """the initial state, in words"""
    initial_speed: float
    """(rad/s)"""
    initial_angle: float
    """the rotor's angle at the start (rad)"""
    prescribed_speed: bool
    """the rotor's speed held, not integrated"""
    initial_speed_source: str | None = None
    """where the initial speed comes from, in words"""


class Fem3dTransient(Record, eq=False):  # arrays: no elementwise ==
    """A 3D full-order run on its output grid, with its summary (SI)."""

    case: str
    t: Array
    """(n,) output times (s)"""
    Omega: Array
    """rotor speed (rad/s)"""
    theta: Array
    """rotor angle (rad)"""
    tip_x: Array
    """plate X relative to the ground = the top section's mean X (m)"""
    tip_x_absolute: Array
    """tip_x + ground_x (m)"""
    ground_x: Array
    """ground displacement, the double integral of the applied acceleration (m)"""
    ground_acceleration: Array
    """(m/s**2)"""
    rotor_x: Array
    """rotor mass centre X relative to the ground (m)"""
    rotor_y: Array
    """rotor mass centre along the tube axis (the paper's Y) (m)"""
    plate_z: Array
    """the plate's axial displacement (m)"""
    shaft_x: Array
    """shaft deflection in X, x_r - U_x - e cos(theta) (m)"""
    shaft_y: Array
    """shaft deflection in Y, y_r - U_z - e sin(theta) (m)"""
    drive_torque: Array
    """Md - Mc (N*m)"""
    energy: Array
    """kinetic + potential energy (J); without J Omega**2 / 2 at a prescribed speed"""
    work: Array
    """(n, 4) work since the start: drive - load, shaft on structure, dissipated, base (J)"""
    max_abs: dict[str, float]
    """largest |value| over every step (m)"""
    omega_final: float
    """rotor speed at the end (rad/s)"""
    omega_final_mean: float
    """mean speed over the last 5 % of the run (rad/s)"""
    energy_balance: EnergyBalance
    """E(t) - E(0) against the work done (J), as the reduced models' runs state it"""
    integrator: Fem3dStats
    """what the step loop did"""
    dofs: int
    """unknowns: the tube's (with inert constrained rows), the plate's 6, the rotor's 3"""
    wall_seconds: float
    """assembly, factorisation and integration (s)"""
    model: Fem3dDescription
    """mesh, damping law, start, forcing: what was run"""
    ok: bool
    """every check held"""
    failed_checks: list[str] = msgspec.field(default_factory=list)
    """why ``ok`` is false, one named line each (empty when every check holds)"""


def transient_result(case, out, stats, dofs, wall, info, motion, drive, prescribed, failed) -> Fem3dTransient:
    """The run's record from the loop's outputs: the ground's motion, the energy
    balance against the work done, and every failed check."""
    from .full_order_loop import ground_accelerations, ground_x_displacement

    t = out["t"]
    ground = ground_x_displacement(motion, t)
    W = out["Omega"]
    tail = t >= t[-1] - max(0.05 * (t[-1] - t[0]), 1e-9)
    E, work = out["energy"], out["work"]
    inflow = work[:, 1] if prescribed else work[:, 0]
    resid = (E - E[0]) - (inflow - work[:, 2] + work[:, 3])
    scale = max(
        np.max(np.abs(E - E[0])), np.max(np.abs(inflow)), np.max(np.abs(work[:, 2])), np.max(np.abs(work[:, 3])), 1e-300
    )
    balance = EnergyBalance(
        energy_change=float(E[-1] - E[0]),
        work_drive_minus_load=float(work[-1, 0]),
        work_shaft_on_structure=float(work[-1, 1]),
        dissipated=float(work[-1, 2]),
        work_base=float(work[-1, 3]),
        max_abs_residual=float(np.max(np.abs(resid))),
        scale=float(scale),
        relative_error=float(np.max(np.abs(resid)) / scale),
    )
    failed = list(failed)
    if stats.status != "ok":
        failed.insert(0, f"integrator_stopped: {stats.status}")
    e = balance.relative_error
    if not np.isfinite(e) or e > ENERGY_CHECK:
        failed.append(
            f"energy_balance: the energy balance misses by {100 * e:.3g} % of the energy "
            f"exchanged (limit {100 * ENERGY_CHECK:g} %)"
        )
    return Fem3dTransient(
        case=case,
        t=t,
        Omega=W,
        theta=out["theta"],
        tip_x=out["tip_x"],
        tip_x_absolute=out["tip_x"] + ground,
        ground_x=ground,
        ground_acceleration=ground_accelerations(motion, t)[0],
        rotor_x=out["rotor_x"],
        rotor_y=out["rotor_y"],
        plate_z=out["plate_z"],
        shaft_x=out["shaft_x"],
        shaft_y=out["shaft_y"],
        drive_torque=np.asarray(drive.torque(t, W), dtype=float),
        energy=E,
        work=work,
        max_abs=out["max_abs"],
        omega_final=float(W[-1]),
        omega_final_mean=float(np.mean(W[tail])),
        energy_balance=balance,
        integrator=stats,
        dofs=int(dofs),
        wall_seconds=float(wall),
        model=info,
        ok=not failed,
        failed_checks=failed,
    )
