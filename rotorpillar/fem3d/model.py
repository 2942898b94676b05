"""The tube as a dolfinx model: mesh, function space, K and M in PETSc.

The base (z = 0) is clamped, or, on a flexible foundation, tied to a rigid
base plate that stands on the foundation's springs (rotorpillar.fem3d.
rigid_faces: its 6 dofs take the rows of six of the base face's own, so the
model keeps its size and its top plate's place).  The top (z = H) is free
for the bare tube; with the masses on top it is one of:

- ``rigid``: a rigid top plate glued to the whole top face carries the
  bodies on top (:class:`TopBody`: the gondola, and the rotor welded on in
  the stiff-shaft limit) as rigid bodies: each its mass, its three
  rotary inertias about its own centre and that centre's height above the
  top section's centre (0, 0, H), one 6 x 6 mass block on the plate's dofs
  (with no inertia and no height: a point mass at (0, 0, H), as the
  paper's tip mass).  The plate is 6 extra
  degrees of freedom q = (U_x, U_y, U_z, Theta_x, Theta_y, Theta_z), appended
  after the tube's dofs and owned by the last rank; every top-face node
  follows it exactly, u_i = U + Theta x (x_i - (0, 0, H)) (the top-face dofs
  are eliminated, K~ = T^T K T, and stay as inert placeholder rows).
- ``ring_mass``: the top mass spread uniformly over the top face, no
  stiffening (a lower bound: the top section may ovalise under the mass);
  the bodies' rotary inertias and heights are not represented.

Dirichlet rows of K carry 1 on the diagonal and of M 0, so they are infinite
eigenvalues, never returned by the shift-invert solve.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..mesh import BASE, TOP, MeshData, TubeMeshParams, cached_tube_mesh_data
from .forms import mass_form, stiffness_form
from .rigid_faces import RigidFace, base_carriers, foundation_block, tie_faces

#: Extra dofs of the rigid top plate.
RIGID_DOFS = 6


@dataclass(frozen=True)
class TopBody:
    """A rigid body fixed to the top plate (SI), its axes the model's.

    The plate's 6 dofs are (in the rotor's plane, along the spin axis,
    vertical, pitch, roll, yaw) = (U_x, U_y, U_z, Theta_x, Theta_y, Theta_z).
    """

    mass: float
    """its mass (kg)"""
    pitch_inertia: float = 0.0
    """about the horizontal axis in the rotor's plane (x) through its own centre (kg*m**2)"""
    roll_inertia: float = 0.0
    """about the spin axis (y) through its own centre (kg*m**2)"""
    yaw_inertia: float = 0.0
    """about the vertical (z) through its own centre (kg*m**2)"""
    height: float = 0.0
    """its centre above the top section's centre (0, 0, H) (m)"""

    def mass_block(self) -> np.ndarray:
        """The 6 x 6 mass matrix of the body on the plate's dofs (kg, kg*m, kg*m**2).

        Its centre moves with U + Theta x (0, 0, h) = (U_x + h Theta_y,
        U_y - h Theta_x, U_z); kinetic energy 1/2 m |that|**2 + 1/2 the
        rotations' inertia about the centre, so the block is R^T m R +
        diag(0, 0, 0, I_x, I_y, I_z) with R = [1, -[d]x], d = (0, 0, h):
        the parallel-axis terms m h**2 on pitch and roll, m h between the
        translation and the rotation that carries the centre along it.

        >>> TopBody(2.0, 1.0, 3.0, 5.0, height=0.5).mass_block()[[0, 1, 3, 4], [4, 3, 3, 4]]
        array([ 1. , -1. ,  1.5,  3.5])
        """
        m, h = self.mass, self.height
        B = np.zeros((6, 6))
        B[0, 0] = B[1, 1] = B[2, 2] = m
        B[0, 4] = B[4, 0] = m * h
        B[1, 3] = B[3, 1] = -m * h
        B[3, 3] = self.pitch_inertia + m * h * h
        B[4, 4] = self.roll_inertia + m * h * h
        B[5, 5] = self.yaw_inertia
        return B


def top_mass_block(bodies) -> np.ndarray:
    """The sum of the bodies' 6 x 6 mass blocks on the plate (see TopBody.mass_block)."""
    return sum((b.mass_block() for b in bodies), np.zeros((6, 6)))


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
    """rigid top or base on springs: the tube's dofs u = T x from the unknowns x of K and M"""
    top_block: np.ndarray = field(default_factory=lambda: np.zeros((6, 6)))
    """rigid top: the bodies' 6 x 6 mass block on the plate's dofs (kg, kg*m, kg*m**2)"""
    timings: dict = field(default_factory=dict)
    base_plate: np.ndarray | None = None
    """on a flexible foundation: (6,) the global rows holding the base plate's q = (U_x, U_y,
    U_z, Theta_x, Theta_y, Theta_z), -1 where the foundation holds that motion; None: clamped"""
    rotation_rows: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.int64))
    """this rank's local rows holding the base plate's rotations (a translation's influence is 0 there)"""

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
        arr[self.rotation_rows] = 0.0  # the base plate's rotations, on a flexible foundation
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


def assemble_model(
    pillar,
    mesh_section,
    *,
    top_model: str | None = None,
    top_mass: float = 0.0,
    top_bodies: tuple[TopBody, ...] | None = None,
    comm=None,
    isolated: bool = True,
    mesh_data: MeshData | None = None,
    clamped: bool = True,
    foundation=None,
) -> AssembledPillar:
    """Mesh (Gmsh), assemble K and M (dolfinx) and add the top; see the module docstring.

    ``top_bodies``: the rigid bodies on a rigid top (None: one point mass
    ``top_mass`` at the top section's centre); their masses must sum to
    ``top_mass``.

    ``clamped`` False leaves the base free too (a free-free tube, for tests
    against ring theory): K is then singular and a solve needs sigma < 0.
    ``foundation`` (rotorpillar.reduced.foundation.FoundationStiffness): the base
    tied to a rigid plate on its springs instead of the clamp.
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
            mesh_data = cached_tube_mesh_data(params, isolated=isolated)
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
    base_nodes = np.sort(base[base < V.dofmap.index_map.size_local])
    if not clamped or foundation is not None:
        base = base[:0]
    clamped = clamped and foundation is None
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
    bodies = (TopBody(top_mass),) if top_bodies is None else tuple(top_bodies)
    if top_model == "rigid" and abs(sum(b.mass for b in bodies) - top_mass) > 1e-12 * max(top_mass, 1.0):
        raise ValueError("the top bodies' masses must sum to top_mass")
    block = top_mass_block(bodies)
    if top_model not in (None, "rigid", "ring_mass"):
        raise ValueError(f"unknown top model {top_model!r}")
    faces = []
    if top_model == "rigid":
        extra = RIGID_DOFS
        faces.append(RigidFace(top_nodes, params.height, tube_dofs + np.arange(RIGID_DOFS), block, np.zeros((6, 6))))
    plate, rotation_rows = None, np.empty(0, dtype=np.int64)
    if foundation is not None:
        springs, free = foundation_block(foundation)
        plate, rotation_rows = base_carriers(V, comm, base_nodes, free)
        faces.append(RigidFace(base_nodes, 0.0, plate, np.zeros((6, 6)), springs))
    if faces:
        K, M, T = tie_faces(K, M, V, comm, faces, tube_dofs, extra)
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
        block if top_model == "rigid" else np.zeros((6, 6)),
        timings,
        plate,
        rotation_rows,
    )
