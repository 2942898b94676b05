"""Speed of the reduced transients, measured side by side in one run.

1. A design sweep: run-ups of the paper's model for 1000 values of tau
   (M0 = 300 tau, 1.7 <= tau <= 17), 20 s each.  The compiled batch (one
   numba loop over the runs, rotorpillar.reduced.batch.simulate_batch,
   on every core: threads share the runs, and on one thread)
   against a plain Python loop of scipy.integrate.solve_ivp (RK45, the
   right-hand side written in numpy as one would by hand), at the same rtol
   and at equal accuracy: the error of each (largest |tip - reference| over
   the largest |tip|, reference at rtol 1e-12) is measured on a few runs, and
   the plain loop's rtol is tightened until it is at least as accurate.  The
   plain loop is timed on a sample of the runs (it would take minutes for all).
2. Wall times of the cases `rotorpillar simulate paper` runs (library calls,
   compiled code warm; and the whole command, cold interpreter).
3. The earthquake (El Centro 1940) on the modal ROM against full-order
   models integrated by Newmark: the ROM's time over the full-order time and
   its tip-displacement error.  Full order is (a) the 1D Timoshenko beam with
   every degree of freedom (rotorpillar.reduced.rotor_models.beam_model,
   nonlinear rotor), and (b) the 3D model (rotorpillar.fem3d, ~24k dofs)
   with the rotor at a prescribed speed (linear: one factorisation), against
   the ROM built on the 3D model's own modes, integrated by dp5 and by
   Newmark at the 3D run's step (the latter isolates the truncation error).
4. The 3D full order's step (issue 15.8): El Centro's 15 s on the scene's
   [full_order] mesh with the default shaft and with a stiff one (c2 = 1e10
   N/m, e = 0, b2 = 0: the rotor's bounce at 2,500 rad/s), side by side, and
   the stiff shaft on the 16 x 20 mesh: steps, wall time, peak tip; beside
   them the steps the old rule (40 per period of the fastest of the rotor,
   sqrt(c2 / m_C) and the band) would take.

``quick``: 20 runs of 2 s in the sweep, runs of 2 s, 3D windows of 0.2 s
(does it run).
"""

from __future__ import annotations

import math
import subprocess
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

from rotorpillar.reduced.batch import batch_threads, simulate_batch
from rotorpillar.reduced.beam_model import beam_model
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import load_record, no_motion
from rotorpillar.reduced.integration import Settings, simulate, tolerances
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.pillar_modes import beam_pillar_modes
from rotorpillar.reduced.rhs import eq4_rhs
from rotorpillar.reduced.rotor_models import modal_model
from rotorpillar.reduced.stationary import operating_speed
from rotorpillar.scene import load_scene, override
from rotorpillar.transients.cases import run_case

RUNS = 1000
PLAIN_SAMPLE = 8
DURATION = 20.0
SAMPLES = 201


def plain_rhs(p):
    """The paper's equation 4 as one writes it by hand (rotorpillar.reduced.rhs.eq4_rhs):
    numpy, one call per evaluation."""
    return lambda t, y: eq4_rhs(y, *p)


def _params(model, M0, s, k):
    return (
        model.mass[0, 0],
        model.rotor_mass,
        model.rotor_inertia,
        model.eccentricity,
        model.stiffness[0, 0],
        model.shaft_stiffness,
        model.damping[0, 0] - model.shaft_damping,
        model.shaft_damping,
        M0,
        s,
        k,
    )


def plain_run(model, M0, s, k, rtol, atol, t_eval, duration=DURATION):
    sol = solve_ivp(
        plain_rhs(_params(model, M0, s, k)),
        (0.0, duration),
        np.zeros(8),
        method="RK45",
        t_eval=t_eval,
        rtol=rtol,
        atol=atol,
    )
    return sol.y[0], sol.nfev


def bench_sweep(scene, quick: bool = False) -> list[dict]:
    runs, plain_sample, duration = (20, 2, 2.0) if quick else (RUNS, PLAIN_SAMPLE, DURATION)
    model, _ = build_model(scene, "paper")
    d, L = scene.drive, scene.load
    drive = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
    tau = np.linspace(1.7, 17.0, runs)
    scale = 300.0 * tau / d.torque_at_zero
    rtol = 1e-7
    simulate_batch(model, drive, 1.0, torque_scale=scale[:2], rtol=rtol, samples=SAMPLES)  # compile
    serial = simulate_batch(model, drive, duration, torque_scale=scale, rtol=rtol, samples=SAMPLES, threads=1)
    b = simulate_batch(model, drive, duration, torque_scale=scale, rtol=rtol, samples=SAMPLES)
    threads = batch_threads()
    assert np.array_equal(b.tip, serial.tip)  # the same runs, whichever thread ran them
    serial_rate = runs / serial.wall_seconds
    batch_rate = runs / b.wall_seconds
    # accuracy on a sample of the runs against a tight reference
    pick = np.linspace(0, runs - 1, plain_sample).astype(int)
    ref = simulate_batch(model, drive, duration, torque_scale=scale[pick], rtol=1e-12, samples=SAMPLES)
    ref_tip = ref.tip
    err = lambda tips: float(max(np.max(np.abs(a - r)) / np.max(np.abs(r)) for a, r in zip(tips, ref_tip)))
    batch_err = err(b.tip[pick])
    atol8 = tolerances(model, no_motion(), drive.free_speed(), 1.0)[:8]
    t_eval = b.t
    rows = {}
    for plain_rtol in (rtol, rtol / 10, rtol / 100):
        t0 = time.perf_counter()
        tips, nfev = [], 0
        for i in pick:
            M0 = d.torque_at_zero * scale[i]
            tip, n = plain_run(model, M0, d.slope, L.coefficient, plain_rtol, atol8 * plain_rtol, t_eval, duration)
            tips.append(tip)
            nfev += n
        wall = time.perf_counter() - t0
        rows[plain_rtol] = {"rate": len(pick) / wall, "error": err(tips), "nfev_per_run": nfev / len(pick)}
    equal = next((r for r in sorted(rows, reverse=True) if rows[r]["error"] <= batch_err), min(rows))
    out = [
        {
            "name": "sweep_batch_runs_per_second",
            "compares": f"compiled batch on every core ({threads} "
            f"threads): {runs} run-ups of {duration:g} s (tau 1.7..17), rtol {rtol:g}",
            "value": batch_rate,
            "unit": "runs/s",
            "wall_seconds": b.wall_seconds,
            "error": batch_err,
            "threads": threads,
        },
        {
            "name": "sweep_batch_serial_runs_per_second",
            "compares": "the same compiled batch on one thread",
            "value": serial_rate,
            "unit": "runs/s",
            "wall_seconds": serial.wall_seconds,
            "threads": 1,
        },
        {
            "name": "sweep_batch_thread_speedup",
            "compares": f"batch on {threads} threads over the batch on one (same runs, bit for bit)",
            "value": batch_rate / serial_rate,
            "unit": "x",
            "threads": threads,
        },
        {
            "name": "sweep_plain_solve_ivp_runs_per_second",
            "compares": "Python loop of solve_ivp RK45 "
            f"(numpy right-hand side), rtol {rtol:g}, {len(pick)} of the runs",
            "value": rows[rtol]["rate"],
            "unit": "runs/s",
            "error": rows[rtol]["error"],
            "nfev_per_run": rows[rtol]["nfev_per_run"],
        },
        {
            "name": "sweep_speedup_equal_rtol",
            "compares": f"batch runs/s over the plain loop's, both rtol {rtol:g}",
            "value": batch_rate / rows[rtol]["rate"],
            "unit": "x",
            "batch_error": batch_err,
            "plain_error": rows[rtol]["error"],
        },
        {
            "name": "sweep_speedup_equal_accuracy",
            "compares": f"batch runs/s ({threads} threads) over the "
            f"plain loop's (one process) at the loosest plain rtol ({equal:g}) whose error is no larger "
            "than the batch's",
            "value": batch_rate / rows[equal]["rate"],
            "unit": "x",
            "batch_error": batch_err,
            "plain_error": rows[equal]["error"],
            "plain_rtol": equal,
            "target": 100.0,
            "threads": threads,
        },
        {
            "name": "sweep_speedup_equal_accuracy_serial",
            "compares": "the one-thread batch's runs/s over "
            f"the plain loop's at rtol {equal:g} (equal accuracy, both on one core)",
            "value": serial_rate / rows[equal]["rate"],
            "unit": "x",
            "plain_rtol": equal,
        },
    ]
    return out


def bench_cases(scene, quick: bool = False) -> list[dict]:
    # the paper's pulse starts at 5 s: the earthquake runs past it
    short = ["--set", "simulate.duration=2", "--set", "simulate.earthquake_duration=7"] if quick else []
    if quick:
        scene = override(scene, short[1::2])
    out = []
    for case in ("runup", "earthquake", "sweep"):
        run_case(scene, case, "paper")  # warm
        t0 = time.perf_counter()
        r = run_case(scene, case, "paper")
        wall = time.perf_counter() - t0
        out.append(
            {
                "name": f"case_{case}_paper_seconds",
                "compares": f"`simulate paper --case {case}` "
                "library call, compiled code warm (model, integration, summary)",
                "value": wall,
                "unit": "s",
                "integration_seconds": r.run.stats.wall_seconds,
                "simulated_seconds": float(r.run.t[-1] - r.run.t[0]),
            }
        )
    for case in ("runup", "earthquake"):
        t0 = time.perf_counter()
        p = subprocess.run(
            [
                sys.executable,
                "-m",
                "rotorpillar",
                "simulate",
                "paper",
                "--case",
                case,
                "--out",
                "bench/cache/simulate",
                *short,
            ],
            capture_output=True,
            text=True,
        )
        wall = time.perf_counter() - t0
        out.append(
            {
                "name": f"cli_{case}_paper_seconds",
                "compares": f"`rotorpillar simulate paper --case "
                f"{case}` end to end (interpreter start, numba cache load, run, NPZ/CSV/JSON, chart)",
                "value": wall,
                "unit": "s",
                "returncode": p.returncode,
            }
        )
    return out


def bench_rom_vs_full(scene, quick: bool = False) -> list[dict]:
    d, L = scene.drive, scene.load
    drive = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
    motion = load_record("elcentro", start=2.0)
    t_end = 2.0 if quick else round(motion.end + 3.0, 1)
    samples = int(round(t_end / 0.01)) + 1  # outputs every 10 steps of 1 ms: the grids match
    elements = 10
    full = beam_model(scene.pillar, scene.gondola.mass, scene.rotor, scene.shaft, elements, "timoshenko")
    W = operating_speed(full, d.torque_at_zero, d.slope, L.coefficient)
    q0, v0 = full.steady_initial_state(W)
    st = Settings("newmark", time_step=1e-3, samples=samples)
    simulate(full, drive, motion, 0.1, q0, v0, settings=st, speed_scale=W)  # warm
    F = simulate(full, drive, motion, t_end, q0, v0, settings=st, speed_scale=W)
    top = scene.modal_model.band_factor * max(drive.free_speed(), motion.band())
    # the mode count the band asks of the same beam (the ROM below is built on its modes)
    rom, info = build_model(override(scene, ["modal_model.source=beam"]), "modal", top)
    assert rom.pillar_modes is not None, "a modal model has its pillar modes"
    k = rom.pillar_modes.count
    pm = beam_pillar_modes(scene.pillar, scene.gondola.mass, k, "timoshenko", elements)  # same beam
    rom = modal_model(
        pm,
        scene.rotor.mass,
        scene.rotor.inertia,
        scene.rotor.eccentricity,
        scene.shaft.stiffness,
        scene.shaft.damping,
        scene.pillar.damping,
    )
    q0r, v0r = rom.steady_initial_state(operating_speed(rom, d.torque_at_zero, d.slope, L.coefficient))
    sr = Settings("dp5", rtol=1e-7, samples=samples)
    simulate(rom, drive, motion, 0.1, q0r, v0r, settings=sr, speed_scale=W)
    R = simulate(rom, drive, motion, t_end, q0r, v0r, settings=sr, speed_scale=W)
    assert np.allclose(R.t, F.t)
    err = float(np.max(np.abs(R.tip() - F.tip())) / np.max(np.abs(F.tip())))
    return [
        {
            "name": "earthquake_rom_over_full_order_time",
            "compares": f"modal ROM ({k} modes, dp5) "
            f"over full-order 1D Timoshenko beam ({full.nx} dofs, Newmark h = 1 ms), El Centro 1940",
            "value": R.stats.wall_seconds / F.stats.wall_seconds,
            "unit": "x",
            "rom_seconds": R.stats.wall_seconds,
            "full_order_seconds": F.stats.wall_seconds,
            "full_order": "1D beam (rotorpillar.fem3d not installed)",
        },
        {
            "name": "earthquake_rom_tip_error",
            "compares": "max |tip_ROM - tip_full| / max |tip_full|, El Centro 1940",
            "value": err,
            "unit": "-",
            "modes": k,
            "tip_max_full": float(np.max(np.abs(F.tip()))),
        },
    ]


def newmark_3d(scene, motion, Omega: float, theta0: float, h: float, t_end: float):
    """The earthquake on the 3D model with the rotor turning at a prescribed speed, by
    the library's full-order transient (rotorpillar.fem3d.full_order: Newmark, one
    MUMPS factorisation).  Returns (t, tip X relative to the ground, wall s, dofs)."""
    from rotorpillar.fem3d.full_order import simulate_fem3d

    scene = override(scene, ["full_order.integrator=newmark"])  # the ROM's Newmark beside it
    steps = int(round(t_end / h))
    r = simulate_fem3d(
        scene,
        "earthquake",
        motion=motion,
        duration=t_end,
        time_step=h,
        samples=steps + 1,
        initial_speed=Omega,
        initial_angle=theta0,
        prescribed_speed=True,
    )
    return r.t, r.tip_x, r.wall_seconds, r.dofs


def bench_rom_vs_3d(scene, quick: bool = False) -> list[dict]:
    """The ROM built on the 3D modes against the 3D model itself (Newmark)."""
    import importlib.util

    if importlib.util.find_spec("dolfinx") is None:
        return []
    from rotorpillar.scene import override

    scene = override(scene, ["modal_model.source=fem3d"])
    motion = load_record("elcentro", start=1.0)
    h, t_end = 2e-3, (0.2 if quick else 11.0)
    d, L = scene.drive, scene.load
    from rotorpillar.fem3d.pillar_modes import candidate_pillar_modes

    model, _ = build_model(
        scene,
        "modal",
        scene.modal_model.band_factor
        * max(DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed(), motion.band()),
        pillar_modes=candidate_pillar_modes(scene),
    )
    Omega = operating_speed(model, d.torque_at_zero, d.slope, L.coefficient)
    theta0 = math.pi / 2
    t3, tip3, wall3, dofs = newmark_3d(scene, motion, Omega, theta0, h, t_end)
    # the 3D run's start: the structure at rest, the rotor in its steady whirl on the held plate
    from rotorpillar.fem3d.rotor_top import RotorOnTop, rotor_start

    x, y, vx, vy = rotor_start(RotorOnTop.from_scene(scene), theta0, Omega)
    q0, v0 = np.zeros(model.n), np.zeros(model.n)
    q0[model.rotor_x], q0[model.nx], q0[-1] = x, y, theta0
    v0[model.rotor_x], v0[model.nx], v0[-1] = vx, vy, Omega
    idle = DriveSchedule.constant(0.0, 0.0, 0.0)
    assert model.pillar_modes is not None, "a modal model has its pillar modes"
    out = []
    for label, st in (
        ("dp5", Settings("dp5", rtol=1e-7, samples=len(t3))),
        ("newmark", Settings("newmark", time_step=h, samples=len(t3))),
    ):
        R = simulate(model, idle, motion, t_end, q0, v0, settings=st, prescribed_speed=True, speed_scale=Omega)
        assert np.allclose(R.t, t3)
        err = float(np.max(np.abs(R.tip() - tip3)) / np.max(np.abs(tip3)))
        out.append(
            {
                "name": f"earthquake_rom_{label}_over_3d_newmark_time",
                "compares": f"modal ROM on the 3D modes ({model.pillar_modes.count} X bending modes, {label}) "
                f"over the 3D model ({dofs} dofs, Newmark h = {h:g} s, one MUMPS factorisation), "
                f"El Centro 1940, {t_end:g} s, rotor at {Omega:.1f} rad/s",
                "value": R.stats.wall_seconds / wall3,
                "unit": "x",
                "rom_seconds": R.stats.wall_seconds,
                "full_3d_seconds": wall3,
            }
        )
        out.append(
            {
                "name": f"earthquake_rom_{label}_tip_error_vs_3d",
                "compares": "max |tip_ROM - tip_3D| / max |tip_3D|"
                + (" (same Newmark step: truncation alone)" if label == "newmark" else ""),
                "value": err,
                "unit": "-",
                "tip_max_3d": float(np.max(np.abs(tip3))),
            }
        )
    return out


STIFF = ["shaft.stiffness=1e10", "rotor.eccentricity=0", "shaft.damping=0"]


def bench_full_order_step(quick: bool = False) -> list[dict]:
    """The 3D full order's steps and wall time, default and stiff shaft, in one run."""
    import importlib.util
    import os

    if importlib.util.find_spec("dolfinx") is None:
        return []
    from rotorpillar.fem3d.full_order import simulate_fem3d
    from rotorpillar.fem3d.full_order_plan import case_setup, top_speed
    from rotorpillar.transients.run_plan import fem3d_plan

    out = []
    cases: tuple[tuple[str, list[str], list[str]], ...] = (
        ("default shaft", [], []),
        ("stiff shaft", STIFF, []),
        ("stiff shaft, 16 x 20 mesh", STIFF, ["full_order.elements_around=16", "full_order.elements_along=20"]),
    )
    for label, shaft, mesh in cases:
        scene = load_scene("paper", ["excitation.kind=record"] + shaft + mesh)
        plan = fem3d_plan(scene, "earthquake")
        duration = min(plan.duration, 0.2) if quick else plan.duration
        load = os.getloadavg()[0]
        r = simulate_fem3d(scene, "earthquake", duration=duration, mesh=plan.mesh, samples=20000)
        motion, drive, _, W0, _ = case_setup(scene, "earthquake", None, None, duration, None)
        fast = max(top_speed(drive, W0), math.sqrt(scene.shaft.stiffness / scene.rotor.mass), motion.band())
        old_steps = duration / min(2 * math.pi / fast / 40, motion.time_step)
        it = r.integrator
        m = plan.mesh
        out.append(
            {
                "name": f"full_order_3d_elcentro_{label.replace(', ', '_').replace(' ', '_')}_seconds",
                "compares": f"3D full order, El Centro {duration:g} s, {label} "
                f"({m.elements_around} x {m.elements_along} elements, {r.dofs} dofs): wall time "
                "of meshing, assembly, factorisation and integration",
                "value": r.wall_seconds,
                "unit": "s",
                "steps": it.steps,
                "time_step": it.time_step,
                "integration_seconds": it.integration_seconds,
                "seconds_per_step": it.seconds_per_step,
                "scheme": it.method,
                "rule": it.step_rule.rule if it.step_rule else None,
                "peak_tip": r.max_abs["tip_x"],
                "ok": r.ok,
                "old_rule_steps": old_steps,
                "old_rule_seconds_extrapolated": old_steps * it.seconds_per_step,
                "estimated_seconds": it.estimate.seconds if it.estimate else None,
                "load_average": load,
            }
        )
    return out


def run(quick: bool = False) -> list[dict]:
    scene = load_scene("paper")
    return (
        bench_sweep(scene, quick)
        + bench_cases(scene, quick)
        + bench_rom_vs_full(scene, quick)
        + bench_rom_vs_3d(scene, quick)
        + bench_full_order_step(quick)
    )


if __name__ == "__main__":
    for e in run():
        print(f"{e['name']}: {e['value']:.4g} {e['unit']}  ({e['compares']})")
