"""`rotorpillar compare`: several transient models on one case, against the most complete.

``rotorpillar compare [SCENE] --case earthquake|runup [--models m1,m2,...]``
(default models: modal,fem3d for the earthquake, modal,beam for the run-up).
rotorpillar.transients.compare runs each model as `simulate` does (writing
``simulate_<case>_<model>.{json,npz,csv,png}``) over one common duration,
and writes ``compare_<case>.json`` and ``compare_<case>.png``.
"""

from __future__ import annotations

from ..scene import MODELS


def add_arguments(p) -> None:
    p.add_argument("--case", choices=("earthquake", "runup"), default="earthquake",
                   help="the case compared (default: earthquake)")
    p.add_argument("--models", default=None, metavar="M1,M2",
                   help=f"comma-separated, among {', '.join(MODELS)}; default: modal,fem3d for the "
                        "earthquake, modal,beam for the run-up.  The reference is the most complete "
                        "model given: fem3d > beam > modal > paper")


def compare_command(scene, args, timings):
    from . import EXIT_CHECKS, is_root_rank, launched_ranks, mpi_progress, out_dir
    from ..errors import InputError
    from ..transients.compare import compare_models, parse_models
    case = args.case
    models = parse_models(args.models, case)
    if launched_ranks() > 1 and "fem3d" not in models:
        raise InputError(f"compare --models {','.join(models)} runs on one process (under mpirun only "
                         "the 3D full order, fem3d, shares its work): start it without mpirun")
    check_full_order_budgets(scene, case, models)          # before any model runs or writes
    progress = mpi_progress()
    provenance = {"scene_source": str(args.scene), "overrides": list(args.overrides)}
    from ..postprocess.comparison_charts import comparison_chart
    from ..postprocess.transient_charts import model_run_charts
    with timings("compare"):
        res = compare_models(scene, case, models, out_dir(scene, args), provenance, progress=progress,
                             write=is_root_rank(), run_charts=model_run_charts,
                             compare_chart=comparison_chart)
    doc = res.to_json()
    if any(p.get("ok") is False for p in res.per_model.values()):
        doc["exit_status"] = EXIT_CHECKS
    return doc, summary(scene, res)


def check_full_order_budgets(scene, case: str, models) -> None:
    """Refuse (InputError naming the keys) a full order above ``simulate.max_steps`` over
    the comparison's common duration, before the first model runs: the 3D one
    (fem3d.transient_plan) and the beam (reduced.cases.check_full_order_budget)."""
    from .simulate import check_fem3d_budget
    from ..reduced.cases import check_full_order_budget
    from ..reduced.models import scene_motion
    from ..transients.compare import common_duration
    from ..transients.run import with_duration
    motion = scene_motion(scene) if case == "earthquake" else None
    duration, _ = common_duration(scene, case, models, motion)
    if "fem3d" in models:
        check_fem3d_budget(scene, case, motion, duration)
    if "beam" in models:
        from ..reduced.excitation import no_motion
        check_full_order_budget(with_duration(scene, case, duration), case, motion or no_motion())


def summary(scene, r) -> str:
    lines = [f"rotorpillar compare {scene.name}: case {r.case}, reference {r.reference} "
             f"(over {r.window['start']:g}..{r.window['end']:g} s: {r.window['why']})"]
    for m in r.models_run:
        p = r.per_model[m]
        e = r.errors.get(m)
        err = ("reference" if e is None else
               f"tip history error {100 * e['tip_history_error']:.2f} %, peak "
               f"{100 * (e['peak_tip_difference'] or 0):+.2f} %")
        lines.append(f"  {m:6s} peak tip {p['peak_tip_relative']:.4g} m (relative), "
                     f"{p['dofs']} dofs, {p['wall_seconds']:.3g} s ({r.cost_ratio[m]:.3g} x); {err}")
        for w in p["warnings"]:
            lines.append(f"         WARNING: {w}")
    if r.spectrum:
        s = r.spectrum
        comp = f"{s['computed_peak_tip']:.4g} m" if s["computed_peak_tip"] is not None else "not run"
        lines.append(f"  response spectrum: spectral peak tip {s['spectral_peak_tip']:.4g} m (SRSS), "
                     f"computed (modal) {comp}")
    lines.append(f"  chart: {r.chart}")
    return "\n".join(lines)
