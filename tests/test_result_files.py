"""Every result a command writes, computed for real and read back through its record.

For each concept (the closed forms and the analysis, a case on a reduced model and its
checks, the convergence study, the integrator study, the command files) a real
document is made at a small size, encoded as the writer encodes it, decoded with its
type, and encoded again: the same JSON (a record equal to itself; its arrays and
non-finite numbers pass through JSON the same way both times).  The contract keys the
README and docs/ name are read from the JSON text itself, by key, where a user's script
would read them.  No tolerance: the same numbers pass through JSON both ways.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rotorpillar import analyze, load_scene, override, records
from rotorpillar import converge as cv
from rotorpillar.analysis import AnalysisResult
from rotorpillar.reduced.excitation import NoMotionSizes, PulseSizes, RecordSizes, paper_pulse
from rotorpillar.reduced.stationary import NoPassingFold, PassingTorqueStudy
from rotorpillar.transients.case_summary import NoSpectrumCheck, NoTruncationEstimate, SpectrumCheck, TruncationEstimate
from rotorpillar.transients.cases import run_case, spectral_estimate


def round_trip(record, type_=None):
    """``record`` encoded, decoded as ``type_`` (its own type by default), encoded again:
    the decoded record, after checking the two encodings hold the same JSON (an int
    written to a float field reads back as that float: 528 and 528.0 are one number)."""
    text = records.encode(record)
    back = records.decode(text, type_ or type(record))
    assert json.loads(records.encode(back)) == json.loads(text)
    return back


# -- the closed forms and the analysis ----------------------------------------------------


@pytest.mark.parametrize("overrides", [[], ["shaft.stiffness=5e6"], ["rotor.eccentricity=0.04"]])
def test_the_analysis_round_trips_and_keeps_its_contract_keys(overrides):
    result = analyze(override(load_scene("paper"), overrides))
    back = round_trip(result)
    assert back == result
    doc = json.loads(records.encode(result))
    assert doc["system"]["omega"] == list(result.system.omega)
    assert set(doc["drive"]) >= {"captured_index", "captured_resonance", "captured_at"}
    assert set(doc["pillar_model"]) >= {"kind", "label", "mesh", "dofs", "source", "verified"}


def test_a_missing_section_of_the_analysis_is_named():
    doc = json.loads(records.encode(analyze(load_scene("paper"))))
    del doc["drive"]
    with pytest.raises(records.msgspec.ValidationError, match="Object missing required field `drive`"):
        records.convert(doc, AnalysisResult)


def test_each_model_says_how_it_was_built_under_its_own_tag():
    from rotorpillar.reduced.models import BeamModelInfo, ModalModelInfo, ModelInfo, PaperModelInfo, build_model

    scene = load_scene("paper", ["modal_model.source=beam"])
    for which, kind in (("paper", PaperModelInfo), ("modal", ModalModelInfo), ("beam", BeamModelInfo)):
        _, info = build_model(scene, which, 200.0)
        back = round_trip(info, ModelInfo)
        assert isinstance(back, kind) and back == info and json.loads(records.encode(info))["kind"] == which


@pytest.mark.parametrize("name", ["none", "paper", "elcentro"])
def test_a_ground_motions_sizes_come_back_as_their_kind(name):
    from rotorpillar.reduced.excitation import ExcitationSizes, load_record, no_motion

    motion = {"none": no_motion, "paper": paper_pulse, "elcentro": lambda: load_record("elcentro")}[name]()
    sizes = motion.sizes()
    back = round_trip(sizes, ExcitationSizes)
    assert back == sizes and type(back) is {"none": NoMotionSizes, "paper": PulseSizes, "elcentro": RecordSizes}[name]
    assert json.loads(records.encode(sizes))["kind"] == back.kind


# -- a case on a reduced model, and its checks ------------------------------------------


@pytest.fixture(scope="module")
def earthquake():
    """El Centro's first 2 s on the ROM (the beam's modes: no 3D solve): both checks."""
    scene = load_scene(
        "paper",
        ["excitation.kind=record", "excitation.start=1", "simulate.earthquake_duration=2", "modal_model.source=beam"],
    )
    return run_case(scene, "earthquake", "modal")


def test_a_case_summary_round_trips_with_its_checks(earthquake):
    s = earthquake.summary
    assert isinstance(s.truncation, TruncationEstimate) and isinstance(s.response_spectrum_check, SpectrumCheck)
    back = round_trip(s)
    assert json.loads(records.encode(back)) == json.loads(records.encode(s))
    doc = json.loads(records.encode(s))
    assert doc["truncation"]["kind"] == "estimate" and doc["response_spectrum_check"]["kind"] == "check"
    assert {"ok", "captured_at", "captured_resonance", "captured_index", "speed_state", "max_abs"} <= set(doc)


def test_the_spectral_check_is_the_estimate_of_its_modes(earthquake):
    """The check's one-mode estimate is the largest coupled mode's part, its SRSS every mode's;
    the coupled modes are the X structure's: the pillar's modes and the rotor's."""
    est = spectral_estimate(earthquake.model, earthquake.run.motion)
    check = earthquake.summary.response_spectrum_check
    assert len(est.modes) == earthquake.model.pillar_modes.count + 1
    assert check.tip_estimate == max(m.contribution for m in est.modes)
    assert check.srss_tip_estimate == pytest.approx(sum(m.contribution**2 for m in est.modes) ** 0.5, rel=1e-12)


def test_the_checks_that_were_not_run_say_why_under_their_tag():
    from rotorpillar.transients.case_summary import SpectrumCheckResult, Truncation

    no_trunc = NoTruncationEstimate(2, None, "no truncation estimate: only 2 modes")
    assert round_trip(no_trunc, Truncation) == no_trunc
    no_spec = NoSpectrumCheck("needs the modal model")
    assert round_trip(no_spec, SpectrumCheckResult) == no_spec
    assert json.loads(records.encode(no_spec)) == {"kind": "unavailable", "note": "needs the modal model"}


@pytest.mark.slow  # the passing-torque batches: run-ups by the hundred
def test_a_runup_summary_round_trips_with_its_passing_torque():
    res = run_case(load_scene("sommerfeld"), "runup", "paper")
    pt = res.summary.passing_torque
    assert isinstance(pt, PassingTorqueStudy)
    assert round_trip(res.summary).passing_torque == pt
    fold = NoPassingFold(statement="no fold")
    assert round_trip(fold) == fold


# -- the convergence study's runs (the study's own file: test_converge.py) ----------------


def _cheap(scene):
    # the closed forms, the beams and the three coarsest shells (a reference for
    # ovalling, so a choice): every kind of run (in-process and served) in seconds
    return [
        c
        for c in cv.ladder(scene)
        if cv.FAMILIES[c.family].model in ("closed_form", "beam") or (c.family == "shell_quad" and c.level <= 16)
    ]


def test_failed_and_unavailable_runs_carry_no_result(tmp_path):
    from rotorpillar.converge.runner import ModelUnavailable, run_point, run_study

    scene = override(load_scene("paper"), ["converge.solid=false"])
    cases = [c for c in _cheap(scene) if cv.FAMILIES[c.family].model != "shell" or c.level == 8]

    def runner(case, sc):
        if case.family == "beam_euler" and case.level == 4:
            raise RuntimeError("no convergence")
        if cv.FAMILIES[case.family].model == "shell":
            raise ModelUnavailable("shell model unavailable: test")
        return run_point(case, sc)

    runs = cv.analyse(run_study(cases, scene, tmp_path, runner=runner, progress=False), scene, 1e-2).runs
    assert {r.status for r in runs} == {"ok", "failed", "unavailable"}
    for r in runs:
        doc = json.loads(records.encode(r))
        assert round_trip(r) == r
        assert ("dofs" in doc) == (r.status == "ok") and ("error" in doc) == (r.status != "ok")


# -- the integrator study -----------------------------------------------------------------


def test_the_integrator_study_round_trips_with_its_failed_runs():
    from rotorpillar.reduced.drive import DriveSchedule
    from rotorpillar.reduced.models import beam_candidates, build_model
    from rotorpillar.reduced.pillar_modes import modes_in_band
    from rotorpillar.transients import integrator_study as st

    # the record's three parts as run_integrator_study makes them, each on a short run: the
    # accuracy ladder (quick) holds the rows this test is about; the stiffness and drift parts
    # need only be there, typed (the whole quick study took ~13 s, most of it the drift's 20 s
    # of free whirl)
    scene = load_scene("paper", ["modal_model.source=beam"])
    d, L = scene.drive, scene.load
    drive = DriveSchedule.ramp(d.torque_at_zero, d.slope, L.coefficient, scene.simulate.runup_ramp)
    modes = beam_candidates(scene)
    band = scene.modal_model.band_factor * drive.free_speed()
    model, _ = build_model(scene, "modal", modes=modes_in_band(modes.omega, band), pillar_modes=modes)
    study = st.IntegratorStudy(
        st.accuracy_study(model, drive, 1.0, quick=True),
        st.stability_study(scene, drive, duration=0.2, max_modes=2, pillar_modes=modes),
        st.drift_study(model, duration=1.0),
    )
    # this short ladder has no failed run (nor had the quick study this test ran before, so
    # its check of them checked nothing): one is made as accuracy_study records one, an
    # error of inf, which the JSON holds as null and the reader gives back as None
    rows = list(study.accuracy.rows)
    rows[-1] = records.replace(rows[-1], error=math.inf, status="unstable")
    study = records.replace(study, accuracy=records.replace(study.accuracy, rows=tuple(rows)))
    back = round_trip(study)
    doc = json.loads(records.encode(study))
    for m, summary in study.accuracy.per_method.items():
        assert "nfev_at_1e-06" in doc["accuracy"]["per_method"][m]
        assert back.accuracy.per_method[m].nfev_at_1e_6 == summary.nfev_at_1e_6
    failed = [r for r in study.accuracy.rows if r.error is not None and not np.isfinite(r.error)]
    gone = {(r.method, r.setting) for r in failed}
    assert gone and all(b.error is None for b in back.accuracy.rows if (b.method, b.setting) in gone)
    assert all(b.error == r.error for b, r in zip(back.accuracy.rows, study.accuracy.rows) if r not in failed)


# -- the files the commands write ---------------------------------------------------------


@pytest.mark.slow  # two commands, a few seconds each
def test_simulate_files_read_back_as_their_model_run(tmp_path, here):
    from rotorpillar.transients.model_run import PaperRun, RunRecord

    # in this process (conftest's here): what is read back is the files the command writes
    p = here("simulate", "paper", "--case", "earthquake", "--model", "paper", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    for name in ("simulate_earthquake_paper.json", "simulate_earthquake.json", "simulate.json"):
        run = records.read(tmp_path / name, RunRecord)
        assert isinstance(run, PaperRun) and run.model == "paper" and isinstance(run.excitation, PulseSizes)
        doc = json.loads((tmp_path / name).read_text())
        assert {"ok", "pillar_model", "uncertainty", "compile_seconds", "tip_x_frame", "captured_at"} <= set(doc)
        assert doc["max_abs"]["tip_x_relative"] == run.max_abs["tip_x_relative"]
        round_trip(run, RunRecord)
    files = records.read(tmp_path / "simulate_earthquake.json", RunRecord).files
    assert files is not None and files.npz.endswith("simulate_earthquake.npz")
