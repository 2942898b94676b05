"""Mode shapes, rendered off screen: one PNG per mode and a contact sheet.

Each picture shows the tube deformed by the mode (scaled so that its largest
displacement is visible: a tenth of the height for beam modes, a third of the
radius for shell modes), coloured by the displacement magnitude over its
largest value, over the translucent undeformed tube; the label names the
mode's kind and frequency and the scale factor.  The camera looks across the
plane the mode moves in, slightly turned, with the tube axis up.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..provenance import atomic_path
from .inputs import ModeSet, mode_label
from .offscreen import pyvista

#: Largest displacement on screen: a fraction of the height for the modes
#: that move the whole axis (bending, axial), of the radius for those that
#: move the wall about it (ovalling, torsion, ...).
BEAM_TARGET = 0.10
SHELL_TARGET = 0.30
BEAM_KINDS = ("bending", "axial", "sway")
SCALAR = "u / u_max"

MODE_SIZE = (480, 720)        # width, height of one mode's PNG (px)
SHEET_TILE = (300, 450)       # one tile of the contact sheet (px)
SHEET_COLUMNS = 4
SHEET_MODES = 8


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
    kind = str(modeset.modes[i].get("kind", ""))
    target = (BEAM_TARGET * modeset.height if is_beam_mode(kind)
              else SHELL_TARGET * radius_of(modeset))
    return nice_factor(target / u) if u > 0 else 1.0


def view_direction(modeset: ModeSet, u: np.ndarray, elevation_deg: float = 12.0,
                   turn_deg: float = 25.0) -> np.ndarray:
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


def deformed(modeset: ModeSet, u: np.ndarray, factor: float):
    """A copy of the surface moved by ``factor * u``, with |u| / max |u| on it."""
    mesh = modeset.surface.copy(deep=True)
    mesh.points = np.asarray(modeset.surface.points) + factor * u
    mag = np.linalg.norm(u, axis=1)
    mesh.point_data[SCALAR] = mag / mag.max() if mag.max() > 0 else mag
    return mesh


def _add_mode(plotter, modeset: ModeSet, i: int, label: str, font: int, bar: bool) -> None:
    u = modeset.shape(i)
    factor = mode_scale(modeset, i)
    mesh = deformed(modeset, u, factor)
    # The undeformed tube as an outline (silhouette and rims): a translucent
    # surface z-fights with the deformed one near the clamped base.
    plotter.add_mesh(modeset.surface, color="white", opacity=0.0,
                     silhouette=dict(color="#808080", line_width=1.2))
    plotter.add_mesh(modeset.surface.extract_feature_edges(60, boundary_edges=False,
                                                           non_manifold_edges=False,
                                                           manifold_edges=False),
                     color="#808080", line_width=1.2)
    plotter.add_mesh(mesh, scalars=SCALAR, cmap="viridis", clim=(0.0, 1.0),
                     smooth_shading=True, show_scalar_bar=bar,
                     scalar_bar_args=dict(title=SCALAR, vertical=True, height=0.4,
                                          width=0.06, position_x=0.88, position_y=0.05,
                                          title_font_size=font, label_font_size=font - 2,
                                          color="black", fmt="%.1f"))
    plotter.add_text(f"{label}\ndeformation x{factor:g}", position="upper_left",
                     font_size=font, color="black")
    beam = is_beam_mode(modeset.modes[i].get("kind", ""))
    d = view_direction(modeset, u, elevation_deg=12.0 if beam else 50.0)
    centre = np.array(mesh.center)
    plotter.camera.focal_point = tuple(centre)
    plotter.camera.position = tuple(centre + d * 5 * modeset.height)
    plotter.camera.up = tuple(np.eye(3)[modeset.axes.axial])
    plotter.reset_camera()
    plotter.camera.zoom(1.15)


def render_mode(modeset: ModeSet, i: int, path: str | Path, size=MODE_SIZE) -> Path:
    """One PNG of mode i, ``size`` = (width, height) px."""
    pv = pyvista()
    p = pv.Plotter(off_screen=True, window_size=list(size))
    try:
        p.set_background("white")
        _add_mode(p, modeset, i, mode_label(modeset.modes[i], i), font=10, bar=True)
        with atomic_path(path) as tmp:
            p.screenshot(str(tmp))
    finally:
        p.close()
    return Path(path)


def render_contact_sheet(modeset: ModeSet, path: str | Path, count: int = SHEET_MODES,
                         columns: int = SHEET_COLUMNS, tile=SHEET_TILE, title: str = "") -> Path:
    """The first ``count`` modes side by side, one render of a multi-view window."""
    pv = pyvista()
    count = min(count, len(modeset.arrays))
    if count < 1:
        raise ValueError("no mode to draw")
    rows = math.ceil(count / columns)
    columns = math.ceil(count / rows)     # no empty tiles in a 6-mode sheet
    p = pv.Plotter(off_screen=True, shape=(rows, columns), border=True, border_color="#dddddd",
                   window_size=[tile[0] * columns, tile[1] * rows])
    try:
        p.set_background("white")
        for i in range(count):
            p.subplot(i // columns, i % columns)
            m = modeset.modes[i]
            f = m.get("frequency_hz")
            kind = str(m.get("kind", "?"))
            n = m.get("n_circumferential")
            label = f"{i + 1}: {kind}"
            if n is not None and not kind.startswith("bending"):
                label += f" n={n}"
            label += f"\n{f:.3f} Hz" if f is not None else ""
            _add_mode(p, modeset, i, label, font=9, bar=False)
        if title:
            p.subplot(0, 0)
        with atomic_path(path) as tmp:
            p.screenshot(str(tmp))
    finally:
        p.close()
    return Path(path)


def render_modes(modeset: ModeSet, directory: str | Path, prefix: str, count: int = SHEET_MODES,
                 progress=None) -> dict:
    """PNG of each of the first ``count`` modes and the contact sheet.

    Returns {"modes": [paths], "sheet": path}.
    """
    directory = Path(directory)
    count = min(count, len(modeset.arrays))
    paths = []
    for i in range(count):
        paths.append(render_mode(modeset, i, directory / f"{prefix}_mode_{i + 1:02d}.png"))
        if progress:
            progress(i + 1, count)
    sheet = render_contact_sheet(modeset, directory / f"{prefix}_modes_sheet.png", count)
    return {"modes": paths, "sheet": sheet}
