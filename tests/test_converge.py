"""The convergence study: Richardson, Pareto fronts, the cache, resuming, the choice of a model.

Sources and tolerances:

- Richardson extrapolation (Roache, Verification and Validation in
  Computational Science and Engineering, 1998, ch. 5): on an exact series
  f = f_inf + C h**p it returns p and f_inf to round-off (1e-9), for any
  refinement ratios.
- The 1D beam ladders converge at their theoretical orders: Hermite cubic
  Euler-Bernoulli elements at h**4, linear Timoshenko elements with one-point
  shear at h**2 (Strang and Fix, An Analysis of the Finite Element Method,
  1973, sec. 6.3: eigenvalue error h**(2(k+1-m))); band +-0.3.  Their limits
  are Eq. 1 (1e-9) and the Timoshenko closed form (1e-6).
- The shell ladder's reference, extrapolated from three runs, must agree
  with an independent finer run within its own error estimate (Roache's GCI
  with safety factor 1.25).
- Resuming: an interrupted study (KeyboardInterrupt in the middle of a run)
  leaves only complete cache files, and the next call computes exactly the
  runs that were missing.  Checked by counting calls, not by timing.
"""

import json
import math
import shutil
from pathlib import Path

import msgspec
import numpy as np
import pytest
from conftest import shell_runs

from rotorpillar import converge as cv
from rotorpillar import records
from rotorpillar.records import replace
from rotorpillar.scene import load_scene, override


def test_richardson_recovers_order_and_limit_for_any_ratios():
    for p in (1.0, 2.0, 4.0):
        h = np.array([1 / 8, 1 / 12, 1 / 16])
        f = 3.0 + 0.7 * h**p
        r = cv.richardson(h, f, p)
        assert r.order == pytest.approx(p, rel=1e-9)
        assert r.value == pytest.approx(3.0, abs=1e-9)
        assert r.monotone
        assert r.error_estimate == pytest.approx(1.25 * 0.7 * h[2] ** p, rel=1e-6)


def test_richardson_falls_back_to_theory_when_not_monotone():
    r = cv.richardson([0.5, 0.25, 0.125], [1.0, 1.1, 1.05], 2.0)
    assert r.order is None and not r.monotone
    assert r.value == pytest.approx(1.05 + (1.05 - 1.1) / 3)
    with pytest.raises(ValueError):
        cv.richardson([0.1, 0.2, 0.3], [1, 2, 3])


def test_pareto_front_is_what_brute_force_says():
    rng = np.random.default_rng(3)
    cost = rng.uniform(1, 100, 40)
    err = rng.uniform(-1, 1, 40) * 1e-2
    front = cv.pareto_front(list(cost), list(err))
    brute = [
        i
        for i in range(40)
        if not any(
            (cost[j] <= cost[i] and abs(err[j]) <= abs(err[i])) and (cost[j] < cost[i] or abs(err[j]) < abs(err[i]))
            for j in range(40)
        )
    ]
    assert sorted(front) == sorted(brute)
    assert [cost[i] for i in front] == sorted(cost[i] for i in front)
    assert cv.pareto_front([1.0, 2.0], [None, 0.1]) == [1]


def _beam_cases():
    return [c for c in cv.ladder(load_scene("paper")) if cv.FAMILIES[c.family].model in ("closed_form", "beam")]


def test_beam_ladder_orders_and_limits(tmp_path):
    from rotorpillar.reduced.pillar import cowper_shear_coefficient, omega_euler_bernoulli, omega_timoshenko, section_of

    scene = load_scene("paper")
    recs = cv.run_study(_beam_cases(), scene, tmp_path, progress=False)
    ex = cv.family_extrapolations(recs)
    assert ex["beam_euler"]["bending"].order == pytest.approx(4.0, abs=0.3)
    assert ex["beam_timoshenko"]["bending"].order == pytest.approx(2.0, abs=0.3)
    p, sec = scene.pillar, section_of(scene.pillar)
    eq1 = omega_euler_bernoulli(p.youngs_modulus, sec.second_moment, sec.mass_per_length, p.height)
    kappa = cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    timo = omega_timoshenko(p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area, sec.second_moment, p.height)
    assert ex["beam_euler"]["bending"].value == pytest.approx(eq1, rel=1e-9)
    assert ex["beam_timoshenko"]["bending"].value == pytest.approx(timo, rel=1e-6)
    closed = next(r for r in recs if r.family == "closed_form")
    assert closed.bending == pytest.approx(eq1) and closed.ovalling_n == 2
    assert all(r.ovalling is None for r in recs if r.model == "beam")
    for r in recs:
        assert r.dofs >= 1 and r.wall_time >= 0 and r.peak_memory > 0


def test_cache_key_follows_the_parameters():
    scene = load_scene("paper")
    c = _beam_cases()[3]
    k = cv.case_key(c, scene.pillar)
    assert k == cv.case_key(c, scene.pillar)
    assert k != cv.case_key(c, override(scene, ["pillar.youngs_modulus=2.0e11"]).pillar)
    assert k != cv.case_key(_beam_cases()[4], scene.pillar)
    # the rotor and drive do not enter the bare tube's runs
    assert k == cv.case_key(c, override(scene, ["rotor.mass=2000"]).pillar)
    # the 3D eigen-solve's tolerance enters the 3D runs only
    solid = next(x for x in cv.ladder(scene) if x.family == "solid_hex_p2")
    assert cv.case_key(solid, scene.pillar, 1e-8) != cv.case_key(solid, scene.pillar, 1e-10)
    assert cv.case_key(c, scene.pillar, 1e-8) == cv.case_key(c, scene.pillar, 1e-10)


def test_an_interrupted_study_resumes_without_recomputing(tmp_path):
    scene = load_scene("paper")
    cases = _beam_cases()
    calls = []

    def interrupted(case, sc):
        if len(calls) == 5:
            raise KeyboardInterrupt  # mid-study, as a Ctrl-C would
        calls.append(case)
        return cv.run_point(case, sc)

    with pytest.raises(KeyboardInterrupt):
        cv.run_study(cases, scene, tmp_path, runner=interrupted, progress=False)
    files = sorted(tmp_path.iterdir())
    assert len(files) == 5 and all(f.suffix == ".json" and not f.name.startswith(".") for f in files)
    for f in files:
        json.loads(f.read_text())  # every file complete

    again = []

    def counting(case, sc):
        again.append(case)
        return cv.run_point(case, sc)

    recs = cv.run_study(cases, scene, tmp_path, runner=counting, progress=False)
    assert [c.label for c in again] == [c.label for c in cases[5:]]
    assert sum(r.cached for r in recs) == 5
    assert len(list(tmp_path.iterdir())) == len(cases)
    third = cv.run_study(cases, scene, tmp_path, runner=counting, progress=False)
    assert len(again) == len(cases) - 5 and all(r.cached for r in third)


def _records(**runs):
    """Synthetic runs: name -> (family, wall_time, dofs, bending, ovalling), each of the
    last two (model error, discretisation error) relative, or None (no such mode)."""
    out = []
    for label, (fam, t, dofs, *qs) in runs.items():
        r = cv.ConvergenceRun(
            key=label,
            family=fam,
            model=cv.FAMILIES[fam].model,
            label=label,
            level=0,
            params={},
            status="ok",
            cached=False,
            wall_time=t,
            dofs=dofs,
        )
        for q, ref, split in zip(("bending", "ovalling"), (30.0, 85.0), qs):
            if split is None:
                continue  # no such mode: the frequency and its errors None
            model, disc = split
            r = replace(
                r,
                **{
                    q: ref * (1 + model + disc),
                    f"{q}_error": model + disc,
                    f"{q}_model_error": model,
                    f"{q}_discretisation_error": disc,
                    f"{q}_error_bound": abs(model) + abs(disc),
                },
            )
        out.append(r)
    return out


def _extrapolation(value, error_estimate=0.0, family=None):
    """A Richardson value (rad/s) with its error estimate: a family's, or a reference."""
    ex = cv.FamilyExtrapolation(
        order=4.0, order_theory=4.0, monotone=True, value=value, error_estimate=error_estimate, h=(), f=(), runs=()
    )
    return ex if family is None else cv.ReferenceValue(**msgspec.structs.asdict(ex), family=family)


REF = {
    "bending": _extrapolation(30.0, 30.0 * 1e-5, "solid_hex_p2"),
    "ovalling": _extrapolation(85.0, 85.0 * 1e-5, "solid_hex_p2"),
}
BAND = cv.ExcitationBand(
    omega_max=135.0, free_speed=90.0, earthquake_frequency=math.pi, margin=1.5, driver="drive free speed"
)


def test_selection_takes_the_cheapest_run_that_meets_the_band():
    recs = _records(
        beam=("beam_timoshenko", 0.001, 64, (1e-4, 1e-4), None),
        coarse=("shell_quad", 1.0, 5000, (1e-5, 1e-4), (1e-4, 3e-3)),
        fine=("shell_quad", 3.0, 20000, (1e-5, 1e-6), (1e-4, 4e-4)),
        solid=("solid_hex_p2", 10.0, 50000, (0, 1e-6), (0, 1e-5)),
    )
    sel = cv.select_model(recs, REF, BAND, 1e-3)
    assert sel.needed == ("bending", "ovalling")
    assert sel.chosen is not None and sel.chosen.label == "fine"
    why = {r.label: r.why for r in sel.rejected_cheaper}
    assert "no ovalling" in why["beam"] and "ovalling error bound" in why["coarse"]
    assert "fine" in sel.reason and "135.0 rad/s" in sel.reason
    # a slow scene whose band stops below the ovalling mode: the beam will do
    low = replace(BAND, omega_max=50.0)
    assert cv.select_model(recs, REF, low, 1e-3).chosen.label == "beam"
    # a tolerance nothing meets: no choice, and it says so
    none = cv.select_model(recs, REF, BAND, 1e-7)
    assert none.chosen is None and "no model" in none.reason
    # restricted to the 3D models
    assert cv.select_model(recs, REF, BAND, 1e-3, families=["solid_hex_p2"]).chosen.label == "solid"


def test_a_familys_finer_rung_measured_faster_under_load_is_not_chosen():
    """Two rungs of one family both meet the tolerance and the finer one's wall time came out
    lower (measured on a loaded machine: 160x25x1 18.3 s against 128x20x1 19.6 s): the family
    offers its coarsest candidate, so the choice does not follow the load; across families wall
    time still ranks."""
    recs = _records(
        coarse=("solid_hex_p2", 19.6, 94464, (0, 1e-5), (0, 2e-4)),
        finer=("solid_hex_p2", 18.3, 146880, (0, 1e-6), (0, 1e-4)),
        shell=("shell_quad", 25.0, 20000, (1e-5, 1e-6), (1e-4, 4e-4)),
    )
    sel = cv.select_model(recs, REF, BAND, 1e-3)
    assert sel.chosen is not None and sel.chosen.label == "coarse"
    assert "coarsest" in sel.rule
    faster_shell = _records(shell=("shell_quad", 5.0, 20000, (1e-5, 1e-6), (1e-4, 4e-4)))
    assert cv.select_model(recs[:2] + faster_shell, REF, BAND, 1e-3).chosen.label == "shell"


def test_selection_gives_no_credit_for_cancelling_errors():
    # the shell's limit is 1.1e-3 off (model error); a coarse mesh that errs the
    # other way lands within 1e-4 of the reference by luck: not chosen
    recs = _records(
        lucky=("shell_quad", 0.4, 6560, (1e-5, 1e-5), (-1.1e-3, 1.0e-3)),
        solid=("solid_hex_p2", 14.0, 94464, (0, 1e-4), (0, 6e-4)),
    )
    sel = cv.select_model(recs, REF, BAND, 1e-3)
    assert abs(recs[0].ovalling_error) < 1.5e-4
    assert sel.chosen.label == "solid"
    assert "model -1.1e-03" in sel.rejected_cheaper[0].why


def test_errors_split_into_model_and_discretisation():
    def run(family, bending, ovalling):
        model = cv.FAMILIES[family].model
        return cv.ConvergenceRun(
            key=family,
            family=family,
            model=model,
            label=family,
            level=0,
            params={},
            status="ok",
            cached=False,
            bending=bending,
            ovalling=ovalling,
        )

    recs = (run("shell_quad", 30.3, None), run("closed_form", 31.0, 84.0))
    ex = {"shell_quad": {"bending": _extrapolation(30.6)}}
    ref = {"bending": _extrapolation(30.0, family="shell_quad"), "ovalling": _extrapolation(85.0, family="shell_quad")}
    s, c = cv.attach_errors(recs, ref, ex)
    assert recs[0].bending_error is None  # new records: the runs given are left as they were
    assert s.bending_error == pytest.approx(0.01)
    assert s.bending_model_error == pytest.approx(0.02)
    assert s.bending_discretisation_error == pytest.approx(-0.01)
    assert s.bending_error_bound == pytest.approx(0.03)
    assert s.ovalling_error is None and s.ovalling_error_bound is None
    assert c.ovalling_error_bound == pytest.approx(1 / 85)  # no limit: |measured|


def test_excitation_band_of_the_paper_scene():
    paper = load_scene("paper")
    band = cv.excitation_band(paper.drive, paper.load, paper.converge)
    # Md = Mc: 5100 - 12 W = 0.5 W**2
    assert band.free_speed == pytest.approx(-12 + math.sqrt(144 + 2 * 5100))
    assert band.omega_max == pytest.approx(1.5 * band.free_speed)
    fast = override(paper, ["converge.earthquake_frequency=100"])
    quake = cv.excitation_band(fast.drive, fast.load, fast.converge)
    assert quake.driver == "earthquake" and quake.omega_max == pytest.approx(150.0)


@pytest.fixture
def shell_cache(tmp_path, tmp_path_factory) -> Path:
    """A copy of :func:`conftest.shell_runs`' cache for this test alone (tmp_path/"cache")."""
    cache = tmp_path / "cache"
    shutil.copytree(shell_runs(tmp_path_factory), cache)
    return cache


@pytest.mark.slow  # a shell ladder up to 32 around
def test_shell_reference_agrees_with_a_finer_run(shell_cache):
    scene = override(load_scene("paper"), ["converge.solid=false", "converge.shell_max_around=32"])
    cases = [c for c in cv.ladder(scene) if c.family == "shell_quad" and c.level >= 12]
    recs = cv.run_study(cases, scene, shell_cache, progress=False)
    ref = cv.reference_values(recs, cv.family_extrapolations(recs))
    for q in ("bending", "ovalling"):
        chk = ref[q].check
        assert chk.within_estimate, (q, chk)
        assert abs(chk.finer_value - chk.value) <= chk.error_estimate


def test_the_study_document_round_trips_through_its_type(tmp_path, monkeypatch):
    """convergence.json as written is the study's record beside its provenance, computed
    or read from the run cache (the same numbers); a field of the wrong kind is named."""
    import importlib

    study_module = importlib.import_module("rotorpillar.converge.study")
    scene = override(load_scene("paper"), ["converge.solid=false"])
    cheap = [
        c
        for c in cv.ladder(scene)
        if cv.FAMILIES[c.family].model in ("closed_form", "beam") or (c.family == "shell_quad" and c.level <= 16)
    ]
    monkeypatch.setattr(study_module, "study_cases", lambda sc: cheap)
    # the whole (cheap) ladder: every rung run, so the counts are the ladder's
    st = cv.study(scene, out_dir=tmp_path, tolerance=1e-2, show_progress=False, full=True)
    path = tmp_path / "convergence.json"
    assert st.json_file == str(path) and st.chosen is not None and st.study.computed == len(cheap)
    assert st.refinement is not None and st.refinement.full and st.refinement.runs == len(cheap)
    doc = json.loads(path.read_text())
    again = records.read(path, cv.ConvergenceStudy)
    mine = records.to_builtins(again)
    assert mine == {k: doc[k] for k in mine} and set(doc) - set(mine) == {"versions", "machine", "timings"}
    assert [records.to_builtins(r) for r in again.runs] == doc["runs"] and again.failures == tuple(doc["failures"])
    assert set(again.reference) == {"bending", "ovalling"} and again.charts is None
    assert "json" not in doc and again.json_file is None
    cached = cv.study(scene, out_dir=tmp_path, tolerance=1e-2, show_progress=False, full=True)
    assert cached.study.cached == len(cheap) and [r.bending for r in cached.runs] == [r.bending for r in again.runs]
    doc["runs"][0]["bending"] = "fast"
    path.write_text(json.dumps(doc))
    with pytest.raises(
        ValueError, match=r"convergence\.json: Expected `float \| null`, got `str` - at `\$\.runs\[0\]\.bending`"
    ):
        records.read(path, cv.ConvergenceStudy)


@pytest.mark.slow  # shell and 3D eigensolves, twice each
def test_runs_asking_few_modes_first_give_what_the_full_count_gives():
    """compute_fe asks N_MODES_FIRST modes and N_MODES when the first ovalling
    mode is not among them: the quantities are those of an N_MODES solve (the
    lowest modes are the same eigenpairs; 1e-8 relative, the solver's
    tolerance).  A fine shell finds its ovalling pair among the first 6; a
    coarse P1 tube, whose locked ovalling mode lies high, widens to 12."""
    from rotorpillar.converge.compute import _compute_fe, compute_fe
    from rotorpillar.converge.ladder import N_MODES, N_MODES_FIRST

    scene = load_scene("paper")
    cases = {(c.family, c.level): c for c in cv.ladder(scene)}
    for key, asked in ((("shell_quad", 24), N_MODES_FIRST), (("solid_tet_p1", 32), N_MODES)):
        got = compute_fe(cases[key], scene, fresh=True)
        full = _compute_fe(cases[key], scene, N_MODES, True)
        assert got.modes_asked == asked
        for q in ("bending", "ovalling"):
            assert getattr(got, q) == pytest.approx(getattr(full, q), rel=1e-8)
