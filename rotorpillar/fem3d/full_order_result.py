"""The 3D full-order run's record: ``Fem3dTransient``, its energy balance and checks.

``transient_result`` turns what the step loop (rotorpillar.fem3d.full_order)
sampled into the record: the ground's displacement, E(t) - E(0) against the
work done, and the ``failed_checks`` (integrator stopped, energy balance
missed, the step's accuracy).  No dolfinx here: the record reads back from
JSON without the solver.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from ..reduced.integration import EnergyBalance

WORK_COLUMNS = ("drive_minus_load", "shaft_on_structure", "dissipated", "base")
#: the share of the energy exchanged the balance may miss (as transients.case_summary.ENERGY_CHECK)
ENERGY_CHECK = 0.05


@dataclass(frozen=True, eq=False)
class Fem3dTransient:
    """A 3D full-order run on its output grid, with its summary (SI)."""

    case: str
    t: np.ndarray
    """(n,) output times (s)"""
    Omega: np.ndarray
    """rotor speed (rad/s)"""
    theta: np.ndarray
    """rotor angle (rad)"""
    tip_x: np.ndarray
    """plate X relative to the ground = the top section's mean X (m)"""
    tip_x_absolute: np.ndarray
    """tip_x + ground_x (m)"""
    ground_x: np.ndarray
    """ground displacement, the double integral of the applied acceleration (m)"""
    ground_acceleration: np.ndarray
    """(m/s**2)"""
    rotor_x: np.ndarray
    """rotor mass centre X relative to the ground (m)"""
    rotor_y: np.ndarray
    """rotor mass centre along the tube axis (the paper's Y) (m)"""
    plate_z: np.ndarray
    """the plate's axial displacement (m)"""
    shaft_x: np.ndarray
    """shaft deflection in X, x_r - U_x - e cos(theta) (m)"""
    shaft_y: np.ndarray
    """shaft deflection in Y, y_r - U_z - e sin(theta) (m)"""
    drive_torque: np.ndarray
    """Md - Mc (N*m)"""
    energy: np.ndarray
    """kinetic + potential energy (J); without J Omega**2 / 2 at a prescribed speed"""
    work: np.ndarray
    """(n, 4) work since the start: drive - load, shaft on structure, dissipated, base (J)"""
    max_abs: dict
    """largest |value| over every step (m)"""
    omega_final: float
    omega_final_mean: float
    """mean speed over the last 5 % of the run (rad/s)"""
    energy_balance: EnergyBalance
    """E(t) - E(0) against the work done (J), as the reduced models' runs state it"""
    integrator: dict
    dofs: int
    """unknowns: the tube's (with inert constrained rows), the plate's 6, the rotor's 3"""
    wall_seconds: float
    """assembly, factorisation and integration (s)"""
    model: dict
    """mesh, damping law, start, forcing: what was run"""
    ok: bool
    failed_checks: list = field(default_factory=list)
    """why ``ok`` is false, one named line each (empty when every check holds)"""

    def summary(self) -> dict:
        """The JSON fields the reduced models' runs report, plus dofs and wall time."""
        out = {
            "ok": self.ok,
            "duration": float(self.t[-1] - self.t[0]),
            "omega_final": self.omega_final,
            "omega_final_mean": self.omega_final_mean,
            "max_abs": self.max_abs,
            "energy_balance": self.energy_balance,
            "integrator": self.integrator,
            "dofs": self.dofs,
            "wall_seconds": self.wall_seconds,
            "model": self.model,
        }
        if self.failed_checks:
            out["failed_checks"] = list(self.failed_checks)
        return out

    def series(self) -> dict:
        """The arrays, by name (for NPZ/CSV)."""
        return {f.name: getattr(self, f.name) for f in fields(self) if isinstance(getattr(self, f.name), np.ndarray)}

    def to_json(self) -> dict:
        """JSON-ready; ``from_json`` rebuilds it exactly."""
        return {
            f.name: (v.tolist() if isinstance(v, np.ndarray) else v.to_json() if isinstance(v, EnergyBalance) else v)
            for f in fields(self)
            for v in (getattr(self, f.name),)
        }

    @classmethod
    def from_json(cls, data: dict) -> Fem3dTransient:
        arrays = {f.name for f in fields(cls) if f.type == "np.ndarray"}
        kwargs: dict[str, Any] = {k: (np.asarray(v, dtype=float) if k in arrays else v) for k, v in data.items()}
        kwargs["energy_balance"] = EnergyBalance.from_json(data["energy_balance"])
        return cls(**kwargs)


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
    if stats["status"] != "ok":
        failed.insert(0, f"integrator_stopped: {stats['status']}")
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
