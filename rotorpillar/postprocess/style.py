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


def text_box(text, renderer):
    """The drawn box of a Text or an Annotation's text alone (without its arrow)."""
    from matplotlib.text import Annotation, Text
    if isinstance(text, Annotation):
        text.update_positions(renderer)
    return Text.get_window_extent(text, renderer)


def place_labels(ax, labels, obstacles=(), pad_px: float = 2.0) -> list:
    """Annotate ``ax`` with labels that overlap neither each other nor ``obstacles``.

    ``labels``: dicts with ``xy`` (data coordinates of the point labelled),
    ``text``, optional ``offset`` (points, default (4, 4)) and any
    ``Axes.annotate`` keyword (fontsize, ha, colour...).  Each label, taken
    in order of its point's height, tries its offset (and its mirror image
    left-right), then the same moved down and up by one, two, ... label
    heights, and keeps the first place whose box (as the renderer draws it,
    :func:`text_box`) meets no box placed before, no labelled point, no
    obstacle (artists with a window extent, e.g. the legend) and stays inside
    the axes; a label moved
    off its point gets a thin leader line to it.  Call on the final layout.
    Returns the annotations.
    """
    fig = ax.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = [o.get_window_extent(renderer) for o in obstacles]
    # the labelled points themselves (their markers): no label covers one
    from matplotlib.transforms import Bbox
    for spec in labels:
        x, y = ax.transData.transform(spec["xy"])
        taken.append(Bbox.from_extents(x - 3, y - 3, x + 3, y + 3))
    to_pt = 72.0 / fig.dpi
    flip = {"left": "right", "right": "left", "center": "center"}
    order = sorted(range(len(labels)), key=lambda k: ax.transData.transform(labels[k]["xy"])[1])
    out = [None] * len(labels)
    for k in order:
        spec = dict(labels[k])
        xy, text = spec.pop("xy"), spec.pop("text")
        dx, dy = spec.pop("offset", (4, 4))
        ha = spec.pop("ha", "left")
        spec.setdefault("fontsize", 8)
        t = ax.annotate(text, xy, xytext=(dx, dy), textcoords="offset points", ha=ha,
                        arrowprops=dict(arrowstyle="-", lw=0.5, color="#888888",
                                        shrinkA=0, shrinkB=2), annotation_clip=False, **spec)
        step = (text_box(t, renderer).height + pad_px) * to_pt
        chosen = None
        for n in range(0, 41):
            shift = 0 if n == 0 else (-1) ** n * ((n + 1) // 2) * step
            for side in (1, -1):
                t.xyann = (side * dx, dy + shift)
                t.set_ha(ha if side == 1 else flip[ha])
                box = text_box(t, renderer)
                inside = (box.y0 >= frame.y0 and box.y1 <= frame.y1
                          and box.x0 >= frame.x0 and box.x1 <= frame.x1)
                if inside and not any(box.padded(pad_px / 2).overlaps(b) for b in taken):
                    chosen = shift
                    break
            if chosen is not None:
                break
        if chosen is None:        # nowhere free: keep the first place
            t.xyann = (dx, dy)
            t.set_ha(ha)
            box = text_box(t, renderer)
        t.arrow_patch.set_visible(bool(chosen))
        taken.append(box)
        out[k] = t
    return out
