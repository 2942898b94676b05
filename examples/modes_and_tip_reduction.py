"""The 3D tube's modes (Gmsh, dolfinx, SLEPc) and the paper's tip reduction on them.

A coarse mesh keeps this to seconds; the scene's default mesh (64 x 10 x 1
quadratic hexahedra) puts the first bending frequency within 0.15 % of the
converged value (docs/fem3d.md).
"""

from rotorpillar import load_scene
from rotorpillar.fem3d import modal_analysis, tip_reduction
from rotorpillar.reduced.reduction import pillar_closed_forms

scene = load_scene("paper", ["mesh.elements_around=16", "mesh.elements_along=8", "modal.n_modes=8"])
bare = modal_analysis(scene, top=False)
for row in bare.modes_table():
    print(f"{row.index:>2} {row.kind:<10} omega = {row.omega:8.3f} rad/s")

closed = pillar_closed_forms(scene.pillar)
red = tip_reduction(bare, scene.pillar)
print(f"first bending: 3D {red.omega_bending:.3f} rad/s, Eq. 1 {closed.omega_col1:.3f} rad/s")
print(
    f"tip reduction (Eq. 2 on the 3D mode): m_r = {red.m_reduced:.0f} kg, "
    f"closed form m_col/4 = {closed.tip_mass_limit:.0f} kg"
)
