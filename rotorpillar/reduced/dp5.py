"""Dormand-Prince 5(4), compiled for the rotor-structure model (rotorpillar.reduced.rhs).

``dp5_solve`` follows scipy's RK45 step control (same tableau, error norm,
safety factors and initial step), with scipy's 4th-order dense output on a
uniform output grid, interval peaks, breakpoints where the forcing is
discontinuous, and optional wrapping of theta into [0, 2 pi) so the relative
tolerance does not loosen as theta grows.  ``dp5_batch``: many runs
differing in M0, slope, load, e or c2, in one compiled loop.  Both release
the GIL (``nogil``): rotorpillar.reduced.batch.simulate_batch runs
slices of a batch on several threads at once.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .rhs import MAX_STEPS, NOT_FINITE, OK, STEP_TOO_SMALL, Floats, Packed, deriv_flat, flatten, record_peak

TWO_PI = 2.0 * math.pi


# scipy RK45's tableau and step control
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
_A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1 / 5, 0.0, 0.0, 0.0, 0.0],
        [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
        [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    ]
)
_B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
_E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
# scipy's RK45 dense output (Shampine's 4th-order continuous extension):
# y(t + x h) = y + h K^T P [x, x**2, x**3, x**4]
_P = np.array(
    [
        [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
        [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
        [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
        [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
        [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
    ]
)


@njit(cache=True)
def _inside(t: float, lo: float, hi: float) -> float:
    """t clamped inside the segment [lo, hi]: one-sided forcing at breakpoints."""
    eps = 1e-12 * (abs(lo) + abs(hi) + 1.0)
    if t < lo + eps:
        return lo + eps
    if t > hi - eps:
        return hi - eps
    return t


@njit(cache=True)
def _rms_norm(x: Floats, scale: Floats, m: int) -> float:
    s = 0.0
    for i in range(m):
        r = x[i] / scale[i]
        s += r * r
    return math.sqrt(s / m)


@njit(cache=True)
def _initial_step(
    t: float, y: Floats, f0: Floats, par: Floats, lo: float, hi: float, rtol: float, atol: Floats, m: int
) -> float:
    """Hairer's starting step, as scipy's select_initial_step (order 4)."""
    n2 = y.shape[0]
    scale = np.empty(n2)
    for i in range(n2):
        scale[i] = atol[i] + abs(y[i]) * rtol
    d0 = _rms_norm(y, scale, m)
    d1 = _rms_norm(f0, scale, m)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, hi - t)
    y1 = y + h0 * f0
    f1 = np.empty(n2)
    deriv_flat(_inside(t + h0, lo, hi), y1, par, f1, 0)
    diff = f1 - f0
    d2 = _rms_norm(diff, scale, m) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    return min(100 * h0, h1)


@njit(cache=True, nogil=True)
def dp5_solve(
    P: Packed,
    y0: Floats,
    t0: float,
    t1: float,
    breaks: Floats,
    rtol: float,
    atol: Floats,
    t_out: Floats,
    wrap: bool,
    max_steps: int,
    out_y: Floats,
    out_peak: Floats,
    h_max: float,
) -> tuple[int, int, int, int, float]:
    """Integrate y' = f from t0 to t1 (adaptive Dormand-Prince 5(4)).

    breaks: sorted times where the forcing may jump (the step lands on each);
    atol: per-component absolute tolerances of (q, v, work); give the work
    states a huge atol so they never bind.  Writes y at t_out into out_y (theta unwrapped) and,
    per output interval, the largest |q_i| at the steps and outputs inside it
    into out_peak.  Returns (status, nfev, n_accepted, n_rejected, h_min_used).
    """
    par = flatten(P)  # the model as one vector (rhs.deriv_flat)
    n = P[0].shape[0]
    nth = n - 1  # theta's index
    m = 2 * n  # error-controlled components
    N = y0.shape[0]
    K = np.zeros(7 * N)  # stage j at K[j N:(j + 1) N]: no row views in the loop
    y = y0.copy()
    ynew = np.empty(N)
    ytmp = np.empty(N)
    err = np.empty(N)
    scale = np.empty(N)
    turns = 0.0
    nout = t_out.shape[0]
    for k in range(nout):
        for i in range(n + 1):
            out_peak[k, i] = 0.0
    kout = 0
    while kout < nout and t_out[kout] < t0:
        kout += 1
    if kout < nout and t_out[kout] == t0:
        for i in range(N):
            out_y[kout, i] = y[i]
        record_peak(y, n, par, out_peak, kout)
        kout += 1
    # segments between breakpoints
    nb = breaks.shape[0]
    seg = np.empty(nb + 2)
    ns = 0
    seg[0] = t0
    ns = 1
    for b in range(nb):
        if breaks[b] > t0 and breaks[b] < t1:
            seg[ns] = breaks[b]
            ns += 1
    seg[ns] = t1
    ns += 1
    nfev = 0
    nacc = 0
    nrej = 0
    hmin_used = np.inf
    t = t0
    h = 0.0
    status = OK
    for s in range(ns - 1):
        lo = seg[s]
        hi = seg[s + 1]
        if hi <= lo:
            continue
        deriv_flat(_inside(t, lo, hi), y, par, K, 0)
        nfev += 1
        if h <= 0.0:
            h = _initial_step(t, y, K[:N], par, lo, hi, rtol, atol, N)
            nfev += 1
        while t < hi:
            if nacc + nrej >= max_steps:
                return MAX_STEPS, nfev, nacc, nrej, hmin_used
            h = min(h, h_max)
            h_want = h
            last = False
            if t + h >= hi or t + 1.0001 * h >= hi:
                h = hi - t
                last = True
            step_rejected = False
            while True:
                if h < 1e-14 * max(abs(t), 1.0):
                    return STEP_TOO_SMALL, nfev, nacc, nrej, hmin_used
                for st in range(1, 6):
                    for i in range(N):
                        acc = y[i]
                        for j in range(st):
                            acc += h * _A[st, j] * K[j * N + i]
                        ytmp[i] = acc
                    deriv_flat(_inside(t + _C[st] * h, lo, hi), ytmp, par, K, st * N)
                for i in range(N):
                    acc = y[i]
                    for j in range(6):
                        acc += h * _B[j] * K[j * N + i]
                    ynew[i] = acc
                deriv_flat(_inside(t + h, lo, hi), ynew, par, K, 6 * N)
                nfev += 6
                for i in range(N):
                    acc = 0.0
                    for j in range(7):
                        acc += _E[j] * K[j * N + i]
                    err[i] = h * acc
                    scale[i] = atol[i] + rtol * max(abs(y[i]), abs(ynew[i]))
                # RMS over every component, as scipy does on the same state
                # (the work states carry atol = 1e300: they count, but never bind)
                en = _rms_norm(err, scale, N)
                if not math.isfinite(en):
                    en = 1e300
                if en < 1.0:
                    if en == 0.0:
                        factor = MAX_FACTOR
                    else:
                        factor = min(MAX_FACTOR, SAFETY * en ** (-0.2))
                    if step_rejected:
                        factor = min(1.0, factor)
                    break
                h *= max(MIN_FACTOR, SAFETY * en ** (-0.2))
                last = False
                step_rejected = True
                nrej += 1
                if nacc + nrej >= max_steps:
                    return MAX_STEPS, nfev, nacc, nrej, hmin_used
            tnew = hi if last else t + h
            hs = tnew - t
            if hs < hmin_used:
                hmin_used = hs
            # dense output (scipy RK45's 4th-order interpolant) and interval peaks
            while kout < nout and t_out[kout] <= tnew:
                x = (t_out[kout] - t) / hs
                x2 = x * x
                px0, px1, px2, px3 = x, x2, x2 * x, x2 * x2
                for i in range(N):
                    acc = 0.0
                    for j in range(7):
                        kj = K[j * N + i]
                        acc += kj * (_P[j, 0] * px0 + _P[j, 1] * px1 + _P[j, 2] * px2 + _P[j, 3] * px3)
                    out_y[kout, i] = y[i] + hs * acc
                record_peak(out_y[kout], n, par, out_peak, kout)
                out_y[kout, nth] += turns
                kout += 1
            if kout < nout:
                record_peak(ynew, n, par, out_peak, kout)
            for i in range(N):
                y[i] = ynew[i]
                K[i] = K[6 * N + i]
            bad = False
            for i in range(m):
                if not math.isfinite(y[i]):
                    bad = True
            if bad:
                return NOT_FINITE, nfev, nacc, nrej, hmin_used
            if wrap and abs(y[nth]) > TWO_PI:
                w = TWO_PI * math.floor(y[nth] / TWO_PI)
                y[nth] -= w
                turns += w
            t = tnew
            nacc += 1
            h = hs * factor
            if last and not step_rejected:
                h = max(h, min(h_want, MAX_FACTOR * hs))
    # theta unwrapped in the final state
    y0[:] = y
    y0[nth] += turns
    return status, nfev, nacc, nrej, hmin_used


# --------------------------------------------------------------------------
# Many runs in one compiled loop


@njit(cache=True, nogil=True)
def dp5_batch(
    P: Packed,
    y0: Floats,
    t0: float,
    t1: float,
    breaks: Floats,
    rtol: float,
    atol: Floats,
    t_out: Floats,
    wrap: bool,
    max_steps: int,
    h_max: float,
    torque_scale: Floats,
    slope: Floats,
    load: Floats,
    eccentricity: Floats,
    shaft_stiffness: Floats,
    out_y: Floats,
    out_peak: Floats,
    stats: Floats,
) -> None:
    """Run ``dp5_solve`` once per entry of the per-run parameter arrays.

    torque_scale multiplies the schedule's M0; slope, load, eccentricity and
    shaft_stiffness replace s, k, e and c2 where they are not NaN.  out_y:
    (runs, n_out, N), out_peak: (runs, n_out, n + 1), stats: (runs, 5) with
    status, nfev, accepted, rejected steps, smallest step.
    """
    Minv, Kz, C, G, shaft, base, scal, sched, gpar, gtab = P
    runs = torque_scale.shape[0]
    for r in range(runs):
        sc = scal.copy()
        sh = sched.copy()
        for k in range(sh.shape[1]):
            sh[1, k] *= torque_scale[r]
            if not math.isnan(slope[r]):
                sh[2, k] = slope[r]
        if not math.isnan(load[r]):
            sc[3] = load[r]
        if not math.isnan(eccentricity[r]):
            sc[1] = eccentricity[r]
        if not math.isnan(shaft_stiffness[r]):
            sc[0] = shaft_stiffness[r]
        Pr = (Minv, Kz, C, G, shaft, base, sc, sh, gpar, gtab)
        y = y0.copy()
        res = dp5_solve(Pr, y, t0, t1, breaks, rtol, atol, t_out, wrap, max_steps, out_y[r], out_peak[r], h_max)
        stats[r, 0] = res[0]
        stats[r, 1] = res[1]
        stats[r, 2] = res[2]
        stats[r, 3] = res[3]
        stats[r, 4] = res[4]
