"""mypy as ``make check`` runs it: pyproject.toml's ``[tool.mypy]``, strict on
``reduced/`` and ``scene/`` (its ``[[tool.mypy.overrides]]`` table with mypy's
strict flags, one by one: mypy applies a per-module ``strict = true`` to every
module), the default checks on the rest of the package and on ``tools/``.

``python tools/typecheck.py``: runs mypy, prints its output, then the errors
counted by code and by package; exits with mypy's status.
"""

from __future__ import annotations

import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ERROR = re.compile(r"^(?P<path>[^:]+):\d+: error: .*\[(?P<code>[\w-]+)\]$")


def counts(output: str) -> tuple[Counter[str], Counter[str]]:
    """mypy's errors counted by error code and by package (the path's first two parts)."""
    by_code: Counter[str] = Counter()
    by_package: Counter[str] = Counter()
    for line in output.splitlines():
        m = ERROR.match(line)
        if m:
            by_code[m["code"]] += 1
            by_package["/".join(Path(m["path"]).parts[:2])] += 1
    return by_code, by_package


def main() -> int:
    p = subprocess.run([sys.executable, "-m", "mypy"], cwd=ROOT, capture_output=True, text=True)
    print(p.stdout, end="")
    print(p.stderr, end="", file=sys.stderr)
    by_code, by_package = counts(p.stdout)
    if by_code:
        print("by code:    " + ", ".join(f"{c} {n}" for c, n in by_code.most_common()))
        print("by package: " + ", ".join(f"{c} {n}" for c, n in by_package.most_common()))
    return p.returncode


if __name__ == "__main__":
    sys.exit(main())
