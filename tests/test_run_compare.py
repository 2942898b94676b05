"""`rotorpillar run`'s compare stages, alone (the shared ``run_paper`` skips
them): El Centro on the ROM and the 3D full order, the run-up on the ROM
and the beam, then the report showing both, with no "not computed" left for
them.  Shortened runs (10 s, the 3D 2 s on 8 x 5 elements at a 5 ms step) keep it cheap:
this checks the stages' wiring and the hand-over through the files, not the physics
(test_fem3d_transient, test_transient_pareto, test_components and the compare command's
own tests do that).

`run` itself runs in this process (the ``here`` fixture): what it launches, each stage, is
still its own ``rotorpillar <stage>`` process, as a user's `run` launches it, and the
stages still hand over through the files; the test's own child only added a Python
start-up and the imports (~1 s of CPU)."""

import json

import pytest

from rotorpillar.cli import COMMANDS
from rotorpillar.transients.compare import COMPARISONS, comparison_models


@pytest.mark.slow
@pytest.mark.skipif("compare" not in COMMANDS, reason="the compare command is not on this branch")
def test_run_compare_stages_feed_the_report(tmp_path, here):
    skip = [
        a
        for s in ("analyze", "simulate", "modal", "harmonic", "integrators", "converge", "campbell", "tornado")
        for a in ("--skip", s)
    ]
    p = here(
        "run",
        "paper",
        "--out",
        tmp_path,
        *skip,
        "--no-animations",
        "--set",
        "simulate.duration=10",
        "--set",
        "simulate.earthquake_duration=10",
        # the speed-against-accuracy study's 3D ladder 8 x 1, 2, 3, 4 (the key's least; its
        # default 8 x 20: 8.6 s of the 16 s its 3D runs cost): wiring, not the study's numbers
        "--set",
        "full_order.pareto_along=4",
        # the 3D runs 2 s, not their default 15 s: the comparison's window follows the 3D
        # duration ([full_order], every model runs it), the stages and files are the same;
        # measured on this command: 42.6 -> 31.0 s of user CPU (compare_earthquake 32 -> 20 s)
        # at 5 s; at 2 s with the ladder 8 x 1..4 (8 x 2..8 before) 32.7 -> 24.7 s
        *("--set", "full_order.earthquake_duration=2", "--set", "full_order.runup_duration=2"),
        # the comparisons' 3D mesh 8 x 5, not [full_order]'s 8 x 10 (its 5 s run in the study
        # alone 4.2 s of CPU), still apart from the ladder's meshes (the check below); and a
        # 5 ms step, not the band's rule's 1.68 ms (every 3D and beam run: 14 steps a period
        # of the unbalance's 90 rad/s, 1.7 % period error: the accuracy check needs 5.7): the
        # stages, their records and files are the same; 24.7 -> 20.8 -> 18.6 s of user CPU
        # (compare_earthquake 14.1 -> 11.3 -> 8.6 s, components 4.2 -> 2.7 s)
        *("--set", "full_order.elements_along=5", "--set", "full_order.time_step=0.005"),
    )
    assert p.returncode == 0, p.stderr[-3000:]
    run = json.loads((tmp_path / "run.json").read_text())
    # the two-case comparisons, then El Centro in three components (its own stage), then the report
    assert list(run["stages"]) == [f"compare_{c}" for c in COMPARISONS] + ["compare_earthquake_components", "report"]
    quake = json.loads((tmp_path / "compare_earthquake.json").read_text())
    assert quake["models_run"] == comparison_models("earthquake")
    assert quake["excitation"]["kind"] == "record"
    along = sorted({r["params"]["elements_along"] for r in quake["pareto"]["runs"] if r["family"] == "fem3d"})
    assert along == [1, 2, 3, 4, 5]  # the key's ladder, and the comparison's own 3D mesh (8 x 5)
    assert json.loads((tmp_path / "compare_runup.json").read_text())["models_run"] == comparison_models("runup")
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "<code>rotorpillar compare" not in text
    assert (tmp_path / "figures" / "comparison_earthquake.png").is_file()
    assert (tmp_path / "figures" / "comparison_runup.png").is_file()
