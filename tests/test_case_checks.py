"""The checks of a case's summary (rotorpillar.transients.case_checks) are records that
write the JSON ``simulate_<case>.json`` carries and read it back unchanged: a short
El Centro run on the modal model (beam modes: no 3D solve) has both, the truncation
estimate and the response-spectrum check; the document is the one the writer makes
(strict JSON text, parsed back)."""

import json

import pytest

from rotorpillar.provenance import to_json
from rotorpillar.scene import load_scene
from rotorpillar.transients.case_checks import (
    NoSpectrumCheck,
    NoTruncationEstimate,
    SpectralEstimate,
    SpectrumCheck,
    TruncationEstimate,
    spectrum_check_from_json,
    truncation_from_json,
)
from rotorpillar.transients.case_summary import CaseSummary
from rotorpillar.transients.cases import run_case, spectral_estimate


@pytest.fixture(scope="module")
def earthquake():
    scene = load_scene(
        "paper",
        ["excitation.kind=record", "excitation.start=1", "simulate.earthquake_duration=2", "modal_model.source=beam"],
    )
    return run_case(scene, "earthquake", "modal")


def test_the_checks_round_trip_a_real_document(earthquake):
    doc = json.loads(to_json(earthquake.summary.to_json()))
    trunc, spec = doc["truncation"], doc["response_spectrum_check"]
    assert isinstance(earthquake.summary.truncation, TruncationEstimate)
    assert isinstance(earthquake.summary.response_spectrum_check, SpectrumCheck)
    assert truncation_from_json(trunc).to_json() == trunc
    assert spectrum_check_from_json(spec).to_json() == spec
    assert list(spec)[:3] == ["period", "damping_ratio", "participation_factor"]
    assert CaseSummary.from_json(doc).to_json() == doc


def test_the_spectral_estimate_is_the_srss_of_its_modes(earthquake):
    est = spectral_estimate(earthquake.model, earthquake.run.motion)
    assert isinstance(est, SpectralEstimate) and len(est.modes) == earthquake.model.pillar_modes.count
    # the check's first-mode estimate is the first mode's part, its SRSS every mode's
    check = earthquake.summary.response_spectrum_check
    assert check.tip_estimate == est.modes[0].contribution
    assert check.srss_tip_estimate == pytest.approx(sum(m.contribution**2 for m in est.modes) ** 0.5, rel=1e-12)
    assert SpectralEstimate.from_json(est.to_json()) == est


def test_the_shapes_without_a_check_round_trip():
    no_trunc = NoTruncationEstimate(2, None, "no truncation estimate: only 2 modes")
    assert truncation_from_json(no_trunc.to_json()) == no_trunc
    assert list(no_trunc.to_json()) == ["modes", "modes_check", "statement"]
    no_spec = NoSpectrumCheck("needs the modal model")
    assert spectrum_check_from_json(no_spec.to_json()) == no_spec
    assert no_spec.to_json() == {"note": "needs the modal model"}
