"""The typed records of one model's run of a case: the JSON fields of
``simulate_<case>_<model>.json`` (less the files and the provenance the writer adds).

- ``ReducedRun``: paper, modal, beam (rotorpillar.transients.cases): the case's
  ``CaseSummary`` flattened first, then what the model adds;
- ``Fem3dRun``: the 3D full order (rotorpillar.fem3d.full_order): its own outcome,
  the capture read through the chain's ROM, and its plan (``Fem3dPlan``).

Both end with ``internal_forces`` (rotorpillar.transients.forces), and both keep
the key order the JSON had when they were hand-built dicts.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, replace

from ..chain.record import PillarModel, Uncertain
from ..provenance import JsonRecord
from ..reduced.excitation_records import ExcitationSizes
from ..reduced.integration import EnergyBalance
from ..reduced.models import ModelInfo
from ..reduced.system import DampedMode, Resonance
from ..scene.sections import Mesh
from .case_summary import CaseSummary
from .force_records import InternalForcesSummary
from .references import FullOrderReference


def _resonance(doc: dict) -> Resonance:
    return Resonance(**{**doc, "shape": tuple(doc["shape"])})


def _resonance_json(r: Resonance) -> dict:
    return {**asdict(r), "shape": list(r.shape)}


@dataclass(frozen=True)
class BeamFullOrder(JsonRecord):
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


@dataclass(frozen=True)
class Fem3dPlan(JsonRecord):
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

    def to_json(self) -> dict:
        return {
            "mesh": dict(vars(self.mesh)),
            "duration": self.duration,
            "case_duration": self.case_duration,
            "time_step": self.time_step,
            "note": self.note,
            "reference": self.reference.to_json(),
        }

    @classmethod
    def from_json(cls, doc: dict) -> Fem3dPlan:
        return cls(
            Mesh(**doc["mesh"]),
            doc["duration"],
            doc["case_duration"],
            doc["time_step"],
            doc["note"],
            FullOrderReference.from_json(doc["reference"]),
        )


@dataclass(frozen=True)
class ReducedRun(JsonRecord):
    """paper, modal or beam on one case (SI: m, rad/s, s)."""

    case: str
    model: str
    summary: CaseSummary
    """the case condensed (its fields lead the JSON, ``max_abs`` the run's own)"""
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
    model_description: dict
    """the model's matrices and coordinates (RotorStructure.describe; keys by model)"""
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
    initial_speed: float | None = field(default=None, metadata={"omit_if_none": True})
    """the speed the run starts at, where the case sets one (rad/s)"""
    excitation_in_model: str | None = field(default=None, metadata={"omit_if_none": True})
    """earthquake: how the model applies the ground motion, in words"""
    full_order: BeamFullOrder | None = field(default=None, metadata={"omit_if_none": True})
    """beam: its discretisation and step"""
    internal_forces: InternalForcesSummary | None = None
    """section forces, base reactions, the shaft's demand (None: paper's Eq. 4 has no sections)"""

    @property
    def max_abs(self) -> dict:
        """largest |value| per coordinate (m), and the forces' (N, N m, Pa)"""
        return self.summary.max_abs

    @property
    def ok(self) -> bool:
        """whether the run passed its own checks (as Fem3dRun.ok)"""
        return self.summary.ok

    @property
    def omega_final(self) -> float:
        """rotor speed at the end (rad/s; as Fem3dRun.omega_final)"""
        return self.summary.omega_final

    def with_max_abs(self, max_abs: dict) -> ReducedRun:
        return replace(self, summary=replace(self.summary, max_abs=max_abs))

    def to_json(self) -> dict:
        out = {"case": self.case, "model": self.model, **self.summary.to_json()}
        for key, value in super().to_json().items():
            if key not in ("case", "model", "summary"):
                out[key] = value
        out["resonances"] = [_resonance_json(r) for r in self.resonances]
        return out

    @classmethod
    def from_json(cls, doc: dict) -> ReducedRun:
        rest = {k: v for k, v in doc.items() if k not in ("summary", "resonances")}
        base = super().from_json({**rest, "summary": None, "resonances": []})
        return replace(
            base, summary=CaseSummary.from_json(doc), resonances=tuple(_resonance(r) for r in doc["resonances"])
        )


@dataclass(frozen=True)
class Fem3dRun(JsonRecord):
    """The 3D full order on one case (SI: m, rad/s, s)."""

    case: str
    model: str
    ok: bool
    """the run's own checks held"""
    duration: float
    """the run's length (s)"""
    omega_final: float
    """rotor speed at the end (rad/s)"""
    omega_final_mean: float
    """mean speed over the last 5 % of the run (rad/s)"""
    max_abs: dict
    """largest |value| per output (m), and the forces' (N, N m, Pa)"""
    energy_balance: EnergyBalance
    """the energy balance of the run (J) and its relative error (-)"""
    integrator: dict
    """the scheme, its step (s), steps and wall times (s)"""
    dofs: int
    """unknowns of the 3D model (-)"""
    wall_seconds: float
    """the run's wall time, warm (s)"""
    failed_checks: tuple[str, ...] | None = field(metadata={"omit_if_none": True})
    """why ``ok`` is false (absent when no check failed)"""
    captured_at: float | None
    """the speed the rotor settled at below a resonance (rad/s), or None"""
    captured_resonance: float | None
    """that resonance's omega_i, from the chain's ROM (rad/s), or None"""
    captured_index: int | None
    """its index among the ROM's resonances (-), or None"""
    speed_state: str
    """"captured", "escaping", "accelerating" or "at_speed\""""
    warnings: tuple[str, ...]
    captured_at_source: str
    """where the resonances come from (the chain's ROM), and whether the speed settled"""
    pillar_model: PillarModel
    """the 3D mesh as a pillar model, its source and error the reference's"""
    compile_seconds: float
    """the warm-up's wall time: FFCx's forms (s)"""
    model_description: dict
    """the 3D model's description (fem3d.full_order)"""
    model_info: dict
    """dofs and the mesh"""
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
    excitation: ExcitationSizes | None = field(default=None, metadata={"omit_if_none": True})
    """earthquake: the ground motion's sizes"""
    excitation_in_model: str | None = None
    """earthquake: how the 3D model applies the ground motion, in words (absent for the
    other cases)"""
    internal_forces: InternalForcesSummary | None = None
    """section resultants, base reactions, the shaft's demand and the von Mises peaks"""

    def with_max_abs(self, max_abs: dict) -> Fem3dRun:
        return replace(self, max_abs=max_abs)

    def to_json(self) -> dict:
        out = super().to_json()
        if self.excitation is None:  # written for the earthquake only, null or not
            out.pop("excitation_in_model")
        out["resonances"] = [_resonance_json(r) for r in self.resonances]
        return out

    @classmethod
    def from_json(cls, doc: dict) -> Fem3dRun:
        base = super().from_json({**doc, "failed_checks": doc.get("failed_checks"), "resonances": []})
        return replace(base, resonances=tuple(_resonance(r) for r in doc["resonances"]))


#: one model's run, as ``ModelRun.record`` holds it
RunRecord = ReducedRun | Fem3dRun
