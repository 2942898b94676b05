"""The 3D full order's mesh for a transient case: chosen for what the load excites.

Which modes the case's loads excite, and how much, is transients.participation's
(the loaded tube's 3D modes, never assumed).

The reference mesh is the coarsest 3D run of the convergence study
(``out/<scene>/convergence.json``) whose error bound on the frequencies of
the participating modes in the case's band meets the study's tolerance
(rotorpillar.converge.selection.select_reference), for the run-up also the
ROM's mode source's own bound where that is smaller (the full order is at
least as fine as what it checks).  Without a study the scene's [full_order]
keys give the mesh, unverified; ``full_order.elements_around/along`` set
(non-zero) override the study's choice.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from .. import records
from ..converge.result import ModeSourceFloor, QuantityErrors
from ..records import Record, replace
from ..scene.sections import Mesh
from .participation import ParticipationTable, load_participation

if TYPE_CHECKING:
    from ..converge.result import ConvergenceRun, ConvergenceStudy, RunBrief
    from ..scene import Scene

FLOOR_CASES = ("runup",)
"""Cases whose reference must also be as accurate as the ROM's mode source (issue 15.4
asks it of the run-up, whose old beam reference was coarser than the ROM's modes;
the earthquake's 15 s window costs ~20 times the run-up's, so it keeps the tolerance)."""
REFERENCE_DOF_STEPS = 40e6
"""What refining the reference for the ROM source's floor may cost: DOFs x steps.
The 3D full order costs ~0.45 us per DOF and step on a quiet 2-core machine (8 x 10,
3,033 DOFs: 1.3 ms a step, fem3d.full_order_plan.SECONDS_PER_STEP), so ~20 s; the tolerance's own choice is never held to it
(the paper's El Centro on 8 x 15: 38e6)."""
FALLBACK_AROUND = 8
"""Elements around without a study and without full_order.elements_around (-)."""


class FullOrderReference(Record):
    """The 3D full order's mesh for one case, where it comes from, and its own error."""

    case: str
    mesh: dict
    """the scene [mesh] section the 3D run uses"""
    label: str
    source: str
    """converge (the study's choice) or scene ([full_order] and [mesh] keys, unverified)"""
    verified: bool
    """the study bounds this mesh's error on the participating modes"""
    band_error: float | None
    """largest error bound plus the reference's uncertainty over ``quantities`` (-)"""
    errors: dict[str, QuantityErrors]
    """per quantity: value, error, model_error, discretisation_error, error_bound (the
    bare tube's, from the study)"""
    quantities: tuple[str, ...]
    tolerance: float | None
    required: float | None
    floor: ModeSourceFloor | None
    """the ROM's mode source (run-up: the reference is at least as fine)"""
    meets: bool | None
    overrides: tuple[str, ...]
    """[full_order] keys that replaced the study's choice"""
    participation: ParticipationTable | None
    reason: str
    statement: str
    """the reference's own error and why the modes left out do not matter, in words"""
    study: str | None = None
    """the convergence.json read"""

    @classmethod
    def unverified(cls, case: str, mesh, why: str, overrides: tuple[str, ...] = ()) -> FullOrderReference:
        """The scene's own mesh for ``case``, no study bounding its error (``why``: why not)."""
        label = _label(mesh)
        return cls(
            case=case,
            mesh=dict(vars(mesh)),
            label=label,
            source="scene",
            verified=False,
            band_error=None,
            errors={},
            quantities=(),
            tolerance=None,
            required=None,
            floor=None,
            meets=None,
            overrides=overrides,
            participation=None,
            reason=why,
            statement=f"The 3D reference runs {label}, unverified: {why}.",
        )


# --------------------------------------------------------------------------
# The reference mesh


def read_study(scene: Scene, study_dir: Path | None):
    """The scene's convergence study on disk (ConvergenceStudy), or None when it is
    missing, damaged or for another tube ([pillar] but its damping, [mesh] or
    [converge] differ: what the study's runs and tolerance depend on)."""
    if study_dir is None:
        return None
    from ..converge.result import ConvergenceStudy

    path = Path(study_dir) / "convergence.json"
    try:
        study = records.read(path, ConvergenceStudy)
    except (OSError, ValueError):  # missing or damaged: no study
        return None
    mine, theirs = scene.to_dict(), study.scene
    tube = lambda d: {k: v for k, v in (d or {}).items() if k != "damping"}  # noqa: E731
    if tube(theirs.get("pillar")) != tube(mine["pillar"]) or any(
        theirs.get(k) != mine[k] for k in ("mesh", "converge")
    ):
        return None
    return replace(study, json_file=str(path))


def rom_source_record(scene: Scene, study: ConvergenceStudy) -> ConvergenceRun | RunBrief | None:
    """The study's record of the ROM's mode source (a beam: computed if the ladder
    lacks its element count; 3D: the study's run on that mesh), or None."""
    from ..converge.ladder import FAMILIES, _case

    mm = scene.modal_model
    source = getattr(mm, "source", "beam")
    runs = [r for r in study.runs if r.status == "ok"]
    if source == "beam":
        case = _case(f"beam_{mm.theory}", mm.elements, theory=mm.theory, elements=mm.elements)
        for r in runs:
            if r.family == case.family and r.params == case.settings:
                return r
        from ..converge.compute import compute_in_process
        from ..converge.runner import case_key, run_record
        from ..converge.selection import attach_errors

        result = replace(compute_in_process(case, scene.pillar), wall_time=0.0)
        computed = run_record(case, case_key(case, scene.pillar), result)
        return attach_errors([computed], study.reference, study.extrapolations)[0]
    if source == "fem3d":
        want = dict(vars(scene.mesh))
        for r in runs:
            if FAMILIES[r.family].model == "solid" and all(r.params.get(k) == v for k, v in want.items()):
                return r
        return None
    return study.chosen  # modal_model.source = "auto": the study's choice feeds the ROM


def _mesh_of(scene: Scene, params: dict) -> Mesh:
    return replace(
        scene.mesh,
        **{
            k: params[k]
            for k in ("elements_around", "elements_along", "elements_through", "degree", "cell_type", "grading")
            if k in params
        },
    )


def estimated_steps(scene: Scene, case: str, motion, duration: float) -> int:
    """The 3D run's steps over ``duration`` (its step as simulate_fem3d sets it:
    fem3d.full_order_plan.step_rule)."""
    from ..fem3d.full_order_plan import case_setup, step_rule

    start = scene.simulate.runup_initial_speed if case == "runup" else None
    motion, drive, duration, speed, _ = case_setup(scene, case, motion, None, duration, start or None)
    return max(1, int(round(duration / step_rule(scene, drive, motion, speed).time_step)))


def choose_reference(
    scene: Scene, case: str, study_dir: Path | None = None, motion=None, steps: int | None = None
) -> tuple[Mesh, FullOrderReference]:
    """(the scene [mesh] section the 3D run uses, the record of why) for ``case``;
    ``steps``: the run's Newmark steps, which bound how far the run-up's reference
    is refined for the ROM source (REFERENCE_DOF_STEPS)."""
    from ..converge.ladder import FAMILIES
    from ..converge.selection import run_band_error, select_reference

    fo = scene.full_order
    study = read_study(scene, study_dir)
    overrides = tuple(k for k in ("elements_around", "elements_along") if getattr(fo, k))
    if study is None:
        mesh = replace(
            scene.mesh,
            elements_around=fo.elements_around or FALLBACK_AROUND,
            elements_along=fo.elements_along or scene.mesh.elements_along,
        )
        why = (
            "no convergence study of this tube on disk (out/<scene>/convergence.json; "
            "`rotorpillar converge` writes it): the mesh is the scene's [full_order] "
            f"({fo.elements_around or f'{FALLBACK_AROUND} (default)'} around) on [mesh]'s "
            f"along ({mesh.elements_along}), its error unknown"
        )
        return mesh, FullOrderReference.unverified(case, mesh, why, overrides)
    part = load_participation(scene, case, study_dir, motion)
    quantities = part.quantities
    runs, reference = study.runs, study.reference
    along = [r.dofs for r in runs if r.family == "solid_hex_p2_along" and r.status == "ok" and r.dofs is not None]
    floor = None
    if case in FLOOR_CASES:
        rec = rom_source_record(scene, study)
        if rec is not None:
            floor = ModeSourceFloor(label=rec.label, band_error=run_band_error(rec, quantities, reference))
    choice = select_reference(
        runs,
        reference,
        quantities,
        study.tolerance,
        floor=floor,
        max_dofs=max(along) if along else None,
        floor_max_dofs=None if steps is None else int(REFERENCE_DOF_STEPS / steps),
    )
    if choice is None:
        mesh = replace(
            scene.mesh,
            elements_around=fo.elements_around or FALLBACK_AROUND,
            elements_along=fo.elements_along or scene.mesh.elements_along,
        )
        why = (
            f"no 3D run of the study meets {study.tolerance:g} on "
            f"{', '.join(quantities) or 'the participating modes'}: the scene's [full_order] mesh, "
            "its error unknown"
        )
        return mesh, FullOrderReference(
            case=case,
            mesh=dict(vars(mesh)),
            label=_label(mesh),
            source="scene",
            verified=False,
            band_error=None,
            errors={},
            quantities=quantities,
            tolerance=study.tolerance,
            required=None,
            floor=floor,
            meets=False,
            overrides=overrides,
            participation=part,
            reason=why,
            statement=f"The 3D reference runs {_label(mesh)}, unverified: {why}. " + part.statement,
            study=study.json_file,
        )
    mesh = _mesh_of(scene, choice.params)
    band_err: float | None = choice.band_error
    errors, verified, label = choice.errors, True, choice.label
    reason = choice.reason
    if overrides:
        mesh = replace(mesh, **{k: getattr(fo, k) for k in overrides})
        same = next(
            (
                r
                for r in runs
                if r.status == "ok"
                and FAMILIES[r.family].model == "solid"
                and all(r.params.get(k) == v for k, v in vars(mesh).items())
            ),
            None,
        )
        reason = (
            f"full_order.{' and full_order.'.join(overrides)} set: {_label(mesh)} instead of the study's {choice.label}"
        )
        if same is not None and run_band_error(same, quantities, reference) is not None:
            band_err = run_band_error(same, quantities, reference)
            errors = {q: QuantityErrors.of(same, q) for q in quantities}
            label = same.label
            reason += f" (the study has it: band error {band_err:.1e})"
        else:
            band_err, errors, verified, label = None, {}, False, _label(mesh)
            reason += " (not a run of the study: its error is unknown)"
    statement = (
        f"The 3D reference runs {label}"
        + (
            f": its error on the frequencies the load excites is at most {band_err:.1e} "
            f"(the study's bound on the bare tube, "
            + ", ".join(f"first {q} {e.error:+.1e}" for q, e in errors.items())
            + ")"
            if band_err is not None
            else ", its error unknown"
        )
        + ". "
        + part.statement
    )
    return mesh, FullOrderReference(
        case=case,
        mesh=dict(vars(mesh)),
        label=label,
        source="converge",
        verified=verified,
        band_error=band_err,
        errors=errors,
        quantities=quantities,
        tolerance=choice.tolerance,
        required=choice.required,
        floor=floor,
        meets=choice.meets if not overrides else None,
        overrides=overrides,
        participation=part,
        reason=reason,
        statement=statement,
        study=study.json_file,
    )


def _label(mesh) -> str:
    return f"3D P{mesh.degree} {mesh.cell_type}, {mesh.elements_around}x{mesh.elements_along}x{mesh.elements_through}"
