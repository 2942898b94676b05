"""The comparison of transient models on one case (`rotorpillar compare`): data in, PNG out.

``compare_chart``: the tip's X relative to the ground of every model
overlaid (top), each model's difference to the reference (bottom); the
legend gives each model's error against the reference and its wall time.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .style import CYCLE, figure, save


def compare_chart(path, histories: dict, reference: str, errors: dict, walls: dict,
                  title: str = "") -> Path:
    """``histories``: model -> (t, tip relative to the ground) in the order to draw;
    ``errors``: model -> tip_history_error (the reference has none); ``walls``: model -> s."""
    fig, (a1, a2) = figure(1000, 760, nrows=2, sharex=True)
    t_ref, x_ref = (np.asarray(v, dtype=float) for v in histories[reference])
    colours = dict(zip(histories, CYCLE))
    order = [reference] + [m for m in histories if m != reference]      # the reference underneath
    for name in order:
        (t, x), c = histories[name], colours[name]
        t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
        err = errors.get(name)
        label = (f"{name} (reference), {walls[name]:.3g} s" if name == reference else
                 f"{name}: error {100 * err:.2f} %, {walls[name]:.3g} s")
        a1.plot(t, 1e3 * x, lw=1.6 if name == reference else 0.9, color=c, label=label,
                ls="-" if name == reference else "--")
        if name != reference:
            a2.plot(t_ref, 1e3 * (np.interp(t_ref, t, x) - x_ref), lw=0.8, color=c,
                    label=f"{name} - {reference}")
    a1.set_ylabel("tip X relative to the ground [mm]")
    a1.legend(loc="upper right", fontsize=8)
    a1.set_title(title)
    a2.axhline(0.0, color="0.6", lw=0.6)
    a2.set_ylabel(f"difference to {reference} [mm]")
    a2.set_xlabel("t [s]")
    if len(histories) > 1:
        a2.legend(loc="upper right", fontsize=8)
    return save(fig, path)

