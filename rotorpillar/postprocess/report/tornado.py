"""How much the answer depends on what nobody knows (`rotorpillar tornado`), when tornado.json
is present: the inputs and their ranges with where each range comes from, the
tornado chart, the sentence on what would change the verdict, each check's
utilisation at the ends of each range, and what the sensitivity leaves out."""

from __future__ import annotations

from ... import records
from ...verdict.tornado import TornadoInput, TornadoResult, value_text
from .. import html as h
from .state import Build

TORNADO_JSON = "tornado.json"
TITLE = "How much the answer depends on what nobody knows"


def _inputs_table(inputs: tuple[TornadoInput, ...]) -> str:
    rows = [
        [i.label, i.key, value_text(i.base, i.unit), value_text(i.low, i.unit), value_text(i.high, i.unit), i.why]
        for i in inputs
    ]
    return h.table(["input", "scene key", "the scene's", "low end", "high end", "why this range"], rows)


def _checks_table(r: TornadoResult) -> str:
    inputs = {i.key: i for i in r.inputs}
    rows = []
    for q in r.quantities:
        if q.kind != "check":
            continue
        for b in q.bars:
            c = b.crossing
            i = inputs[b.key]
            where = "-" if c is None else f"{value_text(c.value, i.unit)} ({c.kind})"
            rows.append(
                [
                    q.name,
                    h.num(q.base, 4),
                    i.label,
                    f"{h.num(b.low, 4)} ({b.low_status or '-'})",
                    f"{h.num(b.high, 4)} ({b.high_status or '-'})",
                    where,
                ]
            )
    return h.table(
        [
            "check",
            "utilisation at the scene's values (-)",
            "input",
            "utilisation at the low end (-)",
            "utilisation at the high end (-)",
            "the input where it reaches 1",
        ],
        rows,
    )


def section_tornado(build: Build) -> str | None:
    path = build.out / TORNADO_JSON
    if not path.is_file():
        return None
    try:
        r = records.read(path, TornadoResult)
    except (OSError, ValueError) as exc:
        return h.section(
            "tornado", TITLE, [h.missing(f"{exc}: rebuild it with `rotorpillar tornado {build.scene_cli}`")]
        )
    parts = [
        h.tag(
            "p",
            f"Each uncertain input at the two ends of its range, every other at the scene's value, on the ROM: "
            "the machine's checks as the analysis makes them, the separation margins on the ROM's unbalance "
            "response, and the run-up and the recorded earthquake through "
            f"the design study ({r.runs} runs, {h.num(r.wall_seconds, 2)} s). Over these checks the verdict is "
            f"{r.verdict}.",
        ),
        h.tag("p", [h.tag("strong", "What would change the verdict: "), r.sentence]),
    ]
    names = {f.file for f in r.figures}
    external = build.external
    for prod in [x for x in external if x.path.name in names]:
        parts.append(h.image(prod.path, prod.caption))
    build.external = [x for x in external if x.path.name not in names]
    if not any(x.path.name in names for x in external):
        for f in r.figures:
            if (build.out / f.file).is_file():
                parts.append(h.image(build.out / f.file, f.caption))
    parts.append(h.tag("h3", "The inputs and their ranges"))
    parts.append(_inputs_table(r.inputs))
    parts.append(h.details("each check at the ends of each range", _checks_table(r)))
    left = [h.tag("li", x) for x in (*r.left_out, *r.notes)]
    if left:
        parts.append(h.tag("p", "Not in the tornado, and notes:"))
        parts.append(h.tag("ul", left))
    return h.section("tornado", TITLE, parts)
