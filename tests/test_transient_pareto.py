"""Speed against accuracy for the transients (rotorpillar.transients.pareto).

- the reference's own error: Richardson recovers the limit of peaks made to
  converge as L + C h**3 (to round-off), and falls back to the difference to
  the next coarser where the runs do not converge monotonically;
- the fronts: a run beaten in both cost and error is never on one;
- the runs (slow): every model of a short El Centro case runs from the same
  state, the second call computes nothing (the cache), a deleted run is the
  only one computed again (resumable), a 3D run on a worker process gives the
  run in this process to round-off, and a finer 3D mesh comes closer to the
  finest (the ladder converges).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorpillar import records
from rotorpillar.records import replace
from rotorpillar.transients.pareto import ParetoChoice, analyse_pareto
from rotorpillar.transients.pareto_runs import StoredRun, pareto_along, run_specs

has_dolfinx = pytest.mark.skipif(__import__("importlib").util.find_spec("dolfinx") is None, reason="needs dolfinx")
GRID = np.linspace(0.0, 1.0, 101)


def _doc(family, label, wall, peak, tip, **params):
    return StoredRun(
        key=label,
        family=family,
        label=label,
        params=params,
        dofs=10,
        wall_seconds=wall,
        ok=True,
        peak_tip=peak,
        tip=tuple(tip),
    )


def _solid(along, peak):
    return _doc(
        "fem3d", f"3D, 8x{along}", along, peak, peak * np.sin(6 * GRID), elements_around=8, elements_along=along
    )


def test_reference_error_by_richardson():
    L, C = 0.0103, -0.5
    docs = [_solid(n, L + C * (1.0 / n) ** 3) for n in (10, 15, 20)]
    docs.append(_doc("rom", "ROM, 1 mode", 0.01, 0.0102, 0.0102 * np.sin(6 * GRID), modes=1))
    study, _ = analyse_pareto(docs, ParetoChoice("ROM, 1 mode", "3D, 8x15"))
    ref = study.reference
    assert ref.method == "richardson" and math.isclose(ref.order, 3.0, rel_tol=1e-6)
    assert math.isclose(ref.limit, L, rel_tol=1e-9)
    assert math.isclose(ref.peak_error, 1.25 * abs(L - docs[2].peak_tip) / L, rel_tol=1e-6)
    by = {r.label: r for r in study.runs}
    assert math.isclose(by["ROM, 1 mode"].peak_tip_error, 0.0102 / docs[2].peak_tip - 1)
    assert by["3D, 8x20"].peak_tip_error == ref.peak_error  # the reference: its own error
    assert "ROM, 1 mode" in study.fronts.peak_tip  # cheapest: on every front
    assert "3D, 8x10" not in study.fronts.peak_tip  # dearer and worse than the ROM


def test_reference_error_without_monotone_convergence():
    docs = [_solid(10, 0.0100), _solid(15, 0.0103), _solid(20, 0.0102)]
    study, _ = analyse_pareto(docs, ParetoChoice(None, None))
    ref = study.reference
    assert ref.method == "next_coarser" and ref.order is None
    assert math.isclose(ref.peak_error, abs(0.0102 / 0.0103 - 1))
    assert math.isclose(ref.history_error, abs(0.0102 - 0.0103) / 0.0102, rel_tol=1e-2)


def test_run_specs():
    from rotorpillar.scene import Mesh

    along = pareto_along(20)
    assert along == (5, 10, 15, 20)  # the default's ladder: quarters of the finest
    assert pareto_along(8) == (2, 4, 6, 8) and pareto_along(4) == (1, 2, 3, 4)
    assert pareto_along(10) == (2, 5, 8, 10)  # rounded half to even: still four rungs
    specs = run_specs(2, 12, Mesh(elements_around=16, elements_along=12), along)
    fams = [f for f, _, _ in specs]
    assert fams.count("rom") == 4 and fams.count("beam") == 5
    meshes = [(p["elements_around"], p["elements_along"]) for f, _, p in specs if f == "fem3d"]
    assert (16, 12) in meshes and (8, 20) in meshes
    assert run_specs(2, 3, None, along)[2][2] == {"modes": 3}  # no more modes than the source has
    assert sum(f == "rom" for f, _, _ in run_specs(2, 3, None, along)) == 3


@pytest.mark.slow  # 3D runs on 8 x 2, 3, 4 elements over 0.3 s, twice; a Dask worker
@has_dolfinx
def test_pareto_runs_cache_and_resume(tmp_path):
    import json

    from rotorpillar.scene import load_scene
    from rotorpillar.transients.pareto import ParetoStudy, plan_pareto, transient_pareto
    from rotorpillar.transients.pareto_runs import compute_3d

    scene = load_scene("paper", ["excitation.kind=record"])
    short = dict(duration=0.3, along=(2, 3, 4), beams=(2, 4))
    mesh = replace(scene.mesh, elements_around=8, elements_along=3)
    study, tips = transient_pareto(scene, cache_dir=tmp_path, rom_modes=2, chosen_mesh=mesh, workers=1, **short)
    assert all(r.ok for r in study.runs) and study.cost.computed == len(study.runs)
    assert study.cost.workers == 1 and "fem3d" in study.compile_seconds
    assert study.reference.label == "3D, 8x4" and study.chosen.fem3d == "3D, 8x3"
    # the study is a record writing the JSON it reads back (compare_earthquake.json's pareto)
    doc = json.loads(records.encode(study))
    assert records.to_builtins(records.convert(doc, ParetoStudy)) == doc
    assert list(doc["cost"]) == [
        "runs",
        "computed",
        "cached",
        "workers",
        "wall_seconds",
        "pool_seconds",
        "compute_seconds",
    ]
    # the same start for every model: their tips agree at t = 0 (the pillar at rest)
    assert max(abs(v[0]) for v in tips.values()) < 1e-12
    err = {r.label: abs(r.history_error) for r in study.runs}
    assert err["3D, 8x3"] < err["3D, 8x2"]
    # cached: nothing computed, the same numbers
    again, _ = transient_pareto(scene, cache_dir=tmp_path, rom_modes=2, chosen_mesh=mesh, **short)
    assert again.cost.computed == 0 and all(r.cached for r in again.runs)
    assert [r.peak_tip for r in again.runs] == [r.peak_tip for r in study.runs]
    # resumable: one run lost, one run computed
    victim = next(r for r in study.runs if r.label == "3D, 8x2")
    (tmp_path / f"pareto-{victim.key}.json").unlink()
    third, _ = transient_pareto(scene, cache_dir=tmp_path, rom_modes=2, chosen_mesh=mesh, **short)
    assert third.cost.computed == 1
    # the worker's run is this process's run
    plan = plan_pareto(scene, cache_dir=tmp_path / "none", rom_modes=2, chosen_mesh=mesh, **short)
    i = next(i for i, s in enumerate(plan.specs) if s[1] == "3D, 8x2")
    here, _ = compute_3d((plan.scene, plan.specs[i][2], plan.motion, plan.speed, plan.duration))
    assert math.isclose(here.peak_tip, victim.peak_tip, rel_tol=1e-9)


def test_runs_are_served_from_the_cache_and_a_damaged_entry_is_recomputed(tmp_path):
    """The reduced runs of a short case (no 3D: no reference, so the analysis refuses,
    after the runs are kept): a second plan finds every run in the cache (rotorpillar.cache,
    ``pareto-<key>.json``) with the numbers the first computed; an entry cut short, one of
    another key and one without its verdict are misses, to compute again; the others stay."""
    import json

    from rotorpillar.reduced.models import beam_candidates
    from rotorpillar.scene import load_scene
    from rotorpillar.transients.pareto import ParetoRunning, plan_pareto

    scene = load_scene("paper", ["excitation.kind=record"])
    choices = dict(duration=0.2, along=(), beams=(2,), pillar_modes=beam_candidates(scene))
    plan = plan_pareto(scene, cache_dir=tmp_path, rom_modes=1, **choices)
    assert plan.results == {} and len(plan.specs) >= 3  # ROMs with 1, 2, 3 modes and a beam
    with pytest.raises(ValueError, match="no 3D run"):
        ParetoRunning(plan, workers=0).finish()
    files = sorted(tmp_path.glob("pareto-*.json"))
    assert len(files) == len(plan.specs)
    computed = {i: records.to_builtins(run) for i, run in plan.results.items()}
    # the record is the cache entry's value: its JSON, beside the key, read back whole
    assert all(
        json.loads((tmp_path / f"pareto-{r.key}.json").read_text()) == {"key": r.key, "value": records.to_builtins(r)}
        for r in plan.results.values()
    )
    assert not any(r.cached for r in plan.results.values())

    again = plan_pareto(scene, cache_dir=tmp_path, rom_modes=1, **choices)
    assert again.keys == plan.keys and sorted(again.results) == list(range(len(plan.specs)))
    assert all(r.cached for r in again.results.values())
    assert {i: records.to_builtins(replace(r, cached=False)) for i, r in again.results.items()} == computed

    path = {i: tmp_path / f"pareto-{key}.json" for i, key in enumerate(plan.keys)}
    path[0].write_text(path[0].read_text()[:40])  # cut short
    doc = json.loads(path[1].read_text())
    path[1].write_text(json.dumps({**doc, "key": "another"}))  # another run's
    doc = json.loads(path[2].read_text())
    doc["value"].pop("ok")
    path[2].write_text(json.dumps(doc))  # no verdict
    damaged = {0, 1, 2}
    third = plan_pareto(scene, cache_dir=tmp_path, rom_modes=1, **choices)
    assert set(third.results) == set(range(len(plan.specs))) - damaged
    running = ParetoRunning(third, workers=0)
    assert sorted(running.todo) == sorted(damaged)
    with pytest.raises(ValueError, match="no 3D run"):
        running.finish()
    # recomputed and stored whole again: the next plan finds every run
    assert sorted(plan_pareto(scene, cache_dir=tmp_path, rom_modes=1, **choices).results) == list(
        range(len(plan.specs))
    )


@pytest.mark.parametrize(
    "peaks, method",
    [
        ((0.0103 - 0.5 / 10**3, 0.0103 - 0.5 / 15**3, 0.0103 - 0.5 / 20**3), "richardson"),
        ((0.0100, 0.0103, 0.0102), "next_coarser"),
        ((0.0102,), "none"),
    ],
)
def test_the_reference_writes_the_keys_it_wrote_as_a_dict(peaks, method):
    """``reference`` in compare_earthquake.json's ``pareto``, now a record: the same keys in
    the same order for each way its error is estimated (``limit`` only by Richardson), and
    the study's JSON read back gives itself."""
    import json

    from rotorpillar.transients.pareto import ParetoStudy

    docs = [_solid(n, p) for n, p in zip((10, 15, 20), peaks)]
    study, _ = analyse_pareto(docs, ParetoChoice(None, None))
    doc = json.loads(json.dumps(records.to_builtins(study)))
    ref = doc["reference"]
    assert ref["method"] == method
    keys = ["label", "peak_tip", "peak_error", "history_error", "method", "order"]
    assert list(ref) == keys + (["limit"] if method == "richardson" else []) + ["note"]
    again = records.convert(doc, ParetoStudy)
    assert again.reference == study.reference and records.to_builtins(again) == doc
