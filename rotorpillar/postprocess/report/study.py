"""The design study (`rotorpillar study`), when study.json is present: what was
varied, where it ran, the capture boundary found beside the predicted one,
and the study's charts (claimed here, so "Other figures" does not repeat them)."""

from __future__ import annotations

import numpy as np

from ...studies.boundary import TorqueBoundary
from ...studies.result import StudyResult
from .. import html as h
from .parts import scene_differs
from .state import Build

STUDY_JSON = "study.json"


def _predicted_at(b: TorqueBoundary, x, name: str):
    xs = b.other_values
    ys = getattr(b, name)
    pts = [(u, v) for u, v in zip(xs, ys) if v is not None]
    if not pts:
        return None
    if x is None:
        return pts[0][1]
    u, v = zip(*pts)
    return float(np.interp(float(x), u, v))


def _boundary_table(r: StudyResult) -> list[str]:
    b = r.boundary
    if b is None or not b.found or not isinstance(b.predicted, TorqueBoundary):
        return []
    other = b.predicted.other_key
    rows = []
    for row in b.found:
        x = row.other
        rows.append(
            [
                h.num(x, 4) if x is not None else "-",
                h.num(row.captured_max, 5),
                h.num(row.passed_min, 5),
                h.num(_predicted_at(b.predicted, x, "averaging"), 5),
                h.num(_predicted_at(b.predicted, x, "exact_linear"), 5),
                "yes" if row.monotonic else "no",
            ]
        )
    return [
        h.tag("h3", "The capture boundary: found against predicted"),
        h.tag(
            "p",
            "Per value of the other axis: the largest motor torque M0 the study saw "
            "captured and the smallest that passed, beside the torque the averaging "
            "theory (Eq. 19-23) and the exact linear torque balance say is needed.",
        ),
        h.table(
            [
                other or "",
                "captured up to M0 (N*m)",
                "passes from M0 (N*m)",
                "averaging (N*m)",
                "exact linear (N*m)",
                "monotonic",
            ],
            rows,
        ),
    ]


def section_study(build: Build) -> str | None:
    r = build.study
    if r is None:
        if not (build.out / STUDY_JSON).is_file():
            return None
        return h.section("study", "Design study", [h.missing(build.hint("study"))])
    p, ex, bt = r.performance, r.executor, r.batches
    axes = "; ".join(f"{a.key}: {len(a.values)} values from {a.values[0]} to {a.values[-1]}" for a in r.axes)
    parts = scene_differs(build, build.provenance.study)
    parts.append(
        h.tag(
            "p",
            f"{len(r.runs)} {r.case} runs of the {r.model} model over {axes}. "
            f"Ran on {ex.kind} ({ex.workers} workers) in "
            f"{bt.total} batches ({bt.cached} from disk); "
            f"{p.runs_computed} runs computed at "
            f"{h.num(p.runs_per_second, 3)} runs/s.",
        )
    )
    if r.case != "earthquake":
        passed = sum(bool(x.passed) for x in r.runs)
        parts.append(h.tag("p", f"Passed: {passed}; captured at a resonance: {len(r.runs) - passed}."))
    parts += _boundary_table(r)
    names = {f.file for f in r.figures}
    external = build.external
    for prod in [x for x in external if x.path.name in names]:
        parts.append(h.image(prod.path, prod.caption))
    build.external = [x for x in external if x.path.name not in names]
    rows = [
        [
            x.index,
            *(str(x.params.get(a.key)) for a in r.axes),
            h.num(x.final_speed, 5),
            "-" if x.passed is None else ("yes" if x.passed else "no"),
            h.num(x.peak_tip, 4),
            h.num(x.peak_shaft_deflection, 4),
        ]
        for x in r.runs[:500]
    ]
    parts.append(
        h.details(
            f"the runs ({len(r.runs)}; study.csv has them all)",
            h.table(
                [
                    "run",
                    *(a.key for a in r.axes),
                    "final speed (rad/s)",
                    "passed",
                    "peak tip (m)",
                    "peak shaft deflection (m)",
                ],
                rows,
            ),
        )
    )
    return h.section("study", "Design study", parts)
