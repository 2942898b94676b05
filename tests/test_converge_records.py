"""convergence.json through its records (issue 18.1): the typed study writes exactly
the document its analysis's records give, the runner's runs unchanged in it, for
computed, cached, failed, unavailable and old cached runs."""

from __future__ import annotations

import importlib
import json

import pytest

from rotorpillar import converge as cv
from rotorpillar.converge.runner import ModelUnavailable, run_point, run_study
from rotorpillar.provenance import to_json
from rotorpillar.scene import load_scene, override

study_module = importlib.import_module("rotorpillar.converge.study")


def _plain(obj):
    """What json writes of ``obj`` (dicts with numpy numbers, records), read back."""
    return json.loads(to_json(obj))


def _cheap(scene):
    # the closed forms, the beams and the three coarsest shells (a reference for
    # ovalling, so a choice): every kind of run
    # (in-process and served, with its modes, cells and memory) in a few seconds
    return [
        c
        for c in cv.ladder(scene)
        if cv.FAMILIES[c.family].model in ("closed_form", "beam") or (c.family == "shell_quad" and c.level <= 16)
    ]


@pytest.fixture
def scene():
    return override(load_scene("paper"), ["converge.solid=false"])


ERROR_KEYS = {
    f"{q}_{k}" for q in cv.QUANTITIES for k in ("error", "model_error", "discretisation_error", "error_bound")
}


def _without_errors(run_doc: dict) -> dict:
    """A run's document without the errors the analysis attaches: the runner's dict."""
    return {k: v for k, v in run_doc.items() if k not in ERROR_KEYS}


def _runner_docs(records) -> list[dict]:
    """The runner's runs as the document holds them before the analysis attaches errors
    (their aliased ovalling modes dropped, as the analysis does first)."""
    return [_without_errors(r.to_json()) for r in cv.drop_aliases(records)]


def _expected(records, analysis) -> dict:
    """The parts of convergence.json the analysis of the runs gives (its record's
    document); checked beside it: the runs are the runner's runs as they were."""
    assert [_without_errors(r.to_json()) for r in analysis.runs] == _runner_docs(records)
    return _plain(analysis.to_json())


def test_the_study_writes_what_its_dicts_wrote(tmp_path, monkeypatch, scene):
    """A real (small) study, computed then cached: convergence.json's parts equal the
    analysis's dicts of the same runs, and the document round-trips through its type
    (the whole ladder: every rung of the cheap one)."""
    monkeypatch.setattr(study_module, "study_cases", _cheap)
    tol = 1e-2
    first = cv.study(scene, out_dir=tmp_path, tolerance=tol, show_progress=False, full=True)
    assert first.study.computed == len(_cheap(scene)) and first.study.cached == 0
    # every run from the cache
    again = cv.study(scene, out_dir=tmp_path, tolerance=tol, show_progress=False, full=True)
    doc = json.loads((tmp_path / "convergence.json").read_text())
    records = run_study(_cheap(scene), scene, tmp_path / "cache", progress=False)
    analysis = cv.analyse(records, scene, tol)
    assert {k: doc[k] for k in _expected(records, analysis)} == _expected(records, analysis)
    assert doc["families"] == {
        k: {
            "label": f.label,
            "model": f.model,
            "order_theory": f.order,
            "quantities": list(f.quantities),
            "sweep": f.sweep,
        }
        for k, f in cv.FAMILIES.items()
    }
    assert doc["study"]["cached"] == len(records) and doc["study"]["computed"] == 0
    assert doc["refinement"]["full"] and doc["refinement"]["runs"] == doc["refinement"]["ladder_runs"] == len(records)
    assert cv.ConvergenceStudy.from_json(doc).to_json() == doc
    assert again.selection.chosen is not None and again.chosen == again.selection.chosen
    served = [r for r in again.runs if r.model == "shell"]
    assert served and all(r.cells and r.modes and r.modes_asked for r in served)


def test_failed_and_unavailable_runs_keep_their_keys(tmp_path, scene):
    """A failed or unavailable run has no frequencies, cost or memory in the document
    (not even as null), an ok run states its frequencies even when None."""

    def runner(case, sc):
        if case.family == "beam_euler" and case.level == 4:
            raise RuntimeError("no convergence")
        if cv.FAMILIES[case.family].model == "shell":
            raise ModelUnavailable("shell model unavailable: test")
        return run_point(case, sc)

    records = run_study(_cheap(scene), scene, tmp_path, runner=runner, progress=False)
    runs = cv.analyse(records, scene, 1e-2).runs
    assert [_without_errors(r.to_json()) for r in runs] == _runner_docs(records)
    status = {r.status for r in runs}
    assert status == {"ok", "failed", "unavailable"}
    for r in runs:
        doc = r.to_json()
        assert type(r).from_json(doc) == r
        assert ("bending" in doc) == ("dofs" in doc) == (r.status == "ok")
    beam_fe = next(r.to_json() for r in runs if r.family == "beam_timoshenko")
    assert beam_fe["ovalling"] is None and beam_fe["ovalling_error"] is None  # a beam has no ovalling mode


def test_an_old_cached_run_still_loads(tmp_path, monkeypatch, scene):
    """A cached run written before the details a run records now (cells, modes asked,
    the serving process's time and memory) loads, and the study writes it as it is."""
    monkeypatch.setattr(study_module, "study_cases", _cheap)
    cv.study(scene, out_dir=tmp_path, tolerance=1e-2, show_progress=False)
    newer = ("cells", "modes_asked", "baseline_memory", "process_time", "first_run_with_compilation")
    aged = 0
    for path in (tmp_path / "cache").glob("*.json"):
        run = json.loads(path.read_text())
        if run.get("model") == "shell":
            path.write_text(json.dumps({k: v for k, v in run.items() if k not in newer}))
            aged += 1
    assert aged
    st = cv.study(scene, out_dir=tmp_path, tolerance=1e-2, show_progress=False)
    doc = json.loads((tmp_path / "convergence.json").read_text())
    shells = [r for r in doc["runs"] if r["model"] == "shell"]
    assert shells and not any(k in r for r in shells for k in newer)
    assert all(r.cached and r.cells is None for r in st.runs if r.model == "shell")
    assert cv.ConvergenceStudy.from_json(doc).to_json() == doc


def test_the_modal_selection_round_trips_through_its_record(tmp_path, monkeypatch, scene):
    """model_for_modal's choice (modal.json's ``model_selection``) is a record whose
    document reads back to itself; here a study with no 3D run: the scene's own [mesh],
    unmet, the study's own cheapest model named beside it (the slow `modal --tolerance`
    test round-trips a met and an unmet choice among 3D runs)."""
    monkeypatch.setattr(study_module, "study_cases", _cheap)
    sc, sel = cv.model_for_modal(scene, 1e-2, tmp_path)
    assert isinstance(sel, cv.ModalModelSelection)
    doc = _plain(sel.to_json())
    assert cv.ModalModelSelection.from_json(doc).to_json() == doc and list(doc) == [
        "tolerance",
        "met",
        "chosen",
        "reason",
        "rule",
        "band",
        "needed",
        "reference_uncertainty",
        "rejected_cheaper",
        "overall_cheapest",
        "convergence_json",
        "text",
    ]
    study = cv.ConvergenceStudy.read(tmp_path / "convergence.json")
    assert sel.chosen is None and not sel.met and sc.mesh == scene.mesh
    assert sel.overall_cheapest == study.chosen and sel.band == study.band
    assert sel.convergence_json == str(tmp_path / "convergence.json") and sel.convergence_json in sel.text
