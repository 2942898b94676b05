"""What each run of the ladder computes: its first bending and first ovalling frequency.

The closed forms and the 1D beams are numpy only and run in the study's
process (:func:`compute_in_process`); the shell and the 3D solid import
dolfinx and run in a fresh subprocess (:func:`compute_fe`, called by
:func:`rotorpillar.converge.runner.worker`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import msgspec
import numpy as np

from ..reduced.beam_fe import beam_modes
from ..reduced.cylinder import ring_frequency
from ..reduced.foundation import base_springs
from ..reduced.pillar import omega_euler_bernoulli, section_of
from ..reduced.pillar_modes import beam_line
from ..reduced.tower import rayleigh_ritz
from ..scene import Scene
from ..scene.tower import Foundation
from .ladder import FAMILIES, N_MODES, N_MODES_FIRST, Case, solid_mesh
from .result import Mode, RunResult

if TYPE_CHECKING:  # the FE models import dolfinx: at run time, only where they run
    from ..fem3d.modal import ModalResult
    from ..fem3d.naghdi import ShellModalResult


def _first(omega, kind, want: str) -> tuple[float | None, int | None]:
    for i, (w, k) in enumerate(zip(omega, kind)):
        if (want == "bending" and k.startswith("bending")) or (want == "ovalling" and k == "ovalling"):
            return float(w), i
    return None, None


def _modal_summary(omega, kind, n_circ, dofs: int) -> RunResult:
    """The run's quantities from a list of modes."""
    bending, _ = _first(omega, kind, "bending")
    ovalling, i = _first(omega, kind, "ovalling")
    return RunResult(
        bending=bending,
        ovalling=ovalling,
        ovalling_n=None if i is None or n_circ[i] is None else int(n_circ[i]),
        dofs=dofs,
        modes=tuple(Mode(float(w), k, None if n is None else int(n)) for w, k, n in zip(omega, kind, n_circ)),
    )


def compute_in_process(case: Case, pillar, foundation: Foundation | None = None) -> RunResult:
    """The closed forms and the 1D beam models (numpy only), on the ``foundation``'s springs
    (None: clamped).

    The closed forms (Eq. 1, the ring) are a uniform tube's on a clamp; a
    tapered or stepped tower, or one on springs, has Rayleigh-Ritz's first
    bending frequency (an upper bound) in Eq. 1's place and no ovalling
    closed form (rotorpillar.reduced.reduction.pillar_closed_forms)."""
    fam = FAMILIES[case.family]
    base = base_springs(foundation or Foundation())
    if fam.model == "closed_form":
        if pillar.is_uniform and base is None:
            sec = section_of(pillar)
            t, R = sec.wall_thickness, (sec.outer_diameter + sec.inner_diameter) / 4
            bending = omega_euler_bernoulli(
                pillar.youngs_modulus, sec.second_moment, sec.mass_per_length, pillar.height
            )
            ovalling = ring_frequency(2, pillar.youngs_modulus, pillar.poisson_ratio, pillar.density, R, t)
            return RunResult(bending=bending, ovalling=ovalling, ovalling_n=2, dofs=1, modes=())
        ritz = rayleigh_ritz(pillar, base=base)
        return RunResult(bending=float(ritz.omega[0]), ovalling=None, ovalling_n=None, dofs=ritz.terms, modes=())
    s = case.settings
    line = beam_line(pillar, s["elements"])
    m = beam_modes(line, s["elements"], s["theory"], n_modes=1, base=base)
    return RunResult(
        bending=float(m.omega[0]),
        ovalling=None,
        ovalling_n=None,
        dofs=int(m.dofs),
        modes=(Mode(float(m.omega[0]), "bending_x", 1),),
    )


def compute_fe(case: Case, scene: Scene, fresh: bool = False, *, isolated: bool = True) -> RunResult:
    """A shell or solid run, in this process (the subprocess worker calls this).

    The run asks for ``N_MODES_FIRST`` modes and for ``N_MODES`` only when
    the first ovalling mode is not among them (coarse or locking meshes,
    where it lies higher): the lowest modes are the same eigenpairs either
    way, so the quantities are too, and the fine meshes, whose ovalling pair
    comes third and fourth, solve for half as many modes.  A 3D run meshes
    and assembles once for both solves.

    ``fresh``: bypass the 3D model's in-process result cache (a second, timed call).
    ``isolated``: Gmsh in a child process (rotorpillar.mesh.isolated); the serving
    process, itself a child of the study, meshes in-process (False).
    """
    if FAMILIES[case.family].model == "solid":
        return _compute_solid(case, scene, isolated)
    out = _compute_fe(case, scene, N_MODES_FIRST, fresh)
    if out.ovalling is None:
        first = out.timings or {}
        out = _compute_fe(case, scene, N_MODES, fresh)
        out = msgspec.structs.replace(out, timings={k: v + first.get(k, 0.0) for k, v in (out.timings or {}).items()})
    return out


def _summary(r: ShellModalResult | ModalResult, n_modes: int) -> RunResult:
    out = _modal_summary(np.asarray(r.omega), list(r.kind), list(r.n_circumferential), int(r.dofs))
    return msgspec.structs.replace(out, cells=int(r.cells), timings=dict(r.timings), modes_asked=n_modes)


def _compute_solid(case: Case, scene: Scene, isolated: bool) -> RunResult:
    """The bare tube's 3D modes, as ``fem3d.modal_analysis(scene, top=False)`` gives them,
    meshed and assembled once: the N_MODES solve, where needed, reuses K and M (a
    coarse mesh's second mesh and assembly cost as much as its solves)."""
    from .. import fem3d
    from ..fem3d.modal import run_modal

    mesh = solid_mesh(case)
    model = fem3d.assemble_pillar(scene, top=False, mesh=mesh, isolated=isolated)
    try:
        out = _summary(run_modal(model, N_MODES_FIRST, tol=scene.modal.tolerance, mesh_section=mesh), N_MODES_FIRST)
        if out.ovalling is None:
            first = out.timings or {}
            out = _summary(run_modal(model, N_MODES, tol=scene.modal.tolerance, mesh_section=mesh), N_MODES)
            # the mesh and the assembly were done once: only the solve and what follows add up
            out = msgspec.structs.replace(
                out,
                timings={
                    k: v + (first.get(k, 0.0) if k not in model.timings else 0.0)
                    for k, v in (out.timings or {}).items()
                },
            )
    finally:
        model.K.destroy()
        model.M.destroy()
    return out


def _compute_fe(case: Case, scene: Scene, n_modes: int, fresh: bool) -> RunResult:
    """One modal solve of ``n_modes`` through the models' own entries (``fresh``: no
    in-process result cache)."""
    fam = FAMILIES[case.family]
    pillar = scene.pillar
    s = case.settings
    r: ShellModalResult | ModalResult
    if fam.model == "shell":
        from ..fem3d.naghdi import ShellDiscretisation, shell_modal_analysis, shell_section_of, shell_segments_of

        sec, R, H = shell_section_of(pillar)
        disc = ShellDiscretisation(s["elements_around"], s["elements_along"], s["cell_type"], s["degree"])
        r = shell_modal_analysis(sec, R, H, disc, n_modes=n_modes, segments=shell_segments_of(pillar))
    else:
        import inspect

        from .. import fem3d

        extra = (
            {"use_cache": False} if fresh and "use_cache" in inspect.signature(fem3d.modal_analysis).parameters else {}
        )
        r = fem3d.modal_analysis(scene, top=False, n_modes=n_modes, mesh=solid_mesh(case), **extra)
    return _summary(r, n_modes)
