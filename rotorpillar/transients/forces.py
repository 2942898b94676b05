"""A run's internal forces, stresses and shaft demand: the fields added to each transient.

``with_forces(scene, run, ...)`` takes a ``ModelRun`` (rotorpillar.transients.model_run)
and returns it with

- in its JSON: ``max_abs.base_moment`` (N m), ``max_abs.base_shear`` (N),
  ``max_abs.base_stress`` (Pa: |M| c / I + N / A at the base, compression),
  ``max_abs.shaft_deflection`` (m, radial) and ``max_abs.bearing_force``
  (N), for the 3D model ``max_abs.von_mises`` (Pa); and the block
  ``internal_forces`` (``InternalForcesSummary``, below: envelopes
  along the height, base reactions, the shaft's demand, the ROM's modes and
  truncation check, the 3D von Mises peaks and its XDMF file);
- in its series (NPZ, CSV): ``base_moment``, ``base_shear``, ``base_axial``,
  ``base_stress``, ``bearing_force``; in the NPZ also ``section_heights``,
  ``section_moment`` and ``section_shear`` (time x height).

Per model:
- modal (the ROM): modal superposition of the modes' section resultants,
  with at least as many modes as the base moment needs for 1 % over the
  run's band (``reduced.internal_forces.force_truncation``) and as carry
  90 % of the machine's mass along X (tube, gondola, the rotor whole: EN
  1998-1 4.3.3.3.1(3), ``reduced.participation.force_modes``; all the
  candidates, warned of, when they carry less), recorded in
  ``internal_forces.mass``; when that is more than the run kept, the forces
  come from a second run of the case with that many modes (the tip's
  answers stay the first run's);
- beam: the element end forces of every degree of freedom (exact for the
  full-order beam);
- fem3d: the section resultants and the von Mises field the run's observer
  (rotorpillar.fem3d.stress.StressRecovery) recovered at its output times;
- paper: Eq. 4's tip mass on a spring has no sections: the shaft's demand
  only, the section forces null.

N(z) is static (self-weight, gondola, rotor under g) plus, in the reduced
models, the rotor's vertical shaft force -c2 d_y (their pillar is rigid
axially); the 3D model carries its own dynamic axial force.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import numpy as np

from ..fem3d.stress import VonMisesSummary
from ..records import Record, replace
from ..reduced.foundation import FoundationStiffness, foundation_stiffness
from ..reduced.internal_forces import (
    STANDARD_GRAVITY,
    CanStress,
    ForceTruncation,
    UnitLoads,
    can_stresses,
    cantilever_tip_statics,
    extreme_fibre_stress,
    force_truncation,
    hermite_peak,
    modal_damping,
    superpose,
    tip_statics_of_beam,
    tower_axial_force,
    tower_static_resultants,
)
from ..reduced.models import BeamModelInfo
from ..reduced.participation import ForceModes, force_modes, pillar_mass_fractions
from ..reduced.reactions import NOT_COMPUTED, DesignReactions, design_reactions
from ..reduced.tower import base_section, tower_mass


class BaseReactions(Record):
    """What the clamp carries, peaks over the run (the foundation designer's loads)."""

    moment: float
    """largest |M(0, t)| (N*m)"""
    moment_time: float
    """when (s)"""
    shear: float
    """largest |V(0, t)| (N)"""
    shear_time: float
    """when (s)"""
    axial_min: float
    """smallest N(0, t), compression positive (N)"""
    axial_max: float
    """largest N(0, t) (N)"""
    stress: float
    """largest extreme-fibre meridional stress |M| c / I + N / A at the base, compression (Pa)"""
    stress_time: float
    """when (s)"""
    axial_share: float
    """N / A over that stress at that instant: the share of the axial force (EN 1993-1-6's C_x) (-)"""


class ShaftDemand(Record):
    """The shaft's deflection and force, peaks over the run."""

    deflection: float
    """largest radial shaft deflection sqrt(d_x**2 + d_y**2) (m)"""
    deflection_time: float
    """when (s)"""
    spring_force: float
    """largest c2 |d| (N): what the shaft spring carries"""
    bearing_force: float
    """largest |c2 d + b2 v_r| (N): the spring and the damper b2 together, v_r the
    rotor centre's velocity the model's damper acts on (relative to the ground);
    the demand of the force check (the larger: b2 Omega matters beside c2 here)"""
    bearing_force_time: float
    """when (s)"""
    sampled: bool
    """True: peaks over the output samples (velocities by central differences where
    the model gives none); False: from the model's own rates"""


class FoundationResponse(Record):
    """What the foundation's springs carry over a run, and how far the base turns."""

    kind: str
    """the foundation's kind: springs or footing"""
    horizontal_force: float
    """largest |K_H u + K_HR theta| (N)"""
    horizontal_force_time: float
    """when (s)"""
    moment: float
    """largest |K_HR u + K_R theta| (N*m)"""
    moment_time: float
    """when (s)"""
    rotation: float
    """largest |theta|, the base's rotation (rad); against foundation.rotation_limit"""
    rotation_time: float
    """when (s)"""
    displacement: float
    """largest |u|, the base's horizontal displacement relative to the ground (m)"""
    rotation_limit: float | None
    """the scene's serviceability limit on the rotation (rad); None: not stated"""
    springs: FoundationStiffness
    """the springs (at the tube's base)"""


class InternalForcesSummary(Record):
    """The ``internal_forces`` block of a transient's JSON (SI units)."""

    model: str
    """"modal", "beam", "fem3d\""""
    method: str
    """how the section forces were obtained, in words"""
    heights: tuple[float, ...]
    """section heights, base first (m)"""
    moment_envelope: tuple[float, ...]
    """max_t |M(z, t)| at each height (N*m)"""
    shear_envelope: tuple[float, ...]
    """max_t |V(z, t)| at each height (N)"""
    axial_static: tuple[float, ...]
    """N(z) of self-weight, gondola and rotor, compression positive (N)"""
    base: BaseReactions
    shaft: ShaftDemand
    modes: int | None = None
    """the modal ROM: modes the forces superpose"""
    modes_in_run: int | None = None
    """the modal ROM: modes of the case's run (its band)"""
    truncation: ForceTruncation | None = None
    """the modal ROM: the modes the section forces need (rotorpillar.reduced.internal_forces)"""
    mass: ForceModes | None = None
    """the modal ROM: the share of the mass its modes carry along the excitation, and why
    ``modes`` (rotorpillar.reduced.participation: at least 90 %, EN 1998-1 4.3.3.3.1)"""
    von_mises: VonMisesSummary | None = None
    """the 3D model: its von Mises field's peaks"""
    stress_field: str | None = None
    """the 3D model: the XDMF time series (file name, beside the JSON), or None"""
    note: str = ""
    cans: tuple[CanStress, ...] | None = None
    """a tower of cans: each can's largest meridional stress, where and when (EN 1993-1-6 per can)"""
    foundation: FoundationResponse | None = None
    """on a flexible foundation: the springs' forces and the base's rotation"""
    design: DesignReactions | None = None
    """the foundation's design reactions: each base extreme with the others at its instant"""


#: the design reactions a model does not compute, where not the planar models' (reduced.reactions)
_NOT_COMPUTED = {
    "fem3d": "torsion about the pillar's axis, the shear across the rotor's plane and the moment "
    "about X: not computed (the section recovery, rotorpillar.fem3d.sections, takes the shear along X, "
    "the moment about Y and the axial force only)"
}

#: the series each run gains (CSV and NPZ)
FORCE_SERIES = ("base_moment", "base_shear", "base_axial", "base_stress", "bearing_force")


def top_mass(scene: Scene) -> float:
    """What the tube's top carries under gravity: gondola and rotor (kg)."""
    return scene.gondola.mass + scene.rotor.mass


# --------------------------------------------------------------------------
# The shaft


def shaft_demand(scene: Scene, t, dx, dy, vx, vy, sampled: bool) -> tuple[ShaftDemand, np.ndarray]:
    """Peaks of the radial shaft deflection and of the shaft's force, and the force's history (N)."""
    c2, b2 = scene.shaft.stiffness, scene.shaft.damping
    radial = np.hypot(dx, dy)
    force = np.hypot(c2 * dx + b2 * vx, c2 * dy + b2 * vy)
    i, j = int(np.argmax(radial)), int(np.argmax(force))
    return ShaftDemand(
        float(radial[i]), float(t[i]), float(c2 * radial[i]), float(force[j]), float(t[j]), sampled
    ), force


# --------------------------------------------------------------------------
# Assembling the fields


def _summarise(
    scene: Scene,
    model: str,
    method: str,
    t,
    heights,
    moment,
    shear,
    axial,
    moment_rate,
    shaft: ShaftDemand,
    base_motion=None,
    **extra,
) -> tuple[InternalForcesSummary, dict]:
    """The JSON block and the series of section forces (n_t, n_z) at heights (m);
    ``base_motion`` = (u, theta) of the base on a flexible foundation, each (n_t,) (m, rad)."""
    sec = base_section(scene.pillar)
    i0 = int(np.argmin(np.abs(heights)))
    M0, V0, N0 = moment[:, i0], shear[:, i0], axial[:, i0]
    stress = extreme_fibre_stress(M0, N0, sec)
    if moment_rate is not None:
        m_peak, m_time = hermite_peak(t, M0, moment_rate)
    else:
        k = int(np.argmax(np.abs(M0)))
        m_peak, m_time = float(abs(M0[k])), float(t[k])
    s_peak_m = float(extreme_fibre_stress(m_peak, np.interp(m_time, t, N0), sec))
    k = int(np.argmax(stress))
    s_peak, s_time = (s_peak_m, m_time) if s_peak_m >= stress[k] else (float(stress[k]), float(t[k]))
    n_at = float(np.interp(s_time, t, N0))
    v = int(np.argmax(np.abs(V0)))
    base = BaseReactions(
        float(m_peak),
        float(m_time),
        float(abs(V0[v])),
        float(t[v]),
        float(N0.min()),
        float(N0.max()),
        float(s_peak),
        float(s_time),
        n_at / sec.area / s_peak,
    )
    static = tower_axial_force(scene.pillar, heights, top_mass(scene))
    if scene.pillar.cans:
        extra["cans"] = can_stresses(scene.pillar, t, heights, moment, axial)
    foundation, motion = _foundation_response(scene, t, base_motion)
    if foundation is not None:
        extra["foundation"] = foundation
    summary = InternalForcesSummary(
        model=model,
        method=method,
        heights=tuple(map(float, heights)),
        moment_envelope=tuple(map(float, np.max(np.abs(moment), axis=0))),
        shear_envelope=tuple(map(float, np.max(np.abs(shear), axis=0))),
        axial_static=tuple(map(float, static)),
        base=base,
        shaft=shaft,
        design=design_reactions(t, M0, V0, N0, (float(m_peak), float(m_time)), _NOT_COMPUTED.get(model, NOT_COMPUTED)),
        **extra,
    )
    series = {
        "base_moment": M0,
        "base_shear": V0,
        "base_axial": N0,
        "base_stress": stress,
        "section_heights": np.asarray(heights, float),
        "section_moment": moment,
        "section_shear": shear,
        **motion,
    }
    return summary, series


def _foundation_response(scene: Scene, t, base_motion) -> tuple[FoundationResponse | None, dict]:
    """The springs' forces and the base's rotation over the run (None on a clamp), and their series."""
    springs = foundation_stiffness(scene.foundation)
    if springs is None or base_motion is None:
        return None, {}
    u, theta = (np.asarray(a, dtype=float) for a in base_motion)
    force = springs.horizontal * u + springs.coupling * theta
    moment = springs.coupling * u + springs.rocking * theta
    i, j, k = (int(np.argmax(np.abs(a))) for a in (force, moment, theta))
    response = FoundationResponse(
        kind=springs.kind,
        horizontal_force=float(abs(force[i])),
        horizontal_force_time=float(t[i]),
        moment=float(abs(moment[j])),
        moment_time=float(t[j]),
        rotation=float(abs(theta[k])),
        rotation_time=float(t[k]),
        displacement=float(np.max(np.abs(u))),
        rotation_limit=scene.foundation.rotation_limit,
        springs=springs,
    )
    return response, {"base_displacement": u, "base_rotation": theta, "foundation_moment": moment}


def _attach(run, summary: InternalForcesSummary | None, series: dict, force, extra_max: dict):
    """The run with its new JSON fields and series."""
    data = dict(run.data)
    ma = dict(run.record.max_abs or {})
    base = summary.base if summary is not None else None
    ma.update(
        base_moment=None if base is None else base.moment,
        base_shear=None if base is None else base.shear,
        base_stress=None if base is None else base.stress,
        **extra_max,
    )
    warnings = tuple(run.record.warnings)
    if summary is not None and summary.mass is not None and summary.mass.modes_for_mass is None:
        warnings += (f"section forces: {summary.mass.reason}",)
    record = replace(run.record, max_abs=ma, internal_forces=summary, warnings=warnings)
    t = np.asarray(data["t"], dtype=float)
    for key, values in series.items():
        data[key] = values
    data["bearing_force"] = np.asarray(force, dtype=float)[: len(t)]
    return replace(run, record=record, data=data)


def _shaft_of_series(scene: Scene, data: dict, v_rotor=None) -> tuple[ShaftDemand, np.ndarray]:
    t = np.asarray(data["t"], dtype=float)
    e = scene.rotor.eccentricity
    dx = np.asarray(data["shaft_deflection_x"], dtype=float)
    dy = (
        np.asarray(data["shaft_deflection_y"], dtype=float)
        if "shaft_deflection_y" in data
        else np.asarray(data["rotor_y"], dtype=float) - e * np.sin(np.asarray(data["theta"], dtype=float))
    )
    if v_rotor is None:
        vx = np.gradient(np.asarray(data["rotor_x"], dtype=float), t)
        vy = np.gradient(np.asarray(data["rotor_y"], dtype=float), t)
    else:
        vx, vy = v_rotor
    return shaft_demand(scene, t, dx, dy, vx, vy, sampled=v_rotor is None)


# --------------------------------------------------------------------------
# The reduced models


def with_reduced_forces(scene: Scene, run, res, integrator, pillar_modes, motion, progress=None):
    """paper, modal, beam: see the module text (``res`` the CaseResult of the run)."""
    m = res.model
    v = np.asarray(run.data["v"], dtype=float)
    shaft, force = _shaft_of_series(scene, run.data, (v[:, m.rotor_x], v[:, m.nx]))
    extra_max = {"shaft_deflection": shaft.deflection, "bearing_force": shaft.bearing_force}
    if run.model == "beam":
        summary, series = _beam_forces(scene, run, res, shaft)
    elif run.model == "modal" and m.pillar_modes is not None:  # the spatial ROM's: not yet (its warning)
        summary, series = _modal_forces(scene, run, res, integrator, pillar_modes, motion, shaft, progress)
    else:
        summary, series = None, {}
    return _attach(run, summary, series, force, extra_max)


def _vertical_axial(scene: Scene, data, heights) -> np.ndarray:
    """N(z, t) of the reduced models: static, less the shaft's vertical pull c2 d_y (N)."""
    e, c2 = scene.rotor.eccentricity, scene.shaft.stiffness
    dy = np.asarray(data["rotor_y"], dtype=float) - e * np.sin(np.asarray(data["theta"], dtype=float))
    static = tower_axial_force(scene.pillar, heights, top_mass(scene))
    return static[None, :] - c2 * dy[:, None]


def _beam_forces(scene: Scene, run, res, shaft):
    from ..reduced.beam_fe import first_free_dof, section_forces
    from ..reduced.foundation import base_springs
    from ..reduced.pillar_modes import beam_line

    info = res.model_info
    assert isinstance(info, BeamModelInfo)  # the beam's forces are of a beam's run
    n, theory = info.elements, info.theory
    line = beam_line(scene.pillar, n)
    f = first_free_dof(base_springs(scene.foundation))
    nb = 2 * (n + 1) - f
    q, v = np.asarray(run.data["q"], dtype=float), np.asarray(run.data["v"], dtype=float)
    pad = lambda a: np.vstack([np.zeros((f, a.shape[0])), a[:, :nb].T])
    shear, moment = (x.T for x in section_forces(line, n, theory, pad(q)))
    _, rate = section_forces(line, n, theory, pad(v))
    heights = line.nodes
    axial = _vertical_axial(scene, run.data, heights)
    base_motion = (q[:, 0], q[:, 1]) if f == 0 else None
    return _summarise(
        scene,
        "beam",
        f"element end forces K_e u_e of the full-order {theory} beam "
        f"({n} elements), mean of the two elements at an inner node",
        run.data["t"],
        heights,
        moment,
        shear,
        axial,
        rate[0],
        shaft,
        base_motion,
    )


def _modal_forces(scene: Scene, run, res, integrator, pillar_modes, motion, shaft, progress):
    from ..reduced.band import forcing_top
    from ..reduced.foundation import base_springs
    from ..reduced.models import candidate_modes
    from ..scene import with_values
    from .cases import run_case

    candidates = candidate_modes(scene, pillar_modes)
    if not candidates.has_resultants:
        return None, {}
    sec = base_section(scene.pillar)
    base = base_springs(scene.foundation)
    base_statics = None
    statics: dict[str, float] | UnitLoads
    if scene.pillar.is_uniform and base is None:
        from ..reduced.pillar_modes import beam_properties

        bp = beam_properties(scene.pillar)
        statics = cantilever_tip_statics(
            bp.youngs_modulus,
            bp.second_moment,
            bp.shear_coefficient * bp.shear_modulus * bp.area,
            bp.length,
            sec.mass_per_length,
            scene.gondola.mass,
        )
    else:
        # a tower's or a foundation's static tip: the fine beam's own solve (rotorpillar.reduced.internal_forces)
        mm = scene.modal_model
        statics = tip_statics_of_beam(scene.pillar, scene.gondola.mass, mm.theory, max(mm.elements, 200), base)
        z0 = np.asarray(candidates.section_heights, dtype=float)[:1]
        base_statics = tower_static_resultants(scene.pillar, z0, scene.gondola.mass)
    band = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, run.case, motion)
    trunc = force_truncation(
        candidates,
        band,
        modal_damping(candidates, scene.pillar.damping),
        scene.pillar.height,
        sec.mass_per_length,
        scene.gondola.mass,
        statics,
        base_statics=base_statics,
    )
    k_run = res.model.pillar_modes.count
    total = tower_mass(scene.pillar) + top_mass(scene)
    fractions = pillar_mass_fractions(candidates.participation, candidates.modal_mass, scene.rotor.mass, total)
    chosen = force_modes(fractions, k_run, trunc.modes_for_forces, total)
    k = chosen.modes
    data = run.data
    if k > k_run:
        if progress:
            progress(
                f"section forces: the base moment needs {k} modes (the run kept {k_run}); the case again with them"
            )
        # the planar ROM's variants: only its runs get them (the spatial ROM's have neither)
        quiet = with_values(scene, {"simulate.threshold": False, "modal_model.planes": "planar"})
        from .case_summary import series

        again = run_case(
            quiet, run.case, "modal", integrator, k, truncation=False, motion=motion, pillar_modes=pillar_modes
        )
        data = series(again.run, scene.simulate.samples)
        pm = again.model.pillar_modes
    else:
        pm = res.model.pillar_modes
    if pm is None:
        raise ValueError("the modal model runs on pillar modes: it has none")
    q, v = np.asarray(data["q"], dtype=float), np.asarray(data["v"], dtype=float)
    t = np.asarray(run.data["t"], dtype=float)
    on = lambda a: np.column_stack([np.interp(t, data["t"], a[:, j]) for j in range(a.shape[1])])
    eta, rate = on(q[:, :k]), on(v[:, :k])
    if pm.moment_shapes is None or pm.shear_shapes is None:
        raise ValueError("the modal model's pillar modes carry no section resultants")
    moment, shear = superpose(eta, pm.moment_shapes), superpose(eta, pm.shear_shapes)
    heights = np.asarray(pm.section_heights, dtype=float)
    i0 = int(np.argmin(np.abs(heights)))
    axial = _vertical_axial(scene, run.data, heights)
    base_motion = None
    if pm.base_rotation is not None and pm.shapes is not None:
        base_motion = (eta @ np.asarray(pm.shapes)[0, :k], eta @ np.asarray(pm.base_rotation)[:k])
    method = (
        f"modal superposition of {k} modes' section resultants ({pm.source}); for "
        f"{100 * trunc.tolerance:g} % over the band the base moment needs "
        f"{trunc.modes_needed_base_moment or f'more than {trunc.modes_available}'}, the tip "
        f"{trunc.modes_needed_tip}; the base shear's error with {k}: "
        f"{100 * trunc.rows[k - 1].base_shear:.2g} %"
    )
    note = (
        ""
        if k == k_run
        else f"the case's run kept {k_run} modes (its band); the section forces come from the same "
        f"case run again with {k}"
    )
    return _summarise(
        scene,
        "modal",
        method,
        t,
        heights,
        moment,
        shear,
        axial,
        rate @ np.asarray(pm.moment_shapes)[i0],
        shaft,
        base_motion,
        modes=k,
        modes_in_run=k_run,
        truncation=trunc,
        note=note,
        mass=chosen,
    )


# --------------------------------------------------------------------------
# The 3D model


def stress_observer(scene: Scene, duration: float, field_dir, stem: str):
    """The observer a 3D run hands its states to (rotorpillar.fem3d.stress)."""
    from pathlib import Path

    from ..fem3d.stress import StressRecovery

    path = None if field_dir is None else Path(field_dir) / f"{stem}.xdmf"
    return StressRecovery(scene.pillar, top_mass(scene), float(duration), path)


def with_fem3d_forces(scene: Scene, run, recovered, heights, plate=None):
    """fem3d: ``recovered`` = StressRecovery.finish()'s (t, resultants, von Mises, xdmf path),
    ``heights`` its cuts' (m), ``plate`` its base plate's (U_x, Theta_y) per output time on a
    flexible foundation (StressRecovery.base_motion)."""
    from pathlib import Path

    t, res, vm, path = recovered
    base_motion = None if not plate else (np.asarray(plate)[:, 0], np.asarray(plate)[:, 1])
    shaft, force = _shaft_of_series(scene, run.data)
    heights = np.asarray(heights, dtype=float)
    summary, series = _summarise(
        scene,
        "fem3d",
        "nodal forces of the elements beside each element-layer cut, on the rigid "
        "sections' motions (rotorpillar.fem3d.sections; mean of the two sides), at every output time; "
        f"g = {STANDARD_GRAVITY} for the static axial force",
        t,
        heights,
        res[:, :, 1],
        res[:, :, 0],
        res[:, :, 2],
        None,
        shaft,
        base_motion,
        von_mises=vm,
        stress_field=None if path is None else Path(path).name,
    )
    extra_max = {"shaft_deflection": shaft.deflection, "bearing_force": shaft.bearing_force, "von_mises": vm.peak.value}
    return _attach(run, summary, series, force, extra_max)
