"""Pillar modes from the 3D model (rotorpillar.fem3d) as PillarModes.

Numpy only: it reads a ``rotorpillar.fem3d.ModalResult`` (the tube with its
top mass, ``modal_analysis(scene, top=True)``) and keeps its bending modes
in the paper's X (``kind == "bending_x"``), which the 3D model normalises to
a unit mean displacement of the top section: a modal coordinate is then the
tip displacement in metres, as PillarModes wants, and ``modal_mass`` is the
mass referred to the tip.

The participation L_j = phi_j^T M r is not part of the result; it is
integrated along the height from the mode's section-mean deflection
(``beam_line``, per level of nodes): L_j = int m_rho phi_j dz + m_top phi_j(H)
with phi_j(H) = 1, by Simpson's rule on each quadratic element (exact for
the element's own interpolation) or the trapezoidal rule otherwise.  This is
beam kinematics on the 3D shape: exact for the section-mean motion, blind to
the wall's local deformation, which a uniform base translation does not
excite in bending modes.

Each mode's section resultants (shear and moment at the element-layer
cuts, base included: ``ModalResult.section_resultants``, from the nodal
forces of the elements beside each cut, rotorpillar.fem3d.sections) become
the PillarModes' ``moment_shapes`` and ``shear_shapes``.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import trapezoid  # np.trapz is gone in NumPy 2

from ..errors import InputError
from ..reduced.models import MAX_CANDIDATE_MODES
from ..reduced.pillar import section_of
from ..reduced.pillar_modes import PillarModes
from ..reduced.tower import sections_along, tower_mass
from ..scene import Scene


def integrate_levels(z: np.ndarray, f: np.ndarray) -> float:
    """int f dz over node levels: Simpson per element when the levels are
    (end, middle, end) triples of quadratic elements, else trapezoidal."""
    z, f = np.asarray(z, float), np.asarray(f, float)
    n = len(z)
    if n >= 3 and n % 2 == 1 and np.allclose(z[1:-1:2], 0.5 * (z[0:-2:2] + z[2::2]), rtol=0, atol=1e-9 * z[-1]):
        h = z[2::2] - z[0:-2:2]
        return float(np.sum(h / 6 * (f[0:-2:2] + 4 * f[1:-1:2] + f[2::2])))
    return float(trapezoid(f, z))


def pillar_modes_from_fem3d(result, pillar, count: int) -> PillarModes:
    """The first ``count`` X bending modes of a 3D ModalResult with its top mass."""
    if not getattr(result, "top", False):
        raise InputError("the modal model needs the 3D modes with the gondola on top (modal_analysis(scene, top=True))")
    idx = [i for i, k in enumerate(result.kind) if k == "bending_x"]
    if len(idx) < count:
        raise InputError(
            f"the 3D analysis found {len(idx)} X bending modes, the modal model needs "
            f"{count}: raise modal.n_modes (now {len(result.kind)} modes)"
        )
    idx = idx[:count]
    if result.beam_line is None:
        raise InputError("the 3D modes carry no beam line (not on MPI rank 0?)")
    L, shapes, heights, rotation = [], [], None, []
    plate = getattr(result, "base_plate", None)
    for i in idx:
        z, phi = result.beam_line[i]
        z, phi = np.asarray(z, float), np.asarray(phi, float)
        if plate is not None:
            rotation.append(plate[i, 4] / phi[-1])  # Theta_y turns the tube's upper part along +x
        phi = phi / phi[-1]  # unit tip, as the result normalises
        if pillar.is_uniform:
            L.append(section_of(pillar).mass_per_length * integrate_levels(z, phi) + result.top_mass * phi[-1])
        else:
            m_z = sections_along(pillar, z).mass_per_length
            L.append(integrate_levels(z, m_z * phi) + result.top_mass * phi[-1])
        heights = z if heights is None else heights
        shapes.append(phi)
    total = (section_of(pillar).mass_per_length * pillar.height if pillar.is_uniform else tower_mass(pillar)) + (
        result.top_mass
    )
    cuts = getattr(result, "section_resultants", None)
    resultants = (
        {}
        if cuts is None
        else {
            "section_heights": np.asarray(result.section_heights, float),
            "moment_shapes": np.asarray(cuts)[idx, :, 1].T.copy(),
            "shear_shapes": np.asarray(cuts)[idx, :, 0].T.copy(),
        }
    )
    return PillarModes(
        np.asarray(result.omega)[idx],
        np.asarray(result.modal_mass)[idx],
        np.array(L),
        float(total),
        f"fem3d:{result.cell_type}:{result.cells}cells:deg{result.degree}",
        None,
        heights,
        np.column_stack(shapes),
        {
            "top_model": result.top_model,
            "top_mass": result.top_mass,
            "dofs": result.dofs,
            "participation_by": "Simpson along the section-mean deflection",
        },
        **resultants,
        base_rotation=None if plate is None else np.array(rotation),
    )


def fem3d_pillar_modes(scene: Scene, count: int) -> PillarModes:
    """Run (or reuse, per process) the scene's 3D modal analysis and convert it."""
    if scene.modal.top_mass != "gondola":
        raise InputError(
            'modal.top_mass = "gondola_and_rotor" puts the rotor on the tube rigidly; '
            'the modal model hangs it on its shaft: use modal.top_mass = "gondola"'
        )
    from . import modal_analysis  # dolfinx: imported only on this request

    return pillar_modes_from_fem3d(modal_analysis(scene, top=True), scene.pillar, count)


def candidate_pillar_modes(scene: Scene) -> PillarModes:
    """Every X bending mode the scene's 3D analysis finds (at most
    MAX_CANDIDATE_MODES): the candidates ``rotorpillar.reduced.models.build_model``
    takes as ``pillar_modes`` when ``modal_model.source = "fem3d"``."""
    import importlib.util

    if importlib.util.find_spec("dolfinx") is None:
        raise InputError(
            'modal_model.source = "fem3d" needs the 3D model (dolfinx), which is not '
            'installed here; use modal_model.source = "beam"'
        )
    from . import modal_analysis

    n = sum(1 for k in modal_analysis(scene, top=True).kind if k == "bending_x")
    return fem3d_pillar_modes(scene, max(1, min(n, MAX_CANDIDATE_MODES)))
