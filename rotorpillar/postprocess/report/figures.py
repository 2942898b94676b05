"""The PNGs other commands left in the out folder, and the section each belongs to:
the one of the run's case, or of the command, whose JSON names the PNG (never a
word in the file's name)."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

from ... import records
from ...records import Figure, Record
from .state import OWN_DIRS


@dataclass(frozen=True)
class Written:
    """Where a PNG another command wrote belongs, from the JSON that names it."""

    caption: str | None
    """its caption in the JSON's ``figures`` list, if it gives one"""
    group: str
    """the report section (:data:`COMMAND_GROUPS`, else :data:`CASE_GROUPS`), "other" if none"""
    case: str = ""
    """the case of the run that drew it (runup, earthquake, ...), "" if not a run's"""


#: A run's figure (simulate's, compare's) -> the section of its case.
CASE_GROUPS = {"runup": "runs", "rundown": "runs", "sweep": "runs", "earthquake": "earthquake"}
#: The figure of a result that is not one run's -> the section of the command that wrote it.
COMMAND_GROUPS = {
    "converge": "convergence",
    "integrators": "integrators",
    "modal": "modal",
    "study": "study",
    "tornado": "tornado",
    "campbell": "machine3d",
}
#: The charts a command writes beside its JSON without naming them there (campbell.json's
#: record is the diagram alone); its section shows them, "Other figures" must not again.
COMMAND_CHARTS = {"campbell": ("campbell.png",)}
#: The results that name no command in their JSON -> that command (convergence.json).
INPUT_COMMANDS = {"convergence.json": "converge", "integrators.json": "integrators", "study.json": "study"}


class _Chart(Record):
    """A result's ``pareto`` as far as its chart goes."""

    chart: str | None = None


class Charted(Record):
    """What any result file says of the charts it names (every other field left out):
    its ``figures``, its ``charts`` (name -> path), its ``chart`` and its ``pareto.chart``;
    the command that wrote it and the case it ran."""

    command: str | None = None
    case: str | None = None
    figures: tuple[Figure, ...] = ()
    charts: dict[str, str] = {}
    chart: str | None = None
    pareto: _Chart | None = None

    def named(self) -> list[tuple[str, str | None]]:
        """(file name, caption or None) of every chart named."""
        out: list[tuple[str, str | None]] = [(Path(f.file).name, f.caption) for f in self.figures]
        out += [(Path(v).name, None) for v in self.charts.values()]
        for chart in (self.chart, self.pareto.chart if self.pareto is not None else None):
            if chart:
                out.append((Path(chart).name, None))
        return out


def writers(out: Path) -> dict[str, Written]:
    """PNG file name -> where it belongs, from every JSON in ``out`` that names it:
    a study's, the convergence's, the integrators' by the command that wrote it, a
    run's (simulate's, compare's) by its ``case``."""
    found: dict[str, Written] = {}
    for js in sorted(out.glob("*.json")):
        try:
            doc = records.read(js, Charted)
        except (OSError, ValueError):  # not a result (or a damaged one): names no chart
            continue
        command = doc.command or INPUT_COMMANDS.get(js.name, "")
        case = doc.case or ""
        if command in COMMAND_GROUPS:
            group, case = COMMAND_GROUPS[command], ""
        else:
            group = CASE_GROUPS.get(case, "other")
        for name, caption in [*doc.named(), *((c, None) for c in COMMAND_CHARTS.get(command, ()))]:
            was = found.get(name)
            found[name] = Written(caption if caption is not None else (was.caption if was else None), group, case)
    return found


def external_figures(out: Path) -> list[tuple[Path, str, Written]]:
    """PNGs other commands wrote in ``out`` (and its direct subfolders, not ours),
    each with its caption (ours, else the one a JSON beside it gives in a ``figures``
    list, else one made from the file name) and where it belongs (:func:`writers`;
    a PNG no JSON names goes to "Other figures")."""
    written = writers(out)
    found, seen = [], {}
    # the folder itself and its direct subfolders only: --out may point
    # anywhere, and a deep search could sweep up unrelated pictures
    paths = sorted(
        [*out.glob("*.png"), *out.glob("*/*.png")], key=lambda p: (-len(p.stem), str(p))
    )  # a model's own name before its copy
    for p in paths:
        rel = p.relative_to(out)
        if rel.parts[0] in OWN_DIRS or any(part.startswith(".") for part in rel.parts):
            continue
        try:
            digest = hashlib.sha256(p.read_bytes()).hexdigest()
        except OSError:
            continue
        if digest in seen:  # the same picture under two names (simulate's copy)
            continue
        seen[digest] = p
        w = written.get(p.name, Written(None, "other"))
        # ours first: integrators.json's caption says wall time where the axis is evaluations
        found.append((p, CAPTIONS.get(p.name) or w.caption or p.stem.replace("_", " "), w))
    return sorted(found, key=lambda x: str(x[0]))


#: Captions of the charts other commands write without one.
CAPTIONS = {
    "convergence_dofs.png": (
        "Convergence of the pillar models: |relative error| of the first bending frequency, "
        "of the first ovalling frequency, and the error bound on the band's frequencies (what "
        "the choice uses) against the degrees of freedom. Lines: one model family each; circles "
        "(and the grey staircase): the Pareto front, no run both cheaper and more accurate; "
        "star: the model chosen; red dotted line: the tolerance; grey band: the reference's own "
        "uncertainty (errors inside it cannot be told apart); x on the top strip: a run without "
        "that mode."
    ),
    "convergence_time.png": (
        "The same against the wall time per run (on this machine, shared: a noisy measure): "
        "circles: the Pareto front; star: the choice; red dotted line: the tolerance; grey band: "
        "the reference's uncertainty."
    ),
    "integrators.png": (
        "Time integrators. Top: error of the tip history against the number of force "
        "evaluations on a run-up (dashed lines: fixed-step methods; dotted: 10 % error). "
        "Middle: force evaluations as stiffer pillar modes are added (x: the method failed). "
        "Bottom: energy drift of the undamped, unforced system. One colour and marker per "
        "method throughout."
    ),
}
