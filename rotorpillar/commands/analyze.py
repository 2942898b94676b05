"""`rotorpillar analyze`: the paper's closed-form model of the scene."""

from ..analysis import analyze, summary


def analyze_command(scene, args, timings):
    fem3d = None
    if scene.reduction.source == "fem3d":
        from ..fem3d import reduction_from_scene as fem3d
    with timings("analyze"):
        result = analyze(scene, fem3d_reduction=fem3d)
    return result.to_json(), summary(result)
