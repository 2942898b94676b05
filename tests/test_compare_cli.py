"""`rotorpillar simulate --model fem3d|beam|paper` and `rotorpillar compare` through the CLI.

The output contract (docs: the brief's COMPARE_SPEC): the per-model files and
fields, the paper model's base-forcing warning, compare_<case>.json, and bad
input (exit 2, one line, nothing written).  Cheap: the 3D runs on the
[full_order] default mesh (8 x 10 elements) over 4 s of El Centro (from t =
1 s; issue 30: it was 6 s, the command's CPU 8.2 -> 6.1 s).  The modal ROM
against the 3D tube: measured 0.7 % history error over 15 s
(docs/transients.md; the tube's height needs its 10 elements: 8 x 4 gives
20 %), 0.33 % over these 4 s as over 6 s; tolerance 2 %.  The 3D run's energy
balance: 4.8e-5 over 4 s (2.7e-5 over 6 s, 2.5e-4 over 3 s: too short a
window for the bound), bound 1e-4.

The commands run in this process (conftest.cli_here), as test_simulate_cli's do.
"""

import json

import numpy as np
import pytest
from conftest import cli_here

SPEC_FIELDS = (
    "model",
    "case",
    "ok",
    "warnings",
    "max_abs",
    "omega_final",
    "captured_at",
    "energy_balance",
    "integrator",
    "dofs",
    "wall_seconds",
    "excitation",
)
COLUMNS = (
    "t",
    "Omega",
    "tip_x",
    "tip_x_relative",
    "tip_x_absolute",
    "ground_x",
    "ground_acceleration",
    "rotor_x",
    "rotor_y",
    "shaft_deflection_x",
)
RECORD = ["--set", "excitation.kind=record", "--set", "excitation.start=1"]
COARSE_3D = ["--set", "full_order.elements_around=8", "--set", "full_order.earthquake_duration=4"]
has_dolfinx = pytest.mark.skipif(__import__("importlib").util.find_spec("dolfinx") is None, reason="needs dolfinx")


def check_model_files(out, case, model, stem="simulate"):
    doc = json.loads((out / f"{stem}_{case}_{model}.json").read_text())
    for key in SPEC_FIELDS:
        assert key in doc, key
    assert doc["model"] == model and doc["case"] == case
    assert {"tip_x_relative", "tip_x_absolute", "shaft_deflection_x"} <= doc["max_abs"].keys()
    assert isinstance(doc["dofs"], int) and doc["wall_seconds"] > 0
    data = np.load(out / f"{stem}_{case}_{model}.npz")
    for c in COLUMNS:
        assert data[c].shape == data["t"].shape, c
    assert np.allclose(data["tip_x_absolute"] - data["tip_x_relative"], data["ground_x"], atol=1e-12)
    header = (out / f"{stem}_{case}_{model}.csv").read_text().splitlines()[0].split(",")
    assert set(COLUMNS) <= set(header)
    assert (out / f"{stem}_{case}_{model}.png").stat().st_size > 10_000
    return doc


@pytest.mark.slow  # the full-order beam over 8 s of record
def test_beam_earthquake_files(tmp_path):
    p = cli_here(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--model",
        "beam",
        *RECORD,
        "--set",
        "simulate.earthquake_duration=8",
        "--json",
        "--out",
        tmp_path,
    )
    assert p.returncode == 0, p.stderr
    doc = check_model_files(tmp_path, "earthquake", "beam")
    last = json.loads((tmp_path / "simulate_earthquake.json").read_text())
    assert last["max_abs"] == doc["max_abs"] and last["model"] == "beam"
    assert doc["full_order"]["elements"] == 10 and doc["full_order"]["time_step"] > 0
    assert doc["energy_balance"]["relative_error"] < 3e-4
    assert doc["warnings"] == []
    assert (tmp_path / "simulate_earthquake.npz").exists() and (tmp_path / "simulate.json").exists()


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@pytest.mark.parametrize(
    "scene,extra,warned",
    [
        ("paper-stiff", [], True),
        ("paper", ["--set", "excitation.kind=record", "--set", "shaft.stiffness=1e10"], True),
        ("paper", [], False),
    ],
)
def test_paper_model_base_forcing_warning(tmp_path, scene, extra, warned):
    p = cli_here(
        "simulate",
        scene,
        "--case",
        "earthquake",
        "--model",
        "paper",
        *extra,
        "--set",
        "simulate.earthquake_duration=6",
        "--json",
        "--out",
        tmp_path,
    )
    assert p.returncode == 0, p.stderr
    doc = check_model_files(tmp_path, "earthquake", "paper")
    assert bool(doc["warnings"]) is warned
    assert ("warning: Eq. 4's published base forcing" in p.stderr) is warned
    assert doc["ok"] is True  # ok is about the numerics only


@pytest.mark.slow  # ~30 s: the 3D run (the modal-against-3D check)
@has_dolfinx
def test_compare_earthquake_modal_fem3d(tmp_path):
    p = cli_here("compare", "paper", "--case", "earthquake", *RECORD, *COARSE_3D, "--json", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "compare_earthquake.json").read_text())
    assert doc["models_run"] == ["modal", "fem3d"] and doc["reference"] == "fem3d"
    for m in ("modal", "fem3d"):
        pm = doc["per_model"][m]
        assert {
            "peak_tip_relative",
            "peak_tip_absolute",
            "peak_shaft_deflection",
            "omega_final",
            "wall_seconds",
            "compile_seconds",
            "dofs",
            "ok",
            "warnings",
            "json",
            "npz",
            "pillar_model",
        } <= pm.keys()
        # the comparison's own files, apart from the scene's simulate_<case>_<model>.*
        assert pm["json"] == f"compare_earthquake_{m}.json"
        check_model_files(tmp_path, "earthquake", m, stem="compare")
    assert not (tmp_path / "simulate_earthquake_modal.json").exists()
    assert set(doc["errors"]) == {"modal"}
    e = doc["errors"]["modal"]
    assert e["tip_history_error"] < 2e-2
    # e = 2 mm: the ground drives the tip, the rotors stay in phase and the history leads
    assert e["lead"] == "history" and e["angle_drift"] < 0.1
    assert e["tip_envelope_error"] <= e["tip_history_error"] + 1e-12
    assert abs(doc["errors"]["modal"]["omega_final_difference"]) < 1e-5
    assert doc["cost_ratio"]["fem3d"] == 1.0 and doc["chart"] == "compare_earthquake.png"
    assert (tmp_path / "compare_earthquake.png").stat().st_size > 10_000
    sp = doc["spectrum"]
    assert len(sp["period"]) == len(sp["psa"]) and sp["mode_periods"]
    assert sp["spectral_peak_tip"] > 0 and sp["computed_peak_tip"] > 0
    f3 = json.loads((tmp_path / "compare_earthquake_fem3d.json").read_text())
    assert f3["full_order"]["duration"] == 4 and "coarsened" in f3["full_order"]["note"]
    assert f3["energy_balance"]["relative_error"] < 1e-4


@pytest.mark.parametrize("models", ["modal,nosuch", "", "modal,modal", "modal,"])
def test_compare_bad_models(tmp_path, models):
    out = tmp_path / "o"
    p = cli_here("compare", "paper", "--case", "earthquake", "--models", models, "--out", out)
    assert p.returncode == 2
    assert len(p.stderr.strip().splitlines()) == 1 and "--models" in p.stderr
    assert not out.exists()


@pytest.mark.slow  # ~12 s: the 3D run
@has_dolfinx
def test_compare_on_the_spatial_rom_sets_like_against_like(tmp_path):
    """Where the ROM's run-up runs on the spatial model, the 3D full order carries what it
    carries: the motor's reaction on the top, b2 relative to the gondola, the structural ratio.
    Paper with a tenth of its unbalance, so that the reaction dominates the tip: the 3D run
    without the reaction set the ROM at 152 % history error (the model's difference, not the
    ROM's), with it 1.5 % (measured; 3 %: the window's run-up on the default 3D mesh, as the
    earthquake's 2 % above on a longer window)."""
    args = (
        *("--models", "modal,fem3d"),
        *("--set", "modal_model.planes=spatial", "--set", "modal_model.source=beam"),
        *("--set", "rotor.eccentricity=0.0002", "--set", "full_order.elements_around=8"),
        *("--set", "full_order.runup_duration=4"),
    )
    p = cli_here("compare", "paper", "--case", "runup", *args, "--json", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "compare_runup.json").read_text())
    assert doc["errors"]["modal"]["tip_history_error"] < 3e-2
    f3 = json.loads((tmp_path / "compare_runup_fem3d.json").read_text())
    assert "reaction" in f3["model_description"]["forcing"]
    assert "relative to the plate" in f3["model_description"]["damping_law"]
    assert not any("first component" in w for w in f3["warnings"])
    # the beam's run-up (compare's default pair) carries none of it, and says so; the warning
    # is about the models, not the run's length: 4 s of the run-up (simulate.duration) instead
    # of the case's 80 s (4.8e4 beam steps and their charts: 3.4 s of CPU against 2.4 s)
    short = ("--set", "simulate.duration=4")
    p = cli_here("compare", "paper", "--case", "runup", *args[2:], *short, "--json", "--out", tmp_path / "beam")
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "beam" / "compare_runup.json").read_text())
    assert any("spatial model" in w for w in doc["per_model"]["beam"]["warnings"])
    assert "spatial model" in p.stderr
