"""A scene's spatial model: its modes, which planes it needs, what it adds to the planar ROM.

- ``scene_spatial_modes``: the pillar's modes in every direction from the
  chain's source (the 3D modes it passes in: rotorpillar.chain's
  ``ChainModes.spatial``), else the 1D beams of rotorpillar.reduced.spatial_beam
  on the scene's [modal_model] settings, with ``pillar.damping_ratio``;
- ``scene_spatial_model``: the spatial model on the modes below the band;
- ``resolve_planes``: ``modal_model.planes``; "auto" keeps the rotor's plane
  where nothing the scene does reaches the other directions: the ground
  moves in the rotor's plane only, no couple unbalance, the rotor at the top
  (its shaft's force has no lever), and the first mode out of the plane
  (axial, torsion, bending along the spin axis) lies above the band, where
  the rotor's vertical pull moves it only quasi-statically.  The reason is
  written into the result;
- ``spatial_analysis``: analyze.json's ``spatial`` block: every direction's
  resonances under their own names, the critical speeds, and the planar
  model's error against the spatial one on the resonances in the rotor's plane
  and on the unbalance response's peaks;
- ``drive_reaction_analysis``: analyze.json's ``drive_reaction``: the stall
  torque's static effect and the run-up's transient with the reaction acting
  (and without it, for the difference);
- ``transient_planes``, ``transient_model``: the planes and the model a
  transient runs ("auto" also weighs the drive's reaction there).

The records of these results (analyze.json's blocks) are defined beside the
functions that compute them; ``PlanesChoice`` is rotorpillar.reduced.
spatial_rotor's (the spatial ROM carries it).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from ..provenance import Record
from ..scene import Scene
from .campbell import CampbellDiagram, CriticalSpeed
from .drive import DriveSchedule
from .excitation import no_motion
from .foundation import foundation_stiffness
from .rotor_models import RotorStructure
from .spatial_beam import beam_spatial_modes
from .spatial_linear import campbell, critical_speeds, damped_modes, mode_kind, mode_whirl
from .spatial_model import SpatialStructure, spatial_model
from .spatial_modes import AXIAL, SpatialPillarModes
from .spatial_response import peak_near, unbalance_response
from .spatial_rotor import PlanesChoice, SpatialRotor
from .spatial_statics import DriveReaction, drive_reaction


class SpatialResonance(Record):
    """A damped mode of the spatial model at rest, named."""

    label: str
    """its name: the kind that carries most of its kinetic energy and its rank among them"""
    kind: str
    """that kind (rotorpillar.reduced.spatial_modes.KINDS, "rotor on its shaft", ...)"""
    omega: float
    """damped natural frequency at rest (rad/s)"""
    damping_ratio: float
    """zeta (-)"""
    whirl_at_running_speed: str
    """its whirl at the running speed: forward, backward or none (a line)"""


class PlanarError(Record):
    """What the planar model misses: the spatial model's numbers against it."""

    planar_omega: tuple[float, ...]
    """the planar ROM's coupled resonances in the rotor's plane (rad/s)"""
    spatial_omega: tuple[float, ...]
    """the spatial model's nearest resonances moving the rotor's plane (rad/s)"""
    relative_difference: tuple[float, ...]
    """planar / spatial - 1 per resonance (-)"""
    peak_tip_planar: float
    """the planar model's largest unbalance response of the top in the rotor's plane over the band (m)"""
    peak_tip_spatial: float
    """the spatial model's (m)"""
    peak_tip_difference: float
    """planar / spatial - 1 (-)"""
    note: str


class SpatialAnalysis(Record):
    """analyze.json's ``spatial``: the machine in three dimensions, beside the planar ROM."""

    planes: PlanesChoice
    model: str
    """the spatial model, in words (modes, damping, tilt)"""
    mode_source: str
    """where its pillar modes come from"""
    running_speed: float | None
    """the speed the whirl is read at (rad/s)"""
    resonances: tuple[SpatialResonance, ...]
    """every direction's damped modes at rest, named"""
    critical_speeds: tuple[CriticalSpeed, ...]
    """where the 1x line crosses a mode (the undamped gyroscopic pencil)"""
    planar_error: PlanarError


class ReactionRunup(Record):
    """The run-up from rest on the spatial model, with the motor's reaction on the gondola and without."""

    duration: float
    """(s)"""
    final_speed: float
    """Omega at the end (rad/s)"""
    peak_tip_displacement: float
    """the largest |top in the rotor's plane| with the reaction (m)"""
    peak_tip_displacement_without: float
    """the same without it (m)"""
    peak_reaction_part: float
    """the largest |difference| the reaction makes to the top in the rotor's plane (m)"""
    peak_tip_rotation: float
    """the largest |roll of the top| with the reaction (rad)"""


class DriveReactionAnalysis(Record):
    """analyze.json's ``drive_reaction``: the stall torque on the gondola, statically and in the run-up."""

    torque: float
    """M0, the drive's stall torque (N*m)"""
    tip_displacement: float
    """the top's static displacement in the rotor's plane under it (m)"""
    tip_rotation: float
    """the top's static roll (rad)"""
    base_moment: float
    """the base's moment about the spin axis (N*m)"""
    statics: DriveReaction
    runup: ReactionRunup | None
    """the run-up's transient with the reaction acting; None when the drive never starts, or
    when the model's stiffest mode would make it too long a run for analyze (``runup_skipped``)"""
    runup_skipped: str | None = None
    """why there is no run-up although the drive starts (None: it ran, or nothing to run)"""


#: the drive's reaction: its static tip displacement at stall against the planar ROM's largest
#: steady unbalance tip amplitude up to the drive's free speed; above this share "auto" runs the
#: transients on the spatial model (-).  Why 0.1: the reaction is a moment that follows the
#: motor's torque, slow against the pillar's first period, so it adds a quasi-static offset to
#: the tip (the structure is linear) and, being steady within a revolution, no averaged torque on
#: the rotor: the speed history is the same, and the planar run's peak tip misses at most that
#: offset.  Up to a tenth of the response it stays below the spread of the scene's damping and
#: eccentricity (the paper states neither to better than that); above it the tip is misstated.
REACTION_SHARE = 0.1
#: the cases the spatial model runs (the sweep's analysis reads the planar model's averaging)
SPATIAL_CASES = ("runup", "rundown", "earthquake")
#: modes per line the beam source computes (its four lines; the band keeps fewer)
BEAM_MODES_PER_LINE = 8


def scene_spatial_modes(scene: Scene, chain_spatial: SpatialPillarModes | None = None) -> SpatialPillarModes:
    """The pillar's modes in every direction: the chain's 3D ones when given, else the beam's,
    each with the scene's structural damping ratio."""
    zeta = scene.pillar.damping_ratio
    if chain_spatial is not None:
        return chain_spatial.with_damping_ratio(zeta)
    mm = scene.modal_model
    return beam_spatial_modes(
        scene.pillar,
        scene.gondola,
        BEAM_MODES_PER_LINE,
        mm.theory,
        mm.elements,
        extra_roll_inertia=mm.gondola_inertia,
        damping_ratio=zeta,
        foundation=foundation_stiffness(scene.foundation),
    )


def scene_spatial_model(
    scene: Scene,
    band_top: float,
    modes: SpatialPillarModes | None = None,
    *,
    planes: str = "spatial",
    damping_law: str = "gondola",
) -> SpatialStructure:
    """The spatial model of the scene on the pillar modes below ``band_top`` (rad/s)."""
    modes = scene_spatial_modes(scene) if modes is None else modes
    return spatial_model(
        modes.below(band_top),
        scene.rotor,
        scene.shaft,
        scene.pillar.damping,
        damping_law=damping_law,
        planes=planes,
    )


def out_of_plane_share(m: SpatialStructure, band_top: float, samples: int = 60) -> float:
    """The largest response out of the rotor's plane (the top along the spin axis, its pitch and
    yaw times the pillar's height, the rotor along the spin axis) over the one in it (the top and
    the rotor in x), of the unbalance response up to ``band_top`` (rad/s) (-)."""
    H = float(m.modes.section_heights[-1]) if m.modes.section_heights is not None else 1.0
    speeds = np.linspace(band_top / samples, band_top, samples)
    r = unbalance_response(m, speeds)
    out = max(
        float(np.max(r.curve("tip_y").amplitude)),
        H * float(np.max(r.curve("top_pitch").amplitude)),
        H * float(np.max(r.curve("top_yaw").amplitude)),
        float(np.max(r.curve("rotor_y").amplitude)),
    )
    inside = max(float(np.max(r.curve("tip_x").amplitude)), float(np.max(r.curve("rotor_x").amplitude)))
    return out / inside if inside > 0 else math.inf


#: out-of-plane response below this share of the in-plane one: the other directions are not excited (-)
OUT_OF_PLANE_SHARE = 1e-6


def resolve_planes(scene: Scene, band_top: float, modes: SpatialPillarModes) -> PlanesChoice:
    """``modal_model.planes`` resolved (see the module text)."""
    asked = scene.modal_model.planes
    if asked != "auto":
        return PlanesChoice(asked, asked, f"modal_model.planes = {asked!r} as the scene states")
    x, r = scene.excitation, scene.rotor
    why = []
    if x.components > 1 or abs(math.sin(math.radians(x.angle))) > 1e-12:
        why.append(
            f"the ground moves out of the rotor's plane (excitation.components = {x.components}, angle {x.angle:g} deg)"
        )
    if r.couple_unbalance > 0:
        why.append(f"the couple unbalance {r.couple_unbalance:g} kg*m**2 tilts the rotor")
    if r.height > 0:
        why.append(f"the rotor's centre {r.height:g} m above the top gives its shaft's force a lever")
    axial = min((float(w) for w, k in zip(modes.omega, modes.kind) if k == AXIAL), default=math.inf)
    if axial <= band_top:
        why.append(
            f"the first axial mode ({axial:.4g} rad/s), which the rotor's vertical pull drives, lies in the band"
        )
    share = out_of_plane_share(scene_spatial_model(scene, band_top, modes), band_top)
    if share > OUT_OF_PLANE_SHARE:
        why.append(f"the unbalance response out of the rotor's plane reaches {share:.3g} of the one in it")
    if why:
        return PlanesChoice("auto", "spatial", "spatial: " + "; ".join(why))
    return PlanesChoice(
        "auto",
        "planar",
        "planar: the ground moves in the rotor's plane only, no couple unbalance, the rotor at the top, the "
        f"unbalance response out of the plane {share:.2g} of the one in it, and the first axial mode "
        f"({axial:.4g} rad/s) above the band ({band_top:.4g} rad/s): the other directions are not excited "
        "(what the planar model still misses, the gondola's inertia, b2 relative to the gondola and the "
        "structural damping: spatial.planar_error)",
    )


def _planar_error(planar: RotorStructure, m: SpatialStructure, band_top: float) -> PlanarError:
    from .bode import unbalance_response as planar_response

    speeds = np.linspace(band_top / 400, band_top, 400)
    x_planar = [float(w) for w in planar.undamped_modes_x()[0]]
    w_sp, U = m.undamped_modes_x()
    in_plane = [
        float(w)
        for w, u in zip(w_sp, U.T)
        if abs(u @ m.outputs["rotor_x"]) + abs(u @ m.outputs["tip_x"])
        > 0.5 * (abs(u @ m.outputs["rotor_z"]) + abs(u @ m.outputs["tip_y"]) + abs(u @ m.outputs["rotor_y"]))
    ]
    near = [min(in_plane, key=lambda w: abs(w - x)) if in_plane else math.nan for x in x_planar]
    tip_planar = float(np.max(planar_response(planar, speeds).tip_amplitude))
    tip_spatial = float(np.max(unbalance_response(m, speeds).curve("tip_x").amplitude))
    return PlanarError(
        tuple(x_planar),
        tuple(near),
        tuple(a / b - 1 for a, b in zip(x_planar, near)),
        tip_planar,
        tip_spatial,
        tip_planar / tip_spatial - 1 if tip_spatial else math.nan,
        "planar: today's ROM (b2 to the ground, b1 at the tip, no structural ratio, no gondola inertia "
        "but modal_model.gondola_inertia); spatial: this block's model; undamped frequencies and the "
        f"largest unbalance response of the top in the rotor's plane up to {band_top:.4g} rad/s",
    )


def spatial_analysis(
    scene: Scene,
    planar: RotorStructure,
    band_top: float,
    running_speed: float | None,
    modes: SpatialPillarModes | None = None,
) -> SpatialAnalysis:
    """analyze.json's ``spatial`` block (see the module text)."""
    modes = scene_spatial_modes(scene) if modes is None else modes
    m = scene_spatial_model(scene, band_top, modes)
    at_rest = damped_modes(m, 0.0)
    at_speed = damped_modes(m, running_speed or 0.0)
    counts: dict[str, int] = {}
    rows = []
    for j, (s, v) in enumerate(zip(at_rest.eigenvalues, at_rest.shapes.T)):
        kind = mode_kind(m, v)
        counts[kind] = counts.get(kind, 0) + 1
        whirl = mode_whirl(m, at_speed.shapes[:, j])[1] if running_speed else "none"
        rows.append(
            SpatialResonance(f"{kind} {counts[kind]}", kind, float(s.imag), float(at_rest.damping_ratio[j]), whirl)
        )
    return SpatialAnalysis(
        planes=resolve_planes(scene, band_top, modes),
        model="; ".join(m.notes),
        mode_source=modes.source,
        running_speed=running_speed,
        resonances=tuple(rows),
        critical_speeds=tuple(c for c in critical_speeds(m) if c.speed <= band_top),
        planar_error=_planar_error(planar, m, band_top),
    )


def drive_reaction_analysis(
    scene: Scene, band_top: float, modes: SpatialPillarModes | None = None
) -> DriveReactionAnalysis:
    """analyze.json's ``drive_reaction`` (see the module text)."""
    from .integration import Settings, simulate

    modes = scene_spatial_modes(scene) if modes is None else modes
    st = drive_reaction(modes, scene.drive.torque_at_zero, scene.pillar)
    m = scene_spatial_model(scene, band_top, modes)
    d = scene.drive
    run, skipped = None, None
    sched = DriveSchedule.constant(d.torque_at_zero, d.slope, scene.load.coefficient)
    if d.torque_at_zero > 0:
        skipped = stiff_runup(m, sched, scene.simulate.duration)
    if d.torque_at_zero > 0 and skipped is None:
        sim = scene.simulate
        settings = Settings("dp5", rtol=sim.rtol, samples=sim.samples, max_steps=sim.max_steps)
        with_r = simulate(m, sched, no_motion(), sim.duration, settings=settings)
        without = simulate(replace(m, reaction=0 * m.reaction), sched, no_motion(), sim.duration, settings=settings)
        tip = with_r.q[:, : m.nz] @ m.outputs["tip_x"]
        tip0 = without.q[:, : m.nz] @ m.outputs["tip_x"]
        roll = with_r.q[:, : m.nz] @ m.outputs["top_roll"]
        run = ReactionRunup(
            sim.duration,
            float(with_r.Omega[-1]),
            float(np.max(np.abs(tip))),
            float(np.max(np.abs(tip0))),
            float(np.max(np.abs(tip - tip0))),
            float(np.max(np.abs(roll))),
        )
    return DriveReactionAnalysis(st.torque, st.tip_displacement, st.tip_rotation, st.base_moment, st, run, skipped)


#: How many times the steps the rotor's speed needs (STEPS_PER_REVOLUTION) dp5 may be
#: made to take by the model's stiffest mode before analyze leaves the reaction's
#: run-up out (-).  Within it the run costs seconds; a shaft or a rotor at the far
#: end of its range (k/m of 1e12 and more) made it minutes of dp5 steps held at the
#: stability limit, for a mode that has nothing to do with the reaction.
STIFFNESS_ALLOWANCE = 20.0


def stiff_runup(m: SpatialStructure, drive: DriveSchedule, duration: float) -> str | None:
    """Why analyze does not run the reaction's run-up on ``m`` (None: it does): the
    stiffest mode would hold dp5's step far below what the rotor's speed needs."""
    from .explicit_limit import spin_rate, stability_step_count
    from .integration import STEPS_PER_REVOLUTION

    free = drive.free_speed()
    speed = free if math.isfinite(free) else 1.0
    by_speed = STEPS_PER_REVOLUTION * speed / (2 * math.pi) * duration
    by_stiffness = stability_step_count(m, duration, "dp5", drive)
    if by_stiffness <= STIFFNESS_ALLOWANCE * max(by_speed, 1.0):
        return None
    return (
        f"not run: the model's fastest rate ({m.fastest_rate():.3g} 1/s) or the spin's rate under "
        f"the drive ({spin_rate(m, drive):.3g} 1/s) would hold dp5 to "
        f"about {by_stiffness:.3g} steps over {duration:.4g} s, {by_stiffness / max(by_speed, 1.0):.3g} times "
        "what the rotor's speed needs; the static effect above stands (simulate --model modal with "
        "modal_model.planes = spatial runs it, at that cost)"
    )


def scene_campbell(
    scene: Scene,
    speeds: NDArray[np.float64],
    band_top: float,
    running_speed: float | None,
    modes: SpatialPillarModes | None = None,
) -> CampbellDiagram:
    """The Campbell diagram of the scene's spatial model over ``speeds`` (rad/s), each critical
    speed with the AF of the unbalance response's peak near it (None: no peak there)."""
    from ..provenance import replace as record_replace

    m = scene_spatial_model(scene, band_top, modes)
    diagram = campbell(m, speeds, running_speed)
    top = max(float(speeds[-1]), 1e-9)
    grid = np.unique(
        np.concatenate(
            [np.linspace(top / 600, top, 600)]
            + [np.linspace(0.9 * c.speed, min(1.1 * c.speed, top), 41) for c in diagram.critical_speeds]
        )
    )
    response = unbalance_response(m, grid)
    crit = tuple(
        record_replace(c, amplification_factor=None if p is None else p.amplification_factor)
        for c in diagram.critical_speeds
        for p in [peak_near(response, c.speed, 0.1)]
    )
    result: CampbellDiagram = record_replace(
        diagram,
        critical_speeds=crit,
        notes=diagram.notes
        + (
            "amplification_factor: API 684's half-power AF of the unbalance response's peak within 10 % of the critical speed",
        ),
    )
    return result


def reaction_share(scene: Scene, planar: RotorStructure, modes: SpatialPillarModes) -> tuple[float, float, float]:
    """(share, reaction tip, response tip): the drive's reaction's static tip displacement at stall
    (rotorpillar.reduced.spatial_statics.drive_reaction: analyze.json's drive_reaction) over the
    planar ROM's largest steady unbalance tip amplitude up to the drive's free speed (m)."""
    d, L = scene.drive, scene.load
    tip_r = abs(drive_reaction(modes, d.torque_at_zero, scene.pillar).tip_displacement) if d.torque_at_zero else 0.0
    free = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient).free_speed()
    top = free if math.isfinite(free) and free > 0 else max(r.omega for r in planar.quasi_normal())
    # every resonance below the free speed on the grid, and the grid fine near each
    speeds = np.linspace(top / 400, top, 400)
    near = [r.omega * np.linspace(0.97, 1.03, 61) for r in planar.quasi_normal() if r.omega <= top]
    speeds = np.unique(np.concatenate([speeds, *near]))
    tip_u = float(np.max(planar.steady_amplitudes(speeds)["tip_x"]))
    return (tip_r / tip_u if tip_u > 0 else math.inf), tip_r, tip_u


def transient_planes(
    scene: Scene, case: str, band_top: float, modes: SpatialPillarModes, planar: RotorStructure
) -> PlanesChoice:
    """``modal_model.planes`` for a transient ``case`` (resolve_planes's choice, then): the
    sweep stays planar (its analysis is the planar averaging); "auto" on a planar choice turns spatial where the drive's reaction is not negligible
    (``reaction_share`` above REACTION_SHARE), and says how large it is either way."""
    choice = resolve_planes(scene, band_top, modes)
    if case not in SPATIAL_CASES:
        if choice.planes == "spatial":
            return PlanesChoice(
                choice.requested,
                "planar",
                f"planar: the {case} runs the planar ROM (its analysis is the planar averaging's), "
                f"modal_model.planes resolving to spatial ({choice.reason})",
            )
        return choice
    if choice.requested != "auto" or choice.planes == "spatial":
        return choice
    share, tip_r, tip_u = reaction_share(scene, planar, modes)
    words = (
        f"the drive's reaction at stall ({scene.drive.torque_at_zero:g} N*m on the gondola) moves the top "
        f"{tip_r:.3g} m statically, {share:.3g} of the planar ROM's largest steady unbalance tip "
        f"amplitude {tip_u:.3g} m"
    )
    if share > REACTION_SHARE:
        return PlanesChoice(
            "auto", "spatial", f"spatial: {words}, above {REACTION_SHARE:g}: only the spatial ROM receives it"
        )
    return PlanesChoice(
        "auto",
        "planar",
        f"{choice.reason}; {words}, at most {REACTION_SHARE:g}: the planar ROM leaves it out (a quasi-static "
        'offset of the tip, no change of the speed\'s history; modal_model.planes = "spatial" runs it)',
    )


def transient_model(
    scene: Scene,
    case: str,
    band_top: float,
    planar: RotorStructure,
    chain_spatial: SpatialPillarModes | None = None,
) -> tuple[PlanesChoice, SpatialRotor | None]:
    """The modal model's planes for a transient ``case`` (``transient_planes``) and, where they
    resolve to "spatial", the spatial ROM on the chain's modes in every direction
    (``chain_spatial``; None: the beam's) below ``band_top`` (rad/s), its shaft's b2 relative
    to the gondola, the structural ratio and the motor's reaction acting."""
    if scene.modal_model.planes == "planar":
        return PlanesChoice("planar", "planar", "modal_model.planes = 'planar' as the scene states"), None
    modes = scene_spatial_modes(scene, chain_spatial)
    choice = transient_planes(scene, case, band_top, modes, planar)
    if choice.planes != "spatial":
        return choice, None
    return choice, SpatialRotor.of(scene_spatial_model(scene, band_top, modes), choice)
