"""No success for a meaningless run (issue 19.4): each integrator's step against what the run
had to resolve (rotorpillar.reduced.accuracy, transients.case_summary.accuracy_check).

The threshold is the schemes' own error, not these examples: a run fails when its
scheme's period error or amplitude loss per period at the fastest frequency it had to
resolve exceeds 10 % (reduced.accuracy.ERROR_LIMIT; Newmark: fewer than 5.5 steps per
period, central difference 4.4, dp5 3.2), when its step swallows the run or the ground
motion (fewer than 2 steps over either), or when an adaptive method's rtol exceeds 10 %.
The examples of the issue fail it by far (Newmark at 0.5 s: 0.14 steps per period of the
unbalance's rotation at 89.7 rad/s; central difference at 0.05 s: 1.4); the defaults
pass it by far (40-60 steps per period), so no default run turns into a failure.
"""

from __future__ import annotations

import json

import pytest
from conftest import cli_here

from rotorpillar.reduced.accuracy import check_step, steps_per_period_needed

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule).
# The commands run in this process (conftest.cli_here): what these tests check is the run's
# accuracy verdict (simulate.json, the exit code, the failed check's line), not a Python
# start-up (issue 30: the file, 11 commands, 38.0 -> 17.9 s of CPU; 56.2 -> 22.7 s at a
# busier moment)
pytestmark = pytest.mark.slow


def run_json(tmp_path, *args):
    p = cli_here("simulate", "paper", *args, "--out", tmp_path)
    f = tmp_path / "simulate.json"
    doc = json.loads(f.read_text()) if f.exists() else None
    return p, doc


@pytest.mark.parametrize("integrator, step, spp", [("newmark", 0.5, 0.14), ("central_difference", 0.05, 1.4)])
def test_a_step_that_cannot_resolve_the_rotation_is_not_a_success(tmp_path, integrator, step, spp):
    p, doc = run_json(
        tmp_path,
        "--case",
        "runup",
        "--no-threshold",
        "--set",
        f"simulate.integrator={integrator}",
        "--set",
        f"simulate.time_step={step}",
    )
    assert p.returncode == 4, p.stderr
    assert doc["ok"] is False
    line = next(c for c in doc["failed_checks"] if c.startswith("step_accuracy:"))
    assert f"{spp:.3g} steps per period" in line and "unbalance's rotation" in line
    assert "period error" in line  # says why, in the scheme's terms
    assert doc["integrator"]["accuracy"]["steps_per_period"] == pytest.approx(spp, rel=0.02)
    assert "check failed: step_accuracy" in p.stderr


def test_a_loose_tolerance_is_not_a_success(tmp_path):
    # simulate.rtol's range ends at 0.1 (scene.sections): a looser one is refused before
    # the run; the loosest accepted one runs to a result that fails its own checks
    p, doc = run_json(tmp_path, "--case", "runup", "--no-threshold", "--set", "simulate.rtol=0.1")
    assert p.returncode == 4 and doc["ok"] is False and doc["failed_checks"]
    refused = cli_here("simulate", "paper", "--set", "simulate.rtol=0.5", "--out", tmp_path / "loose")
    assert refused.returncode == 2 and "simulate.rtol" in refused.stderr


@pytest.mark.parametrize(
    "args",
    [
        ["--case", "runup", "--no-threshold"],
        # Newmark's default (fixed) step on the first 10 s of the run-up, through the pillar's
        # resonance to the unbalance's 89.7 rad/s: the same step (6.667e-4 s), frequency and
        # steps per period (105.06; 105.05 over the whole 80 s) at a fifth of the cost
        ["--case", "runup", "--no-threshold", "--set", "simulate.integrator=newmark", "--set", "simulate.duration=10"],
        # central difference on the first 10 s likewise: its default step 6.667e-4 s, 89.70 rad/s
        # and 105.06 steps per period (105.05 over the whole 80 s, 4.44 needed); the command
        # 0.82-0.98 -> 0.56-0.73 s of CPU
        [
            "--case",
            "runup",
            "--no-threshold",
            "--set",
            "simulate.integrator=central_difference",
            "--set",
            "simulate.duration=10",
        ],
        # scipy's Radau: the first 5 s of the run-up (through the pillar's resonance to the
        # unbalance's ~90 rad/s, where the steps per period are fewest: 88.72 rad/s at 5 s,
        # 89.70 at 10 s, 89.71 at 20 s); the whole 80 s is four times the cost of 20 s (a
        # minute on a quiet machine), 20 s 2.7 times that of 10 s and 10 s ~1.8 times that of
        # 5 s (the command in this process 5.9 -> 3.1-3.4 s of CPU, warm; its error bars' run
        # at rtol / 100 most of it)
        # for the same check (mean steps per period measured 39.2 over 5 s, 34.5 over 10 s,
        # 32.6 over 20 s, against 2.15 needed: the 2 x asserted is far below each)
        pytest.param(
            [
                "--case",
                "runup",
                "--no-threshold",
                "--set",
                "simulate.integrator=Radau",
                "--set",
                "simulate.duration=5",
            ],
            marks=pytest.mark.slow,
        ),
        ["--case", "earthquake", "--model", "modal", "--set", "excitation.kind=record"],
        [
            "--case",
            "earthquake",
            "--model",
            "beam",
            "--set",
            "excitation.kind=record",
            "--set",
            "simulate.earthquake_duration=12",
        ],
        ["--case", "sweep"],
    ],
    ids=["dp5", "newmark", "central-difference", "radau", "modal-record", "beam-record", "sweep"],
)
def test_the_default_steps_pass_by_far(tmp_path, args):
    p, doc = run_json(tmp_path, *args)
    assert p.returncode == 0, p.stderr
    acc = doc["integrator"]["accuracy"]
    assert doc["ok"] is True and "failed_checks" not in doc
    assert acc["steps_per_period"] >= 2 * acc["steps_per_period_needed"]
    if "beam" in args:  # the full order's step: the band's, by its rule
        rule = doc["integrator"]["step_rule"]
        assert rule["scheme"] == "generalized_alpha" and rule["source"] == "rule"
        assert rule["at_forcing_top"]["period_error"] == pytest.approx(2e-3, rel=1e-3)
        assert doc["integrator"]["time_step"] == pytest.approx(rule["time_step"], rel=1e-3)


def test_an_adaptive_run_is_judged_by_the_periods_it_went_through():
    """Steps over periods: a sound necessary condition (fewer steps than needed x periods
    means some step resolved its moment's fastest frequency with fewer than needed)."""
    need = steps_per_period_needed("dp5")
    ok = check_step(
        "dp5", {}, 0.01, {"unbalance_rotation": 90.0}, 10.0, adaptive=True, periods=100.0, steps=int(need * 100) + 1
    )
    bad = check_step(
        "dp5", {}, 0.01, {"unbalance_rotation": 90.0}, 10.0, adaptive=True, periods=100.0, steps=int(need * 100) - 1
    )
    assert ok.ok and not bad.ok and bad.failed[0].startswith("step_accuracy:")


def test_a_step_that_swallows_the_run_or_the_ground_motion_is_named():
    c = check_step("newmark", {}, 20.0, {"ground_motion_band": 61.8}, 15.0, window=(5.0, 58.7))
    names = [f.split(":")[0] for f in c.failed]
    assert names == ["step_accuracy", "step_swallows_run", "step_swallows_ground_motion"]
