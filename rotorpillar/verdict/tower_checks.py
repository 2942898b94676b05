"""summary.json's checks of a tower: each can's stress and buckling, the foundation's rotation,
the first tower mode against the excitation orders (1P, the blade passing: soft-stiff).

Read from the runs' ``internal_forces`` blocks (``cans``, ``foundation``) and
harmonic.json's ``orders`` (rotorpillar.reduced.margins.order_margins).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..reduced.capacity import FAIL, GAMMA_M0, PASS, Check, check, meridional_buckling

if TYPE_CHECKING:
    from ..reduced.internal_forces import CanStress
    from ..scene import Scene
    from ..transients.forces import FoundationResponse
    from .harmonic import HarmonicResult


def can_checks(scene: Scene, cans: tuple[CanStress, ...], model: str, case: str, src: str) -> list[Check]:
    """Each can's largest stress (where along it, when) against yield and against its own
    shell buckling resistance: EN 1993-1-6 with the can's D/t there, a cone as its
    equivalent cylinder (Annex D.2: r / cos beta), the length the tower's height (its
    girth welds are no boundaries: the long cylinder's C_x is not overstated)."""
    p, mat = scene.pillar, scene.material
    out = []
    for c in cans:
        t = c.wall_thickness
        cos_b = math.cos(c.cone_angle)
        r = (c.outer_diameter - t) / 2 / cos_b
        b = meridional_buckling(
            p.youngs_modulus, r, t, p.height / cos_b, mat.yield_strength, mat.fabrication_class, c.axial_share
        )
        where = f"can {c.can} ({c.bottom:.4g}-{c.top:.4g} m)"
        stress = c.stress
        at = f"at z = {c.height:.4g} m, t = {c.time:.4g} s, D/t = {c.outer_diameter / t:.0f}"
        out.append(
            check(
                f"{where} stress vs yield",
                "can_stress",
                "Pa",
                stress,
                mat.yield_strength / GAMMA_M0,
                model,
                case,
                f"{src}: internal_forces.cans[{c.can}].stress {at}; f_yk, gamma_M0 = {GAMMA_M0:g}",
            )
        )
        out.append(
            check(
                f"{where} stress vs shell buckling",
                "can_stress",
                "Pa",
                stress,
                b.design_stress,
                model,
                case,
                f"{src}: internal_forces.cans[{c.can}].stress {at}; sigma_x,Rd of EN 1993-1-6 with "
                f"the can's r = {r:.4g} m and t = {t:.4g} m there (class {mat.fabrication_class}, C_x "
                f"{b.cx:.3g} at the demand's axial share {c.axial_share:.3g})",
            )
        )
    return out


def foundation_checks(scene: Scene, found: FoundationResponse | None, model: str, case: str, src: str) -> list[Check]:
    """The base's peak rotation on a flexible foundation against foundation.rotation_limit."""
    if found is None:
        return []
    return [
        check(
            "foundation rotation vs limit",
            "foundation_rotation",
            "rad",
            found.rotation,
            scene.foundation.rotation_limit,
            model,
            case,
            f"{src}: internal_forces.foundation.rotation (the base's, on the {found.kind} springs); "
            "foundation.rotation_limit (serviceability)",
        )
    ]


def order_checks(h: HarmonicResult) -> list[Check]:
    """The first tower mode's separation from each excitation order at each running speed."""
    out: list[Check] = []
    orders = h.orders
    if orders is None:
        return out
    for o in orders.rows:
        out.append(
            Check(
                f"tower mode vs {o.order}P (soft-stiff)",
                "order_margin",
                "-",
                o.required,
                o.actual,
                o.required / o.actual if o.actual > 0 else math.inf,
                PASS if o.status == "pass" else FAIL,
                o.mode.model,
                f"running at {o.running_speed:.4g} rad/s",
                f"harmonic.json orders: {o.mode.kind} at {o.mode.omega:.4g} rad/s {o.position} "
                f"{o.order}P = {o.excitation:.4g} rad/s ({orders.regime}); demand = rotor.order_margin, "
                "capacity = the margin there is",
            )
        )
    return out
