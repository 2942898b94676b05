"""Study throughput: runs per second of one design study on three Dask set-ups.

The study is the issue's capture map, `rotorpillar study sommerfeld --case
runup --vary drive.torque_at_zero=560:700:15 --vary
rotor.eccentricity=0.010:0.020:6` (90 run-ups of 120 s, 12 batches), run
cold (an empty batch cache) side by side in this one process:

- a LocalCluster of 1 worker process,
- a LocalCluster of 2 worker processes,
- a `dask scheduler` with two `dask worker` processes (one thread each) on
  127.0.0.1, reached by its address as `--scheduler` would.

Runs per second are over the computing phase (submitting the batches to the
last result), on warm workers: a warm-up study first puts the compiled
kernels in numba's disk cache, and every worker loads them (one tiny batch
each) before the clock starts; the cluster's start with that load is
reported beside it (``cluster_start_seconds``).  ``quick``: 6 run-ups of 5 s
(does it run).
"""

import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from rotorpillar.executor import Executor
from rotorpillar.scene import load_scene
from rotorpillar.studies import design_study
from rotorpillar.studies.batch import warm_kernels

VARY = ["drive.torque_at_zero=560:700:15", "rotor.eccentricity=0.010:0.020:6"]
QUICK_VARY = ["drive.torque_at_zero=560:700:3", "rotor.eccentricity=0.010:0.020:2"]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _study(executor_kwargs: dict, scene, vary):
    with tempfile.TemporaryDirectory(prefix="bench-study-") as tmp:
        t0 = time.perf_counter()
        with Executor(**executor_kwargs) as ex:
            ex.client.run(warm_kernels)
            start = time.perf_counter() - t0
            res = design_study(scene, "runup", "paper", vary, out_dir=Path(tmp), executor=ex, show_progress=False)
        p = res.performance
        return p.runs_per_second, start, p.compute_wall_seconds, res.executor


def _localhost_cluster(workers: int = 2):
    """`dask scheduler` and ``workers`` `dask worker`s on 127.0.0.1: (address, processes)."""
    dask = str(Path(sys.executable).parent / "dask")
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parent.parent))
    quiet = subprocess.DEVNULL
    procs = [
        subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
            stdout=quiet,
            stderr=quiet,
            env=env,
        )
    ]
    time.sleep(2.0)
    for _ in range(workers):
        procs.append(
            subprocess.Popen(
                [
                    dask,
                    "worker",
                    addr,
                    "--nthreads",
                    "1",
                    "--host",
                    "127.0.0.1",
                    "--no-dashboard",
                    "--memory-limit",
                    "0",
                ],
                stdout=quiet,
                stderr=quiet,
                env=env,
            )
        )
    return addr, procs


def run(quick: bool = False) -> list[dict]:
    scene = load_scene("sommerfeld", ["simulate.duration=5"] if quick else [])
    vary = QUICK_VARY if quick else VARY
    with tempfile.TemporaryDirectory() as tmp, Executor(processes=False) as ex:  # warm-up
        design_study(
            scene,
            "runup",
            "paper",
            ["drive.torque_at_zero=600,700"],
            out_dir=Path(tmp),
            executor=ex,
            show_progress=False,
        )
    one = _study({"workers": 1}, scene, vary)
    two = _study({"workers": 2}, scene, vary)
    addr, procs = _localhost_cluster(2)
    try:
        with Executor(scheduler=addr) as ex:
            ex.client.wait_for_workers(2, timeout=60)
        sched = _study({"scheduler": addr}, scene, vary)
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            p.wait(timeout=30)
    what = (
        "6 run-ups of 5 s of sommerfeld (quick)"
        if quick
        else "90 run-ups of sommerfeld (the capture-map study), cold batch cache"
    )
    out = []
    for name, (rate, start, wall, info) in (
        ("1 worker (LocalCluster)", one),
        ("2 workers (LocalCluster)", two),
        ("scheduler + 2 workers on localhost", sched),
    ):
        out.append(
            {
                "name": f"study throughput, {name}",
                "compares": what,
                "value": rate,
                "unit": "runs/s",
                "cluster_start_seconds": start,
                "compute_wall_seconds": wall,
                "executor": info,
            }
        )
    out.append(
        {
            "name": "study speed-up, 2 workers over 1 (LocalCluster)",
            "compares": "runs/s on 2 workers / runs/s on 1 worker, same study",
            "value": two[0] / one[0],
            "unit": "x",
        }
    )
    return out
