"""The 3D model's modes as SpatialPillarModes: every mode of the loaded tube, in every direction.

Numpy only: it reads a ``rotorpillar.fem3d.ModalResult`` of the tube with
the gondola on its rigid top (``modal_analysis(scene, top=True)``) and keeps
every mode: bending in both planes, torsion, axial, ovalling, breathing,
whatever the shape is (rotorpillar.fem3d.identify names it; the words are
rotorpillar.reduced.spatial_modes.KINDS, "ovalling n=2" for a shell mode).
Each carries, for the ModalResult's own scaling (bending: unit mean top
displacement in its plane; every other mode: max |u| = 1):

- ``top``: the rigid plate's six dofs (u_x, u_y, u_z, theta_x, theta_y,
  theta_z) straight from the solve (the plate is 6 unknowns of the model);
- ``modal_mass`` phi^T M phi and ``participation`` phi^T M r_d along x, y, z
  with M everything the model carries (tube, plate, the gondola's 6 x 6
  block), ``total_mass`` r_d^T M r_d of the same M (the clamped base's nodes
  do not move with the ground and are not in it);
- the section resultants at the element-layer cuts, all six
  (rotorpillar.fem3d.sections, spatial): shear in x and y, axial force
  (compression positive), the moments about y and x through the section's
  centre, the torque.

A mode of the wall (ovalling, n >= 2) hardly moves the top: a rigid plate
keeps the top section round and plane, so its n >= 2 motion there is zero
and its n = 0 and n = 1 parts, which could move the plate, are orthogonal
to an n = 2 shape on a tube that is exactly symmetric (a multiple of 4
cells around); what is left is round-off and the eigen-solve's residual
(tests/test_fem3d_spatial_modes.py measures it).
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..reduced.spatial_modes import (
    AXIAL,
    BENDING_ACROSS,
    BENDING_IN_PLANE,
    BREATHING,
    OTHER,
    OVALLING,
    TORSION,
    SpatialPillarModes,
)

#: identify.py's kinds in the words of the spatial side
KIND_WORDS = {
    "bending_x": BENDING_IN_PLANE,
    "bending_y": BENDING_ACROSS,
    "torsion": TORSION,
    "axial": AXIAL,
    "ovalling": OVALLING,
    "breathing": BREATHING,
    "other": OTHER,
}


def kind_words(kind: str, n_circumferential: int | None) -> str:
    """identify.py's kind in words; a shell mode with its wave number ("ovalling n=2")."""
    word = KIND_WORDS[kind]
    return f"{word} n={n_circumferential}" if kind == "ovalling" and n_circumferential is not None else word


def spatial_modes_from_fem3d(result, damping_ratio: float, source: str | None = None) -> SpatialPillarModes:
    """Every mode of a 3D ModalResult of the tube with its rigid top as SpatialPillarModes
    (module text); ``damping_ratio`` zeta (-) on each."""
    if not getattr(result, "top", False) or result.top_model != "rigid":
        raise InputError("the spatial modes need the 3D modes with the gondola on the rigid top plate")
    if result.rigid_top is None:
        raise InputError("the 3D modes carry no top plate motion (not on MPI rank 0?)")
    k = len(result.omega)
    extra: dict = {}
    cuts = result.section_resultants
    if cuts is not None:
        cuts = np.asarray(cuts, float)
        extra = {
            "section_heights": np.asarray(result.section_heights, float),
            "shear_x": cuts[:, :, 0].T.copy(),
            "moment_y": cuts[:, :, 1].T.copy(),
            "axial_force": cuts[:, :, 2].T.copy(),
        }
        if cuts.shape[2] == 6:
            extra.update(shear_y=cuts[:, :, 3].T.copy(), moment_x=cuts[:, :, 4].T.copy(), torque=cuts[:, :, 5].T.copy())
    mesh = result.mesh
    where = (
        f"{mesh.elements_around}x{mesh.elements_along}x{mesh.elements_through}"
        if mesh is not None
        else f"{result.cells}cells"
    )
    return SpatialPillarModes(
        omega=np.asarray(result.omega, float),
        kind=tuple(kind_words(result.kind[j], result.n_circumferential[j]) for j in range(k)),
        modal_mass=np.asarray(result.modal_mass, float),
        top=np.asarray(result.rigid_top, float),
        participation=np.asarray(result.participation, float),
        total_mass=np.asarray(result.rigid_mass, float),
        damping_ratio=np.full(k, float(damping_ratio)),
        source=source or f"fem3d:{result.cell_type}:P{result.degree}:{where}",
        notes=(
            "the SLEPc modes of the tube with the gondola as a rigid body on its rigid top plate; "
            "scaling: bending unit mean top displacement, every other mode max |u| = 1",
        ),
        **extra,
    )
