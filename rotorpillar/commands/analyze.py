"""`rotorpillar analyze`: the headline model (the validated ROM) and the paper's, side by side."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

from ..analysis import analyze, summary
from . import Done, out_dir, progress


def analyze_command(scene: Scene, args, timings):
    from ..chain import resolve

    with timings("pillar_modes"):
        chain = resolve(scene, out_dir(scene, args), progress=progress)
    fem3d = None
    if scene.reduction.source == "fem3d" and chain.pillar_model.kind != "solid":
        from ..fem3d import reduction_from_scene

        fem3d = reduction_from_scene
    with timings("analyze"):
        result = analyze(scene, chain, fem3d_reduction=fem3d)
    for warning in result.warnings + (() if result.machine_checks is None else result.machine_checks.warnings):
        progress(f"warning: {warning}")
    return Done(result, summary(result))
