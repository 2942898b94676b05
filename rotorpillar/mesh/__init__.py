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

from __future__ import annotations

import io
import json
import math
import subprocess
import sys
from dataclasses import asdict, dataclass

import numpy as np

from ..errors import ComputationError, InputError
from ..scene import CELL_TYPES

#: Physical group tags (dimension 3 for the volume, 2 for the surfaces).
TUBE = 1
BASE = 1
TOP = 2
WALL = 3
#: Their names in the Gmsh model.
GROUP_NAMES = {(3, TUBE): "tube", (2, BASE): "base", (2, TOP): "top", (2, WALL): "wall"}

#: Gmsh element type -> (cell name, geometry order)
GMSH_CELLS = {5: ("hexahedron", 1), 12: ("hexahedron", 2), 4: ("tetrahedron", 1),
              11: ("tetrahedron", 2), 3: ("quadrilateral", 1), 10: ("quadrilateral", 2),
              2: ("triangle", 1), 9: ("triangle", 2)}

#: Seconds a meshing child process may take before it is stopped.
MESH_TIMEOUT = 600.0


@dataclass(frozen=True)
class TubeMeshParams:
    """What Gmsh needs to build the tube: its geometry and its discretisation."""
    height: float
    """H (m)"""
    outer_radius: float
    """r_o = D0/2 (m)"""
    inner_radius: float
    """r_i = D1/2 (m), 0 < r_i < r_o"""
    elements_around: int
    """cells around the circumference (-)"""
    elements_along: int
    """cells along the height (-)"""
    elements_through: int
    """cells through the wall (-)"""
    order: int
    """geometry order, 1 (straight edges) or 2 (nodes on the circles)"""
    cell_type: str
    """"hexahedron" or "tetrahedron\""""
    grading: float = 1.0
    """ratio of the longest cell along the height (at the top) to the shortest
    (at the clamped base), a geometric progression; 1 = uniform (-)"""

    def __post_init__(self):
        for key, lo in (("elements_around", 4), ("elements_along", 1), ("elements_through", 1)):
            v = getattr(self, key)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
                raise InputError(f"mesh.{key} = {v!r} is out of range: must be an integer >= {lo}")
        for key, name in (("height", "pillar.height"), ("outer_radius", "pillar.outer_diameter")):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"{name}: {key} = {v!r} is out of range: must be > 0 (m)")
        ri = self.inner_radius
        if not (isinstance(ri, (int, float)) and math.isfinite(ri) and 0 < ri < self.outer_radius):
            raise InputError(f"pillar.inner_diameter = {2 * ri!r} is out of range: the 3D model needs "
                             f"a tube, 0 < inner_diameter < outer_diameter = {2 * self.outer_radius:g} (m)")
        g = self.grading
        if not (isinstance(g, (int, float)) and math.isfinite(g) and g >= 1):
            raise InputError(f"mesh.grading = {g!r} is out of range: must be >= 1")
        if self.order not in (1, 2):
            raise InputError(f"mesh.degree = {self.order!r}: must be one of 1, 2")
        if self.cell_type not in CELL_TYPES:
            raise InputError(f"mesh.cell_type = {self.cell_type!r}: must be one of "
                             + ", ".join(repr(c) for c in CELL_TYPES))

    @property
    def sectors(self) -> int:
        """Transfinite sectors of the annulus: 4 (quarter symmetry) or one per cell."""
        return 4 if self.elements_around % 4 == 0 else self.elements_around

    @property
    def cells(self) -> int:
        """Number of 3D cells."""
        n = self.elements_around * self.elements_along * self.elements_through
        return n if self.cell_type == "hexahedron" else 6 * n


def layer_heights(p: TubeMeshParams) -> np.ndarray:
    """Cumulative heights of the layers along the tube, over H (last = 1).

    A geometric progression from the base, where the clamp's boundary layer
    (length ~ sqrt(R t)) needs short cells, to the top.

    >>> layer_heights(TubeMeshParams(1.0, 1.0, 0.9, 4, 2, 1, 1, "hexahedron", 3.0)).round(4)
    array([0.25, 1.  ])
    """
    n = p.elements_along
    q = p.grading ** (1 / (n - 1)) if n > 1 else 1.0
    sizes = q ** np.arange(n)
    return np.cumsum(sizes) / sizes.sum()


def tube_params(pillar, mesh) -> TubeMeshParams:
    """The mesh parameters of a scene's ``[pillar]`` and ``[mesh]`` sections."""
    return TubeMeshParams(
        height=pillar.height, outer_radius=pillar.outer_diameter / 2,
        inner_radius=pillar.inner_diameter / 2, elements_around=mesh.elements_around,
        elements_along=mesh.elements_along, elements_through=mesh.elements_through,
        order=mesh.degree, cell_type=mesh.cell_type, grading=getattr(mesh, "grading", 1.0))


@dataclass(frozen=True)
class TubeTags:
    """Gmsh entity tags of the built tube, per physical group."""
    volumes: tuple
    base: tuple
    top: tuple
    wall: tuple


def build_tube(model, p: TubeMeshParams) -> TubeTags:
    """Add the tube to a Gmsh ``model`` (built-in kernel), mesh it, name its groups.

    The groups are "tube" (volume TUBE), "base" (z = 0, BASE), "top" (z = H,
    TOP) and "wall" (inner and outer lateral surfaces, WALL).
    """
    import gmsh
    geo = model.geo
    s, layers = p.sectors, p.elements_through
    per_sector = p.elements_around // s
    hexa = p.cell_type == "hexahedron"
    centre = geo.addPoint(0, 0, 0)
    angles = [2 * math.pi * k / s for k in range(s)]
    # One geometric circle per layer interface, so that second-order nodes
    # inside the wall lie on their circles too (Gmsh puts the mid-edge node
    # of a mesh edge that is not on a curve at the chord's midpoint).
    radii = [p.inner_radius + (p.outer_radius - p.inner_radius) * j / layers for j in range(layers + 1)]
    pts = [[geo.addPoint(r * math.cos(a), r * math.sin(a), 0) for a in angles] for r in radii]
    arcs = [[geo.addCircleArc(pts[j][k], centre, pts[j][(k + 1) % s]) for k in range(s)]
            for j in range(layers + 1)]
    radial = [[geo.addLine(pts[j][k], pts[j + 1][k]) for k in range(s)] for j in range(layers)]
    surfaces, inner, outer = [], [], []
    for j in range(layers):
        for k in range(s):
            loop = geo.addCurveLoop([radial[j][k], arcs[j + 1][k], -radial[j][(k + 1) % s],
                                     -arcs[j][k]])
            surfaces.append(geo.addPlaneSurface([loop]))
            inner.append(j == 0)
            outer.append(j == layers - 1)
    for c in (c for ring in arcs for c in ring):
        geo.mesh.setTransfiniteCurve(c, per_sector + 1)
    for c in (c for layer in radial for c in layer):
        geo.mesh.setTransfiniteCurve(c, 2)
    for sf in surfaces:
        geo.mesh.setTransfiniteSurface(sf, "Alternate")
        if hexa:
            geo.mesh.setRecombine(2, sf)
    # Extruded triangles without recombination become 3 tetrahedra per prism.
    out = geo.extrude([(2, sf) for sf in surfaces], 0, 0, p.height,
                      numElements=[1] * p.elements_along, heights=list(layer_heights(p)),
                      recombine=hexa)
    geo.synchronize()
    # Per extruded surface: [top, volume, side(radial k), side(outer arc), side(radial k+1),
    # side(inner arc)], in the order of the curve loop.
    tops, vols, walls = [], [], []
    for i in range(len(surfaces)):
        chunk = out[6 * i: 6 * i + 6]
        tops.append(chunk[0][1])
        vols.append(chunk[1][1])
        if outer[i]:
            walls.append(chunk[3][1])
        if inner[i]:
            walls.append(chunk[5][1])
    tags = TubeTags(tuple(vols), tuple(surfaces), tuple(tops), tuple(walls))
    for (dim, tag), name in GROUP_NAMES.items():
        ents = {TUBE: tags.volumes}[tag] if dim == 3 else {BASE: tags.base, TOP: tags.top,
                                                           WALL: tags.wall}[tag]
        model.addPhysicalGroup(dim, list(ents), tag, name=name)
    gmsh.option.setNumber("Mesh.ElementOrder", p.order)
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    model.mesh.generate(3)
    if p.order == 2:
        model.mesh.setOrder(2)
    return tags


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
        return self.cells[:, :8 if self.cell_type == "hexahedron" else 4]

    def to_bytes(self) -> bytes:
        buf = io.BytesIO()
        np.savez(buf, points=self.points, cells=self.cells, facets=self.facets,
                 facet_markers=self.facet_markers,
                 types=np.array([self.gmsh_cell, self.gmsh_facet]))
        return buf.getvalue()

    @classmethod
    def from_bytes(cls, data: bytes) -> "MeshData":
        z = np.load(io.BytesIO(data))
        return cls(z["points"], z["cells"], int(z["types"][0]), z["facets"], int(z["types"][1]),
                   z["facet_markers"])


def cylindrical_nodes(points: np.ndarray, cells: np.ndarray, reference: np.ndarray,
                      cell_type: str) -> np.ndarray:
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
        sign = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                         [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
        shape = np.prod(1 + reference[:, None, :] * sign[None, :, :], axis=2) / 8
    else:
        u, w, s = reference.T
        shape = np.stack([1 - u - w - s, u, w, s], axis=1)
    rn, tn, zn = (np.einsum("nv,cv->cn", shape, q) for q in (r, theta, v[..., 2]))
    return np.stack([rn * np.cos(tn), rn * np.sin(tn), zn], axis=-1)


def extract_mesh_data(model) -> MeshData:
    """The arrays of a meshed Gmsh model with the tube's physical groups."""
    tags, coords, _ = model.mesh.getNodes()
    order = np.argsort(tags)
    points = coords.reshape(-1, 3)[order]
    index = np.empty(int(tags.max()) + 1, dtype=np.int64)
    index[tags[order]] = np.arange(len(tags))

    def elements(dim, group):
        blocks, etype = [], None
        for ent in model.getEntitiesForPhysicalGroup(dim, group):
            types, _, nodes = model.mesh.getElements(dim, ent)
            if len(types) != 1:
                raise ComputationError(f"Gmsh: entity ({dim}, {ent}) holds {len(types)} element types")
            etype = int(types[0])
            nn = model.mesh.getElementProperties(etype)[3]
            blocks.append(index[nodes[0].astype(np.int64)].reshape(-1, nn))
        return np.concatenate(blocks), etype

    cells, gmsh_cell = elements(3, TUBE)
    if GMSH_CELLS[gmsh_cell][1] > 1:
        reference = np.asarray(model.mesh.getElementProperties(gmsh_cell)[4]).reshape(cells.shape[1], 3)
        points = points.copy()
        points[cells] = cylindrical_nodes(points, cells, reference, GMSH_CELLS[gmsh_cell][0])
    facets, markers, gmsh_facet = [], [], None
    for group in (BASE, TOP, WALL):
        f, gmsh_facet = elements(2, group)
        facets.append(f)
        markers.append(np.full(len(f), group, dtype=np.int32))
    # Drop nodes no cell uses (the circles' centre point) and renumber.
    used = np.unique(cells)
    renumber = np.full(len(points), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    return MeshData(points[used], renumber[cells], gmsh_cell, renumber[np.concatenate(facets)],
                    gmsh_facet, np.concatenate(markers))


def _mesh_in_process(p: TubeMeshParams) -> MeshData:
    import gmsh
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("tube")
        build_tube(gmsh.model, p)
        data = extract_mesh_data(gmsh.model)
    except InputError:
        raise
    except Exception as exc:  # Gmsh raises plain Exceptions carrying its log line
        raise ComputationError(f"Gmsh failed to mesh the tube: {exc}") from None
    finally:
        gmsh.finalize()
    expected = p.cells
    if len(data.cells) != expected:
        raise ComputationError(f"Gmsh made {len(data.cells)} cells, expected {expected}")
    return data


def tube_mesh_data(p: TubeMeshParams, *, isolated: bool = True) -> MeshData:
    """Mesh the tube with Gmsh and return its arrays.

    With ``isolated`` (the default) Gmsh runs in a child process (``python -m
    rotorpillar.mesh``), so that a crash inside Gmsh cannot take the caller,
    possibly an MPI rank holding PETSc objects, down with it.
    """
    if not isolated:
        return _mesh_in_process(p)
    try:
        # The parameters go on the command line, not through stdin: writing to
        # the pipe of a child that has already died raises SIGPIPE, which
        # PETSc's signal handler (installed once petsc4py is imported) turns
        # into an abort of the caller.
        proc = subprocess.run(worker_command() + [json.dumps(asdict(p))], capture_output=True,
                              stdin=subprocess.DEVNULL, timeout=MESH_TIMEOUT)
    except subprocess.TimeoutExpired:
        raise ComputationError(f"Gmsh did not finish meshing the tube within {MESH_TIMEOUT:g} s") from None
    if proc.returncode != 0:
        err = proc.stderr.decode(errors="replace").strip().splitlines()
        last = err[-1] if err else f"exit code {proc.returncode}"
        if proc.returncode < 0:
            last = f"killed by signal {-proc.returncode} ({last})"
        raise ComputationError(f"Gmsh failed to mesh the tube: {last}")
    return MeshData.from_bytes(proc.stdout)


def worker_command() -> list[str]:
    """The command line of the isolated meshing process."""
    return [sys.executable, "-m", "rotorpillar.mesh"]


def _worker() -> int:
    """Child-process entry: params as JSON in argv[1], MeshData as npz bytes on stdout."""
    params = TubeMeshParams(**json.loads(sys.argv[1]))
    try:
        data = _mesh_in_process(params)
    except (ComputationError, InputError) as exc:
        print(str(exc).removeprefix("Gmsh failed to mesh the tube: "), file=sys.stderr)
        return 1
    sys.stdout.buffer.write(data.to_bytes())
    return 0
