"""Several models on one transient case, against the most complete one (`rotorpillar compare`).

``compare_models(scene, case, models, out)`` runs each model through the
same path as `simulate` (``run.run_model`` on the chain's pillar model,
``files.write_model_files``: ``compare_<case>_<model>.*``, apart from the
scene's own ``simulate_<case>_<model>.*``), over one common duration (the
shortest of the models' own: the 3D full order's is [full_order]'s), and
writes ``compare_<case>.json`` (its record, ``CompareResult``, typed to the
leaves here) and the chart ``compare_<case>.png``.  Errors are of the tip's X
relative to the ground, against the reference (fem3d > beam > modal > paper)
on its output times (``compare_series``, below): the history error, and apart
the envelope error, the peak and the rotor angle's drift, with the one that
fits the case leading.  Costs are warm (compilation apart, ``compile_seconds``).
For the earthquake, ``spectrum``: the record's pseudo-acceleration spectrum
(eqsig, 5 %), the modal model's mode periods and its spectral estimate of
the peak tip (SRSS of Gamma_j S_d(T_j), rotorpillar.transients.cases.spectral_estimate)
beside the modal model's computed peak.

How far one model's run is from a reference run, by errors that measure the
model: with a whirling unbalance the tip history of two good models drifts
apart in phase: a rotor angle that lags by a fraction of a radian after a
minute shifts the whirl by as much, and the pointwise history error then
reads tens of per cent while the amplitudes agree to a fraction of one.  So
beside the history error three measures are taken separately: the envelope
error (the running peak |x| over a window of one period of the slowest
resonance, compared pointwise: phase-blind within the window), the peak
difference, and the rotor angle's drift theta - theta_ref (rad), which is the
phase error.  ``lead`` says which measure fits the case: the history while the
rotors stay in phase (drift < ``PHASE_LOCKED`` rad: both models see the same
forcing at the same time, so the history error is the model's), else the
envelope.

The comparisons `rotorpillar run` makes and the report shows are
:data:`COMPARISONS`, as `rotorpillar compare` arguments (``commands/run.py``
builds its stages from them, the report's hints repeat them).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene

import math
from pathlib import Path

import numpy as np

from ..chain.record import PillarModel
from ..errors import InputError
from ..provenance import write_result
from ..records import Record
from ..reduced.excitation import ExcitationSizes
from ..scene import MODELS
from .case_summary import SpectralMode
from .model_run import Fem3dRun, ModelRun, ReducedRun, run_model
from .pareto import ParetoStudy
from .references import FullOrderReference
from .run_plan import fem3d_plan, own_duration
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
    """largest radial shaft deflection sqrt(d_x**2 + d_y**2), the run's
    max_abs.shaft_deflection: the clearance check's (m)"""
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
    """One model against the reference (rotorpillar.transients.compare)."""

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
    """The earthquake's pseudo-acceleration spectrum and the ROM's spectral peak tip over
    its coupled rotor-pillar modes (rotorpillar.transients.cases.spectral_estimate)."""

    period: tuple[float, ...]
    """(s)"""
    psa: tuple[float, ...]
    """pseudo-acceleration at each period, at ``damping`` (eqsig) (m/s**2)"""
    damping: float
    """the drawn spectrum's damping ratio (-); each mode's estimate takes its own"""
    mode_periods: tuple[float, ...]
    """the coupled rotor-pillar modes' periods in X, as in ``modes`` (s)"""
    spectral_peak_tip: float
    """SRSS of the coupled modes' contributions (m)"""
    computed_peak_tip: float | None
    """the modal model's computed peak tip relative to the ground (m); None without it"""
    modes: tuple[SpectralMode, ...]
    """each coupled mode's part: period, own damping, participation, S_d, contribution"""
    note: str
    """what the estimate is, in words"""
    pillar_modes_only: float | None = None
    """the same SRSS over the pillar's own modes with the rotor apart (m): the estimate
    without the rotor's coupling; None from an older rotorpillar"""


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
    on the excitation's kind: rotorpillar.reduced.excitation)"""
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


COMPARE_CASES = ("earthquake", "runup")
DEFAULT_MODELS = {"earthquake": ("modal", "fem3d"), "runup": ("modal", "beam")}
#: spectrum periods (s): log-spaced over the band of a tall pillar's modes
SPECTRUM_PERIODS = (0.02, 10.0, 200)


def parse_models(text: str | None, case: str) -> tuple[str, ...]:
    """``--models m1,m2``: known, not repeated, not empty (InputError otherwise)."""
    if case not in COMPARE_CASES:
        raise InputError(f"--case {case!r}: compare runs {', '.join(COMPARE_CASES)}")
    if text is None:
        return DEFAULT_MODELS[case]
    names = [m.strip() for m in text.split(",")]
    if not text.strip() or any(not m for m in names):
        raise InputError(f"--models {text!r}: give a comma-separated list of {', '.join(MODELS)}")
    for m in names:
        if m not in MODELS:
            raise InputError(f"--models: unknown model {m!r}; must be among {', '.join(MODELS)}")
    if len(set(names)) != len(names):
        raise InputError(f"--models {text!r}: a model is named twice")
    return tuple(names)


def common_duration(scene: Scene, case: str, models, motion, study_dir=None) -> tuple[float, str]:
    """The one duration every model runs (s), and why."""
    own = own_duration(scene, case, motion)
    if "fem3d" not in models:
        return own, "the case's own duration"
    d = fem3d_plan(scene, case, motion, study_dir=study_dir).duration
    return d, (
        f"the 3D full order's duration ([full_order]); every model runs {d:g} s"
        if d < own
        else "the case's own duration"
    )


def compare_models(
    scene: Scene,
    case: str,
    models,
    out: Path,
    provenance: dict,
    progress=None,
    write: bool = True,
    collective: bool = False,
    run_charts=None,
    compare_chart=None,
    pareto: bool = False,
    pareto_chart=None,
    workers: int = 1,
    chain=None,
    timings: dict | None = None,
) -> CompareResult:
    """Run ``models`` on ``case`` and compare them (see the module text).

    ``run_charts`` draws each model's figures (see ``files.write_model_files``);
    ``compare_chart(path, series, reference, title, errors=..., walls=...)``
    the overlay (``rotorpillar.postprocess.compare_charts.comparison_chart``);
    ``pareto_chart(doc, path, title)`` the speed against accuracy
    (``rotorpillar.postprocess.pareto_charts.pareto_chart``); all handed in by
    the command, since drawing lives above this layer.  ``pareto``: the
    earthquake against the 3D full order also runs the speed-against-accuracy
    study (rotorpillar.transients.pareto, its 3D runs on ``workers`` processes).
    ``chain``: the chain's pillar model and modes (rotorpillar.chain.resolve).
    ``provenance`` (scene_source, overrides) and ``timings`` (s, the command's so far) go
    into every file written, beside the scene, versions and machine.
    """
    import time

    start, given = time.perf_counter(), scene
    from ..reduced.models import scene_motion
    from ..scene import with_values

    models = tuple(models)
    # each model runs the case only: the passing-torque batch belongs to the scene's own
    # run on the headline model (simulate), not to a comparison of models
    scene = with_values(scene, {"simulate.threshold": False})
    if case not in COMPARE_CASES:
        raise InputError(f"--case {case!r}: compare runs {', '.join(COMPARE_CASES)}")
    motion = scene_motion(scene) if case == "earthquake" else None
    if chain is None and any(m in ("modal", "fem3d") for m in models):
        from ..chain import resolve

        chain = resolve(scene, out, motion=motion, progress=progress)
    window = None
    if case == "runup" and "fem3d" in models:
        # the 3D run-up through the resonances only; every model from the same state
        from .window import runup_window, window_scene

        if progress:
            progress("compare runup: the window through the resonances (the ROM's run-up from rest)")
        window = runup_window(scene, chain.modes)
        scene = window_scene(scene, window)
    duration, why = common_duration(scene, case, models, motion, out)  # bad input: before any output
    if window is not None:
        why = f"the run-up's window {window.reason}; {why}"
    pending = None
    if pareto and case == "earthquake" and "fem3d" in models:
        # started first: its 3D runs take the other core while this process runs the models
        pending = _start_pareto(scene, motion, out, workers, progress, chain)
    runs: dict[str, ModelRun] = {}
    for i, m in enumerate(models):
        if progress:
            progress(f"compare {case}: model {i + 1} of {len(models)}: {m}")
        begun = time.perf_counter()
        run = run_model(
            scene,
            case,
            m,
            progress=progress,
            motion=motion,
            duration=duration,
            chain=chain,
            # the 3D run's XDMF series is written by every rank together (rank 0 places it)
            field_dir=out if write or collective else None,
            study_dir=out,
            field_stem=f"{compare_stem(case, m)}",
        )
        if write:
            from .files import write_model_files

            write_model_files(
                out,
                scene,
                run,
                provenance,
                {"simulate": time.perf_counter() - begun},
                last_run=False,
                charts=run_charts,
                stem=compare_stem(case, m),
            )
        runs[m] = run
        if progress:
            progress(f"compare {case}: {m} done in {run.record.wall_seconds:.3g} s ({run.record.dofs} dofs)")
    ref = reference_of(models)
    gap = _planar_beside_spatial(runs)
    per_model = {m: _per_model(case, m, runs[m].record, gap if m in ("beam", "paper") else ()) for m in models}
    rd = runs[ref].data
    t_ref, x_ref = rd["t"], rd["tip_x_relative"]
    span = envelope_window(r.omega for r in runs[ref].resonances)
    errors: dict[str, ModelErrors] = {}
    for m in models:
        if m == ref:
            continue
        d = runs[m].data
        pm, pr = per_model[m], per_model[ref]
        series = compare_series(
            d["t"], d["tip_x_relative"], t_ref, x_ref, window=span, theta=d.get("theta"), theta_ref=rd.get("theta")
        )
        errors[m] = ModelErrors(
            tip_history_error=series.history_error,
            peak_tip_difference=(pm.peak_tip_relative / pr.peak_tip_relative - 1 if pr.peak_tip_relative else None),
            omega_final_difference=pm.omega_final / pr.omega_final - 1 if pr.omega_final else None,
            tip_envelope_error=series.envelope_error,
            envelope_window=series.window,
            angle_drift=series.angle_drift,
            angle_drift_final=series.angle_drift_final,
            lead=series.lead,
            lead_why=series.why,
        )
    walls = {m: per_model[m].wall_seconds for m in models}
    cost = {m: walls[m] / walls[ref] if walls[ref] > 0 else None for m in models}
    chart = f"compare_{case}.png"
    spectrum = _spectrum(scene, motion, runs) if case == "earthquake" else None
    study = None if pending is None else _finish_pareto(scene, pending, out, write, pareto_chart)
    result = CompareResult(
        case=case,
        models_run=models,
        reference=ref,
        excitation=motion.sizes() if motion is not None else None,
        per_model=per_model,
        errors=errors,
        cost_ratio=cost,
        chart=chart,
        window=CompareWindow(float(t_ref[0]), float(t_ref[-1]), float(duration), why, window),
        spectrum=spectrum,
        full_order_reference=_full_order_reference(runs),
        pareto=study,
    )
    if write:
        if compare_chart is not None:
            histories = [(m, runs[m].data["t"], runs[m].data["tip_x_relative"]) for m in models]
            compare_chart(
                Path(out) / chart,
                histories,
                ref,
                f"{scene.name}: {case}, tip relative to the ground, reference {ref}",
                errors={m: e.tip_history_error for m, e in errors.items()},
                walls=walls,
            )
        head = {"command": "compare", **provenance, "scene": given.to_dict()}
        write_result(
            Path(out) / f"compare_{case}.json",
            result,
            head,
            {**(timings or {}), "compare": time.perf_counter() - start},
        )
    return result


def compare_stem(case: str, model: str) -> str:
    """The stem of a comparison's per-model files: apart from the scene's own
    ``simulate_<case>_<model>.*`` (a comparison runs a window, or another excitation)."""
    return f"compare_{case}_{model}"


def _start_pareto(scene: Scene, motion, out: Path, workers: int, progress, chain):
    """The speed-against-accuracy study planned and its 3D runs started on ``workers`` - 1
    processes (this one runs compare's own models meanwhile; none: after them, here)."""
    from ..reduced.band import forcing_top
    from ..reduced.models import ModalModelInfo, build_model
    from .pareto import ParetoRunning, plan_pareto

    mesh = fem3d_plan(scene, "earthquake", motion, study_dir=out).mesh
    top = scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, "earthquake", motion)
    _, info = build_model(scene, "modal", top, pillar_modes=chain.modes)
    assert isinstance(info, ModalModelInfo)  # build_model's for "modal"
    plan = plan_pareto(
        scene, cache_dir=Path(out) / "cache", rom_modes=info.modes, chosen_mesh=mesh, pillar_modes=chain.modes
    )
    return ParetoRunning(plan, max(0, workers - 1), progress)


def _finish_pareto(scene: Scene, pending, out: Path, write: bool, chart) -> ParetoStudy:
    """The study, its chart drawn."""
    from ..records import replace

    study, _ = pending.finish()
    if write and chart is not None:
        name = "compare_earthquake_pareto.png"
        chart(
            study,
            Path(out) / name,
            f"{scene.name}: El Centro, speed against accuracy (errors against {study.reference.label})",
        )
        study = replace(study, chart=name)
    return study


def _full_order_reference(runs: dict[str, ModelRun]) -> FullOrderReference | None:
    """The 3D run's reference mesh and its error, or None without a 3D run."""
    if "fem3d" not in runs:
        return None
    record = runs["fem3d"].record
    return record.full_order.reference if isinstance(record, Fem3dRun) else None


def _peak(r: ReducedRun | Fem3dRun, key: str) -> float:
    """A run's peak (m); NaN where the run has none (written null, as a non-finite peak)."""
    value = r.max_abs.get(key)
    return math.nan if value is None else value


#: what a planar model leaves out of the spatial ROM's run beside it (the 3D full order takes it on)
PLANAR_BESIDE_SPATIAL = (
    "the ROM ran on the spatial model (the motor's reaction on the gondola, b2 relative to the "
    "gondola, the structural ratio), which this planar model leaves out: its difference from the "
    "ROM is partly the models' (--models modal,fem3d compares like with like)"
)


def _planar_beside_spatial(runs: dict) -> tuple[str, ...]:
    """What the planar full orders (beam, paper) beside a spatial ROM's run say they leave out
    (a beam run-up on paper with a tenth of its unbalance differed from the spatial ROM by 166 %,
    nearly all of it the motor's reaction the beam does not carry)."""
    modal = runs.get("modal")
    planes = getattr(modal.record, "planes", None) if modal is not None else None
    return (PLANAR_BESIDE_SPATIAL,) if planes is not None and planes.planes == "spatial" else ()


def _per_model(case: str, m: str, r: ReducedRun | Fem3dRun, left_out: tuple[str, ...] = ()) -> ComparedModel:
    stem = compare_stem(case, m)
    return ComparedModel(
        peak_tip_relative=_peak(r, "tip_x_relative"),
        peak_tip_absolute=_peak(r, "tip_x_absolute"),
        peak_shaft_deflection=_peak(r, "shaft_deflection"),
        omega_final=r.omega_final,
        wall_seconds=r.wall_seconds,
        compile_seconds=r.compile_seconds,
        dofs=r.dofs,
        ok=r.ok,
        warnings=tuple(r.warnings) + left_out,
        pillar_model=r.pillar_model,
        json=f"{stem}.json",
        npz=f"{stem}.npz",
    )


def _spectrum(scene: Scene, motion, runs: dict) -> ResponseSpectrum:
    """The record's spectrum, the coupled modes' periods, the ROM's spectral peak tip."""
    from ..reduced.band import forcing_top
    from ..reduced.excitation import response_spectrum
    from ..reduced.models import build_model
    from .cases import spectral_estimate

    model = runs["modal"].case_result.model if "modal" in runs else None
    note = ""
    if model is not None and model.pillar_modes is not None:
        computed = runs["modal"].record.max_abs["tip_x_relative"]
    else:
        # no planar ROM ran: the estimate takes the beam's (a spatial ROM's run, nrel5mw's with
        # three components, has no planar modes for it: it once stopped compare on an assertion)
        from ..scene import with_values

        if model is not None:
            note = "; the modal run is the spatial ROM's: the estimate is the beam's planar ROM's, not set beside it"

        beam = with_values(scene, {"modal_model.source": "beam"})
        model, _ = build_model(
            beam,
            "modal",
            scene.modal_model.band_factor * forcing_top(scene.drive, scene.load, scene.sweep, "earthquake", motion),
        )
        computed = None
    lo, hi, n = SPECTRUM_PERIODS
    periods = np.geomspace(lo, hi, n)
    rs = response_spectrum(motion, periods, damping=0.05)
    est = spectral_estimate(model, motion)
    return ResponseSpectrum(
        period=tuple(periods.tolist()),
        psa=tuple(rs.s_a.tolist()),
        damping=0.05,
        mode_periods=tuple(row.period for row in est.modes),
        spectral_peak_tip=est.srss_tip_estimate,
        computed_peak_tip=computed,
        modes=est.modes,
        note="the curve at 5 % damping (eqsig); the estimate takes the coupled rotor-pillar modes "
        "in X, each at its own damping ratio, combined by SRSS: an estimate, not a bound" + note,
        pillar_modes_only=est.pillar_modes_only,
    )


#: Rotor angles within this of each other (rad) keep the whirls in phase.
PHASE_LOCKED = 0.1


def running_peak(t: np.ndarray, x: np.ndarray, window: float) -> np.ndarray:
    """max |x| over [t - window/2, t + window/2] at each t (m): the peak envelope."""
    t, a = np.asarray(t, dtype=float), np.abs(np.asarray(x, dtype=float))
    lo = np.searchsorted(t, t - window / 2, side="left")
    hi = np.searchsorted(t, t + window / 2, side="right")
    out = np.empty_like(a)
    for i, (j, k) in enumerate(zip(lo, hi)):
        out[i] = a[j : max(k, j + 1)].max()
    return out


class SeriesErrors(Record):
    """One model's tip history against the reference's, on the reference's times."""

    history_error: float
    """max |x - x_ref| / max |x_ref| (-)"""
    envelope_error: float
    """max |env - env_ref| / max env_ref, env the running peak over ``window`` (-)"""
    window: float
    """the envelope's window: one period of the slowest resonance (s)"""
    peak_difference: float | None
    """max |x| / max |x_ref| - 1 (-)"""
    angle_drift: float | None
    """largest |theta - theta_ref| over the run (rad); None without rotor angles"""
    angle_drift_final: float | None
    """theta - theta_ref at the end (rad)"""
    lead: str
    """"history" or "envelope": the measure that fits the case"""
    why: str
    """why that measure leads, in words"""


def compare_series(t, x, t_ref, x_ref, *, window: float, theta=None, theta_ref=None) -> SeriesErrors:
    """The errors of ``x(t)`` against ``x_ref(t_ref)`` (see the module text).

    >>> import math
    >>> t = np.linspace(0.0, 10.0, 2001)
    >>> ref = np.sin(2 * np.pi * t)
    >>> late = np.sin(2 * np.pi * t - 0.5)          # the same whirl, half a radian behind
    >>> m = compare_series(t, late, t, ref, window=1.0, theta=0.5 + t, theta_ref=t)
    >>> round(m.history_error, 3), round(2 * math.sin(0.25), 3)   # the closed form: 2 sin(0.5 / 2)
    (0.495, 0.495)
    >>> round(m.envelope_error, 3), m.lead
    (0.0, 'envelope')
    """
    t_ref, x_ref = np.asarray(t_ref, dtype=float), np.asarray(x_ref, dtype=float)
    xi = np.interp(t_ref, np.asarray(t, dtype=float), np.asarray(x, dtype=float))
    scale = max(float(np.max(np.abs(x_ref))), 1e-300)
    hist = float(np.max(np.abs(xi - x_ref)) / scale)
    env, env_ref = running_peak(t_ref, xi, window), running_peak(t_ref, x_ref, window)
    envelope = float(np.max(np.abs(env - env_ref)) / max(float(np.max(env_ref)), 1e-300))
    peak_ref = float(np.max(np.abs(x_ref)))
    peak = float(np.max(np.abs(np.asarray(x, dtype=float))))
    drift = final = None
    if theta is not None and theta_ref is not None:
        th = np.interp(t_ref, np.asarray(t, dtype=float), np.asarray(theta, dtype=float))
        d = th - np.asarray(theta_ref, dtype=float)
        drift, final = float(np.max(np.abs(d))), float(d[-1])
    if drift is not None and drift >= PHASE_LOCKED:
        lead = "envelope"
        why = (
            f"the rotor angles drift apart by up to {drift:.3g} rad: the whirl's history error "
            "measures that phase drift, not the model; the envelope (the running peak over "
            f"{window:.3g} s) and the peak measure the model"
        )
    else:
        lead = "history"
        why = (
            "the rotors stay in phase (angle drift "
            + ("not measured" if drift is None else f"{drift:.2g} rad")
            + "): both models see the same forcing at the same time, so the history error "
            "measures the model"
        )
    return SeriesErrors(
        hist, envelope, float(window), peak / peak_ref - 1 if peak_ref > 0 else None, drift, final, lead, why
    )


def envelope_window(omegas) -> float:
    """One period of the slowest resonance (s), the envelope's window."""
    w = [float(o) for o in omegas if o and math.isfinite(o) and o > 0]
    return 2 * math.pi / min(w) if w else 1.0


COMPARE_COMMAND = "compare"

#: The comparisons `rotorpillar run` makes and the report shows: case -> the
#: arguments of `rotorpillar compare --case <case>` (``commands/run.py`` builds its stages
#: from these, the report's hints repeat them).  compare runs the scene's
#: excitation, so the earthquake sets the record: El Centro on the
#: physically consistent models (the modal ROM and the 3D full order), with
#: the speed-against-accuracy study of every model of the ladder; the run-up
#: puts the ROM beside the 3D full order too, over the window through its
#: resonances (rotorpillar.transients.window).
COMPARISONS = {
    # El Centro from 1 s after the start (the rotor whirling steadily before) over 9 s: its
    # strong motion and the tip's peak (2.6 s into the record on the paper's ROM) inside,
    # at 60 % of the 15 s the 3D run took with the record starting at 5 s
    "earthquake": (
        "--models",
        "modal,fem3d",
        "--pareto",
        "--set",
        "excitation.kind=record",
        "--set",
        "excitation.record=elcentro",
        "--set",
        "excitation.start=1",
        "--set",
        "full_order.earthquake_duration=9",
    ),
    "runup": ("--models", "modal,fem3d"),
}


def comparison_command(case: str) -> str:
    """The compare command line (without the scene) for one of :data:`COMPARISONS`.

    >>> comparison_command("runup")
    'compare --case runup --models modal,fem3d'
    """
    return " ".join((COMPARE_COMMAND, "--case", case, *COMPARISONS[case]))


def comparison_models(case: str) -> list[str]:
    """The models a comparison runs.

    >>> comparison_models("earthquake")
    ['modal', 'fem3d']
    """
    a = COMPARISONS[case]
    return a[a.index("--models") + 1].split(",")


def comparison_overrides(case: str) -> tuple[str, ...]:
    """The scene keys a comparison sets itself (its inputs differ from the
    scene there on purpose).

    >>> comparison_overrides("earthquake")
    ('excitation.kind', 'excitation.record', 'excitation.start', 'full_order.earthquake_duration')
    """
    a = COMPARISONS[case]
    return tuple(a[i + 1].split("=", 1)[0] for i, x in enumerate(a) if x == "--set")
