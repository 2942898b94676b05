"""The Campbell diagram of the 3D model with the rotor on its top (`rotorpillar campbell --model fem3d`).

The system is rotorpillar.fem3d.spatial_system's: the 3D tube (the chain's
mesh, or the scene's) with the gondola as a rigid body on its rigid top,
the rotor on its shaft (lateral c2, axial, tilt; b2 and the tilt damping on
the motion relative to the gondola), the tip dashpot b1 in both horizontal
directions, ``pillar.damping_ratio`` on every mode of the loaded tube in
the band and past it (twice the band's top), and the gyroscopic matrix
J_C Omega on the spin axis' pitch and yaw.  At each speed Omega,

    (M s**2 + (C + Omega G) s + K) x = 0

for every eigenvalue with |s| up to the band's top (``band_top``), in real
arithmetic, over one factorisation of K (rotorpillar.fem3d.quadratic_eigen:
a block Arnoldi on the linearisation, each speed started from the last
speed's eigenvectors; SLEPc's PEP TOAR with ``method = "toar"``).

The branches are followed by their eigenvectors (rotorpillar.fem3d.
campbell_tracking: degenerate clusters aligned to the previous speed's
vectors first, then the MAC), named at the speed where they appear (the
rotor's share of the kinetic energy, else the tube's shape by
rotorpillar.fem3d.identify), and their whirl read at every speed.  Each
branch's frequency is the damped natural frequency Im(s), its damping
ratio -Re(s) / |s|, its logarithmic decrement 2 pi zeta / sqrt(1 -
zeta**2).  Critical speeds: where Omega equals a tracked (damped) branch's
frequency, linearly interpolated between two of the diagram's speeds;
"excited_by" from the mode's forward circular share of the rotor centre's
motion (static unbalance) or of its spin axis' (couple unbalance).

Before any meshing, the run's size is estimated (``estimate``) and refused
(``check_budget``) above the memory this process may use or a time limit.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import InputError
from ..records import Record
from ..reduced.campbell import CampbellDiagram
from ..scene import Scene
from .campbell_branches import ROTOR_AXIAL, ROTOR_ON_SHAFT, ROTOR_TILT, BranchTracker  # noqa: F401
from .rotor_spatial import SpatialRotor

#: the time a 3D Campbell may take before it is refused (s)
MAX_SECONDS = 3600.0
#: seconds per speed per dof**1.5: 2.4-2.7 s a speed at 24,200 dofs measured on the 2-core
#: machine shared with other jobs (bench/bench_campbell_fem3d.py; ~1 s when it is quiet); the
#: assembly, the modes for the damping and the critical speeds' pencil cost ~15 speeds more; with
#: the AFs, ~2 x AF_POINTS speeds of the unbalance response (~0.4 of a Campbell speed each) per
#: critical speed, ~8 of them.  An estimate, stated as one.
SECONDS_PER_DOF15 = 6.5e-7
FIRST_SPEED = 15.0
AF_SPEEDS = 8 * 2 * 25 * 0.4
#: basis columns of a speed, for the memory estimate (block method: ~60-200 columns, 2 n each)
BASIS_COLUMNS = 200


#: speeds of the 3D unbalance response around each critical speed for its AF (with_af)
AF_POINTS = 25
#: the curves whose peak gives a critical speed's AF: the shaft, the rotor and the top
AF_CURVES = ("shaft x", "shaft z", "rotor x", "rotor z", "top x", "top y", "top z")


class CampbellEstimate(Record):
    """The size of a 3D Campbell diagram before it starts."""

    dofs: int
    """estimated unknowns of the tube, its top and the rotor (-)"""
    speeds: int
    """speeds solved (-)"""
    seconds: float
    """estimated wall time (s)"""
    bytes: float
    """estimated peak memory (bytes)"""


def estimate(scene: Scene, n_speeds: int, mesh=None, with_af: bool = False) -> CampbellEstimate:
    """The run's size from the scene alone (no mesh built)."""
    from ..mesh import tube_params

    p = tube_params(scene.pillar, scene.mesh if mesh is None else mesh)
    dofs = int(p.estimated_dofs + 11)
    seconds = SECONDS_PER_DOF15 * dofs**1.5 * (n_speeds + FIRST_SPEED + (AF_SPEEDS if with_af else 0.0))
    need = p.estimated_bytes + 8.0 * 2 * dofs * BASIS_COLUMNS
    return CampbellEstimate(dofs, int(n_speeds), float(seconds), float(need))


def check_budget(est: CampbellEstimate, max_seconds: float = MAX_SECONDS) -> None:
    """Refuse (InputError, one line) a diagram above this process's memory or ``max_seconds``."""
    from ..provenance import check_memory

    what = f"the 3D Campbell diagram ({est.speeds} speeds on ~{est.dofs:,} DOFs)"
    check_memory(est.bytes, what, "use a coarser mesh")
    if not est.seconds <= max_seconds:
        raise InputError(
            f"{what} would take about {est.seconds / 60:.3g} min, more than {max_seconds / 60:.3g} min: "
            "ask fewer speeds or a coarser mesh"
        )


def campbell_fem3d(
    scene: Scene,
    speeds,
    *,
    band_top: float,
    mesh=None,
    damping_law: str = "gondola",
    method: str = "block",
    running_speed: float | None = None,
    max_seconds: float = MAX_SECONDS,
    with_af: bool = False,
    comm=None,
    progress=None,
) -> CampbellDiagram:
    """The 3D Campbell diagram at ``speeds`` (rad/s) of the modes up to ``band_top`` (rad/s) on
    ``mesh`` (a scene Mesh section; default ``scene.mesh``); see the module text.  ``with_af``:
    each critical speed the unbalance drives gets the AF of the 3D unbalance response's peak
    near it (``amplification_factors``: AF_POINTS speeds of the response each).  Collective."""
    from mpi4py import MPI

    from . import assemble_pillar
    from .critical_speeds import critical_speeds
    from .quadratic_eigen import METHODS, Products, solve_quadratic, solve_quadratic_toar, stiffness_factor
    from .spatial_system import assemble_system

    speeds = np.asarray(speeds, dtype=float)
    if speeds.ndim != 1 or len(speeds) < 2 or np.any(~np.isfinite(speeds)) or np.any(np.diff(speeds) <= 0):
        raise InputError("speeds: at least two, finite and ascending (rad/s)")
    if not (math.isfinite(band_top) and band_top > 0):
        raise InputError(f"band_top = {band_top!r}: must be finite and > 0 (rad/s)")
    if method not in METHODS:
        raise InputError(f"method = {method!r}: must be one of {', '.join(METHODS)}")
    if scene.modal.top_model != "rigid":
        raise InputError('the 3D Campbell hangs the rotor on the rigid top plate: modal.top_model must be "rigid"')
    if scene.modal.top_mass != "gondola":
        raise InputError('the 3D Campbell hangs the rotor on its shaft: modal.top_mass must be "gondola"')
    comm = MPI.COMM_WORLD if comm is None else comm
    say = progress or (lambda m: None)
    est = estimate(scene, len(speeds), mesh, with_af)
    check_budget(est, max_seconds)
    say(f"campbell (3D): {len(speeds)} speeds on ~{est.dofs:,} DOFs, about {est.seconds:.0f} s (estimate)")
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    model = assemble_pillar(scene, top=True, mesh=mesh, comm=comm)
    rotor = SpatialRotor.from_scene(scene)
    radius = float(band_top)
    system = assemble_system(
        model,
        rotor,
        tip_damping=scene.pillar.damping,
        damping_ratio=scene.pillar.damping_ratio,
        damped_up_to=2.0 * radius,
        damping_law=damping_law,
        tol=scene.modal.tolerance,
    )
    timings["assembly"] = time.perf_counter() - t0
    ksp = None
    try:
        t0 = time.perf_counter()
        ksp, factor = stiffness_factor(system.K)
        timings["factorisation"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        ops = Products(system, 0.0, factor, comm)
        tracker = BranchTracker(system, comm, ops)
        seeds, solves, worst = None, 0, 0.0
        for i, w in enumerate(speeds):
            if method == "block":
                q = solve_quadratic(system, float(w), radius, factor, tol=scene.modal.tolerance, seeds=seeds, ops=ops)
                seeds = q.seeds
            else:
                n_want = max(8, 2 * tracker.alive + 4)
                q = solve_quadratic_toar(system, float(w), radius, n_wanted=n_want, tol=scene.modal.tolerance)
            solves += q.solves
            worst = max(worst, float(np.max(q.backward_error, initial=0.0)))
            tracker.add(i, float(w), q.s, q.X)
            if progress and (i + 1) % max(1, len(speeds) // 10) == 0:
                say(f"campbell (3D): speed {i + 1} of {len(speeds)} ({w:.4g} rad/s)")
        timings["speeds"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        branches = tracker.branches(len(speeds))
        criticals = critical_speeds(system, radius, speeds, branches, factor, ops)
        timings["critical_speeds"] = time.perf_counter() - t0
        if with_af:
            t0 = time.perf_counter()
            criticals = amplification_factors(system, criticals, branches, speeds)
            timings["af"] = time.perf_counter() - t0
    finally:
        if ksp is not None:
            ksp.destroy()
        system.destroy()
        model.K.destroy()
        model.M.destroy()
    warnings = []
    if worst > 1e-6:
        warnings.append(f"the eigenpairs' largest backward error is {worst:.2g}: the frequencies may be off")
    p = model.params
    cells = f"{p.elements_around} x {p.elements_along} x {p.elements_through}"
    description = (
        f"3D tube ({cells} {model.params.cell_type} cells of degree {model.V.ufl_element().degree()}, "
        f"{system.size:,} unknowns) with the gondola on its rigid top and the rotor on its shaft"
        f"{'' if rotor.tilts else ' (tilting with the gondola)'}; "
        f"{'block Arnoldi on the linearisation' if method == 'block' else 'SLEPc PEP TOAR'}, "
        f"real arithmetic, one factorisation of K"
    )
    notes = (
        f"damping: b1 = {scene.pillar.damping:g} N*s/m at the top in both horizontal directions; "
        f"zeta = {scene.pillar.damping_ratio:.4g} on each of the loaded tube's {len(system.d)} modes below "
        f"{2 * radius:.4g} rad/s (modal, the ROM's); the shaft's b2 = {rotor.lateral_damping:g} N*s/m "
        + ("relative to the gondola" if damping_law == "gondola" else "relative to the ground (Eq. 4)"),
        f"timings: assembly {timings['assembly']:.3g} s, factorisation {timings['factorisation']:.3g} s, "
        f"{len(speeds)} speeds {timings['speeds']:.3g} s ({timings['speeds'] / len(speeds):.3g} s a speed, "
        f"{solves / len(speeds):.0f} right-hand sides a speed); largest backward error {worst:.2g}",
        "critical speeds: the undamped gyroscopic pencil K v = Omega**2 (M - i G) v (s = i Omega), "
        f"each named after the branch whose frequency is nearest Omega there ({timings['critical_speeds']:.3g} s)",
    )
    return CampbellDiagram(
        model="fem3d",
        speeds=speeds,
        modes=tuple(branches),
        critical_speeds=tuple(criticals),
        running_speed=running_speed,
        description=description,
        notes=notes,
        warnings=tuple(warnings),
    )


def amplification_factors(system, criticals, branches, speeds) -> list:
    """The critical speeds with the AF of the 3D unbalance response's peak near each one the
    unbalance drives, read as the spatial ROM reads its own (rotorpillar.reduced.spatial_response:
    ``peaks_from_samples`` on each of its PEAK_CURVES, the half-power points on the sampled
    curve, then ``peak_near``: of the peaks within 15 % the one with the largest AF): the 3D
    response (static and couple at once) at AF_POINTS speeds over +-45 % of it and as many over
    +-4 zeta (zeta of its branch there); None where no curve shows a peak near it."""
    from ..records import replace
    from ..reduced.spatial_response import (
        PEAK_CURVES,
        ROTATIONS,
        ResponseCurve,
        SpatialResponse,
        peak_near,
        peaks_from_samples,
    )
    from .harmonic import spatial_response

    out = []
    for c in criticals:
        if c.excited_by == "neither":
            out.append(c)
            continue
        zeta = 0.01
        for b in branches:
            if b.label == c.label and b.damping_ratio is not None:
                z = np.asarray(b.damping_ratio, float)
                ok = np.isfinite(z)
                if np.any(ok):
                    zeta = float(np.interp(c.speed, speeds[ok], z[ok]))
        u = np.linspace(-1.0, 1.0, AF_POINTS)
        grid = np.unique(c.speed * np.r_[1 + 0.45 * u, 1 + min(max(4 * zeta, 1e-3), 0.45) * u])
        r = spatial_response(system, grid, "both")
        samples = {
            "shaft_x": r.shaft[:, 0],
            "shaft_z": r.shaft[:, 1],
            "rotor_x": r.rotor[:, 0],
            "rotor_y": r.rotor[:, 1],
            "rotor_z": r.rotor[:, 2],
            "tip_x": r.top[:, 0],
            "tip_y": r.top[:, 1],
            "tip_z": r.top[:, 2],
            "top_pitch": r.top[:, 3],
            "top_yaw": r.top[:, 5],
        }
        # each peak's share of the largest response in the window, rotations times the height
        # (the ROM's share is of the whole curve's largest: over +-45 % the same for these peaks)
        H = system.model.params.height
        amp = {name: np.abs(samples[name]) * (H if name in ROTATIONS else 1.0) for name in PEAK_CURVES}
        largest = max(float(np.max(a)) for a in amp.values()) or 1.0
        curves = tuple(
            ResponseCurve(
                name,
                name,
                np.abs(samples[name]),
                np.zeros(len(grid)),
                tuple(
                    replace(p, share=p.amplitude * (H if name in ROTATIONS else 1.0) / largest)
                    for p in peaks_from_samples(name, grid, np.abs(samples[name]))
                ),
            )
            for name in PEAK_CURVES
        )
        peak = peak_near(SpatialResponse(grid, 0.0, 0.0, curves, ()), c.speed)
        out.append(replace(c, amplification_factor=None if peak is None else peak.amplification_factor))
    return out
