"""Every script in examples/ runs as a user would run it (as scikit-fem runs its docs examples).

The examples print numbers that other tests check against independent
references; here each must run to the end without error and print.
"""

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.py"))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(script, tmp_path):
    p = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                       cwd=tmp_path, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    assert p.stdout.strip(), "an example shows its result"


def test_every_public_name_resolves():
    """``rotorpillar.__all__`` is what notebooks import: each name must load."""
    import rotorpillar
    for name in rotorpillar.__all__:
        assert getattr(rotorpillar, name) is not None, name
