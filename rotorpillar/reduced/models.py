"""The models of a scene: the paper's Eq. 4 with the scene's tip
reduction, or the modal model on pillar modes, and the scene's ground motion.

The modal model picks its modes from candidates: those the caller passes in
(the chain's, rotorpillar.chain: the model the convergence study chose, its 3D
modes computed by rotorpillar.fem3d — this package never runs the 3D model),
or, when none are passed and ``modal_model.source = "beam"``, the 1D beam's,
computed here.
"""

from __future__ import annotations

from ..errors import InputError
from ..provenance import Record
from ..scene import Scene
from .beam_model import beam_model
from .excitation import GroundMotion, load_record, paper_pulse
from .foundation import base_springs
from .pillar_modes import PillarModes, beam_pillar_modes, modes_in_band
from .reduction import TipReductionUsed, pillar_closed_forms, resolve_reduction
from .rotor_models import RotorStructure, modal_model, paper_model
from .system import ReducedSystem, reduced_system

#: the most pillar modes a modal model picks from
MAX_CANDIDATE_MODES = 12


class PaperModelInfo(Record, tag_field="kind", tag="paper"):
    """How the paper's Eq. 4 model was built: its tip reduction."""

    reduction: TipReductionUsed


class BeamModelInfo(Record, tag_field="kind", tag="beam"):
    """How the full-order 1D beam was built."""

    elements: int
    """finite elements along the pillar (-)"""
    theory: str
    """"euler_bernoulli" or "timoshenko\""""
    dofs: int
    """unknowns of the rotor-beam model (-)"""
    element_source: str
    """the scene key that set ``elements``"""


class ModalModelInfo(Record, tag_field="kind", tag="modal"):
    """How the modal model chose its pillar modes."""

    modes: int
    """pillar modes kept (-)"""
    band_top: float | None
    """the band the modes were chosen below (rad/s); None when the count was stated"""
    candidate_omega: tuple[float, ...]
    """the candidates' natural frequencies (rad/s)"""
    mode_choice: str
    """why that many, in words"""


#: How a reduced model was built, by model (``build_model``; tagged by ``kind``).
ModelInfo = PaperModelInfo | BeamModelInfo | ModalModelInfo


def paper_system(scene: Scene) -> tuple[ReducedSystem, TipReductionUsed]:
    """The paper's ReducedSystem with the scene's tip reduction (stated, or the paper's Eq. 2)."""
    red = resolve_reduction(scene, pillar_closed_forms(scene.pillar, base_springs(scene.foundation)))
    return reduced_system(
        scene.rotor, scene.shaft, scene.gondola.mass, scene.pillar.damping, red.tip_mass, red.tip_stiffness
    ), red


def beam_candidates(scene: Scene, count: int = MAX_CANDIDATE_MODES) -> PillarModes:
    """The first ``count`` pillar modes of the scene's 1D beam ([modal_model])."""
    m = scene.modal_model
    return beam_pillar_modes(
        scene.pillar, scene.gondola.mass, count, m.theory, m.elements, m.gondola_inertia, base_springs(scene.foundation)
    )


def candidate_modes(scene: Scene, pillar_modes: PillarModes | None = None) -> PillarModes:
    """The modes a modal model picks from: ``pillar_modes`` when given, else
    the beam's; the 3D source must be given (InputError otherwise)."""
    if pillar_modes is not None:
        return pillar_modes
    if scene.modal_model.source == "beam":
        return beam_candidates(scene)
    raise InputError(
        f'modal_model.source = "{scene.modal_model.source}": the modal model needs the '
        "chain's pillar modes passed in (pillar_modes=, from "
        "rotorpillar.chain.resolve(scene, out_dir).modes)"
    )


def build_model(
    scene: Scene,
    which: str,
    band_top: float | None = None,
    modes: int | None = None,
    pillar_modes: PillarModes | None = None,
) -> tuple[RotorStructure, ModelInfo]:
    """(model, info) for "paper", "modal" or "beam"; the modal model keeps ``modes``
    modes, or those below ``band_top`` (rad/s), of ``candidate_modes``; the
    beam is the full-order 1D beam ([full_order] beam_elements, [modal_model]
    theory and gondola inertia).  "fem3d" is not built here (rotorpillar.fem3d)."""
    if which == "paper":
        s, red = paper_system(scene)
        return paper_model(s), PaperModelInfo(red)
    if which == "beam":
        mm = scene.modal_model
        n = scene.full_order.beam_elements or mm.elements
        model = beam_model(
            scene.pillar,
            scene.gondola.mass,
            scene.rotor,
            scene.shaft,
            n,
            mm.theory,
            mm.gondola_inertia,
            base_springs(scene.foundation),
        )
        source = "full_order.beam_elements" if scene.full_order.beam_elements else "modal_model.elements"
        return model, BeamModelInfo(n, mm.theory, model.n, source)
    if which != "modal":
        raise InputError(f"model {which!r}: build_model makes paper, modal or beam")
    candidates = candidate_modes(scene, pillar_modes)
    k = modes or scene.modal_model.modes or modes_in_band(candidates.omega, band_top or 0.0)
    k = min(k, candidates.count)
    pm = candidates.truncate(k)
    r, sh = scene.rotor, scene.shaft
    model = modal_model(pm, r.mass, r.inertia, r.eccentricity, sh.stiffness, sh.damping, scene.pillar.damping)
    choice = (
        "stated (modal_model.modes)"
        if (modes or scene.modal_model.modes)
        else f"the pillar modes below {band_top:.4g} rad/s = band_factor x the highest forcing frequency"
    )
    return model, ModalModelInfo(k, band_top, tuple(map(float, candidates.omega)), choice)


def scene_motion(scene: Scene) -> GroundMotion:
    """The scene's [excitation] as a GroundMotion."""
    x = scene.excitation
    if x.kind == "paper":
        return paper_pulse(x.amplitude, x.frequency, x.start, x.duration)
    return load_record(x.record, x.record_units, x.record_scale, x.start, max_samples=scene.simulate.max_steps)
