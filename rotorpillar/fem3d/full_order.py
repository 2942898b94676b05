"""Full-order continuum transient: the 3D tube with the rotor at its top, one factorisation.

The tube (the scene's ``[mesh]``, clamped at the base) carries the gondola
on its rigid top plate (``assemble_pillar(scene, top=True)``, modal.top_model
= "rigid"); the rotor hangs on its shaft at the plate's reference point
(rotorpillar.fem3d.rotor_top) and spins under the motor and machine torques.
Everything is relative to the ground, forced by the ground's inertia
-M r a_g(t) in X on the tube, the plate and the rotor (the physically
consistent base forcing; the modal model's), so the tip's displacement
relative to the ground comes out directly; absolute = relative + the ground
displacement whose second derivative is the applied acceleration.

Damping, chosen to be the modal model's exactly: the pillar's b1 as a
dashpot on the plate's X (the paper's b1 is a tip damper; the modal model
puts b1 on the tip, which the 3D modes normalise to the plate's U_x), b2 on
the rotor centre's velocity in X and Y.  No Rayleigh term: the modal model
built on this tube's modes is then this model truncated, and nothing else.
Modes that do not move the plate in X (ovalling, torsion) stay undamped; the
X load barely excites them.

Integration: the generalized-alpha method (Chung & Hulbert 1993;
``full_order.integrator``, default, with ``full_order.rho_inf``; or HHT-alpha,
Hilber, Hughes & Taylor 1977, or Newmark's average acceleration) on the whole
coupled system: unconditionally stable and second order, so the step
follows the band (transient_plan.step_rule: the fastest forcing resolved
within 2e-3, no coarser than a record's sampling), and the modes far above
it (a stiff shaft, the tube's axial and ovalling modes) shrink by rho_inf
each step instead of being resolved.  The tube is linear, so the step's
effective stiffness (1 - af) K + (1 - am)/(beta h**2) M + the plate's
dashpot, with the rotor centre condensed onto the plate, is factorised once
(MUMPS) and reused for every step; the unbalance enters through two fixed
solutions of that operator, so the nonlinear spin equation closes each step
as one scalar Newton solve (rotor_top.solve_spin), fully implicit.  Every
force but inertia is weighted between the old and the new time by alpha_f
(the forces, so the new time's unbalance is affine in cos and sin of the
new theta, which keeps the scalar structure).

Start: the tube at rest, the rotor in its steady whirl at the initial speed
on a held plate (rotor_top.rotor_start; at rest: the shaft unstretched).
The tube's initial acceleration is the consistent one, -r a_g(0) plus M^-1
of the whirl's shaft force on the plate (one solve with M): an inconsistent
start would cost the scheme its second order.

Before any meshing the run's steps and wall time are estimated and refused
above ``simulate.max_steps`` (transient_plan.check_budget); after it, the
step taken is checked against what the run had to resolve, and a run that
fails it, stops, or misses its energy balance is ``ok: false`` with its
``failed_checks``.

The run's record (``Fem3dTransient``), its energy balance and checks:
rotorpillar.fem3d.full_order_result.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from ..errors import InputError
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import GroundMotion
from ..scene import Scene
from .full_order_plan import (  # noqa: F401
    CASES_3D,
    accuracy,
    beam_operating_speed,
    case_setup,
    check_budget,
    estimate,
    scheme_parameters,
    step_rule,
    top_speed,
)
from .full_order_result import Fem3dDescription, Fem3dStats, Fem3dTransient, transient_result
from .rotor_top import (
    Affine,
    RotorOnTop,
    Step,
    coupling_torque,
    drive_torque,
    plate_and_rotor,
    rotor_start,
    rotor_step_stiffness,
    solve_spin,
)
from .step_operator import Plate, add_shaft_acceleration, step_operator


def simulate_fem3d(
    scene: Scene,
    case: str,
    *,
    motion: GroundMotion | None = None,
    drive: DriveSchedule | None = None,
    duration: float | None = None,
    time_step: float | None = None,
    mesh=None,
    samples: int = 2001,
    initial_speed: float | None = None,
    initial_angle: float = 0.0,
    prescribed_speed: bool = False,
    comm=None,
    progress=None,
    observer=None,
) -> Fem3dTransient:
    """Run ``case`` ("earthquake" or "runup") on the 3D tube with the rotor at its top.

    Defaults follow the reduced models' cases: the scene's excitation, a
    constant drive and the operating speed for the earthquake; the ramped
    drive from rest for the run-up; durations from ``[simulate]``.
    """
    from . import assemble_pillar

    if scene.modal.top_model != "rigid":
        raise InputError('the 3D transient hangs the rotor on the rigid top plate: modal.top_model must be "rigid"')
    if scene.modal.top_mass != "gondola":
        raise InputError(
            'modal.top_mass = "gondola_and_rotor" puts the rotor on the tube rigidly; '
            'the 3D transient hangs it on its shaft: use modal.top_mass = "gondola"'
        )
    motion, drive, duration, W0, notes = case_setup(scene, case, motion, drive, duration, initial_speed)
    rule = step_rule(scene, drive, motion, W0, time_step)
    est = estimate(scene, duration, rule, mesh)
    check_budget(scene, case, est)  # before any meshing
    if progress:
        progress(
            f"3D transient: {est.steps:.0f} steps of {rule.time_step:.3g} s ({_scheme_name(scene)}), "
            f"about {est.seconds:.0f} s on ~{est.dofs:,} dofs (estimate)"
        )
    steps = max(1, int(round(duration / rule.time_step)))
    h = duration / steps
    fo = scene.full_order
    step = Step(h, **scheme_parameters(fo.integrator, fo.rho_inf))
    stride = max(1, int(math.ceil(steps / max(1, samples - 1))))
    start = time.perf_counter()
    model = assemble_pillar(scene, top=True, mesh=mesh, comm=comm)
    rotor = RotorOnTop.from_scene(scene)
    try:
        if observer is not None:
            observer.attach(model)
        out, counts = _integrate(
            model,
            rotor,
            scene.pillar.damping,
            drive,
            motion,
            step,
            steps,
            stride,
            initial_angle,
            W0,
            prescribed_speed,
            progress,
            observer,
        )
    finally:
        model.K.destroy()
        model.M.destroy()
    wall = time.perf_counter() - start
    reached = W0 if prescribed_speed else float(np.max(np.abs(out["Omega"])))
    check = accuracy(scene, h, duration, max(reached, abs(W0)), motion)
    stats = Fem3dStats(
        method=fo.integrator,
        scheme=_scheme_words(fo.integrator, step, rule),
        time_step=h,
        step_rule=rule,
        accuracy=check,
        estimate=est,
        assembly_seconds=sum(model.timings.values()),
        **counts,
    )
    mesh_section = scene.mesh if mesh is None else mesh
    info = Fem3dDescription(
        mesh=mesh_section,
        top="rigid plate with the gondola",
        damping_law="pillar: b1 as a dashpot on the plate's X; b2 on the rotor centre's "
        "velocity relative to the ground in X and Y; no Rayleigh term",
        frame="relative_to_ground",
        forcing="-M r a_g in X on tube, plate and rotor",
        start="tube at rest, rotor in its steady whirl on a held plate",
        initial_speed=W0,
        initial_angle=initial_angle,
        prescribed_speed=bool(prescribed_speed),
        **notes,
    )
    return transient_result(case, out, stats, model.size + 3, wall, info, motion, drive, prescribed_speed, check.failed)


def _scheme_name(scene: Scene) -> str:
    fo = scene.full_order
    return fo.integrator + ("" if fo.integrator == "newmark" else f", rho_inf {fo.rho_inf:g}")


def _scheme_words(method: str, step: Step, rule) -> str:
    name = {
        "newmark": "Newmark's average acceleration",
        "hht": "HHT-alpha",
        "generalized_alpha": "generalized-alpha (Chung & Hulbert 1993)",
    }[method]
    return (
        f"{name}: alpha_m {step.alpha_m:.4g}, alpha_f {step.alpha_f:.4g}, beta {step.beta:.4g}, "
        f"gamma {step.gamma:.4g}, spectral radius at infinity {rule.spectral_radius_infinity:.3g}; "
        "one MUMPS factorisation, the spin equation by scalar Newton inside each step"
    )


def _integrate(
    model,
    rotor: RotorOnTop,
    b1: float,
    drive: DriveSchedule,
    motion: GroundMotion,
    step: Step,
    steps: int,
    stride: int,
    theta0: float,
    W0: float,
    prescribed: bool,
    progress,
    observer=None,
):
    """The generalized-alpha ``step`` over ``steps`` steps; see the module text.

    Each scalar dof's equation (rotor centre x, y; the plate's dashpot) is
    Step.history + the new-time couplings; the tube's is
    Keff u1 = M (cm u~ - am a - r a_g) - af K u + the plate's rows.
    """
    K, M = model.K, model.M
    N = model.tube_dofs
    rows = (N, N + 2)  # the plate's U_x, U_z
    c2, b2, mC, J, e = (rotor.shaft_stiffness, rotor.shaft_damping, rotor.mass, rotor.inertia, rotor.eccentricity)
    h, am, af, wf = step.h, step.alpha_m, step.alpha_f, step.new_weight
    cm, cc = step.mass_coefficient, step.damping_coefficient
    kr = rotor_step_stiffness(rotor, step)
    t0 = time.perf_counter()
    # the plate's rows: its dashpot, and the rotor centre condensed onto it (w c2 - (w c2)**2 / k_r)
    ksp, Keff, (d_x, d_z) = step_operator(
        K, M, N, cc * b1 + wf * c2 - (wf * c2) ** 2 / kr, wf * c2 - (wf * c2) ** 2 / kr, wf, cm, model.comm
    )
    vecs = [K.createVecRight() for _ in range(14)]
    u, v, a, w, R, u1, gN, gZ, tmp, pred, Ku, Mu, Mv, Ma = vecs
    plate = Plate(u, rows, model.comm)
    for x in vecs:
        x.set(0.0)
    for g, i in ((gN, 0), (gZ, 1)):  # the plate under a unit load on U_x, U_z
        unit = [0.0, 0.0]
        unit[i] = 1.0
        plate.add(R, unit)
        ksp.solve(R, g)
        R.set(0.0)
    (gNN, gNZ), (gZN, gZZ) = plate.get(gN), plate.get(gZ)
    gcoef = (gNN, gZN, gNZ, gZZ)
    gamma = -wf * c2 * e * (1 - wf * c2 / kr)
    setup = time.perf_counter() - t0
    r = model.influence(0)
    Mr = M.createVecLeft()
    M.mult(r, Mr)
    mask = M.getDiagonal()  # rows with mass: not clamped, not placeholders
    mask.getArray()[:] = mask.getArray(readonly=True) != 0.0
    vecs += [r, Mr, mask]

    tg = h * np.arange(steps + 1)
    ag = np.asarray(motion.evaluate(tg)[2], dtype=float)
    ug = np.asarray(motion.inertial_displacement(tg), dtype=float)
    M0s, slopes = (np.asarray(x, dtype=float) for x in drive.at(tg))
    kload = drive.load_coefficient
    # start (see the module text)
    x, y, vx, vy = rotor_start(rotor, theta0, W0)
    Ux = Uz = vUx = 0.0
    th, W = theta0, W0
    a.pointwiseMult(r, mask)
    a.scale(-ag[0])
    t_start = time.perf_counter()
    add_shaft_acceleration(M, mask, plate, a, (c2 * (x - e * math.cos(th)), c2 * (y - e * math.sin(th))))
    setup += time.perf_counter() - t_start
    aUx = float(plate.get(a)[0])
    ax = (-c2 * (x - e * math.cos(th)) - b2 * vx - mC * ag[0]) / mC
    ay = (-c2 * (y - e * math.sin(th)) - b2 * vy) / mC
    tau = drive_torque(M0s[0], slopes[0], kload, W0)
    Tc = coupling_torque(rotor, x - Ux, y - Uz, th)
    alpha = 0.0 if prescribed else (tau + Tc) / J
    work = np.zeros(4)
    n_out = steps // stride + (1 if steps % stride else 0) + 1
    keys = ("t", "Omega", "theta", "tip_x", "rotor_x", "rotor_y", "plate_z", "shaft_x", "shaft_y", "energy")
    out: dict[str, Any] = {k: np.zeros(n_out) for k in keys}
    out["work"] = np.zeros((n_out, 4))
    peaks = dict.fromkeys(
        ("tip_x", "tip_x_absolute", "rotor_x", "rotor_y", "shaft_deflection_x", "shaft_deflection_y", "plate_z"), 0.0
    )

    M.mult(a, Ma)

    def energy():
        E = 0.5 * u.dot(Ku) + 0.5 * v.dot(Mv) + 0.5 * mC * (vx * vx + vy * vy)
        E += 0.5 * c2 * ((x - Ux - e * math.cos(th)) ** 2 + (y - Uz - e * math.sin(th)) ** 2)
        return E + (0.0 if prescribed else 0.5 * J * W * W)

    def record(j, t):
        for k, val in (
            ("t", t),
            ("Omega", W),
            ("theta", th),
            ("tip_x", Ux),
            ("rotor_x", x),
            ("rotor_y", y),
            ("plate_z", Uz),
            ("shaft_x", x - Ux - e * math.cos(th)),
            ("shaft_y", y - Uz - e * math.sin(th)),
            ("energy", energy()),
        ):
            out[k][j] = val
        out["work"][j] = work
        if observer is not None:
            observer.record(t, u)

    record(0, 0.0)
    j, newton, newton_max, status = 1, 0, 0, "ok"
    bu, bv, ba = h, h * h * (0.5 - step.beta), h * (1 - step.gamma)
    t_int = time.perf_counter()
    for n in range(1, steps + 1):
        t = n * h
        agw = wf * ag[n] + af * ag[n - 1]
        sx0, sy0 = x - Ux - e * math.cos(th), y - Uz - e * math.sin(th)
        # R = M (cm u~ - am a - r a_g) - af K u + the plate's dashpot and condensed rotor,
        # from the products M u, M v, M a, K u the last step left (no product here)
        u.copy(pred)
        pred.axpy(bu, v)
        pred.axpy(bv, a)  # pred = u~
        Mu.copy(w)
        w.axpy(bu, Mv)
        w.axpy(bv, Ma)  # w = M u~
        w.copy(R)
        R.scale(cm)
        if am:
            R.axpy(-am, Ma)
        R.axpy(-agw, Mr)
        if af:
            R.axpy(-af, Ku)
        rho_x = step.history(mC, b2, x, vx, ax, -c2 * sx0) - mC * agw
        rho_y = step.history(mC, b2, y, vy, ay, -c2 * sy0)
        dash = step.history(0.0, b1, Ux, vUx, aUx, 0.0)
        plate.add(R, (dash + af * c2 * sx0 + wf * c2 * rho_x / kr, af * c2 * sy0 + wf * c2 * rho_y / kr))
        ksp.solve(R, u1)
        ux_hat, uz_hat = plate.get(u1)
        UxA, UzA, xA, yA = plate_and_rotor(rotor, kr, ux_hat, uz_hat, rho_x, rho_y, gamma, gcoef, wf)
        sx = Affine(xA.a0 - UxA.a0, xA.ac - UxA.ac, xA.as_ - UxA.as_)
        sy = Affine(yA.a0 - UzA.a0, yA.ac - UzA.ac, yA.as_ - UzA.as_)
        if prescribed:
            th1, W1, alpha1, it = theta0 + W0 * t, W0, 0.0, 0
        else:
            try:
                th1, W1, alpha1, it = solve_spin(
                    rotor, h, th, W, alpha, sx, sy, M0s[n], slopes[n], kload, step=step, old_torque=tau + Tc
                )
            except ArithmeticError:
                status = f"Newton on the spin equation failed at t = {t:g} s"
                break
        newton += it
        newton_max = max(newton_max, it)
        c, s = math.cos(th1), math.sin(th1)
        u1.axpy(gamma * c, gN)
        u1.axpy(gamma * s, gZ)
        Ux1, Uz1, x1, y1 = UxA.at(c, s), UzA.at(c, s), xA.at(c, s), yA.at(c, s)
        if not all(map(math.isfinite, (Ux1, x1, y1, th1))):
            status = f"solution diverged (not finite) at t = {t:g} s"
            break
        # the new products: K u1 by one product; M u1 from the step's own equation
        # (Keff u1 = R + the unbalance: cm M u1 = that - wf K u1 - D u1, precise
        # because cm is large), M a1 and M v1 by Newmark's updates, as a1 and v1
        K.mult(u1, Ku)
        rMu0 = r.dot(Mu)
        R.copy(tmp)
        plate.add(tmp, (gamma * c - d_x * Ux1, gamma * s - d_z * Uz1))
        tmp.axpy(-wf, Ku)
        tmp.scale(1.0 / cm)
        tmp.copy(Mu)  # M u1
        v.axpy(ba, a)  # v~
        a.waxpy(-1.0, pred, u1)
        a.scale(1.0 / (step.beta * h * h))  # a1 = (u1 - u~) / (beta h**2)
        v.axpy(step.gamma * h, a)
        Mv.axpy(ba, Ma)
        Ma.waxpy(-1.0, w, Mu)
        Ma.scale(1.0 / (step.beta * h * h))
        Mv.axpy(step.gamma * h, Ma)
        dbase = -0.5 * (ag[n - 1] + ag[n]) * (r.dot(Mu) - rMu0 + mC * (x1 - x))
        u1.copy(u)
        vUx1, aUx1 = step.update(Ux1, *step.predict(Ux, vUx, aUx))
        vx1, ax1 = step.update(x1, *step.predict(x, vx, ax))
        vy1, ay1 = step.update(y1, *step.predict(y, vy, ay))
        tau1 = drive_torque(M0s[n], slopes[n], kload, W1)
        Tc1 = coupling_torque(rotor, x1 - Ux1, y1 - Uz1, th1)
        # work increments by the trapezoidal rule (Newmark's energy identity for its linear part)
        work[0] += 0.5 * (tau + tau1) * (th1 - th)
        work[1] -= 0.5 * (Tc + Tc1) * (th1 - th)
        work[2] += (
            b1 * (Ux1 - Ux) * 0.5 * (vUx + vUx1) + b2 * (x1 - x) * 0.5 * (vx + vx1) + b2 * (y1 - y) * 0.5 * (vy + vy1)
        )
        work[3] += dbase
        Ux, Uz, vUx, aUx, x, y, vx, vy, ax, ay = Ux1, Uz1, vUx1, aUx1, x1, y1, vx1, vy1, ax1, ay1
        th, W, alpha, tau, Tc = th1, W1, alpha1, tau1, Tc1
        for k, val in (
            ("tip_x", Ux),
            ("tip_x_absolute", Ux + ug[n]),
            ("rotor_x", x),
            ("rotor_y", y),
            ("plate_z", Uz),
            ("shaft_deflection_x", x - Ux - e * c),
            ("shaft_deflection_y", y - Uz - e * s),
        ):
            peaks[k] = max(peaks[k], abs(val))
        if n % stride == 0 or n == steps:
            record(j, t)
            j += 1
        if progress and n % max(1, steps // 10) == 0:
            progress(f"3D transient: step {n} of {steps} (t = {t:.3g} s)")
    t_int = time.perf_counter() - t_int
    for obj in vecs + [ksp, Keff]:
        obj.destroy()
    out = {k: val[:j] for k, val in out.items()}
    out["max_abs"] = {k: float(val) for k, val in peaks.items()}
    stats = {
        "status": status,
        "steps": int(n if status == "ok" else n - 1),
        "factorisations": 1,
        "solves": int(n + 2),
        "newton_iterations": int(newton),
        "newton_max": int(newton_max),
        "factorisation_seconds": setup,
        "integration_seconds": t_int,
        "seconds_per_step": t_int / max(n, 1),
        "output_stride": stride,
    }
    return out, stats
