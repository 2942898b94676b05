"""The main job as a new user meets it: `rotorpillar run SCENE` from an empty out/.

For `paper` (what `make run` runs) and `sommerfeld`: the whole command in a
fresh process, after set-up (numba's and FFCx's caches warm, as `make setup`
leaves them: tools/warm_caches.py) but with an empty out/ and an empty user
cache of results (``ROTORPILLAR_CACHE``: the chain's 3D modes), so that every
stage computes what a first run computes.  Recorded: the wall time of the
whole command, each stage's wall and processor time (run.json: the stage and
the processes it waited for; the processor time is the steadier measure on a
shared machine), the machine's load average before and after (other work on
the machine inflates the wall times, never the processor times).

The README quotes the ``main_job_paper_seconds`` entry with its machine.
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


def main_job(scene: str, quick: bool = False) -> dict:
    """One `rotorpillar run` from nothing; its entry."""
    with tempfile.TemporaryDirectory(prefix="bench-main-job-") as tmp:
        out = Path(tmp) / "out"
        env = dict(os.environ, ROTORPILLAR_CACHE=str(Path(tmp) / "cache"))
        argv = [sys.executable, "-m", "rotorpillar", "run", scene, "--out", str(out), *(QUICK if quick else [])]
        load = os.getloadavg()
        cpu0, t0 = _children_cpu(), time.perf_counter()
        p = subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wall, cpu = time.perf_counter() - t0, _children_cpu() - cpu0
        if p.returncode != 0:
            raise RuntimeError(f"rotorpillar run {scene} exited {p.returncode}: {p.stderr[-2000:]}")
        done = records.read(out / "run.json", RunResult)
    stages = {k: {"seconds": v.seconds, "cpu_seconds": v.cpu_seconds, "wave": v.wave} for k, v in done.stages.items()}
    what = "the run-up and the paper's earthquake on the ROM, quick" if quick else "every stage"
    return {
        "name": f"main_job_{scene}_seconds",
        "compares": f"`rotorpillar run {scene}` from an empty out/ and result cache, after set-up "
        f"({what}): wall time of the whole command",
        "value": wall,
        "unit": "s",
        "cpu_seconds": cpu,
        "stages": stages,
        "load_average_before": load[0],
        "load_average_after": os.getloadavg()[0],
        "target_seconds": 180.0,
    }


def run(quick: bool = False) -> list[dict]:
    return [main_job(s, quick) for s in (SCENES[:1] if quick else SCENES)]


if __name__ == "__main__":
    for e in run("--quick" in sys.argv):
        print(json.dumps(e, indent=1))
