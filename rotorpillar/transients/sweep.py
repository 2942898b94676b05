"""The quasi-static sweep: stationary speeds and amplitudes per M0 bin, jumps.

A sweep ramps M0 up and down slowly; per bin of M0 the mean speed and the
largest amplitudes stand for the stationary regime.  Jumps: between
consecutive M0 bins the speed moves more than ``JUMP_FACTOR`` times what the
motor and load alone would allow, dM0 / (s + 2 k Omega); consecutive
flagged bins make one jump.  They are compared with the folds of the
averaging theory (rotorpillar.reduced.averaging), and their delay by the
finite sweep rate is extrapolated to a zero rate (``rate_convergence``).
The records first: the bins of a ramp, the jumps found and predicted, the
amplitudes against Eq. 19, the rate checks and the rate study;
``SweepFindings`` is what a sweep adds to ``simulate_sweep.json`` (its ``sweep``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..records import Record, replace
from ..reduced import averaging as av
from ..reduced.averaging import Jump
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import no_motion
from ..reduced.integration import Settings, Transient, simulate
from ..reduced.rotor_models import RotorStructure
from ..scene import Sweep


class SweepBins(Record, eq=False, omit_defaults=True):
    """Stationary speed and amplitudes per M0 bin over one ramp of a sweep, the bins in
    the ramp's order (M0 rising for "up", falling for "down"); empty bins left out."""

    M0: np.ndarray
    """the bin's middle torque at zero speed (N*m)"""
    omega: np.ndarray
    """mean rotor speed in the bin (rad/s)"""
    tip_x: np.ndarray
    """largest |tip X| in the bin (m)"""
    rotor_y: np.ndarray
    """largest |rotor Y| in the bin (m)"""
    rotor_x: np.ndarray
    """largest |rotor X| in the bin (m)"""
    M0_inertia_corrected: np.ndarray
    """M0 - J dOmega/dt: the torque the stationary balance sees (N*m)"""
    direction: str
    """up or down"""
    in_jump: np.ndarray | None = None
    """per bin: inside a jump, not stationary (``detect_jumps``); None before the scan"""

    def column(self, name: str) -> np.ndarray:
        """The column called ``name`` ("tip_x", "rotor_y", ...)."""
        value: np.ndarray = getattr(self, name)
        return value


class JumpScan(Record, eq=False):
    """One ramp's jumps (``detect_jumps``)."""

    jumps: list[NumericJump]
    """the numeric jumps, in the ramp's order"""
    largest_step_ratio: float
    """the largest speed step over what the motor and load alone allow (-; 1 on a smooth curve)"""
    in_jump: np.ndarray
    """per bin: inside a jump (not stationary)"""


class NumericJump(Record):
    """A jump the sweep made: consecutive bins whose speed moved more than JUMP_FACTOR
    times what the motor and load alone allow."""

    direction: str
    """up or down: the ramp it was found on"""
    omega_from: float
    """the speed it left (rad/s)"""
    omega_to: float
    """the speed it reached (rad/s)"""
    torque_at_zero: float
    """M0 at the jump: the middle of its first two bins (N*m)"""
    bins: int
    """consecutive flagged bin steps it spans (-)"""


class JumpMatch(Record, omit_defaults=True):
    """A predicted jump beside the numeric one it is matched to, or beside none."""

    predicted: Jump
    """the averaging theory's jump"""
    numeric: NumericJump | None
    """the numeric jump of the same direction nearest to it (and it nearest to that), or None"""
    rel_error_omega_from: float | None = None
    """numeric / predicted - 1 of the speed left (-); absent without a match"""
    rel_error_omega_to: float | None = None
    """numeric / predicted - 1 of the speed reached (-); absent without a match"""
    rel_error_torque: float | None = None
    """numeric / predicted - 1 of M0 at the jump (-); absent without a match"""


class AmplitudeCheck(Record):
    """The sweep's stationary amplitudes near one resonance against the paper's Eq. 19 and
    the exact linear steady state (relative errors: model / numeric - 1)."""

    index: int
    """the resonance's index (-)"""
    direction: str
    """X or Y: the resonance's direction"""
    omega: float
    """its circular frequency omega_i (rad/s)"""
    coordinate: str
    """the amplitude compared: tip_x (X) or rotor_y (Y)"""
    sweep: str
    """up or down: the ramp"""
    bins: int
    """stationary bins near the resonance (-)"""
    numeric_peak: float
    """the largest numeric amplitude among them (m)"""
    omega_at_numeric_peak: float
    """the speed of that bin (rad/s)"""
    eq19_at_that_speed: float
    """Eq. 19's amplitude there (m)"""
    exact_at_that_speed: float
    """the exact linear amplitude there (m)"""
    eq19_a_max: float
    """Eq. 19's amplitude at omega_i (m)"""
    rel_error_eq19: float
    """largest |error| of Eq. 19 over the bins (-)"""
    rel_error_exact: float
    """largest |error| of the exact linear amplitude over the bins (-)"""
    rel_error_eq19_median: float
    """median |error| of Eq. 19 (-)"""
    rel_error_exact_median: float
    """median |error| of the exact linear amplitude (-)"""
    rel_error_eq19_at_peak: float
    """Eq. 19's error at the numeric peak (-)"""
    rel_error_exact_at_peak: float
    """the exact linear amplitude's error at the numeric peak (-)"""


class RateCheck(Record):
    """Whether the sweep is slow enough at one resonance it crosses: the speed's rate over
    n_i**2 (quasi-static when < 0.1)."""

    index: int
    """the resonance's index (-)"""
    omega: float
    """its circular frequency omega_i (rad/s)"""
    n: float
    """its half-power width n_i (rad/s)"""
    speed_rate: float
    """dOmega/dt the sweep's rate of M0 drives there (rad/s**2)"""
    ratio: float
    """speed_rate / n_i**2 (-)"""
    quasi_static: bool
    """ratio < 0.1"""


class RateRow(Record, omit_defaults=True):
    """One numeric jump at the sweep rates r, r/2, r/4, and its limit at zero rate: per
    quantity the limit and the fitted exponent p of the delay ~ rate**p (None where the
    three do not converge monotonically, or a rate found no such jump)."""

    direction: str
    """up or down"""
    rates: tuple[float, ...]
    """the sweep rates of M0 (N*m/s)"""
    torque_at_zero: tuple[float | None, ...]
    """the jump's M0 at each rate (N*m); None where that rate found no jump of the direction"""
    omega_from: tuple[float | None, ...]
    """the speed it left at each rate (rad/s)"""
    omega_to: tuple[float | None, ...]
    """the speed it reached at each rate (rad/s)"""
    torque_at_zero_limit: float | None
    """M0 extrapolated to zero rate (N*m)"""
    torque_at_zero_exponent: float | None
    """p of M0's delay (-)"""
    omega_from_limit: float | None
    """the speed left, extrapolated to zero rate (rad/s)"""
    omega_from_exponent: float | None
    """p of its delay (-)"""
    omega_to_limit: float | None
    """the speed reached, extrapolated to zero rate (rad/s)"""
    omega_to_exponent: float | None
    """p of its delay (-)"""
    predicted_torque_at_zero: float | None = None
    """the averaging theory's M0 of the nearest predicted jump (N*m); absent without one or without a limit"""
    rel_error_limit_vs_predicted: float | None = None
    """torque_at_zero_limit / predicted_torque_at_zero - 1 (-); absent with it"""


class RateConvergence(Record):
    """The sweep's jumps at decreasing rates, extrapolated to a quasi-static sweep
    (``rate_convergence`` in ``simulate_sweep.json``)."""

    rows: tuple[RateRow, ...]
    """one per numeric jump at the scene's rate"""
    note: str
    """what the rows are, in words"""


class SweepAnalysis(Record, eq=False):
    """A quasi-static sweep against the averaging theory (``sweep_analysis``); its parts
    that ``simulate_sweep.json`` writes are rows as the JSON has them."""

    up: SweepBins
    """the bins of the ramp with M0 rising"""
    down: SweepBins
    """the bins of the ramp with M0 falling"""
    numeric_jumps: tuple[NumericJump, ...]
    """the jumps the sweep made, up then down (``JumpScan.jumps``)"""
    predicted_jumps: tuple[Jump, ...]
    """the averaging theory's jumps inside the swept torque range"""
    jump_comparison: tuple[JumpMatch, ...]
    """each predicted jump beside the nearest numeric one (``match_jumps``)"""
    largest_speed_step_ratio: dict[str, float]
    """per direction ("up", "down"): the largest speed step over what motor and load alone
    allow (-); a mapping by direction, as the JSON has it"""
    amplitudes: tuple[AmplitudeCheck, ...]
    """numeric stationary amplitudes against the paper's Eq. 19 and the exact linear ones
    (``compare_amplitudes``)"""
    rate_check: tuple[RateCheck, ...]
    """per resonance in range: is the sweep quasi-static there"""
    no_jump_reason: str | None
    """why no jump was found, or None"""
    captured_at: float | None
    """the up-sweep held below a resonance until its fold: the speed it left (rad/s), or None"""
    captured_resonance: float | None
    """that resonance's omega_i (rad/s), or None"""
    captured_index: int | None
    """that resonance's index (-), or None"""
    curves: dict[str, Any]
    """the stationary curves on a speed grid, by name: omega (rad/s), F_averaging and F_exact
    (N*m), exact (m, by coordinate) and eq19 (m, by resonance label)"""


class SweepFindings(Record):
    """What a quasi-static sweep adds to its summary (rotorpillar.transients.sweep): the
    keys ``simulate_sweep.json`` writes after ``jumps``, in this order."""

    predicted_jumps: tuple[Jump, ...]
    """the averaging theory's jumps inside the swept torque range"""
    jump_comparison: tuple[JumpMatch, ...]
    """each predicted jump beside the nearest numeric one"""
    largest_speed_step_ratio: dict[str, float]
    """{"up", "down"}: the largest speed step over what motor and load alone allow (-)"""
    amplitudes: tuple[AmplitudeCheck, ...]
    """numeric stationary amplitudes against the paper's Eq. 19 and the exact linear ones"""
    rate_check: tuple[RateCheck, ...]
    """per resonance in range: is the sweep quasi-static there"""
    no_jump_reason: str | None
    """why no jump was found, or None"""
    rate_convergence: RateConvergence | None
    """the jumps at rates r, r/2, r/4 and their limit, or None without jumps"""


JUMP_FACTOR = 5.0


def sweep_bins(
    run: Transient, drive: DriveSchedule, phase: tuple[float, float], bins: int, direction: str
) -> SweepBins:
    """Stationary speed and amplitudes per M0 bin over one ramp of a sweep."""
    m = run.model
    t0, t1 = phase
    sel = (run.t >= t0) & (run.t <= t1)
    M0 = drive.at(run.t[sel])[0]
    lo, hi = float(min(M0.min(), M0.max())), float(max(M0.min(), M0.max()))
    edges = np.linspace(lo, hi, bins + 1)
    idx = np.clip(np.digitize(M0, edges) - 1, 0, bins - 1)
    W = run.Omega[sel]
    tt = run.t[sel]
    tip, ry, rx = run.peak[sel, -1], run.peak[sel, m.nx], run.peak[sel, m.rotor_x]
    st = binned_statistics(idx, bins, tt, W, tip, ry, rx)
    M0_bins = np.where(np.isfinite(st.omega), 0.5 * (edges[:-1] + edges[1:]), np.nan)
    cols = {
        "M0": M0_bins,
        "omega": st.omega,
        "tip_x": st.tip_x,
        "rotor_y": st.rotor_y,
        "rotor_x": st.rotor_x,
        # the rotor's inertia: M0 - J dOmega/dt is what the stationary balance sees
        "M0_inertia_corrected": M0_bins - m.rotor_inertia * st.acceleration,
    }
    keep = np.isfinite(cols["M0"])
    step = -1 if direction == "down" else 1
    kept = {k: v[keep][::step] for k, v in cols.items()}
    return SweepBins(
        M0=kept["M0"],
        omega=kept["omega"],
        tip_x=kept["tip_x"],
        rotor_y=kept["rotor_y"],
        rotor_x=kept["rotor_x"],
        M0_inertia_corrected=kept["M0_inertia_corrected"],
        direction=direction,
    )


def binned_statistics(
    idx: NDArray[np.int_],
    bins: int,
    t: NDArray[np.float64],
    omega: NDArray[np.float64],
    tip: NDArray[np.float64],
    rotor_y: NDArray[np.float64],
    rotor_x: NDArray[np.float64],
) -> BinStatistics:
    """Per bin (samples with ``idx`` == b): the mean speed, the least-squares slope of the
    speed over time (0 with fewer than three samples, as before), and the largest of each
    peak; NaN in a bin without samples.  Sums by bin (np.bincount) in one pass each instead
    of a loop over the bins: the sweep's 20000-bin end took 37 s in that loop."""
    n = np.bincount(idx, minlength=bins).astype(float)
    has = n > 0
    safe = np.where(has, n, 1.0)
    mean_t = np.bincount(idx, t, bins) / safe
    mean_w = np.bincount(idx, omega, bins) / safe
    # the slope from deviations about each bin's means: no cancellation of large sums
    dt = t - mean_t[idx]
    dw = omega - mean_w[idx]
    var = np.bincount(idx, dt * dt, bins)
    cov = np.bincount(idx, dt * dw, bins)
    acc = np.where((n > 2) & (var > 0), cov / np.where(var > 0, var, 1.0), 0.0)
    tops = []
    for x in (tip, rotor_y, rotor_x):
        top = np.full(bins, -np.inf)
        np.maximum.at(top, idx, x)
        tops.append(np.where(has, top, np.nan))
    return BinStatistics(np.where(has, mean_w, np.nan), acc, *tops)


@dataclass(frozen=True)
class BinStatistics:
    """What a ramp's samples give per M0 bin; NaN in a bin without samples."""

    omega: NDArray[np.float64]
    """mean speed (rad/s)"""
    acceleration: NDArray[np.float64]
    """least-squares dOmega/dt (rad/s**2)"""
    tip_x: NDArray[np.float64]
    """largest |top| (m)"""
    rotor_y: NDArray[np.float64]
    """largest |rotor y| (m)"""
    rotor_x: NDArray[np.float64]
    """largest |rotor x| (m)"""


def detect_jumps(bins: SweepBins, slope: float, load: float) -> JumpScan:
    """Jumps along one ramp's bins; also the largest speed step over what the
    motor and load alone allow (1 on a smooth curve), and the bins inside a
    jump (not stationary: left out of the amplitude comparison)."""
    M0, W = bins.M0, bins.omega
    sign = 1.0 if bins.direction == "up" else -1.0
    dM = np.abs(np.diff(M0))
    dW = sign * np.diff(W)
    expected = dM / (slope + 2 * load * np.abs(W[:-1]))
    ratio = dW / np.maximum(expected, 1e-300)
    flagged = ratio > JUMP_FACTOR
    in_jump = np.zeros(len(W), dtype=bool)
    in_jump[:-1] |= flagged
    in_jump[1:] |= flagged
    jumps = []
    i = 0
    while i < len(flagged):
        if not flagged[i]:
            i += 1
            continue
        j = i
        while j + 1 < len(flagged) and flagged[j + 1]:
            j += 1
        w_from, w_to = float(W[i]), float(W[j + 1])
        if abs(w_to - w_from) > 0.01 * abs(w_from):
            jumps.append(
                NumericJump(
                    direction=bins.direction,
                    omega_from=w_from,
                    omega_to=w_to,
                    torque_at_zero=float(0.5 * (M0[i] + M0[i + 1])),
                    bins=int(j - i + 1),
                )
            )
        i = j + 1
    return JumpScan(jumps, float(np.max(ratio)) if len(ratio) else 0.0, in_jump)


def compare_amplitudes(model: RotorStructure, bins: SweepBins) -> list[AmplitudeCheck]:
    """Numeric stationary amplitudes of the sweep against the paper's Eq. 19 and the exact
    linear steady state, near each resonance the sweep crosses."""
    out = []
    W = bins.omega
    stationary = ~bins.in_jump if bins.in_jump is not None else np.ones(len(W), bool)
    res = model.quasi_normal()
    for r in res:
        key = "tip_x" if r.direction == "X" else "rotor_y"
        # where resonance i dominates: within 2 n_i, and nearer to omega_i than
        # to any other resonance of the same direction; stationary bins only
        gap = min((abs(q.omega - r.omega) for q in res if q.direction == r.direction and q is not r), default=math.inf)
        near = (np.abs(W - r.omega) <= min(2 * r.n, 0.5 * gap)) & stationary
        if near.sum() < 2:
            continue
        num = bins.column(key)[near]
        eq19 = np.asarray(av.amplitude(W[near], r))
        exact = model.steady_amplitudes(W[near])[key]
        k = int(np.argmax(num))
        out.append(
            AmplitudeCheck(
                index=r.index,
                direction=r.direction,
                omega=r.omega,
                coordinate=key,
                sweep=bins.direction,
                bins=int(near.sum()),
                numeric_peak=float(num[k]),
                omega_at_numeric_peak=float(W[near][k]),
                eq19_at_that_speed=float(eq19[k]),
                exact_at_that_speed=float(exact[k]),
                eq19_a_max=float(av.amplitude(r.omega, r)),
                rel_error_eq19=float(np.max(np.abs(eq19 / num - 1))),
                rel_error_exact=float(np.max(np.abs(exact / num - 1))),
                rel_error_eq19_median=float(np.median(np.abs(eq19 / num - 1))),
                rel_error_exact_median=float(np.median(np.abs(exact / num - 1))),
                rel_error_eq19_at_peak=float(eq19[k] / num[k] - 1),
                rel_error_exact_at_peak=float(exact[k] / num[k] - 1),
            )
        )
    return out


def match_jumps(numeric: list[NumericJump], predicted: list[av.Jump]) -> list[JumpMatch]:
    """Each predicted jump beside the numeric one of the same direction it is
    nearest to and that is nearest to it (in the speed it leaves), or beside
    none: a jump the sweep did not make (a resonance out of its range) is not
    measured against another resonance's jump."""

    def nearest(x, cands):
        return min(cands, key=lambda c: abs(c.omega_from - x.omega_from), default=None)

    rows = []
    for p in predicted:
        j = nearest(p, [j for j in numeric if j.direction == p.direction])
        if j is None or nearest(j, [q for q in predicted if q.direction == p.direction]) is not p:
            rows.append(JumpMatch(p, None))
            continue
        rows.append(
            JumpMatch(
                p,
                j,
                rel_error_omega_from=j.omega_from / p.omega_from - 1,
                rel_error_omega_to=j.omega_to / p.omega_to - 1,
                rel_error_torque=j.torque_at_zero / p.torque_at_zero - 1,
            )
        )
    return rows


def sweep_analysis(
    sweep: Sweep, slope: float, load_coefficient: float, model: RotorStructure, run: Transient, drive: DriveSchedule
) -> SweepAnalysis:
    """The sweep's bins, jumps (numeric and predicted), amplitudes, rate check and curves,
    for the motor's ``slope`` s (N*m*s) and the load's coefficient k (N*m*s**2)."""
    w = sweep
    t = drive.times
    up = sweep_bins(run, drive, (t[1], t[2]), w.bins, "up")
    down = sweep_bins(run, drive, (t[3], t[4]), w.bins, "down")
    s, k = slope, load_coefficient
    scan_up, scan_down = detect_jumps(up, s, k), detect_jumps(down, s, k)
    up, down = replace(up, in_jump=scan_up.in_jump), replace(down, in_jump=scan_down.in_jump)
    j_up, r_up = scan_up.jumps, scan_up.largest_step_ratio
    j_down, r_down = scan_down.jumps, scan_down.largest_step_ratio
    res = model.quasi_normal()
    # the analysis' folds: for this drive slope and load, M0 free
    pred = av.analyse_drive(av.Characteristic(w.torque_high, s, k), res)
    predicted = [j for j in pred.jumps if w.torque_low <= j.torque_at_zero <= w.torque_high]
    numeric = j_up + j_down
    held = None
    if j_up:
        below = [r for r in res if r.omega <= j_up[0].omega_from * (1 + 0.03)]
        held = max(below, key=lambda r: r.omega) if below else None
    rate_check = []
    for r in res:
        if not (w.torque_low <= float(r.omega * (s + k * r.omega)) <= w.torque_high):
            continue
        acc = w.rate / (s + 2 * k * r.omega)
        rate_check.append(RateCheck(r.index, r.omega, r.n, acc, acc / r.n**2, bool(acc / r.n**2 < 0.1)))
    if numeric:
        reason = None
    elif predicted:
        reason = "the analysis predicts jumps the sweep did not find (see predicted_jumps)"
    else:
        worst = max((av.peak_resistance_ratio(r, k) for r in res if k > 0), default=0.0)
        reason = (
            f"No jumps: the speed rose and fell smoothly with M0 (largest step {max(r_up, r_down):.2f}x "
            f"what the motor and load alone allow; a jump needs > {JUMP_FACTOR:g}x), as the "
            f"analysis predicts: no fold of Md = L in [{w.torque_low:g}, {w.torque_high:g}] N*m; "
            f"the resonances draw at most {100 * worst:.2g} % of Mc at their own speed."
        )
    W_curve = av.stationary_speed_grid(res, 1.05 * max(np.nanmax(up.omega), np.nanmax(down.omega)), 1500)
    curves = {
        "omega": W_curve,
        "F_averaging": av.total_resistance(W_curve, k, res) + s * W_curve,
        "F_exact": k * W_curve**2 + s * W_curve - model.steady_torque(W_curve),
        "exact": model.steady_amplitudes(W_curve),
        "eq19": {f"{r.direction}{r.index}": av.amplitude(W_curve, r) for r in res},
    }
    return SweepAnalysis(
        up=up,
        down=down,
        numeric_jumps=tuple(numeric),
        predicted_jumps=tuple(predicted),
        jump_comparison=tuple(match_jumps(numeric, predicted)),
        largest_speed_step_ratio={"up": r_up, "down": r_down},
        amplitudes=tuple(compare_amplitudes(model, up) + compare_amplitudes(model, down)),
        rate_check=tuple(rate_check),
        no_jump_reason=reason,
        captured_at=j_up[0].omega_from if held is not None else None,
        captured_resonance=None if held is None else held.omega,
        captured_index=None if held is None else held.index,
        curves=curves,
    )


def _zero_rate_limit(v: tuple[float | None, ...]) -> tuple[float | None, float | None]:
    """(limit, exponent p) of three values at rates halving, or (None, None)."""
    if len(v) != 3 or any(x is None for x in v):
        return None, None
    a, b, c = (float(x) for x in v if x is not None)
    d1, d2 = a - b, b - c
    if not (d1 * d2 > 0 and abs(d2) < abs(d1)):
        return None, None
    p = math.log2(d1 / d2)
    return c - d2 / (2**p - 1), p


def rate_convergence(
    sweep: Sweep,
    slope: float,
    load_coefficient: float,
    model: RotorStructure,
    st: Settings,
    jumps: tuple[NumericJump, ...] | list[NumericJump],
    predicted: tuple[av.Jump, ...] | list[av.Jump],
    factors: tuple[float, ...] = (1.0, 0.5, 0.25),
) -> RateConvergence:
    """The sweep's jumps at rates r, r/2, r/4, and their limit at zero rate.

    A slow passage past a fold is delayed by a power of the rate (about 2/3
    for a saddle-node); with three rates halving, the exponent p follows from
    the differences d1, d2 and the limit is M(r/4) - d2 / (2**p - 1).
    """
    w = sweep
    s, k = slope, load_coefficient
    rows = []
    found: dict[float, list[NumericJump]] = {1.0: list(jumps)}
    for f in factors:
        if f == 1.0:
            continue
        drive = DriveSchedule.sweep(s, k, w.torque_low, w.torque_high, w.rate * f, w.settle)
        run = simulate(
            model,
            drive,
            no_motion(),
            drive.times[-1],
            settings=replace(st, samples=max(st.samples, int(40 * w.bins / f))),
            speed_scale=drive.free_speed(drive.times[2]),
        )
        t = drive.times
        bins = int(w.bins / f)
        j_up = detect_jumps(sweep_bins(run, drive, (t[1], t[2]), bins, "up"), s, k).jumps
        j_dn = detect_jumps(sweep_bins(run, drive, (t[3], t[4]), bins, "down"), s, k).jumps
        found[f] = j_up + j_dn
    for j in jumps:
        same: list[NumericJump | None] = [j]
        for f in factors[1:]:
            c = [x for x in found[f] if x.direction == j.direction]
            same.append(min(c, key=lambda x: abs(x.omega_from - j.omega_from)) if c else None)
        torque = tuple(None if x is None else x.torque_at_zero for x in same)
        w_from = tuple(None if x is None else x.omega_from for x in same)
        w_to = tuple(None if x is None else x.omega_to for x in same)
        (m_lim, m_p), (f_lim, f_p), (t_lim, t_p) = map(_zero_rate_limit, (torque, w_from, w_to))
        pred = [q for q in predicted if q.direction == j.direction]
        predicted_torque = rel_error = None
        if pred and m_lim is not None:
            q = min(pred, key=lambda q: abs(q.omega_from - j.omega_from))
            predicted_torque = q.torque_at_zero
            rel_error = m_lim / q.torque_at_zero - 1
        rows.append(
            RateRow(
                direction=j.direction,
                rates=tuple(w.rate * f for f in factors),
                torque_at_zero=torque,
                omega_from=w_from,
                omega_to=w_to,
                torque_at_zero_limit=m_lim,
                torque_at_zero_exponent=m_p,
                omega_from_limit=f_lim,
                omega_from_exponent=f_p,
                omega_to_limit=t_lim,
                omega_to_exponent=t_p,
                predicted_torque_at_zero=predicted_torque,
                rel_error_limit_vs_predicted=rel_error,
            )
        )
    return RateConvergence(
        rows=tuple(rows),
        note="jump torques at decreasing sweep rates, extrapolated to a "
        "quasi-static sweep (rate -> 0) with a fitted power of the rate",
    )
