"""``python -m rotorpillar.mesh``: the isolated Gmsh worker (see tube_mesh_data)."""

import sys

from .isolated import _worker

sys.exit(_worker())
