"""Which pillar model the chain uses: the convergence study's choice, or the scene's own mesh.

With ``modal_model.source = "auto"`` (the default) the model the study chose
for the scene's band (``out/<scene>/convergence.json``, when it was run for
this pillar, mesh ladder and band) feeds everything downstream:

- a 3D solid: the ROM's pillar modes are the SLEPc modes of that mesh, and
  `modal` runs it;
- a shell: the shell carries no top mass here, so the chain takes the
  cheapest 3D mesh of the study that meets the same tolerance (and says so);
- a beam (a band with no shell mode in it): the ROM's modes are that beam's,
  and `modal` runs the cheapest 3D mesh within the tolerance;
- the closed form (Eq. 1 within the tolerance: a slender tube): the ROM takes
  the Euler-Bernoulli beam, the closed form's own model, finely discretised.

Without a study on disk the stages use the scene's own ``[mesh]`` (source
"scene"): verified when the study's run cache holds that mesh and enough of
the ladder for a reference, else ``verified: false``.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import records
from ..scene import Mesh, Scene
from ..scene.tower import Foundation
from .record import PillarModel

if TYPE_CHECKING:
    from ..converge.result import ConvergenceRun, ConvergenceStudy, ReferenceValue, RunBrief, RunErrors

#: Scene keys a convergence study's runs depend on: the tube, the ladder's shape
#: (from [mesh]), the tolerance and limits (with the band's margin).  The band's top
#: (the drive's free speed, [drive] and [load]) enters the choice only through the
#: modes inside it (converge.selection.needed_quantities): the ladder solves the bare
#: tube's first bending and ovalling modes whatever the band, and the choice asks the
#: ones inside it.  A study run for another drive answers for this one when its band
#: holds the same modes (:func:`band_mismatch`).
STUDY_INPUTS = {
    "pillar": ("height", "outer_diameter", "inner_diameter", "youngs_modulus", "poisson_ratio", "density", "cans"),
    "foundation": None,
    "mesh": None,
    "converge": None,
}

#: Sections the band's top reads (reduced.band.excitation_band).
BAND_INPUTS = ("drive", "load")

#: The closed form's own model, for the ROM's modes when the study chose Eq. 1.
CLOSED_FORM_BEAM: dict[str, Any] = {"theory": "euler", "elements": 64}


@dataclass(frozen=True)
class Choice:
    """The chain's pillar models: the ROM's mode source and the 3D mesh `modal` runs."""

    rom: PillarModel
    """where the ROM's pillar modes come from"""
    solid: PillarModel
    """the 3D mesh of `modal` (the same as ``rom`` when the ROM takes 3D modes)"""

    @property
    def solid_mesh(self) -> Mesh:
        return solid_mesh_section(self.solid.mesh)


def solid_mesh_section(mesh: dict) -> Mesh:
    """The scene [mesh] section of a 3D model's discretisation."""
    names = {f.name for f in fields(Mesh)}
    return Mesh(**{k: v for k, v in mesh.items() if k in names})


def study_mismatch(scene: Scene, study_scene: dict) -> str | None:
    """The first scene key the study was run with a different value of, or None."""
    mine = scene.to_dict()
    # a key the study's scene predates (the cans, the foundation) stands at its default there
    defaults = {"pillar": {"cans": []}, "foundation": asdict(Foundation())}
    for section, keys in STUDY_INPUTS.items():
        a, b = mine.get(section) or {}, study_scene.get(section) or {}
        for k in keys or sorted(set(a) | set(b)):
            old = defaults.get(section, {})
            if _plain(a.get(k, old.get(k))) != _plain(b.get(k, old.get(k))):
                return f"{section}.{k}"
    return None


def run_for_another_drive(scene: Scene, study: ConvergenceStudy) -> bool:
    """The study's [drive] or [load] differs from the scene's (BAND_INPUTS)."""
    mine, theirs = scene.to_dict(), study.scene or {}
    return any(_plain(mine.get(k)) != _plain(theirs.get(k)) for k in BAND_INPUTS)


def band_mismatch(scene: Scene, study: ConvergenceStudy) -> str | None:
    """Why a study run for another drive or load does not answer for ``scene`` (None: it
    does): the scene's band holds other modes than the study's did."""
    from ..converge.selection import needed_quantities
    from ..reduced.band import excitation_band

    if not run_for_another_drive(scene, study):
        return None
    band = excitation_band(scene.drive, scene.load, scene.converge)
    now, then = needed_quantities(study.reference, band), list(study.selection.needed)
    if now == then:
        return None
    return (
        f"its band ({study.band.omega_max:.4g} rad/s) held {', '.join(then) or 'no mode'}; this scene's "
        f"({band.omega_max:.4g} rad/s) holds {', '.join(now) or 'no mode'}"
    )


def _plain(v: Any) -> Any:
    """A scene value as JSON reads it back (tuples as lists)."""
    return records.to_builtins(v)


def study_on_disk(scene: Scene, out_dir: Path):
    """(ConvergenceStudy or None, why): the study in ``out_dir`` when it was run for this scene."""
    from ..converge.result import ConvergenceStudy

    path = Path(out_dir) / "convergence.json"
    if not path.is_file():
        return None, f"no convergence study in {out_dir} (rotorpillar converge {scene.name})"
    try:
        study = records.read(path, ConvergenceStudy)
    except (OSError, ValueError) as exc:
        return None, f"{path} is unreadable ({exc}); run rotorpillar converge again"
    study = records.replace(study, json_file=str(path))
    key = study_mismatch(scene, study.scene or {})
    if key is not None:
        return None, (
            f"{path} was run for another {key.split('.')[0]} ({key} differs): not used; "
            f"run rotorpillar converge for this scene"
        )
    band = band_mismatch(scene, study)
    if band is not None:
        return None, f"{path} was run for another drive: {band}; not used; run rotorpillar converge for this scene"
    if run_for_another_drive(scene, study):
        return study, (
            f"the convergence study {path}, run for another drive: its band "
            f"({study.band.omega_max:.4g} rad/s) holds the same modes as this scene's "
            f"({', '.join(study.selection.needed) or 'none'}), so its choice stands"
        )
    return study, f"the convergence study {path}"


def _errors(run: RunErrors, ref_unc: dict[str, float]) -> dict[str, float]:
    """Per frequency: the run's error bound plus the reference's uncertainty (-)."""
    out = {}
    for q, u in ref_unc.items():
        b = run.error_bound(q)
        if b is not None:
            out[q] = float(b) + float(u)
    return out


def model_of_run(
    run: RunBrief, reference_uncertainty: dict[str, float], tolerance: float, note: str, study: str | None = None
) -> PillarModel:
    """A run the study chose (its brief: label, family, params, dofs, error bounds) as the
    chain's PillarModel."""
    return _model(run, "converge", True, tolerance, _errors(run, reference_uncertainty), note, study)


def _model(
    run: RunBrief,
    source: str,
    verified: bool,
    tolerance: float | None,
    errors: dict[str, float],
    note: str,
    study: str | None,
) -> PillarModel:
    from ..converge.ladder import FAMILIES

    kind = FAMILIES[run.family].model
    return PillarModel(
        kind, run.label, dict(run.params), int(run.dofs), source, verified, tolerance, errors, note, study
    )


def solid_families() -> list[str]:
    """The 3D families whose meshes resolve every frequency the study measures (not the
    bending-only family: `modal` shows the shell modes too)."""
    from ..converge.ladder import FAMILIES, QUANTITIES

    return [k for k, f in FAMILIES.items() if f.model == "solid" and set(QUANTITIES) <= set(f.quantities)]


def _solid_within(study: ConvergenceStudy, tolerance: float) -> RunBrief | None:
    """The cheapest 3D run of the study that meets the tolerance (its brief), or None."""
    from ..converge.selection import select_model

    return select_model(study.runs, study.reference, study.band, tolerance, families=solid_families()).chosen


@dataclass(frozen=True)
class SolidCase:
    """A 3D mesh as a case of the convergence ladder."""

    label: str
    family: str
    model: str
    """"solid\""""
    params: dict[str, int | float | str]
    """the mesh's keys as the ladder names a run's"""
    dofs: int
    """degrees of freedom, estimated from the mesh (-)"""


def scene_solid_run(scene: Scene) -> SolidCase:
    """The scene's own [mesh] as a case of the ladder."""
    return solid_run_of(scene.mesh)


def solid_run_of(m: Mesh) -> SolidCase:
    """A 3D mesh as a case of the ladder."""
    from ..converge.ladder import FAMILIES, Case, estimated_dofs

    family = f"solid_{'hex' if m.cell_type == 'hexahedron' else 'tet'}_p{m.degree}"
    params: dict[str, int | float | str] = {
        "elements_around": m.elements_around,
        "elements_along": m.elements_along,
        "elements_through": m.elements_through,
        "cell_type": m.cell_type,
        "degree": m.degree,
        "grading": m.grading,
    }
    case = Case(family, m.elements_around, tuple(sorted(params.items())))
    return SolidCase(case.label, family, FAMILIES[family].model, params, estimated_dofs(case))


def _same_mesh(run: ConvergenceRun, params: dict) -> bool:
    return all(run.params.get(k) == v for k, v in params.items())


def _scene_errors(
    runs: Iterable[ConvergenceRun], reference: Mapping[str, ReferenceValue], params: dict
) -> dict[str, float]:
    from ..converge.selection import reference_uncertainty

    ref_unc = reference_uncertainty(reference) if reference else {}
    for r in runs:
        if r.status == "ok" and r.model == "solid" and _same_mesh(r, params):
            return _errors(r, ref_unc)
    return {}


def _from_cache(scene: Scene, cache_dir: Path) -> tuple[dict[str, float], str]:
    """The scene mesh's errors from the study's run cache alone (nothing computed)."""
    from ..converge.ladder import study_cases
    from ..converge.runner import run_study
    from ..converge.study import analyse

    if not Path(cache_dir).is_dir():
        return {}, "no study's run cache"

    def not_cached(case, sc):
        raise RuntimeError("not in the cache")

    records = run_study(study_cases(scene), scene, Path(cache_dir), runner=not_cached, progress=False)
    if not any(r.cached for r in records):
        return {}, "no study's run cache"
    analysis = analyse(records, scene, scene.converge.tolerance)
    errs = _scene_errors(analysis.runs, analysis.reference, scene_solid_run(scene).params)
    return errs, f"the study's run cache {cache_dir}"


def _dolfinx_here() -> bool:
    import importlib.util

    return importlib.util.find_spec("dolfinx") is not None


def _beam_model(
    scene: Scene,
    source: str,
    note: str,
    theory: str,
    elements: int,
    errors: dict | None = None,
    tolerance=None,
    study=None,
    label=None,
) -> PillarModel:
    kind = "beam"
    return PillarModel(
        kind,
        label or f"beam {theory}, {elements} el.",
        {"theory": theory, "elements": elements},
        2 * elements,
        source,
        bool(errors),
        tolerance,
        errors or {},
        note,
        study,
    )


def from_scene(scene: Scene, cache_dir: Path, why: str) -> Choice:
    """No usable study: the scene's own [mesh], verified from the run cache where it can be."""
    if not _dolfinx_here():
        mm = scene.modal_model
        rom = _beam_model(
            scene,
            "scene",
            f"{why}; the 3D model (dolfinx) is not installed here, so "
            f"the ROM takes the {mm.theory} beam of [modal_model] (unverified)",
            mm.theory,
            mm.elements,
        )
        return Choice(rom, rom)
    run = scene_solid_run(scene)
    errors, where = _from_cache(scene, cache_dir)
    note = f"{why}; the stages use the scene's own [mesh], {run.label}: " + (
        f"its error from {where}" if errors else "unverified (no convergence study measured this mesh)"
    )
    pm = PillarModel(
        "solid",
        run.label,
        run.params,
        run.dofs,
        "scene",
        bool(errors),
        scene.converge.tolerance if errors else None,
        errors,
        note,
        None,
    )
    return Choice(pm, pm)


def from_study(scene: Scene, study: ConvergenceStudy) -> Choice:
    """The study's choice for the scene's band, made usable by the chain (see the module text)."""
    from ..converge.selection import reference_uncertainty

    sel, path, tol = study.selection, study.json_file, study.tolerance
    ref_unc = reference_uncertainty(study.reference)
    if sel.chosen is None:
        run = scene_solid_run(scene)
        errors = _scene_errors(study.runs, study.reference, run.params)
        pm = PillarModel(
            "solid",
            run.label,
            run.params,
            run.dofs,
            "scene",
            bool(errors),
            tol,
            errors,
            f"the convergence study found no model that meets {tol:g} on the band "
            f"({sel.reason}); the stages use the scene's own [mesh]",
            path,
        )
        return Choice(pm, pm)
    chosen = sel.chosen
    kind = chosen.model
    from ..reduced.band import excitation_band

    top = excitation_band(scene.drive, scene.load, scene.converge).omega_max
    if abs(top - study.band.omega_max) <= 1e-9 * top:
        band = f"the scene's band (up to {top:.1f} rad/s)"
    else:  # run for another drive (band_mismatch let it through: the same modes)
        band = (
            f"its band (up to {study.band.omega_max:.1f} rad/s, run for another drive; this scene's, "
            f"up to {top:.1f} rad/s, holds the same modes: {', '.join(sel.needed) or 'none'})"
        )
    why = f"the model the convergence study chose for {band} at tolerance {tol:g}: {sel.reason}"
    if kind == "solid":
        pm = _model(chosen, "converge", True, tol, _errors(chosen, ref_unc), why, path)
        return Choice(pm, pm)
    solid_run = _solid_within(study, tol)
    if solid_run is None:
        run = scene_solid_run(scene)
        solid = PillarModel(
            "solid",
            run.label,
            run.params,
            run.dofs,
            "scene",
            False,
            None,
            {},
            "no 3D mesh of the study meets the tolerance: the scene's own [mesh]",
            path,
        )
    else:
        solid = _model(
            solid_run,
            "converge",
            True,
            tol,
            _errors(solid_run, ref_unc),
            f"the cheapest 3D mesh of the study within {tol:g} (the study's choice, {chosen.label}, is not a 3D model)",
            path,
        )
    if kind == "beam":
        p = chosen.params
        rom = _beam_model(
            scene,
            "converge",
            why,
            str(p["theory"]),
            int(p["elements"]),
            _errors(chosen, ref_unc),
            tol,
            path,
            chosen.label,
        )
        return Choice(rom, solid)
    if kind == "closed_form":
        rom = PillarModel(
            "closed_form",
            chosen.label,
            dict(CLOSED_FORM_BEAM),
            2 * CLOSED_FORM_BEAM["elements"],
            "converge",
            True,
            tol,
            _errors(chosen, ref_unc),
            why + "; its modes for the ROM come from the Euler-Bernoulli beam (the "
            f"closed form's own model) with {CLOSED_FORM_BEAM['elements']} elements",
            path,
        )
        return Choice(rom, solid)
    # a shell: no top mass in the shell model here, so the 3D mesh within the tolerance serves
    note = (
        why + f"; the shell model carries no top mass here, so the chain uses {solid.label}, "
        "the cheapest 3D mesh within the same tolerance"
    )
    rom = PillarModel(
        solid.kind,
        solid.label,
        solid.mesh,
        solid.dofs,
        solid.source,
        solid.verified,
        solid.tolerance,
        solid.errors,
        note,
        path,
    )
    return Choice(rom, rom)


def choose(scene: Scene, out_dir: Path | None, cache_dir: Path | None = None) -> Choice:
    """The chain's pillar models for a scene whose results go to ``out_dir``.

    ``modal_model.source`` "beam" or "fem3d" state the mode source outright
    (the 3D modes then on the scene's [mesh]); "auto" takes the study's choice
    (``out_dir`` None: no study, the scene's own model).
    """
    if out_dir is None:
        out_dir = cache_dir = Path("/nonexistent/rotorpillar")
    out_dir = Path(out_dir)
    cache_dir = out_dir / "cache" if cache_dir is None else Path(cache_dir)
    src = scene.modal_model.source
    if src == "beam":
        mm = scene.modal_model
        rom = _beam_model(
            scene,
            "scene",
            f'modal_model.source = "beam": the {mm.theory} beam of [modal_model], as the scene states',
            mm.theory,
            mm.elements,
        )
        solid = from_scene(scene, cache_dir, 'modal_model.source = "beam"').solid
        return Choice(rom, solid)
    if src == "fem3d":
        return from_scene(scene, cache_dir, 'modal_model.source = "fem3d" (the scene\'s [mesh])')
    study, why = study_on_disk(scene, out_dir)
    if study is None:
        return from_scene(scene, cache_dir, why)
    return from_study(scene, study)
