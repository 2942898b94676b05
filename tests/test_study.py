"""Design studies (rotorpillar.studies) against single runs and against themselves.

Independent references: the single-run integrator ``simulate`` (one model,
one drive, one run, as `rotorpillar simulate` integrates a case) and the
simulated passing torque of ``passing_torque`` (its own bisection of
run-ups).  Executors: a Dask LocalCluster against the in-process scheduler.
"""

from pathlib import Path

import numpy as np
import pytest

from rotorpillar import records
from rotorpillar.executor import Executor
from rotorpillar.postprocess.study_charts import study_charts
from rotorpillar.records import replace
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.excitation import no_motion
from rotorpillar.reduced.integration import Settings, simulate
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.stationary import passing_torque
from rotorpillar.scene import load_scene, override
from rotorpillar.studies import StudyResult, design_study, plan
from rotorpillar.studies.batch import settle_time
from rotorpillar.transients.case_summary import capture_state

SMALL = ["drive.torque_at_zero=560,600,700", "rotor.eccentricity=0.010:0.020:3"]


@pytest.fixture(scope="module")
def small_study(tmp_path_factory):
    """The 3 x 3 run-ups of the sommerfeld scene on the in-process scheduler."""
    out = tmp_path_factory.mktemp("study_inproc")
    with Executor(processes=False) as ex:
        return design_study(
            load_scene("sommerfeld"), "runup", "paper", SMALL, out_dir=out, executor=ex, show_progress=False
        )


def test_each_run_of_a_study_is_the_single_run(small_study):
    """Every run against `simulate` of the same scene (dp5, the scene's rtol).

    Both integrate the same equations with the same compiled dp5 and step
    control at rtol = 1e-7; they differ only in the absolute tolerances'
    scales (the batch loop takes the speed scale of its strongest motor and
    its largest e), so their step sequences differ and the results agree to
    the integrator's tolerance, not bitwise: on these runs, which settle on
    a stable speed (none sits at the fold), 1e-5 relative in the final speed
    and the sampled shaft deflection (the same output grid, dense output) is
    100 x rtol of margin for the error accumulated over ~30 000 steps.  The
    peak tip is taken at the integrator's steps, which miss the crest of an
    oscillation at Omega by up to 1 - cos(Omega h / 2) ~ (Omega h)**2 / 8
    relative (h the step): each run's peak is that close to the true one, so
    the two agree within twice that bound, with the run's mean step and its
    highest speed."""
    base = load_scene("sommerfeld")
    assert len(small_study.runs) == 9
    kinds = set()
    for r in small_study.runs:
        sc = override(base, [f"{k}={v}" for k, v in r.params.items()])
        model, _ = build_model(sc, "paper")
        d = sc.drive
        drive = DriveSchedule.ramp(d.torque_at_zero, d.slope, sc.load.coefficient, sc.simulate.runup_ramp)
        run = simulate(
            model, drive, no_motion(), sc.simulate.duration, settings=Settings(rtol=sc.simulate.rtol, samples=6001)
        )
        assert r.ok and run.ok
        assert r.final_speed == pytest.approx(run.Omega[-1], rel=1e-5)
        h = sc.simulate.duration / run.stats.steps
        crest = 2 * (float(np.max(run.Omega)) * h) ** 2 / 8
        assert r.peak_tip == pytest.approx(float(np.max(run.peak[:, -1])), rel=crest)
        m = model
        shaft = np.hypot(
            run.q[:, : m.nx] @ m.shaft - m.eccentricity * np.cos(run.q[:, -1]),
            run.q[:, m.nx] - m.eccentricity * np.sin(run.q[:, -1]),
        )
        since = run.t >= settle_time(sc, sc.simulate.duration)
        assert r.peak_shaft_deflection == pytest.approx(float(shaft[since].max()), rel=1e-5)
        state = capture_state(model, run.t, run.Omega, drive.free_speed())
        assert r.captured_at == state.captured_at or r.captured_at == pytest.approx(
            state.captured_at, rel=1e-5
        )  # the batch and the single run's output grids
        assert r.passed == (state.speed_state not in ("captured", "escaping"))
        kinds.add(r.passed)
    assert kinds == {True, False}  # the grid holds both outcomes


@pytest.fixture(scope="module")
def cluster():
    """A Dask LocalCluster of two worker processes, shared by the two tests that run on one
    (a study's batches, a convergence study's runs): each worker process's start and imports
    (Dask, numba, scipy: ~1.3-1.9 s of CPU each) once for both, not once per test."""
    with Executor(workers=2) as ex:
        yield ex


@pytest.mark.slow  # a Dask LocalCluster's start and the study again
def test_local_cluster_and_in_process_scheduler_agree(small_study, cluster, tmp_path):
    """The same batches on two worker processes: the same code on the same
    inputs, so the same numbers (bitwise: the integrator is deterministic)."""
    ex = cluster
    assert ex.describe().workers == 2
    other = design_study(
        load_scene("sommerfeld"), "runup", "paper", SMALL, out_dir=tmp_path, executor=ex, show_progress=False
    )
    assert other.executor.kind == "LocalCluster" and small_study.executor.kind == "in-process"
    strip = lambda r: {k: v for k, v in records.to_builtins(r).items() if k != "batch"}
    assert [strip(a) for a in other.runs] == [strip(b) for b in small_study.runs]


def test_study_round_trips_and_writes_one_csv_row_per_run(small_study):
    doc = records.to_builtins(small_study)
    assert records.to_builtins(records.convert(doc, StudyResult)) == doc
    lines = Path(small_study.files.csv).read_text().splitlines()
    assert lines[0].startswith("index,drive.torque_at_zero,rotor.eccentricity,final_speed")
    assert len(lines) == 1 + 9


def test_runs_sharing_a_model_go_to_one_batch_loop():
    """Run-ups varying only what the batch loop takes per run share one model:
    one group per batch; a key that changes the model makes its own groups."""
    from rotorpillar.studies.batch import group_key

    pts = [{"drive.torque_at_zero": m, "rotor.eccentricity": e} for m in (1, 2, 3) for e in (4, 5)]
    assert {group_key(p, "runup") for p in pts} == {()}
    assert len(plan(pts, "runup", batch_runs=8)) == 1
    pts = [{"rotor.mass": m, "drive.torque_at_zero": t} for m in (1, 2) for t in (1, 2, 3)]
    batches = plan(pts, "runup", batch_runs=3)
    assert [len({group_key(r.params, "runup") for r in b}) for b in batches] == [1, 1]


def test_the_study_boundary_brackets_the_simulated_passing_torque(tmp_path):
    """The study's capture boundary at e = 15 mm lies within its grid step
    (10 N*m) of the passing torque `simulate` reports (its own refined
    bisection of run-ups), and the averaging prediction is carried beside it."""
    sc = load_scene("sommerfeld")
    with Executor(processes=False) as ex:
        st = design_study(
            sc,
            "runup",
            "paper",
            ["drive.torque_at_zero=560:700:15"],
            out_dir=tmp_path,
            executor=ex,
            show_progress=False,
            charts=study_charts,
        )
    (row,) = st.boundary.found
    lo, hi = row.captured_max, row.passed_min
    assert hi - lo == pytest.approx(10.0)
    model, _ = build_model(sc, "paper")
    d = sc.drive
    pt = passing_torque(
        model,
        DriveSchedule.ramp(d.torque_at_zero, d.slope, sc.load.coefficient, sc.simulate.runup_ramp),
        sc.simulate.duration,
        sc.simulate.rtol,
    )
    assert lo - 10.0 <= pt.simulated <= hi + 10.0
    assert abs(0.5 * (lo + hi) - pt.simulated) <= 10.0
    assert st.boundary.predicted.averaging[0] == pytest.approx(pt.predicted, rel=1e-9)
    print(f"study boundary {lo}..{hi}, simulate {pt.simulated:.2f}, averaging {pt.predicted:.2f}")
    assert (Path(tmp_path) / "study_final.png").is_file()


@pytest.mark.slow  # a Dask LocalCluster (the module's)
def test_converge_runs_on_the_executor_give_the_serial_records(cluster, tmp_path):
    """The convergence study's runs through a LocalCluster: the same
    frequencies and DOFs as serially, each run cached once.  On the module's cluster of two
    workers (run_study's ``executor``), as `converge --workers 2` runs them: run_study's own
    cluster for ``workers`` > 1 is the same Executor (``executor or Executor(workers)``), its
    start the same as the fixture's; measured in pairs, the file 17.6 -> 13.8 and 12.1 -> 11.0 s of CPU."""
    import rotorpillar.converge as cv

    scene = load_scene("paper")
    cases = [c for c in cv.ladder(scene) if cv.FAMILIES[c.family].model == "beam"][:6]
    serial = cv.run_study(cases, scene, tmp_path / "a", progress=False)
    parallel = cv.run_study(cases, scene, tmp_path / "b", progress=False, workers=2, executor=cluster)
    for a, b in zip(serial, parallel):
        assert (a.label, a.bending, a.dofs) == (b.label, b.bending, b.dofs)
    assert len(list((tmp_path / "b").glob("*.json"))) == len(cases)


def test_modal_model_study_runs(tmp_path):
    """The modal model goes through the same batch loop (two pillar modes)."""
    sc = replace(load_scene("sommerfeld"))
    with Executor(processes=False) as ex:
        st = design_study(
            sc, "runup", "modal", ["drive.torque_at_zero=600,700"], out_dir=tmp_path, executor=ex, show_progress=False
        )
    assert [r.ok for r in st.runs] == [True, True]
    assert st.runs[1].final_speed > st.runs[0].final_speed


def test_an_earthquake_at_an_angle_runs_on_the_spatial_rom_as_simulate_does():
    """A study over ``excitation.angle`` (issue 26: `study --vary excitation.angle` finds the worst
    incidence): the batch loop integrates the planar ROM alone, on which the angle changed
    nothing (the same peak at every angle, measured before this fix); where the scene's planes
    resolve to spatial the runs go through ``run_case`` as `simulate` runs them.  Each study run
    equals the single run of its scene (another path: simulate's, to round-off; 1e-12 relative),
    and the peak in the rotor's plane differs between the ground moving in it (0 deg) and across
    it (90 deg): with one component at 90 deg only the gyroscopic and tilt coupling reach the rotor's
    plane, so its peak tip falls by far more than the 10 % asserted."""
    from rotorpillar.scene import with_values
    from rotorpillar.studies.axes import implied_settings, parse_axes
    from rotorpillar.studies.batch import PlannedRun, _run_group
    from rotorpillar.transients.cases import run_case

    scene = with_values(
        load_scene("paper"),
        {
            "excitation.kind": "record",
            "excitation.record": "elcentro",
            "modal_model.source": "beam",
            "simulate.earthquake_duration": 6.0,
        },
    )
    implied = implied_settings(parse_axes(["excitation.angle=0,90"], scene), "earthquake", scene)
    assert implied == {"modal_model.planes": "spatial"}
    runs = [PlannedRun(index=i, params={"excitation.angle": a}) for i, a in enumerate((0.0, 90.0))]
    got = []
    for p in runs:
        own = with_values(scene, {**implied, **p.params})
        (r,) = _run_group(own, "earthquake", "modal", [p])
        one = run_case(own, "earthquake", "modal", truncation=False)
        assert one.model.__class__.__name__ == "SpatialRotor"
        assert r.peak_tip == pytest.approx(one.summary.max_abs["tip_x"], rel=1e-12)
        assert r.final_speed == pytest.approx(one.summary.omega_final, rel=1e-12)
        got.append(r.peak_tip)
    assert got[1] < 0.9 * got[0], got


def _cube(x: int) -> int:
    return x**3


def test_each_map_on_one_executor_computes_its_own_items():
    """The convergence ladder's rounds call ``map`` again on the study's one executor: each
    call gets its own items' results.  Before, a task's key was ``fn-i-id(executor)``, the
    same in every call, and the scheduler handed back the result it still held under it:
    19 rounds in 20 got the previous round's (a study recorded its finest 3D rung with the
    rung before's modes).  Reference: the function itself."""
    with Executor(2, processes=False) as ex:  # threads: the keys are the scheduler's either way
        for k in range(6):
            assert dict(ex.map(_cube, [k, k + 10])) == {0: k**3, 1: (k + 10) ** 3}, k
