"""Fixed-step schemes, compiled for the rotor-structure model (rotorpillar.reduced.rhs).

- ``genalpha_solve``: the generalized-alpha family (Chung & Hulbert 1993)
  with Newton iterations on the analytic Jacobian: Newmark average
  acceleration (alpha_m = alpha_f = 0, beta = 1/4, gamma = 1/2), HHT-alpha
  (alpha_m = 0) and Chung-Hulbert by rho_inf; ``genalpha_parameters`` gives
  each one's (alpha_m, alpha_f, beta, gamma).
- ``cd_solve``: explicit central difference in velocity-Verlet form,
  conditionally stable for h < 2/omega_max.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .rhs import N_WORK, NEWTON_FAILED, NOT_FINITE, OK, Floats, Packed, deriv_flat, flatten, jacobians, record_peak


@njit(cache=True)
def _start_output(
    q: Floats, v: Floats, par: Floats, out_q: Floats, out_v: Floats, out_w: Floats, out_peak: Floats
) -> int:
    """Clear the fixed-step schemes' peaks, store the initial state as row 0
    (no work done yet); returns the number of output rows."""
    out_peak[:, :] = 0.0
    _store_sample(0, q, v, np.zeros(out_w.shape[1]), out_q, out_v, out_w)
    record_peak(q, q.shape[0], par, out_peak, 0)
    return out_q.shape[0]


@njit(cache=True)
def _store_sample(k: int, q: Floats, v: Floats, W: Floats, out_q: Floats, out_v: Floats, out_w: Floats) -> None:
    """Row k of the fixed-step schemes' output: coordinates, velocities, work."""
    for i in range(q.shape[0]):
        out_q[k, i] = q[i]
        out_v[k, i] = v[i]
    for i in range(W.shape[0]):
        out_w[k, i] = W[i]


@njit(cache=True)
def _eval(t: float, q: Floats, v: Floats, par: Floats, yw: Floats, dw: Floats) -> None:
    """Accelerations and powers at (t, q, v) through ``deriv_flat``: dw[n:2n], dw[2n:]."""
    n = q.shape[0]
    for i in range(n):
        yw[i] = q[i]
        yw[n + i] = v[i]
    deriv_flat(t, yw, par, dw, 0)


@njit(cache=True)
def _end_of_step(
    step: int,
    stride: int,
    h: float,
    n: int,
    q: Floats,
    v: Floats,
    dw: Floats,
    W: Floats,
    pw_old: Floats,
    par: Floats,
    kout: int,
    nout: int,
    out_q: Floats,
    out_v: Floats,
    out_w: Floats,
    out_peak: Floats,
) -> int:
    """A fixed-step scheme's step, closed: the work by the trapezoid rule, the
    peak of the output interval, the sample at every stride-th step.  Returns
    the next output index."""
    for i in range(N_WORK):
        W[i] += 0.5 * h * (pw_old[i] + dw[2 * n + i])
        pw_old[i] = dw[2 * n + i]
    if kout < nout:
        record_peak(q, n, par, out_peak, kout)
    if (step + 1) % stride == 0 and kout < nout:
        _store_sample(kout, q, v, W, out_q, out_v, out_w)
        kout += 1
    return kout


@njit(cache=True)
def genalpha_solve(
    P: Packed,
    q0: Floats,
    v0: Floats,
    t0: float,
    h: float,
    nsteps: int,
    stride: int,
    alpha_m: float,
    alpha_f: float,
    beta: float,
    gamma: float,
    newton_tol: float,
    max_iter: int,
    out_q: Floats,
    out_v: Floats,
    out_w: Floats,
    out_peak: Floats,
) -> tuple[int, int, int]:
    """Fixed-step generalized-alpha with Newton iterations on the analytic Jacobian.

    Equilibrium is enforced at the weighted point
        (1-am) a_{n+1} + am a_n = Minv F(t_{n+1-af}, q_{n+1-af}, v_{n+1-af}),
    x_{n+1-af} = (1-af) x_{n+1} + af x_n, with Newmark's updates.  Output
    every ``stride`` steps (row 0 is the initial state).  Work integrals by
    the trapezoidal rule.  Returns (status, n_force_evaluations, newton_iterations).
    """
    n = q0.shape[0]
    Minv = P[0]
    par = flatten(P)
    yw = np.zeros(2 * n + N_WORK)
    dw = np.zeros(2 * n + N_WORK)
    q = q0.copy()
    v = v0.copy()
    _eval(t0, q, v, par, yw, dw)
    a = dw[n : 2 * n].copy()
    nfev = 1
    nit = 0
    W = np.zeros(N_WORK)
    pw_old = dw[2 * n :].copy()
    qn = np.empty(n)
    vn = np.empty(n)
    an = np.empty(n)
    qm = np.empty(n)
    vm = np.empty(n)
    R = np.empty(n)
    Jq = np.empty((n, n))
    Jv = np.empty((n, n))
    Jr = np.empty((n, n))
    nout = _start_output(q, v, par, out_q, out_v, out_w, out_peak)
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
            _eval(tf, qm, vm, par, yw, dw)
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
            if it > 0 and (
                rn <= newton_tol * (math.sqrt(ref) + 1e-300)
                or rn <= 1e-13 * r0
                or (it > 1 and rn >= 0.5 * r_prev and rn <= 1e-8 * r0)
            ):
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
        _eval(t, q, v, par, yw, dw)
        nfev += 1
        kout = _end_of_step(step, stride, h, n, q, v, dw, W, pw_old, par, kout, nout, out_q, out_v, out_w, out_peak)
    return OK, nfev, nit


@njit(cache=True)
def cd_solve(
    P: Packed,
    q0: Floats,
    v0: Floats,
    t0: float,
    h: float,
    nsteps: int,
    stride: int,
    out_q: Floats,
    out_v: Floats,
    out_w: Floats,
    out_peak: Floats,
) -> tuple[int, int, int]:
    """Explicit central difference (velocity-Verlet form).

    v_{n+1/2} = v_n + h/2 a_n;  q_{n+1} = q_n + h v_{n+1/2};
    a_{n+1} = Minv F(t_{n+1}, q_{n+1}, v_n + h a_n);  v_{n+1} = v_{n+1/2} + h/2 a_{n+1}.
    The velocity-dependent forces use the Euler-predicted velocity, which
    keeps the scheme explicit and second order.  Stable for h < 2/omega_max
    (undamped).  Returns (status, nfev, 0).
    """
    n = q0.shape[0]
    par = flatten(P)
    yw = np.zeros(2 * n + N_WORK)
    dw = np.zeros(2 * n + N_WORK)
    q = q0.copy()
    v = v0.copy()
    vp = np.empty(n)
    _eval(t0, q, v, par, yw, dw)
    a = dw[n : 2 * n].copy()
    nfev = 1
    W = np.zeros(N_WORK)
    pw_old = dw[2 * n :].copy()
    nout = _start_output(q, v, par, out_q, out_v, out_w, out_peak)
    kout = 1
    for step in range(nsteps):
        t = t0 + (step + 1) * h
        for i in range(n):
            vp[i] = v[i] + h * a[i]
            v[i] += 0.5 * h * a[i]
            q[i] += h * v[i]
        _eval(t, q, vp, par, yw, dw)
        nfev += 1
        for i in range(n):
            a[i] = dw[n + i]
            v[i] += 0.5 * h * a[i]
            if not math.isfinite(q[i]) or abs(q[i]) > 1e100:
                return NOT_FINITE, nfev, 0
        kout = _end_of_step(step, stride, h, n, q, v, dw, W, pw_old, par, kout, nout, out_q, out_v, out_w, out_peak)
    return OK, nfev, 0


def genalpha_parameters(method: str, hht_alpha: float, rho_inf: float) -> tuple[float, float, float, float]:
    """(alpha_m, alpha_f, beta, gamma) of ``genalpha_solve`` for ``method`` (newmark, hht with
    ``hht_alpha``, generalized_alpha with ``rho_inf``).

    Newmark average acceleration: (0, 0, 1/4, 1/2).  HHT-alpha with
    alpha in [-1/3, 0]: alpha_f = -alpha, gamma = (1 - 2 alpha)/2,
    beta = (1 - alpha)**2/4.  Chung-Hulbert: alpha_m = (2 rho - 1)/(rho + 1),
    alpha_f = rho/(rho + 1), gamma = 1/2 - alpha_m + alpha_f,
    beta = (1 - alpha_m + alpha_f)**2/4.
    """
    if method == "newmark":
        return 0.0, 0.0, 0.25, 0.5
    if method == "hht":
        a = hht_alpha
        return 0.0, -a, (1 - a) ** 2 / 4, 0.5 - a
    if method == "generalized_alpha":
        r = rho_inf
        am, af = (2 * r - 1) / (r + 1), r / (r + 1)
        return am, af, 0.25 * (1 - am + af) ** 2, 0.5 - am + af
    raise ValueError(method)
