"""What the models of the convergence ladder cost against each other, side by side.

At the mesh the study chooses for `paper` at 1e-3 (shell Q2 16 x 20) and at
the [mesh] default (32 x 40): the shell's modal analysis against the 1D
Timoshenko beam (64 elements: bending to 2e-4, no ovalling mode), and, when
the 3D model is available, the 3D P2 hexahedral model on the same mesh
against the shell.  Each timed after one warm-up call (form compilation is a
one-off, cached on disk), best of three.
"""

import time

from rotorpillar.fem3d.shell import ShellDiscretisation, shell_modal_analysis, shell_section_of
from rotorpillar.reduced.beam_fe import BeamProperties, beam_modes
from rotorpillar.reduced.pillar import cowper_shear_coefficient, section_of
from rotorpillar.scene import Mesh, load_scene


def _best(fn, repeat=3):
    fn()
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def run():
    scene = load_scene("paper")
    p = scene.pillar
    sec = section_of(p)
    kappa = cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    props = BeamProperties(p.youngs_modulus, p.poisson_ratio, kappa, p.density, sec.area,
                           sec.second_moment, p.height)
    shell_sec, R, H = shell_section_of(p)
    t_beam = _best(lambda: beam_modes(props, 64, "timoshenko", 1))
    out = []
    for na, nz in ((16, 20), (32, 40)):
        t_shell = _best(lambda: shell_modal_analysis(shell_sec, R, H, ShellDiscretisation(na, nz),
                                                     n_modes=12))
        out.append({"name": f"shell_q2_{na}x{nz}_vs_timoshenko_64",
                    "compares": f"shell Q2 {na}x{nz} modal time / 1D Timoshenko 64 el. time",
                    "value": t_shell / t_beam, "unit": "x", "shell_s": t_shell, "beam_s": t_beam})
        try:
            from rotorpillar.fem3d import modal_analysis
        except ImportError:
            continue
        mesh = Mesh(elements_around=na, elements_along=nz, elements_through=1, degree=2,
                    cell_type="hexahedron")
        t_solid = _best(lambda: modal_analysis(scene, top=False, n_modes=12, mesh=mesh,
                                               use_cache=False))
        out.append({"name": f"solid_p2_hex_{na}x{nz}_vs_shell",
                    "compares": f"3D P2 hex {na}x{nz}x1 modal time / shell Q2 {na}x{nz} time",
                    "value": t_solid / t_shell, "unit": "x", "solid_s": t_solid,
                    "shell_s": t_shell})
    return out
