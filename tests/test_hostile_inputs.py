"""Damaged or foreign input files, named (issue 31.7): the hostile suite's inputs.

Every result file the report (and the verdict it writes first) reads goes through its
record (records.read); a damaged one is named with the field at fault, NaN where a
number is needed is damage (strict JSON has no NaN: a hand or another tool wrote it,
or a null stands where the record needs a number), and `report --strict` says on
stderr why it fails.  Checked against files damaged by hand from a real one, each
kind of damage a user meets: a wrong type, a missing field, a NaN token, a null
amplitude, a truncated file, a truncated NPZ.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from rotorpillar import records
from rotorpillar.postprocess.readers import read_simulation
from rotorpillar.scene import load_scene
from rotorpillar.verdict.harmonic import HarmonicResult
from rotorpillar.verdict.summary import engineering_summary


def test_malformed_json_is_named_with_its_line_and_column(tmp_path):
    path = tmp_path / "harmonic.json"
    path.write_text('{"running_speeds": [1.0,\n  NaN]}')
    with pytest.raises(ValueError, match=r"^harmonic\.json: not JSON \(.* at line 2, column 3: 'NaN\]}'\)$"):
        records.read(path, HarmonicResult)
    path.write_text('{"running_speeds": [1.0,')
    with pytest.raises(ValueError, match=r"^harmonic\.json: not JSON \(Input data was truncated\)$"):
        records.read(path, HarmonicResult)


def test_a_damaged_npz_is_named(tmp_path):
    path = tmp_path / "simulate_runup.npz"
    np.savez(path, t=np.linspace(0, 1, 1000), tip_x=np.zeros(1000))
    path.write_bytes(path.read_bytes()[:300])  # truncated, as by a full disk or a killed copy
    with pytest.raises(ValueError, match=r"^simulate_runup\.npz: not a readable NPZ"):
        read_simulation(tmp_path, "runup")


def test_the_verdict_names_a_damaged_input_it_left_out(tmp_path):
    """A damaged modal.json, harmonic.json or run file is not read around: the verdict
    lists it as not read, with the field at fault."""
    (tmp_path / "modal.json").write_text('{"modes": "none"}')
    (tmp_path / "harmonic.json").write_text('{"running_speeds": ["fast"]}')
    (tmp_path / "simulate_runup_modal.json").write_text("{")
    s = engineering_summary(load_scene("paper"), tmp_path)
    missing = "\n".join(s.not_assessed)
    assert "harmonic.json is damaged" in missing and "`$.running_speeds[0]`" in missing
    assert "modal.json is damaged" in missing and "simulate_runup_modal.json is damaged" in missing
    assert not s.inputs


# -- through the command: a real harmonic.json, damaged by hand --------------------------

DAMAGE = {
    "wrong type": (lambda d: d.update(rom="x"), "Expected `object`, got `str` - at `$.rom`"),
    "missing field": (lambda d: d.pop("running_speeds"), "missing required field `running_speeds`"),
    "null amplitude": (
        lambda d: d["rom"]["tip_amplitude"].__setitem__(3, None),
        "Expected `float`, got `null` - at `$.rom.tip_amplitude[3]`",
    ),
    "NaN amplitude": (lambda d: d["rom"]["tip_amplitude"].__setitem__(3, float("nan")), "'NaN"),
}


@pytest.fixture(scope="module")
def harmonic_doc(tmp_path_factory):
    from rotorpillar.cli import main

    d = tmp_path_factory.mktemp("harmonic")
    assert main(["harmonic", "paper", "--no-fem3d", "--out", str(d)]) == 0  # its failure on the captured stderr
    return json.loads((d / "harmonic.json").read_text())


@pytest.mark.slow  # a whole command for the fixture
@pytest.mark.parametrize("damage", list(DAMAGE))
def test_each_damage_of_harmonic_json_is_named_with_its_field(tmp_path, harmonic_doc, damage):
    doc = json.loads(json.dumps(harmonic_doc))
    change, words = DAMAGE[damage]
    change(doc)
    path = tmp_path / "harmonic.json"
    path.write_text(json.dumps(doc))  # json writes a NaN as the token NaN, as Python's json does
    with pytest.raises(ValueError) as err:
        records.read(path, HarmonicResult)
    assert str(err.value).startswith("harmonic.json: ") and words in str(err.value)


@pytest.mark.slow  # harmonic, then report
def test_report_strict_says_on_stderr_which_input_is_damaged(tmp_path, harmonic_doc, here):
    """The two reports in this process (conftest's ``here``: stderr as a child's)."""
    doc = json.loads(json.dumps(harmonic_doc))
    doc["rom"]["tip_amplitude"][3] = None
    (tmp_path / "harmonic.json").write_text(json.dumps(doc))
    p = here("report", "paper", "--out", tmp_path, "--no-animations", "--strict")
    assert p.returncode == 1, p.stderr
    lines = [line for line in p.stderr.splitlines() if line.startswith("rotorpillar report: --strict:")]
    assert lines == [
        "rotorpillar report: --strict: input harmonic.json: ValueError: harmonic.json: Expected `float`, "
        "got `null` - at `$.rom.tip_amplitude[3]`"
    ]
    got = json.loads((tmp_path / "report.json").read_text())
    assert got["inputs"]["harmonic"] is True and got["inputs"]["study"] is False
    assert "$.rom.tip_amplitude[3]" in got["damaged"]["harmonic"]
    page = (tmp_path / "report.html").read_text()
    section = page[page.index('id="unbalance"') :][:1000]
    assert "Harmonic.json is damaged" in section and "tip_amplitude[3]" in section
    assert "rotorpillar harmonic paper" in section
    # without --strict the same page, exit 0
    assert here("report", "paper", "--out", tmp_path, "--no-animations").returncode == 0
