"""The full order's reference mesh and the transients' speed against accuracy, as
``compare_<case>.json`` states them (``full_order_reference``, ``pareto``): the
reference's own error and why the modes left out do not matter; the Pareto
chart of every model on El Centro with its reading.  Pieces the comparison
blocks of the runs and earthquake sections use."""

from __future__ import annotations

import math

from .. import html as h
from .state import Build


def _pct(x) -> str:
    return "-" if not isinstance(x, (int, float)) or not math.isfinite(x) else f"{100 * abs(x):.2g} %"


def reference_block(doc: dict) -> list[str]:
    """What the 3D reference is, its own error, and the participation of the loaded modes."""
    ref = doc.get("full_order_reference")
    if not isinstance(ref, dict):
        return []
    parts = [h.tag("p", ref.get("statement", ""), class_=None if ref.get("verified") else "warn")]
    part = ref.get("participation")
    if isinstance(part, dict) and part.get("modes"):
        loads = list(part.get("loads") or [])
        rows = [
            [
                m["index"],
                m["kind"] + (f" n = {m['n_circumferential']}" if m["kind"] == "ovalling" else ""),
                h.num(m["omega"], 5),
                "yes" if m["in_band"] else "no",
                *[h.num(m["shares"].get(k), 2) for k in loads],
                "yes" if m["participates"] else "no",
            ]
            for m in part["modes"]
        ]
        parts.append(
            h.details(
                f"participation of the loaded tube's modes ({part.get('source')}, band up to "
                f"{h.num(part.get('band_top'), 4)} rad/s)",
                h.table(
                    ["mode", "kind", "omega (rad/s)", "in band", *[f"share: {k}" for k in loads], "takes part"], rows
                ),
            )
        )
    return parts


def pareto_block(build: Build) -> list[str]:
    """compare_earthquake.json's speed against accuracy: the chart and what it says."""
    c = build.comparisons.get("earthquake")
    pa = c.doc.get("pareto") if c is not None else None
    if not isinstance(pa, dict):
        return [
            h.tag(
                "p",
                "Not computed: `rotorpillar compare --case earthquake --models "
                f"modal,fem3d --pareto {build.scene_cli}` adds it.",
                class_="meta",
            )
        ]
    parts = []
    name = pa.get("chart")
    for p in build.products.get("external", []):
        if name and p.path.name == name:
            p.group = "used"
            parts.append(h.image(p.path, p.caption))
    case, ref, cost = pa.get("case") or {}, pa.get("reference") or {}, pa.get("cost") or {}
    parts.append(
        h.tag(
            "p",
            (
                f"El Centro ({case.get('record')}) from t = {h.num(case.get('record_start'), 3)} s, "
                f"{h.num(case.get('duration'), 3)} s, {case.get('start', 'every model from the same state')}. "
                f"The errors are against {ref.get('label')}, whose own error is estimated at "
                f"{_pct(ref.get('peak_error'))} on the peak and {_pct(ref.get('history_error'))} on the "
                f"history ({ref.get('note', ref.get('method'))}): an error below that is not resolved. "
                + (pa.get("chosen") or {}).get("why", "")
                + "."
            ),
        )
    )
    rows = [
        [
            r["label"],
            h.num(r["dofs"]),
            h.num(r["wall_seconds"], 3),
            h.num(r["peak_tip"], 5),
            _pct(r.get("peak_tip_error")),
            _pct(r.get("history_error")),
            ", ".join(k for k, f in (pa.get("fronts") or {}).items() if r["label"] in f) or "-",
        ]
        for r in pa.get("runs", [])
    ]
    parts.append(
        h.details(
            f"every run ({cost.get('runs')}: {cost.get('computed')} computed, "
            f"{cost.get('cached')} from the cache, {h.num(cost.get('wall_seconds'), 3)} s)",
            h.table(
                [
                    "model",
                    "DOFs",
                    "wall time, warm (s)",
                    "peak tip (m)",
                    "peak error",
                    "history error",
                    "on the front of",
                ],
                rows,
            ),
        )
    )
    comp = pa.get("compile_seconds") or {}
    if comp:
        parts.append(
            h.tag(
                "p",
                "Compilation before the timed runs (not in their times): "
                + ", ".join(f"{k} {h.num(v, 3)} s" for k, v in comp.items())
                + ".",
                class_="meta",
            )
        )
    return parts
