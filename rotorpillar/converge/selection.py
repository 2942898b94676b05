"""Each run's errors, the Pareto fronts, and the choice of a model for a scene.

Each run's error against the reference splits into the model's own error
(its family's limit against the reference) and the discretisation's; the
choice is the cheapest run (wall time) whose error bound meets a tolerance
over the frequency band the scene needs (its highest excitation frequency
times a margin), each family offering its coarsest such run (a family's cost
rises with its DOFs; wall times measured under load need not).  ``select_reference`` picks the transients' full-order
reference: the coarsest 3D run for the frequencies the load excites.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

import msgspec

from ..records import Record
from ..reduced.band import excitation_band  # noqa: F401  (the study's band, re-exported)
from .ladder import FAMILIES, QUANTITIES
from .result import (
    ConvergenceRun,
    ExcitationBand,
    Extrapolation,
    ModelSelection,
    ModeSourceFloor,
    Param,
    QuantityErrors,
    ReferenceValue,
    RejectedRun,
    RunBrief,
    RunErrors,
)

Reference = Mapping[str, ReferenceValue]
"""Per quantity, its reference value (the study's ``reference``)."""


def attach_errors(
    runs: Iterable[ConvergenceRun], reference: Reference, extrapolations: Mapping[str, Mapping[str, Extrapolation]]
) -> tuple[ConvergenceRun, ...]:
    """The runs with their errors per quantity against the reference.

    ``{q}_error``: measured, (f - f_ref)/f_ref.  Split through the family's
    own Richardson limit L: ``{q}_model_error`` = (L - f_ref)/f_ref (what
    no refinement removes) and ``{q}_discretisation_error`` = (f - L)/f_ref.
    ``{q}_error_bound`` = |model| + |discretisation|: no credit for the two
    cancelling on one mesh by luck.  A side sweep splits through its parent
    family's limit (same model).  Without a limit (a closed form, a family
    with fewer than three runs) the bound is |measured|.
    """
    return tuple(_with_errors(r, reference, extrapolations) for r in runs)


def _with_errors(
    r: ConvergenceRun, reference: Reference, extrapolations: Mapping[str, Mapping[str, Extrapolation]]
) -> ConvergenceRun:
    b = _split(r, "bending", reference, extrapolations)
    o = _split(r, "ovalling", reference, extrapolations)
    return msgspec.structs.replace(
        r,
        bending_error=b[0],
        bending_model_error=b[1],
        bending_discretisation_error=b[2],
        bending_error_bound=b[3],
        ovalling_error=o[0],
        ovalling_model_error=o[1],
        ovalling_discretisation_error=o[2],
        ovalling_error_bound=o[3],
    )


def _split(
    r: ConvergenceRun, q: str, reference: Reference, extrapolations: Mapping[str, Mapping[str, Extrapolation]]
) -> tuple[float | None, float | None, float | None, float | None]:
    """A run's (error, model error, discretisation error, error bound) on ``q`` (see attach_errors)."""
    v, ref = r.frequency(q), reference.get(q)
    if v is None or ref is None or r.status != "ok":
        return None, None, None, None
    f_ref = ref.value
    err = (v - f_ref) / f_ref
    ex = extrapolations.get(FAMILIES[r.family].parent or r.family, {}).get(q)
    if ex is None:
        model, disc = err, 0.0
    else:
        model, disc = (ex.value - f_ref) / f_ref, (v - ex.value) / f_ref
    return err, model, disc, abs(model) + abs(disc)


def pareto_front(cost, error) -> list[int]:
    """Indices of the points no other point beats in both cost and |error|, by cost."""
    pts = [
        (c, abs(e), i)
        for i, (c, e) in enumerate(zip(cost, error))
        if c is not None and e is not None and math.isfinite(e)
    ]
    pts.sort(key=lambda t: (t[0], t[1]))
    front, best = [], math.inf
    for _c, e, i in pts:
        if e < best:
            front.append(i)
            best = e
    return front


def reference_uncertainty(reference: Reference) -> dict[str, float]:
    """Per quantity, the reference's own relative error estimate (-)."""
    return {q: r.error_estimate / abs(r.value) for q, r in reference.items()}


#: fewest elements around of a chosen 3D or shell model: the chain names its modes (bending in x,
#: ovalling ...) from their harmonics around, and with fewer than 16 nodes around (8 quadratic
#: cells) the bending pair's harmonic aliases higher ones (the around-only sweep's 4 and 6 show it)
MIN_AROUND = 8


def needed_quantities(reference: Reference, band: ExcitationBand) -> list[str]:
    """The quantities whose reference frequency lies inside the band."""
    return [q for q in QUANTITIES if q in reference and reference[q].value <= band.omega_max]


def band_error(run: RunErrors, needed: Sequence[str], ref_unc: Mapping[str, float]) -> float | None:
    """What the choice compares with the tolerance: the largest, over the needed
    quantities, of the error bound plus the reference's uncertainty (None: a
    needed mode is missing)."""
    errs = [run.error_bound(q) for q in needed]
    if any(e is None for e in errs):
        return None
    return max((e + ref_unc.get(q, 0.0) for q, e in zip(needed, errs) if e is not None), default=0.0)


def select_model(
    runs: Sequence[ConvergenceRun],
    reference: Reference,
    band: ExcitationBand,
    tolerance: float,
    families: Sequence[str] | None = None,
) -> ModelSelection:
    """The cheapest run (wall time) whose needed frequencies all meet ``tolerance``.

    Needed: the quantities whose reference lies inside the band.  A run meets
    the tolerance if, for each, its error bound (model + discretisation, see
    attach_errors) plus the reference's own uncertainty is within it; the
    cheapest such run is on the Pareto front of that band error against wall
    time.  ``families`` restricts the candidates (e.g. to the models a command
    can run).
    """
    needed = needed_quantities(reference, band)
    ref_unc = reference_uncertainty(reference)
    fams = None if families is None else tuple(families)
    ok_runs = [r for r in runs if r.status == "ok" and (fams is None or r.family in fams)]
    # a frequency some run puts inside the band but no reference covers has no error
    # estimate: no model can be shown to meet the tolerance on it
    unreferenced = [
        q
        for q in QUANTITIES
        if q not in reference
        and any((f := r.frequency(q)) is not None and f <= band.omega_max for r in runs if r.status == "ok")
    ]
    if unreferenced or not reference:
        what = ", ".join(unreferenced) or "any frequency"
        return ModelSelection(
            tolerance=tolerance,
            band=band,
            needed=tuple(needed + unreferenced),
            reference_uncertainty={q: ref_unc[q] for q in needed},
            families=fams,
            candidates=0,
            rule="no choice without an error estimate that meets the tolerance",
            chosen=None,
            rejected_cheaper=(),
            reason=(
                f"no model chosen: the study has no converged reference for {what} "
                f"inside the band (up to {band.omega_max:.4g} rad/s), so no run has "
                "an error estimate to meet the tolerance with; extend the ladder "
                "([converge] limits, converge.solid = true)"
            ),
        )
    meets: list[ConvergenceRun] = []
    rejected: list[tuple[ConvergenceRun, float, str]] = []
    for r in ok_runs:
        around = r.params.get("elements_around")
        if isinstance(around, int) and around < MIN_AROUND:
            # the chain names this model's modes (bending in x, ...): too few nodes around alias them
            rejected.append((r, math.inf, f"{around} elements around: too few to name its modes"))
            continue
        missing = [q for q in needed if r.frequency(q) is None]
        if missing:
            rejected.append((r, math.inf, "no " + " and no ".join(missing) + " mode"))
            continue
        worst = band_error(r, needed, ref_unc)
        if worst is None:
            rejected.append((r, math.inf, "no error bound on " + " or ".join(needed)))
            continue
        if worst <= tolerance:
            meets.append(r)
        else:
            rejected.append((r, worst, _why(r, needed, ref_unc, tolerance)))
    chosen: ConvergenceRun | None = None
    by_family: dict[str, tuple[ConvergenceRun, str]] = {}
    if meets:
        # within a family the cost rises with the DOFs; the measured wall times, taken on a shared
        # machine, once ranked a finer rung below a coarser one (3D P2 hexahedra 160x25x1 18.3 s,
        # 128x20x1 19.6 s, under load) and the choice followed the load: each family offers its
        # coarsest candidate, and wall time ranks the families
        coarsest: dict[str, ConvergenceRun] = {}
        for r in meets:
            if r.family not in coarsest or _cost(r.dofs) < _cost(coarsest[r.family].dofs):
                coarsest[r.family] = r
        chosen = min(coarsest.values(), key=lambda r: (_cost(r.wall_time), _cost(r.dofs)))
        # per family, its most accurate run among those cheaper than the choice
        for r, _worst, why in sorted(rejected, key=lambda t: t[1]):
            if _cost(r.wall_time) < _cost(chosen.wall_time):
                by_family.setdefault(r.family, (r, why))
        reason = _reason(chosen, needed, band, tolerance, reference, by_family)
    else:
        reason = (
            f"no model in the study meets {tolerance:g} on {', '.join(needed) or 'nothing'} "
            "(error bounds: "
            + "; ".join(
                f"{FAMILIES[f].label} best {min(w for r, w, _ in rejected if r.family == f):.1e}"
                for f in dict.fromkeys(r.family for r, _, _ in rejected)
            )
            + "); refine the ladder ([converge] limits) or loosen the tolerance"
        )
    return ModelSelection(
        tolerance=tolerance,
        band=band,
        needed=tuple(needed),
        reference_uncertainty={q: ref_unc[q] for q in needed},
        families=fams,
        candidates=len(meets),
        rule="cheapest wall time among runs whose error bound (|model error| + "
        "|discretisation error| + reference uncertainty) meets the tolerance on "
        "every frequency inside the band, each family offering its coarsest such run",
        chosen=None if chosen is None else brief(chosen),
        rejected_cheaper=tuple(rejected_run(brief(r), why) for r, why in by_family.values()),
        reason=reason,
    )


def _cost(value: float | None) -> float:
    """An ok run's wall time or DOFs (an ok run has both)."""
    if value is None:
        raise ValueError("an ok run of the study without its cost (wall_time, dofs)")
    return value


def _why(r: ConvergenceRun, needed: Sequence[str], ref_unc: Mapping[str, float], tolerance: float) -> str:
    """Why a run with every needed mode misses the tolerance: its worst quantity's split."""
    bound = {q: (r.error_bound(q) or 0.0) + ref_unc[q] for q in needed}
    q = max(needed, key=lambda q: bound[q])
    return (
        f"{q} error bound {bound[q]:.1e} > {tolerance:g}: "
        f"model {r.relative_error(q, 'model_error'):+.1e}, discretisation "
        f"{r.relative_error(q, 'discretisation_error'):+.1e}, reference {ref_unc[q]:.1e}"
    )


def brief(r: ConvergenceRun) -> RunBrief:
    """An ok run as the choice names it: its case, cost, frequencies and errors."""
    return RunBrief(
        label=r.label,
        family=r.family,
        model=r.model,
        params=r.params,
        dofs=int(_cost(r.dofs)),
        wall_time=_cost(r.wall_time),
        peak_memory=r.peak_memory,
        bending=r.bending,
        ovalling=r.ovalling,
        bending_error=r.bending_error,
        bending_model_error=r.bending_model_error,
        bending_discretisation_error=r.bending_discretisation_error,
        bending_error_bound=r.bending_error_bound,
        ovalling_error=r.ovalling_error,
        ovalling_model_error=r.ovalling_model_error,
        ovalling_discretisation_error=r.ovalling_discretisation_error,
        ovalling_error_bound=r.ovalling_error_bound,
    )


def rejected_run(b: RunBrief, why: str) -> RejectedRun:
    """A run's brief with why it does not meet the tolerance."""
    return RejectedRun(**msgspec.structs.asdict(b), why=why)


def _reason(
    best: ConvergenceRun,
    needed: Sequence[str],
    band: ExcitationBand,
    tol: float,
    reference: Reference,
    rejected: Mapping[str, tuple[ConvergenceRun, str]],
) -> str:
    ref_unc = reference_uncertainty(reference)
    parts = [f"{best.label} ({_cost(best.dofs):,} DOFs, {_cost(best.wall_time):.2f} s) is the cheapest run whose "]
    parts.append(
        " and ".join(
            f"first {q} ({best.frequency(q):.3f} rad/s, error {best.relative_error(q):+.1e}, "
            f"error bound {(best.error_bound(q) or 0.0) + ref_unc.get(q, 0.0):.1e} with the reference's "
            f"uncertainty {ref_unc.get(q, 0.0):.1e})"
            for q in needed
        )
    )
    parts.append(
        f" meet {tol:g} against the reference. The band to resolve reaches "
        f"{band.omega_max:.1f} rad/s ({band.margin:g} x the {band.driver}, "
        f"{max(band.free_speed, band.earthquake_frequency):.1f} rad/s)"
    )
    inside = [f"first {q} {reference[q].value:.2f}" for q in needed]
    outside = [f"first {q} {reference[q].value:.2f}" for q in QUANTITIES if q in reference and q not in needed]
    if inside:
        parts.append(", which contains the " + " and the ".join(inside) + " rad/s")
    if outside:
        parts.append("; " + ", ".join(outside) + " rad/s lie(s) above it")
    parts.append(".")
    if rejected:
        parts.append(
            " Cheaper runs fail: "
            + "; ".join(
                (
                    f"{FAMILIES[f].label} ({why})"
                    if r.label == FAMILIES[f].label
                    else f"{FAMILIES[f].label} (best {r.label.split(', ')[-1]}: {why})"
                )
                for f, (r, why) in rejected.items()
            )
            + "."
        )
    return "".join(parts)


# --------------------------------------------------------------------------
# The transients' full-order reference: the coarsest 3D mesh for what the load excites


class ReferenceChoice(Record):
    """The 3D mesh a transient's full-order reference runs on, chosen from the study
    for the frequencies the load excites (relative errors, -)."""

    label: str
    """the study's run: family and mesh"""
    family: str
    params: dict[str, Param]
    """the run's discretisation (elements_around, elements_along, ... as in the study)"""
    dofs: int
    """the bare tube's DOFs in the study"""
    quantities: tuple[str, ...]
    """the study's frequencies the choice had to meet (those of the modes the load excites)"""
    band_error: float
    """the largest, over ``quantities``, of the error bound plus the reference's uncertainty"""
    errors: dict[str, QuantityErrors]
    """per quantity: value (rad/s), error, model_error, discretisation_error, error_bound (-)"""
    required: float
    """the bound the choice had to meet: the tolerance, or the ROM source's own if smaller"""
    tolerance: float
    floor: ModeSourceFloor | None
    """the ROM's mode source the reference must be at least as fine as"""
    meets: bool
    """band_error <= required (False: no candidate met it; the most accurate was taken)"""
    candidates: int
    """the study's 3D runs considered (at most ``max_dofs``)"""
    max_dofs: int | None
    floor_max_dofs: int | None
    """the finest the refinement for the floor may go (the case's DOF-step budget)"""
    rule: str
    reason: str


def run_band_error(run: RunErrors, quantities: Iterable[str], reference: Reference) -> float | None:
    """A run's band error on ``quantities``: its largest error bound plus the
    reference's uncertainty (None: a quantity is missing)."""
    return band_error(run, list(quantities), reference_uncertainty(reference))


def select_reference(
    runs: Sequence[ConvergenceRun],
    reference: Reference,
    quantities: Iterable[str],
    tolerance: float,
    *,
    floor: ModeSourceFloor | None = None,
    max_dofs: int | None = None,
    floor_max_dofs: int | None = None,
) -> ReferenceChoice | None:
    """The coarsest 3D run (fewest DOFs) whose band error on ``quantities`` meets
    the tolerance; where ``floor.band_error`` (the ROM's mode source) is
    smaller, the coarsest that meets that too: the reference must be at least
    as accurate as what it checks.

    Candidates: the study's solid runs with at most ``max_dofs`` DOFs; the
    refinement for the floor goes no further than ``floor_max_dofs`` (what the
    case's steps afford).  When no candidate within it meets the floor, the
    most accurate one is taken with ``meets`` False; when none meets even the
    tolerance, None.
    """
    wanted = tuple(q for q in quantities if q in reference)
    unc = reference_uncertainty(reference)
    err: dict[int, float] = {}
    for r in runs:
        around = r.params.get("elements_around")
        if isinstance(around, int) and around < MIN_AROUND:
            continue  # its loaded modes cannot be named (see MIN_AROUND)
        if r.status == "ok" and FAMILIES[r.family].model == "solid" and (max_dofs is None or _cost(r.dofs) <= max_dofs):
            e = band_error(r, wanted, unc)
            if e is not None:
                err[id(r)] = e
    cands = [r for r in runs if id(r) in err]
    if not wanted or not cands:
        return None

    def by_cost(r: ConvergenceRun) -> tuple[float, float]:
        return (_cost(r.dofs), _cost(r.wall_time))

    within_tol = sorted((r for r in cands if err[id(r)] <= tolerance), key=by_cost)
    if not within_tol:
        return None
    best, ok, required = within_tol[0], True, tolerance
    limit = None
    if floor is not None and floor.band_error is not None and floor.band_error < err[id(best)]:
        required = floor.band_error
        limit = max(floor_max_dofs if floor_max_dofs is not None else math.inf, _cost(best.dofs))
        pool = [r for r in within_tol if _cost(r.dofs) <= limit]
        reach = [r for r in pool if err[id(r)] <= required]
        best, ok = (reach[0], True) if reach else (min(pool, key=lambda r: (err[id(r)], _cost(r.dofs))), False)
    e = err[id(best)]
    dofs = _cost(best.dofs)
    what = " and ".join(
        f"first {q} {best.frequency(q):.4f} rad/s (error bound {(best.error_bound(q) or 0.0) + unc.get(q, 0.0):.1e})"
        for q in wanted
    )
    if ok:
        reason = (
            f"{best.label} ({dofs:,} DOFs) is the coarsest 3D run of the study whose "
            f"{what} meet{'s' if len(wanted) == 1 else ''} {required:.2g} with the "
            f"reference's uncertainty (band error {e:.1e})"
        )
    else:
        cap = min(limit if limit is not None else math.inf, max_dofs if max_dofs is not None else math.inf)
        within = ""
        if math.isfinite(cap):
            within = (
                f" within {cap:,.0f} DOFs ("
                + (
                    "what the case's steps afford"
                    if limit is not None and limit <= cap
                    else "the finest the transient's candidates go"
                )
                + ")"
            )
        reason = (
            f"{best.label} ({dofs:,} DOFs) is the most accurate 3D run of the study"
            f"{within}: {what}, band error {e:.1e}, within the tolerance {tolerance:g}"
        )
    if floor is not None and floor.band_error is not None:
        reason += f"; the ROM's mode source ({floor.label}) has {floor.band_error:.1e}, " + (
            "and the reference is at least as accurate"
            if ok
            else "which no 3D run the case affords reaches: the comparison checks the ROM "
            "only to the reference's own error"
        )
    rule = (
        "fewest DOFs among the study's 3D runs (at most max_dofs) whose error bound plus the "
        "reference's uncertainty on the frequencies of the modes the load excites meets the "
        "tolerance, and the ROM mode source's own bound where smaller (within floor_max_dofs)"
    )
    return ReferenceChoice(
        label=best.label,
        family=best.family,
        params=dict(best.params),
        dofs=int(dofs),
        quantities=wanted,
        band_error=float(e),
        errors={q: QuantityErrors.of(best, q) for q in wanted},
        required=float(required),
        tolerance=float(tolerance),
        floor=floor,
        meets=ok,
        candidates=len(cands),
        max_dofs=max_dofs,
        floor_max_dofs=floor_max_dofs,
        rule=rule,
        reason=reason,
    )
