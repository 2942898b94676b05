"""3D continuum model of the pillar: linear elasticity (dolfinx), SLEPc modes.

The public API (dolfinx, PETSc and SLEPc are imported inside the functions):

- :func:`modal_analysis` (scene, top=...) -> :class:`ModalResult`: the k lowest
  modes of the bare tube or of the tube with its masses on top, each named
  from its shape (bending_x/y, ovalling with n, torsion, axial, breathing,
  other; see :mod:`rotorpillar.fem3d.identify`).
- :func:`reduction_from_scene` (scene) -> (m_reduced, tip_stiffness): the
  paper's Eq. 2 done on the 3D model's first bending mode.
- :func:`assemble_pillar` (scene, top=...) -> :class:`AssembledPillar`: the
  assembled K and M in PETSc with the node coordinates and top-face nodes,
  for time integration of the 3D model.

- :mod:`rotorpillar.fem3d.pillar_modes`: the 3D X bending modes as the
  reduced package's PillarModes (``candidate_pillar_modes`` for the modal
  model when ``modal_model.source = "fem3d"``).

Axes (``AXES``): the tube axis is z, base at z = 0; x is the paper's X (the
rotor's plane); y is horizontal, normal to it.

Where the paper's equations live on the 3D side (the first line of each
function's docstring carries the tag; the reduced side's index is in
rotorpillar.reduced):

Eq. 2    rotorpillar.fem3d.reduction.tip_reduction
Eq. 2    rotorpillar.fem3d.reduction.beam_line_tip_mass
"""

from __future__ import annotations

from collections import OrderedDict

from ..scene import Scene
from .modal import AXES, ModalResult  # noqa: F401  (numpy-only modules)
from .reduction import TipReduction, tip_reduction  # noqa: F401

#: The last few results, so that `run` (analyze with reduction.source = fem3d,
#: then modal) solves each configuration once; small, because a result holds
#: its mode shapes and a convergence study makes many.
_CACHE: OrderedDict = OrderedDict()
CACHE_SIZE = 4


def top_bodies(scene: Scene) -> tuple:
    """The rigid bodies on the loaded tube's top (rotorpillar.fem3d.model.TopBody).

    The gondola with its rotary inertias and its centre ``gondola.height``
    above the top; with ``modal.top_mass = "gondola_and_rotor"`` the rotor
    too, welded on at ``rotor.height`` with its diametral inertia on pitch
    and yaw and none on roll (about its spin axis it spins freely: its polar
    inertia is not carried by the structure).
    """
    from .model import TopBody

    g, r = scene.gondola, scene.rotor
    # the keys of issue 26 (scene/sections.py): absent in an older scene, 0 as today
    bodies = [
        TopBody(
            g.mass,
            getattr(g, "pitch_inertia", 0.0),
            getattr(g, "roll_inertia", 0.0),
            getattr(g, "yaw_inertia", 0.0),
            getattr(g, "height", 0.0),
        )
    ]
    if scene.modal.top_mass == "gondola_and_rotor":
        Id = getattr(r, "diametral_inertia", 0.0)
        bodies.append(TopBody(r.mass, Id, 0.0, Id, getattr(r, "height", 0.0)))
    return tuple(bodies)


def _top_settings(scene: Scene, top: bool):
    """(top model, mass on top (kg), its bodies) of the bare (top False) or loaded tube."""
    if not top:
        return None, 0.0, ()
    bodies = top_bodies(scene)
    return scene.modal.top_model, sum(b.mass for b in bodies), bodies


def assemble_pillar(scene: Scene, *, top: bool, mesh=None, comm=None, isolated: bool = True):
    """The assembled 3D model of the scene's pillar (see :class:`model.AssembledPillar`).

    ``mesh`` (a scene ``Mesh`` section) replaces ``scene.mesh``; ``top`` adds
    the masses on top as ``scene.modal`` says (rigid plate or ring mass).
    """
    from ..reduced.foundation import foundation_stiffness
    from .model import assemble_model

    top_model, top_mass, bodies = _top_settings(scene, top)
    return assemble_model(
        scene.pillar,
        scene.mesh if mesh is None else mesh,
        top_model=top_model,
        top_mass=top_mass,
        top_bodies=bodies or None,
        comm=comm,
        isolated=isolated,
        foundation=foundation_stiffness(scene.foundation),
    )


def modal_analysis(
    scene: Scene,
    *,
    top: bool,
    n_modes: int | None = None,
    mesh=None,
    comm=None,
    isolated: bool = True,
    use_cache: bool = True,
) -> ModalResult:
    """The ``n_modes`` lowest modes (default ``scene.modal.n_modes``) of the pillar.

    ``top`` False: the bare tube, clamped at the base, free at the top (what
    Eq. 1 describes).  True: with the gondola (and, by ``scene.modal.top_mass``,
    the rotor) on top.  ``mesh`` (a scene ``Mesh`` section) replaces
    ``scene.mesh``.  Results are cached per (pillar, mesh, top, modal
    settings, n_modes, communicator size) within a process.
    """
    from mpi4py import MPI

    from .modal import run_modal

    comm = MPI.COMM_WORLD if comm is None else comm
    mesh = scene.mesh if mesh is None else mesh
    n_modes = scene.modal.n_modes if n_modes is None else n_modes
    if n_modes == 0:
        return _band_modes(scene, top=top, mesh=mesh, comm=comm, isolated=isolated, use_cache=use_cache)
    key = _cache_key(scene, top, n_modes, mesh, comm.size)
    if use_cache and comm is MPI.COMM_WORLD and key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    model = assemble_pillar(scene, top=top, mesh=mesh, comm=comm, isolated=isolated)
    try:
        result = run_modal(
            model,
            n_modes,
            tol=scene.modal.tolerance,
            mesh_section=mesh,
            material=(scene.pillar.youngs_modulus, scene.pillar.poisson_ratio) if top else None,
            spatial=top,
        )
    finally:
        model.K.destroy()
        model.M.destroy()
    if use_cache and comm is MPI.COMM_WORLD:
        _keep(key, result)
    return result


def _cache_key(scene: Scene, top: bool, n_modes: int, mesh, ranks: int) -> tuple:
    """What a result depends on: the pillar, its foundation, the mesh, the top, the
    modes asked, the solver's tolerance and the number of MPI ranks."""
    top_model, _, bodies = _top_settings(scene, top)
    return (scene.pillar, scene.foundation, mesh, top_model, bodies, n_modes, scene.modal.tolerance, ranks)


def remember(scene: Scene, top: bool, n_modes: int, mesh, result: ModalResult) -> None:
    """Keep ``result`` in this process's cache as :func:`modal_analysis` would have kept
    it for these arguments on one rank (a solve done in a second process,
    rotorpillar.fem3d.beside)."""
    _keep(_cache_key(scene, top, n_modes, scene.mesh if mesh is None else mesh, 1), result)


def in_cache(scene: Scene, top: bool, n_modes: int, mesh) -> bool:
    """Whether this process's cache holds :func:`modal_analysis`'s result for these
    arguments on one rank."""
    return _cache_key(scene, top, n_modes, scene.mesh if mesh is None else mesh, 1) in _CACHE


def _keep(key: tuple, result: ModalResult) -> None:
    _CACHE[key] = result
    while len(_CACHE) > CACHE_SIZE:
        _CACHE.popitem(last=False)


BAND_MODES = 8
"""Modes first computed for ``modal.n_modes = 0`` (doubled while the band is not passed)."""


def _band_modes(scene: Scene, **kw) -> ModalResult:
    """Enough modes to pass the scene's band: the 3D modes a scene needs (its
    excitation up to the band's edge, and the mode beyond it), in blocks of
    BAND_MODES; not the 16 or more a fixed count asks on every scene."""
    from ..reduced.band import excitation_band

    edge = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    n = BAND_MODES
    while True:
        result = modal_analysis(scene, n_modes=n, **kw)
        if len(result.omega) < n or result.omega[-1] > edge or n >= 500:
            return result
        n *= 2


def reduction_from_scene(scene: Scene) -> tuple[float, float]:
    """(m_reduced in kg, tip_stiffness in N/m) from the bare tube's first bending mode.

    Kinetic-energy equivalence (the paper's Eq. 2) on the 3D mode normalised
    to unit tip displacement: m_r = phi^T M phi, c1 = m_r omega**2.  This is
    the callable ``rotorpillar.analysis.analyze(scene, fem3d_reduction=...)``
    takes when ``reduction.source = "fem3d"``.
    """
    red = tip_reduction(modal_analysis(scene, top=False), scene.pillar)
    return red.m_reduced, red.tip_stiffness
