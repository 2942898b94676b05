"""The rotor-structure model's right-hand side: compiled (numba) for the
integrators, and the paper's Eq. 4 as published in plain numpy.

One generic model covers the paper's Eq. 4, the planar modal model
(rotorpillar.reduced.rotor_models) and the spatial model
(rotorpillar.reduced.spatial_model): nz structural coordinates Z (the
pillar's, the rotor centre's; the last one, y, is the planar models' rotor
centre in Y, the paper's q3) and the rotor angle theta.  With M the mass
matrix (its inverse Minv given; a zero row for theta prescribes a constant
speed), the forces are

    F_Z     = -K Z - (C + W G) Z' - c2 d_x (d_x.Z - e cos theta) - c2 d_v (d_v.Z - e sin theta)
              + sum_c (kb_c u_c + cb_c v_c + mb_c a_c) + Md r + U_c W**2 b(theta)
    F_theta = Md(t, W) - Mc(W) + c2 e (-(d_x.Z) sin theta + (d_v.Z) cos theta) - U_c W (b(theta).Z')

with W = theta', Md = M0(t) - s(t) W (a piecewise-linear schedule), Mc = k W |W|,
d_x and d_v the shaft-deflection vectors in the rotor's plane and in the vertical
(rotor centre minus bearing), G the gyroscopic matrix per unit speed (J_C on the
tilts), r the generalised force of the motor's reaction per unit torque,
b(theta) = b_c cos theta + b_s sin theta the couple unbalance's direction and
(u_c, v_c, a_c) ground component c's displacement, velocity and acceleration.
The planar models have Z = (z, y), K = diag(Ks, 0), C = diag(C, b2), G = 0,
d_x = (d, 0), d_v = (0, 1), r = b = 0 and one ground component: Eq. 4 as the
paper writes it (q3's equation apart).  The couple unbalance's torque on theta
closes the energy balance; the terms in W' it also brings are left out (they
act only where the speed changes within a revolution).

The arrays travel as one tuple P = (Minv, K, C, G, shaft, base, scal, sched,
gpar, gtab), built by the models' ``pack``:

- shaft (2, nz):      d_x, d_v
- base  (3 nc + 4, nz): per ground component c rows kb_c, cb_c, mb_c; then
  the tip vector (tip X = tip.Z, for the peaks), r, b_c, b_s
- scal  (4,):    c2, e, U_c, k
- sched (3, m):  knot times, M0, s
- gpar  (6,):    kind (0 none, 1 harmonic pulse on component 0, 2 table), A, omega, t0, t1, dt
- gtab  (3 nc, ng): per component tabulated u_g, v_g, a_g on t0 + i dt (kind 2)

The integrators' loops see P flattened once per run into one vector
(``flatten``, offsets by ``layout``) and call ``deriv_flat``.

Four work integrals ride along with the state (not error-controlled):
drive minus load (Md - Mc) W with the motor reaction's work on the gondola,
work done by the rotor (shaft torque, couple, reaction) on the structure,
dissipation, and base-force work; they close the energy balance.
"""

from __future__ import annotations

import hashlib
import math
import os
from pathlib import Path
from typing import Any

import numba.core.config
import numpy as np
from numba import njit
from numpy.typing import NDArray

#: The modules whose kernels numba caches (``@njit(cache=True)``); dp5 and fixed_step inline
#: this module's functions, and numba's own staleness stamp looks at a kernel's own file only.
KERNEL_SOURCES = ("rhs.py", "dp5.py", "fixed_step.py")


def kernel_cache_dir(sources: tuple[Path, ...], root: Path) -> Path:
    """numba's cache directory under ``root`` for kernels compiled from ``sources``: named by a
    hash of their contents, so that a change in one module invalidates the compiled code of
    every kernel that inlined it (numba's stamp, a file's own time and size, misses that: a
    fixed-step run-up once read a stale cache after rhs.py changed and stayed at 0 rad/s)."""
    h = hashlib.sha256()
    for p in sources:
        h.update(p.name.encode() + b"\0" + p.read_bytes())
    return root / h.hexdigest()[:16]


def _use_kernel_cache() -> None:
    """Point numba's cache at :func:`kernel_cache_dir` (``$XDG_CACHE_HOME`` or ``~/.cache``,
    ``rotorpillar/numba``) unless the user set ``NUMBA_CACHE_DIR``; before the first
    decorator below, which is when numba reads it."""
    config: Any = numba.core.config  # untyped: numba ships no stubs
    if config.CACHE_DIR:
        return
    here = Path(__file__).resolve().parent
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "rotorpillar" / "numba"
    config.CACHE_DIR = str(kernel_cache_dir(tuple(here / f for f in KERNEL_SOURCES), base))


_use_kernel_cache()

#: A float64 array: every array the kernels take.
Floats = NDArray[np.float64]
#: The model's arrays as one tuple (Minv, K, C, G, shaft, base, scal, sched, gpar, gtab): above.
Packed = tuple[Floats, Floats, Floats, Floats, Floats, Floats, Floats, Floats, Floats, Floats]

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
def ground_flat(t: float, a: Floats, o_gpar: int, o_gtab: int, ng: int, c: int = 0) -> tuple[float, float, float]:
    """Component c's ground displacement, velocity, acceleration at t (m, m/s, m/s**2),
    from gpar at a[o_gpar:] and the table gtab (3 nc, ng) at a[o_gtab:] (``layout``): rows
    3c, 3c + 1, 3c + 2 are component c's u_g, v_g, a_g.  The pulse (kind 1) is component
    0's only."""
    kind = int(a[o_gpar])
    if kind == 1:
        if c > 0:
            return 0.0, 0.0, 0.0
        A, w, t0, t1 = a[o_gpar + 1], a[o_gpar + 2], a[o_gpar + 3], a[o_gpar + 4]
        if t >= t0 and t < t1:
            cw = math.cos(w * t)
            sw = math.sin(w * t)
            return A * (cw - 1.0), -A * w * sw, -A * w * w * cw
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
        o = o_gtab + 3 * c * ng
        u, v, w = o + i, o + ng + i, o + 2 * ng + i
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
HEADER = 5
"""par[0:5] = nx, m (drive knots), ng (ground table length), nc (ground components),
gyro (1 when G is not zero)"""
#: rows of ``base`` after the ground components' (kb, cb, mb) triples
TIP_ROW, REACTION_ROW, COUPLE_COS_ROW, COUPLE_SIN_ROW = 0, 1, 2, 3
EXTRA_ROWS = 4


@njit(cache=True, inline="always")
def layout(nx: int, m: int, ng: int, nc: int) -> tuple[int, int, int, int, int, int, int, int, int, int, int, int, int]:
    """Offsets in par of Minv (n, n), K, C, G (nz, nz), shaft (2, nz), base (3 nc + 4, nz),
    scal (4), sched (3, m), gpar (6), gtab (3 nc, ng) and the force scratch F (n); then
    the offset of base's tip row and the size (n = nx + 2, nz = nx + 1)."""
    n = nx + 2
    nz = nx + 1
    o_minv = HEADER
    o_k = o_minv + n * n
    o_c = o_k + nz * nz
    o_g = o_c + nz * nz
    o_d = o_g + nz * nz
    o_base = o_d + 2 * nz
    o_scal = o_base + (3 * nc + EXTRA_ROWS) * nz
    o_sched = o_scal + 4
    o_gpar = o_sched + 3 * m
    o_gtab = o_gpar + 6
    o_f = o_gtab + 3 * nc * ng
    o_tip = o_base + 3 * nc * nz
    return o_minv, o_k, o_c, o_g, o_d, o_base, o_scal, o_sched, o_gpar, o_gtab, o_f, o_tip, o_f + n


@njit(cache=True)
def _put(par: Floats, k: int, a: Floats) -> None:
    for i in range(a.shape[0]):
        for j in range(a.shape[1]):
            par[k] = a[i, j]
            k += 1


@njit(cache=True)
def flatten(P: Packed) -> Floats:
    """The tuple P as one vector (``layout``), with room for the forces."""
    Minv, Kz, C, G, shaft, base, scal, sched, gpar, gtab = P
    if gpar.shape[0] != 6:
        raise ValueError("gpar must have 6 entries")
    nz, m, ng = Kz.shape[0], sched.shape[1], gtab.shape[1]
    nx = nz - 1
    nc = (base.shape[0] - EXTRA_ROWS) // 3
    if gtab.shape[0] != 3 * nc or base.shape[0] != 3 * nc + EXTRA_ROWS:
        raise ValueError("base must have 3 nc + 4 rows and gtab 3 nc")
    gyro = 0.0
    for i in range(nz):
        for j in range(nz):
            if G[i, j] != 0.0:
                gyro = 1.0
    o = layout(nx, m, ng, nc)
    par = np.zeros(o[12])
    par[0], par[1], par[2], par[3], par[4] = nx, m, ng, nc, gyro
    _put(par, o[0], Minv)
    _put(par, o[1], Kz)
    _put(par, o[2], C)
    _put(par, o[3], G)
    _put(par, o[4], shaft)
    _put(par, o[5], base)
    _put(par, o[6], scal.reshape((1, 4)))
    _put(par, o[7], sched)
    _put(par, o[8], gpar.reshape((1, gpar.shape[0])))
    _put(par, o[9], gtab)
    return par


@njit(cache=True)
def deriv_flat(t: float, y: Floats, par: Floats, out: Floats, o: int) -> None:
    """Eq. 4 in generic form: the first-order right-hand side y' of the flat model ``par``.

    Written into out[o:o + 2n + 4].

    y = (q, v, ...) with q = (Z, theta), Z = (z, y_r) the nz = n - 1 structural
    coordinates; writes out[o:o + n] = v, the next n Minv F, then the powers
    (drive - load with the motor's reaction, rotor on structure, dissipation,
    base); the forces F are left in par's scratch.  One flat body: no nested
    calls that pass arrays in the common case (no ground motion, a constant
    drive, no gyroscopic term).
    """
    nx, m, ng, nc = int(par[0]), int(par[1]), int(par[2]), int(par[3])
    gyro = par[4] != 0.0
    n = nx + 2
    nz = nx + 1
    o_minv, o_k, o_c, o_g, o_d, o_base, o_scal, o_sched, o_gpar, o_gtab, o_f, o_tip, _ = layout(nx, m, ng, nc)
    c2, e, uc, kload = par[o_scal], par[o_scal + 1], par[o_scal + 2], par[o_scal + 3]
    th = y[nz]
    W = y[n + nz]
    ct = math.cos(th)
    st = math.sin(th)
    ground = par[o_gpar] != 0.0
    if m == 1:
        M0, s = par[o_sched + 1], par[o_sched + 2]
    else:
        M0, s = drive_flat(t, par, o_sched, m)
    motor = M0 - s * W
    dxz = 0.0
    dvz = 0.0
    for i in range(nz):
        dxz += par[o_d + i] * y[i]
        dvz += par[o_d + nz + i] * y[i]
    sx = dxz - e * ct
    sv = dvz - e * st
    mc = uc * W * W
    p_diss = 0.0
    p_base = 0.0
    p_react = 0.0
    bv = 0.0  # the couple unbalance's direction b(theta) on the velocities
    o_r, o_cc, o_cs = o_tip + nz, o_tip + 2 * nz, o_tip + 3 * nz
    for i in range(nz):
        vi = y[n + i]
        acc = -c2 * par[o_d + i] * sx - c2 * par[o_d + nz + i] * sv
        if ground:
            fb = 0.0
            for c in range(nc):
                ug, vg, ag = ground_flat(t, par, o_gpar, o_gtab, ng, c)
                ob = o_base + 3 * c * nz + i
                fb += par[ob] * ug + par[ob + nz] * vg + par[ob + 2 * nz] * ag
            acc += fb
            p_base += fb * vi
        r = par[o_r + i]
        if r != 0.0:
            acc += motor * r
            p_react += motor * r * vi
        b = par[o_cc + i] * ct + par[o_cs + i] * st
        if b != 0.0:
            acc += mc * b
            bv += b * vi
        for j in range(nz):
            cij = par[o_c + i * nz + j]
            acc -= par[o_k + i * nz + j] * y[j] + cij * y[n + j]
            p_diss += vi * cij * y[n + j]
        if gyro:
            for j in range(nz):
                acc -= W * par[o_g + i * nz + j] * y[n + j]
        par[o_f + i] = acc
    drive = motor - kload * W * abs(W)
    shaft = c2 * e * (-dxz * st + dvz * ct) - uc * W * bv
    par[o_f + nz] = drive + shaft
    for i in range(n):
        acc = 0.0
        for j in range(n):
            acc += par[o_minv + i * n + j] * par[o_f + j]
        out[o + n + i] = acc
        out[o + i] = y[n + i]
    out[o + 2 * n] = drive * W + p_react
    out[o + 2 * n + 1] = -shaft * W + p_react
    out[o + 2 * n + 2] = p_diss
    out[o + 2 * n + 3] = p_base


@njit(cache=True)
def jacobians(t: float, q: Floats, v: Floats, P: Packed, Jq: Floats, Jv: Floats) -> None:
    """dF/dq and dF/dv of the forces of ``deriv_flat`` into Jq, Jv."""
    Minv, Kz, C, G, shaft, base, scal, sched, gpar, gtab = P
    nz = Kz.shape[0]
    n = nz + 1
    nc = (base.shape[0] - EXTRA_ROWS) // 3
    tip = 3 * nc
    c2, e, uc, kload = scal[0], scal[1], scal[2], scal[3]
    th = q[nz]
    W = v[nz]
    ct = math.cos(th)
    st = math.sin(th)
    M0, s = drive_at(t, sched)
    dxz = 0.0
    dvz = 0.0
    bv = 0.0
    bpv = 0.0  # d(b)/d(theta) on the velocities
    for i in range(nz):
        dxz += shaft[0, i] * q[i]
        dvz += shaft[1, i] * q[i]
        bv += (base[tip + 2, i] * ct + base[tip + 3, i] * st) * v[i]
        bpv += (-base[tip + 2, i] * st + base[tip + 3, i] * ct) * v[i]
    for i in range(n):
        for j in range(n):
            Jq[i, j] = 0.0
            Jv[i, j] = 0.0
    mc = uc * W * W
    for i in range(nz):
        dx, dv = shaft[0, i], shaft[1, i]
        b = base[tip + 2, i] * ct + base[tip + 3, i] * st
        bp = -base[tip + 2, i] * st + base[tip + 3, i] * ct
        gv = 0.0
        for j in range(nz):
            Jq[i, j] = -Kz[i, j] - c2 * (dx * shaft[0, j] + dv * shaft[1, j])
            Jv[i, j] = -C[i, j] - W * G[i, j]
            gv += G[i, j] * v[j]
        Jq[i, nz] = -c2 * e * (dx * st - dv * ct) + mc * bp
        Jv[i, nz] = -s * base[tip + 1, i] - gv + 2.0 * uc * W * b
        Jq[nz, i] = c2 * e * (-dx * st + dv * ct)
        Jv[nz, i] = -uc * W * b
    Jq[nz, nz] = -c2 * e * (dxz * ct + dvz * st) - uc * W * bpv
    Jv[nz, nz] = -s - 2.0 * kload * abs(W) - uc * bv


@njit(cache=True)
def record_peak(q: Floats, n: int, par: Floats, peak: Floats, k: int) -> None:
    """peak[k, i] = max(peak[k, i], |q_i|) for i < n; peak[k, n] tracks |tip.Z|
    (tip = base's row after the ground components', in par)."""
    nx = n - 2
    o_tip = layout(nx, int(par[1]), int(par[2]), int(par[3]))[11]
    tipz = 0.0
    for i in range(nx + 1):
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
