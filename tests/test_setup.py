"""`make test` ran tools/setup.sh just before pytest: a second run with
nothing changed must install nothing (apt and pip are not called: no
'installing' line, and it finishes without touching the network)."""

import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_setup_is_idempotent():
    p = subprocess.run([str(ROOT / "tools" / "setup.sh")], capture_output=True, text=True,
                       cwd=ROOT, timeout=120)
    assert p.returncode == 0, p.stderr
    assert "installing" not in p.stdout + p.stderr
    assert "creating" not in p.stdout + p.stderr
