"""The convergence study's inner results as records (issue 18.1): Richardson's
extrapolations and references, the runner's runs and the run cache serialise to
exactly the dicts the code before them built (keys, order, values).

The reference is the dict code as it was at the branch point (commit 5202ea9),
kept here verbatim as ``_old_*``: it is the contract (convergence.json, converge.json
and the run cache's files), so the records are checked against it field by field on
the same inputs, beside the closed forms Richardson must reproduce on an exact
series f = 1 + C h**p (its limit and order to round-off, 1e-9).
"""

from __future__ import annotations

import json
from dataclasses import replace
from typing import Any

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorpillar import converge as cv
from rotorpillar.converge.compute import _modal_summary, compute_in_process
from rotorpillar.converge.ladder import FAMILIES, QUANTITIES
from rotorpillar.converge.result import ConvergenceRun, Extrapolation
from rotorpillar.converge.runner import cache_doc, case_key, run_record
from rotorpillar.scene import load_scene

# ---------------------------------------------------------------------------
# the dict code at the branch point (rotorpillar/converge/richardson.py, runner.py)


def _old_richardson(h, f, order_theory=None) -> dict:
    h = np.asarray(h, dtype=float)
    f = np.asarray(f, dtype=float)
    d1, d2 = f[0] - f[1], f[1] - f[2]
    p, monotone = None, False
    if d2 == 0.0:
        p, monotone = order_theory, d1 == 0.0
    elif d1 / d2 > 0:
        ratio = d1 / d2

        def g(q):
            return (h[0] ** q - h[1] ** q) / (h[1] ** q - h[2] ** q) - ratio

        lo, hi = 0.3, 12.0
        if g(lo) * g(hi) < 0:
            p, monotone = brentq(g, lo, hi, xtol=1e-12), True
    p_used = p if p is not None else order_theory
    value = float(f[2]) if p_used is None else float(f[2] + (f[2] - f[1]) / ((h[1] / h[2]) ** p_used - 1))
    return {
        "order": p,
        "order_theory": order_theory,
        "monotone": monotone,
        "value": value,
        "error_estimate": 1.25 * abs(value - f[2]),
        "h": h.tolist(),
        "f": f.tolist(),
    }


def _old_series(records, family, quantity):
    rows = [r for r in records if r["family"] == family and r.get("status") == "ok" and r.get(quantity) is not None]
    return sorted(rows, key=lambda r: r["level"])


def _old_family_extrapolations(records) -> dict:
    out: dict[str, dict[str, Any]] = {}
    for name, fam in FAMILIES.items():
        if fam.order is None:
            continue
        for q in fam.quantities:
            rows = _old_series(records, name, q)
            if len(rows) < 3:
                continue
            last = rows[-3:]
            r = _old_richardson([1.0 / x["level"] for x in last], [x[q] for x in last], fam.order)
            r["runs"] = [x["label"] for x in last]
            out.setdefault(name, {})[q] = r
    return out


def _old_reference_values(records, extrapolations) -> dict:
    out = {}
    for q in QUANTITIES:
        for fam in sorted(FAMILIES.values(), key=lambda f: -f.fidelity):
            if fam.fidelity <= 0 or q not in extrapolations.get(fam.name, {}):
                continue
            ref = dict(extrapolations[fam.name][q])
            ref["family"] = fam.name
            rows = _old_series(records, fam.name, q)
            if len(rows) >= 4:
                prev = rows[-4:-1]
                chk = _old_richardson([1.0 / x["level"] for x in prev], [x[q] for x in prev], fam.order)
                finest = rows[-1][q]
                chk.update(
                    finer_run=rows[-1]["label"],
                    finer_value=finest,
                    difference=finest - chk["value"],
                    within_estimate=abs(finest - chk["value"]) <= chk["error_estimate"],
                )
                ref["check"] = chk
            out[q] = ref
            break
    return out


def _json(obj):
    """What json writes of a dict with numpy numbers, read back."""
    return json.loads(json.dumps(obj, default=lambda x: x.item()))


# ---------------------------------------------------------------------------
# Richardson


@pytest.mark.parametrize(
    "h", [(1 / 8, 1 / 16, 1 / 32), (1 / 8, 1 / 12, 1 / 16), (0.5, 0.3, 0.1)], ids=["r2", "r1.5/1.33", "uneven"]
)
def test_richardson_record_is_the_old_dict_on_a_closed_form(h):
    """f = 1 + h**2: order 2 and limit 1 to round-off, and the record's document is the
    old dict (same keys, same order, same values) with and without a theoretical order."""
    f = [1.0 + x**2 for x in h]
    for theory in (2.0, 4.0, None):
        rec = cv.richardson(h, f, theory)
        assert isinstance(rec, Extrapolation)
        assert rec.order == pytest.approx(2.0, rel=1e-9) and rec.value == pytest.approx(1.0, abs=1e-9)
        doc = rec.to_json()
        assert doc == _json(_old_richardson(h, f, theory)) and list(doc) == list(_old_richardson(h, f, theory))
        assert Extrapolation.from_json(doc) == rec


def test_richardson_record_is_the_old_dict_where_it_falls_back():
    """Not monotone (theory used), no theory at all, and a converged series (d2 = 0)."""
    cases = [
        ([0.5, 0.25, 0.125], [1.0, 1.1, 1.05], 2.0),
        ([0.5, 0.25, 0.125], [1.0, 1.1, 1.05], None),
        ([0.5, 0.25, 0.125], [1.0, 1.0, 1.0], 4.0),
        ([0.5, 0.25, 0.125], [1.2, 1.0, 1.0], 4.0),
    ]
    for h, f, theory in cases:
        doc = cv.richardson(h, f, theory).to_json()
        assert doc == _json(_old_richardson(h, f, theory)), (f, theory)
        assert type(doc["monotone"]) is bool


def _run(family: str, level: int, bending: float | None, ovalling: float | None = None) -> ConvergenceRun:
    return ConvergenceRun(
        key=f"{family}-{level}",
        family=family,
        model=FAMILIES[family].model,
        label=f"{family}, {level}",
        level=level,
        params={"elements_around": level, "degree": 2},
        status="ok",
        bending=bending,
        ovalling=ovalling,
        ovalling_n=None if ovalling is None else 2,
        dofs=100 * level,
    )


def _ladder() -> list[ConvergenceRun]:
    """Two shell families on exact series (C h**4 and C h**2 on top of a limit), one
    with a fifth, failed run and a run missing ovalling; a beam family beside them."""
    runs = [_run("shell_quad", n, 30.8 + 40.0 / n**4, 85.0 + 900.0 / n**4) for n in (8, 12, 16, 24, 32)]
    runs += [_run("shell_tri", n, 30.9 + 3.0 / n**2, None if n == 8 else 85.1 + 80.0 / n**2) for n in (8, 12, 16, 24)]
    runs += [_run("beam_euler", n, 31.3 + 0.2 / n**4) for n in (2, 4, 8)]
    runs.append(replace(_run("shell_quad", 48, None), status="failed", error="test: no convergence"))
    return runs


def test_family_extrapolations_and_references_are_the_old_dicts():
    """On a ladder of exact series: every family's extrapolation and each quantity's
    reference (with its check against the finest run) serialise to the old dicts."""
    runs = _ladder()
    docs = [cache_doc(r) for r in runs]  # the runner's dicts the old code read
    ex = cv.family_extrapolations(runs)
    old_ex = _old_family_extrapolations(docs)
    assert {k: {q: e.to_json() for q, e in v.items()} for k, v in ex.items()} == _json(old_ex)
    ref = cv.reference_values(runs, ex)
    old_ref = _old_reference_values(docs, old_ex)
    assert {q: r.to_json() for q, r in ref.items()} == _json(old_ref)
    assert [list(r.to_json()) for r in ref.values()] == [list(r) for r in old_ref.values()]
    assert ref["bending"].family == "shell_quad" and ref["bending"].check is not None
    assert ref["bending"].value == pytest.approx(30.8, rel=1e-9)  # the exact limit
    assert ex["shell_tri"]["ovalling"].runs == ("shell_tri, 12", "shell_tri, 16", "shell_tri, 24")


# ---------------------------------------------------------------------------
# the runner's runs and the run cache


def _old_record(case, key: str, result: dict) -> dict:
    return {
        "key": key,
        "family": case.family,
        "model": FAMILIES[case.family].model,
        "label": case.label,
        "level": case.level,
        "params": case.settings,
        "status": "ok",
        **result,
    }


def _old_compute_in_process(case, pillar) -> dict:
    from rotorpillar.reduced.beam_fe import BeamProperties, beam_modes
    from rotorpillar.reduced.cylinder import ring_frequency
    from rotorpillar.reduced.pillar import cowper_shear_coefficient, omega_euler_bernoulli, section_of

    sec = section_of(pillar)
    if FAMILIES[case.family].model == "closed_form":
        t = (pillar.outer_diameter - pillar.inner_diameter) / 2
        R = (pillar.outer_diameter + pillar.inner_diameter) / 4
        return {
            "bending": omega_euler_bernoulli(
                pillar.youngs_modulus, sec.second_moment, sec.mass_per_length, pillar.height
            ),
            "ovalling": ring_frequency(2, pillar.youngs_modulus, pillar.poisson_ratio, pillar.density, R, t),
            "ovalling_n": 2,
            "dofs": 1,
            "modes": [],
        }
    s = case.settings
    kappa = cowper_shear_coefficient(pillar.outer_diameter, pillar.inner_diameter, pillar.poisson_ratio)
    props = BeamProperties(
        pillar.youngs_modulus, pillar.poisson_ratio, kappa, pillar.density, sec.area, sec.second_moment, pillar.height
    )
    m = beam_modes(props, s["elements"], s["theory"], n_modes=1)
    return {
        "bending": float(m.omega[0]),
        "ovalling": None,
        "ovalling_n": None,
        "dofs": int(m.dofs),
        "modes": [{"omega": float(m.omega[0]), "kind": "bending_x", "n": 1}],
    }


def test_an_in_process_run_is_the_old_dict():
    """A beam and the closed forms, computed: the run's cache document has the old
    record's keys and values (the pure results to the bit; the cost fields present)."""
    scene = load_scene("paper")
    cases = [c for c in cv.ladder(scene) if FAMILIES[c.family].model in ("closed_form", "beam")][:3]
    for case in cases:
        key = case_key(case, scene.pillar, scene.modal.tolerance)
        result = compute_in_process(case, scene.pillar)
        assert result.to_json() == _json(_old_compute_in_process(case, scene.pillar))
        old = _old_record(case, key, _json(_old_compute_in_process(case, scene.pillar)))
        assert cache_doc(run_record(case, key, result)) == old
        point = cv.run_point(case, scene)
        old_point = _old_record(case, key, point.to_json())
        assert set(old_point) - set(old) == {"wall_time", "peak_memory", "memory_method", "timings"}
        assert cache_doc(run_record(case, key, point)) == old_point


def test_a_modal_summary_is_the_old_dict():
    """The modes of a shell or solid solve summarised as the old dict was."""
    omega = np.array([30.8, 30.8, 85.2, 85.2, 120.0])
    kind = ["bending_x", "bending_y", "ovalling", "ovalling", "torsion"]
    n_circ = [1, 1, 2, 2, None]
    doc = _modal_summary(omega, kind, n_circ, 1234).to_json()
    old = {
        "modes": [{"omega": float(w), "kind": k, "n": n} for w, k, n in zip(omega, kind, n_circ)],
        "bending": 30.8,
        "ovalling": 85.2,
        "ovalling_n": 2,
        "dofs": 1234,
    }
    assert doc == old


def test_cache_files_in_the_old_key_order_still_load(tmp_path):
    """A run cache written by the dict code (its keys in the old order) is a valid cache:
    every run loads from it, cached, and is the run the records' code writes."""
    scene = load_scene("paper")
    cases = [c for c in cv.ladder(scene) if FAMILIES[c.family].model in ("closed_form", "beam")][:4]
    first = cv.run_study(cases, scene, tmp_path, progress=False)
    order = ["key", "family", "model", "label", "level", "params", "status", "bending", "ovalling", "ovalling_n"]
    order += ["dofs", "modes", "wall_time", "peak_memory", "memory_method", "timings"]
    for path in tmp_path.glob("*.json"):
        doc = json.loads(path.read_text())
        assert set(doc) == set(order)  # the old record's keys, no more
        path.write_text(json.dumps({k: doc[k] for k in order}))

    def not_cached(case, sc):
        raise AssertionError(f"{case.label} recomputed")

    again = cv.run_study(cases, scene, tmp_path, runner=not_cached, progress=False)
    assert all(r.cached for r in again)
    assert [replace(r, cached=False) for r in again] == first


def test_drop_aliases_is_the_old_in_place_edit():
    """An "ovalling" mode with more waves than the nodes carry becomes ovalling_alias,
    as the old in-place edit of the run dicts did (a bending-only run's alias included,
    whose ovalling its family does not resolve)."""
    coarse = replace(_run("shell_quad", 4, 30.5, 88.0), ovalling_n=3, params={"elements_around": 4, "degree": 1})
    bending_only = replace(coarse, ovalling=None)
    fine = _run("shell_quad", 16, 30.8, 85.0)
    runs = cv.drop_aliases([coarse, bending_only, fine])
    assert runs[2] is fine
    for r, was in zip(runs[:2], (coarse, bending_only)):
        old = cache_doc(was)
        old.update(ovalling_alias={"omega": old["ovalling"], "n": old["ovalling_n"]}, ovalling=None, ovalling_n=None)
        assert cache_doc(r) == {k: v for k, v in old.items() if k != "ovalling_alias"}
        assert r.to_json()["ovalling_alias"] == old["ovalling_alias"]
