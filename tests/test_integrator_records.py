"""integrators.json through its record (issue 18.1): the integrator study's three
experiments are records typed to their leaves, and a document read back gives
itself again.

The document is the study's own, computed here on the paper model at a small
size (a 1 s run-up, one rung in two, two of the beam's pillar modes, a 1 s drift): the same
code path as the command, so every kind of value the file holds appears
(fixed-step rows with their steps per period, adaptive rows without, methods
that never fail: null in ``first_failure``).  It goes through the writer's JSON
(non-finite numbers become null) and back; no tolerance: the same numbers pass
through JSON both ways.
"""

from __future__ import annotations

import json
import math

import pytest

from rotorpillar.provenance import to_json
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.models import beam_candidates, build_model
from rotorpillar.scene import load_scene
from rotorpillar.transients.integrator_records import IntegratorStudy, MethodSummary
from rotorpillar.transients.integrator_study import accuracy_study, drift_study, stability_study


@pytest.fixture(scope="module")
def study() -> IntegratorStudy:
    scene = load_scene("paper")
    d, L = scene.drive, scene.load
    drive = DriveSchedule.ramp(d.torque_at_zero, d.slope, L.coefficient, scene.simulate.runup_ramp)
    model, _ = build_model(scene, "paper")
    acc = accuracy_study(model, drive, 1.0, samples=41, quick=True)
    stab = stability_study(scene, drive, duration=0.2, max_modes=2, pillar_modes=beam_candidates(scene))
    drift = drift_study(model, duration=1.0)
    return IntegratorStudy(acc, stab, drift)


def _as_written(study: IntegratorStudy) -> dict:
    """The result part of integrators.json as the one writer writes it."""
    return json.loads(to_json(study.to_json()))


def test_a_document_read_back_gives_itself(study):
    doc = _as_written(study)
    again = IntegratorStudy.from_json(doc).to_json()
    assert again == doc
    # key order too: the file is written in the record's field order
    assert json.dumps(again) == json.dumps(doc)


def test_the_document_keeps_its_keys(study):
    """The names integrators.json has always had (contracts): the ones no Python name
    can hold are written under their old names."""
    doc = _as_written(study)
    acc = doc["accuracy"]
    assert list(acc) == ["duration", "samples", "omega_max", "reference", "rows", "per_method"]
    assert "agreement_with_DOP853_1e-12" in acc["reference"]
    per = next(iter(acc["per_method"].values()))
    assert list(per) == [
        "fails",
        "coarsest_ok_steps_per_period",
        "best_error",
        "wall_seconds_at_0.001",
        "nfev_at_0.001",
        "wall_seconds_at_1e-06",
        "nfev_at_1e-06",
    ]
    fixed = [r for r in acc["rows"] if r["family"] == "fixed"]
    adaptive = [r for r in acc["rows"] if r["family"] == "adaptive"]
    assert fixed and adaptive
    # steps per rotor period: fixed-step rows only (left out of the adaptive ones, not null)
    assert all("steps_per_rotor_period" in r for r in fixed)
    assert not any("steps_per_rotor_period" in r for r in adaptive)
    # a method that never failed is null in first_failure, not left out
    assert None in doc["stability"]["first_failure"].values()
    assert all(r["time_step"] is None for r in doc["stability"]["rows"] if r["method"] == "dp5")
    # without the command's additions, its optional parts are absent
    assert set(doc) == {"accuracy", "stability", "energy_drift"}


def test_json_names_are_read_by_their_fields(study):
    doc = _as_written(study)
    read = IntegratorStudy.from_json(doc)
    name, per = next(iter(doc["accuracy"]["per_method"].items()))
    summary = read.accuracy.per_method[name]
    assert isinstance(summary, MethodSummary)
    assert summary.nfev_at_1e_3 == per["nfev_at_0.001"]
    assert summary.wall_seconds_at_1e_6 == per["wall_seconds_at_1e-06"]
    assert read.accuracy.reference.agreement_with_dop853 == doc["accuracy"]["reference"]["agreement_with_DOP853_1e-12"]
    # rows come back as records, an infinite error (a failed run) as JSON null
    for row, raw in zip(read.accuracy.rows, study.accuracy.rows):
        assert row.error == (raw.error if math.isfinite(raw.error) else None)
