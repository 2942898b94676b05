"""An earthquake in two or three components: the spatial ROM against the 3D full order.

`rotorpillar compare --case earthquake --components 3` (the run's stage
``compare_earthquake_components``): the scene's record and its second and
vertical components (``excitation.components``, ``excitation.angle``;
rotorpillar.reduced.ground3d: the built-in El Centro's 180, 270 and UP
records) act at once on

- the spatial reduced model (rotorpillar.reduced.spatial_model, on the
  chain's pillar modes in every direction, b2 relative to the gondola, the
  structural ratio ``pillar.damping_ratio``), over the whole record;
- the 3D full order with the rotor on its top, the same damping law and
  ratio (rotorpillar.fem3d.full_order.simulate_fem3d, damping_law
  "gondola"), over a short window from the start (``full_order.earthquake_
  duration``): it is the expensive part.

Both start at the planar ROM's operating speed with the rotor in its steady
whirl on a motionless top (rotorpillar.fem3d.rotor_start), the drive's
torque curve acting.  The base reactions in six components (two shears,
the axial force, two moments, the torque) come from each model's own
section resultants (the ROM: the modes' base resultants superposed,
rotorpillar.reduced.spatial_forces; the 3D: the base cut's nodal forces,
rotorpillar.fem3d.stress); the base stress from the resultant moment
sqrt(M_x**2 + M_y**2) at each instant and the axial force, not from the sum
of the two moments' maxima (which is given beside it, to show what that
sum would overstate).  The ROM's peaks are given twice: over the whole record
and over the 3D model's window, the like-for-like comparison.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..chain import ChainModes
    from ..scene import Scene

import time
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..records import Array, Record, replace

#: the base reactions compared, in the ROM's BaseReactions' names, with the 3D's index
#: in its section resultants (rotorpillar.fem3d.stress.base_reactions_six's order)
COMPONENTS = (
    ("shear_x", 0, "shear force in the rotor's plane", "N"),
    ("shear_y", 3, "shear force along the spin axis", "N"),
    ("axial_force", 2, "axial force, compression positive, the weights included", "N"),
    ("moment_x", 4, "moment about x (bending along the spin axis)", "N*m"),
    ("moment_y", 1, "moment about y (bending in the rotor's plane)", "N*m"),
    ("torque", 5, "torque about the vertical", "N*m"),
)
#: samples of the series kept in the JSON (each model's)
SERIES_SAMPLES = 1501


class ComponentPeak(Record):
    """One base reaction's peak |value| on both models."""

    name: str
    """shear_x, shear_y, axial_force, moment_x, moment_y, torque, moment (the resultant) or stress"""
    label: str
    """what it is, in words"""
    unit: str
    """N, N*m or Pa"""
    modal: float
    """the spatial ROM's peak over the whole record"""
    modal_window: float
    """the spatial ROM's peak over the 3D model's window"""
    fem3d: float | None
    """the 3D full order's peak over its window; None when it did not run"""
    relative: float | None
    """(modal_window - fem3d) / fem3d (-)"""


class ComponentSeries(Record, eq=False):
    """A model's base reactions over time (sampled), for the page's chart."""

    t: Array
    """(n,) times (s)"""
    moment: Array
    """(n,) resultant base moment sqrt(M_x**2 + M_y**2) (N*m)"""
    moment_x: Array
    """(n,) moment about x (N*m)"""
    moment_y: Array
    """(n,) moment about y (N*m)"""
    stress: Array
    """(n,) base stress from the resultant moment and the axial force, compression positive (Pa)"""
    tip_x: Array
    """(n,) the top's displacement in the rotor's plane, relative to the ground (m)"""


class ComponentsComparison(Record, eq=False):
    """compare_earthquake_components.json: a multi-component earthquake on the spatial ROM and the
    3D full order, the base reactions in six components."""

    case: str
    """"earthquake\""""
    components: tuple[str, ...]
    """the ground motion's components, in words"""
    directions: tuple[tuple[float, float, float], ...]
    """each component's unit direction (x in the rotor's plane, y along the spin axis, z vertical)"""
    angle: float
    """excitation.angle: the first horizontal component's angle to the rotor's plane (deg)"""
    operating_speed: float
    """the rotor's speed at the start (rad/s)"""
    modal_duration: float
    """the ROM's run: the whole record (s)"""
    window: float
    """the 3D full order's run, from the start (s)"""
    peaks: tuple[ComponentPeak, ...]
    """each base reaction's peak on both models, then the resultant moment and the base stress"""
    sum_of_maxima: ComponentPeak
    """max |M_x| + max |M_y|, what adding the two moments' maxima would claim (N*m)"""
    peak_tip: tuple[ComponentPeak, ...]
    """the top's largest displacement relative to the ground in the rotor's plane (tip_x) and
    along the spin axis (tip_y) (m)"""
    modal: ComponentSeries
    fem3d: ComponentSeries | None
    modal_model: str
    """the spatial ROM, in words"""
    fem3d_model: str
    """the 3D full order, in words"""
    modal_seconds: float
    """the ROM's wall time (s)"""
    fem3d_seconds: float | None
    """the 3D full order's wall time (s)"""
    modal_peak_time: float | None = None
    """when the spatial ROM's resultant base moment is largest over the whole record (s, from the
    run's start; the 3D full order's window from the start holds it when it is at most ``window``)"""
    warnings: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


def _series(t, **values) -> ComponentSeries:
    """Every series at the same ~SERIES_SAMPLES of the run's own instants (picked, not
    interpolated: the resultant stays the hypotenuse of its components at each one)."""
    t = np.asarray(t, dtype=float)
    pick = np.unique(np.linspace(0, len(t) - 1, min(SERIES_SAMPLES, len(t))).round().astype(int))
    return ComponentSeries(t[pick], **{k: np.asarray(v, dtype=float)[pick] for k, v in values.items()})


def compare_components(scene: Scene, chain: ChainModes | None, *, progress=None, fem3d: bool = True):
    """The comparison of the module text on ``scene`` (its excitation a record with
    ``components`` >= 2); ``fem3d`` False: the ROM alone (its peaks only)."""
    from ..fem3d.rotor_top import RotorOnTop, rotor_start
    from ..reduced.band import forcing_top
    from ..reduced.drive import DriveSchedule
    from ..reduced.ground3d import scene_spatial_motion
    from ..reduced.integration import Settings, simulate
    from ..reduced.models import build_model
    from ..reduced.spatial_forces import base_reactions
    from ..reduced.spatial_rotor import SpatialRotor
    from ..reduced.spatial_scene import scene_spatial_model, scene_spatial_modes
    from ..reduced.stationary import operating_speed
    from ..reduced.tower import section_at

    x = scene.excitation
    if x.kind != "record" or x.components < 2:
        raise InputError(
            f"excitation.components = {x.components} (kind {x.kind}): the multi-component comparison "
            'needs excitation.kind = "record" and components 2 or 3'
        )
    say = progress or (lambda m: None)
    motion = scene_spatial_motion(x)
    d, L = scene.drive, scene.load
    top = scene.modal_model.band_factor * forcing_top(d, L, scene.sweep, "earthquake", motion.components[0])
    planar, _ = build_model(scene, "modal", top, pillar_modes=None if chain is None else chain.modes)
    W0 = operating_speed(planar, d.torque_at_zero, d.slope, L.coefficient)
    drive = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
    modes = scene_spatial_modes(scene, None if chain is None else getattr(chain, "spatial", None))
    m = scene_spatial_model(scene, top, modes)
    rx, rz, vx, vz = rotor_start(RotorOnTop.from_scene(scene), 0.0, W0)
    q0, v0 = np.zeros(m.n), np.zeros(m.n)
    ix, iz = m.coordinates.index("rotor_x"), m.coordinates.index("rotor_vertical")
    q0[ix], q0[iz], v0[ix], v0[iz], v0[-1] = rx, rz, vx, vz, W0
    # at speed the motor's reaction Md holds the top rolled: both models start on its static
    # deflection (as simulate's spatial ROM does, rotorpillar.transients.cases.on_reaction), so
    # that neither rings from a moment switched on at t = 0
    q0 = q0 + SpatialRotor.of(m).reaction_deflection(d.torque_at_zero - d.slope * W0)
    end = float(motion.end)
    sim = scene.simulate
    say(f"components: the spatial ROM ({m.n} dofs) under {motion.count} components over {end:.3g} s")
    start = time.perf_counter()
    R = simulate(
        m,
        drive,
        motion,
        end,
        q0,
        v0,
        settings=Settings("dp5", rtol=sim.rtol, samples=max(sim.samples, 4001), max_steps=sim.max_steps),
        speed_scale=W0,
    )
    modal_seconds = time.perf_counter() - start
    rb = base_reactions(m, R.t, R.q, scene.pillar, scene.gondola.mass)
    assert m.frame == "relative_to_ground"  # its coordinates: the top relative to the ground
    tip = R.q[:, : m.nz]
    tip_x, tip_y = tip @ m.outputs["tip_x"], tip @ m.outputs["tip_y"]
    window = min(float(scene.full_order.earthquake_duration or end), end)
    warnings, notes = [], []
    sec = section_at(scene.pillar, 0.0)
    f3 = None
    fem3d_seconds = None
    fem3d_model = "not run"
    if fem3d:
        f3, fem3d_seconds, fem3d_model = _fem3d_run(scene, motion, drive, window, W0, say)
    modal_series = _series(
        R.t, moment=rb.moment, moment_x=rb.moment_x, moment_y=rb.moment_y, stress=rb.stress, tip_x=tip_x
    )
    inside = R.t <= window + 1e-9
    peaks = []
    for name, k, label, unit in COMPONENTS:
        a = np.abs(getattr(rb, name))
        b = None if f3 is None else float(np.max(np.abs(f3.base[:, k])))
        peaks.append(_peak(name, label, unit, a, inside, b))
    for name, label, unit in (
        ("moment", "resultant base moment sqrt(M_x**2 + M_y**2), its largest at one instant", "N*m"),
        ("stress", "base stress from the resultant moment and the axial force, compression positive", "Pa"),
    ):
        b = None if f3 is None else float(np.max(np.abs(getattr(f3, name))))
        peaks.append(_peak(name, label, unit, np.abs(getattr(rb, name)), inside, b))
    summed = _peak(
        "sum_of_maxima",
        "max |M_x| + max |M_y|: the two moments' maxima added (what the resultant at each instant avoids)",
        "N*m",
        None,
        inside,
        None if f3 is None else float(np.max(np.abs(f3.base[:, 4])) + np.max(np.abs(f3.base[:, 1]))),
        modal=(
            float(np.max(np.abs(rb.moment_x)) + np.max(np.abs(rb.moment_y))),
            float(np.max(np.abs(rb.moment_x[inside])) + np.max(np.abs(rb.moment_y[inside]))),
        ),
    )
    tip_peak = (
        _peak("tip_x", "the top in the rotor's plane", "m", np.abs(tip_x), inside, None if f3 is None else f3.tip[0]),
        _peak("tip_y", "the top along the spin axis", "m", np.abs(tip_y), inside, None if f3 is None else f3.tip[1]),
    )
    # a reaction nothing excites (the torque: the tube is axisymmetric and the rotor's spin axis
    # is horizontal, so only round-off twists it) has no relative difference worth a number
    floor = 1e-6 * max(p.modal_window for p in peaks if p.name == "moment")
    quiet = [p.name for p in peaks if p.unit == "N*m" and max(p.modal_window, p.fem3d or 0.0) < floor]
    peaks = [replace(p, relative=None) if p.name in quiet else p for p in peaks]
    if quiet:
        notes.append(
            f"{', '.join(quiet)}: below 1e-6 of the resultant moment on both models, round-off (nothing "
            "excites it): no relative difference given"
        )
    if f3 is not None:
        notes.append(
            "along the spin axis the two models differ by design: the spatial ROM carries the rotor on "
            "the shaft's axial stiffness (its 'rotor along the spin axis' mode), the 3D full order moves "
            "it with the top plate along the spin axis; the spin axis' shear, moment_x and tip_y differ "
            "by that as well as by the ROM's truncation"
        )
    if any(d[2] != 0 for d in motion.directions):
        # the vertical component's inertia: the pillar's axial modes lie far above the band, so
        # the ROM keeps none and the base's axial force misses the whole mass times the
        # vertical acceleration (the mode displacement method's truncation; the 3D has it)
        from ..reduced.tower import tower_mass

        mass = tower_mass(scene.pillar) + scene.gondola.mass + scene.rotor.mass
        grid = np.linspace(motion.start, motion.end, 20001)
        az = float(np.max(np.abs(motion.evaluate(grid)[2, 2])))
        warnings.append(
            f"the ROM's axial force leaves out the vertical component's inertia (no axial mode in its "
            f"band): up to {mass * az / 1e3:.3g} kN (the machine's {mass:.0f} kg x the record's "
            f"{az:.3g} m/s**2), {mass * az / sec.area / 1e6:.3g} MPa of base stress; the 3D full "
            "order's axial force and stress include it"
        )
    at = float(R.t[int(np.argmax(rb.moment))])
    if at > window:
        warnings.append(
            f"the ROM's largest base moment comes at {at:.3g} s, past the 3D model's window ({window:g} s): "
            "the 3D full order is compared over its window only (modal_window); raise "
            f"full_order.earthquake_duration past {at:.3g} s for its window to hold it"
        )
    notes.append(_window_note(at, window))
    if f3 is not None and not f3.ok:
        warnings.append("the 3D full order failed its own checks (energy balance or stability): see its notes")
    notes.append(
        f"base stress: |M| c / I + N / A at the base section (c = {sec.outer_diameter / 2:g} m, "
        f"I = {sec.second_moment:.4g} m**4, A = {sec.area:.4g} m**2)"
    )
    notes.append(
        "not validated as a whole against an independent reference: the spatial ROM and the 3D full "
        "order agree on one component in the rotor's plane (tests/test_fem3d_transient.py, 1 %); this "
        "comparison is the check of the other directions"
    )
    return ComponentsComparison(
        case="earthquake",
        components=tuple(motion.names),
        directions=tuple(motion.directions),
        angle=float(x.angle),
        operating_speed=float(W0),
        modal_duration=end,
        window=window,
        peaks=tuple(peaks),
        sum_of_maxima=summed,
        peak_tip=tip_peak,
        modal=modal_series,
        fem3d=None if f3 is None else f3.series,
        modal_model="spatial ROM: " + "; ".join(m.notes),
        fem3d_model=fem3d_model,
        modal_seconds=modal_seconds,
        fem3d_seconds=fem3d_seconds,
        modal_peak_time=at,
        warnings=tuple(warnings),
        notes=tuple(notes),
    )


def _window_note(at: float, window: float) -> str:
    """Why the 3D full order's window starts with the run, not around the ROM's peak."""
    where = "inside it" if at <= window else "past it"
    return (
        f"the 3D full order runs the first {window:g} s from the start (the ROM's largest base moment at "
        f"{at:.3g} s is {where}), not a window placed around the ROM's peak: started from rest partway "
        "into the record, it would miss the motion the record built up before (the free response of "
        "that mismatch decays only over 1 / (zeta omega) of the first bending mode, seconds at a few "
        "per cent of damping) and its ground would jump in velocity where the record is cut; started "
        "from the ROM's state, it would need the ROM's modal coordinates expanded onto the 3D mesh's "
        "nodes, which pillar modes from another model (the chain's beam or mesh) do not give. From "
        "the start both models begin from one state, the rotor whirling steadily on a motionless top"
    )


def _peak(name, label, unit, a, inside, fem3d, modal=None) -> ComponentPeak:
    whole, win = modal if modal is not None else (float(np.max(a)), float(np.max(a[inside])))
    rel = None if fem3d is None or fem3d == 0 else (win - fem3d) / fem3d
    return ComponentPeak(name, label, unit, whole, win, fem3d, rel)


def _fem3d_run(scene: Scene, motion, drive, window: float, W0: float, say):
    """The 3D full order over ``window`` (s): its base resultants, resultant moment, stress, tip."""
    from ..fem3d.full_order import simulate_fem3d
    from ..reduced.tower import section_at
    from .forces import stress_observer
    from .run_plan import fem3d_plan

    plan = fem3d_plan(scene, "earthquake", motion.components[0], window)
    mesh = plan.mesh
    say(f"components: the 3D full order on {mesh.elements_around} x {mesh.elements_along} elements over {window:g} s")
    observer = stress_observer(scene, window, None, "")
    start = time.perf_counter()
    try:
        r = simulate_fem3d(
            scene,
            "earthquake",
            motion=motion,
            drive=drive,
            duration=window,
            time_step=plan.time_step,
            mesh=mesh,
            samples=scene.simulate.samples,
            initial_speed=W0,
            progress=say,
            observer=observer,
            damping_law="gondola",
            damping_ratio=scene.pillar.damping_ratio,
            drive_reaction=True,
        )
        t, res, _vm, _path = observer.finish()
    finally:
        observer.close()
    seconds = time.perf_counter() - start
    base = np.asarray(res, dtype=float)[:, 0, :]
    if base.shape[1] != 6:
        raise RuntimeError("the 3D observer kept fewer than six components per cut")
    moment = np.hypot(base[:, 1], base[:, 4])
    sec = section_at(scene.pillar, 0.0)
    stress = moment * (sec.outer_diameter / 2) / sec.second_moment + base[:, 2] / sec.area
    tip_x = np.interp(t, r.t, r.tip_x)
    series = _series(t, moment=moment, moment_x=base[:, 4], moment_y=base[:, 1], stress=stress, tip_x=tip_x)
    words = (
        f"3D full order, {mesh.elements_around} x {mesh.elements_along} x {mesh.elements_through} elements "
        f"of degree {mesh.degree} ({plan.reference.source if hasattr(plan, 'reference') else 'its plan'}), "
        f"{window:g} s from the start; b2 relative to the gondola, zeta = {scene.pillar.damping_ratio:g} on the "
        "loaded tube's modes"
    )
    run = _Fem3dBase(base, moment, stress, (float(r.max_abs["tip_x"]), float(r.max_abs["tip_y"])), series, r.ok)
    return run, seconds, words


@dataclass(frozen=True, eq=False)
class _Fem3dBase:
    """What the comparison reads of the 3D run (not written)."""

    base: np.ndarray
    """(n, 6) the base cut's resultants (rotorpillar.fem3d.stress's order)"""
    moment: np.ndarray
    stress: np.ndarray
    tip: tuple[float, float]
    """the largest |tip_x|, |tip_y| (m)"""
    series: ComponentSeries
    ok: bool
