"""Charts of the engineer's answers: data in, PNG path out (matplotlib Agg, lazy).

- ``bode_chart``: the steady unbalance response against speed, amplitude
  (log) and phase of the tip and of the shaft deflection, the ROM and the
  3D model overlaid, Eq. 19's curves near the resonances, the running speeds;
- ``campbell_chart``: the structural modes against the rotor speed with the
  1x line (and a wind turbine's blade-passing order), the running speeds and
  API 684's required margins as bands;
- ``envelope_chart``: max |M(z)| and max |V(z)| along the height, per model;
- ``history_chart``: a base quantity's history, per model overlaid.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .style import COLOURS, CYCLE, figure, save

#: line styles per model: the ROM dashed over the full orders' solid lines
STYLE = {
    "modal": dict(ls="--", lw=1.2),
    "fem3d": dict(ls="-", lw=1.8, alpha=0.8),
    "beam": dict(ls="-", lw=1.6, alpha=0.8),
}
NAMES = {"modal": "ROM", "fem3d": "3D", "beam": "1D beam"}


def bode_chart(path, curves, averaging=(), running_speeds=(), title: str = "", size=(1000, 760)) -> Path:
    """``curves``: BodeCurve records (model, speeds, tip/shaft amplitude and phase);
    ``averaging``: AveragingCurve records (Eq. 19 near each resonance)."""
    fig, axes = figure(*size, nrows=2, ncols=2, sharex=True, height_ratios=(3, 2))
    for col, (amp, phase, what) in enumerate(
        (("tip_amplitude", "tip_phase", "tip X"), ("shaft_amplitude", "shaft_phase", "shaft deflection X"))
    ):
        a, p = axes[0][col], axes[1][col]
        for c, colour in zip(curves, CYCLE):
            W = np.asarray(c.speeds)
            style = dict(STYLE.get(c.model, {}))
            a.semilogy(
                W,
                1e3 * np.asarray(getattr(c, amp)),
                color=colour,
                label=NAMES.get(c.model, c.model),
                marker="." if c.model == "fem3d" else None,
                ms=3,
                **style,
            )
            p.plot(W, getattr(c, phase), color=colour, **style)
        if col == 0:
            for k, av in enumerate(averaging):
                a.semilogy(
                    av.speeds,
                    1e3 * np.asarray(av.amplitude),
                    color=COLOURS.get("reference", "k"),
                    lw=0.8,
                    ls=":",
                    label="Eq. 19 (averaging)" if k == 0 else None,
                )
        for w in running_speeds:
            for ax in (a, p):
                ax.axvline(w, color="#888888", lw=0.8, ls="-.")
        a.set_title(what)
        a.set_ylabel("amplitude [mm]")
        p.set_ylabel("lag behind the unbalance [deg]")
        p.set_xlabel("rotor speed Omega [rad/s]")
        p.set_ylim(0, 360)
        p.set_yticks([0, 90, 180, 270, 360])
    axes[0][0].legend(loc="upper right", fontsize=8)
    if running_speeds:
        axes[1][0].text(running_speeds[-1], 20, " running", fontsize=8, color="#555555")
    if title:
        fig.suptitle(title)
    return save(fig, path)


def campbell_chart(
    path, modes, running_speeds, top: float, title: str = "", size=(1000, 640), orders: Sequence[int] = ()
) -> Path:
    """Modes (ModeEntry: omega, damping_ratio, kind, model) as horizontal lines (the
    model has no gyroscopic terms: its modes do not move with the speed), the 1x
    line and each further excitation order k of ``orders`` (a rotor of k blades:
    the blade passing, k x its speed), the running speeds, and per mode the speeds API 684 keeps clear,
    (omega / (1 + SM_above), omega / (1 - SM_below)), as a band: red where a
    running speed falls inside."""
    from ..reduced.margins import amplification_factor, required_margin
    from .style import place_labels

    fig, ax = figure(*size)
    ax.plot([0.0, top], [0.0, top], color="k", lw=1.0, label="1x (synchronous unbalance)")
    order_lines(ax, orders, top)
    for w in running_speeds:
        ax.axvline(w, color="#555555", lw=1.0, ls="-.")
        ax.text(w, 0.02 * top, f" running {w:.1f}", rotation=90, va="bottom", fontsize=8)
    labels: dict[Any, dict[str, Any]] = {}
    done: dict[Any, bool] = {}
    for m in modes:
        colour = CYCLE[0] if m.model == "modal" else CYCLE[1]
        af = amplification_factor(m.damping_ratio)
        lo = m.omega / (1 + required_margin(af, below=False))
        hi = m.omega / (1 - required_margin(af, below=True))
        hit = any(lo < w < hi for w in running_speeds)
        key = (m.model, round(m.omega, 6))
        if key not in done:
            ax.axhline(m.omega, color=colour, lw=0.9, ls="--" if m.model == "modal" else "-")
            labels[key] = dict(
                xy=(top, m.omega),
                text=f"{m.kind} ({NAMES.get(m.model, m.model)})",
                color=colour,
                fontsize=7,
                ha="right",
                offset=(-4, 3),
            )
            done[key] = True
        else:
            labels[key]["text"] = labels[key]["text"].replace(
                f" ({NAMES.get(m.model, m.model)})", f", {m.kind} ({NAMES.get(m.model, m.model)})"
            )
        if hi > lo:
            ax.plot(
                [lo, min(hi, top)],
                [m.omega, m.omega],
                color="#d62728" if hit else colour,
                lw=5,
                alpha=0.55 if hit else 0.3,
                solid_capstyle="butt",
            )
            if hit:
                ax.axvspan(lo, min(hi, top), color="#d62728", alpha=0.12, lw=0)
    ax.set_xlim(0, top)
    ax.set_ylim(0, top)
    place_labels(ax, list(labels.values()))
    ax.set_xlabel("rotor speed Omega [rad/s]")
    ax.set_ylabel("natural frequency omega [rad/s]")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title or "Campbell diagram: modes, the 1x line and API 684's separation margins")
    return save(fig, path)


def order_lines(ax, orders: Sequence[int], top: float) -> None:
    """The excitation orders past 1x (k x the rotor speed: a rotor of k blades' blade passing)
    as straight lines from the origin, to the chart's ``top`` (rad/s) on the frequency axis."""
    for k in sorted({int(k) for k in orders} - {0, 1}):
        ax.plot([0.0, top / k], [0.0, top], color="#8c564b", lw=1.0, ls=(0, (6, 2)), label=f"{k}x (the blade passing)")


def envelope_chart(path, runs, title: str = "", size=(1000, 560)) -> Path:
    """``runs``: [(label, model, heights, moment envelope, shear envelope)] -> M(z), V(z)."""
    fig, (a1, a2) = figure(*size, ncols=2, sharey=True)
    for (label, model, z, M, V), colour in zip(runs, CYCLE):
        style = dict(STYLE.get(model, {}))
        a1.plot(1e-6 * np.asarray(M), z, color=colour, label=label, marker="o", ms=2, **style)
        a2.plot(1e-3 * np.asarray(V), z, color=colour, label=label, marker="o", ms=2, **style)
    a1.set_xlabel("max |M(z)| [MN m]")
    a2.set_xlabel("max |V(z)| [kN]")
    a1.set_ylabel("height z [m]")
    a1.legend(loc="upper right", fontsize=8)
    a1.set_xlim(left=0)
    a2.set_xlim(left=0)
    if title:
        fig.suptitle(title)
    return save(fig, path)


def history_chart(path, series, ylabel: str, scale: float = 1.0, title: str = "", size=(1000, 420)) -> Path:
    """``series``: [(label, model, t, values)] overlaid."""
    fig, ax = figure(*size)
    for (label, model, t, y), colour in zip(series, CYCLE):
        ax.plot(t, scale * np.asarray(y), color=colour, label=label, **dict(STYLE.get(model, {})))
    ax.set_xlabel("t [s]")
    ax.set_ylabel(ylabel)
    ax.legend(loc="upper right", fontsize=8)
    if title:
        ax.set_title(title)
    return save(fig, path)
