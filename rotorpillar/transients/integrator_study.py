"""Which time integrator, at what cost, and where each one fails.

Three experiments on a scene (`rotorpillar integrators`):

1. **Accuracy against cost** on a run-up from rest (the scene's motor,
   ``duration`` seconds, through the resonances): every integrator over a
   ladder of tolerances (adaptive) or steps (fixed), error = the largest
   |tip X - reference| over the largest |tip X| on a common output grid, the
   reference being the compiled Dormand-Prince at rtol 1e-12 (checked
   against scipy's DOP853 at 1e-12).  Where a scheme's error passes 10 %
   it "fails": steps too large for the rotor's period through the
   resonances, or a tolerance too loose to follow them.
2. **Stiffness as modes are added**: the modal model with 1, 2, ... pillar
   modes (its highest frequency grows as the square of the mode number);
   explicit schemes at a fixed step go unstable past h = 2/omega_max, the
   adaptive explicit ones survive by shrinking their step (cost grows with
   omega_max), the implicit ones do not care.
3. **Energy drift** of the undamped, unforced system (no damping, no motor,
   no load, the rotor spinning freely through its coupling): (E(T) - E(0))
   over E(0) after 200 s at a loose setting (rtol 1e-4; 20 steps per period
   of the fastest motion), where the schemes' characters show.

Its record, ``IntegratorStudy`` (integrators.json), comes first, typed to the
rows; a run that failed holds an error of inf (null in the JSON, None read back).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import msgspec
import numpy as np

from ..cache import DiskCache, cache_key, source_hash
from ..chain.record import PillarModel
from ..records import Figure, Record, replace
from ..reduced.drive import DriveSchedule
from ..reduced.excitation import no_motion
from ..reduced.integration import FIXED_STEP, Settings, simulate
from ..reduced.models import build_model
from ..reduced.rotor_models import model_digest
from ..scene import SCIPY_METHODS, Scene

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
    kept: str | None = None
    """the file the rows were read back from, when this model had been integrated with these
    settings before (:func:`drift_study`); None when they were computed in this run"""


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


ADAPTIVE = ("dp5",) + SCIPY_METHODS
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
RTOLS_IMPLICIT = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
STEP_REFINEMENTS = (1, 2, 4, 8, 16, 32, 64, 128)  # steps per output interval
FAIL = 0.1


def _error(run, ref) -> float:
    if not run.ok or len(run.t) != len(ref.t) or not np.all(np.isfinite(run.q)):
        return math.inf
    a, b = run.tip(), ref.tip()
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def accuracy_study(
    model, drive, duration: float, samples: int = 401, quick: bool = False, progress=None
) -> AccuracyStudy:
    """Experiment 1: error against cost on a run-up.

    Each scheme first runs once on a hundredth of the run, untimed: its compiled
    kernels load (from numba's cache, or compile) there, not in the first timed run
    of its ladder, whose cost would otherwise carry them.
    """
    spacing = duration / (samples - 1)
    for m in dict.fromkeys(("dp5", "DOP853", *ADAPTIVE, *FIXED_STEP)):
        warm = Settings(m, time_step=spacing, samples=11) if m in FIXED_STEP else Settings(m, rtol=1e-3, samples=11)
        simulate(model, drive, no_motion(), max(0.01 * duration, 10 * spacing), settings=warm)
    ref = simulate(model, drive, no_motion(), duration, settings=Settings("dp5", rtol=1e-12, samples=samples))
    check = simulate(model, drive, no_motion(), duration, settings=Settings("DOP853", rtol=1e-12, samples=samples))
    ref_agreement = _error(check, ref)
    W_max = float(np.max(ref.Omega))
    rows: list[AccuracyRow] = []
    rtols = RTOLS[::2] if quick else RTOLS
    for m in ADAPTIVE:
        ladder = [r for r in rtols if m not in ("Radau", "BDF", "LSODA") or r in RTOLS_IMPLICIT]
        if progress:
            progress(f"integrators: {m}")
        for rtol in ladder:
            run = simulate(model, drive, no_motion(), duration, settings=Settings(m, rtol=rtol, samples=samples))
            rows.append(
                AccuracyRow(
                    method=m,
                    family="adaptive",
                    setting=rtol,
                    setting_name="rtol",
                    error=_error(run, ref),
                    wall_seconds=run.stats.wall_seconds,
                    nfev=run.stats.nfev,
                    status=run.stats.status,
                )
            )
    for m in FIXED_STEP:
        if progress:
            progress(f"integrators: {m}")
        for k in STEP_REFINEMENTS[::2] if quick else STEP_REFINEMENTS:
            h = spacing / k
            run = simulate(model, drive, no_motion(), duration, settings=Settings(m, time_step=h, samples=samples))
            rows.append(
                AccuracyRow(
                    method=m,
                    family="fixed",
                    setting=h,
                    setting_name="time_step",
                    steps_per_rotor_period=2 * math.pi / (W_max * h),
                    error=_error(run, ref),
                    wall_seconds=run.stats.wall_seconds,
                    nfev=run.stats.nfev,
                    status=run.stats.status,
                )
            )
    return AccuracyStudy(
        duration=duration,
        samples=samples,
        omega_max=W_max,
        reference=Reference("dp5", 1e-12, ref.stats.nfev, ref.stats.wall_seconds, ref_agreement),
        rows=tuple(rows),
        per_method=_per_method(rows),
    )


def _error_of(r: AccuracyRow) -> float:
    """A row's error; inf where the run failed (None once read back from JSON's null)."""
    return math.inf if r.error is None else r.error


def _cost_at(rows: list[AccuracyRow], target: float) -> tuple[float | None, float | None]:
    """Wall time and evaluations to reach ``target`` error, log-interpolated along the ladder."""
    pts = sorted(
        ((r.wall_seconds, _error_of(r), r.nfev) for r in rows if math.isfinite(_error_of(r)) and _error_of(r) > 0),
        key=lambda p: p[0],
    )
    for (w0, e0, n0), (w1, e1, n1) in zip(pts, pts[1:]):
        if e0 > target >= e1:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return (math.exp(math.log(w0) + f * (math.log(w1) - math.log(w0))), n0 + f * (n1 - n0))
    ok = [p for p in pts if p[1] <= target]
    return (ok[0][0], ok[0][2]) if ok else (None, None)


def _steps(r: AccuracyRow) -> float:
    """A fixed-step run's steps per rotor period (-)."""
    assert r.steps_per_rotor_period is not None  # every fixed-step row has them
    return r.steps_per_rotor_period


def _per_method(rows: list[AccuracyRow]) -> dict[str, MethodSummary]:
    # keyed by the integrator's name: the methods present are the study's choice
    out = {}
    for m in sorted({r.method for r in rows}):
        mine = [r for r in rows if r.method == m]
        bad = [r for r in mine if not math.isfinite(_error_of(r)) or _error_of(r) > FAIL]
        worst_ok: float | None
        if mine[0].family == "fixed":
            worst_ok = min((_steps(r) for r in mine if r not in bad), default=None)
            fails = (
                f"error > {100 * FAIL:g} % at {max(_steps(r) for r in bad):.3g} "
                "steps per rotor period (top speed) or fewer"
                if bad
                else f"no failure down to {min(_steps(r) for r in mine):.3g} steps per period"
            )
        else:
            worst_ok = None
            fails = (
                f"error > {100 * FAIL:g} % at rtol >= {min(r.setting for r in bad):g}"
                if bad
                else f"no failure up to rtol {max(r.setting for r in mine):g}"
            )
        w3, n3 = _cost_at(mine, 1e-3)
        w6, n6 = _cost_at(mine, 1e-6)
        out[m] = MethodSummary(fails, worst_ok, min(_error_of(r) for r in mine), w3, n3, w6, n6)
    return out


def stability_study(
    scene: Scene,
    drive,
    duration: float = 2.0,
    max_modes: int = 8,
    time_step: float = 2.5e-3,
    rtol: float = 1e-6,
    progress=None,
    pillar_modes=None,
) -> StabilityStudy:
    """Experiment 2: modal model with more and more pillar modes (of
    ``pillar_modes`` when given, see ``models.build_model``)."""
    rows: list[StabilityRow] = []
    for k in range(1, max_modes + 1):
        model, _ = build_model(scene, "modal", modes=k, pillar_modes=pillar_modes)
        w_max = model.stiffest_frequency()
        if progress:
            progress(f"integrators: {k} pillar modes (omega_max {w_max:.0f} rad/s)")
        for m in ADAPTIVE + FIXED_STEP:
            st = Settings(m, rtol=rtol, time_step=time_step, samples=201)
            t0 = time.perf_counter()
            run = simulate(model, drive, no_motion(), duration, settings=st)
            wall = time.perf_counter() - t0
            ok = run.ok and bool(np.all(np.isfinite(run.q))) and float(np.max(np.abs(run.tip()))) < 1.0
            rows.append(
                StabilityRow(
                    method=m,
                    modes=k,
                    omega_max=w_max,
                    ok=ok,
                    nfev=run.stats.nfev,
                    wall_seconds=wall,
                    status=run.stats.status,
                    time_step=time_step if m in FIXED_STEP else None,
                    stability_limit_central_difference=2.0 / w_max,
                )
            )
    first_fail: dict[str, FirstFailure | None] = {}
    for m in ADAPTIVE + FIXED_STEP:
        bad = [r for r in rows if r.method == m and not r.ok]
        first_fail[m] = None if not bad else FirstFailure(bad[0].modes, bad[0].omega_max, time_step * bad[0].omega_max)
    growth = {}
    for m in ADAPTIVE + FIXED_STEP:
        mine = sorted((r for r in rows if r.method == m and r.ok), key=lambda r: r.modes)
        if len(mine) > 1:
            growth[m] = CostGrowth(
                (mine[0].modes, mine[-1].modes), (mine[0].nfev, mine[-1].nfev), mine[-1].nfev / mine[0].nfev
            )
    return StabilityStudy(
        duration=duration,
        time_step=time_step,
        rtol=rtol,
        rows=tuple(rows),
        first_failure=first_fail,
        cost_growth=growth,
        note="central difference is stable for h*omega_max < 2 (undamped); the implicit "
        "schemes and the adaptive ones never blow up, the explicit adaptive ones pay "
        "with steps ~ 1/omega_max",
    )


#: Layout of a cached energy-drift study: a change here makes every kept one a miss.
DRIFT_CACHE_VERSION = 1


def _drift_code() -> str:
    """The code a drift study runs: this module and reduced/ (the models and the integrators)."""
    here = Path(__file__).resolve()
    return source_hash([here, *sorted((here.parent.parent / "reduced").glob("*.py"))])


def drift_study(
    model,
    duration: float = 200.0,
    speed: float = 50.0,
    rtol: float = 1e-4,
    steps_per_period: float = 20.0,
    progress=None,
    cache_dir: Path | None = None,
) -> DriftStudy:
    """Experiment 3: energy drift without damping, motor or load.

    The drift reads no drive, damping, ground motion or wall clock: the same model and
    settings give the same rows.  With ``cache_dir`` the study is kept there
    (``drift-<key>.json``, the key the model's digest, the settings and the code), so a
    run that changed only the drive (the torque, the ramp) reads it back instead of
    integrating 40 s of free whirl with every scheme again."""
    m0 = replace(model, damping=np.zeros_like(model.damping), shaft_damping=0.0)
    cache = key = None
    digest = model_digest(m0) if cache_dir is not None else None
    if cache_dir is not None and digest is not None:  # a model that does not pickle: no cache
        cache = DiskCache(Path(cache_dir), prefix="drift-")
        args = {
            "model": digest,
            "duration": duration,
            "speed": speed,
            "rtol": rtol,
            "steps_per_period": steps_per_period,
            "methods": list(ADAPTIVE + FIXED_STEP),
        }
        key = cache_key(args, version=DRIFT_CACHE_VERSION, code=_drift_code())
        kept = cache.read(key, DriftStudy)
        if kept is not None:
            if progress:
                progress("integrators: energy drift unchanged (the same model and settings), read back")
            return replace(kept, kept=str(cache.path(key)))
    drive = DriveSchedule.constant(0.0, 0.0, 0.0)
    q0, v0 = m0.steady_initial_state(speed)
    q0 = q0 + 0.5 * m0.eccentricity * np.r_[np.ones(m0.nx), 0.0, 0.0]
    rows = []
    for m in ADAPTIVE + FIXED_STEP:
        if progress:
            progress(f"integrators: energy drift, {m}")
        st = Settings(m, rtol=rtol, steps_per_period=steps_per_period, samples=2001)
        run = simulate(m0, drive, no_motion(), duration, q0, v0, settings=st, speed_scale=speed)
        T, P = m0.energy(run.q, run.v)
        E = T + P
        ok = run.ok and np.all(np.isfinite(E))
        rows.append(
            DriftRow(
                method=m,
                drift=float((E[-1] - E[0]) / E[0]) if ok else None,
                max_deviation=float(np.max(np.abs(E - E[0])) / E[0]) if ok else None,
                nfev=run.stats.nfev,
                status=run.stats.status,
                setting=rtol if m not in FIXED_STEP else run.stats.time_step,
            )
        )
    study = DriftStudy(duration, speed, rtol, steps_per_period, tuple(rows))
    if cache is not None and key is not None:
        try:
            cache.write(key, study)
        except OSError:
            pass  # a read-only folder costs the next run the study, nothing else
    return study


def run_integrator_study(
    scene: Scene,
    duration: float = 10.0,
    quick: bool = False,
    progress=None,
    pillar_modes=None,
    probe_modes=None,
    cache_dir: Path | None = None,
) -> IntegratorStudy:
    """All three experiments: accuracy (1) and energy drift (3) on the scene's headline
    model, the ROM on ``pillar_modes`` (the chain's; the paper model when None); the
    stiffness study (2) on ``probe_modes`` (many pillar modes: the 1D beam's, a probe of
    the integrators' stiffness, not the scene's model; ``pillar_modes`` when None).
    ``cache_dir``: where the energy drift is kept (:func:`drift_study`)."""
    d, L = scene.drive, scene.load
    drive = DriveSchedule.ramp(d.torque_at_zero, d.slope, L.coefficient, scene.simulate.runup_ramp)
    if pillar_modes is None:
        model, _ = build_model(scene, "paper")
    else:
        from ..reduced.pillar_modes import modes_in_band

        band = scene.modal_model.band_factor * drive.free_speed()
        model, _ = build_model(scene, "modal", modes=modes_in_band(pillar_modes.omega, band), pillar_modes=pillar_modes)
    acc = replace(accuracy_study(model, drive, duration, quick=quick, progress=progress), model=model.name)
    stab = stability_study(
        scene,
        drive,
        max_modes=5 if quick else 8,
        progress=progress,
        pillar_modes=probe_modes if probe_modes is not None else pillar_modes,
    )
    # 40 s of the ROM's free whirl (20 quick; 320 rotor periods at 50 rad/s): its third
    # resonance (~156 rad/s on the paper's tube) makes the scipy methods take many times the
    # steps of the paper's two masses; the drifts grow with time, and the study compares
    # the integrators at one duration (measured: 6 s against 25 s for 200 s, quiet machine)
    drift = drift_study(model, duration=20.0 if quick else 40.0, progress=progress, cache_dir=cache_dir)
    return IntegratorStudy(acc, stab, drift)
