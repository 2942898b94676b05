"""`rotorpillar run`'s compare stages, alone (the shared ``run_paper`` skips
them): El Centro on the ROM and the 3D full order, the run-up on the ROM
and the beam, then the report showing both, with no "not computed" left for
them.  Shortened runs (10 s, the 3D 5 s) keep it cheap: this checks the stages' wiring
and the hand-over through the files, not the physics (test_fem3d_transient
and the compare command's own tests do that)."""

import json

import pytest
from conftest import cli

from rotorpillar.cli import COMMANDS
from rotorpillar.transients.compare import COMPARISONS, comparison_models


@pytest.mark.slow
@pytest.mark.skipif("compare" not in COMMANDS, reason="the compare command is not on this branch")
def test_run_compare_stages_feed_the_report(tmp_path):
    skip = [
        a
        for s in ("analyze", "simulate", "modal", "harmonic", "integrators", "converge", "campbell", "tornado")
        for a in ("--skip", s)
    ]
    p = cli(
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
        # the speed-against-accuracy study's 3D ladder 8 x 2, 4, 6, 8 (its default 8 x 20:
        # 8.6 s of the 16 s its 3D runs cost): wiring, not the study's numbers
        "--set",
        "full_order.pareto_along=8",
        # the 3D runs 5 s, not their default 15 s: the comparison's window follows the 3D
        # duration ([full_order], every model runs it), the stages and files are the same;
        # measured on this command: 42.6 -> 31.0 s of user CPU (compare_earthquake 32 -> 20 s)
        *("--set", "full_order.earthquake_duration=5", "--set", "full_order.runup_duration=5"),
    )
    assert p.returncode == 0, p.stderr[-3000:]
    run = json.loads((tmp_path / "run.json").read_text())
    # the two-case comparisons, then El Centro in three components (its own stage), then the report
    assert list(run["stages"]) == [f"compare_{c}" for c in COMPARISONS] + ["compare_earthquake_components", "report"]
    quake = json.loads((tmp_path / "compare_earthquake.json").read_text())
    assert quake["models_run"] == comparison_models("earthquake")
    assert quake["excitation"]["kind"] == "record"
    along = sorted({r["params"]["elements_along"] for r in quake["pareto"]["runs"] if r["family"] == "fem3d"})
    assert along == [2, 4, 6, 8, 10]  # the key's ladder, and the comparison's own 3D mesh (8 x 10)
    assert json.loads((tmp_path / "compare_runup.json").read_text())["models_run"] == comparison_models("runup")
    text = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "<code>rotorpillar compare" not in text
    assert (tmp_path / "figures" / "comparison_earthquake.png").is_file()
    assert (tmp_path / "figures" / "comparison_runup.png").is_file()
