"""The typed record of compare_<case>.json, to its leaves (no heavy imports: the report reads it back)."""

from __future__ import annotations

from ..chain.record import PillarModel
from ..records import Record
from ..reduced.excitation import ExcitationSizes
from .case_checks import SpectralMode
from .pareto import ParetoStudy
from .references import FullOrderReference
from .window import RunupWindow

#: the reference of a comparison: the most complete model run
REFERENCE_ORDER = ("fem3d", "beam", "modal", "paper")


class ComparedModel(Record):
    """One model's run in a comparison: its answers, its cost and its files."""

    peak_tip_relative: float
    """largest |tip X relative to the ground| (m)"""
    peak_tip_absolute: float
    """largest |absolute tip X| (m)"""
    peak_shaft_deflection: float
    """largest |shaft deflection along X| (m)"""
    omega_final: float
    """rotor speed at the end (rad/s)"""
    wall_seconds: float
    """the run's wall time, warm (s)"""
    compile_seconds: float | None
    """the warm-up's wall time: what the run compiled (s)"""
    dofs: int
    """unknowns of the model (-)"""
    ok: bool
    """the run's own checks held"""
    warnings: tuple[str, ...]
    """the run's warnings, in words"""
    pillar_model: PillarModel | None
    """the pillar model it ran on"""
    json: str
    """its compare_<case>_<model>.json"""
    npz: str
    """its compare_<case>_<model>.npz"""


class ModelErrors(Record):
    """One model against the reference (rotorpillar.transients.measures)."""

    tip_history_error: float
    """max_t |tip_m - tip_ref| / max_t |tip_ref|, tips relative to the ground on the
    reference's times (-)"""
    peak_tip_difference: float | None
    """peak_m / peak_ref - 1 (-); None when the reference's peak is zero"""
    omega_final_difference: float | None
    """omega_final_m / omega_final_ref - 1 (-); None when the reference's is zero"""
    tip_envelope_error: float
    """the running peak over envelope_window compared as the history (-)"""
    envelope_window: float
    """the envelope's window: one period of the slowest resonance (s)"""
    angle_drift: float | None
    """largest |theta_m - theta_ref| (rad)"""
    angle_drift_final: float | None
    """theta_m - theta_ref at the end (rad)"""
    lead: str
    """"history" or "envelope": the measure that fits the case"""
    lead_why: str
    """why that measure, in words"""


class CompareWindow(Record, omit_defaults=True):
    """The span every model's history is compared over."""

    start: float
    """(s)"""
    end: float
    """(s)"""
    duration: float
    """the one duration every model runs (s)"""
    why: str
    """why that duration, in words"""
    runup: RunupWindow | None = None
    """the run-up's window through the resonances (runup against fem3d), else absent"""


class ResponseSpectrum(Record):
    """The earthquake's pseudo-acceleration spectrum and the ROM's spectral peak tip."""

    period: tuple[float, ...]
    """(s)"""
    psa: tuple[float, ...]
    """pseudo-acceleration at each period, 5 % damping (eqsig) (m/s**2)"""
    damping: float
    """the spectrum's damping ratio (-)"""
    mode_periods: tuple[float, ...]
    """the modal model's mode periods (s)"""
    spectral_peak_tip: float
    """SRSS of the modes' contributions (m)"""
    computed_peak_tip: float | None
    """the modal model's computed peak tip relative to the ground (m); None without it"""
    modes: tuple[SpectralMode, ...]
    note: str


class CompareResult(Record, omit_defaults=True):
    """Several models on one case (SI: m, rad/s, s).  ``errors`` and ``cost_ratio`` are
    against ``reference``; the histories are compared over ``window`` (every model is
    run over the same duration)."""

    case: str
    models_run: tuple[str, ...]
    """in the order given"""
    reference: str
    """the most complete model run: fem3d > beam > modal > paper"""
    excitation: ExcitationSizes | None
    """the ground motion's sizes (earthquake), as in simulate's JSON (their fields depend
    on the excitation's kind: rotorpillar.reduced.excitation_records)"""
    per_model: dict[str, ComparedModel]
    """model -> its answers, cost and files"""
    errors: dict[str, ModelErrors]
    """model (not the reference) -> its errors against the reference"""
    cost_ratio: dict[str, float | None]
    """model -> wall_seconds_m / wall_seconds_ref, both warm (compilation apart:
    per_model's compile_seconds) (-)"""
    chart: str
    """compare_<case>.png: tip histories relative to the ground overlaid, difference below"""
    window: CompareWindow
    """the span of the comparison and why"""
    spectrum: ResponseSpectrum | None = None
    """earthquake: the record's spectrum and the ROM's spectral estimate of the peak tip"""
    full_order_reference: FullOrderReference | None = None
    """fem3d run: its mesh, where it comes from (the convergence study, or the scene), its own
    error on the frequencies the load excites, and the participation of the loaded modes"""
    pareto: ParetoStudy | None = None
    """earthquake against the 3D full order: speed against accuracy of every model of the
    ladder on El Centro"""


def reference_of(models) -> str:
    """The most complete model among ``models``."""
    return next(m for m in REFERENCE_ORDER if m in models)
