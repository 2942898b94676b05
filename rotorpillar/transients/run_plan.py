"""The length of a transient case's run and the 3D full order's plan for it.

``own_duration`` is a case's run length as the reduced models run it,
``with_duration`` the scene with it set (compare: one window for every model);
``fem3d_plan`` the 3D run's mesh, duration and step from [full_order] and the
convergence study's reference (rotorpillar.transients.references), what was
chosen, shortened and why (the ``full_order`` block of the JSON: ``Fem3dPlan``,
the beam's ``BeamFullOrder``).  The pillar model each run names (a
rotorpillar.chain.PillarModel): ``reduced_pillar_model``, the chain's (modal),
the scene's beam at full order (beam) or the paper's tip reduction (paper);
``solid_pillar_model``, the 3D full order's mesh, its source and error the
reference's.  rotorpillar.transients.model_run runs the models on them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

from ..chain import ChainModes, PillarModel
from ..errors import InputError
from ..records import Record
from ..reduced.models import BeamModelInfo, ModelInfo, PaperModelInfo
from ..scene import Mesh, with_values
from .references import FullOrderReference


class BeamFullOrder(Record):
    """The full-order 1D beam's discretisation and step (the beam's ``full_order`` block)."""

    elements: int
    """elements along the pillar (-)"""
    theory: str
    """the beam theory (euler or timoshenko)"""
    duration: float
    """the run's length: the case's full duration (s)"""
    time_step: float | None
    """the fixed step taken (s)"""
    note: str
    """the beam's degrees of freedom and step, in words"""


class Fem3dPlan(Record):
    """The 3D run's mesh, duration and step, and what was chosen, shortened and why
    (the ``full_order`` block of a fem3d run's JSON)."""

    mesh: Mesh
    """the scene [mesh] section the 3D run uses"""
    duration: float
    """the run's length (s)"""
    case_duration: float
    """the case's own length, as the reduced models run it (s)"""
    time_step: float | None
    """[full_order] time_step, None: the band's step; after the run, the step taken (s)"""
    note: str
    """what was coarsened or shortened, and why"""
    reference: FullOrderReference
    """where the mesh comes from and its own error"""


def own_duration(scene: Scene, case: str, motion=None) -> float:
    """The length of a case's run as the reduced models run it (s)."""
    sim = scene.simulate
    if case == "earthquake":
        from ..reduced.models import scene_motion

        motion = motion or scene_motion(scene)
        length = sim.earthquake_duration or motion.end + 5.0
        if length <= motion.start:
            raise InputError(
                f"simulate.earthquake_duration = {length:g} s ends before the ground motion starts "
                f"({motion.start:g} s, excitation.start): the run would see no earthquake; give a longer run"
            )
        return length
    if case in ("runup", "rundown"):
        return sim.duration
    raise InputError(f"case {case!r}: a common duration is defined for runup, rundown and earthquake")


def _scene_motion(scene: Scene):
    from ..reduced.models import scene_motion

    return scene_motion(scene)


def with_duration(scene: Scene, case: str, duration: float):
    """The scene with the case's run length set to ``duration`` (s)."""
    key = "earthquake_duration" if case == "earthquake" else "duration"
    return with_values(scene, {f"simulate.{key}": float(duration)})


def fem3d_plan(scene: Scene, case: str, motion=None, duration: float | None = None, study_dir=None) -> Fem3dPlan:
    """The 3D run's mesh, duration and step, and what was chosen, shortened and why
    (the ``full_order`` block of the JSON).  The mesh: the convergence study's
    reference for the modes the case's load excites when ``study_dir`` holds
    convergence.json, else [full_order]'s (rotorpillar.transients.references);
    ``reference`` says which, its own error and the participation of the modes."""
    from ..fem3d.full_order import CASES_3D
    from .references import choose_reference, estimated_steps

    if case not in CASES_3D:
        raise InputError(f"--model fem3d: case {case!r} is not available; the 3D full order runs {', '.join(CASES_3D)}")
    fo, m = scene.full_order, scene.mesh
    own = own_duration(scene, case, motion)
    stated = fo.earthquake_duration if case == "earthquake" else fo.runup_duration
    length = min(own, stated or own, duration or own)
    if case == "earthquake":
        start = (motion or _scene_motion(scene)).start
        if length <= start:
            key = "full_order.earthquake_duration" if stated and stated <= own else "simulate.earthquake_duration"
            raise InputError(
                f"{key} = {length:g} s ends before the ground motion starts ({start:g} s, "
                "excitation.start): the run would see no earthquake; give a longer run"
            )
    steps = estimated_steps(scene, case, motion, length) if study_dir is not None else None
    mesh, reference = choose_reference(scene, case, study_dir, motion, steps)
    source = (
        "the convergence study's reference for the modes the load excites"
        if reference.source == "converge"
        else "[full_order]'s, no study on disk"
    )
    if reference.overrides:
        source += f", full_order.{' and full_order.'.join(reference.overrides)} set"
    notes = []
    if (mesh.elements_around, mesh.elements_along) != (m.elements_around, m.elements_along):
        coarser = mesh.elements_around * mesh.elements_along < m.elements_around * m.elements_along
        notes.append(
            f"mesh {'coarsened' if coarser else 'changed'} from the scene's "
            f"{m.elements_around} x {m.elements_along} to {mesh.elements_around} x "
            f"{mesh.elements_along} elements (around x along; {source})"
        )
    else:
        notes.append(f"the scene's mesh ({source})")
    if length < own:
        notes.append(
            f"run shortened from the case's {own:g} s to {length:g} s "
            f"(full_order.{'earthquake' if case == 'earthquake' else 'runup'}_duration)"
        )
    why = (
        "the 3D run costs its steps (40 per period of the fastest forcing) times one solve; the "
        "scene's [full_order] section keeps it to tens of seconds (its docstring and "
        "docs/transients.md give the measured cost and the agreement with the ROM)"
    )
    return Fem3dPlan(
        mesh,
        float(length),
        float(own),
        fo.time_step or None,
        "; ".join(notes) + (f": {why}" if length < own else ""),
        reference,
    )


def reduced_pillar_model(which: str, chain: ChainModes | None, info: ModelInfo | None) -> PillarModel:
    """The pillar model a reduced model ran on: the chain's (modal), the scene's beam at
    full order (beam), or the paper's stated tip reduction (paper: not the validated chain)."""
    if which == "modal":
        if chain is None:
            raise ValueError("the modal model's pillar model is the chain's: none handed in")
        return chain.pillar_model
    if which == "beam":
        assert isinstance(info, BeamModelInfo)  # build_model's for "beam"
        n, theory = info.elements, info.theory
        return PillarModel(
            "beam",
            f"beam {theory}, {n} el. (full order)",
            {"theory": theory, "elements": n},
            2 * n,
            "scene",
            False,
            None,
            {},
            f"the full-order 1D {theory} beam of {info.element_source}",
            None,
        )
    assert isinstance(info, PaperModelInfo)  # build_model's for "paper"
    red = info.reduction
    return PillarModel(
        "reduction",
        "Eq. 4: one tip mass and spring",
        {"tip_mass": red.tip_mass, "tip_stiffness": red.tip_stiffness},
        1,
        "scene",
        False,
        None,
        {},
        f"the paper's model: m_r ({red.tip_mass_source}) and c1 "
        f"({red.tip_stiffness_source}) at the tip; not the validated chain",
        None,
    )


def solid_pillar_model(mesh: Mesh, dofs: int, reference: FullOrderReference, note: str) -> PillarModel:
    """The 3D full order's mesh as a PillarModel, its source and error the reference's."""
    from ..chain.choice import solid_run_of

    run = solid_run_of(mesh)
    errors = {q: e.error_bound for q, e in reference.errors.items() if e.error_bound is not None}
    return PillarModel(
        "solid",
        run.label + " (full order)",
        run.params,
        int(dofs),
        reference.source,
        reference.verified,
        reference.tolerance,
        errors,
        note + ("; " + reference.statement if reference.statement else ""),
        reference.study,
    )
