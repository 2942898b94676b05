"""Section resultants of the 3D tube: shear, bending moment and axial force at element-layer cuts.

The structured tube's cells lie in layers along the height; the faces
between two layers are cross-sections at known heights z_k (the base z = 0
and the top z = H included).  At each cut the resultant the part above
exerts on the part below is read from the nodal forces of the elements on
either side (the consistent, variationally exact way, the 3D counterpart
of the beam's element end forces K_e u_e):

    R_q(u) = 1/2 a_below(u, w_q) - 1/2 a_above(u, w_q)

with a(u, w) = int sigma(u) : eps(w) dx over the layer below or above the
cut, and w_q the finite-element field equal on the cut's nodes to a unit
rigid motion of the section and zero at every other node: a translation
along x (shear V), along z (axial force, N = -R, compression positive) or
the rotation about y through the section's centre, w = (0, 0, -x) (bending
moment M; e_y x (x, y, 0) = (0, 0, -x)).  a(u, w) is the work of the
element's nodal forces on the section's rigid motion, so R is the section's
resultant exactly where the nodes carry no inertia: in statics the two
sides agree and a tip load P gives V = P, M = P (H - z) to round-off at
every cut; in dynamics they differ by the cut nodes' share of the inertia,
which the mean splits evenly (the base and the top, with one side only,
take that side).  Signs as rotorpillar.reduced.internal_forces.

Each R_q is linear in the displacement, so it is assembled once as a vector
L_q (one vector form; every third cut at once, per component) and applied to
any state with a dot product: R_q = L_q . u (all cuts at once: one small
dense product per rank and one reduction).  With the rigid top the unknowns are x and u
= T x: the functionals are carried over once, T^T L_q.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

#: the components of a cut's resultant, in this order: the planar three, then (``spatial``) the
#: shear along y, the moment about x through the section's centre (w = e_x x (x, y, 0) = (0, 0, y))
#: and the torque about z (w = (-y, x, 0)), the same rule: the part above on the part below
COMPONENTS = ("shear", "moment", "axial")
SPATIAL_COMPONENTS = COMPONENTS + ("shear_y", "moment_x", "torque")


def cut_heights(params) -> np.ndarray:
    """The element-layer interfaces of the structured tube, base and top included (m)."""
    from ..mesh.tube import layer_heights

    return np.r_[0.0, layer_heights(params) * params.height]


@dataclass
class SectionFunctionals:
    """The linear functionals of the section resultants of one assembled model."""

    heights: np.ndarray
    """(n_z,) cut heights, base first (m)"""
    rows: np.ndarray
    """(n_local, 3 n_z) this rank's rows of the functionals over the model's unknowns:
    per cut, the force along x, the y-moment, the force along z"""
    comm: Any
    """the MPI communicator (mpi4py)"""

    components: int = 3
    """3 (shear in x, moment about y, axial) or 6 (and shear in y, moment about x, torque)"""
    _sparse: Any = None
    """``rows``' transpose without its zeros (scipy CSR), built at the first ``resultants``"""

    def resultants(self, x) -> np.ndarray:
        """(n_z, 3 or 6) shear V (N), moment M (N*m) and axial force N (N, compression
        positive) at each cut for the model's unknowns ``x`` (a PETSc Vec; collective),
        then (6) the shear in y (N), the moment about x (N*m) and the torque (N*m)."""
        if self._sparse is None:
            # each cut's functional lives on its element layer: 15 % of the rows' entries on
            # the 8 x 15 reference mesh, a third of the dense product's time (0.05 ms against
            # 0.15), paid at every output time of a transient
            from scipy.sparse import csr_matrix

            self._sparse = csr_matrix(self.rows.T)
        local = self._sparse @ x.getArray(readonly=True)
        out = (self.comm.allreduce(local) if self.comm.size > 1 else local).reshape(-1, self.components)
        out[:, 2] *= -1.0
        return out

    def destroy(self) -> None:
        self.rows = np.zeros((0, 0))
        self._sparse = None


def section_functionals(
    model, youngs_modulus: float, poisson_ratio: float, spatial: bool = False
) -> SectionFunctionals:
    """The functionals L_q of every cut of an AssembledPillar (collective); ``spatial``: the
    six components (SPATIAL_COMPONENTS), else the planar three.

    One compiled vector form, its two coefficients (the layer weight chi,
    piecewise constant, and the cuts' rigid field w) set per component and for
    every third cut at once (see the loop).
    """
    from .dolfinx_import import import_dolfinx

    import_dolfinx()
    import dolfinx.fem.petsc  # noqa: F401
    import ufl
    from dolfinx import fem
    from dolfinx.mesh import compute_midpoints
    from petsc4py import PETSc

    from .forms import epsilon, sigma

    mesh, V = model.mesh, model.V
    heights = cut_heights(model.params)
    H = model.params.height
    tol = 1e-6 * H
    tdim = mesh.topology.dim
    n_cells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
    mid = compute_midpoints(mesh, tdim, np.arange(n_cells, dtype=np.int32))[:, 2]
    layer = np.clip(np.searchsorted(heights, mid) - 1, 0, len(heights) - 2)
    Q = fem.FunctionSpace(mesh, ("DG", 0))
    chi = fem.Function(Q)
    w = fem.Function(V)
    v = ufl.TestFunction(V)
    dx = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": 2 * model.V.ufl_element().degree()})
    form = fem.form(chi * ufl.inner(sigma(w, youngs_modulus, poisson_ratio), epsilon(v)) * dx)
    coords = V.tabulate_dof_coordinates()
    n_nodes = coords.shape[0]  # owned and ghost nodes
    count = 6 if spatial else 3
    dofmap_cells = Q.dofmap.list.array
    columns: dict[tuple[int, int], np.ndarray] = {}
    # A cut's functional lives on the two layers beside it: its cells, and its nodes from
    # z_{k-1} to z_{k+1}.  Cuts three apart share neither, so one assembly serves every
    # third cut (a third of the cuts at once, a third of the assemblies per cut), and its
    # vector is split by height.  Each entry is the same sum as one cut's assembly alone
    # (the other cuts add exact zeros to it), so the numbers are the same.
    for phase in range(3):
        cuts = range(phase, len(heights), 3)
        weights = np.zeros(n_cells)
        for k in cuts:
            if k > 0:
                weights[layer == k - 1] = 1.0 if k == len(heights) - 1 else 0.5
            if k < len(heights) - 1:
                weights[layer == k] = -1.0 if k == 0 else -0.5
        chi.x.array[dofmap_cells] = weights
        on_cut = {k: np.abs(coords[:, 2] - heights[k]) <= tol for k in cuts}
        beside = {
            k: (coords[:, 2] >= heights[max(k - 1, 0)] - tol)
            & (coords[:, 2] <= heights[min(k + 1, len(heights) - 1)] + tol)
            for k in cuts
        }
        for q in range(count):
            field = np.zeros((n_nodes, 3))
            for k in cuts:
                _rigid_motion(field, coords, on_cut[k], q)
            w.x.array[:] = field.ravel()
            vec = fem.petsc.assemble_vector(form)
            vec.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
            for k in cuts:
                part = vec.copy()
                owned = part.array.reshape(-1, 3)
                owned[~beside[k][: len(owned)]] = 0.0
                columns[k, q] = _to_unknowns(model, part)
            vec.destroy()
    ordered = [columns[k, q] for k in range(len(heights)) for q in range(count)]
    return SectionFunctionals(heights, np.column_stack(ordered), model.comm, count)


def _rigid_motion(field: np.ndarray, coords: np.ndarray, on_cut: np.ndarray, q: int) -> None:
    """Set on the cut's nodes the unit rigid motion of component ``q`` (SPATIAL_COMPONENTS'
    order): a translation along x, the rotation about y, a translation along z, along y,
    the rotation about x, the twist about z."""
    x, y = coords[on_cut, 0], coords[on_cut, 1]
    if q == 0:
        field[on_cut, 0] = 1.0
    elif q == 1:
        field[on_cut, 2] = -x
    elif q == 2:
        field[on_cut, 2] = 1.0
    elif q == 3:
        field[on_cut, 1] = 1.0
    elif q == 4:
        field[on_cut, 2] = y
    else:
        field[on_cut, 0] = -y
        field[on_cut, 1] = x


def _to_unknowns(model, vec) -> np.ndarray:
    """L over the tube's dofs -> this rank's rows over the model's unknowns (T^T L with the rigid top)."""
    if model.T is None:
        n = model.K.getLocalSize()[1]
        out = vec.getArray(readonly=True)[:n].copy()
    else:
        tx = model.T.createVecRight()
        model.T.multTranspose(vec, tx)
        out = tx.getArray(readonly=True).copy()
        tx.destroy()
    vec.destroy()
    return out
