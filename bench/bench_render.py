"""Cost of the report's renders: EGL against OSMesa, and each kind of picture.

Each backend runs in its own process (VTK picks its render window when the
first one is created), rendering the same synthetic tube modes and a short
animation; the numbers are side by side in one `make bench` run.  Values are
wall-clock per item on this machine, not asserted anywhere.  ``quick``: a
coarse tube (16 x 10) and 4 animation frames (does it run).
"""

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

#: tests/fixtures.py writes the synthetic inputs.
TESTS = Path(__file__).resolve().parent.parent / "tests"

WORKER = r"""
import json, sys, time
from pathlib import Path
sys.path.insert(0, sys.argv[2])   # tests/, for the synthetic inputs
import fixtures
from rotorpillar.postprocess.geometry import load_modes
from rotorpillar import records
from rotorpillar.fem3d.modal_summary import ModalSummary
from rotorpillar.postprocess.readers import read_simulation
from rotorpillar.postprocess.modeshapes import render_mode, render_contact_sheet
from rotorpillar.postprocess.animation import animate
from rotorpillar.postprocess.offscreen import render_window_class
out = Path(sys.argv[1])
around, along, n, frames = (int(a) for a in sys.argv[3:7])
fixtures.write_modal_fixture(out, around=around, along=along)
fixtures.write_simulation_fixture(out, "runup", n=n)
modal = records.read(out / "modal.json", ModalSummary)
ms = load_modes(out / "modes_top.vtu", modal.modes_with_top, modal.axes)
render_mode(ms, 0, out / "warm.png")
t0 = time.perf_counter()
for i in range(len(ms.arrays)):
    render_mode(ms, i, out / f"m{i}.png")
t_mode = (time.perf_counter() - t0) / len(ms.arrays)
t0 = time.perf_counter()
render_contact_sheet(ms, out / "sheet.png")
t_sheet = time.perf_counter() - t0
r = animate(read_simulation(out, "runup"), ms, out / "a.mp4", max_frames=frames, progress=False)
print(json.dumps({"window": render_window_class(), "mode": t_mode, "sheet": t_sheet,
                  "frame": r.seconds / frames, "points": int(ms.surface.n_points)}))
"""


def _measure(window: str, sizes: tuple[int, ...]) -> dict:
    env = dict(os.environ, VTK_DEFAULT_OPENGL_WINDOW=window)
    env.pop("DISPLAY", None)
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run(
            [sys.executable, "-c", WORKER, tmp, str(TESTS), *map(str, sizes)],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
    return json.loads(p.stdout.strip().splitlines()[-1])


def run(quick: bool = False) -> list[dict]:
    # around, along, samples of the run-up, animation frames
    sizes = (16, 10, 2000, 4) if quick else (32, 40, 20000, 60)
    egl = _measure("vtkEGLRenderWindow", sizes)
    osm = _measure("vtkOSOpenGLRenderWindow", sizes)
    out = []
    for key, what, unit in (
        ("mode", "one mode-shape PNG (480x720)", "s"),
        ("sheet", "the contact sheet (6 views)", "s"),
        ("frame", "one animation frame (880x560, 3D view + chart panel, H.264)", "s"),
    ):
        out.append(
            {
                "name": f"render_{key}_egl",
                "compares": f"{what}, EGL ({egl['window']})",
                "value": egl[key],
                "unit": unit,
                "surface_points": egl["points"],
            }
        )
        out.append(
            {
                "name": f"render_{key}_osmesa",
                "compares": f"{what}, OSMesa ({osm['window']})",
                "value": osm[key],
                "unit": unit,
                "surface_points": osm["points"],
            }
        )
        out.append(
            {
                "name": f"render_{key}_osmesa_over_egl",
                "compares": f"{what}: OSMesa time / EGL time",
                "value": osm[key] / egl[key],
                "unit": "x",
            }
        )
    return out
