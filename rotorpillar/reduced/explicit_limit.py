"""How far an explicit adaptive integrator can step on a model: its stability limit.

An explicit method's error control cannot take it past the edge of its region
of absolute stability on the model's fastest eigenvalue, whatever its
tolerance (Hairer & Wanner, *Solving ODEs II*, IV.2).  A stiff shaft, a light
rotor on its shaft or a light rotor's spin under the motor's slope then sets
the step count, not the rotor's speed.  The counts here are lower bounds: a
run's budget refuses on them, so a run that would fit is never refused.

- ``first_order_rate``: the largest |eigenvalue| of M q'' + C q' + K q = 0 (1/s):
  a lightly damped mode's omega, an overdamped one's faster root (about c/m);
- ``spin_rate``: how fast the drive pulls the spin back to its speed (1/s);
- ``stability_step_count``: the fewest steps over a run (-).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigvals

from .drive import DriveSchedule

if TYPE_CHECKING:
    from .transient_model import TransientModel

#: The largest |h lambda| inside the method's region of absolute stability in the
#: left half-plane (-).  Dormand-Prince 5(4) (dp5, scipy's RK45): R(z) = sum z**k/k!
#: (k <= 5) + z**6/600; its largest radius with |R| <= 1, found numerically, is 3.40
#: (3.31 on the negative real axis).  Near the imaginary axis the region is far
#: thinner: on a lightly damped stiff mode dp5 takes about 20 times this bound
#: (tests/test_stability_budget.py measures it), on a real eigenvalue 1.03 times.
STABILITY_RADIUS = {"dp5": 3.40, "RK45": 3.40}


def first_order_rate(mass: NDArray[np.float64], stiffness: NDArray[np.float64], damping: NDArray[np.float64]) -> float:
    """The largest |lambda| of the first-order form of M q'' + C q' + K q = 0 (1/s)."""
    n = mass.shape[0]
    if n == 0:
        return 0.0
    Minv = np.linalg.inv(mass)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ stiffness, -Minv @ damping]])
    return float(np.max(np.abs(eigvals(A))))


def spin_rate(model: TransientModel, drive: DriveSchedule) -> float:
    """How fast the drive pulls the spin back to its speed (1/s): (s + 2 k Omega) / I, the
    motor's slope and the load's quadratic law at the drive's free speed, over the model's
    rotor inertia, the largest over the drive's knots.  Where a model adds the unbalance's
    m e**2 to I the true rate is lower by m e**2 / I (1e-6 on paper's rotor)."""
    inertia = model.rotor_inertia
    if not inertia > 0:
        return 0.0
    k = abs(drive.load_coefficient)
    rates = []
    for t, s in zip(drive.times, drive.slope):
        free = drive.free_speed(float(t))
        rates.append((abs(s) + 2 * k * (free if math.isfinite(free) else 0.0)) / inertia)
    return max(rates)


def stability_step_count(
    model: TransientModel, duration: float, method: str, drive: DriveSchedule | None = None
) -> float:
    """The fewest steps an explicit adaptive ``method`` can take over ``duration`` on
    ``model``: the faster of its fastest_rate and the drive's spin_rate over the method's
    STABILITY_RADIUS (-); 0 for a method without one (the implicit methods, LSODA, DOP853)."""
    radius = STABILITY_RADIUS.get(method)
    if radius is None:
        return 0.0
    rate = model.fastest_rate()
    if drive is not None:
        rate = max(rate, spin_rate(model, drive))
    return duration * rate / radius
