"""The project's word lists, in one place: cases, models, integrators, cell types.

Every module, the CLI and the report take them from here (re-exported by
:mod:`rotorpillar.scene`), so a new case, model, integrator or cell type is
added once.
"""

#: Transient cases of `rotorpillar simulate`.
CASES = ("runup", "rundown", "sweep", "earthquake")
#: The cases of `rotorpillar study` (the sweep is a study of its own).
STUDY_CASES = ("runup", "rundown", "earthquake")
#: Transient models: the paper's Eq. 4 as published, the pillar by its modes
#: (the reduced-order model), and at full order the 3D tube and the 1D beam.
MODELS = ("paper", "modal", "fem3d", "beam")
FULL_ORDER_MODELS = ("fem3d", "beam")
#: The models of `rotorpillar study` (its batches run the compiled ODE models; not the 3D).
STUDY_MODELS = ("paper", "modal", "beam")
#: The compiled adaptive integrator, scipy's solve_ivp methods, and the
#: compiled fixed-step schemes.
ADAPTIVE_INTEGRATORS = ("dp5",)
SCIPY_METHODS = ("RK45", "DOP853", "Radau", "BDF", "LSODA")
FIXED_STEP_INTEGRATORS = ("newmark", "hht", "generalized_alpha", "central_difference")
INTEGRATORS = ADAPTIVE_INTEGRATORS + SCIPY_METHODS + FIXED_STEP_INTEGRATORS
#: Cells of the 3D solid mesh, and of the shell's mid-surface mesh.
CELL_TYPES = ("hexahedron", "tetrahedron")
SHELL_CELL_TYPES = ("quadrilateral", "triangle")
