"""The one chart style of the project: figure creation, colours, atomic PNGs.

Every matplotlib figure (``charts``, ``transient_charts``,
``convergence_charts``, the animation's chart panel) is made by
:func:`figure` or :func:`blank` and written by :func:`save`, so all the
figures look alike and a PNG is never seen half written.

Legibility is checked where the chart is drawn: :func:`save` measures every
text of the figure (titles, axis and tick labels, legends, annotations) as
the renderer draws it and writes into the PNG itself (a ``tEXt`` chunk,
:data:`LAYOUT_KEY`) the smallest font in pixels and the problems it found:
a text running off the figure, two texts overlapping, a label
:func:`place_labels` found no free place for, a font below
:data:`MIN_FONT_PX` at the width the report shows the figure
(:data:`PAGE_WIDTH_PX`).  The 3D renders tag theirs with :func:`tag_png`.
The report's reader test reads the chunk back (:func:`png_layout`).
"""

from __future__ import annotations

import json
import struct
import zlib
from pathlib import Path

from ..provenance import atomic_path

#: Pixels per inch of saved charts: a 7.5 x 4.5 in figure is 900 x 540 px.
DPI = 120
#: The smallest text a reader is asked to read, at the width the page shows it (px).
MIN_FONT_PX = 9.0
#: The widest the report shows a figure: its text column (px); wider PNGs are scaled down.
PAGE_WIDTH_PX = 1060
#: The PNG text chunk holding a picture's legibility record (JSON).
LAYOUT_KEY = "rotorpillar:layout"

#: Colours by role, colour-blind safe (Okabe-Ito).
COLOURS = {
    "drive": "#0072B2",  # motor torque Md
    "load": "#7f7f7f",  # machine load Mc
    "stable": "#009E73",
    "unstable": "#D55E00",
    "analytic": "#000000",
    "numeric": "#E69F00",
    "ground": "#CC79A7",
    "accent": "#56B4E9",
    "rising": "#D55E00",  # a run or sweep going up in speed or torque
    "falling": "#0072B2",  # ... going down
    "reference": "#999999",  # marker lines: resonances, thresholds
    "tolerance": "#CC0000",  # red: the line a result must get under
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
    """Write ``fig`` as a PNG of exactly its pixel size, atomically, and close it;
    its legibility record (:func:`legibility`) goes into the PNG."""
    import matplotlib.image

    plt = pyplot()
    path = Path(path)
    record = legibility(fig)  # draws the figure
    if not _frozen(fig):
        # the layout as drawn and measured, kept: savefig would lay it out and draw it twice more
        fig.set_layout_engine("none")
    metadata = {LAYOUT_KEY: json.dumps(record, separators=(",", ":"))}
    with atomic_path(path) as tmp:
        if fig.dpi == DPI and not fig.stale and _frozen(fig):
            # what savefig writes (Agg's print_png), without drawing it a second time
            matplotlib.image.imsave(
                tmp, fig.canvas.buffer_rgba(), format="png", origin="upper", dpi=DPI, metadata=metadata
            )
        else:
            fig.savefig(tmp, format="png", dpi=DPI, metadata=metadata)
    plt.close(fig)
    return path


def freeze_layout(fig) -> None:
    """Lay ``fig`` out as its first draw would (its layout engine, e.g. constrained), and
    keep that layout: the axes move no more, labels placed on it stay where they were
    placed (:func:`place_labels`, ``drawn=True``) and :func:`save` draws the figure once.
    The layout without the draw: the draw a caller made for it was a quarter of the run-up
    chart's time, and :func:`save` draws the figure again anyway (the same PNG bytes)."""
    engine = fig.get_layout_engine()
    if engine is not None and fig.axes:
        engine.execute(fig)
    fig.set_layout_engine("none")


def _frozen(fig) -> bool:
    """No layout engine moves the axes when ``fig`` is drawn again (none, or the
    placeholder ``set_layout_engine("none")`` leaves)."""
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    engine = fig.get_layout_engine()
    return engine is None or isinstance(engine, PlaceHolderLayoutEngine)


def _texts(fig) -> list:
    """Every visible, non-empty text the figure draws: suptitle and figure
    texts, titles, axis labels, the tick labels inside the view, annotations,
    legends (figure and axes)."""
    out = list(fig.texts)
    for leg in fig.legends:
        out += list(leg.get_texts()) + [leg.get_title()]
    for ax in fig.axes:
        out += [
            ax.title,
            getattr(ax, "_left_title", None),
            getattr(ax, "_right_title", None),
            ax.xaxis.label,
            ax.yaxis.label,
        ]
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            log = axis.get_scale() == "log" and lo > 0
            slack = 1e-9 * (abs(hi - lo) if not log else 0.0)
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                x = tick.get_loc()
                inside = (lo * (1 - 1e-9) <= x <= hi * (1 + 1e-9)) if log else (lo - slack <= x <= hi + slack)
                if inside:
                    out += [tick.label1, tick.label2]
        out += list(ax.texts)
        if ax.get_legend() is not None:
            out += list(ax.get_legend().get_texts()) + [ax.get_legend().get_title()]
    return [
        t
        for t in out
        if t is not None and t.get_visible() and t.get_text().strip() and (t.axes is None or t.axes.get_visible())
    ]


def legibility(fig, display_width: float | None = None) -> dict:
    """The figure's legibility as the renderer draws it: ``font_px`` (its
    smallest text, px), ``width_px``, ``display_font_px`` (the smallest
    text at the width the page shows it: ``display_width``, default
    min(width, PAGE_WIDTH_PX)) and ``problems`` (texts off the figure,
    overlapping texts, labels :func:`place_labels` could not place, fonts
    below MIN_FONT_PX where shown)."""
    fig.canvas.draw()
    drawn_stale = fig.stale
    renderer = fig.canvas.get_renderer()
    frame = fig.bbox
    texts = _texts(fig)
    boxes = [text_box(t, renderer, drawn=True) for t in texts]
    # Asking the axes for their tick objects marks the figure stale although nothing drawn
    # changes; left so, save() drew every figure twice more through savefig (a 9-panel
    # chart: 1.5 s of 3.6).  The canvas holds the picture this record measured.
    fig.stale = drawn_stale
    problems = []
    for t, b in zip(texts, boxes):
        if b.x0 < frame.x0 - 1 or b.y0 < frame.y0 - 1 or b.x1 > frame.x1 + 1 or b.y1 > frame.y1 + 1:
            problems.append(f"off the figure: {t.get_text()[:60]!r}")
    for i in range(len(texts)):
        for j in range(i + 1, len(texts)):
            if boxes[i].width and boxes[j].width and boxes[i].overlaps(boxes[j]) and _area(boxes[i], boxes[j]) > 2.0:
                problems.append(f"overlap: {texts[i].get_text()[:40]!r} / {texts[j].get_text()[:40]!r}")
    problems += [f"no free place for the label {x!r}" for x in getattr(fig, "_unplaced_labels", [])]
    sizes = [t.get_fontsize() * fig.dpi / 72.0 for t in texts]
    font_px = float(min(sizes)) if sizes else None
    width = float(frame.width)
    shown = min(width, display_width or PAGE_WIDTH_PX)
    display_font = None if font_px is None else font_px * shown / width
    if display_font is not None and display_font < MIN_FONT_PX - 1e-6:
        problems.append(
            f"smallest text {display_font:.1f} px where the page shows the figure "
            f"({shown:.0f} px wide), below {MIN_FONT_PX:g} px"
        )
    return {"font_px": font_px, "width_px": width, "display_font_px": display_font, "problems": problems}


def _area(a, b) -> float:
    """Area (px**2) of the intersection of two boxes."""
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return max(w, 0.0) * max(h, 0.0)


def tag_png(path: str | Path, font_px: float, width_px: float, problems=()) -> Path:
    """Write the legibility record of a picture drawn elsewhere (a 3D render:
    its smallest font, as the renderer sizes it, in px) into its PNG, in place."""
    path = Path(path)
    raw = path.read_bytes()
    shown = min(width_px, PAGE_WIDTH_PX)
    record = {
        "font_px": float(font_px),
        "width_px": float(width_px),
        "display_font_px": float(font_px) * shown / width_px,
        "problems": list(problems),
    }
    body = LAYOUT_KEY.encode("latin-1") + b"\0" + json.dumps(record).encode("latin-1")
    chunk = struct.pack(">I", len(body)) + b"tEXt" + body + struct.pack(">I", zlib.crc32(b"tEXt" + body) & 0xFFFFFFFF)
    end = raw.rfind(b"IEND") - 4  # the IEND chunk's length field
    with atomic_path(path) as tmp:
        Path(tmp).write_bytes(raw[:end] + chunk + raw[end:])
    return path


def png_layout(data: bytes) -> dict | None:
    """The legibility record in a PNG's bytes (:data:`LAYOUT_KEY`), or None."""
    pos = 8
    while pos + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[pos : pos + 8])
        if kind == b"tEXt":
            key, _, value = data[pos + 8 : pos + 8 + n].partition(b"\0")
            if key.decode("latin-1") == LAYOUT_KEY:
                return json.loads(value.decode("latin-1"))
        if kind == b"IEND":
            break
        pos += 12 + n
    return None


def blank(width_px: int = 900, height_px: int = 540):
    """An empty figure of the given pixel size (lay out its axes yourself)."""
    plt = pyplot()
    return plt.figure(figsize=(width_px / DPI, height_px / DPI), dpi=DPI)


def text_box(text, renderer, drawn: bool = False):
    """The drawn box of a Text or an Annotation's text alone (without its arrow).
    ``drawn``: the figure was drawn since the annotation last moved, so its place is
    current (placing it again would mark the figure stale: :func:`save` redraws it)."""
    from matplotlib.text import Annotation, Text

    if isinstance(text, Annotation) and not drawn:
        text.update_positions(renderer)
    return Text.get_window_extent(text, renderer)


def _line_points(line, renderer, step_px: float = 2.0):
    """The display points of a drawn line, at most ``step_px`` apart (its
    segments filled in), as an (n, 2) array: what a label must not cover."""
    import numpy as np

    xy = line.get_transform().transform(np.column_stack(line.get_data()).astype(float))
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    if len(xy) < 2:
        return xy
    a, b = xy[:-1], xy[1:]
    n = np.maximum(np.ceil(np.hypot(*(b - a).T) / step_px).astype(int), 1)  # pieces per segment
    seg = np.repeat(np.arange(len(n)), n)
    k = np.arange(1, len(seg) + 1) - np.repeat(np.cumsum(n) - n, n)  # 1..n within each segment
    # linspace(0, 1, n + 1)[1:], bit for bit: k * (1 / n), the end exactly 1
    s = np.where(k == n[seg], 1.0, k * (1.0 / n[seg]))[:, None]
    return np.concatenate([xy[:1], a[seg] + s * (b - a)[seg]])


def place_labels(ax, labels, obstacles=(), pad_px: float = 2.0, lines=(), drawn: bool = False) -> list:
    """Annotate ``ax`` with labels that overlap neither each other nor ``obstacles``.

    ``labels``: dicts with ``xy`` (data coordinates of the point labelled),
    ``text``, optional ``offset`` (points, default (4, 4)) and any
    ``Axes.annotate`` keyword (fontsize, ha, colour...).  Each label, taken
    in order of its point's height, tries its offset (and its mirror image
    left-right), then the same moved down and up by one, two, ... label
    heights, and keeps the first place whose box (as the renderer draws it,
    :func:`text_box`) meets no box placed before, no labelled point, no
    obstacle (artists with a window extent, e.g. the legend), no point of
    the curves in ``lines`` (Line2D: a label stays off the curve) and stays
    inside the axes; a label moved off its point gets a thin leader line to
    it.  A label with no free place keeps its first place and is recorded on
    the figure (``fig._unplaced_labels``): :func:`save` reports it.  Call on
    the final layout; ``drawn``: the caller has drawn it since (a draw is a
    quarter of a second on a large figure; labels placed on another axes
    move no axes once the layout engine is off).  Returns the annotations.
    """
    import numpy as np

    fig = ax.figure
    if not drawn:
        fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = [o.get_window_extent(renderer) for o in obstacles]
    pieces = [_line_points(ln, renderer) for ln in lines]
    curve = np.concatenate(pieces) if pieces else np.zeros((0, 2))
    # the labelled points themselves (their markers): no label covers one
    from matplotlib.transforms import Bbox

    for spec in labels:
        x, y = ax.transData.transform(spec["xy"])
        taken.append(Bbox.from_extents(x - 3, y - 3, x + 3, y + 3))
    to_pt = 72.0 / fig.dpi
    flip = {"left": "right", "right": "left", "center": "center"}
    order = sorted(range(len(labels)), key=lambda k: ax.transData.transform(labels[k]["xy"])[1])
    out = [None] * len(labels)

    def on_curve(box) -> bool:
        b = box.padded(pad_px / 2)
        return bool(len(curve)) and bool(
            np.any((curve[:, 0] >= b.x0) & (curve[:, 0] <= b.x1) & (curve[:, 1] >= b.y0) & (curve[:, 1] <= b.y1))
        )

    for k in order:
        spec = dict(labels[k])
        xy, text = spec.pop("xy"), spec.pop("text")
        dx, dy = spec.pop("offset", (4, 4))
        ha = spec.pop("ha", "left")
        spec.setdefault("fontsize", 8)
        t = ax.annotate(
            text,
            xy,
            xytext=(dx, dy),
            textcoords="offset points",
            ha=ha,
            arrowprops=dict(arrowstyle="-", lw=0.5, color="#888888", shrinkA=0, shrinkB=2),
            annotation_clip=False,
            **spec,
        )
        step = (text_box(t, renderer).height + pad_px) * to_pt
        chosen = None
        for n in range(0, 61):
            shift = 0 if n == 0 else (-1) ** n * ((n + 1) // 2) * step
            for side in (1, -1):
                t.xyann = (side * dx, dy + shift)
                t.set_ha(ha if side == 1 else flip[ha])
                box = text_box(t, renderer)
                inside = box.y0 >= frame.y0 and box.y1 <= frame.y1 and box.x0 >= frame.x0 and box.x1 <= frame.x1
                if inside and not any(box.padded(pad_px / 2).overlaps(b) for b in taken) and not on_curve(box):
                    chosen = shift
                    break
            if chosen is not None:
                break
        if chosen is None:  # nowhere free: keep the first place, and say so
            t.xyann = (dx, dy)
            t.set_ha(ha)
            box = text_box(t, renderer)
            fig._unplaced_labels = getattr(fig, "_unplaced_labels", []) + [str(text)]
        t.arrow_patch.set_visible(bool(chosen))
        taken.append(box)
        out[k] = t
    return out
