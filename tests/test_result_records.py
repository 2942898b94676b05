"""The result records, typed to their leaves, write the JSON the commands wrote before
them; every JSON a command writes carries its provenance (issue 18.1).

One short `rotorpillar compare` (the paper's pulse on the paper model against the
ROM, 12 s: a few seconds warm) is read back: each record built from its file
gives that file back (``to_json``), and again itself (``from_json``); where a
record replaced a dict the old code built, the test builds that dict the old
way from the same inputs (the per-model files the comparison names) and finds
it equal, key order included.  No tolerance: the same numbers pass through
JSON both ways.
"""

from __future__ import annotations

import json

import pytest
from conftest import cli

from rotorpillar.provenance import PROVENANCE_KEYS
from rotorpillar.transients.records import CompareResult

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow

#: what a command writes beside a record's own fields
HEAD = ("command", "scene_source", "overrides", "scene")


@pytest.fixture(scope="module")
def compared(tmp_path_factory):
    out = tmp_path_factory.mktemp("compare")
    p = cli(
        "compare",
        "paper",
        "--case",
        "earthquake",
        "--models",
        "paper,modal",
        "--set",
        "simulate.earthquake_duration=12",
        "--out",
        out,
    )
    assert p.returncode == 0, p.stderr
    return out


def _fields(doc: dict) -> dict:
    """A result file less its provenance."""
    return {k: v for k, v in doc.items() if k not in HEAD + PROVENANCE_KEYS}


def test_every_json_a_command_writes_carries_its_provenance(compared):
    written = sorted(compared.glob("*.json"))
    assert {p.name for p in written} >= {
        "compare.json",
        "compare_earthquake.json",
        "compare_earthquake_paper.json",
        "compare_earthquake_modal.json",
    }
    for path in written:
        doc = json.loads(path.read_text())
        for key in PROVENANCE_KEYS:
            assert doc.get(key), f"{path.name}: no {key}"
        assert doc["scene"]["name"] == "paper", path.name
        assert doc["command"] == "compare" or path.name.startswith("compare_earthquake_"), path.name


def _old_per_model(r: dict, stem: str) -> dict:
    """What compare wrote per model before CompareResult was typed (its _per_model)."""
    ma = r["max_abs"]
    return {
        "peak_tip_relative": ma["tip_x_relative"],
        "peak_tip_absolute": ma["tip_x_absolute"],
        "peak_shaft_deflection": ma["shaft_deflection_x"],
        "omega_final": r["omega_final"],
        "wall_seconds": r["wall_seconds"],
        "compile_seconds": r.get("compile_seconds"),
        "dofs": r["dofs"],
        "ok": r["ok"],
        "warnings": list(r.get("warnings") or []),
        "pillar_model": r.get("pillar_model"),
        "json": f"{stem}.json",
        "npz": f"{stem}.npz",
    }


def test_compare_result_round_trips_its_file(compared):
    doc = json.loads((compared / "compare_earthquake.json").read_text())
    result = CompareResult.from_json(doc)
    assert result.to_json() == _fields(doc)
    assert list(result.to_json()) == list(_fields(doc))
    assert CompareResult.from_json(result.to_json()) == result
    # typed to the leaves: no dict left where the shape is known
    assert result.per_model["modal"].pillar_model.kind in ("beam", "solid", "shell", "closed_form")
    assert result.errors["paper"].lead in ("history", "envelope")
    assert result.spectrum.modes[0].mode == 1 and result.window.runup is None
    # the old dicts, from the same inputs: the per-model files the comparison names
    for m in ("paper", "modal"):
        run = json.loads((compared / f"compare_earthquake_{m}.json").read_text())
        old = _old_per_model(run, f"compare_earthquake_{m}")
        assert result.per_model[m].to_json() == old
        assert list(result.per_model[m].to_json()) == list(old)
    assert list(doc["errors"]["paper"]) == [
        "tip_history_error",
        "peak_tip_difference",
        "omega_final_difference",
        "tip_envelope_error",
        "envelope_window",
        "angle_drift",
        "angle_drift_final",
        "lead",
        "lead_why",
    ]
    assert list(doc["window"]) == ["start", "end", "duration", "why"]
    assert list(doc["spectrum"]) == [
        "period",
        "psa",
        "damping",
        "mode_periods",
        "spectral_peak_tip",
        "computed_peak_tip",
        "modes",
        "note",
    ]


#: the keys of a reduced model's run, in the order the hand-built dict of
#: transients/model_run.py wrote them (the case summary's, then the model's)
REDUCED_KEYS = [
    "case",
    "model",
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
    "excitation",
]
REDUCED_TAIL = [
    "warnings",
    "pillar_model",
    "uncertainty",
    "dofs",
    "wall_seconds",
    "compile_seconds",
    "model_description",
    "model_info",
    "resonances",
    "damped_frequencies",
    "tip_x_frame",
    "max_abs_sampled",
    "initial_speed",
    "excitation_in_model",
    "internal_forces",
]
#: what files.write_model_files adds after the record
WRITER = ("model_files", "files", "figures")


@pytest.mark.parametrize("model,middle", [("paper", []), ("modal", ["truncation"])])
def test_reduced_run_round_trips_its_file(compared, model, middle):
    from rotorpillar.chain.record import Uncertain
    from rotorpillar.reduced.system import Resonance
    from rotorpillar.transients.run_records import ReducedRun

    doc = json.loads((compared / f"compare_earthquake_{model}.json").read_text())
    fields = {k: v for k, v in _fields(doc).items() if k not in WRITER}
    run = ReducedRun.from_json(fields)
    assert run.to_json() == fields
    assert list(run.to_json()) == REDUCED_KEYS + middle + REDUCED_TAIL
    assert ReducedRun.from_json(run.to_json()) == run
    assert all(isinstance(r, Resonance) for r in run.resonances) and run.resonances
    assert run.summary.max_abs is run.max_abs and run.max_abs["tip_x_relative"] > 0
    assert (run.uncertainty is None) is (model == "paper")
    if run.uncertainty is not None:
        assert all(isinstance(u, Uncertain) for u in run.uncertainty.values())
    assert run.pillar_model.kind in ("beam", "solid", "shell", "closed_form", "reduction")
    from rotorpillar.reduced.models import ModalModelInfo, PaperModelInfo

    assert isinstance(run.model_info, PaperModelInfo if model == "paper" else ModalModelInfo)
    from rotorpillar.reduced.system import DampedMode

    assert run.damped_frequencies and all(isinstance(d, DampedMode) for d in run.damped_frequencies)
    # the case summary to its leaves
    from rotorpillar.transients.case_summary import CaseSummary, EnergyBalance, Passage

    assert isinstance(run.summary.energy_balance, EnergyBalance)
    assert run.summary.energy_balance.relative_error < 0.05  # ENERGY_CHECK: the run is ok
    assert run.summary.passages and all(isinstance(p, Passage) for p in run.summary.passages)
    assert CaseSummary.from_json(run.summary.to_json()) == run.summary


@pytest.mark.slow  # one 3D run: 8 x 10 elements, 3 s of El Centro
def test_fem3d_run_round_trips_its_file(tmp_path):
    from rotorpillar.transients.run_records import Fem3dPlan, Fem3dRun

    p = cli(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--model",
        "fem3d",
        "--set",
        "excitation.kind=record",
        "--set",
        "excitation.start=1",
        "--set",
        "full_order.elements_around=8",
        "--set",
        "full_order.earthquake_duration=3",
        "--out",
        tmp_path,
    )
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "simulate_earthquake_fem3d.json").read_text())
    fields = {k: v for k, v in _fields(doc).items() if k not in WRITER}
    run = Fem3dRun.from_json(fields)
    assert run.to_json() == fields and Fem3dRun.from_json(run.to_json()) == run
    # the order the hand-built dict had: the 3D run's summary, then the capture through the ROM
    assert list(fields) == [
        "case",
        "model",
        "ok",
        "duration",
        "omega_final",
        "omega_final_mean",
        "max_abs",
        "energy_balance",
        "integrator",
        "dofs",
        "wall_seconds",
        "captured_at",
        "captured_resonance",
        "captured_index",
        "speed_state",
        "warnings",
        "captured_at_source",
        "pillar_model",
        "compile_seconds",
        "model_description",
        "model_info",
        "resonances",
        "damped_frequencies",
        "tip_x_frame",
        "full_order",
        "initial_speed",
        "excitation",
        "excitation_in_model",
        "internal_forces",
    ]
    assert isinstance(run.full_order, Fem3dPlan) and run.full_order.mesh.elements_around == 8
    assert run.full_order.reference.case == "earthquake"


def test_simulate_files_round_trip_through_the_run_record(tmp_path):
    # simulate_<case>.json (the scene's run, which the report reads) and the model's own
    # simulate_<case>_<model>.json are ReducedRun's JSON plus the writer's keys: read through
    # the record and written back, each gives its fields back, key order included
    from rotorpillar.transients.run_records import ReducedRun

    p = cli(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--model",
        "paper",
        "--set",
        "simulate.earthquake_duration=12",
        "--out",
        tmp_path,
    )
    assert p.returncode == 0, p.stderr
    for name in ("simulate_earthquake.json", "simulate_earthquake_paper.json"):
        doc = json.loads((tmp_path / name).read_text())
        fields = {k: v for k, v in _fields(doc).items() if k not in WRITER}
        run = ReducedRun.from_json(fields)
        assert json.dumps(run.to_json()) == json.dumps(fields), name
        assert run.case == "earthquake" and run.model == "paper"
