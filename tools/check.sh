#!/usr/bin/env bash
# `make check`: the house rules (tools/house_check.py), ruff's lint and format
# check, and mypy (strict on reduced/ and scene/), as pyproject.toml configures
# them.  Every step runs; the exit status is 1 when one of them failed.
set -uo pipefail
cd "$(dirname "$0")/.."

VENV=.venv
PY=$VENV/bin/python
RUFF=$VENV/bin/ruff
PATHS=(rotorpillar tests tools bench examples)

status=0
step() {    # step NAME COMMAND...: run it, say how it went
  local name=$1; shift
  echo "== $name"
  if "$@"; then echo "== $name: ok"; else echo "== $name: FAIL"; status=1; fi
}

step "house rules" "$PY" tools/house_check.py
step "ruff lint" "$RUFF" check "${PATHS[@]}"
step "ruff format --check" "$RUFF" format --check "${PATHS[@]}"
step "mypy (strict on reduced/ and scene/)" "$PY" tools/typecheck.py
exit $status
