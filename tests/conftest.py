"""What several test modules share: the CLI as a user runs it, and one `run`.

- :func:`cli` runs ``python -m rotorpillar ARGS...`` in a child process, as a
  user would, and returns the CompletedProcess (text stdout and stderr).
- ``run_paper`` (session fixture): one ``rotorpillar run paper --skip
  converge --skip compare`` into a temporary directory, shared by every test
  that checks what the main job writes, instead of one run each (the
  comparisons run the 3D full order: tests/test_run_compare.py runs that
  stage alone).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
if str(TESTS) not in sys.path:          # tests import their helpers (imagecheck, fixtures)
    sys.path.insert(0, str(TESTS))


def cli(*args, env=None, cwd=None, prefix=(), timeout=None) -> subprocess.CompletedProcess:
    """``rotorpillar ARGS...`` in a child process; ``prefix`` goes before it (mpirun)."""
    return subprocess.run([*prefix, sys.executable, "-m", "rotorpillar", *map(str, args)],
                          capture_output=True, text=True, env=env, cwd=cwd, timeout=timeout)


class RunOutput:
    """The finished ``run paper --skip converge --skip compare``: its directory and process."""

    def __init__(self, out: Path, process: subprocess.CompletedProcess):
        self.out, self.process = out, process


@pytest.fixture(scope="session")
def run_paper(tmp_path_factory) -> RunOutput:
    out = tmp_path_factory.mktemp("run_paper")
    p = cli("run", "paper", "--out", out, "--skip", "converge", "--skip", "compare")
    assert p.returncode == 0, p.stderr
    return RunOutput(out, p)
