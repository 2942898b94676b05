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

import numpy as np

from .style import COLOURS, CYCLE, figure, save

#: Standard gravity, to show accelerations in g (m/s**2).
STANDARD_GRAVITY = 9.80665


def comparison_chart(path, series, reference: str, title: str = "", size=(1000, 700),
                     errors: dict | None = None, walls: dict | None = None) -> Path:
    """``series``: [(model, t, tip relative to the ground)], one of them
    named ``reference``.  Top: the histories overlaid (mm); below: each
    other model minus the reference, the reference interpolated linearly
    onto the model's times (mm).  ``errors`` (model -> tip history error)
    and ``walls`` (model -> s), where given, go into the legend."""
    fig, (a1, a2) = figure(*size, nrows=2, sharex=True, height_ratios=(3, 2))
    ref = next(((t, y) for m, t, y in series if m == reference), None)
    for (model, t, y), c in zip(series, CYCLE):
        t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
        is_ref = model == reference
        label = f"{model} (reference)" if is_ref else model
        if errors and model in errors:
            label += f": error {100 * errors[model]:.2f} %"
        if walls and model in walls:
            label += f", {walls[model]:.3g} s"
        a1.plot(t, 1e3 * y, lw=1.6 if is_ref else 0.9, ls="-" if is_ref else "--", color=c,
                label=label, zorder=1 if is_ref else 2)
        if ref is not None and not is_ref:
            a2.plot(t, 1e3 * (y - np.interp(t, ref[0], ref[1])), lw=0.9, color=c,
                    label=f"{model} - {reference}")
    a1.set_ylabel("tip X relative to the ground [mm]")
    a1.legend(loc="upper right", fontsize=8)
    a1.set_title(title)
    a2.axhline(0.0, color=COLOURS["reference"], lw=0.7)
    a2.set_ylabel(f"difference from {reference} [mm]")
    a2.set_xlabel("t [s]")
    if ref is None:
        a2.text(0.5, 0.5, f"no arrays of the reference ({reference})", ha="center", va="center",
                transform=a2.transAxes)
    elif len(series) > 1:
        a2.legend(loc="upper right", fontsize=8)
    return save(fig, path)


def spectrum_chart(path, period, psa, mode_periods=(), damping: float | None = None,
                   title: str = "", size=(900, 540)) -> Path:
    """The pseudo-acceleration ``psa`` (m/s**2) against ``period`` (s), shown
    in g on a logarithmic period axis, each of ``mode_periods`` marked and
    labelled with its number."""
    fig, ax = figure(*size)
    T, S = np.asarray(period, dtype=float), np.asarray(psa, dtype=float) / STANDARD_GRAVITY
    ok = np.isfinite(T) & np.isfinite(S) & (T > 0)
    label = "PSA" + (f", {100 * damping:g} % damping" if damping is not None else "")
    ax.plot(T[ok], S[ok], color=COLOURS["drive"], lw=1.4, label=label)
    top = float(np.max(S[ok])) if ok.any() else 1.0
    for j, Tj in enumerate(mode_periods, start=1):
        ax.axvline(Tj, color=COLOURS["unstable"], lw=0.9, ls="--")
        ax.text(Tj, top * (1.0 - 0.12 * ((j - 1) % 3)), f"mode {j}\nT = {Tj:.3g} s",
                fontsize=8, va="top", ha="left", color=COLOURS["unstable"],
                bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85))
    ax.set_xscale("log")
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("pseudo-acceleration [g]")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title or "Response spectrum")
    return save(fig, path)
