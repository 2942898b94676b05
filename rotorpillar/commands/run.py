"""`rotorpillar run`: the main job, every stage on one scene, then the report."""

from . import progress

# The stages of `rotorpillar run`, in order: (command name, what it does).
RUN_STAGES = [
    ("analyze", "closed forms and averaging"),
    ("modal", "3D modes of the tube, bare and with its top mass"),
]


def run_command(scene, args, timings, context):
    """Every stage of RUN_STAGES, each writing its own JSON."""
    from ..cli import execute
    stages, lines = {}, []
    for i, (name, what) in enumerate(RUN_STAGES, start=1):
        progress(f"run {i}/{len(RUN_STAGES)}: {name} ({what})")
        with timings(name):
            doc = execute(name, scene, args, context)
        stages[name] = {"json": doc.get("_path"), "seconds": doc["timings"]["total"]}
        lines.append(f"{name:>12}: {doc['timings']['total']:8.2f} s  -> {doc.get('_path')}")
    return {"stages": stages}, f"rotorpillar run {scene.name}\n" + "\n".join(lines)
