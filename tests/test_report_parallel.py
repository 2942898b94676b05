"""The report's 3D pictures in worker processes (rotorpillar.postprocess.report.parallel).

- Ctrl-C and SIGTERM stop `rotorpillar report` while its workers render, with the
  exit codes every command has (130, 143), and leave no worker behind: checked on
  the process tree, not by timing.
- The pictures drawn by the workers are those drawn in the report's own process
  (one worker): the same files, the same frames, the same failures.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import fixtures
import pytest
from conftest import sigint_as_in_the_foreground

from rotorpillar import cli


def _inputs(out, analyze=True):
    if analyze:
        assert cli.main(["analyze", "paper", "--out", str(out)]) == 0
    fixtures.write_modal_fixture(out, around=24, along=16)
    for case in ("runup", "earthquake"):
        fixtures.write_simulation_fixture(out, case, n=1500)


def _children(pid: int) -> list[int]:
    got = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout.split()
    return [int(p) for p in got]


def _workers(pid: int) -> list[int]:
    """The report's render workers (spawned interpreters), not multiprocessing's tracker."""
    out = []
    for child in _children(pid):
        try:
            args = open(f"/proc/{child}/cmdline", "rb").read().replace(b"\0", b" ")
        except OSError:
            continue
        if b"spawn_main" in args:
            out.append(child)
    return out


@pytest.mark.slow  # renders in worker processes, twice
@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_a_signal_stops_the_report_and_its_workers(tmp_path, sig, code):
    _inputs(tmp_path)
    proc = subprocess.Popen(
        [sys.executable, "-m", "rotorpillar", "report", "paper", "--out", str(tmp_path), "--max-frames", "2000"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=sigint_as_in_the_foreground,
    )
    deadline = time.time() + 120
    workers: list[int] = []
    while time.time() < deadline and proc.poll() is None:
        workers = _workers(proc.pid)
        if len(workers) == 2:
            break
        time.sleep(0.1)
    assert len(workers) == 2, "the report's two render workers never started"
    time.sleep(2.0)  # at work: past their start, inside a render
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == code, err
    assert "interrupted" in err
    time.sleep(0.5)
    alive = [w for w in workers if os.path.exists(f"/proc/{w}") and b"Z" not in _state(w)]
    assert not alive, f"render workers left running: {alive}"
    for f in tmp_path.glob("*.json"):
        json.loads(f.read_text())  # every file on disk whole


def _state(pid: int) -> bytes:
    try:
        return open(f"/proc/{pid}/stat", "rb").read().split(b")")[-1].split()[0]
    except OSError:
        return b"Z"


@pytest.mark.slow  # renders every picture twice
@pytest.mark.renders
def test_the_workers_draw_what_one_process_draws(tmp_path, monkeypatch):
    from rotorpillar.postprocess.report import parallel

    # two pictures a mode set (--mode-pictures 2): both mode jobs and both animations still run
    # on each side, and their files, frames and failures are compared; eight a set cost
    # 18.6-18.9 -> 15.5-16.4 s of CPU for this test (measured in pairs).
    # No analyze.json: its charts (the drive's) are drawn by the report's own process on both
    # sides, never by a worker, and the jobs (the modes from modal.json and its VTUs, the
    # animations from the runs' files) read nothing of it; each report's CPU in this process
    # 2.1 -> 0.7 s, the analyze 0.4 s, the test's 13.3 -> 9.7 s
    runs = {}
    for workers in (1, 2):
        out = tmp_path / f"w{workers}"
        _inputs(out, analyze=False)
        monkeypatch.setattr(parallel, "WORKERS", workers)
        assert cli.main(["report", "paper", "--out", str(out), "--max-frames", "6", "--mode-pictures", "2"]) == 0
        runs[workers] = json.loads((out / "report.json").read_text())
    one, two = runs[1], runs[2]
    assert one["failures"] == two["failures"] == {}
    assert sorted(p.split("/w1/")[1] for p in one["figures"]) == sorted(p.split("/w2/")[1] for p in two["figures"])
    assert {k: v["frames"] for k, v in one["animations"].items()} == {
        k: v["frames"] for k, v in two["animations"].items()
    }
    assert one["render_window"] and one["render_window"] == two["render_window"]


@pytest.mark.slow  # two render workers start
def test_an_interrupt_a_library_swallowed_stops_the_workers_at_once(tmp_path, monkeypatch):
    """A Ctrl-C whose KeyboardInterrupt a library caught while the report drew its charts
    (``during``) is recorded (errors.RECEIVED) and must stop the render workers at the next look,
    not after their jobs: before, the report waited in select() until a job ended (~30 s on
    these 2000-frame animations; 3 stops in 45 of the signal test above).  Here the swallowed
    interrupt is made deterministic: ``during`` records it and returns."""
    from rotorpillar import errors
    from rotorpillar.postprocess.readers import read_simulation
    from rotorpillar.postprocess.report import parallel

    for case in ("runup", "earthquake"):
        fixtures.write_simulation_fixture(tmp_path, case, n=1500)
    jobs = [
        parallel.AnimationJob(
            case,
            read_simulation(tmp_path, case),
            case,
            {},
            None,
            (20.0, 2.0, 1.96),
            tmp_path / f"{case}.mp4",
            tmp_path / f"{case}.png",
            2000,
        )
        for case in ("runup", "earthquake")
    ]
    monkeypatch.setattr(errors, "RECEIVED", [])

    def during():
        errors.RECEIVED.append(signal.SIGINT)  # the handler ran; its exception was caught

    seen = []
    with pytest.raises(KeyboardInterrupt):
        for outcome in parallel.run_jobs(jobs, during):
            seen.append(outcome)
    assert seen == []  # no job ran to its end: the workers were stopped first
    assert not (tmp_path / "runup.mp4").exists() and not (tmp_path / "earthquake.mp4").exists()
