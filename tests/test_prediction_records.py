"""The averaging theory's prediction and the passing-torque study as records
(rotorpillar.reduced.stationary): each serialises to the JSON the dict-building
code wrote before them, key for key and value for value, and round-trips.

The reference is that old code, kept below as it was (``_old_*``): run on the
same model with the same inputs, its dict written by ``provenance.to_json`` is
the text the record gives, exactly (no tolerance: the same floating-point
operations in the same order).  The simulated run-ups are shared by the two
(``simulate_batch`` memoised), so the batches' wall time is one number too.
Read back (``from_json``, through ``CaseSummary`` and the command's own file), the
records write the same JSON again.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest
from conftest import cli
from scipy.optimize import brentq

from rotorpillar.provenance import to_json
from rotorpillar.reduced import averaging as av
from rotorpillar.reduced import stationary
from rotorpillar.reduced.batch import Batch
from rotorpillar.reduced.drive import DriveSchedule
from rotorpillar.reduced.models import build_model
from rotorpillar.reduced.stationary import (
    AveragingPrediction,
    NoPassingFold,
    PassingTorqueStudy,
    averaging_prediction,
    exact_folds,
    passing_torque,
    passing_torque_from_json,
    stationary_exact,
)
from rotorpillar.scene import load_scene
from rotorpillar.transients.case_summary import CaseSummary
from rotorpillar.transients.cases import run_case

# --------------------------------------------------------------------------
# The code that built the dicts (rotorpillar/reduced/stationary.py before the records)


def _old_stationary_exact(model, M0, slope, load, top=None, n=3000):
    free = DriveSchedule.constant(M0, slope, load).free_speed()
    res = model.quasi_normal()
    top = top or 1.2 * max(free, max(r.omega for r in res))
    grid = av.stationary_speed_grid(res, top, n)

    def g(W):
        return M0 - slope * W - load * W * abs(W) + float(model.steady_torque(W))

    vals = np.concatenate(
        [
            M0 - slope * w - load * w * np.abs(w) + model.steady_torque(w)
            for w in np.array_split(grid, 1 + len(grid) // 500)
        ]
    )
    out = []
    for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)[0]:
        w = brentq(g, grid[i], grid[i + 1], xtol=1e-12 * grid[i + 1])
        h = 1e-6 * w
        out.append({"omega": w, "stable": bool(g(w + h) - g(w - h) < 0)})
    return out


def _old_averaging_prediction(model, M0, slope, load):
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(M0, slope, load), res)
    return {
        "stationary": [vars(s) for s in d.stationary],
        "jumps": [vars(j) for j in d.jumps],
        "runup_speed": d.runup_speed,
        "rundown_speed": d.rundown_speed,
        "captured_index": d.captured_index,
        "captured_resonance": None
        if d.captured_index is None
        else next(r.omega for r in res if r.index == d.captured_index),
        "captured_at": None if d.captured_index is None else d.runup_speed,
        "resonances": [
            {
                "index": r.index,
                "direction": r.direction,
                "omega": r.omega,
                "nu": r.nu,
                "a_max": float(av.amplitude(r.omega, r)),
                "dL_max": float(av.resistance_increment(r.omega, r)),
            }
            for r in res
        ],
    }


def _old_exact_folds(model, slope, load, top):
    W = av.stationary_speed_grid(model.quasi_normal(), top, 4000)
    F = load * W**2 + slope * W - model.steady_torque(W)
    dF = np.diff(F)
    out = []
    for i in np.nonzero(np.sign(dF[:-1]) != np.sign(dF[1:]))[0]:
        out.append({"kind": "A" if dF[i] > 0 else "D", "omega": float(W[i + 1]), "torque_at_zero": float(F[i + 1])})
    return out


def _old_predicted_passing_torque(model, torque_at_zero, slope, load, folds=_old_exact_folds):
    res = model.quasi_normal()
    d = av.analyse_drive(av.Characteristic(torque_at_zero, slope, load), res)
    ups = sorted((j for j in d.jumps if j.direction == "up"), key=lambda j: j.torque_at_zero)
    if not ups:
        return None, None
    j = ups[0]
    exact = [
        f
        for f in folds(model, slope, load, 1.5 * j.omega_to)
        if f["kind"] == "A" and abs(f["omega"] - j.omega_from) < 0.2 * j.omega_from
    ]
    return j, (exact[0] if exact else None)


def _old_passing_torque(model, drive, duration, rtol, span=0.2, points=41, folds=_old_exact_folds):
    s, k = drive.slope[-1], drive.load_coefficient
    res = model.quasi_normal()
    j, fold = _old_predicted_passing_torque(model, max(drive.torque_at_zero), s, k, folds)
    if j is None:
        return {
            "predicted": None,
            "statement": "The analysis finds no fold for this motor slope and load: a run-up "
            "passes every resonance with any torque that reaches it; nothing to test.",
        }
    r = next(r for r in res if r.index == j.resonance)
    exact = [fold] if fold else []
    M_pred = j.torque_at_zero
    threshold = 0.5 * (j.omega_from + j.omega_to)
    M_scene = float(max(drive.torque_at_zero))

    def runs(M):
        b = stationary.simulate_batch(
            model, drive, duration, torque_scale=np.asarray(M) / M_scene, rtol=rtol, samples=401
        )
        final = b.Omega[:, -20:].mean(axis=1)
        return b, final, final > threshold

    grid = M_pred * np.linspace(1 - span, 1 + span, points)
    b1, final1, passed1 = runs(grid)
    wall = b1.wall_seconds
    out: dict[str, Any] = {
        "resonance": {"index": r.index, "direction": r.direction, "omega": r.omega, "nu": r.nu},
        "predicted": M_pred,
        "predicted_jump": vars(j),
        "predicted_exact_linear": exact[0]["torque_at_zero"] if exact else None,
        "duration": duration,
        "pass_threshold_speed": threshold,
        "grid": grid,
        "grid_final_speed": final1,
        "grid_passed": passed1,
    }
    if passed1.all() or not passed1.any():
        out["simulated"] = None
        out["statement"] = (
            "every run "
            + ("passed" if passed1.all() else "was captured")
            + f" for M0 within +-{100 * span:g} % of the prediction"
        )
    else:
        i = int(np.argmax(passed1))
        if not passed1[i:].all():
            out["non_monotonic"] = True
        fine = np.linspace(grid[i - 1], grid[i], 21)
        b2, final2, passed2 = runs(fine)
        wall += b2.wall_seconds
        i2 = int(np.argmax(passed2)) if passed2.any() else len(fine) - 1
        lo, hi = fine[max(i2 - 1, 0)], fine[i2]
        out.update(
            {
                "simulated": 0.5 * (lo + hi),
                "simulated_bracket": [lo, hi],
                "rel_error_predicted": M_pred / (0.5 * (lo + hi)) - 1,
                "rel_error_exact_linear": (exact[0]["torque_at_zero"] / (0.5 * (lo + hi)) - 1) if exact else None,
            }
        )
        out["statement"] = (
            f"Run-up through resonance {r.index} ({r.omega:.2f} rad/s): the analysis "
            f"(Eq. 19-23) says M0 >= {M_pred:.1f} N*m passes; simulated run-ups "
            f"from rest over {duration:g} s pass from {0.5 * (lo + hi):.1f} N*m "
            f"({100 * out['rel_error_predicted']:+.1f} %)."
        )
    below, above = 0.95 * M_pred, 1.05 * M_pred
    b3, final3, passed3 = runs([below, above])
    wall += b3.wall_seconds
    out["bracket_runs"] = [
        {"torque_at_zero": float(M), "final_speed": float(f), "passed": bool(p)}
        for M, f, p in zip((below, above), final3, passed3)
    ]
    out["bracket_series"] = {"t": b3.t, "Omega": b3.Omega, "tip_peak": b3.tip_peak}
    out["runs"] = int(len(grid) + (21 if out.get("simulated") else 0) + 2)
    out["batch_wall_seconds"] = wall
    return out


# --------------------------------------------------------------------------
# Models and drives


@pytest.fixture(scope="module")
def sommerfeld():
    return load_scene("sommerfeld", ["modal_model.source=beam"])


def _model(scene, which="paper"):
    return build_model(scene, which, modes=1 if which == "modal" else None)[0]


def _drive(scene):
    d = scene.drive
    return DriveSchedule.ramp(d.torque_at_zero, d.slope, scene.load.coefficient, scene.simulate.runup_ramp)


@pytest.fixture
def shared_batches(monkeypatch):
    """``simulate_batch`` computed once per set of torques: the record's function and the
    old code see the same runs (wall time included)."""
    real, memo = stationary.simulate_batch, {}

    def once(model, drive, t_end, *, torque_scale, **kw):
        key = (id(model), t_end, np.asarray(torque_scale).tobytes(), tuple(sorted(kw.items())))
        if key not in memo:
            memo[key] = real(model, drive, t_end, torque_scale=torque_scale, **kw)
        return memo[key]

    monkeypatch.setattr(stationary, "simulate_batch", once)
    return memo


def _same_json(record, old) -> dict:
    """The record's JSON is the old dict's, as the writer puts it in the file (text equal:
    keys, their order, values), and it comes back from that text."""
    assert to_json(record) == to_json(old)
    return json.loads(to_json(old))


# --------------------------------------------------------------------------
# The averaging prediction


@pytest.mark.parametrize(
    "scene,over,which",
    [
        ("paper", [], "paper"),  # no fold, no capture
        ("paper", ["shaft.damping=0"], "paper"),  # an undamped Y resonance: a_max unbounded (null)
        ("sommerfeld", ["modal_model.source=beam"], "paper"),  # a fold, captured at omega_1
        ("sommerfeld", ["modal_model.source=beam"], "modal"),
    ],
)
def test_averaging_prediction_writes_the_old_json(scene, over, which):
    sc = load_scene(scene, over)
    model, d, L = _model(sc, which), sc.drive, sc.load
    pred = averaging_prediction(model, d.torque_at_zero, d.slope, L.coefficient)
    doc = _same_json(pred, _old_averaging_prediction(model, d.torque_at_zero, d.slope, L.coefficient))
    back = AveragingPrediction.from_json(doc)
    assert back == pred and back.to_json() == pred.to_json()
    assert all(isinstance(s, av.Stationary) for s in back.stationary)
    assert all(isinstance(j, av.Jump) for j in back.jumps)
    if "shaft.damping=0" in over:
        assert any(r.a_max is None for r in pred.resonances)  # where the JSON has null
    if scene == "sommerfeld":
        assert pred.captured_index == 1 and pred.captured_at == pred.runup_speed and pred.jumps


def test_exact_stationary_speeds_and_folds_as_the_old_dicts(sommerfeld):
    model, d, L = _model(sommerfeld), sommerfeld.drive, sommerfeld.load
    st = stationary_exact(model, d.torque_at_zero, d.slope, L.coefficient)
    old = _old_stationary_exact(model, d.torque_at_zero, d.slope, L.coefficient)
    assert [s.to_json() for s in st] == old and len(st) == 3  # inside the fold: three speeds
    folds = exact_folds(model, d.slope, L.coefficient, 40.0)
    assert [f.to_json() for f in folds] == _old_exact_folds(model, d.slope, L.coefficient, 40.0)
    assert [f.kind for f in folds][:2] == ["A", "D"]


# --------------------------------------------------------------------------
# The passing-torque study


def test_passing_torque_study_writes_the_old_json(sommerfeld, shared_batches):
    model, drive = _model(sommerfeld), _drive(sommerfeld)
    pt = passing_torque(model, drive, sommerfeld.simulate.duration, sommerfeld.simulate.rtol)
    old = _old_passing_torque(model, drive, sommerfeld.simulate.duration, sommerfeld.simulate.rtol)
    doc = _same_json(pt, old)
    assert isinstance(pt, PassingTorqueStudy) and pt.simulated is not None  # the bracketed branch
    assert len(shared_batches) == 3  # grid, refinement, brackets: both ran the same three batches
    back = passing_torque_from_json(doc)
    assert isinstance(back, PassingTorqueStudy) and back == pt and back.to_json() == doc


def test_no_fold_writes_the_old_json():
    sc = load_scene("paper")
    model, drive = _model(sc), _drive(sc)
    pt = passing_torque(model, drive, sc.simulate.duration, sc.simulate.rtol)
    doc = _same_json(pt, _old_passing_torque(model, drive, sc.simulate.duration, sc.simulate.rtol))
    assert isinstance(pt, NoPassingFold) and list(doc) == ["predicted", "statement"]
    assert passing_torque_from_json(doc) == pt


def _scripted(j: av.Jump, passes):
    """A ``simulate_batch`` whose run-ups end above the jump (passed) where ``passes(M0)``,
    below it (captured) elsewhere: the study's other branches without their physics."""

    def batch(model, drive, t_end, *, torque_scale, **kw):
        M = np.asarray(torque_scale) * max(drive.torque_at_zero)
        final = np.where([passes(m) for m in M], j.omega_to, j.omega_from)
        t = np.linspace(0.0, t_end, 401)
        Omega = final[:, None] * np.minimum(1.0, 2 * t / t_end)[None, :]
        zeros = np.zeros_like(Omega)
        n = len(M)
        return Batch(t, Omega, zeros, zeros, np.zeros((n, 8)), np.zeros(n, int), np.ones(n, int), 0.25 * n)

    return batch


@pytest.mark.parametrize(
    "case,exact",
    [
        ("all_passed", True),
        ("all_captured", True),
        ("non_monotonic", True),
        ("bracketed", False),  # no exact fold beside it: rel_error_exact_linear present, null
        ("all_passed", False),
    ],
)
def test_every_shape_of_the_study_writes_the_old_json(sommerfeld, monkeypatch, case, exact):
    model, drive = _model(sommerfeld), _drive(sommerfeld)
    d, L = sommerfeld.drive, sommerfeld.load
    j, _ = stationary.predicted_passing_torque(model, d.torque_at_zero, d.slope, L.coefficient)
    assert j is not None
    M = j.torque_at_zero
    passes = {
        "all_passed": lambda m: True,
        "all_captured": lambda m: False,
        "non_monotonic": lambda m: m >= M and not 1.1 * M < m < 1.12 * M,
        "bracketed": lambda m: m >= 1.03 * M,
    }[case]
    monkeypatch.setattr(stationary, "simulate_batch", _scripted(j, passes))
    folds = _old_exact_folds
    if not exact:
        monkeypatch.setattr(stationary, "exact_folds", lambda *a: [])
        folds = lambda *a: []  # noqa: E731
    pt = passing_torque(model, drive, 100.0, 1e-7)
    doc = _same_json(pt, _old_passing_torque(model, drive, 100.0, 1e-7, folds=folds))
    assert isinstance(pt, PassingTorqueStudy)
    assert ("simulated_bracket" in doc) is (case in ("non_monotonic", "bracketed"))
    assert ("rel_error_exact_linear" in doc) is ("simulated_bracket" in doc)
    assert doc.get("non_monotonic") is (True if case == "non_monotonic" else None)
    assert (doc["predicted_exact_linear"] is None) is (not exact)
    back = passing_torque_from_json(doc)
    assert back == pt and back.to_json() == doc


# --------------------------------------------------------------------------
# In the case summary


def test_a_runup_summary_with_its_study_round_trips_as_records(sommerfeld):
    s = run_case(sommerfeld, "runup", "paper").summary
    assert isinstance(s.prediction, AveragingPrediction) and isinstance(s.passing_torque, PassingTorqueStudy)
    d = s.to_json()
    assert d["prediction"] == s.prediction.to_json() and d["passing_torque"] == s.passing_torque.to_json()
    assert CaseSummary.from_json(d).to_json() == d
    # through the text the command writes
    again = CaseSummary.from_json(json.loads(to_json(d)))
    assert isinstance(again.prediction, AveragingPrediction) and isinstance(again.passing_torque, PassingTorqueStudy)
    assert again == s and to_json(again.to_json()) == to_json(d)


@pytest.mark.slow  # a whole command: the slow tier runs it
def test_simulate_runup_file_reads_back_to_records_and_writes_itself(tmp_path):
    """simulate_runup.json as the command writes it (sommerfeld: a fold, a study) read
    through ReducedRun: the prediction and the study come back as records and the fields
    are written back as they were, key order included."""
    from rotorpillar.provenance import PROVENANCE_KEYS
    from rotorpillar.transients.run_records import ReducedRun

    p = cli("simulate", "sommerfeld", "--case", "runup", "--model", "paper", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "simulate_runup.json").read_text())
    skip = {"command", "scene_source", "overrides", "model_files", "files", "figures", *PROVENANCE_KEYS}
    fields = {k: v for k, v in doc.items() if k not in skip}
    run = ReducedRun.from_json(fields)
    pt = run.summary.passing_torque
    assert isinstance(run.summary.prediction, AveragingPrediction) and isinstance(pt, PassingTorqueStudy)
    assert json.dumps(run.to_json()) == json.dumps(fields)
    assert pt.statement in p.stdout  # simulate's summary reads it by attribute
