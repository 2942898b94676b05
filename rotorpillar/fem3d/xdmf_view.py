"""A quadratic field written to XDMF as the linear field through its nodes.

dolfinx 0.5's ``XDMFFile.write_function`` of a degree-2 function on a
degree-2 mesh evaluates the function at every geometry node by pulling the
node back into each cell (a Newton solve per node): ~120 ms a call on a
320-cell tube.  The same values on the linear view below take ~20 ms
(measured on paper's 16 x 20 tube, 3936 nodes).
A 3D transient writes two fields at 40 frames, so its XDMF cost ~8 s of
the run.

Here each 27-node hexahedron is cut along its nodes into 8 linear
hexahedra, and the field's nodal values are copied onto that linear mesh: the same values at the same
points, drawn linearly between neighbouring nodes instead of quadratically
across the cell (ParaView draws a quadratic cell by subdividing it anyway).
Writing it is dolfinx's fast path.

One process only (in parallel the nodes' owners differ between the two
meshes): :func:`linear_view` returns None there, on other cells than
hexahedra, and where the two fields do not share their nodes; the caller
then writes the quadratic fields as before.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

#: The 8 sub-hexahedra of a 3 x 3 x 3 lattice of nodes: each one's corners as lattice
#: offsets (i, j, k) in dolfinx's vertex order for a hexahedron (x fastest, then y, z).
_HEX_CORNERS = np.array([(i, j, k) for k in (0, 1) for j in (0, 1) for i in (0, 1)])


@dataclass
class LinearView:
    """A linear mesh through the nodes of a quadratic one, and the two fields on it."""

    mesh: Any
    """the linear dolfinx mesh (8 cells per quadratic cell)"""
    vector: Any
    """the vector field on it (P1), named as the quadratic one"""
    scalar: Any
    """the scalar field on it (P1), named as the quadratic one"""
    vector_from: np.ndarray
    """per node of the linear mesh's vector space: the quadratic space's node"""
    scalar_from: np.ndarray
    """per node of the linear mesh's scalar space: the quadratic space's node"""

    def write(self, file, t: float, vector, scalar) -> None:
        """The quadratic ``vector`` and ``scalar`` fields at time ``t`` (s) into ``file``."""
        self.vector.x.array[:] = vector.x.array.reshape(-1, 3)[self.vector_from].ravel()
        self.scalar.x.array[:] = scalar.x.array[self.scalar_from]
        file.write_function(self.vector, t)
        file.write_function(self.scalar, t)


def _lattice_cells(space) -> np.ndarray | None:
    """(cells * 8, 8) the linear hexahedra through a degree-2 hexahedral space's nodes,
    as node indices of that space; None for another cell or degree."""
    element = space.element
    points = np.asarray(element.interpolation_points())
    if points.shape != (27, 3):
        return None
    lattice = np.rint(points * 2).astype(int)  # reference coordinates 0, 1/2, 1 -> 0, 1, 2
    local = {tuple(p): n for n, p in enumerate(lattice)}
    if len(local) != 27:
        return None
    sub = np.array(
        [[local[(a + i, b + j, c + k)] for i, j, k in _HEX_CORNERS] for c in (0, 1) for b in (0, 1) for a in (0, 1)]
    )
    dofs = space.dofmap.list.array.reshape(-1, 27)
    return dofs[:, sub].reshape(-1, 8)


def linear_view(vector, scalar) -> LinearView | None:
    """The :class:`LinearView` of a degree-2 ``vector`` and ``scalar`` field (dolfinx
    Functions) on a hexahedral mesh, or None where it does not apply (see the module text)."""
    import ufl
    from dolfinx import fem
    from dolfinx.mesh import create_mesh

    S = scalar.function_space
    mesh = S.mesh
    if mesh.comm.size > 1 or S.ufl_element().degree() != 2:
        return None
    xs = S.tabulate_dof_coordinates()
    if not np.array_equal(xs, vector.function_space.tabulate_dof_coordinates()):
        return None  # the two fields do not number their nodes alike
    cells = _lattice_cells(S)
    if cells is None:
        return None
    domain = ufl.Mesh(ufl.VectorElement("Lagrange", ufl.hexahedron, 1))
    linear = create_mesh(mesh.comm, cells.astype(np.int64), xs, domain)
    node = np.asarray(linear.geometry.input_global_indices)  # its geometry node -> our node

    def on_linear(space) -> np.ndarray:
        # the degree-1 space's node of each geometry node, cell by cell (the same layout)
        geometry = linear.geometry.dofmap.array.reshape(-1, 8)
        dofs = space.dofmap.list.array.reshape(-1, 8)
        source = np.empty(space.dofmap.index_map.size_local, dtype=np.int64)
        source[dofs.ravel()] = node[geometry.ravel()]
        return source

    V1 = fem.VectorFunctionSpace(linear, ("Lagrange", 1))
    S1 = fem.FunctionSpace(linear, ("Lagrange", 1))
    return LinearView(
        linear,
        fem.Function(V1, name=vector.name),
        fem.Function(S1, name=scalar.name),
        on_linear(V1),
        on_linear(S1),
    )
