#!/usr/bin/env bash
# `make check`: the house rules (tools/house_check.py), ruff's lint and mypy,
# as pyproject.toml configures them.  Every step runs; the exit status is 1
# when one of them failed.
#
# STRICT=1 (`make check-strict`): the configuration the lead switches on once
# the branches are merged, reported as counts: ruff's lint with the rules in
# RUFF_STRICT added, `ruff format --check`, mypy without the typing debt and
# strict on reduced/ and scene/ (tools/typecheck.py --strict).  The flip:
# RUFF_STRICT's rules go into pyproject's [tool.ruff.lint] select, `ruff
# format` runs once over the tree, tools/typecheck.py's STRICT_BLOCK replaces
# the debt table of [tool.mypy], and this script's strict branch becomes the
# plain one.
set -uo pipefail
cd "$(dirname "$0")/.."

VENV=.venv
PY=$VENV/bin/python
RUFF=$VENV/bin/ruff
PATHS=(rotorpillar tests tools bench examples)
RUFF_STRICT=I,UP,B,NPY,RUF,E731

status=0
step() {    # step NAME COMMAND...: run it, say how it went
  local name=$1; shift
  echo "== $name"
  if "$@"; then echo "== $name: ok"; else echo "== $name: FAIL"; status=1; fi
}

step "house rules" "$PY" tools/house_check.py
if [ "${STRICT:-}" = "1" ]; then
  step "ruff lint (+$RUFF_STRICT)" "$RUFF" check --statistics --extend-select "$RUFF_STRICT" "${PATHS[@]}"
  step "ruff format --check" bash -c "$RUFF format --check ${PATHS[*]} | tail -n 1; exit \${PIPESTATUS[0]}"
  step "mypy (target: no debt, strict reduced/ and scene/)" "$PY" tools/typecheck.py --strict
else
  step "ruff lint" "$RUFF" check "${PATHS[@]}"
  step "mypy" "$PY" tools/typecheck.py
fi
exit $status
