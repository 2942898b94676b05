"""The verdict (summary.json), `rotorpillar harmonic` and the report's engineering sections.

What is checked, and against what:
- `harmonic --no-fem3d`: the running speed is the ROM's operating speed
  (reduced.stationary: the same function, another path: through the CLI
  and the JSON); every row's margins are API 684's formulas of the AF of
  its unbalance response's peak (no peak: none required);
- the summary's checks against the run's own peaks and the scene's
  capacities: utilisation = demand / capacity exactly; a clearance below
  the El Centro shaft deflection (27 mm) fails, a force limit above its
  force (11 kN) passes; with no capacity stated: "not assessed", never
  passed; the verdict "fail" when one check fails;
- `report` writes summary.json (the typed record reads it back) and opens
  the Summary with the checks table, each row naming model and case.
"""

import json

import pytest
from conftest import cli_here

from rotorpillar import records
from rotorpillar.reduced.margins import required_margin
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.stationary import operating_speed
from rotorpillar.scene import load_scene, override
from rotorpillar.transients.files import write_model_files
from rotorpillar.transients.model_run import run_model
from rotorpillar.verdict.harmonic import HarmonicResult
from rotorpillar.verdict.summary import EngineeringSummary, engineering_summary

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow

QUAKE = ["excitation.kind=record", "simulate.earthquake_duration=12"]


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    """The ROM's El Centro (12 s) and the harmonic stage (ROM only) in one directory."""
    d = tmp_path_factory.mktemp("verdict")
    scene = override(load_scene("paper"), QUAKE)
    write_model_files(d, scene, run_model(scene, "earthquake", "modal"), {}, last_run=False)
    p = cli_here("harmonic", "paper", "--no-fem3d", "--out", d)  # in this process: its files are what is read
    assert p.returncode == 0, p.stderr
    return d


def test_harmonic_rom_only(out):
    from rotorpillar.chain import resolve

    r = records.read(out / "harmonic.json", HarmonicResult)
    scene = load_scene("paper")
    # the harmonic stage's ROM is the chain's, as every stage's: the same modes here
    chain = resolve(scene, out)
    assert r.pillar_model == chain.pillar_model
    model, _ = build_model(scene, "modal", r.band_top, pillar_modes=chain.modes)
    d, L = scene.drive, scene.load
    assert r.running_speeds[-1] == pytest.approx(
        operating_speed(model, d.torque_at_zero, d.slope, L.coefficient), rel=1e-9
    )
    assert r.fem3d is None and len(r.rom.speeds) > 100
    assert {m.model for m in r.modes} == {"modal"}  # no modal.json beside: the ROM's modes only
    assert any("modal.json" in n for n in r.notes)
    # API 684: each row's AF is its response peak's half-power AF; no peak, no margin
    assert r.spatial is not None and any(p.amplification_factor for c in r.spatial.curves for p in c.peaks)
    for row in r.separation:
        if row.amplification_factor is None:
            assert row.required == 0.0 and "no peak" in row.af_source
        else:
            assert row.required == pytest.approx(required_margin(row.amplification_factor, row.position == "below"))
            assert "half-power" in row.af_source and row.peak_speed is not None
        assert row.status == ("pass" if row.actual >= row.required else "fail")


def test_checks_against_capacities(out):
    s = engineering_summary(override(load_scene("paper"), ["rotor.clearance=0.01", "shaft.force_limit=2e4"]), out)
    by = {c.name: c for c in s.checks}
    stress = by["base stress vs yield"]
    doc = json.loads((out / "simulate_earthquake_modal.json").read_text())
    assert stress.demand == doc["max_abs"]["base_stress"]
    assert stress.utilisation == pytest.approx(stress.demand / 355e6, rel=1e-12)
    assert (stress.model, stress.case) == ("modal", "earthquake (elcentro)")
    assert by["shaft deflection vs clearance"].status == "fail"  # 27 mm against 10 mm
    assert by["shaft force vs force limit"].status == "pass"  # 11 kN against 20 kN
    assert by["base stress vs shell buckling"].capacity == pytest.approx(s.buckling.design_stress)
    assert s.verdict == "fail"
    plain = engineering_summary(load_scene("paper"), out)
    assert {c.name: c.status for c in plain.checks}["shaft deflection vs clearance"] == "not assessed"
    assert any("rotor.clearance" in x for x in plain.not_assessed)


def test_report_writes_summary_and_opens_with_the_verdict(out, here):
    p = here("report", "paper", "--out", out, "--no-animations")
    assert p.returncode == 0, p.stderr
    s = records.read(out / "summary.json", EngineeringSummary)
    assert s.scene == "paper" and s.checks
    html = (out / "report.html").read_text()
    summary = html[html.index('<section id="answer">') :]
    assert summary.index("Verdict:") < summary.index("</section>")
    assert "base stress vs shell buckling" in summary and "earthquake (elcentro)" in summary
    assert '<section id="forces">' in html and '<section id="unbalance">' in html


def test_campbell_headlines_pick_the_first_of_each_whirl_per_model(tmp_path):
    """summary.json's Campbell headlines: the lowest critical speed of each whirl and the lowest
    the static unbalance excites, for the ROM and the 3D model beside it; None where none."""
    from rotorpillar.provenance import write_result
    from rotorpillar.records import replace
    from rotorpillar.reduced.campbell import CriticalSpeed, campbell_example

    rom = campbell_example()
    # a 3D diagram whose crossings are all lines (no whirl): its forward and backward are None
    fem3d = replace(
        rom,
        model="fem3d",
        critical_speeds=(CriticalSpeed(29.0, "bending 1", "none", "static unbalance"),),
    )
    head = {"command": "campbell", "scene_source": "paper", "overrides": [], "scene": {"name": "paper"}}
    write_result(tmp_path / "campbell.json", replace(rom, fem3d=fem3d), head)
    s = engineering_summary(load_scene("paper"), tmp_path)
    h = {x.key: x for x in s.headlines}
    assert "campbell.json" in s.inputs
    # campbell_example: backward at 30 / 1.05, forward (static unbalance) at 30 / 0.95
    assert h["first_backward_critical_speed_modal"].value == pytest.approx(30 / 1.05)
    assert h["first_forward_critical_speed_modal"].value == pytest.approx(30 / 0.95)
    assert h["first_unbalance_critical_speed_modal"].value == pytest.approx(30 / 0.95)
    assert h["first_forward_critical_speed_fem3d"].value is None
    assert "none up to 100.0 rad/s" in h["first_forward_critical_speed_fem3d"].text
    assert h["first_unbalance_critical_speed_fem3d"].value == 29.0
