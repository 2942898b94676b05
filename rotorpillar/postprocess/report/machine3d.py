"""The machine in three dimensions on the page: the Campbell diagram of the ROM and the 3D
model side by side (campbell.json, campbell.png) and El Centro in three components on the
spatial ROM and the 3D full order (compare_earthquake_components.json); the spatial ROM's
unbalance response in both lateral directions and its orbits (harmonic.json's ``spatial``,
drawn here as orbits.png).

Both files are read through their records (rotorpillar.reduced.campbell.CampbellDiagram,
rotorpillar.transients.components.ComponentsComparison); the prose is the template's
(``templates/sections/machine3d.html.j2``).
"""

from __future__ import annotations

from pathlib import Path

from ... import records
from ...reduced.campbell import CampbellDiagram
from ...transients.components import ComponentsComparison
from ...verdict.harmonic import HarmonicResult
from .compare_section import Picture
from .page import Section, render, with_subsections
from .state import FIGURES_DIR, Build


def _read(build: Build, file: str, record_type: type) -> tuple[object | None, str | None]:
    """The record in ``file``, or None; and the line naming a damaged file (None if whole)."""
    path = Path(build.out) / file
    if not path.is_file():
        return None, None
    try:
        return records.read(path, record_type), None
    except (ValueError, OSError) as exc:
        build.failures[f"input {file}"] = str(exc)
        return None, f"{file} is damaged ({exc}): rebuild it with its command"


def section_machine3d(build: Build) -> Section | None:
    """The Campbell diagram and the three-component earthquake; None when neither ran."""
    campbell, campbell_damaged = _read(build, "campbell.json", CampbellDiagram)
    quake, quake_damaged = _read(build, "compare_earthquake_components.json", ComponentsComparison)
    if campbell is None and quake is None and campbell_damaged is None and quake_damaged is None:
        return None
    orbits = _orbits(build, campbell)
    chart = Path(build.out) / "campbell.png"
    picture = (
        Picture(
            str(chart),
            "Campbell diagram: each mode's damped frequency against the rotor's speed, the ROM in "
            "colour and the 3D model in grey, the running speed's API 684 band and the 1x line",
        )
        if chart.is_file()
        else None
    )
    html = render(
        "sections/machine3d.html.j2",
        campbell=campbell,
        campbell_damaged=campbell_damaged,
        picture=picture,
        quake=quake,
        quake_damaged=quake_damaged,
        orbits=orbits,
        scene=build.scene_cli,
    )
    return with_subsections("machine3d", "The machine in three dimensions", str(html))


def _orbits(build: Build, campbell) -> Picture | None:
    """orbits.png from harmonic.json's spatial response (None: no file, no spatial response, or
    the chart failed: the failure is the build's)."""
    from ..orbit_chart import orbit_chart
    from . import kept

    harmonic, _ = _read(build, "harmonic.json", HarmonicResult)
    spatial = getattr(harmonic, "spatial", None)
    if spatial is None:
        return None
    running = getattr(campbell, "running_speed", None)
    png = Path(build.out) / FIGURES_DIR / "orbits.png"
    path = kept.chart(build, "orbits", png, orbit_chart, png, spatial, running)
    if path is None:
        return None
    return Picture(
        str(path),
        "The spatial ROM's steady unbalance response (harmonic.json: spatial). Left: the amplitudes of "
        "the top and of the rotor centre in the rotor's plane and along the spin axis against the speed. "
        "Right: the semi-axes of each orbit (the shaft's deflection and the rotor centre in the plane "
        "normal to the spin axis, the top in the horizontal plane), the line style its whirl; the "
        "dash-dotted line is the running speed",
    )
