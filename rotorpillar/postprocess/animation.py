"""Animations of a transient: the pillar deformed by its modal coordinates,
the rotor's orbit at the top, time and speed on screen.

What deforms the tube (its 3D mode shapes times the run's modal coordinates,
or its tip displacement times one shape), the frames' times (uniform or
time-warped) and the deflection's factor come from
rotorpillar.postprocess.animation_frames; this module draws and writes them.
The ground motion moves the whole tube at true scale; the elastic deflection is exaggerated by one factor and the
rotor's motion about the pillar top (drawn on its shaft) by its own, so the
rotor stays within a few tube radii of the top; both are shown on screen.
A run-up's frames can be time-warped: most of them in the passage through
resonance, said on every frame.  A warning can be burnt into every frame
(the paper's pulse is not an earthquake).

A frame is the 3D view (pyvista, off screen) beside a matplotlib panel: the
rotor's orbit relative to the pillar top (mm, the trail since the previous
frame over the whole path in grey) and Omega(t) and the tip deflection with
a cursor.  Frames sample the run in time (uniformly, or time-warped): a
stroboscope, so the pillar's vibration at the rotor speed aliases; the orbit
trail is drawn from every stored sample and does not.

MP4 (H.264 through imageio-ffmpeg) by default, GIF (Pillow) when ffmpeg is
not available.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..provenance import atomic_path
from ..records import Record
from .animation_frames import (
    MAX_FRAMES,
    PillarMotion,
    elastic_field,
    exaggeration,
    frame_times,
    interpolate,
    pillar_motion,
    rotor_orbit,
)
from .geometry import ModeSet
from .modeshapes import nice_factor
from .offscreen import pyvista
from .readers import Simulation

#: Subdivisions of the quadratic faces in an animation (see inputs.SUBDIVISION).
ANIMATION_SUBDIVISION = 1
#: Nodes around the tube an animation draws (at least; ModeSet.fewer_around): the tube is
#: some 50 px wide in the 400 x 560 view and the frames show its bending (n = 1) modes,
#: whose sections move rigidly; the paper's 128 x 20 mesh has 256 nodes around, and a
#: frame's render time grows with its triangles (bench/bench_render.py: 43,000 of them
#: cost 0.19 s a frame, 5,000 0.05 s).
ANIMATION_AROUND = 48
FPS = 20
VIEW_SIZE = (400, 560)  # 3D view, width x height (px)
PANEL_SIZE = (480, 560)  # chart panel; 880 x 560 together, multiples of 16


class AnimationResult(Record):
    """What an animation shows and what it cost."""

    path: Path
    """the MP4 (or GIF) written"""
    frames: int
    """frames in it (-)"""
    fps: int
    """frames per second of playback (1/s)"""
    factor: float
    """exaggeration of the pillar's elastic deflection (-)"""
    poster: Path | None
    """PNG of the frame of largest deflection"""
    source: str
    """what deforms the tube (modal coordinates, or tip_x times a shape)"""
    writer: str
    """the encoder used"""
    seconds: float
    """wall-clock time to render and encode (s)"""
    notes: tuple[str, ...] = ()
    """the notes shown on screen"""
    orbit_factor: float = 1.0
    """exaggeration of the rotor's motion about the pillar top (-)"""
    focus: tuple[float, float] | None = None
    """the window the frames were time-warped into (s), or None (uniform)"""
    frames_in_focus: int = 0
    """frames inside that window (-)"""


def _decimate(idx_lo: int, idx_hi: int, most: int) -> slice:
    step = max(1, (idx_hi - idx_lo) // most)
    return slice(idx_lo, idx_hi + 1, step)


class _Panel:
    """The matplotlib half of a frame, redrawn by blitting the moving artists."""

    def __init__(self, sim: Simulation, motion: PillarMotion, size, title: str, tf=None, focus=None):
        from .style import COLOURS, pyplot

        plt = pyplot()
        self.t = motion.t
        # the time axis as the frames run: warped where the frames are dense
        n = len(tf) if tf is not None else 2
        self.u = (lambda x: np.interp(x, tf, np.linspace(0.0, 1.0, n))) if focus is not None else (lambda x: x)
        self.orbit = rotor_orbit(sim)
        w, h = size
        fig = plt.figure(figsize=(w / 100, h / 100), dpi=100, layout="constrained")
        gs = fig.add_gridspec(2, 1, height_ratios=[1.35, 1])
        ax_o, ax_t = fig.add_subplot(gs[0]), fig.add_subplot(gs[1])
        fig.suptitle(title, fontsize=10)
        self.moving = []
        if self.orbit is not None:
            ox, oy = (1e3 * a for a in self.orbit)
            full = _decimate(0, len(ox) - 1, 4000)
            ax_o.plot(ox[full], oy[full], color="#cccccc", lw=0.6)
            r = 1.1 * max(np.abs(ox).max(), np.abs(oy).max(), 1e-9)
            ax_o.set_xlim(-r, r)
            ax_o.set_ylim(-r, r)
            ax_o.set_aspect("equal")
            ax_o.set_xlabel("horizontal X, rotor minus pillar top (mm)")
            ax_o.set_ylabel("vertical Y (mm)")
            ax_o.set_title("rotor orbit relative to the pillar top", fontsize=9)
            (self.trail,) = ax_o.plot([], [], color=COLOURS["drive"], lw=1.0, animated=True)
            (self.dot,) = ax_o.plot([], [], "o", color=COLOURS["unstable"], ms=5, animated=True)
            self.ox, self.oy = ox, oy
            self.moving += [(ax_o, self.trail), (ax_o, self.dot)]
        else:
            ax_o.text(0.5, 0.5, "no rotor_x / rotor_y in this run", ha="center", va="center", transform=ax_o.transAxes)
            ax_o.set_axis_off()
        Om = sim.arrays.Omega
        u = self.u(self.t)
        if Om is not None:
            ax_t.plot(u, Om, color=COLOURS["drive"], lw=1.0)
            ax_t.ticklabel_format(axis="y", useOffset=False, style="plain")
        ax_t.set_xlabel("t (s)")
        if focus is not None:
            ax_t.axvspan(self.u(focus[0]), self.u(focus[1]), color="#E69F00", alpha=0.12, lw=0)
            ticks: list[float] = []
            for x in np.round([self.t[0], focus[0], 0.5 * (focus[0] + focus[1]), focus[1], self.t[-1]], 2):
                if all(abs(self.u(x) - self.u(y)) > 0.08 for y in ticks):
                    ticks.append(float(x))
            ax_t.set_xticks(self.u(np.array(ticks)), [f"{x:g}" for x in ticks])
            ax_t.set_xlabel("t (s), time-warped: the shaded passage stretched")
        ax_t.set_ylabel("Omega (rad/s)", color=COLOURS["drive"])
        ax_d = ax_t.twinx()
        tipdef = 1e3 * (motion.coefficients.sum(axis=1))
        part = _decimate(0, len(self.t) - 1, 6000)
        ax_d.plot(u[part], tipdef[part], color=COLOURS["numeric"], lw=0.5, alpha=0.8)
        ax_d.set_ylabel("elastic tip deflection (mm)", color=COLOURS["numeric"])
        ax_d.grid(False)
        self.cursor = ax_t.axvline(u[0], color="black", lw=1.0, animated=True)
        self.moving.append((ax_t, self.cursor))
        for a in fig.axes:  # 9.5 pt at 100 dpi: 13 px, legible in the video
            a.tick_params(labelsize=9.5)
            a.xaxis.label.set_fontsize(10)
            a.yaxis.label.set_fontsize(10)
        self.fig = fig
        fig.canvas.draw()
        self.background = fig.canvas.copy_from_bbox(fig.bbox)

    def frame(self, tf: float, t_prev: float) -> np.ndarray:
        canvas = self.fig.canvas
        canvas.restore_region(self.background)
        if self.orbit is not None:
            lo = int(np.searchsorted(self.t, t_prev))
            hi = max(lo, int(np.searchsorted(self.t, tf, side="right")) - 1)
            s = _decimate(lo, hi, 800)
            self.trail.set_data(self.ox[s], self.oy[s])
            self.dot.set_data([np.interp(tf, self.t, self.ox)], [np.interp(tf, self.t, self.oy)])
        self.cursor.set_xdata([self.u(tf)] * 2)
        for ax, artist in self.moving:
            ax.draw_artist(artist)
        canvas.blit(self.fig.bbox)
        return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()

    def close(self):
        from .style import pyplot

        pyplot().close(self.fig)


def have_ffmpeg() -> bool:
    """Is imageio-ffmpeg's ffmpeg binary available?"""
    try:
        import imageio_ffmpeg

        return bool(imageio_ffmpeg.get_ffmpeg_exe())
    except (ImportError, RuntimeError):
        return False


def _writer(path: Path, fps: int):
    """An imageio writer for MP4 (H.264, yuv420p: what browsers play)."""
    import imageio.v2 as iio

    return iio.get_writer(
        str(path),
        format="FFMPEG",
        fps=fps,
        codec="libx264",
        quality=6,
        pixelformat="yuv420p",
        macro_block_size=16,
        ffmpeg_log_level="error",
        # x264's veryfast preset: half the encoder's CPU time of its default (medium) for a
        # file 4 % larger at the same quality factor (the paper's run-up, 180 frames)
        output_params=["-preset", "veryfast"],
    )


def rest_silhouette(surface, camera):
    """The outline of ``surface`` seen from ``camera`` (VTK's silhouette filter, run once)."""
    pv = pyvista()
    from vtkmodules.vtkFiltersHybrid import vtkPolyDataSilhouette

    outline = vtkPolyDataSilhouette()
    outline.SetInputData(surface if isinstance(surface, pv.PolyData) else surface.extract_surface())
    outline.SetCamera(camera)
    outline.SetEnableFeatureAngle(False)
    outline.Update()
    return pv.wrap(outline.GetOutput())


def _shaft(start, end, radius: float):
    """The rotor's shaft: a line and the tube around it (``pyvista.Line(...).tube(radius)``
    kept as one VTK filter: moving the line's points and updating the filter redraws it,
    instead of a new line, tube and copy each frame)."""
    pv = pyvista()
    from vtkmodules.vtkFiltersCore import vtkTubeFilter

    line = pv.Line(tuple(start), tuple(end))
    tube = vtkTubeFilter()
    tube.SetInputData(line)
    tube.SetRadius(radius)
    tube.SetCapping(True)
    tube.SetNumberOfSides(20)  # pyvista's tube(): 20 sides, capped, radius factor 10
    tube.SetRadiusFactor(10.0)
    tube.Update()
    return line, tube


def animate(
    sim: Simulation,
    modeset: ModeSet,
    path: str | Path,
    title: str = "",
    max_frames: int = MAX_FRAMES,
    fps: int = FPS,
    view_size=VIEW_SIZE,
    panel_size=PANEL_SIZE,
    poster: str | Path | None = None,
    progress: bool = True,
    gif: bool = False,
    focus=None,
    banner: str = "",
) -> AnimationResult:
    """Write the animation of one run to ``path`` (.mp4; .gif if ``gif`` or
    if ffmpeg is missing) and, if asked, a poster PNG at the frame of
    largest deflection.  ``focus`` = (t0, t1): the frames time-warped into
    that window (:func:`frame_times`), said on every frame; ``banner``: a
    warning burnt into every frame (red, at the top of the 3D view)."""
    start = time.perf_counter()
    pv = pyvista()
    path = Path(path)
    # quadratic cells through their nodes only, the outer wall at a picture's resolution
    modeset = modeset.coarser(ANIMATION_SUBDIVISION).fewer_around(ANIMATION_AROUND)
    motion = pillar_motion(sim, modeset)
    ax = modeset.axes
    ex, ea = np.eye(3)[ax.x], np.eye(3)[ax.axial]
    H = modeset.height
    factor = exaggeration(motion, H)
    tf = frame_times(motion.t, max_frames, focus)
    warped = focus is not None and len(tf) >= 10 and not np.allclose(np.diff(tf), tf[1] - tf[0])
    q = interpolate(motion.t, motion.coefficients, tf)
    g = interpolate(motion.t, motion.ground_x, tf)
    omega = sim.arrays.Omega
    Om = interpolate(motion.t, omega, tf) if omega is not None else None
    orbit = rotor_orbit(sim)
    base = np.asarray(modeset.surface.points, dtype=float)
    top = base[np.argmax(base[:, ax.axial])]
    top_centre = np.array(modeset.surface.center) + ea * (top[ax.axial] - modeset.surface.center[ax.axial])
    radius = 0.5 * max(np.ptp(base[:, ax.x]), np.ptp(base[:, ax.y]))
    # colour: the true elastic displacement (mm), one scale for the whole run
    peak = np.array([np.abs(s).max() for s in motion.shapes])
    u_max = 1e3 * float(np.max(np.abs(motion.coefficients) @ peak)) or 1.0

    mesh = modeset.surface.copy(deep=True)
    mesh.point_data["elastic deflection (mm)"] = np.zeros(mesh.n_points)
    hub = top_centre + 1.3 * radius * ea  # the rotor's centre at rest, on its shaft
    rotor = pv.Sphere(radius=0.4 * radius, center=tuple(hub))
    rotor_base = np.asarray(rotor.points, dtype=float)
    # the rotor's orbit about the pillar top: its own factor, to about 1.5 tube radii
    reach = max(float(np.abs(orbit[0]).max()), float(np.abs(orbit[1]).max())) if orbit is not None else 0.0
    orbit_factor = min(factor, nice_factor(1.5 * radius / reach)) if reach > 0 else factor
    shaft_line, shaft = _shaft(top_centre, hub, 0.08 * radius)
    p = pv.Plotter(off_screen=True, window_size=list(view_size))
    # no multisampling: llvmpipe's multisampled frame (pyvista asks for 8 samples) took
    # 2/3 of a frame's CPU time (60 of 90 ms on the paper's run-up); the frames' edges
    # are a pixel sharper, the H.264 encoding smooths them
    p.ren_win.SetMultiSamples(0)
    p.set_background("white")
    p.add_mesh(
        mesh,
        scalars="elastic deflection (mm)",
        cmap="viridis",
        clim=(0.0, u_max),
        smooth_shading=True,
        scalar_bar_args=dict(
            title="",
            vertical=False,
            width=0.5,
            height=0.05,
            position_x=0.45,
            position_y=0.03,
            color="black",
            label_font_size=16,
            fmt="%.3g",
            n_labels=3,
        ),
    )
    # the colour bar's title beside it, never over its ticks
    p.add_text("deflection (mm):", position=(8, 14), font_size=9, color="black")
    p.add_mesh(rotor, color="#D55E00")
    p.add_mesh(shaft.GetOutput(), color="#333333")
    g_lo, g_hi = float(min(g.min(), 0.0)), float(max(g.max(), 0.0))
    ground = pv.Plane(
        center=tuple(np.array(modeset.surface.center) * (1 - ea) + ea * base[:, ax.axial].min()),
        direction=tuple(ea),
        i_size=6 * radius + (g_hi - g_lo),
        j_size=6 * radius + (g_hi - g_lo),
    )
    ground_base = np.asarray(ground.points, dtype=float)
    # opaque and unlit, in the colour the earlier 0.6-opaque #d9c9a8 showed on the white
    # background: nothing lies behind the ground from this camera, and a translucent actor
    # costs every frame a translucent pass in software OpenGL
    p.add_mesh(ground, color="#bdb5a3", lighting=False)
    readout = p.add_text(
        "",
        position=(8, view_size[1] - 44 - 16 * banner.count("\n") - (22 if banner else 0)),
        font_size=10,
        color="black",
    )
    if banner:
        p.add_text(
            banner, position=(8, view_size[1] - 8 - 16 * (banner.count("\n") + 1)), font_size=10, color="#C00000"
        )
    notes = [f"pillar deflection x{factor:g}", f"rotor about the pillar top x{orbit_factor:g}"]
    if np.any(g != 0):
        notes.append("ground motion true scale")
    if warped:
        inside = int(np.sum((tf >= focus[0]) & (tf <= focus[1])))
        notes.append(f"time-warped: {inside} of {len(tf)} frames")
        notes.append(f"  in {focus[0]:.2g} .. {focus[1]:.2g} s (slow motion)")
    if not modeset.source.endswith(".vtu"):
        notes.append("shape: Euler-Bernoulli cantilever (no 3D modes)")
    p.add_text("\n".join(notes), position=(8, 44), font_size=9, color="#333333")
    # fixed camera across the bending plane, framing the whole excursion
    lateral = factor * float(np.max(np.abs(q) @ peak)) + max(abs(g_lo), abs(g_hi)) + 2 * radius + orbit_factor * reach
    centre = np.array(modeset.surface.center) + ex * 0.5 * (g_lo + g_hi)
    across = -np.eye(3)[ax.y]
    d = (
        math.cos(math.radians(8)) * (math.cos(math.radians(20)) * across + math.sin(math.radians(20)) * ex)
        + math.sin(math.radians(8)) * ea
    )
    p.camera.focal_point = tuple(centre)
    p.camera.position = tuple(centre + 4 * H * d)
    p.camera.up = tuple(ea)
    p.camera.view_angle = 30.0
    half = np.full(3, lateral)
    half[ax.axial] = 0.55 * H
    p.reset_camera(bounds=tuple(float(v) for pair in zip(centre - half, centre + half) for v in pair))
    # the undeformed tube's outline from the fixed camera, once, as opaque lines (a live
    # silhouette of an invisible surface re-ran its filter and a translucent pass every frame:
    # a quarter of the frame's time, measured on the paper's run-up)
    p.add_mesh(rest_silhouette(modeset.surface, p.renderer.camera), color="#a0a0a0", line_width=1.0)

    panel = _Panel(sim, motion, panel_size, title, tf, focus if warped else None)
    use_gif = gif or not have_ffmpeg()
    if use_gif:
        path = path.with_suffix(".gif")
    writer: Any = None
    frames_gif: list[Any] = []
    best, best_frame = -1.0, None
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(
            total=len(tf), desc=f"animation {sim.case}", unit="frame", file=sys.stderr, leave=False, mininterval=0.5
        )
    try:
        with atomic_path(path) as tmp:
            if not use_gif:
                writer = _writer(tmp, fps)
            for j, t in enumerate(tf):
                U = elastic_field(q[j], motion.shapes)
                mesh.points = base + factor * U + g[j] * ex
                mesh.point_data["elastic deflection (mm)"] = 1e3 * np.linalg.norm(U, axis=1)
                rel = np.zeros(3)
                if orbit is not None:
                    rel = np.interp(t, motion.t, orbit[0]) * ex + np.interp(t, motion.t, orbit[1]) * ea
                tip = factor * q[j] @ np.array([s[np.argmax(base[:, ax.axial])] @ ex for s in motion.shapes])
                rotor.points = rotor_base + (tip + g[j]) * ex + orbit_factor * rel
                top_now = top_centre + (tip + g[j]) * ex
                shaft_line.points = np.array([top_now, hub + (tip + g[j]) * ex + orbit_factor * rel])
                shaft.Update()
                ground.points = ground_base + g[j] * ex
                text = f"t = {t:7.3f} s" if warped else f"t = {t:7.2f} s"
                if Om is not None:
                    text += f"\nOmega = {Om[j]:7.2f} rad/s"
                if warped and focus[0] <= t <= focus[1]:
                    text += "  (slow motion)"
                readout.SetInput(text)
                p.render()
                view = p.screenshot(return_img=True)
                chart = panel.frame(t, tf[j - 1] if j else t - (tf[1] - tf[0]))
                h = max(view.shape[0], chart.shape[0])
                frame = np.hstack([_pad(view, h), _pad(chart, h)])
                amp = float(np.abs(q[j]).sum())
                if amp > best:
                    best, best_frame = amp, frame
                if use_gif:
                    frames_gif.append(frame[::2, ::2])
                else:
                    writer.append_data(frame)
                if bar:
                    bar.update()
            if use_gif:
                import imageio.v2 as iio

                iio.mimsave(str(tmp), frames_gif, format="GIF", duration=1.0 / fps, loop=0)
            else:
                writer.close()
                writer = None
    finally:
        if writer is not None:
            writer.close()
        if bar:
            bar.close()
        panel.close()
        p.close()
    poster_path = None
    if poster is not None and best_frame is not None:
        import imageio.v2 as iio

        with atomic_path(poster) as tmp:
            iio.imwrite(str(tmp), best_frame, format="PNG")
        poster_path = Path(poster)
    return AnimationResult(
        path,
        len(tf),
        fps,
        factor,
        poster_path,
        motion.source,
        "GIF (Pillow)" if use_gif else "MP4 (H.264, imageio-ffmpeg)",
        time.perf_counter() - start,
        tuple(notes),
        orbit_factor,
        tuple(focus) if warped else None,
        int(np.sum((tf >= focus[0]) & (tf <= focus[1]))) if warped else 0,
    )


def _pad(img: np.ndarray, h: int) -> np.ndarray:
    if img.shape[0] == h:
        return img
    out = np.full((h, img.shape[1], 3), 255, dtype=np.uint8)
    out[: img.shape[0]] = img
    return out
