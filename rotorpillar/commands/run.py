"""`rotorpillar run`: the main job, every stage on one scene, then the report.

Each stage runs as its own ``rotorpillar <stage>`` process, exactly as a user
would run it.  Stages hand their results over through the files they write;
a fresh process per stage returns the 3D model's memory, keeps MPI, PETSc,
Gmsh and VTK state apart, and a crash in one stage leaves the finished
stages' files in place.
"""

from __future__ import annotations

import json
import subprocess
import sys

from ..errors import StageError
from ..postprocess.comparisons import COMPARISONS
from . import progress


def _report_flags(args) -> list[str]:
    flags = []
    if getattr(args, "max_frames", None) is not None:
        flags += ["--max-frames", str(args.max_frames)]
    if getattr(args, "no_animations", False):
        flags.append("--no-animations")
    if getattr(args, "strict", False):
        flags.append("--strict")
    return flags


# The stages of `rotorpillar run`, in order: (command, what it does, extra
# arguments from run's own, the stage's own arguments).  A stage's own
# arguments go before the user's --set, so the user's win.  The comparisons
# come before the scene's own runs: simulate_<case>.* (the last run of a
# case) stay the scene's run as before.  The report stays last.
RUN_STAGES = [
    ("analyze", "closed forms and averaging", None, ()),
    # minutes the first time, then read from its cache: the report's "which model
    # does this scene need" section, and the comparisons' 3D reference mesh
    # (chosen for the modes the load excites), come from it
    ("converge", "mesh convergence, speed against accuracy, the model chosen (cached)", None, ()),
    ("modal", "3D modes of the tube, bare and with its top mass", None, ()),
    # El Centro on the modal ROM and the 3D full order (the study's reference mesh)
    ("compare --case earthquake", "a recorded earthquake: the ROM against the 3D full order",
     None, COMPARISONS["earthquake"]),
    ("compare --case runup", "run-up through the resonances: the ROM against the 3D full order",
     None, COMPARISONS["runup"]),
    ("simulate --case runup", "run-up from rest, reduced model", None, ()),
    ("simulate --case earthquake", "the paper's case: its pulse on Eq. 4 as published", None, ()),
    ("integrators", "time integrators: error against cost, where each fails", None, ()),
    ("report", "charts, mode shapes, animations, report.html", _report_flags, ()),
]


def stage_argv(command: str, args, extra=None, own=()) -> list[str]:
    """The command line of one stage: the command, its own arguments, run's
    scene, --out and overrides (after the stage's own --set: the user's win)."""
    from . import out_dir
    argv = [sys.executable, "-m", "rotorpillar", *command.split(), *own, str(args.scene),
            "--out", str(out_dir(args._scene, args))]
    for o in args.overrides:
        argv += ["--set", o]
    return argv + (extra(args) if extra else [])


def stage_stem(command: str) -> str:
    """The JSON a stage leaves that run.json points to: <command>.json, or
    per case for simulate and compare.

    >>> stage_stem("simulate --case runup"), stage_stem("compare --case earthquake"), stage_stem("modal")
    ('simulate_runup', 'compare_earthquake', 'modal')
    """
    words = command.split()
    if words[0] in ("simulate", "compare") and "--case" in words:
        return f"{words[0]}_{words[words.index('--case') + 1]}"
    return words[0]


def add_arguments(parser) -> None:
    """run's own flags, beside the report's (which it passes on)."""
    names = sorted({st[0].split()[0] for st in RUN_STAGES} - {"report"})
    parser.add_argument("--skip", action="append", default=[], metavar="STAGE",
                        help=f"leave out a stage ({', '.join(names)}); repeatable")


def run_command(scene, args, timings):
    """Every stage of RUN_STAGES, each writing its own JSON."""
    from . import out_dir
    from ..errors import InputError
    from ..mesh import tube_params
    from .report import checked_frames
    tube_params(scene.pillar, scene.mesh)      # a mesh this machine cannot hold: refused now, not late
    checked_frames(args)
    args._scene = scene
    skip = set(getattr(args, "skip", []))
    known = {st[0].split()[0] for st in RUN_STAGES} - {"report"}
    if skip - known:
        raise InputError(f"--skip {sorted(skip - known)[0]}: must be one of {', '.join(sorted(known))}")
    todo = [st for st in RUN_STAGES if st[0].split()[0] not in skip]
    stages, lines, report = {}, [], None
    for i, (command, what, extra, own) in enumerate(todo, start=1):
        progress(f"run {i}/{len(todo)}: {command} ({what})")
        with timings(command):
            # the stage's summary goes to stderr: stdout may carry run's --json
            p = subprocess.run(stage_argv(command, args, extra, own), stdout=sys.stderr)
        if p.returncode != 0:
            raise StageError(f"stage {command!r} failed (exit {p.returncode}); "
                                   "the stages before it finished and wrote their files")
        stem = stage_stem(command)
        path = out_dir(scene, args) / f"{stem}.json"
        doc = json.loads(path.read_text(encoding="utf-8"))
        stages[stem] = {"json": str(path), "seconds": timings[command], "command": command,
                        "arguments": list(own), "stage_seconds": doc.get("timings", {}).get("total")}
        lines.append(f"{command:>26}: {timings[command]:8.2f} s  -> {path}")
        if command.split()[0] == "report":
            report = doc.get("report")
    if report:
        lines.append(f"{'page':>26}: {report}")
    return ({"stages": stages, "report": report},
            f"rotorpillar run {scene.name}\n" + "\n".join(lines))
