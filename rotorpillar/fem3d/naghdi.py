r"""A linear Naghdi (Reissner-Mindlin) shell model of the tube's mid-surface.

The wall, D/t = 100, is the textbook case of a shell: its mid-surface (a
cylinder of radius R = (D0 + D1)/4) carries a displacement ``u`` (three
Cartesian components) and the rotation ``beta`` of its director (two
components in the tangent frame ``e1 = e_theta``, ``e2 = e_z``; the normal is
``n = e_r``).  On the smooth cylinder the frame is known in closed form, so no
drilling rotation exists and none needs stabilising.  From the 3D kinematics
U(xi, zeta) = u + zeta beta, X = xi + zeta n, to first order in zeta:

- membrane strain  eps   = sym(P^T grad(u) P)
- bending strain   kappa = sym(P^T (grad(beta) - grad(u) grad(n)) P)
- shear strain     gamma = P^T beta + P^T grad(u)^T n

with P = [e1 e2] (3x2) and grad the tangential gradient on the manifold.
The ``grad(u) grad(n)`` term makes kappa vanish under every rigid motion of
the curved surface (a flat-facet formula would see a spurious twist).
Plane-stress resultants N = t C eps, M = t**3/12 C kappa, Q = k_s mu t gamma
(k_s = 5/6); kinetic energy rho t |u'|**2 + rho t**3/12 |beta'|**2.

Discretisation: quadratic Lagrange for u and beta on quadratic cells
(9-node quadrilaterals or 6-node triangles); membrane and shear energies are
integrated with a degree-2 rule (2x2 Gauss on quadrilaterals), which frees
the thin wall from shear and membrane locking (selective reduced
integration).  The clamp at the base fixes u and beta.

Checked (tests/test_shell.py) against the exact modes of a simply supported
cylinder in Sanders' shell theory (Leissa, Vibration of Shells, NASA SP-288,
1973, ch. 2) and against the Timoshenko beam limit for bending.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field

import numpy as np

from ..mesh.midsurface import BASE, TOP, MidSurface, cone_points, gmsh_mid_surface, mid_surface_radius
from .eigensolver import solve_gep_shift_invert
from .identify import describe_mode, rings_of

SHEAR_CORRECTION = 5.0 / 6.0
"""k_s of Reissner-Mindlin theory (-)"""
REDUCED_DEGREE = 2
"""quadrature degree of the membrane and shear energies (-)"""
FULL_DEGREE = 4
"""quadrature degree of the bending and kinetic energies (-)"""
N_MAX = 8
"""highest circumferential harmonic a mode is named by (-): the shell's coarsest meshes
have 8 nodes around, where higher harmonics are aliases of lower ones"""
END_CONDITIONS = ("clamped-free", "simply-supported")
EIGEN_TOLERANCE = 1e-10
"""relative residual of the eigenpairs (-)"""
EIGEN_MAX_IT = 200
"""Krylov-Schur restarts at most (-)"""


@dataclass(frozen=True)
class ShellSection:
    """A homogeneous isotropic wall."""

    youngs_modulus: float
    """E (Pa)"""
    poisson_ratio: float
    """nu (-)"""
    density: float
    """rho (kg/m**3)"""
    thickness: float
    """t (m)"""


@dataclass(frozen=True)
class ShellDiscretisation:
    """Mesh of the mid-surface for the shell model."""

    elements_around: int = 32
    """cells around the circumference (-)"""
    elements_along: int = 40
    """cells along the height (-)"""
    cell_type: str = "quadrilateral"
    """"quadrilateral" or "triangle" (-)"""
    degree: int = 2
    """Lagrange degree of u and beta (-)"""


@dataclass(frozen=True)
class ShellModalResult:
    """Modes of the shell model, ascending (the fields of fem3d's ModalResult)."""

    omega: np.ndarray
    """natural angular frequencies (rad/s)"""
    kind: list
    """per mode: one of fem3d.identify.KINDS ("bending_x", "ovalling", ...)"""
    n_circumferential: list
    """per mode: dominant circumferential wave number n, None for "other" (-)"""
    dofs: int
    """number of unknowns (-)"""
    cells: int
    """number of cells (-)"""
    cell_type: str
    degree: int
    timings: dict = field(default_factory=dict)
    """wall seconds per stage: mesh, forms (JIT compile), assemble, solve, classify"""

    @property
    def frequency_hz(self) -> np.ndarray:
        return self.omega / (2 * np.pi)


def shell_section_of(pillar) -> tuple[ShellSection, float, float]:
    """(section, mid-surface radius R (m), height H (m)) of a scene's ``[pillar]``: the
    base's, for a tower of cans (whose cones and walls ``shell_segments_of`` gives)."""
    base = pillar.segments()[0]
    t = (base.outer_bottom - base.inner_bottom) / 2
    R = mid_surface_radius(base.outer_bottom, base.inner_bottom)
    return (ShellSection(pillar.youngs_modulus, pillar.poisson_ratio, pillar.density, t), R, pillar.height)


def shell_segments_of(pillar) -> tuple:
    """A tower's segments as the shell takes them: (bottom, top, mid-surface radius at bottom,
    at top, wall at bottom, at top) (m); empty for the uniform tube."""
    if pillar.is_uniform:
        return ()
    return tuple(
        (
            s.bottom,
            s.top,
            mid_surface_radius(s.outer_bottom, s.inner_bottom),
            mid_surface_radius(s.outer_top, s.inner_top),
            (s.outer_bottom - s.inner_bottom) / 2,
            (s.outer_top - s.inner_top) / 2,
        )
        for s in pillar.segments()
    )


# --------------------------------------------------------------------------
# The physics as UFL expressions


def cylinder_frame(x):
    """Orthonormal frame (e_theta, e_z, e_r) of the cylinder at spatial point x."""
    import ufl

    r = ufl.sqrt(x[0] ** 2 + x[1] ** 2)
    e1 = ufl.as_vector([-x[1] / r, x[0] / r, 0.0])
    e2 = ufl.as_vector([0.0, 0.0, 1.0])
    n = ufl.as_vector([x[0] / r, x[1] / r, 0.0])
    return e1, e2, n


def cone_frame(x, slope):
    """Orthonormal frame (e_theta, meridian, normal) of a cone dR/dz = ``slope`` at x:
    the meridian (slope e_r + e_z) / c and the normal (e_r - slope e_z) / c, c =
    sqrt(1 + slope**2); the cylinder's frame at slope 0."""
    import ufl

    r = ufl.sqrt(x[0] ** 2 + x[1] ** 2)
    c = ufl.sqrt(1.0 + slope**2)
    er = ufl.as_vector([x[0] / r, x[1] / r, 0.0])
    ez = ufl.as_vector([0.0, 0.0, 1.0])
    e1 = ufl.as_vector([-x[1] / r, x[0] / r, 0.0])
    return e1, (slope * er + ez) / c, (er - slope * ez) / c


def _piecewise(z, segments, value):
    """A UFL expression equal to ``value(segment)`` on each segment's heights (the cells
    meet every joint, so no quadrature point sits on one)."""
    import ufl

    expr = value(segments[-1])
    for seg in reversed(segments[:-1]):
        expr = ufl.conditional(ufl.lt(z, seg[1]), value(seg), expr)
    return expr


def tangent_projector(e1, e2):
    """P = [e1 e2], 3x2: takes tangent-plane components to Cartesian ones."""
    import ufl

    return ufl.as_matrix([[e1[i], e2[i]] for i in range(3)])


def membrane_strain(u, P):
    import ufl

    return ufl.sym(P.T * ufl.grad(u) * P)


def bending_strain(u, beta, P, n):
    import ufl

    return ufl.sym(P.T * (ufl.grad(beta) - ufl.grad(u) * ufl.grad(n)) * P)


def shear_strain(u, beta, P, n):
    import ufl

    return P.T * beta + P.T * (ufl.grad(u).T * n)


def plane_stress(e, E: float, nu: float):
    """C : e for an isotropic plane-stress material."""
    import ufl

    lmbda = E * nu / (1 - nu**2)
    mu = E / (2 * (1 + nu))
    return lmbda * ufl.tr(e) * ufl.Identity(2) + 2 * mu * e


def shell_stiffness_form(u, beta, v, gamma_, sec: ShellSection, P, n, dx_reduced, dx_full):
    """Bilinear strain-energy form a((u, beta), (v, gamma_))."""
    import ufl

    E, nu, t = sec.youngs_modulus, sec.poisson_ratio, sec.thickness
    mu = E / (2 * (1 + nu))
    membrane = t * ufl.inner(plane_stress(membrane_strain(u, P), E, nu), membrane_strain(v, P))
    bending = t**3 / 12 * ufl.inner(plane_stress(bending_strain(u, beta, P, n), E, nu), bending_strain(v, gamma_, P, n))
    shear = SHEAR_CORRECTION * mu * t * ufl.dot(shear_strain(u, beta, P, n), shear_strain(v, gamma_, P, n))
    return (membrane + shear) * dx_reduced + bending * dx_full


def shell_mass_form(u, beta, v, gamma_, sec: ShellSection, dx_full):
    """Bilinear kinetic-energy form: translation and rotary inertia of the wall."""
    import ufl

    rho, t = sec.density, sec.thickness
    return (rho * t * ufl.dot(u, v) + rho * t**3 / 12 * ufl.dot(beta, gamma_)) * dx_full


# --------------------------------------------------------------------------
# The modal analysis


def shell_modal_analysis(
    section: ShellSection,
    radius: float,
    height: float,
    disc: ShellDiscretisation = ShellDiscretisation(),
    *,
    n_modes: int = 12,
    ends: str = "clamped-free",
    comm=None,
    method: str | None = None,
    segments: tuple = (),
) -> ShellModalResult:
    """The lowest ``n_modes`` modes of the tube as a shell.

    ``segments``: a tower of cans (``shell_segments_of``): the mid-surface
    on each can's cone (its frame ``cone_frame``), the wall linear along
    each; ``section.thickness`` and ``radius`` are then the base's.

    ``ends``: "clamped-free" (the pillar) or "simply-supported" (shear
    diaphragms at both ends: u_x = u_y = 0, the closed-form check).
    ``method``: the eigen-solver's (:func:`.eigensolver.solve_gep_shift_invert`;
    None: its default for ``n_modes``).
    """
    if ends not in END_CONDITIONS:
        raise ValueError(f"ends must be one of {END_CONDITIONS}")
    from .dolfinx_import import import_dolfinx

    import_dolfinx()
    import dolfinx.fem.petsc  # noqa: F401  (registers fem.petsc)
    import ufl
    from dolfinx import fem
    from mpi4py import MPI

    comm = MPI.COMM_WORLD if comm is None else comm
    timings = {}
    t0 = time.perf_counter()
    msh, _, facets = _mesh(radius, height, disc, comm, segments)
    timings["mesh"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    cell = msh.ufl_cell()
    Ue = ufl.VectorElement("Lagrange", cell, disc.degree, dim=3)
    Be = ufl.VectorElement("Lagrange", cell, disc.degree, dim=2)
    V = fem.FunctionSpace(msh, ufl.MixedElement([Ue, Be]))
    x = ufl.SpatialCoordinate(msh)
    if segments:
        z = x[2]
        slope = _piecewise(z, segments, lambda s: (s[3] - s[2]) / (s[1] - s[0]))
        e1, e2, n = cone_frame(x, slope)
        thickness = _piecewise(z, segments, lambda s: s[4] + (s[5] - s[4]) * (z - s[0]) / (s[1] - s[0]))
        section = dataclasses.replace(section, thickness=thickness)
    else:
        e1, e2, n = cylinder_frame(x)
    P = tangent_projector(e1, e2)
    (u, b), (v, c) = ufl.TrialFunctions(V), ufl.TestFunctions(V)
    beta, gamma_ = b[0] * e1 + b[1] * e2, c[0] * e1 + c[1] * e2
    dx_red = ufl.dx(metadata={"quadrature_degree": REDUCED_DEGREE})
    dx_full = ufl.dx(metadata={"quadrature_degree": FULL_DEGREE})
    a = fem.form(shell_stiffness_form(u, beta, v, gamma_, section, P, n, dx_red, dx_full))
    m = fem.form(shell_mass_form(u, beta, v, gamma_, section, dx_full))
    bcs = _boundary_conditions(V, facets, ends)
    timings["forms"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    A = fem.petsc.assemble_matrix(a, bcs=bcs)
    A.assemble()
    # zero diagonal on constrained rows: their eigenvalues go to infinity
    M = fem.petsc.assemble_matrix(m, bcs=bcs, diagonal=0.0)
    M.assemble()
    timings["assemble"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    # a slightly negative shift keeps K - sigma M regular when rigid motions
    # are free (the axial translation of the simply supported cylinder)
    sol = solve_gep_shift_invert(A, M, n_modes, sigma=-1.0, tol=EIGEN_TOLERANCE, max_it=EIGEN_MAX_IT, method=method)
    timings["solve"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    Vu, u_dofs = V.sub(0).collapse()
    # the modes are named as the solid model's are (fem3d.identify), from the mid-surface's nodes
    rings = rings_of(_gather(Vu.tabulate_dof_coordinates(), comm), height)
    omega, kinds, ns = [], [], []
    for lam, vec in zip(sol.eigenvalues, sol.vectors):
        mode = describe_mode(None, _gather(vec.array[u_dofs].reshape(-1, 3), comm), rings, n_max=N_MAX)
        omega.append(np.sqrt(max(lam, 0.0)))
        kinds.append(mode.kind)
        ns.append(mode.n_circumferential)
    timings["classify"] = time.perf_counter() - t0
    dofs = V.dofmap.index_map.size_global * V.dofmap.index_map_bs
    cells = msh.topology.index_map(2).size_global
    for vec in sol.vectors:
        vec.destroy()
    A.destroy()
    M.destroy()
    return ShellModalResult(np.array(omega), kinds, ns, int(dofs), int(cells), disc.cell_type, disc.degree, timings)


def _mesh(radius, height, disc: ShellDiscretisation, comm, segments: tuple = ()):
    mid = tuple(s[:4] for s in segments)
    params = MidSurface(radius, height, disc.elements_around, disc.elements_along, disc.cell_type, segments=mid)
    return mid_surface_mesh(params, comm)


def _boundary_conditions(V, facets, ends: str):
    from dolfinx import fem

    if ends == "clamped-free":
        base = facets.find(BASE)
        bcs = []
        for i in (0, 1):
            Vi, _ = V.sub(i).collapse()
            dofs = fem.locate_dofs_topological((V.sub(i), Vi), 1, base)
            bcs.append(fem.dirichletbc(fem.Function(Vi), dofs, V.sub(i)))
        return bcs
    # shear diaphragms: no radial or circumferential displacement at the ends,
    # i.e. u_x = u_y = 0; axial motion and rotations free
    bcs = []
    for tag in (BASE, TOP):
        for k in (0, 1):
            Vk, _ = V.sub(0).sub(k).collapse()
            dofs = fem.locate_dofs_topological((V.sub(0).sub(k), Vk), 1, facets.find(tag))
            bcs.append(fem.dirichletbc(fem.Function(Vk), dofs, V.sub(0).sub(k)))
    return bcs


def _gather(a: np.ndarray, comm) -> np.ndarray:
    if comm.size == 1:
        return a
    return np.concatenate(comm.allgather(a))


def mid_surface_mesh(params: MidSurface, comm=None):
    """The dolfinx mesh of the mid-surface: (mesh, cell_tags, facet_tags)."""
    import gmsh
    from mpi4py import MPI

    from .dolfinx_import import import_dolfinx

    import_dolfinx()
    from dolfinx.io import gmshio

    comm = MPI.COMM_WORLD if comm is None else comm
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        if comm.rank == 0:
            gmsh.model.add("tube_mid_surface")
            gmsh_mid_surface(gmsh.model, params)
            gmsh.model.mesh.generate(2)
            # complete 9-node quadrilaterals: dolfinx reads these, not 8-node ones
            gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
            gmsh.model.mesh.setOrder(params.order)
        msh, cells, facets = gmshio.model_to_mesh(gmsh.model, comm, 0, gdim=3)
    finally:
        gmsh.finalize()
    if params.segments:
        msh.geometry.x[:] = cone_points(msh.geometry.x, params)
    return msh, cells, facets
