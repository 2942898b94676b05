"""What a design study writes: ``StudyResult`` (study.json) and its runs (``StudyRun``)."""

from __future__ import annotations

from ..chain.record import PillarModel
from ..executor import ExecutorInfo
from ..records import Figure, Record
from .axes import Axis, Param
from .boundary import StudyBoundary


class StudyRun(Record, omit_defaults=True):
    """One run of the study: its parameters and what it reached."""

    index: int
    """position in the product of the axes (last axis fastest)"""
    params: dict[str, Param]
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
    pga: float | None = None
    """earthquake: peak ground acceleration (m/s**2)"""
    initial_speed: float | None = None
    """run-down and earthquake: the operating speed it started at (rad/s)"""


class BatchCounts(Record):
    """The study's batches: how many, from disk or computed."""

    total: int
    cached: int
    """read from the batch cache (-)"""
    computed: int
    runs_per_batch_max: int
    groups: int
    """batch-loop calls over the batches (-)"""
    cache_dir: str
    """the batch cache's folder"""


class StudyPerformance(Record):
    """How fast the study ran."""

    runs: int
    runs_computed: int
    cluster_start_seconds: float
    """starting the executor (s)"""
    compute_wall_seconds: float
    """the computing phase (s)"""
    batch_seconds: float
    """summed over the batches computed (s)"""
    runs_per_second: float | None
    """computed runs over the computing phase (1/s); None when none was computed"""
    wall_seconds: float
    """the whole study (s)"""


class StudyFiles(Record):
    """The study's files beside study.json."""

    csv: str
    """study.csv: one row a run"""
    cache_dir: str
    """the batch cache's folder"""


class StudyResult(Record, omit_defaults=True):
    """A design study (study.json): the axes, every run, the analytic boundary, where it
    ran and how fast."""

    scene_name: str
    case: str
    """runup, rundown or earthquake"""
    model: str
    """paper or modal"""
    axes: tuple[Axis, ...]
    implied: dict[str, Param]
    """scene keys set because of the axes (e.g. excitation.kind = record)"""
    runs: tuple[StudyRun, ...]
    boundary: StudyBoundary | None
    """run-ups: the torque needed to pass, by the averaging theory (equations
    19-23) and by the exact linear torque balance, along the other axis, beside the
    one found; None where it does not apply"""
    executor: ExecutorInfo
    batches: BatchCounts
    performance: StudyPerformance
    figures: tuple[Figure, ...] = ()
    """the charts"""
    files: StudyFiles | None = None
    """study.csv and the cache folder"""
    pillar_model: PillarModel | None = None
    """the modal model's pillar; None for the paper model"""

    def values(self, name: str):
        """One result over the runs, in run order (e.g. ``values("final_speed")``)."""
        return [getattr(r, name) for r in self.runs]
