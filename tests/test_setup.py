"""`make test` ran tools/setup.sh just before pytest: a second run with
nothing changed must install and compile nothing (apt and pip are not
called: no 'installing' line; the warm-up of numba's kernels and FFCx's forms
finds its stamp current: no 'warming' line).  Slow: the set-up itself runs
(and, on a machine where something did change, does its work)."""

import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
def test_setup_is_idempotent():
    runs = [
        subprocess.run([str(ROOT / "tools" / "setup.sh")], capture_output=True, text=True, cwd=ROOT, timeout=1800)
        for _ in range(2)
    ]
    for p in runs:
        assert p.returncode == 0, p.stderr
    second = runs[1].stdout + runs[1].stderr
    assert "installing" not in second
    assert "creating" not in second
    assert "warming" not in second
