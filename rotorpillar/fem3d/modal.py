"""Modal analysis of the tube: assemble, solve, name, normalise, reduce.

The pipeline of :func:`modal_analysis`: Gmsh mesh -> K, M (dolfinx) ->
shift-invert (block Lanczos or SLEPc) -> the shapes gathered on rank 0 -> each mode named from
its shape (:mod:`.identify`), degenerate pairs aligned with x/y (or cos/sin)
-> normalised (bending: unit mean displacement of the top section in its
direction, so that a modal coordinate is the tip displacement in metres;
every other mode: max |u| = 1) -> generalised mass and stiffness.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ComputationError
from ..records import Record, replace
from . import identify
from .eigensolver import solve_gep_shift_invert
from .model import AssembledPillar

#: Two eigenvalues closer than this (relative) form a degenerate pair.
PAIR_TOLERANCE = 1e-5
#: An aligned pair whose Rayleigh quotients differ by less than this (relative) is one
#: eigenvalue split by the solve's round-off (~1e-8 at modal.tolerance 1e-8): it shares their mean.
ROUND_OFF_SPLIT = 1e-7

#: The axes of the 3D model (written to modal.json as ``axes``).
AXES = {
    "tube_axis": "z (base z = 0, top z = H)",
    "x": "the paper's X: horizontal, in the rotor's plane (bending_x)",
    "y": "horizontal, normal to the rotor's plane, along the rotor's spin axis (the paper's Z; bending_y)",
    "z": "the paper's Y (vertical, along the pillar)",
    "origin": "centre of the base section",
}


class ModeRow(Record, omit_defaults=True):
    """One mode of the tube as modal.json lists it (``modes``, ``modes_with_top``)."""

    index: int
    """its place in the ascending list (-)"""
    omega: float
    """angular frequency (rad/s)"""
    frequency_hz: float
    """frequency (Hz)"""
    kind: str
    """bending_x, bending_y, ovalling, torsion, axial, breathing or other"""
    n_circumferential: int | None
    """waves around the circumference (1 bending, 0 torsion/axial/breathing), or None (-)"""
    n_axial: int | None
    """sign changes of its profile along the height (0 = first of its family), or None (-)"""
    harmonic_share: float
    """share of its dominant circumferential harmonic (-)"""
    normalisation: str
    """"unit_tip" (bending: unit mean tip displacement) or "unit_max\""""
    modal_mass: float
    """phi^T M phi for the normalised shape (kg)"""
    modal_stiffness: float
    """phi^T K phi for the normalised shape (N/m)"""
    tip_displacement: tuple[float, ...]
    """mean (u_x, u_y) of the top section, normalised shape (m per unit modal coordinate)"""
    tip_modal_mass: float | None = None
    """bending only: the modal mass referred to the tip displacement (kg)"""
    tip_stiffness: float | None = None
    """bending only: the modal stiffness referred to the tip displacement (N/m)"""
    pillar_modal_mass: float | None = None
    """bending with the top mass only: the tip modal mass less the top's (kg)"""
    top_plate_motion: tuple[float, ...] | None = None
    """rigid top only: the plate's (U, Theta) per normalised mode (m, rad)"""
    participation: tuple[float, ...] | None = None
    """L_j = phi_j^T M r_d along x, y, z for the normalised shape (kg)"""
    effective_mass: tuple[float, ...] | None = None
    """L_j**2 / m_j along x, y, z (kg)"""


@dataclass(frozen=True)
class ModalResult:
    """Modes of the tube, ascending, named from their shapes.

    Arrays of shapes and geometry are on MPI rank 0 only (None elsewhere).
    """

    omega: np.ndarray
    """angular frequencies (rad/s)"""
    kind: tuple
    """per mode: bending_x, bending_y, ovalling, torsion, axial, breathing or other"""
    n_circumferential: tuple
    """per mode: waves around the circumference (1 bending, 0 torsion/axial/breathing), or None"""
    n_axial: tuple
    """per mode: sign changes of its profile along the height (0 = first of its family), or None"""
    share: np.ndarray
    """per mode: share of its dominant circumferential harmonic (-)"""
    normalisation: tuple
    """per mode: "unit_tip" (bending) or "unit_max\""""
    modal_mass: np.ndarray
    """phi^T M phi for the normalised shape (kg)"""
    modal_stiffness: np.ndarray
    """phi^T K phi for the normalised shape (N/m)"""
    tip: np.ndarray
    """(n, 2) mean (u_x, u_y) of the top section, normalised shape (m per unit modal coordinate)"""
    top: bool
    """the masses on top (True) or the bare tube (False)"""
    top_model: str | None
    """None, "rigid" or "ring_mass\""""
    top_mass: float
    """mass on top (kg)"""
    dofs: int
    """global number of unknowns (tube dofs + 6 for a rigid top)"""
    cells: int
    cell_type: str
    degree: int
    mesh: object
    """the scene's [mesh] section used"""
    timings: dict
    """seconds: mesh, assembly, solve, postprocess"""
    solver: dict = field(default_factory=dict)
    """SLEPc: iterations, tolerance, max residual"""
    points: np.ndarray | None = None
    """coordinates of the VTU's nodes (m), rank 0: every node of the cells on a
    quadratic mesh (the P2 nodes, on the circles), the vertices on a linear one"""
    vtu_cells: np.ndarray | None = None
    """cell connectivity into ``points`` in VTK's node order (27 or 10 nodes
    per quadratic cell, 8 or 4 per linear one), rank 0"""
    shapes: np.ndarray | None = None
    """(modes, points, 3) normalised displacement at ``points``, rank 0"""
    beam_line: dict | None = None
    """per bending_x mode index: (z levels, mean u_x per level), rank 0"""
    rigid_top: np.ndarray | None = None
    """(modes, 6) the rigid plate's q = (U, Theta) per normalised mode, rank 0"""
    base_plate: np.ndarray | None = None
    """on a flexible foundation: (modes, 6) the base plate's q per normalised mode, rank 0"""
    section_heights: np.ndarray | None = None
    """(n_z,) heights of the element-layer cuts, base first (m); with ``material`` only"""
    section_resultants: np.ndarray | None = None
    """(modes, n_z, 3 or 6) per normalised mode: shear V (N), bending moment M (N*m) and
    axial force N (N, compression positive) at each cut, then (``spatial``) the shear in y
    (N), the moment about x (N*m) and the torque (N*m) (rotorpillar.fem3d.sections)"""
    rigid_mass: np.ndarray | None = None
    """(3,) r_d^T M r_d along x, y, z: everything the model carries that moves with the
    ground (the clamped nodes excluded) (kg)"""
    participation: np.ndarray | None = None
    """(modes, 3) L_j = phi_j^T M r_d for the rigid translations r_d along x, y, z of
    everything the model carries (tube and top), normalised shape (kg): a ground
    acceleration a_g along d forces mode j with -L_j a_g; L_j**2 / m_j is its
    effective mass"""

    def lowest(self, n: int) -> ModalResult:
        """The lowest ``n`` modes of this result (every per-mode field cut to them)."""
        if n >= len(self.omega):
            return self
        cut = lambda a: None if a is None else a[:n]
        return replace(
            self,
            omega=self.omega[:n],
            kind=self.kind[:n],
            n_circumferential=self.n_circumferential[:n],
            n_axial=self.n_axial[:n],
            share=self.share[:n],
            normalisation=self.normalisation[:n],
            modal_mass=self.modal_mass[:n],
            modal_stiffness=self.modal_stiffness[:n],
            tip=self.tip[:n],
            shapes=cut(self.shapes),
            rigid_top=cut(self.rigid_top),
            base_plate=cut(self.base_plate),
            participation=cut(self.participation),
            section_resultants=cut(self.section_resultants),
            beam_line=None if self.beam_line is None else {i: v for i, v in self.beam_line.items() if i < n},
        )

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.omega / (2 * math.pi)

    def index(
        self, kind: str, n_axial: int | None = None, n_circumferential: int | None = None, nth: int = 0
    ) -> int | None:
        """Index of the ``nth`` mode of a kind (and wave numbers), or None."""
        hits = [
            i
            for i, k in enumerate(self.kind)
            if k == kind
            and (n_axial is None or self.n_axial[i] == n_axial)
            and (n_circumferential is None or self.n_circumferential[i] == n_circumferential)
        ]
        return hits[nth] if len(hits) > nth else None

    def first(self, kind: str, **kw) -> float | None:
        """Angular frequency of the first mode of a kind (rad/s), or None."""
        i = self.index(kind, **kw)
        return None if i is None else float(self.omega[i])

    def modes_table(self) -> list[ModeRow]:
        """One row per mode (modal.json's ``modes`` and ``modes_with_top``)."""
        out = []
        for i in range(len(self.omega)):
            bending = self.kind[i] in ("bending_x", "bending_y")
            L = None if self.participation is None else self.participation[i]
            out.append(
                ModeRow(
                    index=i,
                    omega=float(self.omega[i]),
                    frequency_hz=float(self.frequency_hz[i]),
                    kind=self.kind[i],
                    n_circumferential=self.n_circumferential[i],
                    n_axial=self.n_axial[i],
                    harmonic_share=float(self.share[i]),
                    normalisation=self.normalisation[i],
                    modal_mass=float(self.modal_mass[i]),
                    modal_stiffness=float(self.modal_stiffness[i]),
                    tip_displacement=tuple(float(t) for t in self.tip[i]),
                    # unit tip: the modal mass is the mass referred to the tip displacement
                    tip_modal_mass=float(self.modal_mass[i]) if bending else None,
                    tip_stiffness=float(self.modal_stiffness[i]) if bending else None,
                    pillar_modal_mass=float(self.modal_mass[i] - self.top_mass) if bending and self.top else None,
                    top_plate_motion=None if self.rigid_top is None else tuple(float(q) for q in self.rigid_top[i]),
                    participation=None if L is None else tuple(float(x) for x in L),
                    effective_mass=None if L is None else tuple(float(x * x / self.modal_mass[i]) for x in L),
                )
            )
        return out


def _vtu_map(model: AssembledPillar, coords: np.ndarray):
    """The VTU's nodes and cells (VTK order) and, for each node, its node in the global dof order.

    On a quadratic mesh with the degree-2 space (the default) every node of
    every cell is a node of the space: the cells are written whole, so the
    shapes carry every P2 value and the picture the true geometry.  Otherwise
    (degree 1, or a space of another degree than the geometry) the cells'
    vertices only.
    """
    from scipy.spatial import cKDTree

    from .output import vtk_cells

    data = model.mesh_data
    assert data is not None, "the Gmsh arrays are on rank 0"
    whole = data.order == model.V.ufl_element().degree()
    cells = vtk_cells(data.cells, data.gmsh_cell) if whole else data.corner_cells()
    used, inverse = np.unique(cells, return_inverse=True)
    pts = data.points[used]
    dist, node = cKDTree(coords).query(pts)
    scale = max(model.params.height, model.params.outer_radius)
    if np.max(dist) > 1e-8 * scale:
        raise ComputationError(f"mode shapes: a mesh node has no dof at its place (distance {np.max(dist):.3g} m)")
    return pts, inverse.reshape(cells.shape), node


def _align_and_normalise(omega, shapes, rings):
    """Per mode: description, T with normalised modes = raw modes @ T, pairs (rank 0)."""
    n = len(omega)
    T = np.eye(n)
    pairs = []
    desc = [identify.describe_mode(None, shapes[i], rings) for i in range(n)]
    i = 0
    while i < n - 1:
        close = abs(omega[i + 1] - omega[i]) <= PAIR_TOLERANCE * max(omega[i], 1e-30)
        nc = desc[i].n_circumferential
        if close and nc is not None and nc >= 1 and nc == desc[i + 1].n_circumferential:
            R = identify.pair_coefficients(rings, shapes[i], shapes[i + 1], nc)
            T[np.ix_([i, i + 1], [i, i + 1])] = R
            pairs.append(i)
            i += 2
        else:
            i += 1
    aligned = np.einsum("mij,mk->kij", shapes, T)
    desc = [identify.describe_mode(None, aligned[k], rings) for k in range(n)]
    scale, norm = np.ones(n), []
    for k, d in enumerate(desc):
        if d.kind in ("bending_x", "bending_y"):
            t = d.tip[0] if d.kind == "bending_x" else d.tip[1]
            if abs(t) > 1e-12 * d.max_abs:
                scale[k], label = 1 / t, "unit_tip"
            else:
                scale[k], label = 1 / d.max_abs, "unit_max"
        else:
            u = aligned[k]
            flat = u.reshape(-1)
            j = int(np.argmax(np.abs(flat)))
            scale[k], label = np.sign(flat[j]) / d.max_abs, "unit_max"
        norm.append(label)
    T = T * scale[None, :]
    desc = [
        replace(d, tip=(d.tip[0] * scale[k], d.tip[1] * scale[k]), max_abs=d.max_abs * abs(scale[k]))
        for k, d in enumerate(desc)
    ]
    return desc, T, norm, pairs


def _generalised(A, local: np.ndarray, comm) -> np.ndarray:
    """phi_k^T A phi_k of every column phi_k of ``local`` (this rank's rows of the modes):
    one sparse-times-dense product (the matrix read once for all the modes, not once a
    mode), then each column's dot product, summed over the ranks."""
    from petsc4py import PETSc

    Phi = PETSc.Mat().createDense(
        ((local.shape[0], PETSc.DETERMINE), (PETSc.DECIDE, local.shape[1])), array=np.asfortranarray(local), comm=A.comm
    )
    APhi = A.matMult(Phi)
    own = np.einsum("ik,ik->k", local, APhi.getDenseArray(readonly=True))
    APhi.destroy()
    Phi.destroy()
    return comm.allreduce(own) if comm.size > 1 else own


def run_modal(
    model: AssembledPillar,
    n_modes: int,
    *,
    tol: float = 1e-10,
    sigma: float = 0.0,
    mesh_section=None,
    material: tuple[float, float] | None = None,
    spatial: bool = False,
) -> ModalResult:
    """Solve, gather, name, align and normalise the modes of an assembled model.

    ``material`` (E in Pa, nu) adds each mode's section resultants at the
    element-layer cuts (rotorpillar.fem3d.sections), on every rank; ``spatial``
    all six of them (else the three of the rotor's plane).

    One eigenpair more than asked is computed, so that a degenerate pair cut
    by ``n_modes`` is still aligned (the last mode returned is then the
    x or cos member of its pair, not an arbitrary combination).
    """
    comm = model.comm
    timings = dict(model.timings)
    t0 = time.perf_counter()
    sol = solve_gep_shift_invert(model.K, model.M, n_modes + 1, sigma=sigma, tol=tol)
    timings["solve"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    lam = np.asarray(sol.eigenvalues)
    if np.any(lam < -1e-6 * np.max(np.abs(lam))):
        raise ComputationError(f"negative eigenvalue {lam.min():.4g}: the model is not stable")
    omega = np.sqrt(np.maximum(lam, 0.0))
    coords = model.gather_coordinates()
    n_nodes = model.tube_dofs // 3
    raw = [model.gather_vector(model.tube_displacement(x)) for x in sol.vectors]
    raw_q = [model.gather_vector(x) for x in sol.vectors] if model.extra_dofs or model.base_plate is not None else None
    desc = T = norm = pairs = None
    if comm.rank == 0:
        # rank 0 holds the gathered arrays (None elsewhere)
        assert coords is not None and all(r is not None for r in raw)
        shapes = np.stack([r.reshape(n_nodes, 3) for r in raw if r is not None])
        rings = identify.rings_of(coords, model.params.height)
        desc, T, norm, pairs = _align_and_normalise(omega, shapes, rings)
        desc, T, norm = desc[:n_modes], T[:, :n_modes], norm[:n_modes]
        pairs = [i for i in pairs if i + 1 < n_modes]
    T = comm.bcast(T, root=0)
    pairs = comm.bcast(pairs, root=0)
    omega = omega[:n_modes]
    # The normalised modes as distributed vectors: generalised mass and stiffness.
    local = np.stack([x.getArray() for x in sol.vectors], axis=1) @ T
    mm, kk = _generalised(model.M, local, comm), _generalised(model.K, local, comm)
    Mr = []
    for d in range(3):
        r = model.influence(d)
        Mr.append(model.M.createVecLeft())
        model.M.mult(r, Mr[-1])
        r.destroy()
    rigid_mass = np.empty(3)
    for d in range(3):
        r = model.influence(d)
        rigid_mass[d] = r.dot(Mr[d])
        r.destroy()
    # L_j = phi_j^T M r_d: this rank's rows, then the sum over the ranks
    part = local.T @ np.stack([v.getArray(readonly=True) for v in Mr], axis=1)
    part = comm.allreduce(part) if comm.size > 1 else part
    for v in Mr:
        v.destroy()
    for x in sol.vectors:
        x.destroy()
    cuts = None if material is None else mode_resultants(model, local, *material, spatial=spatial)
    # The Rayleigh quotient of each final vector: its Ritz value for a simple
    # mode; a degenerate pair (equal by symmetry, split ~1e-8 by round-off)
    # gets the mean of its two.  A pair split by the physics more than that
    # (the gondola's roll and pitch inertias differ: the two bending planes
    # ~1e-5 apart) keeps each its own: aligned with x and y, each is exact.
    lam = np.maximum(kk / mm, 0.0)
    for i in pairs:
        if abs(lam[i] - lam[i + 1]) <= ROUND_OFF_SPLIT * max(lam[i], lam[i + 1]):
            lam[i] = lam[i + 1] = (lam[i] + lam[i + 1]) / 2
    desc = comm.bcast(desc, root=0)
    norm = comm.bcast(norm, root=0)
    # a split pair may come out in descending order: ascending, every per-mode quantity along
    perm = np.argsort(lam, kind="stable")
    if np.any(perm != np.arange(n_modes)):
        lam, mm, kk, part, T, local = lam[perm], mm[perm], kk[perm], part[perm], T[:, perm], local[:, perm]
        desc, norm = [desc[i] for i in perm], [norm[i] for i in perm]
        if cuts is not None:
            cuts = (cuts[0], cuts[1][perm])
    omega = np.sqrt(lam)
    points = vtu_cells = shapes_out = beam_line = rigid = base_plate = None
    if comm.rank == 0:
        assert coords is not None
        shapes_n = (np.stack([r for r in raw if r is not None], axis=1) @ T).T.reshape(n_modes, n_nodes, 3)
        points, vtu_cells, node = _vtu_map(model, coords)
        shapes_out = shapes_n[:, node, :]
        beam_line = {}
        for k, d in enumerate(desc):
            if d.kind == "bending_x":
                beam_line[k] = (rings.levels.copy(), identify.level_mean(rings, shapes_n[k][:, 0]))
        if raw_q is not None and model.extra_dofs:
            rigid = (np.stack([q[model.tube_dofs :] for q in raw_q if q is not None], axis=1) @ T).T.copy()
        if raw_q is not None and model.base_plate is not None:
            at = np.asarray(model.base_plate)
            q0 = np.stack([np.where(at >= 0, q[np.maximum(at, 0)], 0.0) for q in raw_q if q is not None], axis=1)
            base_plate = (q0 @ T).T.copy()
    timings["postprocess"] = time.perf_counter() - t0
    ms = mesh_section
    cell_type = model.params.cell_type if ms is None else ms.cell_type
    return ModalResult(
        omega=omega,
        kind=tuple(d.kind for d in desc),
        n_circumferential=tuple(d.n_circumferential for d in desc),
        n_axial=tuple(d.n_axial for d in desc),
        share=np.array([d.share for d in desc]),
        normalisation=tuple(norm),
        modal_mass=mm,
        modal_stiffness=kk,
        tip=np.array([d.tip for d in desc]),
        top=model.top_model is not None,
        top_model=model.top_model,
        top_mass=model.top_mass,
        dofs=model.size,
        cells=model.mesh.topology.index_map(3).size_global,
        cell_type=cell_type,
        degree=model.V.ufl_element().degree(),
        mesh=ms,
        timings=timings,
        solver={
            "iterations": sol.iterations,
            "tolerance": tol,
            "shift": sigma,
            "max_error_estimate": float(np.max(sol.errors)),
            "computed": len(sol.eigenvalues),
            "type": f"{sol.method}, sinvert, mumps ldlt",
            "solves": sol.solves,
            "ranks": comm.size,
        },
        points=points,
        vtu_cells=vtu_cells,
        shapes=shapes_out,
        beam_line=beam_line,
        rigid_top=rigid,
        base_plate=base_plate,
        participation=part,
        rigid_mass=rigid_mass,
        section_heights=None if cuts is None else cuts[0],
        section_resultants=None if cuts is None else cuts[1],
    )


def mode_resultants(
    model: AssembledPillar, local: np.ndarray, youngs_modulus: float, poisson_ratio: float, spatial: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """(heights, (modes, n_z, 3 or 6) resultants) of the distributed mode vectors ``local``
    (this rank's rows of the unknowns, one column per mode); collective (``spatial``: the six
    components of rotorpillar.fem3d.sections.SPATIAL_COMPONENTS)."""
    from .sections import section_functionals

    sf = section_functionals(model, youngs_modulus, poisson_ratio, spatial)
    part = sf.rows.T @ local
    full = model.comm.allreduce(part) if model.comm.size > 1 else part
    out = full.reshape(len(sf.heights), sf.components, -1).transpose(2, 0, 1).copy()
    out[:, :, 2] *= -1.0
    return sf.heights, out
