"""`rotorpillar compare`: several transient models on one case, against the most complete.

``rotorpillar compare [SCENE] --case earthquake|runup [--models m1,m2,...]``
(default models: modal,fem3d for the earthquake, modal,beam for the run-up).
rotorpillar.transients.compare runs each model as `simulate` does, on the
chain's pillar model (writing ``compare_<case>_<model>.{json,npz,csv,png}``)
over one common duration, and writes ``compare_<case>.json`` and
``compare_<case>.png``.

``--case earthquake --components 2|3``: the earthquake in that many components
(the scene's record and its ``second_record``, ``vertical_record``) on the
spatial ROM over the whole record against the 3D full order over
``full_order.earthquake_duration`` from the start, the base reactions in six
components (rotorpillar.transients.components); writes
``compare_earthquake_components.json``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..scene import MODELS, Scene

if TYPE_CHECKING:
    from ..transients.compare import CompareResult


def add_arguments(p) -> None:
    p.add_argument(
        "--case", choices=("earthquake", "runup"), default="earthquake", help="the case compared (default: earthquake)"
    )
    p.add_argument(
        "--models",
        default=None,
        metavar="M1,M2",
        help=f"comma-separated, among {', '.join(MODELS)}; default: modal,fem3d for the "
        "earthquake, modal,beam for the run-up.  The reference is the most complete "
        "model given: fem3d > beam > modal > paper",
    )
    p.add_argument(
        "--pareto",
        action="store_true",
        help="earthquake against fem3d: also the speed-against-accuracy study (the ROM by "
        "its modes, beams and 3D meshes on El Centro, errors against the finest 3D "
        "run; each run cached under cache/): compare_earthquake.json's pareto",
    )
    p.add_argument(
        "--components",
        type=int,
        choices=(2, 3),
        default=None,
        help="earthquake: the record in 2 or 3 components (sets excitation.components) on the spatial ROM "
        "against the 3D full order, six base reactions: compare_earthquake_components.json",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="processes for the speed-against-accuracy study's 3D runs (default: one per core)",
    )


def preflight(scene: Scene, args) -> None:
    """What `compare` refuses before any work (`run` calls it for its stages too): the
    models, MPI, the record, the common duration and each model's run
    (commands.simulate.check_run: the 3D plan, mesh and step budget, the reduced runs'
    step budgets)."""
    from ..errors import InputError
    from ..reduced.models import scene_motion
    from ..transients.compare import common_duration, parse_models
    from . import launched_ranks
    from .simulate import check_run

    if getattr(args, "components", None) is not None:
        if args.case != "earthquake":
            raise InputError(f"--components {args.components}: only with --case earthquake")
        if scene.excitation.kind != "record":
            raise InputError(
                f'--components {args.components}: needs excitation.kind = "record" (the paper\'s pulse has one component)'
            )
        return
    models = parse_models(args.models, args.case)
    motion = scene_motion(scene) if args.case == "earthquake" else None
    duration, _ = common_duration(scene, args.case, models, motion)
    if launched_ranks() > 1 and "fem3d" not in models:
        raise InputError(
            f"compare --models {','.join(models)} runs on one process (under mpirun only "
            "the 3D full order, fem3d, shares its work): start it without mpirun"
        )
    for m in models:  # the full orders' budgets over the common duration
        check_run(scene, args.case, m, motion=motion, duration=duration)
    if getattr(args, "pareto", False) and args.case == "earthquake" and "fem3d" in models:
        from ..transients.pareto_runs import pareto_estimate
        from . import mpi_progress

        mpi_progress()(pareto_estimate(scene))  # its 3D runs: estimated, or refused, before any work


def compare_command(scene: Scene, args, timings):
    from ..transients.compare import compare_models, parse_models
    from . import EXIT_CHECKS, Done, is_root_rank, launched_ranks, mpi_progress, out_dir

    preflight(scene, args)
    if getattr(args, "components", None) is not None:
        return _components(scene, args, timings)
    case = args.case
    models = parse_models(args.models, case)
    progress = mpi_progress()
    provenance = {"scene_source": str(args.scene), "overrides": list(args.overrides)}
    from ..errors import InputError
    from ..executor import default_workers
    from ..postprocess.compare_charts import comparison_chart
    from ..postprocess.pareto_charts import pareto_chart
    from ..postprocess.transient_charts import model_run_charts

    workers = getattr(args, "workers", None)
    if workers is not None and workers < 1:
        raise InputError(f"--workers {workers}: must be >= 1")
    chain = None
    if any(m in ("modal", "fem3d") for m in models):
        from ..chain import resolve
        from ..reduced.models import scene_motion

        with timings("pillar_modes"):
            chain = resolve(
                scene,
                out_dir(scene, args),
                progress=progress,
                motion=scene_motion(scene) if case == "earthquake" else None,
            )
    with timings("compare"):
        res = compare_models(
            scene,
            case,
            models,
            out_dir(scene, args),
            provenance,
            progress=progress,
            write=is_root_rank(),
            collective=launched_ranks() > 1,
            run_charts=model_run_charts,
            compare_chart=comparison_chart,
            pareto=getattr(args, "pareto", False),
            pareto_chart=pareto_chart,
            workers=workers or default_workers(),
            chain=chain,
            timings=timings,
        )
    for run in res.per_model.values():
        for warning in run.warnings:
            progress(f"warning: {warning}")
    status = EXIT_CHECKS if any(not p.ok for p in res.per_model.values()) else 0
    return Done(res, _summary(scene, res), status)


#: the multi-component comparison's JSON (its stage's ``RunStage.stem`` in `run`)
COMPONENTS_STEM = "compare_earthquake_components"


def _components(scene: Scene, args, timings):
    """--components: the spatial ROM against the 3D full order under 2 or 3 components."""
    from pathlib import Path

    from ..chain import resolve
    from ..provenance import write_result
    from ..reduced.ground3d import scene_spatial_motion
    from ..scene import with_values
    from ..transients.components import compare_components
    from . import Done, is_root_rank, mpi_progress, out_dir

    scene = with_values(scene, {"excitation.components": args.components})
    progress = mpi_progress()
    out = out_dir(scene, args)
    with timings("pillar_modes"):
        chain = resolve(scene, out, progress=progress, motion=scene_spatial_motion(scene.excitation).components[0])
    with timings("compare"):
        r = compare_components(scene, chain, progress=progress)
    for w in r.warnings:
        progress(f"warning: {w}")
    if is_root_rank():
        head = {
            "command": "compare",
            "scene_source": str(args.scene),
            "overrides": list(args.overrides),
            "scene": scene.to_dict(),
        }
        write_result(Path(out) / f"{COMPONENTS_STEM}.json", r, head, dict(timings))
    lines = [
        f"rotorpillar compare {scene.name}: earthquake in {len(r.components)} components "
        f"({', '.join(r.components)}); the spatial ROM over {r.modal_duration:.3g} s ({r.modal_seconds:.3g} s), "
        f"the 3D full order over {r.window:g} s ({r.fem3d_seconds or 0:.3g} s)",
        f"  {'peak':<14} {'ROM (record)':>14} {'ROM (window)':>14} {'3D (window)':>14}",
    ]
    for p in (*r.peaks, r.sum_of_maxima, *r.peak_tip):
        f3 = "-" if p.fem3d is None else f"{p.fem3d:14.5g}"
        rel = "" if p.relative is None else f"  {100 * p.relative:+.1f} %"
        lines.append(f"  {p.name:<14} {p.modal:14.5g} {p.modal_window:14.5g} {f3:>14} {p.unit}{rel}")
    lines += [f"  WARNING: {w}" for w in r.warnings]
    lines.append(f"  wrote {COMPONENTS_STEM}.json")
    return Done(r, "\n".join(lines))


def _summary(scene: Scene, r: CompareResult) -> str:
    w = r.window
    lines = [
        f"rotorpillar compare {scene.name}: case {r.case}, reference {r.reference} "
        f"(over {w.start:g}..{w.end:g} s: {w.why})"
    ]
    for m in r.models_run:
        p = r.per_model[m]
        e = r.errors.get(m)
        lead = 0.0 if e is None else (e.tip_history_error if e.lead == "history" else e.tip_envelope_error)
        err = (
            "reference"
            if e is None
            else f"tip {e.lead} error {100 * lead:.2f} % (leads: "
            f"{'rotors in phase' if e.lead == 'history' else 'the rotor angles drift'}), "
            f"history {100 * e.tip_history_error:.2f} %, envelope "
            f"{100 * e.tip_envelope_error:.2f} %, peak {100 * (e.peak_tip_difference or 0):+.2f} %"
            + ("" if e.angle_drift is None else f", rotor angle drift {e.angle_drift:.3g} rad")
        )
        lines.append(
            f"  {m:6s} peak tip {p.peak_tip_relative:.4g} m (relative), "
            f"{p.dofs} dofs, {p.wall_seconds:.3g} s ({r.cost_ratio[m]:.3g} x); {err}"
        )
        for warning in p.warnings:
            lines.append(f"         WARNING: {warning}")
    if r.spectrum:
        s = r.spectrum
        comp = f"{s.computed_peak_tip:.4g} m" if s.computed_peak_tip is not None else "not run"
        lines.append(
            f"  response spectrum: spectral peak tip {s.spectral_peak_tip:.4g} m (SRSS over the coupled modes), computed (modal) {comp}"
        )
    if r.pareto and r.pareto.cost:  # a finished study: its runs done, their cost known
        pa, cost = r.pareto, r.pareto.cost
        lines.append(
            f"  speed against accuracy ({cost.runs} runs, {cost.computed} "
            f"computed in {cost.wall_seconds:.3g} s): errors against "
            f"{pa.reference.label} (own peak error {_pct(pa.reference.peak_error)}, "
            f"{pa.reference.method}); {pa.chosen.why}"
        )
    if r.full_order_reference:
        lines.append(f"  3D reference: {r.full_order_reference.statement}")
    lines.append(f"  chart: {r.chart}")
    return "\n".join(lines)


def _pct(x) -> str:
    return "-" if x is None else f"{100 * abs(x):.2g} %"
