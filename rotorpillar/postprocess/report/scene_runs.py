"""What the earthquake stages ran with, beside the scene's table (issue 29.4).

The run's earthquake stages set their own excitation (`rotorpillar run`'s
stage arguments: El Centro in place of the scene's ``excitation.kind``, its
start, the 3D window); each stage's JSON keeps the scene it resolved and its
own ``--set`` overrides (its provenance).  The page's scene table shows the
scene; this shows, for each earthquake stage, the keys it ran with other
values, and the scene table's value says so beside it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ... import records
from ...provenance import Provenance
from .. import html as h
from .page import model_name
from .parts import scene_changes
from .state import Build

#: an earthquake stage's file: simulate's and compare's per model, and the multi-component comparison
_EARTHQUAKE_FILE = re.compile(r"(simulate|compare)_earthquake_(\w+)\.json")


@dataclass(frozen=True)
class StageScene:
    """One earthquake stage's scene as it ran: the keys it changed and their values."""

    run: str
    """the stage in words, e.g. "El Centro in three components (the spatial ROM and the 3D full order)\""""
    overrides: tuple[str, ...]
    """its command line's ``--set`` overrides"""
    values: dict[str, Any]
    """dotted key -> the value it ran with, where the scene's differs"""


def _words(command: str, what: str) -> str:
    if what == "components":
        return "El Centro in three components (the spatial ROM and the 3D full order)"
    verb = "the earthquake comparison" if command == "compare" else "the earthquake run"
    return f"{verb}: {model_name(what)}"


def earthquake_stages(build: Build) -> list[StageScene]:
    """Each earthquake stage's JSON in ``build.out`` that names keys the page's scene differs in."""
    out = []
    for path in sorted(Path(build.out).glob("*_earthquake_*.json")):
        m = _EARTHQUAKE_FILE.fullmatch(path.name)
        words = "" if m is None else _words(m.group(1), m.group(2))
        if not words:
            continue
        try:
            prov = records.read(path, Provenance)
        except (ValueError, OSError):  # damaged: its own section names it
            continue
        changes = scene_changes(build, prov)
        if changes:
            out.append(StageScene(words, tuple(prov.overrides), {c.key: c.then for c in changes}))
    return out


def ran_with(stages: list[StageScene]) -> tuple[tuple[str, str], ...]:
    """(dotted key, the values the earthquake stages ran with instead, each once, in words).

    >>> ran_with([StageScene("a", (), {"excitation.kind": "record"}), StageScene("b", (), {"excitation.kind": "record"})])
    (('excitation.kind', 'record'),)
    """
    cells: dict[str, list[str]] = {}
    for s in stages:
        for k, v in s.values.items():
            if h.num(v) not in cells.setdefault(k, []):
                cells[k].append(h.num(v))
    return tuple((k, ", ".join(v)) for k, v in cells.items())


def stages_table(stages: list[StageScene]) -> list[str]:
    """The table of what each earthquake stage ran with, one row per stage (stages that ran
    with the same values share it); nothing when none differs."""
    if not stages:
        return []
    groups: dict[tuple, list[str]] = {}
    for s in stages:
        groups.setdefault((tuple(s.values.items()), s.overrides), []).append(s.run)
    rows = [
        [
            "; ".join(runs),
            "; ".join(f"{k} = {h.num(v)}" for k, v in values),
            ", ".join(overrides) or "-",
        ]
        for (values, overrides), runs in groups.items()
    ]
    return [
        h.tag(
            "p",
            "The earthquake stages ran with their own excitation, not the scene's: each one's keys that "
            "differ from the scene's table, with the values it ran with, and the overrides it was given.",
        ),
        h.table(["earthquake stage", "keys it ran with (SI)", "its overrides"], rows),
    ]
