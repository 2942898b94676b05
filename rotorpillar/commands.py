"""The commands behind the CLI: each takes a scene and returns (result, summary).

Commands stay thin: the physics lives in the library modules they call.
"""

from __future__ import annotations

import sys

from .analyze import analyze, summary


def progress(message: str) -> None:
    """A stage line on stderr (stdout may carry --json)."""
    print(f"[rotorpillar] {message}", file=sys.stderr, flush=True)


def analyze_command(scene, args, timings, context):
    with timings("analyze"):
        result = analyze(scene)
    context["analyze"] = result
    return result, summary(result)


# The stages of `rotorpillar run`, in order: (command name, what it does).
RUN_STAGES = [
    ("analyze", "closed forms and averaging"),
]


def run_command(scene, args, timings, context):
    """The main job: every stage of RUN_STAGES, each writing its own JSON."""
    from .cli import execute
    stages, lines = {}, []
    for i, (name, what) in enumerate(RUN_STAGES, start=1):
        progress(f"run {i}/{len(RUN_STAGES)}: {name} ({what})")
        with timings(name):
            doc = execute(name, scene, args, context)
        stages[name] = {"json": doc.get("_path"), "seconds": doc["timings"]["total"]}
        lines.append(f"{name:>12}: {doc['timings']['total']:8.2f} s  -> {doc.get('_path')}")
    return {"stages": stages}, "rotorpillar run: " + scene.name + "\n" + "\n".join(lines)
