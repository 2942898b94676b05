"""The CLI round trip: JSON on stdout equals the file, numbers equal an
independent eigen-solve of Eq. 4's pencil, bad input exits 2 with one line
and writes nothing.

The round trip runs in a child, as a user runs it: its stdout holds the JSON and nothing
else, start-up and imports included.  The other cases run in this process (conftest's
``here``: rotorpillar.cli.main, what reaches the file descriptors caught as a child's would
be): their exit codes, files and lines are the checks, not the start-up; 0.15-1.2 s of CPU
a command in a child, the tests' 4.7 -> 1.9 s.
"""

import json

import numpy as np
import pytest
from scipy.linalg import eigh


def test_analyze_json_round_trip(tmp_path, here):
    # in this process (``here`` reads stdout off the file descriptor, what a library printed in
    # C included): no Python start-up to check what the command prints
    p = here("analyze", "paper-stiff", "--json", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)  # stdout is the JSON and nothing else
    assert doc == json.loads((tmp_path / "analyze.json").read_text())
    assert doc["scene"]["shaft"]["stiffness"] == 5e6
    assert {"versions", "timings", "machine", "paper_comparison"} <= doc.keys()
    # independent check of the paper model's omega_1,2 from the scene data (Eq. 4's pencil)
    s = doc["scene"]
    mA = s["reduction"]["tip_mass"] + s["gondola"]["mass"]
    c1, c2 = s["reduction"]["tip_stiffness"], s["shaft"]["stiffness"]
    lam = eigh([[c1 + c2, -c2], [-c2, c2]], np.diag([mA, s["rotor"]["mass"]]), eigvals_only=True)
    assert doc["paper_model"]["system"]["omega"] == pytest.approx(np.sqrt(lam), rel=1e-10)
    assert doc["paper_model"]["reduction"]["tip_mass_source"] == "stated"
    # the headline model is the ROM on the chain's pillar model, which it names
    assert doc["pillar_model"]["source"] == "scene" and doc["pillar_model"]["kind"] in ("solid", "beam")
    x = [r for r in doc["resonances"] if r["direction"] == "X"]
    assert len(x) == doc["system"]["modes"] + 1  # k pillar modes + the rotor
    assert [r["omega"] for r in x] == doc["system"]["omega"]
    assert all(r["uncertainty"]["omega"]["value"] == r["omega"] for r in doc["resonances"])
    # issue 26: system.omega stays the rotor plane's resonances (the contract above); the
    # spatial model stands beside it, and the drive's reaction is the stall torque's
    sp, dr = doc["spatial"], doc["drive_reaction"]
    assert sp["planar_error"]["planar_omega"] == pytest.approx(doc["system"]["omega"], rel=1e-12)
    assert sp["planes"]["requested"] == "auto" and sp["planes"]["planes"] in ("planar", "spatial")
    assert {"bending in the rotor's plane", "bending along the spin axis"} <= {r["kind"] for r in sp["resonances"]}
    assert dr["torque"] == dr["base_moment"] == s["drive"]["torque_at_zero"]
    assert dr["runup"]["final_speed"] > 0
    for row in doc["paper_comparison"]:
        assert row["flag"] == (abs(row["rel_diff"]) > 0.02)
        assert row["rel_diff"] == pytest.approx((row["computed"] - row["paper"]) / row["paper"])


def test_set_overrides_and_closed_form_reduction(tmp_path, here):
    p = here("analyze", "paper", "--json", "--out", tmp_path, "--set", "reduction.source=closed_form")
    doc = json.loads(p.stdout)
    red, pil = doc["paper_model"]["reduction"], doc["pillar"]
    assert red["tip_mass_source"] == "closed_form"
    assert red["tip_mass"] == pytest.approx(pil["mass"] / 4)
    assert red["tip_stiffness"] == pytest.approx(pil["mass"] / 4 * pil["omega_col1"] ** 2)


def test_summary_prints_the_comparison_table(tmp_path, here):
    p = here("analyze", "--out", tmp_path)
    assert p.returncode == 0
    assert "Paper's printed numbers against ours" in p.stdout
    assert "omega_col1" in p.stdout and (tmp_path / "analyze.json").exists()


@pytest.mark.parametrize(
    "args, key",
    [
        (["analyze", "paper", "--set", "pillar.inner_diameter=2.1"], "pillar.inner_diameter"),
        (["analyze", "paper", "--set", "rotor.mass=-5"], "rotor.mass"),
        (["analyze", "missing.toml"], "missing.toml"),
        (["analyze", "paper", "--set", "shaft.stiffness=abc"], "shaft.stiffness"),
    ],
)
def test_bad_input_exits_2_with_one_line_and_writes_nothing(tmp_path, args, key, here):
    out = tmp_path / "out"
    p = here(*args, "--out", out)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and key in lines[0]
    assert p.stdout == ""
    assert not out.exists()


def test_run_refuses_an_unknown_stage_to_skip(tmp_path, here):
    p = here("run", "paper", "--out", tmp_path, "--skip", "lunch")
    assert p.returncode == 2 and "--skip lunch" in p.stderr and "converge" in p.stderr
    assert "compare" in p.stderr
    assert not tmp_path.exists() or not list(tmp_path.iterdir())
