"""Cost of the Campbell diagram on the spatial reduced model (issue 26: 151 speeds on the ROM).

The paper's scene, its spatial model on the 1D beams' modes in every direction
below the band (rotorpillar.reduced.spatial_scene), 151 speeds from 0 to the
band's top: the damped modes at each speed (one dense eigenproblem of the
first-order form), their tracking (MAC and the Hungarian assignment) and the
critical speeds (one Hermitian pencil); then the same with the AF of every
critical speed from the unbalance response (``scene_campbell``), and one speed of
the unbalance response alone.  Medians of REPEAT runs (the machine is shared).
The 3D model's Campbell diagram is fem3d's own entry.
``quick``: 21 speeds, one call each (does it run; its speed is make bench's).
"""

import statistics
import time

import numpy as np

REPEAT = 5
SPEEDS = 151


def _median(fn, repeat=REPEAT):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def run(quick: bool = False) -> list[dict]:
    repeat, speeds_n = (1, 21) if quick else (REPEAT, SPEEDS)
    from rotorpillar.reduced.band import forcing_top
    from rotorpillar.reduced.spatial_linear import campbell
    from rotorpillar.reduced.spatial_response import steady_state
    from rotorpillar.reduced.spatial_scene import scene_campbell, scene_spatial_model, scene_spatial_modes
    from rotorpillar.scene import load_scene

    scene = load_scene("paper")
    top = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, "runup", None)
    modes = scene_spatial_modes(scene)
    model = scene_spatial_model(scene, top, modes)
    speeds = np.linspace(0.0, top, speeds_n)
    t_campbell = _median(lambda: campbell(model, speeds, 89.7), repeat)
    t_with_af = _median(lambda: scene_campbell(scene, speeds, top, 89.7, modes), repeat=min(3, repeat))
    t_speed = _median(lambda: steady_state(model, 50.0), repeat=1 if quick else 200)
    desc = f"paper, {model.nz} coordinates ({model.modes.count} pillar modes of {modes.source} below {top:.4g} rad/s)"
    return [
        {
            "name": "campbell_rom_151_speeds",
            "compares": f"the spatial ROM's Campbell diagram, {speeds_n} speeds: damped modes, tracking, critical speeds; {desc}",
            "value": t_campbell,
            "unit": "s",
        },
        {
            "name": "campbell_rom_151_speeds_with_af",
            "compares": "the same with every critical speed's AF from the unbalance response's peak (`rotorpillar campbell`'s work)",
            "value": t_with_af,
            "unit": "s",
        },
        {
            "name": "spatial_unbalance_response_per_speed",
            "compares": "one speed of the spatial ROM's steady unbalance response (one complex solve)",
            "value": t_speed,
            "unit": "s",
        },
    ]
