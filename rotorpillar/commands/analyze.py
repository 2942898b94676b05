"""`rotorpillar analyze`: the paper's closed-form model of the scene."""

from ..analyze import analyze, summary


def analyze_command(scene, args, timings, context):
    fem3d = None
    if scene.reduction.source == "fem3d":
        from ..fem3d import reduction_from_scene as fem3d
    with timings("analyze"):
        result = analyze(scene, fem3d_reduction=fem3d)
    context["analyze"] = result
    return result, summary(result)
