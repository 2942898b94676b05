"""The rotor-structure model's right-hand side: compiled (numba) for the
integrators, and the paper's Eq. 4 as published in plain numpy.

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

The integrators' loops see P flattened once per run into one vector
(``flatten``, offsets by ``layout``) and call ``deriv_flat``.

Four work integrals ride along with the state (not error-controlled):
drive minus load (Md - Mc) W, work done by the shaft torque on the
structure, dissipation, and base-force work; they close the energy balance.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

#: A float64 array: every array the kernels take.
Floats = NDArray[np.float64]
#: The model's arrays as one tuple (Minv, Ks, C, d, base, scal, sched, gpar, gtab): above.
Packed = tuple[Floats, Floats, Floats, Floats, Floats, Floats, Floats, Floats, Floats]

N_WORK = 4
#: status codes of the integrators
OK, MAX_STEPS, STEP_TOO_SMALL, NOT_FINITE, NEWTON_FAILED = 0, 1, 2, 3, 4


def eq4_rhs(
    y: Floats,
    m_A: float,
    m_C: float,
    J: float,
    e: float,
    c1: float,
    c2: float,
    b1: float,
    b2: float,
    M0: float,
    s: float,
    k: float,
    q5: float = 0.0,
    q5_rate: float = 0.0,
    q6: float = 0.0,
    q6_rate: float = 0.0,
) -> Floats:
    """Eq. 4 as published, the reference for deriv_flat: y' for y = (q1..q4, q1'..q4').

    q1 pillar tip X, q2 and q3 rotor mass centre X and Y, q4 rotor angle (m,
    rad); m_A = m_r + m* and m_C (kg), J (kg*m**2), e (m), c1, c2 (N/m),
    b1, b2 (N*s/m); the drive Md = M0 - s q4' and the load Mc = k q4' |q4'|
    (N*m, the paper's Eq. 22); q5, q6 the ground's X and Y displacement
    (m) and their rates (m/s).  With c0 = c1 + c2 and b0 = b1 + b2::

        m_A q1'' + c0 q1 + b0 q1' - c2 q2 = -c2 e cos q4 + c0 q5 + b0 q5'
        m_C q2'' - c2 q1 + c2 q2 + b2 q2' =  c2 e cos q4 + c2 q5 + b2 q5'
        m_C q3''         + c2 q3 + b2 q3' =  c2 e sin q4 + c2 q6 + b2 q6'
        J q4'' = Md - Mc - c2 e (q2 - q1) sin q4 + c2 e q3 cos q4

    Plain numpy, one call per evaluation: the reference the compiled
    ``deriv_flat`` is checked against, and the hand-written right-hand side of
    the benchmarks.
    """
    q1, q2, q3, q4, v1, v2, v3, v4 = y
    c0, b0 = c1 + c2, b1 + b2
    return np.array(
        [
            v1,
            v2,
            v3,
            v4,
            (-c0 * q1 - b0 * v1 + c2 * q2 - c2 * e * np.cos(q4) + c0 * q5 + b0 * q5_rate) / m_A,
            (c2 * q1 - c2 * q2 - b2 * v2 + c2 * e * np.cos(q4) + c2 * q5 + b2 * q5_rate) / m_C,
            (-c2 * q3 - b2 * v3 + c2 * e * np.sin(q4) + c2 * q6 + b2 * q6_rate) / m_C,
            (M0 - s * v4 - k * v4 * abs(v4) - c2 * e * (q2 - q1) * np.sin(q4) + c2 * e * q3 * np.cos(q4)) / J,
        ]
    )


@njit(cache=True)
def ground_flat(t: float, a: Floats, o_gpar: int, o_gtab: int, ng: int) -> tuple[float, float, float]:
    """Ground displacement, velocity, acceleration at t (m, m/s, m/s**2), from
    gpar at a[o_gpar:] and the table gtab (3, ng) at a[o_gtab:] (``layout``)."""
    kind = int(a[o_gpar])
    if kind == 1:
        A, w, t0, t1 = a[o_gpar + 1], a[o_gpar + 2], a[o_gpar + 3], a[o_gpar + 4]
        if t >= t0 and t < t1:
            c = math.cos(w * t)
            s = math.sin(w * t)
            return A * (c - 1.0), -A * w * s, -A * w * w * c
        return 0.0, 0.0, 0.0
    if kind == 2:
        t0, dt = a[o_gpar + 3], a[o_gpar + 5]
        x = (t - t0) / dt
        if x < 0.0 or x > ng - 1:
            return 0.0, 0.0, 0.0
        i = int(x)
        if i >= ng - 1:
            i = ng - 2
        f = x - i
        u, v, w = o_gtab + i, o_gtab + ng + i, o_gtab + 2 * ng + i
        return ((1.0 - f) * a[u] + f * a[u + 1], (1.0 - f) * a[v] + f * a[v + 1], (1.0 - f) * a[w] + f * a[w + 1])
    return 0.0, 0.0, 0.0


@njit(cache=True)
def drive_flat(t: float, a: Floats, o: int, m: int) -> tuple[float, float]:
    """Motor M0 (N*m) and slope s (N*m*s) at t: piecewise linear, held outside;
    the schedule (3, m) of knot times, M0, s at a[o:] (``layout``)."""
    if m == 1 or t <= a[o]:
        return a[o + m], a[o + 2 * m]
    if t >= a[o + m - 1]:
        return a[o + 2 * m - 1], a[o + 3 * m - 1]
    lo, hi = 0, m - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if a[o + mid] <= t:
            lo = mid
        else:
            hi = mid
    span = a[o + hi] - a[o + lo]
    if span <= 0.0:
        return a[o + m + hi], a[o + 2 * m + hi]
    f = (t - a[o + lo]) / span
    return ((1.0 - f) * a[o + m + lo] + f * a[o + m + hi], (1.0 - f) * a[o + 2 * m + lo] + f * a[o + 2 * m + hi])


@njit(cache=True)
def drive_at(t: float, sched: Floats) -> tuple[float, float]:
    """``drive_flat`` of a schedule (3, m)."""
    return drive_flat(t, sched.ravel(), 0, sched.shape[1])


# The hot kernels see the model as one flat vector ``par`` (``flatten``): a
# compiled function that takes an array increments and decrements its
# reference count on every call, an atomic operation on memory the threads
# of a batch share; with the nine arrays of P (and views of the stage array)
# that was 70 % of a run-up batch's time (perf).  One vector: one count.
HEADER = 3
"""par[0:3] = nx, m (drive knots), ng (ground table length)"""


@njit(cache=True, inline="always")
def layout(nx: int, m: int, ng: int) -> tuple[int, int, int, int, int, int, int, int, int, int, int]:
    """Offsets in par of Minv (n, n), Ks, C (nx, nx), d (nx), base (4, nx), scal (4),
    sched (3, m), gpar (6), gtab (3, ng) and the force scratch F (n); then the size."""
    n = nx + 2
    o_minv = HEADER
    o_ks = o_minv + n * n
    o_c = o_ks + nx * nx
    o_d = o_c + nx * nx
    o_base = o_d + nx
    o_scal = o_base + 4 * nx
    o_sched = o_scal + 4
    o_gpar = o_sched + 3 * m
    o_gtab = o_gpar + 6
    o_f = o_gtab + 3 * ng
    return o_minv, o_ks, o_c, o_d, o_base, o_scal, o_sched, o_gpar, o_gtab, o_f, o_f + n


@njit(cache=True)
def _put(par: Floats, k: int, a: Floats) -> None:
    for i in range(a.shape[0]):
        for j in range(a.shape[1]):
            par[k] = a[i, j]
            k += 1


@njit(cache=True)
def flatten(P: Packed) -> Floats:
    """The tuple P as one vector (``layout``), with room for the forces."""
    Minv, Ks, C, d, base, scal, sched, gpar, gtab = P
    if gpar.shape[0] != 6:
        raise ValueError("gpar must have 6 entries")
    nx, m, ng = Ks.shape[0], sched.shape[1], gtab.shape[1]
    o = layout(nx, m, ng)
    par = np.zeros(o[10])
    par[0], par[1], par[2] = nx, m, ng
    _put(par, o[0], Minv)
    _put(par, o[1], Ks)
    _put(par, o[2], C)
    _put(par, o[3], d.reshape((1, nx)))
    _put(par, o[4], base)
    _put(par, o[5], scal.reshape((1, 4)))
    _put(par, o[6], sched)
    _put(par, o[7], gpar.reshape((1, gpar.shape[0])))
    _put(par, o[8], gtab)
    return par


@njit(cache=True)
def deriv_flat(t: float, y: Floats, par: Floats, out: Floats, o: int) -> None:
    """Eq. 4 in generic form: the first-order right-hand side y' of the flat model ``par``.

    Written into out[o:o + 2n + 4].

    y = (q, v, ...) with n = len(q); writes out[o:o + n] = v, the next n
    Minv F, then the powers (drive - load, shaft on structure, dissipation,
    base); the forces F are left in par's scratch.  One flat body: no nested
    calls that pass arrays in the common case (no ground motion, a constant
    drive).
    """
    nx, m, ng = int(par[0]), int(par[1]), int(par[2])
    n = nx + 2
    o_minv, o_ks, o_c, o_d, o_base, o_scal, o_sched, o_gpar, o_gtab, o_f, _ = layout(nx, m, ng)
    c2, e, b2y, kload = par[o_scal], par[o_scal + 1], par[o_scal + 2], par[o_scal + 3]
    th = y[nx + 1]
    W = y[n + nx + 1]
    ct = math.cos(th)
    st = math.sin(th)
    if par[o_gpar] == 0.0:
        ug, vg, ag = 0.0, 0.0, 0.0
    else:
        ug, vg, ag = ground_flat(t, par, o_gpar, o_gtab, ng)
    if m == 1:
        M0, s = par[o_sched + 1], par[o_sched + 2]
    else:
        M0, s = drive_flat(t, par, o_sched, m)
    dz = 0.0
    for i in range(nx):
        dz += par[o_d + i] * y[i]
    sx = dz - e * ct
    p_diss = 0.0
    p_base = 0.0
    for i in range(nx):
        fb = par[o_base + i] * ug + par[o_base + nx + i] * vg + par[o_base + 2 * nx + i] * ag
        acc = -c2 * par[o_d + i] * sx + fb
        for j in range(nx):
            cij = par[o_c + i * nx + j]
            acc -= par[o_ks + i * nx + j] * y[j] + cij * y[n + j]
            p_diss += y[n + i] * cij * y[n + j]
        par[o_f + i] = acc
        p_base += fb * y[n + i]
    yy = y[nx]
    vy = y[n + nx]
    par[o_f + nx] = -c2 * (yy - e * st) - b2y * vy
    p_diss += b2y * vy * vy
    drive = M0 - s * W - kload * W * abs(W)
    shaft = -c2 * e * dz * st + c2 * e * yy * ct
    par[o_f + nx + 1] = drive + shaft
    for i in range(n):
        acc = 0.0
        for j in range(n):
            acc += par[o_minv + i * n + j] * par[o_f + j]
        out[o + n + i] = acc
        out[o + i] = y[n + i]
    out[o + 2 * n] = drive * W
    out[o + 2 * n + 1] = -shaft * W
    out[o + 2 * n + 2] = p_diss
    out[o + 2 * n + 3] = p_base


@njit(cache=True)
def jacobians(t: float, q: Floats, v: Floats, P: Packed, Jq: Floats, Jv: Floats) -> None:
    """dF/dq and dF/dv of the forces of ``deriv_flat`` into Jq, Jv."""
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
def record_peak(q: Floats, n: int, par: Floats, peak: Floats, k: int) -> None:
    """peak[k, i] = max(peak[k, i], |q_i|) for i < n; peak[k, n] tracks |tip.z|
    (tip = row 3 of base in par)."""
    nx = n - 2
    o_tip = layout(nx, int(par[1]), int(par[2]))[4] + 3 * nx
    tipz = 0.0
    for i in range(nx):
        tipz += par[o_tip + i] * q[i]
    for i in range(n):
        if abs(q[i]) > peak[k, i]:
            peak[k, i] = abs(q[i])
    if abs(tipz) > peak[k, n]:
        peak[k, n] = abs(tipz)


@njit(cache=True)
def shaft_deflection_into(q: Floats, shaft: Floats, e: Floats, out: Floats, out_x: Floats) -> None:
    """The shaft's deflection (d.z - e cos theta, y - e sin theta) (m) for states
    q (k, n): z = q[:nx], y = q[nx], theta = q[nx + 1]; its size into out (k,),
    its x component into out_x (k,).

    Compiled and scalar (libm per value) on purpose: numpy's vector cos/sin
    take a SIMD path on the aligned part of an array and libm on the rest, so
    the last ulp depends on where the allocator put the array, and a study's
    numbers would depend on the process its batch ran in (CI saw it).
    """
    nx = shaft.shape[0]
    for k in range(q.shape[0]):
        th = q[k, nx + 1]
        dz = 0.0
        for i in range(nx):
            dz += shaft[i] * q[k, i]
        out_x[k] = dz - e[k] * math.cos(th)
        out[k] = math.hypot(out_x[k], q[k, nx] - e[k] * math.sin(th))


@njit(cache=True)
def rhs_first_order(t: float, y: Floats, par: Floats) -> Floats:
    """y' for y = (q, v, work): the first-order form scipy integrates, on the
    flat model ``par`` (``flatten(P)``, once per run)."""
    out = np.empty_like(y)
    deriv_flat(t, y, par, out, 0)
    return out


@njit(cache=True)
def jac_first_order(t: float, y: Floats, P: Packed) -> Floats:
    """d(y')/dy of ``rhs_first_order`` (the work rows are left zero)."""
    Minv = P[0]
    n = Minv.shape[0]
    m = y.shape[0]
    J = np.zeros((m, m))
    Jq = np.empty((n, n))
    Jv = np.empty((n, n))
    jacobians(t, y[:n], y[n : 2 * n], P, Jq, Jv)
    Aq = Minv @ Jq
    Av = Minv @ Jv
    for i in range(n):
        J[i, n + i] = 1.0
        for j in range(n):
            J[n + i, j] = Aq[i, j]
            J[n + i, n + j] = Av[i, j]
    return J
