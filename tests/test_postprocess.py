"""Renders, animations and charts of rotorpillar.postprocess, on synthetic inputs.

Sources and tolerances:
- Mode shapes: analytic tube modes (tests/fixtures.py): the
  Euler-Bernoulli cantilever shape (rotorpillar.reduced.pillar.cantilever_mode,
  normalised to a unit tip), an n = 2 ovalling, a torsion.  Deformation and
  superposition are exact arithmetic (1e-12).  Pictures are checked as files
  (PNG header size, decoded size, pixel spread > 8 grey levels: a blank
  render has ~0) and by one geometric property that a wrong camera or a
  missing deformation would break: in a bending mode's picture the tube's top
  sits sideways of its base by more than half the tube's drawn width, in the
  torsion mode's by less than a quarter.
  The tube fills its picture: its coloured rows span most of the height
  below the label.  An ovalling mode's picture holds its cross-sections (the
  right-hand view has coloured pixels; a bending mode's picture has one view).
- The quadratic VTU (a Gmsh tube's hexahedron27 cells, written as modal
  does): its drawn surface subdivides each face through the cells' shape
  functions, so a field quadratic along the height, u_x = z**2, comes back
  exact at points between the nodes (1e-6 relative: VTK's surface filter
  stores its points in float32), where a linear tessellation through the
  nodes would miss by (dz/2)**2 ~ 3 m**2 here.
- Animations: the frame count read back from the MP4 by ffmpeg equals the
  requested bound; frame size 880 x 560 (the 3D view beside the panel).
- Drive chart, main panel: its torque axis is the motor's range, HEADROOM
  times Md at rest (a falling characteristic is largest there), not the
  resonances far above it (sommerfeld: 18,000 N*m against a 600 N*m motor);
  each resonance whose own peak (analyze.json's dL_max, the averaging's
  maximum) exceeds it is marked at the top edge; no two labels' boxes as the
  renderer draws them (Text.get_window_extent) intersect, on three scenes.
- Drive chart: L(Omega) rebuilt from analyze.json's resonance parameters by
  the averaging closed forms against the curves analyze stored (1e-9
  relative, the same formulas); the stable/unstable switch points against the
  fold points analyse_drive finds by root finding (within 2 grid steps).
"""

import json
import math

import fixtures
import numpy as np
import pytest
from imagecheck import assert_real_png, labels_overlap, pixels, png_size

from rotorpillar import records
from rotorpillar.analysis import analyze
from rotorpillar.fem3d.modal_summary import ModalSummary
from rotorpillar.postprocess import charts, transient_charts
from rotorpillar.postprocess import html as h
from rotorpillar.postprocess.animation import animate
from rotorpillar.postprocess.animation_frames import elastic_field, frame_times, pillar_motion
from rotorpillar.postprocess.geometry import ModeLabel, bending_columns, cantilever_tube, load_modes, tube_axes
from rotorpillar.postprocess.modeshapes import (
    BEAM_TARGET,
    MODE_SIZE,
    SHEET_TILE,
    SPLIT,
    deformed,
    has_sections,
    mode_scale,
    render_contact_sheet,
    render_mode,
    section_levels,
)
from rotorpillar.postprocess.readers import Simulation, read_simulation
from rotorpillar.postprocess.run_arrays import RunArrays, read_npz
from rotorpillar.reduced.pillar import cantilever_mode
from rotorpillar.scene import load_scene, override

# The tests that reach pyvista/VTK (the modes read from .vtu, the renders, the animations,
# the cantilever tube) are marked ``renders``: the VTK leak check of tests/conftest.py runs
# after each.  The others (charts, records, fixtures' documents) never call into pyvista or
# VTK (traced: no call into a pyvista or vtk module from their setup, call or teardown), so
# no VTK object of theirs can outlive them; each of them paid two scans of every Python
# object for nothing (the module 12.0 -> 9.2 s of CPU alone, more in a worker holding the
# suite's objects)
renders = pytest.mark.renders


@pytest.fixture(scope="module")
def modal_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("modal")
    fixtures.write_modal_fixture(out, around=24, along=16)
    return out


@pytest.fixture(scope="module")
def modes_top(modal_dir):
    m = records.read(modal_dir / "modal.json", ModalSummary)
    return load_modes(modal_dir / "modes_top.vtu", m.modes_with_top, m.axes)


def _without_triad(px):
    """The picture with the axis triad's corner (the lower left 30 % x 20 %,
    modeshapes._triad) blanked: its coloured arrows are not the tube."""
    px = px.copy()
    h, w = px.shape[:2]
    px[int(0.8 * h) :, : int(0.3 * w)] = 255
    return px


def _coloured_columns(px, rows):
    """Mean column of the strongly coloured (not white, not grey) pixels in ``rows``."""
    sub = px[rows]
    sat = sub.max(axis=2) - sub.min(axis=2)
    ys, xs = np.nonzero(sat > 40)
    return xs.mean(), np.ptp(xs)


def _tube_lean(path):
    px = _without_triad(pixels(path))
    px = px[:, : int(0.8 * px.shape[1])]  # the colour bar sits at the right
    sat = px.max(axis=2) - px.min(axis=2)
    rows = np.flatnonzero((sat > 40).sum(axis=1) > 3)
    # skip the label and the colour bar: the tube is the tallest coloured run
    top = slice(rows.min() + 2, rows.min() + 2 + max(4, len(rows) // 12))
    bottom = slice(rows.max() - max(4, len(rows) // 12), rows.max() - 2)
    x_top, _ = _coloured_columns(px, top)
    x_bot, width = _coloured_columns(px, bottom)
    return abs(x_top - x_bot), width


@renders
def test_fixture_modes_read_back_with_their_metadata(modes_top, modal_dir):
    doc = json.loads((modal_dir / "modal.json").read_text())
    assert len(modes_top.arrays) == len(doc["modes_with_top"]) == 6
    assert modes_top.axes == tube_axes({"tube": "z", "paper_x": "x"})
    assert modes_top.height == pytest.approx(20.0)
    # unit tip: the top of a bending_x mode moves 1 m in X (the surface's
    # top points, up to the section's rotation, which moves them axially only)
    i = bending_columns(modes_top.modes, 1)[0]
    pts = np.asarray(modes_top.surface.points)
    top = pts[:, 2] > 20.0 - 1e-9
    assert modes_top.shape(i)[top, 0] == pytest.approx(1.0, abs=1e-9)


@renders
def test_deformation_and_scale(modes_top):
    i = 0
    u = modes_top.shape(i)
    f = mode_scale(modes_top, i)
    mesh = deformed(modes_top, u, f)
    assert np.asarray(mesh.points) - np.asarray(modes_top.surface.points) == pytest.approx(f * u, abs=1e-12)
    # rounded to 1-2-5: within a factor sqrt(2.5) of the target
    shown = f * np.linalg.norm(u, axis=1).max()
    assert BEAM_TARGET * 20.0 / 1.6 <= shown <= BEAM_TARGET * 20.0 * 1.6


@renders
def test_mode_pictures_are_real_and_show_the_mode(modes_top, tmp_path):
    kinds = [m.kind for m in modes_top.modes]
    bend, tors = kinds.index("bending_x"), kinds.index("torsion")
    p_bend = render_mode(modes_top, bend, tmp_path / "bend.png")
    p_tors = render_mode(modes_top, tors, tmp_path / "tors.png")
    for p in (p_bend, p_tors):
        assert_real_png(p, MODE_SIZE)
    lean, width = _tube_lean(p_bend)
    assert lean > 0.5 * width
    lean, width = _tube_lean(p_tors)
    assert lean < 0.25 * width
    # the tube fills its picture's height (the label's four lines, mode, direction,
    # frequency and scale, take the top ~12 %)
    px = _without_triad(pixels(p_bend))[:, : int(0.8 * MODE_SIZE[0])]
    rows = np.flatnonzero(((px.max(axis=2) - px.min(axis=2)) > 40).sum(axis=1) > 3)
    assert np.ptp(rows) > 0.8 * MODE_SIZE[1]


@renders
def test_ovalling_mode_is_drawn_with_its_cross_sections(modes_top, tmp_path):
    kinds = [m.kind for m in modes_top.modes]
    oval, bend = kinds.index("ovalling"), kinds.index("bending_x")
    assert has_sections(modes_top.modes[oval]) and not has_sections(modes_top.modes[bend])
    levels = section_levels(modes_top, modes_top.shape(oval))
    assert levels == sorted(levels, reverse=True) and 0 < min(levels) and max(levels) < 20.0
    assert np.min(-np.diff(levels)) > 20.0 / 8
    split = int(MODE_SIZE[0] * SPLIT[0] / sum(SPLIT))

    p_oval = render_mode(modes_top, oval, tmp_path / "oval.png")
    assert_real_png(p_oval, MODE_SIZE)
    # the right-hand view: one run of coloured rows per deformed ring
    px = pixels(p_oval)[: int(0.9 * MODE_SIZE[1]), split + 5 :]  # the colour bar sits below
    rows = np.flatnonzero(((px.max(axis=2) - px.min(axis=2)) > 40).sum(axis=1) > 0)
    runs = 1 + int(np.sum(np.diff(rows) > 5))
    assert runs == len(levels) == 3


@renders
def test_quadratic_cells_are_drawn_through_their_shape_functions(tmp_path):
    import meshio

    from rotorpillar.fem3d.output import vtk_cells
    from rotorpillar.mesh import tube_mesh_data
    from rotorpillar.mesh.tube import TubeMeshParams

    H = 20.0
    d = tube_mesh_data(TubeMeshParams(H, 1.0, 0.9, 8, 3, 1, 2, "hexahedron"), isolated=False)
    pts = d.points
    u = np.zeros_like(pts)
    u[:, 0] = pts[:, 2] ** 2
    meshio.write(
        tmp_path / "q.vtu",
        meshio.Mesh(pts, [("hexahedron27", vtk_cells(d.cells, d.gmsh_cell))], point_data={"mode_000": u}),
    )
    ms = load_modes(tmp_path / "q.vtu", [ModeLabel("bending_x")], {"tube": "z", "paper_x": "x"})
    s = np.asarray(ms.surface.points)
    # VTK's surface filter gives float32 points: z**2 to 2 x 6e-8 relative
    assert ms.shape(0)[:, 0] == pytest.approx(s[:, 2].astype(float) ** 2, rel=1e-6, abs=1e-6 * H**2)
    # and there are points between the nodes (seven levels of nodes, more drawn)
    assert len(np.unique(np.round(s[:, 2], 9))) > 2 * 3 + 1


@renders
def test_contact_sheet_size(modes_top, tmp_path):
    p = render_contact_sheet(modes_top, tmp_path / "sheet.png", count=6, columns=4)
    # six modes on four columns at most: two rows of three, no empty tile
    assert_real_png(p, (3 * SHEET_TILE[0], 2 * SHEET_TILE[1]))


@renders
def test_fallback_tube_carries_the_cantilever_shape():
    ms = cantilever_tube(20.0, 2.0, 1.96)
    pts = np.asarray(ms.surface.points)
    xi = pts[:, 2] / 20.0
    ref = cantilever_mode(xi) / cantilever_mode(1.0)
    assert ms.shape(0)[:, 0] == pytest.approx(ref, abs=1e-12)
    assert ms.shape(0)[np.argmax(xi), 0] == pytest.approx(1.0)
    assert np.abs(ms.shape(0)[xi < 1e-9]).max() == pytest.approx(0.0, abs=1e-12)


@renders
def test_superposition_of_unit_tip_modes_gives_the_tip_sum(modes_top):
    n = 50
    q = np.column_stack([np.linspace(-0.01, 0.02, n), np.linspace(0.003, -0.001, n)])
    sim = Simulation(
        "runup",
        None,
        RunArrays.of(
            {"t": np.linspace(0, 1, n), "modal_coordinates": q, "tip_x": q.sum(axis=1), "Omega": np.linspace(0, 10, n)}
        ),
    )
    motion = pillar_motion(sim, modes_top)
    assert motion.coefficients.shape == (n, 2) and "modal coordinates" in motion.source
    pts = np.asarray(modes_top.surface.points)
    top = np.flatnonzero(pts[:, 2] > 20.0 - 1e-9)
    for j in (0, n // 2, n - 1):
        U = elastic_field(motion.coefficients[j], motion.shapes)
        assert U[top, 0] == pytest.approx(q[j].sum(), abs=1e-12)
    # the paper's model: no modal coordinates, tip_x - ground_x drives mode 1
    sim2 = Simulation(
        "earthquake", None, RunArrays.of({"t": sim.arrays.t, "tip_x": 1.0 + q[:, 0], "ground_x": np.ones(n)})
    )
    m2 = pillar_motion(sim2, modes_top)
    assert m2.coefficients[:, 0] == pytest.approx(q[:, 0], abs=1e-12)


def test_frame_times_are_bounded():
    t = np.linspace(0, 80, 100001)
    f = frame_times(t, 150)
    assert len(f) == 150 and f[0] == 0 and f[-1] == 80
    assert len(frame_times(t[:10], 150)) == 10


@pytest.mark.parametrize("case, modal", [("runup", True), ("earthquake", False)])
def test_the_simulation_fixture_is_a_run_record_document(tmp_path, case, modal):
    # the report reads simulate_<case>.json through ReducedRun: the fixture is one, written
    # by the records' constructors, and reads back to the record it was written from
    from rotorpillar.transients.model_run import ReducedRun

    doc = fixtures.write_simulation_fixture(tmp_path, case, modal=modal, n=400, warnings=["w"])
    sim = read_simulation(tmp_path, case)
    assert isinstance(sim.run, ReducedRun) and records.to_builtins(sim.run) == doc
    assert sim.run.model == ("modal" if modal else "paper") and sim.run.warnings == ("w",)
    assert sim.run.max_abs["tip_x"] == pytest.approx(np.abs(sim.arrays.tip_x).max(), rel=1e-15)
    assert (sim.excitation is None) is (case != "earthquake")


def test_run_arrays_keep_every_series_of_the_npz(tmp_path):
    # the typed fields are the file's own columns (as floats); every other array, the
    # writer's string scalars included, stays readable by its name
    fixtures.write_simulation_fixture(tmp_path, "earthquake", modal=True, n=50)
    a = read_npz(tmp_path / "simulate_earthquake.npz")
    with np.load(tmp_path / "simulate_earthquake.npz") as z:
        assert a.names == list(z.files)
        for k in z.files:
            assert np.array_equal(a.series(k), z[k])
        assert a.t.dtype == float and np.array_equal(a.t, z["t"]) and np.array_equal(a.tip_x, z["tip_x"])
    assert a.series("no such series") is None and RunArrays().tip_to_ground(None) is None
    # relative to the ground: the written column first, else the frame decides
    bare = RunArrays.of({"tip_x": np.array([6.0, 7.0]), "ground_x": np.array([6.0, 6.5])})
    assert bare.tip_to_ground("absolute").tolist() == [0.0, 0.5]
    assert bare.tip_to_ground("relative_to_ground").tolist() == [6.0, 7.0]
    assert RunArrays.of({"tip_x": np.ones(2), "tip_x_relative": np.zeros(2)}).tip_to_ground("absolute").tolist() == [
        0,
        0,
    ]
    (tmp_path / "broken.npz").write_bytes(b"PK not a zip")
    with pytest.raises(ValueError, match="broken.npz"):
        read_npz(tmp_path / "broken.npz")


@pytest.mark.parametrize("case, models", [("earthquake", ("modal", "fem3d")), ("runup", ("modal", "beam", "paper"))])
def test_the_comparison_fixture_runs_are_run_record_documents(tmp_path, case, models):
    # each model's simulate_<case>_<model>.json is its record's JSON (Fem3dRun for the 3D
    # full order, else ReducedRun), read by the comparison's reader to that record
    from rotorpillar.postprocess.compare_reader import read_comparison
    from rotorpillar.transients.model_run import Fem3dRun, ReducedRun

    fixtures.write_comparison_fixture(tmp_path, case, models, n=200)
    c = read_comparison(tmp_path, case)
    assert list(c.runs) == list(models)
    for m in models:
        doc = json.loads((tmp_path / f"simulate_{case}_{m}.json").read_text())
        kind = Fem3dRun if m == "fem3d" else ReducedRun
        assert isinstance(c.runs[m], kind) and records.to_builtins(c.runs[m]) == doc
        assert c.runs[m].max_abs["tip_x_relative"] == pytest.approx(np.abs(c.arrays[m].tip_x_relative).max())


def test_the_forces_section_reads_each_run_through_its_record(tmp_path):
    # a run without internal forces is left out, and so is a file that is no run's record
    from rotorpillar.postprocess.report.force_runs import forces_runs
    from rotorpillar.postprocess.report.state import Build, ReportOptions

    build = Build(load_scene("paper"), tmp_path, "paper", ReportOptions(animations=False))
    doc = fixtures.write_simulation_fixture(tmp_path, "runup", per_model=True, n=100)
    assert forces_runs(build) == []
    (tmp_path / "simulate_runup_modal.json").write_text(json.dumps({**doc, "internal_forces": 7}))
    assert forces_runs(build) == []


def test_the_scene_run_of_the_3d_full_order_reads_by_its_record(tmp_path):
    # simulate --model fem3d writes simulate_<case>.json as a Fem3dRun: the runs, summary
    # and earthquake sections read it by attribute (its outcome on the run itself)
    from rotorpillar.postprocess.report.earthquake import paper_case
    from rotorpillar.postprocess.report.runs import section_runs
    from rotorpillar.postprocess.report.state import Build, ReportOptions

    build = Build(load_scene("paper"), tmp_path, "paper", ReportOptions(animations=False))
    for case in ("runup", "earthquake"):
        a = fixtures.model_arrays(case, "fem3d", n=200)
        peaks = {k: float(np.abs(a[k]).max()) for k in ("tip_x_relative", "tip_x", "rotor_x", "rotor_y")}
        ex = fixtures.burst_sizes() if case == "earthquake" else None
        run = fixtures.fem3d_run(case, a["t"], a["Omega"], peaks, dofs=9, wall_seconds=1.0, excitation=ex)
        build.simulations[case] = Simulation(case, run, RunArrays.of(a))
    build.quake_case = build.simulations["earthquake"]
    runs = section_runs(build)
    from html import escape

    from rotorpillar.postprocess.report.page import model_name

    # the heading names the run by what it is (its case, start, length and model), no file name
    assert escape(f"the scene's own run ({model_name('fem3d')})") in runs
    final = build.simulations["runup"].run.omega_final
    assert f"<td>final speed (rad/s)</td><td>{h.num(final)}</td>" in runs
    assert "<td>energy balance: relative error (-)</td><td>2e-05</td>" in runs and ">jumps<" not in runs
    quake = "".join(paper_case(build))
    assert "The scene&#x27;s earthquake run (fem3d model, record)" in quake
    assert "simulate_earthquake_fem3d.json: simulate raised no warning." in quake


@pytest.mark.parametrize(
    "change, words",
    [
        ({"passages": 5}, "Expected `array`, got `int` - at `$.passages`"),
        ({"energy_balance": None}, "Expected `object`, got `null` - at `$.energy_balance`"),
        ({"drop": "omega_final"}, "Object missing required field `omega_final`"),
        ({"drop": "pillar_model"}, "Object missing required field `pillar_model`"),
        ({"resonances": {}}, "Expected `array`, got `object` - at `$.resonances`"),
        ({"model": "fem3d"}, "Object missing required field `duration`"),  # read as the 3D run's
        ({"model": "quake"}, "Invalid value 'quake' - at `$.model`"),
    ],
    ids=["kind", "summary-record", "summary-key", "run-key", "run-kind", "fem3d", "tag"],
)
def test_a_simulate_file_its_record_cannot_take_is_damaged(tmp_path, change, words):
    # named with its file and the path of the field at fault, never read around (the
    # report names it damaged)
    doc = fixtures.write_simulation_fixture(tmp_path, "runup", n=100)
    change = dict(change)
    drop = change.pop("drop", None)
    doc.update(change)
    if drop:
        doc.pop(drop)
    if doc["model"] == "fem3d":
        doc = {"case": "runup", "model": "fem3d", "ok": True}
    (tmp_path / "simulate_runup.json").write_text(json.dumps(doc))
    with pytest.raises(ValueError) as exc:
        read_simulation(tmp_path, "runup")
    assert str(exc.value).startswith("simulate_runup.json: ") and words in str(exc.value)


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@renders
def test_animation_mp4_frame_count_and_poster(modes_top, tmp_path):
    import imageio_ffmpeg

    fixtures.write_simulation_fixture(tmp_path, "runup", n=1500)
    sim = read_simulation(tmp_path, "runup")
    r = animate(
        sim,
        modes_top,
        tmp_path / "runup.mp4",
        title="test",
        max_frames=12,
        poster=tmp_path / "poster.png",
        progress=False,
    )
    assert r.path.suffix == ".mp4" and r.frames == 12
    frames, _ = imageio_ffmpeg.count_frames_and_secs(str(r.path))
    assert frames == 12
    assert_real_png(r.poster, (880, 560))


@renders
def test_animation_gif_fallback_and_cantilever_fallback(tmp_path):
    from PIL import Image

    fixtures.write_simulation_fixture(tmp_path, "earthquake", modal=False, n=800)
    sim = read_simulation(tmp_path, "earthquake")
    ms = cantilever_tube(20.0, 2.0, 1.96)
    r = animate(sim, ms, tmp_path / "quake.mp4", max_frames=6, gif=True, progress=False)
    assert r.path.suffix == ".gif"
    assert "Euler-Bernoulli" in r.source
    with Image.open(r.path) as im:
        assert im.n_frames == 6
        assert im.size == (440, 280)


# --------------------------------------------------------------------------
# Charts


@pytest.fixture(scope="module")
def analyses():
    paper = load_scene("paper")
    # through JSON, as the report reads them
    return {
        "paper": analyze(paper),
        "fold": analyze(override(paper, ["rotor.eccentricity=0.04"])),
    }


@pytest.mark.parametrize("case", ["paper", "fold"])
def test_drive_curves_match_analyze(analyses, case):
    a = analyses[case]
    data = charts.drive_curve_data(a)
    for r in a.resonances:
        c = r.curves
        L = np.interp(c.omega, data["omega"], data["L"])
        exact = charts.av.total_resistance(np.asarray(c.omega), a.drive.load_coefficient, charts.resonances_of(a))
        assert exact == pytest.approx(c.L_all, rel=1e-9)
        assert L == pytest.approx(c.L_all, rel=2e-3)  # the chart's grid, interpolated


def test_stability_switches_at_the_fold_points(analyses):
    a = analyses["fold"]
    data = charts.drive_curve_data(a)
    W, stable = data["omega"], data["stable"]
    switches = W[np.flatnonzero(np.diff(stable.astype(int))) + 1]
    folds = [j["from"][0] for j in data["jumps"]]
    assert len(folds) >= 2
    step = np.max(np.diff(W))
    for w in folds:
        assert np.min(np.abs(switches - w)) < 2 * step
    # and the stationary speeds' stability agrees with the mask
    for s in data["stationary"]:
        assert stable[np.argmin(np.abs(W - s.omega))] == s.stable


def test_paper_scene_has_no_unstable_branch(analyses):
    data = charts.drive_curve_data(analyses["paper"])
    assert data["jumps"] == [] and data["stable"].all()


@pytest.fixture(scope="module")
def sommerfeld():
    return analyze(load_scene("sommerfeld"))


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
def test_drive_chart_spans_the_motor_and_marks_what_lies_beyond(sommerfeld, tmp_path):
    a = sommerfeld
    data = charts.drive_curve_data(a)
    fig = charts.drive_figure(a)
    top = fig.axes[0]
    M0 = a.drive.torque_at_zero
    assert a.drive.slope > 0  # a falling characteristic: Md is largest at rest
    assert top.get_ylim() == pytest.approx((0.0, charts.HEADROOM * M0))
    y_max = top.get_ylim()[1]
    far = {r.index for r in a.resonances if r.dL_max > y_max}
    assert far and max(r.dL_max for r in a.resonances) > 20 * y_max  # the scene's point
    assert {b["resonance"] for b in data["beyond"]} == far
    texts = [t.get_text() for t in top.texts]
    for b in data["beyond"]:
        assert b["peak"] > y_max
        assert any(t.startswith(f"omega_{b['resonance']}: L peaks at") for t in texts)
    # the capture: every stationary speed of the motor is inside the panel
    for st in a.drive.stationary:
        assert 0 < M0 - a.drive.slope * st.omega < y_max and st.omega < top.get_xlim()[1]
        assert any(t.startswith(f"{st.omega:.2f} rad/s") for t in texts)
    assert labels_overlap(fig) == []
    from rotorpillar.postprocess.style import save

    assert_real_png(save(fig, tmp_path / "d.png"), (1060, _drive_height(a)))


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
@pytest.mark.parametrize("case", ["paper", "fold"])
def test_drive_chart_labels_do_not_overlap(analyses, case):
    fig = charts.drive_figure(analyses[case])
    assert labels_overlap(fig) == []
    # a resonance left off the chart lies beyond the drive's reach (the ROM's third X
    # resonance, 157 rad/s, against the paper's free speed of 90 rad/s)
    free = analyses[case].drive.free_speed
    assert all(b["omega"] > free for b in charts.drive_curve_data(analyses[case])["beyond"]) or case == "fold"


def _drive_height(a) -> int:
    """The Md/L chart's height: the overview (420 px) and a row of 400 px per three
    resonances (the ROM's k + 1 in X and the vertical one: four on the paper's scene)."""
    return 420 + 400 * math.ceil(len(a.resonances) / 3)


@pytest.mark.slow  # seconds: whole commands (the slow tier runs it)
def test_chart_files(analyses, tmp_path):
    a = analyses["fold"]
    assert_real_png(charts.drive_chart(a, tmp_path / "d.png"), (1060, _drive_height(a)))
    # the amplitude panels: 70 px of titles and legend, 330 px a row of three
    assert_real_png(charts.amplitude_chart(a, tmp_path / "a.png"), (1060, 70 + 330 * math.ceil(len(a.resonances) / 3)))
    arrays = fixtures.simulation_arrays("earthquake", n=2000)
    e = transient_charts.earthquake_chart(
        tmp_path / "e.png",
        arrays["t"],
        arrays["ground_acceleration"],
        arrays["tip_x"],
        arrays["rotor_x"],
        arrays["Omega"],
    )
    assert_real_png(e, (900, 800))
    assert png_size(tmp_path / "d.png") == (1060, _drive_height(a))
