"""The pillar's closed forms and the tip reduction the reduced model uses.

The paper's Eq. 1 with Timoshenko's correction, its Eq. 2 reductions (lumped, continuous
limit, Rayleigh) of the bare tube, and which tip mass and stiffness a scene's
reduced model takes (stated, Eq. 2, or the 3D model's, handed in by the
caller: this package never builds the 3D model itself).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from ..scene import Pillar, Scene, SceneError
from .pillar import (
    cantilever_root,
    cowper_shear_coefficient,
    omega_euler_bernoulli,
    omega_timoshenko,
    rayleigh_reduction,
    section_of,
    tip_mass_continuous,
    tip_mass_lumped,
)

LUMPINGS = (1, 2, 3, 5, 10, 20, 50, 100)


def pillar_closed_forms(pillar: Pillar) -> dict[str, Any]:
    """The paper's Eq. 1 (with Timoshenko's correction) and 2 (the reductions) on the bare
    tube of ``[pillar]``."""
    p = pillar
    sec = section_of(p)
    I, A, m_rho = sec.second_moment, sec.area, sec.mass_per_length
    mass = m_rho * p.height
    w1 = omega_euler_bernoulli(p.youngs_modulus, I, m_rho, p.height)
    kappa = cowper_shear_coefficient(p.outer_diameter, p.inner_diameter, p.poisson_ratio)
    w_timo = omega_timoshenko(p.youngs_modulus, p.poisson_ratio, kappa, p.density, A, I, p.height)
    lumped = [
        {"n": n, "tip_mass": tip_mass_lumped(mass, n), "tip_stiffness": tip_mass_lumped(mass, n) * w1**2}
        for n in LUMPINGS
    ]
    m_inf = tip_mass_continuous(mass)
    rayleigh = []
    for shape in ("uniform_load", "tip_load"):
        r = rayleigh_reduction(mass, p.youngs_modulus, I, p.height, shape)
        rayleigh.append(
            {
                "shape": shape,
                "tip_mass": r.tip_mass,
                "tip_stiffness": r.tip_stiffness,
                "omega": r.omega,
                "omega_error": r.omega / w1 - 1,
            }
        )
    return {
        "area": A,
        "second_moment": I,
        "mass_per_length": m_rho,
        "mass": mass,
        "wall_thickness": sec.wall_thickness,
        "diameter_to_thickness": p.outer_diameter / sec.wall_thickness,
        "slenderness": p.height / sec.radius_of_gyration,
        "omega_col1": w1,
        "frequency_col1_hz": w1 / (2 * math.pi),
        "cantilever_root": cantilever_root(1),
        "omega_euler_bernoulli": [omega_euler_bernoulli(p.youngs_modulus, I, m_rho, p.height, k) for k in (1, 2, 3)],
        "shear_coefficient": kappa,
        "omega_col1_timoshenko": w_timo,
        "timoshenko_correction": w_timo / w1 - 1,
        "tip_mass_lumped": lumped,
        "tip_mass_limit": m_inf,
        "tip_stiffness_limit": m_inf * w1**2,
        "rayleigh": rayleigh,
    }


def resolve_reduction(
    scene: Scene, closed: dict[str, Any], fem3d_reduction: Callable[[Scene], tuple[float, float]] | None = None
) -> dict[str, Any]:
    """The tip mass and stiffness the reduced model uses, and where each came from.

    ``fem3d_reduction`` is a callable scene -> (m_reduced, tip_stiffness), used
    when the scene's source is "fem3d".
    """
    red = scene.reduction
    computed = {"tip_mass": closed["tip_mass_limit"], "tip_stiffness": closed["tip_stiffness_limit"]}
    source = "closed_form"
    if red.source == "fem3d":
        if fem3d_reduction is None:
            raise SceneError(
                'reduction.source = "fem3d" needs the 3D model (rotorpillar.fem3d), which is not available here'
            )
        m, c = fem3d_reduction(scene)
        computed, source = {"tip_mass": m, "tip_stiffness": c}, "fem3d"
    out = {"source": red.source}
    for key in ("tip_mass", "tip_stiffness"):
        stated = getattr(red, key)
        if stated is not None and red.source in ("auto", "stated"):
            out[key], out[f"{key}_source"] = stated, "stated"
        elif red.source == "stated":
            raise SceneError(f'reduction.{key}: required when reduction.source = "stated"')
        else:
            out[key], out[f"{key}_source"] = computed[key], source
        out[f"{key}_computed"] = computed[key]
    out["computed_source"] = source
    return out
