"""What the user takes away: renders, animations, charts and the HTML report.

The only package that imports pyvista or matplotlib, and only inside the
functions that need them, so ``import rotorpillar`` stays light.  Everything
here reads the results other commands wrote to ``out/<scene>/`` (contracts in
:mod:`rotorpillar.postprocess.readers`) and never recomputes the physics
beyond evaluating the closed forms those results already carry.

- :mod:`.offscreen`   pyvista without a display (EGL or OSMesa)
- :mod:`.style`       the one chart style: figure creation, colours, atomic PNG writes
- :mod:`.readers`     each result file read into its record (one reader each), damaged inputs named
- :mod:`.geometry`    the tube's surface carrying the mode shapes of a VTU (pyvista), the cantilever fallback
- :mod:`.modeshapes`  one PNG per mode and a contact sheet
- :mod:`.animation`   run-up and earthquake animations (MP4, GIF fallback)
- :mod:`.charts`      drive/resistance curves (Figs. 3-4), a(z)
- :mod:`.transient_charts` run-up, earthquake, sweep and integrator charts
- :mod:`.compare_reader` compare_<case>.json and its runs
- :mod:`.compare_charts` models of one case overlaid with their differences; a record's response spectrum
- :mod:`.html`        the report page: escaped text, embedded images, no external resource
- :mod:`.report`      `rotorpillar report`: every figure that its inputs allow, then the page
- :mod:`.convergence_charts` error against DOFs and against wall time (`rotorpillar converge`)

The synthetic inputs the tests use live in ``tests/fixtures.py``.
"""
