"""pyvista without a display.

VTK 9.7 from PyPI carries an X, an EGL and an OSMesa render window.  With no
X server its default (X) window prints "bad X server connection" and then
falls back to EGL; asking for an off-screen window up front skips the failed
attempt.  Measured on this machine (Debian 12, Mesa llvmpipe, 800x600, an
11k-point tube): EGL 50 ms and OSMesa 63 ms per rendered frame, the same
pixels.  We prefer EGL when libEGL is present and OSMesa otherwise
(``libosmesa6`` is in tools/setup.sh's DEBS, so it always is); a
``VTK_DEFAULT_OPENGL_WINDOW`` already set by the user wins.
"""

from __future__ import annotations

import ctypes.util
import os

_WINDOWS = {"egl": "vtkEGLRenderWindow", "osmesa": "vtkOSOpenGLRenderWindow"}


def choose_window(display: str | None, have_egl: bool) -> str | None:
    """The VTK render window class to request, or None to keep VTK's default.

    >>> choose_window(":0", True) is None
    True
    >>> choose_window(None, True), choose_window(None, False)
    ('vtkEGLRenderWindow', 'vtkOSOpenGLRenderWindow')
    """
    if display:
        return None
    return _WINDOWS["egl"] if have_egl else _WINDOWS["osmesa"]


def configure() -> None:
    """Set the environment for off-screen rendering before VTK is imported."""
    os.environ.setdefault("PYVISTA_OFF_SCREEN", "true")
    if "VTK_DEFAULT_OPENGL_WINDOW" not in os.environ:
        # Even with a DISPLAY we render off screen; only an unset DISPLAY
        # makes the X window fail noisily.
        window = choose_window(os.environ.get("DISPLAY"),
                               ctypes.util.find_library("EGL") is not None)
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
