"""Charts of the models compared on one case: data in, PNG path out (matplotlib Agg, lazy).

- ``comparison_chart``: the tip histories of several models of one case
  overlaid (relative to the ground), and below each model's difference from
  the reference model;
- ``spectrum_chart``: a record's pseudo-acceleration response spectrum with
  the pillar's modal periods marked.

Figures, colours and the atomic PNG write come from :mod:`.style`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .style import COLOURS, CYCLE, figure, save

#: Standard gravity, to show accelerations in g (m/s**2).
STANDARD_GRAVITY = 9.80665


def comparison_chart(
    path,
    series,
    reference: str,
    title: str = "",
    size=(1060, 700),
    errors: dict | None = None,
    walls: dict | None = None,
    zoom: tuple[float, float] | None = None,
) -> Path:
    """``series``: [(model, t, tip relative to the ground)], one of them
    named ``reference``.  Top: the histories overlaid (mm); below: each
    other model minus the reference, the reference interpolated linearly
    onto the model's times (mm).  ``errors`` (model -> tip history error)
    and ``walls`` (model -> s), where given, go into the legend.  With
    ``zoom`` (t0, t1), a second column shows that window (the passage
    through resonance of a run-up)."""
    cols = 2 if zoom else 1
    t0, t1 = zoom if zoom else (0.0, 0.0)
    fig, axes = figure(*size, nrows=2, ncols=cols, sharex="col", height_ratios=(3, 2), squeeze=False)
    ref = next(((t, y) for m, t, y in series if m == reference), None)
    for col in range(cols):
        a1, a2 = axes[:, col]
        for (model, t, y), c in zip(series, CYCLE):
            t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
            sel = slice(None) if col == 0 else (t >= t0) & (t <= t1)
            is_ref = model == reference
            label = f"{model} (reference)" if is_ref else model
            if errors and model in errors:
                label += f": error {100 * errors[model]:.2f} %"
            if walls and model in walls:
                label += f", {walls[model]:.3g} s"
            a1.plot(
                t[sel],
                1e3 * y[sel],
                lw=1.6 if is_ref else 0.9,
                ls="-" if is_ref else "--",
                color=c,
                label=label if col == 0 else None,
                zorder=1 if is_ref else 2,
            )
            if ref is not None and not is_ref:
                a2.plot(
                    t[sel],
                    1e3 * (y - np.interp(t, ref[0], ref[1]))[sel],
                    lw=0.9,
                    color=c,
                    label=f"{model} - {reference}" if col == 0 else None,
                )
        a2.axhline(0.0, color=COLOURS["reference"], lw=0.7)
        a2.set_xlabel("t [s]")
        if col == 0:
            a1.set_ylabel("tip, horizontal X,\nrelative to the ground [mm]")
            a2.set_ylabel(f"difference from {reference} [mm]")
        else:
            a1.set_title(f"zoomed on the passage: {t0:.3g} .. {t1:.3g} s", fontsize=9)
    a1, a2 = axes[:, 0]
    a1.legend(loc="upper right", fontsize=8)
    if zoom:
        a1.set_title("the whole run", fontsize=9)
    if ref is None:
        a2.text(0.5, 0.5, f"no arrays of the reference ({reference})", ha="center", va="center", transform=a2.transAxes)
    elif len(series) > 1:
        a2.legend(loc="upper right", fontsize=8)
    fig.suptitle(title, fontsize=10)
    return save(fig, path)


def spectral_value(period, psa, T: float) -> float:
    """The spectrum at period ``T``, read off the curve (linear in log T),
    in the units of ``psa``; NaN outside the periods computed.

    >>> spectral_value([0.1, 1.0], [2.0, 4.0], 10 ** -0.5)
    3.0
    """
    T_, S = np.asarray(period, dtype=float), np.asarray(psa, dtype=float)
    ok = np.isfinite(T_) & np.isfinite(S) & (T_ > 0)
    T_, S = T_[ok], S[ok]
    order = np.argsort(T_)
    T_, S = T_[order], S[order]
    if not len(T_) or not T_[0] <= T <= T_[-1]:
        return float("nan")
    return float(np.interp(np.log(T), np.log(T_), S))


def spectrum_chart(
    path, period, psa, mode_periods=(), damping: float | None = None, title: str = "", size=(900, 540)
) -> Path:
    """The pseudo-acceleration ``psa`` (m/s**2) against ``period`` (s), shown
    in g on a logarithmic period axis; each mode of ``mode_periods`` (a
    period, or (label, period), or (label, period, its own pseudo-acceleration
    in m/s**2 at its own damping)) marked at that value, else on the curve at
    its spectral value, its label placed off the curve."""
    from .style import freeze_layout, place_labels

    fig, ax = figure(*size)
    T, S = np.asarray(period, dtype=float), np.asarray(psa, dtype=float) / STANDARD_GRAVITY
    ok = np.isfinite(T) & np.isfinite(S) & (T > 0)
    label = "PSA" + (f", {100 * damping:g} % damping" if damping is not None else "")
    (curve,) = ax.plot(T[ok], S[ok], color=COLOURS["drive"], lw=1.4, label=label)
    top = float(np.max(S[ok])) if ok.any() else 1.0
    labels: list[dict[str, Any]] = []
    for j, m in enumerate(mode_periods, start=1):
        m = tuple(m) if isinstance(m, (tuple, list)) else (f"mode {j}", m)
        name, Tj = m[0], m[1]
        Sj = float(m[2]) / STANDARD_GRAVITY if len(m) > 2 else spectral_value(T[ok], S[ok], float(Tj))
        ax.axvline(Tj, color=COLOURS["unstable"], lw=0.8, ls="--", zorder=1)
        if np.isfinite(Sj):
            own = len(m) > 2 and not any(t.get_label().startswith("modes at their own") for t in ax.lines)
            ax.plot(
                [Tj],
                [Sj],
                "o",
                color=COLOURS["unstable"],
                ms=6,
                zorder=3,
                label="modes at their own damping" if own else "_nolegend_",
            )
            labels.append(
                {
                    "xy": (Tj, Sj),
                    "offset": (6, 6),
                    "fontsize": 8,
                    "color": COLOURS["unstable"],
                    "text": f"{name}: T = {Tj:.3g} s, {Sj:.3g} g",
                    "bbox": dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.9),
                }
            )
    ax.set_xscale("log")
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("pseudo-acceleration [g]")
    # room above the curve and every mode's own point (at its own damping it may stand above
    # the curve's damping) for the labels, and every mode's period inside the axis
    top = max([top] + [lab["xy"][1] for lab in labels])
    ax.set_ylim(0, 1.25 * top)
    periods = [float(t) for t in T[ok]] + [lab["xy"][0] for lab in labels]
    if periods:
        ax.set_xlim(min(periods) / 1.5, max(periods) * 1.5)
    legend = ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title or "Response spectrum")
    freeze_layout(fig)
    place_labels(ax, labels, obstacles=[legend], lines=[curve], drawn=True)
    return save(fig, path)
