"""The typed record of compare_<case>.json (no heavy imports: the report reads it back)."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..provenance import JsonRecord

#: the reference of a comparison: the most complete model run
REFERENCE_ORDER = ("fem3d", "beam", "modal", "paper")


@dataclass(frozen=True)
class CompareResult(JsonRecord):
    """Several models on one case (SI: m, rad/s, s).  ``errors`` and ``cost_ratio`` are
    against ``reference``; the histories are compared over ``window`` (every model is
    run over the same duration)."""
    case: str
    models_run: tuple[str, ...]
    """in the order given"""
    reference: str
    """the most complete model run: fem3d > beam > modal > paper"""
    excitation: dict | None
    """the ground motion's sizes (earthquake), as in simulate's JSON"""
    per_model: dict
    """model -> peak_tip_relative, peak_tip_absolute, peak_shaft_deflection, omega_final,
    wall_seconds, dofs, ok, warnings, json, npz"""
    errors: dict
    """model (not the reference) -> tip_history_error = max_t |tip_m - tip_ref| / max_t |tip_ref|
    (tips relative to the ground, on the reference's times), peak_tip_difference =
    peak_m / peak_ref - 1, omega_final_difference = omega_final_m / omega_final_ref - 1,
    tip_envelope_error (the running peak over envelope_window s compared the same way),
    angle_drift and angle_drift_final (theta_m - theta_ref, rad), lead ("history" or
    "envelope": the measure that fits the case) and lead_why
    (rotorpillar.transients.measures)"""
    cost_ratio: dict
    """model -> wall_seconds_m / wall_seconds_ref, both warm (compilation apart:
    per_model's compile_seconds)"""
    chart: str
    """compare_<case>.png: tip histories relative to the ground overlaid, difference below"""
    window: dict = field(default_factory=dict)
    """start, end (s) of the comparison and why"""
    spectrum: dict | None = field(default=None, metadata={"omit_if_none": True})
    """earthquake: period, psa (eqsig, 5 %), mode_periods, spectral_peak_tip, computed_peak_tip"""
    full_order_reference: dict | None = field(default=None, metadata={"omit_if_none": True})
    """fem3d run: its mesh, where it comes from (the convergence study, or the scene), its own
    error on the frequencies the load excites, and the participation of the loaded modes
    (rotorpillar.transients.references.FullOrderReference)"""
    pareto: dict | None = field(default=None, metadata={"omit_if_none": True})
    """earthquake against the 3D full order: speed against accuracy of every model of the
    ladder on El Centro (rotorpillar.transients.pareto.ParetoStudy)"""


def reference_of(models) -> str:
    """The most complete model among ``models``."""
    return next(m for m in REFERENCE_ORDER if m in models)
