"""The 3D model's geometry as the report draws it: which axis is what, the
tube's outer surface carrying the mode shapes of a ``modes_*.vtu`` (a pyvista
PolyData), the cantilever fallback when there is none, and which modes a
simulation's modal coordinates refer to.  pyvista is imported lazily."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import msgspec
import numpy as np

from ..fem3d.modal import ModeRow
from ..fem3d.modal_summary import ModalAxes
from ..records import Record

# --------------------------------------------------------------------------
# Axes of the 3D model


@dataclass(frozen=True)
class TubeAxes:
    """Which axis of the 3D model is what (indices 0, 1, 2 = x, y, z)."""

    axial: int
    """along the tube, base to top"""
    x: int
    """the paper's X: the direction the pillar bends in"""

    @property
    def y(self) -> int:
        """the remaining lateral axis"""
        return 3 - self.axial - self.x


def _axis_index(value) -> int | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int) and 0 <= value <= 2:
        return value
    if isinstance(value, str):
        s = value.strip().lower().lstrip("+-")
        if s in ("x", "y", "z"):
            return "xyz".index(s)
        if s in ("0", "1", "2"):
            return int(s)
    if isinstance(value, (list, tuple)) and len(value) == 3:
        try:
            v = np.abs(np.asarray(value, dtype=float))
        except (TypeError, ValueError):
            return None
        return int(np.argmax(v))
    return None


def tube_axes(meta: Mapping[str, Any] | ModalAxes | None, bounds=None) -> TubeAxes:
    """Read ``modal.json``'s ``axes`` (strings "x"/"y"/"z", indices or unit
    vectors, under keys naming the tube axis and the paper's X), falling back
    to the longest extent of ``bounds`` (xmin, xmax, ymin, ymax, zmin, zmax)
    for the tube and the first other axis for X.

    >>> tube_axes({"tube": "z", "paper_x": "x"})
    TubeAxes(axial=2, x=0)
    >>> tube_axes({"axial": [0, 1, 0], "X": 2})
    TubeAxes(axial=1, x=2)
    >>> tube_axes(None, (-1, 1, -1, 1, 0, 20))
    TubeAxes(axial=2, x=0)
    """
    axial = x = None
    if isinstance(meta, ModalAxes):
        meta = msgspec.structs.asdict(meta)
    if isinstance(meta, Mapping):
        for key, value in meta.items():
            k = key.lower()
            if axial is None and any(w in k for w in ("tube", "axial", "along", "height", "vertical")):
                axial = _axis_index(value)
            elif x is None and (
                k in ("x", "paper_x", "paperx", "paper x", "bending", "bending_x")
                or (k.startswith("paper") and k.endswith("x"))
            ):
                x = _axis_index(value)
    if axial is None:
        if bounds is not None:
            ext = [bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]]
            axial = int(np.argmax(ext))
        else:
            axial = 2
    if x is None or x == axial:
        x = 0 if axial != 0 else 1
    return TubeAxes(axial, x)


# --------------------------------------------------------------------------
# Mode shapes


class ModeLabel(Record):
    """What a picture says of a mode that has no row of modal.json (an analytic shape,
    a placeholder): its kind and wave numbers, as a ``ModeRow`` names them."""

    kind: str = "?"
    """bending_x, bending_y, ovalling, torsion, axial, or "?" """
    n_circumferential: int | None = None
    """waves around (-)"""
    n_axial: int | None = None
    """nodes along the height (-)"""
    frequency_hz: float | None = None
    """(Hz)"""
    omega: float | None = None
    """(rad/s)"""
    normalisation: str = ""
    """how the shape is scaled (unit_tip, unit_max)"""
    note: str = ""
    """where the shape comes from"""


#: A mode's label on a picture: a row of modal.json, or a ModeLabel.
Mode = ModeRow | ModeLabel


@dataclass
class ModeSet:
    """Mode shapes on the tube's outer surface (a pyvista PolyData)."""

    surface: Any
    """pyvista.PolyData with point arrays ``arrays[i]`` (3-vectors)"""
    modes: list[Mode]
    """each mode's row of modal.json (kind, frequency_hz, ...), or its label"""
    arrays: list[str]
    axes: TubeAxes
    source: str
    """where the shapes came from (a VTU path, or the closed-form fallback)"""
    notes: list[str] = field(default_factory=list)
    grid: Any = None
    """the VTU's cells (pyvista.UnstructuredGrid) the surface was drawn from, or None"""

    def coarser(self, subdivision: int) -> ModeSet:
        """The same modes on a surface subdivided ``subdivision`` times (quadratic
        cells; an animation's hundreds of frames need fewer points than a picture)."""
        if self.grid is None:
            return self
        return dataclasses.replace(self, surface=tube_surface(self.grid, subdivision))

    def fewer_around(self, around: int) -> ModeSet:
        """The same modes on the tube's walls at about ``around`` of its nodes around (at
        least that many; every node along): what a picture a few dozen pixels wide shows
        of a mesh of hundreds of nodes around, at a fraction of the triangles
        (:func:`tube_walls`).  Unchanged where the surface's nodes are no grid."""
        walls = tube_walls(self.surface, self.axes, around)
        return self if walls is None else dataclasses.replace(self, surface=walls)

    def shape(self, i: int) -> np.ndarray:
        """Point displacements of mode i (n_points x 3)."""
        return np.asarray(self.surface.point_data[self.arrays[i]], dtype=float)

    @property
    def height(self) -> float:
        b = self.surface.bounds
        return float(b[2 * self.axes.axial + 1] - b[2 * self.axes.axial])


#: Recursive subdivisions of each quadratic face on the drawn surface: 1
#: triangulates it through its nodes, 2 adds the quadratic shapes at quarter
#: points between them (needed on the graded default mesh, whose long top
#: cells show the second bending mode's curvature as a kink at 1).
SUBDIVISION = 2


def tube_surface(grid, subdivision: int = SUBDIVISION):
    """The outer surface of a VTU's cells as triangles, the mode arrays on it.

    Quadratic cells (the 3D model's default) are drawn on their curved
    geometry: each face is subdivided ``subdivision`` times through its
    shape functions, so a mode's curvature between the nodes and the circles
    between them show (a bending mode is not kinked at the cell faces).
    Linear cells give their faces.
    """
    linear = {3, 5, 8, 9, 10, 12, 13, 14}  # VTK's linear cell types
    if set(np.unique(np.asarray(grid.celltypes)).tolist()) <= linear:
        return grid.extract_surface(algorithm=None)
    return grid.extract_surface(nonlinear_subdivision=subdivision, algorithm="dataset_surface")


def _stride(n: int, at_least: int) -> int:
    """The largest step that divides n and keeps at least ``at_least`` of n (1: all).

    >>> _stride(256, 48), _stride(64, 48), _stride(30, 8)
    (4, 1, 3)
    """
    return max(k for k in range(1, n + 1) if n % k == 0 and n // k >= min(at_least, n))


def _ring_grid(theta, z, pick, around: int):
    """Indices (nodes around x along) of the nodes ``pick`` (a mask) on a grid of angles
    and heights, every k-th around (k as _stride); None where they are not a full grid."""
    sel = np.flatnonzero(pick)
    # nodes identified to a millionth of a radian and of the height (the mesh's own
    # coordinates: far coarser than that)
    ti = np.round(theta[sel] * 1e6).astype(np.int64) % round(2 * np.pi * 1e6)
    zi = np.round((z[sel] - z.min()) / max(float(np.ptp(z)), 1e-300) * 1e6).astype(np.int64)
    t_levels, t_of = np.unique(ti, return_inverse=True)
    z_levels, z_of = np.unique(zi, return_inverse=True)
    nt, nz = len(t_levels), len(z_levels)
    if nt < 8 or nz < 2:
        return None
    index = np.full((nt, nz), -1, dtype=np.int64)
    index[t_of, z_of] = sel
    if (index < 0).any():  # not every (around, along) pair has a node: no grid
        return None
    return index[:: _stride(nt, around)]


def tube_walls(surface, axes: TubeAxes, around: int):
    """The tube's outer and inner walls and its two end rings as quadrilaterals through
    its own nodes, every k-th node around (k the largest divisor of the nodes around that
    keeps at least ``around``), every node along, the surface's point arrays on them:
    the mode shapes exactly, at the nodes kept (the through-thickness nodes of the ends
    left out).  Every face's normal points out of the wall.  None where the walls' nodes
    are not a grid (around x along) of the same angles and heights."""
    from .offscreen import pyvista

    pts = np.asarray(surface.points, dtype=float)
    lateral = [i for i in range(3) if i != axes.axial]
    # the axis: every ring's nodes are evenly spaced around (a node repeated on a seam
    # counted once)
    scale = max(float(np.abs(pts).max()), 1e-300)
    centre = np.unique(np.round(pts[:, lateral] / scale, 9), axis=0).mean(axis=0) * scale
    d = pts[:, lateral] - centre
    r = np.hypot(d[:, 0], d[:, 1])
    wall = float(np.ptp(r)) if r.size else 0.0
    if wall <= 0:
        return None
    theta = np.mod(np.arctan2(d[:, 1], d[:, 0]), 2 * np.pi)
    z = pts[:, axes.axial]
    # a wall's nodes: within a tenth of the wall's thickness of its radius (a face
    # subdivided through its quadratic shape lies a hair inside the circle; the
    # through-thickness nodes of the ends a quarter of the wall or more away)
    outer = _ring_grid(theta, z, r >= r.max() - 0.1 * wall, around)
    inner = _ring_grid(theta, z, r <= r.min() + 0.1 * wall, around)
    if outer is None or inner is None or outer.shape != inner.shape:
        return None
    m, nz = outer.shape
    ids = np.arange(2 * m * nz).reshape(2, m, nz)  # [outer, inner] x around x along
    # theta turns about +axial when (lateral, axial) is a right-handed frame
    if (lateral[1] - lateral[0]) * (1 if axes.axial != 1 else -1) < 0:
        ids = ids[:, ::-1]
    o, i = ids
    quads = [
        _quads(o[:, :-1], np.roll(o[:, :-1], -1, axis=0), np.roll(o[:, 1:], -1, axis=0), o[:, 1:]),  # out
        _quads(i[:, :-1], i[:, 1:], np.roll(i[:, 1:], -1, axis=0), np.roll(i[:, :-1], -1, axis=0)),  # in
        _quads(o[:, 0], i[:, 0], np.roll(i[:, 0], -1), np.roll(o[:, 0], -1)),  # base ring, down
        _quads(o[:, -1], np.roll(o[:, -1], -1), np.roll(i[:, -1], -1), i[:, -1]),  # top ring, up
    ]
    flat = np.concatenate([outer.ravel(), inner.ravel()])
    walls = pyvista().PolyData(pts[flat], np.concatenate(quads))
    for name in surface.point_data.keys():
        walls.point_data[name] = np.asarray(surface.point_data[name])[flat]
    return walls


def _quads(a, b, c, d) -> np.ndarray:
    """VTK's face list of the quadrilaterals a-b-c-d (index arrays of one shape)."""
    a = np.asarray(a).ravel()
    return np.column_stack([np.full(a.size, 4), a, np.ravel(b), np.ravel(c), np.ravel(d)]).ravel()


def load_modes(
    vtu: str | Path, modes: Sequence[Mode], axes_meta: Mapping[str, Any] | ModalAxes | None = None
) -> ModeSet | None:
    """The mode shapes of a ``modes_*.vtu`` on its outer surface, with their metadata.

    Point arrays ``mode_000``, ``mode_001``, ... in the order of ``modes``;
    arrays beyond the list get a placeholder label, list entries without an
    array are dropped.
    """
    from .offscreen import pyvista

    vtu = Path(vtu)
    if not vtu.is_file():
        return None
    with open(vtu, "rb") as fh:  # refuse a damaged file ourselves: VTK would print
        head = fh.read(256).lstrip()  # its parser's errors and return an empty grid
    if not (head.startswith(b"<?xml") or head.startswith(b"<VTKFile")):
        raise ValueError(f"{vtu.name} is damaged (not a VTU file): rebuild it with `rotorpillar modal`")
    pv = pyvista()
    grid = pv.read(vtu)
    names = sorted(n for n in grid.point_data.keys() if n.startswith("mode_"))
    if grid.n_points == 0 or not names:
        raise ValueError(
            f"{vtu.name}: no tube with point arrays mode_000, mode_001, ... "
            f"({grid.n_points} points, arrays {list(grid.point_data.keys())})"
        )
    surface = tube_surface(grid)
    meta: list[Mode] = [modes[i] if i < len(modes) else ModeLabel() for i in range(len(names))]
    return ModeSet(surface, meta, names, tube_axes(axes_meta, surface.bounds), str(vtu), grid=grid)


def cantilever_tube(
    height: float, outer_diameter: float, inner_diameter: float, around: int = 48, along: int = 60
) -> ModeSet:
    """The fallback when no 3D mode shapes exist: a tube surface generated by
    pyvista (axis z, X = x) carrying the first Euler-Bernoulli cantilever mode
    (:func:`rotorpillar.reduced.pillar.cantilever_mode`), unit tip."""
    from ..reduced.pillar import cantilever_mode
    from .offscreen import pyvista

    pv = pyvista()
    r_in = max(inner_diameter / 2, 1e-3 * outer_diameter)
    grid = pv.CylinderStructured(
        radius=[r_in, outer_diameter / 2],
        height=height,
        center=(0, 0, height / 2),
        direction=(0, 0, 1),
        theta_resolution=around,
        z_resolution=along + 1,
    )
    surface = grid.extract_surface(algorithm=None)
    xi = np.clip(surface.points[:, 2] / height, 0.0, 1.0)
    u = np.zeros((surface.n_points, 3))
    u[:, 0] = cantilever_mode(xi) / cantilever_mode(1.0)
    surface.point_data["mode_000"] = u
    meta: list[Mode] = [ModeLabel("bending_x", normalisation="unit_tip", note="Euler-Bernoulli cantilever, Eq. 1")]
    return ModeSet(
        surface,
        meta,
        ["mode_000"],
        TubeAxes(2, 0),
        "Euler-Bernoulli cantilever shape on a generated tube (no modes_top.vtu)",
    )


def bending_columns(modes: Sequence[Mode], k: int, explicit=None) -> list[int]:
    """Indices into ``modes`` of the k modes a simulation's ``modal_coordinates``
    columns refer to: ``explicit`` if the simulation names them, else the
    first k modes of kind "bending_x" (the paper's X), else the first k
    bending modes of any direction.

    >>> ms = [ModeLabel(k) for k in ("bending_x", "bending_y", "ovalling", "bending_x")]
    >>> bending_columns(ms, 2), bending_columns(ms, 1, explicit=[3])
    ([0, 3], [3])
    """
    if explicit is not None:
        idx = [int(i) for i in explicit][:k]
        if len(idx) == k and all(0 <= i < len(modes) for i in idx):
            return idx
    x = [i for i, m in enumerate(modes) if m.kind == "bending_x"]
    if len(x) >= k:
        return x[:k]
    anyb = [i for i, m in enumerate(modes) if m.kind.startswith("bending")]
    return anyb[:k]
