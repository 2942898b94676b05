"""The typed records of one model's run of a case: the JSON fields of
``simulate_<case>_<model>.json`` (the provenance is written beside them).

- ``PaperRun``, ``ModalRun``, ``BeamRun`` (a ``ReducedRun``: rotorpillar.transients.cases):
  the case's ``CaseSummary``, then what the model adds;
- ``Fem3dRun``: the 3D full order (rotorpillar.fem3d.full_order): its own outcome,
  the capture read through the chain's ROM, and its plan (``Fem3dPlan``).

A ``RunRecord`` is any of them, told apart by its ``model`` (the union's tag).
Both kinds end with ``internal_forces`` (rotorpillar.transients.forces) and the
files the writer adds (rotorpillar.transients.files).
"""

from __future__ import annotations

from ..chain.record import PillarModel, Uncertain
from ..fem3d.full_order_result import Fem3dDescription, Fem3dStats
from ..records import Figure, Record, tag
from ..reduced.models import ModelInfo
from ..reduced.rotor_models import StructureDescription
from ..reduced.system import DampedMode, Resonance
from .case_summary import CaseSummary, RunOutcome
from .force_records import InternalForcesSummary
from .run_plan import BeamFullOrder, Fem3dPlan


class RunFiles(Record):
    """The series written beside a run's JSON (paths)."""

    npz: str
    """every series and the scalars tip_x_frame, model, case"""
    csv: str
    """the plain columns (rotorpillar.transients.files.CSV_COLUMNS)"""


class ModelFiles(Record):
    """The names of a model's own files (``simulate_<case>_<model>.*``), which the generic
    ``simulate_<case>.*`` copy."""

    npz: str
    csv: str
    json: str
    figures: tuple[str, ...]


class ReducedRun(CaseSummary, kw_only=True, omit_defaults=True, tag_field="model"):
    """paper, modal or beam on one case (SI: m, rad/s, s): the case's summary, then the run."""

    case: str
    warnings: tuple[str, ...]
    """what makes the answer doubtful, in words (also on the commands' stderr)"""
    pillar_model: PillarModel
    """the pillar model the run used"""
    uncertainty: dict[str, Uncertain] | None
    """modal: peak_tip_relative (m), peak_shaft_deflection (m), omega_final (rad/s) with
    their error bars; None for the other models"""
    dofs: int
    """unknowns of the model (-)"""
    wall_seconds: float
    """the run's wall time, warm (s)"""
    compile_seconds: float
    """the warm-up's wall time: what the run compiled (s)"""
    model_description: StructureDescription
    """the model's matrices and coordinates (RotorStructure.describe)"""
    model_info: ModelInfo | None
    """how the model was built: the reduction (paper), the modes chosen (modal), the
    elements (beam)"""
    resonances: tuple[Resonance, ...]
    """the model's quasi-normal resonances (Eq. 7)"""
    damped_frequencies: tuple[DampedMode, ...]
    """damped natural frequencies (rad/s) and damping ratios (-) of the linear structure"""
    tip_x_frame: str
    """the frame of ``tip_x``: "absolute" or "relative_to_ground\""""
    max_abs_sampled: tuple[str, ...]
    """the ``max_abs`` keys read from the decimated output, not from every step"""
    initial_speed: float | None = None
    """the speed the run starts at, where the case sets one (rad/s)"""
    excitation_in_model: str | None = None
    """earthquake: how the model applies the ground motion, in words"""
    full_order: BeamFullOrder | None = None
    """beam: its discretisation and step"""
    internal_forces: InternalForcesSummary | None = None
    """section forces, base reactions, the shaft's demand (None: paper's Eq. 4 has no sections)"""
    files: RunFiles | None = None
    """the series written beside the JSON"""
    figures: tuple[Figure, ...] = ()
    """the run's charts"""
    model_files: ModelFiles | None = None
    """the model's own files"""

    @property
    def model(self) -> str:
        """ "paper", "modal" or "beam\""""
        return tag(self)


class PaperRun(ReducedRun, tag="paper"):
    """The paper's Eq. 4 on one case."""


class ModalRun(ReducedRun, tag="modal"):
    """The ROM (the pillar by its modes) on one case."""


class BeamRun(ReducedRun, tag="beam"):
    """The 1D beam at full order on one case."""


#: the reduced runs' records by model
REDUCED_RUNS: dict[str, type[ReducedRun]] = {"paper": PaperRun, "modal": ModalRun, "beam": BeamRun}


class Fem3dRun(RunOutcome, kw_only=True, omit_defaults=True, tag_field="model", tag="fem3d"):
    """The 3D full order on one case (SI: m, rad/s, s)."""

    case: str
    integrator: Fem3dStats
    """the scheme, its step, steps, solves and wall times"""
    warnings: tuple[str, ...]
    captured_at_source: str
    """where the resonances come from (the chain's ROM), and whether the speed settled"""
    pillar_model: PillarModel
    """the 3D mesh as a pillar model, its source and error the reference's"""
    dofs: int
    """unknowns of the 3D model (-)"""
    wall_seconds: float
    """the run's wall time, warm (s)"""
    compile_seconds: float
    """the warm-up's wall time: FFCx's forms (s)"""
    model_description: Fem3dDescription
    """what was run: mesh, top, damping law, frame, forcing, start (fem3d.full_order)"""
    resonances: tuple[Resonance, ...]
    """the chain's ROM's quasi-normal resonances (Eq. 7)"""
    damped_frequencies: tuple[DampedMode, ...]
    """the ROM's damped natural frequencies (rad/s) and damping ratios (-)"""
    tip_x_frame: str
    """"relative_to_ground\""""
    full_order: Fem3dPlan
    """the mesh, duration and step, and why"""
    initial_speed: float | None
    """the speed the run starts at (rad/s), None: from rest"""
    excitation_in_model: str | None = None
    """earthquake: how the 3D model applies the ground motion, in words"""
    internal_forces: InternalForcesSummary | None = None
    """section resultants, base reactions, the shaft's demand and the von Mises peaks"""
    files: RunFiles | None = None
    figures: tuple[Figure, ...] = ()
    model_files: ModelFiles | None = None

    @property
    def model(self) -> str:
        return "fem3d"


#: one model's run, as ``ModelRun.record`` holds it (tagged by ``model``)
RunRecord = PaperRun | ModalRun | BeamRun | Fem3dRun
