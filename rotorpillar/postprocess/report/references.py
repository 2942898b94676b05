"""The full order's reference mesh and the transients' speed against accuracy, as
``compare_<case>.json`` states them (``full_order_reference``, ``pareto``): the
reference's own error and why the modes left out do not matter; the Pareto
chart of every model on El Centro with its reading.  Pieces the comparison
blocks of the runs and earthquake sections use."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .. import html as h
from .page import bare, shown_unit
from .state import Build

if TYPE_CHECKING:
    from ...transients.references import FullOrderReference


def _pct(x) -> str:
    return "-" if not isinstance(x, (int, float)) or not math.isfinite(x) else f"{100 * abs(x):.2g} %"


#: The loads of a participation table in words.
LOAD_WORDS = {
    "base_x": "the ground's acceleration",
    "plate_x": "the shaft's force along X",
    "plate_z": "the shaft's force along Z",
}


def reference_block(ref: FullOrderReference | None) -> list[str]:
    """What the 3D reference is, its own error, and the participation of the loaded modes."""
    if ref is None:
        return []
    parts = [h.tag("p", ref.statement, class_=None if ref.verified else "warn")]
    part = ref.participation
    if part is not None and part.modes:
        loads = list(part.loads)
        rows = [
            [
                m.index,
                m.kind.replace("_", " ") + (f" n = {m.n_circumferential}" if m.kind == "ovalling" else ""),
                h.num(m.omega, 5),
                "yes" if m.in_band else "no",
                *[h.num(m.shares.get(k), 2) for k in loads],
                "yes" if m.participates else "no",
            ]
            for m in part.modes
        ]
        parts.append(
            h.details(
                f"participation of the loaded tube's modes ({part.source}, band up to {h.num(part.band_top, 4)} rad/s)",
                h.table(
                    [
                        "mode",
                        "kind",
                        "omega (rad/s)",
                        "in band",
                        *[f"share of {LOAD_WORDS.get(k, k)} (-)" for k in loads],
                        "takes part",
                    ],
                    rows,
                ),
            )
        )
    return parts


def pareto_block(build: Build) -> list[str]:
    """compare_earthquake.json's speed against accuracy: the chart and what it says."""
    c = build.comparisons.get("earthquake")
    pa = c.record.pareto if c is not None else None
    if pa is None:
        return [
            h.tag(
                "p",
                "Not computed: `rotorpillar compare --case earthquake --models "
                f"modal,fem3d --pareto {build.scene_cli}` adds it.",
                class_="meta",
            )
        ]
    parts = []
    name = pa.chart
    for p in build.external:
        if name and p.path.name == name:
            p.group = "used"
            parts.append(h.image(p.path, p.caption))
    case, ref, cost = pa.case, pa.reference, pa.cost
    parts.append(
        h.tag(
            "p",
            (
                (
                    f"El Centro ({case.record}) from t = {h.num(case.record_start, 3)} s, "
                    f"{h.num(case.duration, 3)} s, {case.start}. "
                    if case is not None
                    else ""
                )
                + f"The errors are against {ref.label}, whose own error is estimated at "
                f"{_pct(ref.peak_error)} on the peak and {_pct(ref.history_error)} on the "
                f"history ({ref.note or ref.method}): an error below that is not resolved. " + pa.chosen.why + "."
            ),
        )
    )
    # the errors' window and reference in their headers: the comparison's table measures
    # the ROM over another window against another mesh, and its digits differ
    over = f", t = 0 .. {h.num(case.duration, 3)} s" if case is not None else ""
    rows = [
        [
            r.label,
            h.num(r.dofs),
            h.num(r.wall_seconds, 3),
            bare(r.peak_tip, "m"),
            _pct(r.peak_tip_error).removesuffix(" %"),
            _pct(r.history_error).removesuffix(" %"),
            ", ".join(k for k in ("peak_tip", "history") if r.label in getattr(pa.fronts, k)) or "-",
        ]
        for r in pa.runs
    ]
    said = (
        f"every run ({cost.runs}: {cost.computed} computed, {cost.cached} from the cache, "
        f"{h.num(cost.wall_seconds, 3)} s)"
        if cost is not None
        else f"every run ({len(pa.runs)})"
    )
    parts.append(
        h.details(
            said,
            h.table(
                [
                    "model",
                    "DOFs",
                    "wall time, warm (s)",
                    f"peak tip, relative to the ground ({shown_unit('m')})",
                    f"peak tip error against {ref.label}{over} (%)",
                    f"tip history error against {ref.label}{over} (%)",
                    "on the front of",
                ],
                rows,
            ),
        )
    )
    if pa.compile_seconds:
        parts.append(
            h.tag(
                "p",
                "Compilation before the timed runs (not in their times): "
                + ", ".join(f"{k} {h.num(v, 3)} s" for k, v in pa.compile_seconds.items())
                + ".",
                class_="meta",
            )
        )
    return parts
