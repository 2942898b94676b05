"""What the transients' full-order references cost, side by side in one run.

- the 3D full order's cost per Newmark step on the references the study
  chooses for the paper's tube (8 x 15: the earthquake's, 8 x 40: the
  run-up's, as fine as the ROM's modes) over the old [full_order] default
  8 x 10, on 0.3 s of El Centro (forms compiled and a run made before: warm;
  the median of REPEAT runs, the machine is shared);
- the speed-against-accuracy study on a short case (0.3 s, 3D meshes 8 x 2,
  3, 4, beams of 2 and 4 elements): cold (every run computed, in this
  process) over cached (every run read from its JSON).

``quick``: one run of each, 0.05 s windows, the meshes 8 x 3 and 8 x 4 over
8 x 2 (does it run).
"""

import statistics
import tempfile
import time
from dataclasses import replace
from pathlib import Path

REPEAT = 3
WINDOW = 0.3


def _step_seconds(scene, around, along, repeat=REPEAT, window=WINDOW):
    from rotorpillar.fem3d.full_order import simulate_fem3d

    mesh = replace(scene.mesh, elements_around=around, elements_along=along)
    runs = []
    for _ in range(repeat):
        r = simulate_fem3d(scene, "earthquake", duration=window, mesh=mesh, samples=10)
        runs.append(r.wall_seconds / r.integrator.steps)
    return statistics.median(runs), r.dofs


def run(quick: bool = False) -> list[dict]:
    from rotorpillar.scene import load_scene
    from rotorpillar.transients.pareto import transient_pareto

    scene = load_scene("paper", ["excitation.kind=record", "excitation.start=0.1"])
    repeat, window = (1, 0.05) if quick else (REPEAT, WINDOW)
    base_along = 2 if quick else 10
    if not quick:
        _step_seconds(scene, 4, 1)  # forms compiled, kernels loaded
    base, dofs0 = _step_seconds(scene, 8, base_along, repeat, window)
    out = []
    refs = (
        ((8, 3, "a quick run's"), (8, 4, "a quick run's"))
        if quick
        else ((8, 15, "the earthquake's reference"), (8, 40, "the run-up's reference (as fine as the ROM's modes)"))
    )
    for around, along, what in refs:
        t, dofs = _step_seconds(scene, around, along, repeat, window)
        out.append(
            {
                "name": f"fem3d_step_cost_{around}x{along}_over_8x{base_along}",
                "value": t / base,
                "unit": "x",
                "compares": f"seconds per Newmark step (assembly and factorisation spread over "
                f"{window:g} s), {around}x{along} ({dofs} DOFs, {what}) over 8x{base_along} "
                f"({dofs0} DOFs{', the old default' if base_along == 10 else ''})",
                "seconds_per_step": t,
                f"seconds_per_step_8x{base_along}": base,
            }
        )
    duration, alongs, beams = (0.1, (2, 3), (2,)) if quick else (0.3, (2, 3, 4), (2, 4))
    mesh = replace(scene.mesh, elements_around=8, elements_along=3)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cold, _ = transient_pareto(
            scene, cache_dir=Path(tmp), rom_modes=2, chosen_mesh=mesh, duration=duration, along=alongs, beams=beams
        )
        t_cold = time.perf_counter() - t0
        t0 = time.perf_counter()
        transient_pareto(
            scene, cache_dir=Path(tmp), rom_modes=2, chosen_mesh=mesh, duration=duration, along=alongs, beams=beams
        )
        t_cached = time.perf_counter() - t0
    assert cold.cost is not None, "a study that ran has its cost"
    out.append(
        {
            "name": "pareto_cold_over_cached",
            "value": t_cold / t_cached,
            "unit": "x",
            "compares": f"the speed-against-accuracy study on a short case ({cold.cost.runs} runs): "
            "every run computed over every run read from the cache",
            "cold_seconds": t_cold,
            "cached_seconds": t_cached,
        }
    )
    return out
