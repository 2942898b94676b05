"""`rotorpillar run`'s order is the chain of models, and its waves run stages side by side.

- Order: converge (the choice) before modal (the chosen mesh) before analyze
  (the ROM on it) before every stage that uses the ROM, and the report last.
- Each stage sees the scene and the arguments its own process will parse from
  the command line run launches it with (the reference: that command line
  parsed by the CLI's parser and its scene loaded as ``cli`` loads it, its own
  --set before the user's, so the user's win); run computes them without
  parsing that command line back.
- ``run_wave`` runs at most ``slots`` stage processes at once (measured by the
  processes themselves: each records its start and end in a file), returns
  every stage's wall time, and a failing stage is named in the StageError
  after the stages already running have finished.
"""

from __future__ import annotations

import sys

import pytest

from rotorpillar.commands.parser import build_parser
from rotorpillar.commands.run import RUN_STAGES, plan_stages, run_wave
from rotorpillar.errors import StageError
from rotorpillar.scene import load_scene


def _wave(name: str) -> int:
    return next(st.wave for st in RUN_STAGES if st.name == name)


def test_the_stages_follow_the_chain():
    assert _wave("converge") < _wave("modal") < _wave("analyze")
    for st in RUN_STAGES:
        if st.name in ("simulate", "compare", "integrators"):
            assert st.wave > _wave("analyze")
    assert RUN_STAGES[-1].command == "report" and RUN_STAGES[-1].wave > max(st.wave for st in RUN_STAGES[:-1])
    # the paper's own earthquake runs on the paper's model, the scene's run-up on the headline model
    quake = next(st for st in RUN_STAGES if st.command == "simulate --case earthquake")
    assert quake.arguments == ("--model", "paper")
    # the Campbell diagram reads the chain's modes (cached by modal) and puts the 3D beside the ROM
    assert _wave("campbell") > _wave("modal")
    assert "both" in next(st for st in RUN_STAGES if st.command == "campbell").arguments


@pytest.mark.parametrize(
    "scene, more",
    [
        ("paper", []),
        # the user's --set of the keys the comparisons set themselves: the user's win
        ("paper", ["--set", "excitation.start=2", "--set", "full_order.earthquake_duration=3"]),
        (
            "nrel5mw",
            [
                *("--set", "drive.torque_at_zero=6000", "--max-frames", "3", "--mode-pictures", "3"),
                *("--no-animations", "--strict", "--quick"),
            ],
        ),
    ],
)
def test_each_stage_sees_what_its_process_parses(tmp_path, scene, more):
    args = build_parser().parse_args(["run", scene, "--out", str(tmp_path), *more])
    plans = plan_stages(RUN_STAGES, load_scene(args.scene, args.overrides), args, tmp_path)
    assert [p.stage for p in plans] == list(RUN_STAGES)
    for p in plans:
        assert list(p.argv[:3]) == [sys.executable, "-m", "rotorpillar"]
        theirs = build_parser().parse_args(list(p.argv[3:]))  # as the stage's process parses it
        assert p.scene == load_scene(theirs.scene, theirs.overrides), p.stage.command
        # the same arguments for its pre-flight checks, but the --set (the scene has them)
        assert vars(p.args) == {**vars(theirs), "overrides": []}, p.stage.command
    quake = next(p for p in plans if p.stage.command == "compare --case earthquake")
    assert quake.scene.excitation.kind == "record" and quake.scene.excitation.record == "elcentro"
    if "excitation.start=2" in more:
        assert (quake.scene.excitation.start, quake.scene.full_order.earthquake_duration) == (2.0, 3.0)
    else:
        assert (quake.scene.excitation.start, quake.scene.full_order.earthquake_duration) == (1.0, 9.0)
    report = plans[-1]
    # run's report flags go on to the report, as run got them (--max-frames and --mode-pictures
    # have defaults)
    switches = ("--no-animations", "--strict") if "--strict" in more else ()
    pictures = ("--mode-pictures", str(args.mode_pictures))
    assert report.passed_on == ("--max-frames", str(args.max_frames), *pictures, *switches)
    assert report.args.mode_pictures == (3 if "--mode-pictures" in more else 8)
    # run --quick goes on to the integrator study as its own --quick, and to no other stage
    integrators = next(p for p in plans if p.stage.name == "integrators")
    assert integrators.args.quick is ("--quick" in more)
    assert integrators.passed_on == (("--quick",) if "--quick" in more else ())
    assert ("--quick" in integrators.argv) is ("--quick" in more)
    assert all(p.passed_on == () for p in plans[:-1] if p is not integrators)


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
