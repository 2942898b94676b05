"""The 3D full order's mesh for a transient case: chosen for what the load excites.

How much each mode of the loaded tube takes part in a transient case's loads
(``load_participation``, first below).  A transient loads the pillar in a few
ways only: the ground's acceleration along x (the earthquake: -M r a_g, r the
rigid x translation of the tube and its top), and the rotor's shaft force on
the top plate along x and along the tube's axis z (the run-up; the earthquake
too, through the rotor's own inertia).  Mode j takes part in a load as much as
the load does work on it:

- base x: its effective mass L_j**2 / m_j with L_j = phi_j^T M r, as a
  share of the mass the base carries (tube and top);
- plate x, plate z: phi_j(plate)**2 / (m_j omega_j**2), its part of the
  plate's static compliance along x (the cantilever's H**3 / (3 E I)) or z
  (H / (E A)); over all modes they sum to the 3D model's own compliance.

Both are computed from the 3D modes of the loaded tube (modal.json's
``modes_with_top`` when it matches the scene, else ``modal_analysis(scene,
top=True)`` on the scene's [mesh], which resolves every mode of the band,
shell modes included), never assumed.  By the tube's symmetry the n = 2
ovalling pairs, torsion and the bending in y take no part (shares ~1e-20,
round-off), the axial modes only through plate z.

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
from ..chain.record import MeshValue
from ..converge.result import ModeSourceFloor, QuantityErrors
from ..records import Record, replace
from ..scene.sections import Mesh

if TYPE_CHECKING:
    from ..converge.result import ConvergenceRun, ConvergenceStudy, RunBrief
    from ..scene import Scene
import math
from typing import TYPE_CHECKING

import numpy as np

from ..fem3d.modal import ModeRow  # numpy-only: the 3D model's table of modes

if TYPE_CHECKING:
    from collections.abc import Sequence

    from ..scene import Scene


PARTICIPATION_FLOOR = 1e-6
"""A mode whose largest share of a case's loads is below this takes no part (-);
symmetry leaves the others at round-off, ~1e-20, and bending at 0.2 - 0.6."""
LOADS = {"earthquake": ("base_x", "plate_x"), "runup": ("plate_x", "plate_z")}
"""The loads of each case: the ground's acceleration along x, the shaft force on the plate."""
QUANTITY_OF: dict[tuple[str, int | None], str] = {("bending_x", 0): "bending", ("ovalling", 0): "ovalling"}
"""(kind, n_axial) of a loaded mode -> the study's frequency that bounds its error
(the study measures the first bending and the first n = 2 ovalling of the bare tube)."""


class ModeParticipation(Record):
    """One mode of the loaded tube and its part in a case's loads."""

    index: int
    kind: str
    """bending_x, bending_y, ovalling, torsion, axial, breathing or other"""
    n_circumferential: int | None
    n_axial: int | None
    omega: float
    """(rad/s)"""
    modal_mass: float
    """phi^T M phi of the normalised shape (kg)"""
    effective_mass_x: float | None
    """L_x**2 / m_j for a base acceleration along x (kg)"""
    shares: dict[str, float]
    """load -> share (-): base_x of the base's mass, plate_x / plate_z of the plate's
    static compliance (closed form: H**3 / (3 E I) along x, H / (E A) along z)"""
    in_band: bool
    participates: bool


class ParticipationTable(Record):
    """The loaded tube's modes and which of them a case's loads excite."""

    case: str
    loads: tuple[str, ...]
    band_top: float
    """the case's band: margin x its fastest forcing (rad/s)"""
    floor: float
    """share below which a mode takes no part (-)"""
    total_mass: float
    """the mass a base acceleration moves: tube and top (kg)"""
    source: str
    """modal.json (its loaded modes) or computed (modal_analysis on the scene's mesh)"""
    mesh: dict[str, MeshValue]
    """the mesh the modes were computed on"""
    modes: tuple[ModeParticipation, ...]
    participating: tuple[int, ...]
    """indices of the modes in the band that take part"""
    left_out: tuple[int, ...]
    """indices of the modes in the band that take no part"""
    quantities: tuple[str, ...]
    """the study's frequencies that bound the participating modes' errors"""
    uncovered: tuple[str, ...]
    """participating modes in the band no study frequency covers (their error is unbounded)"""
    statement: str


def participation_table(
    rows: Sequence[ModeRow],
    case: str,
    band_top: float,
    total_mass: float,
    compliance: tuple[float, float],
    *,
    source: str,
    mesh: dict,
    floor: float = PARTICIPATION_FLOOR,
) -> ParticipationTable:
    """Which modes the case's loads excite, from the loaded modes' table rows
    (``ModalResult.modes_table()`` or modal.json's ``modes_with_top``: omega, kind,
    modal_mass, participation, top_plate_motion); ``compliance``: the plate's static
    compliance along x and z that the plate shares are parts of (m/N)."""
    loads = LOADS[case]
    w = np.array([r.omega for r in rows], float)
    m = np.array([r.modal_mass for r in rows], float)
    plate = np.array([(r.top_plate_motion or (0.0,) * 6)[:3] for r in rows], float)
    Lx = np.array([(r.participation or (math.nan,) * 3)[0] for r in rows], float)
    stiff = np.maximum(m * w**2, 1e-300)
    shares = {
        "base_x": Lx**2 / m / total_mass,
        "plate_x": plate[:, 0] ** 2 / stiff / compliance[0],
        "plate_z": plate[:, 2] ** 2 / stiff / compliance[1],
    }
    if np.any(~np.isfinite(shares["base_x"])) and "base_x" in loads:
        raise ValueError("the loaded modes carry no participation (modal.json from before it?)")
    modes: list[ModeParticipation] = []
    part: list[int] = []
    left: list[int] = []
    for i, r in enumerate(rows):
        s = {k: float(shares[k][i]) for k in loads}
        inside = bool(w[i] <= band_top)
        takes = max(s.values()) >= floor
        modes.append(
            ModeParticipation(
                index=int(r.index),
                kind=r.kind,
                n_circumferential=r.n_circumferential,
                n_axial=r.n_axial,
                omega=float(w[i]),
                modal_mass=float(m[i]),
                effective_mass_x=None if not math.isfinite(Lx[i]) else float(Lx[i] ** 2 / m[i]),
                shares=s,
                in_band=inside,
                participates=bool(takes),
            )
        )
        if inside:
            (part if takes else left).append(i)
    quantities, uncovered = [], []
    for i in part:
        q = QUANTITY_OF.get((rows[i].kind, rows[i].n_axial))
        if q is None:
            uncovered.append(f"{rows[i].kind} at {w[i]:.2f} rad/s")
        elif q not in quantities:
            quantities.append(q)
    return ParticipationTable(
        case=case,
        loads=loads,
        band_top=float(band_top),
        floor=floor,
        total_mass=float(total_mass),
        source=source,
        mesh=dict(mesh),
        modes=tuple(modes),
        participating=tuple(part),
        left_out=tuple(left),
        quantities=tuple(quantities),
        uncovered=tuple(uncovered),
        statement=_participation_statement(case, modes, part, left, band_top, floor, uncovered),
    )


def _participation_statement(case, modes, part, left, band_top, floor, uncovered) -> str:
    def name(p):
        extra = f" n = {p.n_circumferential}" if p.kind == "ovalling" else ""
        return f"{p.kind}{extra} ({p.omega:.2f} rad/s)"

    loads = " and ".join(
        {
            "base_x": "the ground's acceleration along x",
            "plate_x": "the shaft force on the plate along x",
            "plate_z": "along the axis",
        }[k]
        for k in LOADS[case]
    )
    text = f"In the band up to {band_top:.1f} rad/s, {loads} excite " + (
        ", ".join(f"{name(modes[i])}, share {max(modes[i].shares.values()):.2g}" for i in part) or "no mode"
    )
    if left:
        worst = max(max(modes[i].shares.values()) for i in left)
        text += (
            "; " + ", ".join(name(modes[i]) for i in left) + f" take no part (largest share "
            f"{worst:.1e}, below {floor:g}: the tube's symmetry leaves them unloaded), so their "
            "frequencies, however coarse the mesh, do not enter the response"
        )
    if uncovered:
        text += (
            "; the study bounds no frequency of "
            + ", ".join(uncovered)
            + ": its error is not part of the reference's bound"
        )
    return text + "."


class LoadedModes(Record):
    """modal.json as far as the participation reads it: the loaded tube's modes."""

    modes_with_top: tuple[ModeRow, ...]
    """the modes of the tube with its top mass, lowest first"""
    mesh: dict[str, MeshValue] = {}
    """the mesh they were computed on (the chain's choice: not always the scene's [mesh])"""


def loaded_mode_rows(scene: Scene, study_dir: Path | None) -> tuple[list[ModeRow], str, dict]:
    """The loaded tube's mode table: from modal.json when it is this scene's modes
    and carries the participation, else computed on the scene's [mesh]."""
    from ..provenance import Provenance

    mine = scene.to_dict()
    found = None
    if study_dir is not None:
        path = Path(study_dir) / "modal.json"
        try:
            found, written = records.read(path, LoadedModes), records.read(path, Provenance)
        except (OSError, ValueError):  # missing or damaged: computed below
            found = None
    if found is not None and isinstance(written.scene, dict) and _same_loaded_modes(scene, written.scene, found):
        rows = list(found.modes_with_top)
        if rows and all(r.participation is not None for r in rows):
            return rows, "modal.json", dict(found.mesh) or dict(mine["mesh"])
    import json

    key = json.dumps(mine, sort_keys=True, default=str)
    if key not in _COMPUTED_ROWS:
        from ..fem3d import modal_analysis

        _COMPUTED_ROWS[key] = tuple(modal_analysis(scene, top=True).modes_table())
    return list(_COMPUTED_ROWS[key]), "computed", dict(vars(scene.mesh))


#: The sections modal.json's modes may depend on, the ones `run`'s key for modal takes
#: (commands.stage_keys: every section but the transients' and [drive] and [load]); the
#: drive and the load reach the modes only through the band's edge, see below.
MODES_READ = (
    "pillar",
    "foundation",
    "material",
    "gondola",
    "rotor",
    "shaft",
    "reduction",
    "mesh",
    "converge",
    "modal",
    "modal_model",
)


def _same_loaded_modes(scene: Scene, written: dict, found: LoadedModes) -> bool:
    """Whether modal.json's loaded modes, written for the scene ``written``, are the ones
    ``scene`` computes: the same sections the modes read and, where `modal` cuts them at the
    band's edge (``modal.n_modes = 0``), the same cut at this scene's edge (reduced.band.
    cut_stands, as `run`'s key for modal takes it: commands.run.modal_band).  A new stall
    torque whose band holds the same modes then reads modal.json, not a solve of its own
    (paper, drive.torque_at_zero x 1.1: 2 s of CPU in each 3D comparison)."""
    from ..reduced.band import cut_stands, excitation_band

    mine = scene.to_dict()
    if any(written.get(k) != mine[k] for k in MODES_READ):
        return False
    if scene.modal.n_modes or all(written.get(k) == mine[k] for k in ("drive", "load")):
        return True
    edge = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    return cut_stands([r.omega for r in found.modes_with_top], edge)


_COMPUTED_ROWS: dict[str, tuple[ModeRow, ...]] = {}
"""The scene (its JSON) -> the loaded tube's mode table computed for it in this process:
a comparison plans its 3D run three times (the duration, the study's mesh, the run), and
where modal.json is not this scene's (a rerun with another drive: the band's modes) each
plan solved the same modes again (paper: 2 s each)."""


def case_band_top(scene: Scene, case: str, motion=None) -> float:
    """The band a case excites: converge.margin x its fastest forcing (the drive's
    free speed; the ground motion's band for the earthquake) (rad/s)."""
    from ..reduced.band import excitation_band

    top = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    if case == "earthquake" and motion is not None:
        top = max(top, scene.converge.margin * motion.band())
    return float(top)


def load_participation(scene: Scene, case: str, study_dir: Path | None = None, motion=None) -> ParticipationTable:
    """The participation of the loaded tube's modes in ``case``."""
    from ..reduced.foundation import foundation_stiffness
    from ..reduced.pillar import section_of
    from ..reduced.tower import top_compliances, tower_mass

    rows, source, mesh = loaded_mode_rows(scene, study_dir)
    p = scene.pillar
    springs = foundation_stiffness(scene.foundation)
    if p.is_uniform and springs is None:
        sec = section_of(p)
        total = sec.mass_per_length * p.height + scene.gondola.mass
        compliance = (
            p.height**3 / (3 * p.youngs_modulus * sec.second_moment),
            p.height / (p.youngs_modulus * sec.area),
        )
    else:
        total = tower_mass(p) + scene.gondola.mass
        compliance = top_compliances(p, springs)
    return participation_table(
        rows, case, case_band_top(scene, case, motion), total, compliance, source=source, mesh=mesh
    )


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
    mesh: dict[str, MeshValue]
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

        result = replace(compute_in_process(case, scene.pillar, scene.foundation), wall_time=0.0)
        computed = run_record(case, case_key(case, scene.pillar, foundation=scene.foundation), result)
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
            f": its error bound on the frequencies the load excites is {band_err:.1e} "
            f"(the study's, on the bare tube, the reference's uncertainty included; its error against "
            "the reference: " + ", ".join(f"first {q} {e.error:+.1e}" for q, e in errors.items()) + ")"
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
