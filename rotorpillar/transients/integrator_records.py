"""The records of the integrator study (``integrators.json``, `rotorpillar integrators`).

``IntegratorStudy`` holds the three experiments of
:mod:`rotorpillar.transients.integrator_study`: ``accuracy`` (error against
cost on a run-up), ``stability`` (the modal model with more and more pillar
modes) and ``energy_drift`` (the undamped, unforced system).  Numpy-free
records (the report reads them).  A non-finite number (an error of a run that
failed: inf) is written as JSON null, so a field read back may hold None
where the study held inf.
"""

from __future__ import annotations

import msgspec

from ..chain.record import PillarModel
from ..records import Figure, Record

#: Fixed-step runs' and adaptive runs' ``family``.
FAMILIES = ("adaptive", "fixed")


class AccuracyRow(Record, kw_only=True, omit_defaults=True):
    """One run of the accuracy ladder: an integrator at one setting on the run-up."""

    method: str
    """the integrator (dp5, a scipy method, or a fixed-step scheme)"""
    family: str
    """"adaptive" (a tolerance ladder) or "fixed" (a step ladder)"""
    setting: float
    """the rung: the relative tolerance (-) or the time step (s), as ``setting_name`` says"""
    setting_name: str
    """"rtol" or "time_step\""""
    steps_per_rotor_period: float | None = None
    """time steps per rotor period at the run's top speed (-); fixed-step runs only"""
    error: float | None
    """largest |tip X - reference| over the largest |tip X| on the output grid (-); inf
    when the run failed (null in the JSON, None read back)"""
    wall_seconds: float
    """wall time of the run (s; noisy on a shared machine)"""
    nfev: int
    """force evaluations (-)"""
    status: str
    """the integrator's status ("ok" or why it stopped)"""


class Reference(Record):
    """The accuracy study's reference run, and its check against another method."""

    method: str
    """the reference integrator (dp5)"""
    rtol: float
    """its relative tolerance (-)"""
    nfev: int
    """its force evaluations (-)"""
    wall_seconds: float
    """its wall time (s)"""
    agreement_with_dop853: float = msgspec.field(name="agreement_with_DOP853_1e-12")
    """the error measure of scipy's DOP853 at rtol 1e-12 against the reference (-)"""


class MethodSummary(Record):
    """One integrator over its ladder: where it fails, its best error, its cost to reach
    an error of 1e-3 and 1e-6 (log-interpolated along the ladder; None when never reached)."""

    fails: str
    """where the error passes 10 %, in words (or "no failure ...")"""
    coarsest_ok_steps_per_period: float | None
    """fewest steps per rotor period with an error under 10 % (-); None for adaptive methods
    or when every rung fails"""
    best_error: float | None
    """the smallest error over the ladder (-); inf when every rung failed (null in the
    JSON, None read back)"""
    wall_seconds_at_1e_3: float | None = msgspec.field(name="wall_seconds_at_0.001")
    """wall time to an error of 1e-3 (s)"""
    nfev_at_1e_3: float | None = msgspec.field(name="nfev_at_0.001")
    """force evaluations to an error of 1e-3 (-, interpolated)"""
    wall_seconds_at_1e_6: float | None = msgspec.field(name="wall_seconds_at_1e-06")
    """wall time to an error of 1e-6 (s)"""
    nfev_at_1e_6: float | None = msgspec.field(name="nfev_at_1e-06")
    """force evaluations to an error of 1e-6 (-, interpolated)"""


class AccuracyStudy(Record, kw_only=True, omit_defaults=True):
    """Experiment 1: error against cost on a run-up from rest."""

    duration: float
    """length of the run-up (s)"""
    samples: int
    """points of the common output grid (-)"""
    omega_max: float
    """the reference run's top rotor speed (rad/s)"""
    reference: Reference
    rows: tuple[AccuracyRow, ...]
    per_method: dict[str, MethodSummary]
    """method -> its summary, methods in sorted order"""
    model: str | None = None
    """the model integrated (its name); set by ``run_integrator_study``"""


class StabilityRow(Record):
    """One run of the stiffness study: an integrator on the modal model with ``modes``."""

    method: str
    """the integrator"""
    modes: int
    """pillar modes in the model (-)"""
    omega_max: float
    """the model's highest frequency (rad/s)"""
    ok: bool
    """the run finished, finite, with a tip under 1 m"""
    nfev: int
    """force evaluations (-)"""
    wall_seconds: float
    """wall time of the run (s; noisy on a shared machine)"""
    status: str
    """the integrator's status"""
    time_step: float | None
    """the fixed step (s); None for adaptive methods"""
    stability_limit_central_difference: float
    """2 / omega_max: the largest stable step of central difference, undamped (s)"""


class FirstFailure(Record):
    """The fewest pillar modes at which an integrator failed."""

    modes: int
    """pillar modes (-)"""
    omega_max: float
    """the model's highest frequency (rad/s)"""
    h_times_omega_max: float
    """the study's time step times omega_max (-)"""


class CostGrowth(Record):
    """An integrator's force evaluations from the fewest to the most modes it survived."""

    modes: tuple[int, ...]
    """[fewest, most] pillar modes (-)"""
    nfev: tuple[int, ...]
    """force evaluations at each (-)"""
    factor: float
    """the ratio of the two (-)"""


class StabilityStudy(Record):
    """Experiment 2: the modal model with more and more pillar modes."""

    duration: float
    """length of each run (s)"""
    time_step: float
    """the fixed-step schemes' step (s)"""
    rtol: float
    """the adaptive methods' relative tolerance (-)"""
    rows: tuple[StabilityRow, ...]
    first_failure: dict[str, FirstFailure | None]
    """method -> its first failure, None if it never failed"""
    cost_growth: dict[str, CostGrowth]
    """method -> its cost growth (methods that survived more than one model)"""
    note: str
    """what the study shows, in words"""


class DriftRow(Record):
    """One integrator's energy drift on the undamped, unforced system."""

    method: str
    """the integrator"""
    drift: float | None
    """(E(T) - E(0)) / E(0) (-); None when the run failed"""
    max_deviation: float | None
    """max |E - E(0)| / E(0) over the run (-); None when the run failed"""
    nfev: int
    """force evaluations (-)"""
    status: str
    """the integrator's status"""
    setting: float | None
    """the relative tolerance (-) of an adaptive method, the time step (s) of a fixed-step one"""


class DriftStudy(Record):
    """Experiment 3: energy drift without damping, motor or load."""

    duration: float
    """length of each run (s)"""
    speed: float
    """the rotor's initial speed (rad/s)"""
    rtol: float
    """the adaptive methods' relative tolerance (-)"""
    steps_per_period: float
    """the fixed-step schemes' steps per period of the fastest motion (-)"""
    rows: tuple[DriftRow, ...]


class IntegratorStudy(Record, omit_defaults=True):
    """The integrator study: integrators.json's result (the command adds the pillar
    model, the probe's words and the figures to the study's three experiments)."""

    accuracy: AccuracyStudy
    stability: StabilityStudy
    energy_drift: DriftStudy
    pillar_model: PillarModel | None = None
    """the pillar model of the accuracy and drift studies' ROM"""
    stiffness_probe: str | None = None
    """what the stiffness study's pillar modes are, in words"""
    figures: tuple[Figure, ...] = ()
    """the charts"""
