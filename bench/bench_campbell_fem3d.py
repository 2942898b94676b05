"""The 3D model's Campbell diagram beside the spatial ROM's (issue 26: 151 speeds, per speed).

The paper's scene on the scene's mesh (the chain's when no study is on
disk: 64 x 10 x 1 quadratic hexahedra, ~24,200 unknowns with the top and
the rotor), 151 speeds from 0 to the band's top: the 3D model with the
rotor on its top (rotorpillar.fem3d.campbell: one factorisation of K, a
block Arnoldi per speed started from the last speed's eigenvectors, the
tracking, the critical speeds' pencil) against the spatial ROM on the same
mesh's 3D modes below the band (rotorpillar.reduced.spatial_linear), one
run each (the 3D one takes minutes); the largest difference of their
frequencies in the band beside the times; and one speed of the 3D unbalance
response (one real LDL^T of K - Omega**2 M and Woodbury's identity).
``quick``: 11 speeds on a 16 x 4 x 1 mesh (does it run; its speed is make bench's).
"""

import time

import numpy as np

SPEEDS = 151


def run(quick: bool = False) -> list[dict]:
    from dataclasses import replace

    from rotorpillar.fem3d import assemble_pillar, modal_analysis
    from rotorpillar.fem3d.campbell import campbell_fem3d
    from rotorpillar.fem3d.harmonic import spatial_response
    from rotorpillar.fem3d.rotor_spatial import SpatialRotor
    from rotorpillar.fem3d.spatial_modes import spatial_modes_from_fem3d
    from rotorpillar.fem3d.spatial_system import assemble_system
    from rotorpillar.reduced.band import forcing_top
    from rotorpillar.reduced.spatial_linear import campbell
    from rotorpillar.reduced.spatial_scene import scene_spatial_model
    from rotorpillar.scene import load_scene

    scene = load_scene("paper")
    speeds_n = SPEEDS
    if quick:
        speeds_n = 11
        scene = replace(scene, mesh=replace(scene.mesh, elements_around=16, elements_along=4))
    top = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, "runup", None)
    speeds = np.linspace(0.0, top, speeds_n)
    modes = spatial_modes_from_fem3d(modal_analysis(scene, top=True, n_modes=32), scene.pillar.damping_ratio)
    model = scene_spatial_model(scene, top, modes)
    t0 = time.perf_counter()
    rom = campbell(model, speeds, None)
    t_rom = time.perf_counter() - t0
    t0 = time.perf_counter()
    fem = campbell_fem3d(scene, speeds, band_top=top)
    t_fem = time.perf_counter() - t0
    by_label = {b.label: b for b in rom.modes}
    diff = 0.0
    for b in fem.modes:
        a = by_label.get(b.label)
        if a is not None and np.nanmax(b.frequency) < top:
            diff = max(diff, float(np.nanmax(np.abs(b.frequency - a.frequency) / a.frequency)))
    m = assemble_pillar(scene, top=True)
    system = assemble_system(
        m,
        SpatialRotor.from_scene(scene),
        tip_damping=scene.pillar.damping,
        damping_ratio=scene.pillar.damping_ratio,
        damped_up_to=2 * top,
    )
    try:
        t_speed = spatial_response(system, np.array([50.0, 60.0, 70.0]), "both").seconds_per_speed
    finally:
        system.destroy()
        m.K.destroy()
        m.M.destroy()
    desc = f"paper, {speeds_n} speeds 0 ... {top:.4g} rad/s; {fem.description}"
    return [
        {
            "name": "campbell_fem3d_151_speeds",
            "compares": f"the 3D model's Campbell diagram with its rotor (assembly, modes for the damping, "
            f"factorisation, speeds, critical speeds); {desc}",
            "value": t_fem,
            "unit": "s",
        },
        {
            "name": "campbell_fem3d_per_speed",
            "compares": "the same per speed, beside the spatial ROM's on the same mesh's 3D modes "
            f"({model.modes.count} modes; {t_rom / speeds_n:.3g} s a speed)",
            "value": t_fem / speeds_n,
            "unit": "s",
        },
        {
            "name": "campbell_fem3d_over_rom",
            "compares": f"the 3D diagram's time over the ROM's, {speeds_n} speeds each, one run side by side",
            "value": t_fem / t_rom,
            "unit": "x",
        },
        {
            "name": "campbell_rom_vs_fem3d_frequency",
            "compares": "largest relative difference of the branches' frequencies in the band, ROM against 3D "
            "(the ROM's truncation on this mesh; the same branch labels)",
            "value": diff,
            "unit": "-",
        },
        {
            "name": "spatial_unbalance_response_fem3d_per_speed",
            "compares": "one speed of the 3D unbalance response (static and couple), one LDL^T and Woodbury",
            "value": t_speed,
            "unit": "s",
        },
    ]
