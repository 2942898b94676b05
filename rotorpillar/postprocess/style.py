"""The one chart style of the project: figure creation, colours, atomic PNGs.

Every matplotlib figure (``charts``, ``transient_charts``,
``convergence_charts``, the animation's chart panel) is made by
:func:`figure` or :func:`blank` and written by :func:`save`, so all the
figures look alike and a PNG is never seen half written.
"""

from __future__ import annotations

from pathlib import Path

from ..provenance import atomic_path

#: Pixels per inch of saved charts: a 7.5 x 4.5 in figure is 900 x 540 px.
DPI = 120

#: Colours by role, colour-blind safe (Okabe-Ito).
COLOURS = {
    "drive": "#0072B2",      # motor torque Md
    "load": "#7f7f7f",       # machine load Mc
    "stable": "#009E73",
    "unstable": "#D55E00",
    "analytic": "#000000",
    "numeric": "#E69F00",
    "ground": "#CC79A7",
    "accent": "#56B4E9",
    "rising": "#D55E00",     # a run or sweep going up in speed or torque
    "falling": "#0072B2",    # ... going down
    "reference": "#999999",  # marker lines: resonances, thresholds
    "tolerance": "#CC0000",   # red: the line a result must get under
}
CYCLE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"]

RC = {
    "figure.dpi": DPI,
    "savefig.dpi": DPI,
    "font.size": 9,
    "axes.titlesize": 10,
    "axes.labelsize": 9,
    "legend.fontsize": 8,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "lines.linewidth": 1.4,
    "figure.constrained_layout.use": True,
}


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display), with our style."""
    import matplotlib
    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt
    from cycler import cycler
    plt.rcParams.update(RC)
    plt.rcParams["axes.prop_cycle"] = cycler(color=CYCLE)
    return plt


def figure(width_px: int = 900, height_px: int = 540, **subplots_kw):
    """A figure of the given pixel size and its axes (``plt.subplots`` arguments)."""
    plt = pyplot()
    return plt.subplots(figsize=(width_px / DPI, height_px / DPI), dpi=DPI, **subplots_kw)


def save(fig, path: str | Path) -> Path:
    """Write ``fig`` as a PNG of exactly its pixel size, atomically, and close it."""
    plt = pyplot()
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format="png", dpi=DPI)
    plt.close(fig)
    return path


def blank(width_px: int = 900, height_px: int = 540):
    """An empty figure of the given pixel size (lay out its axes yourself)."""
    plt = pyplot()
    return plt.figure(figsize=(width_px / DPI, height_px / DPI), dpi=DPI)
