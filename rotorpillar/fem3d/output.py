"""Mode shapes to disk: one VTU per configuration, for ParaView, pyvista, meshio.

The tube's cells on their own geometry: for the default quadratic mesh
(``mesh.degree = 2``) VTK's triquadratic hexahedron (type 29, meshio
"hexahedron27") or quadratic tetrahedron (24, "tetra10"), whose nodes are
the Lagrange space's nodes (on the circles, see
:func:`rotorpillar.mesh.arrays.cylindrical_nodes`); for a first-order mesh
the 8- or 4-vertex cells.  One point array per mode, ``mode_000``,
``mode_001``, ... (3-vector displacement at every node, the normalised shape
of modal.json's list in the same order; the frequencies are in modal.json).
Written atomically on rank 0 only.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..provenance import atomic_path

#: Gmsh element type -> the permutation taking its node order to VTK's:
#: ``vtk_cells = gmsh_cells[:, GMSH_TO_VTK[type]]``.  Vertices agree; Gmsh
#: numbers the hexahedron's edges 01 03 04 12 15 23 26 37 45 47 56 67 and its
#: faces z-, y-, x-, x+, y+, z+, VTK its edges 01 12 23 30 45 56 67 74 04 15
#: 26 37 and its faces x-, x+, y-, y+, z-, z+ (gmsh.info "Node ordering";
#: vtkTriQuadraticHexahedron, vtkQuadraticTetra).  A test checks every node
#: against VTK's own parametric coordinates.
GMSH_TO_VTK = {
    5: list(range(8)),
    4: list(range(4)),
    12: [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26],
    11: [0, 1, 2, 3, 4, 5, 6, 7, 9, 8],
}

#: Nodes per cell -> meshio's name of the VTK cell.
VTK_CELL = {8: "hexahedron", 27: "hexahedron27", 4: "tetra", 10: "tetra10"}


def mode_array_name(i: int) -> str:
    """Point-array name of mode i: mode_000, mode_001, ..."""
    return f"mode_{i:03d}"


def vtk_cells(gmsh_cells: np.ndarray, gmsh_type: int) -> np.ndarray:
    """Gmsh cell connectivity (``MeshData.cells``) in VTK's node order.

    >>> vtk_cells(np.arange(10)[None, :], 11).tolist()
    [[0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
    """
    return np.asarray(gmsh_cells)[:, GMSH_TO_VTK[gmsh_type]]


def write_modes_vtu(path: str | Path, result) -> Path:
    """Write a ModalResult's shapes to ``path`` (.vtu); call on rank 0."""
    import meshio

    if result.shapes is None:
        raise ValueError("this ModalResult has no shapes (not rank 0?)")
    cells = np.asarray(result.vtu_cells, dtype=np.int64)
    point_data = {
        mode_array_name(i): np.ascontiguousarray(result.shapes[i], dtype=np.float64) for i in range(len(result.omega))
    }
    mesh = meshio.Mesh(
        np.asarray(result.points, dtype=np.float64), [(VTK_CELL[cells.shape[1]], cells)], point_data=point_data
    )
    with atomic_path(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
    return Path(path)
