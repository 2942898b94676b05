"""campbell.png: the Campbell diagram (a CampbellDiagram record in, a PNG out; matplotlib Agg, lazy).

Each branch's damped frequency against the rotor speed, solid where it whirls
forward, dashed backward, dotted where its orbit is a line; the 1x line; the
critical speeds (where the 1x line crosses a branch) as dots, filled where the
unbalance excites them; around the running speed, API 684's bands: the speeds a
critical speed must keep clear of, N_run (1 - SM_below) to N_run (1 + SM_above),
for the most demanding AF (infinite: 17 % below, 27 % above) and, darker, for
each critical speed's own AF where the unbalance response shows its peak.  The
labels sit off the lines (style.place_labels).  A diagram with the 3D model's
beside it (its ``fem3d``): the 3D branches in grey, thin, a cross at each of
its speeds (their whirl by the same line styles), its critical speeds as black
crosses, the legend naming the ROM and the 3D model apart.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .style import CYCLE, figure, save

#: line style per whirl
WHIRL_STYLE = {"forward": "-", "backward": "--", "none": ":"}


def _segments(x, y, whirl):
    """(x, y, whirl) runs of one whirl along a branch."""
    out, start = [], 0
    for i in range(1, len(x) + 1):
        if i == len(x) or whirl[i] != whirl[start]:
            stop = min(i + 1, len(x))
            out.append((x[start:stop], y[start:stop], whirl[start]))
            start = i
    return out


def campbell_diagram_chart(path, diagram, title: str = "", size=(1000, 680), orders: Sequence[int] = ()) -> Path:
    """``diagram``: a rotorpillar.reduced.campbell.CampbellDiagram; ``orders``: the excitation
    orders past 1x to draw (a rotor's blade count: the blade passing)."""
    from ..reduced.margins import SM_ABOVE_EXTRA, SM_BELOW, required_margin
    from .engineering_charts import order_lines
    from .style import place_labels

    speeds = np.asarray(diagram.speeds, dtype=float)
    top = float(speeds[-1])
    fig, ax = figure(*size)
    lines = []
    labels: list[dict] = []
    shown = [b for b in diagram.modes if float(np.min(b.frequency)) <= 1.15 * top]
    for b, colour in zip(shown, CYCLE * (len(shown) // len(CYCLE) + 1)):
        for x, y, w in _segments(speeds, np.asarray(b.frequency), b.whirl):
            (ln,) = ax.plot(x, y, color=colour, ls=WHIRL_STYLE.get(w, "-"), lw=1.3)
            lines.append(ln)
        at = (
            (speeds[-1], float(b.frequency[-1])) if b.frequency[-1] <= 1.1 * top else (speeds[0], float(b.frequency[0]))
        )
        near = [lab for lab in labels if abs(lab["xy"][1] - at[1]) <= 0.02 * top and lab["xy"][0] == at[0]]
        if near:  # branches on top of each other (the two bending planes): one label
            near[0]["text"] += ", " + b.label
        else:
            labels.append(dict(xy=at, text=b.label, color=colour, fontsize=7, ha="right", offset=(-4, 3)))
    ref = getattr(diagram, "fem3d", None)
    if ref is not None:
        rs = np.asarray(ref.speeds, dtype=float)
        for b in ref.modes:
            if float(np.min(b.frequency)) > 1.15 * top:
                continue
            for x, y, w in _segments(rs, np.asarray(b.frequency), b.whirl):
                (ln,) = ax.plot(x, y, color="#7f7f7f", ls=WHIRL_STYLE.get(w, "-"), lw=0.8, marker="x", ms=4)
                lines.append(ln)
        for c in ref.critical_speeds:
            ax.plot([c.speed], [c.speed], "x", ms=8, mew=1.5, color="k", zorder=6)
    (one,) = ax.plot([0.0, top], [0.0, top], color="k", lw=1.0, label="1x (the unbalance)")
    lines.append(one)
    order_lines(ax, orders, 1.15 * top)
    run = diagram.running_speed
    if run is not None:
        ax.axvspan(run * (1 - SM_BELOW), run * (1 + SM_BELOW + SM_ABOVE_EXTRA), color="#d62728", alpha=0.07, lw=0)
        ax.axvline(run, color="#555555", lw=1.0, ls="-.")
        labels.append(dict(xy=(run, 0.03 * top), text=f"running {run:.1f} rad/s", fontsize=8, color="#555555"))
        afs = [c.amplification_factor for c in diagram.critical_speeds if c.amplification_factor is not None]
        if afs and max(afs) >= 2.5:
            af = max(afs)
            ax.axvspan(
                run * (1 - required_margin(af, True)),
                run * (1 + required_margin(af, False)),
                color="#d62728",
                alpha=0.12,
                lw=0,
                label=f"API 684: speeds to keep clear at the largest AF, {af:.3g}",
            )
    for c in diagram.critical_speeds:
        excited = c.excited_by != "neither"
        ax.plot([c.speed], [c.speed], "o", ms=6, mfc="#d62728" if excited else "white", mec="#d62728", zorder=5)
        af = "no peak" if c.amplification_factor is None else f"AF {c.amplification_factor:.3g}"
        same = [lab for lab in labels if lab.get("critical") and abs(lab["xy"][0] - c.speed) <= 0.02 * top]
        if same:
            continue  # a critical speed on top of another one: the first one's label stands for both
        labels.append(
            dict(xy=(c.speed, c.speed), text=f"{c.speed:.1f} rad/s, {af}", fontsize=7, color="#a01010", critical=True)
        )
    ax.plot([], [], color="#444444", ls="-", label="forward whirl")
    ax.plot([], [], color="#444444", ls="--", label="backward whirl")
    ax.plot([], [], color="#444444", ls=":", label="no whirl (a line)")
    ax.plot([], [], "o", mfc="#d62728", mec="#d62728", label="critical speed, excited")
    ax.plot([], [], "o", mfc="white", mec="#d62728", label="critical speed, not excited")
    if ref is not None:
        ax.plot([], [], color="#444444", lw=1.3, label="ROM (colours, labelled)")
        ax.plot([], [], color="#7f7f7f", lw=0.8, marker="x", ms=4, label=f"3D model ({len(ref.speeds)} speeds)")
        ax.plot([], [], "x", ms=8, mew=1.5, color="k", label="3D critical speed (its gyroscopic pencil)")
    if run is not None:
        ax.fill_between([], [], color="#d62728", alpha=0.15, label="API 684: speeds to keep clear (AF infinite)")
    ax.set_xlim(0.0 if speeds[0] <= 0.05 * top else speeds[0], top)
    ax.set_ylim(0.0, 1.15 * top)
    ax.set_xlabel("rotor speed Omega [rad/s]")
    ax.set_ylabel("damped natural frequency [rad/s]")
    legend = ax.legend(loc="upper left", fontsize=7)
    ax.set_title(title or f"Campbell diagram ({diagram.model})")
    for lab in labels:
        lab.pop("critical", None)
    place_labels(ax, labels, obstacles=[legend], lines=lines)
    return save(fig, path)
