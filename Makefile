# The two commands of a fresh Debian 12 machine, each doing its own set-up
# (tools/setup.sh: Debian packages, .venv, this package; idempotent).
VENV := .venv
PY   := $(VENV)/bin/python
SCENE ?= paper

.PHONY: run test test-fast check bench bench-quick setup clean

# The last line `rotorpillar run` prints is the report's path:
# "report: /abs/path/out/<scene>/report.html".
run: setup
	$(VENV)/bin/rotorpillar run $(SCENE)

# Both tiers run on JOBS processes (pytest-xdist; worksteal: a process that
# runs dry takes queued tests from the other); the main job's fixture runs
# once for all of them (tests/conftest.py, once_per_session).
JOBS ?= 2
XDIST := -n $(JOBS) --dist worksteal

# The whole suite, with the 15 slowest tests listed at the end.
test: setup
	$(PY) -m pytest $(XDIST) --durations=15

# The tests not marked slow (no 3D or shell model, no whole `run`, no study,
# no set-up): about a minute on a 2-core machine (1053 tests, 58 s on 2026-11-29).
test-fast: setup
	$(PY) -m pytest $(XDIST) -m "not slow" --durations=10

# The house rules, ruff's lint and format check, mypy (tools/check.sh).
check: setup
	@tools/check.sh

bench: setup
	$(PY) bench/run.py

# Every benchmark once at a small size (CI, after make test): each still runs
# and writes its entries (bench/results-quick.json); its numbers mean nothing.
bench-quick: setup
	$(PY) bench/run.py --quick

setup:
	@tools/setup.sh

clean:
	rm -rf out bench/results.json bench/results-quick.json .pytest_cache
