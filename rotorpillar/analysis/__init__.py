"""The scene as the paper's closed-form model sees it: `rotorpillar analyze`.

Above ``reduced/`` (whose formulas it calls) and beside ``fem3d/`` (whose tip
reduction it receives as a callable when a scene asks for it):

- :mod:`.scene_analysis`  :func:`analyze` (scene) -> :class:`AnalysisResult`
- :mod:`.results`         the typed result (records, read back by ``records.read``)
- :mod:`.paper`           every number the paper prints, beside ours
- :mod:`.summary`         the readable text
"""

from .paper import compare_with_paper
from .results import (
    AnalysisResult,
    CoupledModes,
    DriveRegimes,
    PaperRow,
    PillarClosedForms,
    ResonanceAnalysis,
    TipReductionUsed,
)
from .scene_analysis import analyze
from .text import summary

__all__ = [
    "AnalysisResult",
    "DriveRegimes",
    "PaperRow",
    "PillarClosedForms",
    "ResonanceAnalysis",
    "CoupledModes",
    "TipReductionUsed",
    "analyze",
    "compare_with_paper",
    "summary",
]
