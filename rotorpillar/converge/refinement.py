"""How far the study refined each family of the ladder, and why no further
(rotorpillar.converge.adaptive decides it; convergence.json's ``refinement``)."""

from __future__ import annotations

from ..records import Record

STOPS = (
    "ladder end",
    "tolerance met",
    "no mode",
    "model error",
    "cost",
    "unavailable",
    "full ladder",
)
"""Why a family was refined no further."""


class FamilyRefinement(Record):
    """How far the study refined one family, and why no further."""

    family: str
    """the family's key on the ladder (rotorpillar.converge.ladder.FAMILIES)"""
    runs: int
    """its rungs run (-)"""
    rungs: int
    """its rungs on the ladder (-)"""
    stop: str
    """why it was refined no further: one of STOPS"""
    why: str
    """the same in words, with the numbers that decided it"""


class LadderRefinement(Record):
    """The ladder's runs against those the study ran (rotorpillar.converge.adaptive)."""

    full: bool
    """every rung of every family was run (``--full-ladder``)"""
    ladder_runs: int
    """rungs on the ladder (-)"""
    runs: int
    """of them run (-)"""
    rounds: int
    """rounds of refinement (-)"""
    families: tuple[FamilyRefinement, ...]
    """each family's refinement, in the ladder's order"""
    rule: str
    """the stopping rule, in words"""
