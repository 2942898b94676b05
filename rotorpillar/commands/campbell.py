"""`rotorpillar campbell`: the Campbell diagram (campbell.json, campbell.png).

``rotorpillar campbell [SCENE] [--model modal|fem3d|both] [--speeds START:STOP:N]``

- ``--model modal`` (default): the spatial reduced model
  (rotorpillar.reduced.spatial_scene.scene_campbell) on the chain's pillar modes
  in every direction (the 3D ones where the chain has them, else the 1D beams);
- ``--model fem3d``: the 3D model with the rotor on its top
  (rotorpillar.fem3d.campbell.campbell_fem3d);
- ``--model both`` (the run's campbell stage): the ROM's diagram with the 3D
  model's beside it (campbell.json's ``fem3d`` and ``differences``; one chart),
  the 3D at ``--fem3d-speeds`` speeds over the same range (its critical speeds
  come from the gyroscopic pencil, exactly, whatever the speeds) on the chain's
  chosen mesh, or the scene's [mesh] with ``--fem3d-mesh scene`` (said in the
  JSON's warnings and on stderr when the two differ).

Speeds: START:STOP:N rad/s, default 0 to the band's top (modal_model.band_factor x
the drive's free speed), 151 speeds.  The running speed is the planar ROM's stable
stationary speed with the scene's drive.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..reduced.campbell import CampbellDiagram
    from ..scene import Scene

import numpy as np

from ..errors import InputError
from . import Done, is_root_rank, out_dir, progress

MODELS = ("modal", "fem3d", "both")
DEFAULT_SPEEDS = 151
#: the 3D model's speeds beside the ROM's (--model both): a branch's tracking needs a few, the
#: critical speeds none (the pencil gives them exactly); each costs ~2-7 s on 24k-94k DOFs
DEFAULT_FEM3D_SPEEDS = 5
#: where the 3D model of --model both is meshed
FEM3D_MESHES = ("chain", "scene")


def add_arguments(p) -> None:
    p.add_argument(
        "--model", choices=MODELS, default="modal", help="modal: the spatial ROM (default); fem3d: the 3D model"
    )
    p.add_argument(
        "--speeds",
        default=None,
        metavar="START:STOP:N",
        help=f"rotor speeds (rad/s): N from START to STOP (default 0 to the band's top, {DEFAULT_SPEEDS})",
    )
    p.add_argument(
        "--fem3d-speeds",
        type=int,
        default=DEFAULT_FEM3D_SPEEDS,
        metavar="N",
        help=f"--model both: the 3D model's speeds over the same range (default {DEFAULT_FEM3D_SPEEDS}, at least 2)",
    )
    p.add_argument(
        "--fem3d-mesh",
        choices=FEM3D_MESHES,
        default="chain",
        help="--model both: the 3D model on the convergence study's chosen mesh (default) or the scene's [mesh] (cheaper)",
    )


def preflight(scene: Scene, args) -> None:
    """--fem3d-speeds in range (one line, before any work)."""
    n = getattr(args, "fem3d_speeds", DEFAULT_FEM3D_SPEEDS)
    if not 2 <= n <= 100_000:
        raise InputError(f"--fem3d-speeds {n}: must be an integer from 2 to 100000")


def parse_speeds(text: str | None, top: float) -> np.ndarray:
    """START:STOP:N as N ascending speeds (rad/s); None: 0 to ``top``, DEFAULT_SPEEDS of them."""
    if text is None:
        return np.linspace(0.0, top, DEFAULT_SPEEDS)
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise InputError(f"--speeds {text!r}: must be START:STOP:N, e.g. 0:150:151 (rad/s, N an integer)") from None
    if not (np.isfinite(start) and np.isfinite(stop) and 0 <= start < stop <= 1e6 and 2 <= n <= 100_000):
        raise InputError(f"--speeds {text!r}: must have 0 <= START < STOP <= 1e6 rad/s and 2 <= N <= 100000")
    return np.linspace(start, stop, n)


def campbell_command(scene: Scene, args, timings) -> Done:
    from ..chain import resolve
    from ..reduced.band import forcing_top
    from ..reduced.models import build_model
    from ..verdict.harmonic import running_speeds

    top = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, "runup", None)
    speeds = parse_speeds(getattr(args, "speeds", None), top)
    model = getattr(args, "model", "modal")
    preflight(scene, args)
    if model in ("fem3d", "both"):
        _fem3d_function()  # refused now, before any work, when the 3D side is absent
    out = out_dir(scene, args)
    with timings("pillar_modes"):
        chain = resolve(scene, out, progress=progress)
    planar, _ = build_model(scene, "modal", top, pillar_modes=chain.modes)
    running = running_speeds(planar, scene)
    run = running[-1] if running else None
    progress(f"campbell {scene.name}: {len(speeds)} speeds, {speeds[0]:g} ... {speeds[-1]:g} rad/s, model {model}")
    with timings("campbell"):
        if model != "fem3d":
            from ..reduced.spatial_scene import scene_campbell, scene_spatial_modes

            diagram = scene_campbell(
                scene, speeds, float(speeds[-1]), run, scene_spatial_modes(scene, getattr(chain, "spatial", None))
            )
        else:
            diagram = _fem3d(scene, speeds, run)
    if model == "both":
        with timings("campbell_fem3d"):
            diagram = _beside(scene, diagram, speeds, run, out, args)
    if is_root_rank():
        from ..postprocess.campbell_chart import campbell_diagram_chart

        what = "the ROM against the 3D model" if model == "both" else model
        with timings("chart"):
            campbell_diagram_chart(
                out / "campbell.png",
                diagram,
                f"{scene.name}: Campbell diagram ({what})",
                orders=(scene.rotor.blades,) if scene.rotor.blades else (),
            )
    return Done(diagram, summary_text(diagram))


def _beside(scene: Scene, rom: CampbellDiagram, speeds, running, out, args) -> CampbellDiagram:
    """The ROM's diagram with the 3D one beside it (--model both): the 3D at --fem3d-speeds
    speeds over the ROM's range, on the chain's chosen mesh or the scene's [mesh]."""
    from ..chain import choose
    from ..fem3d.campbell import estimate
    from ..records import replace
    from ..reduced.campbell import critical_speed_differences

    chosen = choose(scene, out).solid_mesh
    which = getattr(args, "fem3d_mesh", "chain")
    mesh = chosen if which == "chain" else scene.mesh
    n = getattr(args, "fem3d_speeds", DEFAULT_FEM3D_SPEEDS)
    speeds3 = np.linspace(float(speeds[0]), float(speeds[-1]), n)
    warnings: tuple[str, ...] = ()
    if mesh != chosen:
        mine, theirs = estimate(scene, n, mesh), estimate(scene, n, chosen)
        warnings = (
            f"the 3D Campbell diagram is on the scene's [mesh] (~{mine.dofs:,} DOFs), not on the convergence study's chosen "
            f"mesh (~{theirs.dofs:,} DOFs, {chosen.elements_around} x {chosen.elements_along} x "
            f"{chosen.elements_through}) that the ROM's pillar modes come from: that one costs ~4x the time (the "
            "run's budget); its frequencies may differ from the ROM's by that mesh's error as well (see "
            "convergence.json); `rotorpillar campbell --model both --fem3d-mesh chain` computes it there",
        )
        for w in warnings:
            progress("warning: " + w)
    fem3d = _fem3d(scene, speeds3, running, mesh)
    fem3d = replace(fem3d, warnings=fem3d.warnings + warnings)
    return replace(
        rom,
        fem3d=fem3d,
        differences=critical_speed_differences(rom, fem3d),
        description=rom.description + "; beside it the 3D model's (fem3d): " + fem3d.description,
        warnings=rom.warnings + warnings,
    )


def _fem3d_function():
    import importlib

    try:
        campbell_fem3d = importlib.import_module("rotorpillar.fem3d.campbell").campbell_fem3d
    except (ImportError, AttributeError):
        raise InputError(
            "campbell --model fem3d: the 3D Campbell diagram is not in this build yet (rotorpillar.fem3d.campbell); "
            "use --model modal"
        ) from None
    return campbell_fem3d


def _fem3d(scene: Scene, speeds, running, mesh=None):
    campbell_fem3d = _fem3d_function()
    return campbell_fem3d(
        scene, speeds, band_top=float(speeds[-1]), mesh=mesh, running_speed=running, progress=progress
    )


def summary_text(d: CampbellDiagram) -> str:
    lines = [f"Campbell diagram ({d.model}): {len(d.speeds)} speeds, {d.speeds[0]:g} ... {d.speeds[-1]:g} rad/s"]
    if d.running_speed is not None:
        lines.append(f"  running speed {d.running_speed:.4g} rad/s")
    for b in d.modes:
        if b.frequency[0] <= 1.5 * d.speeds[-1]:
            lines.append(
                f"  {b.label:<45} {b.frequency[0]:9.3f} -> {b.frequency[-1]:9.3f} rad/s, "
                f"log decrement {b.log_decrement[0]:.3g}"
            )
    lines.append("critical speeds (the 1x line crossing a mode):")
    for c in d.critical_speeds:
        none = "no peak" if d.model == "modal" else "AF not read (the unbalance response is `rotorpillar harmonic`'s)"
        af = none if c.amplification_factor is None else f"AF {c.amplification_factor:.3g}"
        lines.append(f"  {c.speed:9.3f} rad/s  {c.label:<40} {c.whirl:<9} excited by {c.excited_by}; {af}")
    from ..reduced.campbell import first_critical

    for name, dd in (("ROM", d), ("3D", d.fem3d)):
        if dd is None:
            continue
        for whirl in ("forward", "backward"):
            first = first_critical(dd, whirl)
            lines.append(
                f"first {whirl} critical speed ({name}): "
                + ("none in the range" if first is None else f"{first.speed:.3f} rad/s ({first.label})")
            )
    if d.fem3d is not None:
        lines.append(f"beside it, the 3D model's ({len(d.fem3d.speeds)} speeds): {d.fem3d.description}")
        for x in d.differences:
            theirs = "none" if x.fem3d is None else f"{x.fem3d:9.3f} rad/s ({x.fem3d_label})"
            rel = "" if x.relative is None else f", {100 * x.relative:+.2f} %"
            lines.append(f"  ROM {x.modal:9.3f} rad/s {x.label:<35} 3D {theirs}{rel}")
    for w in d.warnings:
        lines.append("  warning: " + w)
    return "\n".join(lines)
