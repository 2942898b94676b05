"""`rotorpillar run`: the main job, every stage on one scene, then the report."""

import argparse

from . import progress

# The stages of `rotorpillar run`, in order: (command name, what it does[,
# extra arguments of that command]).
RUN_STAGES = [
    ("analyze", "closed forms and averaging"),
    ("simulate", "run-up from rest", {"case": "runup"}),
    ("simulate", "earthquake", {"case": "earthquake"}),
    ("modal", "3D modes of the tube, bare and with its top mass"),
    ("report", "charts, mode shapes, animations, report.html"),   # keep last
]


def run_command(scene, args, timings, context):
    """Every stage of RUN_STAGES, each writing its own JSON."""
    from ..cli import execute
    stages, lines = {}, []
    for i, (name, what, *extra) in enumerate(RUN_STAGES, start=1):
        progress(f"run {i}/{len(RUN_STAGES)}: {name} ({what})")
        stage_args = argparse.Namespace(**{**vars(args), **(extra[0] if extra else {})})
        key = "_".join([name, *map(str, (extra[0] if extra else {}).values())])
        with timings(key):
            doc = execute(name, scene, stage_args, context)
        stages[key] = {"json": doc.get("_path"), "seconds": doc["timings"]["total"]}
        lines.append(f"{key:>20}: {doc['timings']['total']:8.2f} s  -> {doc.get('_path')}")
    report = context.get("report", {}).get("report")
    if report:
        lines.append(f"{'page':>20}: {report}")
    return ({"stages": stages, "report": report},
            f"rotorpillar run {scene.name}\n" + "\n".join(lines))
