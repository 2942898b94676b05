"""A modal analysis in a second process (rotorpillar.fem3d.beside) gives this process's answer.

Sources and tolerances
----------------------
- The reference is the same solve done here (``modal_analysis`` with its cache off):
  the same code on the same input.  The frequencies and the shapes agree to 1e-12
  relative: only round-off could differ between two processes (measured: bit for
  bit on the paper's 128 x 20 mesh).
- The result lands in this process's cache: the caller's ``modal_analysis`` after it
  returns that very object (no second solve).
- A second process that fails (here: a module that does not exist) leaves the
  solve to this process, with the same answer, and says so in one line on stderr.
- ``start`` starts none for a result already in this process's cache (it would be
  solved twice).
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorpillar import fem3d
from rotorpillar.fem3d import beside as beside_module
from rotorpillar.fem3d import modal_analysis
from rotorpillar.fem3d.beside import Beside
from rotorpillar.scene import load_scene
from rotorpillar.scene.sections import Mesh

SMALL = Mesh(elements_around=16, elements_along=4)  # a 3D solve of about a second


def _same(got, expected) -> None:
    np.testing.assert_allclose(got.omega, expected.omega, rtol=1e-12)
    assert got.kind == expected.kind
    np.testing.assert_allclose(np.abs(got.shapes), np.abs(expected.shapes), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("top", [False, True])
def test_the_second_process_solves_what_this_one_would(top):
    scene = load_scene("paper")
    here = modal_analysis(scene, top=top, n_modes=8, mesh=SMALL, use_cache=False)
    fem3d._CACHE.clear()
    with Beside(scene, top=top, n_modes=8, mesh=SMALL) as job:
        there = job.result()
    _same(there, here)
    # in this process's cache now: the next call reads it, it does not solve again
    assert modal_analysis(scene, top=top, n_modes=8, mesh=SMALL) is there


def test_a_failed_second_process_leaves_the_solve_here(monkeypatch, capsys):
    scene = load_scene("paper")
    here = modal_analysis(scene, top=False, n_modes=8, mesh=SMALL, use_cache=False)
    fem3d._CACHE.clear()
    monkeypatch.setattr(beside_module, "MODULE", "rotorpillar.no_such_module")
    with Beside(scene, top=False, n_modes=8, mesh=SMALL) as job:
        assert job.proc is not None and job.proc.wait() != 0
        there = job.result()
    _same(there, here)
    assert not job.folder.exists()  # its folder removed
    said = capsys.readouterr().err
    assert "second process's solve failed" in said and "No module named" in said and "solving here" in said


def test_no_second_process_for_a_result_this_one_holds():
    scene = load_scene("paper")
    fem3d._CACHE.clear()
    assert not fem3d.in_cache(scene, False, 8, SMALL)
    modal_analysis(scene, top=False, n_modes=8, mesh=SMALL)
    assert fem3d.in_cache(scene, False, 8, SMALL)
    assert beside_module.start(scene, top=False, n_modes=8, mesh=SMALL) is None
