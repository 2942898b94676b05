"""The meshed tube as arrays (Gmsh's numbering), and the quadratic nodes on the circles."""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np

from ..errors import ComputationError
from .tube import BASE, GMSH_CELLS, TOP, TUBE, WALL, TubeMeshParams, conical_points


@dataclass(frozen=True)
class MeshData:
    """The tube's mesh as arrays, in Gmsh's node numbering and ordering.

    ``cells`` and ``facets`` index rows of ``points``; ``facet_markers`` holds
    the physical group (BASE, TOP, WALL) of each facet.
    """

    points: np.ndarray
    """node coordinates (n, 3) (m)"""
    cells: np.ndarray
    """cell-node connectivity (c, nodes per cell), Gmsh node order"""
    gmsh_cell: int
    """Gmsh element type of the cells (5, 12, 4, 11)"""
    facets: np.ndarray
    """facet-node connectivity (f, nodes per facet), Gmsh node order"""
    gmsh_facet: int
    """Gmsh element type of the facets"""
    facet_markers: np.ndarray
    """physical group of each facet (f,)"""

    @property
    def cell_type(self) -> str:
        return GMSH_CELLS[self.gmsh_cell][0]

    @property
    def order(self) -> int:
        return GMSH_CELLS[self.gmsh_cell][1]

    def corner_cells(self) -> np.ndarray:
        """The cells by their vertices only (first-order connectivity, VTK order)."""
        return self.cells[:, : 8 if self.cell_type == "hexahedron" else 4]

    def to_bytes(self) -> bytes:
        buf = io.BytesIO()
        np.savez(
            buf,
            points=self.points,
            cells=self.cells,
            facets=self.facets,
            facet_markers=self.facet_markers,
            types=np.array([self.gmsh_cell, self.gmsh_facet]),
        )
        return buf.getvalue()

    @classmethod
    def from_bytes(cls, data: bytes) -> MeshData:
        z = np.load(io.BytesIO(data))
        return cls(z["points"], z["cells"], int(z["types"][0]), z["facets"], int(z["types"][1]), z["facet_markers"])


def cylindrical_nodes(points: np.ndarray, cells: np.ndarray, reference: np.ndarray, cell_type: str) -> np.ndarray:
    """Positions of the cells' nodes, mapped from their vertices in cylindrical coordinates.

    Gmsh puts the mid-edge node of a straight mesh edge (a tetrahedron's
    diagonal, for one) at the chord's midpoint, inside the wall's true
    surface.  Here every node of a cell is placed by the first-order map of
    the cell's vertices in (r, theta, z): exact on the circles, and equal on
    an edge or face shared by two cells.  ``reference`` holds the nodes'
    reference coordinates (Gmsh's, [-1, 1]**3 or the unit simplex).

    >>> pts = np.array([[1., 0, 0], [0, 1, 0], [0, 0, 1], [0.5, 0.5, 0]])
    >>> ref = np.array([[0., 0, 0], [1, 0, 0], [0, 1, 0], [0.5, 0, 0]])
    >>> cylindrical_nodes(pts, np.array([[0, 1, 2, 3]]), ref, "tetrahedron")[0, 3].round(6)
    array([0.707107, 0.707107, 0.      ])
    """
    nv = 8 if cell_type == "hexahedron" else 4
    v = points[cells[:, :nv]]
    r = np.hypot(v[..., 0], v[..., 1])
    theta = np.arctan2(v[..., 1], v[..., 0])
    theta = theta[:, :1] + (theta - theta[:, :1] + np.pi) % (2 * np.pi) - np.pi
    if cell_type == "hexahedron":
        # trilinear shape functions on [-1, 1]**3 in Gmsh's vertex order
        sign = np.array(
            [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]],
            dtype=float,
        )
        shape = np.prod(1 + reference[:, None, :] * sign[None, :, :], axis=2) / 8
    else:
        u, w, s = reference.T
        shape = np.stack([1 - u - w - s, u, w, s], axis=1)
    rn, tn, zn = (np.einsum("nv,cv->cn", shape, q) for q in (r, theta, v[..., 2]))
    return np.stack([rn * np.cos(tn), rn * np.sin(tn), zn], axis=-1)


def extract_mesh_data(model, params: TubeMeshParams | None = None) -> MeshData:
    """The arrays of a meshed Gmsh model with the tube's physical groups; a tower's
    (``params.segments``) with its nodes on the cans' cones (tube.conical_points)."""
    tags, coords, _ = model.mesh.getNodes()
    order = np.argsort(tags)
    points = coords.reshape(-1, 3)[order]
    if params is not None:
        points = conical_points(points, params)
    index = np.empty(int(tags.max()) + 1, dtype=np.int64)
    index[tags[order]] = np.arange(len(tags))

    def elements(dim: int, group: int) -> tuple[np.ndarray, int]:
        blocks, etype = [], None
        for ent in model.getEntitiesForPhysicalGroup(dim, group):
            types, _, nodes = model.mesh.getElements(dim, ent)
            if len(types) != 1:
                raise ComputationError(f"Gmsh: entity ({dim}, {ent}) holds {len(types)} element types")
            etype = int(types[0])
            nn = model.mesh.getElementProperties(etype)[3]
            blocks.append(index[nodes[0].astype(np.int64)].reshape(-1, nn))
        if etype is None:
            raise ComputationError(f"Gmsh: physical group ({dim}, {group}) holds no elements")
        return np.concatenate(blocks), etype

    cells, gmsh_cell = elements(3, TUBE)
    if GMSH_CELLS[gmsh_cell][1] > 1:
        reference = np.asarray(model.mesh.getElementProperties(gmsh_cell)[4]).reshape(cells.shape[1], 3)
        points = points.copy()
        points[cells] = cylindrical_nodes(points, cells, reference, GMSH_CELLS[gmsh_cell][0])
    facets, markers = [], []
    for group in (BASE, TOP, WALL):
        f, gmsh_facet = elements(2, group)
        facets.append(f)
        markers.append(np.full(len(f), group, dtype=np.int32))
    # Drop nodes no cell uses (the circles' centre point) and renumber.
    used = np.unique(cells)
    renumber = np.full(len(points), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    return MeshData(
        points[used], renumber[cells], gmsh_cell, renumber[np.concatenate(facets)], gmsh_facet, np.concatenate(markers)
    )
