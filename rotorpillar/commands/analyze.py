"""`rotorpillar analyze`: the paper's closed-form model of the scene."""

from ..analyze import analyze, summary


def analyze_command(scene, args, timings, context):
    with timings("analyze"):
        result = analyze(scene)
    context["analyze"] = result
    return result, summary(result)
