"""Cost of the 3D modal solve against one factorisation, and assembly throughput.

For the default mesh of the paper's tube (and one with twice the cells
along the height, to show the trend), side by side in one run:

- the SLEPc shift-invert solve of the modes `rotorpillar modal` asks for,
  over one MUMPS factorisation of K - sigma M of the same matrices (the
  solve contains one such factorisation; the rest is the Krylov-Schur steps:
  one triangular solve, one M-product and the M-orthogonalisation each);
- the assembly of K and M by dolfinx, in dofs per second (forms compiled
  beforehand, so JIT time is not counted).

Each time is the median of REPEAT runs.
"""

import statistics
import time

REPEAT = 3


def _median_time(fn, repeat=REPEAT):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def _case(scene, mesh, label):
    from petsc4py import PETSc

    from rotorpillar.fem3d import assemble_pillar
    from rotorpillar.fem3d.eigensolver import factorisation_time, solve_gep_shift_invert
    model = assemble_pillar(scene, top=False, mesh=mesh)
    n = scene.modal.n_modes + 1              # what rotorpillar modal computes
    solve_gep_shift_invert(model.K, model.M, n)          # warm-up
    tf = statistics.median(factorisation_time(model.K, model.M) for _ in range(REPEAT))
    PETSc.Log.begin()
    event = PETSc.Log.Event("MatSolve")
    c0, t0 = event.getPerfInfo()["count"], event.getPerfInfo()["time"]

    def solve():
        solve_gep_shift_invert(model.K, model.M, n)
    ts = _median_time(solve)
    steps = (event.getPerfInfo()["count"] - c0) // REPEAT
    triangular = (event.getPerfInfo()["time"] - t0) / REPEAT
    dofs = model.size

    # assembly throughput: K and M of the same mesh, forms already compiled
    import ufl
    from dolfinx import fem
    import dolfinx.fem.petsc  # noqa: F401
    from rotorpillar.fem3d.forms import mass_form, stiffness_form
    V = model.V
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    dx = ufl.Measure("dx", domain=model.mesh, metadata={"quadrature_degree": 2 * mesh.degree})
    p = scene.pillar
    a = fem.form(stiffness_form(u, v, p.youngs_modulus, p.poisson_ratio, dx))
    m = fem.form(mass_form(u, v, p.density, dx))

    def assemble():
        for form in (a, m):
            A = fem.petsc.assemble_matrix(form)
            A.assemble()
            A.destroy()
    ta = _median_time(assemble)
    model.K.destroy()
    model.M.destroy()
    mesh_desc = (f"{mesh.elements_around}x{mesh.elements_along}x{mesh.elements_through} "
                 f"{mesh.cell_type} degree {mesh.degree}, grading {mesh.grading:g}")
    return [
        {"name": f"fem3d_solve_over_factorisation_{label}",
         "compares": f"SLEPc shift-invert solve of {n} modes / one MUMPS LDL^T factorisation "
                     f"of K - sigma M ({dofs} dofs, {mesh_desc})",
         "value": ts / tf, "unit": "x", "solve_s": ts, "factorisation_s": tf,
         "krylov_steps": steps, "step_s": (ts - tf) / max(steps, 1), "dofs": dofs,
         "triangular_solves_s": triangular,
         # what the ratio would be with M-products and orthogonalisation free
         "floor_ratio": 1 + triangular / tf, "target": 3.0},
        {"name": f"fem3d_assembly_throughput_{label}",
         "compares": f"dofs of K and M assembled per second by dolfinx ({mesh_desc})",
         "value": dofs / ta, "unit": "dofs/s", "assembly_s": ta, "dofs": dofs},
    ]


def run():
    from dataclasses import replace

    from rotorpillar.scene import load_scene
    scene = load_scene("paper")
    d = scene.mesh
    finer = replace(d, elements_along=2 * d.elements_along)
    return _case(scene, d, "default") + _case(scene, finer, "2x_along")
