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

import numpy as np

from ..errors import InputError
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import GroundMotion
from ..scene import Scene
from .full_order_loop import integrate
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
from .rotor_top import RotorOnTop, Step


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
    damping_law: str = "ground",
    damping_ratio: float = 0.0,
    drive_reaction: bool = False,
) -> Fem3dTransient:
    """Run ``case`` ("earthquake" or "runup") on the 3D tube with the rotor at its top.

    Defaults follow the reduced models' cases: the scene's excitation, a
    constant drive and the operating speed for the earthquake; the ramped
    drive from rest for the run-up; durations from ``[simulate]``.  ``motion``
    a GroundMotion (along x) or a SpatialGroundMotion (x, y, z).
    ``damping_law`` "ground" (b2 on the rotor's own velocity, Eq. 4 and the
    planar ROM: the default, today's runs) or "gondola" (relative to the
    plate, the spatial model's); ``damping_ratio`` zeta on every mode of the
    loaded tube up to twice the band (the spatial model's
    ``pillar.damping_ratio``; 0: none, today's runs); ``drive_reaction``: the
    motor's reaction on the plate, as on the spatial ROM's gondola (a run that
    starts at speed starts on its static deflection; a run-up does not, as the
    spatial ROM's; False: today's planar runs).
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
    if damping_law not in ("ground", "gondola"):
        raise InputError(f"damping_law = {damping_law!r}: must be ground or gondola")
    start = time.perf_counter()
    model = assemble_pillar(scene, top=True, mesh=mesh, comm=comm)
    rotor = RotorOnTop.from_scene(scene)
    try:
        band = 2.0 * scene.modal_model.band_factor * max(rule.forcing.values(), default=0.0)
        modal = _modal_damping(model, damping_ratio, band, scene.modal.tolerance) if damping_ratio > 0 else None
        _rotor_along_the_spin_axis(model, rotor.mass)
        if observer is not None:
            observer.attach(model)
        out, counts = integrate(
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
            damping_law=damping_law,
            modal=modal,
            drive_reaction=drive_reaction,
            reaction_start=drive_reaction and case != "runup",
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
        damping_law="pillar: b1 as a dashpot on the plate's x and y; b2 on the rotor centre's "
        + ("velocity relative to the ground" if damping_law == "ground" else "motion relative to the plate")
        + " in x and vertical; "
        + (
            f"zeta = {damping_ratio:g} on the loaded tube's {len(modal[1])} modes below {band:.4g} rad/s"
            if modal is not None
            else "no structural ratio"
        )
        + "; no Rayleigh term",
        frame="relative_to_ground",
        forcing="-M r_d a_d along each direction the ground moves, on tube, plate and rotor "
        "(along the spin axis the rotor rides on the plate)"
        + ("; the motor's reaction Md on the plate about the spin axis" if drive_reaction else ""),
        start=(
            "tube on its static deflection under the motor's reaction, rotor in its steady whirl on it"
            if drive_reaction and case != "runup"
            else "tube at rest, rotor in its steady whirl on a held plate"
        ),
        initial_speed=W0,
        initial_angle=initial_angle,
        prescribed_speed=bool(prescribed_speed),
        **notes,
    )
    return transient_result(case, out, stats, model.size + 3, wall, info, motion, drive, prescribed_speed, check.failed)


def _modal_damping(model, zeta: float, up_to: float, tol: float):
    """(W, d) of the structural ratio on the loaded tube's modes below ``up_to`` (rad/s), the
    rotor not on them (rotorpillar.fem3d.spatial_system, as the spatial model has it)."""
    from .spatial_system import _modal_damping as modal

    W, d, _ = modal(model, zeta, up_to, tol, 0)
    return W, d


def _rotor_along_the_spin_axis(model, mass: float) -> None:
    """The rotor's mass on the plate's U_y: along the spin axis it rides on the plate (N + 1)."""
    from petsc4py import PETSc

    row = model.tube_dofs + 1
    lo, hi = model.M.getOwnershipRange()
    if lo <= row < hi:
        model.M.setValue(row, row, mass, addv=PETSc.InsertMode.ADD_VALUES)
    model.M.assemble()


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
