"""`rotorpillar report`: every figure its inputs allow, then one HTML page.

- :mod:`.build`       the options, the build, the section list (``SECTIONS``), report.json
- :mod:`.page`        the jinja2 environment (templates/, autoescape on), its filters, the page
- :mod:`.answer`      the first screen: the verdict, the checks, the numbers that decide it
- :mod:`.state`       what the page is assembled from (Build, Product, the options)
- :mod:`.render`      the report's own charts, mode shapes and animations
- :mod:`.figures`     the other commands' PNGs (each picture once), the section each belongs to (from the JSON naming it)
- :mod:`.parts`       pieces every section uses (a run's key numbers, each value once)
- :mod:`.models`      the headline model and the paper's, side by side
- :mod:`.modal`       the scene, the modal validation, the paper's numbers
- :mod:`.runs`        the passage through resonance and the transient runs
- :mod:`.passage`     the run-ups' passage through each resonance against the averaging
- :mod:`.compare_section` the models of one case side by side (compare_<case>.json), the record's spectrum
- :mod:`.earthquake`  a real record on the ROM and the 3D full order first, then the paper's case
- :mod:`.convergence` the convergence study's choice; the integrators
- :mod:`.provenance`  other figures; versions, machine and timings

Adding a section: a builder module here, ``section_<name>(build) -> page.Section``,
that makes the records its partial reads and renders
``templates/sections/<name>.html.j2`` (the prose is in the partial; the
macros of ``templates/macros.html.j2`` give a table, a figure with its
caption, a collapsed block, a warning, a missing input), and an entry
``(anchor, title, section_<name>, appendix)`` in ``build.SECTIONS``.  The
answer, the comparisons and the spectrum are templated; the other sections
still return the HTML of ``postprocess.html`` and pass through as it is.
The contents list picks up each section and its ``<h3>`` subsections.
Charts: draw with ``postprocess.style`` (``figure``/``blank``, ``place_labels`` for every
label that could collide, ``save``), at most ``style.PAGE_WIDTH_PX`` wide
with text >= 9 px there; render them in the section's own ``render_*``
step through ``state.attempt`` (a failed chart costs its picture, not the
page) and register them as ``Product`` with a caption; show them with
``parts.product_image``.  Directions in words: ``postprocess.directions``.
Every image needs a caption; each picture appears once.
tests/test_report_reader.py checks all of that in a browser, and the first
screen a designer sees (designer_problems).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .build import ReportOptions, ReportResult, build_report, report_text

__all__ = ["ReportOptions", "ReportResult", "build_report", "report_text"]


def __getattr__(name: str) -> object:
    # The build (every section, jinja2, the transients' records and their numba kernels) is
    # imported when it is asked for, not with the package: the render workers import
    # .parallel alone, and each of them spent 0.4-0.6 s importing the build it never runs.
    if name in __all__:
        from . import build

        return getattr(build, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
