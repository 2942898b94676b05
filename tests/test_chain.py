"""One chain of models: the pillar model the study chose feeds the ROM, with its error bars.

Sources and tolerances
----------------------
- The choice is read from a convergence study (a document of the same shape
  as ``convergence.json``, made here so the test needs no 3D run): a 3D choice
  is the ROM's mode source; a beam or a shell choice leaves `modal` on the
  cheapest 3D run within the tolerance; a study run for another tube is not
  used.  Exact comparisons: these are rules, not numerics.
- The ROM with one pillar mode of mass m_A and stiffness c1 has the stiffness
  matrix of Eq. 4, so its X resonances are Eq. 5's (``omega_pair``) to
  round-off (1e-10 relative: an eigen-solve of a 2x2 problem).
- A pillar frequency error delta moves each coupled resonance by at most
  delta times its own frequency (the rotor on its shaft dilutes it; the
  vertical mode does not see the pillar at all): the discretisation error bar
  is bounded by it and is zero in the vertical direction.
- The 3D modes of the scene's mesh (slow): the loaded tube's first X bending
  frequency within 1 % of the Timoshenko beam's with the gondola (the default
  mesh's bending error is 1.5e-3 and Timoshenko's model error under 1e-3, see
  docs/converge.md), and the disk cache returns the same arrays bit for bit.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from convergence_doc import convergence_doc

from rotorpillar import records
from rotorpillar.analysis import AnalysisResult, analyze
from rotorpillar.analysis.rom import rom_of
from rotorpillar.chain import ChainModes, PillarModel, TipReductionOf, Uncertain, choose
from rotorpillar.chain.choice import study_on_disk
from rotorpillar.chain.modes import chain_modes
from rotorpillar.reduced.pillar_modes import PillarModes, beam_pillar_modes
from rotorpillar.reduced.system import omega_pair, paper_example
from rotorpillar.scene import load_scene, override


def _run(label, family, model, params, dofs, wall, bending, ovalling=None):
    return {
        "label": label,
        "family": family,
        "model": model,
        "params": params,
        "dofs": dofs,
        "wall_time": wall,
        "status": "ok",
        "bending": 30.8,
        "ovalling": 85.0,
        "bending_error_bound": bending,
        "ovalling_error_bound": ovalling,
        "bending_error": bending,
        "ovalling_error": ovalling,
        "bending_model_error": 0.0,
        "ovalling_model_error": 0.0,
        "bending_discretisation_error": bending,
        "ovalling_discretisation_error": ovalling,
    }


SOLID = {
    "elements_around": 128,
    "elements_along": 20,
    "elements_through": 1,
    "cell_type": "hexahedron",
    "degree": 2,
    "grading": 30.0,
}
COARSE = {**SOLID, "elements_around": 64, "elements_along": 10}


def _study_doc(scene, chosen: dict, runs: list[dict]) -> dict:
    return convergence_doc(
        scene,
        runs,
        {
            "bending": {"value": 30.8, "error_estimate": 3.08e-3},
            "ovalling": {"value": 85.0, "error_estimate": 8.5e-3},
        },
        chosen=chosen,
    )


def _write(tmp_path, doc):
    (tmp_path / "convergence.json").write_text(json.dumps(doc))
    return tmp_path


def test_a_3d_choice_is_the_roms_mode_source_with_the_studys_error(tmp_path):
    s = load_scene("paper")
    chosen = _run("3D P2 hexahedra, 128x20x1", "solid_hex_p2", "solid", SOLID, 94464, 6.4, 3e-4, 6e-4)
    runs = [chosen, _run("3D P2 hexahedra, 64x10x1", "solid_hex_p2", "solid", COARSE, 24192, 1.5, 1.5e-3, 8.7e-3)]
    c = choose(s, _write(tmp_path, _study_doc(s, chosen, runs)))
    assert c.rom == c.solid and c.rom.kind == "solid" and c.rom.source == "converge"
    assert c.rom.mesh == SOLID and c.rom.verified
    # the error bound plus the reference's own uncertainty (3.08e-3 / 30.8 = 1e-4)
    assert c.rom.bending_error == pytest.approx(3e-4 + 1e-4)
    assert c.solid_mesh.elements_around == 128


def test_a_beam_choice_feeds_the_rom_and_leaves_modal_on_the_cheapest_3d_mesh(tmp_path):
    s = load_scene("paper")
    beam = _run(
        "beam Timoshenko (linear), 16 el.",
        "beam_timoshenko",
        "beam",
        {"theory": "timoshenko", "elements": 16},
        32,
        0.001,
        2e-4,
    )
    runs = [
        beam,
        _run("3D P2 hexahedra, 64x10x1", "solid_hex_p2", "solid", COARSE, 24192, 1.5, 1.5e-3),
        _run("3D P2 hexahedra, 128x20x1", "solid_hex_p2", "solid", SOLID, 94464, 6.4, 3e-4),
    ]
    doc = _study_doc(s, beam, runs)
    doc["band"]["omega_max"] = 60.0  # no shell mode in the band: a beam can serve
    c = choose(s, _write(tmp_path, doc))
    assert c.rom.kind == "beam" and c.rom.mesh == {"theory": "timoshenko", "elements": 16}
    assert c.solid.kind == "solid" and c.solid.mesh == SOLID  # 64x10 misses the tolerance
    modes = chain_modes(s, c, 180.0)
    assert modes.modes.source == "beam:timoshenko:16"


def test_a_shell_choice_uses_the_3d_mesh_within_the_same_tolerance_and_says_why(tmp_path):
    s = load_scene("paper")
    shell = _run(
        "shell Q2 quadrilaterals, 16x20",
        "shell_quad",
        "shell",
        {"elements_around": 16, "elements_along": 20, "cell_type": "quadrilateral", "degree": 2},
        6600,
        0.45,
        2e-4,
        4e-4,
    )
    runs = [shell, _run("3D P2 hexahedra, 128x20x1", "solid_hex_p2", "solid", SOLID, 94464, 6.4, 3e-4, 6e-4)]
    c = choose(s, _write(tmp_path, _study_doc(s, shell, runs)))
    assert c.rom.kind == "solid" and c.rom.mesh == SOLID
    assert "shell" in c.rom.note and "no top mass" in c.rom.note


def test_a_study_of_another_tube_is_not_used(tmp_path):
    s = load_scene("paper")
    chosen = _run("3D P2 hexahedra, 128x20x1", "solid_hex_p2", "solid", SOLID, 94464, 6.4, 3e-4, 6e-4)
    other = override(s, ["pillar.height=25"])
    _write(tmp_path, _study_doc(other, chosen, [chosen]))
    study, why = study_on_disk(s, tmp_path)
    assert study is None and "pillar.height" in why
    c = choose(override(s, ["modal_model.source=beam"]), tmp_path)
    assert c.rom.source == "scene" and not c.rom.verified


def test_pillar_modes_round_trip_and_scale():
    paper = load_scene("paper")
    pm = beam_pillar_modes(paper.pillar, paper.gondola.mass, 3, elements=10)
    back = records.convert(json.loads(json.dumps(records.to_builtins(pm))), PillarModes)
    for name in ("omega", "modal_mass", "participation", "shapes", "heights"):
        np.testing.assert_array_equal(getattr(back, name), getattr(pm, name))
    up = pm.scaled(1.01)
    np.testing.assert_allclose(up.omega, 1.01 * pm.omega, rtol=1e-15)
    np.testing.assert_allclose(up.modal_stiffness, 1.01**2 * pm.modal_stiffness, rtol=1e-14)


def _one_mode_chain(scene, m_A: float, c1: float, delta=None) -> ChainModes:
    modes = PillarModes(
        np.array([math.sqrt(c1 / m_A)]), np.array([m_A]), np.array([m_A]), m_A, "test", None, None, None
    )
    errors = {} if delta is None else {"bending": delta}
    pm = PillarModel("beam", "one mode", {}, 1, "scene", delta is not None, None, errors, "test")
    return ChainModes(pm, modes, TipReductionOf(m_A, c1, math.sqrt(c1 / m_A), "test"))


def test_rom_with_one_mode_has_eq5s_resonances():
    s = load_scene("paper")
    p = paper_example()
    chain = _one_mode_chain(s, p.tip_mass, p.pillar_stiffness)
    rom = rom_of(s, chain, 1)
    x = [r.omega for r in rom.quasi_normal() if r.direction == "X"]
    assert x == pytest.approx(list(omega_pair(p)), rel=1e-10)


def test_error_bars_are_bounded_by_the_pillar_frequency_error():
    s = load_scene("paper")
    p = paper_example()
    delta = 2e-3
    a = analyze(s, _one_mode_chain(s, p.tip_mass, p.pillar_stiffness, delta))
    for r in a.resonances:
        bar = r.uncertainty.omega
        assert bar.value == r.omega
        if r.direction == "Y":
            assert bar.sources["discretisation"] == 0.0  # the rotor on its shaft alone
        else:
            assert 0 < bar.sources["discretisation"] <= delta * r.omega * (1 + 1e-9)
        assert "truncation" in bar.unassessed  # one mode: no more to add
    assert a.paper_model.system.omega == pytest.approx(omega_pair(p), rel=1e-12)
    doc = json.loads(json.dumps(records.to_builtins(a)))
    assert records.to_builtins(records.convert(doc, AnalysisResult)) == doc


def test_uncertain_sums_the_magnitudes_and_names_what_was_not_assessed():
    u = Uncertain.of(10.0, "m", discretisation=-0.2, truncation=0.05, integration=None)
    assert u.error == pytest.approx(0.25) and u.unassessed == ("integration",)
    assert "±" in u.text()


@pytest.mark.slow
def test_3d_modes_of_the_scene_mesh_match_the_beam_and_are_cached(tmp_path, monkeypatch):
    monkeypatch.setenv("ROTORPILLAR_CACHE", str(tmp_path / "cache"))
    s = load_scene("paper")
    c = choose(s, None)
    assert c.rom.kind == "solid" and c.rom.source == "scene" and not c.rom.verified
    first = chain_modes(s, c, 180.0)
    assert first.seconds > 0 and first.modes.count >= 3  # the band's 2 modes and one more
    beam = beam_pillar_modes(s.pillar, s.gondola.mass, 2, "timoshenko", 80)
    assert first.modes.omega[0] == pytest.approx(beam.omega[0], rel=1e-2)
    again = chain_modes(s, c, 180.0)
    assert again.seconds == 0.0 and again.cache_file == first.cache_file
    np.testing.assert_array_equal(again.modes.omega, first.modes.omega)
    np.testing.assert_array_equal(again.modes.participation, first.modes.participation)
    assert again.reduction == first.reduction
    # another structural damping ratio: the same solve read back, each spatial mode carrying
    # the new ratio (it labels the modes; the eigenproblem is undamped)
    damped = override(s, ["pillar.damping_ratio=0.02"])
    other = chain_modes(damped, choose(damped, None), 180.0)
    assert other.seconds == 0.0 and other.cache_file == first.cache_file
    assert first.spatial is not None and other.spatial is not None
    np.testing.assert_array_equal(other.spatial.omega, first.spatial.omega)
    assert np.all(other.spatial.damping_ratio == 0.02)
    assert np.all(first.spatial.damping_ratio == s.pillar.damping_ratio) and s.pillar.damping_ratio != 0.02


def test_a_study_for_another_drive_stands_when_its_band_holds_the_same_modes(tmp_path):
    """The ladder solves the bare tube's first bending and ovalling modes whatever the band;
    the drive moves only the band's top (margin x free speed) and with it which of them the
    choice asks.  paper's band (134.6 rad/s) holds bending (30.8) and ovalling (85.0): a
    stall torque 10 % higher keeps both (the study stands and says so); one that puts the top
    below 85 rad/s drops ovalling (the study is not used, and the line says why)."""
    s = load_scene("paper")
    from rotorpillar.reduced.band import excitation_band

    chosen = _run("3D P2 hexahedra, 128x20x1", "solid_hex_p2", "solid", SOLID, 94464, 6.4, 3e-4, 6e-4)
    doc = _study_doc(s, chosen, [chosen])
    # what the study writes for its band: the reference's modes below its top
    top = excitation_band(s.drive, s.load, s.converge).omega_max
    doc["selection"]["needed"] = [q for q in ("bending", "ovalling") if doc["reference"][q]["value"] <= top]
    assert doc["selection"]["needed"] == ["bending", "ovalling"]
    _write(tmp_path, doc)
    stronger = override(s, [f"drive.torque_at_zero={s.drive.torque_at_zero * 1.1}"])
    study, why = study_on_disk(stronger, tmp_path)
    assert study is not None and "another drive" in why and "same modes" in why
    rom = choose(stronger, tmp_path).rom
    assert rom.source == "converge" and "run for another drive" in rom.note and "134.6" in rom.note
    # free speed ~ M0 / s on paper (its load is light): a top of 1.5 x 50 = 75 rad/s < 85
    weaker = override(s, [f"drive.torque_at_zero={s.drive.slope * 50}"])
    assert excitation_band(weaker.drive, weaker.load, weaker.converge).omega_max < 85.0
    study, why = study_on_disk(weaker, tmp_path)
    assert study is None and "bending, ovalling" in why and "holds bending;" in why
