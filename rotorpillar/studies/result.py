"""What a design study writes: ``StudyResult`` (study.json) and its runs (``StudyRun``)."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..provenance import JsonRecord
from .axes import Axis


@dataclass(frozen=True)
class StudyRun(JsonRecord):
    """One run of the study: its parameters and what it reached."""

    index: int
    """position in the product of the axes (last axis fastest)"""
    params: dict
    """{scene key: value} of this run"""
    ok: bool
    """the integrator finished"""
    final_speed: float
    """rotor speed at the end (rad/s)"""
    final_speed_mean: float
    """mean speed over the last 5 % of the run (rad/s)"""
    captured_at: float | None
    """the speed the rotor settled at below a resonance (rad/s), or None"""
    passed: bool | None
    """run-up and run-down: neither captured nor escaping a resonance at the end; earthquake: None"""
    peak_tip: float
    """largest |tip X| relative to the ground (m)"""
    peak_shaft_deflection: float
    """largest |shaft deflection| (X and Y together) on the output grid (m)"""
    free_speed: float
    """where the motor alone would settle (Md = Mc) (rad/s)"""
    nfev: int
    """right-hand side evaluations of the run"""
    batch: str = ""
    """the batch (cache file) that computed it"""
    speed_state: str = ""
    """"captured", "escaping", "accelerating" or "at_speed" (transients.case_summary.capture_state)"""
    pga: float | None = field(default=None, metadata={"omit_if_none": True})
    """earthquake: peak ground acceleration (m/s**2)"""
    initial_speed: float | None = field(default=None, metadata={"omit_if_none": True})
    """run-down and earthquake: the operating speed it started at (rad/s)"""


@dataclass(frozen=True)
class StudyResult(JsonRecord):
    """A design study (study.json): the axes, every run, the analytic boundary, where it
    ran and how fast."""

    scene_name: str
    case: str
    """runup, rundown or earthquake"""
    model: str
    """paper or modal"""
    axes: tuple[Axis, ...]
    implied: dict
    """scene keys set because of the axes (e.g. excitation.kind = record)"""
    runs: tuple[StudyRun, ...]
    boundary: dict | None
    """run-ups: the torque needed to pass, by the averaging theory (equations
    19-23) and by the exact linear torque balance, along the other axis; None
    where it does not apply"""
    executor: dict
    """kind (LocalCluster, scheduler, in-process), scheduler address, workers, threads"""
    batches: dict
    """total, cached, computed, runs per batch, groups (batch-loop calls), cache_dir"""
    performance: dict
    """runs, runs_computed, cluster_start_seconds, compute_wall_seconds (the
    computing phase), batch_seconds (summed over the batches computed),
    runs_per_second (computed runs over the computing phase), wall_seconds"""
    figures: tuple[dict, ...] = ()
    """the charts: {file, caption}"""
    files: dict = field(default_factory=dict)
    """study.csv and the cache folder"""
    pillar_model: dict | None = field(default=None, metadata={"omit_if_none": True})
    """the modal model's pillar (rotorpillar.chain.PillarModel as JSON); None for the paper model"""

    def values(self, name: str):
        """One result over the runs, in run order (e.g. ``values("final_speed")``)."""
        return [getattr(r, name) for r in self.runs]
