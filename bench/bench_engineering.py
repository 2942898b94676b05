"""Cost of the engineering answers: the 3D stress recovery and one harmonic-response speed.

Side by side in one run, on the 3D full order's mesh ([full_order]: 8 x 10
P2 hexahedra) and the scene's modal mesh (64 x 10):

- the section resultants of every cut at one state (rotorpillar.fem3d.sections:
  one small dense product and a reduction), and the von Mises field's L2
  projection at one state (one vector assembly and one solve with the
  factorised scalar mass matrix), each over one step of the 3D transient
  (one MUMPS solve with its factorised Newmark operator): what the
  recovery adds to a run per output time and per frame;
- the set-up of the recovery (the cuts' functionals, the projection's
  factorisation) over the transient's own factorisation;
- one speed of the harmonic response: the 3D model's real 2 x 2 block
  system (its values, MUMPS numerical LU, solve; a call of SPEEDS speeds,
  whose one symbolic analysis is shared) against the ROM's complex solve at
  the same speed (RotorStructure.steady_state), and against one fresh LU of
  the 3D model's real operator alone (the block form's price).

Times are medians of REPEAT runs (the machine is shared).  ``quick``: one
run of each on 8 x 2 meshes (does it run).
"""

import statistics
import time

REPEAT = 5
#: speeds per harmonic-response call: the symbolic analysis and the block conversion are shared
SPEEDS = 10


def _median(fn, repeat=None):
    repeat = REPEAT if repeat is None else repeat
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def _newmark(model, h=2e-3):
    """A factorised Newmark operator K + 4/h**2 M and a right-hand side, as the transient has them."""
    from petsc4py import PETSc

    A = model.K.copy()
    A.axpy(4 / h**2, model.M, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
    ksp = PETSc.KSP().create(model.comm)
    ksp.setOperators(A)
    ksp.setType("preonly")
    ksp.getPC().setType("lu")
    ksp.getPC().setFactorSolverType("mumps")
    t0 = time.perf_counter()
    ksp.setUp()
    fact = time.perf_counter() - t0
    b, x = A.createVecLeft(), A.createVecRight()
    b.set(1.0)
    ksp.solve(b, x)
    return ksp, A, b, x, fact


def _stress_entries(scene, mesh, label):
    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.sections import section_functionals
    from rotorpillar.fem3d.stress import VonMisesProjection

    model = assemble_pillar(scene, top=True, mesh=mesh)
    ksp, A, b, x, fact = _newmark(model)
    step = _median(lambda: ksp.solve(b, x))
    desc = f"{mesh.elements_around}x{mesh.elements_along} P{mesh.degree}, {model.size} dofs"
    p = scene.pillar
    section_functionals(model, p.youngs_modulus, p.poisson_ratio)  # forms compiled: not timed
    t0 = time.perf_counter()
    sf = section_functionals(model, p.youngs_modulus, p.poisson_ratio)
    t_sections = time.perf_counter() - t0
    t0 = time.perf_counter()
    vm = VonMisesProjection(model, p, scene.gondola.mass + scene.rotor.mass)
    t_vm_setup = time.perf_counter() - t0
    per_state = _median(lambda: sf.resultants(x), repeat=1 if REPEAT == 1 else 50)
    per_frame = _median(lambda: vm.project(x))
    vm.destroy()
    for obj in (ksp, A, b, x, model.K, model.M):
        obj.destroy()
    return [
        {
            "name": f"stress_sections_per_state_over_step_{label}",
            "compares": f"section resultants at {len(sf.heights)} cuts for one state / one Newmark step's "
            f"MUMPS solve ({desc})",
            "value": per_state / step,
            "unit": "x",
            "sections_s": per_state,
            "step_s": step,
        },
        {
            "name": f"stress_von_mises_per_frame_over_step_{label}",
            "compares": f"von Mises L2 projection of one state / one Newmark step's MUMPS solve ({desc})",
            "value": per_frame / step,
            "unit": "x",
            "projection_s": per_frame,
            "step_s": step,
        },
        {
            "name": f"stress_setup_over_factorisation_{label}",
            "compares": f"the recovery's set-up (cuts' functionals + the projection's factorisation) / the "
            f"Newmark operator's MUMPS factorisation ({desc})",
            "value": (t_sections + t_vm_setup) / fact,
            "unit": "x",
            "functionals_s": t_sections,
            "projection_setup_s": t_vm_setup,
            "factorisation_s": fact,
        },
    ]


def _harmonic_entries(scene, mesh, label):
    import numpy as np
    from petsc4py import PETSc

    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.harmonic import harmonic_response
    from rotorpillar.fem3d.rotor_top import RotorOnTop
    from rotorpillar.reduced.models import build_model
    from rotorpillar.scene import override

    model = assemble_pillar(scene, top=True, mesh=mesh)
    rotor = RotorOnTop.from_scene(scene)
    W = 27.0
    batch = np.linspace(0.9, 1.1, SPEEDS) * W  # one analysis, SPEEDS refactorisations
    harmonic_response(model, rotor, scene.pillar.damping, batch[:1])  # warm-up
    t3d = _median(lambda: harmonic_response(model, rotor, scene.pillar.damping, batch)) / SPEEDS

    def real_lu():
        A = model.K.copy()
        A.axpy(-(W**2), model.M, structure=PETSc.Mat.Structure.DIFFERENT_NONZERO_PATTERN)
        ksp = PETSc.KSP().create(model.comm)
        ksp.setOperators(A)
        ksp.setType("preonly")
        ksp.getPC().setType("lu")
        ksp.getPC().setFactorSolverType("mumps")
        ksp.setUp()
        ksp.destroy()
        A.destroy()

    t_lu = _median(real_lu)
    # the ROM's cost depends on its mode count only; the beam's modes spare a chain run here
    rom, _ = build_model(override(scene, ["modal_model.source=beam"]), "modal", 186.0)
    t_rom = _median(lambda: rom.steady_state(W), repeat=1 if REPEAT == 1 else 200)
    desc = f"{mesh.elements_around}x{mesh.elements_along} P{mesh.degree}, {model.size} dofs"
    size = model.size
    model.K.destroy()
    model.M.destroy()
    return [
        {
            "name": f"harmonic_3d_over_rom_per_speed_{label}",
            "compares": f"one speed of the 3D harmonic response (real 2x2 block, {2 * size} unknowns, "
            f"values + MUMPS numerical LU + solve, in a call of {SPEEDS}; {desc}) / one speed "
            f"of the ROM ({rom.nx} X "
            "coordinates, complex solve)",
            "value": t3d / t_rom,
            "unit": "x",
            "fem3d_s": t3d,
            "rom_s": t_rom,
        },
        {
            "name": f"harmonic_block_over_real_lu_{label}",
            "compares": f"one speed of the 3D block system / one MUMPS LU of K - Omega^2 M alone ({desc})",
            "value": t3d / t_lu,
            "unit": "x",
            "fem3d_s": t3d,
            "real_lu_s": t_lu,
        },
    ]


def run(quick: bool = False) -> list[dict]:
    global REPEAT
    from dataclasses import replace

    from rotorpillar.scene import load_scene

    scene = load_scene("paper")
    fo = scene.full_order
    full_order = replace(
        scene.mesh,
        elements_around=fo.elements_around or scene.mesh.elements_around,
        elements_along=fo.elements_along or scene.mesh.elements_along,
    )
    meshes = [(full_order, "full_order_mesh"), (scene.mesh, "modal_mesh")]
    if quick:
        REPEAT = 1
        meshes = [(replace(scene.mesh, elements_around=8, elements_along=2), "quick_mesh")]
    out = []
    for mesh, label in meshes:
        out += _stress_entries(scene, mesh, label) + _harmonic_entries(scene, mesh, label)
    return out


if __name__ == "__main__":
    for e in run():
        print(f"{e['name']}: {e['value']:.4g} {e['unit']}  ({e['compares']})")
