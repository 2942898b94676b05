"""The convergence study's choice of a model (and the reasons), its
reference frequencies and failures, and the integrator study."""

from __future__ import annotations

from .. import html as h
from ..inputs import INPUTS, entries, plain
from .parts import figures_of, run_table, scene_differs
from .state import Build


def chosen(study) -> tuple[str, str] | None:
    """(what, why) of the model choice in convergence.json's ``selection``, or None."""
    sel = getattr(study, "selection", None)
    c = getattr(sel, "chosen", None)
    if c is None:
        return None
    band, needed = sel.band, sel.needed or []
    bounds = ", ".join(f"{q} {h.num(getattr(c, f'{q}_error_bound', None), 2)}" for q in needed)
    why = (f"the cheapest run whose error bound meets the tolerance {h.num(sel.tolerance)} on "
           f"every frequency the scene excites: the band up to {h.num(band.omega_max, 4)} rad/s "
           f"({h.num(band.margin)} x the {getattr(band, 'driver', 'highest excitation')}) holds "
           f"{', '.join(needed) or 'no mode'}; its bounds: {bounds}")
    return f"{c.label} ({c.dofs} DOFs, {h.num(c.wall_time, 3)} s)", why


def _choice(study) -> list[str]:
    """The model chosen, why, and the cheaper ones that do not meet the tolerance."""
    what = chosen(study)
    if not what:
        return [h.tag("p", "convergence.json names no chosen model (no run meets the "
                           "tolerance).", class_="meta")]
    sel = study.selection
    parts = [h.tag("p", [h.tag("strong", "Chosen: "), what[0]]),
             h.tag("p", [h.tag("strong", "Why: "), what[1] + "."])]
    if sel.rule:
        parts.append(h.tag("p", f"Rule: {sel.rule}.", class_="meta"))
    rejected = getattr(sel, "rejected_cheaper", None) or []
    if rejected:
        parts.append(h.tag("h3", "Cheaper models that do not meet it"))
        parts.append(h.table(["model", "DOFs", "wall time (s)", "why not"],
                             [[r.label, r.dofs, h.num(r.wall_time, 3), r.why] for r in rejected]))
    return parts


def _references(study) -> list[str]:
    """The Richardson reference of each frequency and its check on the finest run."""
    ref = entries(getattr(study, "reference", None))
    if not ref:
        return []
    rows = []
    for q, r in ref:
        chk = getattr(r, "check", None)
        rows.append([q, h.num(r.value, 7), h.num(r.error_estimate, 2), h.num(r.order, 3),
                     h.num(r.order_theory, 2), ", ".join(getattr(r, "runs", None) or []),
                     ("yes" if chk.within_estimate else "no") if chk else "-"])
    return [h.tag("h3", "Reference frequencies (Richardson extrapolation)"),
            h.table(["mode", "reference (rad/s)", "+- estimate", "observed order", "theory", "from",
                     "three coarser runs predict the finest"], rows)]


def _convergence_parts(study) -> list[str]:
    parts = _choice(study) + _references(study)
    failures = getattr(study, "failures", None) or []
    if failures:
        parts.append(h.tag("h3", "Where each method fails"))
        parts.append(h.tag("ul", [h.tag("li", f) for f in failures]))
    slim = {k: v for k, v in plain(study).items()
            if k not in ("runs", "families", "selection", "reference", "failures", "extrapolations")}
    parts.append(h.details("convergence.json (less its runs)", run_table(slim)))
    return parts


def section_convergence(build: Build) -> str:
    c = build.convergence
    parts = []
    if c is None:
        parts.append(h.missing(build.hint(INPUTS["convergence"][1])))
        a = build.analysis
        if a is not None:
            parts.append(h.tag("p", "Until the study runs, the headline model's pillar is "
                                    f"{a.pillar_model.describe()}: {a.pillar_model.note}."))
    else:
        parts += scene_differs(build, c)
        parts += _convergence_parts(c)
    parts += figures_of(build, "convergence")
    parts.append(h.tag("h3", "Integrators"))
    if build.integrators is None:
        parts.append(h.missing(build.hint(INPUTS["integrators"][1])))
    else:
        parts += scene_differs(build, build.integrators)
        parts.append(h.details("integrators.json", run_table(build.integrators)))
    parts += figures_of(build, "integrators")
    return h.section("convergence", "Convergence and the model chosen", parts)
