"""The full order's reference mesh for a transient (rotorpillar.transients.references,
rotorpillar.converge.selection.select_reference) and the run-up's window
(rotorpillar.transients.window).

- participation: the bookkeeping on synthetic modes (a share is its definition:
  L**2 / m over the carried mass, phi_plate**2 / (m omega**2) over the closed-form
  compliance), and on the 3D tube (slow) against two independent facts: the
  symmetric modes take no part (round-off, < 1e-12), and the first bending mode's
  effective mass L**2 / m is the 1D Timoshenko beam's (1 % : the 8 x 10 mesh's
  bending error is 1.5e-3, the beam's shear model 1e-4; their mode shapes agree
  to the same order, and the fraction is quadratic in the shape);
- the choice: the coarsest run that meets the bound, the ROM source's floor, a
  study of another tube ignored, the [full_order] overrides;
- the window: from 0.7 x the lowest resonance, every model from the same state
  (the held whirl: a steady solution on a rigid pillar, checked by integrating it).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from conftest import cli_here
from convergence_doc import convergence_doc

from rotorpillar import records
from rotorpillar.converge.result import ERROR_KINDS, ConvergenceStudy, ModeSourceFloor
from rotorpillar.converge.selection import select_reference
from rotorpillar.fem3d.modal import ModeRow
from rotorpillar.records import replace
from rotorpillar.scene import load_scene, override
from rotorpillar.transients.references import PARTICIPATION_FLOOR, choose_reference, participation_table, read_study
from rotorpillar.transients.window import START_FRACTION, runup_window, window_scene

has_dolfinx = pytest.mark.skipif(__import__("importlib").util.find_spec("dolfinx") is None, reason="needs dolfinx")
TOTAL, COMPLIANCE = 22_000.0, (1e-7, 1e-9)


def _row(i, kind, omega, m, L=(0.0, 0.0, 0.0), plate=(0.0, 0.0, 0.0), n=None, m_ax=0):
    # what the bookkeeping reads: omega, modal mass, L, the plate's motion, the names
    return ModeRow(
        index=i,
        omega=omega,
        frequency_hz=omega / (2 * math.pi),
        kind=kind,
        n_circumferential=n,
        n_axial=m_ax,
        harmonic_share=1.0,
        normalisation="unit_tip" if kind.startswith("bending") else "unit_max",
        modal_mass=m,
        modal_stiffness=m * omega**2,
        tip_displacement=(0.0, 0.0),
        top_plate_motion=tuple(plate) + (0.0,) * 3,
        participation=tuple(L),
    )


ROWS = [
    _row(0, "bending_x", 25.0, 7000.0, (10_000.0, 0, 0), (1.0, 0, 0), n=1),
    _row(1, "bending_y", 25.0, 7000.0, (1e-13, 10_000.0, 0), (0, 1.0, 0), n=1),
    _row(2, "ovalling", 108.0, 4800.0, (1e-12, 1e-13, 0), (1e-17, 0, 1e-18), n=2),
    _row(3, "bending_x", 157.0, 14_000.0, (-8000.0, 0, 0), (1.0, 0, 0), n=1, m_ax=1),
    _row(4, "axial", 120.0, 9000.0, (0, 0, 9000.0), (0, 0, 1.0), n=0),
]


def test_participation_earthquake_keeps_bending_x_only():
    t = participation_table(ROWS, "earthquake", 134.6, TOTAL, COMPLIANCE, source="test", mesh={})
    assert t.participating == (0,) and t.left_out == (1, 2, 4)
    assert t.quantities == ("bending",) and t.uncovered == ()
    assert math.isclose(t.modes[0].shares["base_x"], 10_000.0**2 / 7000.0 / TOTAL, rel_tol=1e-12)
    assert math.isclose(t.modes[0].shares["plate_x"], 1.0 / (7000.0 * 25.0**2) / COMPLIANCE[0], rel_tol=1e-12)
    assert not t.modes[3].in_band and t.modes[3].participates  # out of the band: not needed
    assert all(max(t.modes[i].shares.values()) < PARTICIPATION_FLOOR for i in t.left_out)
    assert "take no part" in t.statement and "ovalling n = 2" in t.statement


def test_participation_runup_sees_the_axial_mode_and_says_the_study_misses_it():
    t = participation_table(ROWS, "runup", 134.6, TOTAL, COMPLIANCE, source="test", mesh={})
    assert t.participating == (0, 4)  # the shaft's force along the axis
    assert t.quantities == ("bending",) and len(t.uncovered) == 1 and "axial" in t.uncovered[0]
    assert "bounds no frequency of axial" in t.statement


def _run(family, around, along, dofs, bound, model_err=0.0, wall=1.0):
    return {
        "family": family,
        "label": f"{family} {around}x{along}",
        "status": "ok",
        "dofs": dofs,
        "wall_time": wall,
        "model": "solid",
        "bending": 30.8 * (1 + bound),
        "bending_error": bound,
        "bending_model_error": model_err,
        "bending_discretisation_error": bound - model_err,
        "bending_error_bound": bound,
        "params": {
            "elements_around": around,
            "elements_along": along,
            "elements_through": 1,
            "degree": 2,
            "cell_type": "hexahedron",
            "grading": 30.0,
        },
    }


RUNS = [
    _run("solid_hex_p2_along", 8, n, 300 * n, b, -1.7e-4)
    for n, b in ((5, 1.4e-2), (10, 1.7e-3), (15, 7.2e-4), (20, 4.7e-4), (40, 2.5e-4))
]
RUNS += [_run("solid_hex_p2", 128, 20, 94_464, 3.1e-4), _run("solid_hex_p2", 224, 35, 286_272, 1e-4)]
REFERENCE = {"bending": {"value": 30.818, "error_estimate": 30.818 * 1.4e-4}}


def _study():
    """RUNS and REFERENCE as a study on disk reads (its runs and reference records)."""
    return records.convert(convergence_doc(load_scene("paper"), RUNS, REFERENCE), ConvergenceStudy)


def test_select_reference_coarsest_meeting_the_bound():
    study = _study()
    runs, reference = study.runs, study.reference
    c = select_reference(runs, reference, ("bending",), 1e-3, max_dofs=12_000)
    assert c.params["elements_along"] == 15 and c.meets
    assert math.isclose(c.band_error, 7.2e-4 + 1.4e-4, rel_tol=1e-9)
    # a ROM whose modes are better than that: the reference must be at least as good
    c = select_reference(runs, reference, ("bending",), 1e-3, floor=ModeSourceFloor("rom", 7e-4), max_dofs=12_000)
    assert c.params["elements_along"] == 20 and c.meets and c.required == 7e-4
    # out of reach within the transient's DOFs: the most accurate, and said so
    c = select_reference(runs, reference, ("bending",), 1e-3, floor=ModeSourceFloor("rom", 2e-4), max_dofs=12_000)
    assert c.params["elements_along"] == 40 and not c.meets and "only to the reference's own" in c.reason
    # what the case's steps afford caps that refinement
    c = select_reference(
        runs,
        reference,
        ("bending",),
        1e-3,
        floor=ModeSourceFloor("rom", 2e-4),
        max_dofs=12_000,
        floor_max_dofs=7_000,
    )
    assert c.params["elements_along"] == 20 and not c.meets and "within 7,000 DOFs" in c.reason
    # without the DOFs cap the fine solid run would do
    c = select_reference(runs, reference, ("bending",), 1e-3, floor=ModeSourceFloor("rom", 2.5e-4))
    assert c.params["elements_around"] == 224
    assert select_reference(runs, reference, ("bending",), 1e-4) is None


def _study_on_disk(tmp_path, scene, runs=RUNS):
    doc = convergence_doc(
        scene,
        runs,
        REFERENCE,
        extrapolations={"beam_timoshenko": {"bending": {"value": 30.8208}}},
        selection={"reason": "none meets it"},
    )
    (tmp_path / "convergence.json").write_text(json.dumps(doc))
    modes = [records.to_builtins(r) for r in ROWS]
    (tmp_path / "modal.json").write_text(json.dumps({"scene": scene.to_dict(), "modes_with_top": modes}))


def test_choose_reference_from_the_study_on_disk(tmp_path):
    # the ROM's modes from the 40-element beam (stated): its error is the run-up's floor
    scene = load_scene("paper", ["modal_model.source=beam"])
    _study_on_disk(tmp_path, scene)
    mesh, ref = choose_reference(scene, "earthquake", tmp_path)
    assert (mesh.elements_around, mesh.elements_along) == (8, 15) and ref.source == "converge"
    assert ref.verified and ref.participation.source == "modal.json" and ref.quantities == ("bending",)
    assert (
        "error bound on the frequencies the load excites is 8.6e-04" in ref.statement
        and "take no part" in ref.statement
    )
    # the run-up: at least as fine as the ROM's modes (the 40-element Timoshenko beam, its
    # error computed against this study: ~1.6e-4 + the reference's 1.4e-4)
    mesh, ref = choose_reference(scene, "runup", tmp_path)
    assert ref.floor.label.startswith("beam Timoshenko") and ref.floor.band_error < 4e-4
    assert mesh.elements_along == 40 and ref.meets is False
    # errors and floor serialise as the dicts they were (compare_<case>.json's full_order_reference)
    run = next(r for r in _study().runs if r.label == ref.label)
    doc = records.to_builtins(ref)
    assert doc["floor"] == {"label": ref.floor.label, "band_error": ref.floor.band_error}
    assert doc["errors"] == {
        q: {"value": run.frequency(q), **{k: run.relative_error(q, k) for k in ERROR_KINDS}} for q in ref.quantities
    }
    assert list(doc["errors"]["bending"]) == ["value", *ERROR_KINDS]
    assert records.convert(json.loads(json.dumps(doc)), type(ref)) == ref
    # a long run-up (5,000 steps) affords 8,000 DOFs (REFERENCE_DOF_STEPS): 8 x 20, said so
    mesh, ref = choose_reference(scene, "runup", tmp_path, steps=5_000)
    assert mesh.elements_along == 20 and ref.meets is False and "afford" in ref.reason
    # explicit [full_order] keys override the choice; the study's error goes with the mesh
    mesh, ref = choose_reference(override(scene, ["full_order.elements_along=20"]), "earthquake", tmp_path)
    assert mesh.elements_along == 20 and ref.overrides == ("elements_along",) and ref.verified
    mesh, ref = choose_reference(override(scene, ["full_order.elements_along=12"]), "earthquake", tmp_path)
    assert mesh.elements_along == 12 and not ref.verified and ref.band_error is None


def test_a_study_of_another_tube_is_not_used(tmp_path):
    scene = load_scene("paper")
    _study_on_disk(tmp_path, override(scene, ["pillar.height=25"]))
    assert read_study(scene, tmp_path) is None
    mesh, ref = choose_reference(scene, "earthquake", tmp_path)
    assert ref.source == "scene" and not ref.verified and "no convergence study" in ref.reason
    assert (mesh.elements_around, mesh.elements_along) == (8, scene.mesh.elements_along)
    # the pillar's damping does not change the study's runs: still this tube's study
    _study_on_disk(tmp_path, override(scene, ["pillar.damping=10e3"]))
    assert read_study(scene, tmp_path) is not None


@pytest.mark.parametrize("name", ["paper", "sommerfeld"])
def test_runup_window(name):
    scene = load_scene(name)
    w = runup_window(scene)
    assert math.isclose(w.initial_speed, START_FRACTION * min(w.resonances), rel_tol=1e-12)
    assert 0 < w.start < w.end <= scene.simulate.duration and w.duration < scene.simulate.duration
    if name == "sommerfeld":  # captured at its first resonance (the scene's point)
        assert w.captured_resonance is not None and abs(w.captured_resonance - 22.76) < 0.1
        assert w.end > w.peak_time
    else:  # passes 14.9, 15.8 and 27.1 rad/s within its first second
        assert w.captured_resonance is None and len(w.passed) == 3 and w.end < 1.0
    run = window_scene(scene, w).simulate
    assert (run.runup_initial_speed, run.duration, run.threshold) == (w.initial_speed, w.duration, False)


def test_held_whirl_is_steady_on_a_rigid_pillar():
    """The rotor's whirl on a held structure (the window's start) is the steady
    solution when the pillar does not move: integrated at a prescribed speed under a
    gondola of 1e8 kg (its inertia m W**2 = 1.6e11 N/m against the shaft's 4e5 holds the
    tip to ~3e-6 of the whirl), the rotor stays on its circle."""
    from rotorpillar.reduced.drive import DriveSchedule
    from rotorpillar.reduced.excitation import no_motion
    from rotorpillar.reduced.integration import Settings, simulate
    from rotorpillar.reduced.models import build_model

    scene = override(load_scene("paper"), ["gondola.mass=1e8", "modal_model.source=beam"])
    model, _ = build_model(scene, "modal", modes=1)
    W = 40.0
    q0, v0 = model.held_whirl_state(W)
    assert np.all(q0[: model.nx - 1] == 0) and np.all(v0[: model.nx - 1] == 0)
    X = abs(complex(q0[model.rotor_x], q0[model.nx]))
    c2, m, b, e = scene.shaft.stiffness, scene.rotor.mass, scene.shaft.damping, scene.rotor.eccentricity
    assert math.isclose(X, c2 * e / abs(complex(c2 - m * W**2, W * b)), rel_tol=1e-12)
    run = simulate(
        model,
        DriveSchedule.constant(0, 0, 0),
        no_motion(),
        2.0,
        q0,
        v0,
        settings=Settings(rtol=1e-9),
        prescribed_speed=True,
        speed_scale=W,
    )
    r = np.hypot(run.q[:, model.rotor_x], run.q[:, model.nx])
    # the start's own transient is the held tip's ~3e-6 X; the integrator's 1e-9: 1e-4 is loose
    assert np.max(np.abs(r / X - 1)) < 1e-4


@pytest.mark.slow  # one 3D modal solve of the loaded tube, 8 x 10
@has_dolfinx
def test_participation_of_the_3d_modes():
    from rotorpillar.fem3d import modal_analysis
    from rotorpillar.reduced.pillar import section_of
    from rotorpillar.reduced.pillar_modes import beam_pillar_modes

    # equal roll and pitch inertias of the gondola: the two bending planes are the same mode turned
    scene = load_scene("paper", ["gondola.roll_inertia=850"])
    r = modal_analysis(scene, top=True, mesh=replace(scene.mesh, elements_around=8, elements_along=10))
    total = section_of(scene.pillar).mass_per_length * scene.pillar.height + r.top_mass
    eff = r.participation**2 / r.modal_mass[:, None] / total
    for i, kind in enumerate(r.kind):
        if kind != "bending_x":
            assert eff[i, 0] < 1e-12, (kind, eff[i])
    i1, j1 = r.kind.index("bending_x"), r.kind.index("bending_y")
    # the same mode turned by 90 degrees: the same share along its own axis
    assert math.isclose(eff[j1, 1], eff[i1, 0], rel_tol=1e-6)
    # the effective mass in kg (the beam's r^T M r leaves out its clamped node's mass)
    beam = beam_pillar_modes(scene.pillar, scene.gondola.mass, 1, "timoshenko", 40)
    assert math.isclose(
        r.participation[i1, 0] ** 2 / r.modal_mass[i1], beam.participation[0] ** 2 / beam.modal_mass[0], rel_tol=1e-2
    )


@pytest.mark.slow  # the 3D run-up over the window (0.7 s, 8 x 10): ~30 s
@has_dolfinx
def test_compare_runup_on_the_3d_full_order(tmp_path):
    # in this process (conftest.cli_here): the comparison's files are the checks
    p = cli_here(
        "compare",
        "paper",
        "--case",
        "runup",
        "--models",
        "modal,fem3d",
        "--set",
        "simulate.threshold=false",
        "--json",
        "--out",
        tmp_path,
    )
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "compare_runup.json").read_text())
    w = doc["window"]["runup"]
    assert doc["reference"] == "fem3d" and doc["window"]["duration"] == pytest.approx(w["duration"])
    runs = {m: json.loads((tmp_path / f"compare_runup_{m}.json").read_text()) for m in ("modal", "fem3d")}
    for m, r in runs.items():
        assert r["initial_speed"] == pytest.approx(w["initial_speed"], rel=1e-12), m
    ref = doc["full_order_reference"]
    assert ref["source"] == "scene" and ref["verified"] is False  # no study in tmp_path
    assert runs["fem3d"]["full_order"]["mesh"]["elements_around"] == 8
    # ROM against the 3D tube through three resonances: 0.6 % history, 0.4 % peak measured
    # on this mesh (its bending error 1.5e-3 shifts the passages' phase); tolerance 2 %
    assert doc["errors"]["modal"]["tip_history_error"] < 2e-2
    assert abs(doc["errors"]["modal"]["peak_tip_difference"]) < 2e-2


def test_the_ladder_has_the_bending_only_family():
    """Its rungs refine along only, at 8 around; its runs report bending alone, even a
    cached run it shares with the around-only sweep (8 x 10: the same mesh)."""
    from rotorpillar.converge.ladder import ALONG_FAMILY_AROUND, ALONG_LEVELS, ladder, resolved_only

    scene = load_scene("paper")
    rungs = [c for c in ladder(scene) if c.family == "solid_hex_p2_along"]
    assert [c.level for c in rungs] == list(ALONG_LEVELS)
    assert {c.settings["elements_around"] for c in rungs} == {ALONG_FAMILY_AROUND}
    shared = [
        c
        for c in ladder(scene)
        if c.family == "solid_hex_p2_around"
        and c.settings == next(r for r in rungs if r.level == scene.mesh.elements_along).settings
    ]
    assert len(shared) == 1  # one cached run, two families
    from rotorpillar.converge.result import ConvergenceRun

    case = shared[0]
    run = ConvergenceRun(
        key="k",
        family=case.family,
        model="solid",
        label=case.label,
        level=case.level,
        params=case.settings,
        status="ok",
        cached=False,
        bending=30.86,
        ovalling=696.0,
        ovalling_n=2,
    )
    along = resolved_only("solid_hex_p2_along", run)
    assert (along.bending, along.ovalling, along.ovalling_n) == (30.86, None, 2)
    assert resolved_only("solid_hex_p2_around", run) is run


def test_the_loaded_modes_computed_once_a_scene(monkeypatch, tmp_path):
    """Where modal.json is not this scene's, the loaded tube's table is computed, once per
    scene in a process (a comparison plans its 3D run three times): the second plan reads
    the first's table, the same rows; another scene computes its own."""
    import rotorpillar.fem3d as fem3d
    from rotorpillar.transients import references

    solved = []

    class Table:
        def __init__(self, scene):
            self.scene = scene

        def modes_table(self):
            return [("bending_x", 25.0 + self.scene.drive.torque_at_zero * 1e-6)]  # a row: its numbers

    def modal_analysis(scene, top):
        solved.append(scene.drive.torque_at_zero)
        return Table(scene)

    monkeypatch.setattr(fem3d, "modal_analysis", modal_analysis)
    monkeypatch.setattr(references, "_COMPUTED_ROWS", {})
    scene = load_scene("paper")
    first = references.loaded_mode_rows(scene, tmp_path)  # no modal.json there
    again = references.loaded_mode_rows(load_scene("paper"), tmp_path)
    assert first == again and first[1] == "computed" and solved == [scene.drive.torque_at_zero]
    other = override(scene, ["drive.torque_at_zero=5610"])
    assert references.loaded_mode_rows(other, tmp_path)[0] != first[0] and solved[-1] == 5610.0


def test_modal_json_serves_a_drive_whose_band_holds_the_same_modes(monkeypatch, tmp_path):
    """modal.json's loaded modes, cut at the band's edge (modal.n_modes = 0), are read for a
    scene with another stall torque when the cut at its edge is the same (reduced.band.
    cut_stands, as `run`'s key for modal reuses modal.json), labelled with the mesh they were
    computed on; a band that needs more modes, or another tube, computes its own."""
    import rotorpillar.fem3d as fem3d
    from rotorpillar.transients import references

    solved = []

    class Table:
        def modes_table(self):
            return [_row(0, "bending_x", 1.0, 1.0)]

    def modal_analysis(scene, top):
        solved.append(scene.drive.torque_at_zero)
        return Table()

    monkeypatch.setattr(fem3d, "modal_analysis", modal_analysis)
    monkeypatch.setattr(references, "_COMPUTED_ROWS", {})
    scene = load_scene("paper")  # band edge 134.6 rad/s; x 1.1: 141.9; x 3: 245.0
    assert scene.modal.n_modes == 0
    # eight modes, the last past 141.9 but not past 245: the cut stands at x 1.1, not at x 3
    rows = [
        records.to_builtins(_row(i, "bending_x", w, 7000.0))
        for i, w in enumerate((25, 25, 105, 105, 155, 155, 188, 200))
    ]
    chosen = {"elements_around": 128, "elements_along": 20, "elements_through": 1, "degree": 2}
    (tmp_path / "modal.json").write_text(json.dumps({"scene": scene.to_dict(), "modes_with_top": rows, "mesh": chosen}))
    t0 = scene.drive.torque_at_zero
    for factor, source in ((1.0, "modal.json"), (1.1, "modal.json"), (3.0, "computed")):
        got, src, mesh = references.loaded_mode_rows(override(scene, [f"drive.torque_at_zero={t0 * factor}"]), tmp_path)
        assert src == source, factor
        if src == "modal.json":
            assert [r.omega for r in got] == [r["omega"] for r in rows] and mesh == chosen
    assert solved == [3 * t0]
    # another top mass: modal.json is not this tube's modes
    got, src, mesh = references.loaded_mode_rows(override(scene, ["gondola.mass=31000"]), tmp_path)
    assert src == "computed" and mesh == dict(vars(scene.mesh))


def test_modal_json_is_read_on_the_sections_modals_key_reads():
    """references.MODES_READ (the sections modal.json's loaded modes must share with a scene
    to serve it) are the sections `run`'s key for modal reads (commands.stage_keys), its name
    aside: two lists of one fact, kept in step here (transients/ may not import commands/)."""
    from rotorpillar.commands.stage_keys import SECTIONS_NOT_READ
    from rotorpillar.transients.references import MODES_READ

    sections = set(load_scene("paper").to_dict())
    assert set(MODES_READ) == sections - SECTIONS_NOT_READ["modal"] - {"name"}
