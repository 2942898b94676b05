"""The figures no section claimed, and the versions, machine and timings."""

from __future__ import annotations

import json
from datetime import UTC, datetime

from ... import __version__
from ...provenance import machine, versions
from .. import html as h
from .parts import figures_of
from .state import Build


def section_other(build: Build) -> str | None:
    figs = figures_of(build, "other")
    return h.section("other", "Other figures", figs) if figs else None


def _stages_of(doc: dict) -> tuple[float | None, str]:
    """(total, "stage s, ...") of a result's timings; a comparison without
    its own total counts its models' wall times."""
    t = doc.get("timings", {}) if isinstance(doc.get("timings"), dict) else {}
    stages = {k: v for k, v in t.items() if k != "total" and isinstance(v, (int, float))}
    total = t.get("total")
    per = doc.get("per_model") if isinstance(doc.get("per_model"), dict) else None
    if not stages and per:
        stages = {
            f"{m} (wall time)": r["wall_seconds"]
            for m, r in per.items()
            if isinstance(r, dict) and isinstance(r.get("wall_seconds"), (int, float))
        }
    if total is None and stages:
        total = sum(stages.values())
    if total is None and isinstance(doc.get("wall_seconds"), (int, float)):
        total, stages = doc["wall_seconds"], {"the run (wall time)": doc["wall_seconds"]}
    return total, ", ".join(f"{k} {v:.2f}" for k, v in stages.items())


def _timing_rows(build: Build) -> list:
    """Per result JSON in the out folder, its total and stage times; then
    `rotorpillar run`'s stages (run.json, written after its report: the
    previous run's, said so); then this report's."""
    rows = []
    for js in sorted(build.out.glob("*.json")):
        if js.name in ("report.json", "run.json"):  # written after this page: stale here
            continue
        try:
            doc = json.loads(js.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        if not isinstance(doc, dict):
            continue
        total, stages = _stages_of(doc)
        link = h.tag("a", js.name, href=h.relative(js, build.out))
        rows.append(
            [link, h.num(total, 4), stages, datetime.fromtimestamp(js.stat().st_mtime).strftime("%Y-%m-%d %H:%M:%S")]
        )
    run = build.out / "run.json"
    try:
        doc = json.loads(run.read_text(encoding="utf-8")) if run.is_file() else None
    except (OSError, ValueError):
        doc = None
    st = doc.get("stages") if isinstance(doc, dict) else None
    if isinstance(st, dict) and st:
        secs = {
            k: v.get("seconds")
            for k, v in st.items()
            if isinstance(v, dict) and isinstance(v.get("seconds"), (int, float))
        }
        when = datetime.fromtimestamp(run.stat().st_mtime).strftime("%Y-%m-%d %H:%M:%S")
        rows.append(
            [
                h.Raw(
                    h.tag("a", "run.json", href=h.relative(run, build.out))
                    + " (the last <code>rotorpillar run</code>, stages as processes)"
                ),
                h.num(sum(secs.values()), 4),
                ", ".join(f"{k} {v:.2f}" for k, v in secs.items()),
                when,
            ]
        )
    own = ", ".join(f"{k} {v:.2f}" for k, v in build.render_seconds.items())
    rows.append(["this report", h.num(sum(build.render_seconds.values()), 4), own, "now"])
    return rows


def section_provenance(build: Build) -> str:
    parts = [
        h.tag(
            "p",
            f"rotorpillar {__version__}; report written "
            f"{datetime.now(UTC).strftime('%Y-%m-%d %H:%M UTC')}; off-screen "
            f"rendering through {build.render_window or 'no 3D render'}.",
            class_="meta",
        )
    ]
    parts.append(h.tag("h3", "Timings (s)"))
    parts.append(h.table(["result", "total", "stages", "written"], _timing_rows(build)))
    parts.append(h.tag("h3", "Versions"))
    parts.append(h.table(["package", "version"], [[k, val] for k, val in versions().items()]))
    parts.append(h.tag("h3", "Machine"))
    parts.append(h.table(["", ""], [[k, h.num(val)] for k, val in machine().items()]))
    return h.section("provenance", "Versions, machine and timings", parts)
