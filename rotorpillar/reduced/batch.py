"""Many runs of one reduced model at once: ``simulate_batch`` and its ``Batch``.

Run-ups (or any drive schedule) for many parameter values in one compiled
dp5 loop (rotorpillar.reduced.kernels.dp5_batch), slices of the runs on a
thread pool; ``shaft_deflection`` and ``project``, the process-independent
reductions of its states.  One run at a time: rotorpillar.reduced.integration.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import kernels as K
from .drive import DriveSchedule
from .excitation import GroundMotion
from .integration import Arr, _breaks, _output_grid, tolerances
from .rhs import Floats
from .rotor_models import RotorStructure


@dataclass(frozen=True, eq=False)
class Batch:
    """Many runs of one model differing in M0 (scale), s, k, e or c2."""

    t: NDArray[np.float64]
    """(n_t,) output times (s)"""
    Omega: NDArray[np.float64]
    """(runs, n_t) rotor speed (rad/s)"""
    tip_peak: NDArray[np.float64]
    """(runs, n_t) largest |tip X| per output interval (m)"""
    tip: NDArray[np.float64]
    """(runs, n_t) tip X at the outputs (m)"""
    final_state: NDArray[np.float64]
    """(runs, 2n + 4) state at t_end (theta unwrapped)"""
    status: NDArray[np.int_]
    nfev: NDArray[np.int_]
    wall_seconds: float
    shaft_deflection: NDArray[np.float64] | None = None
    """(runs, n_t) |shaft deflection| = |(d.z - e cos theta, y - e sin theta)| at the outputs (m)"""

    @property
    def ok(self) -> NDArray[np.bool_]:
        ok: NDArray[np.bool_] = self.status == K.OK
        return ok


def shaft_deflection(q: ArrayLike, shaft: ArrayLike, e: ArrayLike) -> tuple[Floats, Floats]:
    """|shaft deflection| and its x component (m) at states q (k, n), e (m) per
    state or one for all: the same bits in any process (rhs.shaft_deflection_into)."""
    qs = np.ascontiguousarray(q, dtype=float)
    es = np.broadcast_to(np.asarray(e, dtype=float), (qs.shape[0],)).copy()
    size, x = np.empty(qs.shape[0]), np.empty(qs.shape[0])
    K.shaft_deflection_into(qs, np.ascontiguousarray(shaft, dtype=float), es, size, x)
    return size, x


def project(q: NDArray[np.float64], w: NDArray[np.float64]) -> NDArray[np.float64]:
    """q @ w summed term by term in a fixed order, whatever BLAS would do with
    its threads there: a study's numbers must not depend on the process its
    batch ran in.  (CI's 1-ulp difference came from numpy's cos, see
    ``shaft_deflection``; BLAS was the first suspect, not proven.)"""
    out = np.zeros(q.shape[:-1])
    for j, wj in enumerate(np.asarray(w, dtype=float)):
        out += q[..., j] * wj
    return out


def simulate_batch(
    model: RotorStructure,
    drive: DriveSchedule,
    t_end: float,
    *,
    torque_scale: Arr = None,
    slope: Arr = None,
    load: Arr = None,
    eccentricity: Arr = None,
    shaft_stiffness: Arr = None,
    motion: GroundMotion | None = None,
    q0: Arr = None,
    v0: Arr = None,
    rtol: float = 1e-7,
    samples: int = 201,
    speed_scale: float | None = None,
    threads: int | None = None,
) -> Batch:
    """Run-ups (or any drive schedule) for many parameter values in one compiled
    loop: no Python between runs.  Each keyword is an array over the runs
    (torque_scale multiplies the schedule's M0; the others replace s, k, e, c2).

    ``threads``: how many threads share the runs (None: every core this
    process may use, ``batch_threads()``; 1: the plain serial loop).  The
    compiled loop releases the GIL, so slices of the runs go to a thread
    pool; each run is computed exactly as in the serial loop, so the result
    does not depend on ``threads`` (bit for bit).  Inside a process that is
    itself one of several workers on the machine, pass ``threads=1``."""
    from .excitation import no_motion

    motion = motion or no_motion()
    arrays = {
        "torque_scale": torque_scale,
        "slope": slope,
        "load": load,
        "eccentricity": eccentricity,
        "shaft_stiffness": shaft_stiffness,
    }
    runs = max((len(np.atleast_1d(a)) for a in arrays.values() if a is not None), default=1)
    fill: Callable[[ArrayLike | None, float], Floats] = lambda a, default: (
        np.full(runs, default, dtype=float)
        if a is None
        else np.broadcast_to(np.asarray(a, dtype=float), (runs,)).copy()
    )
    ts = fill(torque_scale, 1.0)
    others = [fill(arrays[k], np.nan) for k in ("slope", "load", "eccentricity", "shaft_stiffness")]
    n = model.n
    q0 = np.zeros(n) if q0 is None else np.asarray(q0, float)
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, float)
    y0 = np.concatenate([q0, v0, np.zeros(K.N_WORK)])
    if speed_scale is None:
        speed_scale = max(drive.free_speed() * float(np.sqrt(np.max(ts))), abs(v0[-1]), 1.0)
    ecc = float(np.nanmax(others[2])) if np.any(np.isfinite(others[2])) else model.eccentricity
    m_for_tol = model if ecc <= model.eccentricity else _with_eccentricity(model, ecc)
    atol = tolerances(m_for_tol, motion, speed_scale, rtol)
    t_out = _output_grid(0.0, t_end, samples)
    out_y = np.zeros((runs, len(t_out), len(y0)))
    out_peak = np.zeros((runs, len(t_out), n + 1))
    stats = np.zeros((runs, 5))
    P = model.pack(drive, motion)
    args = (
        P,
        y0,
        0.0,
        float(t_end),
        _breaks(drive, motion),
        rtol,
        atol,
        t_out,
        True,
        200_000_000,
        motion.time_step if motion.kind == "record" else np.inf,
    )
    s_run, k_run, e_run, c2_run = others
    start = time.perf_counter()
    _run_slices(
        lambda a, b: K.dp5_batch(
            *args, ts[a:b], s_run[a:b], k_run[a:b], e_run[a:b], c2_run[a:b], out_y[a:b], out_peak[a:b], stats[a:b]
        ),
        runs,
        batch_threads() if threads is None else threads,
    )
    wall = time.perf_counter() - start
    e = np.where(np.isfinite(others[2]), others[2], model.eccentricity)
    shaft = shaft_deflection(out_y[:, :, :n].reshape(-1, n), model.shaft, np.repeat(e, len(t_out)))[0].reshape(
        runs, len(t_out)
    )
    return Batch(
        t_out,
        out_y[:, :, 2 * n - 1],
        out_peak[:, :, -1],
        project(out_y[:, :, : model.nx], model.tip),
        out_y[:, -1, :],
        stats[:, 0].astype(int),
        stats[:, 1].astype(int),
        wall,
        shaft,
    )


def batch_threads() -> int:
    """The cores this process may run on (its CPU affinity), at least 1."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _run_slices(run_slice: Callable[[int, int], object], runs: int, threads: int) -> None:
    """Call ``run_slice(a, b)`` over slices covering range(runs), on ``threads`` threads.

    Runs differ in cost (a slow run-up takes longer), so the slices are
    small (about four per thread) and each thread takes the next free one.
    """
    if threads < 1:
        raise ValueError(f"threads = {threads!r} must be >= 1")
    threads = min(threads, runs)
    if threads <= 1:
        run_slice(0, runs)
        return
    size = max(1, -(-runs // (4 * threads)))
    edges = list(range(0, runs, size)) + [runs]
    with ThreadPoolExecutor(max_workers=threads) as pool:
        for f in [pool.submit(run_slice, a, b) for a, b in zip(edges[:-1], edges[1:])]:
            f.result()


def _with_eccentricity(model: RotorStructure, e: float) -> RotorStructure:
    from dataclasses import replace

    return replace(model, eccentricity=e)
