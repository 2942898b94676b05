"""The suite's VTK hygiene (tests/conftest.py) fails the tests it should, and only those.

As pyvista checks its own ``check_gc``: small test files run by pytest in a
child process with this suite's conftest.py: a ``renders`` test that leaves
a VTK object alive in a module global or a cache fails; one that lets its
objects go (a reference cycle included: VTK 9's wrappers take part in the
garbage collection) passes; any test that leaves a pyvista plotter open
fails, marked or not.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

pytest_plugins = ["pytester"]

CASES = """
import pytest

import functools

GLOBAL = []


@functools.lru_cache
def cached_source(n):
    import vtk
    source = vtk.vtkSphereSource()
    source.SetThetaResolution(n)
    return source


@pytest.mark.renders
def test_cache():
    cached_source(8).Update()                # a cache keeps the source...


@pytest.mark.renders
def test_global():
    import vtk
    GLOBAL.append(vtk.vtkPolyData())        # ...a module global the data


@pytest.mark.renders
def test_clean():
    import vtk
    source = vtk.vtkSphereSource()
    source.self_ref = source                 # a cycle: collected
    source.Update()
    assert source.GetOutput().GetNumberOfPoints() > 0


def test_plotter_left_open():
    from rotorpillar.postprocess.offscreen import pyvista
    pyvista().Plotter(off_screen=True)


@pytest.mark.renders
def test_plotter_closed():
    from rotorpillar.postprocess.offscreen import pyvista
    pv = pyvista()
    p = pv.Plotter(off_screen=True, window_size=(16, 16))
    p.add_mesh(pv.Sphere())
    p.screenshot(return_img=True)
    p.close()
"""


def test_the_leak_check_fails_leaking_tests_and_passes_clean_ones(pytester: pytest.Pytester):
    shutil.copy(Path(__file__).with_name("conftest.py"), pytester.path / "conftest.py")
    pytester.makepyfile(test_cases=CASES)
    result = pytester.runpytest_subprocess(
        "-p", "no:cacheprovider", "-q", "-o", "markers=renders: in-process rendering"
    )
    # the fixture checks after the test, as pyvista's does: a leak is an error at teardown
    result.assert_outcomes(passed=5, errors=3)
    errors = sorted(line.split()[1] for line in result.outlines if line.startswith("ERROR "))
    assert errors == [
        "test_cases.py::test_cache",
        "test_cases.py::test_global",
        "test_cases.py::test_plotter_left_open",
    ]
    text = "\n".join(result.outlines)
    assert "vtkSphereSource" in text and "PolyData" in text
    assert "VTK objects outlive the test" in text and "plotter(s) left open" in text
