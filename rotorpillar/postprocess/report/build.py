"""`rotorpillar report`: every figure its inputs allow, then one HTML page.

Reads what the other commands left in ``out/<scene>/`` (see
:mod:`rotorpillar.postprocess.readers`), renders what it can (charts, mode
shapes, animations: :mod:`.render`), embeds the PNGs the other chart modules
wrote there (:mod:`.figures`), and writes ``report.html``: the scene, the
modal validation (the paper's Eq. 1 against the 3D model, the
reduction, Table 1 and every number the paper prints, flagged), the
averaging analysis, the runs (the run-up's ROM against a full-order model),
the earthquake (a real record on the ROM and the 3D full order, then the
paper's case), the model choice, and the
versions and timings, one module per group of sections.  A section whose
input is missing says which command produces it; a figure that fails to
render says why, and the rest of the report is still written.  Returns what
`rotorpillar report` writes as report.json.
"""

from __future__ import annotations

import re
import sys
import traceback
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from ...provenance import Provenance, write_text
from ...records import Record
from ...transients.compare import COMPARISONS
from .. import html as h
from ..animation import AnimationResult
from ..compare_reader import read_comparison
from ..readers import CASES, INPUTS, SIMULATE_COMMAND, read_record, read_simulation
from .answer import section_answer
from .convergence import section_convergence, section_integrators
from .earthquake import section_earthquake, section_fronts, section_paper_earthquake
from .engineering import section_internal_forces, section_unbalance
from .figures import external_figures
from .machine3d import section_machine3d
from .modal import section_modal, section_paper, section_scene
from .page import Section, page, with_subsections
from .provenance import section_other, section_provenance
from .render import render_3d, render_charts, render_comparisons
from .runs import section_averaging, section_runs
from .state import Build, Product, ReportOptions, debugging, say
from .study import section_study
from .tornado import section_tornado
from .tower import section_tower

if TYPE_CHECKING:
    from ...scene import Scene

__all__ = ["ReportOptions", "ReportResult", "build_report", "report_text"]

R = TypeVar("R")

#: The page, in order: (anchor, title, builder, appendix).  A builder takes the
#: Build and returns its section (a ``page.Section`` from its template, or the
#: HTML of ``html.section`` where the section is not templated yet) or None to
#: leave it out.  The answers come first; the paper's validation, the
#: convergence study, the integrators and the speed-accuracy fronts follow as
#: appendices, collapsed.  A new section is one entry here.
SECTIONS = [
    ("answer", "The answer", section_answer, False),
    ("tornado", "How much the answer depends on what nobody knows", section_tornado, False),
    ("forces", "Internal forces and stresses", section_internal_forces, False),
    ("unbalance", "Unbalance response and separation margins", section_unbalance, False),
    ("earthquake", "The recorded earthquake", section_earthquake, False),
    ("machine3d", "The machine in three dimensions", section_machine3d, False),
    ("runs", "The runs", section_runs, False),
    ("tower", "The tower and its foundation", section_tower, False),
    ("study", "Design study", section_study, False),
    ("scene", "Appendix A: the scene", section_scene, True),
    ("modal", "Appendix B: modal validation", section_modal, True),
    ("paper", "Appendix C: the paper's numbers against ours", section_paper, True),
    ("averaging", "Appendix D: passage through resonance (the paper's averaging)", section_averaging, True),
    # the fronts before the paper's case: their chart is the record's, not one of the pulse's figures
    ("fronts", "Appendix E: speed against accuracy on the record", section_fronts, True),
    ("paper-earthquake", "Appendix F: the paper's earthquake case", section_paper_earthquake, True),
    ("convergence", "Appendix G: convergence study and the model chosen", section_convergence, True),
    ("integrators", "Appendix H: time integrators", section_integrators, True),
    ("other", "Appendix I: other figures", section_other, True),
    ("provenance", "Appendix J: versions, machine and timings", section_provenance, True),
]

#: The sections that read no 3D render (mode pictures, animations) and no other section's
#: figure: built while the workers render (each draws its charts).
BUILT_WHILE_RENDERING = frozenset({"forces", "unbalance", "machine3d"})

_LEGACY = re.compile(r'<section id="[^"]*"><h2>.*?</h2>(.*)</section>', re.S)


def _as_section(ident: str, title: str, got: Section | str, appendix: bool) -> Section:
    """A section built by a template as it is; one built by ``html.section``
    (not templated yet) unwrapped from its <section> and titled as listed."""
    if isinstance(got, Section):
        return Section(got.ident, title, got.body, appendix, got.subsections)
    m = _LEGACY.fullmatch(str(got))
    return with_subsections(ident, title, m.group(1) if m else str(got), appendix)


def _why(exc: Exception) -> str:
    """What went wrong, in one line."""
    return f"{type(exc).__name__}: {exc}"


def _guarded_section(build: Build, ident: str, title: str, fn) -> Section | str | None:
    """A section, or, if its input does not have the shape it expects (an
    older or newer writer), a notice saying so: one section lost, not the page."""
    try:
        return fn(build)
    except Exception as exc:
        key = f"section_{ident}"
        build.failures[key] = _why(exc)
        say(f"section {title!r} failed: {build.failures[key]}")
        if debugging():
            traceback.print_exc(file=sys.stderr)
        return h.section(
            ident,
            title,
            [
                h.tag(
                    "p",
                    f"This section could not be written from its inputs ({build.failures[key]}); "
                    "they may come from another version of rotorpillar: re-run the command that "
                    "wrote them.",
                    class_="failed",
                )
            ],
        )


#: What a damaged input file raises when read (truncated, empty, binary, wrong shape).
DAMAGE = (ValueError, OSError, EOFError, KeyError, TypeError, AttributeError, zipfile.BadZipFile)


def _read(build: Build, command: str, what: str, read):
    """One input read; a damaged file costs its sections only, which say so."""
    try:
        return read()
    except DAMAGE as exc:
        why = str(exc.args[0]) if isinstance(exc, KeyError) and exc.args else str(exc)
        build.damaged[command] = f"{what} is damaged ({type(exc).__name__}: {why[:120]})"
        build.failures[f"input {what}"] = (
            f"{build.damaged[command]}: rebuild it with `rotorpillar {command} {build.scene_cli}`"
        )
        say(f"{what} is damaged ({type(exc).__name__}); its sections say how to rebuild it")
        return None


def _record(build: Build, name: str, record_type: Any) -> tuple[Any, Provenance | None]:
    """The record of input ``name`` and what its command wrote beside it; (None, None) where
    the file is missing or damaged."""
    file, command = INPUTS[name]
    got = _read(build, command, file, lambda: read_record(build.out / file, record_type))
    return (None, None) if got is None else (got.record, got.provenance)


def load_inputs(build: Build) -> None:
    from ...analysis.results import AnalysisResult
    from ...converge.result import ConvergenceStudy
    from ...fem3d.modal_summary import ModalSummary
    from ...studies.result import StudyResult
    from ...transients.integrator_study import IntegratorStudy

    out = build.out
    p = build.provenance
    build.analysis, p.analyze = _record(build, "analyze", AnalysisResult)
    build.modal, p.modal = _record(build, "modal", ModalSummary)
    build.convergence, p.convergence = _record(build, "convergence", ConvergenceStudy)
    build.integrators, p.integrators = _record(build, "integrators", IntegratorStudy)
    for case in CASES:
        sim = _read(build, SIMULATE_COMMAND, f"simulate_{case}.json/.npz", lambda case=case: read_simulation(out, case))
        if sim is not None:
            build.simulations[case] = sim
    # the paper's case: the paper model's own file, else the last earthquake run
    build.quake_case = _read(
        build,
        SIMULATE_COMMAND,
        "simulate_earthquake_paper.json/.npz",
        lambda: read_simulation(out, "earthquake", "paper"),
    ) or build.simulations.get("earthquake")
    for case in COMPARISONS:
        c = _read(build, "compare", f"compare_{case}.json", lambda case=case: read_comparison(out, case))
        if c is not None:
            build.comparisons[case] = c
    # study.json is read by its section; a damaged one is named here as a failed input
    study = _read(build, "study", "study.json", lambda: read_record(out / "study.json", StudyResult))
    if study is not None:
        build.study, p.study = study.record, study.provenance


class ReportResult(Record):
    """report.json: what the report found and rendered, what failed, and the timings."""

    report: str | None
    """the page written (None off MPI rank 0)"""
    inputs: dict[str, bool] = {}
    """input -> whether it was there"""
    figures: tuple[str, ...] = ()
    """the figures on the page (paths)"""
    animations: dict[str, AnimationResult] = {}
    """name -> the animation rendered"""
    failures: dict[str, str] = {}
    """what could not be rendered or read, and why"""
    damaged: dict[str, str] = {}
    """command -> what is wrong with its file"""
    render_seconds: dict[str, float] = {}
    """step -> wall time (s)"""
    render_window: str = ""
    """VTK's render window class (off screen)"""
    reused: dict[str, str] = {}
    """pictures and charts an earlier report drew, unchanged since (``modes_bare``,
    ``chart_response_spectrum``, ...) -> when it drew them (UTC, ISO 8601):
    postprocess.report.kept"""
    bytes: int = 0
    """the page's size (bytes)"""
    summary: str | None = None
    """the summary.json written beside (None: not written)"""


def build_report(
    scene: Scene, out: str | Path, scene_cli: str, options: ReportOptions | None = None, timings=None
) -> ReportResult:
    """Render every figure the inputs in ``out`` allow and write ``out/report.html``."""
    from ...provenance import Timings

    timings = Timings() if timings is None else timings
    build = Build(scene, Path(out), scene_cli, options or ReportOptions())
    with timings("read_inputs"):
        load_inputs(build)

    early: dict[str, Section | str | None] = {}

    def charts() -> None:
        with timings("charts"):
            render_charts(build)
            render_comparisons(build)
            # the sections that draw charts and read no 3D render, built here too: after the
            # workers they kept one core idle (1.4 s of charts on paper's report)
            for ident, title, fn, _ in SECTIONS:
                if ident in BUILT_WHILE_RENDERING:
                    early[ident] = _guarded_section(build, ident, title, fn)

    # the mode shapes and the animations in worker processes, the charts here meanwhile
    with timings("renders"):
        render_3d(build, during=charts)
    build.external = [Product(p, c, group=w.group, case=w.case) for p, c, w in external_figures(build.out)]
    with timings("html"):
        sections = []
        for ident, title, fn, appendix in SECTIONS:
            got = early[ident] if ident in early else _guarded_section(build, ident, title, fn)
            if got:
                sections.append(_as_section(ident, title, got, appendix))
        document = page(f"rotorpillar report: {scene.name}", scene.description or "", sections)
        path = write_text(build.out / "report.html", document)
    figures = [str(p.path) for p in build.products.values() if p.kind == "figure"]
    figures += [str(x.path) for pictures in build.mode_pictures.values() for x in pictures]
    figures += [str(x.path) for x in build.external]
    present = {name: (build.out / f).is_file() for name, (f, _) in INPUTS.items()}
    present.update({f"simulate_{c}": c in build.simulations for c in CASES})
    present["simulate_earthquake_paper"] = (build.out / "simulate_earthquake_paper.json").is_file()
    present.update({f"compare_{c}": c in build.comparisons for c in COMPARISONS})
    # read by their sections (the unbalance response, the design study)
    present.update({name: (build.out / f"{name}.json").is_file() for name in ("harmonic", "study")})
    return ReportResult(
        report=str(path),
        inputs=present,
        figures=tuple(sorted(figures)),
        animations=dict(build.animations),
        failures=dict(build.failures),
        damaged=dict(build.damaged),
        render_seconds=dict(build.render_seconds),
        render_window=build.render_window,
        reused=dict(build.reused),
        bytes=path.stat().st_size,
    )


def report_text(result: ReportResult) -> str:
    have = [k for k, v in result.inputs.items() if v]
    lacking = [k for k, v in result.inputs.items() if not v]
    lines = [
        f"report: {len(result.figures)} figures, {len(result.animations)} animation(s), {result.bytes / 2**20:.1f} MB",
        "  inputs found: " + (", ".join(have) or "none"),
        "  not computed: " + (", ".join(lacking) or "nothing"),
    ]
    for k, v in result.animations.items():
        lines.append(f"  animation {k}: {v.frames} frames, x{v.factor:g}, {v.seconds:.1f} s -> {v.path}")
    for k, when in result.reused.items():
        lines.append(f"  {k}: unchanged since {when}, reused")
    for k, w in result.failures.items():
        lines.append(f"  FAILED {k}: {w}")
    lines.append("  render seconds: " + ", ".join(f"{k} {t:.1f}" for k, t in result.render_seconds.items()))
    return "\n".join(lines)
