"""The figures no section claimed, and the versions, machine and timings."""

from __future__ import annotations

from datetime import UTC, datetime

from ... import __version__, records
from ...provenance import machine, versions
from ...records import Record
from .. import html as h
from .parts import figures_of
from .state import Build


def section_other(build: Build) -> str | None:
    figs = figures_of(build, "other")
    return h.section("other", "Other figures", figs) if figs else None


class _Wall(Record):
    wall_seconds: float | None = None


class Timed(Record):
    """What any result file says of its time (every other field left out): its
    provenance's ``timings``, a comparison's models' wall times, a run's own."""

    timings: dict[str, float] = {}
    per_model: dict[str, _Wall] = {}
    wall_seconds: float | None = None

    def stages(self) -> tuple[float | None, str]:
        """(total, "stage s, ...") of the timings; a comparison without its own total
        counts its models' wall times."""
        stages = {k: v for k, v in self.timings.items() if k != "total"}
        total = self.timings.get("total")
        if not stages and self.per_model:
            stages = {
                f"{m} (wall time)": r.wall_seconds for m, r in self.per_model.items() if r.wall_seconds is not None
            }
        if total is None and stages:
            total = sum(stages.values())
        if total is None and self.wall_seconds is not None:
            total, stages = self.wall_seconds, {"the run (wall time)": self.wall_seconds}
        return total, ", ".join(f"{k} {v:.2f}" for k, v in stages.items())


class _StageSeconds(Record):
    seconds: float | None = None


class _Stages(Record):
    """run.json as far as its stages' times go."""

    stages: dict[str, _StageSeconds] = {}


def _timing_rows(build: Build) -> list:
    """Per result JSON in the out folder, its total and stage times; then
    `rotorpillar run`'s stages (run.json, written after its report: the
    previous run's, said so); then this report's."""
    rows = []
    for js in sorted(build.out.glob("*.json")):
        if js.name in ("report.json", "run.json"):  # written after this page: stale here
            continue
        try:
            total, stages = records.read(js, Timed).stages()
        except (OSError, ValueError):  # not a result with its time
            continue
        link = h.tag("a", js.name, href=h.relative(js, build.out))
        rows.append(
            [link, h.num(total, 4), stages, datetime.fromtimestamp(js.stat().st_mtime).strftime("%Y-%m-%d %H:%M:%S")]
        )
    run = build.out / "run.json"
    try:
        st = records.read(run, _Stages).stages if run.is_file() else {}
    except (OSError, ValueError):
        st = {}
    secs = {k: v.seconds for k, v in st.items() if v.seconds is not None}
    if secs:
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
    if build.reused:
        own += "; reused, unchanged: " + ", ".join(f"{k} (drawn {v})" for k, v in build.reused.items())
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
    parts.append(h.table(["result", "total (s)", "stages (s)", "written"], _timing_rows(build)))
    parts.append(h.tag("h3", "Versions"))
    parts.append(h.table(["package", "version"], [[k, val] for k, val in versions().items()]))
    parts.append(h.tag("h3", "Machine"))
    parts.append(h.table(["", ""], [[k, h.num(val)] for k, val in records.to_builtins(machine()).items()]))
    return h.section("provenance", "Versions, machine and timings", parts)
