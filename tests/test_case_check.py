"""A case checked before any work (``transients.cases.check_case``, what the commands'
preflight calls): it refuses what ``run_case`` refuses, with the same line, and
integrates nothing.

The reference is ``run_case`` itself: its ``simulate`` refuses an over-budget run
before integrating, and its start refuses an earthquake that ends before the ground
moves, so the refusals cost milliseconds.  Messages are compared exactly (both
come from the same functions: no tolerance).  That nothing is integrated is shown
by replacing ``simulate`` with a function that fails when called.
"""

from __future__ import annotations

import pytest

from rotorpillar.errors import InputError
from rotorpillar.scene import CASES, load_scene, with_values
from rotorpillar.transients import cases
from rotorpillar.transients.cases import check_case, run_case

#: the modal model on the 1D beam's modes, as the preflight estimates it (no 3D solve)
BEAM_MODES = {"modal_model.source": "beam"}

REFUSED = [
    ("runup", "paper", {"simulate.max_steps": 1000}),
    ("runup", "modal", {"simulate.max_steps": 1000, "simulate.runup_initial_speed": 50.0}),
    ("rundown", "modal", {"simulate.max_steps": 1000}),
    ("rundown", "paper", {"drive.torque_at_zero": 1e-3}),  # no stable speed to run down from
    ("earthquake", "paper", {"simulate.earthquake_duration": 1.0}),  # ends before the ground moves
    ("earthquake", "modal", {"simulate.integrator": "newmark", "simulate.time_step": 1e-8}),
    ("sweep", "paper", {"sweep.rate": 1e-3}),
]


@pytest.mark.parametrize("case, which, values", REFUSED, ids=[f"{c}-{w}" for c, w, _ in REFUSED])
def test_refuses_as_run_case_does(case, which, values):
    scene = with_values(load_scene("paper"), {**BEAM_MODES, **values})
    with pytest.raises(InputError) as checked:
        check_case(scene, case, which)
    with pytest.raises(InputError) as ran:
        run_case(scene, case, which, truncation=False)
    assert str(checked.value) == str(ran.value)


class Integrated(Exception):
    pass


def _no_integration(*args, **kwargs):
    raise Integrated


@pytest.mark.parametrize("which", ["paper", "modal"])
def test_passes_a_run_without_integrating_it(monkeypatch, which):
    scene = with_values(load_scene("paper"), BEAM_MODES)
    monkeypatch.setattr(cases, "simulate", _no_integration)
    for case in CASES:
        assert check_case(scene, case, which) is None
    with pytest.raises(Integrated):  # the run itself does reach simulate: the patch is where it calls
        run_case(scene, "runup", which, truncation=False)
