"""`rotorpillar report`: every figure its inputs allow, then one HTML page.

- :mod:`.build`       the options, the build, what report.json holds, the summary text
- :mod:`.state`       what the page is assembled from (Build, Product, the options)
- :mod:`.render`      the report's own charts, mode shapes and animations
- :mod:`.figures`     the other commands' PNGs and the section each belongs to
- :mod:`.parts`       pieces every section uses
- :mod:`.summary`     the findings
- :mod:`.modal`       the scene, the modal validation, the paper's numbers
- :mod:`.runs`        the passage through resonance and the transient runs
- :mod:`.comparison`  the models of one case side by side (compare_<case>.json), the record's spectrum
- :mod:`.earthquake`  a real record on the ROM and the 3D full order first, then the paper's case
- :mod:`.convergence` the convergence study's choice and the integrators
- :mod:`.provenance`  other figures; versions, machine and timings
"""

from .build import ReportOptions, build_report, summary_text

__all__ = ["ReportOptions", "build_report", "summary_text"]
