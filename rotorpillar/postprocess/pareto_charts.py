"""The transients' speed against accuracy (compare_earthquake.json's ``pareto``).

Two panels, |error of the peak tip| and error of the tip history against
the warm wall time, one line per family (the ROM by its modes, the beam by
its elements, the 3D tube by its mesh), each point labelled; the Pareto
front as a staircase with its points ringed; the comparison's models
starred; the reference's own error estimate shaded across (an error below
it is not resolved).  Figure and atomic PNG from :mod:`.style`.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from .style import COLOURS, figure, save

if TYPE_CHECKING:
    from ..transients.pareto import ParetoStudy

FAMILY_STYLE = {
    "rom": dict(color="#0072B2", marker="o", label="ROM (1, 2, ... pillar modes)"),
    "beam": dict(color="#009E73", marker="s", label="beam, full order (elements)"),
    "fem3d": dict(color="#CC79A7", marker="D", label="3D, full order (mesh)"),
}
PANELS = (
    ("peak_tip_error", "peak_tip", "peak tip relative to the ground: |error|"),
    ("history_error", "history", "tip history: max |difference| / max |tip|"),
)
FLOOR = 1e-7


def _short(label: str) -> str:
    return (
        label.replace("ROM, ", "").replace(" modes", "").replace(" mode", "").replace("beam, ", "").replace("3D, ", "")
    )


def pareto_chart(pareto: ParetoStudy, path: str | Path, title: str = "") -> Path:
    """Write the chart of a ParetoStudy to ``path`` (PNG)."""
    fig, axes = figure(1400, 560, ncols=2, sharey=True)
    runs = [r for r in pareto.runs if r.ok]
    ref = pareto.reference
    chosen = {c for c in (pareto.chosen.rom, pareto.chosen.fem3d) if c is not None}

    def error(r, field: str) -> float | None:
        value: float | None = getattr(r, field)
        return value

    errs = [abs(e) for r in runs for f, _, _ in PANELS if (e := error(r, f))]
    errs += [e for e in (ref.peak_error, ref.history_error) if e]
    bottom = max(FLOOR, 0.3 * min(errs)) if errs else FLOOR
    for ax, (field, front_key, panel_title) in zip(axes, PANELS):
        for fam, style in FAMILY_STYLE.items():
            pts = sorted(
                (
                    (r.wall_seconds, abs(e), r.label)
                    for r in runs
                    if r.family == fam and (e := error(r, field)) is not None
                ),
                key=lambda p: p[0],
            )
            if not pts:
                continue
            xs, ys, labels = zip(*pts)
            kw = dict(style)
            ax.plot(xs, [max(y, FLOOR) for y in ys], ls="-", lw=1.2, ms=5, **kw)
            for x, y, lab in pts:
                ax.annotate(
                    _short(lab),
                    (x, max(y, FLOOR)),
                    fontsize=7,
                    xytext=(3, 3),
                    textcoords="offset points",
                    color=style["color"],
                )
        on_front = set(getattr(pareto.fronts, front_key))
        fr = sorted(
            (r.wall_seconds, max(abs(e), FLOOR))
            for r in runs
            if r.label in on_front and (e := error(r, field)) is not None
        )
        if fr:
            xs, ys = zip(*fr)
            ax.step(xs, ys, where="post", color="0.3", lw=2.5, alpha=0.35, zorder=0, label="Pareto front")
            ax.plot(xs, ys, ls="none", marker="o", ms=12, mfc="none", mec="0.3", zorder=0)
        for r in runs:
            e = error(r, field)
            if r.label in chosen and e is not None:
                ax.plot(
                    [r.wall_seconds],
                    [max(abs(e), FLOOR)],
                    marker="*",
                    ms=17,
                    color=COLOURS["numeric"],
                    mec="k",
                    ls="none",
                    zorder=5,
                    label="compare's models" if r.label == min(chosen) else None,
                )
        own = ref.peak_error if front_key == "peak_tip" else ref.history_error
        if own:
            ax.axhspan(bottom, own, color="0.85", zorder=-1, label=f"the reference's own error ({ref.method})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(bottom=bottom)
        ax.set_xlabel("wall time, warm (s)")
        ax.set_title(panel_title, fontsize=10)
        ax.grid(True, which="major", alpha=0.3)
    axes[0].set_ylabel(f"relative error against {ref.label}")
    axes[0].legend(loc="best", fontsize=7)
    if title:
        fig.suptitle(title, fontsize=10)
    return save(fig, path)
