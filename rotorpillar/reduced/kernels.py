"""Compiled (numba) right-hand sides and time integrators of the rotor-structure model.

One generic model covers the paper's Eq. 4 and the modal model
(rotorpillar.reduced.rotor_models): nx structural X coordinates z (pillar
and rotor centre), the rotor centre's Y coordinate y, and the rotor angle
theta.  With M the mass matrix (its inverse Minv given; a zero row for theta
prescribes a constant speed), the forces are

    F_z     = -Ks z - C z' - c2 d (d.z - e cos theta) + kb u_g + cb v_g + mb a_g
    F_y     = -c2 (y - e sin theta) - b2y y'
    F_theta = Md(t, W) - Mc(W) - c2 e (d.z) sin theta + c2 e y cos theta

with W = theta', Md = M0(t) - s(t) W (a piecewise-linear schedule),
Mc = k W |W|, d the shaft-deflection vector (rotor X minus tip X) and
(u_g, v_g, a_g) the ground displacement, velocity and acceleration.

The arrays travel as one tuple P = (Minv, Ks, C, d, base, scal, sched, gpar,
gtab), built by ``rotor_models.pack``:

- base  (4, nx): rows kb, cb, mb, and the tip vector (tip X = tip.z, for the peaks)
- scal  (4,):    c2, e, b2y, k
- sched (3, m):  knot times, M0, s
- gpar  (6,):    kind (0 none, 1 harmonic pulse, 2 table), A, omega, t0, t1, dt
- gtab  (3, ng): tabulated u_g, v_g, a_g on t0 + i dt (kind 2)

Four work integrals ride along with the state (not error-controlled):
drive minus load (Md - Mc) W, work done by the shaft torque on the
structure, dissipation, and base-force work; they close the energy balance.

Integrators, all written for this model and compiled once (cache=True):

- ``dp5_solve``: Dormand-Prince 5(4) with scipy's RK45 step control (same
  tableau, error norm, safety factors and initial step), scipy's 4th-order dense
  output on a uniform output grid, interval peaks, breakpoints where the
  forcing is discontinuous, and optional wrapping of theta into [0, 2 pi) so
  the relative tolerance does not loosen as theta grows.
- ``genalpha_solve``: the generalized-alpha family (Chung & Hulbert 1993)
  with Newton iterations on the analytic Jacobian: Newmark average
  acceleration (alpha_m = alpha_f = 0, beta = 1/4, gamma = 1/2), HHT-alpha
  (alpha_m = 0) and Chung-Hulbert by rho_inf.
- ``cd_solve``: explicit central difference in velocity-Verlet form,
  conditionally stable for h < 2/omega_max.
- ``dp5_batch``: many runs differing in M0, slope, load, e or c2, in one
  compiled loop.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

N_WORK = 4
#: status codes of the integrators
OK, MAX_STEPS, STEP_TOO_SMALL, NOT_FINITE, NEWTON_FAILED = 0, 1, 2, 3, 4
TWO_PI = 2.0 * math.pi


# --------------------------------------------------------------------------
# Model


@njit(cache=True)
def ground(t, gpar, gtab):
    """Ground displacement, velocity, acceleration at t (m, m/s, m/s**2)."""
    kind = int(gpar[0])
    if kind == 1:
        A, w, t0, t1 = gpar[1], gpar[2], gpar[3], gpar[4]
        if t >= t0 and t < t1:
            c = math.cos(w * t)
            s = math.sin(w * t)
            return A * (c - 1.0), -A * w * s, -A * w * w * c
        return 0.0, 0.0, 0.0
    if kind == 2:
        t0, dt = gpar[3], gpar[5]
        n = gtab.shape[1]
        x = (t - t0) / dt
        if x < 0.0 or x > n - 1:
            return 0.0, 0.0, 0.0
        i = int(x)
        if i >= n - 1:
            i = n - 2
        f = x - i
        return ((1.0 - f) * gtab[0, i] + f * gtab[0, i + 1],
                (1.0 - f) * gtab[1, i] + f * gtab[1, i + 1],
                (1.0 - f) * gtab[2, i] + f * gtab[2, i + 1])
    return 0.0, 0.0, 0.0


@njit(cache=True)
def drive_at(t, sched):
    """Motor M0 (N*m) and slope s (N*m*s) at t: piecewise linear, held outside."""
    ts = sched[0]
    m = ts.shape[0]
    if m == 1 or t <= ts[0]:
        return sched[1, 0], sched[2, 0]
    if t >= ts[m - 1]:
        return sched[1, m - 1], sched[2, m - 1]
    lo, hi = 0, m - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if ts[mid] <= t:
            lo = mid
        else:
            hi = mid
    span = ts[hi] - ts[lo]
    if span <= 0.0:
        return sched[1, hi], sched[2, hi]
    f = (t - ts[lo]) / span
    return ((1.0 - f) * sched[1, lo] + f * sched[1, hi],
            (1.0 - f) * sched[2, lo] + f * sched[2, hi])


@njit(cache=True)
def deriv(t, y, P, out, F):
    """The first-order right-hand side, in one flat body (no nested calls
    that pass arrays: each costs more than the physics here).

    y = (q, v, ...) with n = len(q); writes out[:n] = v, out[n:2n] = Minv F,
    out[2n:2n+4] = the powers (drive - load, shaft on structure, dissipation,
    base); F (n) is scratch and holds the forces on return.
    """
    Minv, Ks, C, d, base, scal, sched, gpar, gtab = P
    nx = Ks.shape[0]
    n = nx + 2
    c2, e, b2y, kload = scal[0], scal[1], scal[2], scal[3]
    th = y[nx + 1]
    W = y[n + nx + 1]
    ct = math.cos(th)
    st = math.sin(th)
    # the common cases without a call: no ground motion, a constant drive
    if gpar[0] == 0.0:
        ug, vg, ag = 0.0, 0.0, 0.0
    else:
        ug, vg, ag = ground(t, gpar, gtab)
    if sched.shape[1] == 1:
        M0, s = sched[1, 0], sched[2, 0]
    else:
        M0, s = drive_at(t, sched)
    dz = 0.0
    for i in range(nx):
        dz += d[i] * y[i]
    sx = dz - e * ct
    p_diss = 0.0
    p_base = 0.0
    for i in range(nx):
        fb = base[0, i] * ug + base[1, i] * vg + base[2, i] * ag
        acc = -c2 * d[i] * sx + fb
        for j in range(nx):
            acc -= Ks[i, j] * y[j] + C[i, j] * y[n + j]
            p_diss += y[n + i] * C[i, j] * y[n + j]
        F[i] = acc
        p_base += fb * y[n + i]
    yy = y[nx]
    vy = y[n + nx]
    F[nx] = -c2 * (yy - e * st) - b2y * vy
    p_diss += b2y * vy * vy
    drive = M0 - s * W - kload * W * abs(W)
    shaft = -c2 * e * dz * st + c2 * e * yy * ct
    F[nx + 1] = drive + shaft
    for i in range(n):
        acc = 0.0
        for j in range(n):
            acc += Minv[i, j] * F[j]
        out[n + i] = acc
        out[i] = y[n + i]
    out[2 * n] = drive * W
    out[2 * n + 1] = -shaft * W
    out[2 * n + 2] = p_diss
    out[2 * n + 3] = p_base


@njit(cache=True)
def jacobians(t, q, v, P, Jq, Jv):
    """dF/dq and dF/dv of the forces of ``deriv`` into Jq, Jv."""
    Minv, Ks, C, d, base, scal, sched, gpar, gtab = P
    nx = Ks.shape[0]
    n = nx + 2
    c2, e, b2y, kload = scal[0], scal[1], scal[2], scal[3]
    th = q[nx + 1]
    W = v[nx + 1]
    ct = math.cos(th)
    st = math.sin(th)
    dz = 0.0
    for i in range(nx):
        dz += d[i] * q[i]
    for i in range(n):
        for j in range(n):
            Jq[i, j] = 0.0
            Jv[i, j] = 0.0
    for i in range(nx):
        for j in range(nx):
            Jq[i, j] = -Ks[i, j] - c2 * d[i] * d[j]
            Jv[i, j] = -C[i, j]
        Jq[i, nx + 1] = -c2 * d[i] * e * st
        Jq[nx + 1, i] = -c2 * e * d[i] * st
    y = q[nx]
    Jq[nx, nx] = -c2
    Jq[nx, nx + 1] = c2 * e * ct
    Jv[nx, nx] = -b2y
    M0, s = drive_at(t, sched)
    Jq[nx + 1, nx] = c2 * e * ct
    Jq[nx + 1, nx + 1] = -c2 * e * dz * ct - c2 * e * y * st
    Jv[nx + 1, nx + 1] = -s - 2.0 * kload * abs(W)


@njit(cache=True)
def _start_output(q, v, P, out_q, out_v, out_w, out_peak):
    """Clear the fixed-step schemes' peaks, store the initial state as row 0
    (no work done yet); returns the number of output rows."""
    out_peak[:, :] = 0.0
    _store_sample(0, q, v, np.zeros(out_w.shape[1]), out_q, out_v, out_w)
    _record_peak(q, P, out_peak[0])
    return out_q.shape[0]


@njit(cache=True)
def _store_sample(k, q, v, W, out_q, out_v, out_w):
    """Row k of the fixed-step schemes' output: coordinates, velocities, work."""
    for i in range(q.shape[0]):
        out_q[k, i] = q[i]
        out_v[k, i] = v[i]
    for i in range(W.shape[0]):
        out_w[k, i] = W[i]


@njit(cache=True)
def _record_peak(q, P, peak_row):
    """peak_row[i] = max(peak_row[i], |q_i|); the last entry tracks |tip.z|."""
    base = P[4]
    nx = base.shape[1]
    n = q.shape[0]
    tipz = 0.0
    for i in range(nx):
        tipz += base[3, i] * q[i]
    for i in range(n):
        if abs(q[i]) > peak_row[i]:
            peak_row[i] = abs(q[i])
    if abs(tipz) > peak_row[n]:
        peak_row[n] = abs(tipz)


@njit(cache=True)
def rhs_first_order(t, y, P):
    """y' for y = (q, v, work): the first-order form scipy integrates."""
    out = np.empty_like(y)
    F = np.empty(P[0].shape[0])
    deriv(t, y, P, out, F)
    return out


@njit(cache=True)
def jac_first_order(t, y, P):
    """d(y')/dy of ``rhs_first_order`` (the work rows are left zero)."""
    Minv = P[0]
    n = Minv.shape[0]
    m = y.shape[0]
    J = np.zeros((m, m))
    Jq = np.empty((n, n))
    Jv = np.empty((n, n))
    jacobians(t, y[:n], y[n:2 * n], P, Jq, Jv)
    Aq = Minv @ Jq
    Av = Minv @ Jv
    for i in range(n):
        J[i, n + i] = 1.0
        for j in range(n):
            J[n + i, j] = Aq[i, j]
            J[n + i, n + j] = Av[i, j]
    return J


# --------------------------------------------------------------------------
# Dormand-Prince 5(4), scipy RK45's tableau and step control

_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
_A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]])
_B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
_E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
# scipy's RK45 dense output (Shampine's 4th-order continuous extension):
# y(t + x h) = y + h K^T P [x, x**2, x**3, x**4]
_P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]])


@njit(cache=True)
def _inside(t, lo, hi):
    """t clamped inside the segment [lo, hi]: one-sided forcing at breakpoints."""
    eps = 1e-12 * (abs(lo) + abs(hi) + 1.0)
    if t < lo + eps:
        return lo + eps
    if t > hi - eps:
        return hi - eps
    return t


@njit(cache=True)
def _rms_norm(x, scale, m):
    s = 0.0
    for i in range(m):
        r = x[i] / scale[i]
        s += r * r
    return math.sqrt(s / m)


@njit(cache=True)
def _initial_step(t, y, f0, P, lo, hi, rtol, atol, m, F):
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
    deriv(_inside(t + h0, lo, hi), y1, P, f1, F)
    diff = f1 - f0
    d2 = _rms_norm(diff, scale, m) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 5.0)
    return min(100 * h0, h1)


@njit(cache=True)
def dp5_solve(P, y0, t0, t1, breaks, rtol, atol, t_out, wrap, max_steps,
              out_y, out_peak, h_max):
    """Integrate y' = f from t0 to t1 (adaptive Dormand-Prince 5(4)).

    breaks: sorted times where the forcing may jump (the step lands on each);
    atol: per-component absolute tolerances of (q, v, work); give the work
    states a huge atol so they never bind.  Writes y at t_out into out_y (theta unwrapped) and,
    per output interval, the largest |q_i| at the steps and outputs inside it
    into out_peak.  Returns (status, nfev, n_accepted, n_rejected, h_min_used).
    """
    n = P[0].shape[0]
    nth = n - 1                         # theta's index
    m = 2 * n                           # error-controlled components
    N = y0.shape[0]
    F = np.empty(n)
    K = np.zeros((7, N))
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
        _record_peak(y[:n], P, out_peak[kout])
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
        deriv(_inside(t, lo, hi), y, P, K[0], F)
        nfev += 1
        if h <= 0.0:
            h = _initial_step(t, y, K[0], P, lo, hi, rtol, atol, N, F)
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
                            acc += h * _A[st, j] * K[j, i]
                        ytmp[i] = acc
                    deriv(_inside(t + _C[st] * h, lo, hi), ytmp, P, K[st], F)
                for i in range(N):
                    acc = y[i]
                    for j in range(6):
                        acc += h * _B[j] * K[j, i]
                    ynew[i] = acc
                deriv(_inside(t + h, lo, hi), ynew, P, K[6], F)
                nfev += 6
                for i in range(N):
                    acc = 0.0
                    for j in range(7):
                        acc += _E[j] * K[j, i]
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
                        kj = K[j, i]
                        acc += kj * (_P[j, 0] * px0 + _P[j, 1] * px1 + _P[j, 2] * px2 + _P[j, 3] * px3)
                    out_y[kout, i] = y[i] + hs * acc
                _record_peak(out_y[kout, :n], P, out_peak[kout])
                out_y[kout, nth] += turns
                kout += 1
            if kout < nout:
                _record_peak(ynew[:n], P, out_peak[kout])
            for i in range(N):
                y[i] = ynew[i]
                K[0, i] = K[6, i]
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
# Generalized-alpha family (Newmark, HHT, Chung-Hulbert) and central difference


@njit(cache=True)
def _eval(t, q, v, P, yw, dw, F):
    """Accelerations and powers at (t, q, v) through ``deriv``: dw[n:2n], dw[2n:]."""
    n = q.shape[0]
    for i in range(n):
        yw[i] = q[i]
        yw[n + i] = v[i]
    deriv(t, yw, P, dw, F)


@njit(cache=True)
def genalpha_solve(P, q0, v0, t0, h, nsteps, stride, alpha_m, alpha_f, beta, gamma,
                   newton_tol, max_iter, out_q, out_v, out_w, out_peak):
    """Fixed-step generalized-alpha with Newton iterations on the analytic Jacobian.

    Equilibrium is enforced at the weighted point
        (1-am) a_{n+1} + am a_n = Minv F(t_{n+1-af}, q_{n+1-af}, v_{n+1-af}),
    x_{n+1-af} = (1-af) x_{n+1} + af x_n, with Newmark's updates.  Output
    every ``stride`` steps (row 0 is the initial state).  Work integrals by
    the trapezoidal rule.  Returns (status, n_force_evaluations, newton_iterations).
    """
    n = q0.shape[0]
    Minv = P[0]
    F = np.empty(n)
    yw = np.zeros(2 * n + N_WORK)
    dw = np.zeros(2 * n + N_WORK)
    q = q0.copy()
    v = v0.copy()
    _eval(t0, q, v, P, yw, dw, F)
    a = dw[n:2 * n].copy()
    nfev = 1
    nit = 0
    W = np.zeros(N_WORK)
    pw_old = dw[2 * n:].copy()
    qn = np.empty(n)
    vn = np.empty(n)
    an = np.empty(n)
    qm = np.empty(n)
    vm = np.empty(n)
    R = np.empty(n)
    Jq = np.empty((n, n))
    Jv = np.empty((n, n))
    Jr = np.empty((n, n))
    nout = _start_output(q, v, P, out_q, out_v, out_w, out_peak)
    kout = 1
    t = t0
    for step in range(nsteps):
        tf = t + (1.0 - alpha_f) * h
        # predictor: a_{n+1} = a_n
        for i in range(n):
            an[i] = a[i]
        converged = False
        r0 = 0.0
        r_prev = 0.0
        for it in range(max_iter + 1):
            for i in range(n):
                qn[i] = q[i] + h * v[i] + h * h * ((0.5 - beta) * a[i] + beta * an[i])
                vn[i] = v[i] + h * ((1.0 - gamma) * a[i] + gamma * an[i])
                qm[i] = (1.0 - alpha_f) * qn[i] + alpha_f * q[i]
                vm[i] = (1.0 - alpha_f) * vn[i] + alpha_f * v[i]
            _eval(tf, qm, vm, P, yw, dw, F)
            nfev += 1
            rn = 0.0
            ref = 0.0
            for i in range(n):
                acc = dw[n + i]
                R[i] = (1.0 - alpha_m) * an[i] + alpha_m * a[i] - acc
                rn += R[i] * R[i]
                ref += acc * acc + an[i] * an[i]
            rn = math.sqrt(rn)
            if it == 0:
                r0 = rn
            # converged when the residual is small against the accelerations,
            # or down to round-off of the first residual (stiff modes: the
            # terms of the residual are far larger than the accelerations),
            # or no longer falling once far below the first (stagnation at
            # round-off).  A linear problem needs one update.
            if it > 0 and (rn <= newton_tol * (math.sqrt(ref) + 1e-300) or rn <= 1e-13 * r0
                           or (it > 1 and rn >= 0.5 * r_prev and rn <= 1e-8 * r0)):
                converged = True
                break
            r_prev = rn
            if it == max_iter:
                break
            jacobians(tf, qm, vm, P, Jq, Jv)
            for i in range(n):
                for j in range(n):
                    s = 0.0
                    for l in range(n):
                        s += Minv[i, l] * (beta * h * h * Jq[l, j] + gamma * h * Jv[l, j])
                    Jr[i, j] = -(1.0 - alpha_f) * s
                Jr[i, i] += 1.0 - alpha_m
            da = np.linalg.solve(Jr, R)
            for i in range(n):
                an[i] -= da[i]
            nit += 1
        if not converged:
            return NEWTON_FAILED, nfev, nit
        t = t0 + (step + 1) * h
        for i in range(n):
            q[i] = qn[i]
            v[i] = vn[i]
            a[i] = an[i]
            if not math.isfinite(q[i]):
                return NOT_FINITE, nfev, nit
        _eval(t, q, v, P, yw, dw, F)
        nfev += 1
        for i in range(N_WORK):
            W[i] += 0.5 * h * (pw_old[i] + dw[2 * n + i])
            pw_old[i] = dw[2 * n + i]
        if kout < nout:
            _record_peak(q, P, out_peak[kout])
        if (step + 1) % stride == 0 and kout < nout:
            _store_sample(kout, q, v, W, out_q, out_v, out_w)
            kout += 1
    return OK, nfev, nit


@njit(cache=True)
def cd_solve(P, q0, v0, t0, h, nsteps, stride, out_q, out_v, out_w, out_peak):
    """Explicit central difference (velocity-Verlet form).

    v_{n+1/2} = v_n + h/2 a_n;  q_{n+1} = q_n + h v_{n+1/2};
    a_{n+1} = Minv F(t_{n+1}, q_{n+1}, v_n + h a_n);  v_{n+1} = v_{n+1/2} + h/2 a_{n+1}.
    The velocity-dependent forces use the Euler-predicted velocity, which
    keeps the scheme explicit and second order.  Stable for h < 2/omega_max
    (undamped).  Returns (status, nfev, 0).
    """
    n = q0.shape[0]
    F = np.empty(n)
    yw = np.zeros(2 * n + N_WORK)
    dw = np.zeros(2 * n + N_WORK)
    q = q0.copy()
    v = v0.copy()
    vp = np.empty(n)
    _eval(t0, q, v, P, yw, dw, F)
    a = dw[n:2 * n].copy()
    nfev = 1
    W = np.zeros(N_WORK)
    pw_old = dw[2 * n:].copy()
    nout = _start_output(q, v, P, out_q, out_v, out_w, out_peak)
    kout = 1
    for step in range(nsteps):
        t = t0 + (step + 1) * h
        for i in range(n):
            vp[i] = v[i] + h * a[i]
            v[i] += 0.5 * h * a[i]
            q[i] += h * v[i]
        _eval(t, q, vp, P, yw, dw, F)
        nfev += 1
        for i in range(n):
            a[i] = dw[n + i]
            v[i] += 0.5 * h * a[i]
            if not math.isfinite(q[i]) or abs(q[i]) > 1e100:
                return NOT_FINITE, nfev, 0
        for i in range(N_WORK):
            W[i] += 0.5 * h * (pw_old[i] + dw[2 * n + i])
            pw_old[i] = dw[2 * n + i]
        if kout < nout:
            _record_peak(q, P, out_peak[kout])
        if (step + 1) % stride == 0 and kout < nout:
            _store_sample(kout, q, v, W, out_q, out_v, out_w)
            kout += 1
    return OK, nfev, 0


# --------------------------------------------------------------------------
# Many runs in one compiled loop


@njit(cache=True)
def dp5_batch(P, y0, t0, t1, breaks, rtol, atol, t_out, wrap, max_steps, h_max,
              torque_scale, slope, load, eccentricity, shaft_stiffness,
              out_y, out_peak, stats):
    """Run ``dp5_solve`` once per entry of the per-run parameter arrays.

    torque_scale multiplies the schedule's M0; slope, load, eccentricity and
    shaft_stiffness replace s, k, e and c2 where they are not NaN.  out_y:
    (runs, n_out, N), out_peak: (runs, n_out, n + 1), stats: (runs, 5) with
    status, nfev, accepted, rejected steps, smallest step.
    """
    Minv, Ks, C, d, base, scal, sched, gpar, gtab = P
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
        Pr = (Minv, Ks, C, d, base, sc, sh, gpar, gtab)
        y = y0.copy()
        res = dp5_solve(Pr, y, t0, t1, breaks, rtol, atol, t_out, wrap, max_steps,
                        out_y[r], out_peak[r], h_max)
        stats[r, 0] = res[0]
        stats[r, 1] = res[1]
        stats[r, 2] = res[2]
        stats[r, 3] = res[3]
        stats[r, 4] = res[4]
