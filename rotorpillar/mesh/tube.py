"""The tube as a Gmsh model: its parameters, the structured builder, the group tags.

Axes: z along the tube (base at z = 0), x the paper's X, y the other
horizontal direction.  Units: m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..provenance import check_memory
from ..scene import CELL_TYPES

#: Physical group tags (dimension 3 for the volume, 2 for the surfaces).
TUBE = 1
BASE = 1
TOP = 2
WALL = 3
#: Their names in the Gmsh model.
GROUP_NAMES = {(3, TUBE): "tube", (2, BASE): "base", (2, TOP): "top", (2, WALL): "wall"}

#: Gmsh element type -> (cell name, geometry order)
GMSH_CELLS = {
    5: ("hexahedron", 1),
    12: ("hexahedron", 2),
    4: ("tetrahedron", 1),
    11: ("tetrahedron", 2),
    3: ("quadrilateral", 1),
    10: ("quadrilateral", 2),
    2: ("triangle", 1),
    9: ("triangle", 2),
}


#: Peak memory per displacement DOF of one modal solve in one process (mesh,
#: assembly, the MUMPS factors of K - sigma M, the Krylov basis, the
#: interpreter): 11.5 kB/DOF measured on the convergence study's finest run
#: (3.3 GB at 286 k DOFs, docs/converge.md); `modal` solves twice in one
#: process (bare, then with the top) and peaks at twice this (24 kB/DOF
#: measured at 24 k, 70 k and 231 k DOFs): its check counts two solves.
BYTES_PER_DOF = 12e3
#: Wall time of one `modal` run on a mesh (s), an estimate: MODAL_SECONDS[0] * dofs +
#: MODAL_SECONDS[1] * dofs * front, where ``front`` is the unknowns across the mesh's
#: narrowest cross-section (``TubeMeshParams.front``): meshing, assembly and the Krylov
#: solves grow with the DOFs, the sparse factors of K - sigma M with the DOFs times that
#: front.  Fitted (least relative squares) to whole `modal` runs of the paper's scene
#: (chain modes, two solves, the VTU files) on the 2-core machine shared with another
#: run: 64 x 10 x 1 (around x along x through, 24,192 DOFs) 44 s, 256 x 10 x 1 (96,768)
#: 63 s, 16 x 4 x 20 (35,424) 45 s, 8 x 4 x 100 (86,832) 72 s, 4096 x 4 x 1 (663,552)
#: 243 s; the fit gives 0.3 (the scene's own mesh: its band asks many modes of the
#: loaded tube), 0.9, 1.1, 1.0 and 1.2 of them.  Start-up and form compilation (~3 s: 8 x
#: 4 x 1 runs in 4.7 s) are not counted; the machine's load multiplies the rest.
MODAL_SECONDS = (3.4e-4, 1.2e-6)
#: Smallest tube Gmsh meshes reliably (m): its geometric tolerance is ~1e-8 of the model.
MIN_SIZE = 1e-3


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
    segments: tuple = ()
    """a tower of cans: per segment from the base, (bottom, top, outer diameter at bottom,
    at top, inner diameter at bottom, at top) (m), each diameter linear between; the mesh's
    layers meet every joint and its nodes lie on each can's cones (``conical_points``).
    Empty: the uniform tube of ``outer_radius`` and ``inner_radius``"""

    def __post_init__(self):
        object.__setattr__(self, "segments", tuple(tuple(float(v) for v in s) for s in self.segments))
        if self.segments:
            self._check_segments()
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
            raise InputError(
                f"pillar.inner_diameter = {2 * ri!r} is out of range: the 3D model needs "
                f"a tube, 0 < inner_diameter < outer_diameter = {2 * self.outer_radius:g} (m)"
            )
        if self.height < MIN_SIZE or self.outer_radius - self.inner_radius < MIN_SIZE / 100:
            raise InputError(
                f"pillar: the 3D mesh needs height >= {MIN_SIZE:g} m and a wall "
                f">= {MIN_SIZE / 100:g} m thick (height {self.height:g} m, wall "
                f"{self.outer_radius - self.inner_radius:g} m): Gmsh's tolerances"
            )
        g = self.grading
        if not (isinstance(g, (int, float)) and math.isfinite(g) and g >= 1):
            raise InputError(f"mesh.grading = {g!r} is out of range: must be >= 1")
        if self.order not in (1, 2):
            raise InputError(f"mesh.degree = {self.order!r}: must be one of 1, 2")
        if self.cell_type not in CELL_TYPES:
            raise InputError(
                f"mesh.cell_type = {self.cell_type!r}: must be one of " + ", ".join(repr(c) for c in CELL_TYPES)
            )
        check_memory(
            self.estimated_bytes,
            f"mesh: {self.elements_around} around x {self.elements_along} along x "
            f"{self.elements_through} through: about {self.estimated_dofs:.3g} DOFs",
            "use fewer elements",
        )

    def _check_segments(self) -> None:
        if len(self.segments) > self.elements_along:
            raise InputError(
                f"mesh.elements_along = {self.elements_along} is out of range: must be >= the "
                f"{len(self.segments)} cans, a layer of cells each at least"
            )
        for i, (_, _, o0, o1, i0, i1) in enumerate(self.segments):
            wall = min(o0 - i0, o1 - i1) / 2
            if wall < MIN_SIZE / 100 or min(i0, i1) <= 0:
                raise InputError(
                    f"pillar.cans[{i}]: the 3D mesh needs a tube with a wall >= {MIN_SIZE / 100:g} m "
                    f"and an inner diameter > 0 (wall {wall:g} m): Gmsh's tolerances"
                )

    @property
    def estimated_dofs(self) -> int:
        """Displacement DOFs of the 3D model on this mesh, before meshing (-).

        The structured tube has (k na)(k nt + 1)(k nl + 1) nodes of degree k
        (tetrahedra add face-diagonal nodes: about as many again as a
        hexahedral P2 mesh has, so the same count is a fair estimate).
        """
        k = self.order
        nodes = (k * self.elements_around) * (k * self.elements_through + 1) * (k * self.elements_along + 1)
        return 3 * nodes

    def solver_dofs(self, rigid_top: bool) -> int:
        """Unknowns of the modal problem on this mesh (-): the displacement DOFs above
        the clamped base; with a rigid top plate, those below the top face and the
        plate's 6.  The eigen-solver returns at most this many modes.

        >>> TubeMeshParams(20.0, 1.0, 0.98, 8, 2, 1, 2, "hexahedron").solver_dofs(True)
        438
        """
        k = self.order
        layer = (k * self.elements_around) * (k * self.elements_through + 1)
        free_layers = k * self.elements_along - (1 if rigid_top else 0)
        return 3 * layer * free_layers + (6 if rigid_top else 0)

    @property
    def estimated_bytes(self) -> float:
        """Peak memory of meshing, assembling and factorising this mesh (bytes)."""
        return BYTES_PER_DOF * self.estimated_dofs

    @property
    def front(self) -> int:
        """Unknowns across the mesh's narrowest cross-section (-): the nodes over the
        longest of the node grid's three extents (around, through, along), three DOFs
        each; the width of the sparse factors' separators, on which their cost grows.

        >>> TubeMeshParams(20.0, 1.0, 0.98, 8, 2, 1, 2, "hexahedron").front
        45
        """
        k = self.order
        extents = (k * self.elements_around, k * self.elements_through + 1, k * self.elements_along + 1)
        return 3 * math.prod(extents) // max(extents)

    @property
    def estimated_seconds(self) -> float:
        """Wall time of one `modal` run on this mesh, an estimate (s; MODAL_SECONDS)."""
        a, b = MODAL_SECONDS
        dofs = self.estimated_dofs
        return float(a * dofs + b * dofs * self.front)

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
    cum = np.cumsum(sizes) / sizes.sum()
    if len(p.segments) <= 1:
        return cum
    # a tower of cans: the same graded cells, shared out among the cans (each at least one)
    # and rescaled within each, so that a layer interface lies on every joint
    H = p.height
    tops = np.array([s[1] for s in p.segments]) / H
    owner = np.minimum(np.searchsorted(tops, cum - 1e-12), len(tops) - 1)
    counts = np.array([max(1, int(np.sum(owner == k))) for k in range(len(tops))])
    while counts.sum() > n:
        counts[int(np.argmax(counts))] -= 1
    out, start, lo = [], 0, 0.0
    for k, c in enumerate(counts):
        part = sizes[start : start + c]
        out.append(lo + np.cumsum(part) / part.sum() * (tops[k] - lo))
        start, lo = start + c, tops[k]
    return np.concatenate(out)


def tube_params(pillar, mesh) -> TubeMeshParams:
    """The mesh parameters of a scene's ``[pillar]`` and ``[mesh]`` sections."""
    segs = pillar.segments()
    base = segs[0]
    return TubeMeshParams(
        height=pillar.height,
        outer_radius=base.outer_bottom / 2,
        inner_radius=base.inner_bottom / 2,
        segments=()
        if pillar.is_uniform
        else tuple((s.bottom, s.top, s.outer_bottom, s.outer_top, s.inner_bottom, s.inner_top) for s in segs),
        elements_around=mesh.elements_around,
        elements_along=mesh.elements_along,
        elements_through=mesh.elements_through,
        order=mesh.degree,
        cell_type=mesh.cell_type,
        grading=getattr(mesh, "grading", 1.0),
    )


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
    arcs = [[geo.addCircleArc(pts[j][k], centre, pts[j][(k + 1) % s]) for k in range(s)] for j in range(layers + 1)]
    radial = [[geo.addLine(pts[j][k], pts[j + 1][k]) for k in range(s)] for j in range(layers)]
    surfaces, inner, outer = [], [], []
    for j in range(layers):
        for k in range(s):
            loop = geo.addCurveLoop([radial[j][k], arcs[j + 1][k], -radial[j][(k + 1) % s], -arcs[j][k]])
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
    out = geo.extrude(
        [(2, sf) for sf in surfaces],
        0,
        0,
        p.height,
        numElements=[1] * p.elements_along,
        heights=list(layer_heights(p)),
        recombine=hexa,
    )
    geo.synchronize()
    # Per extruded surface: [top, volume, side(radial k), side(outer arc), side(radial k+1),
    # side(inner arc)], in the order of the curve loop.
    tops, vols, walls = [], [], []
    for i in range(len(surfaces)):
        chunk = out[6 * i : 6 * i + 6]
        tops.append(chunk[0][1])
        vols.append(chunk[1][1])
        if outer[i]:
            walls.append(chunk[3][1])
        if inner[i]:
            walls.append(chunk[5][1])
    tags = TubeTags(tuple(vols), tuple(surfaces), tuple(tops), tuple(walls))
    for (dim, tag), name in GROUP_NAMES.items():
        ents = {TUBE: tags.volumes}[tag] if dim == 3 else {BASE: tags.base, TOP: tags.top, WALL: tags.wall}[tag]
        model.addPhysicalGroup(dim, list(ents), tag, name=name)
    gmsh.option.setNumber("Mesh.ElementOrder", p.order)
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    model.mesh.generate(3)
    if p.order == 2:
        model.mesh.setOrder(2)
    return tags


def tube_radii(p: TubeMeshParams, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(outer, inner) radius at heights z (m); at a joint where the wall steps, the mean of
    the two cans' (a node there belongs to both: the step spreads over the layers beside it)."""
    z = np.asarray(z, dtype=float)
    if not p.segments:
        return np.full_like(z, p.outer_radius), np.full_like(z, p.inner_radius)
    ro, ri, hits = np.zeros_like(z), np.zeros_like(z), np.zeros_like(z)
    tol = 1e-9 * p.height
    for z0, z1, o0, o1, i0, i1 in p.segments:
        on = (z >= z0 - tol) & (z <= z1 + tol)
        s = np.clip((z[on] - z0) / (z1 - z0), 0.0, 1.0)
        ro[on] += (o0 + s * (o1 - o0)) / 2
        ri[on] += (i0 + s * (i1 - i0)) / 2
        hits[on] += 1
    return ro / hits, ri / hits


def conical_points(points: np.ndarray, p: TubeMeshParams) -> np.ndarray:
    """The structured tube's nodes moved onto the cans' cones: a node at the fraction s of
    the reference wall (radii ``inner_radius`` .. ``outer_radius``) goes to the same
    fraction of the wall at its height, at its angle and height.  A straight generator of
    a can stays straight, so the first-order map of each cell in (r, theta, z)
    (arrays.cylindrical_nodes) puts the quadratic nodes on the cones exactly."""
    if not p.segments:
        return points
    x, y, z = points[:, 0], points[:, 1], points[:, 2]
    r = np.hypot(x, y)
    s = (r - p.inner_radius) / (p.outer_radius - p.inner_radius)
    ro, ri = tube_radii(p, z)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = np.where(r > 0, (ri + s * (ro - ri)) / r, 1.0)
    return np.column_stack([x * scale, y * scale, z])
