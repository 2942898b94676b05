"""The full-order 1D beam with the rotor on its shaft: every beam degree of freedom, no modal truncation.

The same physics as the planar modal model (rotorpillar.reduced.rotor_models.modal_model):
b1 as a dashpot at the tip, b2 on the rotor relative to the ground, -M r a_g.
"""

from __future__ import annotations

import numpy as np

from ..scene import Pillar, Rotor, Shaft
from .rotor_models import RotorStructure


def beam_model(
    pillar: Pillar,
    gondola_mass: float,
    rotor: Rotor,
    shaft: Shaft,
    elements: int = 10,
    theory: str = "timoshenko",
    gondola_inertia: float = 0.0,
) -> RotorStructure:
    """Full order: every degree of freedom of the 1D beam (deflection and
    rotation per node, the gondola on top) and the rotor centre in X,
    relative to the ground, with the same physics as ``modal_model`` (b1 as
    a dashpot at the tip, -M r a_g).  The modal model with all the beam's
    modes is this model in other coordinates; with fewer it is its reduction."""
    from .beam_fe import assemble
    from .pillar_modes import beam_properties

    bp = beam_properties(pillar, theory)
    K, M = assemble(bp, elements, theory, gondola_mass, gondola_inertia)
    nb = K.shape[0]
    nx = nb + 1
    tip_dof = nb - 2  # (w, psi) per node: the top node's w
    Mx = np.zeros((nx, nx))
    Mx[:nb, :nb] = M
    Mx[nb, nb] = rotor.mass
    Ks = np.zeros((nx, nx))
    Ks[:nb, :nb] = K
    C = np.zeros((nx, nx))
    C[tip_dof, tip_dof] = pillar.damping
    C[nb, nb] = shaft.damping
    d = np.zeros(nx)
    d[tip_dof], d[nb] = -1.0, 1.0
    tip = np.zeros(nx)
    tip[tip_dof] = 1.0
    r = np.zeros(nx)
    r[0:nb:2] = 1.0
    r[nb] = 1.0
    names = tuple(f"{'w' if i % 2 == 0 else 'psi'}{i // 2 + 1}" for i in range(nb)) + ("rotor_x",)
    return RotorStructure(
        name="beam",
        coordinates=names,
        mass=Mx,
        stiffness=Ks,
        damping=C,
        shaft=d,
        tip=tip,
        rotor_x=nb,
        shaft_stiffness=shaft.stiffness,
        shaft_damping=shaft.damping,
        eccentricity=rotor.eccentricity,
        rotor_mass=rotor.mass,
        rotor_inertia=rotor.inertia,
        base_displacement=np.zeros(nx),
        base_velocity=np.zeros(nx),
        base_acceleration=-(Mx @ r),
        frame="relative_to_ground",
        notes={
            "equations": f"full-order 1D {theory} beam, {elements} elements, rotor on its shaft",
            "dofs": nx + 2,
            "full_order": True,
        },
    )
