"""Transient runs of a rotor-structure model with any of the integrators.

``simulate(model, drive, motion, t_end, ...)`` integrates from a given state
and returns a ``Transient``: the state on a uniform output grid, the
largest |q_i| inside each output interval (taken at every step, so peaks
are not lost to the decimation), the work integrals, and the integrator's
statistics.

Integrators (``INTEGRATORS``):

- ``dp5``: Dormand-Prince 5(4), compiled (rotorpillar.reduced.dp5), with
  scipy RK45's step control, theta wrapped into [0, 2 pi) so that the
  relative tolerance keeps the unbalance's phase;
- scipy's ``RK45``, ``DOP853``, ``Radau``, ``BDF``, ``LSODA`` on the compiled
  right-hand side (and its analytic Jacobian for the implicit ones);
- fixed-step structural schemes, compiled: ``newmark`` (average
  acceleration), ``hht`` (HHT-alpha, alpha = -0.1), ``generalized_alpha``
  (Chung-Hulbert, rho_inf = 0.8), ``central_difference`` (explicit).

Tolerances: rtol as given; atol per component = rtol times the component's
scale (displacements: the eccentricity or the quasi-static response to the
ground motion; velocities: that times the speed scale; theta: 1 rad; its
speed: the speed scale).

Many runs of one model in one compiled loop: rotorpillar.reduced.batch.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..provenance import Record
from ..scene import FIXED_STEP_INTEGRATORS, INTEGRATORS, SCIPY_METHODS
from . import kernels as K
from .accuracy import AccuracyCheck, StepRule
from .drive import DriveSchedule
from .excitation import NoMotionSizes
from .explicit_limit import stability_step_count
from .rhs import Floats, Packed
from .transient_model import G, M, Motion, TransientModel

#: What one integrator gives: t, q, v, work, peak, stats (Transient's fields).
#: An optional array argument (one value or one per run).
Arr = ArrayLike | None
_Run = tuple[Floats, Floats, Floats, Floats, Floats, dict[str, Any]]

FIXED_STEP = FIXED_STEP_INTEGRATORS
IMPLICIT = ("Radau", "BDF", "LSODA", "newmark", "hht", "generalized_alpha")
STATUS = {
    K.OK: "ok",
    K.MAX_STEPS: "too many steps",
    K.STEP_TOO_SMALL: "step size underflow",
    K.NOT_FINITE: "solution diverged (not finite)",
    K.NEWTON_FAILED: "Newton iterations failed",
}


class EnergyBalance(Record):
    """E(t) - E(0) against the work done over the run (J), and how well it closes."""

    energy_change: float
    """(J)"""
    work_drive_minus_load: float
    """(J)"""
    work_shaft_on_structure: float
    """(J)"""
    dissipated: float
    """(J)"""
    work_base: float
    """work of the ground motion (J)"""
    max_abs_residual: float
    """largest |energy change - work| over the run (J)"""
    scale: float
    """the energy exchanged the residual is measured against (J)"""
    relative_error: float
    """max_abs_residual / scale (-)"""


class IntegratorStats(Record, kw_only=True, omit_defaults=True):
    """What the integrator did on a run (a run's ``integrator``); a field a method does not
    report is absent."""

    method: str
    """one of INTEGRATORS"""
    status: str
    """"ok", or why it stopped"""
    steps: int
    """integration steps taken (-)"""
    nfev: int = 0
    """right-hand side evaluations (-; 0 and absent: not counted, the 3D step loop)"""
    njev: int | None = None
    """Jacobian evaluations, scipy's implicit methods (-)"""
    rejected: int | None = None
    """steps rejected by the error control, dp5 (-)"""
    smallest_step: float | None = None
    """the smallest step taken, dp5 (s)"""
    rtol: float | None = None
    """relative tolerance, adaptive methods (-)"""
    time_step: float | None = None
    """the step, fixed-step methods (s)"""
    newton_iterations: int | None = None
    """Newton iterations over the run, implicit fixed-step methods (-)"""
    scheme: dict[str, float] | str | None = None
    """the fixed-step scheme's parameters (alpha_m, alpha_f, beta, gamma), or in words"""
    wall_seconds: float = 0.0
    """the integration's wall time (s)"""
    implicit: bool | None = None
    """the method is implicit"""
    accuracy: AccuracyCheck | None = None
    """the step against what the run had to resolve"""
    step_rule: StepRule | None = None
    """the full order's step rule (beam, 3D)"""


@dataclass(frozen=True)
class Settings:
    """How to integrate."""

    method: str = "dp5"
    """one of INTEGRATORS"""
    rtol: float = 1e-7
    """relative tolerance of the adaptive methods (-)"""
    time_step: float = 0.0
    """step of the fixed-step methods, 0 = automatic (s)"""
    steps_per_period: float = 60.0
    """automatic fixed step: this many steps per period of the fastest of the
    rotor speed scale and the structure's modes in the band (-)"""
    samples: int = 20000
    """largest number of output samples (-)"""
    wrap_angle: bool = True
    """dp5: keep theta in [0, 2 pi) for the error control"""
    hht_alpha: float = -0.1
    """HHT-alpha's alpha in [-1/3, 0] (-)"""
    rho_inf: float = 0.8
    """generalized-alpha's spectral radius at infinite frequency (-)"""
    max_steps: int = 200_000_000
    """budget of steps: a run estimated above it is refused before it starts, and
    the adaptive integrator stops there (-)"""
    newton_tol: float = 1e-10


@dataclass(frozen=True, eq=False)
class Transient(Generic[M, G]):
    """A transient run: states on the output grid and what the integrator did."""

    model: M
    t: NDArray[np.float64]
    """(n_t,) output times (s)"""
    q: NDArray[np.float64]
    """(n_t, n) coordinates z, y, theta (m, m, rad)"""
    v: NDArray[np.float64]
    """(n_t, n) their rates"""
    work: NDArray[np.float64]
    """(n_t, 4) work since the start: drive - load, shaft on structure, dissipated, base (J)"""
    peak: NDArray[np.float64]
    """(n_t, n + 1) largest |q_i| (and, last, |tip X|) in the interval ending
    at each output, over every step (m); scipy methods: at the outputs only"""
    stats: IntegratorStats
    """what the integrator did"""
    prescribed_speed: bool = False
    drive: DriveSchedule | None = None
    motion: G | None = None

    @property
    def ok(self) -> bool:
        return self.stats.status == "ok"

    @property
    def Omega(self) -> NDArray[np.float64]:
        return self.v[:, -1]

    def tip(self) -> NDArray[np.float64]:
        return self.q[:, : self.model.nx] @ self.model.tip

    def energy_balance(self) -> EnergyBalance:
        """E(t) - E(0) against the work done, and the relative error.

        Free rotor: d(T + P)/dt = (Md - Mc) W - dissipation + base power.
        Prescribed speed: the structure's energy (without the rotor's kinetic
        energy) changes by the shaft's work on it - dissipation + base power.
        """
        T, P = self.model.energy(self.q, self.v)
        if self.prescribed_speed:
            T = T - 0.5 * self.model.rotor_inertia * self.v[:, -1] ** 2
            inflow = self.work[:, 1]
        else:
            inflow = self.work[:, 0]
        E = T + P
        resid = (E - E[0]) - (inflow - self.work[:, 2] + self.work[:, 3])
        scale = max(
            np.max(np.abs(E - E[0])),
            np.max(np.abs(inflow)),
            np.max(np.abs(self.work[:, 2])),
            np.max(np.abs(self.work[:, 3])),
            1e-300,
        )
        return EnergyBalance(
            energy_change=float(E[-1] - E[0]),
            work_drive_minus_load=float(self.work[-1, 0]),
            work_shaft_on_structure=float(self.work[-1, 1]),
            dissipated=float(self.work[-1, 2]),
            work_base=float(self.work[-1, 3]),
            max_abs_residual=float(np.max(np.abs(resid))),
            scale=float(scale),
            relative_error=float(np.max(np.abs(resid)) / scale),
        )


def tolerances(model: TransientModel, motion: Motion, speed_scale: float, rtol: float) -> NDArray[np.float64]:
    """Absolute tolerances of (q, v, work): rtol times each component's scale."""
    n = model.n
    om = model.undamped_modes_x()[0]
    elastic = om[om > 1e-6 * max(float(om.max()), 1e-300)] if len(om) else om
    w_min = float(elastic.min()) if len(elastic) else 1.0  # rigid modes carry no scale
    g_scale = 0.0
    sizes = motion.sizes()
    if not isinstance(sizes, NoMotionSizes):
        g_scale = sizes.peak_acceleration / w_min**2
        if model.frame == "absolute":
            g_scale = max(g_scale, sizes.peak_displacement)
    xs = max(model.eccentricity, 1e-3 * g_scale, 1e-7)
    W = max(speed_scale, 1.0)
    atol = np.empty(2 * n + K.N_WORK)
    atol[: n - 1] = rtol * xs
    atol[n - 1] = rtol * 1.0
    atol[n : 2 * n - 1] = rtol * xs * max(W, w_min)
    atol[2 * n - 1] = rtol * W
    atol[2 * n :] = 1e300
    return atol


def _breaks(drive: DriveSchedule, motion: Motion) -> NDArray[np.float64]:
    return np.array(sorted(set(drive.breakpoints()) | set(motion.breakpoints())), dtype=float)


def auto_time_step(model: TransientModel, speed_scale: float, settings: Settings, motion: Motion) -> float:
    """Fixed step resolving the fastest of the rotor and the structure's modes
    below the band (steps_per_period each), and the record's sampling."""
    fast = max(speed_scale, model.stiffest_frequency(), motion.band(), 1e-3)
    h = 2 * math.pi / fast / settings.steps_per_period
    if motion.kind == "record":
        h = min(h, motion.time_step)
    return h


def check_simulation(
    model: TransientModel,
    drive: DriveSchedule,
    motion: Motion,
    t_end: float,
    v0: Arr = None,
    settings: Settings = Settings(),
    t_start: float = 0.0,
    speed_scale: float | None = None,
) -> float:
    """What :func:`simulate` refuses before it integrates, given the same arguments: a bad
    interval or method (ValueError), a run over its step budget (InputError, one line).
    Returns the speed scale the run integrates at (rad/s): ``speed_scale``, or from the
    start's speed and the drive's free speed.  Nothing is integrated: a command calls it
    to refuse a run before any work."""
    if not (math.isfinite(t_end) and t_end > t_start):
        raise ValueError(f"t_end = {t_end!r} must be finite and > t_start = {t_start!r}")
    if settings.method not in INTEGRATORS:
        raise ValueError(f"method must be one of {INTEGRATORS}")
    v0 = np.zeros(model.n) if v0 is None else np.asarray(v0, dtype=float)
    if speed_scale is None:
        speed_scale = (
            max(abs(v0[-1]), drive.free_speed(), drive.free_speed(0.0))
            if math.isfinite(drive.free_speed())
            else max(abs(v0[-1]), 1.0)
        )
    check_step_budget(model, motion, t_end - t_start, settings, speed_scale, drive)
    return speed_scale


def simulate(
    model: M,
    drive: DriveSchedule,
    motion: G,
    t_end: float,
    q0: Arr = None,
    v0: Arr = None,
    settings: Settings = Settings(),
    t_start: float = 0.0,
    prescribed_speed: bool = False,
    speed_scale: float | None = None,
) -> Transient[M, G]:
    """Integrate the model from (q0, v0) at t_start to t_end; refused first as
    :func:`check_simulation` refuses it."""
    speed_scale = check_simulation(model, drive, motion, t_end, v0, settings, t_start, speed_scale)
    n = model.n
    q0 = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float)
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, dtype=float)
    P = model.pack(drive, motion, prescribed_speed)
    start = time.perf_counter()
    if settings.method == "dp5":
        out = _run_dp5(P, model, q0, v0, t_start, t_end, drive, motion, settings, speed_scale)
    elif settings.method in SCIPY_METHODS:
        out = _run_scipy(P, model, q0, v0, t_start, t_end, drive, motion, settings, speed_scale)
    else:
        out = _run_fixed(P, model, q0, v0, t_start, t_end, drive, motion, settings, speed_scale)
    t, q, v, w, peak, counts = out
    stats = IntegratorStats(
        method=settings.method,
        wall_seconds=time.perf_counter() - start,
        implicit=settings.method in IMPLICIT,
        **counts,
    )
    return Transient(model, t, q, v, w, peak, stats, prescribed_speed, drive, motion)


#: Adaptive steps per rotor revolution at least (dp5 at rtol 1e-7 takes 10-60):
#: the estimate is a lower bound, so no run that would fit its budget is refused.
STEPS_PER_REVOLUTION = 10.0


def estimated_step_count(
    model: TransientModel,
    motion: Motion,
    duration: float,
    settings: Settings,
    speed_scale: float,
    drive: DriveSchedule | None = None,
) -> float:
    """Integration steps a run will take, from its settings, before it starts (-).

    Fixed step: duration / h.  Adaptive: at least STEPS_PER_REVOLUTION per
    revolution at the speed scale, one per sample of a record, and for an
    explicit method (STABILITY_RADIUS) the fastest rate of the model and the
    drive's spin over the method's stability limit (stability_step_count).
    """
    if settings.method in FIXED_STEP:
        h = settings.time_step or auto_time_step(model, speed_scale, settings, motion)
        return duration / h
    n = STEPS_PER_REVOLUTION * max(speed_scale, 0.0) / (2 * math.pi) * duration
    if motion.kind == "record":
        n = max(n, duration / motion.time_step)
    return max(n, stability_step_count(model, duration, settings.method, drive))


def check_step_budget(
    model: TransientModel,
    motion: Motion,
    duration: float,
    settings: Settings,
    speed_scale: float,
    drive: DriveSchedule | None = None,
) -> None:
    """Refuse (one line, InputError) a run estimated above ``settings.max_steps``."""
    n = estimated_step_count(model, motion, duration, settings, speed_scale, drive)
    if not math.isfinite(n) or n > settings.max_steps:
        stiff = stability_step_count(model, duration, settings.method, drive)
        why = (
            f" (the model's fastest rate over {settings.method}'s stability limit: an implicit "
            "simulate.integrator is not bound by it)"
            if stiff >= n
            else ""
        )
        raise InputError(
            f"this run of {duration:.4g} s would take about {n:.3g} {settings.method} steps{why}, more "
            f"than simulate.max_steps = {settings.max_steps:.3g}: shorten it, coarsen the step, "
            "or raise simulate.max_steps"
        )


def _output_grid(t0: float, t1: float, samples: int) -> NDArray[np.float64]:
    return np.linspace(t0, t1, max(2, int(samples)))


def _run_dp5(
    P: Packed,
    model: TransientModel,
    q0: Floats,
    v0: Floats,
    t0: float,
    t1: float,
    drive: DriveSchedule,
    motion: Motion,
    settings: Settings,
    speed_scale: float,
) -> _Run:
    n = model.n
    y0 = np.concatenate([q0, v0, np.zeros(K.N_WORK)])
    t_out = _output_grid(t0, t1, settings.samples)
    out_y = np.zeros((len(t_out), len(y0)))
    out_peak = np.zeros((len(t_out), n + 1))
    atol = tolerances(model, motion, speed_scale, settings.rtol)
    h_max = motion.time_step if motion.kind == "record" else np.inf
    status, nfev, nacc, nrej, hmin = K.dp5_solve(
        P,
        y0,
        float(t0),
        float(t1),
        _breaks(drive, motion),
        settings.rtol,
        atol,
        t_out,
        settings.wrap_angle,
        settings.max_steps,
        out_y,
        out_peak,
        h_max,
    )
    stats = {
        "status": STATUS[status],
        "nfev": int(nfev),
        "steps": int(nacc),
        "rejected": int(nrej),
        "smallest_step": float(hmin),
        "rtol": settings.rtol,
    }
    return (t_out, out_y[:, :n], out_y[:, n : 2 * n], out_y[:, 2 * n :], out_peak, stats)


def _run_scipy(
    P: Packed,
    model: TransientModel,
    q0: Floats,
    v0: Floats,
    t0: float,
    t1: float,
    drive: DriveSchedule,
    motion: Motion,
    settings: Settings,
    speed_scale: float,
) -> _Run:
    from scipy.integrate import solve_ivp

    n = model.n
    y = np.concatenate([q0, v0, np.zeros(K.N_WORK)])
    t_out = _output_grid(t0, t1, settings.samples)
    atol = tolerances(model, motion, speed_scale, settings.rtol)
    par = K.flatten(P)
    fun: Callable[[float, Floats], Floats] = lambda t, yy: K.rhs_first_order(t, yy, par)
    kw: dict[str, Any] = {}
    if settings.method in ("Radau", "BDF", "LSODA"):
        kw["jac"] = lambda t, yy: K.jac_first_order(t, yy, P)
    edges = [t0] + [b for b in _breaks(drive, motion) if t0 < b < t1] + [t1]
    ys, nfev, njev, steps, status = [], 0, 0, 0, "ok"
    for a, b in zip(edges[:-1], edges[1:]):
        sel = (t_out >= a) & ((t_out < b) if b < t1 else (t_out <= b))
        # one-sided forcing at the segment's edges, as the compiled kernel
        eps = 1e-12 * (abs(a) + abs(b) + 1.0)

        def f(t: float, yy: Floats, a: float = a, b: float = b, eps: float = eps) -> Floats:
            return fun(min(max(t, a + eps), b - eps), yy)

        te = t_out[sel]
        # dense output instead of t_eval: the same interpolants at the outputs, and
        # the steps taken (sol.t), which the accuracy check counts
        sol = solve_ivp(f, (a, b), y, method=settings.method, dense_output=True, rtol=settings.rtol, atol=atol, **kw)
        nfev += sol.nfev
        njev += getattr(sol, "njev", 0)
        if sol.status != 0 or not sol.success:
            status = f"scipy: {sol.message}"
            break
        steps += len(sol.t) - 1
        ys.append(sol.sol(te).T if len(te) else np.zeros((0, len(y))))
        y = sol.y[:, -1]
    Y = np.vstack(ys) if ys else np.zeros((0, len(y)))
    if len(Y) < len(t_out):
        Y = np.vstack([Y, np.full((len(t_out) - len(Y), Y.shape[1] if len(Y) else 2 * n + K.N_WORK), np.nan)])
    peak = np.column_stack([np.abs(Y[:, :n]), np.abs(Y[:, : model.nx] @ model.tip)])
    stats = {"status": status, "nfev": int(nfev), "njev": int(njev), "rtol": settings.rtol, "steps": int(steps)}
    return (t_out, Y[:, :n], Y[:, n : 2 * n], Y[:, 2 * n :], peak, stats)


def _run_fixed(
    P: Packed,
    model: TransientModel,
    q0: Floats,
    v0: Floats,
    t0: float,
    t1: float,
    drive: DriveSchedule,
    motion: Motion,
    settings: Settings,
    speed_scale: float,
) -> _Run:
    n = model.n
    h = settings.time_step or auto_time_step(model, speed_scale, settings, motion)
    nsteps = max(1, int(math.ceil((t1 - t0) / h - 1e-9)))
    h = (t1 - t0) / nsteps
    stride = max(1, int(math.ceil(nsteps / max(1, settings.samples - 1))))
    nsteps = stride * int(math.ceil(nsteps / stride))  # the last output lands on t1
    h = (t1 - t0) / nsteps
    nout = nsteps // stride + 1
    out_q = np.zeros((nout, n))
    out_v = np.zeros((nout, n))
    out_w = np.zeros((nout, K.N_WORK))
    out_peak = np.zeros((nout, n + 1))
    m = settings.method
    if m == "central_difference":
        status, nfev, nit = K.cd_solve(
            P, q0.copy(), v0.copy(), float(t0), h, nsteps, stride, out_q, out_v, out_w, out_peak
        )
        scheme: dict[str, float] = {}
    else:
        am, af, beta, gamma = K.genalpha_parameters(m, settings.hht_alpha, settings.rho_inf)
        scheme = {"alpha_m": am, "alpha_f": af, "beta": beta, "gamma": gamma}
        status, nfev, nit = K.genalpha_solve(
            P,
            q0.copy(),
            v0.copy(),
            float(t0),
            h,
            nsteps,
            stride,
            am,
            af,
            beta,
            gamma,
            settings.newton_tol,
            30,
            out_q,
            out_v,
            out_w,
            out_peak,
        )
    t = t0 + h * stride * np.arange(nout)
    stats = {
        "status": STATUS[status],
        "nfev": int(nfev),
        "steps": int(nsteps),
        "time_step": h,
        "newton_iterations": int(nit),
        "scheme": scheme,
    }
    if status != K.OK:
        out_q[:] = np.nan if status == K.NOT_FINITE else out_q
    return t, out_q, out_v, out_w, out_peak, stats
