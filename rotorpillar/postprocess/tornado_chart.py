"""The tornado chart of ``rotorpillar tornado`` (tornado.png), from its ``TornadoResult``.

One panel per quantity: each assessed check's utilisation (demand over
capacity, the capacity drawn at 1) and each transient response (in mm), the
governing check first.  In a panel, one bar per input, from its value at the
low end of the input's range to its value at the high end, the longest bar on
top; the scene's value is the dashed line.  The axes are logarithmic: the
utilisations of one scene span orders of magnitude, and a factor reads the same
anywhere on them.  Nothing is recomputed: the numbers are tornado.json's.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..records import Figure
from ..verdict.tornado import value_text
from .style import COLOURS, figure, save

TORNADO_PNG = "tornado.png"
LOW, HIGH = COLOURS["falling"], COLOURS["rising"]
#: a response's unit on the chart, and the factor from SI
SHOWN = {"m": ("mm", 1e3)}


def _plain_ticks(ax, decades: float) -> None:
    """Ticks at 1 and 3 (over two decades), 1, 2, 5, or more within a decade, as plain numbers."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    subs = (1.0, 3.0) if decades > 2 else (1.0, 2.0, 5.0) if decades > 1 else (1.0, 1.5, 2.0, 3.0, 5.0, 7.0)
    ax.xaxis.set_major_locator(LogLocator(subs=subs))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())


def _panel(ax, q, labels: dict[str, str]) -> None:
    unit, scale = ("-", 1.0) if q.kind == "check" else SHOWN.get(q.unit, (q.unit, 1.0))
    bars = list(reversed(q.bars))  # barh draws from the bottom: the longest on top
    base = None if q.base is None else q.base * scale
    xs = [] if base is None else [base]
    for y, b in enumerate(bars):
        for v, colour in ((b.low, LOW), (b.high, HIGH)):
            if v is None or base is None or v <= 0 or base <= 0:
                continue
            v *= scale
            xs.append(v)
            ax.barh(y, v - base, left=base, height=0.6, color=colour)
    ax.set_yticks(range(len(bars)), [labels.get(b.key, b.key) for b in bars])
    if xs and min(xs) > 0:
        lo, hi = min(xs), max(xs)
        if q.kind == "check":
            lo, hi = min(lo, 1.0), max(hi, 1.0)
        pad = max(math.log10(hi / lo) * 0.08, 0.05)
        ax.set_xscale("log")
        ax.set_xlim(lo / 10**pad, hi * 10**pad)
        _plain_ticks(ax, math.log10(hi / lo) + 2 * pad)
    if base is not None:
        ax.axvline(base, color=COLOURS["analytic"], linestyle="--", linewidth=1.0)
    if q.kind == "check":
        ax.axvline(1.0, color=COLOURS["tolerance"], linewidth=1.2)
        status = "" if q.base_status is None else f": {q.base_status}"
        ax.set_title(f"{q.name}\nutilisation {q.base:.3g}{status}", loc="left")
        ax.set_xlabel("utilisation, demand / capacity (-)")
    else:
        ax.set_title(f"{q.name}\n{q.base * scale:.3g} {unit} (ROM)", loc="left")
        ax.set_xlabel(f"{q.name.split(': ')[-1]} ({unit})")
    ax.grid(axis="y", visible=False)


def tornado_chart(result, out_dir: str | Path) -> list[Figure]:
    """Draw tornado.png into ``out_dir``; the figures drawn (none when there is no quantity)."""
    quantities = [q for q in result.quantities if q.base is not None and q.bars]
    if not quantities:
        return []
    labels = {i.key: i.label for i in result.inputs}
    rows = math.ceil(len(quantities) / 2)
    fig, axes = figure(1060, 90 + 215 * rows, nrows=rows, ncols=2, squeeze=False)
    for ax, q in zip(axes.flat, quantities):
        _panel(ax, q, labels)
    for ax in list(axes.flat)[len(quantities) :]:
        ax.set_visible(False)
    ends = "; ".join(f"{i.label} {value_text(i.low, i.unit)} to {value_text(i.high, i.unit)}" for i in result.inputs)
    from matplotlib.patches import Patch

    handles = [
        Patch(color=c, label=t)
        for c, t in (
            (LOW, "low end of the range (the top plate: the 1D beam's point mass)"),
            (HIGH, "high end (the 3D model's rigid top plate)"),
        )
    ]
    fig.legend(handles=handles, loc="outside lower center", ncols=2)
    fig.suptitle("How much each check moves over each uncertain input's range (the dashed line: the scene's value)")
    path = save(fig, Path(out_dir) / TORNADO_PNG)
    caption = (
        f"Tornado: each check's utilisation (red line: the capacity) and each response at the two ends of "
        f"each input's range, the others at the scene's values, on the ROM ({result.runs} runs). Ranges: {ends}."
    )
    return [Figure(path.name, caption)]
