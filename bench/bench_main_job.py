"""The main job as a new user meets it: `rotorpillar run SCENE` from an empty out/.

For `paper` (what `make run` runs) and `sommerfeld`: the whole command in a
fresh process, after set-up (numba's and FFCx's caches warm, as `make setup`
leaves them: tools/warm_caches.py) but with an empty out/ and an empty user
cache of results (``ROTORPILLAR_CACHE``: the chain's 3D modes, the kept meshes and records), so that every
stage computes what a first run computes.  Recorded: the wall time of the
whole command, each stage's wall and processor time (run.json: the stage and
the processes it waited for; the processor time is the steadier measure on a
shared machine), the machine's load average before and after (other work on
the machine inflates the wall times, never the processor times).

The README quotes the ``main_job_paper_seconds`` entry with its machine, and
the two reruns after it in the same out/ (``main_job_paper_rerun_unchanged_seconds``,
nothing changed; ``main_job_paper_rerun_torque_changed_seconds``, the stall
torque 10 % up), with the stages each ran again.
``quick``: the run-up and the earthquake on the ROM only (no study, no
comparison, no integrator study, no harmonic response, two animation frames)
on a coarse tube: does the entry still come out.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from rotorpillar import records
from rotorpillar.commands.run import RunResult

SCENES = ("paper", "sommerfeld")
QUICK = [
    "--skip",
    "converge",
    "--skip",
    "compare",
    "--skip",
    "integrators",
    "--skip",
    "harmonic",
    "--max-frames",
    "2",
    "--set",
    "mesh.elements_around=16",
    "--set",
    "mesh.elements_along=4",
]


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


#: The reruns the issue sets targets for (s), after a full run in the same out/: nothing
#: changed, and the drive's stall torque 10 % up (converge and modal keep their results:
#: the band holds the same modes; the rest reads the drive).
RERUN_TARGETS = {"unchanged": 10.0, "torque_changed": 60.0}
TORQUE_FACTOR = 1.1


def _entry(scene: str, out: Path, env: dict, more: list[str], name: str, compares: str, target: float) -> dict:
    """One `rotorpillar run` into ``out`` with the arguments ``more``, as a bench entry: its
    wall and processor time (of it and its stages), each stage's, the stages it ran
    again, the machine's load before and after."""
    argv = [sys.executable, "-m", "rotorpillar", "run", scene, "--out", str(out), *more]
    load = os.getloadavg()
    cpu0, t0 = _children_cpu(), time.perf_counter()
    p = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall, cpu = time.perf_counter() - t0, _children_cpu() - cpu0
    if p.returncode != 0:
        raise RuntimeError(f"rotorpillar run {scene} {' '.join(more)} exited {p.returncode}: {p.stderr[-2000:]}")
    done = records.read(out / "run.json", RunResult)
    return {
        "name": name,
        "compares": compares,
        "value": wall,
        "unit": "s",
        "cpu_seconds": cpu,
        "stages": {
            k: {"seconds": v.seconds, "cpu_seconds": v.cpu_seconds, "wave": v.wave, "reused": v.reused}
            for k, v in done.stages.items()
        },
        "rerun": sorted(k for k, v in done.stages.items() if not v.reused),
        "load_average_before": load[0],
        "load_average_after": os.getloadavg()[0],
        "target_seconds": target,
    }


def main_job(scene: str, quick: bool = False, reruns: bool = False) -> list[dict]:
    """One `rotorpillar run` from nothing; its entry.  ``reruns``: then the same run again
    with nothing changed, and with the stall torque changed; their entries too."""
    from rotorpillar.scene import load_scene

    what = "the run-up and the paper's earthquake on the ROM, quick" if quick else "every stage"
    base = QUICK if quick else []
    with tempfile.TemporaryDirectory(prefix="bench-main-job-") as tmp:
        out = Path(tmp) / "out"
        env = dict(os.environ, ROTORPILLAR_CACHE=str(Path(tmp) / "cache"))
        first = f"`rotorpillar run {scene}` from an empty out/ and result cache, after set-up ({what})"
        entries = [
            _entry(
                scene, out, env, base, f"main_job_{scene}_seconds", f"{first}: wall time of the whole command", 180.0
            )
        ]
        if reruns:
            torque = load_scene(scene).drive.torque_at_zero * TORQUE_FACTOR
            changes = {
                "unchanged": ([], "with nothing changed"),
                "torque_changed": (
                    ["--set", f"drive.torque_at_zero={torque:.6g}"],
                    f"with drive.torque_at_zero x {TORQUE_FACTOR} ({torque:.6g} N*m)",
                ),
            }
            for name, (more, how) in changes.items():
                compares = (
                    f"`rotorpillar run {scene}` again in the same out/ {how} ({what}): wall time of the "
                    "whole command; which stages ran again"
                )
                entries.append(
                    _entry(
                        scene,
                        out,
                        env,
                        [*base, *more],
                        f"main_job_{scene}_rerun_{name}_seconds",
                        compares,
                        RERUN_TARGETS[name],
                    )
                )
    return entries


def run(quick: bool = False) -> list[dict]:
    # the reruns after the paper's run (what `make run` runs), quick or not
    return [e for s in (SCENES[:1] if quick else SCENES) for e in main_job(s, quick, reruns=s == "paper")]


if __name__ == "__main__":
    for e in run("--quick" in sys.argv):
        print(json.dumps(e, indent=1))
