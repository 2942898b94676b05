"""`rotorpillar modal`: the 3D tube's modes, bare and with its masses on top.

On the chain's mesh (rotorpillar.chain): the one the convergence study chose
for the scene's band when a study is on disk (the cheapest 3D mesh within its
tolerance when the choice is a beam or a shell), else the scene's [mesh];
``--tolerance`` asks the study for it now.  It also computes (and caches) the
ROM's pillar modes on that mesh, so the stages after it read them.

Writes modal.json (through the CLI; ``pillar_model`` names the mesh, where it
came from and its error), ``modes_bare.vtu`` and ``modes_top.vtu`` (ParaView,
pyvista, meshio) beside it, and prints a table.  Runs under MPI (``mpirun -n
2 rotorpillar modal``): every rank computes, rank 0 writes and prints.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import msgspec

from ..converge.result import ModalModelSelection
from ..fem3d.modal_summary import ModalSummary
from ..records import Record, replace
from . import Done, progress

#: Mode-shape files, in the output directory.
SHAPE_FILES = {"bare": "modes_bare.vtu", "top": "modes_top.vtu"}


def band_edge(scene: Scene) -> float:
    from ..reduced.band import excitation_band

    return excitation_band(scene.drive, scene.load, scene.converge).omega_max


def band_cut(result, edge: float, first: int = 8):
    """``result`` cut as ``modal.n_modes = 0`` would have solved it: 8 modes, doubled while
    the last lies at or below the band's ``edge`` (rad/s)."""
    from ..reduced.band import cut_count

    return result.lowest(cut_count(result.omega, edge, first))


def quiet_jit_logging() -> None:
    """Keep the compiler's INFO lines (setuptools, on the first JIT of a form) off stderr.

    ffcx installs a root handler at import; setuptools raises the root level
    to INFO while it builds.  A WARNING threshold on the handler keeps the
    console to our own progress lines.
    """
    import logging

    root = logging.getLogger()
    if not root.handlers:
        logging.basicConfig()
    for h in root.handlers:
        h.setLevel(max(h.level, logging.WARNING))


def _rank0() -> bool:
    from mpi4py import MPI

    return MPI.COMM_WORLD.rank == 0


#: Modal solves in one `modal` process (bare, then with the top): its peak memory
#: is this many times one solve's (mesh.tube.BYTES_PER_DOF).
SOLVES = 2


def preflight(scene: Scene, args=None) -> None:
    """What `modal` refuses before any work (`run` calls it for its stage too): a mesh
    this process cannot hold or whose run is estimated above ``modal.max_seconds``, more
    modes than the mesh has, a tolerance out of range."""
    from ..errors import InputError
    from ..mesh import tube_params
    from ..provenance import check_memory

    p = tube_params(scene.pillar, scene.mesh)
    check_memory(
        SOLVES * p.estimated_bytes,
        f"modal: the mesh {p.elements_around} around x {p.elements_along} along x "
        f"{p.elements_through} through ({p.estimated_dofs:,} DOFs, two solves)",
        "use fewer elements",
    )
    seconds, limit = p.estimated_seconds, scene.modal.max_seconds
    if not seconds <= limit:
        from ..fem3d.full_order_plan import duration_text

        raise InputError(
            f"modal: the mesh {p.elements_around} around x {p.elements_along} along x "
            f"{p.elements_through} through ({p.estimated_dofs:,} DOFs) would take about "
            f"{duration_text(seconds)} (an estimate), more than modal.max_seconds = {limit:.3g} s: "
            "use fewer elements, or raise modal.max_seconds"
        )
    n, rigid = scene.modal.n_modes, scene.modal.top_model == "rigid"
    dofs = min(p.solver_dofs(False), p.solver_dofs(rigid))
    if n and n + 1 > dofs:
        raise InputError(
            f"modal.n_modes = {n}: the mesh {p.elements_around} x {p.elements_along} x "
            f"{p.elements_through} has {dofs} unknowns"
            + (" with its rigid top" if rigid else "")
            + f"; the solver returns at most {dofs - 1} modes (it asks one more "
            "than n_modes): ask fewer or refine the mesh"
        )
    if getattr(args, "tolerance", None) is not None:
        from ..converge.study import check_tolerance

        check_tolerance(args.tolerance)


def modal_command(scene: Scene, args, timings):
    import sys

    from . import EXIT_CHECKS, out_dir

    preflight(scene, args)  # bad input: refused before any import or work
    from ..fem3d import modal_analysis
    from ..fem3d.modal_summary import modal_summary, summary
    from ..fem3d.output import write_modes_vtu
    from ..reduced.foundation import base_springs
    from ..reduced.reduction import pillar_closed_forms

    quiet_jit_logging()
    say = progress if _rank0() else (lambda message: None)

    from mpi4py import MPI

    from ..chain import chain_modes, choose, rom_band_top
    from ..chain.choice import Choice, from_scene, model_of_run

    selection: ModalModelSelection | None = None
    if getattr(args, "tolerance", None) is not None:
        from ..converge import model_for_modal
        from ..postprocess.convergence_charts import convergence_charts

        with timings("model_selection"):
            scene, selection = model_for_modal(
                scene,
                args.tolerance,
                out_dir(scene, args),
                cache_dir=args.cache,
                charts=convergence_charts,
                log=say,
                show_progress=sys.stderr.isatty(),
            )
        say(selection.text.splitlines()[0])
        if selection.chosen is None:  # no 3D run has an error estimate: the scene's [mesh]
            choice = from_scene(scene, args.cache or out_dir(scene, args) / "cache", selection.reason)
        else:
            pm = model_of_run(
                selection.chosen,
                selection.reference_uncertainty,
                args.tolerance,
                selection.reason,
                selection.convergence_json,
            )
            choice = Choice(*(2 * [pm if selection.met else replace(pm, verified=False)]))
    else:
        choice = choose(scene, out_dir(scene, args))
        scene = replace(scene, mesh=choice.solid_mesh)
    preflight(scene)  # the mesh run: its memory and modes
    say(f"modal: {choice.solid.describe()}")
    with timings("rom_modes"):
        # the ROM's modes on this mesh, computed once here and cached for the stages after
        chain = chain_modes(scene, choice, rom_band_top(scene), comm=MPI.COMM_WORLD, progress=say)
    say(
        "modal: bare tube, "
        + (
            f"{scene.modal.n_modes} modes"
            if scene.modal.n_modes
            else f"the modes past the band ({band_edge(scene):.1f} rad/s)"
        )
    )
    bare = modal_analysis(scene, top=False)
    say(f"modal: tube with its top mass ({scene.modal.top_model} top)")
    if chain.loaded_modes and scene.modal.n_modes == 0:
        # the ROM's solve of the loaded tube, reused (in this process's cache when the chain
        # solved it here), cut to the modes the band asks: one solve, not two
        loaded = band_cut(modal_analysis(scene, top=True, n_modes=chain.loaded_modes), band_edge(scene))
    else:
        loaded = modal_analysis(scene, top=True)
    for key in ("mesh", "assembly", "solve", "postprocess"):
        timings[key] = bare.timings.get(key, 0.0) + loaded.timings.get(key, 0.0)
        timings[f"bare.{key}"] = bare.timings.get(key, 0.0)
        timings[f"with_top.{key}"] = loaded.timings.get(key, 0.0)
    found = modal_summary(scene, bare, loaded, pillar_closed_forms(scene.pillar, base_springs(scene.foundation)))
    files = None
    if _rank0():
        with timings("write_shapes"):
            d = out_dir(scene, args)
            files = ShapeFiles(
                modes_bare=str(write_modes_vtu(d / SHAPE_FILES["bare"], bare)),
                modes_top=str(write_modes_vtu(d / SHAPE_FILES["top"], loaded)),
            )
    text = summary(found, bare, loaded)
    text = f"Pillar model: {choice.solid.describe()}\n  {choice.solid.note}\n\n" + text
    status, failed = 0, None
    if selection is not None:
        text = selection.text + "\n\n" + text
        if not selection.met:  # written, and marked: the exit code says so too
            status, failed = EXIT_CHECKS, (selection.reason,)
            say(f"modal: check failed: {selection.reason}")
    record = ModalRun(
        **msgspec.structs.asdict(found),
        files=files,
        model_selection=selection,
        ok=failed is None,
        failed_checks=failed,
    )
    return Done(replace(record, pillar_model=choice.solid), text, status)


class ShapeFiles(Record):
    """The mode shapes written beside modal.json (VTU: ParaView, pyvista, meshio)."""

    modes_bare: str
    """the bare tube's modes, one point array ``mode_000``, ``mode_001``, ... a mode"""
    modes_top: str
    """the modes of the tube with its top mass"""


class ModalRun(ModalSummary, kw_only=True, omit_defaults=True):
    """modal.json: what the modal analysis found, the files written and, with
    ``--tolerance``, the mesh chosen and whether it meets the tolerance."""

    files: ShapeFiles | None = None
    """the mode shapes (None off MPI rank 0)"""
    model_selection: ModalModelSelection | None = None
    """``--tolerance``: the 3D mesh run and why"""
    ok: bool = True
    """False when no 3D run of the study meets ``--tolerance`` (exit 4)"""
    failed_checks: tuple[str, ...] | None = None
    """why ``ok`` is false"""
