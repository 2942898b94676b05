"""What the transients' full-order references cost, side by side in one run.

- the 3D full order's cost per Newmark step on the references the study
  chooses for the paper's tube (8 x 15: the earthquake's, 8 x 40: the
  run-up's, as fine as the ROM's modes) over the old [full_order] default
  8 x 10, on 0.3 s of El Centro (forms compiled and a run made before: warm;
  the median of REPEAT runs, the machine is shared);
- the speed-against-accuracy study on a short case (0.3 s, 3D meshes 8 x 2,
  3, 4, beams of 2 and 4 elements): cold (every run computed, in this
  process) over cached (every run read from its JSON).
"""

import statistics
import tempfile
import time
from dataclasses import replace
from pathlib import Path

REPEAT = 3
WINDOW = 0.3


def _step_seconds(scene, around, along):
    from rotorpillar.fem3d.full_order import simulate_fem3d

    mesh = replace(scene.mesh, elements_around=around, elements_along=along)
    runs = []
    for _ in range(REPEAT):
        r = simulate_fem3d(scene, "earthquake", duration=WINDOW, mesh=mesh, samples=10)
        runs.append(r.wall_seconds / r.integrator["steps"])
    return statistics.median(runs), r.dofs


def run():
    from rotorpillar.scene import load_scene
    from rotorpillar.transients.pareto import transient_pareto

    scene = load_scene("paper", ["excitation.kind=record", "excitation.start=0.1"])
    _step_seconds(scene, 4, 1)  # forms compiled, kernels loaded
    base, dofs0 = _step_seconds(scene, 8, 10)
    out = []
    for around, along, what in (
        (8, 15, "the earthquake's reference"),
        (8, 40, "the run-up's reference (as fine as the ROM's modes)"),
    ):
        t, dofs = _step_seconds(scene, around, along)
        out.append(
            {
                "name": f"fem3d_step_cost_{around}x{along}_over_8x10",
                "value": t / base,
                "unit": "x",
                "compares": f"seconds per Newmark step (assembly and factorisation spread over "
                f"{WINDOW:g} s), {around}x{along} ({dofs} DOFs, {what}) over 8x10 "
                f"({dofs0} DOFs, the old default)",
                "seconds_per_step": t,
                "seconds_per_step_8x10": base,
            }
        )
    short = dict(duration=0.3, along=(2, 3, 4), beams=(2, 4))
    mesh = replace(scene.mesh, elements_around=8, elements_along=3)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cold, _ = transient_pareto(scene, cache_dir=Path(tmp), rom_modes=2, chosen_mesh=mesh, **short)
        t_cold = time.perf_counter() - t0
        t0 = time.perf_counter()
        transient_pareto(scene, cache_dir=Path(tmp), rom_modes=2, chosen_mesh=mesh, **short)
        t_cached = time.perf_counter() - t0
    out.append(
        {
            "name": "pareto_cold_over_cached",
            "value": t_cold / t_cached,
            "unit": "x",
            "compares": f"the speed-against-accuracy study on a short case ({cold.cost['runs']} runs): "
            "every run computed over every run read from the cache",
            "cold_seconds": t_cold,
            "cached_seconds": t_cached,
        }
    )
    return out
