"""The tube as a dolfinx model: mesh, function space, K and M in PETSc.

The base (z = 0) is clamped.  The top (z = H) is free for the bare tube;
with the masses on top it is one of:

- ``rigid``: a rigid top plate glued to the whole top face carries the top
  mass at the centre of the top section (0, 0, H).  The plate is 6 extra
  degrees of freedom q = (U_x, U_y, U_z, Theta_x, Theta_y, Theta_z), appended
  after the tube's dofs and owned by the last rank; every top-face node
  follows it exactly, u_i = U + Theta x (x_i - (0, 0, H)) (the top-face dofs
  are eliminated, K~ = T^T K T, and stay as inert placeholder rows).
- ``ring_mass``: the top mass spread uniformly over the top face, no
  stiffening (a lower bound: the top section may ovalise under the mass).

Dirichlet rows of K carry 1 on the diagonal and of M 0, so they are infinite
eigenvalues, never returned by the shift-invert solve.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..mesh import BASE, TOP, MeshData, TubeMeshParams, tube_mesh_data
from .forms import mass_form, stiffness_form

#: Extra dofs of the rigid top plate.
RIGID_DOFS = 6


@dataclass
class AssembledPillar:
    """The assembled tube: what a modal solve or a time integrator needs.

    ``K`` and ``M`` are PETSc matrices over the tube's dofs (``3 *
    nodes`` of the vector Lagrange space, dolfinx's global order: node i has
    rows 3i, 3i+1, 3i+2 for x, y, z) followed, for the rigid top, by the
    plate's 6 dofs.  The base's Dirichlet rows have K_ii = 1, M_ii = 0.
    """

    comm: Any
    """the MPI communicator (mpi4py)"""
    K: Any
    """stiffness matrix (PETSc Mat) (N/m)"""
    M: Any
    """mass matrix (PETSc Mat) (kg)"""
    mesh: Any
    """the dolfinx mesh"""
    V: Any
    """the vector Lagrange space (dolfinx FunctionSpace)"""
    facet_tags: Any
    """the facets' physical groups (dolfinx MeshTags)"""
    params: TubeMeshParams
    mesh_data: MeshData | None
    """the Gmsh arrays (rank 0 only; None elsewhere)"""
    tube_dofs: int
    """global number of tube dofs (3 * nodes)"""
    extra_dofs: int
    """0, or 6 for the rigid top plate (global rows tube_dofs ... tube_dofs + 5)"""
    top_model: str | None
    """None (bare tube), "rigid" or "ring_mass\""""
    top_mass: float
    """mass carried at the top (kg)"""
    base_dofs: np.ndarray
    """local indices of the clamped dofs (owned and ghost)"""
    top_nodes: np.ndarray
    """local indices of the owned nodes on the top face"""
    T: Any = None
    """rigid top only: the tube's dofs u = T x from the unknowns x of K and M"""
    timings: dict = field(default_factory=dict)

    @property
    def size(self) -> int:
        return self.tube_dofs + self.extra_dofs

    def owned_node_coordinates(self) -> np.ndarray:
        """Coordinates of this rank's owned nodes (m), in global node order."""
        n = self.V.dofmap.index_map.size_local
        return self.V.tabulate_dof_coordinates()[:n]

    def gather_coordinates(self) -> np.ndarray | None:
        """All node coordinates in global node order, on rank 0 (None elsewhere)."""
        parts = self.comm.gather(self.owned_node_coordinates(), root=0)
        return np.concatenate(parts) if self.comm.rank == 0 else None

    def influence(self, direction: int):
        """PETSc Vec of a unit rigid translation along axis ``direction`` (0 x, 1 y, 2 z).

        For a ground acceleration a_g(t) along that axis, the relative motion
        obeys M u'' + K u = -M r a_g(t) with r this vector.
        """
        r = self.K.createVecRight()
        n_local = self.V.dofmap.index_map.size_local
        arr = r.getArray()
        arr[:] = 0.0
        arr[direction : 3 * n_local : 3] = 1.0
        if self.extra_dofs and self.comm.rank == self.comm.size - 1:
            arr[3 * n_local + direction] = 1.0
        r.setArray(arr)
        return r

    def tube_displacement(self, x):
        """The tube's displacement Vec (tube dofs) of a Vec x of this model's unknowns."""
        if self.T is None:
            return x
        u = self.T.createVecLeft()
        self.T.mult(x, u)
        return u

    def gather_vector(self, vec) -> np.ndarray | None:
        """A PETSc Vec of this model on rank 0 as a numpy array (None elsewhere)."""
        from petsc4py import PETSc

        scatter, v0 = PETSc.Scatter.toZero(vec)
        try:
            scatter.scatter(vec, v0, addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
            return v0.getArray().copy() if self.comm.rank == 0 else None
        finally:
            scatter.destroy()
            v0.destroy()


def dolfinx_mesh(data: MeshData | None, comm):
    """A distributed dolfinx mesh and facet tags from Gmsh arrays held on rank 0.

    The same steps as ``dolfinx.io.gmshio.model_to_mesh``, from arrays, so
    that Gmsh itself may run in another process.
    """
    from .dolfinx_import import import_dolfinx

    import_dolfinx()
    from dolfinx import cpp
    from dolfinx.io import gmshio
    from dolfinx.mesh import create_mesh, meshtags_from_entities

    if comm.rank == 0:
        assert data is not None, "the Gmsh arrays are on rank 0"
        head = (data.gmsh_cell, data.gmsh_facet, data.cells.shape[1], data.facets.shape[1])
        cells, x = data.cells, data.points
        facets, markers = data.facets, data.facet_markers.astype(np.int32)
    head = comm.bcast(head if comm.rank == 0 else None, root=0)
    gmsh_cell, gmsh_facet, nn, nf = head
    if comm.rank != 0:
        cells, x = np.empty((0, nn), dtype=np.int64), np.empty((0, 3))
        facets, markers = np.empty((0, nf), dtype=np.int64), np.empty(0, dtype=np.int32)
    domain = gmshio.ufl_mesh(gmsh_cell, 3)
    cell_type = cpp.mesh.to_type(str(domain.ufl_cell()))
    mesh = create_mesh(comm, cells[:, gmshio.cell_perm_array(cell_type, nn)], x, domain)
    facet_type = cpp.mesh.cell_entity_type(cell_type, 2, 0)
    facets = facets[:, gmshio.cell_perm_array(facet_type, nf)]
    cpp_mesh = getattr(mesh, "_mesh", mesh)
    entities, values = cpp.io.distribute_entity_data(cpp_mesh, 2, facets.astype(np.int64), markers)
    mesh.topology.create_connectivity(2, 3)
    tags = meshtags_from_entities(mesh, 2, cpp.graph.AdjacencyList_int32(entities), values.astype(np.int32))
    return mesh, tags


def _rigid_links(coords: np.ndarray, height: float) -> np.ndarray:
    """R (3 n, 6): nodal displacements of a rigid motion q of the plane z = H about (0, 0, H)."""
    d = coords - np.array([0.0, 0.0, height])
    R = np.zeros((len(d), 3, 6))
    R[:, 0, 0] = R[:, 1, 1] = R[:, 2, 2] = 1.0
    # Theta x d = -[d]x Theta
    R[:, 0, 4], R[:, 0, 5] = d[:, 2], -d[:, 1]
    R[:, 1, 3], R[:, 1, 5] = -d[:, 2], d[:, 0]
    R[:, 2, 3], R[:, 2, 4] = d[:, 1], -d[:, 0]
    return R.reshape(-1, 6)


def assemble_model(
    pillar,
    mesh_section,
    *,
    top_model: str | None = None,
    top_mass: float = 0.0,
    comm=None,
    isolated: bool = True,
    mesh_data: MeshData | None = None,
    clamped: bool = True,
) -> AssembledPillar:
    """Mesh (Gmsh), assemble K and M (dolfinx) and add the top; see the module docstring.

    ``clamped`` False leaves the base free too (a free-free tube, for tests
    against ring theory): K is then singular and a solve needs sigma < 0.
    """
    from .dolfinx_import import import_dolfinx

    import_dolfinx()
    import dolfinx.fem.petsc  # noqa: F401  (the PETSc assemblers live there)
    import ufl
    from dolfinx import fem
    from mpi4py import MPI
    from petsc4py import PETSc

    from ..mesh import tube_params

    comm = MPI.COMM_WORLD if comm is None else comm
    timings = {}
    params = tube_params(pillar, mesh_section)
    t0 = time.perf_counter()
    if comm.rank == 0 and mesh_data is None:
        try:
            mesh_data = tube_mesh_data(params, isolated=isolated)
            failure = None
        except Exception as exc:  # every rank must learn of the failure, not hang
            failure = exc
    else:
        failure = None
    failure = comm.bcast(failure, root=0)
    if failure is not None:
        raise failure
    mesh, tags = dolfinx_mesh(mesh_data if comm.rank == 0 else None, comm)
    timings["mesh"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    degree = mesh_section.degree
    V = fem.VectorFunctionSpace(mesh, ("Lagrange", degree))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    # Full Gauss integration of the Lagrange products (2p per direction on hexahedra).
    dx = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": 2 * degree})
    a = stiffness_form(u, v, pillar.youngs_modulus, pillar.poisson_ratio, dx)
    m = mass_form(u, v, pillar.density, dx)
    if top_model == "ring_mass" and top_mass > 0:
        ds = ufl.Measure("ds", domain=mesh, subdomain_data=tags, metadata={"quadrature_degree": 2 * degree})
        # The discrete face's area, so that exactly top_mass is added.
        one = fem.Constant(mesh, PETSc.ScalarType(1.0))
        area = comm.allreduce(fem.assemble_scalar(fem.form(one * ds(TOP))))
        m = m + mass_form(u, v, top_mass / area, ds(TOP))
    base = fem.locate_dofs_topological(V, 2, tags.find(BASE))
    if not clamped:
        base = base[:0]
    bcs = [fem.dirichletbc(np.zeros(3, dtype=PETSc.ScalarType), base, V)] if clamped else []
    K = fem.petsc.assemble_matrix(fem.form(a), bcs=bcs, diagonal=1.0)
    K.assemble()
    M = fem.petsc.assemble_matrix(fem.form(m), bcs=bcs, diagonal=0.0)
    M.assemble()
    n_local = V.dofmap.index_map.size_local
    top_nodes = fem.locate_dofs_topological(V, 2, tags.find(TOP))
    top_nodes = np.sort(top_nodes[top_nodes < n_local])
    tube_dofs = 3 * V.dofmap.index_map.size_global
    extra = 0
    T = None
    if top_model == "rigid":
        K, M, T = _rigid_top(K, M, V, comm, top_nodes, params.height, top_mass, tube_dofs)
        extra = RIGID_DOFS
    elif top_model not in (None, "ring_mass"):
        raise ValueError(f"unknown top model {top_model!r}")
    timings["assembly"] = time.perf_counter() - t0
    base_dofs = np.sort(np.concatenate([3 * base + c for c in range(3)]))
    return AssembledPillar(
        comm,
        K,
        M,
        mesh,
        V,
        tags,
        params,
        mesh_data if comm.rank == 0 else None,
        tube_dofs,
        extra,
        top_model,
        float(top_mass),
        base_dofs,
        top_nodes,
        T,
        timings,
    )


def _congruence(A, T):
    """T^T A T, as T^T (A T): PETSc's PtAP for AIJ is ~6x slower on these matrices."""
    AT = A.matMult(T)
    try:
        return T.transposeMatMult(AT)
    finally:
        AT.destroy()


def _rigid_top(K, M, V, comm, top_nodes, height, top_mass, tube_dofs):
    """K~ = T^T K T and M~ = T^T M T + plate mass: the tube with its rigid top plate.

    T maps the reduced unknowns (every tube dof but the top face's, which stay
    as inert placeholders, then the plate's q) to the tube's dofs: identity
    off the top face, u_i = R_i q on it.  An exact constraint, no penalty.
    """
    from petsc4py import PETSc

    n_local = 3 * V.dofmap.index_map.size_local
    start = 3 * V.dofmap.index_map.local_range[0]
    last = comm.rank == comm.size - 1
    n_extra_local = RIGID_DOFS if last else 0
    N = tube_dofs
    R = _rigid_links(V.tabulate_dof_coordinates()[top_nodes], height)  # (3 n_top, 6)
    top_rows = (3 * top_nodes[:, None] + np.arange(3)).ravel()  # local rows
    is_top = np.zeros(n_local, dtype=bool)
    is_top[top_rows] = True
    # A top row holds an explicit 0 on its own column, so that K~ keeps a
    # diagonal slot for the placeholder (inserting new nonzeros is slow).
    counts = np.where(is_top, RIGID_DOFS + 1, 1)
    indptr = np.zeros(n_local + 1, dtype=PETSc.IntType)
    np.cumsum(counts, out=indptr[1:])
    indices = np.empty(indptr[-1], dtype=PETSc.IntType)
    values = np.empty(indptr[-1], dtype=PETSc.ScalarType)
    indices[indptr[:-1]] = start + np.arange(n_local)
    values[indptr[:-1]] = np.where(is_top, 0.0, 1.0)
    slots = indptr[top_rows][:, None] + 1 + np.arange(RIGID_DOFS)
    indices[slots] = N + np.arange(RIGID_DOFS)
    values[slots] = R
    T = PETSc.Mat().createAIJ(
        ((n_local, N), (n_local + n_extra_local, N + RIGID_DOFS)), csr=(indptr, indices, values), comm=comm
    )
    T.assemble()
    Kt, Mt = _congruence(K, T), _congruence(M, T)
    for A in (Kt, Mt):
        A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)
    # Placeholders: K_ii = 1, M_ii = 0, like Dirichlet rows (infinite eigenvalues).
    for i in top_rows:
        Kt.setValue(start + i, start + i, 1.0, addv=PETSc.InsertMode.INSERT_VALUES)
    if last:
        for j in range(3):
            Mt.setValue(N + j, N + j, top_mass, addv=PETSc.InsertMode.ADD_VALUES)
    Kt.assemble()
    Mt.assemble()
    K.destroy()
    M.destroy()
    return Kt, Mt, T
