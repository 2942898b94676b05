"""`rotorpillar run`'s order is the chain of models, and its waves run stages side by side.

- Order: converge (the choice) before modal (the chosen mesh) before analyze
  (the ROM on it) before every stage that uses the ROM, and the report last.
- ``run_wave`` runs at most ``slots`` stage processes at once (measured by the
  processes themselves: each records its start and end in a file), returns
  every stage's wall time, and a failing stage is named in the StageError
  after the stages already running have finished.
"""

from __future__ import annotations

import sys

import pytest

from rotorpillar.commands.run import RUN_STAGES, run_wave
from rotorpillar.errors import StageError


def _wave(name: str) -> int:
    return next(st[4] for st in RUN_STAGES if st[0].split()[0] == name)


def test_the_stages_follow_the_chain():
    assert _wave("converge") < _wave("modal") < _wave("analyze")
    for st in RUN_STAGES:
        if st[0].split()[0] in ("simulate", "compare", "integrators"):
            assert st[4] > _wave("analyze")
    assert RUN_STAGES[-1][0] == "report" and RUN_STAGES[-1][4] > max(st[4] for st in RUN_STAGES[:-1])
    # the paper's own earthquake runs on the paper's model, the scene's run-up on the headline model
    quake = next(st for st in RUN_STAGES if st[0] == "simulate --case earthquake")
    assert tuple(quake[3]) == ("--model", "paper")
    # the Campbell diagram reads the chain's modes (cached by modal) and puts the 3D beside the ROM
    assert _wave("campbell") > _wave("modal")
    assert "both" in next(st for st in RUN_STAGES if st[0] == "campbell")[3]


def _job(tmp_path, name: str, seconds: float, code: int = 0):
    script = (
        f"import time, pathlib; p = pathlib.Path({str(tmp_path)!r}); "
        f"(p / '{name}.start').write_text(repr(time.time())); time.sleep({seconds}); "
        f"(p / '{name}.end').write_text(repr(time.time())); raise SystemExit({code})"
    )
    return name, [sys.executable, "-c", script]


def _intervals(tmp_path, names):
    return {
        n: (float((tmp_path / f"{n}.start").read_text()), float((tmp_path / f"{n}.end").read_text())) for n in names
    }


def test_a_wave_runs_two_at_a_time(tmp_path):
    names = ["a", "b", "c"]
    seconds = run_wave([_job(tmp_path, n, 0.6) for n in names], slots=2)
    assert set(seconds) == set(names) and all(s >= 0.6 for s in seconds.values())
    iv = _intervals(tmp_path, names)
    # a and b overlap; c starts only once one of them has ended
    assert iv["a"][0] < iv["b"][1] and iv["b"][0] < iv["a"][1]
    assert iv["c"][0] >= min(iv["a"][1], iv["b"][1])


def test_a_failing_stage_is_named_after_the_running_ones_finish(tmp_path):
    jobs = [_job(tmp_path, "slow", 0.8), _job(tmp_path, "bad", 0.1, code=3), _job(tmp_path, "never", 0.1)]
    with pytest.raises(StageError, match="'bad' failed \\(exit 3\\)"):
        run_wave(jobs, slots=2)
    assert (tmp_path / "slow.end").exists()  # finished, its files whole
    assert not (tmp_path / "never.start").exists()  # not started after the failure
