"""dolfinx and VTK in one process (a notebook, or pytest itself).

Debian's dolfinx 0.5.2 loads its libraries RTLD_GLOBAL; VTK's wheel then
binds its std::regex to dolfinx's (another C++ string ABI) and its first
scalar bar aborts the process.  rotorpillar.fem3d imports dolfinx locally
(fem3d/dolfinx_import.py).  The check runs in a child process, so a
regression shows as a failed test, not a dead test run.
"""

import subprocess
import sys

import pytest

CHILD = r"""
from rotorpillar.scene import load_scene
from rotorpillar.fem3d import modal_analysis
r = modal_analysis(load_scene("paper", ["mesh.elements_around=8", "mesh.elements_along=2",
                                        "mesh.degree=1"]), top=False, n_modes=2)
from rotorpillar.postprocess import offscreen
pv = offscreen.pyvista()
m = pv.Sphere(); m["s"] = m.points[:, 0]
p = pv.Plotter(off_screen=True, window_size=(200, 150))
p.add_mesh(m, scalars="s", show_scalar_bar=True)
img = p.screenshot(return_img=True)
print("rendered", img.shape, float(img.std()) > 0)
"""


@pytest.mark.slow  # a 3D model and a render, in a child process
def test_modal_then_scalar_bar_render_in_one_process():
    p = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    assert "rendered (150, 200, 3) True" in p.stdout
