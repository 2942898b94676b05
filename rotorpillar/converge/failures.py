"""Where each method fails, in words, from the data of the study."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

from msgspec.structs import replace

from .ladder import FAMILIES, N_MODES, ORDER_NOTES, Family
from .result import ConvergenceRun, Extrapolation, OvallingAlias, Param, ReferenceValue

Extrapolations = Mapping[str, Mapping[str, Extrapolation]]
"""Per refined family, per quantity: Richardson on its three finest runs."""


def _why(
    name: str,
    fam: Family,
    q: str,
    rows: list[ConvergenceRun],
    extrapolations: Extrapolations,
    reference: Mapping[str, ReferenceValue],
) -> str:
    """The likely cause of a family's error floor on quantity q, from its data."""
    ex = extrapolations.get(name, {}).get(q)
    ref = reference[q]
    if fam.model in ("beam", "closed_form"):
        limit = ex.value if ex is not None else rows[-1].frequency(q)
        if limit is None:
            return "model error"
        gap = (limit - ref.value) / ref.value
        return f"model error: its own limit {limit:.4f} rad/s is {gap:+.1e} from the reference"
    if fam.sweep and q == "bending":
        along = rows[-1].params["elements_along"]
        return f"the bending mode is set by the cells along, fixed at {along} here: more cells around do not help it"
    if fam.sweep:
        coarse = min(rows, key=lambda r: r.level)
        e = coarse.relative_error(q)
        return (
            f"too few elements around: {coarse.params['elements_around']} around gives "
            + ("no such mode" if e is None else f"{e:+.1e}")
            + f" with {coarse.params['elements_along']} along"
        )
    if fam.model == "solid" and case_degree(rows[-1].params) == 1:
        return "locking: linear elements across a thin wall are far too stiff in bending"
    if ex is not None and ex.order is not None and ex.order_theory is not None and ex.order < 0.6 * ex.order_theory:
        return (
            f"locking: the error falls at order {ex.order:.1f}, not {ex.order_theory:g}, "
            "as the wall's bending is over-stiffened"
        )
    if ex is not None:
        gap = (ex.value - ref.value) / ref.value
        if abs(gap) > 0.5 * (ex.error_estimate + ref.error_estimate) / abs(ref.value) and abs(gap) > 1e-4:
            return f"its limit differs from the reference by {gap:+.1e} (model error)"
    return "the meshes of the convergence study are too coarse for it"


def nyquist(params: Mapping[str, Param]) -> int:
    """The highest circumferential wave number a mesh's nodes around can carry (its
    discretisation ``params``: elements_around, degree)."""
    return int(params.get("elements_around", 10**6)) * int(params.get("degree", 1)) // 2


def case_degree(params: Mapping[str, Param]) -> int:
    """The element degree of a run's discretisation (0: not a finite-element mesh)."""
    return int(params.get("degree", 0))


def failures(
    runs: Sequence[ConvergenceRun],
    extrapolations: Extrapolations,
    reference: Mapping[str, ReferenceValue],
    tolerance: float,
) -> list[str]:
    """Where each method fails, in words, from the data."""
    out = []
    no_shell = [FAMILIES[f].label for f in ("beam_euler", "beam_timoshenko") if any(r.family == f for r in runs)]
    if no_shell:
        out.append(
            "no shell modes: " + " and ".join(no_shell) + " have no ovalling mode at all "
            "(the ring closed form estimates it, for a long tube only)"
        )
    for name, fam in FAMILIES.items():
        rows = sorted((r for r in runs if r.family == name and r.status == "ok"), key=lambda r: r.level)
        if not rows:
            continue
        for q in fam.quantities:
            if q not in reference:
                continue
            errs = [(r, r.relative_error(q)) for r in rows]
            found = [(abs(e), r) for r, e in errs if e is not None]
            missing = [r for r, e in errs if e is None]
            aliased = [(r, r.ovalling_alias) for r in rows if q == "ovalling" and r.ovalling_alias is not None]
            if aliased:
                out.append(
                    f"{fam.label}: too few nodes around on "
                    + ", ".join(
                        f"{r.label.split(', ')[-1]} ({nyquist(r.params) * 2} nodes: "
                        f"its 'ovalling' n = {alias.n} is an alias "
                        "of the bending pair)"
                        for r, alias in aliased
                    )
                    + ": no ovalling mode resolved"
                )
                missing = [r for r in missing if r.ovalling_alias is None]
            if missing:
                out.append(
                    f"{fam.label}: no {q} mode among the lowest {N_MODES} on "
                    + ", ".join(r.label.split(", ")[-1] for r in missing)
                    + " (too coarse or locked: the mode is pushed above the others)"
                )
            if found and min(e for e, _ in found) > tolerance:
                best = min(found, key=lambda t: t[0])[1]
                out.append(
                    f"{fam.label}: {q} error never below {tolerance:g} (best "
                    f"{best.label.split(', ')[-1]}: {best.relative_error(q):+.1e}) - "
                    + _why(name, fam, q, rows, extrapolations, reference)
                )
    for r in runs:
        if r.status == "failed":
            out.append(f"{r.label}: run failed: {r.error}")
    for model in sorted({r.model for r in runs if r.status == "unavailable"}):
        err = next(r.error for r in runs if r.status == "unavailable" and r.model == model)
        out.append(f"the {model} model did not run here ({err}): the reference falls back to the best family that ran")
    for name, qs in extrapolations.items():
        for q, ex in qs.items():
            if ex.order is None:
                out.append(
                    f"{FAMILIES[name].label}: {q} does not converge monotonically over "
                    "its three finest runs (no observed order)"
                )
            elif ex.order_theory and abs(ex.order - ex.order_theory) > 0.25 * ex.order_theory:
                out.append(
                    f"{FAMILIES[name].label}: observed order {ex.order:.2f} on {q}, "
                    f"theory {ex.order_theory:g}: not in the asymptotic range"
                    + (f" ({ORDER_NOTES[name, q]})" if (name, q) in ORDER_NOTES else "")
                )
    return out


def drop_aliases(runs: Iterable[ConvergenceRun]) -> list[ConvergenceRun]:
    """An "ovalling" mode with more waves than the nodes around can carry is an
    alias (with 8 nodes around, the bending pair reads as n = 7): no ovalling
    mode was resolved (the alias stays as ``ovalling_alias``)."""
    return [_dealiased(r) for r in runs]


def _dealiased(r: ConvergenceRun) -> ConvergenceRun:
    n = r.ovalling_n
    if r.status == "ok" and n is not None and n > nyquist(r.params):
        return replace(r, ovalling_alias=OvallingAlias(omega=r.ovalling, n=n), ovalling=None, ovalling_n=None)
    return r
