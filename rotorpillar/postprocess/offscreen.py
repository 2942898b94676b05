"""pyvista without a display.

VTK 9.7 from PyPI carries an X, an EGL and an OSMesa render window.  With no
X server its default (X) window prints "bad X server connection" and then
falls back to EGL; asking for an off-screen window up front skips the failed
attempt.  Both off-screen windows work here (Debian 12, Mesa llvmpipe) and
give the same pixels; measured side by side by ``bench/bench_render.py``
(2 shared cores): a 480x720 mode picture 0.29 s with OSMesa against 0.41 s
with EGL (creating the window dominates), an 880x560 animation frame about
0.1 s with either.  We take OSMesa, whose library ``libosmesa6`` is in
tools/setup.sh's DEBS, and EGL only where OSMesa is missing; a
``VTK_DEFAULT_OPENGL_WINDOW`` already set by the user wins.
"""

from __future__ import annotations

import ctypes.util
import os

_WINDOWS = {"egl": "vtkEGLRenderWindow", "osmesa": "vtkOSOpenGLRenderWindow"}


def choose_window(have_osmesa: bool, have_egl: bool) -> str | None:
    """The VTK render window class to request, or None to keep VTK's default.

    >>> choose_window(True, True), choose_window(False, True), choose_window(False, False)
    ('vtkOSOpenGLRenderWindow', 'vtkEGLRenderWindow', None)
    """
    if have_osmesa:
        return _WINDOWS["osmesa"]
    if have_egl:
        return _WINDOWS["egl"]
    return None


def configure() -> None:
    """Set the environment for off-screen rendering before VTK is imported."""
    os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
    if "VTK_DEFAULT_OPENGL_WINDOW" not in os.environ:
        window = choose_window(
            ctypes.util.find_library("OSMesa") is not None, ctypes.util.find_library("EGL") is not None
        )
        if window:
            os.environ["VTK_DEFAULT_OPENGL_WINDOW"] = window


def pyvista():
    """The pyvista module, configured to render off screen."""
    configure()
    import pyvista as pv

    pv.OFF_SCREEN = True
    return pv


def render_window_class() -> str:
    """Name of the render window VTK actually creates here (for the report)."""
    pv = pyvista()
    p = pv.Plotter(off_screen=True, window_size=(8, 8))
    try:
        return type(p.ren_win).__name__
    finally:
        p.close()
