"""The typed result of `rotorpillar analyze`: what the closed forms say about a scene.

Records (rotorpillar.records) whose fields are the keys of ``analyze.json``, in
the order written there; the report reads the file back with
``records.read(path, AnalysisResult)``.  SI units: rad/s, kg, N/m, N*m, m.
"""

from __future__ import annotations

from ..chain.modes import TipReductionOf
from ..chain.record import PillarModel, Uncertain
from ..records import Record
from ..reduced.averaging import Jump  # noqa: F401  (records of analyze.json too)
from ..reduced.averaging import Stationary as StationarySpeed
from ..reduced.base_forcing import BaseForcingFinding
from ..reduced.reduction import (  # noqa: F401  (records of analyze.json too)
    Lumping,
    PillarClosedForms,
    RayleighEstimate,
    TipReductionUsed,
)
from ..reduced.spatial_scene import DriveReactionAnalysis, SpatialAnalysis
from ..reduced.system import DampedMode  # noqa: F401  (a record of analyze.json too)
from .machine import MachineChecks
from .tower import TowerFindings


class CoupledModes(Record):
    """The reduced rotor-pillar system: its modes and quasi-normal coefficients."""

    tip_mass_total: float
    c0: float
    b0: float
    omega: tuple[float, ...]
    """omega_1, omega_2: the X modes (rad/s)"""
    omega3: float
    """the Y mode (rad/s)"""
    frequency_hz: tuple[float, ...]
    modal_vectors: tuple[tuple[float, ...], ...]
    modal_masses: tuple[float, ...]
    forcing: tuple[float, ...]
    coupling: tuple[float, ...]
    two_n: tuple[float, ...]
    nu: tuple[float, ...]
    f4: float
    """c2 e, the paper's torque coupling (N)"""


class ResonanceCurves(Record):
    """The averaging curves around one resonance, on z = Omega / omega_i."""

    z: tuple[float, ...]
    omega: tuple[float, ...]
    a: tuple[float, ...]
    a_linear: tuple[float, ...]
    dL: tuple[float, ...]
    L: tuple[float, ...]
    L_all: tuple[float, ...]
    Md: tuple[float, ...]


class ResonanceAnalysis(Record, omit_defaults=True):
    """One resonance by the averaging theory: amplitude, extra torque, jumps."""

    index: int
    direction: str
    omega: float
    forcing: float
    coupling: float
    two_n: float
    nu: float
    modal_mass: float
    shape: tuple[float, ...]
    a_max: float
    rotor_relative_amplitude_max: float
    a_max_as_printed: float
    dL_max: float
    Mc_at_omega: float
    dL_max_over_Mc: float | None
    dL_max_over_Mc_as_printed: float | None
    stationary: tuple[StationarySpeed, ...]
    jumps: tuple[Jump, ...]
    critical_slope: float
    critical_eccentricity: float
    statement: str
    curves: ResonanceCurves
    uncertainty: ResonanceBars | None = None
    """error bars of omega, a_max and dL_max (the headline model's; absent on the paper's)"""


class ResonanceBars(Record):
    """A resonance's headline numbers with their error bars (rotorpillar.analysis.rom)."""

    omega: Uncertain
    """rad/s"""
    a_max: Uncertain
    """m"""
    dL_max: Uncertain
    """N*m"""


class DriveBars(Record):
    """The drive's stationary speeds with their error bars."""

    runup_speed: Uncertain | None
    """rad/s"""
    rundown_speed: Uncertain | None
    """rad/s"""


class DriveRegimes(Record, omit_defaults=True):
    """The motor on the whole machine: stationary speeds, jumps, capture."""

    torque_at_zero: float
    slope: float
    load_coefficient: float
    free_speed: float
    stationary: tuple[StationarySpeed, ...]
    jumps: tuple[Jump, ...]
    runup_speed: float | None
    """where a quasi-static run-up to this M0 settles (rad/s)"""
    rundown_speed: float | None
    """where a quasi-static run-down to this M0 settles (rad/s)"""
    captured_index: int | None
    """the resonance (its index) below which the run-up settles while a faster stable
    regime exists: Sommerfeld capture; None when the run-up passes"""
    captured_resonance: float | None
    """that resonance's omega_i (rad/s)"""
    captured_at: float | None
    """the speed the rotor settles at when captured (rad/s)"""
    uncertainty: DriveBars | None = None


class PaperRow(Record, omit_defaults=True):
    """One number the paper prints, beside ours."""

    key: str
    quantity: str
    paper: float
    computed: float
    rel_diff: float
    flag: bool
    where: str
    note: str
    details: BaseForcingFinding | None = None
    """what a finding (not a printed number) states: eq4_base_forcing's"""


class RomSystem(Record):
    """The headline model: the chain's pillar modes with the rotor on its shaft."""

    modes: int
    """pillar modes kept, those below band_top (-)"""
    band_top: float
    """modal_model.band_factor x the highest forcing frequency (rad/s)"""
    mode_source: str
    """the modes' model, e.g. fem3d:3D P2 hexahedra, 128x20x1"""
    candidate_omega: tuple[float, ...]
    """the pillar modes (gondola on top) it picked from (rad/s)"""
    omega: tuple[float, ...]
    """the coupled X resonances, ascending (rad/s)"""
    omega_vertical: float
    """the rotor on its shaft, vertical, sqrt(c2/m_C) (rad/s)"""
    frequency_hz: tuple[float, ...]
    """the resonances in the order of ``resonances`` (Hz)"""
    damped: tuple[DampedMode, ...]
    f4: float
    """c2 e, the paper's torque coupling (N)"""
    tip_reduction: TipReductionOf
    """Eq. 2 on the chain model's bare first bending mode"""
    truncation_modes: int | None
    """pillar modes of the truncation check (None: the source offers no more)"""
    frequency_error: float | None
    """relative error bound of the pillar frequencies from the study (None: unverified) (-)"""
    error_note: str
    """how the error bars were made"""


class PaperModel(Record):
    """The paper's Eq. 4 with its stated tip reduction, analysed as the paper does."""

    reduction: TipReductionUsed
    system: CoupledModes
    resonances: tuple[ResonanceAnalysis, ...]
    drive: DriveRegimes
    note: str


class AnalysisResult(Record):
    """Everything `rotorpillar analyze` computes for a scene (``analyze.json``).

    ``system``, ``resonances`` and ``drive`` are the headline model's (the
    validated ROM on the chain's ``pillar_model``); ``paper_model`` is Eq. 4 with
    the paper's stated reduction, in its own block, and ``paper_comparison``
    sets the paper's printed numbers beside it.
    """

    pillar: PillarClosedForms
    pillar_model: PillarModel
    system: RomSystem
    resonances: tuple[ResonanceAnalysis, ...]
    drive: DriveRegimes
    paper_model: PaperModel
    paper_comparison: tuple[PaperRow, ...] = ()
    spatial: SpatialAnalysis | None = None
    """the machine in three dimensions beside the planar ROM (issue 26): every direction's
    resonances under their own names, the critical speeds, which planes the scene needs and
    the planar model's error; ``system.omega`` stays the resonances in the rotor's plane"""
    drive_reaction: DriveReactionAnalysis | None = None
    """the motor's stall torque reacting on the gondola: static tip displacement and rotation,
    base moment, and the run-up's transient with the reaction acting"""
    tower: TowerFindings | None = None
    """a tower (cans, a flexible foundation, or published numbers of its own): its first
    frequencies clamped and on its foundation, the published ones beside ours"""
    machine_checks: MachineChecks | None = None
    """the machine's checks on the headline ROM: balance grade, vibration, modal mass (analyze.json `machine_checks`; `machine` is the computer it ran on)"""
    warnings: tuple[str, ...] = ()
    """where a number above is the paper's formulation's rather than this machine's
    (rotorpillar.analysis.damping_law), printed on stderr too"""
