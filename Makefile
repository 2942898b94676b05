# The two commands of a fresh Debian 12 machine, each doing its own set-up
# (tools/setup.sh: Debian packages, .venv, this package; idempotent).
VENV := .venv
PY   := $(VENV)/bin/python
SCENE ?= paper

.PHONY: run test test-fast bench setup clean

# The last line `rotorpillar run` prints is the report's path:
# "report: /abs/path/out/<scene>/report.html".
run: setup
	$(VENV)/bin/rotorpillar run $(SCENE)

test: setup
	$(PY) -m pytest

# The tests without the 3D finite-element and long-study ones.
test-fast: setup
	$(PY) -m pytest -m "not slow"

bench: setup
	$(PY) bench/run.py

setup:
	@tools/setup.sh

clean:
	rm -rf out bench/results.json .pytest_cache
