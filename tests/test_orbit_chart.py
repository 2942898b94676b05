"""The orbits on the page (issue 26.8): the spatial ROM's unbalance response in both lateral
directions and its orbits, drawn from harmonic.json's ``spatial`` in "The machine in three
dimensions".  The numbers are checked in tests/test_spatial*.py (the orbits' whirl against the
Campbell branches, the half-power AFs); here, that the chart is a real, legible picture of
them and that the section shows it."""

import numpy as np
import pytest
from imagecheck import assert_real_png

from rotorpillar.postprocess.orbit_chart import orbit_chart
from rotorpillar.postprocess.style import png_layout


def _response():
    from rotorpillar.reduced.spatial_response import unbalance_response
    from rotorpillar.reduced.spatial_scene import scene_spatial_model
    from rotorpillar.scene import load_scene, with_values

    scene = with_values(load_scene("paper"), {"modal_model.source": "beam"})
    return unbalance_response(scene_spatial_model(scene, 180.0), np.linspace(1.0, 180.0, 120))


def test_the_orbit_chart_is_a_legible_picture(tmp_path):
    path = orbit_chart(tmp_path / "orbits.png", _response(), 89.7, "paper")
    assert_real_png(path)
    layout = png_layout(path.read_bytes())
    assert layout is not None and layout["problems"] == []


@pytest.mark.slow  # two commands, then the section
def test_the_machine_in_3d_section_shows_the_orbits(tmp_path, here):
    from rotorpillar.postprocess.report.machine3d import section_machine3d
    from rotorpillar.postprocess.report.state import Build, ReportOptions
    from rotorpillar.scene import load_scene

    # the ROM's harmonic response only: the orbits are the spatial ROM's (the 3D curve is
    # test_harmonic_3d's)
    for command in (["harmonic", "--no-fem3d"], ["campbell", "--speeds", "0:180:61"]):
        # in this process (conftest's here): the files are what the section reads
        p = here(command[0], "paper", *command[1:], "--set", "modal_model.source=beam", "--out", tmp_path)
        assert p.returncode == 0, p.stderr
    build = Build(load_scene("paper"), tmp_path, "paper", ReportOptions())
    html = str(section_machine3d(build))
    assert "Unbalance response and orbits in both lateral directions" in html
    assert (tmp_path / "figures" / "orbits.png").is_file() and "orbits" not in build.failures
