"""The 3D rungs of the convergence study (slow: 3D P2 models up to 95k DOFs).

Sources and tolerances:

- Lagrange elements of degree k: eigenvalue (and frequency) error ~ h**(2k)
  for a smooth mode (Strang and Fix, An Analysis of the Finite Element
  Method, 1973, sec. 6.3): 4 for P2.  The first bending mode is smooth except
  in the clamp's 3D boundary layer under the base rim, about one wall
  thickness t = 2 cm deep.  With cells graded 200:1 towards the base the
  smallest cell (2.5 cm at 20 along) resolves it, and the observed order
  over 64, 96, 128 around (measured 3.92) must lie in [3.3, 4.7]; with the scene's grading
  30 (smallest cell 11 cm) it is lower (measured 2.9 there, ~2 further up the
  ladder), which the study reports as "not asymptotic" and explains.
- Richardson's reference from 32, 64, 96 around must predict an
  independent finer run (128 around) within its own error estimate
  (Roache's GCI, safety factor 1.25), for both frequencies.  Measured
  (issue 30): |error| / estimate 0.21 (bending) and 0.27 (ovalling); from
  64, 96, 128 against 160 it was 0.36 and 0.34, the same check a rung finer
  at 2.6 times the cost (the 160 run alone was half the study's time).
- Another method: the shell model's converged limits against the 3D
  model's.  Bending: the shell's clamp leaves the wall's Poisson contraction
  free at the base, the 3D clamp does not: 3e-4.  Ovalling: the shell's
  first-order kinematics differ from 3D elasticity by O(t/R) = 2e-2 at
  most; measured 1.1e-3 (the study shows it as the shell's model error);
  2e-3 here.  The limits: the 3D model's from 64, 96, 128 around (bending
  measured -2.2e-4, ovalling -1.07e-3; from 96, 128, 160: -1.5e-4 and
  -1.07e-3), the shell's from 16, 24, 32 (the same limits as from 24, 32, 48
  to 1e-7: the shell's Q2 rungs are converged far below both tolerances).
- The runs are the fewest these three checks allow (issue 30, measured): the
  3D runs' process times 1.1, 1.1, 3.4, 6.0 s at 32, 64, 96, 128 around.
  Richardson and the shell from grading 200 alone (32, 64, 96 against 128:
  |error| / estimate 0.37 and 0.27; shell limits -9e-5 and -1.07e-3 off)
  would drop the scene grading's 64 ... 128, but with them the check that its
  order is lower: over 32, 64, 96 the two orders are 3.39 and 3.47, too close
  to tell apart; only the finer rungs separate them (2.9 against 3.92).
- The shell's rungs are read from the session's run cache of the shell ladder
  (conftest.shell_runs), which four other slow tests read too: computed once,
  not in each (issue 30).
"""

import shutil

import pytest
from conftest import once_per_session, shell_runs

from rotorpillar import converge as cv
from rotorpillar import records
from rotorpillar.scene import load_scene, override

pytestmark = pytest.mark.slow


def _cases(scene, family, levels):
    return [c for c in cv.ladder(scene) if c.family == family and c.level in levels]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    # Once for the session, workers included (issue 30): under `make test` (xdist,
    # worksteal) this module's tests land on both workers, and a module fixture ran the
    # whole study on each (63 s in CI; 136 s and 69 s measured side by side on 2 busy
    # cores).  The runs are the same records either way: the first worker computes them,
    # the other reads them back through their record type, so every test below still
    # checks the numbers of these very runs.
    def compute(out):
        # the shell rungs from the session's run cache (conftest.shell_runs: the
        # same runs, keyed by case, tube and code), computed once for five tests
        shutil.copytree(shell_runs(tmp_path_factory), out, dirs_exist_ok=True)
        scene = load_scene("paper")
        graded = override(scene, ["mesh.grading=200"])
        done = {
            # close=False: the next study reuses this one's serving process (its imports)
            "g30": cv.run_study(
                _cases(scene, "solid_hex_p2", (32, 64, 96, 128)), scene, out, progress=False, close=False
            ),
            "g200": cv.run_study(
                _cases(graded, "solid_hex_p2", (64, 96, 128)), graded, out, progress=False, close=False
            ),
            "shell": cv.run_study(_cases(scene, "shell_quad", (16, 24, 32)), scene, out, progress=False),
        }
        return records.to_builtins(done)

    _, done = once_per_session("converge_solid_runs", tmp_path_factory, compute)
    return {name: records.convert(rows, list[cv.ConvergenceRun]) for name, rows in done.items()}


def _order(recs, q):
    rows = recs[-3:]
    return cv.richardson([1 / r.level for r in rows], [r.frequency(q) for r in rows], 4.0)


def test_p2_hexahedra_bending_order_is_theirs_once_the_clamp_layer_is_resolved(runs):
    assert all(r.status == "ok" for rs in runs.values() for r in rs)
    p200 = _order(runs["g200"], "bending").order
    p30 = _order(runs["g30"][1:], "bending").order  # 64, 96, 128 as g200's
    assert p200 is not None and 3.3 <= p200 <= 4.7, p200
    assert p30 is not None and p30 < p200


def test_p2_hexahedra_reference_predicts_a_finer_run(runs):
    recs = runs["g30"]
    ref = cv.reference_values(recs, cv.family_extrapolations(recs))
    for q in ("bending", "ovalling"):
        chk = ref[q].check
        assert chk.finer_run.endswith("128x20x1")
        assert abs(chk.finer_value - chk.value) <= chk.error_estimate, (q, chk)


def test_shell_and_3d_limits_agree_within_the_shells_model_error(runs):
    solid = cv.family_extrapolations(runs["g30"][1:])["solid_hex_p2"]  # 64, 96, 128
    shell = cv.family_extrapolations(runs["shell"])["shell_quad"]
    assert shell["bending"].value == pytest.approx(solid["bending"].value, rel=3e-4)
    assert shell["ovalling"].value == pytest.approx(solid["ovalling"].value, rel=2e-3)
