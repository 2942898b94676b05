"""The tube's mid-surface for the shell model: a cylinder of radius R = (D0 + D1)/4, or a tower's cones.

A circle of ``elements_around`` equal arcs, extruded along the height in
``elements_along`` layers: a structured mesh of quadrilaterals (or of two
triangles per quadrilateral), made quadratic (9-node quadrilaterals, 6-node
triangles) so that the cells follow the circle; flat facets would shrink the
radius by O(h**2) and cap the shell's convergence at second order.

A tower of cans (``segments``) is meshed as the cylinder of its base's
mid-surface radius, its layers meeting every joint, and its nodes then
moved radially onto each can's mid-surface cone (``cone_points``): exact for
the quadratic cells, whose nodes lie on straight generators and circles.

Physical groups: the surface (``SURFACE``), the base circle (``BASE``, the
clamp) and the top circle (``TOP``).  Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
    segments: tuple = ()
    """a tower of cans: per segment (bottom, top, mid-surface radius at bottom, at top) (m),
    linear between; empty: the cylinder of ``radius``"""

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
    n = params.elements_along
    heights = list(layer_fractions(params)) if params.segments else []
    out = occ.extrude(
        [(1, circle)],
        0.0,
        0.0,
        params.height,
        numElements=[1] * n if heights else [n],
        heights=heights,
        recombine=params.cell_type == "quadrilateral",
    )
    occ.synchronize()
    # extrude returns [top curve, surface, seam curves...]
    (_, top), (_, surface) = out[0], out[1]
    model.addPhysicalGroup(2, [surface], SURFACE, name="mid_surface")
    model.addPhysicalGroup(1, [circle], BASE, name="base")
    model.addPhysicalGroup(1, [top], TOP, name="top")
    return {"surface": surface, "base": circle, "top": top}


def layer_fractions(params: MidSurface) -> np.ndarray:
    """Cumulative heights of the cell layers over H (last = 1): equal within each segment,
    shared out among the segments by length (each at least one), a layer interface on
    every joint."""
    n, H = params.elements_along, params.height
    if len(params.segments) > n:
        raise ValueError(f"{len(params.segments)} cans need at least as many cells along, not {n}")
    tops = np.array([s[1] for s in params.segments]) / H
    share = np.diff(np.r_[0.0, tops]) * n
    counts = np.maximum(1, np.floor(share).astype(int))
    while counts.sum() < n:
        counts[int(np.argmax(share - counts))] += 1
    while counts.sum() > n:
        counts[int(np.argmax(np.where(counts > 1, counts - share, -np.inf)))] -= 1
    lo, out = 0.0, []
    for top, c in zip(tops, counts):
        out.append(lo + (top - lo) * np.arange(1, c + 1) / c)
        lo = top
    return np.concatenate(out)


def mid_radius_at(params: MidSurface, z: np.ndarray) -> np.ndarray:
    """The mid-surface radius at heights z (m); at a joint where it steps, the two cans' mean."""
    z = np.asarray(z, dtype=float)
    if not params.segments:
        return np.full_like(z, params.radius)
    out, hits = np.zeros_like(z), np.zeros_like(z)
    tol = 1e-9 * params.height
    for z0, z1, r0, r1 in params.segments:
        on = (z >= z0 - tol) & (z <= z1 + tol)
        s = np.clip((z[on] - z0) / (z1 - z0), 0.0, 1.0)
        out[on] += r0 + s * (r1 - r0)
        hits[on] += 1
    return out / hits


def cone_points(points: np.ndarray, params: MidSurface) -> np.ndarray:
    """The cylinder's nodes moved radially onto the cans' mid-surface cones (same angle, height)."""
    if not params.segments:
        return points
    r = np.hypot(points[:, 0], points[:, 1])
    scale = np.where(r > 0, mid_radius_at(params, points[:, 2]) / np.where(r > 0, r, 1.0), 1.0)
    out = points.copy()
    out[:, 0] *= scale
    out[:, 1] *= scale
    return out
