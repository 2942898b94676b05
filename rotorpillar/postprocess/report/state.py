"""What the report page is assembled from: the options, the inputs read, the
files made, and the record of what failed.

The bottom of the report package: every section module reads a
:class:`Build`, none of them imports the others' builders.
"""

from __future__ import annotations

import os
import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, TypeVar

from ...provenance import Provenance
from ..readers import Simulation, not_computed

if TYPE_CHECKING:
    from ...analysis.results import AnalysisResult
    from ...converge.result import ConvergenceStudy
    from ...fem3d.modal_summary import ModalSummary
    from ...scene import Scene
    from ...studies.result import StudyResult
    from ...transients.integrator_study import IntegratorStudy
    from ..animation import AnimationResult
    from ..compare_reader import Comparison

T = TypeVar("T")

FIGURES_DIR = "figures"
MODES_DIR = "modes"
ANIMATIONS_DIR = "animations"
#: The report's own folders: the PNGs there are not another command's figures.
OWN_DIRS = (FIGURES_DIR, MODES_DIR, ANIMATIONS_DIR)


@dataclass(frozen=True)
class ReportOptions:
    """What `rotorpillar report` renders."""

    animations: bool = True
    """render the run-up and earthquake animations"""
    max_frames: int = 180
    """frames per animation (-)"""
    modes: int = 8
    """mode shapes rendered per set, and on the contact sheet (-)"""


@dataclass
class Product:
    """A file the report made or found, with its caption."""

    path: Path
    caption: str
    kind: str = "figure"  # figure | video
    group: str = ""
    poster: Path | None = None
    case: str = ""
    """the case of the run that drew it (another command's figure; "" if none)"""


@dataclass
class InputProvenance:
    """What each command wrote beside the record the report read from it (the scene,
    versions, machine, timings): None where the input is missing, damaged or has none."""

    analyze: Provenance | None = None
    modal: Provenance | None = None
    convergence: Provenance | None = None
    integrators: Provenance | None = None
    study: Provenance | None = None


@dataclass
class Build:
    """Everything the page is assembled from."""

    scene: Scene
    out: Path
    scene_cli: str
    options: ReportOptions
    analysis: AnalysisResult | None = None
    """analyze.json's record, or None"""
    modal: ModalSummary | None = None
    """modal.json's record, or None"""
    convergence: ConvergenceStudy | None = None
    """convergence.json's record, or None"""
    study: StudyResult | None = None
    """study.json's record, or None"""
    provenance: InputProvenance = field(default_factory=InputProvenance)
    """what each input's command wrote beside its record"""
    integrators: IntegratorStudy | None = None
    """integrators.json's record, or None"""
    simulations: dict[str, Simulation] = field(default_factory=dict)
    """case -> ``readers.Simulation`` of simulate_<case>.* (the last run of the case)"""
    quake_case: Simulation | None = None
    """the paper's earthquake case (simulate_earthquake_paper.*, else simulate_earthquake.*), or None"""
    comparisons: dict[str, Comparison] = field(default_factory=dict)
    """case -> ``compare_reader.Comparison`` of compare_<case>.json and its models' runs"""
    products: dict[str, Product] = field(default_factory=dict)
    """the figures and videos the report drew, by key (``drive_chart``, ``sheet_top``,
    ``animation_runup``, ...)"""
    mode_pictures: dict[str, list[Product]] = field(default_factory=dict)
    """mode set ("bare", "top") -> its modes' pictures, one per mode"""
    external: list[Product] = field(default_factory=list)
    """the other commands' figures found in the output folder, not yet placed by a section"""
    animations: dict[str, AnimationResult] = field(default_factory=dict)
    """animation name -> what rendering it reported"""
    quake_case_animation: str | None = None
    """the product key of the paper's earthquake case's animation, where it was rendered"""
    failures: dict[str, str] = field(default_factory=dict)  # key -> message
    damaged: dict[str, str] = field(default_factory=dict)  # command -> what is wrong with its file
    render_seconds: dict[str, float] = field(default_factory=dict)
    render_window: str = ""
    reused: dict[str, str] = field(default_factory=dict)
    """pictures not drawn again (``modes_bare``, ...) -> when they were drawn (UTC, ISO 8601)"""

    def hint(self, command: str) -> str:
        """What the reader must run: the input is missing, or damaged and to be rebuilt."""
        if command in self.damaged:
            return f"{self.damaged[command]}: rebuild it with `rotorpillar {command} {self.scene_cli}`"
        return not_computed(command, self.scene_cli)


def debugging() -> bool:
    """``--debug`` was given (the CLI passes it on to every stage by ROTORPILLAR_DEBUG)."""
    return bool(os.environ.get("ROTORPILLAR_DEBUG"))


def say(message: str) -> None:
    print(f"[rotorpillar] report: {message}", file=sys.stderr, flush=True)


def attempt(build: Build, key: str, fn: Callable[..., T]) -> T | None:
    """Run one rendering step; on failure record why and carry on."""
    start = time.perf_counter()
    try:
        return fn()
    except Exception as exc:  # a broken figure must not cost the whole report
        build.failures[key] = f"{type(exc).__name__}: {exc}"
        say(f"{key} failed: {build.failures[key]}")
        if debugging():
            traceback.print_exc(file=sys.stderr)
        return None
    finally:
        build.render_seconds[key] = build.render_seconds.get(key, 0.0) + time.perf_counter() - start
