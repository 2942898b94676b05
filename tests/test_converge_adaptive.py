"""The ladder refined only as far as the choice needs (rotorpillar.converge.adaptive),
against the full ladder: every rung of every family.

The check (issue 30.1): the early-stopped study chooses the run the full ladder
chooses, overall and among the 3D models (`modal`'s choice), with fewer runs.
The chosen run's errors agree with the full ladder's within the two references'
uncertainties: both references are Richardson limits of the same family, the
early one from coarser rungs, and each is within its own error estimate (Roache's
GCI) of the limit, so they differ by at most the sum of the two.

- On a synthetic ladder (each family's frequencies f = f_ref (1 + m + C (h/h0)**p),
  with model errors m and orders p like the paper's tube's), at tolerances from
  3e-4 to 3e-2: instant, so the rules are exercised where the choice moves from
  the closed forms to a shell, a side sweep and the 3D models.
- On a real small ladder (beams and shells up to 32 around, no 3D model).
"""

from __future__ import annotations

import math
import shutil

import pytest
from conftest import SHELL_LADDER, shell_runs

from rotorpillar import converge as cv
from rotorpillar.converge.adaptive import SOLID_CLASS
from rotorpillar.converge.ladder import estimated_dofs, estimated_seconds
from rotorpillar.converge.refinement import STOPS
from rotorpillar.converge.result import RunResult
from rotorpillar.converge.study import _closest, ladder_runs
from rotorpillar.scene import load_scene, override

REFERENCE = {"bending": 30.82, "ovalling": 85.06}
"""The limits the synthetic models converge to, or miss by their model error (rad/s)."""

#: model -> per frequency (model error m, a, pa, b, pb): f = f_ref (1 + m + a (8/around)**pa
#: + b (5/along)**pb) for a shell or 3D mesh, f_ref (1 + m + b (1/elements)**pb) for a beam;
#: None: no such mode.  A function of the mesh, not of the family: a mesh on two families'
#: ladders (64 x 10 is a rung of the 3D P2 hexahedra and of their around-only sweep) gives
#: one answer.  Shaped on the paper's full ladder (its convergence.json): the shell's
#: ovalling misses by 1.06e-3, P1 elements lock (large a, b, slow orders), the P2
#: triangles converge slowly, the 3D P2 hexahedra's bending is set by the cells along.
SYNTHETIC = {
    "closed_form": {"bending": (1.67e-2, 0, 1, 0, 1), "ovalling": (-8.1e-3, 0, 1, 0, 1)},
    "beam_euler": {"bending": (1.67e-2, 0, 1, 4.8e-3, 4.0), "ovalling": None},
    "beam_timoshenko": {"bending": (9e-5, 0, 1, 8.6e-2, 2.0), "ovalling": None},
    "shell_quad": {"bending": (-1e-4, 4.5e-4, 4.0, 1.1e-2, 4.0), "ovalling": (-1.06e-3, 1.2e-2, 3.95, 1e-4, 4.0)},
    "shell_tri": {"bending": (-1e-4, 5e-3, 2.0, 5e-3, 2.0), "ovalling": (-1.06e-3, 1.3, 2.7, 1e-3, 2.0)},
    "solid_hex_p1": {"bending": (0.0, 1e-3, 2.0, 0.27, 1.8), "ovalling": (0.0, 45.0, 1.6, 1e-2, 2.0)},
    "solid_tet_p1": {"bending": (0.0, 2e-3, 2.0, 1.4, 2.0), "ovalling": (0.0, 290.0, 1.8, 2e-2, 2.0)},
    "solid_hex_p2": {"bending": (0.0, 2e-4, 4.0, 1.4e-2, 3.2), "ovalling": (0.0, 23.0, 3.8, 1e-3, 3.0)},
    "solid_tet_p2": {"bending": (0.0, 4e-4, 4.0, 2.8e-2, 3.1), "ovalling": (0.0, 30.5, 2.6, 2e-3, 3.0)},
}


def _model_of(case) -> str:
    model, s = cv.FAMILIES[case.family].model, case.settings
    if model in ("closed_form", "beam"):
        return case.family if model == "beam" else model
    if model == "shell":
        return "shell_quad" if s["cell_type"] == "quadrilateral" else "shell_tri"
    return f"solid_{s['cell_type'][:3]}_p{s['degree']}"


def synthetic_runner(case, scene) -> RunResult:
    """A run of the synthetic ladder: its frequencies from SYNTHETIC, its cost the ladder's model."""
    s = case.settings
    freq = {}
    for q, law in SYNTHETIC[_model_of(case)].items():
        if law is None:
            freq[q] = None
            continue
        m, a, pa, b, pb = law
        if "elements_around" in s:
            e = a * (8 / s["elements_around"]) ** pa + b * (5 / s["elements_along"]) ** pb
        else:
            e = b * (1 / s["elements"]) ** pb if "elements" in s else 0.0
        freq[q] = REFERENCE[q] * (1 + m + e)
    return RunResult(
        bending=freq["bending"],
        ovalling=freq["ovalling"],
        ovalling_n=2 if freq["ovalling"] is not None else None,
        dofs=estimated_dofs(case),
        modes=(),
        wall_time=estimated_seconds(case),
    )


def _choices(runs, scene, tol):
    a = cv.analyse(runs, scene, tol)
    solid = cv.select_model(a.runs, a.reference, a.band, tol, families=list(SOLID_CLASS)).chosen
    return a, a.selection.chosen, solid


def _same_choice(early, full, scene, tol):
    a, chosen, solid = _choices(early, scene, tol)
    b, chosen_full, solid_full = _choices(full, scene, tol)
    assert (chosen and chosen.label) == (chosen_full and chosen_full.label), tol
    assert (solid and solid.label) == (solid_full and solid_full.label), tol
    if solid is None:
        # `modal`'s choice where no 3D run meets the tolerance: the most accurate 3D run
        most, most_full = (_closest(x.runs, x.reference, x.band, list(SOLID_CLASS), tol, "")[0] for x in (a, b))
        assert (most and most.label) == (most_full and most_full.label), tol
    if chosen is None:
        return a
    for q in cv.QUANTITIES:
        e, f = chosen.relative_error(q), chosen_full.relative_error(q)
        if e is None or f is None:
            continue
        # the two references differ by at most their two uncertainties (GCI)
        unc = (a.reference[q].error_estimate + b.reference[q].error_estimate) / b.reference[q].value
        assert abs(e - f) <= unc, (tol, q, e, f, unc)
    return a


# 1e-9: no run meets it, and `modal` takes the most accurate 3D run
@pytest.mark.parametrize("tol", [1e-9, 3e-4, 7e-4, 1e-3, 2e-3, 3e-3, 1e-2, 3e-2])
def test_the_early_study_chooses_what_the_full_ladder_chooses(tmp_path, tol):
    scene = load_scene("paper")
    full, whole = ladder_runs(scene, tol, tmp_path, runner=synthetic_runner, full=True)
    early, refined = ladder_runs(scene, tol, tmp_path, runner=synthetic_runner)
    assert whole.full and whole.runs == whole.ladder_runs == len(full) == len(cv.ladder(scene))
    assert not refined.full and refined.runs == len(early) < len(full)
    assert {r.label for r in early} <= {r.label for r in full}
    assert all(r.cached for r in early)  # the full ladder's runs, read from the cache
    _same_choice(early, full, scene, tol)
    stops = {f.family: f.stop for f in refined.families}
    assert stops["solid_hex_p2_along"] == "ladder end" == stops["closed_form"]
    assert all(s in STOPS for s in stops.values())


def test_what_stops_each_family_at_the_papers_tolerance(tmp_path):
    """At 1e-3 the band needs both frequencies: the beams lack the ovalling mode, the
    around-only 3D sweep's bending is held above the tolerance by its cells along, the
    locking families cost too much, the P2 hexahedra meet it; the reference family stops
    short of its finest rungs."""
    scene = load_scene("paper")
    runs, refined = ladder_runs(scene, 1e-3, tmp_path, runner=synthetic_runner)
    stop = {f.family: f for f in refined.families}
    assert stop["beam_euler"].stop == stop["beam_timoshenko"].stop == "no mode"
    assert stop["beam_euler"].runs == 3
    assert stop["solid_hex_p2_around"].stop == "model error"
    assert stop["solid_hex_p1"].stop == stop["solid_tet_p1"].stop == "cost"
    assert stop["solid_hex_p2"].stop == "tolerance met"
    assert stop["solid_hex_p2"].runs < stop["solid_hex_p2"].rungs
    # every round's decisions were made on whole rounds: a second study reads the same runs
    again, _ = ladder_runs(scene, 1e-3, tmp_path, runner=synthetic_runner)
    assert [r.label for r in again] == [r.label for r in runs] and all(r.cached for r in again)


def test_the_reference_family_is_refined_while_its_uncertainty_decides(tmp_path):
    """A run that meets the tolerance but for the reference's own uncertainty keeps the
    reference's family refining: with the shell's ovalling model error just inside a
    tolerance of 1.2e-3, the shell's coarse runs are only shown to meet it by a finer
    reference; the early study finds the shell the full ladder finds."""
    scene = load_scene("paper")
    tol = 1.2e-3
    full, _ = ladder_runs(scene, tol, tmp_path, runner=synthetic_runner, full=True)
    early, refined = ladder_runs(scene, tol, tmp_path, runner=synthetic_runner)
    a = _same_choice(early, full, scene, tol)
    assert a.selection.chosen is not None and a.selection.chosen.family == "shell_quad"
    ref = {f.family: f for f in refined.families}["solid_hex_p2"]
    assert ref.runs > 3


def test_without_a_reference_every_rung_runs(tmp_path):
    """No family with three rungs: no reference, no error estimate, nothing to stop on."""
    scene = override(
        load_scene("paper"),
        ["converge.solid=false", "converge.shell_max_around=12", "converge.shell_tri_max_around=8"],
    )
    runs, refined = ladder_runs(scene, 1e-3, tmp_path, runner=synthetic_runner)
    assert refined.runs == refined.ladder_runs == len(cv.ladder(scene)) == len(runs)


def test_a_tolerance_no_run_meets_takes_the_full_ladders_most_accurate_3d_run(tmp_path):
    # A short 3D ladder (tests/test_converge_cli.py's): the P2 hexahedra have one rung, so
    # the most accurate 3D run is the around-only family's finest, 48x10x1.  Its model error
    # stopped it after three rungs, and `modal --tolerance 1e-9` took 32x5x1 (band error 0.12
    # against 0.028) until the 3D families ran on where no 3D run meets the tolerance.
    scene = override(
        load_scene("paper"),
        [
            "converge.shell_max_around=16",
            "converge.shell_tri_max_around=8",
            "converge.solid_p1_max_around=32",
            "converge.solid_p2_max_around=48",
            "converge.solid_tet_p2_max_around=32",
        ],
    )
    full, _ = ladder_runs(scene, 1e-9, tmp_path, runner=synthetic_runner, full=True)
    early, refined = ladder_runs(scene, 1e-9, tmp_path, runner=synthetic_runner)
    assert refined.runs < refined.ladder_runs  # the shells still stop early
    a = _same_choice(early, full, scene, 1e-9)
    most, _ = _closest(a.runs, a.reference, a.band, list(SOLID_CLASS), 1e-9, "")
    assert most is not None and most.label == "3D P2 hexahedra, around only, 48x10x1"
    stops = {f.family: f.stop for f in refined.families}
    assert all(stops[f] == "ladder end" for f in SOLID_CLASS)


@pytest.mark.slow  # beams and shells up to 32 around (the shells: the session's run cache)
def test_a_real_small_ladder_chooses_what_its_full_ladder_chooses(tmp_path, tmp_path_factory):
    # its shell rungs read from a copy of the session's run cache (conftest.shell_runs:
    # the same runs, by the same runner); the closed forms and beams computed here
    shell_cache = tmp_path / "cache"
    shutil.copytree(shell_runs(tmp_path_factory), shell_cache)
    scene = override(load_scene("paper"), list(SHELL_LADDER))
    full, _ = ladder_runs(scene, 2e-3, shell_cache, full=True)
    for tol in (1e-3, 2e-3, 5e-3, 2e-2):
        early, refined = ladder_runs(scene, tol, shell_cache)
        assert refined.runs < refined.ladder_runs and all(r.cached for r in early)
        _same_choice(early, full, scene, tol)
    assert math.isfinite(sum(r.wall_time or 0.0 for r in full))
