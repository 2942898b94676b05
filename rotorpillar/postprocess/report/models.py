"""The models whose answers the page shows: the headline model first, the
paper's model (its Eq. 4 with its stated reduction) beside it in its own
column where analyze.json holds both.

analyze.json's ``system``, ``resonances`` and ``drive`` are the headline
model's; a ``paper_model`` block of the same shape, where present, is the
paper's; ``pillar_model`` ({kind, mesh, dofs, source, verified}) names
what the headline model's pillar modes came from.  Nothing here assumes a
number of resonances: they are grouped by direction as the records hold them.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .. import html as h
from ..directions import direction

if TYPE_CHECKING:
    from ...analysis.results import AnalysisResult, DriveRegimes, ResonanceAnalysis
    from ...chain.record import PillarModel


@dataclass(frozen=True)
class ModelView:
    """One model's resonance answers as analyze.json holds them."""

    title: str
    """how the page names it"""
    resonances: list[ResonanceAnalysis]
    drive: DriveRegimes | None
    system: Any
    headline: bool


def pillar_model_text(pm: PillarModel | None) -> str:
    """A ``pillar_model`` in words ("" without one).

    >>> from rotorpillar.chain.record import PillarModel
    >>> pillar_model_text(PillarModel("solid", "3D P2 hexahedra, 128x20x1", {}, 94464, "converge", True, None, {}, ""))
    'pillar modes: 3D P2 hexahedra, 128x20x1 (94464 DOFs), chosen by the convergence study'
    >>> pillar_model_text(PillarModel("beam", "", {}, 0, "scene", False, None, {}, ""))
    "pillar modes: beam, the scene's own, unverified"
    """
    if pm is None:
        return ""
    what = pm.label or pm.kind
    if pm.dofs:
        what += f" ({pm.dofs} DOFs)"
    src = {"converge": "chosen by the convergence study", "scene": "the scene's own"}.get(pm.source, pm.source)
    text = f"pillar modes: {what}" + (f", {src}" if src else "")
    if not pm.verified:
        text += ", unverified"
    return text


def headline_title(analysis: AnalysisResult) -> str:
    """The headline model's name: the reduced model with its pillar modes'
    source where analyze.json says it, else (no ``paper_model`` block) the
    paper's model itself."""
    if getattr(analysis, "paper_model", None) is None:
        return "the paper's model (Eq. 4 with the scene's reduction)"
    said = pillar_model_text(getattr(analysis, "pillar_model", None))
    return "the reduced model (ROM)" + (f": {said}" if said else "")


def model_views(analysis: AnalysisResult) -> list[ModelView]:
    """The headline model, then the paper's (where analyze.json has it)."""
    views = [ModelView(headline_title(analysis), list(analysis.resonances), analysis.drive, analysis.system, True)]
    pm = getattr(analysis, "paper_model", None)
    if pm is not None and getattr(pm, "resonances", None) is not None:
        views.append(
            ModelView(
                "the paper's model (Eq. 4, its stated reduction)",
                list(pm.resonances),
                getattr(pm, "drive", None),
                getattr(pm, "system", None),
                False,
            )
        )
    return views


def by_direction(resonances: Iterable[Any]) -> dict[str, list[Any]]:
    """Resonances grouped by direction, X first, each group in order of frequency."""
    out: dict[str, list[Any]] = {}
    for r in sorted(resonances, key=lambda r: (str(r.direction) != "X", r.omega)):
        out.setdefault(str(r.direction), []).append(r)
    return out


def resonance_table(views: list[ModelView]) -> str:
    """The resonance frequencies, one row per direction and order, one column per model."""
    groups = [by_direction(v.resonances) for v in views]
    dirs = list(dict.fromkeys(d for g in groups for d in g))
    rows = []
    for d in dirs:
        n = max(len(g.get(d, [])) for g in groups)
        for k in range(n):
            cells = []
            for g in groups:
                rs = g.get(d, [])
                cells.append(f"{h.num(rs[k].omega, 4)} (#{rs[k].index})" if k < len(rs) else "-")
            rows.append([direction(d), k + 1, *cells])
    return h.table(["direction", "order", *[f"omega, undamped (rad/s), {v.title}" for v in views]], rows)
