"""`rotorpillar converge`: the ladder of pillar models, refined, and the model a scene needs.

Writes ``convergence.json`` (every run, the reference values, observed
orders, Pareto fronts, failures and the chosen model), the two charts
``convergence_dofs.png`` and ``convergence_time.png``, and the usual
``converge.json`` record.  Runs are cached under ``<out>/cache/`` (or
``--cache DIR``): a second call, or one after an interruption, computes only
what is missing.
"""

from __future__ import annotations

import time
from pathlib import Path

from . import progress
from ..errors import InputError


def add_arguments(p) -> None:
    p.add_argument("--cache", type=Path, default=None, metavar="DIR",
                   help="run cache directory (default: <out>/cache)")
    p.add_argument("--tolerance", type=float, default=None, metavar="TOL",
                   help="relative frequency tolerance of the chosen model "
                        "(default: the scene's converge.tolerance)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def add_modal_arguments(p) -> None:
    """`rotorpillar modal --tolerance TOL`: run the model the study picks for TOL."""
    p.add_argument("--tolerance", type=float, default=None, metavar="TOL",
                   help="pick the cheapest 3D mesh that meets this relative frequency "
                        "tolerance over the scene's band, from the convergence study "
                        "(run, or loaded from its cache: see `rotorpillar converge`)")
    p.add_argument("--cache", type=Path, default=None, metavar="DIR",
                   help="the study's run cache (default: <out>/cache)")


def study(scene, *, out_dir: Path, cache_dir: Path | None = None, tolerance: float | None = None,
          show_progress: bool = True, charts: bool = True, timings=None) -> dict:
    """Run (or load) the study and analyse it; write convergence.json and the charts."""
    from .. import converge as cv
    from ..provenance import Timings, machine, versions, write_json

    timings = Timings() if timings is None else timings
    tol = scene.converge.tolerance if tolerance is None else tolerance
    if not 0 < tol < 1:
        raise InputError(f"--tolerance = {tol!r} is out of range: must be > 0 and < 1")
    cache_dir = Path(out_dir) / "cache" if cache_dir is None else Path(cache_dir)
    start = time.perf_counter()
    with timings("study"):
        records = cv.run_study(cv.study_cases(scene), scene, cache_dir,
                               progress=show_progress, log=progress)
    with timings("analysis"):
        analysis = cv.analyse(records, scene, tol)
    doc = {
        "scene_name": scene.name,
        "scene": scene.to_dict(),
        "tolerance": tol,
        "cache_dir": str(cache_dir),
        "families": {k: {"label": f.label, "model": f.model, "order_theory": f.order,
                         "quantities": list(f.quantities), "sweep": f.sweep}
                     for k, f in cv.FAMILIES.items()},
        "runs": records,
        **analysis,
        "study": {"runs": len(records), "cached": sum(bool(r.get("cached")) for r in records),
                  "computed": sum(not r.get("cached") for r in records),
                  "failed": sum(r.get("status") == "failed" for r in records),
                  "unavailable": sum(r.get("status") == "unavailable" for r in records),
                  "compute_seconds": sum(r.get("process_time", r.get("wall_time", 0.0)) or 0.0
                                         for r in records if not r.get("cached"))},
    }
    if charts:
        from ..postprocess.convergence_charts import convergence_charts
        with timings("charts"):
            doc["charts"] = {k: str(v) for k, v in convergence_charts(doc, out_dir).items()}
    doc["study"]["wall_time"] = time.perf_counter() - start
    doc.update(versions=versions(), machine=machine(), timings=dict(timings))
    doc["json"] = str(write_json(Path(out_dir) / "convergence.json", doc))
    return doc


def summary(doc: dict) -> str:
    ref, sel = doc["reference"], doc["selection"]
    lines = [f"rotorpillar converge {doc['scene_name']}: {doc['study']['runs']} runs "
             f"({doc['study']['cached']} cached, {doc['study']['computed']} computed, "
             f"{doc['study']['failed']} failed) in {doc['study']['wall_time']:.0f} s", "",
             "Reference values (Richardson on the finest three runs):"]
    for q, r in ref.items():
        p = "n/a" if r["order"] is None else f"{r['order']:.2f}"
        lines.append(f"  first {q:9s} {r['value']:10.4f} rad/s +- {r['error_estimate']:.1e} "
                     f"({doc['families'][r['family']]['label']}; observed order {p}, "
                     f"theory {r['order_theory']:g})")
        if "check" in r:
            c = r["check"]
            lines.append(f"    check: from the three runs before, {c['value']:.4f} +- "
                         f"{c['error_estimate']:.1e}; the finer run gives {c['finer_value']:.4f} "
                         f"({'within' if c['within_estimate'] else 'OUTSIDE'} the estimate)")
    lines += ["", "Observed orders per family (theory in brackets):"]
    for fam, qs in doc["extrapolations"].items():
        parts = [f"{q} {('n/a' if e['order'] is None else format(e['order'], '.2f'))} "
                 f"[{e['order_theory']:g}] -> {e['value']:.4f}" for q, e in qs.items()]
        lines.append(f"  {doc['families'][fam]['label']:34s} " + "; ".join(parts))
    b = sel["band"]
    lines += ["", f"Band: up to {b['omega_max']:.1f} rad/s = {b['margin']:g} x "
                  f"max(drive free speed {b['free_speed']:.1f}, earthquake "
                  f"{b['earthquake_frequency']:.2f}) rad/s; needs: {', '.join(sel['needed'])}",
              f"Pareto front (band error vs wall time): "
              + ", ".join(doc["pareto"]["wall_time"]["band"])]
    lines += ["", f"Chosen at tolerance {sel['tolerance']:g}: "
              + (sel["chosen"]["label"] if sel["chosen"] else "none"), "  " + sel["reason"]]
    if doc["failures"]:
        lines += ["", "Where methods fail:"] + [f"  - {f}" for f in doc["failures"]]
    if "charts" in doc:
        lines += ["", "charts: " + ", ".join(doc["charts"].values()), f"study: {doc['json']}"]
    return "\n".join(lines)


def model_for_modal(scene, tolerance: float, out_dir: Path, *, cache_dir: Path | None = None,
                    timings=None):
    """The scene with the [mesh] the study picks for ``tolerance``, and why.

    `modal` computes the 3D model, so the choice is among the 3D families;
    the cheapest model of all (a shell, a beam) is reported beside it.
    Serially the study runs what its cache lacks; under MPI it must be
    cached already (`rotorpillar converge` first), since its runs are
    subprocesses.
    """
    import dataclasses
    from mpi4py import MPI
    from .. import converge as cv

    if MPI.COMM_WORLD.size > 1:
        def runner(case, sc):
            raise InputError(f"modal --tolerance under MPI needs the convergence study cached "
                             f"({case.label} is not): run `rotorpillar converge {scene.name}` "
                             "serially first")
        cases = cv.study_cases(scene)
        cache = Path(out_dir) / "cache" if cache_dir is None else Path(cache_dir)
        records = cv.run_study(cases, scene, cache, runner=runner, progress=False)
        analysis = cv.analyse(records, scene, tolerance)
        doc = {"runs": records, **analysis, "json": None}
    else:
        doc = study(scene, out_dir=out_dir, cache_dir=cache_dir, tolerance=tolerance,
                    timings=timings)
    solid = [k for k, f in cv.FAMILIES.items() if f.model == "solid"]
    sel = cv.select_model(doc["runs"], doc["reference"], doc["band"], tolerance, families=solid)
    if sel["chosen"] is None:
        raise InputError(f"--tolerance = {tolerance:g}: no 3D model of the study meets it "
                         "(raise converge.solid_p2_max_around, or loosen the tolerance)")
    chosen = sel["chosen"]
    p = chosen["params"]
    mesh = dataclasses.replace(scene.mesh, elements_around=p["elements_around"],
                               elements_along=p["elements_along"],
                               elements_through=p["elements_through"], degree=p["degree"],
                               cell_type=p["cell_type"], grading=p["grading"])
    overall = doc["selection"]["chosen"]
    lines = [f"Model chosen for tolerance {tolerance:g}: {chosen['label']} "
             f"({chosen['dofs']:,} DOFs, {chosen['wall_time']:.1f} s for the bare tube in the study).",
             "Why: " + sel["reason"],
             "The same mesh carries the top mass (the study's errors are the bare tube's)."]
    if overall is not None and overall["label"] != chosen["label"]:
        lines.append(f"Cheapest of all models at this tolerance: {overall['label']} "
                     f"({overall['wall_time']:.2f} s), not a 3D model: `rotorpillar converge` "
                     "has it.")
    if doc.get("json"):
        lines.append(f"Study: {doc['json']}")
    selection = {"tolerance": tolerance, "chosen": chosen, "reason": sel["reason"],
                 "rule": sel["rule"], "band": sel["band"], "needed": sel["needed"],
                 "rejected_cheaper": sel["rejected_cheaper"], "overall_cheapest": overall,
                 "convergence_json": doc.get("json"), "text": "\n".join(lines)}
    return dataclasses.replace(scene, mesh=mesh), selection


def _under_mpi() -> bool:
    import os
    return any(int(os.environ.get(k, "1")) > 1 for k in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE"))


def converge_command(scene, args, timings):
    from . import out_dir
    if _under_mpi():
        raise InputError("rotorpillar converge runs serially (each run is its own "
                         "subprocess): start it without mpirun")
    doc = study(scene, out_dir=out_dir(scene, args), cache_dir=args.cache,
                tolerance=args.tolerance, show_progress=not args.no_progress, timings=timings)
    result = {"convergence_json": doc["json"], "charts": doc.get("charts", {}),
              "tolerance": doc["tolerance"], "reference": doc["reference"],
              "selection": doc["selection"], "failures": doc["failures"], "study": doc["study"]}
    return result, summary(doc)
