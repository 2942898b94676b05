"""`rotorpillar simulate` through the CLI: the output contract (`integrators`: the main job's
study, tests/test_main_job.py).

Checks the files and fields other commands rely on (branch post reads
``simulate_<case>.json``/``.npz``: t, Omega, tip_x, rotor_x, rotor_y,
ground_x, modal_coordinates), that the JSON copy equals simulate.json, that
series are decimated to at most simulate.samples rows, and the numbers
against independent references where one exists: the run-up's final speed
is the root of Md = Mc shifted by the resonances' small tail torque (the
exact linear balance, 1e-6), the modal model's modal coordinates sum to the
tip (1e-12), the paper model's ground is q5 as written, and a run-down with
the motor off follows the quasi-static J W' = -k W**2 - dL(W) with the exact
averaged torque dL of the linear structure (1e-3).

The commands run in this process (conftest.cli_here: rotorpillar.cli.main, what
``python -m rotorpillar`` calls, its stdout, stderr and exit code): the contract is the
files, the JSON and the messages, not a Python start-up (issue 30: with test_compare_cli,
50.8 -> 25.0 s of CPU).
"""

import json
import math

import numpy as np
import pytest
from conftest import cli_here
from scipy.integrate import solve_ivp

from rotorpillar.reduced.excitation import STANDARD_GRAVITY
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.stationary import stationary_exact
from rotorpillar.scene import load_scene

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def runup(tmp_path_factory):
    out = tmp_path_factory.mktemp("runup")
    p = cli_here("simulate", "paper", "--case", "runup", "--json", "--out", out)
    assert p.returncode == 0, p.stderr
    return out, json.loads(p.stdout)


def test_runup_outputs_and_fields(runup):
    out, doc = runup
    assert doc == json.loads((out / "simulate.json").read_text())
    copy = json.loads((out / "simulate_runup.json").read_text())
    for key in ("omega_final", "max_abs", "jumps", "captured_at", "energy_balance", "integrator", "case"):
        assert copy[key] == doc[key]
    assert doc["jumps"] == [] and doc["captured_at"] is None
    assert doc["energy_balance"]["relative_error"] < 1e-6
    assert {"tip_x", "rotor_x", "rotor_y"} <= doc["max_abs"].keys()
    data = np.load(out / "simulate_runup.npz")
    for key in ("t", "Omega", "tip_x", "rotor_x", "rotor_y", "ground_x"):
        assert data[key].shape == data["t"].shape
    assert len(data["t"]) <= load_scene("paper").simulate.samples
    # the scene's run is on the headline model, the ROM, which names its pillar model
    assert doc["model"] == "modal" and doc["pillar_model"]["kind"] in ("solid", "beam")
    assert str(data["tip_x_frame"]) == "relative_to_ground"
    bars = doc["uncertainty"]["peak_tip_relative"]
    assert bars["value"] == doc["max_abs"]["tip_x_relative"] and bars["error"] >= 0
    header = (out / "simulate_runup.csv").read_text().splitlines()[0]
    assert header.startswith("t,Omega,tip_x,rotor_x,rotor_y,ground_x")
    assert (out / "simulate_runup.png").stat().st_size > 10_000
    assert doc["figures"][0]["file"] == "simulate_runup.png"


def test_runup_settles_on_the_exact_stationary_speed(runup):
    _, doc = runup
    scene = load_scene("paper")
    model, _ = build_model(scene, "paper")
    st = stationary_exact(model, scene.drive.torque_at_zero, scene.drive.slope, scene.load.coefficient)
    assert doc["omega_final"] == pytest.approx(max(s.omega for s in st), rel=1e-6)
    # Md = Mc alone (no resonance) differs by the tail torque only: < 0.1 %
    free = (-12 + math.sqrt(144 + 4 * 0.5 * 5100)) / (2 * 0.5)
    assert doc["omega_final"] == pytest.approx(free, rel=1e-3)


def test_modal_earthquake_contract(tmp_path):
    p = cli_here("simulate", "paper", "--case", "earthquake", "--model", "modal", "--json", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    data = np.load(tmp_path / "simulate_earthquake.npz")
    k = doc["truncation"]["modes"]
    assert data["modal_coordinates"].shape == (len(data["t"]), k)
    assert np.allclose(data["modal_coordinates"].sum(axis=1), data["tip_x"], rtol=1e-12, atol=1e-15)
    assert str(data["tip_x_frame"]) == "relative_to_ground"
    assert np.allclose(data["tip_x_absolute"], data["tip_x"] + data["ground_x"])
    assert data["mode_shapes"].shape[1] == k
    assert doc["excitation"]["peak_acceleration_g"] == pytest.approx(math.pi, rel=1e-9)
    assert doc["excitation"]["realistic"] is False
    assert doc["truncation"]["modes_check"] == k + 1
    assert abs(doc["truncation"]["tip_x_max_rel_diff"]) < 0.05


def test_paper_earthquake_ground_is_q5_as_written(tmp_path):
    p = cli_here("simulate", "paper", "--case", "earthquake", "--model", "paper", "--json", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    data = np.load(tmp_path / "simulate_earthquake.npz")
    t, g = data["t"], data["ground_x"]
    inside = (t >= 5) & (t < 12)
    assert np.allclose(g[inside], -STANDARD_GRAVITY / math.pi * (1 - np.cos(math.pi * t[inside])))
    assert np.all(g[~inside] == 0)


def test_rundown_with_the_motor_off(tmp_path):
    p = cli_here("simulate", "paper", "--case", "rundown", "--json", "--out", tmp_path, "--set", "simulate.duration=20")
    doc = json.loads(p.stdout)
    # quasi-static reference: J W' = -k W^2 - dL(W), dL the exact averaged
    # torque of the linear structure at constant speed (frequency domain)
    W0, k, J = doc["initial_speed"], 0.5, 100.0
    model, _ = build_model(load_scene("paper"), "paper")
    Wg = np.linspace(0.5, 1.1 * W0, 4000)
    Tg = model.steady_torque(Wg)
    sol = solve_ivp(
        lambda t, W: [(-k * W[0] ** 2 + np.interp(W[0], Wg, Tg)) / J], (0, 20), [W0], rtol=1e-10, atol=1e-12
    )
    assert doc["omega_final"] == pytest.approx(sol.y[0][-1], rel=1e-3)
    # the resonances cost the run-down about 1 % against Mc alone, W0 / (1 + W0 k t / J)
    assert doc["omega_final"] < W0 / (1 + W0 * k * 20 / J)


def test_bad_modes_and_integrator(tmp_path):
    p = cli_here("simulate", "paper", "--modes", "0", "--out", tmp_path)
    assert p.returncode == 2 and "--modes" in p.stderr
    p = cli_here("simulate", "paper", "--integrator", "euler", "--out", tmp_path)
    assert p.returncode == 2
    assert not list(tmp_path.iterdir())


def test_decimation_keeps_the_peaks():
    from rotorpillar.transients.case_summary import decimate
    from rotorpillar.transients.cases import run_case

    r = run_case(load_scene("paper"), "runup", "paper").run
    d = decimate(r, 1000)
    assert len(d.t) <= 1000 and d.t[-1] == r.t[-1] and d.t[0] == r.t[0]
    assert np.max(d.peak, axis=0) == pytest.approx(np.max(r.peak, axis=0), rel=0, abs=0)
    i = np.searchsorted(r.t, d.t)
    assert np.array_equal(d.q, r.q[i])


@pytest.mark.parametrize(
    "sets, key",
    [
        (["excitation.kind=record", "excitation.record=BAD"], "excitation.record"),
        (["simulate.duration=-5"], "simulate.duration"),
        (["simulate.earthquake_duration=-1"], "simulate.earthquake_duration"),
        (["excitation.duration=nan"], "excitation.duration"),
    ],
)
def test_cli_refuses_bad_earthquake_input(tmp_path, sets, key):
    args = ["simulate", "paper", "--case", "earthquake", "--out", tmp_path]
    for s in sets:
        args += ["--set", s]
    p = cli_here(*args)
    assert p.returncode == 2, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and key in lines[0]
    assert not list(tmp_path.iterdir())


def test_cli_refuses_an_empty_accelerogram_file(tmp_path):
    f = tmp_path / "empty.txt"
    f.write_text("")
    out = tmp_path / "out"
    p = cli_here(
        "simulate",
        "paper",
        "--case",
        "earthquake",
        "--out",
        out,
        "--set",
        "excitation.kind=record",
        "--set",
        f"excitation.record='{f}'",
    )
    assert p.returncode == 2
    assert "empty" in p.stderr and len(p.stderr.strip().splitlines()) == 1
    assert not out.exists()
