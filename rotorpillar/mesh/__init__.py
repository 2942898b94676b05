"""Gmsh builders of the pillar: the tube as a structured mesh, and its arrays.

Axes: the tube axis is z (base at z = 0, top at z = H); x is the paper's X
(the horizontal bending direction in the rotor's plane); y is the other
horizontal direction (the paper's Z, along the rotor's spin axis).

The annulus 0 <= theta < 2 pi, r_i <= r <= r_o is meshed as transfinite
sectors (quadrilaterals, or triangles for tetrahedra) and swept along z in
layers, so the mesh has ``elements_around`` x ``elements_through`` x
``elements_along`` cells (hexahedra) or six times as many tetrahedra.  When
``elements_around`` is a multiple of 4 the mesh keeps the tube's quarter
symmetry, and the two bending directions stay an exact degenerate pair.
With degree 2 the geometry is second order too (27-node hexahedra, 10-node
tetrahedra, nodes on the circles): a polygonal first-order section would
lose ``(2/3) sin(pi/N)**2`` of the radius of gyration squared.

Gmsh can abort the process it runs in (a C++ crash is not an exception), so
:func:`tube_mesh_data` runs it by default in a child Python process that
hands the arrays back through a pipe (no file is written); a failure there
is a :class:`~rotorpillar.errors.ComputationError` naming Gmsh.

>>> p = TubeMeshParams(20.0, 1.0, 0.98, 8, 4, 1, 1, "hexahedron")
>>> p.cells, p.sectors
(32, 4)
>>> TubeMeshParams(20.0, 1.0, 0.98, 0, 4, 1, 1, "hexahedron")
Traceback (most recent call last):
...
rotorpillar.errors.InputError: mesh.elements_around = 0 is out of range: must be an integer >= 4
"""

from .arrays import MeshData, cylindrical_nodes, extract_mesh_data
from .isolated import MESH_TIMEOUT, cached_tube_mesh_data, tube_mesh_data, worker_command
from .midsurface import MidSurface, gmsh_mid_surface, mid_surface_radius
from .tube import (
    BASE,
    GMSH_CELLS,
    GROUP_NAMES,
    TOP,
    TUBE,
    WALL,
    TubeMeshParams,
    TubeTags,
    build_tube,
    layer_heights,
    tube_params,
)

__all__ = [
    "BASE",
    "GMSH_CELLS",
    "GROUP_NAMES",
    "MESH_TIMEOUT",
    "TOP",
    "TUBE",
    "WALL",
    "MeshData",
    "MidSurface",
    "TubeMeshParams",
    "TubeTags",
    "build_tube",
    "cached_tube_mesh_data",
    "cylindrical_nodes",
    "extract_mesh_data",
    "gmsh_mid_surface",
    "layer_heights",
    "mid_surface_radius",
    "tube_mesh_data",
    "tube_params",
    "worker_command",
]
