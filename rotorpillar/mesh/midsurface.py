"""The tube's mid-surface for the shell model: a cylinder of radius R = (D0 + D1)/4.

A circle of ``elements_around`` equal arcs, extruded along the height in
``elements_along`` layers: a structured mesh of quadrilaterals (or of two
triangles per quadrilateral), made quadratic (9-node quadrilaterals, 6-node
triangles) so that the cells follow the circle; flat facets would shrink the
radius by O(h**2) and cap the shell's convergence at second order.

Physical groups: the surface (``SURFACE``), the base circle (``BASE``, the
clamp) and the top circle (``TOP``).  Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..scene import SHELL_CELL_TYPES

SURFACE = 1
"""Cell tag of the mid-surface."""
BASE = 1
"""Facet tag of the base circle, z = 0."""
TOP = 2
"""Facet tag of the top circle, z = H."""


@dataclass(frozen=True)
class MidSurface:
    """A structured mesh of a cylinder's lateral surface."""

    radius: float
    """mid-surface radius R (m)"""
    height: float
    """H (m)"""
    elements_around: int
    """cells around the circumference (-)"""
    elements_along: int
    """cells along the height (-)"""
    cell_type: str = "quadrilateral"
    """"quadrilateral" or "triangle" (two per quadrilateral)"""
    order: int = 2
    """geometric order of the cells (-)"""

    def __post_init__(self):
        if self.cell_type not in SHELL_CELL_TYPES:
            raise ValueError(f"cell_type must be one of {SHELL_CELL_TYPES}")
        if self.elements_around < 3 or self.elements_along < 1:
            raise ValueError("need elements_around >= 3 and elements_along >= 1")


def mid_surface_radius(outer_diameter: float, inner_diameter: float) -> float:
    """R = (D0 + D1)/4 (m): the shell's reference surface halves the wall."""
    return (outer_diameter + inner_diameter) / 4


def gmsh_mid_surface(model, params: MidSurface) -> dict[str, int]:
    """Add the meshed cylinder surface to a Gmsh ``model``; return its tags.

    ``model`` is ``gmsh.model`` (Gmsh initialised by the caller).
    """
    occ = model.occ
    circle = occ.addCircle(0.0, 0.0, 0.0, params.radius)
    occ.synchronize()
    # A closed curve: n + 1 nodes make n segments (the end node is the start).
    model.mesh.setTransfiniteCurve(circle, params.elements_around + 1)
    out = occ.extrude(
        [(1, circle)],
        0.0,
        0.0,
        params.height,
        numElements=[params.elements_along],
        recombine=params.cell_type == "quadrilateral",
    )
    occ.synchronize()
    # extrude returns [top curve, surface, seam curves...]
    (_, top), (_, surface) = out[0], out[1]
    model.addPhysicalGroup(2, [surface], SURFACE, name="mid_surface")
    model.addPhysicalGroup(1, [circle], BASE, name="base")
    model.addPhysicalGroup(1, [top], TOP, name="top")
    return {"surface": surface, "base": circle, "top": top}
