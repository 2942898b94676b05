"""summary.json's machine checks (issue 29.6) read from what `analyze` and the runs wrote.

What is checked, and against what:
- the balance check's demand is G = e Omega at the running speed analyze.json
  states (ISO 21940-11, 1e-12: the same product), its capacity
  rotor.balance_grade; the paper's 2 mm at 89.7 rad/s fails G 2.5 by ~72x;
- the vibration checks carry API 617's limit (25.4 um below 12000 rpm) and
  ISO 20816-3's B/C boundary of the group and support analyze.json states;
- the modal-mass check's capacity is the share analyze.json's ROM for forces keeps (the
  headline's 2 modes carry 82.8 %, below it), and
  each modal run's row the share of the modes its forces used (its own internal_forces.mass);
- the El Centro run's foundation loads: the moment's envelope is the run's
  own base moment (one number: the same refined peak), torsion not computed.
"""

import pytest
from conftest import cli

from rotorpillar import records
from rotorpillar.analysis.results import AnalysisResult
from rotorpillar.reduced.vibration_limits import ISO20816_3_BOUNDARIES
from rotorpillar.scene import load_scene, override
from rotorpillar.transients.files import write_model_files
from rotorpillar.transients.model_run import run_model
from rotorpillar.verdict.summary import engineering_summary

# a ROM run and a whole command: the slow tier (conftest's rule)
pytestmark = pytest.mark.slow

QUAKE = ["excitation.kind=record", "simulate.earthquake_duration=12"]


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    """The ROM's El Centro (12 s) and `analyze` in one directory."""
    d = tmp_path_factory.mktemp("machine")
    scene = override(load_scene("paper"), QUAKE)
    write_model_files(d, scene, run_model(scene, "earthquake", "modal"), {}, last_run=False)
    p = cli("analyze", "paper", "--out", d)
    assert p.returncode == 0, p.stderr
    return d


def test_machine_checks_in_the_summary(out):
    scene = load_scene("paper")
    a = records.read(out / "analyze.json", AnalysisResult)
    m = a.machine_checks
    assert m is not None and m.running_speed == a.drive.runup_speed
    s = engineering_summary(scene, out)
    assert s.machine_checks == m and "analyze.json" in s.inputs
    by = {c.name: c for c in s.check_details if c.case and c.case.startswith("running at")}
    b = by["balance grade (ISO 21940-11)"]
    assert b.demand == pytest.approx(1e3 * scene.rotor.eccentricity * m.running_speed, rel=1e-12)
    assert b.capacity == 2.5 and b.status == "fail" and b.utilisation == pytest.approx(71.8, rel=1e-2)
    shaft = by["shaft vibration (API 617)"]
    assert shaft.capacity == pytest.approx(25.4e-6, rel=1e-12)
    housing = by["housing vibration (ISO 20816-3)"]
    assert m.housing is not None and m.housing.group is not None
    assert housing.capacity == ISO20816_3_BOUNDARIES[(m.housing.group, m.housing.support)][1]
    mass = [c for c in s.check_details if c.name == "effective modal mass (EN 1998-1)"]
    assert {c.case for c in mass} == {"analyze: the ROM for forces", "earthquake (elcentro)"}
    rom = next(c for c in mass if c.case == "analyze: the ROM for forces")
    f = m.force_rom
    assert rom.demand == 0.9 and rom.capacity == f.fraction_for_forces
    # the headline ROM keeps its band's 2 modes (82.8 %); the ROM for forces keeps the 90 %
    assert f.fraction_kept < 0.9 <= f.fraction_for_forces and f.modes_for_forces == f.modes_needed
    run = next(c for c in mass if c.case == "earthquake (elcentro)")
    quake = records.read(out / "simulate_earthquake_modal.json", dict)["internal_forces"]
    assert run.capacity == quake["mass"]["fraction"] >= 0.9 and run.status == "pass"
    assert s.verdict == "fail"


def test_the_earthquake_run_gives_the_foundation_loads(out):
    s = engineering_summary(load_scene("paper"), out)
    (loads,) = s.foundation
    assert (loads.model, loads.case) == ("modal", "earthquake (elcentro)")
    run = records.read(out / "simulate_earthquake_modal.json", dict)
    base = run["internal_forces"]["base"]
    r = loads.reactions
    assert r.moment_envelope == base["moment"] and r.shear_envelope == base["shear"]
    assert abs(r.rows[0].moment) == base["moment"] and r.rows[0].time == base["moment_time"]
    assert r.torsion_envelope is None and all(row.torsion is None for row in r.rows)
