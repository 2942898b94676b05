"""The transients' internal forces (rotorpillar.transients.forces), on the paper's El Centro.

References and tolerances:
- the ROM's base moment, superposed from the modes its truncation check
  asks for (1 % over the band), against the full-order beam's own element
  end forces on the same case (10 Timoshenko elements, Newmark at 40 steps
  per forcing period, whose period error in the upper modes is the other
  difference): peak within 1 % (measured 0.2 %), history within 1 % of the
  peak (measured 0.5 %);
- the ROM with more of the beam's modes closes on the beam: with 12 of its
  20 modes the peak base moment within 0.1 % (measured 0.02 %);
- the base stress is M c / I + N / A of the base history itself (exact);
- the static axial force N(0) = g (m_rho H + m* + m_C) (exact), and the
  rotor's vertical pull moves it by c2 |d_y| at most;
- the files: the CSV holds the new columns after the old ones (no comment
  line added), the NPZ the section histories.
"""

import csv

import numpy as np
import pytest

from rotorpillar import records
from rotorpillar.reduced.internal_forces import STANDARD_GRAVITY, extreme_fibre_stress
from rotorpillar.reduced.pillar import section_of
from rotorpillar.scene import load_scene, override
from rotorpillar.transients.files import write_model_files
from rotorpillar.transients.model_run import run_model

# seconds each: a whole command (or several) per test; the slow tier runs it (conftest's rule)
pytestmark = pytest.mark.slow

SCENE = [
    "excitation.kind=record",
    "simulate.earthquake_duration=12",
    "modal_model.elements=10",
    "modal_model.source=beam",  # the ROM on the beam's own modes: the beam is its full order
    "full_order.beam_elements=10",
]


@pytest.fixture(scope="module")
def scene():
    return override(load_scene("paper"), SCENE)


@pytest.fixture(scope="module")
def beam(scene):
    return run_model(scene, "earthquake", "beam")


@pytest.fixture(scope="module")
def rom(scene):
    return run_model(scene, "earthquake", "modal")


def test_rom_base_moment_against_the_full_order_beam(rom, beam):
    f = records.to_builtins(rom.record)["internal_forces"]
    assert f["modes"] >= f["truncation"]["modes_needed_base_moment"]
    assert f["modes"] > f["modes_in_run"]  # the paper's band keeps 2; the moment needs 3
    ma, mb = records.to_builtins(rom.record)["max_abs"], records.to_builtins(beam.record)["max_abs"]
    assert ma["base_moment"] == pytest.approx(mb["base_moment"], rel=1e-2)
    M = np.interp(beam.data["t"], rom.data["t"], rom.data["base_moment"])
    assert np.max(np.abs(M - beam.data["base_moment"])) <= 1e-2 * mb["base_moment"]
    assert ma["base_moment"] > 5e5  # El Centro bends the paper's pillar: ~1.1 MN m


def test_more_modes_close_on_the_beam(scene, beam):
    run = run_model(scene, "earthquake", "modal", modes=12)
    assert records.to_builtins(run.record)["internal_forces"]["modes"] == 12
    assert records.to_builtins(run.record)["max_abs"]["base_moment"] == pytest.approx(
        records.to_builtins(beam.record)["max_abs"]["base_moment"], rel=1e-3
    )


def test_base_stress_and_axial_force(scene, rom):
    sec = section_of(scene.pillar)
    d = rom.data
    assert d["base_stress"] == pytest.approx(extreme_fibre_stress(d["base_moment"], d["base_axial"], sec))
    N0 = STANDARD_GRAVITY * (sec.mass_per_length * scene.pillar.height + scene.gondola.mass + scene.rotor.mass)
    pull = scene.shaft.stiffness * np.max(np.abs(d["rotor_y"])) + scene.shaft.stiffness * scene.rotor.eccentricity
    assert np.all(np.abs(d["base_axial"] - N0) <= pull)
    f = records.to_builtins(rom.record)["internal_forces"]
    assert f["axial_static"][0] == pytest.approx(N0, rel=1e-12)
    assert records.to_builtins(rom.record)["max_abs"]["base_stress"] >= np.max(d["base_stress"]) * (1 - 1e-12)
    assert len(f["moment_envelope"]) == len(f["heights"]) and f["moment_envelope"][0] == pytest.approx(
        records.to_builtins(rom.record)["max_abs"]["base_moment"], rel=1e-2
    )


def test_shaft_demand(scene, rom):
    s = records.to_builtins(rom.record)["internal_forces"]["shaft"]
    assert s["deflection"] >= records.to_builtins(rom.record)["max_abs"]["shaft_deflection_x"] * (1 - 1e-9)
    assert s["spring_force"] == pytest.approx(scene.shaft.stiffness * s["deflection"])
    assert records.to_builtins(rom.record)["max_abs"]["bearing_force"] == s["bearing_force"] > 0


def test_files_carry_the_force_histories(tmp_path, scene, rom):
    write_model_files(tmp_path, scene, rom, {}, last_run=False)
    with open(tmp_path / "simulate_earthquake_modal.csv") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
    header = rows[0]
    for col in ("base_moment", "base_shear", "base_axial", "base_stress", "bearing_force"):
        assert col in header
    assert header.index("base_moment") > header.index("shaft_deflection_x")
    z = np.load(tmp_path / "simulate_earthquake_modal.npz")
    assert z["section_moment"].shape == (len(z["t"]), len(z["section_heights"]))
    assert z["section_moment"][:, 0] == pytest.approx(z["base_moment"])


def test_paper_model_has_no_sections(scene):
    run = run_model(scene, "earthquake", "paper")
    assert records.to_builtins(run.record)["internal_forces"] is None
    assert records.to_builtins(run.record)["max_abs"]["base_moment"] is None
    assert records.to_builtins(run.record)["max_abs"]["shaft_deflection"] > 0
