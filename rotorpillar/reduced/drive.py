"""Motor and machine torques of a transient run, shared by every model.

The motor characteristic of the paper's Eq. 22, Md = M0 - s Omega, with M0
and s allowed to vary in time along a piecewise-linear schedule (a soft
start, a motor switched off, a weaker motor, a quasi-static sweep of M0),
and the machine's resistance Mc = k Omega |Omega| (= k Omega**2 for the
forward spin of Eq. 22; the sign keeps it a resistance if the rotor ever
turns backwards).

>>> d = DriveSchedule.constant(5100.0, 12.0, 0.5)
>>> float(d.torque(0.0, 10.0)), round(d.free_speed(), 3)
(4930.0, 89.705)
>>> off = DriveSchedule.switched(5100.0, 12.0, 0.5, at=1.0, torque_after=0.0, slope_after=0.0)
>>> off.table()[:, -1].tolist()
[1.0, 0.0, 0.0]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray


@dataclass(frozen=True)
class DriveSchedule:
    """Md(t, Omega) = M0(t) - s(t) Omega and Mc(Omega) = k Omega |Omega|.

    M0 and s are linear between the knots and held beyond them; a repeated
    knot time makes a switch.
    """

    times: tuple[float, ...]
    """knot times (s), non-decreasing"""
    torque_at_zero: tuple[float, ...]
    """M0 at each knot (N*m)"""
    slope: tuple[float, ...]
    """s at each knot (N*m*s)"""
    load_coefficient: float
    """k (N*m*s**2)"""

    def __post_init__(self) -> None:
        if not (len(self.times) == len(self.torque_at_zero) == len(self.slope) >= 1):
            raise ValueError("times, torque_at_zero and slope must have the same length >= 1")
        if any(b < a for a, b in zip(self.times, self.times[1:])):
            raise ValueError("schedule times must be non-decreasing")

    # ----------------------------------------------------------- builders
    @classmethod
    def constant(cls, torque_at_zero: float, slope: float, load_coefficient: float) -> DriveSchedule:
        return cls((0.0,), (float(torque_at_zero),), (float(slope),), float(load_coefficient))

    @classmethod
    def ramp(cls, torque_at_zero: float, slope: float, load_coefficient: float, ramp_time: float) -> DriveSchedule:
        """M0 rising linearly from 0 to its value over ``ramp_time`` (a soft start)."""
        if ramp_time <= 0:
            return cls.constant(torque_at_zero, slope, load_coefficient)
        return cls((0.0, float(ramp_time)), (0.0, float(torque_at_zero)), (float(slope),) * 2, float(load_coefficient))

    @classmethod
    def switched(
        cls,
        torque_at_zero: float,
        slope: float,
        load_coefficient: float,
        at: float,
        torque_after: float,
        slope_after: float,
    ) -> DriveSchedule:
        """The motor (M0, s) until ``at``, then (torque_after, slope_after):
        (0, 0) is the motor switched off, Md = 0."""
        return cls(
            (0.0, float(at), float(at)),
            (float(torque_at_zero),) * 2 + (float(torque_after),),
            (float(slope),) * 2 + (float(slope_after),),
            float(load_coefficient),
        )

    @classmethod
    def sweep(
        cls, slope: float, load_coefficient: float, torque_low: float, torque_high: float, rate: float, settle: float
    ) -> DriveSchedule:
        """M0 held at ``torque_low`` for ``settle``, raised at ``rate`` to
        ``torque_high``, held for ``settle``, lowered back at ``rate``."""
        ramp = (torque_high - torque_low) / rate
        t = (0.0, settle, settle + ramp, 2 * settle + ramp, 2 * settle + 2 * ramp)
        M0 = (torque_low, torque_low, torque_high, torque_high, torque_low)
        return cls(t, M0, (float(slope),) * 5, float(load_coefficient))

    # ----------------------------------------------------------- evaluation
    def table(self) -> NDArray[np.float64]:
        """(3, m): knot times, M0, s, as the compiled kernels take it."""
        return np.array([self.times, self.torque_at_zero, self.slope], dtype=float)

    def at(self, t: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(M0, s) at time(s) t."""
        t = np.asarray(t, dtype=float)
        ts = np.asarray(self.times)
        if len(ts) == 1:
            return np.full_like(t, self.torque_at_zero[0]), np.full_like(t, self.slope[0])
        # np.interp takes the right-hand value at a repeated knot, as the kernel does
        return (np.interp(t, ts, self.torque_at_zero), np.interp(t, ts, self.slope))

    def torque(self, t: ArrayLike, Omega: ArrayLike) -> NDArray[np.float64]:
        """Md - Mc at time t and speed Omega (N*m)."""
        M0, s = self.at(t)
        W = np.asarray(Omega, dtype=float)
        net: NDArray[np.float64] = M0 - s * W - self.load_coefficient * W * np.abs(W)
        return net

    def breakpoints(self) -> list[float]:
        """Times where dM0/dt or ds/dt jumps: integrators step onto them."""
        return sorted(
            set(float(t) for t in self.times[1:]) | ({float(self.times[0])} if len(self.times) > 1 else set())
        )

    def free_speed(self, t: float | None = None) -> float:
        """Speed where Md = Mc with no resonance, for M0, s at time t (default:
        the last knot) (rad/s)."""
        M0, s = (self.torque_at_zero[-1], self.slope[-1]) if t is None else map(float, self.at(t))
        k = self.load_coefficient
        if k > 0:
            return (-s + math.sqrt(s * s + 4 * k * M0)) / (2 * k)
        return M0 / s if s > 0 else math.inf

    def describe(self) -> dict[str, Any]:
        return {
            "times": list(self.times),
            "torque_at_zero": list(self.torque_at_zero),
            "slope": list(self.slope),
            "load_coefficient": self.load_coefficient,
            "law": "Md = M0(t) - s(t)*Omega, Mc = k*Omega*|Omega|, M0 and s linear between knots",
        }
