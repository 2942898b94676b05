"""The convergence study's choice of a model (and the reasons), its
reference frequencies and failures, and the integrator study."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .. import html as h
from ..readers import INPUTS
from .parts import band_keys, figures_of, scene_differs
from .state import Build

if TYPE_CHECKING:
    from ...converge.result import ConvergenceStudy
    from ...records import Record
    from ...transients.integrator_study import IntegratorStudy, MethodSummary


def chosen(study: ConvergenceStudy) -> tuple[str, str] | None:
    """(what, why) of the model choice in convergence.json's ``selection``, or None."""
    sel = study.selection
    c = sel.chosen
    if c is None:
        return None
    band, needed = sel.band, sel.needed
    # the error bound as the rule defines it, the reference's uncertainty included: the
    # same number as the pillar model's line and the rejected runs' (one definition)
    unc = sel.reference_uncertainty
    bounds = ", ".join(
        f"{q} {(getattr(c, f'{q}_error_bound') or 0.0) + unc.get(q, 0.0):.1e}"
        f" (|model| + |discretisation| {getattr(c, f'{q}_error_bound') or 0.0:.1e}, reference {unc.get(q, 0.0):.1e})"
        for q in needed
    )
    why = (
        f"the cheapest run whose error bound meets the tolerance {h.num(sel.tolerance)} "
        f"on every frequency the scene excites: the band up to "
        f"{h.num(band.omega_max, 4)} rad/s ({h.num(band.margin)} x the "
        f"{band.driver or 'highest excitation'}) holds "
        f"{', '.join(needed) or 'no mode'}; its bounds: {bounds}"
    )
    return (f"{c.label} ({c.dofs} DOFs, {h.num(c.wall_time, 3)} s)", why)


def _choice(study: ConvergenceStudy) -> list[str]:
    """The model chosen, why, and the cheaper ones that do not meet the tolerance."""
    what = chosen(study)
    if not what:
        return [h.tag("p", "convergence.json names no chosen model (no run meets the tolerance).", class_="meta")]
    sel = study.selection
    parts = [h.tag("p", [h.tag("strong", "Chosen: "), what[0]]), h.tag("p", [h.tag("strong", "Why: "), what[1] + "."])]
    if sel.rule:
        parts.append(h.tag("p", f"Rule: {sel.rule}.", class_="meta"))
    if sel.rejected_cheaper:
        parts.append(h.tag("h3", "Cheaper models that do not meet it"))
        parts.append(
            h.table(
                ["model", "DOFs", "wall time (s)", "why not"],
                [[r.label, r.dofs, h.num(r.wall_time, 3), r.why] for r in sel.rejected_cheaper],
            )
        )
    return parts


def _references(study: ConvergenceStudy) -> list[str]:
    """The Richardson reference of each frequency and its check on the finest run."""
    if not study.reference:
        return []
    rows = [
        [
            q,
            h.num(r.value, 7),
            h.num(r.error_estimate, 2),
            h.num(r.order, 3),
            h.num(r.order_theory, 2),
            ", ".join(r.runs),
            ("yes" if r.check.within_estimate else "no") if r.check is not None else "-",
        ]
        for q, r in study.reference.items()
    ]
    return [
        h.tag("h3", "Reference frequencies (Richardson extrapolation)"),
        h.table(
            [
                "mode",
                "reference (rad/s)",
                "+- estimate (rad/s)",
                "observed order (-)",
                "order in theory (-)",
                "from",
                "three coarser runs predict the finest",
            ],
            rows,
        ),
    ]


def cancellation(study: ConvergenceStudy) -> str | None:
    """The sentence on a model whose measured error sits under the tolerance
    by cancellation (its model and mesh errors of opposite signs) and that
    the choice rejects all the same, from the study's runs; None if none."""
    sel = study.selection
    tol, need = sel.tolerance, sel.needed
    if not need:
        return None
    for r in sorted(study.runs, key=lambda r: r.wall_time or 0.0):
        if r.status != "ok":
            continue
        e = [getattr(r, f"{q}_error") for q in need]
        b = [getattr(r, f"{q}_error_bound") for q in need]
        if any(x is None for x in e + b) or not all(abs(x) <= tol for x in e) or max(b) <= tol:
            continue
        q = need[b.index(max(b))]
        m, d = getattr(r, f"{q}_model_error"), getattr(r, f"{q}_discretisation_error")
        if m is None or d is None or m * d >= 0:
            continue
        return (
            f"A model can sit under the tolerance line and still be rejected: {r.label} "
            f"measures {'an' if q[0] in 'aeiou' else 'a'} {q} error of "
            f"{e[need.index(q)]:+.1e}, below {tol:g}, only because its "
            f"model error ({m:+.1e}, the shell theory's) and its mesh error ({d:+.1e}) have "
            f"opposite signs and cancel; a finer mesh would remove the one and leave the "
            f"other, so the choice counts |model| + |mesh| + the reference's uncertainty "
            f"({max(b):.1e}), over the tolerance."
        )
    return None


def _convergence_parts(study: ConvergenceStudy) -> list[str]:
    parts = _choice(study)
    said = cancellation(study)
    if said:
        parts.append(h.tag("p", said))
    parts += _references(study)
    failures = list(study.failures)
    if failures:
        parts.append(h.tag("h3", "Where each method fails"))
        parts.append(h.tag("ul", [h.tag("li", f) for f in failures]))
    return parts


def section_convergence(build: Build) -> str:
    c = build.convergence
    parts = []
    if c is None:
        parts.append(h.missing(build.hint(INPUTS["convergence"][1])))
        a = build.analysis
        if a is not None:
            parts.append(
                h.tag(
                    "p",
                    "Until the study runs, the headline model's pillar is "
                    f"{a.pillar_model.describe()}: {a.pillar_model.note}.",
                )
            )
    else:
        from ...chain.choice import band_mismatch

        # a study run for another drive answers for this one when the band holds the same
        # modes (the chain uses it, and the pillar model's note says so): no warning for that
        same_modes = band_keys(build) if band_mismatch(build.scene, c) is None else ()
        parts += scene_differs(build, build.provenance.convergence, same_modes)
        parts += _convergence_parts(c)
    parts += figures_of(build, "convergence")
    return h.section("convergence", "Convergence and the model chosen", parts)


def _best(per: dict[str, MethodSummary], key: str, among=None) -> tuple[str | None, float | None]:
    """(method, value) with the smallest positive ``key`` (a field of the methods'
    summaries) in per_method (among ``among``)."""
    vals = [
        (m, v)
        for m, v in ((m, getattr(s, key)) for m, s in per.items() if among is None or m in among)
        if isinstance(v, (int, float)) and v > 0
    ]
    return min(vals, key=lambda x: x[1]) if vals else (None, None)


def integrators_conclusion(study: IntegratorStudy) -> str:
    """One paragraph from integrators.json: which integrator for which case,
    where each fails."""
    acc, stab = study.accuracy, study.stability
    per = acc.per_method
    growth = stab.cost_growth
    fixed = {r.method for r in acc.rows if r.family == "fixed"}
    adaptive = set(per) - fixed
    said = []
    m, n = _best(per, "nfev_at_1e_6", adaptive)
    if m:
        said.append(
            f"On the reduced models (a few degrees of freedom, the band's modes only) an "
            f"explicit adaptive method is the right tool: {m} reaches a 1e-6 error in the "
            f"fewest force evaluations ({n:.0f}); dp5, the default, is the same "
            f"Dormand-Prince pair as scipy's RK45, compiled, so their points coincide."
        )
    # central difference is explicit: its cost stays flat only until it blows up (below)
    flat = sorted(k for k, g in growth.items() if g.factor == 1 and k in fixed and "central" not in k)
    steep = sorted(
        ((k, g.factor) for k, g in growth.items() if isinstance(g.factor, (int, float)) and k in adaptive),
        key=lambda x: -x[1],
    )
    if flat and steep:
        said.append(
            f"As stiffer modes are added (a beam or 3D full order), the explicit methods' "
            f"cost grows with the highest frequency ({steep[0][0]}: x{steep[0][1]:.3g} "
            f"from {growth[steep[0][0]].modes[0]} to {growth[steep[0][0]].modes[-1]} "
            f"modes) while the implicit fixed-step ones ({', '.join(flat)}) cost the same: "
            "for stiff full-order models use Newmark (energy-conserving) or, to damp "
            "the unresolved high modes, HHT or generalised-alpha."
        )
    fails = [f"{k}: {v.fails}" for k, v in sorted(per.items()) if v.fails and not str(v.fails).startswith("no failure")]
    for k, f in stab.first_failure.items():
        if f is not None and f.omega_max:
            fails.append(
                f"{k}: unstable once the highest frequency reaches "
                f"{f.omega_max:.4g} rad/s (h omega_max = "
                f"{f.h_times_omega_max:.3g} > 2)"
            )
    if fails:
        said.append("Where each fails: " + "; ".join(fails) + ".")
    return " ".join(said)


def _rows_table(rows: Sequence[Record], columns: list[tuple[str, str]]) -> str:
    """The rows' fields (``columns``: field, header with its unit) as a table."""
    return h.table([c for _, c in columns], [[h.num(getattr(r, k, None), 4) for k, _ in columns] for r in rows])


def section_integrators(build: Build) -> str:
    parts = []
    study = build.integrators
    if study is None:
        parts.append(h.missing(build.hint(INPUTS["integrators"][1])))
    else:
        parts += scene_differs(build, build.provenance.integrators)
        said = integrators_conclusion(study)
        if said:
            parts.append(h.tag("p", said))
    parts += figures_of(build, "integrators")
    if study is not None:
        acc, stab, drift = study.accuracy, study.stability, study.energy_drift
        if acc.rows:
            parts.append(
                h.details(
                    f"accuracy runs ({len(acc.rows)})",
                    _rows_table(
                        acc.rows,
                        [
                            ("method", "method"),
                            ("family", "family"),
                            ("setting_name", "setting"),
                            ("setting", "its value (s or -)"),
                            ("error", "tip history error (-)"),
                            ("nfev", "force evaluations"),
                            ("wall_seconds", "wall time (s)"),
                            ("status", "status"),
                        ],
                    ),
                )
            )
        if stab.rows:
            parts.append(
                h.details(
                    f"stiffness runs ({len(stab.rows)})",
                    _rows_table(
                        stab.rows,
                        [
                            ("method", "method"),
                            ("modes", "pillar modes"),
                            ("omega_max", "highest frequency (rad/s)"),
                            ("ok", "solved"),
                            ("nfev", "force evaluations"),
                            ("time_step", "time step (s)"),
                            ("status", "status"),
                        ],
                    ),
                )
            )
        if drift.rows:
            parts.append(
                h.details(
                    f"energy drift runs ({len(drift.rows)})",
                    _rows_table(
                        drift.rows,
                        [
                            ("method", "method"),
                            ("drift", "energy drift (-)"),
                            ("max_deviation", "largest energy deviation (-)"),
                            ("nfev", "force evaluations"),
                            ("setting", "setting (s or -)"),
                            ("status", "status"),
                        ],
                    ),
                )
            )
    return h.section("integrators", "Time integrators", parts)
