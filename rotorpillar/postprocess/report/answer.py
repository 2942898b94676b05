"""The page's first section, the answer: the verdict, the checks (the
governing one marked) and the numbers a reader came for, each once.

Read from summary.json (``verdict.summary.EngineeringSummary``, written by
`rotorpillar report` before the page); the words are in
``templates/sections/answer.html.j2``.
"""

from __future__ import annotations

from ... import records
from ...records import Record
from ...reduced.capacity import Check
from ...verdict.headline import Headline
from ...verdict.summary import EngineeringSummary
from .page import Section, render, with_subsections
from .state import Build

#: The models a quantity is shown from, the most complete first.
COMPLETENESS = ("fem3d", "beam", "modal", "paper")


class KeyNumber(Record):
    """One quantity a reader came for, shown once: the most complete model's value."""

    label: str
    """what it is, in words"""
    value: float | None
    """in ``unit``"""
    unit: str
    """SI unit of ``value`` and ``error``"""
    error: float | None
    """its error bar (``unit``), where one was made"""
    model: str | None
    """the model it comes from"""
    case: str | None
    """the case it comes from"""
    others: tuple[tuple[str, float], ...] = ()
    """(model, relative difference to ``value`` (-)) of the other models that give it"""


class Answer(Record):
    """What the first screen shows."""

    verdict: str
    """"pass", "fail" or "incomplete\""""
    checks: tuple[Check, ...]
    """one row per check, its governing model and case"""
    governing: int | None
    """the index in ``checks`` of the largest utilisation (None: none assessed)"""
    numbers: tuple[KeyNumber, ...]
    not_assessed: tuple[str, ...]
    """the checks without a capacity or a demand, and what to state"""


def governing(checks: tuple[Check, ...]) -> int | None:
    """The check with the largest utilisation, or None when none is assessed.

    >>> from rotorpillar.reduced.capacity import check
    >>> governing((check("a", "q", "m", 1.0, 4.0, None, None, ""), check("b", "q", "m", 3.0, 4.0, None, None, "")))
    1
    """
    assessed = [(c.utilisation, k) for k, c in enumerate(checks) if c.utilisation is not None]
    return max(assessed)[1] if assessed else None


def key_numbers(headlines: tuple[Headline, ...]) -> tuple[KeyNumber, ...]:
    """Each headline quantity once, from the most complete model that gives it;
    the others as their relative difference to it."""
    groups: dict[str, list[Headline]] = {}
    for x in headlines:
        groups.setdefault(x.label, []).append(x)
    out = []
    for label, xs in groups.items():
        xs.sort(key=lambda x: COMPLETENESS.index(x.model) if x.model in COMPLETENESS else len(COMPLETENESS))
        lead = xs[0]
        others = tuple(
            (str(x.model), x.value / lead.value - 1)
            for x in xs[1:]
            if x.value is not None and lead.value and x.model is not None
        )
        out.append(KeyNumber(label, lead.value, lead.unit, lead.error, lead.model, lead.case, others))
    return tuple(out)


def answer(summary: EngineeringSummary) -> Answer:
    """The first screen's record, from summary.json's."""
    return Answer(
        summary.verdict,
        summary.checks,
        governing(summary.checks),
        key_numbers(summary.headlines),
        summary.not_assessed,
    )


def read_summary(build: Build) -> EngineeringSummary | None:
    """summary.json's record, or None (a damaged one recorded as a failed input)."""
    path = build.out / "summary.json"
    if not path.is_file():
        return None
    try:
        return records.read(path, EngineeringSummary)
    except (ValueError, OSError) as exc:
        build.failures["input summary.json"] = f"{type(exc).__name__}: {exc}"
        return None


def section_answer(build: Build) -> Section:
    s = read_summary(build)
    html_ = render(
        "sections/answer.html.j2",
        answer=None if s is None else answer(s),
        command=f"rotorpillar run {build.scene_cli}",
    )
    return with_subsections("answer", "The answer", html_)
