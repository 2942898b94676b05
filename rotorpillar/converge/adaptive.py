"""The ladder refined only as far as the choice needs it.

A family's rungs go coarse to fine.  Every family starts with its first
``INITIAL_RUNGS`` rungs (enough for Richardson: its limit, its order, and so
the error of a finer rung); then the study goes in rounds, and after each
round every family is refined by one rung unless one of these holds:

- **tolerance met**: one of its runs meets the tolerance over the band (it
  is a candidate; a finer rung of the same family only costs more);
- **no mode**: it lacks a frequency the band needs (a beam has no ovalling
  mode): it can never be a candidate;
- **model error**: its limit against the reference, less the limit's own
  uncertainty, exceeds the tolerance on a frequency the band needs: no
  refinement removes that (a side sweep's limit is its limit around the
  circumference, at its fixed cells along);
- **cost**: the rung Richardson predicts it needs to meet the tolerance
  would cost more than ``COST_MARGIN`` times the cheapest candidate so far
  (the ladder's cost model, :func:`.ladder.estimated_seconds`; before any
  run meets, the reference family's own prediction stands in for it: its
  model error is nil by construction, so it will meet);
- **ladder end**.

Where no 3D run meets the tolerance and no 3D family refines on, `modal` takes the
most accurate 3D run instead: the 3D families stopped on model error or cost then
run on to their ladders' ends, as the full ladder would have run them.

The reference's family is refined further while its uncertainty alone
keeps a run from meeting the tolerance ("reference uncertainty": a run,
no costlier than the cheapest candidate of its class, whose error bound
meets the tolerance without the reference's uncertainty and not with it):
the reference is as fine as the choice needs, not finer.  The bending-only
3D family is the transients' references (rotorpillar.transients.references:
its finest run bounds their candidates' size, and the run-up's must match
the ROM's mode source): it runs its whole ladder, as do the closed forms.

The decisions are made on the runs of whole rounds, never on which run of a
round finished first: the same scene gives the same runs whatever the
machine's load, and a second study reads them all from the cache.  The
rules only ever stop what cannot change the choice, so the study chooses
what the full ladder chooses (tests/test_converge_adaptive.py checks it on
a small ladder); ``full=True`` runs every rung (``rotorpillar converge
--full-ladder``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

from ..scene import Scene
from .failures import drop_aliases
from .ladder import FAMILIES, QUANTITIES, Case, estimated_seconds, rung
from .refinement import FamilyRefinement, LadderRefinement
from .result import ConvergenceRun, Extrapolation
from .richardson import family_extrapolations, reference_values, richardson
from .selection import attach_errors, band_error, excitation_band, needed_quantities, reference_uncertainty

INITIAL_RUNGS = 3
"""Rungs every refined family starts with: the fewest Richardson extrapolates from."""
COST_MARGIN = 2.0
"""A family is stopped on cost when its predicted rung costs more than this times the
cheapest candidate: the ladder's cost model is within about +-50 % of the measured
wall times (paper: 3D P2 128 x 20 estimated 13.8 s, measured 11.5 s; shell 64 x 80
11.6 s, 7.4 s; 3D P1 256 x 40 5.9 s, 8.2 s), so a family stopped on cost is at least
a third dearer than the choice."""
EXHAUSTIVE = ("closed_form", "solid_hex_p2_along")
"""Families run over their whole ladder (see the module text)."""
SOLID_CLASS = tuple(k for k, f in FAMILIES.items() if f.model == "solid" and set(QUANTITIES) <= set(f.quantities))
"""The 3D families `modal` chooses among (every frequency resolved): they compete with
each other too, so their cost is held against the cheapest 3D candidate."""


RULE = (
    "each family refined coarse to fine from its first three rungs, one rung a round, until a run meets "
    "the tolerance over the band, it lacks a needed frequency, its model error alone exceeds the tolerance, "
    f"or the rung Richardson predicts it needs costs more than {COST_MARGIN:g} x the cheapest candidate; "
    "the reference's family further while the reference's uncertainty alone keeps a cheaper run from meeting; "
    "the bending-only 3D family and the closed forms over their whole ladder; "
    "where no 3D run meets the tolerance, the 3D families over their whole ladder (`modal` takes the most accurate)"
)


@dataclass(frozen=True)
class Decision:
    """A family after a round: the rung to run next (None: stop), and why."""

    family: str
    next: Case | None
    stop: str | None
    """None: refine (``next``) or wait for the reference"""
    why: str


@dataclass(frozen=True)
class _State:
    """What the runs so far say: errors against the reference, and what the band needs."""

    runs: tuple[ConvergenceRun, ...]
    """the ok runs, errors attached"""
    reference: Mapping
    extrapolations: Mapping[str, Mapping[str, Extrapolation]]
    needed: tuple[str, ...]
    uncertainty: Mapping[str, float]
    decidable: bool
    """a reference for every frequency a run puts in the band"""


def _state(scene: Scene, runs: Sequence[ConvergenceRun]) -> _State:
    dealiased = drop_aliases([r for r in runs if r.status == "ok"])
    ex = family_extrapolations(dealiased)
    ref = reference_values(dealiased, ex)
    band = excitation_band(scene.drive, scene.load, scene.converge)
    with_errors = attach_errors(dealiased, ref, ex)
    in_band = {q for q in QUANTITIES for r in dealiased if (f := r.frequency(q)) is not None and f <= band.omega_max}
    return _State(
        runs=with_errors,
        reference=ref,
        extrapolations=ex,
        needed=tuple(needed_quantities(ref, band)),
        uncertainty=reference_uncertainty(ref),
        decidable=bool(ref) and in_band <= set(ref),
    )


Rungs = Mapping[str, Sequence[Case]]
"""Per family, its rungs on the ladder, coarse to fine."""


def initial_cases(rungs: Rungs, full: bool = False) -> list[Case]:
    """The first round: every family's first rungs (all of them for ``full`` and for
    EXHAUSTIVE families)."""
    out: list[Case] = []
    for name, cs in rungs.items():
        out += cs if full or name in EXHAUSTIVE else cs[:INITIAL_RUNGS]
    return out


def reference_families(state: _State) -> set[str]:
    """The families the needed references come from."""
    return {state.reference[q].family for q in state.needed if q in state.reference}


def _cost(scene: Scene, r: ConvergenceRun) -> float:
    """A run's cost by the ladder's cost model (s): the same for every study of the scene."""
    return estimated_seconds(rung(scene, r.family, r.level))


def _limit(rows: Sequence[ConvergenceRun], q: str, family: str, state: _State) -> Extrapolation | None:
    """A family's limit on ``q``: its Richardson extrapolation (a side sweep's: over its
    three finest runs around, at the parent's theoretical order)."""
    fam = FAMILIES[family]
    if not fam.sweep:
        return state.extrapolations.get(family, {}).get(q)
    rows = [r for r in rows if r.frequency(q) is not None]
    if len(rows) < 3:
        return None
    last = rows[-3:]
    order = FAMILIES[fam.parent].order if fam.parent else None
    return richardson([1.0 / r.level for r in last], [r.frequency(q) for r in last], order)


@dataclass(frozen=True)
class _Outlook:
    """Where a family is heading, per the extrapolation of its finest runs."""

    model_error: float
    """its largest optimistic model error over the needed frequencies: |limit - reference|
    less the limit's own uncertainty, at least 0 (-)"""
    model_quantity: str
    level: float
    """the refinement level Richardson predicts meets the tolerance (inf: none)"""
    level_quantity: str


def _outlook(family: str, rows: Sequence[ConvergenceRun], state: _State, tolerance: float) -> _Outlook | None:
    """None while a needed frequency has no limit yet (too few runs resolve it).

    Per needed frequency q: the limit L (Richardson on the family's three finest
    runs), the discretisation error e = |f - L| / f_ref of its finest run, and the
    error left for it, tolerance - optimistic model error;
    e ~ h**p then gives the level that meets it (p: the observed order or the
    theoretical one, whichever is faster).  The reference's own family has no model error, and its
    refinement shrinks the reference's uncertainty too.
    """
    model = (0.0, "")
    level = (0.0, "")
    own = family in reference_families(state)
    for q in state.needed:
        ex = _limit(rows, q, family, state)
        if ex is None:
            return None
        ref = state.reference[q].value
        m = 0.0 if own else max(0.0, abs(ex.value - ref) - ex.error_estimate) / abs(ref)
        finest = [r for r in rows if r.frequency(q) is not None][-1]
        # the reference's uncertainty shrinks as its family is refined, which a run that
        # meets the tolerance but for it asks for (_undecided): another family is held to
        # the tolerance alone; the reference's own, the one whose refinement shrinks it,
        # leaves at most half the tolerance to it
        u = state.uncertainty.get(q, 0.0)
        target = tolerance - (min(u, 0.5 * tolerance) if own else 0.0) - m
        e = abs((finest.frequency(q) or 0.0) - ex.value) / abs(ref)
        # the faster of the observed and the theoretical order: coarse rungs short of the
        # asymptotic range converge slower than they will, and a stop must not rest on that
        p = max(ex.order if ex.monotone and ex.order is not None else 0.0, ex.order_theory or 0.0)
        if target <= 0 or not p:
            lq = math.inf
        elif e <= target:
            lq = float(finest.level)
        else:
            lq = finest.level * (e / target) ** (1.0 / p)
        model = max(model, (m, q))
        level = max(level, (lq, q))
    return _Outlook(model[0], model[1], level[0], level[1])


def _candidates(state: _State, tolerance: float, families: Sequence[str] | None = None) -> list[ConvergenceRun]:
    """The runs that meet the tolerance over the band (of ``families``)."""
    return [
        r
        for r in state.runs
        if (families is None or r.family in families)
        and (e := band_error(r, state.needed, state.uncertainty)) is not None
        and e <= tolerance
    ]


@dataclass(frozen=True)
class _Bars:
    """The cost a family must not exceed (COST_MARGIN aside): the cheapest candidate's,
    else the reference family's predicted rung's (inf: none), of all families and of
    the 3D ones `modal` chooses among (s)."""

    all: float
    solid: float

    def of(self, family: str) -> float:
        return self.solid if family in SOLID_CLASS else self.all


def _bars(scene: Scene, state: _State, tolerance: float, rows: Mapping[str, list[ConvergenceRun]]) -> _Bars:
    out = []
    for fams in (None, SOLID_CLASS):
        cands = _candidates(state, tolerance, fams)
        if cands:
            out.append(min(_cost(scene, r) for r in cands))
            continue
        bar = math.inf
        for name in reference_families(state):
            if fams is not None and name not in fams:
                continue
            look = _outlook(name, rows.get(name, []), state, tolerance)
            if look is not None and math.isfinite(look.level):
                bar = min(bar, estimated_seconds(rung(scene, name, math.ceil(look.level))))
        out.append(bar)
    return _Bars(*out)


def _undecided(scene: Scene, state: _State, tolerance: float) -> ConvergenceRun | None:
    """A run the reference's uncertainty alone keeps from meeting the tolerance, no
    costlier than the cheapest candidate of its class (None: the reference decides)."""
    plain = {q: 0.0 for q in state.needed}
    cheapest = _Bars(
        *(
            min((_cost(scene, r) for r in _candidates(state, tolerance, fams)), default=math.inf)
            for fams in (None, SOLID_CLASS)
        )
    )
    for r in state.runs:
        be, bx = band_error(r, state.needed, state.uncertainty), band_error(r, state.needed, plain)
        if be is None or bx is None or not bx <= tolerance < be:
            continue
        # a 3D run cheaper than the cheapest 3D candidate would be `modal`'s choice
        if _cost(scene, r) < cheapest.of(r.family):
            return r
    return None


def decide(
    scene: Scene, tolerance: float, runs: Sequence[ConvergenceRun], rungs: Rungs, full: bool = False
) -> list[Decision]:
    """Every family's decision on the runs so far (those of whole rounds), on the
    ladder ``rungs``."""
    state = _state(scene, runs)
    by_family: dict[str, list[ConvergenceRun]] = {}
    for r in state.runs:
        by_family.setdefault(r.family, []).append(r)
    for rows in by_family.values():
        rows.sort(key=lambda r: r.level)
    done = {(r.family, r.level) for r in runs}
    bars = _bars(scene, state, tolerance, by_family) if state.decidable else _Bars(math.inf, math.inf)
    refs = reference_families(state)
    undecided = _undecided(scene, state, tolerance) if state.decidable else None
    out = []
    nexts: dict[str, Case | None] = {}
    for name, cs in rungs.items():
        if not cs:
            continue
        ran = [c.level for c in cs if (name, c.level) in done]
        later = [c for c in cs if c.level > max(ran, default=-1)]
        nxt = nexts[name] = later[0] if later else None
        rows = by_family.get(name, [])
        if any(r.family == name and r.status == "unavailable" for r in runs):
            out.append(Decision(name, None, "unavailable", next(r.error or "" for r in runs if r.family == name)))
        elif nxt is None:
            out.append(Decision(name, None, "ladder end", f"its finest rung, {cs[-1].label}, ran"))
        elif full or name in EXHAUSTIVE:
            out.append(Decision(name, nxt, None, "its whole ladder"))
        elif not state.decidable:
            out.append(Decision(name, nxt, None, "no reference for every frequency in the band yet"))
        else:
            out.append(_decide(scene, name, rows, nxt, state, tolerance, bars, name in refs, undecided))
    return _on_for_the_most_accurate(out, nexts, state, tolerance) if state.decidable and not full else out


def _on_for_the_most_accurate(
    decisions: list[Decision], nexts: Mapping[str, Case | None], state: _State, tolerance: float
) -> list[Decision]:
    """Where no 3D run meets the tolerance and no 3D family refines on, `modal` takes the
    most accurate 3D run, which the full ladder finds among every 3D family's finest
    rungs: the 3D families stopped on model error or cost run on.  Each round decides so
    again from the runs alone (the rules stop them, no 3D run meets, none refines), so the
    families climb a rung a round to their ladders' ends.  Without this, a tolerance no
    run meets (1e-9) stopped every family after its first rungs, and `modal` took 3D P2
    32x5x1 (band error 0.12) where the same ladder's 48x10x1 reaches 0.028."""
    if _candidates(state, tolerance, SOLID_CLASS):
        return decisions
    if any(d.next is not None for d in decisions if d.family in SOLID_CLASS):
        return decisions
    return [
        Decision(
            d.family,
            nexts[d.family],
            None,
            f"no 3D run meets {tolerance:g}: `modal` takes the most accurate, so the 3D families run on ({d.why})",
        )
        if d.family in SOLID_CLASS and d.stop in ("model error", "cost") and nexts.get(d.family) is not None
        else d
        for d in decisions
    ]


def _decide(
    scene: Scene,
    name: str,
    rows: list[ConvergenceRun],
    nxt: Case,
    state: _State,
    tolerance: float,
    bars: _Bars,
    reference: bool,
    undecided: ConvergenceRun | None,
) -> Decision:
    fam = FAMILIES[name]
    own = Decision(name, nxt, None, "")
    missing = [q for q in state.needed if q not in fam.quantities]
    meets = _candidates(state, tolerance, [name])
    look = None if missing or meets else _outlook(name, rows, state, tolerance)
    if missing:
        own = Decision(name, None, "no mode", f"no {' and no '.join(missing)} mode in this model, which the band needs")
    elif meets:
        best = min(meets, key=lambda r: r.level)
        own = Decision(name, None, "tolerance met", f"{best.label} meets {tolerance:g} over the band")
    elif look is None:
        own = Decision(name, nxt, None, "too few runs resolve every needed frequency to extrapolate")
    elif look.model_error > tolerance:
        own = Decision(
            name,
            None,
            "model error",
            f"its {look.model_quantity} limit lies {look.model_error:.3g} beyond the reference, past its own uncertainty "
            f"(more than {tolerance:g}): no refinement removes that",
        )
    else:
        bar = bars.of(name)
        cost = estimated_seconds(rung(scene, name, math.ceil(look.level))) if math.isfinite(look.level) else math.inf
        if cost > COST_MARGIN * bar:
            where = (
                f"{math.ceil(look.level)} (about {cost:.0f} s)"
                if math.isfinite(cost)
                else "none (its error does not reach the tolerance)"
            )
            own = Decision(
                name,
                None,
                "cost",
                f"the rung its Richardson estimate needs for {tolerance:g} on {look.level_quantity} is {where}: "
                f"more than {COST_MARGIN:g} x the cheapest candidate's {bar:.1f} s",
            )
    if reference and own.stop is not None and undecided is not None:
        return Decision(
            name,
            nxt,
            None,
            f"reference uncertainty: {undecided.label} meets {tolerance:g} but for the reference's own uncertainty",
        )
    return own


def run_ladder(
    scene: Scene,
    tolerance: float,
    run_round: Callable[[list[Case], int], list[ConvergenceRun]],
    ladder: Sequence[Case],
    *,
    full: bool = False,
) -> tuple[list[ConvergenceRun], LadderRefinement]:
    """The study's runs on ``ladder`` (``ladder.study_cases``), round by round:
    ``run_round(cases, round)`` runs (or loads) a round's cases; the runs come back in
    the ladder's order, with how far each family was refined and why."""
    rungs: dict[str, list[Case]] = {}
    for c in ladder:
        rungs.setdefault(c.family, []).append(c)
    for cs in rungs.values():
        cs.sort(key=lambda c: c.level)
    order = {(c.family, c.level): i for i, c in enumerate(ladder)}
    runs: dict[tuple[str, int], ConvergenceRun] = {}
    todo, rounds = initial_cases(rungs, full), 0
    decisions: list[Decision] = []
    while todo:
        for c, r in zip(todo, run_round(todo, rounds)):
            runs[c.family, c.level] = r
        rounds += 1
        decisions = decide(scene, tolerance, list(runs.values()), rungs, full)
        todo = [d.next for d in decisions if d.next is not None and (d.next.family, d.next.level) not in runs]
    ordered = sorted(runs.values(), key=lambda r: order.get((r.family, r.level), len(order)))
    families = tuple(
        FamilyRefinement(
            family=d.family,
            runs=sum(1 for r in ordered if r.family == d.family),
            rungs=len(rungs[d.family]),
            stop="full ladder" if full and d.stop == "ladder end" else (d.stop or "ladder end"),
            why=d.why,
        )
        for d in decisions
    )
    return ordered, LadderRefinement(
        full=full, ladder_runs=len(ladder), runs=len(ordered), rounds=rounds, families=families, rule=RULE
    )
