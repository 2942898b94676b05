"""Stresses of the 3D tube during a transient: section resultants, von Mises, an XDMF time series.

``StressRecovery`` watches a 3D full-order run (rotorpillar.fem3d.full_order):
the run hands it the assembled model once (``attach``) and the state at
each output time (``record(t, x)``: the PETSc Vec of the unknowns).  It keeps

- the section resultants V, M, N at every element-layer cut (base and top
  included, rotorpillar.fem3d.sections) at every output time: a dot product
  each;
- the von Mises stress field, recovered by L2 projection onto the
  continuous Lagrange space of the mesh's degree (the stress of a Lagrange
  displacement is discontinuous between cells), at ``frames`` evenly spaced
  times and at the instants of the largest base moment and base shear;
  written with the displacement to an XDMF time series (ParaView opens
  ``<stem>.xdmf``, with its ``<stem>.h5`` beside it; on one process the
  quadratic fields go as linear ones through their nodes, 8 linear cells a
  quadratic cell: rotorpillar.fem3d.xdmf_view);
- the peak von Mises stress, where and when, and apart from it the peak at
  the clamp (z below the shell's bending boundary layer, l_b = pi sqrt(r t)
  / (3 (1 - nu**2))**(1/4)), beside the nominal section stress there (|M|
  c / I + N / A from the base resultants at the same instant): their ratio
  is the clamp's stress concentration, which the linear elastic corner
  makes mesh-dependent (the nominal stress is not).

The 3D transient carries no gravity: its stresses are the dynamic ones.
Self-weight, the gondola and the rotor enter as the beam's axial stress
sigma_zz = -N(z) / A superposed on the dynamic field (exact away from the
clamp; at the clamp the wall's Poisson restraint under that load, ~nu
times it, is left out), and N(z) is added to the cuts' axial force.
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..records import Record
from ..reduced.internal_forces import STANDARD_GRAVITY, extreme_fibre_stress, tower_axial_force
from ..reduced.pillar import section_of
from ..reduced.tower import base_section, section_at, sections_along
from ..scene import Pillar


class StressPeak(Record):
    """A peak of the von Mises field: its value, where and when."""

    value: float
    """von Mises stress (Pa)"""
    position: tuple[float, float, float]
    """(x, y, z) of the node (m)"""
    time: float
    """(s)"""
    nominal: float
    """the section's nominal stress at that height and instant, |M| c / I + N / A (Pa)"""
    ratio: float
    """value / nominal (-)"""


class VonMisesSummary(Record):
    """What the von Mises recovery found over the frames and the peak instants."""

    peak: StressPeak
    """the largest anywhere"""
    clamp: StressPeak
    """the largest within the clamp's boundary layer (z <= clamp_zone); ratio: the stress concentration"""
    away_from_clamp: StressPeak
    """the largest above the clamp's boundary layer; ratio: against the beam's nominal stress"""
    clamp_zone: float
    """height of the clamp's boundary layer l_b (m)"""
    instants: int
    """states evaluated: the frames and the peak instants of base moment and shear (-)"""
    gravity: str
    """how self-weight enters"""
    space: str
    """the continuous space the stress was projected on"""


class BaseComponent(Record):
    """One component of the base reaction: its peak over the run."""

    name: str
    """shear_x, shear_y, axial, moment_x, moment_y or torque (rotorpillar.fem3d.sections)"""
    peak: float
    """largest |value| (N or N*m)"""
    time: float
    """when (s)"""
    minimum: float
    """smallest value (N or N*m; axial: compression positive)"""
    maximum: float
    """largest value (N or N*m)"""


class BaseReactionsSix(Record):
    """What the clamp carries in all six components over a 3D run (the foundation's loads):
    the section resultants at the base cut (the part above on the foundation, as
    rotorpillar.fem3d.sections signs them), shear in x and y (N), axial force (N,
    compression positive, self-weight included), moments about x and y (N*m), torque (N*m)."""

    components: tuple[BaseComponent, ...]
    """in SPATIAL_COMPONENTS' order: shear_x, moment_y, axial, shear_y, moment_x, torque"""
    horizontal_shear: float
    """largest sqrt(V_x**2 + V_y**2) (N)"""
    overturning_moment: float
    """largest sqrt(M_x**2 + M_y**2) (N*m)"""


def base_reactions_six(t, resultants) -> BaseReactionsSix:
    """The six base components' peaks from a run's (t, resultants (n_t, n_z, 6)) (base first).

    >>> import numpy as np
    >>> res = np.zeros((3, 2, 6)); res[:, 0, 0] = [0, 3, -1]; res[:, 0, 3] = [0, 4, 0]
    >>> r = base_reactions_six(np.array([0.0, 1.0, 2.0]), res)
    >>> r.components[0].peak, r.components[0].time, r.horizontal_shear
    (3.0, 1.0, 5.0)
    """
    t = np.asarray(t, dtype=float)
    base = np.asarray(resultants, dtype=float)[:, 0, :]
    if base.shape[1] != 6:
        raise ValueError("the six base components need the spatial section functionals (6 per cut)")
    out = []
    for i, name in enumerate(("shear_x", "moment_y", "axial", "shear_y", "moment_x", "torque")):
        k = int(np.argmax(np.abs(base[:, i])))
        out.append(
            BaseComponent(name, float(abs(base[k, i])), float(t[k]), float(base[:, i].min()), float(base[:, i].max()))
        )
    return BaseReactionsSix(
        tuple(out),
        float(np.max(np.hypot(base[:, 0], base[:, 3]))),
        float(np.max(np.hypot(base[:, 1], base[:, 4]))),
    )


#: von Mises frames of the XDMF time series (evenly spaced over the run); each frame costs
#: an L2 projection and two writes (a few ms each on the linear view, rotorpillar.fem3d.xdmf_view)
FRAMES = 40


def boundary_layer_length(radius: float, thickness: float, poisson_ratio: float) -> float:
    """The cylinder's bending boundary layer, pi sqrt(r t) / (3 (1 - nu**2))**(1/4) (m):
    the half-wavelength over which an edge disturbance of a shell decays."""
    return math.pi * math.sqrt(radius * thickness) / (3 * (1 - poisson_ratio**2)) ** 0.25


@dataclass
class StressRecovery:
    """The observer of a 3D transient (see the module text); collective under MPI."""

    pillar: Pillar
    """the scene's [pillar] section"""
    top_mass: float
    """what the top carries: gondola and rotor (kg)"""
    duration: float
    """the run's length, for the frames' spacing (s)"""
    xdmf_path: Path | None = None
    """where the time series goes (None: no file)"""
    frames: int = FRAMES
    times: list = field(default_factory=list)
    resultants: list = field(default_factory=list)
    base_motion: list = field(default_factory=list)
    """on a flexible foundation: the base plate's (U_x, Theta_y) at each output time (m, rad)"""

    def attach(self, model) -> None:
        """Build the functionals and the projection on the assembled model."""
        from .sections import section_functionals

        self._model = model
        # all six components (issue 26): the base reactions in every direction
        self._sections = section_functionals(model, self.pillar.youngs_modulus, self.pillar.poisson_ratio, spatial=True)
        self._heights = self._sections.heights
        self._vm = VonMisesProjection(model, self.pillar, self.top_mass)
        self._next_frame = 0.0
        # per quantity: (|base value|, time (s), the state then: a PETSc Vec)
        self._peaks: dict[str, tuple[float, float | None, Any]] = {
            "moment": (-1.0, None, None),
            "shear": (-1.0, None, None),
        }
        self._frame_values: list[tuple[float, np.ndarray]] = []
        self._writer = _Writer(self.xdmf_path, model, self._vm) if self.xdmf_path else None

    @property
    def heights(self) -> np.ndarray:
        """The cuts' heights, base first (m)."""
        return self._heights

    def record(self, t: float, x) -> None:
        """The state at one output time (x: the model's unknowns)."""
        r = self._sections.resultants(x)
        self.times.append(float(t))
        self.resultants.append(r)
        plate = self._model.base_plate
        if plate is not None:
            # the plate's U_x and Theta_y live in two rows of one rank (rotorpillar.fem3d.rigid_faces)
            lo, hi = x.getOwnershipRange()
            arr = x.getArray(readonly=True)
            mine = [arr[c - lo] if c >= 0 and lo <= c < hi else 0.0 for c in (plate[0], plate[4])]
            self.base_motion.append(self._model.comm.allreduce(np.array(mine)))
        for key, col in (("moment", 1), ("shear", 0)):
            if abs(r[0, col]) > self._peaks[key][0]:
                old = self._peaks[key][2]
                if old is not None:
                    old.destroy()
                self._peaks[key] = (abs(r[0, col]), float(t), x.copy())
        if t >= self._next_frame - 1e-12 * max(self.duration, 1.0):
            self._frame_values.append(self._evaluate(t, x, write=True))
            self._next_frame += self.duration / max(self.frames - 1, 1)

    def _evaluate(self, t: float, x, write: bool):
        vm = self._vm.project(x)
        if write and self._writer is not None:
            self._writer.write(t, self._vm)
        return (float(t), vm)

    def finish(self) -> tuple[np.ndarray, np.ndarray, VonMisesSummary, str | None]:
        """(t, resultants (n_t, n_z, 6) with N static included, the von Mises summary,
        the XDMF file or None); frees the PETSc objects.  The resultants' six components:
        rotorpillar.fem3d.sections.SPATIAL_COMPONENTS (the planar three first);
        base_reactions_six reads the base's peaks."""
        for _, t, x in self._peaks.values():
            if x is not None and t is not None:
                self._frame_values.append(self._evaluate(t, x, write=False))
                x.destroy()
        self._peaks = {}
        res = np.array(self.resultants)
        static = tower_axial_force(self.pillar, self.heights, self.top_mass)
        res[:, :, 2] += static[None, :]
        summary = self._summary(np.array(self.times), res)
        path = self._writer.close() if self._writer is not None else None
        self.close()
        return np.array(self.times), res, summary, path

    def close(self) -> None:
        """Free what attach built (idempotent; a failed run calls it too)."""
        writer = self.__dict__.pop("_writer", None)
        if writer is not None:
            writer.abandon()
        for name in ("_sections", "_vm"):
            built = self.__dict__.pop(name, None)
            if built is not None:
                built.destroy()

    def _summary(self, t: np.ndarray, res: np.ndarray) -> VonMisesSummary:
        p = self.pillar
        sec = base_section(p)
        r = (sec.outer_diameter + sec.inner_diameter) / 4
        lb = boundary_layer_length(r, sec.wall_thickness, p.poisson_ratio)
        coords = self._vm.coordinates
        comm = self._model.comm
        found = {}
        for name, mask in (
            ("peak", np.ones(len(coords), bool)),
            ("clamp", coords[:, 2] <= lb),
            ("away", coords[:, 2] > lb),
        ):
            best: tuple[float, tuple[float, ...] | None, float | None] = (-1.0, None, None)
            for time_, vm in self._frame_values:
                if mask.any():
                    i = int(np.argmax(np.where(mask, vm, -1.0)))
                    if vm[i] > best[0]:
                        best = (float(vm[i]), tuple(map(float, coords[i])), time_)
            found[name] = _global_best(comm, best)
        out = {}
        for name, (val, pos, when) in found.items():
            j = int(np.argmin(np.abs(t - when)))
            z = pos[2]
            Mz = np.interp(z, self.heights, res[j, :, 1])
            Nz = np.interp(z, self.heights, res[j, :, 2])
            nominal = float(extreme_fibre_stress(Mz, Nz, section_at(p, min(max(z, 0.0), p.height))))
            if name == "clamp":
                nominal = float(extreme_fibre_stress(res[j, 0, 1], res[j, 0, 2], sec))
            out[name] = StressPeak(val, pos, float(when), nominal, val / nominal if nominal else math.nan)
        return VonMisesSummary(
            out["peak"],
            out["clamp"],
            out["away"],
            float(lb),
            len(self._frame_values),
            "the beam's axial stress -N(z)/A (self-weight, gondola, rotor; g = "
            f"{STANDARD_GRAVITY}) superposed on the 3D dynamic field",
            self._vm.space_name,
        )


def _global_best(comm, best):
    """The largest (value, position, time) over the ranks."""
    every = comm.allgather(best)
    return max(every, key=lambda b: b[0])


class VonMisesProjection:
    """L2 projection of the von Mises stress onto the scalar Lagrange space of the mesh's degree.

    ``gravity``: superpose the beam's axial stress -N(z)/A of self-weight and
    ``top_mass`` (see the module text).
    """

    def __init__(self, model, pillar, top_mass: float, gravity: bool = True):
        from .dolfinx_import import import_dolfinx

        import_dolfinx()
        import dolfinx.fem.petsc  # noqa: F401
        import ufl
        from dolfinx import fem
        from petsc4py import PETSc

        from .forms import sigma

        mesh = model.mesh
        degree = mesh.geometry.cmap.degree
        self.S = fem.FunctionSpace(mesh, ("Lagrange", degree))
        self.space_name = f"continuous Lagrange P{degree} (the mesh's geometry degree), L2 projection"
        Vd = fem.VectorFunctionSpace(mesh, ("Lagrange", degree))
        self.u = fem.Function(model.V, name="displacement")
        self.u_out = self.u if model.V.ufl_element().degree() == degree else fem.Function(Vd, name="displacement")
        self.vm = fem.Function(self.S, name="von_mises")
        g = STANDARD_GRAVITY
        if pillar.is_uniform:
            sec = section_of(pillar)
            z = ufl.SpatialCoordinate(mesh)[2]
            nz = g * (sec.mass_per_length * (pillar.height - z) + top_mass) / sec.area
        else:
            # a tower: N(z)/A(z) of its own sections, interpolated on the stress space
            nz = fem.Function(self.S)
            nz.interpolate(lambda x: tower_axial_force(pillar, x[2], top_mass) / sections_along(pillar, x[2]).area)
        ez = ufl.as_vector((0.0, 0.0, 1.0))
        s = sigma(self.u, pillar.youngs_modulus, pillar.poisson_ratio)
        if gravity:
            s = s - nz * ufl.outer(ez, ez)
        dev = s - ufl.tr(s) / 3 * ufl.Identity(3)
        vm = ufl.sqrt(1.5 * ufl.inner(dev, dev) + 1e-30)
        p, q = ufl.TrialFunction(self.S), ufl.TestFunction(self.S)
        dx = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": 2 * degree + 1})
        self.rhs = fem.form(vm * q * dx)
        A = fem.petsc.assemble_matrix(fem.form(p * q * dx))
        A.assemble()
        self.A = A
        self.ksp = PETSc.KSP().create(mesh.comm)
        self.ksp.setOperators(A)
        self.ksp.setType("preonly")
        self.ksp.getPC().setType("lu")
        self.ksp.getPC().setFactorSolverType("mumps")
        self.b = fem.petsc.create_vector(self.rhs)
        self.model = model
        n = self.S.dofmap.index_map.size_local
        self.coordinates = self.S.tabulate_dof_coordinates()[:n]

    def project(self, x) -> np.ndarray:
        """The projected von Mises stress at this rank's owned nodes for the unknowns x (Pa)."""
        import dolfinx.fem.petsc  # noqa: F401
        from dolfinx import fem
        from petsc4py import PETSc

        u = self.model.tube_displacement(x)
        n = self.u.vector.getLocalSize()
        self.u.vector.getArray()[:n] = u.getArray(readonly=True)[:n]
        self.u.x.scatter_forward()
        if u is not x:
            u.destroy()
        with self.b.localForm() as loc:
            loc.set(0.0)
        fem.petsc.assemble_vector(self.b, self.rhs)
        self.b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self.ksp.solve(self.b, self.vm.vector)
        self.vm.x.scatter_forward()
        if self.u_out is not self.u:
            self.u_out.interpolate(self.u)
        return self.vm.x.array[: len(self.coordinates)].copy()

    def destroy(self) -> None:
        for obj in (self.ksp, self.A, self.b):
            obj.destroy()


class _Writer:
    """The XDMF time series, written in a scratch directory and moved into place at the end."""

    def __init__(self, path: Path, model, vm: VonMisesProjection):
        from dolfinx.io import XDMFFile

        from .xdmf_view import linear_view

        self.path, self.comm = Path(path), model.comm
        if self.comm.rank == 0:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        scratch = tempfile.mkdtemp(prefix=".xdmf-", dir=self.path.parent) if self.comm.rank == 0 else None
        self.scratch = Path(self.comm.bcast(scratch, root=0))
        self.file: Any = XDMFFile(self.comm, str(self.scratch / self.path.name), "w")
        # the projection's quadratic fields as linear ones through their nodes: dolfinx's
        # write of a quadratic field costs ~6x more (rotorpillar.fem3d.xdmf_view)
        self.view = linear_view(vm.u_out, vm.vm)
        self.file.write_mesh(model.mesh if self.view is None else self.view.mesh)

    def write(self, t: float, vm: VonMisesProjection) -> None:
        if self.view is not None:
            self.view.write(self.file, t, vm.u_out, vm.vm)
            return
        self.file.write_function(vm.u_out, t)
        self.file.write_function(vm.vm, t)

    def close(self) -> str:
        self.file.close()
        self.comm.barrier()
        if self.comm.rank == 0:
            for f in sorted(self.scratch.iterdir()):  # .h5 first, then the .xdmf naming it
                os.replace(f, self.path.parent / f.name)
            shutil.rmtree(self.scratch, ignore_errors=True)
        self.comm.barrier()
        self.file = None
        return str(self.path)

    def abandon(self) -> None:
        if self.file is not None:
            self.file.close()
            self.file = None
            if self.comm.rank == 0:
                shutil.rmtree(self.scratch, ignore_errors=True)
