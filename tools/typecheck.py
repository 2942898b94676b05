"""mypy as ``make check`` runs it, or in the configuration the house is heading for.

``python tools/typecheck.py``: mypy with pyproject.toml's ``[tool.mypy]`` as
it stands (the modules of the typing debt, listed there with
``ignore_errors = true``, are skipped).

``python tools/typecheck.py --strict`` (``make check-strict``): the target
configuration, which ``make check`` will hold after the flip: the same
``[tool.mypy]`` without the debt blocks (an override that sets
``ignore_errors``), plus ``strict = true`` on ``reduced/`` and ``scene/``
(:data:`STRICT_BLOCK`).  It prints the errors, then their count by error
code and by module.

The flip: paste :data:`STRICT_BLOCK` into pyproject.toml as a
``[[tool.mypy.overrides]]`` table, delete the debt table, fix what
``--strict`` reports.
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
import tomllib
from collections import Counter
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]

#: The override the strict flip adds to pyproject.toml: ``--strict``'s flags, one by one
#: (mypy 2.4 applies a per-module ``strict = true`` to every module).
STRICT_BLOCK: dict[str, Any] = {
    "module": ["rotorpillar.reduced", "rotorpillar.reduced.*", "rotorpillar.scene", "rotorpillar.scene.*"],
    "disallow_any_generics": True,
    "disallow_subclassing_any": True,
    "disallow_untyped_calls": True,
    "disallow_untyped_defs": True,
    "disallow_incomplete_defs": True,
    "check_untyped_defs": True,
    "disallow_untyped_decorators": True,
    "warn_unused_ignores": True,
    "warn_return_any": True,
    "implicit_reexport": False,
    "strict_equality": True,
    "extra_checks": True,
}
ERROR = re.compile(r"^(?P<path>[^:]+):\d+: error: .*\[(?P<code>[\w-]+)\]$")


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"no TOML for {v!r}")


def target_config(pyproject: Path) -> str:
    """The ``[tool.mypy]`` of ``pyproject`` without its debt, with :data:`STRICT_BLOCK`, as TOML."""
    mypy = dict(tomllib.loads(pyproject.read_text())["tool"]["mypy"])
    overrides = [o for o in mypy.pop("overrides", []) if "ignore_errors" not in o]
    lines = ["[tool.mypy]"] + [f"{k} = {_toml_value(v)}" for k, v in mypy.items()]
    for block in [*overrides, STRICT_BLOCK]:
        lines += ["", "[[tool.mypy.overrides]]"]
        lines += [f"{k} = {_toml_value(v)}" for k, v in block.items()]
    return "\n".join(lines) + "\n"


def counts(output: str) -> tuple[Counter[str], Counter[str]]:
    """mypy's errors counted by error code and by file."""
    by_code: Counter[str] = Counter()
    by_file: Counter[str] = Counter()
    for line in output.splitlines():
        m = ERROR.match(line)
        if m:
            by_code[m["code"]] += 1
            by_file[m["path"]] += 1
    return by_code, by_file


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument(
        "--strict", action="store_true", help="the target configuration: no debt, strict reduced/ and scene/"
    )
    args = parser.parse_args(argv)
    cmd = [sys.executable, "-m", "mypy"]
    if not args.strict:
        return subprocess.call(cmd, cwd=ROOT)
    with tempfile.TemporaryDirectory() as tmp:
        config = Path(tmp) / "mypy-target.toml"
        config.write_text(target_config(ROOT / "pyproject.toml"))
        p = subprocess.run([*cmd, "--config-file", str(config)], cwd=ROOT, capture_output=True, text=True)
    print(p.stdout, end="")
    print(p.stderr, end="", file=sys.stderr)
    by_code, by_file = counts(p.stdout)
    print(f"\nmypy, target configuration: {sum(by_code.values())} errors in {len(by_file)} files")
    print("by code:   " + ", ".join(f"{c} {n}" for c, n in by_code.most_common()))
    strict = Counter({f: n for f, n in by_file.items() if f.startswith(("rotorpillar/reduced/", "rotorpillar/scene/"))})
    print(
        f"strict reduced/ and scene/: {sum(strict.values())} errors in {len(strict)} files; "
        f"the rest: {sum(by_file.values()) - sum(strict.values())} errors in "
        f"{len(by_file) - len(strict)} files"
    )
    return p.returncode


if __name__ == "__main__":
    sys.exit(main())
