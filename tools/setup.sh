#!/usr/bin/env bash
# One idempotent set-up for `make run`, `make test`, `make check` and `make
# bench` on a fresh Debian 12 machine: Debian packages (FEniCSx lives only
# there), then a venv on top of the system interpreter, then this package with
# its test and dev tools (pytest, ruff, mypy), then the one-off compilation of
# the main job (numba's kernels, FFCx's forms: tools/warm_caches.py).  A second
# run with nothing changed installs and compiles nothing: apt is asked only
# for missing packages, pip only when pyproject.toml or the constraints
# changed, the warm-up only when its key changed (a stamp records each).
set -euo pipefail
cd "$(dirname "$0")/.."

DEBS=(python3-dolfinx-real python3-gmsh python3-meshio python3-slepc4py-real libopenblas0-serial
      python3-venv python3-scipy libosmesa6 libgl1 libxrender1 libxcursor1
      libxft2 libxinerama1 libglu1-mesa chromium)
SYSPY=/usr/bin/python3
VENV=.venv

missing=()
for p in "${DEBS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ ! -x "$VENV/bin/python" ]; then
  echo "setup: creating $VENV from $SYSPY (with system site-packages, for dolfinx)"
  "$SYSPY" -m venv --system-site-packages "$VENV"
fi

# pip must not replace the numpy/scipy that petsc4py, slepc4py and dolfinx
# were built against: pin them to the system's versions.
"$SYSPY" - > "$VENV/constraints.txt" <<'PY'
import numpy, scipy
print(f"numpy=={numpy.__version__}")
print(f"scipy=={scipy.__version__}")
PY

stamp="$VENV/.installed"
want=$(cat pyproject.toml "$VENV/constraints.txt" | sha256sum | cut -d' ' -f1)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "setup: installing rotorpillar and its Python dependencies into $VENV"
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check \
      -c "$VENV/constraints.txt" -e ".[test,dev]"
  echo "$want" > "$stamp"
fi

# The package's bytecode, written here: a shell that sets PYTHONDONTWRITEBYTECODE
# (some CI images and sandboxes do) makes every `rotorpillar` process compile the
# package's ~220 modules from source again, 0.27 s of CPU each (a report on an
# analyze's files: 0.90 -> 0.63 s), and `run` and the tests start hundreds of
# them.  Python reads a current .pyc whatever that variable says and compiles a
# stale one's source in memory, so an edit is never missed; 0.07 s when current.
"$VENV/bin/python" -m compileall -q rotorpillar

# numba's kernels and FFCx's forms, compiled once here rather than in the
# first `make run` (about 50 s there); nothing when the caches are current.
"$VENV/bin/python" tools/warm_caches.py
