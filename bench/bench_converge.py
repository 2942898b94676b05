"""What the models the convergence study chooses for `paper` cost against each other.

Side by side, in one run, best of three after one warm-up call (forms are
compiled once per machine): the Timoshenko beam with 16 elements (the choice
when a scene's band holds the bending mode only), the shell Q2 16 x 20 (the
choice at 2e-3 and 3e-3) and, when the 3D model is available, the 3D P2
hexahedra 128 x 20 x 1 (the choice at 1e-3).  Each value is a time ratio.
And the per-run overhead of a small 3D run of the ladder (the along-only
8 x 20 x 1, which widens from 6 to 12 modes) as the study's serving process
runs it (Gmsh in-process, one mesh and assembly for both solves) against
the 3D model's own entry with Gmsh in a child process, as before.
``quick``: one call each, the 3D model at 32 x 5 x 1 (does it run).
"""

import inspect
import time

from rotorpillar.converge.ladder import N_MODES_FIRST as N_MODES  # what the study solves for here
from rotorpillar.fem3d.naghdi import ShellDiscretisation, shell_modal_analysis, shell_section_of
from rotorpillar.reduced.beam_fe import beam_modes
from rotorpillar.reduced.pillar_modes import beam_properties
from rotorpillar.scene import Mesh, load_scene


def _best(fn, repeat=3):
    if repeat == 1:  # quick: one call, no warm-up
        t0 = time.perf_counter()
        fn()
        return time.perf_counter() - t0
    fn()
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def run(quick: bool = False) -> list[dict]:
    repeat = 1 if quick else 3
    scene = load_scene("paper")
    p = scene.pillar
    props = beam_properties(p)  # the paper's uniform tube
    shell_sec, R, H = shell_section_of(p)
    t_beam = _best(lambda: beam_modes(props, 16, "timoshenko", 1), repeat)
    t_shell = _best(lambda: shell_modal_analysis(shell_sec, R, H, ShellDiscretisation(16, 20), n_modes=N_MODES), repeat)
    out = [
        {
            "name": "shell_q2_16x20_vs_timoshenko_16",
            "compares": "shell Q2 16x20 modal time (the choice at 2e-3) / Timoshenko 16 el. (bending only)",
            "value": t_shell / t_beam,
            "unit": "x",
            "shell_s": t_shell,
            "beam_s": t_beam,
        }
    ]
    try:
        from rotorpillar.fem3d import modal_analysis
    except ImportError:
        return out
    around, along = (32, 5) if quick else (128, 20)
    mesh = Mesh(
        elements_around=around,
        elements_along=along,
        elements_through=1,
        degree=2,
        cell_type="hexahedron",
        grading=scene.mesh.grading,
    )
    extra = {"use_cache": False} if "use_cache" in inspect.signature(modal_analysis).parameters else {}
    t_solid = _best(lambda: modal_analysis(scene, top=False, n_modes=N_MODES, mesh=mesh, **extra), repeat)
    from rotorpillar.converge.compute import _compute_fe, compute_fe
    from rotorpillar.converge.ladder import N_MODES as WIDE
    from rotorpillar.converge.ladder import rung

    small = rung(scene, "solid_hex_p2_along", 20)

    def before():  # what the study did: a meshing child, and the widened solve from scratch
        _compute_fe(small, scene, N_MODES, True)
        _compute_fe(small, scene, WIDE, True)

    t_served = _best(lambda: compute_fe(small, scene, fresh=True, isolated=False), repeat)
    t_before = _best(before, repeat)
    out.append(
        {
            "name": "small_solid_run_served_vs_before",
            "compares": f"{small.label}: as served (Gmsh in-process, meshed and assembled once for its "
            "6- and 12-mode solves) / as before (a meshing child, everything twice)",
            "value": t_served / t_before,
            "unit": "x",
            "served_s": t_served,
            "before_s": t_before,
        }
    )
    out.append(
        {
            "name": f"solid_p2_hex_{around}x{along}_vs_shell_q2_16x20",
            "compares": f"3D P2 hex {around}x{along}x1 modal time (the choice at 1e-3: 128x20) / shell Q2 16x20 "
            "(the choice at 2e-3)",
            "value": t_solid / t_shell,
            "unit": "x",
            "solid_s": t_solid,
            "shell_s": t_shell,
        }
    )
    return out
