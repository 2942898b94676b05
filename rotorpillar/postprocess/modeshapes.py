"""Mode shapes, rendered off screen: one PNG per mode and a contact sheet.

Each picture shows the tube deformed by the mode (scaled so that its largest
displacement is visible: a tenth of the height for beam modes, a third of the
radius for shell modes), coloured by the displacement magnitude over its
largest value, over the outline of the undeformed tube; the label names the
mode's kind and frequency and the scale factor.  The camera looks across the
plane the mode moves in, slightly turned, with the tube axis up, in parallel
projection, framed so that the tube fills its picture's height (or width)
below the label.  A mode that changes the shape of the cross-section (an
ovalling mode, n >= 2 waves around) gets a second view beside the first,
along the tube's axis: its deformed cross-sections at a few heights over the
undeformed circles, so that its n lobes can be counted.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..provenance import atomic_path
from .directions import MODEL_AXIS, mode_label
from .geometry import Mode, ModeSet
from .offscreen import pyvista
from .style import tag_png

#: Largest displacement on screen: a fraction of the height for the modes
#: that move the whole axis (bending, axial), of the radius for those that
#: move the wall about it (ovalling, torsion, ...).
BEAM_TARGET = 0.10
SHELL_TARGET = 0.30
BEAM_KINDS = ("bending", "axial", "sway")
SCALAR = "u / u_max"
#: The colour bar's title, drawn above it (VTK's own title overprints the top tick).
BAR_TITLE = "u / u_max"
#: Pixels of a font's em per point of VTK's font size, measured here (a capital
#: is 14, 15, 17 px tall at 9, 10, 11 points: em ~ 2.1 px per point); 2 is
#: what the pictures' legibility records (style.tag_png) count.
PX_PER_POINT = 2.0
#: Font sizes (points): a picture of one mode (18 px), a tile of the contact
#: sheet (14 px; the sheet is shown at 1060/1200 of its size: 12 px).
MODE_FONT, SHEET_FONT = 9, 7

MODE_SIZE = (480, 720)  # width, height of one mode's PNG (px)
#: Points around the tube a mode picture draws (at least; ModeSet.fewer_around): the tube
#: is some 150 px wide in it, and an ovalling mode of n waves needs a few dozen points
#: a wave; the paper's 128 x 20 mesh, its quadratic faces subdivided twice, has 512.
#: A picture's render time grows with its triangles (172,000 on that mesh: 1 s a view).
MODE_AROUND = 128
SHEET_TILE = (300, 450)  # one tile of the contact sheet (px)
SHEET_COLUMNS = 4
SHEET_MODES = 8
#: Width of the side view : the sections' view, in a tile of an ovalling mode.
SPLIT = (2, 3)
#: Cross-sections drawn in the view along the axis.
SECTIONS = 3
#: Height of a line of text per point of font size (px).
LINE = 1.95


def nice_factor(x: float) -> float:
    """Round a scale factor to the nearest (in ratio) 1, 2 or 5 times a power of ten.

    >>> [nice_factor(v) for v in (0.37, 1.0, 1.9, 7.9, 2400.0)]
    [0.5, 1.0, 2.0, 10.0, 2000.0]
    """
    if not (x > 0 and math.isfinite(x)):
        return 1.0
    p = 10.0 ** math.floor(math.log10(x))
    best = min((1.0, 2.0, 5.0, 10.0), key=lambda m: abs(math.log(x / (m * p))))
    return float(f"{best * p:.12g}")


def radius_of(modeset: ModeSet) -> float:
    """Outer radius of the tube (m): half its largest lateral extent."""
    b = modeset.surface.bounds
    ext = [b[1] - b[0], b[3] - b[2], b[5] - b[4]]
    return 0.5 * max(ext[modeset.axes.x], ext[modeset.axes.y])


def is_beam_mode(kind: str) -> bool:
    """Does a mode of this kind move the tube's axis (rather than its wall)?"""
    return str(kind).startswith(BEAM_KINDS)


def mode_scale(modeset: ModeSet, i: int) -> float:
    """The factor that brings mode i's largest displacement to its target size."""
    u = np.linalg.norm(modeset.shape(i), axis=1).max()
    kind = modeset.modes[i].kind
    target = BEAM_TARGET * modeset.height if is_beam_mode(kind) else SHELL_TARGET * radius_of(modeset)
    return nice_factor(target / u) if u > 0 else 1.0


def view_direction(modeset: ModeSet, u: np.ndarray, elevation_deg: float = 12.0, turn_deg: float = 25.0) -> np.ndarray:
    """Unit vector from the focal point to the camera: across the lateral
    direction the mode moves most in, turned by ``turn_deg``, raised by
    ``elevation_deg``."""
    ax = modeset.axes
    ex, ey, ea = np.eye(3)[ax.x], np.eye(3)[ax.y], np.eye(3)[ax.axial]
    moves_x = np.abs(u[:, ax.x]).sum() >= np.abs(u[:, ax.y]).sum()
    motion, across = (ex, -ey) if moves_x else (ey, ex)
    t, e = math.radians(turn_deg), math.radians(elevation_deg)
    d = math.cos(e) * (math.cos(t) * across + math.sin(t) * motion) + math.sin(e) * ea
    return d / np.linalg.norm(d)


def frame(
    camera, points: np.ndarray, direction: np.ndarray, up: np.ndarray, aspect: float, free=(0.03, 0.03, 0.03, 0.12)
) -> float:
    """Point a parallel-projection camera along ``-direction`` so that ``points``
    fill the view but for the ``free`` fractions (left, right, bottom, top)
    kept for the label and the colour bar; ``aspect`` = view width / height.
    Returns the parallel scale (half the view's height, m).

    >>> from types import SimpleNamespace
    >>> cam = SimpleNamespace()
    >>> pts = np.array([[0., 0, 0], [0, 0, 10], [1, 0, 0]])
    >>> frame(cam, pts, np.array([0., -1, 0]), np.array([0., 0, 1]), 0.5, (0, 0, 0, 0.5))
    10.0
    """
    d = direction / np.linalg.norm(direction)
    u_s = up - (up @ d) * d
    u_s = u_s / np.linalg.norm(u_s)
    r_s = np.cross(u_s, d)  # screen right for a camera looking along -d
    a, b = points @ r_s, points @ u_s
    left, right, bottom, top = free
    half = max((np.ptp(b) or 1e-9) / (2 * (1 - bottom - top)), (np.ptp(a) or 1e-9) / (2 * aspect * (1 - left - right)))
    # the points' centre goes to the centre of the free part of the view
    a_c = 0.5 * (a.min() + a.max()) - ((left + 1 - right) / 2 - 0.5) * 2 * half * aspect
    b_c = 0.5 * (b.min() + b.max()) - ((bottom + 1 - top) / 2 - 0.5) * 2 * half
    focal = a_c * r_s + b_c * u_s + float(np.mean(points @ d)) * d
    reach = 10 * float(np.ptp(points, axis=0).max() or 1.0)
    camera.parallel_projection = True
    camera.focal_point = tuple(focal)
    camera.position = tuple(focal + reach * d)
    camera.up = tuple(u_s)
    camera.parallel_scale = float(half)
    return float(half)


def has_sections(mode: Mode) -> bool:
    """Does this mode change the shape of the cross-section (n >= 2 waves around)?

    >>> from rotorpillar.postprocess.geometry import ModeLabel
    >>> has_sections(ModeLabel("ovalling", 3)), has_sections(ModeLabel("bending_x"))
    (True, False)
    """
    kind = mode.kind
    n = mode.n_circumferential
    return kind == "ovalling" or (not is_beam_mode(kind) and isinstance(n, int) and n >= 2)


def section_levels(modeset: ModeSet, u: np.ndarray, count: int = SECTIONS) -> list[float]:
    """Heights (axial coordinate, m) of the cross-sections to draw, top first:
    where the section deforms most, then those of 95, 75, 50, 25 % of the
    height that deform most, each at least an eighth of the height from the
    others; a section deforming less than a tenth of the most is left out."""
    ax = modeset.axes
    z = np.asarray(modeset.surface.points)[:, ax.axial].astype(float)
    z0, H = float(z.min()), float(np.ptp(z))
    lateral = np.linalg.norm(u[:, [ax.x, ax.y]], axis=1)
    levels, where = np.unique(np.round((z - z0) / H, 6), return_inverse=True)
    amp = np.zeros(len(levels))
    np.maximum.at(amp, where.ravel(), lateral)
    levels = z0 + levels * H

    def amplitude(h):
        return float(np.interp(h, levels, amp))

    peak = float(np.clip(levels[int(np.argmax(amp))], z0 + 0.02 * H, z0 + 0.98 * H))
    chosen = [peak]
    for h in sorted((z0 + f * H for f in (0.95, 0.75, 0.5, 0.25)), key=lambda h: -amplitude(h)):
        if len(chosen) < count and amplitude(h) >= 0.1 * amp.max() and all(abs(h - c) > H / 8 for c in chosen):
            chosen.append(float(h))
    return sorted(chosen, reverse=True)


def deformed(modeset: ModeSet, u: np.ndarray, factor: float):
    """A copy of the surface moved by ``factor * u``, with |u| / max |u| on it."""
    mesh = modeset.surface.copy(deep=True)
    mesh.points = np.asarray(modeset.surface.points) + factor * u
    mag = np.linalg.norm(u, axis=1)
    mesh.point_data[SCALAR] = mag / mag.max() if mag.max() > 0 else mag
    return mesh


def _bar_args(font: int, horizontal: bool = False) -> dict:
    where = (
        dict(vertical=False, height=0.05, width=0.45, position_x=0.52, position_y=0.02)
        if horizontal
        else dict(vertical=True, height=0.4, width=0.06, position_x=0.88, position_y=0.05)
    )
    # a scalar bar's labels come out at ~1 px per point (add_text's ~2): twice the size
    return dict(title="", label_font_size=2 * font, color="black", fmt="%.1f", n_labels=2 if horizontal else 3, **where)


def _bar_title(plotter, font: int, horizontal: bool = False) -> None:
    """The colour bar's title, clear of its ticks: above a vertical bar,
    left of a horizontal one."""
    if horizontal:
        plotter.add_text(BAR_TITLE, position=(0.03, 0.025), viewport=True, font_size=font, color="black")
    else:
        plotter.add_text(BAR_TITLE, position=(0.70, 0.49), viewport=True, font_size=font, color="black")


def _triad(plotter) -> None:
    """The axes, named as the paper names them: X horizontal in the rotor's
    plane, Z along the shaft, Y up (bending in X and in Z look alike without it)."""
    names = {i: MODEL_AXIS["xyz"[i]] for i in range(3)}
    plotter.add_axes(
        xlabel=names[0],
        ylabel=names[1],
        zlabel=names[2],
        line_width=3,
        viewport=(0.0, 0.0, 0.3, 0.2),
        label_size=(0.5, 0.25),
    )


def _label(plotter, text: str, font: int, view_height: float) -> None:
    """``text`` at the view's upper left, at ``font`` points whatever the view's size
    (a corner annotation would scale with the view: a narrow view got a tiny label)."""
    lines = text.count("\n") + 1
    y = 1 - (lines * LINE * font + 6) / view_height
    plotter.add_text(text, position=(0.03, y), viewport=True, font_size=font, color="black")


def _add_mode(
    plotter,
    modeset: ModeSet,
    i: int,
    label: str,
    font: int,
    bar: bool,
    aspect: float,
    free,
    view_height: float,
    triad: bool = True,
) -> None:
    """The deformed tube over the undeformed one's outline, in the current view."""
    u = modeset.shape(i)
    factor = mode_scale(modeset, i)
    mesh = deformed(modeset, u, factor)
    # The undeformed tube as an outline (silhouette and rims): a translucent
    # surface z-fights with the deformed one near the clamped base.
    plotter.add_mesh(modeset.surface, color="white", opacity=0.0, silhouette=dict(color="#808080", line_width=1.2))
    plotter.add_mesh(
        modeset.surface.extract_feature_edges(60, boundary_edges=False, non_manifold_edges=False, manifold_edges=False),
        color="#808080",
        line_width=1.2,
    )
    plotter.add_mesh(
        mesh,
        scalars=SCALAR,
        cmap="viridis",
        clim=(0.0, 1.0),
        smooth_shading=True,
        show_scalar_bar=bar,
        scalar_bar_args=_bar_args(font),
    )
    if bar:
        _bar_title(plotter, font)
    if triad:
        _triad(plotter)
    _label(plotter, f"{label}\ndeformation x{factor:g}", font, view_height)
    beam = is_beam_mode(modeset.modes[i].kind)
    d = view_direction(modeset, u, elevation_deg=12.0 if beam else 20.0)
    pts = np.concatenate([np.asarray(mesh.points), np.asarray(modeset.surface.points)])
    # the renderer's camera, not plotter.camera: that getter first places a default view
    # (bounds of every actor, a camera reset), ~0.3 s a tile, which frame() then replaces
    frame(plotter.renderer.camera, pts, d, np.eye(3)[modeset.axes.axial], aspect, free)
    plotter.renderer.ResetCameraClippingRange()


def _add_sections(
    plotter, modeset: ModeSet, i: int, font: int, aspect: float, free, bar: bool, view_height: float
) -> None:
    """Mode i's cross-sections seen along the axis (top down), stacked top first."""
    ax = modeset.axes
    ex, ey, ea = np.eye(3)[ax.x], np.eye(3)[ax.y], np.eye(3)[ax.axial]
    u = modeset.shape(i)
    factor = mode_scale(modeset, i)
    peak = np.linalg.norm(u, axis=1).max() or 1.0
    R = radius_of(modeset)
    lo = np.asarray(modeset.surface.points)[:, ax.axial].min()
    step = 3.3 * R
    anchors, texts, every = [], [], []
    for k, z in enumerate(section_levels(modeset, u)):
        cut = modeset.surface.slice(normal=tuple(ea), origin=tuple(ea * z))
        if cut.n_points == 0:
            continue
        # the outer wall's ring, as one polyline
        q = np.asarray(cut.points)
        r = np.hypot(q[:, ax.x], q[:, ax.y])
        cut = (
            cut.extract_points(r > 0.5 * (r.min() + r.max()) - 1e-12 * R, adjacent_cells=False)
            .extract_surface(algorithm=None)
            .strip()
        )
        p = np.asarray(cut.points)
        w = np.asarray(cut.point_data[modeset.arrays[i]], dtype=float)
        shift = -k * step * ey
        flat = p[:, [ax.x]] * ex + p[:, [ax.y]] * ey + shift
        moved = flat + factor * (w[:, [ax.x]] * ex + w[:, [ax.y]] * ey)
        rest, ring = cut.copy(deep=True), cut.copy(deep=True)
        rest.points, ring.points = flat, moved
        ring.point_data[SCALAR] = np.linalg.norm(w, axis=1) / peak
        # wide GL lines break up on the software renderer: lines drawn as tubes
        plotter.add_mesh(rest, color="#909090", line_width=2, render_lines_as_tubes=True, lighting=False)
        plotter.add_mesh(
            ring,
            scalars=SCALAR,
            cmap="viridis",
            clim=(0.0, 1.0),
            line_width=4,
            render_lines_as_tubes=True,
            lighting=False,
            show_scalar_bar=bar and k == 0,
            scalar_bar_args=_bar_args(font, True),
        )
        if bar and k == 0:
            _bar_title(plotter, font, True)
        anchors.append(shift + 1.45 * R * ey - 1.3 * R * ex)
        texts.append(f"z = {z - lo:.1f} m")
        every += [flat, moved, anchors[-1][None, :]]
    if not anchors:
        return
    # a point label's font is ~1 px per point, not add_text's ~2: twice the size
    plotter.add_point_labels(
        np.array(anchors),
        texts,
        font_size=2 * font,
        text_color="black",
        shape=None,
        show_points=False,
        always_visible=True,
    )
    _label(plotter, "sections, from above", font, view_height)
    # the renderer's camera, not plotter.camera: that getter first places a default view
    # (bounds of every actor, a camera reset), ~0.3 s a tile, which frame() then replaces
    frame(plotter.renderer.camera, np.concatenate(every), ea, ey, aspect, free)
    plotter.renderer.ResetCameraClippingRange()


def _free(font: int, tile_height: int, lines: int, bar_right: bool) -> tuple:
    """Fractions of a view kept free (left, right, bottom, top): the label's
    lines at the top, the vertical colour bar at the right."""
    top = min(0.3, (lines * LINE * font + 10) / tile_height)
    return (0.03, 0.16 if bar_right else 0.03, 0.02, top)


def render_mode(modeset: ModeSet, i: int, path: str | Path, size=MODE_SIZE) -> Path:
    """One PNG of mode i, ``size`` = (width, height) px; an ovalling mode beside
    its cross-sections."""
    pv = pyvista()
    split = has_sections(modeset.modes[i])
    p = pv.Plotter(
        off_screen=True,
        window_size=list(size),
        shape=(1, 2 if split else 1),
        col_weights=list(SPLIT) if split else None,
        border=False,
    )
    try:
        p.set_background("white")
        w = size[0] * SPLIT[0] / sum(SPLIT) if split else size[0]
        label = mode_label(modeset.modes[i], i, lines=True)
        lines = label.count("\n") + 2
        font = MODE_FONT
        p.subplot(0, 0)
        _add_mode(
            p,
            modeset,
            i,
            label,
            font=font,
            bar=not split,
            aspect=w / size[1],
            free=_free(font, size[1], lines, not split),
            view_height=size[1],
        )
        if split:
            p.subplot(0, 1)
            _add_sections(
                p,
                modeset,
                i,
                font,
                (size[0] - w) / size[1],
                free=(0.03, 0.03, 0.1, _free(font, size[1], 2, False)[3]),
                bar=True,
                view_height=size[1],
            )
        with atomic_path(path) as tmp:
            p.screenshot(str(tmp))
        tag_png(path, PX_PER_POINT * font, size[0])
    finally:
        p.close()
    return Path(path)


def _sheet_label(m: Mode, i: int) -> str:
    r"""A tile's label: number and family, direction or waves around, frequency.

    >>> from rotorpillar.postprocess.geometry import ModeLabel
    >>> _sheet_label(ModeLabel("bending_y", n_axial=0, frequency_hz=4.0769), 1)
    '2: 1st bending\nalong the shaft (Z)\n4.077 Hz'
    """
    return mode_label(m, i, lines=True).removeprefix("mode ")


def render_contact_sheet(
    modeset: ModeSet,
    path: str | Path,
    count: int = SHEET_MODES,
    columns: int = SHEET_COLUMNS,
    tile=SHEET_TILE,
) -> Path:
    """The first ``count`` modes side by side, one render of a multi-view window;
    an ovalling mode's tile holds its side view and its cross-sections."""
    pv = pyvista()
    count = min(count, len(modeset.arrays))
    if count < 1:
        raise ValueError("no mode to draw")
    rows = math.ceil(count / columns)
    columns = math.ceil(count / rows)  # no empty tiles in a 6-mode sheet
    # Two views per tile; a tile without sections merges its two into one.
    split = [has_sections(modeset.modes[i]) for i in range(count)]
    groups = [
        (i // columns, np.s_[2 * (i % columns) : 2 * (i % columns) + 2])
        for i in range(rows * columns)
        if i >= count or not split[i]
    ]
    p = pv.Plotter(
        off_screen=True,
        shape=(rows, 2 * columns),
        groups=groups or None,
        col_weights=list(SPLIT) * columns,
        border=True,
        border_color="#dddddd",
        window_size=[tile[0] * columns, tile[1] * rows],
    )
    try:
        p.set_background("white")
        w_side = tile[0] * SPLIT[0] / sum(SPLIT)
        for i in range(count):
            r, c = i // columns, 2 * (i % columns)
            p.subplot(r, c)
            label = _sheet_label(modeset.modes[i], i)
            free = _free(SHEET_FONT, tile[1], label.count("\n") + 2, False)
            _add_mode(
                p,
                modeset,
                i,
                label,
                font=SHEET_FONT,
                bar=False,
                aspect=(w_side if split[i] else tile[0]) / tile[1],
                free=free,
                view_height=tile[1],
                triad=not split[i],
            )
            if split[i]:
                p.subplot(r, c + 1)
                _add_sections(
                    p,
                    modeset,
                    i,
                    SHEET_FONT,
                    (tile[0] - w_side) / tile[1],
                    free=(0.03, 0.03, 0.03, _free(SHEET_FONT, tile[1], 2, False)[3]),
                    bar=False,
                    view_height=tile[1],
                )
        with atomic_path(path) as tmp:
            p.screenshot(str(tmp))
        tag_png(path, PX_PER_POINT * SHEET_FONT, tile[0] * columns)
    finally:
        p.close()
    return Path(path)


@dataclass(frozen=True)
class ModePictures:
    """The pictures :func:`render_modes` drew of one set of modes."""

    modes: list[Path]
    """one PNG per mode, the first mode first"""
    sheet: Path
    """the contact sheet of all of them (PNG)"""


def render_modes(
    modeset: ModeSet, directory: str | Path, prefix: str, count: int = SHEET_MODES, progress=None
) -> ModePictures:
    """PNG of each of the first ``count`` modes and the contact sheet."""
    directory = Path(directory)
    count = min(count, len(modeset.arrays))
    modeset = modeset.fewer_around(MODE_AROUND)
    paths = []
    for i in range(count):
        paths.append(render_mode(modeset, i, directory / f"{prefix}_mode_{i + 1:02d}.png"))
        if progress:
            progress(i + 1, count)
    sheet = render_contact_sheet(modeset, directory / f"{prefix}_modes_sheet.png", count)
    return ModePictures(paths, sheet)
