"""CaseSummary (rotorpillar.transients.case_summary): the typed summary of a case
round-trips exactly through ``to_json``/``from_json`` and through the JSON
text the simulate command writes, with the keys in the order of
``simulate_<case>.json``.  Exact equality: no tolerance."""

import json

import pytest

from rotorpillar.provenance import to_json
from rotorpillar.reduced.averaging import Jump
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import no_motion, paper_pulse
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.stationary import NoPassingFold, averaging_prediction
from rotorpillar.scene import load_scene
from rotorpillar.transients.case_checks import NoSpectrumCheck, NoTruncationEstimate
from rotorpillar.transients.case_summary import CaseSummary, run_summary
from rotorpillar.transients.sweep_records import JumpMatch, NumericJump, SweepFindings

BASE_KEYS = [
    "ok",
    "duration",
    "omega_final",
    "omega_final_mean",
    "max_abs",
    "captured_at",
    "speed_state",
    "passages",
    "energy_balance",
    "integrator",
    "prediction",
    "jumps",
]
SWEEP_KEYS = [
    "predicted_jumps",
    "jump_comparison",
    "largest_speed_step_ratio",
    "amplitudes",
    "rate_check",
    "no_jump_reason",
    "rate_convergence",
]


@pytest.fixture(scope="module")
def summary():
    scene = load_scene("paper")
    model, _ = build_model(scene, "paper")
    d, L = scene.drive, scene.load
    drive = DriveSchedule.constant(d.torque_at_zero, d.slope, L.coefficient)
    run = simulate(model, drive, no_motion(), 2.0, settings=Settings("dp5", rtol=1e-6, samples=201))
    pred = averaging_prediction(model, d.torque_at_zero, d.slope, L.coefficient)
    return run_summary(run, drive.free_speed(), pred)


def _roundtrip(s: CaseSummary):
    d = s.to_json()
    assert CaseSummary.from_json(d) == s
    text = to_json(d)
    again = CaseSummary.from_json(json.loads(text))
    assert to_json(again.to_json()) == text
    return d


def test_plain_case_keys_and_roundtrip(summary):
    d = _roundtrip(summary)
    assert list(d) == BASE_KEYS
    assert d["jumps"] == [] and summary.sweep is None


def test_optional_sections_in_the_order_simulate_writes_them(summary):
    from dataclasses import replace

    jump = Jump("up", 25.0, 31.0, 600.0, 1)
    sweep = SweepFindings((jump,), (JumpMatch(jump, None),), {"up": 1.0, "down": 1.2}, (), (), None, None)
    s = replace(
        summary,
        sweep=sweep,
        jumps=(NumericJump("up", 25.5, 30.0, 610.0, 2),),
        captured_at=26.0,
        truncation=NoTruncationEstimate(2, None, "x"),
    )
    d = _roundtrip(s)
    assert list(d) == BASE_KEYS + SWEEP_KEYS + ["truncation"]
    assert d["no_jump_reason"] is None and d["rate_convergence"] is None  # present, null
    s = replace(summary, passing_torque=NoPassingFold(statement="none"))
    assert list(_roundtrip(s)) == BASE_KEYS + ["passing_torque"]
    s = replace(summary, excitation=paper_pulse().sizes(), response_spectrum_check=NoSpectrumCheck("x"))
    assert list(_roundtrip(s)) == BASE_KEYS + ["excitation", "response_spectrum_check"]


def test_summary_is_frozen(summary):
    with pytest.raises(AttributeError):
        summary.omega_final = 0.0
