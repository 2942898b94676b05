"""How accurate a time step is: each scheme's error on one oscillator, and what a run must resolve.

A scheme applied to the undamped oscillator x'' + omega**2 x = 0 with the
step h multiplies its state by an amplification matrix A(Omega), Omega =
omega h.  Its principal eigenvalues lambda = |lambda| exp(+-i Omega_bar)
give the scheme's errors at that step, exactly (no series):

- the relative period error T_bar / T - 1 = Omega / Omega_bar - 1
  (Newmark's average acceleration: 2 atan(Omega / 2) = Omega_bar, so
  ~ Omega**2 / 12; Hilber, Hughes & Taylor 1977; Chung & Hulbert 1993);
- the amplitude lost per period of the true motion, 1 - |lambda|**(2 pi / Omega)
  (zero for Newmark and central difference: they dissipate nothing);
- the spectral radius max |lambda|, and at Omega -> infinity rho_inf, the
  factor by which the modes far above the step's reach shrink each step.

The same numbers are what a forced response sees: a trapezoidal scheme
computes the response to a forcing at omega as the exact system's at the
warped frequency omega (1 + period error) (Tustin's pre-warping), so a
period error of eps moves every resonance the run meets by eps.

Schemes: the generalized-alpha family (``newmark``, ``hht``,
``generalized_alpha``: the 3 x 3 matrix on (x, h v, h**2 a), Chung &
Hulbert 1993 eq. 9-12), ``central_difference`` (velocity Verlet), the
explicit Runge-Kutta methods by their tableau (``dp5`` and scipy's ``RK45``:
Dormand-Prince 5(4); ``DOP853``), ``Radau`` (IIA, order 5: its stability
function).  ``BDF`` and ``LSODA`` change their order as they go: no single
amplification holds, and only the sampling limit applies to them.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
from numpy.typing import NDArray

from ..provenance import Record
from .excitation import GroundMotion

#: A run whose scheme moves the fastest frequency it must resolve by more than
#: this (relative period error), or loses more than this share of an
#: oscillation's amplitude per period there, is no answer of its equations:
#: at 10 % a resonance of damping ratio zeta < 5 % lands outside its own
#: half-power band (width 2 zeta), so a response near it can be wrong by its
#: own size, and an oscillation drifts half a cycle in 5 periods.
#: (Newmark needs 5.5 steps per period for it; HHT and generalized-alpha at
#: rho_inf 0.8: 6.1 and 5.7; central difference 4.4; dp5 3.2.  The defaults
#: take 40-60.)
ERROR_LIMIT = 0.10
#: At fewer steps per period than this (Nyquist) a forcing is aliased: the
#: run sees another frequency, whatever its scheme.
NYQUIST_STEPS = 2.0

GENALPHA = ("newmark", "hht", "generalized_alpha")
EXPLICIT_RK = ("dp5", "RK45", "DOP853")
VARIABLE_ORDER = ("BDF", "LSODA")


class SchemeError(Record):
    """A scheme's error on an undamped oscillator at one step."""

    steps_per_period: float
    """2 pi / (omega h) (-)"""
    period_error: float
    """T_bar / T - 1 (-); inf when the scheme no longer oscillates (or is unstable)"""
    amplitude_loss: float
    """share of the amplitude lost per period of the true motion (-); < 0: it grows"""
    spectral_radius: float
    """max |lambda| of the amplification (-)"""
    stable: bool
    """spectral radius <= 1 (to round-off)"""

    @property
    def worst(self) -> float:
        """The larger of |period error| and |amplitude loss| (-)."""
        return max(abs(self.period_error), abs(self.amplitude_loss))


def genalpha_amplification(
    Omega: float, alpha_m: float, alpha_f: float, beta: float, gamma: float
) -> NDArray[np.float64]:
    """The generalized-alpha step on x'' + omega**2 x = 0 as a matrix on (x, h v, h**2 a).

    (1 - am) a1 + am a0 + omega**2 ((1 - af) x1 + af x0) = 0 with Newmark's
    updates (Chung & Hulbert 1993); Omega = omega h.
    """
    W2 = Omega * Omega
    L = np.array([[W2 * (1 - alpha_f), 0.0, 1 - alpha_m], [1.0, 0.0, -beta], [0.0, 1.0, -gamma]])
    R = np.array([[-W2 * alpha_f, 0.0, -alpha_m], [1.0, 1.0, 0.5 - beta], [0.0, 1.0, 1 - gamma]])
    return np.linalg.solve(L, R)


def central_difference_amplification(Omega: float) -> NDArray[np.float64]:
    """Velocity Verlet on x'' + omega**2 x = 0, a matrix on (x, h v)."""
    W2 = Omega * Omega
    x1 = np.array([1 - W2 / 2, 1.0])  # x1 from (x0, V0)
    return np.array([x1, [-W2 / 2 * (1 + x1[0]), 1 - W2 / 2 * x1[1]]])


def _rk_tableau(method: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    if method in ("dp5", "RK45"):
        from .dp5 import _A, _B

        s = len(_B)
        A = np.zeros((s, s))
        A[:, : _A.shape[1]] = _A
        return A, _B
    from scipy.integrate._ivp import dop853_coefficients as dop853

    s = len(dop853.B)
    return np.asarray(dop853.A)[:s, :s], np.asarray(dop853.B)


def stability_function(method: str, z: complex) -> complex:
    """R(z) of a one-step method on y' = lambda y, z = lambda h."""
    if method in EXPLICIT_RK:
        A, b = _rk_tableau(method)
        s = len(b)
        return complex(1 + z * (b @ np.linalg.solve(np.eye(s) - z * A, np.ones(s))))
    if method == "Radau":  # Radau IIA, 3 stages: the (2, 3) Pade
        return (1 + 2 * z / 5 + z**2 / 20) / (1 - 3 * z / 5 + 3 * z**2 / 20 - z**3 / 60)
    raise ValueError(f"no stability function for {method!r}")


def has_amplification(method: str) -> bool:
    """True when the scheme's error at a step is known (not BDF or LSODA)."""
    return method in GENALPHA + ("central_difference", "Radau") + EXPLICIT_RK


def scheme_error(
    method: str, Omega: float, alpha_m: float = 0.0, alpha_f: float = 0.0, beta: float = 0.25, gamma: float = 0.5
) -> SchemeError:
    """The error of ``method`` at Omega = omega h on an undamped oscillator.

    The generalized-alpha family takes its four parameters
    (rotorpillar.reduced.fixed_step.genalpha_parameters).
    """
    Omega = float(Omega)
    spp = 2 * math.pi / Omega if Omega > 0 else math.inf
    if not Omega > 0:
        return SchemeError(spp, 0.0, 0.0, 1.0, True)
    Omega = min(Omega, 1e8)  # beyond: as far above the reach as 1e8
    if method in GENALPHA or method == "central_difference":
        A = (
            central_difference_amplification(Omega)
            if method == "central_difference"
            else genalpha_amplification(Omega, alpha_m, alpha_f, beta, gamma)
        )
        lam = np.linalg.eigvals(A)
        rho = float(np.max(np.abs(lam)))
        # the principal pair: the complex root of largest modulus (the spurious root is real)
        cplx = [x for x in lam if abs(x.imag) > 1e-12 * max(abs(x), 1e-300)]
        if cplx:
            root = max(cplx, key=abs)
            phase, mod = abs(cmath.phase(root)), abs(root)
        else:  # real roots: no oscillation left
            root = max(lam, key=abs)
            phase, mod = (math.pi if root.real < 0 else 0.0), abs(root)
    else:
        root = stability_function(method, 1j * Omega)
        phase, mod = abs(cmath.phase(root)), abs(root)
        rho = mod
    stable = rho <= 1 + 1e-12
    period = Omega / phase - 1 if phase > 0 else math.inf
    growth = spp * math.log(mod) if mod > 0 else -math.inf
    loss = 1 - math.exp(growth) if growth < 700 else -math.inf
    return SchemeError(spp, float(period), float(loss), rho, bool(stable))


def steps_per_period_needed(method: str, limit: float = ERROR_LIMIT, **params: float) -> float:
    """The fewest steps per period at which ``method`` keeps its period error and its
    amplitude loss per period within ``limit`` (-), by bisection (the errors fall
    as the step does); never fewer than NYQUIST_STEPS."""

    def ok(n: float) -> bool:
        return scheme_error(method, 2 * math.pi / n, **params).worst <= limit

    lo, hi = NYQUIST_STEPS, 4.0
    if ok(lo):
        return lo
    while not ok(hi):
        lo, hi = hi, 2 * hi
        if hi > 1e7:
            return math.inf
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    return hi


def largest_step(method: str, omega: float, limit: float, **params: float) -> float:
    """The longest step (s) at which ``method`` resolves ``omega`` (rad/s) within ``limit``."""
    return 2 * math.pi / omega / steps_per_period_needed(method, limit, **params)


def infinity_radius(method: str, **params: float) -> float | None:
    """rho_inf: the spectral radius far above the step's reach (-); 1 for the
    schemes that damp nothing; None for the explicit ones (unstable there)."""
    if method == "central_difference" or method in EXPLICIT_RK:
        return None
    return scheme_error(method, 1e8, **params).spectral_radius


# --------------------------------------------------------------------------
# What a run must resolve


#: The forcing frequencies' names in words.
FORCING_WORDS = {
    "unbalance_rotation": "the unbalance's rotation",
    "ground_motion_band": "the ground motion's band",
    "rotor_speed": "the rotor's speed",
}


def forcing_frequencies(eccentricity: float, top_speed: float, motion: GroundMotion | None) -> dict[str, float]:
    """The frequencies that force a run (rad/s), by name: the unbalance's rotation at
    the fastest speed the run reaches (when e > 0) and the ground motion's band
    (the pulse's omega, or the record's 99 %-energy frequency)."""
    out = {}
    if eccentricity > 0 and top_speed > 0:
        out["unbalance_rotation"] = float(top_speed)
    if motion is not None and motion.kind != "none" and motion.band() > 0:
        out["ground_motion_band"] = float(motion.band())
    return out


# --------------------------------------------------------------------------
# The full orders' step

FULL_ORDER_SCHEMES = GENALPHA + ("central_difference",)


def full_order_parameters(method: str, rho_inf: float) -> dict[str, float]:
    """The generalized-alpha parameters of a full order's ``method`` at ``rho_inf``
    (rotorpillar.reduced.fixed_step.genalpha_parameters: Chung & Hulbert 1993; HHT-alpha
    with alpha = (rho_inf - 1) / (rho_inf + 1), Hilber, Hughes & Taylor 1977); empty
    for central difference.  InputError for HHT below its reach (rho_inf < 0.5)."""
    from ..errors import InputError
    from .fixed_step import genalpha_parameters

    if method not in FULL_ORDER_SCHEMES:
        raise InputError(f"full order integrator {method!r}: must be one of {', '.join(FULL_ORDER_SCHEMES)}")
    if method == "central_difference":
        return {}
    if method == "hht" and rho_inf < 0.5:
        raise InputError(
            f"full_order.rho_inf = {rho_inf:g}: HHT-alpha reaches 0.5 at the least "
            "(alpha = -1/3); take generalized_alpha for less"
        )
    am, af, beta, gamma = genalpha_parameters(method, (rho_inf - 1) / (rho_inf + 1), rho_inf)
    return {"alpha_m": am, "alpha_f": af, "beta": beta, "gamma": gamma}


#: The full order is the reference the reduced models are judged by: its step
#: keeps the scheme's error (period error, and amplitude lost per period) at
#: the fastest forcing within 2e-3, what 40 steps per period of Newmark's
#: average acceleration gave before ((2 pi / 40)**2 / 12 = 2.1e-3); on El
#: Centro with a stiff shaft it leaves the 3D peak tip within 0.1 % of a run
#: at a tenth of the step (docs/transients.md).  The band's modes above the
#: forcing (up to band_factor times it) keep band_factor**2 times that.
FULL_ORDER_ERROR = 2e-3


class StepRule(Record):
    """How a full-order run's step was chosen and what it resolves (the JSON's ``integrator``)."""

    scheme: str
    """newmark, hht or generalized_alpha"""
    spectral_radius_infinity: float | None
    """rho_inf: the factor the modes far above the band shrink by per step (-);
    None for central difference (explicit: unstable there)"""
    time_step: float
    """the step taken (s)"""
    rule: str
    """in words: what set the step"""
    source: str
    """"rule", or the scene key that stated the step"""
    forcing: dict[str, float]
    """the frequencies that force the run, by name (rad/s)"""
    forcing_top: float
    """the fastest of them (rad/s)"""
    band_edge: float
    """band_factor x forcing_top: the highest mode the run resolves (rad/s)"""
    error_target: float
    """the scheme's largest error allowed at forcing_top (-)"""
    at_forcing_top: SchemeError
    """the scheme's error there at the step taken"""
    at_band_edge: SchemeError
    """the scheme's error at the band's edge at the step taken"""
    record_time_step: float | None = None
    """the record's sampling, which the step never exceeds (s); None without a record"""


def full_order_step(
    method: str,
    params: dict[str, float],
    forcing: dict[str, float],
    band_factor: float,
    record_time_step: float | None = None,
    stated: float = 0.0,
    stated_by: str = "full_order.time_step",
    target: float = FULL_ORDER_ERROR,
) -> StepRule:
    """The full order's step (s): the longest whose error at the fastest forcing is within
    ``target`` for ``method`` (its generalized-alpha ``params``), no coarser than a
    record's sampling; ``stated`` > 0 takes that step instead.

    Not the stiffest part's: the schemes are unconditionally stable, and the modes
    far above the band (a stiff shaft, the beam's shear modes, the tube's
    ovalling and axial modes) are damped by the scheme (rho_inf < 1), not resolved.
    """
    top = max(forcing.values(), default=0.0)
    names = FORCING_WORDS
    if stated > 0:
        h, source = float(stated), stated_by
        rule = f"stated: {stated_by} = {stated:g} s"
    elif top > 0:
        h, source = largest_step(method, top, target, **params), "rule"
        which = max(forcing, key=forcing.__getitem__)
        rule = (
            f"the longest step whose period error and amplitude loss per period stay within "
            f"{target:g} at the fastest forcing, {names.get(which, which)} ({top:.4g} rad/s)"
        )
        if record_time_step and record_time_step < h:
            h = float(record_time_step)
            rule += f"; no coarser than the record's sampling ({record_time_step:g} s)"
        rule += "; the modes far above the band are damped by the scheme, not resolved"
    else:
        h, source, rule = 0.01, "rule", "nothing forces the run: 0.01 s"
    ref = top if top > 0 else 2 * math.pi / (100 * h)
    return StepRule(
        method,
        infinity_radius(method, **params),
        h,
        rule,
        source,
        dict(forcing),
        top,
        band_factor * top,
        target,
        scheme_error(method, ref * h, **params),
        scheme_error(method, band_factor * ref * h, **params),
        record_time_step if record_time_step else None,
    )


# --------------------------------------------------------------------------
# The check a run passes


class AccuracyCheck(Record):
    """The step a run took against the periods it had to resolve and its duration."""

    method: str
    step: float
    """the fixed step, or the adaptive steps' mean (s)"""
    step_kind: str
    """"fixed" or "mean of the adaptive steps\""""
    frequencies: dict[str, float]
    """what the run had to resolve, by name (rad/s)"""
    steps_per_period: float
    """fixed: at the fastest frequency; adaptive: the steps over the periods the run
    went through at the fastest frequency of each moment (-)"""
    steps_per_period_needed: float
    """the fewest at which the scheme's error stays within ``limit`` (-)"""
    error: SchemeError | None
    """the scheme's error at the fastest frequency at ``step`` (None: unknown for BDF, LSODA)"""
    limit: float
    """ERROR_LIMIT (-)"""
    duration: float
    """the run's length (s)"""
    failed: list[str]
    """named failures, "name: why" (empty: the step is fit for the run)"""
    statement: str
    """in words"""

    @property
    def ok(self) -> bool:
        return not self.failed


def check_step(
    method: str,
    params: dict[str, float],
    step: float,
    frequencies: dict[str, float],
    duration: float,
    *,
    adaptive: bool = False,
    periods: float | None = None,
    steps: int | None = None,
    window: tuple[float, float] | None = None,
    rtol: float | None = None,
    limit: float = ERROR_LIMIT,
) -> AccuracyCheck:
    """Is ``step`` fit for a run of ``duration`` that must resolve ``frequencies``?

    Fixed step: the scheme's error at the fastest frequency within ``limit``.
    Adaptive (``adaptive``, ``steps`` taken, ``periods`` gone through at the
    fastest frequency of each moment): if every step had resolved its moment's
    fastest frequency with steps_per_period_needed steps a period, the run
    would have taken at least that many times ``periods`` steps; fewer means
    some steps did not (the mean step's error is then a lower bound).  Both:
    at least NYQUIST_STEPS steps over the run and over the ground motion's
    ``window``, and an error control no looser than ``limit``.
    """
    known = has_amplification(method)
    needed = steps_per_period_needed(method, limit, **params) if known else NYQUIST_STEPS
    fastest = max(frequencies.values(), default=0.0)
    which = max(frequencies, key=frequencies.__getitem__) if frequencies else None
    if adaptive and steps is not None and periods:
        spp = steps / periods
    else:
        spp = 2 * math.pi / (fastest * step) if fastest > 0 and step > 0 else math.inf
    err = scheme_error(method, 2 * math.pi / spp, **params) if known and math.isfinite(spp) else None
    failed = []
    words = FORCING_WORDS
    where = f"{words.get(which, which)} ({fastest:.4g} rad/s)" if which else ""
    kind = "mean step" if adaptive else "step"
    if which and spp < needed:
        said = (
            f"period error {_pct(err.period_error)}, amplitude {_loss(err.amplitude_loss)} per period"
            if err is not None
            else "aliased below 2 steps a period"
            if spp < NYQUIST_STEPS
            else ""
        )
        failed.append(
            f"step_accuracy: {method} at a {kind} of {step:.4g} s takes {spp:.3g} steps per "
            f"period of {where}, fewer than the {needed:.3g} it needs to keep its error within "
            f"{100 * limit:g} %" + (f" (at this step: {said})" if said else "")
        )
    if step > 0 and duration / step < NYQUIST_STEPS:
        failed.append(
            f"step_swallows_run: a {kind} of {step:.4g} s against a run of {duration:.4g} s "
            f"({duration / step:.3g} steps)"
        )
    if (
        window is not None
        and step > 0
        and window[1] > window[0]
        and (min(window[1], duration) - window[0]) / step < NYQUIST_STEPS
        and window[0] < duration
    ):
        failed.append(
            f"step_swallows_ground_motion: a {kind} of {step:.4g} s against the ground "
            f"motion's {window[1] - window[0]:.4g} s inside the run"
        )
    if rtol is not None and rtol > limit:
        failed.append(f"tolerance: rtol = {rtol:g} lets each step err by more than {100 * limit:g} % of the response")
    if not which:
        statement = "nothing forces the run at a frequency; only its duration is checked"
    else:
        statement = (
            f"{method}, {kind} {step:.4g} s: {spp:.3g} steps per period of {where} "
            f"(needs {needed:.3g} for {100 * limit:g} %)"
        )
        if err is not None:
            statement += (
                f"; the scheme's period error there {_pct(err.period_error)}, amplitude "
                f"{_loss(err.amplitude_loss)} per period"
            )
    return AccuracyCheck(
        method,
        float(step),
        "mean of the adaptive steps" if adaptive else "fixed",
        dict(frequencies),
        float(spp),
        float(needed),
        err,
        limit,
        float(duration),
        failed,
        statement,
    )


def _pct(x: float) -> str:
    return "unbounded" if not math.isfinite(x) else f"{100 * x:+.3g} %"


def _loss(x: float) -> str:
    if not math.isfinite(x):
        return "growing without bound"
    return f"{100 * x:.3g} % lost" if x >= 0 else f"{-100 * x:.3g} % gained"
