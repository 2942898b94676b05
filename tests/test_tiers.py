"""The tiers of tests/conftest.py: a test that uses the main job's fixture is slow, and
the main job runs once per test session even on several pytest-xdist workers
(``make test``: -n 2).

Checked as pyvista checks its conftest: test files run by pytest in a child
process with this suite's conftest.py; ``run_paper`` replaced by a cheap fixture
of the same name that goes through :func:`conftest.once_per_session` and counts
its computations in a file.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

pytest_plugins = ["pytester"]

USERS = """
import os
import pytest
from conftest import once_per_session


@pytest.fixture(scope="session")
def run_paper(tmp_path_factory):
    def compute(out):
        with open(os.environ["CALLS"], "a") as fh:
            fh.write(os.environ.get("PYTEST_XDIST_WORKER", "main") + "\\n")
        (out / "report.html").write_text("done")
        return {"returncode": 0}
    return once_per_session("run_paper", tmp_path_factory, compute)


@pytest.mark.parametrize("i", range(6))
def test_uses_the_main_job(run_paper, i):
    out, record = run_paper
    assert record == {"returncode": 0} and (out / "report.html").read_text() == "done"


@pytest.mark.parametrize("i", range(4))
def test_does_not(i):
    pass
"""


@pytest.fixture
def suite(pytester: pytest.Pytester, tmp_path: Path, monkeypatch) -> pytest.Pytester:
    shutil.copy(Path(__file__).with_name("conftest.py"), pytester.path / "conftest.py")
    pytester.makepyfile(test_users=USERS)
    monkeypatch.setenv("CALLS", str(tmp_path / "calls"))
    return pytester


def test_users_of_the_main_job_are_slow(suite):
    result = suite.runpytest_subprocess("-p", "no:cacheprovider", "-q", "-m", "not slow", "-o", "markers=slow: x")
    result.assert_outcomes(passed=4, deselected=6)


def test_the_main_job_runs_once_on_two_workers(suite, tmp_path):
    result = suite.runpytest_subprocess("-p", "no:cacheprovider", "-v", "-n", "2", "-o", "markers=slow: x")
    result.assert_outcomes(passed=10)
    workers = {line.split()[0] for line in result.outlines if "PASSED" in line and "test_uses_the_main_job" in line}
    assert workers == {"[gw0]", "[gw1]"}  # both workers used the fixture...
    calls = (tmp_path / "calls").read_text().split()
    assert len(calls) == 1 and calls[0].startswith("gw"), calls  # ...computed once
