"""`rotorpillar tornado`: how much the verdict's checks depend on the inputs nobody knows well.

``rotorpillar tornado [SCENE] [--vary KEY=LO,HI]... [--out DIR]``.  Each
uncertain input (the pillar's damping, the rotor's eccentricity, the shaft's
stiffness, the top plate's model; ``--vary`` replaces a range or adds an input)
at the two ends of its range, the others at the scene's, on the ROM: the
machine's checks as `analyze` makes them, the separation margins as `harmonic`
makes them (without its 3D response), and the run-up and the earthquake
through the design study's batch loop.  Writes ``out/<scene>/tornado.json``
(this command's record, :class:`rotorpillar.verdict.tornado.TornadoResult`),
the chart ``tornado.png`` and the study's batches under ``tornado/`` (a rerun
reads them).  Measured on the paper's scene: ~7 s (18 ROM runs).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scene import Scene
    from ..verdict.tornado import TornadoResult

from . import Done, progress


def add_arguments(p) -> None:
    p.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="KEY=LO,HI",
        help="an input's range: its two ends (repeatable; replaces a default range or adds an input), "
        "e.g. --vary pillar.damping=10e3,50e3",
    )


def preflight(scene: Scene, args) -> None:
    """What `tornado` refuses before any work: a --vary that is not a scene key's two valid ends."""
    from ..verdict.tornado import inputs_for

    inputs_for(scene, list(getattr(args, "vary", []) or []), with_fem3d=False)


def tornado_command(scene: Scene, args, timings):
    from ..postprocess.tornado_chart import tornado_chart
    from ..records import replace
    from ..verdict.tornado import tornado_study
    from . import out_dir

    preflight(scene, args)
    out = out_dir(scene, args)
    with timings("tornado"):
        res = tornado_study(scene, out, args.vary, log=progress)
    with timings("chart"):
        res = replace(res, figures=tuple(tornado_chart(res, out)))
    return Done(res, _summary(res))


def _summary(r: TornadoResult) -> str:
    lines = [f"rotorpillar tornado {r.scene_name}: {r.runs} ROM runs in {r.wall_seconds:.1f} s; verdict {r.verdict}"]
    from ..verdict.tornado import value_text

    for i in r.inputs:
        lines.append(
            f"  {i.key}: {value_text(i.low, i.unit)} .. {value_text(i.high, i.unit)} "
            f"(scene: {value_text(i.base, i.unit)})"
        )
    for q in r.quantities:
        if q.kind != "check":
            continue
        top = q.bars[0] if q.bars else None
        swing = "" if top is None else f"; widest {top.key}: {top.low:.4g} .. {top.high:.4g}"
        lines.append(f"  {q.name}: utilisation {q.base:.4g} ({q.base_status}){swing}")
    lines.append(f"  {r.sentence}")
    lines += [f"  left out: {x}" for x in r.left_out]
    lines += [f"  note: {x}" for x in r.notes]
    lines += [f"  chart: {f.file}" for f in r.figures]
    return "\n".join(lines)
